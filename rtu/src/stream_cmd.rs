//! `rtu bundle-stream`: scene job streams through the streaming results processor's RTL
//! (`rtl::bundle::stream::BundleStream`, or `rtl::bundle::stream_float::BundleStreamFloat` for a float
//! format; rust-hdl simulation, every clock checked against the clock model
//! and every mask against the traversal model): per scene and ray set, the clocks the job trees take
//! closed loop, the pair-input utilisation against the model's busy-pair count, clocks per job, and the
//! decided jobs alone as one stream (bundle tests per clock). The streams and the replay are
//! `tb::bundle::stream_scene`.

use crate::opts::list;
use golden::bundle::fix::BundleFixFormat;
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use indicatif::{ProgressBar, ProgressStyle};
use rtl::bundle::stream::BundleStreamIo;
use std::fmt::Write as _;
use std::path::Path;
use tb::bundle::stream::StreamRtl;
use tb::bundle::stream_scene::{
    run_decided, run_trees, scene_streams, JobTrees, SceneDatapath, StreamRun,
};

/// Arguments of `rtu bundle-stream`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Scenes, comma-separated: built-in names (room, grass, mesh, soup) or OBJ files (`*.obj`).
    #[arg(long, default_value = "room,grass")]
    scenes: String,
    /// Image width and height of the primary rays.
    #[arg(long, default_value_t = 64)]
    width: usize,
    #[arg(long, default_value_t = 48)]
    height: usize,
    /// Tile size of the primary-ray bundles (tile x tile pixels, at most 16 rays).
    #[arg(long, default_value_t = 4)]
    tile: usize,
    /// Builder of the bounce and shadow bundles, `rays:dir_spread` (at most 16 rays).
    #[arg(long, default_value = "16:0.2")]
    builder: String,
    /// Format of the processor: a fixed preset (b8, b12, b16) or a float one (fp32, bf16, fp16).
    #[arg(long, default_value = "b12")]
    format: String,
    /// Seed of the scenes and the secondary rays.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Re-bounding rules, comma-separated: `keep` (children get their parent's bundle) and `stored`
    /// (children get the bundle the processor re-bounds around the rays kept).
    #[arg(long, default_value = "keep,stored")]
    rebound: String,
}

/// CSV header of `bundle_stream_<format>.csv`.
pub const CSV_HEADER: &str = "scene,rays,bundling,format,rebound,bundles,jobs,decided,clocks,busy_clocks,model_pair_cycles,utilisation,clocks_per_job,decided_stream_jobs,decided_stream_clocks,decided_tests_per_clock,one_job_clocks,speedup_vs_one_job";

/// The closed-loop and the decided-only runs of `trees`, on a thread with a big stack (the processor's
/// block is large).
fn replay<S: BundleStreamIo>(
    dp: &S::Dp,
    trees: &JobTrees<S::Dp>,
    pb: &ProgressBar,
) -> Result<(StreamRun, StreamRun), String> {
    let (dp, trees, pb) = (*dp, trees.clone(), pb.clone());
    tb::plane::float::with_big_stack(move || {
        let r = run_trees(&dp, &trees, &mut StreamRtl::<S>::new(&dp), || pb.inc(1))?;
        let d = run_decided(&dp, &trees, &mut StreamRtl::<S>::new(&dp))?;
        Ok((r, d))
    })
}

/// Runs the measurement; returns the markdown table, writes `bundle_stream_<format>.csv` and `.md`
/// under `out`, the format named as `rtu bundle-scenes` names it (`b12`, `e5m10`), so that runs of
/// different formats sit side by side.
pub fn run(a: &Args, out: &Path) -> Result<String, String> {
    if let Ok(f) = FloatFormat::parse(&a.format) {
        let name = f.name();
        return rtl::with_bundle_stream_float!(&f, S, { measure(a, &f, &name, out, replay::<S>) })
            .map_err(|e| format!("--format {}: {e}", a.format))?;
    }
    let fmt = FixFormat::parse(&a.format).map_err(|e| format!("--format {}: {e}", a.format))?;
    let bf = BundleFixFormat::over(fmt).map_err(|e| e.to_string())?;
    let preset = BundleFixFormat::presets()
        .iter()
        .position(|p| *p == bf)
        .ok_or_else(|| {
            format!(
                "--format {}: the processor is built over b8, b12 and b16 (and fp32, bf16, fp16)",
                a.format
            )
        })?;
    let name = ["b8", "b12", "b16"][preset];
    rtl::with_bundle_stream!(&bf.base, S, { measure(a, &bf, name, out, replay::<S>) })?
}

/// [`run`] on the processor over `dp` (format `name`), whose job trees `replay` runs.
fn measure<P: SceneDatapath>(
    a: &Args,
    dp: &P,
    name: &str,
    out: &Path,
    replay: impl Fn(&P, &JobTrees<P>, &ProgressBar) -> Result<(StreamRun, StreamRun), String>,
) -> Result<String, String> {
    let names = list(&a.scenes, |s| Ok(s.to_string()))?;
    let (n, ds) = a
        .builder
        .split_once(':')
        .ok_or_else(|| format!("--builder `{}`: expected `rays:dir_spread`", a.builder))?;
    let rays: usize = n
        .trim()
        .parse()
        .map_err(|_| format!("--builder rays = `{n}` is not a number"))?;
    let spread: f64 = ds
        .trim()
        .parse()
        .map_err(|_| format!("--builder dir_spread = `{ds}` is not a number"))?;
    if a.tile == 0 || a.tile * a.tile > 16 || rays == 0 || rays > 16 {
        return Err(format!(
            "--tile {} and --builder {}: a bundle holds 1 to 16 rays (the ray store's set)",
            a.tile, a.builder
        ));
    }
    let rules = list(&a.rebound, |r| match r {
        "keep" => Ok(false),
        "stored" => Ok(true),
        _ => Err(format!(
            "--rebound `{r}`: the processor's rules are keep and stored"
        )),
    })?;
    let mut csv = format!("{CSV_HEADER}\n");
    let mut table = String::from(
        "| scene | rays | bundling | rebound | bundles | jobs | decided | clocks | pair busy (= model) | utilisation | clocks / job | decided jobs alone: tests / clock | one-job processor: clocks (x) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for scene in &names {
        let sc = crate::sweep_cmd::load_scene(scene, a.seed)?;
        let mut streams = vec![];
        for &rb in &rules {
            let s = scene_streams(
                &sc,
                a.seed,
                (a.width, a.height),
                a.tile,
                (rays, spread),
                dp,
                rb,
            )
            .map_err(|e| format!("{scene}: {e}"))?;
            streams.extend(s.into_iter().map(|s| (rb, s)));
        }
        // Each ray set with either rule, side by side.
        streams.sort_by_key(|(rb, (set, ..))| (*set != "primary", *set != "bounce", *rb));
        for (rb, (set, bundling, trees)) in &streams {
            let rule = if *rb { "stored" } else { "keep" };
            let pb = ProgressBar::new(trees.bundles.len() as u64);
            pb.set_style(
                ProgressStyle::with_template("{msg:40} {bar:30} {pos}/{len} eta {eta}")
                    .expect("template"),
            );
            pb.set_message(format!("{scene} {set} {bundling} {rule}"));
            let (r, d) =
                replay(dp, trees, &pb).map_err(|e| format!("{scene} {set} {bundling}: {e}"))?;
            if pb.is_hidden() {
                eprintln!("{} done", pb.message());
            }
            pb.finish_and_clear();
            let dt = d.jobs as f64 / d.clocks.max(1) as f64;
            // The one-job processor exists on the fixed datapath only.
            let (one_csv, one_md) = match trees.one_job_clocks {
                Some(c) => {
                    let x = c as f64 / r.clocks.max(1) as f64;
                    (format!("{c},{x:.3}"), format!("{c} ({x:.2}x)"))
                }
                None => (",".to_string(), "-".to_string()),
            };
            let _ = writeln!(
                csv,
                "{scene},{set},{bundling},{name},{rule},{},{},{},{},{},{},{:.4},{:.4},{},{},{:.4},{one_csv}",
                r.bundles,
                r.jobs,
                r.decided,
                r.clocks,
                r.busy,
                r.pair_cycles,
                r.utilisation(),
                r.clocks_per_job(),
                d.jobs,
                d.clocks,
                dt,
            );
            let _ = writeln!(
                table,
                "| {scene} | {set} | {bundling} | {rule} | {} | {} | {} | {} | {} | {:.3} | {:.2} | {:.3} | {one_md} |",
                r.bundles,
                r.jobs,
                r.decided,
                r.clocks,
                r.busy,
                r.utilisation(),
                r.clocks_per_job(),
                dt,
            );
        }
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join(format!("bundle_stream_{name}.csv")), &csv)?;
    crate::out_file::write_file(&out.join(format!("bundle_stream_{name}.md")), &table)?;
    Ok(table)
}
