//! The float slab datapath: quantisation of world rays and boxes into a float format, the bit-accurate
//! model of the conservative tester, and the textbook round-to-nearest method it is compared with.
//!
//! The structure is the fixed-point datapath's ([`crate::slab::fix`]) with directed rounding in place of
//! floor and ceil (directed rounding is the float datapath's tool):
//!
//! ```text
//! d >= 0:  e = RD(near - o_hi)     x = RU(far - o_lo)
//! d <  0:  e = RD(o_lo - near)     x = RU(o_hi - far)
//! entry_a = RD(e * (e >= 0 ? m_lo : m_hi))      exit_a = RU(x * (x >= 0 ? m_hi : m_lo))
//! ```
//!
//! with the ray carried as intervals: `o_lo = RD(o)`, `o_hi = RU(o)`, `m_lo = RD(|1/d|)`,
//! `m_hi = RU(|1/d|)`, and the box rounded outward. The one indeterminate product, `0 x inf` (an origin
//! on a slab plane with a zero direction component, or an unbounded box face against an inverse that
//! underflowed to zero), leaves the axis unconstrained: `-inf` for an entry, `+inf` for an exit — where
//! the textbook method computes NaN. `t_entry = max(t_min, entry_x, entry_y, entry_z)`,
//! `t_exit = min(t_max, ...)`, with `max(a, b) = a < b ? b : a` and `min(a, b) = b < a ? b : a`;
//! `hit = box not empty && t_entry <= t_exit && t_entry != +inf && t_exit != -inf`.
//!
//! t stays in world units: float formats have the range that the fixed-point grid gets from scaling.

use crate::error::Error;
use crate::exact::{ExactHit, Ext};
use crate::format::float::{Class, FloatFormat, Rounding};
use crate::geom::{Aabb, Ray};

const AXES: [&str; 3] = ["x", "y", "z"];

/// A ray quantised into a float format: origin and inverse-direction intervals, signs, t range.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FloatRay {
    pub o_lo: [u32; 3],
    pub o_hi: [u32; 3],
    pub m_lo: [u32; 3],
    pub m_hi: [u32; 3],
    pub neg: [bool; 3],
    pub t_min: u32,
    pub t_max: u32,
}

/// A box rounded outward; the canonical empty box is `lo = +inf`, `hi = -inf` on every axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FloatBox {
    pub lo: [u32; 3],
    pub hi: [u32; 3],
}

/// Output of the float slab tester: `t_entry`, `t_exit` are values of the format, in world units.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SlabFloatOut {
    pub hit: bool,
    pub t_entry: u32,
    pub t_exit: u32,
}

fn fits(f: &FloatFormat, what: String, x: f64) -> Result<(), Error> {
    if x.abs() > f.to_f64(f.max_finite(false)) {
        Err(Error::DoesNotFit {
            what,
            value: x,
            why: format!(
                "beyond the largest finite {} value {}",
                f.name(),
                f.to_f64(f.max_finite(false))
            ),
        })
    } else {
        Ok(())
    }
}

/// `[RD, RU](1 / |d|)` for a finite nonzero `d`, exactly: `q = 1/|d|` in f64, and the sign of
/// `fma(q, |d|, -1)` (exact) tells on which side of the true inverse `q` lies.
fn inverse_bounds(f: &FloatFormat, d: f64) -> (u32, u32) {
    if d == 0.0 {
        return (f.inf(false), f.inf(false));
    }
    let a = d.abs();
    let q = 1.0 / a;
    if q.is_infinite() {
        // The inverse exceeds f64's range, let alone the format's.
        return (f.max_finite(false), f.inf(false));
    }
    let r = q.mul_add(a, -1.0); // q * |d| - 1, rounded once: its sign is exact
    let mut lo = f.from_f64(q, Rounding::Down);
    let mut hi = f.from_f64(q, Rounding::Up);
    if f.to_f64(lo) == q && r > 0.0 {
        lo = f.next_down(lo);
    }
    if f.to_f64(hi) == q && r < 0.0 {
        hi = f.next_up(hi);
    }
    (lo, hi)
}

/// Quantises a ray into `f`; an origin beyond the format's range is an error naming it.
pub fn quantize_ray(f: &FloatFormat, r: &Ray) -> Result<FloatRay, Error> {
    r.validate()?;
    let mut q = FloatRay::default();
    for a in 0..3 {
        fits(f, format!("ray origin.{}", AXES[a]), r.origin[a])?;
        q.o_lo[a] = f.from_f64(r.origin[a], Rounding::Down);
        q.o_hi[a] = f.from_f64(r.origin[a], Rounding::Up);
        q.neg[a] = r.dir[a].is_sign_negative();
        (q.m_lo[a], q.m_hi[a]) = inverse_bounds(f, r.dir[a]);
    }
    q.t_min = f.from_f64(r.t_min, Rounding::Down);
    q.t_max = f.from_f64(r.t_max, Rounding::Up);
    Ok(q)
}

/// Rounds a box outward into `f`; a bound beyond the format's range is an error naming it.
pub fn quantize_box(f: &FloatFormat, b: &Aabb) -> Result<FloatBox, Error> {
    b.validate()?;
    if b.is_empty() {
        return Ok(FloatBox {
            lo: [f.inf(false); 3],
            hi: [f.inf(true); 3],
        });
    }
    let mut q = FloatBox::default();
    for a in 0..3 {
        fits(f, format!("box min.{}", AXES[a]), b.min[a])?;
        fits(f, format!("box max.{}", AXES[a]), b.max[a])?;
        q.lo[a] = f.from_f64(b.min[a], Rounding::Down);
        q.hi[a] = f.from_f64(b.max[a], Rounding::Up);
    }
    Ok(q)
}

/// Value `>= 0` (either zero counts).
#[inline]
fn non_negative(f: &FloatFormat, x: u32) -> bool {
    !f.is_negative(x) || f.class(x) == Class::Zero
}

/// `RD(e * m)`, with `0 x inf` meaning "unconstrained": `-inf`.
#[inline]
pub fn mul_lower(f: &FloatFormat, e: u32, m: u32) -> u32 {
    let p = f.mul(e, m, Rounding::Down);
    if f.is_nan(p) {
        f.inf(true)
    } else {
        p
    }
}

/// `RU(x * m)`, with `0 x inf` meaning "unconstrained": `+inf`.
#[inline]
pub fn mul_upper(f: &FloatFormat, x: u32, m: u32) -> u32 {
    let p = f.mul(x, m, Rounding::Up);
    if f.is_nan(p) {
        f.inf(false)
    } else {
        p
    }
}

/// `a < b ? b : a`.
#[inline]
pub fn fmax(f: &FloatFormat, a: u32, b: u32) -> u32 {
    if f.lt(a, b) {
        b
    } else {
        a
    }
}

/// `b < a ? b : a`.
#[inline]
pub fn fmin(f: &FloatFormat, a: u32, b: u32) -> u32 {
    if f.lt(b, a) {
        b
    } else {
        a
    }
}

/// The conservative float slab test, bit for bit as the float RTL is to compute it.
pub fn slab_float(f: &FloatFormat, r: &FloatRay, b: &FloatBox) -> SlabFloatOut {
    let mut entry = r.t_min;
    let mut exit = r.t_max;
    let mut empty = false;
    for a in 0..3 {
        let (near, far) = if r.neg[a] {
            (b.hi[a], b.lo[a])
        } else {
            (b.lo[a], b.hi[a])
        };
        let (e, x) = if r.neg[a] {
            (
                f.sub(r.o_lo[a], near, Rounding::Down),
                f.sub(r.o_hi[a], far, Rounding::Up),
            )
        } else {
            (
                f.sub(near, r.o_hi[a], Rounding::Down),
                f.sub(far, r.o_lo[a], Rounding::Up),
            )
        };
        empty |= f.lt(b.hi[a], b.lo[a]);
        let en = mul_lower(
            f,
            e,
            if non_negative(f, e) {
                r.m_lo[a]
            } else {
                r.m_hi[a]
            },
        );
        let ex = mul_upper(
            f,
            x,
            if non_negative(f, x) {
                r.m_hi[a]
            } else {
                r.m_lo[a]
            },
        );
        entry = fmax(f, entry, en);
        exit = fmin(f, exit, ex);
    }
    SlabFloatOut {
        hit: !empty && f.le(entry, exit) && entry != f.inf(false) && exit != f.inf(true),
        t_entry: entry,
        t_exit: exit,
    }
}

/// The textbook float slab test in format `f`: every input rounded to nearest, `inv = RN(1/d)`, products
/// and differences rounded to nearest, the `t0/t1` swap and comparison-based min/max. Kept to show where
/// it fails: NaN from `0 x inf`, and false misses at grazing angles.
pub fn slab_float_textbook(f: &FloatFormat, ray: &Ray, b: &Aabb) -> bool {
    let rn = Rounding::NearestEven;
    let q = |x: f64| f.from_f64(x, rn);
    let mut entry = q(ray.t_min);
    let mut exit = q(ray.t_max);
    for a in 0..3 {
        let inv = f.from_f64(1.0 / ray.dir[a], rn);
        let o = q(ray.origin[a]);
        let t0 = f.mul(f.sub(q(b.min[a]), o, rn), inv, rn);
        let t1 = f.mul(f.sub(q(b.max[a]), o, rn), inv, rn);
        let (lo, hi) = if f.lt(t0, t1) { (t0, t1) } else { (t1, t0) };
        if f.lt(entry, lo) {
            entry = lo;
        }
        if f.lt(hi, exit) {
            exit = hi;
        }
    }
    f.le(entry, exit)
}

/// A float result's t value exactly (`+-inf` included).
pub fn t_ext(f: &FloatFormat, x: u32) -> Ext {
    Ext::from_f64(f.to_f64(x))
}

/// Judges a float result against the exact oracle (see [`crate::slab::check::judge`]).
pub fn judge_float(
    f: &FloatFormat,
    out: &SlabFloatOut,
    exact: &ExactHit,
) -> crate::slab::check::Verdict {
    crate::slab::check::judge(exact, out.hit, || {
        if f.is_nan(out.t_entry) || f.is_nan(out.t_exit) {
            None
        } else {
            Some((t_ext(f, out.t_entry), t_ext(f, out.t_exit)))
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn inverse_bounds_bracket_the_true_inverse() {
        let f = FloatFormat::FP16;
        for d in [0.3, -3.0, 1e-9, 7.0, 1.0 / 3.0, 1e-320] {
            let (lo, hi) = inverse_bounds(&f, d);
            let inv = crate::exact::rat(1.0) / crate::exact::rat(d.abs());
            assert!(Ext::from_f64(f.to_f64(lo)) <= Ext::Fin(inv.clone()), "{d}");
            assert!(Ext::Fin(inv) <= Ext::from_f64(f.to_f64(hi)), "{d}");
        }
        // Exactly representable inverses give a point interval.
        assert_eq!(inverse_bounds(&f, 0.25).0, inverse_bounds(&f, 0.25).1);
    }

    #[test]
    fn origin_on_slab_plane_with_zero_direction_hits_where_textbook_misses() {
        let f = FloatFormat::FP16;
        let r = Ray::new(
            DVec3::new(-4.0, 0.0, 0.5),
            DVec3::new(1.0, 0.0, 0.0),
            0.0,
            f64::INFINITY,
        )
        .unwrap();
        let b = Aabb::new(DVec3::ZERO, DVec3::ONE).unwrap();
        let out = slab_float(
            &f,
            &quantize_ray(&f, &r).unwrap(),
            &quantize_box(&f, &b).unwrap(),
        );
        assert!(out.hit);
        assert_eq!((f.to_f64(out.t_entry), f.to_f64(out.t_exit)), (4.0, 5.0));
        assert!(!slab_float_textbook(&f, &r, &b));
    }

    #[test]
    fn value_beyond_the_format_is_an_error_naming_it() {
        let f = FloatFormat::FP16;
        let r = Ray::new(DVec3::new(0.0, 1e6, 0.0), DVec3::X, 0.0, 1.0).unwrap();
        let e = quantize_ray(&f, &r).unwrap_err().to_string();
        assert!(e.contains("ray origin.y") && e.contains("65504"), "{e}");
    }
}
