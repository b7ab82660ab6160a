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
    let f = S::format();
    shrinking_pipelined(
        name,
        CASES,
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
