//! `rtu fit`: for each scene and a budget of extra tester cycles, the smallest fixed-point grid width and
//! the smallest float format whose slab tester meets it, per ray set (primary, bounce, shadow, and all
//! three), with their area and latency against binary32's as ratios and their Verilog exported.
//!
//! The search walks the format ladders (`golden::format::fixed::FixFormat::grid`, 6..=20 grid bits;
//! `golden::format::float::FloatFormat::LADDER`, narrowest first) through the same traversal model as `rtu sweep`
//! (single rays, no planes), against the exact machine; the first format within the budget is the fit.
//! "all" is the first format within the budget on every ray set at once. A format a ray does not fit
//! (an origin beyond its range) is skipped, with a line on stderr. Area comes from the synthesis table, or
//! from Yosys with `--synth` for a fitted format not in it; the latency ratio is the datapath's pipeline
//! depth (4 clocks fixed, 9 float), the area ratios count iCE40 LUT4s and 7-series LUTs (DSPs beside).
//!
//! With `--clock MHz` the fit also asks for speed: per scene and ray set, the first format of the ladder
//! within the budget for which some pipeline depth of its slab tester (`rtl::slab::fix::SLAB_FIX_DEPTHS`,
//! `rtl::slab::float::SLAB_FLOAT_DEPTHS`, shallowest first) has a post-route Fmax in the timing table of
//! at least the clock; that depth is the pick. Formats within the budget that have no timing row, or
//! whose fastest depth is too slow, are passed over and listed, so an untimed narrower format is never
//! silently taken for a slow one (`fit/fit_clock.csv`, and a section of `fit/fit.md`).

use crate::sweep_cmd::{
    load_area, load_scene, load_timing, read_area, run_set, tester, Area, Format, Prepared, RunCfg,
    Timing,
};
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use golden::scene::sweep::{ExactTester, RaySet, SceneStats};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `rtu fit`.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// Scenes, comma-separated: built-in names (room, grass, mesh, soup) or OBJ files (`*.obj`).
    #[arg(long, default_value = "room,grass,mesh,soup")]
    pub scenes: String,
    /// Budget: the most extra tester cycles against the exact tester, in percent.
    #[arg(long, default_value_t = 1.0)]
    pub budget: f64,
    /// Image width and height of the primary rays.
    #[arg(long, default_value_t = 32)]
    pub width: usize,
    #[arg(long, default_value_t = 24)]
    pub height: usize,
    /// Secondary-ray origin offset, as a fraction of the scene's diagonal (see `rtu sweep --help`).
    #[arg(long, default_value_t = 1e-5)]
    pub offset: f64,
    /// Seed of the scenes and the secondary rays.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Synthesis table (as for `rtu sweep`; default docs/sweep/area.csv of this source tree).
    #[arg(long)]
    pub area: Option<PathBuf>,
    /// Synthesise with Yosys every fitted format missing from the table (minutes per float format); the
    /// rows are written to <out>/fit/area.csv.
    #[arg(long)]
    pub synth: bool,
    /// Traversal mode, as for `rtu sweep`: `default` (closest hit for primary and bounce rays, any hit for
    /// shadow rays), `closest`, `any` or `all`.
    #[arg(long, default_value = "default")]
    pub mode: String,
    /// Clock target in MHz: also pick, per scene and ray set, the smallest format and pipeline depth
    /// within the budget whose post-route Fmax on ECP5 (the timing table) reaches it; written to
    /// fit/fit_clock.csv and a section of fit/fit.md.
    #[arg(long)]
    pub clock: Option<f64>,
    /// Post-route timing table for `--clock` (the CSV `scripts/timing` writes); default:
    /// docs/timing/timing.csv of this source tree.
    #[arg(long)]
    pub timing: Option<PathBuf>,
}

/// The result of one format on one ray set, measured on demand and kept.
struct Search<'a, 'p> {
    p: &'p Prepared<'a>,
    sets: Vec<RaySet<'p>>,
    exact: Vec<SceneStats>,
    cache: HashMap<(usize, String), Option<SceneStats>>,
    cfg: RunCfg,
}

impl Search<'_, '_> {
    /// Stats of format `f` on set `i`; `None` when the format cannot take the scene or its rays.
    fn run(&mut self, i: usize, f: &Format) -> Result<Option<SceneStats>, String> {
        let key = (i, f.name());
        if let Some(r) = self.cache.get(&key) {
            return Ok(*r);
        }
        let r = match tester(self.p, f, &[], 0) {
            Ok((mut t, _)) => Some(run_set(
                self.p,
                self.p.sets[i].0,
                &mut self.sets[i],
                t.as_mut(),
                None,
                self.cfg,
            )?),
            Err(e) => {
                eprintln!("{}: {} skipped ({e})", self.p.sc.name, f.name());
                None
            }
        };
        self.cache.insert(key, r);
        Ok(r)
    }

    /// Extra box tests of `f` on set `i` against the exact tester (`None`: cannot run).
    fn extra(&mut self, i: usize, f: &Format) -> Result<Option<(f64, SceneStats)>, String> {
        let e = self.exact[i];
        Ok(self.run(i, f)?.map(|st| (extra(&st, &e), st)))
    }
}

fn extra(st: &SceneStats, exact: &SceneStats) -> f64 {
    st.box_tests as f64 / exact.box_tests.max(1) as f64 - 1.0
}

/// The fixed ladder then the float ladder, as sweep formats.
fn ladders() -> [Vec<Format>; 2] {
    [
        FixFormat::ladder().into_iter().map(Format::Fix).collect(),
        FloatFormat::LADDER
            .iter()
            .copied()
            .map(Format::Float)
            .collect(),
    ]
}

/// A fit: the format, the cut points of its tester, the largest extra of the sets, and the sets' pooled
/// stats and pooled exact stats.
type Fit = (Format, usize, f64, SceneStats, SceneStats);

/// What a clock target makes of a format within the budget.
enum Depth {
    /// The tester with these cut points (the shallowest that reaches the clock).
    Take(usize),
    /// Passed over: no depth in the timing table, or the fastest one's Fmax (MHz) is below the clock.
    Pass(Option<f64>),
}

/// The first format of `ladder` within `budget` on every set of `sets` that `depth` takes; with it,
/// the formats within the budget that `depth` passed over before it (narrowest first) and why.
fn first_fit(
    s: &mut Search,
    ladder: &[Format],
    sets: &[usize],
    budget: f64,
    depth: &mut dyn FnMut(&Format) -> Depth,
) -> Result<(Option<Fit>, Vec<(Format, Option<f64>)>), String> {
    let mut passed = vec![];
    if sets.is_empty() {
        return Ok((None, passed));
    }
    'ladder: for f in ladder {
        let (mut worst, mut pooled, mut pooled_exact) = (
            f64::NEG_INFINITY,
            SceneStats::default(),
            SceneStats::default(),
        );
        for &i in sets {
            match s.extra(i, f)? {
                Some((x, st)) if x <= budget => {
                    worst = worst.max(x);
                    pooled.add(&st);
                    pooled_exact.add(&s.exact[i]);
                }
                _ => continue 'ladder,
            }
        }
        match depth(f) {
            Depth::Take(cuts) => {
                return Ok((Some((*f, cuts, worst, pooled, pooled_exact)), passed))
            }
            Depth::Pass(fmax) => passed.push((*f, fmax)),
        }
    }
    Ok((None, passed))
}

/// The cut points of a format's default slab tester (the first of its depths).
fn default_cuts(f: &Format) -> usize {
    depths(f)[0].0
}

/// The built depths of a datapath's slab tester, shallowest first: `(cut points, module-name suffix)`.
fn depths(f: &Format) -> &'static [(usize, &'static str)] {
    match f {
        Format::Fix(_) => &rtl::slab::fix::SLAB_FIX_DEPTHS,
        Format::Float(_) => &rtl::slab::float::SLAB_FLOAT_DEPTHS,
    }
}

/// The shallowest depth of `f`'s tester whose timing row reaches `mhz`, else the fastest Fmax found.
fn at_clock(f: &Format, mhz: f64, timing: &HashMap<String, Timing>) -> Depth {
    let mut best: Option<f64> = None;
    for &(cuts, _) in depths(f) {
        if let Some(t) = timing.get(&module(f, cuts)) {
            if t.fmax_mhz >= mhz {
                return Depth::Take(cuts);
            }
            best = Some(best.map_or(t.fmax_mhz, |b: f64| b.max(t.fmax_mhz)));
        }
    }
    Depth::Pass(best)
}

/// One row of the clock fit.
struct Clocked {
    scene: String,
    set: String,
    datapath: &'static str,
    fit: Option<Fit>,
    passed: Vec<(Format, Option<f64>)>,
}

/// One fitted row: scene, ray set, format, extra box tests, and the rest of its figures.
struct Fitted {
    scene: String,
    set: String,
    datapath: &'static str,
    fit: Option<(Format, f64, SceneStats, SceneStats)>,
}

/// `rtu fit`.
pub fn run(a: &Args, out: &Path) -> Result<String, String> {
    if !(a.budget.is_finite() && a.budget >= 0.0) {
        return Err(format!("--budget {}: a percentage >= 0 expected", a.budget));
    }
    if a.width == 0 || a.height == 0 {
        return Err("--width and --height must be at least 1".into());
    }
    let dir = out.join("fit");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut area = load_area(a.area.as_deref())?;
    let fit_area = dir.join("area.csv");
    if fit_area.exists() {
        for (k, v) in read_area(&fit_area)? {
            area.entry(k).or_insert(v);
        }
    }
    let budget = a.budget / 100.0;
    let ladders = ladders();
    let set_names: Vec<String> = ["primary", "bounce", "shadow"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let cfg = RunCfg {
        k: 0,
        b: 1,
        w: a.width,
        h: a.height,
        mode: crate::sweep_cmd::parse_mode(&a.mode)?,
    };
    let clock = match a.clock {
        None => None,
        Some(mhz) if mhz.is_finite() && mhz > 0.0 => Some((mhz, load_timing(a.timing.as_deref())?)),
        Some(mhz) => return Err(format!("--clock {mhz}: a clock target in MHz > 0 expected")),
    };
    let mut rows: Vec<Fitted> = vec![];
    let mut clocked: Vec<Clocked> = vec![];
    let mut empty: Vec<(String, String)> = vec![];
    for name in a.scenes.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let sc = load_scene(name, a.seed)?;
        let p = Prepared::new(&sc, a.width, a.height, a.seed, &set_names, a.offset)?;
        let sets: Vec<RaySet> = p
            .sets
            .iter()
            .map(|(_, r)| RaySet::new(&p.bvh, &sc.tris, r))
            .collect();
        let mut s = Search {
            p: &p,
            sets,
            exact: vec![],
            cache: HashMap::new(),
            cfg,
        };
        for i in 0..p.sets.len() {
            let mut ex = ExactTester::new(&p.bvh, &[], 0);
            let st = run_set(&p, p.sets[i].0, &mut s.sets[i], &mut ex, None, cfg)?;
            s.exact.push(st);
        }
        // Ray sets with rays (a scene may give no secondary rays at all).
        let live: Vec<usize> = (0..p.sets.len()).filter(|&i| s.exact[i].rays > 0).collect();
        for i in 0..p.sets.len() {
            if !live.contains(&i) {
                empty.push((name.to_string(), p.sets[i].0.to_string()));
            }
        }
        for (dp, ladder) in ["fixed", "float"].into_iter().zip(&ladders) {
            // Per set, then all sets at once (the first format within the budget on every one; its
            // extra is the largest of the sets', the stats are pooled).
            let groups: Vec<(String, Vec<usize>)> = live
                .iter()
                .map(|&i| (p.sets[i].0.to_string(), vec![i]))
                .chain(std::iter::once(("all".to_string(), live.clone())))
                .collect();
            for (set, group) in groups {
                let (fit, _) = first_fit(&mut s, ladder, &group, budget, &mut |f| {
                    Depth::Take(default_cuts(f))
                })?;
                rows.push(Fitted {
                    scene: name.to_string(),
                    set: set.clone(),
                    datapath: dp,
                    fit: fit.map(|(f, _, x, st, ex)| (f, x, st, ex)),
                });
                if let Some((mhz, timing)) = &clock {
                    let (fit, passed) = first_fit(&mut s, ladder, &group, budget, &mut |f| {
                        at_clock(f, *mhz, timing)
                    })?;
                    clocked.push(Clocked {
                        scene: name.to_string(),
                        set,
                        datapath: dp,
                        fit,
                        passed,
                    });
                }
            }
        }
        eprintln!("{name}: {} ladder runs", s.cache.len());
    }
    // Export (and with --synth synthesise) every fitted format and fp32, and every tester the clock
    // fit picked.
    let fp32 = Format::Float(FloatFormat::FP32);
    let mut to_export = vec![(fp32, 0)];
    let fits = rows
        .iter()
        .filter_map(|r| r.fit.map(|(f, ..)| (f, default_cuts(&f))));
    let clock_fits = clocked
        .iter()
        .filter_map(|r| r.fit.map(|(f, c, ..)| (f, c)));
    for (f, c) in fits.chain(clock_fits) {
        if !to_export
            .iter()
            .any(|(x, xc)| module(x, *xc) == module(&f, c))
        {
            to_export.push((f, c));
        }
    }
    let mut new_rows = String::new();
    for (f, cuts) in &to_export {
        let m = module(f, *cuts);
        let path = dir.join(format!("{m}.v"));
        crate::out_file::write_file(&path, verilog(f, *cuts)?)?;
        if a.synth && !area.contains_key(&m) {
            eprintln!("synthesising {m} ...");
            let row = crate::synth::synth_module(&path, &m, latency(f, *cuts), &dir.join("synth"))?
                .area();
            let _ = writeln!(
                new_rows,
                "{m},{},,{},,,{},{},{}",
                row.latency, row.ice40_lut4, row.ice40_depth, row.xilinx_lut, row.xilinx_dsp
            );
            area.insert(m.clone(), row);
        }
    }
    if !new_rows.is_empty() {
        let mut text = std::fs::read_to_string(&fit_area).unwrap_or_default();
        if text.is_empty() {
            text.push_str("module,latency,generic_cells,ice40_lut4,ice40_carry,ice40_ff,ice40_depth,xilinx_lut,xilinx_dsp\n");
        }
        text.push_str(&new_rows);
        crate::out_file::write_file(&fit_area, text)?;
    }
    let (csv, mut md) = render(a, &rows, &empty, &area, &fp32);
    crate::out_file::write_file(&dir.join("fit.csv"), &csv)?;
    if let Some((mhz, timing)) = &clock {
        let (csv, section) = render_clock(a, *mhz, &clocked, timing);
        crate::out_file::write_file(&dir.join("fit_clock.csv"), &csv)?;
        md.push_str(&section);
    }
    crate::out_file::write_file(&dir.join("fit.md"), &md)?;
    Ok(md)
}

/// `fit_clock.csv` and the clock section of `fit.md`.
fn render_clock(
    a: &Args,
    mhz: f64,
    rows: &[Clocked],
    timing: &HashMap<String, Timing>,
) -> (String, String) {
    let mut csv = String::from("scene,ray_set,datapath,clock_mhz,format,coord_bits,module,latency,extra_cycles,cycles_per_ray,ecp5_fmax_mhz,ecp5_lut4,ecp5_ff,ecp5_mult18,rays_per_s_at_clock,passed_over\n");
    let mut md = format!(
        "\n## At {mhz} MHz\n\nThe smallest format and, for it, the shallowest pipeline depth within the budget \
         ({}% extra tester cycles) whose post-route Fmax on ECP5 (LFE5U-85F, speed 8; timing table {}) \
         reaches {mhz} MHz. Rays per second at that clock: the clock over the tester's cycles per ray. \
         Passed over: formats within the budget, narrower than the pick, without a timing row (\"untimed\"; \
         `scripts/timing <module>` places and routes one) or whose fastest depth is too slow.\n\n\
         | scene | rays | datapath | format and depth | extra cycles | Fmax (MHz) | LUT4 / FF / DSP | latency | rays/s at {mhz} MHz | passed over |\n|---|---|---|---|---|---|---|---|---|---|\n",
        a.budget,
        a.timing
            .as_ref()
            .map_or("docs/timing/timing.csv".to_string(), |p| p.display().to_string()),
    );
    for r in rows {
        let passed: Vec<String> = r
            .passed
            .iter()
            .map(|(f, fmax)| match fmax {
                None => format!("{} untimed", f.name()),
                Some(v) => format!("{} {v:.1} MHz", f.name()),
            })
            .collect();
        let passed = passed.join("; ");
        // The table names the untimed formats by count and range, the too slow ones each.
        let untimed: Vec<String> = r
            .passed
            .iter()
            .filter(|p| p.1.is_none())
            .map(|p| p.0.name())
            .collect();
        let mut brief: Vec<String> = match untimed.as_slice() {
            [] => vec![],
            [one] => vec![format!("{one} untimed")],
            [first, .., last] => vec![format!("{} untimed ({first} to {last})", untimed.len())],
        };
        brief.extend(
            r.passed
                .iter()
                .filter_map(|(f, fmax)| fmax.map(|v| format!("{} at most {v:.1} MHz", f.name()))),
        );
        let brief = brief.join("; ");
        let Some((f, cuts, x, st, _)) = &r.fit else {
            let _ = writeln!(
                md,
                "| {} | {} | {} | none within the budget reaches {mhz} MHz | | | | | | {brief} |",
                r.scene, r.set, r.datapath
            );
            let _ = writeln!(
                csv,
                "{},{},{},{mhz},,,,,,,,,,,,{passed}",
                r.scene, r.set, r.datapath
            );
            continue;
        };
        let m = module(f, *cuts);
        let t = &timing[&m];
        let cpr = st.cycles_per_ray();
        let rays = mhz * 1e6 / cpr;
        let opt = |v: Option<u64>| v.map_or(String::new(), |v| v.to_string());
        let _ = writeln!(
            csv,
            "{},{},{},{mhz},{},{},{m},{},{x:.6},{cpr:.4},{:.1},{},{},{},{rays:.4e},{passed}",
            r.scene,
            r.set,
            r.datapath,
            f.name(),
            f.bits(),
            latency(f, *cuts),
            t.fmax_mhz,
            t.lut4,
            opt(t.ff),
            opt(t.mult18),
        );
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} ({} bits), `{m}` | {:+.2}% | {:.1} | {} / {} / {} | {} | {rays:.3e} | {brief} |",
            r.scene,
            r.set,
            r.datapath,
            f.name(),
            f.bits(),
            100.0 * x,
            t.fmax_mhz,
            t.lut4,
            t.ff.map_or("-".into(), |v| v.to_string()),
            t.mult18.map_or("-".into(), |v| v.to_string()),
            latency(f, *cuts),
        );
    }
    (csv, md)
}

/// `fit.csv` and `fit.md`.
fn render(
    a: &Args,
    rows: &[Fitted],
    empty: &[(String, String)],
    area: &HashMap<String, Area>,
    fp32: &Format,
) -> (String, String) {
    let mut csv = String::from("scene,ray_set,datapath,format,coord_bits,extra_cycles,exact_cycles_per_ray,extra_tri_tests,false_hit_rate,module,latency,ice40_lut4,xilinx_lut,xilinx_dsp,lut4_vs_fp32,xilinx_lut_vs_fp32,latency_vs_fp32,third_of_fp32\n");
    let mut md = format!(
        "Budget: at most {}% extra tester cycles against the exact slab tester (single rays, no planes), \
         {}x{} primary rays, secondary origins offset by {:e} of the diagonal. \"all\": the first format \
         within the budget on every ray set (extra: the largest of the sets').\n\n\
         | scene | rays | datapath | fitted format | extra cycles | extra triangle tests | iCE40 LUT4 (vs fp32) | 7-series LUT + DSP (vs fp32) | latency (vs fp32) | at most 1/3 of fp32 |\n|---|---|---|---|---|---|---|---|---|---|\n",
        a.budget, a.width, a.height, a.offset
    );
    let base = area.get(&module(fp32, 0)).cloned();
    for r in rows {
        let Some((f, x, st, ex)) = &r.fit else {
            let _ = writeln!(
                md,
                "| {} | {} | {} | none on the ladder meets the budget | | | | | | |",
                r.scene, r.set, r.datapath
            );
            let _ = writeln!(csv, "{},{},{},,,,,,,,,,,,,,,", r.scene, r.set, r.datapath);
            continue;
        };
        let m = module(f, default_cuts(f));
        let ar = area.get(&m).cloned();
        let ratio = |g: &dyn Fn(&Area) -> f64| match (&ar, &base) {
            (Some(a), Some(b)) => Some(g(a) / g(b)),
            _ => None,
        };
        let lut = ratio(&|a| a.ice40_lut4 as f64);
        let xl = ratio(&|a| a.xilinx_lut as f64);
        let lat = latency(f, default_cuts(f)) as f64 / latency(fp32, 0) as f64;
        let third = lut.map(|v| v <= 1.0 / 3.0);
        let tri = st.tri_tests as f64 / ex.tri_tests.max(1) as f64 - 1.0;
        let opt = |v: Option<String>| v.unwrap_or_default();
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{x:.6},{:.4},{tri:.6},{:.6},{m},{},{},{},{},{},{},{lat:.3},{}",
            r.scene,
            r.set,
            r.datapath,
            f.name(),
            f.bits(),
            ex.box_tests as f64 / ex.rays.max(1) as f64,
            st.false_hit_rate(),
            latency(f, default_cuts(f)),
            opt(ar.as_ref().map(|a| a.ice40_lut4.to_string())),
            opt(ar.as_ref().map(|a| a.xilinx_lut.to_string())),
            opt(ar.as_ref().map(|a| a.xilinx_dsp.to_string())),
            opt(lut.map(|v| format!("{v:.4}"))),
            opt(xl.map(|v| format!("{v:.4}"))),
            opt(third.map(|t| t.to_string())),
        );
        let two = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2}"));
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} ({} bits) | {:+.2}% | {:+.2}% | {} ({}) | {} ({}) | {} ({lat:.2}) | {} |",
            r.scene,
            r.set,
            r.datapath,
            f.name(),
            f.bits(),
            100.0 * x,
            100.0 * tri,
            ar.as_ref()
                .map_or("not synthesised".to_string(), |a| a.ice40_lut4.to_string()),
            two(lut),
            ar.as_ref()
                .map_or("-".to_string(), |a| format!("{} + {}", a.xilinx_lut, a.xilinx_dsp)),
            two(xl),
            latency(f, default_cuts(f)),
            third.map_or("- (run with --synth)".to_string(), |t| {
                if t { "yes" } else { "no" }.to_string()
            }),
        );
    }
    for (scene, set) in empty {
        let _ = writeln!(
            md,
            "| {scene} | {set} | - | no rays in this set | | | | | | |"
        );
    }
    let _ = writeln!(
        md,
        "\nVerilog of every fitted format and of fp32: `fit/*.v` under the output folder"
    );
    (csv, md)
}

/// Module name of `f`'s slab tester with cut points `cuts`.
fn module(f: &Format, cuts: usize) -> String {
    match f {
        Format::Fix(x) => rtl::names::slab_fix_module_cuts(x, cuts),
        Format::Float(x) => rtl::names::slab_float_module_cuts(x, cuts),
    }
}

/// Latency in clocks of `f`'s slab tester with cut points `cuts`.
fn latency(f: &Format, cuts: usize) -> usize {
    match f {
        Format::Fix(_) => rtl::slab::fix::slab_fix_latency(cuts),
        Format::Float(_) => rtl::slab::float::slab_float_latency(cuts),
    }
}

/// Verilog of `f`'s slab tester with cut points `cuts`: any ladder format at the default depth, the
/// exported presets at the others.
fn verilog(f: &Format, cuts: usize) -> Result<String, String> {
    if cuts == default_cuts(f) {
        return match f {
            Format::Fix(x) => rtl::export::slab_fix_verilog_ladder(x),
            Format::Float(x) => rtl::export::slab_float_verilog_ladder(x),
        };
    }
    let m = module(f, cuts);
    rtl::export::find(&m).map(|e| e.verilog()).map_err(|_| {
        format!(
            "{m}: the timing table has this tester, but only the preset formats are built at {} clocks",
            latency(f, cuts)
        )
    })
}
