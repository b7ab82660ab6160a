//! The chained float node testers' exported Verilog: lint-clean under `verilator --lint-only -Wall`,
//! accepted by Icarus, and bit-exact in Verilator with the model (`node_float`) on every vector and with
//! the rust-hdl simulation (every output, every cycle) over the first 3,000 cycles — 100,000 cycles for
//! binary16 with two planes, 20,000 for binary16 K = 1, 4 and bfloat16 K = 2, 10,000 for binary32 K = 2;
//! the other configurations (bfloat16 K = 1, 4, binary32 K = 1, 4) are linted and compiled by Icarus
//! only, to keep the Verilator builds (about half a minute each) down. Vectors: valid quantised world nodes with
//! fitted planes, raw bit patterns every third test, a bubble every ninth cycle.

use golden::plane::float::CullFloatFormat;
use rtl::export::plane_float_verilog;
use rtl::names::plane_float_module;
use rtl::plane::float::PlaneFloatIo;
use tb::plane::float::{node_stream, with_big_stack, CullFloatCtx};
use tb::xsim::xsim;

/// Cycles also checked against the rust-hdl simulation (about 2,000 cycles/s there).
const LOCKSTEP: u64 = 3_000;

/// Lint, Icarus, and (unless `cycles` is 0) Verilator cross-simulation over `cycles` cycles.
fn check<P: PlaneFloatIo>(cycles: u64, seed: u64) {
    let (f, k) = (P::format(), P::planes());
    let cf = CullFloatFormat::over(f);
    let module = plane_float_module(&cf, k);
    let v = with_big_stack(move || plane_float_verilog(&f, k).unwrap());
    let path = tb::verilog_tools::write(&v, &module);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    if cycles == 0 {
        return; // lint and Icarus only (each Verilator build costs about half a minute)
    }
    let h = tb::verilator::build(&v, &module, &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let ctx = CullFloatCtx::new(cf, k);
    let t0 = std::time::Instant::now();
    let stats = with_big_stack(move || {
        let vectors = node_stream(ctx, seed, 3, 9).take(cycles as usize);
        xsim(ctx, P::make, &h, vectors, LOCKSTEP, |_| {})
    })
    .unwrap_or_else(|e| panic!("{module}: {e}"));
    eprintln!(
        "{module}: {} tests ({} hits) in {:.1} s",
        stats.tests,
        stats.hits,
        t0.elapsed().as_secs_f64()
    );
    assert_eq!(stats.tests, cycles - cycles / 9);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
}

#[test]
fn e5m10_k1() {
    check::<rtl::PlaneFloatE5M10K1>(20_000, 11);
}
#[test]
fn e5m10_k2() {
    check::<rtl::PlaneFloatE5M10K2>(100_000, 12);
}
#[test]
fn e5m10_k4() {
    check::<rtl::PlaneFloatE5M10K4>(20_000, 14);
}
#[test]
fn e8m7_k1() {
    check::<rtl::PlaneFloatE8M7K1>(0, 21);
}
#[test]
fn e8m7_k2() {
    check::<rtl::PlaneFloatE8M7K2>(20_000, 22);
}
#[test]
fn e8m7_k4() {
    check::<rtl::PlaneFloatE8M7K4>(0, 24);
}
#[test]
fn e8m23_k1() {
    check::<rtl::PlaneFloatE8M23K1>(0, 31);
}
#[test]
fn e8m23_k2() {
    check::<rtl::PlaneFloatE8M23K2>(10_000, 32);
}
#[test]
fn e8m23_k4() {
    check::<rtl::PlaneFloatE8M23K4>(0, 34);
}

/// Synchronous reset of the float cull-plane tester (`tb::reset`): a test met by a reset never leaves,
/// every other leaves on time with the model's result, and Verilator agrees with rust-hdl clock by clock.
#[test]
fn reset_clears_every_valid_bit_e5m10_k1() {
    type P = rtl::PlaneFloatE5M10K1;
    let (f, k) = (P::format(), P::planes());
    let cf = CullFloatFormat::over(f);
    let module = plane_float_module(&cf, k);
    let v = with_big_stack(move || plane_float_verilog(&f, k).unwrap());
    let ctx = CullFloatCtx::new(cf, k);
    let s = with_big_stack(move || {
        let tests: Vec<_> = node_stream(ctx, 34, 3, 0).take(300).flatten().collect();
        tb::reset::check_block(ctx, P::make, &tests, &module, &v, 34)
    })
    .unwrap_or_else(|e| panic!("{e}"));
    s.both_sides().unwrap_or_else(|e| panic!("{e}"));
}
