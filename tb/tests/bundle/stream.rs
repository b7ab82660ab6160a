//! The streaming results processors (`rtl::bundle::stream::BundleStream` around the fixed pair,
//! `rtl::bundle::stream_float::BundleStreamFloat` around the float pair): the rust-hdl simulation clock
//! for clock against `golden::bundle::stream::StreamModel` (ready, done, tag, result and the held result
//! fields in every clock) on open-loop job streams with bursts, split jobs queueing, four ray sets loaded
//! while jobs run, garbage writes and resets; a wrong model is caught; the exported Verilog (Verilator
//! lint, Icarus, Verilator cross-simulation against the model and the rust-hdl simulation).
//! Each test prints its counts and time (run with `--nocapture`).

use golden::bundle::fix::BundleFixFormat;
use golden::bundle::stream::StreamModel;
use golden::format::float::FloatFormat;
use rtl::bundle::pair_fix::BUNDLE_FIX_LATENCY;
use rtl::bundle::stream::BundleStreamIo;
use std::time::Instant;
use tb::bundle::stream::{
    run_stream, stream_xsim, StreamCases, StreamChecker, StreamRtl, StreamStats, StreamStim,
};

/// The float processors' blocks are large: every test runs on a thread with a big stack.
fn big_stack(f: impl FnOnce() + Send + 'static) {
    tb::plane::float::with_big_stack(f)
}

fn preset(i: usize) -> BundleFixFormat {
    BundleFixFormat::presets()[i]
}

/// Every outcome, full splits, a queue in use, reports out of order and refused starts must occur.
fn well_covered<P: StreamCases>(dp: &P, s: &StreamStats) {
    let j = s.done / 20;
    assert!(
        s.all_hit > j && s.all_miss > j && s.split > j && s.full_splits > 0,
        "{}: every outcome must be well represented: {s:?}",
        dp.label()
    );
    assert!(
        s.max_queued >= 3 && s.overtakes > j && s.refused > j,
        "{}: the queue, out-of-order reports and refused starts must occur: {s:?}",
        dp.label()
    );
    assert!(
        !P::REBOUNDS || s.rebounds > s.split / 2,
        "{}: most split jobs must report a re-bounded bundle: {s:?}",
        dp.label()
    );
}

fn rtl_matches_model<S: BundleStreamIo>(dp: S::Dp, clocks: u64, seed: u64)
where
    S::Dp: StreamCases,
{
    big_stack(move || {
        let start = Instant::now();
        let mut dut = StreamRtl::<S>::new(&dp);
        let stats = run_stream(
            StreamChecker::of::<S>(&dp),
            &mut dut,
            StreamStim::new(dp, seed, clocks),
        )
        .unwrap_or_else(|e| panic!("{}: {e}", rtl::names::bundle_stream_of::<S>(&dp)));
        println!(
            "{}: {stats:?} match in {:.1} s",
            rtl::names::bundle_stream_of::<S>(&dp),
            start.elapsed().as_secs_f64()
        );
        assert_eq!(stats.clocks, clocks);
        well_covered(&dp, &stats);
    })
}

#[test]
fn stream_rtl_matches_model_b8() {
    rtl_matches_model::<rtl::BundleStreamB8>(preset(0), 20_000, 1);
}

#[test]
fn stream_rtl_matches_model_b12() {
    rtl_matches_model::<rtl::BundleStreamB12>(preset(1), 20_000, 2);
}

#[test]
fn stream_rtl_matches_model_b16() {
    rtl_matches_model::<rtl::BundleStreamB16>(preset(2), 20_000, 3);
}

/// Over the 5-clock fixed pair: the same control with 5-clock delay lines.
#[test]
fn stream_rtl_matches_model_b12_p5() {
    rtl_matches_model::<rtl::BundleStreamB12P5>(preset(1), 20_000, 12);
}

#[test]
fn stream_float_rtl_matches_model_fp16() {
    rtl_matches_model::<rtl::BundleStreamFp16>(FloatFormat::FP16, 8_000, 31);
}

#[test]
fn stream_float_rtl_matches_model_bf16() {
    rtl_matches_model::<rtl::BundleStreamBf16>(FloatFormat::BF16, 8_000, 32);
}

#[test]
fn stream_float_rtl_matches_model_fp32() {
    rtl_matches_model::<rtl::BundleStreamFp32>(FloatFormat::FP32, 8_000, 33);
}

/// Over the 13-clock float pair (two Waits per delay line).
#[test]
fn stream_float_rtl_matches_model_fp16_p13() {
    rtl_matches_model::<rtl::BundleStreamFp16P13>(FloatFormat::FP16, 8_000, 34);
}

/// The check can fail: a model whose pair answers one clock late disagrees with the RTL, on either
/// datapath.
#[test]
fn stream_wrong_model_is_caught() {
    big_stack(|| {
        let bf = preset(1);
        let mut dut = StreamRtl::<rtl::BundleStreamB12>::new(&bf);
        let e = run_stream(
            StreamChecker::with_model(StreamModel::new(bf, BUNDLE_FIX_LATENCY + 1)),
            &mut dut,
            StreamStim::new(bf, 4, 2_000),
        )
        .expect_err("a wrong latency must be caught");
        println!("caught: {e}");
    });
    big_stack(|| {
        let f = FloatFormat::FP16;
        let mut dut = StreamRtl::<rtl::BundleStreamFp16>::new(&f);
        let e = run_stream(
            StreamChecker::with_model(StreamModel::new(
                f,
                rtl::bundle::pair_float::BUNDLE_FLOAT_LATENCY - 1,
            )),
            &mut dut,
            StreamStim::new(f, 4, 2_000),
        )
        .expect_err("a wrong latency must be caught");
        println!("caught: {e}");
    });
}

/// Synchronous reset at random clocks: every job in flight is dropped, in the rust-hdl simulation and
/// in Verilator (every clock against rust-hdl and the model).
fn reset_drops_jobs_in_flight<S: BundleStreamIo>(dp: S::Dp, clocks: u64)
where
    S::Dp: StreamCases,
{
    big_stack(move || {
        let mut dut = StreamRtl::<S>::new(&dp);
        let stats = run_stream(
            StreamChecker::of::<S>(&dp),
            &mut dut,
            StreamStim::new(dp, 51, clocks).with_resets(),
        )
        .unwrap_or_else(|e| panic!("{}: {e}", rtl::names::bundle_stream_of::<S>(&dp)));
        assert!(stats.resets > clocks / 1000, "{stats:?}");
        assert!(stats.done < stats.taken, "{stats:?}");
        let (v, _) = export::<S>(&dp);
        let h = tb::verilator::build(
            &v,
            &rtl::names::bundle_stream_of::<S>(&dp),
            &tb::out_dir().join("verilator"),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let x = stream_xsim::<S, _>(
            dp,
            &h,
            StreamStim::new(dp, 51, clocks).with_resets(),
            u64::MAX,
        )
        .unwrap_or_else(|e| panic!("{}: {e}", rtl::names::bundle_stream_of::<S>(&dp)));
        assert_eq!(x, stats);
    })
}

#[test]
fn stream_reset_drops_jobs_in_flight_b12() {
    reset_drops_jobs_in_flight::<rtl::BundleStreamB12>(preset(1), 20_000);
}

#[test]
fn stream_float_reset_drops_jobs_in_flight_fp16() {
    reset_drops_jobs_in_flight::<rtl::BundleStreamFp16>(FloatFormat::FP16, 8_000);
}

fn export<S: BundleStreamIo>(dp: &S::Dp) -> (String, std::path::PathBuf) {
    let name = rtl::names::bundle_stream_of::<S>(dp);
    let v = rtl::verilog::verilog_named(&mut S::for_format(dp), &name);
    let path = tb::verilog_tools::write(&v, &name);
    (v, path)
}

#[test]
fn stream_verilog_is_lint_clean_and_accepted_by_icarus() {
    big_stack(|| {
        for path in [
            export::<rtl::BundleStreamB8>(&preset(0)).1,
            export::<rtl::BundleStreamB12>(&preset(1)).1,
            export::<rtl::BundleStreamB16>(&preset(2)).1,
            export::<rtl::BundleStreamB12P5>(&preset(1)).1,
            export::<rtl::BundleStreamFp32>(&FloatFormat::FP32).1,
            export::<rtl::BundleStreamBf16>(&FloatFormat::BF16).1,
            export::<rtl::BundleStreamFp16>(&FloatFormat::FP16).1,
            export::<rtl::BundleStreamFp16P13>(&FloatFormat::FP16).1,
        ] {
            tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
            tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
        }
    });
}

fn cross_simulate<S: BundleStreamIo>(dp: S::Dp, clocks: u64, lockstep: u64, seed: u64)
where
    S::Dp: StreamCases,
{
    big_stack(move || {
        let start = Instant::now();
        let (v, _) = export::<S>(&dp);
        let h = tb::verilator::build(
            &v,
            &rtl::names::bundle_stream_of::<S>(&dp),
            &tb::out_dir().join("verilator"),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let built = start.elapsed().as_secs_f64();
        let stats = stream_xsim::<S, _>(dp, &h, StreamStim::new(dp, seed, clocks), lockstep)
            .unwrap_or_else(|e| panic!("{}: {e}", rtl::names::bundle_stream_of::<S>(&dp)));
        println!(
            "{}: {stats:?} (harness ready in {built:.1} s, {:.1} s in all)",
            rtl::names::bundle_stream_of::<S>(&dp),
            start.elapsed().as_secs_f64()
        );
        assert_eq!(stats.clocks, clocks);
        assert!(stats.done >= 300_000, "{stats:?}");
        well_covered(&dp, &stats);
    })
}

#[test]
fn stream_verilator_matches_model_and_rtl_b8() {
    cross_simulate::<rtl::BundleStreamB8>(preset(0), 900_000, 50_000, 8);
}

#[test]
fn stream_verilator_matches_model_and_rtl_b12() {
    cross_simulate::<rtl::BundleStreamB12>(preset(1), 900_000, 50_000, 6);
}

#[test]
fn stream_verilator_matches_model_and_rtl_b16() {
    cross_simulate::<rtl::BundleStreamB16>(preset(2), 900_000, 50_000, 7);
}

/// The exported 5-clock-pair processor, as the others.
#[test]
fn stream_verilator_matches_model_and_rtl_b12_p5() {
    cross_simulate::<rtl::BundleStreamB12P5>(preset(1), 900_000, 50_000, 9);
}

#[test]
fn stream_float_verilator_matches_model_and_rtl_fp32() {
    cross_simulate::<rtl::BundleStreamFp32>(FloatFormat::FP32, 900_000, 3_000, 41);
}

#[test]
fn stream_float_verilator_matches_model_and_rtl_bf16() {
    cross_simulate::<rtl::BundleStreamBf16>(FloatFormat::BF16, 900_000, 3_000, 42);
}

#[test]
fn stream_float_verilator_matches_model_and_rtl_fp16() {
    cross_simulate::<rtl::BundleStreamFp16>(FloatFormat::FP16, 900_000, 3_000, 43);
}

/// The exported 13-clock-pair processor, as the others.
#[test]
fn stream_float_verilator_matches_model_and_rtl_fp16_p13() {
    cross_simulate::<rtl::BundleStreamFp16P13>(FloatFormat::FP16, 900_000, 3_000, 44);
}

/// Scene job streams, closed loop (`tb::bundle::stream_scene`): on a small room, primary rays in 4x4
/// tiles and bounce and shadow rays bundled 16 at most, without and with re-bounding, every job's mask
/// and re-bounded bundle equal the recorded traversal's and every clock equals the clock-by-clock model;
/// the pair's input is used in exactly the model's busy-pair count of clocks. Prints utilisation and
/// clocks per job (figures, not thresholds).
#[test]
fn stream_scene_jobs_replay_closed_loop_b12() {
    big_stack(|| scene_jobs_replay::<rtl::BundleStreamB12>(preset(1), (24, 16)));
}

/// The same through the float processor (binary16), whose re-bounded bundles are the float rule's, on
/// 16x12 rays (its rust-hdl simulation is slower).
#[test]
fn stream_float_scene_jobs_replay_closed_loop_fp16() {
    big_stack(|| scene_jobs_replay::<rtl::BundleStreamFp16>(FloatFormat::FP16, (16, 12)));
}

fn scene_jobs_replay<S: BundleStreamIo>(dp: S::Dp, image: (usize, usize))
where
    S::Dp: tb::bundle::stream_scene::SceneDatapath,
{
    use tb::bundle::stream_scene::{run_decided, run_trees, scene_streams, JobTrees};
    let sc = golden::scene::tri_scene::by_name("room", 1, None).unwrap();
    let keep = scene_streams(&sc, 1, image, 4, (16, 0.2), &dp, false).unwrap();
    let stored = scene_streams(&sc, 1, image, 4, (16, 0.2), &dp, true).unwrap();
    assert_eq!(keep.len(), 3);
    // Re-bounding hands some jobs a bundle other than their root's, and never without it.
    let rebounded = |t: &JobTrees<S::Dp>| {
        t.jobs
            .iter()
            .filter(|j| j.job.bundle != t.jobs[t.bundles[j.bundle].1].job.bundle)
            .count()
    };
    assert!(stored.iter().map(|s| rebounded(&s.2)).sum::<usize>() > 0);
    assert_eq!(keep.iter().map(|s| rebounded(&s.2)).sum::<usize>(), 0);
    let differ = keep
        .iter()
        .zip(&stored)
        .filter(|(k, s)| k.2.pair_cycles != s.2.pair_cycles)
        .count();
    assert!(differ > 0, "re-bounding changes no job stream");
    for (rule, (set, bundling, trees)) in keep
        .iter()
        .map(|s| ("keep", s))
        .chain(stored.iter().map(|s| ("stored", s)))
    {
        assert!(trees.jobs.len() > trees.bundles.len(), "{set}: {trees:?}");
        let mut dut = StreamRtl::<S>::new(&dp);
        let r = run_trees(&dp, trees, &mut dut, || {}).unwrap_or_else(|e| panic!("{set}: {e}"));
        assert_eq!(r.jobs, trees.jobs.len() as u64, "{set}");
        assert_eq!(
            r.busy, trees.pair_cycles,
            "{set}: busy clocks = model pair cycles"
        );
        let mut dut = StreamRtl::<S>::new(&dp);
        let d = run_decided(&dp, trees, &mut dut).unwrap_or_else(|e| panic!("{set}: {e}"));
        println!(
            "{} {set} {bundling} {rule}: {} bundles, {} jobs, {} clocks, utilisation {:.3}, {:.2} \
             clocks/job; decided-only stream: {:.3} tests/clock",
            dp.label(),
            r.bundles,
            r.jobs,
            r.clocks,
            r.utilisation(),
            r.clocks_per_job(),
            d.jobs as f64 / d.clocks as f64
        );
    }
}

/// In the waveform: decided jobs started on consecutive clocks each report (`done`)
/// `decided_latency(L) = L + 2` clock edges after their start, one a clock, while `ready` stays high;
/// then a split job of 16 rays holds `ready` low for its 8 pair clocks and reports no earlier than
/// `split_latency(L, 8) = 2L + 4 + 8` edges after its start.
fn waveform_timing<S: BundleStreamIo>(dp: S::Dp, name: String)
where
    S::Dp: StreamCases,
{
    big_stack(move || {
        use golden::bundle::stream::{
            decided_latency, split_latency, PairDatapath, StreamInOf, StreamJob,
        };
        let (lo, hi) = tb::campaign::campaign_bounds();
        let mut gen = golden::bundle::gen::BundleGen::new(21, lo, hi, 0.6);
        let mut model = tb::bundle::stream::stream_model::<S>(&dp);
        // Three decided cases and one undecided case whose 16 rays split.
        let (mut decided, mut undecided) = (vec![], None);
        while decided.len() < 3 || undecided.is_none() {
            let Some((b, p, mut rays)) = dp.case(&mut gen, false) else {
                continue;
            };
            let (h, m) = dp.decide(&b, &p);
            if h || m {
                decided.push((b, p));
            } else if undecided.is_none() {
                while rays.len() < 16 {
                    rays.extend_from_within(..);
                }
                rays.truncate(16);
                undecided = Some((b, p, rays));
            }
        }
        let (ub, up, rays) = undecided.unwrap();
        let mut stim: Vec<StreamInOf<S::Dp>> = rays
            .iter()
            .enumerate()
            .map(|(i, r)| StreamInOf::<S::Dp> {
                write: Some((1, i as u8, *r)),
                ..Default::default()
            })
            .collect();
        let job = |b, p, active, tag| StreamInOf::<S::Dp> {
            start: Some(StreamJob {
                bundle: b,
                boxes: p,
                active,
                set: 1,
                tag,
            }),
            ..Default::default()
        };
        for (k, (b, p)) in decided.iter().enumerate() {
            stim.push(job(*b, *p, 0xffff, k as u8));
        }
        stim.extend((0..S::PAIR_LATENCY + 3).map(|_| StreamInOf::<S::Dp>::default()));
        stim.push(job(ub, up, 0xffff, 9));
        stim.extend((0..60).map(|_| StreamInOf::<S::Dp>::default()));
        let path = tb::out_dir().join("vcd").join(format!("{name}_timing.vcd"));
        {
            let mut dut = StreamRtl::<S>::new(&dp).vcd_to(&path).unwrap();
            for input in &stim {
                let got = dut.step(input);
                model.step(input);
                assert_eq!(got, model.outputs());
            }
        }
        let trace = tb::vcd_read::read_trace(&path, &["start", "done", "ready"]).unwrap();
        let (starts, dones) = (trace.rises("start"), trace.rises("done"));
        // The three decided starts are one rise (start held high three clocks); the split job's is the second.
        assert_eq!(starts.len(), 2, "{starts:?}");
        assert_eq!(
            dones.len(),
            2,
            "done pulses merge for consecutive reports: {dones:?}"
        );
        let l = S::PAIR_LATENCY;
        assert_eq!(
            trace.edges_between(starts[0], dones[0]),
            decided_latency(l),
            "decided: L + 2"
        );
        let split = trace.edges_between(starts[1], dones[1]);
        assert!(
            split >= split_latency(l, 8),
            "split job reported after {split} edges"
        );
        // ready falls once, for the split job's eight pair clocks.
        let falls = trace.rises("ready").len();
        assert_eq!(
            falls, 2,
            "ready rises at time 0 and after the split job's rays"
        );
        println!(
            "{name}: decided: {} edges; split of 16 rays: {split} edges",
            l + 1
        );
    })
}

#[test]
fn stream_waveform_timing_b16() {
    waveform_timing::<rtl::BundleStreamB16>(preset(2), "bundle_stream_b16".into());
}

#[test]
fn stream_float_waveform_timing_fp16() {
    waveform_timing::<rtl::BundleStreamFp16>(FloatFormat::FP16, "bundle_stream_fp16".into());
}
