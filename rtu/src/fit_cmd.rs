//! `rtu fit`: for each scene and a budget of extra tester cycles, the smallest fixed-point grid width and
//! the smallest float format whose slab tester meets it, per ray set (primary, bounce, shadow, and all
//! three), with their area and latency against binary32's as ratios and their Verilog exported (issue 6).
//!
//! The search walks the format ladders (`golden::fixed::FixFormat::grid`, 6..=20 grid bits;
//! `golden::float::FloatFormat::LADDER`, narrowest first) through the same traversal model as `rtu sweep`
//! (single rays, no planes), against the exact machine; the first format within the budget is the fit.
//! Area comes from the synthesis table, or from Yosys with `--synth` for a fitted format not in it.

use crate::sweep_cmd::{load_scene, read_area, run_set, tester, Area, Format, Prepared};
use golden::fixed::FixFormat;
use golden::float::FloatFormat;
use golden::scene_trav::{ExactTester, RaySet, SceneStats};
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
    /// Synthesis table (as for `rtu sweep`).
    #[arg(long, default_value = "docs/sweep/area.csv")]
    pub area: PathBuf,
    /// Synthesise with Yosys every fitted format missing from the table (minutes per float format); the
    /// rows are written to <out>/fit/area.csv.
    #[arg(long)]
    pub synth: bool,
}

/// One ladder format's result on one ray set.
struct Tried {
    format: Format,
    st: SceneStats,
}

fn extra(st: &SceneStats, exact: &SceneStats) -> f64 {
    st.box_tests as f64 / exact.box_tests.max(1) as f64 - 1.0
}

/// The fixed ladder then the float ladder, as sweep formats.
fn ladders() -> (Vec<Format>, Vec<Format>) {
    (
        FixFormat::ladder().into_iter().map(Format::Fix).collect(),
        FloatFormat::LADDER
            .iter()
            .copied()
            .map(Format::Float)
            .collect(),
    )
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
    let mut area = read_area(&crate::sweep_cmd::area_path(&a.area))?;
    let fit_area = dir.join("area.csv");
    for (k, v) in read_area(&fit_area)? {
        area.entry(k).or_insert(v);
    }
    let budget = a.budget / 100.0;
    let (fixed, floats) = ladders();
    let sets = ["primary", "bounce", "shadow"];
    let set_names: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let mut csv = String::from("scene,rays,datapath,format,bits,extra_cycles,exact_cycles_per_ray,module,latency,ice40_lut4,xilinx_lut,xilinx_dsp,lut4_vs_fp32,xilinx_lut_vs_fp32,latency_vs_fp32,third_of_fp32\n");
    let mut md = format!(
        "Budget: at most {}% extra tester cycles against the exact slab tester (single rays, no planes), \
         {}x{} primary rays, secondary origins offset by {:e} of the diagonal.\n\n\
         | scene | rays | datapath | fitted format | extra cycles | iCE40 LUT4 (vs fp32) | 7-series LUT + DSP (vs fp32) | latency (vs fp32) | at most 1/3 of fp32 |\n|---|---|---|---|---|---|---|---|---|\n",
        a.budget, a.width, a.height, a.offset
    );
    let mut to_export: Vec<Format> = vec![];
    let mut pending: Vec<(String, String, Format, f64, f64)> = vec![];
    for name in a.scenes.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let sc = load_scene(name, a.seed)?;
        let p = Prepared::new(&sc, a.width, a.height, a.seed, &set_names, a.offset)?;
        let mut rsets: Vec<RaySet> = p
            .sets
            .iter()
            .map(|(_, r)| RaySet::new(&p.bvh, &sc.tris, r))
            .collect();
        // Per ray set (and "all"): the exact machine, then every ladder format until both fit.
        let mut per_set: Vec<(String, SceneStats, Vec<Tried>)> = vec![];
        for (i, set) in rsets.iter_mut().enumerate() {
            let sn = p.sets[i].0;
            let mut ex = ExactTester::new(&p.bvh, &[], 0);
            let exact = run_set(&p, sn, set, &mut ex, None, 1, a.width, a.height)?;
            let mut tried = vec![];
            for ladder in [&fixed, &floats] {
                for f in ladder.iter() {
                    let (mut t, _) = match tester(&p, f, &[], 0) {
                        Ok(t) => t,
                        Err(e) => {
                            eprintln!("{name} {}: skipped ({e})", f.name());
                            continue;
                        }
                    };
                    let st = run_set(&p, sn, set, t.as_mut(), None, 1, a.width, a.height)?;
                    let ok = extra(&st, &exact) <= budget;
                    tried.push(Tried { format: *f, st });
                    if ok {
                        break;
                    }
                }
            }
            eprintln!("{name} {sn}: {} formats tried", tried.len());
            per_set.push((sn.to_string(), exact, tried));
        }
        // "all": sums over the sets of every format tried on all of them.
        let mut all_exact = SceneStats::default();
        for s in &per_set {
            all_exact.add(&s.1);
        }
        let mut rows: Vec<(String, SceneStats, Vec<(Format, SceneStats)>)> = per_set
            .iter()
            .map(|(n, e, t)| (n.clone(), *e, t.iter().map(|x| (x.format, x.st)).collect()))
            .collect();
        let mut all_tried = vec![];
        for ladder in [&fixed, &floats] {
            for f in ladder.iter() {
                let mut sum = SceneStats::default();
                let mut complete = true;
                for (_, _, t) in &rows {
                    match t.iter().find(|x| x.0.name() == f.name()) {
                        Some(x) => sum.add(&x.1),
                        None => complete = false,
                    }
                }
                if !complete {
                    // A set stopped earlier: measure the missing sets now.
                    sum = SceneStats::default();
                    let Ok((mut t, _)) = tester(&p, f, &[], 0) else {
                        continue;
                    };
                    for (i, set) in rsets.iter_mut().enumerate() {
                        let st =
                            run_set(&p, p.sets[i].0, set, t.as_mut(), None, 1, a.width, a.height)?;
                        sum.add(&st);
                    }
                }
                all_tried.push((*f, sum));
                if extra(&sum, &all_exact) <= budget {
                    break;
                }
            }
        }
        rows.push(("all".into(), all_exact, all_tried));
        for (set, exact, tried) in &rows {
            for dp in ["fixed", "float"] {
                let fit = tried
                    .iter()
                    .find(|(f, st)| f.datapath() == dp && extra(st, exact) <= budget);
                match fit {
                    Some((f, st)) => {
                        if !to_export.iter().any(|x| x.name() == f.name()) {
                            to_export.push(*f);
                        }
                        pending.push((
                            name.to_string(),
                            set.clone(),
                            *f,
                            extra(st, exact),
                            exact.box_tests as f64 / exact.rays.max(1) as f64,
                        ));
                    }
                    None => {
                        let _ = writeln!(
                            md,
                            "| {name} | {set} | {dp} | none on the ladder meets the budget | | | | | |"
                        );
                        let _ = writeln!(csv, "{name},{set},{dp},,,,,,,,,,,,,");
                    }
                }
            }
        }
    }
    // Export and (optionally) synthesise the fitted formats, then fill in the table.
    let fp32 = Format::Float(FloatFormat::FP32);
    let fp32_mod = module(&fp32);
    let mut new_rows = String::new();
    for f in std::iter::once(&fp32).chain(to_export.iter()) {
        let m = module(f);
        let v = match f {
            Format::Fix(x) => rtl::export::slab_fix_verilog_ladder(x)?,
            Format::Float(x) => rtl::export::slab_float_verilog_ladder(x)?,
        };
        let path = dir.join(format!("{m}.v"));
        std::fs::write(&path, v).map_err(|e| format!("{}: {e}", path.display()))?;
        if a.synth && !area.contains_key(&m) {
            eprintln!("synthesising {m} ...");
            let lat = latency(f);
            let row = crate::synth::synth(&path, &m, lat, &dir.join("synth"))?;
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
        std::fs::write(&fit_area, text).map_err(|e| format!("{}: {e}", fit_area.display()))?;
    }
    let base = area.get(&fp32_mod).cloned();
    for (scene, set, f, x, _) in &pending {
        let m = module(f);
        let a_ = area.get(&m).cloned();
        let ratio = |g: &dyn Fn(&Area) -> f64| match (&a_, &base) {
            (Some(a), Some(b)) => Some(g(a) / g(b)),
            _ => None,
        };
        let lut = ratio(&|a| a.ice40_lut4 as f64);
        let xl = ratio(&|a| a.xilinx_lut as f64);
        let lat = latency(f) as f64 / latency(&fp32) as f64;
        let third = lut.map(|r| r <= 1.0 / 3.0);
        let fmt_r = |r: Option<f64>| r.map_or("-".to_string(), |r| format!("{r:.2}"));
        let _ = writeln!(
            csv,
            "{scene},{set},{},{},{},{x:.6},,{m},{},{},{},{},{},{},{lat:.3},{}",
            f.datapath(),
            f.name(),
            f.bits(),
            latency(f),
            a_.as_ref()
                .map_or(String::new(), |a| a.ice40_lut4.to_string()),
            a_.as_ref()
                .map_or(String::new(), |a| a.xilinx_lut.to_string()),
            a_.as_ref()
                .map_or(String::new(), |a| a.xilinx_dsp.to_string()),
            lut.map_or(String::new(), |r| format!("{r:.4}")),
            xl.map_or(String::new(), |r| format!("{r:.4}")),
            third.map_or(String::new(), |t| t.to_string()),
        );
        let _ = writeln!(
            md,
            "| {scene} | {set} | {} | {} ({} bits) | {:+.2}% | {} ({}) | {} ({}) | {} ({lat:.2}) | {} |",
            f.datapath(),
            f.name(),
            f.bits(),
            100.0 * x,
            a_.as_ref().map_or("not synthesised".to_string(), |a| a.ice40_lut4.to_string()),
            fmt_r(lut),
            a_.as_ref().map_or("-".to_string(), |a| format!("{} + {}", a.xilinx_lut, a.xilinx_dsp)),
            fmt_r(xl),
            latency(f),
            third.map_or("- (run with --synth)".to_string(), |t| if t { "yes".into() } else { "no".into() }),
        );
    }
    let _ = writeln!(
        md,
        "\nVerilog of every fitted format and of fp32: {}/*.v",
        dir.display()
    );
    std::fs::write(dir.join("fit.csv"), &csv).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("fit.md"), &md).map_err(|e| e.to_string())?;
    Ok(md)
}

fn module(f: &Format) -> String {
    match f {
        Format::Fix(x) => rtl::export::slab_fix_module(x),
        Format::Float(x) => rtl::export::slab_float_module(x),
    }
}

fn latency(f: &Format) -> usize {
    match f {
        Format::Fix(_) => rtl::SLAB_FIX_LATENCY,
        Format::Float(_) => rtl::SLAB_FLOAT_LATENCY,
    }
}
