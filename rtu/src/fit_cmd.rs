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

use crate::sweep_cmd::{
    load_area, load_scene, read_area, run_set, tester, Area, Format, Prepared, RunCfg,
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
    let mut rows: Vec<Fitted> = vec![];
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
            // Per set: the first format within the budget.
            for &i in &live {
                let mut fit = None;
                for f in ladder {
                    if let Some((x, st)) = s.extra(i, f)? {
                        if x <= budget {
                            fit = Some((*f, x, st, s.exact[i]));
                            break;
                        }
                    }
                }
                rows.push(Fitted {
                    scene: name.to_string(),
                    set: p.sets[i].0.to_string(),
                    datapath: dp,
                    fit,
                });
            }
            // All sets at once: the first format within the budget on every one (its extra is the
            // largest of the sets'; the stats are pooled).
            let mut fit = None;
            'ladder: for f in ladder {
                let (mut worst, mut pooled, mut pooled_exact) = (
                    f64::NEG_INFINITY,
                    SceneStats::default(),
                    SceneStats::default(),
                );
                for &i in &live {
                    match s.extra(i, f)? {
                        Some((x, st)) if x <= budget => {
                            worst = worst.max(x);
                            pooled.add(&st);
                            pooled_exact.add(&s.exact[i]);
                        }
                        _ => continue 'ladder,
                    }
                }
                if !live.is_empty() {
                    fit = Some((*f, worst, pooled, pooled_exact));
                }
                break;
            }
            rows.push(Fitted {
                scene: name.to_string(),
                set: "all".into(),
                datapath: dp,
                fit,
            });
        }
        eprintln!("{name}: {} ladder runs", s.cache.len());
    }
    // Export (and with --synth synthesise) every fitted format and fp32.
    let fp32 = Format::Float(FloatFormat::FP32);
    let mut to_export = vec![fp32];
    for r in &rows {
        if let Some((f, ..)) = &r.fit {
            if !to_export.iter().any(|x| x.name() == f.name()) {
                to_export.push(*f);
            }
        }
    }
    let mut new_rows = String::new();
    for f in &to_export {
        let m = module(f);
        let v = match f {
            Format::Fix(x) => rtl::export::slab_fix_verilog_ladder(x)?,
            Format::Float(x) => rtl::export::slab_float_verilog_ladder(x)?,
        };
        let path = dir.join(format!("{m}.v"));
        crate::out_file::write_file(&path, v)?;
        if a.synth && !area.contains_key(&m) {
            eprintln!("synthesising {m} ...");
            let row = crate::synth::synth(&path, &m, latency(f), &dir.join("synth"))?;
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
    let (csv, md) = render(a, &rows, &empty, &area, &fp32);
    crate::out_file::write_file(&dir.join("fit.csv"), &csv)?;
    crate::out_file::write_file(&dir.join("fit.md"), &md)?;
    Ok(md)
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
    let base = area.get(&module(fp32)).cloned();
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
        let m = module(f);
        let ar = area.get(&m).cloned();
        let ratio = |g: &dyn Fn(&Area) -> f64| match (&ar, &base) {
            (Some(a), Some(b)) => Some(g(a) / g(b)),
            _ => None,
        };
        let lut = ratio(&|a| a.ice40_lut4 as f64);
        let xl = ratio(&|a| a.xilinx_lut as f64);
        let lat = latency(f) as f64 / latency(fp32) as f64;
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
            latency(f),
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
            latency(f),
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
