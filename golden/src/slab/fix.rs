//! Bit-accurate model of the fixed-point slab datapath (`rtl::slab::fix::SlabFix` matches it bit for bit).
//!
//! Per axis, with the near/far planes chosen by the direction's sign (Williams et al., JGT 2005), the
//! distances are taken in the direction of travel so the inverse direction is a non-negative magnitude:
//!
//! ```text
//! d >= 0:  e = near - o_hi      x = far - o_lo        (near = lo, far = hi)
//! d <  0:  e = o_lo - near      x = o_hi - far        (near = hi, far = lo)
//! entry_a = floor(e * (e >= 0 ? m_lo : m_hi) / 2^(FI-FT))     a lower bound of the true entry
//! exit_a  =  ceil(x * (x >= 0 ? m_hi : m_lo) / 2^(FI-FT))     an upper bound of the true exit
//! ```
//!
//! Taking the lower end of the origin interval against the upper end (and the matching end of the
//! inverse interval by the sign of the distance) makes each bound hold for every origin and inverse in
//! the two intervals, so the result encloses the exact one (the interval form of Keely, HPG 2014).
//!
//! Saturation and the unbounded inverse code:
//! - a chosen inverse of all-ones (unbounded): `entry_a = e > 0 ? +inf : -inf`,
//!   `exit_a = x >= 0 ? +inf : -inf` — the `0 x inf` case (origin on the slab plane, zero direction)
//!   leaves the axis unconstrained, and an origin wholly outside the slab misses;
//! - a finite lower bound saturates into `[-inf, largest finite]`, an upper bound into
//!   `[smallest finite, +inf]`.
//!
//! Then `t_entry = max(t_min, entry_x, entry_y, entry_z)`, `t_exit = min(t_max, exit_x, exit_y, exit_z)`,
//! and `hit = box not empty && t_entry <= t_exit && t_entry != +inf && t_exit != -inf`.

use crate::format::fixed::{FixBox, FixFormat, FixRay};

/// Output of the fixed slab tester: `t_entry` and `t_exit` are t codes (see [`crate::format::fixed`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SlabFixOut {
    pub hit: bool,
    pub t_entry: i64,
    pub t_exit: i64,
}

/// The lower-bound scaled product: `floor(e * m / 2^shift)`, saturated. Mirrors `rtl::MulRound` (floor).
#[inline(always)]
pub fn mul_floor(fmt: &FixFormat, e: i64, m: u64) -> i64 {
    let (ninf, pinf) = (fmt.t_neg_inf(), fmt.t_pos_inf());
    if m == fmt.inv_inf() {
        return if e > 0 { pinf } else { ninf };
    }
    let q = (e * m as i64) >> fmt.shift();
    q.clamp(ninf, pinf - 1)
}

/// The upper-bound scaled product: `ceil(x * m / 2^shift)`, saturated. Mirrors `rtl::MulRound` (ceil).
#[inline(always)]
pub fn mul_ceil(fmt: &FixFormat, x: i64, m: u64) -> i64 {
    let (ninf, pinf) = (fmt.t_neg_inf(), fmt.t_pos_inf());
    if m == fmt.inv_inf() {
        return if x >= 0 { pinf } else { ninf };
    }
    let q = -((-(x * m as i64)) >> fmt.shift());
    q.clamp(ninf + 1, pinf)
}

/// Per-axis distances `(e, x)` and emptiness, as stage 1 of the pipeline computes them.
#[inline(always)]
pub fn axis_distances(r: &FixRay, b: &FixBox, a: usize) -> (i64, i64, bool) {
    let (near, far) = if r.neg[a] {
        (b.hi[a], b.lo[a])
    } else {
        (b.lo[a], b.hi[a])
    };
    let (e, x) = if r.neg[a] {
        (r.o_lo[a] - near, r.o_hi[a] - far)
    } else {
        (near - r.o_hi[a], far - r.o_lo[a])
    };
    (e, x, b.lo[a] > b.hi[a])
}

/// The fixed-point slab test, bit for bit as the RTL computes it.
#[inline]
pub fn slab_fix(fmt: &FixFormat, r: &FixRay, b: &FixBox) -> SlabFixOut {
    let mut entry = r.t_min;
    let mut exit = r.t_max;
    let mut empty = false;
    for a in 0..3 {
        let (e, x, em) = axis_distances(r, b, a);
        empty |= em;
        let en = mul_floor(fmt, e, if e >= 0 { r.m_lo[a] } else { r.m_hi[a] });
        let ex = mul_ceil(fmt, x, if x >= 0 { r.m_hi[a] } else { r.m_lo[a] });
        entry = entry.max(en);
        exit = exit.min(ex);
    }
    SlabFixOut {
        hit: !empty && entry <= exit && entry != fmt.t_pos_inf() && exit != fmt.t_neg_inf(),
        t_entry: entry,
        t_exit: exit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::fixed::GridMap;
    use crate::geom::{Aabb, Ray};
    use glam::DVec3;

    fn setup(
        o: [f64; 3],
        d: [f64; 3],
        bmin: [f64; 3],
        bmax: [f64; 3],
    ) -> (FixFormat, FixRay, FixBox) {
        let fmt = FixFormat::b12();
        let m = GridMap::for_bounds(fmt, DVec3::splat(-8.0), DVec3::splat(8.0)).unwrap();
        let r = Ray::new(o.into(), d.into(), 0.0, f64::INFINITY).unwrap();
        let b = Aabb::new(bmin.into(), bmax.into()).unwrap();
        (
            fmt,
            m.quantize_ray(&r).unwrap(),
            m.quantize_box(&b).unwrap(),
        )
    }

    #[test]
    fn axis_aligned_hit_reports_face_distances_exactly() {
        let (fmt, r, b) = setup([-4.0, 0.5, 0.5], [1.0, 0.0, 0.0], [0.0; 3], [1.0; 3]);
        let out = slab_fix(&fmt, &r, &b);
        assert!(out.hit);
        assert_eq!(r.t_entry_f64(&fmt, out.t_entry), 4.0);
        assert_eq!(r.t_exit_f64(&fmt, out.t_exit), 5.0);
    }

    #[test]
    fn origin_on_slab_plane_with_zero_direction_hits() {
        let (fmt, r, b) = setup([-4.0, 1.0, 0.5], [1.0, 0.0, -0.0], [0.0; 3], [1.0; 3]);
        assert!(slab_fix(&fmt, &r, &b).hit);
    }

    #[test]
    fn zero_direction_outside_slab_misses() {
        let (fmt, r, b) = setup([-4.0, 1.5, 0.5], [1.0, -0.0, 0.0], [0.0; 3], [1.0; 3]);
        assert!(!slab_fix(&fmt, &r, &b).hit);
    }

    #[test]
    fn ray_pointing_away_misses() {
        let (fmt, r, b) = setup([-4.0, 0.5, 0.5], [-1.0, 0.0, 0.0], [0.0; 3], [1.0; 3]);
        assert!(!slab_fix(&fmt, &r, &b).hit);
    }

    #[test]
    fn empty_box_misses() {
        let (fmt, r, b) = setup([-4.0, 0.5, 0.5], [1.0, 0.0, 0.0], [1.0; 3], [0.0; 3]);
        assert!(!slab_fix(&fmt, &r, &b).hit);
    }

    #[test]
    fn saturation_keeps_bounds_on_their_side() {
        let fmt = FixFormat::b8();
        assert_eq!(mul_floor(&fmt, 1 << 8, 4000), fmt.t_pos_inf() - 1);
        assert_eq!(mul_floor(&fmt, -(1 << 8), 4000), fmt.t_neg_inf());
        assert_eq!(mul_ceil(&fmt, 1 << 8, 4000), fmt.t_pos_inf());
        assert_eq!(mul_ceil(&fmt, -(1 << 8), 4000), fmt.t_neg_inf() + 1);
        assert_eq!(mul_floor(&fmt, 0, fmt.inv_inf()), fmt.t_neg_inf());
        assert_eq!(mul_ceil(&fmt, 0, fmt.inv_inf()), fmt.t_pos_inf());
    }
}
