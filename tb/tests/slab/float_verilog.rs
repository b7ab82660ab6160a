//! The float slab testers' exported Verilog: lint-clean under `verilator --lint-only -Wall`, accepted by
//! Icarus, and bit-exact in Verilator with the rust-hdl simulation (every cycle) and the model over 100,000
//! vectors per format, and the same for the 13-clock tester in binary16 and binary32.

use golden::format::float::FloatFormat;
use golden::slab::float::{quantize_box, quantize_ray};
use golden::slab::gen::GenKind;
use rtl::export::slab_float_verilog_of;
use rtl::names::slab_float_module_cuts;
use rtl::slab::float::SlabFloatIo;
use tb::xsim::xsim;

const VECTORS: u64 = 100_000;

fn check<S: SlabFloatIo>(seed: u64) {
    let f = S::format();
    let module = slab_float_module_cuts(&f, S::CUTS);
    let v = slab_float_verilog_of::<S>();
    let path = tb::verilog_tools::write(&v, &module);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));

    let h = tb::verilator::build(&v, &module, &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let (lo, hi) = tb::campaign::campaign_bounds();
    let mut gen = golden::slab::gen::SlabGen::new(GenKind::Mixed, lo, hi, 1.0 / 64.0, seed);
    let vectors = (0..VECTORS).map(move |i| {
        if i % 9 == 8 {
            None // a bubble
        } else {
            let (r, b) = gen.next().expect("endless");
            Some((
                quantize_ray(&f, &r).expect("fits"),
                quantize_box(&f, &b).expect("fits"),
            ))
        }
    });
    let stats =
        xsim(f, S::make, &h, vectors, u64::MAX, |_| {}).unwrap_or_else(|e| panic!("{module}: {e}"));
    assert_eq!(stats.tests, VECTORS - VECTORS / 9);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
}

/// One test per instantiated float slab tester, and the list of what they run.
macro_rules! per_format {
    ($($name:ident: $t:ty = $seed:literal),* $(,)?) => {
        $(#[test]
        fn $name() {
            check::<$t>($seed);
        })*
        /// The formats the tests above run, in order.
        fn tested() -> Vec<FloatFormat> {
            vec![$(<$t as SlabFloatIo>::format()),*]
        }
    };
}

per_format! {
    e8m23: rtl::SlabFloatE8M23 = 1,
    e8m15: rtl::SlabFloatE8M15 = 2,
    e8m7: rtl::SlabFloatE8M7 = 3,
    e5m10: rtl::SlabFloatE5M10 = 4,
    e6m5: rtl::SlabFloatE6M5 = 5,
}

#[test]
fn e5m10_13_clocks() {
    check::<rtl::SlabFloatE5M10P13>(6);
}

#[test]
fn e8m23_13_clocks() {
    check::<rtl::SlabFloatE8M23P13>(7);
}

/// The tests above run exactly the formats the registry instantiates (`rtl::SLAB_FLOAT_FORMATS`), each
/// once, and the registry's dispatch of each format reaches the block the test ran for it.
#[test]
fn every_instantiated_format_is_covered() {
    let run = tested();
    assert_eq!(run, rtl::SLAB_FLOAT_FORMATS.to_vec());
    for f in &run {
        let reached = rtl::with_slab_float!(f, S, { S::format() }).unwrap();
        assert_eq!(reached, *f);
    }
}
