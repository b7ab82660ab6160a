//! Randomized equivalence: the rust-hdl `SlabFloat` against `golden::slab::float::slab_float`, bit for bit,
//! with latency and tag order checked by `tb::dut::run_checked`, per format. Every input field is drawn
//! from all patterns of the format (NaN and infinities included) or from quantised world vectors; a failing
//! case is shrunk and written out as a VCD named after the test and case.

use golden::slab::float::slab_float;
use rtl::slab::float::SlabFloatIo;
use tb::prop::shrinking_pipelined;
use tb::rtl_sim::SlabFloatRtl;
use tb::slab::strategies::float_burst;

const CASES: u32 = 3_000;

fn equivalence<S: SlabFloatIo>(name: &str) {
    equivalence_n::<S>(name, CASES);
}

fn equivalence_n<S: SlabFloatIo>(name: &str, cases: u32) {
    let f = S::format();
    shrinking_pipelined(
        name,
        cases,
        float_burst(f),
        |burst| burst.clone(),
        |vcd| match vcd {
            Some(p) => SlabFloatRtl::<S>::float_with_vcd(p).expect("VCD"),
            None => SlabFloatRtl::<S>::float(),
        },
        |v| slab_float(&f, &v.0, &v.1),
    );
}

#[test]
fn slab_float_e8m23_matches_model() {
    equivalence::<rtl::SlabFloatE8M23>("slab_float_e8m23");
}
#[test]
fn slab_float_e8m15_matches_model() {
    equivalence::<rtl::SlabFloatE8M15>("slab_float_e8m15");
}
#[test]
fn slab_float_e8m7_matches_model() {
    equivalence::<rtl::SlabFloatE8M7>("slab_float_e8m7");
}
#[test]
fn slab_float_e5m10_matches_model() {
    equivalence::<rtl::SlabFloatE5M10>("slab_float_e5m10");
}
#[test]
fn slab_float_e6m5_matches_model() {
    equivalence::<rtl::SlabFloatE6M5>("slab_float_e6m5");
}
#[test]
fn slab_float_e8m23_13_clocks_matches_model() {
    equivalence::<rtl::SlabFloatE8M23P13>("slab_float_e8m23_p13");
}
#[test]
fn slab_float_e5m10_13_clocks_matches_model() {
    equivalence::<rtl::SlabFloatE5M10P13>("slab_float_e5m10_p13");
}

/// Configurations of the optional cut points (`rtl::slab::float::cut`) on E6M5 — each cut alone, the
/// adders' pair, the multipliers' pair and two mixed — latencies 10 to 11 (the 13-clock tester with all
/// four is tested above): the side data's waits follow the units' latencies in each.
#[test]
fn every_cut_configuration_matches_model_e6m5() {
    use rtl::slab::float::{cut, slab_float_latency, SlabFloat};
    macro_rules! each {
        ($($c:literal),*) => {$(
            assert_eq!(<SlabFloat<6, 5, 12, $c> as rtl::TesterIo>::LATENCY, slab_float_latency($c));
            equivalence_n::<SlabFloat<6, 5, 12, $c>>(concat!("slab_float_e6m5_c", $c), 400);
        )*};
    }
    each!(1, 2, 4, 8, 3, 12, 6, 9);
    const _: () = assert!(cut::ALL == 15, "four cut points");
    let lat: Vec<usize> = [0, 1, 2, 4, 8, 3, 12, 6, 9, cut::ALL]
        .into_iter()
        .map(slab_float_latency)
        .collect();
    assert_eq!(lat, [9, 10, 10, 10, 10, 11, 11, 11, 11, 13]);
}
