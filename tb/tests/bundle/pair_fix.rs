//! The fixed-point bundle pair (AllHit + AnyHit, `rtl::bundle::pair_fix::BundleFix`): rust-hdl simulation bit
//! for bit against `golden::bundle::fix::{all_hit_fix, all_miss_fix}` on BundleGen bundles (random and
//! adversarial), on-grid single rays, two-ray inputs (on-grid and off-grid quantised rays) and raw codes,
//! with bubbles, for every preset (results, tag order, latency); a wrong model is caught; two-ray mode
//! never calls a hitting ray a miss (exact oracle); the waveform's latency; the exported Verilog (Verilator lint,
//! Icarus, Verilator cross-simulation against the rust-hdl simulation and the model). The 5-clock pairs
//! (`BundleFixB8P5` ..., products and compares registered) get the same checks as the 3-clock ones. Each test prints
//! its counts and time (run with `--nocapture`).

use golden::bundle::edge::ray_hits_exact;
use golden::bundle::fix::{
    all_hit_fix, all_miss_fix, quantize_box_pair, quantize_bundle, BundleFixFormat, FixBundle,
};
use golden::bundle::gen::BundleGen;
use golden::exact::slab_exact;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::bundle::pair_fix::{BundleFixIo, PairInput};
use std::time::Instant;
use tb::bundle::pair_fix::{bundle_model, bundle_rtl, bundle_vectors, quantised_case, BundleVec};
use tb::campaign::{campaign_bounds, campaign_map};
use tb::dut::run_checked;
use tb::vcd_read::read_trace;
use tb::xsim::xsim;

fn preset(i: usize) -> BundleFixFormat {
    BundleFixFormat::presets()[i]
}

fn rtl_matches_model<S: BundleFixIo>(bf: BundleFixFormat, n: u64, seed: u64) {
    let start = Instant::now();
    let mut dut = bundle_rtl::<S>(&bf);
    let tests: Vec<_> = bundle_vectors(bf, seed, n, true).collect();
    let answers =
        tests
            .iter()
            .flatten()
            .map(|v| bundle_model(&bf, v))
            .fold([0usize; 4], |mut c, (h, m)| {
                c[h as usize + 2 * m as usize] += 1;
                c
            });
    let done = run_checked(&mut dut, tests, |v| bundle_model(&bf, v))
        .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    assert_eq!(done, n as usize);
    println!(
        "{}: {done} tests match in {:.1} s (all hit {}, all miss {}, neither {}, both {} (two rays, raw codes))",
        bf.name(),
        start.elapsed().as_secs_f64(),
        answers[1],
        answers[2],
        answers[0],
        answers[3]
    );
    assert!(
        answers[..3].iter().all(|&c| c > n as usize / 50),
        "every answer must be well represented: {answers:?}"
    );
}

#[test]
fn rtl_matches_model_b8() {
    rtl_matches_model::<rtl::BundleFixB8>(preset(0), 50_000, 1);
}

#[test]
fn rtl_matches_model_b12() {
    rtl_matches_model::<rtl::BundleFixB12>(preset(1), 50_000, 2);
}

#[test]
fn rtl_matches_model_b16() {
    rtl_matches_model::<rtl::BundleFixB16>(preset(2), 50_000, 3);
}

#[test]
fn rtl_matches_model_5_clocks() {
    rtl_matches_model::<rtl::BundleFixB8P5>(preset(0), 20_000, 11);
    rtl_matches_model::<rtl::BundleFixB12P5>(preset(1), 20_000, 12);
    rtl_matches_model::<rtl::BundleFixB16P5>(preset(2), 20_000, 13);
}

/// The equivalence check can fail: a model that judges AllHit with AnyHit's bounds (outer box, `t_hi`)
/// and AnyHit with AllHit's disagrees with the RTL.
#[test]
fn a_wrong_model_is_caught() {
    let bf = preset(1);
    let mut dut = bundle_rtl::<rtl::BundleFixB12>(&bf);
    let swap_t = |b: &FixBundle| FixBundle {
        t_lo: b.t_hi,
        t_hi: b.t_lo,
        ..*b
    };
    let swapped = |v: &BundleVec| {
        let ((a, b), p) = (v.0.sides(), v.1);
        (
            all_hit_fix(&bf, &swap_t(a), &p.outer),
            all_miss_fix(&bf, &swap_t(b), &p.inner),
        )
    };
    let err = run_checked(&mut dut, bundle_vectors(bf, 4, 5_000, false), swapped)
        .expect_err("a wrong model must be caught");
    println!("caught: {err}");
}

/// An on-grid ray is a point bundle, decided exactly by both tests: as a bundle, AllHit says "hits"
/// exactly when AnyHit says "does not miss"; in two-ray mode (the same ray on both testers) the pair gives
/// the same two answers. The RTL gives both bit for bit.
#[test]
fn one_on_grid_ray_gets_one_answer_in_both_modes() {
    let bf = preset(1);
    let map = campaign_map(bf.base);
    let (lo, hi) = campaign_bounds();
    let mut gen = BundleGen::new(9, lo, hi, 1.0);
    let mut tests = vec![];
    while tests.len() < 4_000 {
        let c = gen.grid_one_ray(&map);
        if let (Ok(b), Ok(p)) = (
            quantize_bundle(&bf, &map, &c.bundle),
            quantize_box_pair(&map, &c.bounds),
        ) {
            assert_eq!(p.inner, p.outer, "an on-grid box needs no rounding");
            assert_eq!(
                (b.o_lo, b.d_lo, b.t_lo),
                (b.o_hi, b.d_hi, b.t_hi),
                "a point bundle"
            );
            tests.push(Some((PairInput::Bundle(b), p)));
            tests.push(Some((PairInput::TwoRays(b, b), p)));
        }
    }
    let mut hits = 0;
    for pair in tests.chunks(2) {
        let (Some((bundle, p)), Some((two, _))) = (&pair[0], &pair[1]) else {
            unreachable!()
        };
        let (all_hit, all_miss) = bundle.model(&bf, p);
        assert_eq!(all_hit, !all_miss, "{bundle:?} {p:?}");
        assert_eq!(two.model(&bf, p), (all_hit, all_miss), "{two:?} {p:?}");
        hits += all_hit as usize;
    }
    let rays = tests.len() / 2;
    assert!(hits > 100 && hits < rays - 100, "degenerate: {hits} hits");
    let mut dut = bundle_rtl::<rtl::BundleFixB12>(&bf);
    let n =
        run_checked(&mut dut, tests, |v| bundle_model(&bf, v)).unwrap_or_else(|e| panic!("{e}"));
    println!(
        "{rays} single rays ({n} tests), {hits} hits, decided alike by both tests and both modes"
    );
}

/// Two-ray mode is sound for rays off the grid: over world rays (on-grid single rays and the listed rays
/// of BundleGen cases, random and adversarial) each quantised to its tiny bundle and paired with the next
/// ray of its case (ray `k` is A in one test and B in another), the pair never says "misses" (`!all_hit`
/// for ray A, `all_miss` for ray B) of a ray that truly hits its case's box (the exact oracle
/// `golden::bundle::edge::ray_hits_exact`, checked against `golden::exact::slab_exact`). The RTL runs the same
/// tests against the model, so the claim holds for the RTL too. AllHit bounds on the tiny bundle (ray A
/// in the old two-ray mode) drop hits, and their count shows the check has teeth.
#[test]
fn two_ray_mode_never_misses_a_hitting_ray() {
    fn run<S: BundleFixIo>(bf: BundleFixFormat, seed: u64) {
        let start = Instant::now();
        let map = campaign_map(bf.base);
        let (lo, hi) = campaign_bounds();
        let mut gen = BundleGen::new(seed, lo, hi, 0.6);
        let mut rng = Pcg64::seed_from_u64(seed);
        let (mut hits, mut off_grid, mut old_false_misses) = (0, 0, 0);
        let mut tests: Vec<Option<BundleVec>> = vec![];
        while tests.len() < 12_000 {
            let c = if rng.gen_ratio(1, 4) {
                gen.grid_one_ray(&map)
            } else {
                gen.next_case()
            };
            let Some((_, p, q)) = quantised_case(&bf, &map, &c) else {
                continue;
            };
            let hit: Vec<bool> = c
                .rays
                .iter()
                .map(|r| {
                    let h = ray_hits_exact(r, &c.bounds).unwrap();
                    assert_eq!(h, slab_exact(r, &c.bounds).hit, "{r:?} {:?}", c.bounds);
                    h
                })
                .collect();
            for k in 0..q.len() {
                let j = (k + 1) % q.len();
                let input = PairInput::TwoRays(q[k], q[j]);
                let (a_may_hit, b_misses) = input.model(&bf, &p);
                for (ray, sound) in [(k, a_may_hit), (j, !b_misses)] {
                    assert!(
                        !hit[ray] || sound,
                        "{}: two-ray mode says a hitting ray misses ({} side)\n  ray {:?}\n  box {:?}\n  \
                         quantised {:?}\n  boxes {p:?}",
                        bf.name(),
                        if ray == k { "A" } else { "B" },
                        c.rays[ray],
                        c.bounds,
                        q[ray]
                    );
                }
                let a = &q[k];
                if hit[k] {
                    hits += 1;
                    old_false_misses += !all_hit_fix(&bf, a, &p.inner) as usize;
                }
                off_grid += (a.o_lo != a.o_hi || a.d_lo != a.d_hi || a.t_lo != a.t_hi) as usize;
                tests.push(Some((input, p)));
            }
        }
        let rays = tests.len();
        assert!(
            hits > rays / 10 && off_grid > rays / 4,
            "{}: degenerate: {hits} hits, {off_grid} off the grid of {rays}",
            bf.name()
        );
        assert!(
            old_false_misses > 0,
            "{}: AllHit bounds dropped no hit",
            bf.name()
        );
        let mut dut = bundle_rtl::<S>(&bf);
        let n = run_checked(&mut dut, tests, |v| bundle_model(&bf, v))
            .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
        assert_eq!(n, rays);
        println!(
            "{}: {rays} rays ({hits} hit, {off_grid} off the grid): no hit called a miss, RTL = model; \
             AllHit bounds would drop {old_false_misses} ({:.1} s)",
            bf.name(),
            start.elapsed().as_secs_f64()
        );
    }
    run::<rtl::BundleFixB8>(preset(0), 20);
    run::<rtl::BundleFixB12>(preset(1), 21);
    run::<rtl::BundleFixB16>(preset(2), 22);
}

/// The waveform of an isolated test and three back to back: `valid_out` rises exactly the pair's
/// latency (3 clocks, 5 for the deep pair) after `valid_in`.
fn valid_leaves_latency_clocks_after_it_enters<S: BundleFixIo>(bf: BundleFixFormat) {
    let path = tb::out_dir().join("vcd").join(format!(
        "{}_latency.vcd",
        rtl::names::bundle_fix_of::<S>(&bf)
    ));
    let tests: Vec<_> = bundle_vectors(bf, 5, 4, false).collect();
    let mut stream = vec![tests[0]];
    stream.extend(std::iter::repeat_n(None, 9));
    stream.extend(tests[1..].iter().cloned());
    {
        let mut dut = bundle_rtl::<S>(&bf).vcd_to(&path).unwrap();
        let n = run_checked(&mut dut, stream, |v| bundle_model(&bf, v))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(n, 4);
    }
    let trace = read_trace(&path, &["valid_in", "valid_out"]).unwrap();
    trace
        .check_valid_latency(2, S::LATENCY)
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn valid_leaves_latency_clocks_after_it_enters_b16() {
    valid_leaves_latency_clocks_after_it_enters::<rtl::BundleFixB16>(preset(2));
}

#[test]
fn valid_leaves_latency_clocks_after_it_enters_5_clocks() {
    assert_eq!(<rtl::BundleFixB12P5 as rtl::io::TesterIo>::LATENCY, 5);
    valid_leaves_latency_clocks_after_it_enters::<rtl::BundleFixB12P5>(preset(1));
}

fn export<S: BundleFixIo>(bf: &BundleFixFormat) -> (String, std::path::PathBuf) {
    let name = rtl::names::bundle_fix_of::<S>(bf);
    let v = rtl::verilog::verilog_named(&mut S::for_format(bf), &name);
    let path = tb::verilog_tools::write(&v, &name);
    (v, path)
}

#[test]
fn exported_verilog_is_lint_clean_and_accepted_by_icarus() {
    for path in [
        export::<rtl::BundleFixB8>(&preset(0)).1,
        export::<rtl::BundleFixB12>(&preset(1)).1,
        export::<rtl::BundleFixB16>(&preset(2)).1,
        export::<rtl::BundleFixB8P5>(&preset(0)).1,
        export::<rtl::BundleFixB12P5>(&preset(1)).1,
        export::<rtl::BundleFixB16P5>(&preset(2)).1,
    ] {
        tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
        tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    }
}

fn cross_simulate<S: BundleFixIo>(bf: BundleFixFormat, n: u64, lockstep: u64, seed: u64) {
    let start = Instant::now();
    let (v, _) = export::<S>(&bf);
    let h = tb::verilator::build(
        &v,
        &rtl::names::bundle_fix_of::<S>(&bf),
        &tb::out_dir().join("verilator"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let built = start.elapsed().as_secs_f64();
    let stats = xsim(
        bf,
        || S::for_format(&bf),
        &h,
        bundle_vectors(bf, seed, n, true),
        lockstep,
        |_| {},
    )
    .unwrap_or_else(|e| panic!("{}: {e}", bf.name()));
    println!(
        "{}: {stats:?} (harness ready in {built:.1} s, {:.1} s in all)",
        bf.name(),
        start.elapsed().as_secs_f64()
    );
    assert_eq!(stats.tests, n);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
}

#[test]
fn verilator_matches_rtl_and_model_b8() {
    cross_simulate::<rtl::BundleFixB8>(preset(0), 500_000, 50_000, 6);
}

#[test]
fn verilator_matches_rtl_and_model_b12() {
    cross_simulate::<rtl::BundleFixB12>(preset(1), 500_000, 50_000, 7);
}

#[test]
fn verilator_matches_rtl_and_model_b16() {
    cross_simulate::<rtl::BundleFixB16>(preset(2), 500_000, 50_000, 8);
}

#[test]
fn verilator_matches_rtl_and_model_5_clocks() {
    cross_simulate::<rtl::BundleFixB8P5>(preset(0), 200_000, 20_000, 16);
    cross_simulate::<rtl::BundleFixB12P5>(preset(1), 200_000, 20_000, 17);
    cross_simulate::<rtl::BundleFixB16P5>(preset(2), 200_000, 20_000, 18);
}

/// Synchronous reset of the pair (`tb::reset`): `rst` at random clocks while bundle and two-ray tests
/// stream; a test met by a reset never leaves, every other leaves on time with the model's answer and
/// its tag, and Verilator agrees with rust-hdl clock by clock.
fn reset_clears_every_valid_bit<S: BundleFixIo>(bf: BundleFixFormat) {
    let (v, _) = export::<S>(&bf);
    let name = rtl::names::bundle_fix_of::<S>(&bf);
    let tests: Vec<_> = bundle_vectors(bf, 41, 400, false).flatten().collect();
    let s = tb::reset::check_block(bf, || S::for_format(&bf), &tests, &name, &v, 41)
        .unwrap_or_else(|e| panic!("{e}"));
    s.both_sides().unwrap_or_else(|e| panic!("{name}: {e}"));
}

#[test]
fn reset_clears_every_valid_bit_b12() {
    reset_clears_every_valid_bit::<rtl::BundleFixB12>(preset(1));
}

#[test]
fn reset_clears_every_valid_bit_b12_5_clocks() {
    reset_clears_every_valid_bit::<rtl::BundleFixB12P5>(preset(1));
}
