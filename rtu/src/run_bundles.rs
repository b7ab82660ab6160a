//! `rtu run --bundles`: users' bundle vectors (`golden::bundle::vectors`) through the AllHit / AnyHit pair
//! and the results processor, on the fixed or float datapath.

use crate::out_file::Output;
use glam::DVec3;
use golden::bundle::edge::Bundle;
use golden::bundle::fix::{self as bundle_fix, BundleFixFormat};
use golden::bundle::float as bundle_float;
use golden::bundle::split::{split_fix, split_with, SplitResult};
use golden::bundle::vectors::{
    read_numbered_bundles, write_bundle_result, BundleResult, BundleVector,
};
use golden::format::fixed::{FixFormat, GridMap};
use golden::format::float::FloatFormat;
use rtl::bundle::split::{BundleSplitIo, SplitIn, SplitJob, SPLIT_RAYS};
use std::io::BufReader;
use std::path::Path;
use tb::bundle::split::SplitRtl;
use tb::engine::Engine;

/// A datapath ready to judge world bundles.
enum Dp {
    Fix(BundleFixFormat, GridMap),
    Float(FloatFormat),
}

impl Dp {
    /// `(all_hit, all_miss)` of a world bundle against a world box.
    fn decide(&self, b: &Bundle, bx: &golden::Aabb) -> Result<(bool, bool), golden::Error> {
        match self {
            Dp::Fix(bf, map) => bundle_fix::decide_fix(bf, map, b, bx),
            Dp::Float(f) => bundle_float::decide_float(f, b, bx),
        }
    }
}

/// The results processor on one vector: the bundle test, then its rays two per clock if undecided.
fn judge(dp: &Dp, v: &BundleVector) -> Result<BundleResult, golden::Error> {
    let (all_hit, all_miss) = dp.decide(&v.bundle, &v.bx)?;
    if v.rays.is_empty() {
        return Ok(BundleResult {
            all_hit,
            all_miss,
            rays: None,
        });
    }
    let mut ray_answers = Vec::with_capacity(v.rays.len());
    for r in &v.rays {
        ray_answers.push(!dp.decide(&Bundle::of_ray(r)?, &v.bx)?.1);
    }
    let n = v.rays.len();
    let active = if n == 64 { u64::MAX } else { (1u64 << n) - 1 };
    let s: SplitResult = split_with(|| (all_hit, all_miss), |i| ray_answers[i], active);
    Ok(BundleResult {
        all_hit,
        all_miss,
        rays: Some((
            s.split,
            (0..n).map(|i| s.mask >> i & 1 == 1).collect(),
            s.pair_cycles,
        )),
    })
}

/// The fixed datapath's inputs of one vector: the job (bundle, box pair, every ray active) and the rays,
/// each quantised as a tiny bundle.
fn fix_job(
    bf: &BundleFixFormat,
    map: &GridMap,
    v: &BundleVector,
) -> Result<(SplitJob, Vec<golden::bundle::fix::FixBundle>), golden::Error> {
    let rays = v
        .rays
        .iter()
        .map(|r| bundle_fix::quantize_bundle(bf, map, &Bundle::of_ray(r)?))
        .collect::<Result<Vec<_>, _>>()?;
    let job = SplitJob {
        bundle: bundle_fix::quantize_bundle(bf, map, &v.bundle)?,
        boxes: bundle_fix::quantize_box_pair(map, &v.bx)?,
        active: ((1u32 << rays.len()) - 1) as u16,
    };
    Ok((job, rays))
}

/// Runs the vectors on the rust-hdl results processor `S`: per vector, its rays written into the ray store
/// one a clock, then the job, then clocks until `done`. Each result is compared with the model's
/// (`golden::bundle::split::split_fix`); a difference stops the run.
fn run_rtl<S: BundleSplitIo>(
    bf: &BundleFixFormat,
    map: &GridMap,
    vs: &[BundleVector],
    at: &[String],
    vcd: Option<&Path>,
    mut sink: impl FnMut(u64, BundleResult) -> Result<(), String>,
) -> Result<(), String> {
    let mut dut = SplitRtl::<S>::new(bf);
    if let Some(p) = vcd {
        dut = dut.vcd_to(p).map_err(|e| format!("{}: {e}", p.display()))?;
    }
    for (v, at) in vs.iter().zip(at) {
        if v.rays.len() > SPLIT_RAYS {
            return Err(format!(
                "{at}: bundle with tag {}: {} rays, but the results processor holds {SPLIT_RAYS}",
                v.tag,
                v.rays.len()
            ));
        }
        let (job, rays) =
            fix_job(bf, map, v).map_err(|e| format!("{at}: bundle with tag {}: {e}", v.tag))?;
        for (a, r) in rays.iter().enumerate() {
            dut.step(&SplitIn {
                write: Some((a, *r)),
                start: None,
                reset: false,
            });
        }
        let mut out = dut.step(&SplitIn {
            write: None,
            start: Some(job),
            reset: false,
        });
        let mut clocks = 1;
        while !out.done {
            if clocks > 64 {
                return Err(format!(
                    "bundle with tag {}: no result after 64 clocks",
                    v.tag
                ));
            }
            out = dut.step(&SplitIn::default());
            clocks += 1;
        }
        let got = out.result();
        let want = split_fix(bf, &job.bundle, &job.boxes, &rays, job.active as u64);
        if got != want {
            return Err(format!(
                "bundle with tag {}: the RTL says {got:?}, the model {want:?}",
                v.tag
            ));
        }
        let n = v.rays.len();
        sink(
            v.tag,
            BundleResult {
                all_hit: got.all_hit,
                all_miss: got.all_miss,
                rays: (n > 0).then(|| {
                    (
                        got.split,
                        (0..n).map(|i| got.mask >> i & 1 == 1).collect(),
                        got.pair_cycles,
                    )
                }),
            },
        )?;
    }
    Ok(())
}

/// Bounds of every origin and box in the file, for the fixed-point grid.
pub(crate) fn bounds<'a>(vs: impl IntoIterator<Item = &'a BundleVector>) -> Option<(DVec3, DVec3)> {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for v in vs {
        lo = lo.min(DVec3::from(v.bundle.o_lo)).min(v.bx.min);
        hi = hi.max(DVec3::from(v.bundle.o_hi)).max(v.bx.max);
    }
    lo.is_finite().then_some((lo, hi))
}

/// Runs a bundle vector file (JSON lines) on `format` (fixed preset or float format) and writes one result
/// line per bundle. Engines: `model` (both datapaths), `rtl` (the fixed presets: the rust-hdl results
/// processor `BundleSplit`, each result checked against the model; `vcd` writes its waveform).
pub fn run(
    input: &Path,
    output: Option<&Path>,
    engine: Engine,
    format: &str,
    grid: Option<(DVec3, DVec3)>,
    vcd: Option<&Path>,
) -> Result<(), String> {
    if engine == Engine::Verilator {
        return Err("--bundles runs on the model and rtl engines; the Verilated pair and results processor \
             are checked against the same model by `cargo test -p tb --test bundle`"
            .into());
    }
    if vcd.is_some() && engine != Engine::Rtl {
        return Err("a waveform (--vcd) needs the rtl engine".into());
    }
    let src = input.display().to_string();
    let reader: Box<dyn std::io::BufRead + Send> = if input == Path::new("-") {
        Box::new(BufReader::new(std::io::stdin()))
    } else {
        Box::new(BufReader::new(
            std::fs::File::open(input).map_err(|e| format!("{src}: {e}"))?,
        ))
    };
    let numbered: Vec<(usize, BundleVector)> = read_numbered_bundles(reader, src.clone())
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    let (at, vs): (Vec<String>, Vec<BundleVector>) = numbered
        .into_iter()
        .map(|(line, v)| (format!("{src}:{line}"), v))
        .unzip();
    let lower = format.to_ascii_lowercase();
    let dp = if lower.starts_with('e') || lower.starts_with("fp") || lower.starts_with("bf") {
        Dp::Float(FloatFormat::parse(format).map_err(|e| e.to_string())?)
    } else {
        let f = FixFormat::parse(format)
            .map_err(|e| format!("{e} (or a float format: fp32, fp16, bf16, eXmY)"))?;
        let (lo, hi) = match grid.or_else(|| bounds(&vs)) {
            Some(b) => b,
            None => return Err(format!("{src}: no bundles")),
        };
        Dp::Fix(
            BundleFixFormat::over(f).map_err(|e| e.to_string())?,
            GridMap::for_bounds(f, lo, hi).map_err(|e| e.to_string())?,
        )
    };
    let mut w = Output::open(output)?;
    let mut sink = |tag: u64, r: BundleResult| {
        write_bundle_result(&mut w, tag, &r).map_err(|e| format!("{}: cannot write: {e}", w.name()))
    };
    match (&dp, engine) {
        (_, Engine::Model) => {
            for (v, at) in vs.iter().zip(&at) {
                let r = judge(&dp, v).map_err(|e| format!("{at}: bundle with tag {}: {e}", v.tag))?;
                sink(v.tag, r)?;
            }
        }
        (Dp::Fix(bf, map), _) => {
            rtl::with_bundle_split!(&bf.base, S, {
                run_rtl::<S>(bf, map, &vs, &at, vcd, sink)
            })??;
        }
        (Dp::Float(_), _) => {
            return Err("float bundles run on the model engine (the float pair has no results processor \
                 in RTL; the pair is checked against the model by `cargo test -p tb --test bundle`)"
                .into())
        }
    }
    w.commit()?;
    eprintln!(
        "rtu run --bundles: {} bundles on {format}, {engine:?} engine",
        vs.len()
    );
    Ok(())
}
