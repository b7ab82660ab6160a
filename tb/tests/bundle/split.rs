//! The bundle results processor (`rtl::bundle::split::BundleSplit`): the rust-hdl simulation clock for clock
//! against `golden::bundle::split::split_fix` and `rtl::bundle::split::split_clocks` on many jobs
//! (BundleGen bundles with their rays quantised, random and adversarial, padded ray sets, raw ray codes,
//! random active masks, back-to-back jobs, idle gaps, starts while busy and garbage writes, which must be
//! ignored); a wrong model is caught; the waveform's start-to-done timing; the exported Verilog
//! (Verilator lint, Icarus, Verilator cross-simulation against the model and the rust-hdl simulation).
//! Each test prints its counts and time (run with `--nocapture`).

use golden::bundle::fix::{all_hit_fix, BundleFixFormat};
use golden::bundle::split::{split_with, SplitResult};
use rtl::bundle::split::{split_clocks, BundleSplitIo, SplitJob};
use rtl::names::bundle_split_module;
use std::time::Instant;
use tb::bundle::pair_fix::quantised_case;
use tb::bundle::split::{
    directed, run_split, split_model, split_xsim, RayStore, SplitRtl, SplitStats, SplitStim,
};
use tb::campaign::{campaign_bounds, campaign_map};
use tb::vcd_read::read_trace;

fn preset(i: usize) -> BundleFixFormat {
    BundleFixFormat::presets()[i]
}

fn well_covered(bf: &BundleFixFormat, s: &SplitStats) {
    let j = s.jobs / 20;
    assert!(
        s.all_hit > j && s.all_miss > j && s.split > j,
        "{}: every outcome must be well represented: {s:?}",
        bf.name()
    );
    assert!(
        s.odd_splits > 0 && s.full_splits > 0 && s.back_to_back > j,
        "{}: odd and full ray counts and back-to-back jobs must occur: {s:?}",
        bf.name()
    );
}

fn rtl_matches_model<S: BundleSplitIo>(bf: BundleFixFormat, jobs: u64, seed: u64) {
    let start = Instant::now();
    let mut dut = SplitRtl::<S>::new(&bf);
    let stats = run_split(&mut dut, SplitStim::new(bf, seed, jobs, false, split_model))
        .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    println!(
        "{}: {stats:?} match in {:.1} s",
        bf.name(),
        start.elapsed().as_secs_f64()
    );
    assert_eq!(stats.jobs, jobs);
    well_covered(&bf, &stats);
}

#[test]
fn rtl_matches_model_b8() {
    rtl_matches_model::<rtl::BundleSplitB8>(preset(0), 20_000, 1);
}

#[test]
fn rtl_matches_model_b12() {
    rtl_matches_model::<rtl::BundleSplitB12>(preset(1), 20_000, 2);
}

#[test]
fn rtl_matches_model_b16() {
    rtl_matches_model::<rtl::BundleSplitB16>(preset(2), 20_000, 3);
}

/// A wrong model: each ray judged with AllHit bounds on the inner box (the two-ray mode before it was
/// made sound).
pub(crate) fn allhit_rays(bf: &BundleFixFormat, j: &SplitJob, store: &RayStore) -> SplitResult {
    let right = split_model(bf, j, store);
    split_with(
        || (right.all_hit, right.all_miss),
        |i| all_hit_fix(bf, &store[i], &j.boxes.inner),
        j.active as u64,
    )
}

/// A wrong model: one pair clock too few for odd ray counts.
pub(crate) fn floor_cycles(bf: &BundleFixFormat, j: &SplitJob, store: &RayStore) -> SplitResult {
    let mut r = split_model(bf, j, store);
    if r.split {
        r.pair_cycles = 1 + j.active.count_ones() / 2;
    }
    r
}

/// The check can fail: a model that judges each ray with AllHit bounds on the inner box disagrees with
/// the RTL on some mask, and so does one that counts one pair clock too few for odd ray counts.
#[test]
fn a_wrong_model_is_caught() {
    let bf = preset(1);
    let mut dut = SplitRtl::<rtl::BundleSplitB12>::new(&bf);
    let e = run_split(&mut dut, SplitStim::new(bf, 4, 2_000, false, allhit_rays))
        .expect_err("AllHit per ray must be caught");
    println!("caught: {e}");
    let mut dut = SplitRtl::<rtl::BundleSplitB12>::new(&bf);
    let e = run_split(&mut dut, SplitStim::new(bf, 4, 2_000, false, floor_cycles))
        .expect_err("a wrong cycle count must be caught");
    println!("caught: {e}");
}

/// In the waveform, `done` rises `split_clocks` clock edges after each `start` (4 for a decided job,
/// 7 + ceil(rays / 2) for a split one), and `ready` is low in between.
#[test]
fn done_rises_split_clocks_after_start() {
    let bf = preset(2);
    let path = tb::out_dir()
        .join("vcd")
        .join("bundle_split_b16_timing.vcd");
    let stim: Vec<_> = SplitStim::new(bf, 5, 40, true, split_model).collect();
    let want: Vec<u32> = stim
        .iter()
        .filter_map(|(_, e)| e.done.as_ref().map(|d| d.clocks))
        .collect();
    {
        let mut dut = SplitRtl::<rtl::BundleSplitB16>::new(&bf)
            .vcd_to(&path)
            .unwrap();
        run_split(&mut dut, stim).unwrap_or_else(|e| panic!("{e}"));
    }
    let trace = read_trace(&path, &["start", "done", "ready"]).unwrap();
    let (starts, dones) = (trace.rises("start"), trace.rises("done"));
    assert_eq!(
        (starts.len(), dones.len()),
        (want.len(), want.len()),
        "{starts:?} {dones:?}"
    );
    let mut kinds = std::collections::BTreeSet::new();
    for ((s, d), w) in starts.iter().zip(&dones).zip(&want) {
        let n = trace.edges_between(*s, *d);
        assert_eq!(n as u32, *w, "start at {s}, done at {d}");
        kinds.insert(n);
    }
    assert!(
        kinds.contains(&4) && kinds.len() > 3,
        "timings seen: {kinds:?}"
    );
    // ready rises once per job, with its done (and once at time 0).
    let ready: Vec<u64> = trace
        .rises("ready")
        .into_iter()
        .filter(|&t| t > 0)
        .collect();
    assert_eq!(ready, dones, "ready rises with each done");
    println!("{} jobs, start-to-done clocks seen {kinds:?}", want.len());
}

/// Corner jobs by name, back to back on one ray store of 16 rays: an undecided bundle with no active
/// ray (split, empty mask, one pair clock, 4 clocks), one active ray (B slot empty), the first and the
/// last ray (one pair across the store), rays 15 and 14 only, every even ray, all 16 rays (8 pair clocks,
/// 15 clocks); then a decided hit (mask = active) and a decided miss (mask 0) with all rays active.
#[test]
fn corner_jobs_by_name() {
    let bf = preset(1);
    let map = campaign_map(bf.base);
    let (lo, hi) = campaign_bounds();
    let mut gen = golden::bundle::gen::BundleGen::new(11, lo, hi, 0.6);
    let (mut undecided, mut hit, mut miss) = (None, None, None);
    while undecided.is_none() || hit.is_none() || miss.is_none() {
        let c = gen.next_case();
        let Some((b, p, rays)) = quantised_case(&bf, &map, &c) else {
            continue;
        };
        let mut r16 = rays.clone();
        while r16.len() < 16 {
            r16.extend_from_slice(&rays);
        }
        r16.truncate(16);
        let job = |active| SplitJob {
            bundle: b,
            boxes: p,
            active,
        };
        let store: RayStore = r16.clone().try_into().unwrap();
        let r = split_model(&bf, &job(0xffff), &store);
        let slot = if r.all_hit {
            &mut hit
        } else if r.all_miss {
            &mut miss
        } else if r.mask != 0 && r.mask != 0xffff {
            &mut undecided
        } else {
            continue;
        };
        if slot.is_none() {
            *slot = Some((r16, job(0)));
        }
    }
    let (rays, base) = undecided.unwrap();
    let masks: [(u16, u32, u32); 6] = [
        (0, 1, 4),
        (1 << 5, 2, 8),
        (1 | 1 << 15, 2, 8),
        (3 << 14, 2, 8),
        (0x5555, 5, 11),
        (0xffff, 9, 15),
    ];
    let mut jobs: Vec<SplitJob> = masks
        .iter()
        .map(|&(active, _, _)| SplitJob { active, ..base })
        .collect();
    let stim = directed(&bf, &rays, &jobs, split_model);
    let mut dut = SplitRtl::<rtl::BundleSplitB12>::new(&bf);
    let stats = run_split(&mut dut, stim.clone()).unwrap_or_else(|e| panic!("{e}"));
    let reports: Vec<_> = stim.iter().filter_map(|(_, e)| e.done.clone()).collect();
    for (d, &(active, cycles, clocks)) in reports.iter().zip(&masks) {
        assert!(d.result.split, "{d:?}");
        assert_eq!(
            (d.result.pair_cycles, d.clocks),
            (cycles, clocks),
            "active {active:#06x}"
        );
    }
    assert_eq!(stats.split, masks.len() as u64);
    // The decided bundles, on their own ray sets.
    for (what, case) in [("hit", hit.unwrap()), ("miss", miss.unwrap())] {
        jobs = vec![SplitJob {
            active: 0xffff,
            ..case.1
        }];
        let stim = directed(&bf, &case.0, &jobs, split_model);
        let d = stim.iter().find_map(|(_, e)| e.done.clone()).unwrap();
        assert_eq!(
            d.result.mask,
            if what == "hit" { 0xffff } else { 0 },
            "{what}"
        );
        assert_eq!((d.result.pair_cycles, d.clocks), (1, 4), "{what}");
        let mut dut = SplitRtl::<rtl::BundleSplitB12>::new(&bf);
        run_split(&mut dut, stim).unwrap_or_else(|e| panic!("{what}: {e}"));
    }
    println!("{} corner jobs match", masks.len() + 2);
}

#[test]
fn split_clocks_follow_the_schedule() {
    let r = |split, pair_cycles| SplitResult {
        split,
        pair_cycles,
        ..Default::default()
    };
    assert_eq!(split_clocks(&r(false, 1)), 4);
    assert_eq!(split_clocks(&r(true, 1)), 4);
    assert_eq!(split_clocks(&r(true, 2)), 8);
    assert_eq!(split_clocks(&r(true, 9)), 15);
}

fn export<S: BundleSplitIo>(bf: &BundleFixFormat) -> (String, std::path::PathBuf) {
    let name = bundle_split_module(bf);
    let v = rtl::verilog::verilog_named(&mut S::for_format(bf), &name);
    let path = tb::verilog_tools::write(&v, &name);
    (v, path)
}

#[test]
fn exported_verilog_is_lint_clean_and_accepted_by_icarus() {
    for path in [
        export::<rtl::BundleSplitB8>(&preset(0)).1,
        export::<rtl::BundleSplitB12>(&preset(1)).1,
        export::<rtl::BundleSplitB16>(&preset(2)).1,
    ] {
        tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
        tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    }
}

fn cross_simulate<S: BundleSplitIo>(bf: BundleFixFormat, jobs: u64, lockstep: u64, seed: u64) {
    let start = Instant::now();
    let (v, _) = export::<S>(&bf);
    let h = tb::verilator::build(
        &v,
        &bundle_split_module(&bf),
        &tb::out_dir().join("verilator"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let built = start.elapsed().as_secs_f64();
    let stats = split_xsim::<S, _>(
        bf,
        &h,
        SplitStim::new(bf, seed, jobs, false, split_model),
        lockstep,
    )
    .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    println!(
        "{}: {stats:?} (harness ready in {built:.1} s, {:.1} s in all)",
        bf.name(),
        start.elapsed().as_secs_f64()
    );
    assert_eq!(stats.jobs, jobs);
    well_covered(&bf, &stats);
}

#[test]
fn verilator_matches_model_and_rtl_b8() {
    cross_simulate::<rtl::BundleSplitB8>(preset(0), 300_000, 100_000, 8);
}

#[test]
fn verilator_matches_model_and_rtl_b12() {
    cross_simulate::<rtl::BundleSplitB12>(preset(1), 300_000, 100_000, 6);
}

#[test]
fn verilator_matches_model_and_rtl_b16() {
    cross_simulate::<rtl::BundleSplitB16>(preset(2), 300_000, 100_000, 7);
}

/// Synchronous reset: one job in six dropped by `rst` in a random clock of it (the report clock
/// included), resets between jobs, and starts and writes in the reset clocks; the dropped job never
/// reports, the block is ready after the reset, and every other job reports the model's result on
/// time, in the rust-hdl simulation and in Verilator (every clock against rust-hdl).
#[test]
fn reset_drops_the_job_in_progress_b12() {
    let bf = preset(1);
    let jobs = 3_000;
    let mut dut = SplitRtl::<rtl::BundleSplitB12>::new(&bf);
    let stats = run_split(
        &mut dut,
        SplitStim::new(bf, 51, jobs, false, split_model).with_resets(),
    )
    .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    assert!(stats.resets > jobs / 10, "{stats:?}");
    assert!(stats.jobs < jobs && stats.jobs > jobs / 2, "{stats:?}");
    let (v, _) = export::<rtl::BundleSplitB12>(&bf);
    let h = tb::verilator::build(
        &v,
        &bundle_split_module(&bf),
        &tb::out_dir().join("verilator"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let x = split_xsim::<rtl::BundleSplitB12, _>(
        bf,
        &h,
        SplitStim::new(bf, 51, jobs, false, split_model).with_resets(),
        u64::MAX,
    )
    .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    assert_eq!(x, stats);
}
