//! Randomized equivalence: the rust-hdl `SlabFix` against `golden::slab::fix::slab_fix`, bit for bit, with
//! latency and tag order checked by `tb::dut::run_checked`, at 4 clocks (b8, b12, b16) and at 6 (b12,
//! b16). 10,000 proptest cases (bursts of 1 to 8
//! tests with bubbles) per width configuration; a failing case is shrunk and written out as a VCD named
//! after the test and case.

use golden::format::fixed::FixFormat;
use golden::slab::fix::{slab_fix, SlabFixOut};
use rtl::slab::fix::SlabFixIo;
use tb::prop::{expect_caught, shrinking_pipelined};
use tb::rtl_sim::SlabFixRtl;
use tb::slab::strategies::slab_burst;

const CASES: u32 = 10_000;

/// Runs the equivalence property for block `S`; on failure writes `out/vcd/<name>_<hash>.vcd`.
fn equivalence<S: SlabFixIo>(
    fmt: FixFormat,
    name: &str,
    model: impl Fn(&FixFormat, &SlabVecIn) -> SlabFixOut,
) {
    shrinking_pipelined(
        name,
        CASES,
        slab_burst(fmt),
        |burst| burst.clone(),
        |vcd| match vcd {
            Some(p) => SlabFixRtl::<S>::with_vcd(&fmt, p).expect("write VCD"),
            None => SlabFixRtl::<S>::new(&fmt),
        },
        |v| model(&fmt, v),
    );
}

type SlabVecIn = (golden::format::fixed::FixRay, golden::format::fixed::FixBox);

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

#[test]
fn slab_fix_b12_6_clocks_matches_model() {
    equivalence::<rtl::SlabFixB12P6>(FixFormat::b12(), "slab_fix_b12_p6", |f, v| {
        slab_fix(f, &v.0, &v.1)
    });
}

#[test]
fn slab_fix_b16_6_clocks_matches_model() {
    equivalence::<rtl::SlabFixB16P6>(FixFormat::b16(), "slab_fix_b16_p6", |f, v| {
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
    expect_caught("valid_out", || {
        equivalence::<rtl::SlabFixB8>(fmt, "slab_fix_b8_wrong_model", wrong)
    });
}
