//! Bit-accurate model of a binary floating-point format with `E` exponent bits and `M` fraction bits:
//! encode and decode, add and subtract, multiply, compare, minimum and maximum, under round-to-nearest-
//! even and the two directed modes.
//!
//! The layout and semantics are IEEE 754's binary formats (sign, biased exponent, fraction; exponent all
//! ones for infinities and NaN; exponent zero for zeros and subnormals), so E8M23 is binary32, E5M10 is
//! binary16 and E8M7 is bfloat16.
//!
//! **Subnormals are supported**, not flushed. Flushing a tiny result to zero would break the directed
//! modes' guarantee (a round-up of a tiny positive value must not give zero), so support is the choice
//! that keeps the datapath conservative, and it is what `half` and native `f32` do.
//!
//! Every result is the exact result rounded once (the operands are exact, the sum and product are formed
//! exactly in up to 64 bits, or with a sticky bit when the operands' exponents are more than 38 apart).
//! NaN results are the canonical quiet NaN (exponent all ones, fraction MSB set, sign clear).
//!
//! Directed rounding is the float datapath's tool for conservativeness: lower bounds
//! round toward -inf, upper bounds toward +inf.

use crate::error::Error;

/// A rounding mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rounding {
    /// Round to nearest, ties to even.
    NearestEven,
    /// Toward -inf.
    Down,
    /// Toward +inf.
    Up,
}

impl Rounding {
    pub const ALL: [Rounding; 3] = [Rounding::NearestEven, Rounding::Down, Rounding::Up];
}

/// A binary floating-point format; values are carried as the low `1 + E + M` bits of a `u32`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FloatFormat {
    /// Exponent bits `E`.
    pub e: u32,
    /// Fraction (stored mantissa) bits `M`.
    pub m: u32,
}

/// What a bit pattern is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    Zero,
    Subnormal,
    Normal,
    Inf,
    NaN,
}

impl FloatFormat {
    /// `2 <= E <= 8`, `1 <= M <= 23`: at most binary32, so every value is exactly an `f64` and every
    /// product of two significands fits in 48 bits.
    pub fn new(e: u32, m: u32) -> Result<Self, Error> {
        if !(2..=8).contains(&e) {
            return Err(Error::BadFormat {
                param: "E (exponent bits)",
                value: e as i64,
                why: "must be in 2..=8".into(),
            });
        }
        if !(1..=23).contains(&m) {
            return Err(Error::BadFormat {
                param: "M (fraction bits)",
                value: m as i64,
                why: "must be in 1..=23".into(),
            });
        }
        Ok(FloatFormat { e, m })
    }
    /// binary32.
    pub const FP32: FloatFormat = FloatFormat { e: 8, m: 23 };
    /// E8M15: binary32's range, 16 bits of precision.
    pub const E8M15: FloatFormat = FloatFormat { e: 8, m: 15 };
    /// bfloat16.
    pub const BF16: FloatFormat = FloatFormat { e: 8, m: 7 };
    /// binary16.
    pub const FP16: FloatFormat = FloatFormat { e: 5, m: 10 };
    /// An 8-bit format (E4M3 with IEEE infinities), small enough to test exhaustively.
    pub const E4M3: FloatFormat = FloatFormat { e: 4, m: 3 };

    /// The float format ladder: every format with an instantiated float slab tester
    /// (`rtl::SLAB_FLOAT_LADDER`), narrowest first (by total width `1 + E + M`, then by `E`), so a fit can
    /// take the first one that holds a scene's range and meets its precision.
    ///
    /// | E | M | widths | why |
    /// | --- | --- | --- | --- |
    /// | 5 | 3 ..= 10 | 9 ..= 16 | binary16's range (normal `2^-14 ..= 65504`): scenes of tens to thousands of units; every fraction width up to binary16 |
    /// | 6 | 3 ..= 10, 12, 15 | 10 ..= 17, 19, 22 | range `2^-30 ..= 2^32`, for scenes or t ranges beyond binary16's; 12 and 15 bridge to E8 |
    /// | 8 | 7, 10, 12, 15, 23 | 16 ..= 32 | binary32's range: bfloat16 up to binary32 (E8 with fewer than 7 fraction bits buys range nobody needs at that precision) |
    ///
    /// `E >= 5` and `M >= 3`: the RTL needs `E >= 4` (its working significand lives in the format's own
    /// width); E4 tops out at 240 with M = 3 (too little range for a scene in world units), and below
    /// `M = 3` a box is quantised to fewer than four steps per octave. It includes the five formats
    /// instantiated before the ladder: e8m23, e8m15, e8m7, e5m10, e6m5.
    pub const LADDER: [FloatFormat; 23] = [
        FloatFormat { e: 5, m: 3 },
        FloatFormat { e: 5, m: 4 },
        FloatFormat { e: 6, m: 3 },
        FloatFormat { e: 5, m: 5 },
        FloatFormat { e: 6, m: 4 },
        FloatFormat { e: 5, m: 6 },
        FloatFormat { e: 6, m: 5 },
        FloatFormat { e: 5, m: 7 },
        FloatFormat { e: 6, m: 6 },
        FloatFormat { e: 5, m: 8 },
        FloatFormat { e: 6, m: 7 },
        FloatFormat { e: 5, m: 9 },
        FloatFormat { e: 6, m: 8 },
        FloatFormat { e: 5, m: 10 },
        FloatFormat { e: 6, m: 9 },
        FloatFormat { e: 8, m: 7 },
        FloatFormat { e: 6, m: 10 },
        FloatFormat { e: 6, m: 12 },
        FloatFormat { e: 8, m: 10 },
        FloatFormat { e: 8, m: 12 },
        FloatFormat { e: 6, m: 15 },
        FloatFormat { e: 8, m: 15 },
        FloatFormat { e: 8, m: 23 },
    ];

    /// Parses `fp32`, `fp16`, `bf16` or `eXmY` (e.g. `e8m15`), case-insensitive.
    pub fn parse(s: &str) -> Result<Self, Error> {
        let l = s.to_ascii_lowercase();
        match l.as_str() {
            "fp32" => return Ok(Self::FP32),
            "fp16" => return Ok(Self::FP16),
            "bf16" => return Ok(Self::BF16),
            _ => {}
        }
        let bad = || {
            Error::Io(format!(
                "float format `{s}`: expected fp32, fp16, bf16 or eXmY such as e8m15"
            ))
        };
        let rest = l.strip_prefix('e').ok_or_else(bad)?;
        let (e, m) = rest.split_once('m').ok_or_else(bad)?;
        Self::new(e.parse().map_err(|_| bad())?, m.parse().map_err(|_| bad())?)
            .map_err(|e| Error::Io(format!("float format `{s}`: {e}")))
    }

    /// Name used in module names and reports, e.g. `e8m23`.
    pub fn name(&self) -> String {
        format!("e{}m{}", self.e, self.m)
    }
    /// Total width `1 + E + M`.
    pub fn width(&self) -> u32 {
        1 + self.e + self.m
    }
    /// Exponent bias `2^(E-1) - 1`.
    pub fn bias(&self) -> i32 {
        (1 << (self.e - 1)) - 1
    }
    /// Smallest normal exponent.
    pub fn emin(&self) -> i32 {
        1 - self.bias()
    }
    /// The all-ones biased exponent (infinities and NaNs).
    pub fn exp_all_ones(&self) -> u32 {
        (1 << self.e) - 1
    }
    /// Mask of all the format's bits.
    pub fn mask(&self) -> u32 {
        if self.width() == 32 {
            u32::MAX
        } else {
            (1 << self.width()) - 1
        }
    }
    /// The sign bit.
    pub fn sign_bit(&self) -> u32 {
        1 << (self.e + self.m)
    }
    /// Packs sign, biased exponent and fraction field.
    pub fn pack(&self, sign: bool, bexp: u32, frac: u32) -> u32 {
        (u32::from(sign) << (self.e + self.m)) | (bexp << self.m) | frac
    }
    /// Sign, biased exponent and fraction field.
    pub fn fields(&self, x: u32) -> (bool, u32, u32) {
        (
            x & self.sign_bit() != 0,
            (x >> self.m) & self.exp_all_ones(),
            x & ((1 << self.m) - 1),
        )
    }
    /// `+-0`.
    pub fn zero(&self, sign: bool) -> u32 {
        self.pack(sign, 0, 0)
    }
    /// `+-inf`.
    pub fn inf(&self, sign: bool) -> u32 {
        self.pack(sign, self.exp_all_ones(), 0)
    }
    /// The canonical quiet NaN.
    pub fn nan(&self) -> u32 {
        self.pack(false, self.exp_all_ones(), 1 << (self.m - 1))
    }
    /// The largest finite magnitude, with a sign.
    pub fn max_finite(&self, sign: bool) -> u32 {
        self.pack(sign, self.exp_all_ones() - 1, (1 << self.m) - 1)
    }
    /// Classifies a bit pattern.
    pub fn class(&self, x: u32) -> Class {
        let (_, e, f) = self.fields(x);
        match (e, f) {
            (0, 0) => Class::Zero,
            (0, _) => Class::Subnormal,
            (e, 0) if e == self.exp_all_ones() => Class::Inf,
            (e, _) if e == self.exp_all_ones() => Class::NaN,
            _ => Class::Normal,
        }
    }
    #[inline]
    pub fn is_nan(&self, x: u32) -> bool {
        x & !self.sign_bit() > self.inf(false)
    }
    /// Sign bit set.
    pub fn is_negative(&self, x: u32) -> bool {
        x & self.sign_bit() != 0
    }

    /// `(sign, significand, exponent)` of a finite value: `value = +-sig * 2^exp`.
    pub fn decode(&self, x: u32) -> (bool, u64, i32) {
        let (s, e, f) = self.fields(x);
        if e == 0 {
            (s, f as u64, self.emin() - self.m as i32)
        } else {
            (
                s,
                (f | (1 << self.m)) as u64,
                e as i32 - self.bias() - self.m as i32,
            )
        }
    }

    /// The exact value as an f64 (every value of these formats is one).
    pub fn to_f64(&self, x: u32) -> f64 {
        match self.class(x) {
            Class::NaN => f64::NAN,
            Class::Inf => {
                if self.is_negative(x) {
                    f64::NEG_INFINITY
                } else {
                    f64::INFINITY
                }
            }
            _ => {
                let (s, sig, e) = self.decode(x);
                let v = crate::format::fixed::ldexp(sig as f64, e);
                if s {
                    -v
                } else {
                    v
                }
            }
        }
    }

    /// Rounds `+-(sig + d) * 2^exp` into the format, where `d` is 0 when `!sticky` and strictly between
    /// 0 and 1 otherwise. A sticky value must come with at least two bits below the result's last place.
    /// `sig == 0 && !sticky` is not allowed here (exact zeros have their own sign rules).
    #[inline]
    fn round_pack(&self, sign: bool, sig: u64, exp: i32, sticky: bool, mode: Rounding) -> u32 {
        debug_assert!(sig != 0 || sticky);
        let m = self.m as i32;
        let nb = 64 - sig.leading_zeros() as i32; // bit length (0 when sig == 0)
        let lead = exp + nb - 1;
        let q = (lead - m).max(self.emin() - m); // exponent of the result's last place
        let shift = q - exp;
        let (mut kept, above_half, at_half, inexact) = if shift <= 0 {
            debug_assert!(!sticky, "a sticky value needs guard bits");
            (sig << (-shift) as u32, false, false, false)
        } else if shift > nb {
            // Everything is below half of the last place.
            (0, false, false, true)
        } else {
            let s = shift as u32;
            let rem = sig & ((1u64 << s) - 1);
            let half = 1u64 << (s - 1);
            (
                sig >> s,
                rem > half || (rem == half && sticky),
                rem == half && !sticky,
                rem != 0 || sticky,
            )
        };
        let up = match mode {
            Rounding::NearestEven => above_half || (at_half && kept & 1 == 1),
            Rounding::Down => sign && inexact,
            Rounding::Up => !sign && inexact,
        };
        let mut q = q;
        kept += u64::from(up);
        if kept == 1u64 << (m + 1) {
            kept >>= 1;
            q += 1;
        }
        if kept >= 1u64 << m {
            let bexp = q + m + self.bias();
            if bexp >= self.exp_all_ones() as i32 {
                return self.overflow(sign, mode);
            }
            self.pack(sign, bexp as u32, (kept - (1u64 << m)) as u32)
        } else {
            self.pack(sign, 0, kept as u32)
        }
    }

    fn overflow(&self, sign: bool, mode: Rounding) -> u32 {
        match (mode, sign) {
            (Rounding::NearestEven, s) => self.inf(s),
            (Rounding::Down, false) | (Rounding::Up, true) => self.max_finite(sign),
            (Rounding::Down, true) | (Rounding::Up, false) => self.inf(sign),
        }
    }

    /// Rounds an f64 into the format (NaN gives the canonical NaN).
    pub fn from_f64(&self, x: f64, mode: Rounding) -> u32 {
        if x.is_nan() {
            return self.nan();
        }
        if x.is_infinite() {
            return self.inf(x < 0.0);
        }
        if x == 0.0 {
            return self.zero(x.is_sign_negative());
        }
        let bits = x.to_bits();
        let bexp = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1u64 << 52) - 1);
        let (sig, exp) = if bexp == 0 {
            (frac, -1074)
        } else {
            (frac | (1 << 52), bexp - 1075)
        };
        // Two guard bits make a sticky-free, exact input acceptable to round_pack.
        self.round_pack(x < 0.0, sig << 2, exp - 2, false, mode)
    }

    /// True when both operands are finite and nonzero (the hot path of add and mul).
    #[inline(always)]
    fn both_ordinary(&self, a: u32, b: u32) -> bool {
        let (s, inf) = (self.sign_bit(), self.inf(false));
        let (ma, mb) = (a & !s, b & !s);
        ma != 0 && mb != 0 && ma < inf && mb < inf
    }

    /// `a + b`, rounded.
    #[inline]
    pub fn add(&self, a: u32, b: u32, mode: Rounding) -> u32 {
        if self.both_ordinary(a, b) {
            self.add_ordinary(a, b, mode)
        } else {
            self.add_special(a, b, mode)
        }
    }

    #[cold]
    fn add_special(&self, a: u32, b: u32, mode: Rounding) -> u32 {
        let (ca, cb) = (self.class(a), self.class(b));
        let (sa, sb) = (self.is_negative(a), self.is_negative(b));
        match (ca, cb) {
            (Class::NaN, _) | (_, Class::NaN) => self.nan(),
            (Class::Inf, Class::Inf) if sa == sb => a,
            (Class::Inf, Class::Inf) => self.nan(),
            (Class::Inf, _) => a,
            (_, Class::Inf) => b,
            (Class::Zero, Class::Zero) if sa == sb => a,
            (Class::Zero, Class::Zero) => self.zero(mode == Rounding::Down),
            (Class::Zero, _) => b,
            (_, Class::Zero) => a,
            _ => unreachable!("add_special with two ordinary operands"),
        }
    }

    fn add_ordinary(&self, a: u32, b: u32, mode: Rounding) -> u32 {
        let (sa, siga, ea) = self.decode(a);
        let (sb, sigb, eb) = self.decode(b);
        // Make `x` the operand with the larger exponent.
        let ((sx, sigx, ex), (sy, sigy, ey)) = if ea >= eb {
            ((sa, siga, ea), (sb, sigb, eb))
        } else {
            ((sb, sigb, eb), (sa, siga, ea))
        };
        let d = ex - ey;
        // Up to 38 the exact sum fits 64 bits (24 + 38 bits); beyond, y is below x's last place by more
        // than the M + 5 bits the sticky shortcut needs.
        if d <= 38 {
            let x = sigx << d as u32;
            let y = sigy;
            if sx == sy {
                self.round_pack(sx, x + y, ey, false, mode)
            } else if x == y {
                self.zero(mode == Rounding::Down)
            } else if x > y {
                self.round_pack(sx, x - y, ey, false, mode)
            } else {
                self.round_pack(sy, y - x, ey, false, mode)
            }
        } else {
            // |y| < 2^(ex - 14) is far below x's last place: it only decides rounding, as a sticky bit.
            let x = sigx << 3;
            let sig = if sx == sy { x } else { x - 1 };
            self.round_pack(sx, sig, ex - 3, true, mode)
        }
    }

    /// `a - b`, rounded.
    pub fn sub(&self, a: u32, b: u32, mode: Rounding) -> u32 {
        let nb = if self.is_nan(b) {
            b
        } else {
            b ^ self.sign_bit()
        };
        self.add(a, nb, mode)
    }

    /// `a * b`, rounded.
    #[inline]
    pub fn mul(&self, a: u32, b: u32, mode: Rounding) -> u32 {
        let sign = self.is_negative(a) != self.is_negative(b);
        if !self.both_ordinary(a, b) {
            return self.mul_special(a, b, sign);
        }
        let (_, siga, ea) = self.decode(a);
        let (_, sigb, eb) = self.decode(b);
        self.round_pack(sign, siga * sigb, ea + eb, false, mode)
    }

    /// Sign-magnitude order of two non-NaN patterns: the comparator of the hardware.
    #[inline]
    fn order(&self, a: u32, b: u32) -> std::cmp::Ordering {
        use std::cmp::Ordering::*;
        let s = self.sign_bit();
        let (ma, mb) = (a & !s, b & !s);
        if ma == 0 && mb == 0 {
            return Equal; // -0 == +0
        }
        match (a & s != 0, b & s != 0) {
            (false, false) => ma.cmp(&mb),
            (true, true) => mb.cmp(&ma),
            (true, false) => Less,
            (false, true) => Greater,
        }
    }
    #[cold]
    fn mul_special(&self, a: u32, b: u32, sign: bool) -> u32 {
        match (self.class(a), self.class(b)) {
            (Class::NaN, _) | (_, Class::NaN) => self.nan(),
            (Class::Inf, Class::Zero) | (Class::Zero, Class::Inf) => self.nan(),
            (Class::Inf, _) | (_, Class::Inf) => self.inf(sign),
            _ => self.zero(sign),
        }
    }

    /// `a < b` (false when either is NaN; `-0 == +0`).
    #[inline]
    pub fn lt(&self, a: u32, b: u32) -> bool {
        !self.is_nan(a) && !self.is_nan(b) && self.order(a, b).is_lt()
    }
    /// `a <= b` (false when either is NaN).
    #[inline]
    pub fn le(&self, a: u32, b: u32) -> bool {
        !self.is_nan(a) && !self.is_nan(b) && self.order(a, b).is_le()
    }
    /// `a == b` as numbers (false when either is NaN; `-0 == +0`).
    #[inline]
    pub fn eq(&self, a: u32, b: u32) -> bool {
        !self.is_nan(a) && !self.is_nan(b) && self.order(a, b).is_eq()
    }

    /// IEEE 754-2019 `minimum`: NaN if either is NaN, `-0` below `+0`.
    pub fn min(&self, a: u32, b: u32) -> u32 {
        if self.is_nan(a) || self.is_nan(b) {
            return self.nan();
        }
        if self.lt(a, b) || (self.eq(a, b) && self.is_negative(a)) {
            a
        } else {
            b
        }
    }

    /// IEEE 754-2019 `maximum`: NaN if either is NaN, `+0` above `-0`.
    pub fn max(&self, a: u32, b: u32) -> u32 {
        if self.is_nan(a) || self.is_nan(b) {
            return self.nan();
        }
        if self.lt(b, a) || (self.eq(a, b) && !self.is_negative(a)) {
            a
        } else {
            b
        }
    }

    /// The next value toward +inf (NaN and +inf unchanged; `-0` and `+0` both step to the smallest
    /// positive subnormal).
    pub fn next_up(&self, x: u32) -> u32 {
        match self.class(x) {
            Class::NaN => x,
            Class::Inf if !self.is_negative(x) => x,
            Class::Zero => 1,
            _ if self.is_negative(x) => {
                let y = x - 1;
                if y == self.sign_bit() {
                    self.zero(true)
                } else {
                    y
                }
            }
            _ => x + 1,
        }
    }

    /// The next value toward -inf.
    pub fn next_down(&self, x: u32) -> u32 {
        let neg = |v: u32| {
            if self.is_nan(v) {
                v
            } else {
                v ^ self.sign_bit()
            }
        };
        neg(self.next_up(neg(x)))
    }

    /// Special values worth testing in every operation: zeros, smallest and largest subnormals and
    /// normals, one, infinities, NaN, and their neighbours.
    pub fn specials(&self) -> Vec<u32> {
        let mut v = vec![];
        let one = self.from_f64(1.0, Rounding::NearestEven);
        for s in [false, true] {
            let sb = if s { self.sign_bit() } else { 0 };
            let min_normal = 1u32 << self.m;
            for x in [
                0,
                1,
                2,
                min_normal - 1,
                min_normal,
                min_normal + 1,
                one,
                one + 1,
                one - 1,
            ] {
                v.push(sb | x);
            }
            v.push(self.max_finite(s));
            v.push(self.max_finite(s) - 1);
            v.push(self.inf(s));
        }
        v.push(self.nan());
        v.push(self.nan() | 1);
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A name that reads as a format but has a parameter out of range is an error naming the input, as a
    /// name that does not read as one is.
    #[test]
    fn a_bad_format_name_is_an_error_naming_it() {
        for (s, why) in [
            ("e9m99", "exponent bits"),
            ("e5m30", "fraction bits"),
            ("xyz", "expected"),
        ] {
            let e = FloatFormat::parse(s).unwrap_err().to_string();
            assert!(e.contains(&format!("`{s}`")) && e.contains(why), "{s}: {e}");
        }
    }

    #[test]
    fn ladder_is_valid_sorted_and_holds_the_instantiated_formats() {
        let l = FloatFormat::LADDER;
        for f in l {
            assert_eq!(FloatFormat::new(f.e, f.m).unwrap(), f);
            assert_eq!(FloatFormat::parse(&f.name()).unwrap(), f);
            assert!(f.e >= 5 && f.m >= 3, "{}", f.name());
        }
        for w in l.windows(2) {
            assert!(
                (w[0].width(), w[0].e) < (w[1].width(), w[1].e),
                "{} before {}",
                w[0].name(),
                w[1].name()
            );
        }
        for f in [
            FloatFormat::FP32,
            FloatFormat::E8M15,
            FloatFormat::BF16,
            FloatFormat::FP16,
            FloatFormat { e: 6, m: 5 },
        ] {
            assert!(l.contains(&f), "{}", f.name());
        }
        for e in [5, 6] {
            for m in 3..=10 {
                assert!(l.contains(&FloatFormat { e, m }), "e{e}m{m}");
            }
        }
    }

    /// The float slab model works in every ladder format: a box ahead of the ray is hit with an interval
    /// enclosing the exact one, a box beside it is missed, and the whole datapath is conservative.
    #[test]
    fn slab_model_works_in_every_ladder_format() {
        use crate::exact::slab_exact;
        use crate::geom::{Aabb, Ray};
        use crate::slab::float::{judge_float, quantize_box, quantize_ray, slab_float};
        use glam::DVec3;
        let r = Ray::new(
            DVec3::new(-3.3, 0.7, 1.1),
            DVec3::new(1.0, 0.05, -0.1),
            0.0,
            f64::INFINITY,
        )
        .unwrap();
        let ahead = Aabb::new(DVec3::new(10.0, 0.0, -1.0), DVec3::new(12.5, 2.0, 1.0)).unwrap();
        let beside = Aabb::new(DVec3::new(10.0, 5.0, -1.0), DVec3::new(12.5, 7.0, 1.0)).unwrap();
        for f in FloatFormat::LADDER {
            let fr = quantize_ray(&f, &r).unwrap();
            for (b, hit) in [(ahead, true), (beside, false)] {
                let out = slab_float(&f, &fr, &quantize_box(&f, &b).unwrap());
                assert_eq!(out.hit, hit, "{} {out:?}", f.name());
                let v = judge_float(&f, &out, &slab_exact(&r, &b));
                assert!(
                    !matches!(v, crate::slab::check::Verdict::Violation(_)),
                    "{}: {v:?}",
                    f.name()
                );
                if hit {
                    let (t0, t1) = (f.to_f64(out.t_entry), f.to_f64(out.t_exit));
                    assert!(
                        t0 <= 13.3 && t1 >= 14.3 && t0 > 10.0 && t1 < 20.0,
                        "{}: [{t0}, {t1}]",
                        f.name()
                    );
                }
            }
        }
    }

    #[test]
    fn fp32_layout_matches_native_f32() {
        let f = FloatFormat::FP32;
        for x in [
            0.0f32,
            -0.0,
            1.0,
            -2.5,
            1e-45,
            3.4e38,
            f32::INFINITY,
            f32::MIN_POSITIVE,
        ] {
            assert_eq!(
                f.from_f64(x as f64, Rounding::NearestEven),
                x.to_bits(),
                "{x}"
            );
            assert_eq!(f.to_f64(x.to_bits()), x as f64);
        }
    }

    #[test]
    fn directed_rounding_brackets_an_inexact_value() {
        let f = FloatFormat::FP16;
        let d = f.from_f64(0.1, Rounding::Down);
        let u = f.from_f64(0.1, Rounding::Up);
        assert!(f.to_f64(d) < 0.1 && 0.1 < f.to_f64(u));
        assert_eq!(f.next_up(d), u);
    }

    #[test]
    fn overflow_saturates_toward_zero_in_the_mode_that_points_there() {
        let f = FloatFormat::FP16;
        let max = f.max_finite(false);
        assert_eq!(f.add(max, max, Rounding::NearestEven), f.inf(false));
        assert_eq!(f.add(max, max, Rounding::Down), max);
        assert_eq!(f.add(max, max, Rounding::Up), f.inf(false));
        let nmax = f.max_finite(true);
        assert_eq!(f.add(nmax, nmax, Rounding::Up), nmax);
    }

    #[test]
    fn exact_cancellation_gives_minus_zero_only_rounding_down() {
        let f = FloatFormat::BF16;
        let one = f.from_f64(1.0, Rounding::NearestEven);
        assert_eq!(f.sub(one, one, Rounding::NearestEven), f.zero(false));
        assert_eq!(f.sub(one, one, Rounding::Down), f.zero(true));
    }

    #[test]
    fn tiny_addend_far_below_last_place_still_moves_directed_results() {
        let f = FloatFormat::FP32;
        let one = f.from_f64(1.0, Rounding::NearestEven);
        let tiny = 1; // smallest subnormal, 2^-149
        assert_eq!(f.add(one, tiny, Rounding::NearestEven), one);
        assert_eq!(f.add(one, tiny, Rounding::Up), one + 1);
        assert_eq!(f.sub(one, tiny, Rounding::Down), f.next_down(one));
    }

    #[test]
    fn minimum_and_maximum_order_signed_zeros() {
        let f = FloatFormat::FP16;
        assert_eq!(f.min(f.zero(false), f.zero(true)), f.zero(true));
        assert_eq!(f.max(f.zero(true), f.zero(false)), f.zero(false));
        assert!(f.is_nan(f.min(f.nan(), f.zero(false))));
    }
}
