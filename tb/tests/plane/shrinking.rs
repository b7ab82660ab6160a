//! proptest with shrinking for the cull-plane testers, fixed and float (`tb::prop`): bursts of raw node
//! tests (every field over its code range, float NaN and infinities included) with bubbles, rust-hdl
//! against the model; a failing burst is shrunk and written as a VCD. A wrong model is caught, and the
//! failure leaves its waveform.

use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use golden::plane::fix::CullFixFormat;
use golden::plane::float::{node_float, CullFloatFormat};
use tb::plane::fix::{raw_node_fix, CullFixCtx};
use tb::plane::float::{raw_node, with_big_stack};
use tb::prop::{expect_caught, shrinking_equivalence};
use tb::rtl_sim::TesterSim;
use tb::xsim::BlockCtx;

const CASES: u32 = 1_500;
/// More words than a raw node draws (about 3 a field).
const WORDS: usize = 160;

fn plane_fix_b12_k2(name: &'static str, flip: bool) {
    // rust-hdl's simulation and VCD writer recurse deeply: run on a big stack.
    with_big_stack(move || plane_fix_b12_k2_run(name, flip))
}

fn plane_fix_b12_k2_run(name: &str, flip: bool) {
    let c = CullFixCtx {
        cf: CullFixFormat::over(FixFormat::b12()),
        k: 2,
    };
    shrinking_equivalence(
        name,
        CASES,
        WORDS,
        |vcd| {
            let d = TesterSim::wrap(rtl::PlaneFixB12::<2>::new(&c.cf));
            match vcd {
                Some(p) => d.vcd_to(p).expect("VCD"),
                None => d,
            }
        },
        |t| raw_node_fix(&c.cf, t),
        |v| {
            let mut o = c.model(&v.0, &v.1);
            // The mutation: one bit of the exit code wrong when the node is hit.
            if flip && o.hit {
                o.t_exit ^= 1;
            }
            o
        },
    );
}

fn plane_float_e5m10_k2(name: &'static str, flip: bool) {
    with_big_stack(move || {
        type P = rtl::PlaneFloatE5M10K2;
        let cf = CullFloatFormat::over(FloatFormat::FP16);
        shrinking_equivalence(
            name,
            CASES,
            WORDS,
            |vcd| {
                let d = TesterSim::wrap(<P as rtl::plane::float::PlaneFloatIo>::make());
                match vcd {
                    Some(p) => d.vcd_to(p).expect("VCD"),
                    None => d,
                }
            },
            |t| raw_node(&cf, 2, t),
            |v| {
                let mut o = node_float(&cf, 2, &v.0, &v.1);
                if flip && o.hit {
                    o.t_exit ^= 1;
                }
                o
            },
        )
    })
}

#[test]
fn plane_fix_b12_k2_matches_model_shrinking() {
    plane_fix_b12_k2("plane_fix_b12_k2", false);
}

#[test]
fn plane_float_e5m10_k2_matches_model_shrinking() {
    plane_float_e5m10_k2("plane_float_e5m10_k2", false);
}

#[test]
fn a_wrong_model_is_caught_shrunk_and_leaves_a_vcd() {
    let msg = expect_caught("valid_out", || {
        plane_fix_b12_k2("plane_fix_b12_k2_wrong_model", true)
    });
    // Shrinking leaves one test in the burst: the first mismatch is test #0.
    assert!(msg.contains("test #0"), "{msg}");
    expect_caught("valid_out", || {
        plane_float_e5m10_k2("plane_float_e5m10_k2_wrong_model", true)
    });
}
