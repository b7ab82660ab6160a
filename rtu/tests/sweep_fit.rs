//! `rtu sweep` and `rtu fit` end to end on small runs: the CSV has a row per configuration with the
//! exact machine's figures beside it, a single-ray format never does less work than the exact tester,
//! the Pareto flags follow the area table given, the fit's formats meet the budget and their Verilog is
//! written; bad options and malformed scene files are errors that name what is wrong.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn rtu(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_rtu"))
        .args(args)
        .output()
        .expect("rtu runs")
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rtu-sweep-fit-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Rows of a CSV as header -> value maps.
fn rows(p: &Path) -> Vec<HashMap<String, String>> {
    let text = std::fs::read_to_string(p).unwrap();
    let mut lines = text.lines();
    let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            head.iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

const AREA_HEADER: &str =
    "module,latency,generic_cells,ice40_lut4,ice40_carry,ice40_ff,ice40_depth,xilinx_lut,xilinx_dsp\n";

#[test]
fn sweep_measures_every_configuration_and_marks_the_front() {
    let dir = tmp("sweep");
    // A made-up area table: b8's slab cheapest, fp16's dearest; no pair rows, so bundles have no cost.
    let area = dir.join("area.csv");
    std::fs::write(
        &area,
        format!(
            "{AREA_HEADER}slab_fix_g8_i12f8_t14f4,4,1,100,0,0,10,50,1\nslab_float_e5m10,9,1,1000,0,0,30,500,1\n"
        ),
    )
    .unwrap();
    // A made-up timing table with b8's slab tester only: every other configuration has no rays/s.
    let timing = dir.join("timing.csv");
    std::fs::write(
        &timing,
        "module,latency,device,lut4,ff,mult18,fmax_mhz,crit_from,crit_to,seed\nslab_fix_g8_i12f8_t14f4,4,D,400,1,6,80.0,a,b,1\n",
    )
    .unwrap();
    let out = dir.join("out");
    let o = rtu(&[
        "--out",
        out.to_str().unwrap(),
        "sweep",
        "--timing",
        timing.to_str().unwrap(),
        "--scenes",
        "soup",
        "--width",
        "8",
        "--height",
        "6",
        "--fixed",
        "b8",
        "--float",
        "fp16",
        "--k",
        "0,1",
        "--bundle",
        "1,4",
        "--area",
        area.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = rows(&out.join("sweep.csv"));
    assert_eq!(r.len(), 2 * 2 * 2, "one row per format, K and B");
    for row in &r {
        let num = |k: &str| row[k].parse::<f64>().unwrap();
        assert!(num("rays") > 48.0, "primary and secondary rays: {row:?}");
        if row["k"] == "0" {
            // No planes: a cull of a node whose box the ray hits would have been an error.
            assert_eq!(row["plane_culls"], "0", "{row:?}");
        }
        assert_eq!(row["mode"], "default");
        // What the interval costs is measured for single rays, and the planes' entry for K > 0.
        let measured = |k: &str| !row[k].is_empty();
        assert_eq!(measured("exact_interval_box_tests"), row["bundle"] == "1");
        assert_eq!(
            measured("slab_entry_box_tests"),
            row["bundle"] == "1" && row["k"] != "0"
        );
        if row["bundle"] == "1" {
            if row["k"] == "0" {
                // A conservative slab tester keeps every node the exact one keeps.
                assert!(
                    num("cycles_per_ray") >= num("exact_cycles_per_ray"),
                    "{row:?}"
                );
            }
            assert_eq!(row["pair_tests"], "0");
        } else {
            assert!(num("pair_tests") > 0.0, "{row:?}");
        }
    }
    let find = |f: &str, k: &str, b: &str| {
        r.iter()
            .find(|x| x["format"] == f && x["k"] == k && x["bundle"] == b)
            .unwrap()
    };
    // The cheapest point is always on both fronts; the dearest is on the accuracy front only if it is
    // at least as accurate; configurations without area are on neither.
    let b8 = find("b8", "0", "1");
    let fp16 = find("fp16", "0", "1");
    assert_eq!(b8["pareto_accuracy"], "true");
    assert_eq!(b8["pareto_speed"], "true");
    let acc = |x: &HashMap<String, String>| x["extra_cycles"].parse::<f64>().unwrap();
    assert_eq!(fp16["pareto_accuracy"] == "true", acc(fp16) < acc(b8));
    assert_eq!(find("b8", "1", "1")["pareto_accuracy"], "false");
    assert_eq!(find("b8", "1", "1")["ice40_lut4"], "");
    // Rays per second: the module's Fmax over tester cycles per ray, and per 1,000 of its LUT4s.
    let f = |x: &HashMap<String, String>, k: &str| x[k].parse::<f64>().unwrap();
    let rps = 80e6 / f(b8, "cycles_per_ray");
    assert!((f(b8, "rays_per_s") / rps - 1.0).abs() < 1e-3, "{b8:?}");
    assert!((f(b8, "rays_per_s_per_klut4") / (rps / 0.4) - 1.0).abs() < 1e-3);
    assert_eq!(b8["ecp5_fmax_mhz"], "80.0");
    assert_eq!(
        b8["pareto_rays_per_area"], "true",
        "the only timed point is its own front"
    );
    for (f, k, b) in [("fp16", "0", "1"), ("b8", "1", "1"), ("b8", "0", "4")] {
        assert_eq!(
            find(f, k, b)["rays_per_s"],
            "",
            "{f} K{k} B{b} has no timing row"
        );
    }
    let md = std::fs::read_to_string(out.join("sweep.md")).unwrap();
    assert!(md.contains("No post-route timing for") && md.contains("slab_float_e5m10"));
    assert!(md.contains("Traversal mode: default") && md.contains("What a loose interval costs"));
    // Closest hit (primary and bounce rays) skips nodes by entry.
    assert!(r.iter().any(|x| x["entry_skips"] != "0"), "{r:?}");
    for chart in [
        "sweep_soup_accuracy.svg",
        "sweep_soup_speed.svg",
        "sweep_soup_rays_per_area.svg",
    ] {
        let svg = std::fs::read_to_string(out.join(chart)).unwrap();
        assert!(svg.contains("b8 K0 B1"), "{chart} labels the front");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `rtu fit` on the mesh at 8x6 primary rays with the area table `area` and the options `extra`; it
/// must succeed.
fn fit_mesh(out: &Path, area: &Path, extra: &[&str]) {
    let mut args = vec![
        "--out",
        out.to_str().unwrap(),
        "fit",
        "--scenes",
        "mesh",
        "--width",
        "8",
        "--height",
        "6",
        "--area",
        area.to_str().unwrap(),
    ];
    args.extend(extra);
    let o = rtu(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn fit_meets_the_budget_and_writes_verilog() {
    let dir = tmp("fit");
    let out = dir.join("out");
    let area = dir.join("area.csv");
    std::fs::write(&area, AREA_HEADER).unwrap();
    let run = |budget: &str| {
        fit_mesh(&out, &area, &["--budget", budget]);
        rows(&out.join("fit").join("fit.csv"))
    };
    // Any budget: each fitted row is within it; a huge one takes the narrowest ladder formats.
    for (budget, want) in [
        ("1000", Some(("slab_fix_g6_", "slab_float_e5m3"))),
        ("0.5", None),
    ] {
        let r = run(budget);
        assert_eq!(
            r.len(),
            4 * 2,
            "primary, bounce, shadow, all x fixed, float"
        );
        for row in r.iter().filter(|x| !x["format"].is_empty()) {
            let x: f64 = row["extra_cycles"].parse().unwrap();
            assert!(
                x * 100.0 <= budget.parse::<f64>().unwrap() + 1e-9,
                "{row:?}"
            );
            assert!(out
                .join("fit")
                .join(format!("{}.v", row["module"]))
                .exists());
        }
        // "all" fits every set at once, so it is never narrower than any one set's fit.
        for dp in ["fixed", "float"] {
            let bits = |set: &str| -> u32 {
                let row = r
                    .iter()
                    .find(|x| x["datapath"] == dp && x["ray_set"] == set)
                    .unwrap();
                row["coord_bits"].parse().unwrap_or(u32::MAX)
            };
            for set in ["primary", "bounce", "shadow"] {
                assert!(bits("all") >= bits(set), "{dp} {set}: {r:?}");
            }
        }
        if let Some((fix, float)) = want {
            assert!(r
                .iter()
                .filter(|x| x["datapath"] == "fixed")
                .all(|x| x["module"].starts_with(fix)));
            assert!(r
                .iter()
                .filter(|x| x["datapath"] == "float")
                .all(|x| x["module"] == float));
        }
    }
    assert!(out.join("fit").join("slab_float_e8m23.v").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `rtu fit --clock`: on a made-up timing table, the pick is the narrowest format within the budget
/// whose shallowest depth reaches the clock; untimed and too slow formats are passed over and listed;
/// a clock nothing reaches fits nothing; the picked tester's Verilog is written.
#[test]
fn fit_at_a_clock_takes_the_narrowest_timed_format_and_shallowest_depth() {
    let dir = tmp("clock");
    let out = dir.join("out");
    let area = dir.join("area.csv");
    std::fs::write(&area, AREA_HEADER).unwrap();
    let timing = dir.join("timing.csv");
    std::fs::write(
        &timing,
        "module,latency,device,lut4,ff,mult18,fmax_mhz,crit_from,crit_to,seed\n\
         slab_fix_g8_i12f8_t14f4,4,x,400,400,6,90,a,b,1\n\
         slab_fix_g8_i12f8_t14f4_p6,6,x,450,700,6,95,a,b,1\n\
         slab_fix_g12_i16f11_t20f6,4,x,600,500,6,120,a,b,1\n\
         slab_float_e5m10,9,x,5000,2000,6,50,a,b,1\n\
         slab_float_e5m10_p13,13,x,6000,3400,6,120,a,b,1\n",
    )
    .unwrap();
    let run = |clock: &str| {
        let t = timing.to_str().unwrap();
        fit_mesh(
            &out,
            &area,
            &["--budget", "1000", "--timing", t, "--clock", clock],
        );
        rows(&out.join("fit").join("fit_clock.csv"))
    };
    for (clock, fixed, float) in [
        (
            "80",
            Some("slab_fix_g8_i12f8_t14f4"),
            Some("slab_float_e5m10_p13"),
        ),
        (
            "100",
            Some("slab_fix_g12_i16f11_t20f6"),
            Some("slab_float_e5m10_p13"),
        ),
        ("200", None, None),
    ] {
        let r = run(clock);
        assert_eq!(r.len(), 4 * 2, "{clock}: {r:?}");
        for row in &r {
            let want = if row["datapath"] == "fixed" {
                fixed
            } else {
                float
            };
            assert_eq!(row["module"], want.unwrap_or(""), "{clock}: {row:?}");
            let passed = &row["passed_over"];
            // The ladder's narrowest formats have no timing row: passed over, never picked.
            let narrowest = if row["datapath"] == "fixed" {
                "g6_i10f6_t12f4 untimed"
            } else {
                "e5m3 untimed"
            };
            assert!(passed.contains(narrowest), "{clock}: {row:?}");
            if let Some(m) = want {
                assert!(out.join("fit").join(format!("{m}.v")).exists(), "{m}");
                let x: f64 = row["extra_cycles"].parse().unwrap();
                assert!(x <= 10.0 + 1e-9, "{row:?}");
                let fmax: f64 = row["ecp5_fmax_mhz"].parse().unwrap();
                assert!(fmax >= clock.parse::<f64>().unwrap(), "{row:?}");
            }
            // A timed format that cannot reach the clock is named with its best Fmax.
            if row["datapath"] == "fixed" && clock != "80" {
                assert!(passed.contains("b8 95.0 MHz"), "{clock}: {row:?}");
            }
        }
    }
    let md = std::fs::read_to_string(out.join("fit").join("fit.md")).unwrap();
    assert!(md.contains("## At 200 MHz"), "{md}");
    assert!(
        md.contains("none within the budget reaches 200 MHz"),
        "{md}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_options_and_scene_files_are_named_errors() {
    let dir = tmp("bad");
    let obj = dir.join("broken.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 nan\nf 1 2 3\n").unwrap();
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    for (args, want) in [
        (
            vec!["sweep", "--scenes", obj.to_str().unwrap()],
            "broken.obj",
        ),
        (vec!["sweep", "--scenes", "attic"], "unknown scene `attic`"),
        (vec!["sweep", "--k", "9"], "--k 9"),
        (vec!["sweep", "--bundle", "3"], "--bundle 3"),
        (
            vec!["sweep", "--sets", "primary,sideways"],
            "ray set `sideways`",
        ),
        (vec!["sweep", "--offset", "nan"], "--offset"),
        (vec!["fit", "--budget=-1"], "--budget -1"),
        (vec!["sweep", "--mode", "nearest"], "--mode `nearest`"),
        (vec!["fit", "--mode", "first"], "--mode `first`"),
        (
            vec!["fit", "--clock", "0"],
            "--clock 0: a clock target in MHz > 0",
        ),
        (vec!["fit", "--clock", "nan"], "--clock NaN"),
        (
            vec![
                "fit",
                "--clock",
                "200",
                "--timing",
                "/nonexistent/timing.csv",
            ],
            "--timing /nonexistent/timing.csv: no such file",
        ),
        (
            vec!["sweep", "--area", "/nonexistent/area.csv"],
            "--area /nonexistent/area.csv",
        ),
        (
            vec!["sweep", "--timing", "/nonexistent/timing.csv"],
            "--timing /nonexistent/timing.csv: no such file",
        ),
    ] {
        let mut a = vec!["--out", o];
        a.extend(args.iter());
        let r = rtu(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(!r.status.success() && err.contains(want), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// In all-hits mode nothing skips by entry, so the interval is never used: the same culls with exact
/// intervals, or with the slab's interval, do exactly the format's own work.
#[test]
fn all_hits_mode_makes_the_interval_irrelevant() {
    let dir = tmp("all");
    let out = dir.join("out");
    let o = rtu(&[
        "--out",
        out.to_str().unwrap(),
        "sweep",
        "--scenes",
        "mesh",
        "--width",
        "8",
        "--height",
        "6",
        "--fixed",
        "b8",
        "--float",
        "",
        "--k",
        "0,1",
        "--bundle",
        "1",
        "--mode",
        "all",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = rows(&out.join("sweep.csv"));
    assert_eq!(r.len(), 2);
    for row in &r {
        assert_eq!(
            (row["mode"].as_str(), row["entry_skips"].as_str()),
            ("all", "0")
        );
        assert_eq!(row["exact_interval_box_tests"], row["box_tests"], "{row:?}");
        assert_eq!(row["exact_interval_tri_tests"], row["tri_tests"], "{row:?}");
        if row["k"] == "1" {
            assert_eq!(row["slab_entry_box_tests"], row["box_tests"], "{row:?}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `rtu trace` on an OBJ file: a row per ray of every set, the closest triangle's OBJ line, the hit equal
/// to brute force's in closest-hit mode and the verdict in any-hit mode, the tester's entry into the
/// hit's leaf no later than the hit; `cull-scenes` and `bundle-scenes` take the same file.
#[test]
fn trace_writes_per_ray_results_and_every_scene_command_takes_obj() {
    let dir = tmp("trace");
    // A unit quad (line 6, two triangles) in front of a larger triangle (line 10) behind it.
    let obj = dir.join("two.obj");
    std::fs::write(
        &obj,
        "# test\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nv -1 -1 -1\nv 2 -1 -1\nv 0.5 2 -1\nf 5 6 7\n",
    )
    .unwrap();
    let out = dir.join("out");
    let csv = dir.join("t.csv");
    let o = rtu(&[
        "--out",
        out.to_str().unwrap(),
        "trace",
        "--scene",
        obj.to_str().unwrap(),
        "--format",
        "b8",
        "--k",
        "1",
        "--width",
        "8",
        "--height",
        "6",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = rows(&csv);
    let primary: Vec<_> = r.iter().filter(|x| x["set"] == "primary").collect();
    assert_eq!(primary.len(), 48);
    assert!(r.iter().any(|x| x["set"] == "shadow" && x["mode"] == "any"));
    let mut lines = std::collections::HashSet::new();
    for row in &r {
        let num = |k: &str| row[k].parse::<f64>().unwrap();
        assert!(num("node_tests") >= 1.0, "{row:?}");
        if row["mode"] == "closest" {
            assert_eq!(
                (&row["tri"], &row["t"]),
                (&row["ref_tri"], &row["ref_t"]),
                "{row:?}"
            );
        } else {
            assert_eq!(row["hit"] == "true", !row["ref_tri"].is_empty(), "{row:?}");
        }
        if row["hit"] == "true" {
            assert!(
                num("t_entry") <= num("t") * (1.0 + 1e-12) + 1e-300,
                "{row:?}"
            );
            let line = &row["obj_line"];
            let tri: usize = row["tri"].parse().unwrap();
            assert_eq!(line, if tri < 2 { "6" } else { "10" }, "{row:?}");
            lines.insert(line.clone());
        }
    }
    assert!(lines.contains("6"), "the camera sees the quad: {lines:?}");
    for args in [
        vec![
            "cull-scenes",
            "--k",
            "1",
            "--fixed",
            "b12",
            "--float",
            "fp16",
        ],
        vec!["bundle-scenes"],
    ] {
        let mut a = vec!["--out", out.to_str().unwrap()];
        a.extend(args.iter());
        a.extend([
            "--scenes",
            obj.to_str().unwrap(),
            "--width",
            "8",
            "--height",
            "6",
        ]);
        let o = rtu(&a);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(
            o.status.success() && text.contains("two.obj"),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    for (args, want) in [
        (vec!["trace", "--format", "b7"], "--format `b7`"),
        (vec!["trace", "--scene", "attic"], "unknown scene `attic`"),
        (vec!["trace", "--bundle", "3"], "--bundle 3"),
        (
            vec!["cull-scenes", "--scenes", "/nonexistent.obj"],
            "/nonexistent.obj",
        ),
        (
            vec!["bundle-scenes", "--scenes", "attic"],
            "unknown scene `attic`",
        ),
    ] {
        let mut a = vec!["--out", out.to_str().unwrap()];
        a.extend(args.iter());
        let r = rtu(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(!r.status.success() && err.contains(want), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The main job on a triangle scene: its BVH's first 48 boxes and its camera's rays through every
/// preset's RTL, and the small sweep on the same scene.
#[test]
fn main_job_takes_a_triangle_scene() {
    let dir = tmp("main");
    let out = dir.join("out");
    let o = rtu(&[
        "--out",
        out.to_str().unwrap(),
        "scene",
        "--scene",
        "mesh",
        "--width",
        "8",
        "--height",
        "6",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("scene `mesh`: 48 boxes, 48 rays"), "{text}");
    let r = rows(&out.join("sweep").join("sweep.csv"));
    assert!(!r.is_empty() && r.iter().all(|x| x["scene"] == "mesh"));
    let bad = rtu(&["--out", out.to_str().unwrap(), "scene", "--scene", "attic"]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("unknown scene `attic`"));
    std::fs::remove_dir_all(&dir).unwrap();
}
