//! The fixed-point chained slab + cull-plane tester: rust-hdl simulation bit for bit against
//! `golden::plane::fix::node_fix` (latency, tag order, bubbles, raw and quantised vectors), its waveform,
//! the exported Verilog (lint, Icarus, Verilator cross-simulation against rust-hdl and the model), and the
//! model's conservativeness against the exact clip and the exact triangle test.

use golden::format::fixed::FixFormat;
use golden::plane::fix::{CullFixFormat, MAX_PLANES};
use rtl::plane::fix::PlaneFixIo;
use tb::dut::run_checked;
use tb::plane::fix::{cull_fix_campaign, node_fix_vectors, CullFixCtx};
use tb::rtl_sim::TesterSim;
use tb::vcd_read::read_trace;
use tb::xsim::{xsim, BlockCtx};

fn ctx(fmt: FixFormat, k: usize) -> CullFixCtx {
    CullFixCtx {
        cf: CullFixFormat::over(fmt),
        k,
    }
}

fn rtl_matches_model<S: PlaneFixIo>(fmt: FixFormat, n: u64, seed: u64) {
    let c = ctx(fmt, S::PLANES);
    let mut dut = TesterSim::wrap(S::for_format(&c.cf));
    let stream = node_fix_vectors(c, seed, n, true);
    let done = run_checked(&mut dut, stream, |v| c.model(&v.0, &v.1))
        .unwrap_or_else(|e| panic!("{}: {e}", c.name()));
    assert_eq!(done, n as usize);
}

#[test]
fn rtl_matches_model_b12_k1() {
    rtl_matches_model::<rtl::PlaneFixB12<1>>(FixFormat::b12(), 20_000, 1);
}

#[test]
fn rtl_matches_model_b12_k4() {
    rtl_matches_model::<rtl::PlaneFixB12<4>>(FixFormat::b12(), 20_000, 2);
}

#[test]
fn rtl_matches_model_b8_k8() {
    rtl_matches_model::<rtl::PlaneFixB8<8>>(FixFormat::b8(), 10_000, 3);
}

#[test]
fn rtl_matches_model_b16_k2() {
    rtl_matches_model::<rtl::PlaneFixB16<2>>(FixFormat::b16(), 10_000, 4);
}

/// The 11-clock configuration (every sums and bound cut, the 6-clock slab tester, three wait
/// registers) computes the same results as the model, five clocks later.
#[test]
fn rtl_matches_model_b12_k4_p11() {
    assert_eq!(<rtl::PlaneFixB12P11<4> as rtl::TesterIo>::LATENCY, 11);
    rtl_matches_model::<rtl::PlaneFixB12P11<4>>(FixFormat::b12(), 20_000, 12);
}

#[test]
fn rtl_matches_model_b8_k8_p11() {
    rtl_matches_model::<rtl::PlaneFixB8P11<8>>(FixFormat::b8(), 10_000, 13);
}

#[test]
fn rtl_matches_model_b16_k1_p11() {
    rtl_matches_model::<rtl::PlaneFixB16P11<1>>(FixFormat::b16(), 10_000, 14);
}

/// Every depth between the default and the deepest: each sums and bound cut alone, some in pairs and
/// all together, with the slab tester at 4 clocks (waits 0 to 5) or 6 (waits 0 to 3), is the model,
/// `latency` clocks later.
#[test]
fn rtl_matches_model_at_every_depth_b8_k2() {
    use rtl::plane::fix::cut;
    use rtl::slab::fix::{SLAB_FIX_CUTS as S4, SLAB_FIX_CUTS_DEEP as S6};
    type P<const S: usize, const C: usize> =
        rtl::plane::fix::PlaneFix<8, 9, 12, 14, 8, 11, 20, 21, 20, 2, S, C>;
    fn one<X: PlaneFixIo>(want_latency: usize) {
        assert_eq!(X::LATENCY, want_latency);
        rtl_matches_model::<X>(FixFormat::b8(), 3_000, 20 + want_latency as u64);
    }
    one::<P<S4, { cut::PICK }>>(7);
    one::<P<S4, { cut::TABLE }>>(7);
    one::<P<S4, { cut::PRODUCT }>>(7);
    one::<P<S4, { cut::PICK | cut::PRODUCT }>>(8);
    one::<P<S4, { cut::BOUND_STEPS }>>(9);
    one::<P<S6, { cut::TABLE | cut::PRODUCT }>>(8);
    one::<P<S4, { cut::TERMS }>>(7);
    one::<P<S4, { cut::PRODUCTS }>>(7);
    one::<P<S6, { cut::SUM_STEPS }>>(8);
    one::<P<S6, { cut::PRODUCTS | cut::PICK | cut::TABLE }>>(9);
    one::<P<S4, { cut::ALL }>>(11);
}

/// A configuration whose slab tester is longer than its plane path is refused, not run misaligned.
#[test]
#[should_panic(expected = "must not be longer than the plane path")]
fn a_slab_longer_than_the_plane_path_is_refused() {
    type P = rtl::plane::fix::PlaneFix<
        8,
        9,
        12,
        14,
        8,
        11,
        20,
        21,
        20,
        1,
        { rtl::slab::fix::SLAB_FIX_CUTS_DEEP },
        0,
    >;
    let _ = P::for_format(&CullFixFormat::over(FixFormat::b8()));
}

/// The equivalence check can fail: a model with the planes ignored disagrees with the RTL.
#[test]
fn a_wrong_model_is_caught() {
    let c = ctx(FixFormat::b12(), 2);
    let mut dut = TesterSim::wrap(rtl::PlaneFixB12::<2>::new(&c.cf));
    let stream = node_fix_vectors(c, 5, 5_000, false);
    let wrong = CullFixCtx { k: 0, ..c };
    assert!(run_checked(&mut dut, stream, |v| wrong.model(&v.0, &v.1)).is_err());
}

/// In the waveform, `valid_out` rises exactly the configuration's latency after `valid_in`.
fn valid_leaves_latency_clocks_after_it_enters<S: PlaneFixIo>(want: usize) {
    let c = ctx(FixFormat::b12(), S::PLANES);
    let name = rtl::names::plane_fix_module_of::<S>(&c.cf);
    let path = tb::out_dir()
        .join("vcd")
        .join(format!("{name}_latency.vcd"));
    let tests: Vec<_> = node_fix_vectors(c, 6, 4, false).collect();
    let mut stream = vec![tests[0]];
    stream.extend(std::iter::repeat_n(None, 12));
    stream.extend(tests[1..].iter().cloned());
    {
        let mut dut = TesterSim::wrap(S::for_format(&c.cf)).vcd_to(&path).unwrap();
        let n = run_checked(&mut dut, stream, |v| c.model(&v.0, &v.1))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(n, 4);
    }
    let trace = read_trace(&path, &["valid_in", "valid_out"]).unwrap();
    trace
        .check_valid_latency(2, want)
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn valid_leaves_6_clocks_after_it_enters() {
    valid_leaves_latency_clocks_after_it_enters::<rtl::PlaneFixB12<2>>(
        rtl::plane::fix::PLANE_FIX_LATENCY,
    );
}

#[test]
fn valid_leaves_11_clocks_after_it_enters_in_the_deep_configuration() {
    valid_leaves_latency_clocks_after_it_enters::<rtl::PlaneFixB12P11<2>>(11);
}

/// `(module name, Verilog, path)` of the tester `S` over `c`'s format, written for the tools.
fn export<S: PlaneFixIo>(c: &CullFixCtx) -> (String, String, std::path::PathBuf) {
    let name = rtl::names::plane_fix_module_of::<S>(&c.cf);
    let v = rtl::verilog::verilog_named(&mut S::for_format(&c.cf), &name);
    let path = tb::verilog_tools::write(&v, &name);
    (name, v, path)
}

#[test]
fn exported_verilog_is_lint_clean_and_accepted_by_icarus() {
    let c = ctx(FixFormat::b12(), 4);
    let (_, _, path) = export::<rtl::PlaneFixB12<4>>(&c);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    let (_, _, path) = export::<rtl::PlaneFixB12P11<4>>(&c);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    let c = ctx(FixFormat::b16(), 1);
    let (_, _, path) = export::<rtl::PlaneFixB16<1>>(&c);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    let (name, _, path) = export::<rtl::PlaneFixB16P11<1>>(&c);
    assert!(name.ends_with("_k1_p11"), "{name}");
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
}

fn cross_simulate<S: PlaneFixIo>(fmt: FixFormat, n: u64, lockstep: u64, seed: u64) {
    let c = ctx(fmt, S::PLANES);
    let (name, v, _) = export::<S>(&c);
    let h = tb::verilator::build(&v, &name, &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let stats = xsim(
        c,
        || S::for_format(&c.cf),
        &h,
        node_fix_vectors(c, seed, n, true),
        lockstep,
        |_| {},
    )
    .unwrap_or_else(|e| panic!("{}: {e}", c.name()));
    assert_eq!(stats.tests, n);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
}

#[test]
fn verilator_matches_rtl_and_model_b12_k4() {
    cross_simulate::<rtl::PlaneFixB12<4>>(FixFormat::b12(), 100_000, 20_000, 7);
}

#[test]
fn verilator_matches_rtl_and_model_b8_k8() {
    cross_simulate::<rtl::PlaneFixB8<8>>(FixFormat::b8(), 50_000, 10_000, 8);
}

#[test]
fn verilator_matches_rtl_and_model_b16_k1() {
    cross_simulate::<rtl::PlaneFixB16<1>>(FixFormat::b16(), 50_000, 10_000, 9);
}

#[test]
fn verilator_matches_rtl_and_model_b12_k4_p11() {
    cross_simulate::<rtl::PlaneFixB12P11<4>>(FixFormat::b12(), 100_000, 20_000, 17);
}

#[test]
fn verilator_matches_rtl_and_model_b16_k1_p11() {
    cross_simulate::<rtl::PlaneFixB16P11<1>>(FixFormat::b16(), 50_000, 10_000, 18);
}

/// Conservativeness of the model: the interval encloses the exact clip, nothing the exact clip keeps is
/// culled, and no ray that truly hits the node's triangle is culled — uniform and adversarial cases, every
/// preset, one to eight planes.
#[test]
fn model_is_conservative() {
    for fmt in FixFormat::presets() {
        for k in [1, 4, MAX_PLANES] {
            for (seed, adv) in [(10, 0.0), (11, 1.0)] {
                let st = cull_fix_campaign(ctx(fmt, k), seed + k as u64, 20_000, adv, |_| {})
                    .unwrap_or_else(|e| panic!("{e}"));
                assert_eq!(st.violations, 0);
                assert!(
                    st.culled > 0 && st.tri_hits > 0,
                    "{} k{k}: {st:?}",
                    fmt.name()
                );
                assert!(
                    st.culled <= st.exact_culled,
                    "culls only what the exact clip culls"
                );
            }
        }
    }
}

/// Synchronous reset (`tb::reset`): `rst` at random clocks while node tests stream; a test met by a
/// reset never leaves, every other leaves on time with the model's result, and Verilator agrees with
/// rust-hdl clock by clock.
fn reset_clears_every_valid_bit<S: PlaneFixIo>(fmt: FixFormat, seed: u64) {
    let c = ctx(fmt, S::PLANES);
    let (name, v, _) = export::<S>(&c);
    let tests: Vec<_> = node_fix_vectors(c, seed, 400, false).flatten().collect();
    let s = tb::reset::check_block(c, || S::for_format(&c.cf), &tests, &name, &v, seed)
        .unwrap_or_else(|e| panic!("{e}"));
    s.both_sides().unwrap_or_else(|e| panic!("{name}: {e}"));
}

#[test]
fn reset_clears_every_valid_bit_b12_k4() {
    reset_clears_every_valid_bit::<rtl::PlaneFixB12<4>>(FixFormat::b12(), 31);
}

#[test]
fn reset_clears_every_valid_bit_b12_k4_11_clocks() {
    reset_clears_every_valid_bit::<rtl::PlaneFixB12P11<4>>(FixFormat::b12(), 32);
}
