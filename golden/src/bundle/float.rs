//! Bit-accurate model of the float AllHit / AnyHit bundle datapath: the logic of [`crate::bundle::edge`] (proof
//! and patent figures there) in a [`FloatFormat`], with directed rounding in place of exact integers.
//!
//! # Inputs
//! The origin box rounded outward (`o_lo = RD`, `o_hi = RU`, as [`crate::slab::float::quantize_box`]), the
//! box as a [`BoxPair`] (`inner = [RU(min), RD(max)]` for AllHit, `outer = [RD(min), RU(max)]` for AnyHit),
//! the direction box scaled by the exact power of two `2^j` that brings its largest magnitude into `[1, 2)`
//! (so a narrow format neither overflows nor flushes a direction) and rounded outward, and `t_max` in the
//! unit of the scaled direction (`t 2^-j`): `t_lo = RD` for AllHit, `t_hi = RU` for AnyHit.
//!
//! # Operation sequence (AllHit; AnyHit swaps every RD and RU, the origin ends and the `u` ends)
//! ```text
//! stage 1  per axis:  RU(lo - o_lo)  RD(hi - o_hi)  RU(o_hi - hi)  RD(o_lo - lo)        4 subtractions
//!          class of [d_lo, d_hi] by sign bits and zero tests; mux e, x (straddling: max e, min x),
//!          u_lo, u_hi (negation exact; straddling: 0 and max(-d_lo, d_hi))
//! stage 2  edges:     RU(e_a * (e_a >= 0 ? u_hi_b : u_lo_b))   RD(x_b * (x_b >= 0 ? u_lo_a : u_hi_a))   12
//!          distances: RD(t_lo * u_lo_a)  (0 when u_lo_a = 0)                                           3
//! stage 3  e_a*u_b <= x_b*u_a (6), e_a <= t*u_a (3), x_a >= 0 (3), lo <= hi (3); AND
//! ```
//! Each rounded value bounds the exact one on the side the test needs, and the operand choice by the sign
//! of a rounded bound still bounds the product of the exact one, so Theorems 2a and 2b of
//! [`crate::bundle::edge`] carry over. A difference that overflows becomes `+-inf` (RU) or the largest finite
//! (RD), still a bound; `inf x 0` (an overflowed difference against a zero direction bound) is taken as
//! `+inf` for an upper bound and `-inf` for a lower one ([`mul_upper`], [`mul_lower`]), also bounds.
//! Comparisons use the hardware's sign-magnitude order (`-0 == +0`).

use crate::bundle::edge::{conditions_hold, BoundArith, BoxPair, Bundle, BundleOf, Test};
use crate::bundle::fix::{bundle_dir_exp, origin_box, rename_error};
use crate::error::Error;
use crate::format::fixed::ldexp;
use crate::format::float::{Class, FloatFormat, Rounding};
use crate::geom::Aabb;
use crate::slab::float::{mul_lower, mul_upper, quantize_box, FloatBox};

/// A bundle quantised into a float format (bit patterns; see the module doc).
pub type FloatBundle = BundleOf<u32, u32>;

/// The float arithmetic of a format: directed rounding of every difference and product.
#[derive(Clone, Copy, Debug)]
pub struct FloatArith(pub FloatFormat);

fn mode(up: bool) -> Rounding {
    if up {
        Rounding::Up
    } else {
        Rounding::Down
    }
}

impl BoundArith for FloatArith {
    type V = u32;
    type T = u32;
    type P = u32;
    fn sub(&self, a: &u32, b: &u32, up: bool) -> u32 {
        self.0.sub(*a, *b, mode(up))
    }
    fn mul(&self, v: &u32, u: &u32, up: bool) -> u32 {
        if up {
            mul_upper(&self.0, *v, *u)
        } else {
            mul_lower(&self.0, *v, *u)
        }
    }
    fn le(&self, a: &u32, b: &u32) -> bool {
        self.0.le(*a, *b)
    }
    fn is_neg(&self, a: &u32) -> bool {
        self.0.lt(*a, self.0.zero(false))
    }
    fn neg(&self, a: &u32) -> u32 {
        a ^ self.0.sign_bit()
    }
    fn zero(&self) -> u32 {
        self.0.zero(false)
    }
    fn t_is_neg(&self, t: &u32) -> bool {
        self.is_neg(t)
    }
    fn t_mul(&self, t: &u32, u: &u32, up: bool) -> u32 {
        if self.0.class(*u) == Class::Zero {
            self.zero()
        } else {
            self.mul(t, u, up)
        }
    }
    fn lift(&self, v: &u32) -> u32 {
        *v
    }
    fn le_p(&self, a: &u32, b: &u32) -> bool {
        self.le(a, b)
    }
}

/// AllHit on the float datapath: `true` means every ray of the bundle hits the (inner) box.
pub fn all_hit_float(f: &FloatFormat, b: &FloatBundle, inner: &FloatBox) -> bool {
    conditions_hold(&FloatArith(*f), b, None, &inner.lo, &inner.hi, Test::AllHit)
}

/// AnyHit on the float datapath: `true` means every ray of the bundle misses the (outer) box.
pub fn all_miss_float(f: &FloatFormat, b: &FloatBundle, outer: &FloatBox) -> bool {
    !conditions_hold(&FloatArith(*f), b, None, &outer.lo, &outer.hi, Test::AnyHit)
}

/// Quantises a world bundle and box and runs both tests: `(all_hit, all_miss)` on the float datapath.
pub fn decide_float(f: &FloatFormat, b: &Bundle, bx: &Aabb) -> Result<(bool, bool), Error> {
    let q = quantize_bundle(f, b)?;
    let p = quantize_box_pair(f, bx)?;
    Ok((
        all_hit_float(f, &q, &p.inner),
        all_miss_float(f, &q, &p.outer),
    ))
}

/// `x 2^j` rounded into `f` (exactly: the scaling is done in f64 when it is exact there, and a value that
/// leaves f64's normal range is far outside every format's, where only its sign and size class matter).
fn round_scaled(f: &FloatFormat, x: f64, j: i32, m: Rounding) -> u32 {
    let s = ldexp(x, j);
    if x == 0.0 || x.is_infinite() || s.is_normal() {
        f.from_f64(if x.is_infinite() { x } else { s }, m)
    } else if s.abs() < 1.0 {
        // Below f64's normal range: nonzero, below half the smallest subnormal of the format.
        f.from_f64(x.signum() * f64::from_bits(1), m)
    } else {
        // Overflowed f64: beyond the format's largest finite value.
        f.from_f64(x.signum() * f64::MAX, m)
    }
}

/// Quantises a world bundle into `f`. Errors name the bad input: an invalid bundle, an origin beyond the
/// format's range.
pub fn quantize_bundle(f: &FloatFormat, b: &Bundle) -> Result<FloatBundle, Error> {
    quantize_bundle_at(f, b, bundle_dir_exp(b))
}

/// Quantises a world bundle into `f` on the direction scale `2^j` of the caller's choice (directions
/// times `2^j`, t values times `2^-j`, each rounded outward): [`quantize_bundle`] takes the bundle's own
/// exponent. The pair's answers are sound on any scale, and do not depend on it while every value stays
/// in the format's normal range (a ray is the same for `d 2^j` and
/// `t 2^-j`); a float keeps its relative precision under a power-of-two scale, so a ray put on the scale
/// of a bundle around it loses nothing unless a value leaves the format's normal range (then it is still
/// rounded outward). The rays of one bundle on one scale is what float re-bounding needs
/// ([`crate::bundle::rebound`]).
pub fn quantize_bundle_at(f: &FloatFormat, b: &Bundle, j: i32) -> Result<FloatBundle, Error> {
    b.validate()?;
    let o = quantize_box(f, &origin_box(b)).map_err(|e| rename_error(e, "box", "bundle origin"))?;
    Ok(FloatBundle {
        o_lo: o.lo,
        o_hi: o.hi,
        d_lo: b.d_lo.map(|d| round_scaled(f, d, j, Rounding::Down)),
        d_hi: b.d_hi.map(|d| round_scaled(f, d, j, Rounding::Up)),
        t_lo: round_scaled(f, b.t_lo, -j, Rounding::Down),
        t_hi: round_scaled(f, b.t_hi, -j, Rounding::Up),
    })
}

/// Rounds a world box both ways: `outer` as the slab tester does, `inner = [RU(min), RD(max)]`.
pub fn quantize_box_pair(f: &FloatFormat, b: &Aabb) -> Result<BoxPair<FloatBox>, Error> {
    let outer = quantize_box(f, b)?;
    if b.is_empty() {
        return Ok(BoxPair {
            inner: outer,
            outer,
        });
    }
    let inner = FloatBox {
        lo: std::array::from_fn(|a| f.from_f64(b.min[a], Rounding::Up)),
        hi: std::array::from_fn(|a| f.from_f64(b.max[a], Rounding::Down)),
    };
    Ok(BoxPair { inner, outer })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Ray;
    use glam::DVec3;

    #[test]
    fn tiny_and_huge_scaled_values_round_to_the_right_side() {
        let f = FloatFormat::FP16;
        let tiny = f64::from_bits(1);
        assert_eq!(round_scaled(&f, tiny, 0, Rounding::Down), f.zero(false));
        assert_eq!(round_scaled(&f, tiny, 0, Rounding::Up), 1);
        assert_eq!(round_scaled(&f, -tiny, 0, Rounding::Up), f.zero(true));
        assert_eq!(
            round_scaled(&f, 1e300, 900, Rounding::Down),
            f.max_finite(false)
        );
        assert_eq!(round_scaled(&f, 1e300, 900, Rounding::Up), f.inf(false));
        assert_eq!(
            round_scaled(&f, f64::INFINITY, -5, Rounding::Down),
            f.inf(false)
        );
        assert_eq!(
            round_scaled(&f, 3.0, -1, Rounding::Up),
            f.from_f64(1.5, Rounding::Up)
        );
    }

    #[test]
    fn straddling_bundle_beside_the_box_is_all_miss_in_every_format() {
        let b = crate::bundle::edge::fixtures::fig7_bundle(5.0, 0.05);
        let bx = Aabb::new(DVec3::ZERO, DVec3::ONE).unwrap();
        for f in [FloatFormat::FP16, FloatFormat::BF16, FloatFormat::FP32] {
            assert_eq!(
                decide_float(&f, &b, &bx).unwrap(),
                (false, true),
                "{}",
                f.name()
            );
        }
    }

    #[test]
    fn origin_beyond_the_format_is_an_error_naming_it() {
        let f = FloatFormat::FP16;
        let r = Ray::new(DVec3::new(0.0, 1e6, 0.0), DVec3::X, 0.0, 1.0).unwrap();
        let e = quantize_bundle(&f, &Bundle::of_ray(&r).unwrap())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("bundle origin min.y") && e.contains("65504"),
            "{e}"
        );
    }
}
