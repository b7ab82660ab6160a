//! The main job: every ray of the default scene against every box, through the RTL slab tester of each
//! preset width, judged against the exact oracle; a summary table, Verilog, a VCD and a report.

use crate::scene::Scene;
use golden::check::{judge_fix, Verdict};
use golden::exact::{slab_exact, ExactHit, Ext};
use golden::fixed::{FixFormat, GridMap};
use golden::slab_fix::SlabFixOut;
use golden::slab_ref::slab_ref;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;
use tb::engine::{run_fix, Engine};

/// One row of the summary.
pub struct Row {
    pub fmt: FixFormat,
    pub cell: f64,
    pub tests: u64,
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
        let tests = || {
            let (rays, boxes) = (rays.clone(), boxes.clone());
            (0..n).map(move |i| (i, rays[i / nb], boxes[i % nb]))
        };
        let mut model = vec![SlabFixOut::default(); n];
        run_fix(
            Engine::Model,
            fmt,
            tests(),
            Path::new(""),
            None,
            |i, _, o| {
                model[i] = o;
                Ok(())
            },
        )?;
        let t = Instant::now();
        let mut rtl = vec![SlabFixOut::default(); n];
        run_fix(Engine::Rtl, fmt, tests(), Path::new(""), None, |i, _, o| {
            rtl[i] = o;
            Ok(())
        })?;
        let rtl_rate = n as f64 / t.elapsed().as_secs_f64();
        let mut row = Row {
            fmt,
            cell: golden::fixed::ldexp(1.0, map.k),
            tests: n as u64,
            exact_hits,
            hits: 0,
            false_hits: 0,
            violations: 0,
            rtl_model_mismatches: (0..n).filter(|&i| rtl[i] != model[i]).count() as u64,
            mean_slack: 0.0,
            rtl_rate,
        };
        let mut slack_sum = 0.0;
        let mut slack_n = 0u64;
        for i in 0..n {
            let fr = &rays[i / nb];
            let o = &rtl[i];
            row.hits += o.hit as u64;
            match judge_fix(&fmt, fr, o, &exact[i]) {
                Verdict::Agree => {}
                Verdict::FalseHit => row.false_hits += 1,
                Verdict::Violation(why) => {
                    row.violations += 1;
                    eprintln!(
                        "VIOLATION {}: ray {} box {}: {why}",
                        fmt.name(),
                        i / nb,
                        i % nb
                    );
                }
            }
            if exact[i].hit && o.hit {
                let (en, ex) = (
                    fr.t_world_f64(&fmt, o.t_entry),
                    fr.t_world_f64(&fmt, o.t_exit),
                );
                let s = (world(&exact[i].entry) - en) + (ex - world(&exact[i].exit));
                if s.is_finite() {
                    slack_sum += s;
                    slack_n += 1;
                }
            }
        }
        row.mean_slack = slack_sum / slack_n.max(1) as f64;
        rows.push(row);
    }

    // Verilog and a waveform of the first tests through the b12 tester.
    let vdir = out.join("verilog");
    let written = rtl::export::export_all(&vdir).map_err(|e| format!("{}: {e}", vdir.display()))?;
    let vcd = out.join("vcd").join(format!("{}_b12.vcd", scene.name));
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
            golden::slab_fix::slab_fix(&fmt, &v.0, &v.1)
        })
        .map_err(|e| e.to_string())?;
    }

    let mut report = String::new();
    let _ = writeln!(report, "# rtu main job: scene `{}`\n", scene.name);
    let _ = writeln!(
        report,
        "{} boxes x {} primary rays ({}x{}) = {} ray-box tests per format, each through the rust-hdl\n\
         `SlabFix` simulation, checked bit for bit against the bit-accurate model and judged against the exact\n\
         rational oracle. The f64 round-to-nearest reference misses {f64_false_misses} true hits on this scene.\n",
        nb,
        scene.rays.len(),
        scene.width,
        scene.height,
        n
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
    std::fs::write(out.join("report.md"), &report).map_err(|e| e.to_string())?;
    let mut csv = String::from("format,cell,tests,exact_hits,hits,false_hits,false_hit_rate,violations,rtl_model_mismatches,mean_slack,rtl_tests_per_s\n");
    for r in &rows {
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{:.6},{},{},{:.6},{:.0}",
            r.fmt.name(),
            r.cell,
            r.tests,
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
    std::fs::write(out.join("summary.csv"), csv).map_err(|e| e.to_string())?;
    Ok((rows, report))
}

/// The summary as a Markdown table.
pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| format | grid cell | tests | exact hits | hits | false hits | false-hit rate | false misses / bad intervals | RTL = model | mean slack | RTL tests/s |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {:.2}% | {} | {} | {:.4} | {:.0} |",
            r.fmt.name(),
            r.cell,
            r.tests,
            r.exact_hits,
            r.hits,
            r.false_hits,
            100.0 * r.false_hit_rate(),
            r.violations,
            if r.rtl_model_mismatches == 0 {
                "yes".to_string()
            } else {
                format!("NO ({})", r.rtl_model_mismatches)
            },
            r.mean_slack,
            r.rtl_rate
        );
    }
    s
}
