//! The float bundle pair (AllHit + AnyHit, `rtl::bundle::pair_float::BundleFloat`): rust-hdl simulation bit for
//! bit against `golden::bundle::float::{all_hit_float, all_miss_float}` (as `FloatPairInput::model`
//! combines them) on BundleGen bundles (random and adversarial), single rays quantised as tiny bundles,
//! two-ray inputs and raw bit patterns (NaN and infinities included), with bubbles, for binary16,
//! bfloat16 and binary32 (results, tag order, latency); wrong models are caught, among them the fixed
//! pair's two-ray rule (ray A under AllHit's bounds); single rays get one sound answer from both testers;
//! the waveform's latency; the exported Verilog (Verilator lint, Icarus, Verilator cross-simulation
//! against the rust-hdl simulation and the model). The 13-clock pairs (`BundleFloatFp16P13` ..., every
//! optional cut of the adders and multipliers) get the same checks. Each test prints its counts and
//! time (run with `--nocapture`).

use golden::bundle::edge::ray_hits_exact;
use golden::bundle::float::{all_hit_float, all_miss_float, FloatBundle};
use golden::bundle::gen::{BundleGen, BundleKind};
use golden::format::float::FloatFormat;
use rtl::bundle::pair_float::{BundleFloatIo, FloatPairInput};
use rtl::export::bundle_float_verilog_of;
use std::time::Instant;
use tb::bundle::pair_float::{
    bundle_float_model, bundle_float_rtl, bundle_float_vectors, quantised, ray_bundle,
    two_ray_share_vectors, FloatBundleVec, PairFloatCtx,
};
use tb::campaign::campaign_bounds;
use tb::dut::run_checked;
use tb::plane::float::with_big_stack;
use tb::vcd_read::read_trace;
use tb::xsim::xsim;

fn rtl_matches_model<S: BundleFloatIo + 'static>(n: u64, seed: u64) {
    with_big_stack(move || {
        let f = S::format();
        let start = Instant::now();
        let mut dut = bundle_float_rtl::<S>();
        let tests: Vec<_> = bundle_float_vectors(f, seed, n, true).collect();
        let answers = tests
            .iter()
            .flatten()
            .map(|v| bundle_float_model(&f, v))
            .fold([0usize; 4], |mut c, (h, m)| {
                c[h as usize + 2 * m as usize] += 1;
                c
            });
        let done = run_checked(&mut dut, tests, |v| bundle_float_model(&f, v))
            .unwrap_or_else(|e| panic!("{}: {e}", f.name()));
        assert_eq!(done, n as usize);
        println!(
            "{}: {done} tests match in {:.1} s (all hit {}, all miss {}, neither {}, both {} (two rays, raw))",
            f.name(),
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
    })
}

#[test]
fn rtl_matches_model_fp16() {
    rtl_matches_model::<rtl::BundleFloatFp16>(20_000, 1);
}

#[test]
fn rtl_matches_model_bf16() {
    rtl_matches_model::<rtl::BundleFloatBf16>(20_000, 2);
}

#[test]
fn rtl_matches_model_fp32() {
    rtl_matches_model::<rtl::BundleFloatFp32>(20_000, 3);
}

#[test]
fn rtl_matches_model_13_clocks() {
    rtl_matches_model::<rtl::BundleFloatFp16P13>(10_000, 11);
    rtl_matches_model::<rtl::BundleFloatBf16P13>(10_000, 12);
    rtl_matches_model::<rtl::BundleFloatFp32P13>(10_000, 13);
}

/// The equivalence check can fail: a model that judges AllHit with AnyHit's bounds (outer box, `t_hi`)
/// and AnyHit with AllHit's disagrees with the RTL.
#[test]
fn a_wrong_model_is_caught() {
    with_big_stack(|| {
        let f = FloatFormat::FP16;
        let mut dut = bundle_float_rtl::<rtl::BundleFloatFp16>();
        let swap_t = |b: &FloatBundle| FloatBundle {
            t_lo: b.t_hi,
            t_hi: b.t_lo,
            ..*b
        };
        let swapped = |v: &FloatBundleVec| {
            let ((a, b), p) = (v.0.sides(), v.1);
            (
                all_hit_float(&f, &swap_t(a), &p.outer),
                all_miss_float(&f, &swap_t(b), &p.inner),
            )
        };
        let err = run_checked(&mut dut, bundle_float_vectors(f, 4, 5_000, false), swapped)
            .expect_err("a wrong model must be caught");
        println!("caught: {err}");
    })
}

/// The fixed pair's two-ray rule, ray A under AllHit's bounds (inner box, `t_lo`), is not what the float
/// pair computes (both rays under AnyHit's), and the check sees it on two-ray inputs alone.
#[test]
fn two_rays_under_all_hit_bounds_is_caught() {
    with_big_stack(|| {
        let f = FloatFormat::BF16;
        let mut dut = bundle_float_rtl::<rtl::BundleFloatBf16>();
        let fixed_rule = |v: &FloatBundleVec| {
            let ((a, b), p) = (v.0.sides(), v.1);
            (
                all_hit_float(&f, a, &p.inner),
                all_miss_float(&f, b, &p.outer),
            )
        };
        let tests = two_ray_share_vectors(f, 5, 5_000, false, 8);
        let err = run_checked(&mut dut, tests, fixed_rule)
            .expect_err("the fixed pair's two-ray rule must be caught");
        println!("caught: {err}");
    })
}

/// Two copies of one single ray, one per tester, get one answer: "A may hit" exactly when "B does not
/// miss" (both testers run AnyHit's bounds), the RTL gives it bit for bit, and it is sound: every ray that
/// hits its box (exact oracle) may hit. Printed: how many hitting rays AllHit's bounds on the tiny bundle
/// (the fixed pair's rule) would have called misses.
#[test]
fn one_ray_on_both_testers_gets_one_sound_answer() {
    with_big_stack(|| {
        let f = FloatFormat::FP16;
        let (lo, hi) = campaign_bounds();
        let mut gen = BundleGen::new(9, lo, hi, 1.0);
        let mut tests = vec![];
        let mut truth = vec![];
        while tests.len() < 4_000 {
            let c = gen.case(if tests.len() % 2 == 0 {
                BundleKind::Grazing
            } else {
                BundleKind::TmaxAtFace
            });
            let r = &c.rays[tests.len() % c.rays.len()];
            let (Ok(a), Some((_, p))) = (ray_bundle(&f, r), quantised(&f, &c.bundle, &c.bounds))
            else {
                continue;
            };
            truth.push(ray_hits_exact(r, &c.bounds).unwrap());
            tests.push(Some((FloatPairInput::TwoRays(a, a), p)));
        }
        let (mut hits, mut may_hit, mut all_hit_misses) = (0, 0, 0);
        for (v, &hit) in tests.iter().flatten().zip(&truth) {
            let (a_may_hit, b_misses) = bundle_float_model(&f, v);
            assert_eq!(a_may_hit, !b_misses, "{v:?}");
            assert!(a_may_hit || !hit, "a hitting ray is called a miss: {v:?}");
            hits += hit as usize;
            may_hit += a_may_hit as usize;
            let FloatPairInput::TwoRays(a, _) = v.0 else {
                unreachable!()
            };
            all_hit_misses += (hit && !all_hit_float(&f, &a, &v.1.inner)) as usize;
        }
        assert!(
            hits > 100 && hits < tests.len() - 100,
            "degenerate: {hits} hits"
        );
        let mut dut = bundle_float_rtl::<rtl::BundleFloatFp16>();
        let n = run_checked(&mut dut, tests, |v| bundle_float_model(&f, v))
            .unwrap_or_else(|e| panic!("{e}"));
        println!(
            "{n} single rays: {hits} hit (exact), {may_hit} may hit (RTL, both testers alike); \
             AllHit's bounds would have called {all_hit_misses} hitting rays misses"
        );
    })
}

/// The waveform of an isolated test and three back to back: `valid_out` rises exactly the pair's
/// latency (9 clocks, 13 for the deep pair) after `valid_in`.
fn valid_leaves_latency_clocks_after_it_enters<S: BundleFloatIo + 'static>() {
    with_big_stack(|| {
        let f = S::format();
        let path = tb::out_dir().join("vcd").join(format!(
            "{}_latency.vcd",
            rtl::names::bundle_float_of::<S>()
        ));
        let tests: Vec<_> = bundle_float_vectors(f, 5, 4, false).collect();
        let mut stream = vec![tests[0]];
        stream.extend(std::iter::repeat_n(None, 16));
        stream.extend(tests[1..].iter().cloned());
        {
            let mut dut = bundle_float_rtl::<S>().vcd_to(&path).unwrap();
            let n = run_checked(&mut dut, stream, |v| bundle_float_model(&f, v))
                .unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(n, 4);
        }
        let trace = read_trace(&path, &["valid_in", "valid_out"]).unwrap();
        trace
            .check_valid_latency(2, S::LATENCY)
            .unwrap_or_else(|e| panic!("{e}"));
    })
}

#[test]
fn valid_leaves_latency_clocks_after_it_enters_fp16() {
    assert_eq!(<rtl::BundleFloatFp16 as rtl::TesterIo>::LATENCY, 9);
    valid_leaves_latency_clocks_after_it_enters::<rtl::BundleFloatFp16>();
}

#[test]
fn valid_leaves_latency_clocks_after_it_enters_13_clocks() {
    assert_eq!(<rtl::BundleFloatFp16P13 as rtl::TesterIo>::LATENCY, 13);
    valid_leaves_latency_clocks_after_it_enters::<rtl::BundleFloatFp16P13>();
}

fn export<S: BundleFloatIo + 'static>() -> (String, std::path::PathBuf) {
    let v = with_big_stack(bundle_float_verilog_of::<S>);
    let path = tb::verilog_tools::write(&v, &rtl::names::bundle_float_of::<S>());
    (v, path)
}

#[test]
fn exported_verilog_is_lint_clean_and_accepted_by_icarus() {
    for path in [
        export::<rtl::BundleFloatFp16>().1,
        export::<rtl::BundleFloatBf16>().1,
        export::<rtl::BundleFloatFp32>().1,
        export::<rtl::BundleFloatFp16P13>().1,
        export::<rtl::BundleFloatBf16P13>().1,
        export::<rtl::BundleFloatFp32P13>().1,
    ] {
        tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
        tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    }
}

/// Cycles also checked against the rust-hdl simulation.
const LOCKSTEP: u64 = 3_000;

fn cross_simulate<S: BundleFloatIo + 'static>(n: u64, seed: u64) {
    let f = S::format();
    let start = Instant::now();
    let (v, _) = export::<S>();
    let h = tb::verilator::build(
        &v,
        &rtl::names::bundle_float_of::<S>(),
        &tb::out_dir().join("verilator"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let built = start.elapsed().as_secs_f64();
    let stats = with_big_stack(move || {
        xsim(
            PairFloatCtx(f),
            || S::for_format(&f),
            &h,
            bundle_float_vectors(f, seed, n, true),
            LOCKSTEP,
            |_| {},
        )
    })
    .unwrap_or_else(|e| panic!("{}: {e}", f.name()));
    println!(
        "{}: {stats:?} (harness ready in {built:.1} s, {:.1} s in all)",
        f.name(),
        start.elapsed().as_secs_f64()
    );
    assert_eq!(stats.tests, n);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
}

#[test]
fn verilator_matches_rtl_and_model_fp16() {
    cross_simulate::<rtl::BundleFloatFp16>(200_000, 6);
}

#[test]
fn verilator_matches_rtl_and_model_bf16() {
    cross_simulate::<rtl::BundleFloatBf16>(200_000, 7);
}

#[test]
fn verilator_matches_rtl_and_model_fp32() {
    cross_simulate::<rtl::BundleFloatFp32>(200_000, 8);
}

#[test]
fn verilator_matches_rtl_and_model_13_clocks() {
    cross_simulate::<rtl::BundleFloatFp16P13>(200_000, 16);
    cross_simulate::<rtl::BundleFloatBf16P13>(200_000, 17);
    cross_simulate::<rtl::BundleFloatFp32P13>(200_000, 18);
}

/// Synchronous reset of the float pair (`tb::reset`): as for the fixed pair.
fn reset_clears_every_valid_bit<S: BundleFloatIo + 'static>() {
    let f = S::format();
    let (v, _) = export::<S>();
    let name = rtl::names::bundle_float_of::<S>();
    let s = with_big_stack(move || {
        let tests: Vec<_> = bundle_float_vectors(f, 42, 300, false).flatten().collect();
        tb::reset::check_block(PairFloatCtx(f), || S::for_format(&f), &tests, &name, &v, 42)
    })
    .unwrap_or_else(|e| panic!("{e}"));
    s.both_sides().unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn reset_clears_every_valid_bit_fp16() {
    reset_clears_every_valid_bit::<rtl::BundleFloatFp16>();
}

#[test]
fn reset_clears_every_valid_bit_fp16_13_clocks() {
    reset_clears_every_valid_bit::<rtl::BundleFloatFp16P13>();
}
