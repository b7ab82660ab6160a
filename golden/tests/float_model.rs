//! The float model against `half` (binary16, bfloat16) and native `f32` under round-to-nearest-even, and
//! against an exact characterisation of correct rounding (rational arithmetic) in all three modes.
//! `rtu float-campaign` runs the same comparisons on 10,000,000 pairs per format and operation.

use golden::exact::rat;
use golden::format::float::{Class, FloatFormat, Rounding};
use golden::format::float_check::{check_op, Op};
use half::{bf16, f16};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

const PAIRS: usize = 1_000_000;

fn random_operand(f: &FloatFormat, rng: &mut Pcg64, specials: &[u32]) -> u32 {
    match rng.gen_range(0..10) {
        0 => specials[rng.gen_range(0..specials.len())],
        // Near one another, so sums cancel.
        _ => rng.gen::<u32>() & f.mask(),
    }
}

/// Runs `ours` against `theirs` (both as bit patterns, NaN compared as "is NaN").
fn against<T: Fn(u32, u32) -> u32, U: Fn(u32, u32) -> u32>(
    f: FloatFormat,
    what: &str,
    ours: T,
    theirs: U,
    seed: u64,
) {
    let specials = f.specials();
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut pairs: Vec<(u32, u32)> = specials
        .iter()
        .flat_map(|&a| specials.iter().map(move |&b| (a, b)))
        .collect();
    for _ in 0..PAIRS {
        let a = random_operand(&f, &mut rng, &specials);
        // Half the time a close second operand, for cancellation and ties.
        let b = if rng.gen() {
            (a ^ rng.gen_range(0..64)) & f.mask()
        } else {
            random_operand(&f, &mut rng, &specials)
        };
        pairs.push((a, b));
    }
    for (a, b) in pairs {
        let (x, y) = (ours(a, b), theirs(a, b));
        let same = x == y || (f.is_nan(x) && f.is_nan(y));
        assert!(
            same,
            "{} {what}: {a:#x}, {b:#x} gives {x:#x} here and {y:#x} in the reference",
            f.name()
        );
    }
}

#[test]
fn fp16_matches_half_under_round_to_nearest() {
    let f = FloatFormat::FP16;
    let h = |x: u32| f16::from_bits(x as u16);
    let rne = Rounding::NearestEven;
    against(
        f,
        "add",
        |a, b| f.add(a, b, rne),
        |a, b| (h(a) + h(b)).to_bits() as u32,
        1,
    );
    against(
        f,
        "sub",
        |a, b| f.sub(a, b, rne),
        |a, b| (h(a) - h(b)).to_bits() as u32,
        2,
    );
    against(
        f,
        "mul",
        |a, b| f.mul(a, b, rne),
        |a, b| (h(a) * h(b)).to_bits() as u32,
        3,
    );
}

#[test]
fn bf16_matches_half_under_round_to_nearest() {
    let f = FloatFormat::BF16;
    let h = |x: u32| bf16::from_bits(x as u16);
    let rne = Rounding::NearestEven;
    against(
        f,
        "add",
        |a, b| f.add(a, b, rne),
        |a, b| (h(a) + h(b)).to_bits() as u32,
        4,
    );
    against(
        f,
        "sub",
        |a, b| f.sub(a, b, rne),
        |a, b| (h(a) - h(b)).to_bits() as u32,
        5,
    );
    against(
        f,
        "mul",
        |a, b| f.mul(a, b, rne),
        |a, b| (h(a) * h(b)).to_bits() as u32,
        6,
    );
}

#[test]
fn fp32_matches_native_f32_under_round_to_nearest() {
    let f = FloatFormat::FP32;
    let h = f32::from_bits;
    let rne = Rounding::NearestEven;
    against(
        f,
        "add",
        |a, b| f.add(a, b, rne),
        |a, b| (h(a) + h(b)).to_bits(),
        7,
    );
    against(
        f,
        "sub",
        |a, b| f.sub(a, b, rne),
        |a, b| (h(a) - h(b)).to_bits(),
        8,
    );
    against(
        f,
        "mul",
        |a, b| f.mul(a, b, rne),
        |a, b| (h(a) * h(b)).to_bits(),
        9,
    );
}

#[test]
fn every_fp16_and_bf16_value_decodes_as_half_does() {
    for x in 0..=u16::MAX as u32 {
        let (a, b) = (
            FloatFormat::FP16.to_f64(x),
            f16::from_bits(x as u16).to_f64(),
        );
        assert!(a == b || (a.is_nan() && b.is_nan()), "fp16 {x:#x}");
        let (a, b) = (
            FloatFormat::BF16.to_f64(x),
            bf16::from_bits(x as u16).to_f64(),
        );
        assert!(a == b || (a.is_nan() && b.is_nan()), "bf16 {x:#x}");
        // Encoding the decoded value gives the pattern back (NaNs become the canonical NaN).
        for f in [FloatFormat::FP16, FloatFormat::BF16] {
            if !f.is_nan(x) {
                for m in Rounding::ALL {
                    assert_eq!(f.from_f64(f.to_f64(x), m), x, "{} {x:#x} {m:?}", f.name());
                }
            }
        }
    }
}

#[test]
fn e4m3_is_correctly_rounded_in_every_mode_exhaustively() {
    let f = FloatFormat::E4M3;
    for a in 0..=f.mask() {
        for b in 0..=f.mask() {
            for mode in Rounding::ALL {
                for op in [Op::Add, Op::Sub, Op::Mul] {
                    check_op(&f, op, a, b, mode).unwrap_or_else(|e| panic!("{e}"));
                }
            }
        }
    }
}

#[test]
fn directed_modes_are_correctly_rounded_in_every_format() {
    for f in [
        FloatFormat::FP32,
        FloatFormat::E8M15,
        FloatFormat::BF16,
        FloatFormat::FP16,
        FloatFormat::new(6, 9).unwrap(),
    ] {
        let specials = f.specials();
        let mut rng = Pcg64::seed_from_u64(f.width() as u64);
        for i in 0..60_000 {
            let a = random_operand(&f, &mut rng, &specials);
            let b = if i % 2 == 0 {
                (a ^ rng.gen_range(0..256)) & f.mask()
            } else {
                random_operand(&f, &mut rng, &specials)
            };
            for mode in Rounding::ALL {
                for op in [Op::Add, Op::Sub, Op::Mul] {
                    check_op(&f, op, a, b, mode).unwrap_or_else(|e| panic!("{e}"));
                }
            }
        }
    }
}

#[test]
fn conversion_from_f64_is_correctly_rounded() {
    let mut rng = Pcg64::seed_from_u64(77);
    for f in [
        FloatFormat::FP32,
        FloatFormat::BF16,
        FloatFormat::FP16,
        FloatFormat::E4M3,
    ] {
        for _ in 0..50_000 {
            let x = f64::from_bits(rng.gen::<u64>());
            if !x.is_finite() {
                continue;
            }
            let d = f.from_f64(x, Rounding::Down);
            let u = f.from_f64(x, Rounding::Up);
            let (dv, uv) = (f.to_f64(d), f.to_f64(u));
            assert!(dv <= x && x <= uv, "{} {x:e}: {dv:e} {uv:e}", f.name());
            if dv != x {
                assert_eq!(f.next_up(d), u, "{} {x:e}", f.name());
            }
            // Round to nearest picks one of the two, the nearer.
            let n = f.from_f64(x, Rounding::NearestEven);
            assert!(
                n == d || n == u || (f.class(n) == Class::Inf),
                "{} {x:e}",
                f.name()
            );
            if dv.is_finite() && uv.is_finite() && dv != uv {
                let (ld, lu) = (rat(x) - rat(dv), rat(uv) - rat(x));
                if ld < lu {
                    assert_eq!(n, d);
                } else if lu < ld {
                    assert_eq!(n, u);
                }
            }
        }
    }
}

/// Exact ties, which random f64 inputs never produce: the midpoint of every pair of neighbouring finite
/// values of E4M3 (and a sample of pairs of the wider formats, every binade and the subnormals), both
/// signs. Round to nearest gives the neighbour with the even significand, toward -inf the lower and toward
/// +inf the upper; the midpoint between the largest finite value and the next power of two overflows to
/// infinity under round to nearest (IEEE 754, 7.4) and stays at the largest finite value downward.
#[test]
fn conversion_from_f64_rounds_ties_to_even() {
    let mut rng = Pcg64::seed_from_u64(78);
    for f in [
        FloatFormat::FP32,
        FloatFormat::BF16,
        FloatFormat::FP16,
        FloatFormat::E4M3,
    ] {
        let top = f.max_finite(false);
        let all: Vec<u32> = if f.width() <= 8 {
            (0..top).collect()
        } else {
            (0..20_000).map(|_| rng.gen_range(0..top)).collect()
        };
        let mut ties = [0usize; 2];
        for d in all {
            let u = f.next_up(d);
            let (dv, uv) = (f.to_f64(d), f.to_f64(u));
            let x = dv + (uv - dv) / 2.0;
            assert!(
                dv < x && x < uv,
                "{} {d:#x}: midpoint exact in f64",
                f.name()
            );
            for (x, lo, hi) in [(x, d, u), (-x, u | f.sign_bit(), d | f.sign_bit())] {
                let even = if lo & 1 == 0 { lo } else { hi };
                let name = f.name();
                assert_eq!(
                    f.from_f64(x, Rounding::NearestEven),
                    even,
                    "{name} tie {x:e}"
                );
                assert_eq!(f.from_f64(x, Rounding::Down), lo, "{name} tie {x:e} down");
                assert_eq!(f.from_f64(x, Rounding::Up), hi, "{name} tie {x:e} up");
                ties[usize::from(even == hi)] += 1;
            }
        }
        // Both outcomes occur: the check can tell ties-to-even from ties-up or ties-down.
        assert!(ties[0] > 0 && ties[1] > 0, "{}: {ties:?}", f.name());
        let max = f.to_f64(top);
        let half_ulp = (max - f.to_f64(top - 1)) / 2.0;
        for (s, sign) in [(1.0, false), (-1.0, true)] {
            let x = s * (max + half_ulp);
            assert_eq!(
                f.from_f64(x, Rounding::NearestEven),
                f.inf(sign),
                "{} {x:e}",
                f.name()
            );
            let toward_zero = if sign { Rounding::Up } else { Rounding::Down };
            assert_eq!(
                f.from_f64(x, toward_zero),
                f.max_finite(sign),
                "{} {x:e}",
                f.name()
            );
        }
    }
}

#[test]
fn comparisons_and_min_max_follow_ieee_on_specials_and_randoms() {
    let f = FloatFormat::FP16;
    let s = f.specials();
    for &a in &s {
        for &b in &s {
            let (x, y) = (f16::from_bits(a as u16), f16::from_bits(b as u16));
            assert_eq!(f.lt(a, b), x < y, "{a:#x} < {b:#x}");
            assert_eq!(f.le(a, b), x <= y, "{a:#x} <= {b:#x}");
            assert_eq!(f.eq(a, b), x == y, "{a:#x} == {b:#x}");
            let (mn, mx) = (f.min(a, b), f.max(a, b));
            if f.is_nan(a) || f.is_nan(b) {
                assert!(f.is_nan(mn) && f.is_nan(mx));
            } else {
                assert!(f.le(mn, a) && f.le(mn, b) && f.le(a, mx) && f.le(b, mx));
                assert!(mn == a || mn == b);
                assert!(mx == a || mx == b);
            }
        }
    }
}
