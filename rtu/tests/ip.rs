//! The exported cores as a user drives them: `rtu encode` words simulated in Verilator, captured and
//! `rtu decode`d, equal `rtu run`'s results byte for byte; the exported datasheets and core files; bad
//! input to encode and decode is an error naming the file, the line and the field.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tb::ip::words;

fn rtu(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rtu"))
        .args(args)
        .output()
        .expect("rtu runs")
}

fn ok(args: &[&str]) -> Vec<u8> {
    let o = rtu(args);
    assert!(
        o.status.success(),
        "rtu {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o.stdout
}

fn err(args: &[&str]) -> String {
    let o = rtu(args);
    assert!(!o.status.success(), "rtu {args:?} should fail");
    assert!(
        o.stdout.is_empty(),
        "rtu {args:?} printed results before failing"
    );
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rtu-ip-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &Path) -> String {
    p.display().to_string()
}

/// Drives the encoded input words through the module's Verilog in Verilator, one test a clock, and
/// returns the output words of every clock with `valid_out` high, as a word file.
fn simulate(module: &str, in_hex: &Path) -> String {
    let e = rtl::export::find(module).unwrap();
    let verilog = e.verilog();
    let ports = tb::verilator::parse_ports(&verilog, module).unwrap();
    let ins = words::columns(&ports, true);
    let outs = words::columns(&ports, false);
    let text = std::fs::read_to_string(in_hex).unwrap();
    let rows = words::read(&text, "in", &ports, &ins).unwrap();
    let h = tb::verilator::build(&verilog, module, &tb::out_dir().join("verilator")).unwrap();
    let lat = e.latency;
    let records: Vec<Vec<u64>> = rows
        .iter()
        .map(|(_, r)| Some(r.clone()))
        .chain(std::iter::repeat_n(None, lat + 1))
        .map(|r| {
            h.inputs
                .iter()
                .map(|p| match (&r, p.name.as_str()) {
                    (None, _) | (_, "rst") => 0,
                    (Some(_), "valid_in") => 1,
                    (Some(r), name) => r[ins.iter().position(|c| c.name == name).unwrap()],
                })
                .collect()
        })
        .collect();
    let iv = h.output_index("valid_out").unwrap();
    let mut got = vec![];
    let mut valid_clocks = vec![];
    h.stream(records.into_iter(), |cycle, out| {
        if out[iv] != 0 {
            valid_clocks.push(cycle);
            got.push(
                outs.iter()
                    .map(|c| out[h.output_index(&c.name).unwrap()])
                    .collect::<Vec<u64>>(),
            );
        }
        Ok(())
    })
    .unwrap();
    // Test n goes in at clock n and leaves exactly `lat` clocks later.
    let want: Vec<u64> = (0..rows.len() as u64).map(|n| n + lat as u64 - 1).collect();
    assert_eq!(valid_clocks, want, "{module}: valid_out clocks");
    words::write(&["captured from Verilator".into()], &outs, &got)
}

#[test]
fn decode_of_the_simulated_encoding_equals_rtu_run() {
    // rust-hdl's Verilog generation of the cull-plane tester recurses deeper than a test thread's stack.
    tb::plane::float::with_big_stack(roundtrip)
}

fn roundtrip() {
    let d = dir("roundtrip");
    let v = d.join("v.jsonl");
    ok(&["gen", "-n", "300", "--seed", "7", "-o", &s(&v)]);
    for (module, run) in [
        ("slab_fix_g12_i16f11_t20f6", &["--format", "b12"][..]),
        ("slab_fix_g8_i12f8_t14f4_p6", &["--format", "b8"][..]),
        ("slab_float_e5m10_p13", &["--format", "fp16"][..]),
        (
            "plane_fix_g12_i16f11_t20f6_n8_fd11_r8_k1",
            &["--format", "b12", "--k", "1"][..],
        ),
    ] {
        let (_, decoded) = through_verilator(&d, module, &v);
        let mut args = vec!["run", "--engine", "model"];
        args.extend_from_slice(run);
        args.push(v.to_str().unwrap());
        let want = ok(&args);
        assert!(!want.is_empty());
        assert_eq!(
            String::from_utf8_lossy(&decoded),
            String::from_utf8_lossy(&want),
            "{module}"
        );
    }
    // The bundle pairs: bundle vectors by their bounds, against `rtu run --bundles`.
    let bv = d.join("bundles.jsonl");
    std::fs::write(&bv, bundle_vectors(200, 11)).unwrap();
    for (module, fmt) in [
        ("bundle_fix_g12_i16f11_t20f6_d10", "b12"),
        ("bundle_float_e5m10", "fp16"),
    ] {
        let (rows, decoded) = through_verilator(&d, module, &bv);
        // Every outcome occurs in the stream: all hit, all miss, neither.
        let outcomes: std::collections::BTreeSet<String> = rows
            .iter()
            .filter(|r| !r.starts_with("//"))
            .map(|r| r.split_whitespace().skip(1).collect::<Vec<_>>().join(" "))
            .collect();
        assert_eq!(outcomes.len(), 3, "{module}: {outcomes:?}");
        let want = ok(&[
            "run",
            "--bundles",
            "--engine",
            "model",
            "--format",
            fmt,
            &s(&bv),
        ]);
        assert_eq!(
            String::from_utf8_lossy(&decoded),
            String::from_utf8_lossy(&want),
            "{module}"
        );
    }
    std::fs::remove_dir_all(&d).ok();
}

/// Encodes `vectors` for `module`, simulates the words in Verilator, checks the captured words against
/// the model's (`.out.hex`: its `// ports:` line and every row), and decodes them. Returns the model's
/// rows (with the ports line) and the decoded results.
fn through_verilator(d: &Path, module: &str, vectors: &Path) -> (Vec<String>, Vec<u8>) {
    let prefix = d.join(module);
    ok(&[
        "--out",
        &s(d),
        "encode",
        "--module",
        module,
        &s(vectors),
        "-o",
        &s(&prefix),
    ]);
    let in_hex = PathBuf::from(format!("{}.in.hex", prefix.display()));
    let expect = std::fs::read_to_string(format!("{}.out.hex", prefix.display())).unwrap();
    let captured = simulate(module, &in_hex);
    // The captured words are the model's, bit for bit (the other comments aside).
    let rows = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| !l.starts_with("//") || l.starts_with("// ports:"))
            .map(String::from)
            .collect()
    };
    assert_eq!(rows(&captured), rows(&expect), "{module}");
    let cap = d.join(format!("{module}.cap.hex"));
    std::fs::write(&cap, &captured).unwrap();
    let decoded = ok(&[
        "decode",
        "--module",
        module,
        "--vectors",
        &s(vectors),
        &s(&cap),
    ]);
    (rows(&expect), decoded)
}

/// `n` bundle vectors by their bounds (seeded): boxes and origin boxes around the origin, cones of
/// directions aimed near the box, wide and narrow, so that every outcome of the pair occurs.
fn bundle_vectors(n: usize, seed: u64) -> String {
    let mut x = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    let mut u = |lo: f64, hi: f64| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        lo + (hi - lo) * ((x >> 11) as f64 / (1u64 << 53) as f64)
    };
    let mut out = String::new();
    for tag in 0..n {
        let c: Vec<f64> = (0..3).map(|_| u(-4.0, 4.0)).collect();
        let h: Vec<f64> = (0..3).map(|_| u(0.2, 2.0)).collect();
        let o: Vec<f64> = (0..3).map(|_| u(-8.0, 8.0)).collect();
        // One bundle in three is narrow and aimed at the box's centre (the AllHit tester's case).
        let centred = tag % 3 == 0;
        let w = if centred { 0.01 } else { u(0.0, 0.3) };
        let off = if centred { 0.0 } else { 3.0 };
        let aim: Vec<f64> = (0..3).map(|a| c[a] + u(-off, off) - o[a]).collect();
        let m = aim.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-3);
        let spread = [0.001, 0.02, 0.2][tag % 3];
        let f = |v: Vec<f64>| format!("[{},{},{}]", v[0], v[1], v[2]);
        out += &format!(
            "{{\"tag\":{tag},\"o_lo\":{},\"o_hi\":{},\"d_lo\":{},\"d_hi\":{},\"t_lo\":{},\"t_hi\":\"inf\",\"box_min\":{},\"box_max\":{}}}\n",
            f(o.iter().map(|v| v - w).collect()),
            f(o.iter().map(|v| v + w).collect()),
            f(aim.iter().map(|v| v / m - spread).collect()),
            f(aim.iter().map(|v| v / m + spread).collect()),
            // AllHit needs every ray's range to reach the box: t_max of at least t_lo.
            if centred { "30" } else { "0" },
            f((0..3).map(|a| c[a] - h[a]).collect()),
            f((0..3).map(|a| c[a] + h[a]).collect()),
        );
    }
    out
}

#[test]
fn bad_input_to_encode_and_decode_names_the_line_and_field() {
    let d = dir("bad");
    let v = d.join("v.jsonl");
    ok(&["gen", "-n", "5", "--seed", "3", "-o", &s(&v)]);
    let m = "slab_fix_g8_i12f8_t14f4";
    let prefix = d.join("w");
    ok(&[
        "--out",
        &s(&d),
        "encode",
        "--module",
        m,
        &s(&v),
        "-o",
        &s(&prefix),
    ]);
    let good = std::fs::read_to_string(format!("{}.out.hex", prefix.display())).unwrap();
    let decode = |name: &str, text: &str| {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        err(&["decode", "--module", m, "--vectors", &s(&v), &s(&p)])
    };
    // The header is line 4: rows start at line 5.
    let lines: Vec<&str> = good.lines().collect();
    let row = |k: usize| lines.iter().position(|l| !l.starts_with("//")).unwrap() + k;
    let mut wide = lines.clone();
    let w = format!("7{}", wide[row(1)]); // tag_out gains a digit: 5 hex digits for 16 bits
    wide[row(1)] = &w;
    let e = decode("wide.hex", &wide.join("\n"));
    assert!(
        e.contains(&format!("wide.hex:{}: field `tag_out`", row(1) + 1))
            && e.contains("wider than the port's 16 bits"),
        "{e}"
    );
    let mut swapped = lines.clone();
    swapped.swap(row(0), row(1));
    let e = decode("swapped.hex", &swapped.join("\n"));
    assert!(
        e.contains(&format!("swapped.hex:{}: field `tag_out`", row(0) + 1))
            && e.contains("out of order"),
        "{e}"
    );
    let e = decode("short.hex", &lines[..row(3)].join("\n"));
    assert!(
        e.contains("short.hex: 3 results, but") && e.contains("has 5 vectors"),
        "{e}"
    );
    let e = decode(
        "cols.hex",
        &good.replace("// ports: tag_out", "// ports: tag_in"),
    );
    assert!(
        e.contains("field `tag_in`: a port of the module, but not one this file carries"),
        "{e}"
    );
    // Encode: an unknown module, the results processor, a vector that does not fit.
    let e = err(&["encode", "--module", "slab_fix_b12", &s(&v)]);
    assert!(
        e.contains("module `slab_fix_b12` is not an exported module")
            && e.contains("slab_fix_g12_i16f11_t20f6"),
        "{e}"
    );
    let e = err(&[
        "encode",
        "--module",
        "bundle_split_g12_i16f11_t20f6_d10_n16",
        &s(&v),
    ]);
    assert!(e.contains("takes a job over several clocks"), "{e}");
    let e = err(&[
        "--out",
        &s(&d),
        "encode",
        "--module",
        m,
        "--bounds",
        "0,0,0,1,1,1",
        &s(&v),
    ]);
    assert!(
        e.contains(&format!("{}:1: vector with tag 0:", s(&v))) && e.contains("does not fit"),
        "{e}"
    );
    let e = err(&[
        "--out",
        &s(&d),
        "encode",
        "--module",
        "slab_float_e5m10",
        &s(&d.join("none.jsonl")),
    ]);
    assert!(e.contains("none.jsonl"), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn export_writes_a_datasheet_and_a_core_file_per_module() {
    let d = dir("export");
    ok(&["--out", &s(&d), "export"]);
    let vdir = d.join("verilog");
    for e in rtl::export::catalog() {
        let md = std::fs::read_to_string(vdir.join(format!("{}.md", e.module))).unwrap();
        let verilog = std::fs::read_to_string(vdir.join(format!("{}.v", e.module))).unwrap();
        // Every port is in the datasheet's port table, with its width, and described.
        for p in tb::verilator::parse_ports(&verilog, &e.module).unwrap() {
            let range = if p.width > 1 {
                format!("[{}:0]", p.width - 1)
            } else {
                String::new()
            };
            let row = md
                .lines()
                .find(|l| l.starts_with(&format!("| `{}{range}` |", p.name)))
                .unwrap_or_else(|| panic!("{}: no row for port {}", e.module, p.name));
            assert!(!row.contains("(not described)"), "{}: {row}", e.module);
        }
        assert!(
            md.contains(&format!("| latency | {} |", e.latency)),
            "{}",
            e.module
        );
        // The committed datasheet is what the export writes (regenerate: rtu export --datasheets docs/ip).
        let docs = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../docs/ip")
            .join(format!("{}.md", e.module));
        let committed = std::fs::read_to_string(&docs).unwrap_or_default();
        assert!(
            committed == md,
            "{} is not what rtu export writes: run `rtu export --datasheets docs/ip`",
            docs.display()
        );
        let core = std::fs::read_to_string(vdir.join(format!("{}.core", e.module))).unwrap();
        assert!(
            core.starts_with("CAPI=2:") && core.contains(&format!("{}.v", e.module)),
            "{}",
            e.module
        );
        assert!(vdir.join(format!("{}.gtkw", e.module)).exists());
    }
    // The worked example of the b12 tester is the encoder's and the model's answer.
    let md = std::fs::read_to_string(vdir.join("slab_fix_g12_i16f11_t20f6.md")).unwrap();
    assert!(
        md.contains("| `ray_m_lo_2` | `fffe` |") && md.contains("| `ray_m_hi_2` | `ffff` |"),
        "the tiny z component"
    );
    assert!(md.contains("\"hit\":true"), "the example hits");
    // The cull-plane example's plane tightens the entry (exact 0.625; the slab tester alone says 0.3125).
    let md =
        std::fs::read_to_string(vdir.join("plane_fix_g12_i16f11_t20f6_n8_fd11_r8_k1.md")).unwrap();
    assert!(md.contains("\"t_entry\":0.622528076171875"), "{md}");
    let md = std::fs::read_to_string(vdir.join("bundle_fix_g12_i16f11_t20f6_d10.md")).unwrap();
    assert!(
        md.contains("\"all_hit\":true"),
        "the bundle example is all hit"
    );
    std::fs::remove_dir_all(&d).ok();
}
