//! `rtu campaign`: conservativeness of the bit-accurate model against the exact oracle, and
//! cross-simulation of the exported Verilog against the rust-hdl simulation and the model, at scale.
//! Vectors are streamed (memory stays flat); progress is shown; results go to `<out>/campaign.csv`.

use golden::fixed::FixFormat;
use golden::gen::GenKind;
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;
use tb::campaign::{conservative_campaign, slab_vectors};

#[derive(clap::Args)]
pub struct Args {
    /// Vectors per format and generator (conservativeness) and per format (cross-simulation).
    #[arg(long, default_value_t = 10_000_000)]
    vectors: u64,
    /// Formats, comma-separated presets (b8,b12,b16).
    #[arg(long, default_value = "b8,b12,b16")]
    formats: String,
    /// Seed of the first stream (the others are derived from it).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Threads for the conservativeness campaign.
    #[arg(long, default_value_t = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1))]
    threads: usize,
    /// Skip the conservativeness campaign.
    #[arg(long)]
    no_conservative: bool,
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

pub fn run(a: &Args, out: &Path) -> Result<(), String> {
    let formats: Vec<FixFormat> = a
        .formats
        .split(',')
        .map(|s| FixFormat::parse(s.trim()).map_err(|e| e.to_string()))
        .collect::<Result<_, _>>()?;
    let mut csv = String::from("check,format,generator,vectors,true_hits,false_hits,false_hit_rate,violations,seconds,vectors_per_s\n");
    let mut failed = vec![];
    if !a.no_conservative {
        for (fi, fmt) in formats.iter().enumerate() {
            for (ki, kind) in [GenKind::Uniform, GenKind::Adversarial]
                .into_iter()
                .enumerate()
            {
                let pb = bar(a.vectors, format!("exact {} {kind:?}", fmt.name()));
                let t = Instant::now();
                let seed = a.seed.wrapping_add(1000 * (2 * fi + ki) as u64);
                let st =
                    conservative_campaign(*fmt, kind, a.vectors, seed, a.threads, &|k| pb.inc(k));
                let secs = t.elapsed().as_secs_f64();
                pb.finish_and_clear();
                println!(
                    "conservative {} {kind:?}: {} vectors, {} true hits, {} false hits ({:.3}% of true misses), {} violations, {:.0} s",
                    fmt.name(),
                    st.vectors,
                    st.true_hits,
                    st.false_hits,
                    100.0 * st.false_hit_rate(),
                    st.violation_count,
                    secs
                );
                for v in &st.violations {
                    println!("  VIOLATION {v}");
                }
                if st.violation_count > 0 {
                    failed.push(format!(
                        "{} {kind:?}: {} violations",
                        fmt.name(),
                        st.violation_count
                    ));
                }
                let _ = writeln!(
                    csv,
                    "conservative,{},{kind:?},{},{},{},{:.6},{},{secs:.1},{:.0}",
                    fmt.name(),
                    st.vectors,
                    st.true_hits,
                    st.false_hits,
                    st.false_hit_rate(),
                    st.violation_count,
                    st.vectors as f64 / secs
                );
            }
        }
    }
    if !a.no_xsim {
        for (fi, fmt) in formats.iter().enumerate() {
            let v = rtl::export::slab_fix_verilog(fmt)?;
            let h = tb::verilator::build(
                &v,
                &rtl::export::slab_fix_module(fmt),
                &out.join("verilator"),
            )?;
            let pb = bar(a.vectors, format!("verilator = rtl = model {}", fmt.name()));
            let t = Instant::now();
            let vectors = slab_vectors(
                *fmt,
                GenKind::Mixed,
                a.seed.wrapping_add(7000 + fi as u64),
                a.vectors,
                true,
            );
            let mut last = 0;
            let st = rtl::with_slab_fix!(fmt, S, {
                tb::slab_tb::xsim(
                    *fmt,
                    || S::new(fmt),
                    &h,
                    vectors,
                    true,
                    |n| {
                        pb.inc(n - last);
                        last = n;
                    },
                )
            })?;
            let secs = t.elapsed().as_secs_f64();
            pb.finish_and_clear();
            match st {
                Ok(st) => {
                    println!(
                        "cross-simulation {}: {} vectors in {} cycles, Verilator = rust-hdl = model bit for bit, {:.0} s",
                        fmt.name(),
                        st.tests,
                        st.cycles,
                        secs
                    );
                    let _ = writeln!(
                        csv,
                        "xsim,{},mixed,{},{},,,0,{secs:.1},{:.0}",
                        fmt.name(),
                        st.tests,
                        st.hits,
                        st.tests as f64 / secs
                    );
                }
                Err(e) => {
                    println!("cross-simulation {}: MISMATCH {e}", fmt.name());
                    failed.push(format!("{} cross-simulation: {e}", fmt.name()));
                }
            }
        }
    }
    std::fs::create_dir_all(out).map_err(|e| e.to_string())?;
    std::fs::write(out.join("campaign.csv"), csv).map_err(|e| e.to_string())?;
    println!("wrote {}", out.join("campaign.csv").display());
    if failed.is_empty() {
        Ok(())
    } else {
        Err(failed.join("; "))
    }
}
