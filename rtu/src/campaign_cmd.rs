//! `rtu campaign`: conservativeness of the bit-accurate models against the exact oracle, and
//! cross-simulation of the exported Verilog against the rust-hdl simulation and the model, at scale, for
//! both datapaths. Vectors are streamed (memory stays flat); progress is shown; results go to
//! `<out>/campaign.csv`.

use golden::slab::gen::GenKind;
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;
use tb::campaign::{conservative_campaign, float_campaign, slab_vectors, ConservativeStats};
use tb::xsim::{xsim, XsimStats};

#[derive(clap::Args)]
pub struct Args {
    /// Vectors per format and generator (conservativeness) and per format (cross-simulation).
    #[arg(long, default_value_t = 10_000_000)]
    vectors: u64,
    /// Fixed-point formats, comma-separated presets (b8,b12,b16); empty for none (also `--formats`).
    #[arg(long, alias = "formats", default_value = "b8,b12,b16")]
    fixed: String,
    /// Float formats, comma-separated (fp32,e8m15,bf16,fp16,e6m5); empty for none (also
    /// `--float-formats`).
    #[arg(
        long,
        alias = "float-formats",
        default_value = "fp32,e8m15,bf16,fp16,e6m5"
    )]
    float: String,
    /// Seed of the first stream (the others are derived from it).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Threads for the conservativeness campaign.
    #[arg(long, default_value_t = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1))]
    threads: usize,
    /// Skip the conservativeness campaign.
    #[arg(long)]
    no_conservative: bool,
    /// Cycles of each cross-simulation also compared with the rust-hdl simulation (the rest: Verilator
    /// against the model). The float tester simulates at about 10k tests/s in rust-hdl.
    #[arg(long, default_value_t = 1_000_000)]
    lockstep: u64,
    /// Skip the Verilator cross-simulation.
    #[arg(long)]
    no_xsim: bool,
}

fn bar(n: u64, msg: String) -> ProgressBar {
    let pb = ProgressBar::new(n);
    pb.set_style(
        ProgressStyle::with_template("{msg:34} [{bar:30}] {pos}/{len} {per_sec} eta {eta}")
            .unwrap()
            .progress_chars("=> "),
    );
    pb.set_message(msg);
    pb
}

/// The campaign's log: CSV rows and failures.
struct Log {
    csv: String,
    failed: Vec<String>,
}

impl Log {
    fn conservative(&mut self, name: &str, kind: GenKind, st: &ConservativeStats, secs: f64) {
        println!(
            "conservative {name} {kind:?}: {} vectors, {} true hits, {} false hits ({:.3}% of true misses), {} violations, {secs:.0} s",
            st.vectors,
            st.true_hits,
            st.false_hits,
            100.0 * st.false_hit_rate(),
            st.violation_count
        );
        for v in &st.violations {
            println!("  VIOLATION {v}");
        }
        if st.violation_count > 0 {
            self.failed.push(format!(
                "{name} {kind:?}: {} violations",
                st.violation_count
            ));
        }
        let _ = writeln!(
            self.csv,
            "conservative,{name},{kind:?},{},{},{},{:.6},{},{secs:.1},{:.0}",
            st.vectors,
            st.true_hits,
            st.false_hits,
            st.false_hit_rate(),
            st.violation_count,
            st.vectors as f64 / secs
        );
    }

    fn xsim(&mut self, name: &str, r: Result<XsimStats, String>, lockstep: u64, secs: f64) {
        match r {
            Ok(st) => {
                println!(
                    "cross-simulation {name}: {} vectors in {} cycles, Verilator = model bit for bit (and = rust-hdl on the first {} cycles), {secs:.0} s",
                    st.tests, st.cycles, lockstep
                );
                let _ = writeln!(
                    self.csv,
                    "xsim,{name},mixed,{},{},,,0,{secs:.1},{:.0}",
                    st.tests,
                    st.hits,
                    st.tests as f64 / secs
                );
            }
            Err(e) => {
                println!("cross-simulation {name}: MISMATCH {e}");
                self.failed.push(format!("{name} cross-simulation: {e}"));
            }
        }
    }
}

pub fn run(a: &Args, out: &Path) -> Result<(), String> {
    let fixed = crate::opts::fix_formats(&a.fixed)?;
    let floats = crate::opts::float_formats(&a.float)?;
    let mut log = Log {
        csv: String::from("check,format,generator,vectors,true_hits,false_hits,false_hit_rate,violations,seconds,vectors_per_s\n"),
        failed: vec![],
    };
    let seed = |k: usize| a.seed.wrapping_add(1000 * k as u64);
    if !a.no_conservative {
        let kinds = [GenKind::Uniform, GenKind::Adversarial];
        for (fi, fmt) in fixed.iter().enumerate() {
            for (ki, kind) in kinds.into_iter().enumerate() {
                let pb = bar(a.vectors, format!("exact {} {kind:?}", fmt.name()));
                let t = Instant::now();
                let st = conservative_campaign(
                    *fmt,
                    kind,
                    a.vectors,
                    seed(2 * fi + ki),
                    a.threads,
                    &|k| pb.inc(k),
                );
                pb.finish_and_clear();
                log.conservative(&fmt.name(), kind, &st, t.elapsed().as_secs_f64());
            }
        }
        for (fi, f) in floats.iter().enumerate() {
            for (ki, kind) in kinds.into_iter().enumerate() {
                let pb = bar(a.vectors, format!("exact {} {kind:?}", f.name()));
                let t = Instant::now();
                let st = float_campaign(
                    *f,
                    kind,
                    a.vectors,
                    seed(100 + 2 * fi + ki),
                    a.threads,
                    &|k| pb.inc(k),
                );
                pb.finish_and_clear();
                log.conservative(&f.name(), kind, &st, t.elapsed().as_secs_f64());
            }
        }
    }
    if !a.no_xsim {
        let vdir = out.join("verilator");
        for (fi, fmt) in fixed.iter().enumerate() {
            let module = rtl::names::slab_fix_module(fmt);
            let h = tb::verilator::build(&rtl::export::slab_fix_verilog(fmt)?, &module, &vdir)?;
            let pb = bar(a.vectors, format!("verilator = rtl = model {}", fmt.name()));
            let t = Instant::now();
            let vectors = slab_vectors(*fmt, GenKind::Mixed, seed(7 + fi), a.vectors, true);
            let mut last = 0;
            let r = rtl::with_slab_fix!(fmt, S, {
                xsim(
                    *fmt,
                    || S::new(fmt),
                    &h,
                    vectors,
                    a.lockstep,
                    |n| {
                        pb.inc(n - last);
                        last = n;
                    },
                )
            })?;
            pb.finish_and_clear();
            log.xsim(&fmt.name(), r, a.lockstep, t.elapsed().as_secs_f64());
        }
        for (fi, f) in floats.iter().enumerate() {
            let module = rtl::names::slab_float_module(f);
            let h = tb::verilator::build(&rtl::export::slab_float_verilog(f)?, &module, &vdir)?;
            let pb = bar(a.vectors, format!("verilator = rtl = model {}", f.name()));
            let t = Instant::now();
            let vectors =
                tb::campaign::float_vectors(*f, GenKind::Mixed, seed(107 + fi), a.vectors, true);
            let mut last = 0;
            let r = rtl::with_slab_float!(f, S, {
                xsim(*f, S::new, &h, vectors, a.lockstep, |n| {
                    pb.inc(n - last);
                    last = n;
                })
            })?;
            pb.finish_and_clear();
            log.xsim(&f.name(), r, a.lockstep, t.elapsed().as_secs_f64());
        }
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join("campaign.csv"), &log.csv)?;
    println!("wrote {}", out.join("campaign.csv").display());
    if log.failed.is_empty() {
        Ok(())
    } else {
        Err(log.failed.join("; "))
    }
}
