//! The format ladder (`golden::format::fixed::FixFormat::grid`, `golden::format::float::FloatFormat::LADDER`) in RTL:
//! every ladder format dispatches to an instantiated block; and for the smallest, a middle and the
//! largest fixed format (g6, g13, g20) and the smallest and a middle new float format (e5m3, e6m8):
//! - the rust-hdl simulation equals the bit-accurate model on a few thousand random vectors (quantised
//!   world vectors, raw codes of every field, bubbles; plus proptest bursts weighted to the extremes);
//! - the exported Verilog passes `verilator --lint-only -Wall` with the project waiver, and Verilator runs
//!   it bit-exact with the rust-hdl simulation and the model (the hand-written `MulRound` and `SigMul`
//!   Verilog at the new widths);
//! - the model is conservative against the exact oracle (no false miss, enclosing intervals).

use golden::format::fixed::{FixFormat, GRID_LADDER};
use golden::format::float::FloatFormat;
use golden::slab::fix::slab_fix;
use golden::slab::float::slab_float;
use golden::slab::gen::GenKind;
use proptest::test_runner::{Config, TestCaseError, TestRunner};
use rtl::export::{slab_fix_verilog_ladder, slab_float_verilog_ladder};
use rtl::names::{slab_fix_module, slab_float_module};
use rtl::slab::fix::SlabFixIo;
use rtl::slab::float::SlabFloatIo;
use rtl::TesterIo;
use std::cell::RefCell;
use tb::campaign::{conservative_campaign, float_campaign, float_vectors, slab_vectors};
use tb::dut::run_checked;
use tb::rtl_sim::TesterSim;
use tb::slab::strategies::{float_burst, slab_burst};
use tb::xsim::xsim;

/// Stream vectors per format (world, one in eight raw, bubbles) through the rust-hdl simulation.
const SIM_VECTORS: u64 = 3_000;
/// proptest bursts (1 to 8 tests each) per format, on top of the stream.
const BURSTS: u32 = 300;
/// Vectors per format through the exported Verilog in Verilator.
const XSIM_VECTORS: u64 = 20_000;
/// World vectors per format and generator kind for the conservativeness check.
const CAMPAIGN: u64 = 20_000;

fn grid(g: u32) -> FixFormat {
    FixFormat::grid(g).unwrap()
}

fn ef(e: u32, m: u32) -> FloatFormat {
    FloatFormat::new(e, m).unwrap()
}

// ---------------------------------------------------------------------------------------------------
// Dispatch: every ladder format has a block, formats off the ladder are errors.

#[test]
fn every_fixed_ladder_format_dispatches() {
    let grids: Vec<u32> = GRID_LADDER.collect();
    assert_eq!(rtl::SLAB_FIX_LADDER, grids.as_slice());
    for f in FixFormat::ladder() {
        let (g, i, t) = rtl::with_slab_fix_ladder!(&f, S, {
            // `SlabFix::new` asserts that the block's widths are the format's.
            let s = S::new(&f);
            drop(s);
            (f.g, f.i, f.t)
        })
        .unwrap_or_else(|e| panic!("{}: {e}", f.name()));
        assert_eq!((g, i, t), (f.g, f.i, f.t));
    }
    for f in FixFormat::presets() {
        assert!(rtl::with_slab_fix_ladder!(&f, S, { S::LATENCY }).is_ok());
    }
    // Off the ladder: the same G with another T, and a valid format of a width the ladder lacks.
    for f in [
        FixFormat::new(10, 14, 10, 16, 4).unwrap(),
        FixFormat::new(22, 26, 18, 30, 6).unwrap(),
    ] {
        let e = rtl::with_slab_fix_ladder!(&f, S, { S::LATENCY }).unwrap_err();
        assert!(
            e.contains("no RTL instance") && e.contains(&f.name()),
            "{e}"
        );
        assert!(slab_fix_verilog_ladder(&f).is_err());
    }
}

#[test]
fn every_float_ladder_format_dispatches() {
    assert_eq!(rtl::SLAB_FLOAT_LADDER, FloatFormat::LADDER.as_slice());
    for f in rtl::SLAB_FLOAT_FORMATS {
        assert!(rtl::SLAB_FLOAT_LADDER.contains(&f), "{}", f.name());
    }
    for f in FloatFormat::LADDER {
        let g = rtl::with_slab_float_ladder!(&f, S, {
            let s = S::new();
            drop(s);
            S::format()
        })
        .unwrap_or_else(|e| panic!("{}: {e}", f.name()));
        assert_eq!(g, f);
    }
    for f in [FloatFormat::E4M3, ef(5, 11), ef(8, 3)] {
        let e = rtl::with_slab_float_ladder!(&f, S, { S::LATENCY }).unwrap_err();
        assert!(
            e.contains("no RTL instance") && e.contains(&f.name()),
            "{e}"
        );
    }
}

// ---------------------------------------------------------------------------------------------------
// rust-hdl simulation against the bit-accurate model.

fn fix_matches_model<S: SlabFixIo>(fmt: FixFormat, seed: u64) {
    let dut = RefCell::new(TesterSim::<S>::new(&fmt));
    let vectors: Vec<_> = slab_vectors(fmt, GenKind::Mixed, seed, SIM_VECTORS, true).collect();
    let n = run_checked(&mut *dut.borrow_mut(), vectors, |v| {
        slab_fix(&fmt, &v.0, &v.1)
    })
    .unwrap_or_else(|m| panic!("{}: {m}", fmt.name()));
    assert_eq!(n as u64, SIM_VECTORS);
    let mut runner = TestRunner::new(Config {
        cases: BURSTS,
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(&slab_burst(fmt), |burst| {
            run_checked(&mut *dut.borrow_mut(), burst, |v| {
                slab_fix(&fmt, &v.0, &v.1)
            })
            .map(|_| ())
            .map_err(|m| TestCaseError::fail(m.to_string()))
        })
        .unwrap_or_else(|e| panic!("{}: {e}", fmt.name()));
}

fn float_matches_model<S: SlabFloatIo>(seed: u64) {
    let f = S::format();
    let dut = RefCell::new(TesterSim::<S>::float());
    let vectors: Vec<_> = float_vectors(f, GenKind::Mixed, seed, SIM_VECTORS, true).collect();
    let n = run_checked(&mut *dut.borrow_mut(), vectors, |v| {
        slab_float(&f, &v.0, &v.1)
    })
    .unwrap_or_else(|m| panic!("{}: {m}", f.name()));
    assert_eq!(n as u64, SIM_VECTORS);
    let mut runner = TestRunner::new(Config {
        cases: BURSTS,
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(&float_burst(f), |burst| {
            run_checked(&mut *dut.borrow_mut(), burst, |v| {
                slab_float(&f, &v.0, &v.1)
            })
            .map(|_| ())
            .map_err(|m| TestCaseError::fail(m.to_string()))
        })
        .unwrap_or_else(|e| panic!("{}: {e}", f.name()));
}

#[test]
fn rtl_matches_model_g6() {
    fix_matches_model::<rtl::SlabFixG6>(grid(6), 61);
}

#[test]
fn rtl_matches_model_g13() {
    fix_matches_model::<rtl::SlabFixG13>(grid(13), 131);
}

#[test]
fn rtl_matches_model_g20() {
    fix_matches_model::<rtl::SlabFixG20>(grid(20), 201);
}

#[test]
fn rtl_matches_model_e5m3() {
    float_matches_model::<rtl::SlabFloatE5M3>(53);
}

#[test]
fn rtl_matches_model_e6m8() {
    float_matches_model::<rtl::SlabFloatE6M8>(68);
}

/// The check can fail: the g13 block driven and judged as if it were g12 (another shift and t width) is
/// caught.
#[test]
fn a_block_of_another_ladder_format_is_caught() {
    let (g12, g13) = (grid(12), grid(13));
    let mut dut = TesterSim::<rtl::SlabFixG13>::new(&g13);
    let vectors: Vec<_> = slab_vectors(g12, GenKind::Mixed, 7, 2_000, true).collect();
    assert!(run_checked(&mut dut, vectors, |v| slab_fix(&g12, &v.0, &v.1)).is_err());
}

// ---------------------------------------------------------------------------------------------------
// Exported Verilog: lint, and cross-simulation in Verilator.

fn fix_verilog<S: SlabFixIo>(fmt: FixFormat, seed: u64) {
    let module = slab_fix_module(&fmt);
    let v = slab_fix_verilog_ladder(&fmt).unwrap();
    assert!(v.contains(&format!("module {module}(")), "{module}");
    let path = tb::verilog_tools::write(&v, &module);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    let h = tb::verilator::build(&v, &module, &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let vectors = slab_vectors(fmt, GenKind::Mixed, seed, XSIM_VECTORS, true);
    let stats = xsim(fmt, || S::for_format(&fmt), &h, vectors, u64::MAX, |_| {})
        .unwrap_or_else(|e| panic!("{module}: {e}"));
    assert_eq!(stats.tests, XSIM_VECTORS);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
}

fn float_verilog<S: SlabFloatIo>(seed: u64) {
    let f = S::format();
    let module = slab_float_module(&f);
    let v = slab_float_verilog_ladder(&f).unwrap();
    assert!(v.contains(&format!("module {module}(")), "{module}");
    let path = tb::verilog_tools::write(&v, &module);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    let h = tb::verilator::build(&v, &module, &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let vectors = float_vectors(f, GenKind::Mixed, seed, XSIM_VECTORS, true);
    let stats =
        xsim(f, S::make, &h, vectors, u64::MAX, |_| {}).unwrap_or_else(|e| panic!("{module}: {e}"));
    assert_eq!(stats.tests, XSIM_VECTORS);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
}

#[test]
fn verilog_g6() {
    fix_verilog::<rtl::SlabFixG6>(grid(6), 62);
}

#[test]
fn verilog_g13() {
    fix_verilog::<rtl::SlabFixG13>(grid(13), 132);
}

#[test]
fn verilog_g20() {
    fix_verilog::<rtl::SlabFixG20>(grid(20), 202);
}

#[test]
fn verilog_e5m3() {
    float_verilog::<rtl::SlabFloatE5M3>(54);
}

#[test]
fn verilog_e6m8() {
    float_verilog::<rtl::SlabFloatE6M8>(69);
}

// ---------------------------------------------------------------------------------------------------
// Conservativeness of the models against the exact oracle.

fn fix_conservative(fmt: FixFormat, seed: u64) {
    for (kind, s) in [(GenKind::Uniform, seed), (GenKind::Adversarial, seed + 1)] {
        let st = conservative_campaign(fmt, kind, CAMPAIGN, s, 2, &|_| {});
        assert_eq!(st.vectors, CAMPAIGN);
        assert!(st.true_hits > 0, "{} {kind:?}: no hits", fmt.name());
        assert_eq!(
            st.violation_count,
            0,
            "{} {kind:?}: {} violations, first:\n{}",
            fmt.name(),
            st.violation_count,
            st.violations.join("\n")
        );
    }
}

fn float_conservative(f: FloatFormat, seed: u64) {
    for (kind, s) in [(GenKind::Uniform, seed), (GenKind::Adversarial, seed + 1)] {
        let st = float_campaign(f, kind, CAMPAIGN, s, 2, &|_| {});
        assert_eq!(st.vectors, CAMPAIGN);
        assert!(st.true_hits > 0, "{} {kind:?}: no hits", f.name());
        assert_eq!(
            st.violation_count,
            0,
            "{} {kind:?}: {} violations, first:\n{}",
            f.name(),
            st.violation_count,
            st.violations.join("\n")
        );
    }
}

#[test]
fn conservative_g6() {
    fix_conservative(grid(6), 600);
}

#[test]
fn conservative_g13() {
    fix_conservative(grid(13), 1300);
}

#[test]
fn conservative_g20() {
    fix_conservative(grid(20), 2000);
}

#[test]
fn conservative_e5m3() {
    float_conservative(ef(5, 3), 530);
}

#[test]
fn conservative_e6m8() {
    float_conservative(ef(6, 8), 680);
}
