//! Synchronous reset of the slab testers: `rst` raised at random clocks (and for four clocks in a row)
//! while tests stream through; in the rust-hdl simulation every test met by a reset never leaves and every
//! other leaves on time with the model's result and its tag, and the exported Verilog in Verilator gives
//! the same outputs clock by clock (`tb::reset`). A VCD of each run is written to `out/vcd/`.

use golden::format::fixed::FixFormat;
use golden::slab::gen::GenKind;
use rtl::slab::fix::SlabFixIo;
use rtl::slab::float::SlabFloatIo;
use tb::campaign::slab_vectors;
use tb::reset::check_block;

const TESTS: usize = 400;

fn fix<S: SlabFixIo>(fmt: FixFormat, seed: u64) {
    let module = rtl::names::slab_fix_module_cuts(&fmt, S::CUTS);
    let v = rtl::export::slab_fix_verilog_of::<S>(&fmt);
    let tests: Vec<_> = slab_vectors(fmt, GenKind::Mixed, seed, TESTS as u64, false)
        .flatten()
        .collect();
    let s = check_block(fmt, || S::for_format(&fmt), &tests, &module, &v, seed)
        .unwrap_or_else(|e| panic!("{e}"));
    s.both_sides().unwrap_or_else(|e| panic!("{module}: {e}"));
}

#[test]
fn fix_b12_reset_clears_every_valid_bit() {
    fix::<rtl::SlabFixB12>(FixFormat::b12(), 1);
}

#[test]
fn fix_b12_6_clocks_reset_clears_every_valid_bit() {
    fix::<rtl::SlabFixB12P6>(FixFormat::b12(), 2);
}

fn float<S: SlabFloatIo>(seed: u64) {
    use golden::slab::float::{quantize_box, quantize_ray};
    let f = S::format();
    let module = rtl::names::slab_float_module_cuts(&f, S::CUTS);
    let v = rtl::export::slab_float_verilog_of::<S>();
    let (lo, hi) = tb::campaign::campaign_bounds();
    let tests: Vec<_> = golden::slab::gen::SlabGen::new(GenKind::Mixed, lo, hi, 1.0 / 64.0, seed)
        .take(TESTS)
        .map(|(r, b)| (quantize_ray(&f, &r).unwrap(), quantize_box(&f, &b).unwrap()))
        .collect();
    let s = check_block(f, S::make, &tests, &module, &v, seed).unwrap_or_else(|e| panic!("{e}"));
    s.both_sides().unwrap_or_else(|e| panic!("{module}: {e}"));
}

#[test]
fn float_e5m10_reset_clears_every_valid_bit() {
    tb::plane::float::with_big_stack(|| float::<rtl::SlabFloatE5M10>(3));
}

#[test]
fn float_e5m10_13_clocks_reset_clears_every_valid_bit() {
    tb::plane::float::with_big_stack(|| float::<rtl::SlabFloatE5M10P13>(4));
}
