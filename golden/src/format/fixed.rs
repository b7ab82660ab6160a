//! The fixed-point format of the slab datapath and the outward quantisation that feeds it.
//!
//! # The grid
//! World coordinates map onto a signed `G`-bit integer grid: `q = x / 2^k - c`, with the cell size `2^k`
//! a power of two and the centre `c` an integer, both chosen by [`GridMap::for_bounds`] so that the scene
//! bounds fit. Power-of-two cells make every conversion an exact scaling, so quantisation can be exactly
//! floored or ceiled, and results convert back to world units without rounding.
//!
//! # The ray
//! The direction is scaled by an exact power of two `2^j` so that its largest component has magnitude in
//! `[1, 2)`. The ray parameter in grid units is then `t_g = t * 2^(-k-j)`, and every reported t code
//! converts back exactly: `t_world = code * 2^(k + j - FT)` ([`FixRay::t_exp`]).
//!
//! Following the conservativeness contract, the quantised ray is an *interval*:
//! - origin per axis: `[o_lo, o_hi] = [floor(o_g), ceil(o_g)]` (equal when the origin is on the grid);
//! - inverse direction magnitude per axis: `[m_lo, m_hi] = [floor, ceil](2^FI / |d_j|)`, an unsigned
//!   `I`-bit fixed-point number with `FI` fraction bits, plus a sign bit `neg`. The all-ones code
//!   [`FixFormat::inv_inf`] means "unbounded": `m_hi` is all-ones when the true value exceeds the
//!   largest finite code, and both are all-ones when the component is exactly zero;
//! - t range: `t_min` floored, `t_max` ceiled, as signed `T`-bit codes with `FT` fraction bits. The most
//!   negative code [`FixFormat::t_neg_inf`] means `-inf` and the most positive [`FixFormat::t_pos_inf`]
//!   means `+inf`. A `t_min` below the finite range becomes `-inf` and a `t_max` above it `+inf`: these
//!   widen the range, which is the conservative direction, and are the documented meaning of the codes.
//!
//! This is the reduced-precision idea of Keely, "Reduced Precision for Hardware Ray Tracing in GPUs"
//! (HPG 2014) and Vaidyanathan, Akenine-Möller and Salvi, "Watertight Ray Traversal with Reduced
//! Precision" (HPG 2016): quantise the box outward and carry the ray's quantisation error as an interval
//! so that the test stays conservative.
//!
//! # The box
//! `lo = floor(min_g)`, `hi = ceil(max_g)` (outward). A world box that is empty (`min > max` on an axis)
//! becomes the canonical empty box `lo = GMAX, hi = GMIN` on every axis, which the datapath rejects.
//! Any coordinate outside the grid is an error naming the coordinate.

use crate::error::Error;
use crate::exact::Ext;
use crate::geom::{Aabb, Ray};
use glam::DVec3;
use std::ops::RangeInclusive;

const AXES: [&str; 3] = ["x", "y", "z"];

/// The grid widths of the format ladder, [`FixFormat::grid`]: one format, and one RTL instance
/// (`rtl::SlabFixG6` .. `rtl::SlabFixG20`), per width.
pub const GRID_LADDER: RangeInclusive<u32> = 6..=20;

/// Widths of the fixed-point slab datapath. The RTL block takes the same numbers as const generics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FixFormat {
    /// Grid bits `G`: signed coordinates in `[-2^(G-1), 2^(G-1) - 1]`.
    pub g: u32,
    /// Inverse-direction bits `I` (unsigned magnitude).
    pub i: u32,
    /// Fraction bits `FI` of the inverse direction.
    pub fi: u32,
    /// t bits `T` (signed).
    pub t: u32,
    /// Fraction bits `FT` of t.
    pub ft: u32,
}

impl FixFormat {
    /// Checks the widths: `2 <= G <= 24`, `2 <= I <= 32`, `FI <= I`, `G + 2 <= T <= 32`,
    /// `FT <= min(FI, T - G - 2)` (t must span the grid diagonal), and the product `G + I + 1 <= 63`.
    pub fn new(g: u32, i: u32, fi: u32, t: u32, ft: u32) -> Result<Self, Error> {
        let bad = |param, value: u32, why: String| Error::BadFormat {
            param,
            value: value as i64,
            why,
        };
        if !(2..=24).contains(&g) {
            return Err(bad("G (grid bits)", g, "must be in 2..=24".into()));
        }
        if !(2..=32).contains(&i) {
            return Err(bad(
                "I (inverse-direction bits)",
                i,
                "must be in 2..=32".into(),
            ));
        }
        if fi > i {
            return Err(bad(
                "FI (inverse fraction bits)",
                fi,
                format!("must not exceed I = {i}"),
            ));
        }
        if t < g + 2 || t > 32 {
            return Err(bad(
                "T (t bits)",
                t,
                format!(
                    "must be in G+2..=32 = {}..=32 so that t spans the grid",
                    g + 2
                ),
            ));
        }
        if ft > t - g - 2 || ft > fi {
            return Err(bad(
                "FT (t fraction bits)",
                ft,
                format!("must not exceed T-G-2 = {} nor FI = {fi}", t - g - 2),
            ));
        }
        if g + i + 1 > 63 {
            return Err(bad(
                "I (inverse-direction bits)",
                i,
                format!("product width G+I+1 = {} exceeds 63", g + i + 1),
            ));
        }
        Ok(FixFormat { g, i, fi, t, ft })
    }

    /// 8-bit grid: `G=8, I=12, FI=8, T=14, FT=4`.
    pub fn b8() -> Self {
        Self::new(8, 12, 8, 14, 4).unwrap()
    }
    /// 12-bit grid: `G=12, I=16, FI=11, T=20, FT=6`.
    pub fn b12() -> Self {
        Self::new(12, 16, 11, 20, 6).unwrap()
    }
    /// 16-bit grid: `G=16, I=20, FI=14, T=24, FT=6`.
    pub fn b16() -> Self {
        Self::new(16, 20, 14, 24, 6).unwrap()
    }
    /// The named presets, smallest first.
    pub fn presets() -> [FixFormat; 3] {
        [Self::b8(), Self::b12(), Self::b16()]
    }

    /// The format of grid width `g` on the format ladder ([`GRID_LADDER`], `6..=20`): one format per grid
    /// width, so a fit can pick the smallest `G` that a scene needs and still have an RTL instance.
    ///
    /// The rule interpolates the three presets (`grid(8) == b8()`, `grid(12) == b12()`,
    /// `grid(16) == b16()`) and extends them to both sides:
    ///
    /// | width | rule | what it trades |
    /// | --- | --- | --- |
    /// | `I` | `G + 4` | the multiplier is `(G + 1) x I` bits and the product `G + I + 1 = 2G + 5` bits: area grows as `G^2` |
    /// | `FI` | `floor(3G / 4) + 2` | the inverse direction's fraction bits: its relative error, so the t slack at a distance of `d` cells is about `d * 2^-FI`. `I - FI = ceil(G / 4) + 2` integer bits remain: a direction component below `2^-(I-FI)` of the largest one is "unbounded" (that axis stops constraining t), so the integer part grows slowly with the grid, the fraction takes the rest |
    /// | `FT` | `clamp(floor(G / 2), 4, 6)` | t resolution, `2^-FT` (scaled) grid cells; 6 as in b12 and b16, since past it the product's own rounding dominates, and every bit costs width in the max/min trees and the outputs |
    /// | `T` | `G + 2 + FT` | the least `T` with `FT <= T - G - 2` (t spans the grid, [`FixFormat::new`]): the same integer span as all three presets, so `T` is between `G + 6` and `G + 8` |
    ///
    /// | G | 6 | 7 | 8 | 9 | 10 | 11 | 12 | 13 | 14 | 15 | 16 | 17 | 18 | 19 | 20 |
    /// |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|
    /// | I | 10 | 11 | 12 | 13 | 14 | 15 | 16 | 17 | 18 | 19 | 20 | 21 | 22 | 23 | 24 |
    /// | FI | 6 | 7 | 8 | 8 | 9 | 10 | 11 | 11 | 12 | 13 | 14 | 14 | 15 | 16 | 17 |
    /// | T | 12 | 13 | 14 | 15 | 17 | 18 | 20 | 21 | 22 | 23 | 24 | 25 | 26 | 27 | 28 |
    /// | FT | 4 | 4 | 4 | 4 | 5 | 5 | 6 | 6 | 6 | 6 | 6 | 6 | 6 | 6 | 6 |
    ///
    /// Below `G = 6` a 64-cell grid leaves little to test; above `G = 20` the product passes 45 bits and
    /// the rust-hdl simulation (which stores values over 32 bits bit by bit) slows down. A `g` outside the
    /// ladder is an [`Error::BadFormat`].
    pub fn grid(g: u32) -> Result<Self, Error> {
        if !GRID_LADDER.contains(&g) {
            return Err(Error::BadFormat {
                param: "G (grid bits)",
                value: g as i64,
                why: format!(
                    "the format ladder covers grid widths {}..={}",
                    GRID_LADDER.start(),
                    GRID_LADDER.end()
                ),
            });
        }
        let ft = (g / 2).clamp(4, 6);
        Self::new(g, g + 4, 3 * g / 4 + 2, g + 2 + ft, ft)
    }

    /// Every format of the ladder, smallest grid first (`grid(g)` for `g` in [`GRID_LADDER`]).
    pub fn ladder() -> Vec<Self> {
        GRID_LADDER
            .map(|g| Self::grid(g).expect("the ladder's formats are valid"))
            .collect()
    }

    /// Looks a preset up by name (`b8`, `b12`, `b16`), a ladder format by grid width (`g6` .. `g20`,
    /// [`FixFormat::grid`]) or parses `G,I,FI,T,FT`.
    pub fn parse(s: &str) -> Result<Self, Error> {
        match s {
            "b8" => return Ok(Self::b8()),
            "b12" => return Ok(Self::b12()),
            "b16" => return Ok(Self::b16()),
            _ => {}
        }
        if let Some(g) = s.strip_prefix('g').and_then(|g| g.parse::<u32>().ok()) {
            return Self::grid(g);
        }
        let parts: Vec<&str> = s.split(',').collect();
        let names = ["G", "I", "FI", "T", "FT"];
        if parts.len() != 5 {
            return Err(Error::Io(format!(
                "format `{s}`: expected b8, b12, b16, g6 .. g20 or five numbers G,I,FI,T,FT"
            )));
        }
        let mut v = [0u32; 5];
        for (n, p) in parts.iter().enumerate() {
            v[n] = p.trim().parse().map_err(|_| {
                Error::Io(format!(
                    "format `{s}`: {} = `{p}` is not a number",
                    names[n]
                ))
            })?;
        }
        Self::new(v[0], v[1], v[2], v[3], v[4])
    }

    /// Name used in Verilog module names and reports, e.g. `g16_i20f14_t24f6`.
    pub fn name(&self) -> String {
        format!(
            "g{}_i{}f{}_t{}f{}",
            self.g, self.i, self.fi, self.t, self.ft
        )
    }
    /// Smallest grid coordinate.
    pub fn gmin(&self) -> i64 {
        -(1i64 << (self.g - 1))
    }
    /// Largest grid coordinate.
    pub fn gmax(&self) -> i64 {
        (1i64 << (self.g - 1)) - 1
    }
    /// The all-ones inverse-direction code: unbounded.
    pub fn inv_inf(&self) -> u64 {
        (1u64 << self.i) - 1
    }
    /// The code that means `t = -inf`.
    pub fn t_neg_inf(&self) -> i64 {
        -(1i64 << (self.t - 1))
    }
    /// The code that means `t = +inf`.
    pub fn t_pos_inf(&self) -> i64 {
        (1i64 << (self.t - 1)) - 1
    }
    /// Right shift from product fraction bits to t fraction bits.
    pub fn shift(&self) -> u32 {
        self.fi - self.ft
    }
    /// Width of the signed product `e * m`.
    pub fn product_bits(&self) -> u32 {
        self.g + self.i + 1
    }
}

/// A quantised ray: origin interval, inverse-direction interval and sign, t range. See the module doc.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FixRay {
    pub o_lo: [i64; 3],
    pub o_hi: [i64; 3],
    pub m_lo: [u64; 3],
    pub m_hi: [u64; 3],
    pub neg: [bool; 3],
    pub t_min: i64,
    pub t_max: i64,
    /// World t of code `c` is `c * 2^t_exp` (not an input of the datapath).
    pub t_exp: i32,
}

/// A quantised box: `lo = floor(min)`, `hi = ceil(max)` on the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FixBox {
    pub lo: [i64; 3],
    pub hi: [i64; 3],
}

impl FixRay {
    /// A t code of this ray in world units, exactly (`-inf`/`+inf` for the two end codes).
    pub fn t_world(&self, fmt: &FixFormat, code: i64) -> Ext {
        if code == fmt.t_neg_inf() {
            Ext::NegInf
        } else if code == fmt.t_pos_inf() {
            Ext::PosInf
        } else {
            Ext::dyadic(code, self.t_exp)
        }
    }
    /// An entry code in world units as an f64, rounded down: never above the exact value, and the
    /// largest finite f64 (not `+inf`) when the exact value lies beyond it. Exact whenever f64 holds it.
    pub fn t_entry_f64(&self, fmt: &FixFormat, code: i64) -> f64 {
        self.t_f64(fmt, code, false)
    }

    /// An exit code in world units as an f64, rounded up: never below the exact value, and the most
    /// negative finite f64 (not `-inf`) when the exact value lies below it.
    pub fn t_exit_f64(&self, fmt: &FixFormat, code: i64) -> f64 {
        self.t_f64(fmt, code, true)
    }

    fn t_f64(&self, fmt: &FixFormat, code: i64, up: bool) -> f64 {
        if code == fmt.t_neg_inf() {
            return f64::NEG_INFINITY;
        }
        if code == fmt.t_pos_inf() {
            return f64::INFINITY;
        }
        // Exact when the product is zero or a normal f64 (t codes have fewer than 53 bits); otherwise
        // (overflow, or rounding among the subnormals) round the exact value outward.
        let x = ldexp(code as f64, self.t_exp);
        if code.unsigned_abs() < 1 << 53 && (x.is_normal() || code == 0) {
            return x;
        }
        let e = Ext::dyadic(code, self.t_exp);
        if up {
            e.up_f64()
        } else {
            e.down_f64()
        }
    }
}

/// The world-to-grid mapping of a scene for one format: `q = x / 2^k - c`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridMap {
    pub fmt: FixFormat,
    /// Cell size exponent: one grid unit is `2^k` world units.
    pub k: i32,
    /// Grid centre in cells.
    pub c: [i64; 3],
}

impl GridMap {
    /// The finest grid of `fmt` that holds the box `[lo, hi]` (finite, `lo <= hi`).
    pub fn for_bounds(fmt: FixFormat, lo: DVec3, hi: DVec3) -> Result<Self, Error> {
        for a in 0..3 {
            for (n, v) in [("min", lo[a]), ("max", hi[a])] {
                if !v.is_finite() {
                    return Err(Error::bad_value(
                        format!("scene bounds {n}.{}", AXES[a]),
                        v,
                        "scene bounds must be finite",
                    ));
                }
            }
            if lo[a] > hi[a] {
                return Err(Error::bad_value(
                    format!("scene bounds min.{}", AXES[a]),
                    lo[a],
                    "scene bounds must have min <= max",
                ));
            }
        }
        let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        // Start one step below the smallest plausible cell and grow until everything fits.
        let mut k = exponent(extent) - (fmt.g as i32 - 1) - 1;
        loop {
            let mut c = [0i64; 3];
            let mut fits = true;
            for a in 0..3 {
                let (fl, ch) = match (floor_pow2(lo[a], -k), ceil_pow2(hi[a], -k)) {
                    (Some(f), Some(c)) => (f, c),
                    _ => {
                        fits = false;
                        break;
                    }
                };
                // Centre of [fl, ch], as an integer.
                c[a] = fl + (ch - fl) / 2 - (fmt.gmax() + fmt.gmin()) / 2;
                if fl - c[a] < fmt.gmin() || ch - c[a] > fmt.gmax() {
                    fits = false;
                    break;
                }
            }
            if fits {
                return Ok(GridMap { fmt, k, c });
            }
            k += 1;
            if k > 1100 {
                return Err(Error::Io(
                    "scene bounds cannot be mapped onto the grid".into(),
                ));
            }
        }
    }

    /// World bounds covered by the grid (lowest and highest grid point).
    pub fn world_bounds(&self) -> (DVec3, DVec3) {
        let f = |q: i64, a: usize| ldexp((q + self.c[a]) as f64, self.k);
        (
            DVec3::new(
                f(self.fmt.gmin(), 0),
                f(self.fmt.gmin(), 1),
                f(self.fmt.gmin(), 2),
            ),
            DVec3::new(
                f(self.fmt.gmax(), 0),
                f(self.fmt.gmax(), 1),
                f(self.fmt.gmax(), 2),
            ),
        )
    }

    /// World coordinate of a grid coordinate (exact).
    pub fn to_world(&self, a: usize, q: i64) -> f64 {
        ldexp((q + self.c[a]) as f64, self.k)
    }

    fn coord(&self, what: &str, a: usize, x: f64, up: bool) -> Result<i64, Error> {
        let q = if up {
            ceil_pow2(x, -self.k)
        } else {
            floor_pow2(x, -self.k)
        }
        .map(|q| q - self.c[a]);
        match q {
            Some(q) if q >= self.fmt.gmin() && q <= self.fmt.gmax() => Ok(q),
            _ => {
                let (wl, wh) = self.world_bounds();
                Err(Error::DoesNotFit {
                    what: format!("{what}.{}", AXES[a]),
                    value: x,
                    why: format!(
                        "outside the {}-bit grid, which covers [{}, {}] on this axis",
                        self.fmt.g, wl[a], wh[a]
                    ),
                })
            }
        }
    }

    /// Quantises a box outward; the error names the coordinate that does not fit.
    pub fn quantize_box(&self, b: &Aabb) -> Result<FixBox, Error> {
        b.validate()?;
        if b.is_empty() {
            return Ok(FixBox {
                lo: [self.fmt.gmax(); 3],
                hi: [self.fmt.gmin(); 3],
            });
        }
        let mut out = FixBox::default();
        for a in 0..3 {
            out.lo[a] = self.coord("box min", a, b.min[a], false)?;
            out.hi[a] = self.coord("box max", a, b.max[a], true)?;
        }
        Ok(out)
    }

    /// Quantises a ray into origin and inverse-direction intervals; see the module doc.
    pub fn quantize_ray(&self, r: &Ray) -> Result<FixRay, Error> {
        r.validate()?;
        let fmt = &self.fmt;
        let mut out = FixRay::default();
        for a in 0..3 {
            out.o_lo[a] = self.coord("ray origin", a, r.origin[a], false)?;
            out.o_hi[a] = self.coord("ray origin", a, r.origin[a], true)?;
        }
        let j = dir_scale_exp(r.dir);
        for a in 0..3 {
            let d = r.dir[a];
            out.neg[a] = d.is_sign_negative();
            let (lo, hi) = inv_bounds(d, j, fmt);
            out.m_lo[a] = lo;
            out.m_hi[a] = hi;
        }
        // t_g = t * 2^(-k-j); code = t_g * 2^FT.
        let e = fmt.ft as i32 - self.k - j;
        let (ninf, pinf) = (fmt.t_neg_inf(), fmt.t_pos_inf());
        out.t_min = match floor_pow2(r.t_min, e) {
            _ if r.t_min == f64::NEG_INFINITY => ninf,
            Some(c) if c <= ninf => ninf,
            Some(c) if c >= pinf => pinf - 1,
            Some(c) => c,
            None if r.t_min < 0.0 => ninf,
            None => pinf - 1,
        };
        out.t_max = match ceil_pow2(r.t_max, e) {
            _ if r.t_max == f64::INFINITY => pinf,
            Some(c) if c >= pinf => pinf,
            Some(c) if c <= ninf => ninf + 1,
            Some(c) => c,
            None if r.t_max > 0.0 => pinf,
            None => ninf + 1,
        };
        out.t_exp = self.k + j - fmt.ft as i32;
        Ok(out)
    }
}

/// The exponent `j` of the exact scaling `2^j` that brings a direction's largest component into `[1, 2)`
/// (0 for the zero direction). Every datapath input derived from the direction uses the same `j`, so their
/// t codes share one unit.
pub fn dir_scale_exp(dir: DVec3) -> i32 {
    let dmax = dir.abs().max_element();
    if dmax == 0.0 {
        0
    } else {
        -exponent(dmax)
    }
}

/// `[floor, ceil](2^FI / |d * 2^j|)` as `I`-bit codes, with the all-ones code for "unbounded".
///
/// Exact: with `|d| = (M / 2^52) * 2^e` (`M` the 53-bit significand) the value is `2^(FI - j - e + 52) / M`,
/// an integer division.
fn inv_bounds(d: f64, j: i32, fmt: &FixFormat) -> (u64, u64) {
    let inf = fmt.inv_inf();
    if d == 0.0 {
        return (inf, inf);
    }
    let (m, e) = significand(d.abs());
    let s = fmt.fi as i32 - j - e; // value = 2^s / (m / 2^52), in (2^(s-1), 2^s]
    if s > fmt.i as i32 {
        // Larger than 2^I - 1 > largest finite code.
        return (inf - 1, inf);
    }
    debug_assert!(s >= 0, "|d * 2^j| < 2 keeps s >= FI >= 0");
    let num: u128 = 1u128 << (s + 52);
    let lo = (num / m as u128) as u64;
    let hi = lo + u64::from(!num.is_multiple_of(m as u128));
    (lo.min(inf - 1), if hi >= inf { inf } else { hi })
}

/// `(M, e)` with `x = (M / 2^52) * 2^e`, `M` in `[2^52, 2^53)`, for finite `x > 0` (subnormals included).
fn significand(x: f64) -> (u64, i32) {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    if biased == 0 {
        // Subnormal: normalise the fraction.
        let shift = frac.leading_zeros() as i32 - 11;
        (frac << shift, -1022 - shift)
    } else {
        (frac | (1u64 << 52), biased - 1023)
    }
}

/// `floor(log2(x))` for finite `x > 0`.
pub fn exponent(x: f64) -> i32 {
    significand(x).1
}

/// `x * 2^e`, exact whenever the result is a normal number or zero.
pub fn ldexp(mut x: f64, mut e: i32) -> f64 {
    while e > 1000 {
        x *= f64::from_bits(((1023 + 1000) as u64) << 52);
        e -= 1000;
    }
    while e < -1000 {
        x *= f64::from_bits(((1023 - 1000) as u64) << 52);
        e += 1000;
    }
    x * f64::from_bits(((1023 + e) as u64) << 52)
}

/// `floor(x * 2^e)` exactly, or `None` when it does not fit in 62 bits (or `x` is infinite).
pub fn floor_pow2(x: f64, e: i32) -> Option<i64> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some(0);
    }
    // Below 1 in magnitude the floor is 0 or -1 whatever the rounding of the scaling.
    if x.abs() < ldexp(1.0, -e) {
        return Some(if x > 0.0 { 0 } else { -1 });
    }
    let y = ldexp(x, e); // |y| >= 1: a normal number, so the scaling was exact
    if y.abs() >= (1u64 << 62) as f64 {
        return None;
    }
    Some(y.floor() as i64)
}

/// `ceil(x * 2^e)` exactly, or `None` when it does not fit.
pub fn ceil_pow2(x: f64, e: i32) -> Option<i64> {
    floor_pow2(-x, e).map(|v| -v)
}

/// Two's complement code of `v` in `n` bits.
pub fn code(v: i64, n: usize) -> u64 {
    (v as u64) & if n == 64 { u64::MAX } else { (1u64 << n) - 1 }
}

/// Sign-extends an `n`-bit two's complement code.
pub fn sext(v: u64, n: usize) -> i64 {
    ((v << (64 - n)) as i64) >> (64 - n)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// t codes whose world value lies beyond the f64 range, or among the subnormals, round outward: an
    /// entry never above the exact value (the largest finite f64, not `+inf`), an exit never below it.
    #[test]
    fn t_codes_convert_to_world_outward() {
        let fmt = FixFormat::b16();
        for (code, t_exp) in [
            (3, 1074),
            (-3, 1074),
            (5, -1076),
            (-5, -1076),
            (1, 1023),
            (7, -1080),
        ] {
            let r = FixRay {
                t_exp,
                ..FixRay::default()
            };
            let exact = r.t_world(&fmt, code);
            let (lo, hi) = (r.t_entry_f64(&fmt, code), r.t_exit_f64(&fmt, code));
            assert!(
                Ext::from_f64(lo) <= exact && exact <= Ext::from_f64(hi),
                "{code} 2^{t_exp}"
            );
            assert!(!lo.is_nan() && !hi.is_nan() && lo != f64::INFINITY && hi != f64::NEG_INFINITY);
            if lo.is_finite() && hi.is_finite() && lo != hi {
                assert_eq!(lo.next_up(), hi, "{code} 2^{t_exp}: the neighbouring f64s");
            }
        }
        let r = FixRay {
            t_exp: 1074,
            ..FixRay::default()
        };
        assert_eq!(r.t_entry_f64(&fmt, 3), f64::MAX);
        assert_eq!(r.t_exit_f64(&fmt, -3), -f64::MAX);
        assert_eq!(r.t_entry_f64(&fmt, fmt.t_pos_inf()), f64::INFINITY);
        assert_eq!(r.t_exit_f64(&fmt, fmt.t_neg_inf()), f64::NEG_INFINITY);
        let r = FixRay {
            t_exp: -2,
            ..FixRay::default()
        };
        assert_eq!(
            (r.t_entry_f64(&fmt, 5), r.t_exit_f64(&fmt, 5)),
            (1.25, 1.25)
        );
    }

    fn map(fmt: FixFormat) -> GridMap {
        GridMap::for_bounds(fmt, DVec3::splat(-100.0), DVec3::splat(100.0)).unwrap()
    }

    #[test]
    fn floor_and_ceil_are_exact_at_and_around_integers() {
        assert_eq!(floor_pow2(3.0, 0), Some(3));
        assert_eq!(ceil_pow2(3.0, 0), Some(3));
        assert_eq!(floor_pow2(-3.5, 0), Some(-4));
        assert_eq!(ceil_pow2(-3.5, 0), Some(-3));
        assert_eq!(floor_pow2(5e-324, 10), Some(0));
        assert_eq!(ceil_pow2(5e-324, 10), Some(1));
        assert_eq!(floor_pow2(-5e-324, -10), Some(-1));
        assert_eq!(floor_pow2(1.5, 1), Some(3));
        assert_eq!(floor_pow2(0.75, -1), Some(0));
        assert_eq!(floor_pow2(1e300, 0), None);
    }

    #[test]
    fn grid_holds_scene_bounds_and_no_coarser_than_needed() {
        for fmt in FixFormat::presets() {
            let m = map(fmt);
            let (wl, wh) = m.world_bounds();
            assert!(
                wl.max_element() <= -100.0 && wh.min_element() >= 100.0,
                "{m:?}"
            );
            // One step finer would not hold the 200-unit extent.
            let cells = 200.0 / ldexp(1.0, m.k - 1);
            assert!(cells > (fmt.gmax() - fmt.gmin()) as f64, "{m:?}");
        }
    }

    #[test]
    fn box_rounds_outward_and_empty_box_is_canonical() {
        let m = map(FixFormat::b8());
        let b = Aabb::new(DVec3::splat(0.3), DVec3::splat(0.7)).unwrap();
        let q = m.quantize_box(&b).unwrap();
        for a in 0..3 {
            assert!(m.to_world(a, q.lo[a]) <= 0.3 && m.to_world(a, q.hi[a]) >= 0.7);
        }
        let e = m
            .quantize_box(&Aabb::new(DVec3::ONE, DVec3::ZERO).unwrap())
            .unwrap();
        assert!(e.lo[0] > e.hi[0]);
    }

    #[test]
    fn out_of_grid_origin_is_an_error_naming_it() {
        let m = map(FixFormat::b8());
        let r = Ray::new(DVec3::new(0.0, 5000.0, 0.0), DVec3::X, 0.0, 1.0).unwrap();
        let e = m.quantize_ray(&r).unwrap_err().to_string();
        assert!(e.contains("ray origin.y") && e.contains("5000"), "{e}");
    }

    #[test]
    fn inverse_interval_brackets_the_true_inverse() {
        let fmt = FixFormat::b12();
        let m = map(fmt);
        let r = Ray::new(DVec3::ZERO, DVec3::new(1.0, 0.3, -1e-9), 0.0, 1.0).unwrap();
        let q = m.quantize_ray(&r).unwrap();
        let true_inv = ldexp(1.0, fmt.fi as i32) / 0.3;
        assert!((q.m_lo[1] as f64) <= true_inv && true_inv <= q.m_hi[1] as f64);
        assert_eq!(q.m_hi[1] - q.m_lo[1], 1);
        assert_eq!((q.m_lo[0], q.m_hi[0]), (1 << fmt.fi, 1 << fmt.fi));
        assert_eq!(q.m_hi[2], fmt.inv_inf());
        assert!(q.neg[2] && !q.neg[1]);
    }

    #[test]
    fn grid_ladder_matches_the_presets_and_validates() {
        assert_eq!(FixFormat::grid(8).unwrap(), FixFormat::b8());
        assert_eq!(FixFormat::grid(12).unwrap(), FixFormat::b12());
        assert_eq!(FixFormat::grid(16).unwrap(), FixFormat::b16());
        let ladder = FixFormat::ladder();
        assert_eq!(ladder.len(), GRID_LADDER.count());
        for (n, f) in ladder.iter().enumerate() {
            // Every format passes the constructor's checks and the documented rule.
            let g = f.g;
            assert_eq!(FixFormat::new(f.g, f.i, f.fi, f.t, f.ft).unwrap(), *f);
            assert_eq!(f.i, g + 4, "{}", f.name());
            assert!(f.t >= g + 6 && f.t <= g + 8, "{}", f.name());
            assert!(f.ft <= f.fi.min(f.t - g - 2), "{}", f.name());
            assert_eq!(FixFormat::parse(&format!("g{g}")).unwrap(), *f);
            if n > 0 {
                let p = ladder[n - 1];
                assert_eq!(g, p.g + 1);
                assert!(f.fi >= p.fi && f.ft >= p.ft && f.t > p.t, "{}", f.name());
            }
        }
        assert_eq!(ladder[0].name(), "g6_i10f6_t12f4");
        assert_eq!(ladder[ladder.len() - 1].name(), "g20_i24f17_t28f6");
    }

    #[test]
    fn grid_outside_the_ladder_is_an_error() {
        for g in [0, 2, 5, 21, 24, 100] {
            let e = FixFormat::grid(g).unwrap_err();
            assert!(matches!(e, Error::BadFormat { .. }), "{e:?}");
            assert!(e.to_string().contains("6..=20"), "{e}");
        }
        assert!(FixFormat::parse("g5").is_err());
        assert!(FixFormat::parse("g21").is_err());
    }

    #[test]
    fn format_widths_out_of_range_are_errors() {
        assert!(FixFormat::new(1, 12, 8, 14, 4).is_err());
        assert!(FixFormat::new(8, 12, 13, 14, 4).is_err());
        assert!(FixFormat::new(8, 12, 8, 9, 0).is_err());
        assert!(FixFormat::parse("8,12,8,14").is_err());
        assert_eq!(FixFormat::parse("8,12,8,14,4").unwrap(), FixFormat::b8());
    }
}
