//! The exported Verilog of every preset slab tester, at 4 and at 6 clocks: lint-clean under `verilator --lint-only -Wall` (with
//! the one-line waivers in rtl/lint/verilator_waiver.vlt), accepted by Icarus, and bit-exact with the
//! rust-hdl simulation and the model in Verilator over 100,000 vectors per configuration.
//! The tools are installed by scripts/test; a missing tool fails these tests rather than skipping them.

use golden::format::fixed::FixFormat;
use golden::slab::gen::GenKind;
use rtl::export::{catalog, slab_fix_verilog_of, Family};
use rtl::names::slab_fix_module_cuts;
use rtl::slab::fix::SlabFixIo;
use rust_hdl::prelude::Block;
use std::path::PathBuf;
use tb::campaign::slab_vectors;
use tb::xsim::xsim;

/// `(module, Verilog, path)` of every exported fixed slab tester: the presets at 4 and at 6 clocks.
fn every_module() -> Vec<(String, String, PathBuf)> {
    catalog()
        .into_iter()
        .filter(|e| matches!(e.family, Family::SlabFix { .. }))
        .map(|e| {
            let v = e.verilog();
            let path = tb::verilog_tools::write(&v, &e.module);
            (e.module, v, path)
        })
        .collect()
}

#[test]
fn exported_verilog_is_lint_clean() {
    let all = every_module();
    assert_eq!(all.len(), 6);
    for (m, v, path) in all {
        assert!(
            v.contains(&format!("module {m}(")),
            "module name carries the format"
        );
        tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    }
}

#[test]
fn icarus_accepts_exported_verilog() {
    for (_, _, path) in every_module() {
        tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    }
}

/// The Verilog of block `S` for `fmt`, written to `out/verilog`, with its module name.
fn export<S: SlabFixIo + Block>(fmt: &FixFormat) -> (String, String) {
    let v = slab_fix_verilog_of::<S>(fmt);
    let m = slab_fix_module_cuts(fmt, S::CUTS);
    tb::verilog_tools::write(&v, &m);
    (v, m)
}

const XSIM_VECTORS: u64 = 100_000;

fn cross_simulate<S: SlabFixIo + Block>(fmt: FixFormat, seed: u64) {
    let (v, m) = export::<S>(&fmt);
    let h = tb::verilator::build(&v, &m, &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let vectors = slab_vectors(fmt, GenKind::Mixed, seed, XSIM_VECTORS, true);
    let stats = xsim(fmt, || S::for_format(&fmt), &h, vectors, u64::MAX, |_| {})
        .unwrap_or_else(|e| panic!("{}: {e}", fmt.name()));
    assert_eq!(stats.tests, XSIM_VECTORS);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
    assert!(stats.cycles > stats.tests, "bubbles were driven: {stats:?}");
}

#[test]
fn verilator_matches_rtl_and_model_b8() {
    cross_simulate::<rtl::SlabFixB8>(FixFormat::b8(), 1);
}

#[test]
fn verilator_matches_rtl_and_model_b12() {
    cross_simulate::<rtl::SlabFixB12>(FixFormat::b12(), 2);
}

#[test]
fn verilator_matches_rtl_and_model_b16() {
    cross_simulate::<rtl::SlabFixB16>(FixFormat::b16(), 3);
}

#[test]
fn verilator_matches_rtl_and_model_b12_6_clocks() {
    cross_simulate::<rtl::SlabFixB12P6>(FixFormat::b12(), 5);
}

#[test]
fn verilator_matches_rtl_and_model_b16_6_clocks() {
    cross_simulate::<rtl::SlabFixB16P6>(FixFormat::b16(), 6);
}

/// Cross-simulation can fail: driving the b8 Verilog as if it were the b12 tester is caught within a few
/// cycles, and the failure leaves a waveform of the last cycles.
#[test]
fn a_wrong_verilog_is_caught_and_leaves_a_vcd() {
    let (v, m) = export::<rtl::SlabFixB8>(&FixFormat::b8());
    let h = tb::verilator::build(&v, &m, &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let b12 = FixFormat::b12();
    let vectors = slab_vectors(b12, GenKind::Mixed, 4, 10_000, true);
    let err = xsim(
        b12,
        || rtl::SlabFixB12::new(&b12),
        &h,
        vectors,
        u64::MAX,
        |_| {},
    )
    .expect_err("b8 Verilog passed as b12");
    let vcd = err.rsplit("(rust-hdl): ").next().unwrap().trim();
    assert!(
        std::path::Path::new(vcd).exists(),
        "no VCD at `{vcd}`: {err}"
    );
}
