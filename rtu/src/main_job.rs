//! The main job: every ray of the default scene against every box, through the RTL slab tester of each
//! preset width, judged against the exact oracle; a summary table, Verilog, a VCD and a report.

use crate::scene::Scene;
use golden::exact::{slab_exact, ExactHit, Ext};
use golden::format::fixed::{FixFormat, GridMap};
use golden::slab::float::{quantize_box, quantize_ray};
use golden::slab::reference::slab_ref;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;
use tb::engine::{run_fix, run_float, Engine};
use tb::xsim::TesterCtx;

/// One row of the summary.
pub struct Row {
    /// Format name.
    pub name: String,
    /// Grid cell in world units (fixed point), or `-`.
    pub cell: String,
    pub tests: u64,
    /// Tests also run through the rust-hdl block (and compared with the model).
    pub rtl_tests: u64,
    pub exact_hits: u64,
    pub hits: u64,
    pub false_hits: u64,
    pub violations: u64,
    pub rtl_model_mismatches: u64,
    pub mean_slack: f64,
    pub rtl_rate: f64,
}

impl Row {
    pub fn false_hit_rate(&self) -> f64 {
        self.false_hits as f64 / (self.tests - self.exact_hits).max(1) as f64
    }
}

fn exact_all(scene: &Scene) -> Vec<ExactHit> {
    let nb = scene.boxes.len();
    let n = scene.rays.len() * nb;
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    let chunk = n.div_ceil(threads);
    let mut out = Vec::with_capacity(n);
    std::thread::scope(|s| {
        let hs: Vec<_> = (0..threads)
            .map(|t| {
                s.spawn(move || {
                    (t * chunk..((t + 1) * chunk).min(n))
                        .map(|i| slab_exact(&scene.rays[i / nb], &scene.boxes[i % nb]))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        for h in hs {
            out.extend(h.join().expect("exact thread"));
        }
    });
    out
}

fn world(e: &Ext) -> f64 {
    e.to_f64()
}

/// Tests of each float format also run through its rust-hdl block in the main job (it simulates at about
/// 10k tests/s; the bit-accurate model runs them all).
const FLOAT_RTL_TESTS: usize = 4096;

type Sink<'a, O> = &'a mut dyn FnMut(usize, O) -> Result<(), String>;

/// One row: every ray-box test on the model, the first `rtl_n` also on the RTL (through `run_rtl`), all
/// judged against the exact oracle.
#[allow(clippy::too_many_arguments)]
fn measure<C: TesterCtx>(
    name: String,
    cell: String,
    ctx: C,
    rays: &[C::Ray],
    boxes: &[C::Box],
    exact: &[ExactHit],
    rtl_n: usize,
    run_rtl: impl FnOnce(
        std::vec::IntoIter<(usize, C::Ray, C::Box)>,
        Sink<C::Out>,
    ) -> Result<(), String>,
) -> Result<Row, String> {
    let nb = boxes.len();
    let n = rays.len() * nb;
    let model: Vec<C::Out> = (0..n)
        .map(|i| ctx.model(&rays[i / nb], &boxes[i % nb]))
        .collect();
    let tests: Vec<_> = (0..rtl_n)
        .map(|i| (i, rays[i / nb], boxes[i % nb]))
        .collect();
    let mut mismatches = 0u64;
    let mut rtl_hits = 0u64;
    let t = Instant::now();
    run_rtl(tests.into_iter(), &mut |i, o| {
        mismatches += u64::from(o != model[i]);
        rtl_hits += 1;
        Ok(())
    })?;
    if rtl_hits != rtl_n as u64 {
        return Err(format!(
            "{name}: the RTL returned {rtl_hits} of {rtl_n} results"
        ));
    }
    let mut row = Row {
        name,
        cell,
        tests: n as u64,
        rtl_tests: rtl_n as u64,
        exact_hits: exact.iter().filter(|e| e.hit).count() as u64,
        hits: 0,
        false_hits: 0,
        violations: 0,
        rtl_model_mismatches: mismatches,
        mean_slack: 0.0,
        rtl_rate: rtl_n as f64 / t.elapsed().as_secs_f64(),
    };
    let (mut slack_sum, mut slack_n) = (0.0, 0u64);
    let mut st = tb::campaign::ConservativeStats::default();
    for i in 0..n {
        let (r, o) = (&rays[i / nb], &model[i]);
        let (hit, en, ex) = ctx.world(r, o);
        row.hits += hit as u64;
        st.record(hit, ctx.judge(r, o, &exact[i]), |why| {
            format!("ray {} box {}: {why}", i / nb, i % nb)
        });
        if exact[i].hit && hit {
            let s = (world(&exact[i].entry) - en) + (ex - world(&exact[i].exit));
            if s.is_finite() {
                slack_sum += s;
                slack_n += 1;
            }
        }
    }
    // The row counts every violation; the first ten are printed, as the campaign reports them.
    (row.false_hits, row.violations) = (st.false_hits, st.violation_count);
    for v in &st.violations {
        eprintln!("VIOLATION {}: {v}", row.name);
    }
    row.mean_slack = slack_sum / slack_n.max(1) as f64;
    Ok(row)
}

/// Runs the main job on `scene`, writing into `out`. Returns the rows and the report text.
pub fn run(scene: &Scene, out: &Path) -> Result<(Vec<Row>, String), String> {
    let nb = scene.boxes.len();
    let n = scene.rays.len() * nb;
    println!(
        "scene `{}`: {} boxes, {} rays ({}x{}), {} ray-box tests per format",
        scene.name,
        nb,
        scene.rays.len(),
        scene.width,
        scene.height,
        n
    );
    let t0 = Instant::now();
    let exact = exact_all(scene);
    let exact_hits = exact.iter().filter(|e| e.hit).count() as u64;
    let f64_false_misses = (0..n)
        .filter(|&i| exact[i].hit && !slab_ref(&scene.rays[i / nb], &scene.boxes[i % nb]).hit)
        .count();
    println!(
        "exact oracle: {exact_hits} hits in {:.1} s",
        t0.elapsed().as_secs_f64()
    );

    let (lo, hi) = scene.bounds();
    let mut rows = vec![];
    let all = |_: &Scene| n;
    for fmt in FixFormat::presets() {
        let map = GridMap::for_bounds(fmt, lo, hi).map_err(|e| e.to_string())?;
        let rays: Vec<_> = scene
            .rays
            .iter()
            .map(|r| map.quantize_ray(r))
            .collect::<Result<_, _>>()
            .map_err(|e| e.to_string())?;
        let boxes: Vec<_> = scene
            .boxes
            .iter()
            .map(|b| map.quantize_box(b))
            .collect::<Result<_, _>>()
            .map_err(|e| e.to_string())?;
        let cell = golden::format::fixed::ldexp(1.0, map.k).to_string();
        rows.push(measure(
            fmt.name(),
            cell,
            fmt,
            &rays,
            &boxes,
            &exact,
            all(scene),
            |tests, sink| {
                run_fix(Engine::Rtl, fmt, tests, Path::new(""), None, |i, _, o| {
                    sink(i, o)
                })
                .map(|_| ())
            },
        )?);
    }
    for f in rtl::SLAB_FLOAT_FORMATS {
        let rays: Vec<_> = scene
            .rays
            .iter()
            .map(|r| quantize_ray(&f, r))
            .collect::<Result<_, _>>()
            .map_err(|e| e.to_string())?;
        let boxes: Vec<_> = scene
            .boxes
            .iter()
            .map(|b| quantize_box(&f, b))
            .collect::<Result<_, _>>()
            .map_err(|e| e.to_string())?;
        rows.push(measure(
            f.name(),
            "-".into(),
            f,
            &rays,
            &boxes,
            &exact,
            FLOAT_RTL_TESTS.min(n),
            |tests, sink| {
                run_float(Engine::Rtl, f, tests, Path::new(""), None, |i, _, o| {
                    sink(i, o)
                })
                .map(|_| ())
            },
        )?);
    }

    // Verilog and a waveform of the first tests through the b12 tester.
    let vdir = out.join("verilog");
    let written: Vec<_> = crate::export_cmd::export(&vdir, None)?
        .into_iter()
        .filter(|p| p.extension().is_some_and(|x| x == "v"))
        .collect();
    let vcd = out.join("vcd").join(format!("{}_b12.vcd", scene.name));
    {
        // A GTKWave save file beside the waveform: ports and stage registers grouped by stage.
        let m = rtl::names::slab_fix_module(&FixFormat::b12());
        let v = std::fs::read_to_string(vdir.join(format!("{m}.v"))).map_err(|e| e.to_string())?;
        let name = vcd
            .file_name()
            .expect("a file")
            .to_string_lossy()
            .into_owned();
        std::fs::create_dir_all(out.join("vcd")).map_err(|e| e.to_string())?;
        crate::out_file::write_file(
            &vcd.with_extension("gtkw"),
            tb::ip::package::gtkw_save(&m, &v, &name, "uut")?,
        )?;
    }
    {
        let fmt = FixFormat::b12();
        let map = GridMap::for_bounds(fmt, lo, hi).map_err(|e| e.to_string())?;
        let mut dut = tb::rtl_sim::SlabFixRtl::<rtl::SlabFixB12>::with_vcd(&fmt, &vcd)
            .map_err(|e| format!("{}: {e}", vcd.display()))?;
        let first: Vec<_> = (0..64.min(n))
            .map(|i| {
                Some((
                    map.quantize_ray(&scene.rays[i / nb]).unwrap(),
                    map.quantize_box(&scene.boxes[i % nb]).unwrap(),
                ))
            })
            .collect();
        tb::dut::run_checked(&mut dut, first, |v| {
            golden::slab::fix::slab_fix(&fmt, &v.0, &v.1)
        })
        .map_err(|e| e.to_string())?;
    }

    let mut report = String::new();
    let _ = writeln!(report, "# rtu main job: scene `{}`\n", scene.name);
    let _ = writeln!(
        report,
        "{} boxes x {} primary rays ({}x{}) = {} ray-box tests per format. Fixed-point formats: every test through\n\
         the rust-hdl `SlabFix` simulation; float formats: every test on the bit-accurate model and the first {}\n\
         through the rust-hdl `SlabFloat` simulation; RTL results checked bit for bit against the model, and\n\
         every result judged against the exact rational oracle. The f64 round-to-nearest reference misses\n\
         {f64_false_misses} true hits on this scene.\n",
        nb,
        scene.rays.len(),
        scene.width,
        scene.height,
        n,
        FLOAT_RTL_TESTS.min(n)
    );
    let _ = writeln!(report, "{}", table(&rows));
    let _ = writeln!(report, "- false-hit rate: false hits per true miss; slack: mean (exact entry - entry) + (exit - exact exit) over true hits, world units;");
    let _ = writeln!(report, "- RTL tests/s: the rust-hdl simulation on this machine, one run (not a benchmark: see `rtu bench`).\n");
    let _ = writeln!(report, "Files:");
    for p in &written {
        let _ = writeln!(report, "- Verilog: `{}`", p.display());
    }
    let _ = writeln!(
        report,
        "- waveform of the first 64 tests (b12): `{}`",
        vcd.display()
    );
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join("report.md"), &report)?;
    let mut csv = String::from("format,cell,tests,rtl_tests,exact_hits,hits,false_hits,false_hit_rate,violations,rtl_model_mismatches,mean_slack,rtl_tests_per_s\n");
    for r in &rows {
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{:.6},{},{},{:.6},{:.0}",
            r.name,
            r.cell,
            r.tests,
            r.rtl_tests,
            r.exact_hits,
            r.hits,
            r.false_hits,
            r.false_hit_rate(),
            r.violations,
            r.rtl_model_mismatches,
            r.mean_slack,
            r.rtl_rate
        );
    }
    crate::out_file::write_file(&out.join("summary.csv"), csv)?;
    Ok((rows, report))
}

/// The summary as a Markdown table.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| format | grid cell | tests | exact hits | hits | false hits | false-hit rate | false misses / bad intervals | RTL = model (tests) | mean slack | RTL tests/s |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {:.2}% | {} | {} | {:.4} | {:.0} |",
            r.name,
            r.cell,
            r.tests,
            r.exact_hits,
            r.hits,
            r.false_hits,
            100.0 * r.false_hit_rate(),
            r.violations,
            if r.rtl_model_mismatches == 0 {
                format!("yes ({})", r.rtl_tests)
            } else {
                format!("NO ({})", r.rtl_model_mismatches)
            },
            r.mean_slack,
            r.rtl_rate
        );
    }
    s
}

/// Options of the main job (`rtu`, `rtu scene`).
#[derive(clap::Args, Clone, Debug)]
pub struct Args {
    /// Image width in rays.
    #[arg(long, default_value_t = 48)]
    pub width: usize,
    /// Image height in rays.
    #[arg(long, default_value_t = 32)]
    pub height: usize,
    /// Instead of the default room of boxes, a triangle scene: a built-in name (room, grass, mesh,
    /// soup) or an OBJ file; the boxes are its BVH's first 48 nodes, the rays its camera's, and the
    /// small sweep runs on it.
    #[arg(long)]
    pub scene: Option<String>,
}

impl Default for Args {
    /// What `rtu` with no command runs: the default room, 48 x 32 rays.
    fn default() -> Self {
        Args {
            width: 48,
            height: 32,
            scene: None,
        }
    }
}

/// The front door (`rtu`, `rtu scene`): the scene through every preset slab tester ([`run`]), its
/// summary printed and its files written under `out`; an error when a result violates conservativeness
/// or the RTL differs from the model; then the small sweep on the same scene (`out/sweep`).
pub fn front_door(a: &Args, out: &Path) -> Result<(), String> {
    let scene = match &a.scene {
        None => crate::scene::box_room(a.width, a.height),
        Some(name) => crate::sweep_cmd::load_scene(name, 1)
            .and_then(|ts| crate::scene::from_tri(&ts, a.width, a.height, 48))?,
    };
    let (rows, _) = run(&scene, out)?;
    println!("\n{}", table(&rows));
    println!(
        "wrote {}/report.md, {}/summary.csv, {}/verilog/, {}/vcd/",
        out.display(),
        out.display(),
        out.display(),
        out.display()
    );
    if rows
        .iter()
        .any(|r| r.violations > 0 || r.rtl_model_mismatches > 0)
    {
        return Err("conservativeness violations or RTL/model mismatches: see above".to_string());
    }
    // The small version of the sweep: speed against accuracy on the triangle room.
    let mut sweep = crate::sweep_cmd::Args::small();
    if let Some(name) = &a.scene {
        sweep.scenes = name.clone();
    }
    let dir = out.join("sweep");
    let t = crate::sweep_cmd::run(&sweep, &dir)?;
    println!(
        "\nSpeed against accuracy (small sweep: {}):\n\n{t}",
        sweep.describe()
    );
    println!(
        "wrote {}/sweep.csv, sweep.md and the charts sweep_*.svg",
        dir.display()
    );
    Ok(())
}
