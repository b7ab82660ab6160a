//! `rtu bench`: throughput of the three forms of the fixed slab tester, measured in one run on the same
//! vectors and reported as ratios, plus the peak memory of a streamed cross-simulation at two lengths.
//! Figures go to stdout and `<out>/bench.csv`; nothing here is a pass/fail test.

use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use golden::slab::fix::slab_fix;
use golden::slab::float as slab_float;
use golden::slab::gen::GenKind;
use rtl::slab::fix::SlabFixIo;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;
use tb::dut::PipelinedDut;
use tb::rtl_sim::SlabFixRtl;
use tb::xsim::in_word;

#[derive(clap::Args)]
pub struct Args {
    /// Format to measure (a preset).
    #[arg(long, default_value = "b16")]
    format: String,
    /// Tests for the bit-accurate model.
    #[arg(long, default_value_t = 50_000_000)]
    model_tests: u64,
    /// Tests for the float model, per format.
    #[arg(long, default_value_t = 10_000_000)]
    float_tests: u64,
    /// Tests for the rust-hdl simulation.
    #[arg(long, default_value_t = 500_000)]
    rtl_tests: u64,
    /// Tests for Verilator.
    #[arg(long, default_value_t = 20_000_000)]
    verilator_tests: u64,
    /// Vectors of the shorter streamed cross-simulation used for the memory figure (the longer is 4x).
    #[arg(long, default_value_t = 250_000)]
    stream_tests: u64,
}

/// Peak resident memory of this process so far, in KiB (Linux `VmHWM`).
fn peak_rss_kib() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let l = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    l.split_whitespace().nth(1)?.parse().ok()
}

fn bench_rtl<S: SlabFixIo>(
    fmt: FixFormat,
    pool: &[(golden::format::fixed::FixRay, golden::format::fixed::FixBox)],
    n: u64,
) -> f64 {
    let mut dut = SlabFixRtl::<S>::new(&fmt);
    let t = Instant::now();
    let mut hits = 0u64;
    for i in 0..n as usize {
        let v = &pool[i % pool.len()];
        if let Some((_, o)) = dut.step(Some(((i & 0xffff) as u16, v))) {
            hits += o.hit as u64;
        }
    }
    black_box(hits);
    n as f64 / t.elapsed().as_secs_f64()
}

pub fn run(a: &Args, out: &Path) -> Result<(), String> {
    let fmt = FixFormat::parse(&a.format).map_err(|e| e.to_string())?;
    let pool: Vec<_> = tb::campaign::slab_vectors(fmt, GenKind::Mixed, 99, 1 << 16, false)
        .flatten()
        .collect();
    println!(
        "rtu bench: format {}, {} distinct vectors cycled, one core per engine",
        fmt.name(),
        pool.len()
    );

    // 1. The bit-accurate model.
    let t = Instant::now();
    let mut hits = 0u64;
    for i in 0..a.model_tests as usize {
        let (r, b) = &pool[i & (pool.len() - 1)];
        hits += slab_fix(black_box(&fmt), black_box(r), black_box(b)).hit as u64;
    }
    black_box(hits);
    let model = a.model_tests as f64 / t.elapsed().as_secs_f64();
    println!("  model:     {model:>14.0} tests/s");

    // 1b. The bit-accurate float model, in each issue-3 format, on the same world vectors.
    let mut float_rates = vec![];
    for f in [
        FloatFormat::FP32,
        FloatFormat::E8M15,
        FloatFormat::BF16,
        FloatFormat::FP16,
    ] {
        let map = tb::campaign::campaign_map(fmt);
        let fpool: Vec<_> = tb::campaign::world_gen(&map, GenKind::Mixed, 98)
            .take(1 << 16)
            .map(|(r, b)| {
                (
                    slab_float::quantize_ray(&f, &r).unwrap(),
                    slab_float::quantize_box(&f, &b).unwrap(),
                )
            })
            .collect();
        let t = Instant::now();
        let mut hits = 0u64;
        for i in 0..a.float_tests as usize {
            let (r, b) = &fpool[i & (fpool.len() - 1)];
            hits += slab_float::slab_float(black_box(&f), black_box(r), black_box(b)).hit as u64;
        }
        black_box(hits);
        let rate = a.float_tests as f64 / t.elapsed().as_secs_f64();
        println!("  float model {}: {rate:>14.0} tests/s", f.name());
        float_rates.push((f, rate));
    }

    // 2. The rust-hdl simulation (direct loop).
    let rtl = rtl::with_slab_fix!(&fmt, S, { bench_rtl::<S>(fmt, &pool, a.rtl_tests) })?;
    println!("  rust-hdl:  {rtl:>14.0} tests/s");

    // 3. Verilator: pre-encoded records through the pipe, results counted.
    let v = rtl::export::slab_fix_verilog(&fmt)?;
    let tb_build = Instant::now();
    let h = tb::verilator::build(
        &v,
        &rtl::names::slab_fix_module(&fmt),
        &out.join("verilator"),
    )?;
    let build_s = tb_build.elapsed().as_secs_f64();
    let ports = &h.inputs;
    let recs: std::sync::Arc<Vec<Vec<u64>>> = std::sync::Arc::new(
        pool.iter()
            .enumerate()
            .map(|(i, v)| {
                ports
                    .iter()
                    .map(|p| in_word(&fmt, p, i as u16, &Some(*v)).unwrap())
                    .collect()
            })
            .collect(),
    );
    let iv = h.output_index("valid_out").ok_or("no valid_out")?;
    let n = a.verilator_tests as usize;
    let r2 = recs.clone();
    let t = Instant::now();
    let mut valid = 0u64;
    h.stream((0..n).map(move |i| r2[i % r2.len()].clone()), |_, o| {
        valid += o[iv];
        Ok(())
    })?;
    let verilator = n as f64 / t.elapsed().as_secs_f64();
    println!("  verilator: {verilator:>14.0} tests/s (harness build or cache check {build_s:.1} s, not counted)");

    // 4. Memory of a streamed, fully checked cross-simulation at two lengths.
    let mut rss = vec![];
    for k in [1u64, 4] {
        let n = a.stream_tests * k;
        let vectors = tb::campaign::slab_vectors(fmt, GenKind::Mixed, 5, n, true);
        rtl::with_slab_fix!(&fmt, S, {
            tb::xsim::xsim(fmt, || S::new(&fmt), &h, vectors, 0, |_| {})
        })??;
        rss.push((n, peak_rss_kib().unwrap_or(0)));
    }
    println!(
        "  streamed cross-simulation peak RSS: {} KiB after {} vectors, {} KiB after {} more",
        rss[0].1, rss[0].0, rss[1].1, rss[1].0
    );
    println!("  ratios: model / rust-hdl = {:.0}, verilator / rust-hdl = {:.0}, model / verilator = {:.1}", model / rtl, verilator / rtl, model / verilator);

    let mut csv = String::from("engine,format,tests,tests_per_s,ratio_to_rust_hdl\n");
    for (e, n, r) in [
        ("model", a.model_tests, model),
        ("rust-hdl", a.rtl_tests, rtl),
        ("verilator", a.verilator_tests, verilator),
    ] {
        let _ = writeln!(csv, "{e},{},{n},{r:.0},{:.2}", fmt.name(), r / rtl);
    }
    let _ = writeln!(
        csv,
        "# peak RSS KiB: {} after {} streamed vectors, {} after {} more",
        rss[0].1, rss[0].0, rss[1].1, rss[1].0
    );
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join("bench.csv"), csv)?;
    Ok(())
}
