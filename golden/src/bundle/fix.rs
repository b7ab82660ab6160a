//! Bit-accurate model of the fixed-point AllHit / AnyHit bundle datapath (the pair of edge testers of
//! US 11,308,683; the logic, its proof and the patent's figures are in [`crate::bundle::edge`]).
//!
//! # Inputs
//! On the slab tester's grid ([`crate::format::fixed`]): the origin box rounded outward (`o_lo = floor`,
//! `o_hi = ceil`), the box as a [`BoxPair`] (`inner` rounded inward for AllHit, `outer` outward for AnyHit;
//! equal for a box on the grid), and the direction box scaled by the exact power of two `2^j` that brings
//! its largest magnitude into `[1, 2)`, as `D = FD + 3`-bit signed codes with `FD` fraction bits, rounded
//! outward (`d_lo = floor`, `d_hi = ceil`). `t_max` is a t code of the slab format (`T` bits, `FT` fraction
//! bits, in the unit of the scaled direction): `t_lo` floored for AllHit, `t_hi` ceiled for AnyHit, the
//! all-ones-positive code [`FixFormat::t_pos_inf`] meaning `+inf`. Every rounding makes the bundle a
//! superset of the world bundle (or, for the inner box and `t_lo`, a subset of what must be hit), so both
//! answers stay sound.
//!
//! # The datapath (one pipeline per test, the same structure with the bounds swapped)
//! ```text
//! stage 1  per axis, 4 subtractions (G+1 bits):  lo - o_e, hi - o_x, o_x - hi, o_e - lo
//!          sign class of [d_lo, d_hi] (positive / negative / straddling) -> mux e, x, u_lo, u_hi
//! stage 2  6 edges:    e_a * u_b  and  x_b * u_a        12 products, (G+1) x (FD+3) -> G+FD+4 bits
//!          3 distances: t * u_a (T x (FD+3) -> T+FD+3 bits)  against  e_a * 2^(FD+FT) (a shift)
//! stage 3  6 edge compares, 3 distance compares, 3 sign checks of x, 3 box checks lo <= hi; AND
//! ```
//! Products are full width and exact: the fixed datapath makes no rounding at all after quantisation, so
//! it computes exactly what [`crate::bundle::edge::ExactArith`] computes on the same integers (a bundle of one
//! ray with inputs on the grid gets the exact answer, and so does AllHit for any on-grid bundle that does
//! not straddle an axis). With the preset `FD = G - 2` both multiplier operands are `G + 1` bits, so one
//! square signed multiplier width serves all twelve edge products (`2G + 2` bits, 34 for `b16`); the
//! three distance products are the only other width (`T + G + 1` bits, 41 for `b16`).
//!
//! `t * u` with the `+inf` code is `+inf` for `u > 0` and 0 for `u = 0` (the origin must then lie in the
//! slab), as in the proof's convention.

use crate::bundle::edge::{
    conditions_hold, BoundArith, BoxArrays, BoxPair, Bundle, BundleOf, Test,
};
use crate::error::Error;
use crate::exact::{dyadic, Ext};
use crate::format::fixed::{ceil_pow2, dir_scale_exp, floor_pow2, FixBox, FixFormat, GridMap};
use crate::geom::Aabb;
use glam::DVec3;
use num_bigint::BigInt;
use num_rational::BigRational;

const AXES: [&str; 3] = ["x", "y", "z"];

/// Widths of the fixed-point bundle datapath: the slab format plus the direction's fraction bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BundleFixFormat {
    pub base: FixFormat,
    /// Direction fraction bits `FD`; directions are `D = FD + 3` bits signed.
    pub fd: u32,
}

impl BundleFixFormat {
    /// Checks `1 <= FD <= 30` and that both product widths fit 63 bits.
    pub fn new(base: FixFormat, fd: u32) -> Result<Self, Error> {
        let f = BundleFixFormat { base, fd };
        let why = if !(1..=30).contains(&fd) {
            Some("must be in 1..=30".to_string())
        } else if f.edge_product_bits() > 63 || f.dist_product_bits() > 63 {
            Some(format!(
                "products of {} and {} bits exceed 63",
                f.edge_product_bits(),
                f.dist_product_bits()
            ))
        } else {
            None
        };
        match why {
            Some(why) => Err(Error::BadFormat {
                param: "FD (direction fraction bits)",
                value: fd as i64,
                why,
            }),
            None => Ok(f),
        }
    }

    /// The preset over a slab format: `FD = G - 2` (at least 1), so directions and differences are both
    /// `G + 1` bits wide.
    pub fn over(base: FixFormat) -> Result<Self, Error> {
        Self::new(base, base.g.saturating_sub(2).max(1))
    }

    /// The presets over [`FixFormat::presets`].
    pub fn presets() -> [BundleFixFormat; 3] {
        FixFormat::presets().map(|b| Self::over(b).expect("the presets fit"))
    }

    /// Parses a slab format (`b16`, or `G,I,FI,T,FT`), optionally followed by `,FD`.
    pub fn parse(s: &str) -> Result<Self, Error> {
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        let (base, fd) = match parts.len() {
            1 | 5 => (parts.join(","), None),
            2 | 6 => (parts[..parts.len() - 1].join(","), parts.last().copied()),
            _ => {
                return Err(Error::Io(format!(
                    "bundle format `{s}`: expected b8, b12, b16 or G,I,FI,T,FT, optionally followed by ,FD"
                )))
            }
        };
        let base = FixFormat::parse(&base)?;
        match fd {
            None => Self::over(base),
            Some(v) => Self::new(
                base,
                v.parse().map_err(|_| {
                    Error::Io(format!("bundle format `{s}`: FD = `{v}` is not a number"))
                })?,
            ),
        }
    }

    /// Name for module names and reports, e.g. `g16_i20f14_t24f6_d14`.
    pub fn name(&self) -> String {
        format!("{}_d{}", self.base.name(), self.fd)
    }
    /// Bits of a difference `e`, `x` (signed): `G + 1`.
    pub fn diff_bits(&self) -> u32 {
        self.base.g + 1
    }
    /// Bits of a direction code (signed): `FD + 3` (a magnitude reaches `2^(FD+1)`).
    pub fn dir_bits(&self) -> u32 {
        self.fd + 3
    }
    /// Bits of an edge product (signed): `G + FD + 4`.
    pub fn edge_product_bits(&self) -> u32 {
        self.diff_bits() + self.dir_bits()
    }
    /// Bits of a distance product `t * u` (signed), and of the compare it feeds: `T + FD + 3`.
    pub fn dist_product_bits(&self) -> u32 {
        self.base.t + self.dir_bits()
    }
    /// The left shift that brings a difference to the scale of `t * u`: `FD + FT`.
    pub fn dist_shift(&self) -> u32 {
        self.fd + self.base.ft
    }
}

/// A quantised bundle: grid coordinates, direction codes, t codes (see the module doc).
pub type FixBundle = BundleOf<i64, i64>;

/// The fixed-point arithmetic: exact integers, products at full width.
#[derive(Clone, Copy, Debug)]
pub struct FixArith(pub BundleFixFormat);

impl BoundArith for FixArith {
    type V = i64;
    type T = i64;
    type P = i128;
    fn sub(&self, a: &i64, b: &i64, _up: bool) -> i64 {
        a - b
    }
    fn mul(&self, v: &i64, u: &i64, _up: bool) -> i64 {
        v * u
    }
    fn le(&self, a: &i64, b: &i64) -> bool {
        a <= b
    }
    fn is_neg(&self, a: &i64) -> bool {
        *a < 0
    }
    fn neg(&self, a: &i64) -> i64 {
        -a
    }
    fn zero(&self) -> i64 {
        0
    }
    fn t_is_neg(&self, t: &i64) -> bool {
        *t < 0
    }
    fn t_mul(&self, t: &i64, u: &i64, _up: bool) -> i128 {
        let fmt = &self.0.base;
        if *u == 0 {
            0
        } else if *t == fmt.t_pos_inf() {
            i128::MAX
        } else if *t == fmt.t_neg_inf() {
            i128::MIN
        } else {
            *t as i128 * *u as i128
        }
    }
    fn lift(&self, v: &i64) -> i128 {
        (*v as i128) << self.0.dist_shift()
    }
    fn le_p(&self, a: &i128, b: &i128) -> bool {
        a <= b
    }
}

/// AllHit on the fixed datapath: `true` means every ray of the bundle hits the (inner) box.
pub fn all_hit_fix(bf: &BundleFixFormat, b: &FixBundle, inner: &FixBox) -> bool {
    conditions_hold(&FixArith(*bf), b, None, &inner.lo, &inner.hi, Test::AllHit)
}

/// AnyHit on the fixed datapath: `true` means every ray of the bundle misses the (outer) box.
pub fn all_miss_fix(bf: &BundleFixFormat, b: &FixBundle, outer: &FixBox) -> bool {
    !conditions_hold(&FixArith(*bf), b, None, &outer.lo, &outer.hi, Test::AnyHit)
}

/// Quantises a world bundle and box and runs both tests: `(all_hit, all_miss)` on the fixed datapath.
pub fn decide_fix(
    bf: &BundleFixFormat,
    map: &GridMap,
    b: &Bundle,
    bx: &Aabb,
) -> Result<(bool, bool), Error> {
    decide_fix_quantised(bf, map, &quantize_bundle(bf, map, b)?, bx)
}

/// Both tests of a bundle already on the datapath's codes against a world box quantised onto `map`.
pub fn decide_fix_quantised(
    bf: &BundleFixFormat,
    map: &GridMap,
    q: &FixBundle,
    bx: &Aabb,
) -> Result<(bool, bool), Error> {
    let p = quantize_box_pair(map, bx)?;
    Ok((all_hit_fix(bf, q, &p.inner), all_miss_fix(bf, q, &p.outer)))
}

/// Renames the subject of a quantisation error (the slab quantiser says "box").
pub(crate) fn rename_error(e: Error, from: &str, to: &str) -> Error {
    match e {
        Error::DoesNotFit { what, value, why } => Error::DoesNotFit {
            what: what.replacen(from, to, 1),
            value,
            why,
        },
        Error::BadValue { what, value, why } => Error::BadValue {
            what: what.replacen(from, to, 1),
            value,
            why,
        },
        e => e,
    }
}

/// The origin box of a bundle as an [`Aabb`] (for the box quantisers, which round it outward).
pub(crate) fn origin_box(b: &Bundle) -> Aabb {
    Aabb {
        min: DVec3::from(b.o_lo),
        max: DVec3::from(b.o_hi),
    }
}

/// The exponent `j` of the bundle's direction scaling `2^j` (see [`dir_scale_exp`]).
pub fn bundle_dir_exp(b: &Bundle) -> i32 {
    dir_scale_exp(DVec3::from(b.d_lo).abs().max(DVec3::from(b.d_hi).abs()))
}

/// Quantises a world bundle onto `map`'s grid for the format `bf` (see the module doc). Errors name the
/// bad input: an invalid bundle, an origin off the grid, a grid of another format.
pub fn quantize_bundle(
    bf: &BundleFixFormat,
    map: &GridMap,
    b: &Bundle,
) -> Result<FixBundle, Error> {
    b.validate()?;
    if map.fmt != bf.base {
        return Err(Error::BadFormat {
            param: "grid format",
            value: map.fmt.g as i64,
            why: format!(
                "the grid is for {}, the bundle format for {}",
                map.fmt.name(),
                bf.base.name()
            ),
        });
    }
    let o = map
        .quantize_box(&origin_box(b))
        .map_err(|e| rename_error(e, "box", "bundle origin"))?;
    let j = bundle_dir_exp(b);
    let e = j + bf.fd as i32;
    let code = |x: f64, up: bool, a: usize| {
        // |x 2^j| < 2, so the code is at most 2^(FD+1) in magnitude.
        if up {
            ceil_pow2(x, e)
        } else {
            floor_pow2(x, e)
        }
        .ok_or_else(|| Error::DoesNotFit {
            what: format!("bundle direction.{}", AXES[a]),
            value: x,
            why: "direction code out of range".into(),
        })
    };
    let mut d_lo = [0i64; 3];
    let mut d_hi = [0i64; 3];
    for a in 0..3 {
        d_lo[a] = code(b.d_lo[a], false, a)?;
        d_hi[a] = code(b.d_hi[a], true, a)?;
    }
    let fmt = &bf.base;
    let te = fmt.ft as i32 - map.k - j;
    let pinf = fmt.t_pos_inf();
    // Both t values are >= 0. Floor for AllHit (a shorter range), ceil for AnyHit (a longer one); a value
    // past the finite codes becomes the largest finite code (floor) or +inf (ceil).
    let t_lo = match floor_pow2(b.t_lo, te) {
        Some(c) if c < pinf => c,
        _ if b.t_lo.is_infinite() => pinf,
        _ => pinf - 1,
    };
    let t_hi = match ceil_pow2(b.t_hi, te) {
        Some(c) if c < pinf => c,
        _ => pinf,
    };
    Ok(FixBundle {
        o_lo: o.lo,
        o_hi: o.hi,
        d_lo,
        d_hi,
        t_lo,
        t_hi,
    })
}

/// Quantises a world box both ways: `outer` as the slab tester does ([`GridMap::quantize_box`]),
/// `inner = [ceil(min), floor(max)]` (possibly empty: AllHit then fails, as it must).
pub fn quantize_box_pair(map: &GridMap, b: &Aabb) -> Result<BoxPair<FixBox>, Error> {
    let outer = map.quantize_box(b)?;
    if b.is_empty() {
        return Ok(BoxPair {
            inner: outer,
            outer,
        });
    }
    let mut inner = outer;
    for (a, axis) in AXES.iter().enumerate() {
        // Within [outer.lo, outer.hi], so on the grid once the outer box fits.
        let grid = |v: Option<i64>, x: f64, end: &str| {
            v.map(|q| q - map.c[a]).ok_or_else(|| Error::DoesNotFit {
                what: format!("box {end}.{axis}"),
                value: x,
                why: "beyond the grid".into(),
            })
        };
        inner.lo[a] = grid(ceil_pow2(b.min[a], -map.k), b.min[a], "min")?;
        inner.hi[a] = grid(floor_pow2(b.max[a], -map.k), b.max[a], "max")?;
    }
    Ok(BoxPair { inner, outer })
}

/// The exact rational values of a quantised bundle, in grid units with the direction codes as they are
/// and `t` scaled by `2^-(FD+FT)` (so that `t * u` means the same as on the datapath): the input of
/// [`crate::bundle::edge::ExactArith`] that must give the fixed datapath's answers bit for bit.
pub fn exact_of_fix(bf: &BundleFixFormat, b: &FixBundle) -> BundleOf<BigRational, Ext> {
    let t = |c: &i64| {
        if *c == bf.base.t_pos_inf() {
            Ext::PosInf
        } else {
            Ext::Fin(dyadic(*c, -(bf.dist_shift() as i32)))
        }
    };
    b.map(|&v| BigRational::from_integer(BigInt::from(v)), t)
}

/// A quantised box as exact rational arrays (grid units).
pub fn exact_of_fix_box(b: &FixBox) -> BoxArrays<BigRational> {
    let r = |v: i64| BigRational::from_integer(BigInt::from(v));
    (b.lo.map(r), b.hi.map(r))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Ray;

    fn map(bf: &BundleFixFormat) -> GridMap {
        GridMap::for_bounds(bf.base, DVec3::splat(-8.0), DVec3::splat(8.0)).unwrap()
    }

    #[test]
    fn preset_widths_are_square_multipliers() {
        for bf in BundleFixFormat::presets() {
            assert_eq!(bf.dir_bits(), bf.diff_bits(), "{}", bf.name());
            assert_eq!(bf.edge_product_bits(), 2 * bf.base.g + 2);
        }
        let b16 = BundleFixFormat::parse("b16").unwrap();
        assert_eq!((b16.edge_product_bits(), b16.dist_product_bits()), (34, 41));
        assert_eq!(BundleFixFormat::parse("b16,10").unwrap().fd, 10);
        assert!(BundleFixFormat::parse("b16,0").is_err());
        assert!(BundleFixFormat::parse("b16,x").is_err());
        assert!(BundleFixFormat::parse("b16,1,2").is_err());
    }

    #[test]
    fn on_grid_ray_quantises_to_a_point_bundle_with_its_answer() {
        let bf = BundleFixFormat::presets()[1];
        let m = map(&bf);
        let r = Ray::new(
            DVec3::new(-4.0, 0.5, 0.5),
            DVec3::new(1.0, 0.25, 0.0),
            0.0,
            4.0,
        )
        .unwrap();
        let q = quantize_bundle(&bf, &m, &Bundle::of_ray(&r).unwrap()).unwrap();
        assert_eq!((q.o_lo, q.d_lo, q.t_lo), (q.o_hi, q.d_hi, q.t_hi));
        let bx = quantize_box_pair(&m, &Aabb::new(DVec3::ZERO, DVec3::ONE).unwrap()).unwrap();
        assert_eq!(bx.inner, bx.outer);
        // At t = 4 the ray is at (0, 1.5, 0.5): outside in y. At t = 4 with dir.y = 0.125 it is inside.
        assert!(all_miss_fix(&bf, &q, &bx.outer) && !all_hit_fix(&bf, &q, &bx.inner));
        let r2 = Ray {
            dir: DVec3::new(1.0, 0.125, 0.0),
            ..r
        };
        let q2 = quantize_bundle(&bf, &m, &Bundle::of_ray(&r2).unwrap()).unwrap();
        assert!(all_hit_fix(&bf, &q2, &bx.inner) && !all_miss_fix(&bf, &q2, &bx.outer));
    }

    #[test]
    fn off_grid_box_rounds_inward_for_allhit_and_outward_for_anyhit() {
        let bf = BundleFixFormat::presets()[0];
        let m = map(&bf);
        let b = Aabb::new(DVec3::splat(0.3), DVec3::splat(0.7)).unwrap();
        let p = quantize_box_pair(&m, &b).unwrap();
        for a in 0..3 {
            assert!(m.to_world(a, p.inner.lo[a]) >= 0.3 && m.to_world(a, p.inner.hi[a]) <= 0.7);
            assert!(m.to_world(a, p.outer.lo[a]) <= 0.3 && m.to_world(a, p.outer.hi[a]) >= 0.7);
        }
    }

    #[test]
    fn bad_inputs_are_named_errors() {
        let bf = BundleFixFormat::presets()[0];
        let m = map(&bf);
        let far = Ray::new(DVec3::new(0.0, 0.0, 900.0), DVec3::X, 0.0, 1.0).unwrap();
        let e = quantize_bundle(&bf, &m, &Bundle::of_ray(&far).unwrap())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("bundle origin min.z") && e.contains("900"),
            "{e}"
        );
        let other = BundleFixFormat::presets()[2];
        assert!(quantize_bundle(&other, &m, &Bundle::of_ray(&far).unwrap()).is_err());
        let mut nan = Bundle::of_ray(&Ray::new(DVec3::ZERO, DVec3::X, 0.0, 1.0).unwrap()).unwrap();
        nan.d_lo[2] = f64::NAN;
        let e = quantize_bundle(&bf, &m, &nan).unwrap_err().to_string();
        assert!(e.contains("bundle direction min.z"), "{e}");
    }
}
