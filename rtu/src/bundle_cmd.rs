//! `rtu bundle-scenes`: ray bundles on scenes with the AllHit / AnyHit pair:
//! per scene, ray set, bundling and datapath, the fraction of bundle-box tests decided without splitting
//! against the ideal, and tester cycles against testing the rays one by one, under each re-bounding rule
//! (column `rebound`: `keep`, `world`, and for the fixed and float datapaths `stored`, the results
//! processor's rule). The
//! traversal and its checks are [`golden::bundle::traverse`]; the bundling [`golden::bundle::build`].

use crate::opts::list;
use golden::bundle::build::{build, tiles, BuildParams, Built, SplitMetric};
use golden::bundle::fix::BundleFixFormat;
use golden::bundle::traverse::{
    traverse_all, BundlePath, BundleStats, ExactHits, Rebound, TravOptions,
};
use golden::format::fixed::{FixFormat, GridMap};
use golden::format::float::FloatFormat;
use golden::geom::Ray;
use golden::scene::bvh::Bvh;
use golden::scene::traverse::{trace, AabbOnly};
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;
use std::path::Path;

/// Arguments of `rtu bundle-scenes`.
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
    /// Tile sizes for primary-ray bundles (tile x tile pixels), comma-separated.
    #[arg(long, default_value = "2,4,8")]
    tiles: String,
    /// Builder settings for secondary rays, comma-separated `rays:dir_spread` (origin spread is
    /// `--origin-spread` of the scene's diagonal).
    #[arg(long, default_value = "4:0.2,16:0.2,16:0.5")]
    builder: String,
    /// Largest origin spread of a built bundle, as a fraction of the scene's diagonal.
    #[arg(long, default_value_t = 0.1)]
    origin_spread: f64,
    /// Open bundles of the builder.
    #[arg(long, default_value_t = 16)]
    open_slots: usize,
    /// Datapaths: `exact`, fixed presets (b8, b12, b16) and float formats (fp32, bf16, fp16, eXmY).
    #[arg(long, default_value = "exact,b16,b12,fp32,fp16")]
    paths: String,
    /// Splitting metric `min_rays:max_footprint` run beside "never split early"; `none` for only that.
    #[arg(long, default_value = "2:2.0")]
    metric: String,
    /// Seed of the scenes and the secondary rays.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Datapath of the charts (default: the first fixed one listed, else the first).
    #[arg(long)]
    chart_path: Option<String>,
}

/// One measured configuration, kept for the charts.
struct Rec {
    series: String,
    path: String,
    rebound: Rebound,
    metric: String,
    per: f64,
    st: BundleStats,
}

fn num<T: std::str::FromStr>(s: &str, what: &str) -> Result<T, String> {
    s.trim()
        .parse()
        .map_err(|_| format!("{what} = `{s}` is not a number"))
}

/// A datapath by name: `exact`, a fixed preset, or a float format.
enum PathSpec {
    Exact,
    Fix(BundleFixFormat),
    Float(FloatFormat),
}

fn parse_path(s: &str) -> Result<PathSpec, String> {
    if s == "exact" {
        return Ok(PathSpec::Exact);
    }
    if let Ok(f) = FixFormat::parse(s) {
        return BundleFixFormat::over(f)
            .map(PathSpec::Fix)
            .map_err(|e| e.to_string());
    }
    FloatFormat::parse(s)
        .map(PathSpec::Float)
        .map_err(|e| format!("datapath `{s}`: not `exact`, a fixed preset or a float format ({e})"))
}

fn parse_metric(s: &str) -> Result<Option<SplitMetric>, String> {
    if s == "none" {
        return Ok(None);
    }
    let (a, b) = s
        .split_once(':')
        .ok_or_else(|| format!("metric `{s}`: expected `min_rays:max_footprint` or `none`"))?;
    let m = SplitMetric {
        min_rays: num(a, "metric min_rays")?,
        max_footprint: num(b, "metric max_footprint")?,
    };
    if m.max_footprint.is_nan() || m.max_footprint < 0.0 {
        return Err(format!("metric max_footprint = {b}: must be a number >= 0"));
    }
    Ok(Some(m))
}

/// One bundling of one ray set.
struct Bundling {
    set: &'static str,
    name: String,
    built: Vec<Built>,
}

fn bundlings(
    prim: &[Ray],
    sec: &golden::scene::tri_scene::SecondaryRays,
    a: &Args,
    diag: f64,
    tile_sizes: &[usize],
    builders: &[(usize, f64)],
) -> Result<Vec<(Bundling, &'static str)>, String> {
    let mut out = vec![];
    for &t in tile_sizes {
        out.push((
            Bundling {
                set: "primary",
                name: format!("tile{t}x{t}"),
                built: tiles(prim, a.width, a.height, t).map_err(|e| e.to_string())?,
            },
            "primary",
        ));
    }
    for (set, rays) in [("bounce", &sec.bounce), ("shadow", &sec.shadow)] {
        for &(n, ds) in builders {
            let p = BuildParams {
                max_rays: n,
                origin_spread: a.origin_spread * diag,
                dir_spread: ds,
                t_spread: f64::INFINITY,
                open_slots: a.open_slots,
            };
            out.push((
                Bundling {
                    set,
                    name: format!("build{n}@{ds}"),
                    built: build(rays, &p).map_err(|e| format!("{set} rays: {e}"))?,
                },
                set,
            ));
        }
    }
    Ok(out)
}

/// CSV header of `bundle_scenes.csv`.
pub const CSV_HEADER: &str = "scene,rays,bundling,bundles,rays_per_bundle,mean_dir_spread,datapath,format,rebound,metric,tests,ideal,decided,decided_of_ideal,decided_all_hit,early_splits,pair_cycles,ray_cycles,ray_pair_cycles,speedup_vs_single,speedup_vs_pair,false_hits";

/// Runs the measurement; returns the markdown table, writes `bundle_scenes.csv` under `out`.
pub fn scenes(a: &Args, out: &Path) -> Result<String, String> {
    let names = list(&a.scenes, |s| Ok(s.to_string()))?;
    let tile_sizes = list(&a.tiles, |s| num::<usize>(s, "tile"))?;
    let builders = list(&a.builder, |s| {
        let (n, d) = s
            .split_once(':')
            .ok_or_else(|| format!("builder `{s}`: expected `rays:dir_spread`"))?;
        Ok((
            num::<usize>(n, "builder rays")?,
            num::<f64>(d, "builder dir_spread")?,
        ))
    })?;
    let paths = list(&a.paths, parse_path)?;
    let metrics: Vec<(String, SplitMetric)> = std::iter::once(("never".into(), SplitMetric::NEVER))
        .chain(parse_metric(&a.metric)?.map(|m| (a.metric.clone(), m)))
        .collect();
    let mut csv = format!("{CSV_HEADER}\n");
    let mut table = String::from(
        "| scene | rays | bundling | rays/bundle | datapath | rebound | metric | tests | decided / ideal | cycles: single-ray tester / bundle pair | pair without / with bundles | false hits |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut recs: Vec<Rec> = vec![];
    for name in &names {
        let sc = crate::sweep_cmd::load_scene(name, a.seed)?;
        let bvh = Bvh::build(&sc.tris, 4).map_err(|e| e.to_string())?;
        let prim = golden::scene::tri_scene::primary_rays(&sc, a.width, a.height);
        let (hits, _) = trace(&bvh, &sc.tris, &prim, &mut AabbOnly::new(&bvh));
        let sec = golden::scene::tri_scene::secondary_rays(&sc, &prim, &hits, a.seed + 1);
        let b = sc.bounds();
        let diag = (b.max - b.min).length();
        let (lo, hi) = sc.grid_bounds();
        let mut built_paths = vec![];
        for p in &paths {
            built_paths.push(match p {
                PathSpec::Exact => BundlePath::Exact,
                PathSpec::Fix(bf) => BundlePath::Fix(
                    *bf,
                    GridMap::for_bounds(bf.base, lo, hi).map_err(|e| e.to_string())?,
                ),
                PathSpec::Float(f) => BundlePath::Float(*f),
            });
        }
        let sets: Vec<(&str, &[Ray], ExactHits)> = [
            ("primary", &prim[..]),
            ("bounce", &sec.bounce[..]),
            ("shadow", &sec.shadow[..]),
        ]
        .into_iter()
        .map(|(s, r)| (s, r, ExactHits::new(&bvh, r)))
        .collect();
        for (bd, _) in bundlings(&prim, &sec, a, diag, &tile_sizes, &builders)? {
            let (_, rays, exact) = sets
                .iter()
                .find(|s| s.0 == bd.set)
                .expect("every bundling is of a known ray set");
            let nb = bd.built.len() as u64;
            for path in &built_paths {
                // Stored-ray re-bounding is the results processors' rule: the exact path has no store.
                let rules = Rebound::ALL
                    .into_iter()
                    .filter(|r| *r != Rebound::Stored || !matches!(path, BundlePath::Exact));
                for rebound in rules {
                    for (mname, metric) in &metrics {
                        let pb = ProgressBar::new(nb);
                        pb.set_style(
                            ProgressStyle::with_template("{msg:48} {bar:30} {pos}/{len} eta {eta}")
                                .expect("template"),
                        );
                        pb.set_message(format!(
                            "{name} {} {} {} {}",
                            bd.set,
                            bd.name,
                            path.name(),
                            rebound.name()
                        ));
                        let opt = TravOptions {
                            metric: *metric,
                            rebound,
                        };
                        let st =
                            traverse_all(&bvh, rays, exact, &bd.built, path, &opt, || pb.inc(1))
                                .map_err(|e| {
                                    format!("{name} {} {} {}: {e}", bd.set, bd.name, path.name())
                                })?;
                        if pb.is_hidden() {
                            eprintln!("{} done", pb.message());
                        }
                        pb.finish_and_clear();
                        row(&mut csv, &mut table, name, &bd, path, rebound, mname, &st);
                        recs.push(Rec {
                            series: format!("{name} {}", bd.set),
                            path: path.name(),
                            rebound,
                            metric: mname.clone(),
                            per: st.rays as f64 / st.bundles.max(1) as f64,
                            st,
                        });
                    }
                }
            }
        }
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join("bundle_scenes.csv"), &csv)?;
    let chart_path = match &a.chart_path {
        Some(p) => p.clone(),
        None => paths
            .iter()
            .position(|p| matches!(p, PathSpec::Fix(_)))
            .or((!paths.is_empty()).then_some(0))
            .and_then(|i| recs.iter().find(|r| r.path == path_name(&paths[i])))
            .map_or_else(String::new, |r| r.path.clone()),
    };
    charts(&recs, &chart_path, out)?;
    let _ = writeln!(
        table,
        "\nCharts ({chart_path}, re-bounded in world units, no early split): {}/bundle_decided.svg, {}/bundle_speedup.svg",
        out.display(),
        out.display()
    );
    Ok(table)
}

fn path_name(p: &PathSpec) -> String {
    match p {
        PathSpec::Exact => BundlePath::Exact.name(),
        PathSpec::Fix(bf) => golden::bundle::traverse::short_name(&bf.base),
        PathSpec::Float(f) => f.name(),
    }
}

/// Decided-of-ideal and speed-up against rays per bundle, one series per scene and ray set.
fn charts(recs: &[Rec], path: &str, out: &Path) -> Result<(), String> {
    let mut decided: Vec<crate::chart::Series> = vec![];
    let mut speedup: Vec<crate::chart::Series> = vec![];
    for r in recs
        .iter()
        .filter(|r| r.path == path && r.rebound == Rebound::World && r.metric == "never")
    {
        let i = match decided.iter().position(|s| s.0 == r.series) {
            Some(i) => i,
            None => {
                decided.push((r.series.clone(), vec![]));
                speedup.push((r.series.clone(), vec![]));
                decided.len() - 1
            }
        };
        decided[i].1.push((r.per, 100.0 * r.st.decided_of_ideal()));
        speedup[i].1.push((r.per, r.st.speedup()));
    }
    for s in decided.iter_mut().chain(speedup.iter_mut()) {
        s.1.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    crate::chart::line_chart(
        &out.join("bundle_decided.svg"),
        &format!("Bundle-box tests decided without splitting, % of the decidable ({path})"),
        "rays per bundle (mean)",
        "decided / ideal (%)",
        &decided,
        false,
    )?;
    crate::chart::line_chart(
        &out.join("bundle_speedup.svg"),
        &format!("Single-ray tester cycles / bundle pair cycles ({path})"),
        "rays per bundle (mean)",
        "speed-up (x)",
        &speedup,
        true,
    )
}

#[allow(clippy::too_many_arguments)]
fn row(
    csv: &mut String,
    table: &mut String,
    scene: &str,
    bd: &Bundling,
    path: &BundlePath,
    rebound: Rebound,
    metric: &str,
    st: &BundleStats,
) {
    let per = st.rays as f64 / st.bundles.max(1) as f64;
    let spread = st.dir_spread_sum / st.bundles.max(1) as f64;
    let _ = writeln!(
        csv,
        "{scene},{},{},{},{per:.2},{spread:.4},{},{},{},{metric},{},{},{},{:.4},{},{},{},{},{},{:.3},{:.3},{}",
        bd.set,
        bd.name,
        st.bundles,
        path.kind(),
        path.name(),
        rebound.name(),
        st.tests,
        st.ideal,
        st.decided,
        st.decided_of_ideal(),
        st.decided_hit,
        st.early_splits,
        st.pair_cycles,
        st.ray_cycles,
        st.ray_pair_cycles,
        st.speedup(),
        st.pair_speedup(),
        st.false_hits
    );
    let _ = writeln!(
        table,
        "| {scene} | {} | {} | {per:.1} | {} | {} | {metric} | {} | {:.1}% | {:.2}x | {:.2}x | {} |",
        bd.set,
        bd.name,
        path.name(),
        rebound.name(),
        st.tests,
        100.0 * st.decided_of_ideal(),
        st.speedup(),
        st.pair_speedup(),
        st.false_hits
    );
}

/// Arguments of `rtu bundle-campaign`.
#[derive(clap::Args, Debug)]
pub struct CampaignArgs {
    /// Bundles; each is judged by every datapath listed (shared per-ray truth).
    #[arg(long, default_value_t = 10_000_000)]
    bundles: u64,
    /// Fixed presets, comma-separated; empty for none.
    #[arg(long, default_value = "b8,b12,b16")]
    fixed: String,
    /// Float formats, comma-separated; empty for none.
    #[arg(long, default_value = "fp32,bf16,fp16")]
    float: String,
    /// Fraction of adversarial bundles (grazing edges, mixed signs, zero-width and wide, origins inside,
    /// t_max ending at a face, ...).
    #[arg(long, default_value_t = 0.5)]
    adversarial: f64,
    /// Run the exact bundle oracle on every N-th bundle (1: every bundle).
    #[arg(long, default_value_t = 1)]
    oracle_every: u64,
    /// One on-grid single ray per fixed preset every N bundles, checked for the exact answer.
    #[arg(long, default_value_t = 4)]
    one_ray_every: u64,
    #[arg(long, default_value_t = 1)]
    seed: u64,
    #[arg(long, default_value_t = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1))]
    threads: usize,
}

/// Per datapath: its tally, and for fixed presets the one-ray checks (count, exact answers).
struct Share {
    tallies: Vec<golden::bundle::check::Tally>,
    one_ray: Vec<(u64, u64, Vec<String>)>,
}

/// The conservativeness campaign of the bundle pair: `bundles` cases from `golden::bundle::gen`, each
/// judged on every datapath against the exact per-ray results and the exact oracle
/// (`golden::bundle::check`). Returns the report; errors if any promise is broken.
pub fn campaign(a: &CampaignArgs, out: &Path) -> Result<String, String> {
    use golden::bundle::check::{oracle, truth, Tally};
    use golden::bundle::gen::BundleGen;
    if !(0.0..=1.0).contains(&a.adversarial) {
        return Err(format!(
            "--adversarial {}: a fraction in 0..=1 is expected",
            a.adversarial
        ));
    }
    if a.oracle_every == 0 || a.one_ray_every == 0 || a.threads == 0 {
        return Err("--oracle-every, --one-ray-every and --threads must be at least 1".into());
    }
    let fixed = list(&a.fixed, |s| {
        FixFormat::parse(s)
            .and_then(BundleFixFormat::over)
            .map_err(|e| e.to_string())
    })?;
    let floats = list(&a.float, |s| {
        FloatFormat::parse(s).map_err(|e| e.to_string())
    })?;
    let (lo, hi) = (glam::DVec3::splat(-100.0), glam::DVec3::splat(100.0));
    let maps = fixed
        .iter()
        .map(|bf| GridMap::for_bounds(bf.base, lo, hi).map_err(|e| e.to_string()))
        .collect::<Result<Vec<_>, _>>()?;
    let names: Vec<String> = fixed
        .iter()
        .map(|bf| format!("fixed {}", golden::bundle::traverse::short_name(&bf.base)))
        .chain(floats.iter().map(|f| format!("float {}", f.name())))
        .collect();
    let pb = ProgressBar::new(a.bundles);
    pb.set_style(
        ProgressStyle::with_template("bundles {bar:40} {pos}/{len} {per_sec} eta {eta}")
            .expect("template"),
    );
    let start = std::time::Instant::now();
    let shares: Vec<Share> = std::thread::scope(|s| -> Result<Vec<Share>, String> {
        let handles: Vec<_> = (0..a.threads as u64)
            .map(|t| {
                let n = a.bundles / a.threads as u64 + u64::from(t < a.bundles % a.threads as u64);
                let (fixed, floats, maps, pb) = (&fixed, &floats, &maps, &pb);
                s.spawn(move || {
                    let seed = a.seed.wrapping_mul(1_000_003).wrapping_add(t);
                    let mut g = BundleGen::new(seed, lo, hi, a.adversarial);
                    let mut one = BundleGen::new(seed ^ 0x5eed, lo, hi, 1.0);
                    let mut sh = Share {
                        tallies: vec![Tally::default(); fixed.len() + floats.len()],
                        one_ray: vec![(0, 0, vec![]); fixed.len()],
                    };
                    for i in 0..n {
                        let c = g.next_case();
                        let tr = truth(&c);
                        let or = (i % a.oracle_every == 0).then(|| oracle(&c));
                        for (k, (bf, map)) in fixed.iter().zip(maps).enumerate() {
                            let got =
                                golden::bundle::fix::decide_fix(bf, map, &c.bundle, &c.bounds)
                                    .map_err(|e| format!("fixed {}: {e}", bf.name()))?;
                            sh.tallies[k].add(&c, &tr, or, got);
                        }
                        for (k, f) in floats.iter().enumerate() {
                            let got = golden::bundle::float::decide_float(f, &c.bundle, &c.bounds)
                                .map_err(|e| format!("float {}: {e}", f.name()))?;
                            sh.tallies[fixed.len() + k].add(&c, &tr, or, got);
                        }
                        if i % a.one_ray_every == 0 {
                            for (k, (bf, map)) in fixed.iter().zip(maps).enumerate() {
                                let c = one.grid_one_ray(map);
                                let hit = truth(&c)[0];
                                let got =
                                    golden::bundle::fix::decide_fix(bf, map, &c.bundle, &c.bounds)
                                        .map_err(|e| format!("fixed {}: {e}", bf.name()))?;
                                let o = &mut sh.one_ray[k];
                                o.0 += 1;
                                if got == (hit, !hit) {
                                    o.1 += 1;
                                } else if o.2.len() < 10 {
                                    o.2.push(format!(
                                        "one ray not exact: {got:?} for hit {hit}: {c:?}"
                                    ));
                                }
                            }
                        }
                        if i % 1024 == 1023 {
                            pb.inc(1024);
                            // No terminal (a log, CI): a line per 2^20 bundles of the first thread instead of the bar.
                            if pb.is_hidden() && t == 0 && i % (1 << 20) == (1 << 20) - 1 {
                                eprintln!(
                                    "bundle campaign: {} of {} bundles",
                                    pb.position(),
                                    a.bundles
                                );
                            }
                        }
                    }
                    Ok(sh)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    })?;
    pb.finish_and_clear();
    let secs = start.elapsed().as_secs_f64();
    let mut tallies = vec![Tally::default(); names.len()];
    let mut one_ray = vec![(0u64, 0u64, Vec::<String>::new()); fixed.len()];
    for sh in &shares {
        for (t, s) in tallies.iter_mut().zip(&sh.tallies) {
            t.merge(s);
        }
        for (o, s) in one_ray.iter_mut().zip(&sh.one_ray) {
            o.0 += s.0;
            o.1 += s.1;
            o.2.extend(s.2.iter().cloned());
        }
    }
    let mut rep = format!(
        "bundle campaign: {} bundles, seed {}, {} threads, {:.0} s; adversarial fraction {}, exact oracle on every {} bundle(s)\n",
        a.bundles, a.seed, a.threads, secs, a.adversarial, a.oracle_every
    );
    for (n, t) in names.iter().zip(&tallies) {
        let _ = writeln!(rep, "{}", t.report(n));
    }
    for (k, o) in one_ray.iter().enumerate() {
        let _ = writeln!(
            rep,
            "{}: {} on-grid single rays, {} with the exact answer",
            names[k], o.0, o.1
        );
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join("bundle_campaign.md"), &rep)?;
    let bad: Vec<String> = names
        .iter()
        .zip(&tallies)
        .filter(|(_, t)| t.violation_count > 0)
        .map(|(n, t)| {
            format!(
                "{n}: {} violations, first: {}",
                t.violation_count, t.violations[0]
            )
        })
        .chain(
            names
                .iter()
                .zip(&one_ray)
                .filter(|(_, o)| o.0 != o.1)
                .map(|(n, o)| format!("{n}: {}", o.2[0])),
        )
        .collect();
    if bad.is_empty() {
        Ok(rep)
    } else {
        Err(format!("{rep}\n{}", bad.join("\n")))
    }
}
