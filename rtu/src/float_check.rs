//! `rtu float-check`: the float model at campaign scale. Round to nearest against `half` (binary16,
//! bfloat16) and native `f32` (binary32) on every special pair plus `--pairs` random pairs per format and
//! operation; the directed modes against the exact characterisation of correct rounding on a tenth as many.

use golden::format::float::{FloatFormat, Rounding};
use golden::format::float_check::{check_op, Op};
use half::{bf16, f16};
use indicatif::{ProgressBar, ProgressStyle};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::fmt::Write as _;
use std::path::Path;

#[derive(clap::Args)]
pub struct Args {
    /// Random operand pairs per format and operation under round to nearest.
    #[arg(long, default_value_t = 10_000_000)]
    pairs: u64,
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

/// Operand pairs: every special pair, then `n` random pairs (half of them close, for cancellation and ties).
fn pairs(f: FloatFormat, n: u64, seed: u64) -> impl Iterator<Item = (u32, u32)> {
    let s = f.specials();
    let specials: Vec<(u32, u32)> = s
        .iter()
        .flat_map(|&a| s.iter().map(move |&b| (a, b)))
        .collect();
    let mut rng = Pcg64::seed_from_u64(seed);
    let mask = f.mask();
    let sign = f.sign_bit();
    let random = (0..n).map(move |_| {
        let a = rng.gen::<u32>() & mask;
        let b = match rng.gen_range(0..4) {
            0 => (a ^ rng.gen_range(0..64)) & mask,
            1 => (a ^ sign ^ rng.gen_range(0..64)) & mask,
            _ => rng.gen::<u32>() & mask,
        };
        (a, b)
    });
    specials.into_iter().chain(random)
}

/// The reference result of `op` under round to nearest, for the formats that have one.
fn reference(f: FloatFormat, op: Op, a: u32, b: u32) -> u32 {
    macro_rules! via {
        ($t:ty, $from:expr, $to:expr) => {{
            let (x, y): ($t, $t) = ($from(a), $from(b));
            $to(match op {
                Op::Add => x + y,
                Op::Sub => x - y,
                Op::Mul => x * y,
            })
        }};
    }
    match (f.e, f.m) {
        (8, 23) => via!(f32, f32::from_bits, |r: f32| r.to_bits()),
        (5, 10) => via!(f16, |v: u32| f16::from_bits(v as u16), |r: f16| r.to_bits()
            as u32),
        (8, 7) => via!(
            bf16,
            |v: u32| bf16::from_bits(v as u16),
            |r: bf16| r.to_bits() as u32
        ),
        _ => unreachable!("no reference for {}", f.name()),
    }
}

pub fn run(a: &Args, out: &Path) -> Result<(), String> {
    let style = ProgressStyle::with_template("{msg:34} [{bar:30}] {pos}/{len} {per_sec} eta {eta}")
        .unwrap()
        .progress_chars("=> ");
    let mut csv = String::from("format,operation,mode,reference,pairs,mismatches\n");
    let mut failed = vec![];
    let ops = [Op::Add, Op::Sub, Op::Mul];
    let refs = [
        (FloatFormat::FP32, "native f32"),
        (FloatFormat::FP16, "half f16"),
        (FloatFormat::BF16, "half bf16"),
    ];
    for (k, (f, name)) in refs.into_iter().enumerate() {
        for (j, op) in ops.into_iter().enumerate() {
            let pb = ProgressBar::new(a.pairs)
                .with_style(style.clone())
                .with_message(format!("{} {op:?} vs {name}", f.name()));
            let (mut n, mut bad) = (0u64, 0u64);
            for (x, y) in pairs(f, a.pairs, a.seed + (10 * k + j) as u64) {
                let ours = match op {
                    Op::Add => f.add(x, y, Rounding::NearestEven),
                    Op::Sub => f.sub(x, y, Rounding::NearestEven),
                    Op::Mul => f.mul(x, y, Rounding::NearestEven),
                };
                let theirs = reference(f, op, x, y);
                if ours != theirs && !(f.is_nan(ours) && f.is_nan(theirs)) {
                    if bad < 5 {
                        println!("  MISMATCH {} {op:?} {x:#x}, {y:#x}: {ours:#x} here, {theirs:#x} in {name}", f.name());
                    }
                    bad += 1;
                }
                n += 1;
                if n % 65536 == 0 {
                    pb.inc(65536);
                }
            }
            pb.finish_and_clear();
            println!(
                "{} {op:?} round-to-nearest vs {name}: {n} pairs, {bad} mismatches",
                f.name()
            );
            let _ = writeln!(csv, "{},{op:?},NearestEven,{name},{n},{bad}", f.name());
            if bad > 0 {
                failed.push(format!("{} {op:?} vs {name}: {bad} mismatches", f.name()));
            }
        }
    }
    let directed = a.pairs / 10;
    for (k, f) in rtl::SLAB_FLOAT_FORMATS
        .into_iter()
        .chain([FloatFormat::E4M3])
        .enumerate()
    {
        for mode in [Rounding::Down, Rounding::Up] {
            let pb = ProgressBar::new(directed)
                .with_style(style.clone())
                .with_message(format!("{} {mode:?} vs exact", f.name()));
            let (mut n, mut bad) = (0u64, 0u64);
            for (x, y) in pairs(f, directed, a.seed + 100 + k as u64) {
                for op in ops {
                    if let Err(e) = check_op(&f, op, x, y, mode) {
                        if bad < 5 {
                            println!("  MISMATCH {e}");
                        }
                        bad += 1;
                    }
                }
                n += 1;
                if n % 4096 == 0 {
                    pb.inc(4096);
                }
            }
            pb.finish_and_clear();
            println!("{} add/sub/mul {mode:?} vs exact rounding: {n} pairs x 3 operations, {bad} mismatches", f.name());
            let _ = writeln!(csv, "{},add+sub+mul,{mode:?},exact,{n},{bad}", f.name());
            if bad > 0 {
                failed.push(format!("{} {mode:?}: {bad} mismatches", f.name()));
            }
        }
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join("float_check.csv"), csv)?;
    println!("wrote {}", out.join("float_check.csv").display());
    if failed.is_empty() {
        Ok(())
    } else {
        Err(failed.join("; "))
    }
}
