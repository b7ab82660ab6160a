//! The streaming results processor (`rtl::bundle::stream::BundleStream`): the rust-hdl simulation clock
//! for clock against `golden::bundle::stream::StreamModel` (ready, done, tag, result and the held result
//! fields in every clock) on open-loop job streams with bursts, split jobs queueing, four ray sets loaded
//! while jobs run, garbage writes and resets; a wrong model is caught; the exported Verilog (Verilator
//! lint, Icarus, Verilator cross-simulation against the model and the rust-hdl simulation).
//! Each test prints its counts and time (run with `--nocapture`).

use golden::bundle::fix::BundleFixFormat;
use golden::bundle::stream::StreamModel;
use rtl::bundle::pair_fix::BUNDLE_FIX_LATENCY;
use rtl::bundle::stream::{bundle_stream_module, BundleStreamIo};
use std::time::Instant;
use tb::bundle::stream::{
    run_stream, stream_xsim, StreamChecker, StreamRtl, StreamStats, StreamStim,
};

fn preset(i: usize) -> BundleFixFormat {
    BundleFixFormat::presets()[i]
}

/// Every outcome, full splits, a queue in use, reports out of order and refused starts must occur.
fn well_covered(bf: &BundleFixFormat, s: &StreamStats) {
    let j = s.done / 20;
    assert!(
        s.all_hit > j && s.all_miss > j && s.split > j && s.full_splits > 0,
        "{}: every outcome must be well represented: {s:?}",
        bf.name()
    );
    assert!(
        s.max_queued >= 3 && s.overtakes > j && s.refused > j,
        "{}: the queue, out-of-order reports and refused starts must occur: {s:?}",
        bf.name()
    );
}

fn rtl_matches_model<S: BundleStreamIo>(bf: BundleFixFormat, clocks: u64, seed: u64) {
    let start = Instant::now();
    let mut dut = StreamRtl::<S>::new(&bf);
    let stats = run_stream(
        StreamChecker::new(&bf),
        &mut dut,
        StreamStim::new(bf, seed, clocks),
    )
    .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    println!(
        "{}: {stats:?} match in {:.1} s",
        bf.name(),
        start.elapsed().as_secs_f64()
    );
    assert_eq!(stats.clocks, clocks);
    well_covered(&bf, &stats);
}

#[test]
fn stream_rtl_matches_model_b8() {
    rtl_matches_model::<rtl::BundleStreamB8>(preset(0), 20_000, 1);
}

#[test]
fn stream_rtl_matches_model_b12() {
    rtl_matches_model::<rtl::BundleStreamB12>(preset(1), 20_000, 2);
}

#[test]
fn stream_rtl_matches_model_b16() {
    rtl_matches_model::<rtl::BundleStreamB16>(preset(2), 20_000, 3);
}

/// The check can fail: a model whose pair answers one clock late disagrees with the RTL.
#[test]
fn stream_wrong_model_is_caught() {
    let bf = preset(1);
    let mut dut = StreamRtl::<rtl::BundleStreamB12>::new(&bf);
    let e = run_stream(
        StreamChecker::with_model(StreamModel::new(bf, BUNDLE_FIX_LATENCY + 1)),
        &mut dut,
        StreamStim::new(bf, 4, 2_000),
    )
    .expect_err("a wrong latency must be caught");
    println!("caught: {e}");
}

/// Synchronous reset at random clocks: every job in flight is dropped, in the rust-hdl simulation and
/// in Verilator (every clock against rust-hdl and the model).
#[test]
fn stream_reset_drops_jobs_in_flight_b12() {
    let bf = preset(1);
    let clocks = 20_000;
    let mut dut = StreamRtl::<rtl::BundleStreamB12>::new(&bf);
    let stats = run_stream(
        StreamChecker::new(&bf),
        &mut dut,
        StreamStim::new(bf, 51, clocks).with_resets(),
    )
    .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    assert!(stats.resets > 20, "{stats:?}");
    assert!(stats.done < stats.taken, "{stats:?}");
    let (v, _) = export::<rtl::BundleStreamB12>(&bf);
    let h = tb::verilator::build(
        &v,
        &bundle_stream_module(&bf),
        &tb::out_dir().join("verilator"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let x = stream_xsim::<rtl::BundleStreamB12, _>(
        bf,
        &h,
        StreamStim::new(bf, 51, clocks).with_resets(),
        u64::MAX,
    )
    .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    assert_eq!(x, stats);
}

fn export<S: BundleStreamIo>(bf: &BundleFixFormat) -> (String, std::path::PathBuf) {
    let name = bundle_stream_module(bf);
    let v = rtl::export::verilog_named(&mut S::for_format(bf), &name);
    let path = tb::verilog_tools::write(&v, &name);
    (v, path)
}

#[test]
fn stream_verilog_is_lint_clean_and_accepted_by_icarus() {
    for path in [
        export::<rtl::BundleStreamB8>(&preset(0)).1,
        export::<rtl::BundleStreamB12>(&preset(1)).1,
        export::<rtl::BundleStreamB16>(&preset(2)).1,
    ] {
        tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
        tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    }
}

fn cross_simulate<S: BundleStreamIo>(bf: BundleFixFormat, clocks: u64, lockstep: u64, seed: u64) {
    let start = Instant::now();
    let (v, _) = export::<S>(&bf);
    let h = tb::verilator::build(
        &v,
        &bundle_stream_module(&bf),
        &tb::out_dir().join("verilator"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let built = start.elapsed().as_secs_f64();
    let stats = stream_xsim::<S, _>(bf, &h, StreamStim::new(bf, seed, clocks), lockstep)
        .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    println!(
        "{}: {stats:?} (harness ready in {built:.1} s, {:.1} s in all)",
        bf.name(),
        start.elapsed().as_secs_f64()
    );
    assert_eq!(stats.clocks, clocks);
    assert!(stats.done >= 300_000, "{stats:?}");
    well_covered(&bf, &stats);
}

#[test]
fn stream_verilator_matches_model_and_rtl_b8() {
    cross_simulate::<rtl::BundleStreamB8>(preset(0), 900_000, 50_000, 8);
}

#[test]
fn stream_verilator_matches_model_and_rtl_b12() {
    cross_simulate::<rtl::BundleStreamB12>(preset(1), 900_000, 50_000, 6);
}

#[test]
fn stream_verilator_matches_model_and_rtl_b16() {
    cross_simulate::<rtl::BundleStreamB16>(preset(2), 900_000, 50_000, 7);
}

/// Scene job streams, closed loop (`tb::bundle::stream_scene`): on a small room, primary rays in 4x4
/// tiles and bounce and shadow rays bundled 16 at most, every job's mask equals the recorded model
/// mask and every clock equals the clock-by-clock model; the pair's input is used in exactly the
/// model's busy-pair count of clocks. Prints utilisation and clocks per job (figures, not thresholds).
#[test]
fn stream_scene_jobs_replay_closed_loop_b12() {
    use tb::bundle::stream_scene::{run_decided, run_trees, scene_streams};
    let bf = preset(1);
    let sc = golden::scene::tri_scene::by_name("room", 1, None).unwrap();
    let streams = scene_streams(&sc, 1, (24, 16), 4, (16, 0.2), &bf).unwrap();
    assert_eq!(streams.len(), 3);
    for (set, bundling, trees) in &streams {
        assert!(trees.jobs.len() > trees.bundles.len(), "{set}: {trees:?}");
        let mut dut = StreamRtl::<rtl::BundleStreamB12>::new(&bf);
        let r = run_trees(&bf, trees, &mut dut, || {}).unwrap_or_else(|e| panic!("{set}: {e}"));
        assert_eq!(r.jobs, trees.jobs.len() as u64, "{set}");
        assert_eq!(
            r.busy, trees.pair_cycles,
            "{set}: busy clocks = model pair cycles"
        );
        let mut dut = StreamRtl::<rtl::BundleStreamB12>::new(&bf);
        let d = run_decided(&bf, trees, &mut dut).unwrap_or_else(|e| panic!("{set}: {e}"));
        println!(
            "{set} {bundling}: {} bundles, {} jobs, {} clocks, utilisation {:.3}, {:.2} clocks/job; \
             decided-only stream: {:.3} tests/clock",
            r.bundles,
            r.jobs,
            r.clocks,
            r.utilisation(),
            r.clocks_per_job(),
            d.jobs as f64 / d.clocks as f64
        );
    }
}

/// In the waveform: decided jobs started on consecutive clocks each report (`done`) 4 clock edges after
/// their start, one a clock, while `ready` stays high; then a split job of 16 rays holds `ready` low for
/// its 8 pair clocks and reports no earlier than `2L + 3 + 8` edges after its start.
#[test]
fn stream_waveform_timing_b16() {
    use golden::bundle::stream::StreamJob;
    use rtl::bundle::stream::FixStreamIn;
    let bf = preset(2);
    let map = tb::campaign::campaign_map(bf.base);
    let (lo, hi) = tb::campaign::campaign_bounds();
    let mut gen = golden::bundle::gen::BundleGen::new(21, lo, hi, 0.6);
    let mut model = tb::bundle::stream::stream_model(&bf);
    // Three decided cases and one undecided case whose 16 rays split.
    let (mut decided, mut undecided) = (vec![], None);
    while decided.len() < 3 || undecided.is_none() {
        let c = gen.next_case();
        let Some((b, p, mut rays)) = tb::bundle::pair_fix::quantised_case(&bf, &map, &c) else {
            continue;
        };
        use golden::bundle::stream::PairDatapath;
        let (h, m) = bf.decide(&b, &p);
        if h || m {
            decided.push((b, p));
        } else if undecided.is_none() {
            while rays.len() < 16 {
                rays.extend_from_within(..);
            }
            rays.truncate(16);
            undecided = Some((b, p, rays));
        }
    }
    let (ub, up, rays) = undecided.unwrap();
    let mut stim: Vec<FixStreamIn> = rays
        .iter()
        .enumerate()
        .map(|(i, r)| FixStreamIn {
            write: Some((1, i as u8, *r)),
            ..Default::default()
        })
        .collect();
    let job = |b, p, active, tag| FixStreamIn {
        start: Some(StreamJob {
            bundle: b,
            boxes: p,
            active,
            set: 1,
            tag,
        }),
        ..Default::default()
    };
    for (k, (b, p)) in decided.iter().enumerate() {
        stim.push(job(*b, *p, 0xffff, k as u8));
    }
    stim.extend((0..6).map(|_| FixStreamIn::default()));
    stim.push(job(ub, up, 0xffff, 9));
    stim.extend((0..40).map(|_| FixStreamIn::default()));
    let path = tb::out_dir()
        .join("vcd")
        .join("bundle_stream_b16_timing.vcd");
    {
        let mut dut = StreamRtl::<rtl::BundleStreamB16>::new(&bf)
            .vcd_to(&path)
            .unwrap();
        for input in &stim {
            let got = dut.step(input);
            model.step(input);
            assert_eq!(got, model.outputs());
        }
    }
    let trace = tb::vcd_read::read_trace(&path, &["start", "done", "ready"]).unwrap();
    let (starts, dones) = (trace.rises("start"), trace.rises("done"));
    // The three decided starts are one rise (start held high three clocks); the split job's is the second.
    assert_eq!(starts.len(), 2, "{starts:?}");
    assert_eq!(
        dones.len(),
        2,
        "done pulses merge for consecutive reports: {dones:?}"
    );
    assert_eq!(
        trace.edges_between(starts[0], dones[0]),
        4,
        "decided: L + 1"
    );
    let split = trace.edges_between(starts[1], dones[1]);
    let l = BUNDLE_FIX_LATENCY;
    assert!(
        split >= 2 * l + 3 + 8,
        "split job reported after {split} edges"
    );
    // ready falls once, for the split job's eight pair clocks.
    let falls = trace.rises("ready").len();
    assert_eq!(
        falls, 2,
        "ready rises at time 0 and after the split job's rays"
    );
    println!("decided: 4 edges; split of 16 rays: {split} edges");
}
