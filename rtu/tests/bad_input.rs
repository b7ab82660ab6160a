//! Bad input and extreme values through the `rtu` command, black-box: each malformed file is an error
//! naming the file, the line and the field, with nothing on standard output; a named output file is
//! complete or absent; intervals whose exact ends lie beyond the f64 range come back rounded outward in
//! every fixed and float format, with and without cull planes.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rtu(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rtu"))
        .args(args)
        .output()
        .expect("rtu runs")
}

struct Dir(PathBuf);

impl Dir {
    fn new(name: &str) -> Dir {
        let d = std::env::temp_dir().join(format!("rtu-bad-input-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        Dir(d)
    }
    fn file(&self, name: &str, text: impl AsRef<[u8]>) -> String {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    }
    fn entries(&self) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

const BOX: &str = r#""box_min":[-1,-1,-1],"box_max":[1,1,1]"#;
const HEADER: &str = "tag,ox,oy,oz,dx,dy,dz,t_min,t_max,min_x,min_y,min_z,max_x,max_y,max_z";
const ROW: &str = "1,0,0,-5,0,0,1,0,inf,-1,-1,-1,1,1,1";

/// The inputs the black-box testing found silently misread, and the other malformed inputs: each must
/// fail, name the file and line (`file:line:`) and the field, and print nothing on stdout.
#[test]
fn malformed_inputs_are_errors_naming_file_line_and_field() {
    let d = Dir::new("malformed");
    let ray = r#""origin":[0,0,-5],"dir":[0,0,1]"#;
    let cases: Vec<(&str, String, Vec<&str>, &str)> = vec![
        (
            "typo.jsonl",
            format!("{{{ray},\"tmax\":2,{BOX}}}\n"),
            vec![],
            ":1: field `tmax`: unknown field; did you mean `t_max`?",
        ),
        (
            "plane.jsonl",
            format!("{{{ray},\"plane\":[[1,0,0,0.5]],{BOX}}}\n"),
            vec!["--planes", "1"],
            ":1: field `plane`: unknown field; did you mean `planes`?",
        ),
        (
            "extra.csv",
            format!("{HEADER},tmax\n{ROW},2\n"),
            vec![],
            ":1: field `tmax`: unknown field",
        ),
        (
            "twice.csv",
            format!("{HEADER},t_max\n{ROW},2\n"),
            vec![],
            ":1: field `t_max`: column named twice",
        ),
        (
            "under.jsonl",
            format!("{{\"origin\":[0,0,-5],\"dir\":[0,1e-400,1],{BOX}}}\n"),
            vec![],
            ":1: field `dir`: `1e-400` underflows f64",
        ),
        (
            "over.jsonl",
            format!("{{{ray},\"t_max\":1e400,{BOX}}}\n"),
            vec![],
            ":1: field `t_max`: `1e400` overflows f64",
        ),
        (
            "under.csv",
            format!(
                "{HEADER}\n{}\n",
                ROW.replace("0,0,1,0,inf", "0,1e-400,1,0,inf")
            ),
            vec![],
            ":2: field `dy`: `1e-400` underflows f64",
        ),
        (
            "short.csv",
            format!("{HEADER}\n{ROW}\n2,0,0,-5,0,0,1\n"),
            vec![],
            ":3: field `(row)`: 7 cells, but the header has 15",
        ),
        (
            "empty.csv",
            String::new(),
            vec![],
            ":1: field `ox`: column missing from the header",
        ),
        (
            "nofit.jsonl",
            format!("{{{ray},{BOX}}}\n{{{ray},\"box_min\":[-1,-1,-1],\"box_max\":[9,1,1]}}\n"),
            vec!["--format", "b8", "--bounds=-2,-2,-6,2,2,2"],
            ":2: vector with tag 1:",
        ),
        (
            "bundle.jsonl",
            format!("{{\"rays\":[{{{ray}}}],\"o_lo\":[0,0,-5],{BOX}}}\n"),
            vec!["--bundles"],
            ":1: field `o_hi`: missing: a bundle's bounds are o_lo, o_hi, d_lo and d_hi",
        ),
        (
            "bundle_under.jsonl",
            format!("{{\"rays\":[{{\"origin\":[0,0,-5],\"dir\":[0,-1e-999,1]}}],{BOX}}}\n"),
            vec!["--bundles"],
            ":1: field `dir`: `-1e-999` underflows",
        ),
    ];
    for (name, text, extra, want) in cases {
        let path = d.file(name, &text);
        let mut args = vec!["run", path.as_str()];
        args.extend(extra);
        let o = rtu(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{name} accepted: {err}");
        assert!(
            err.contains(&format!("{path}{want}")),
            "{name}: want `{path}{want}` in: {err}"
        );
        // Standard output streams: only an error after the first vector leaves results before it.
        let first_ok = name == "nofit.jsonl";
        assert_eq!(
            o.stdout.is_empty(),
            !first_ok,
            "{name}: stdout {:?}",
            String::from_utf8_lossy(&o.stdout)
        );
    }
}

/// A byte-order mark is read past by every reader: the same results as without it.
#[test]
fn byte_order_marks_are_accepted_by_every_reader() {
    let d = Dir::new("bom");
    let line = format!("{{\"origin\":[0,0,-5],\"dir\":[0,0,1],{BOX}}}\n");
    let bundle = format!("{{\"rays\":[{{\"origin\":[0,0,-5],\"dir\":[0,0.1,1]}}],{BOX}}}\n");
    for (name, text, extra) in [
        ("v.jsonl", line, vec![]),
        ("v.csv", format!("{HEADER}\n{ROW}\n"), vec![]),
        ("b.jsonl", bundle, vec!["--bundles"]),
    ] {
        let plain = d.file(name, &text);
        let bom = d.file(&format!("bom_{name}"), format!("\u{feff}{text}"));
        let run = |p: &str| {
            let mut args = vec!["run", p];
            args.extend(&extra);
            let o = rtu(&args);
            assert!(
                o.status.success(),
                "{p}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            o.stdout
        };
        let (a, b) = (run(&plain), run(&bom));
        assert!(!a.is_empty());
        assert_eq!(a, b, "{name}");
    }
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let mut outs = vec![];
    for (name, text) in [
        ("t.obj", obj.to_string()),
        ("bom_t.obj", format!("\u{feff}{obj}")),
    ] {
        let p = d.file(name, text);
        let out = d.0.join(format!("sweep_{name}"));
        let o = rtu(&[
            "sweep",
            "--scenes",
            &p,
            "--fixed",
            "b16",
            "--float",
            "",
            "--k",
            "0",
            "--bundle",
            "1",
            "--sets",
            "primary",
            "--width",
            "4",
            "--height",
            "4",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        outs.push(
            std::fs::read_to_string(out.join("sweep.csv"))
                .unwrap()
                .replace("bom_", ""),
        );
    }
    assert_eq!(outs[0], outs[1]);
}

/// A named output is complete or absent: an error part-way (a vector that does not fit, a line that does
/// not parse) leaves an existing file as it was and no temporary file behind; a device is written in
/// place, and a write error names it.
#[test]
fn outputs_are_complete_or_absent() {
    let d = Dir::new("output");
    let ok = format!("{{\"origin\":[0,0,-5],\"dir\":[0,0,1],{BOX}}}\n");
    let nofit = format!("{ok}{ok}{{\"origin\":[0,0,-5],\"dir\":[0,0,1],\"box_min\":[-1,-1,-1],\"box_max\":[9,1,1]}}\n");
    let broken = format!("{ok}{ok}{{\"origin\":[0,0,-5]\n");
    let out = d.0.join("out.jsonl");
    let outs = out.to_str().unwrap();
    for (name, text, fmt) in [
        ("nofit.jsonl", nofit, "b8"),
        ("broken.jsonl", broken, "b16"),
        ("broken_f.jsonl", format!("{ok}{ok}x\n"), "fp16"),
    ] {
        let p = d.file(name, text);
        let run = || {
            rtu(&[
                "run",
                &p,
                "--format",
                fmt,
                "--bounds=-2,-2,-6,2,2,2",
                "-o",
                outs,
            ])
        };
        std::fs::write(&out, "previous results\n").unwrap();
        let o = run();
        assert!(!o.status.success(), "{name}");
        assert_eq!(
            std::fs::read_to_string(&out).unwrap(),
            "previous results\n",
            "{name}"
        );
        std::fs::remove_file(&out).unwrap();
        let o = run();
        assert!(!o.status.success(), "{name}");
        assert!(!out.exists(), "{name}: a partial output was left");
    }
    assert_eq!(
        d.entries(),
        ["broken.jsonl", "broken_f.jsonl", "nofit.jsonl"],
        "no temporary files"
    );
    let p = d.file("ok.csv", format!("{HEADER}\n{ROW}\n{ROW}\n"));
    let o = rtu(&["run", &p, "-o", d.0.join("r.csv").to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = std::fs::read_to_string(d.0.join("r.csv")).unwrap();
    assert_eq!(r.lines().count(), 3, "{r}");
    assert!(
        r.starts_with("tag,hit,t_entry,t_exit\n1,1,4.0,6.0\n"),
        "{r}"
    );
    if Path::new("/dev/full").exists() {
        let many: String = (0..5000).map(|_| ok.as_str()).collect();
        let p = d.file("many.jsonl", many);
        let o = rtu(&["run", &p, "--format", "fp32", "-o", "/dev/full"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains("/dev/full: cannot write"),
            "{err}"
        );
    }
}

/// Regression (black-box test): `origin (0, 2, 0)`, `dir (0, -5e-324, 0)`, box `[0, 1]^3` has the exact
/// interval `[2^1074, 2^1075]`, beyond the largest f64; b16 answered `t_entry = inf`, above the exact
/// entry. Its mirror images on every axis and sign, and with `t_min = -inf` the interval
/// `[-2^1075, -2^1074]`, in every fixed and float preset, on the slab tester and with a cull plane: the
/// answer is a hit, the entry at most the exact entry (so never `+inf` for the first, and `-inf` for the
/// second, as no finite f64 is below `-2^1075`), the exit at least the exact exit (`+inf`, and never
/// `-inf`).
#[test]
fn intervals_beyond_the_f64_range_round_outward_in_every_format() {
    let d = Dir::new("huge");
    let mut text = String::new();
    let mut expect = vec![];
    for axis in 0..3 {
        for (o, dir, t_min, positive) in [
            (2.0, "-5e-324", "0", true),
            (-1.0, "5e-324", "0", true),
            (2.0, "5e-324", "\"-inf\"", false),
            (-1.0, "-5e-324", "\"-inf\"", false),
        ] {
            let mut origin = ["0".to_string(), "0".into(), "0".into()];
            let mut d3 = ["0", "0", "0"];
            origin[axis] = format!("{o:?}");
            d3[axis] = dir;
            text += &format!(
                "{{\"tag\":{},\"origin\":[{}],\"dir\":[{}],\"t_min\":{t_min},\"box_min\":[0,0,0],\"box_max\":[1,1,1],\"planes\":[[1,1,1,100]]}}\n",
                expect.len(),
                origin.join(","),
                d3.join(",")
            );
            expect.push(positive);
        }
    }
    let with_planes = d.file("huge_planes.jsonl", &text);
    let without = d.file("huge.jsonl", text.replace(r#","planes":[[1,1,1,100]]"#, ""));
    for fmt in ["b8", "b12", "b16", "fp32", "bf16", "fp16"] {
        for planes in ["0", "1"] {
            let mut args = vec!["run", "--format", fmt, "--bounds=-2,-2,-2,2,2,2"];
            if planes == "0" {
                args.push(&without);
            } else {
                args.extend(["--planes", planes, &with_planes]);
            }
            let o = rtu(&args);
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(o.status.success(), "{fmt} K={planes}: {err}");
            let lines: Vec<Value> = String::from_utf8_lossy(&o.stdout)
                .lines()
                .map(|l| serde_json::from_str(l).unwrap())
                .collect();
            assert_eq!(lines.len(), expect.len());
            for (r, &positive) in lines.iter().zip(&expect) {
                let t = |k: &str| match &r[k] {
                    Value::String(s) if s == "inf" => f64::INFINITY,
                    Value::String(s) if s == "-inf" => f64::NEG_INFINITY,
                    v => v.as_f64().unwrap(),
                };
                let (en, ex) = (t("t_entry"), t("t_exit"));
                assert_eq!(r["hit"], true, "{fmt} K={planes}: {r}");
                if positive {
                    assert!(
                        en < f64::INFINITY && ex == f64::INFINITY,
                        "{fmt} K={planes}: {r}"
                    );
                } else {
                    assert!(
                        en == f64::NEG_INFINITY && ex > f64::NEG_INFINITY,
                        "{fmt} K={planes}: {r}"
                    );
                }
            }
        }
    }
}

/// `rtu bundle-stream` refuses bundles the ray store cannot hold, formats it is not built over and
/// re-bounding rules it does not follow, naming the option, and writes nothing.
#[test]
fn bundle_stream_options_out_of_range_are_errors() {
    let d = Dir::new("bundle-stream");
    let out = d.0.display().to_string();
    for (args, want) in [
        (vec!["--tile", "5"], "--tile 5"),
        (vec!["--builder", "17:0.2"], "--builder 17:0.2"),
        (vec!["--builder", "16"], "--builder `16`"),
        (vec!["--format", "g10"], "built over b8, b12 and b16"),
        (vec!["--format", "b9"], "--format b9"),
        (vec!["--rebound", "world"], "--rebound `world`"),
    ] {
        let mut a = vec!["--out", &out, "bundle-stream", "--scenes", "room"];
        a.extend(&args);
        let o = rtu(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} must fail");
        assert!(err.contains(want), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}");
        assert!(d.entries().is_empty(), "{args:?}: {:?}", d.entries());
    }
}

/// The commands share one set of option names (`--fixed`/`--float` for format lists, `--k` for planes per
/// node, `--vectors` for counts); the older spellings still parse as aliases, and either way a bad value
/// is an error naming it.
#[test]
fn shared_option_names_and_their_old_aliases_name_a_bad_value() {
    let d = Dir::new("option-names");
    let out = d.0.display().to_string();
    for (args, want) in [
        (vec!["campaign", "--fixed", "b99"], "`b99`"),
        (vec!["campaign", "--formats", "b99"], "`b99`"),
        (vec!["campaign", "--fixed", "", "--float", "e9m99"], "e9m99"),
        (
            vec!["campaign", "--fixed", "", "--float-formats", "e9m99"],
            "e9m99",
        ),
        (vec!["run", "-", "--k", "9"], "--k 9"),
        (vec!["run", "-", "--planes", "9"], "--k 9"),
        (vec!["gen", "--vectors", "x"], "--vectors"),
    ] {
        let mut a = vec!["--out", &out];
        a.extend(&args);
        let o = rtu(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} must fail");
        assert!(err.contains(want), "{args:?}: {err}");
        assert!(d.entries().is_empty(), "{args:?}: {:?}", d.entries());
    }
}
