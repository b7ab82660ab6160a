//! Randomized equivalence: the rust-hdl `SlabFloat` against `golden::slab::float::slab_float`, bit for bit,
//! with latency and tag order checked by `tb::dut::run_checked`, per format. Every input field is drawn
//! from all patterns of the format (NaN and infinities included) or from quantised world vectors; a failing
//! case is shrunk and written out as a VCD named after the test and case.

use golden::slab::float::slab_float;
use proptest::test_runner::{Config, TestCaseError, TestError, TestRunner};
use rtl::slab::float::SlabFloatIo;
use std::cell::RefCell;
use std::hash::{Hash, Hasher};
use tb::dut::run_checked;
use tb::rtl_sim::SlabFloatRtl;
use tb::slab::strategies::float_burst;

const CASES: u32 = 3_000;

fn equivalence<S: SlabFloatIo>(name: &str) {
    let f = S::format();
    let dut = RefCell::new(SlabFloatRtl::<S>::float());
    let mut runner = TestRunner::new(Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    });
    let result = runner.run(&float_burst(f), |burst| {
        let r = run_checked(&mut *dut.borrow_mut(), burst, |v| {
            slab_float(&f, &v.0, &v.1)
        });
        r.map(|_| ()).map_err(|m| {
            // Results of the failed burst are still in the pipeline: shrink on a fresh block.
            *dut.borrow_mut() = SlabFloatRtl::<S>::float();
            TestCaseError::fail(m.to_string())
        })
    });
    match result {
        Ok(()) => {}
        Err(TestError::Fail(why, burst)) => {
            let mut h = std::collections::hash_map::DefaultHasher::new();
            format!("{burst:?}").hash(&mut h);
            let path = tb::out_dir()
                .join("vcd")
                .join(format!("{name}_{:08x}.vcd", h.finish() as u32));
            let mut d = SlabFloatRtl::<S>::float_with_vcd(&path).expect("VCD");
            let _ = run_checked(&mut d, burst.clone(), |v| slab_float(&f, &v.0, &v.1));
            panic!("{name}: RTL differs from the model on the shrunk burst {burst:?}\n{why}\nwaveform: {}", path.display());
        }
        Err(e) => panic!("{name}: {e}"),
    }
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
