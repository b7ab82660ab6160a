//! proptest with shrinking for the bundle pairs, fixed and float (`tb::prop`): bursts of raw tests (a
//! bundle or two rays and a box pair, every code over its range, float NaN and infinities included) with
//! bubbles, rust-hdl against the model; and for the results processor: programs of up to four jobs
//! (`tb::bundle::split::split_program`: new ray sets or the loaded one, idle gaps or back to back, active
//! masks, noise while busy), clock by clock. A failing burst or program is shrunk and written as a VCD.
//! A wrong model is caught, and the failure leaves its waveform.

use golden::bundle::fix::BundleFixFormat;
use golden::format::float::FloatFormat;
use rtl::bundle::pair_float::BundleFloatIo;
use tb::bundle::pair_fix::{bundle_model, bundle_rtl, raw_bundle};
use tb::bundle::pair_float::{bundle_float_model, bundle_float_rtl, raw_float_vec};
use tb::bundle::split::{split_model, split_shrinking};
use tb::plane::float::with_big_stack;
use tb::prop::{expect_caught, shrinking_equivalence};

const CASES: u32 = 1_500;
const WORDS: usize = 160;
/// Job programs for the results processor (each up to four jobs).
const SPLIT_CASES: u32 = 2_000;

/// The mutation of a wrong model: AllHit and AnyHit's answers exchanged.
fn swap((h, m): (bool, bool), wrong: bool) -> (bool, bool) {
    if wrong {
        (m, h)
    } else {
        (h, m)
    }
}

fn pair_fix_b12(name: &'static str, wrong: bool) {
    // rust-hdl's simulation and VCD writer recurse deeply: run on a big stack.
    with_big_stack(move || pair_fix_b12_run(name, wrong))
}

fn pair_fix_b12_run(name: &str, wrong: bool) {
    let bf = BundleFixFormat::presets()[1];
    shrinking_equivalence(
        name,
        CASES,
        WORDS,
        |vcd| {
            let d = bundle_rtl::<rtl::BundleFixB12>(&bf);
            match vcd {
                Some(p) => d.vcd_to(p).expect("VCD"),
                None => d,
            }
        },
        |t| raw_bundle(&bf, t),
        |v| swap(bundle_model(&bf, v), wrong),
    );
}

fn pair_float_fp16(name: &'static str, wrong: bool) {
    with_big_stack(move || {
        type S = rtl::BundleFloatFp16;
        let f = S::format();
        assert_eq!(f, FloatFormat::FP16);
        shrinking_equivalence(
            name,
            CASES,
            WORDS,
            |vcd| {
                let d = bundle_float_rtl::<S>();
                match vcd {
                    Some(p) => d.vcd_to(p).expect("VCD"),
                    None => d,
                }
            },
            |t| raw_float_vec(&f, t),
            |v| swap(bundle_float_model(&f, v), wrong),
        )
    })
}

#[test]
fn pair_fix_b12_matches_model_shrinking() {
    assert_eq!(
        BundleFixFormat::presets()[1].base,
        golden::format::fixed::FixFormat::b12()
    );
    pair_fix_b12("bundle_fix_b12", false);
}

#[test]
fn pair_float_fp16_matches_model_shrinking() {
    pair_float_fp16("bundle_float_fp16", false);
}

#[test]
fn a_wrong_model_is_caught_shrunk_and_leaves_a_vcd() {
    for run in [
        Box::new(|| pair_fix_b12("bundle_fix_b12_wrong_model", true))
            as Box<dyn FnOnce() + std::panic::UnwindSafe>,
        Box::new(|| pair_float_fp16("bundle_float_fp16_wrong_model", true)),
    ] {
        let msg = expect_caught("valid_out", run);
        assert!(
            msg.contains("shrunk burst") && msg.contains("test #0"),
            "{msg}"
        );
    }
}

#[test]
fn split_b12_matches_model_shrinking() {
    let s = with_big_stack(|| {
        split_shrinking::<rtl::BundleSplitB12>(
            "bundle_split_b12",
            BundleFixFormat::presets()[1],
            SPLIT_CASES,
            split_model,
        )
    });
    println!("bundle_split_b12: {s:?}");
    let j = s.jobs / 20;
    assert!(
        s.all_hit > j && s.all_miss > j && s.split > j && s.back_to_back > j,
        "every outcome and back-to-back starts must be well represented: {s:?}"
    );
    assert!(s.odd_splits > 0 && s.full_splits > 0, "{s:?}");
}

/// The results processor's wrong models (`super::split`) are caught, shrunk to a program of one job (or
/// two, when the failing job reuses the ray set an earlier job loaded: proptest removes jobs before it
/// simplifies the rest, and never turns a reuse into a load), and leave a waveform with the block's
/// `done`.
#[test]
fn a_wrong_split_model_is_caught_shrunk_and_leaves_a_vcd() {
    for (name, wrong) in [
        (
            "bundle_split_b12_floor_cycles",
            super::split::floor_cycles as fn(&_, &_, &_) -> _,
        ),
        ("bundle_split_b12_allhit_rays", super::split::allhit_rays),
    ] {
        let msg = expect_caught("done", move || {
            with_big_stack(move || {
                split_shrinking::<rtl::BundleSplitB12>(
                    name,
                    BundleFixFormat::presets()[1],
                    SPLIT_CASES,
                    wrong,
                );
            })
        });
        let program = msg
            .split("job program [")
            .nth(1)
            .expect("the shrunk program");
        let jobs = program
            .split('\n')
            .next()
            .unwrap()
            .matches("SplitStep")
            .count();
        assert!(
            (1..=2).contains(&jobs),
            "{name}: not shrunk to one or two jobs: {msg}"
        );
    }
}

/// The streaming results processor on job programs (`tb::bundle::stream::stream_program`: ray sets
/// loaded or reused, starts held through refusals and retaken, gaps or none), clock by clock against
/// the clock model; a failing program is shrunk and written as a VCD.
#[test]
fn stream_b12_matches_model_shrinking() {
    use tb::bundle::stream::{stream_model, stream_shrinking};
    let bf = BundleFixFormat::presets()[1];
    let s = with_big_stack(move || {
        stream_shrinking::<rtl::BundleStreamB12>("bundle_stream_b12", bf, 300, || {
            stream_model::<rtl::BundleStreamB12>(&bf)
        })
    });
    println!("bundle_stream_b12: {s:?}");
    let j = s.done / 20;
    assert!(
        s.all_hit > j && s.all_miss > j && s.split > j && s.refused > j && s.overtakes > 0,
        "every outcome, refused starts and reports out of order must occur: {s:?}"
    );
}

/// The float streaming processor (binary16) on job programs, as the fixed one above.
#[test]
fn stream_fp16_matches_model_shrinking() {
    use tb::bundle::stream::{stream_model, stream_shrinking};
    let f = golden::format::float::FloatFormat::FP16;
    let s = with_big_stack(move || {
        stream_shrinking::<rtl::BundleStreamFp16>("bundle_stream_fp16", f, 100, || {
            stream_model::<rtl::BundleStreamFp16>(&f)
        })
    });
    println!("bundle_stream_fp16: {s:?}");
    let j = s.done / 20;
    assert!(
        s.all_hit > j && s.all_miss > j && s.split > j && s.refused > j && s.overtakes > 0,
        "every outcome, refused starts and reports out of order must occur: {s:?}"
    );
}

/// A wrong stream model (the pair one clock slower) is caught, shrunk to a program of one job, and
/// leaves a waveform with the block's `done`.
#[test]
fn a_wrong_stream_model_is_caught_shrunk_and_leaves_a_vcd() {
    use golden::bundle::stream::StreamModel;
    use tb::bundle::stream::stream_shrinking;
    let bf = BundleFixFormat::presets()[1];
    let msg = expect_caught("done", move || {
        with_big_stack(move || {
            stream_shrinking::<rtl::BundleStreamB12>(
                "bundle_stream_b12_slow_pair",
                bf,
                300,
                || StreamModel::new(bf, rtl::bundle::pair_fix::BUNDLE_FIX_LATENCY + 1),
            );
        })
    });
    let program = msg
        .split("job program [")
        .nth(1)
        .expect("the shrunk program");
    let jobs = program
        .split('\n')
        .next()
        .unwrap()
        .matches("StreamStep")
        .count();
    assert_eq!(jobs, 1, "not shrunk to one job: {msg}");
}
