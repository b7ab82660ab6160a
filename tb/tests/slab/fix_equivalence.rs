//! Randomized equivalence: the rust-hdl `SlabFix` against `golden::slab::fix::slab_fix`, bit for bit, with
//! latency and tag order checked by `tb::dut::run_checked`. 10,000 proptest cases (bursts of 1 to 8
//! tests with bubbles) per width configuration; a failing case is shrunk and written out as a VCD named
//! after the test and case.

use golden::format::fixed::FixFormat;
use golden::slab::fix::{slab_fix, SlabFixOut};
use proptest::test_runner::{Config, TestCaseError, TestError, TestRunner};
use rtl::slab::fix::SlabFixIo;
use std::cell::RefCell;
use std::hash::{Hash, Hasher};
use tb::dut::run_checked;
use tb::rtl_sim::SlabFixRtl;
use tb::slab::ports::SlabVec;
use tb::slab::strategies::slab_burst;

const CASES: u32 = 10_000;

/// Runs the equivalence property for block `S`; on failure writes `out/vcd/<name>_<hash>.vcd`.
fn equivalence<S: SlabFixIo>(
    fmt: FixFormat,
    name: &str,
    model: impl Fn(&FixFormat, &SlabVecIn) -> SlabFixOut,
) {
    let dut = RefCell::new(SlabFixRtl::<S>::new(&fmt));
    let mut runner = TestRunner::new(Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    });
    let result = runner.run(&slab_burst(fmt), |burst| {
        let r = run_checked(&mut *dut.borrow_mut(), burst, |v| model(&fmt, v));
        r.map(|_| ()).map_err(|m| {
            // Results of the failed burst are still in the pipeline: shrink on a fresh block.
            *dut.borrow_mut() = SlabFixRtl::<S>::new(&fmt);
            TestCaseError::fail(m.to_string())
        })
    });
    if let Err(TestError::Fail(why, burst)) = result {
        let path = write_failure_vcd::<S>(fmt, name, &burst);
        panic!(
            "{name}: RTL differs from the model on the shrunk burst {burst:?}\n{why}\nwaveform: {}",
            path.display()
        );
    } else if let Err(e) = result {
        panic!("{name}: {e}");
    }
}

type SlabVecIn = (golden::format::fixed::FixRay, golden::format::fixed::FixBox);

fn write_failure_vcd<S: SlabFixIo>(
    fmt: FixFormat,
    name: &str,
    burst: &[SlabVec],
) -> std::path::PathBuf {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    format!("{burst:?}").hash(&mut h);
    let path = tb::out_dir()
        .join("vcd")
        .join(format!("{name}_{:08x}.vcd", h.finish() as u32));
    let mut dut = SlabFixRtl::<S>::with_vcd(&fmt, &path).expect("write VCD");
    let _ = run_checked(&mut dut, burst.to_vec(), |v| slab_fix(&fmt, &v.0, &v.1));
    path
}

#[test]
fn slab_fix_b8_matches_model() {
    equivalence::<rtl::SlabFixB8>(FixFormat::b8(), "slab_fix_b8", |f, v| {
        slab_fix(f, &v.0, &v.1)
    });
}

#[test]
fn slab_fix_b12_matches_model() {
    equivalence::<rtl::SlabFixB12>(FixFormat::b12(), "slab_fix_b12", |f, v| {
        slab_fix(f, &v.0, &v.1)
    });
}

#[test]
fn slab_fix_b16_matches_model() {
    equivalence::<rtl::SlabFixB16>(FixFormat::b16(), "slab_fix_b16", |f, v| {
        slab_fix(f, &v.0, &v.1)
    });
}

/// The property can fail: against a model with one bit wrong, the runner reports a shrunk case and a VCD.
#[test]
fn a_wrong_model_is_caught_and_leaves_a_vcd() {
    let fmt = FixFormat::b8();
    let wrong = |f: &FixFormat, v: &SlabVecIn| {
        let mut o = slab_fix(f, &v.0, &v.1);
        o.t_exit ^= 1;
        o
    };
    let r = std::panic::catch_unwind(|| {
        equivalence::<rtl::SlabFixB8>(fmt, "slab_fix_b8_wrong_model", wrong)
    });
    let msg = match r {
        Ok(()) => panic!("a model with a flipped t_exit bit passed"),
        Err(e) => e.downcast_ref::<String>().cloned().unwrap_or_default(),
    };
    let vcd = msg.rsplit("waveform: ").next().unwrap().trim();
    assert!(std::path::Path::new(vcd).exists(), "no VCD at {vcd}: {msg}");
    assert!(std::fs::read_to_string(vcd).unwrap().contains("valid_out"));
}
