//! The float cull-plane datapath: plane storage, plane fitting, the ray's direction interval, and the
//! bit-accurate model of the tester (the float RTL matches it bit for bit).
//!
//! The arithmetic is [`crate::plane::fix`]'s with directed rounding in place of exact integers
//! (directed rounding is the float datapath's tool). All values are of one format `E`/`M`.
//!
//! ```text
//! c_a    = RN(RN(lo_a + hi_a) * 0.5)                the centroid, as the hardware forms it (any point works:
//!                                                   the planes are fitted against this very value)
//! ol_a   = RD(o_lo_a - c_a)     oh_a = RU(o_hi_a - c_a)
//! S_lo   = RD(RD(RD(u_0 + u_1) + u_2) - w)          u_a = RD(n_a * (n_a >= 0 ? ol_a : oh_a))
//! den_lo = RD(RD(l_0 + l_1) + l_2)                  l_a = RD(n_a * (n_a >= 0 ? d_lo_a : d_hi_a))
//! den_hi = RU(RU(h_0 + h_1) + h_2)                  h_a = RU(n_a * (n_a >= 0 ? d_hi_a : d_lo_a))
//! ```
//!
//! (`n_a >= 0` counts either zero.) Then, as in the fixed datapath: `den_lo > 0` is an exit plane with bound
//! `RU(-S_lo * r)`, `r` an upper bound of `1/den_lo` when `S_lo <= 0` and a lower bound of `1/den_hi`
//! otherwise; `den_hi < 0` is an entry plane with bound `RD(S_lo * r)`, `r` a lower bound of `1/|den_lo|` when
//! `S_lo >= 0` and an upper bound of `1/|den_hi|` otherwise; `den_lo = den_hi = 0` culls when `S_lo > 0`;
//! anything else (a `den` interval holding zero, a NaN) leaves the interval alone. A NaN bound (`0 x inf`)
//! becomes `+inf` for an exit and `-inf` for an entry, as in the slab datapath.
//!
//! # The directed reciprocal ([`recip_float`])
//! `mag = 1.f * 2^e`: the top `R` bits of `f` index a table of the format's values just below and just
//! above `1 / 1.f` over the whole bucket (in `(1/2, 1]`), and `r = table * 2^-e` by exponent arithmetic
//! alone. Out of range: a lower bound that underflows is `+0`, an upper bound that underflows is the
//! smallest normal; a lower bound that overflows is the largest finite value, an upper bound `+inf`. A
//! subnormal (or zero) magnitude gives `[2^(bias-1), +inf]`; `+inf` gives `+0` (both bounds); NaN gives NaN.
//!
//! t is in world units, so the result merges with the float slab tester's `t_entry`/`t_exit` with the
//! slab's `max`/`min`: `hit = slab hit && no parallel cull && t_entry <= t_exit`.

use crate::error::Error;
use crate::exact::{rat, Ext};
use crate::format::float::{Class, FloatFormat, Rounding};
use crate::geom::Ray;
use crate::plane::clip::ExactPlane;
use crate::slab::float::{fmax, fmin, mul_lower, mul_upper, FloatBox, FloatRay, SlabFloatOut};
use glam::DVec3;
use num_rational::BigRational;
use num_traits::ToPrimitive;

const AXES: [&str; 3] = ["x", "y", "z"];

/// A float cull-plane format: the value format and the reciprocal table's index bits `R`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CullFloatFormat {
    pub f: FloatFormat,
    pub r: u32,
}

impl CullFloatFormat {
    /// `1 <= R <= 12`.
    pub fn new(f: FloatFormat, r: u32) -> Result<Self, Error> {
        if !(1..=12).contains(&r) {
            return Err(Error::BadFormat {
                param: "R (reciprocal table bits)",
                value: r as i64,
                why: "must be in 1..=12".into(),
            });
        }
        Ok(CullFloatFormat { f, r })
    }
    /// The default: `R = min(M, 8)`.
    pub fn over(f: FloatFormat) -> Self {
        Self::new(f, f.m.min(8)).expect("R in range")
    }
    /// Name for reports and Verilog modules, e.g. `e5m10_r8`.
    pub fn name(&self) -> String {
        format!("{}_r{}", self.f.name(), self.r)
    }
    /// What a node stores: six box coordinates, per plane three normal components and an offset, all
    /// in the format.
    pub fn layout(&self) -> crate::plane::clip::NodeLayout {
        let b = self.f.width();
        crate::plane::clip::NodeLayout {
            box_bits: 6 * b,
            normal_bits: 3 * b,
            offset_bits: b,
        }
    }
}

/// The ray's direction rounded outward into the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FloatDir {
    pub lo: [u32; 3],
    pub hi: [u32; 3],
}

/// A stored plane: normal and offset from the centroid [`centroid`], values of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FloatPlane {
    pub n: [u32; 3],
    pub w: u32,
}

/// Output of the float cull-plane tester (world t values of the format).
pub type PlaneFloatOut = SlabFloatOut;

/// Rounds the direction of a ray outward into the format.
pub fn quantize_dir(cf: &CullFloatFormat, ray: &Ray) -> Result<FloatDir, Error> {
    ray.validate()?;
    let f = &cf.f;
    let mut out = FloatDir::default();
    for a in 0..3 {
        out.lo[a] = f.from_f64(ray.dir[a], Rounding::Down);
        out.hi[a] = f.from_f64(ray.dir[a], Rounding::Up);
    }
    Ok(out)
}

/// The box centroid as the hardware forms it: `RN(RN(lo + hi) * 0.5)` per axis.
pub fn centroid(f: &FloatFormat, b: &FloatBox) -> [u32; 3] {
    let half = f.from_f64(0.5, Rounding::NearestEven);
    std::array::from_fn(|a| {
        f.mul(
            f.add(b.lo[a], b.hi[a], Rounding::NearestEven),
            half,
            Rounding::NearestEven,
        )
    })
}

/// `[RD, RU](num / den)` in the format, exactly, for small positive integers.
fn ratio_bounds(f: &FloatFormat, num: u64, den: u64) -> (u32, u32) {
    let q = num as f64 / den as f64;
    let r = q.mul_add(den as f64, -(num as f64)); // exact sign of q*den - num
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

/// Table entry `i` of `R` index bits: the format's values just below `1 / (1 + (i+1)/2^R)` and just above
/// `1 / (1 + i/2^R)`, each as (unbiased exponent, fraction field); the exponent is `-1` or `0`.
pub fn recip_table_entry(f: &FloatFormat, r: u32, i: u64) -> [(i32, u32); 2] {
    let base = 1u64 << r;
    let lo = ratio_bounds(f, base, base + i + 1).0;
    let hi = ratio_bounds(f, base, base + i).1;
    [lo, hi].map(|v| {
        let (_, be, frac) = f.fields(v);
        (be as i32 - f.bias(), frac)
    })
}

/// A directed bound of `1/mag` for `mag >= 0` (module doc): the upper bound when `upper`, else the lower.
pub fn recip_float(cf: &CullFloatFormat, mag: u32, upper: bool) -> u32 {
    let f = &cf.f;
    let (_, be, frac) = f.fields(mag);
    match f.class(mag) {
        Class::NaN => return f.nan(),
        Class::Inf => return f.zero(false),
        Class::Zero | Class::Subnormal => {
            return if upper {
                f.inf(false)
            } else {
                f.pack(false, (2 * f.bias() - 1) as u32, 0)
            }
        }
        Class::Normal => {}
    }
    let idx = if cf.r <= f.m {
        (frac >> (f.m - cf.r)) as u64
    } else {
        (frac as u64) << (cf.r - f.m)
    };
    let (delta, tfrac) = recip_table_entry(f, cf.r, idx)[usize::from(upper)];
    // r = 2^delta * 1.tfrac * 2^-(be - bias): biased exponent delta + 2 bias - be.
    let rbe = delta + 2 * f.bias() - be as i32;
    if rbe >= f.exp_all_ones() as i32 {
        if upper {
            f.inf(false)
        } else {
            f.max_finite(false)
        }
    } else if rbe <= 0 {
        if upper {
            f.pack(false, 1, 0)
        } else {
            f.zero(false)
        }
    } else {
        f.pack(false, rbe as u32, tfrac)
    }
}

/// Value `>= 0` (either zero counts).
#[inline]
fn non_negative(f: &FloatFormat, x: u32) -> bool {
    !f.is_negative(x) || f.class(x) == Class::Zero
}

/// Fits a plane of world normal `normal` to the vertices of a node whose rounded box is `b`: the normal is
/// scaled so its largest component is 1 and rounded to the format, and `w` is the smallest value of the
/// format with `n . (v - c) <= w` exactly for every vertex, `c` the hardware's [`centroid`]. An offset
/// beyond the format's range returns the unused (zero) plane.
pub fn fit_plane(
    cf: &CullFloatFormat,
    b: &FloatBox,
    normal: DVec3,
    vertices: &[DVec3],
) -> Result<FloatPlane, Error> {
    let f = &cf.f;
    let nmax = normal.abs().max_element();
    if !normal.is_finite() || nmax == 0.0 {
        return Err(Error::bad_value(
            "plane normal",
            nmax,
            "a plane needs a finite, nonzero normal",
        ));
    }
    if vertices.is_empty() {
        return Err(Error::Io("plane fit: the node has no vertices".into()));
    }
    let n: [u32; 3] = std::array::from_fn(|a| f.from_f64(normal[a] / nmax, Rounding::NearestEven));
    let c = centroid(f, b);
    let nr: [BigRational; 3] = std::array::from_fn(|a| rat(f.to_f64(n[a])));
    let cr: [BigRational; 3] = std::array::from_fn(|a| rat(f.to_f64(c[a])));
    let mut best: Option<BigRational> = None;
    for (vi, v) in vertices.iter().enumerate() {
        let mut s = BigRational::from_integer(0.into());
        for a in 0..3 {
            if !v[a].is_finite() {
                return Err(Error::bad_value(
                    format!("vertex {vi}.{}", AXES[a]),
                    v[a],
                    "vertices must be finite",
                ));
            }
            s += &nr[a] * (rat(v[a]) - &cr[a]);
        }
        if best.as_ref().is_none_or(|b| s > *b) {
            best = Some(s);
        }
    }
    let best = best.expect("vertices is not empty");
    let approx = best.to_f64().unwrap_or(f64::INFINITY);
    if approx.abs() > f.to_f64(f.max_finite(false)) {
        return Ok(FloatPlane::default());
    }
    let mut w = f.from_f64(approx, Rounding::Up);
    while rat(f.to_f64(w)) < best {
        w = f.next_up(w);
    }
    if f.class(w) == Class::Inf {
        return Ok(FloatPlane::default());
    }
    Ok(FloatPlane { n, w })
}

impl FloatPlane {
    /// The stored plane as an exact world half-space `n . p <= w + n . c`.
    pub fn to_exact(&self, f: &FloatFormat, b: &FloatBox) -> ExactPlane {
        let c = centroid(f, b);
        let n: [BigRational; 3] = std::array::from_fn(|a| rat(f.to_f64(self.n[a])));
        let mut h = rat(f.to_f64(self.w));
        for a in 0..3 {
            h += &n[a] * rat(f.to_f64(c[a]));
        }
        ExactPlane { n, h }
    }
}

/// `S_lo`, `den_lo`, `den_hi` of one plane, given the centroid offsets `ol = RD(o_lo - c)`, `oh = RU(o_hi - c)`.
#[inline]
pub fn plane_sums_float(
    f: &FloatFormat,
    ol: &[u32; 3],
    oh: &[u32; 3],
    d: &FloatDir,
    p: &FloatPlane,
) -> (u32, u32, u32) {
    let (dn, up) = (Rounding::Down, Rounding::Up);
    let mut u = [0u32; 3];
    let mut l = [0u32; 3];
    let mut h = [0u32; 3];
    for a in 0..3 {
        let pos = non_negative(f, p.n[a]);
        u[a] = f.mul(p.n[a], if pos { ol[a] } else { oh[a] }, dn);
        l[a] = f.mul(p.n[a], if pos { d.lo[a] } else { d.hi[a] }, dn);
        h[a] = f.mul(p.n[a], if pos { d.hi[a] } else { d.lo[a] }, up);
    }
    let s = f.sub(f.add(f.add(u[0], u[1], dn), u[2], dn), p.w, dn);
    let den_lo = f.add(f.add(l[0], l[1], dn), l[2], dn);
    let den_hi = f.add(f.add(h[0], h[1], up), h[2], up);
    (s, den_lo, den_hi)
}

/// What one plane does: `(entry bound, exit bound, cull)`, with `-inf`/`+inf` for "no bound".
#[inline]
pub fn plane_effect_float(
    cf: &CullFloatFormat,
    ol: &[u32; 3],
    oh: &[u32; 3],
    d: &FloatDir,
    p: &FloatPlane,
) -> (u32, u32, bool) {
    let f = &cf.f;
    let (s, dl, dh) = plane_sums_float(f, ol, oh, d, p);
    let zero = f.zero(false);
    let (ninf, pinf) = (f.inf(true), f.inf(false));
    if f.lt(zero, dl) {
        let upper = f.le(s, zero);
        let r = recip_float(cf, if upper { dl } else { dh }, upper);
        (ninf, mul_upper(f, s ^ f.sign_bit(), r), false)
    } else if f.lt(dh, zero) {
        let upper = !f.le(zero, s);
        let mag = (if upper { dh } else { dl }) & !f.sign_bit();
        (mul_lower(f, s, recip_float(cf, mag, upper)), pinf, false)
    } else {
        let par = f.eq(dl, zero) && f.eq(dh, zero) && f.lt(zero, s);
        (ninf, pinf, par)
    }
}

/// The float cull-plane test, chained after the float slab test's result `slab` on the same ray and box.
pub fn cull_float(
    cf: &CullFloatFormat,
    r: &FloatRay,
    d: &FloatDir,
    b: &FloatBox,
    planes: &[FloatPlane],
    slab: &SlabFloatOut,
) -> PlaneFloatOut {
    let f = &cf.f;
    let c = centroid(f, b);
    let ol: [u32; 3] = std::array::from_fn(|a| f.sub(r.o_lo[a], c[a], Rounding::Down));
    let oh: [u32; 3] = std::array::from_fn(|a| f.sub(r.o_hi[a], c[a], Rounding::Up));
    let (mut entry, mut exit, mut cull) = (slab.t_entry, slab.t_exit, !slab.hit);
    for p in planes {
        let (en, ex, par) = plane_effect_float(cf, &ol, &oh, d, p);
        entry = fmax(f, entry, en);
        exit = fmin(f, exit, ex);
        cull |= par;
    }
    PlaneFloatOut {
        hit: !cull && f.le(entry, exit),
        t_entry: entry,
        t_exit: exit,
    }
}

/// A float result's t values exactly, `None` when one is NaN.
pub fn out_interval(f: &FloatFormat, out: &PlaneFloatOut) -> Option<(Ext, Ext)> {
    if f.is_nan(out.t_entry) || f.is_nan(out.t_exit) {
        None
    } else {
        Some((
            Ext::from_f64(f.to_f64(out.t_entry)),
            Ext::from_f64(f.to_f64(out.t_exit)),
        ))
    }
}

/// The most planes a node carries in the testbenches' vector types.
pub use crate::plane::fix::MAX_PLANES;

/// A ray as the chained float slab + cull-plane tester takes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct NodeFloatRay {
    pub ray: FloatRay,
    pub dir: FloatDir,
}

/// A node as the chained float tester takes it: the box and up to [`MAX_PLANES`] planes (unused ones zero).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FloatNode {
    pub b: FloatBox,
    pub planes: [FloatPlane; MAX_PLANES],
}

/// Slab test then `k` planes, bit for bit as the chained float RTL computes it.
pub fn node_float(
    cf: &CullFloatFormat,
    k: usize,
    r: &NodeFloatRay,
    n: &FloatNode,
) -> PlaneFloatOut {
    let slab = crate::slab::float::slab_float(&cf.f, &r.ray, &n.b);
    cull_float(cf, &r.ray, &r.dir, &n.b, &n.planes[..k], &slab)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Aabb;
    use crate::plane::clip::clip_exact;
    use crate::slab::float::{quantize_box, quantize_ray, slab_float};

    #[test]
    fn reciprocal_bounds_bracket_the_true_reciprocal() {
        for f in [
            FloatFormat::FP16,
            FloatFormat::BF16,
            FloatFormat::E4M3,
            FloatFormat::FP32,
        ] {
            let cf = CullFloatFormat::over(f);
            let mut x = f.zero(false);
            let mut n = 0;
            while f.class(x) != Class::Inf && n < 200_000 {
                let v = f.to_f64(x);
                if v > 0.0 {
                    let lo = f.to_f64(recip_float(&cf, x, false));
                    let hi = f.to_f64(recip_float(&cf, x, true));
                    let t = rat(1.0) / rat(v);
                    assert!(rat(lo) <= t, "{} lo {v}", f.name());
                    assert!(hi == f64::INFINITY || t <= rat(hi), "{} hi {v}", f.name());
                }
                x = if f.width() > 16 { x + 977 } else { x + 1 };
                n += 1;
            }
        }
    }

    #[test]
    fn diagonal_plane_culls_the_empty_corner_in_fp16() {
        let cf = CullFloatFormat::over(FloatFormat::FP16);
        let f = &cf.f;
        let wb = Aabb::new(DVec3::ZERO, DVec3::splat(2.0)).unwrap();
        let b = quantize_box(f, &wb).unwrap();
        let verts = [
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 2.0),
            DVec3::new(0.0, 2.0, 1.0),
        ];
        let p = fit_plane(&cf, &b, DVec3::new(1.0, 1.0, 0.0), &verts).unwrap();
        let exact = [p.to_exact(f, &b)];
        for v in verts {
            assert!(exact[0].side(v) <= rat(0.0));
        }
        for (y, t_max, culled) in [(1.75, 10.0, false), (1.75, 2.5, true), (1.9, 2.85, true)] {
            let ray = Ray::new(DVec3::new(3.0, y, 1.0), DVec3::NEG_X, 0.0, t_max).unwrap();
            let fr = quantize_ray(f, &ray).unwrap();
            let fd = quantize_dir(&cf, &ray).unwrap();
            let out = cull_float(&cf, &fr, &fd, &b, &[p], &slab_float(f, &fr, &b));
            let ex = clip_exact(&ray, &wb, &exact);
            assert_eq!(out.hit, !culled, "y {y} t_max {t_max} {out:?}");
            assert_eq!(ex.hit, !culled);
            if out.hit {
                let (en, exi) = out_interval(f, &out).unwrap();
                assert!(en <= ex.entry && exi >= ex.exit);
                assert!(en > Ext::Fin(rat(2.7)));
            }
        }
    }
}
