//! The float reference slab test (f64): the meaning of the test, with defined special cases.
//!
//! Kay and Kajiya's slab method (SIGGRAPH 1986), written as in Williams et al., "An Efficient and Robust
//! Ray-Box Intersection Algorithm" (JGT 2005): per axis the ray is inside the slab for
//! `t in [(min - o) / d, (max - o) / d]` (swapped when `d < 0`); the box interval is the intersection of the
//! three slab intervals and `[t_min, t_max]`.
//!
//! Special cases, all closed-box semantics:
//! - `d = 0` (either sign): the axis does not constrain `t` when `min <= o <= max`, and the ray misses
//!   otherwise. This is the meaning of `0 x inf` for an origin exactly on a slab plane, where the
//!   textbook code computes NaN.
//! - an empty box (`min > max` on an axis) is never hit.
//! - NaN never reaches the test: [`Ray::validate`] and [`Aabb::validate`] reject it.

use crate::geom::{Aabb, Ray, SlabHit};

/// Slab test in f64. Rounding is to nearest, so grazing results may differ from the exact oracle; this
/// model is the yardstick for accuracy, not a conservative test.
pub fn slab_ref(ray: &Ray, b: &Aabb) -> SlabHit {
    let mut entry = ray.t_min;
    let mut exit = ray.t_max;
    let mut inside = !b.is_empty();
    for a in 0..3 {
        let (o, d) = (ray.origin[a], ray.dir[a]);
        if d == 0.0 {
            inside &= b.min[a] <= o && o <= b.max[a];
            continue;
        }
        let inv = 1.0 / d;
        let (mut t0, mut t1) = ((b.min[a] - o) * inv, (b.max[a] - o) * inv);
        if inv < 0.0 {
            std::mem::swap(&mut t0, &mut t1);
        }
        entry = entry.max(t0);
        exit = exit.min(t1);
    }
    SlabHit {
        hit: inside && entry <= exit,
        t_entry: entry,
        t_exit: exit,
    }
}

/// The textbook slab test as usually written (`inv = 1/d`, products, min/max, no special cases), kept
/// to show where it fails: `0 * inf` is NaN when the origin lies on a slab plane of a zero direction
/// component, and NaN silently turns into a miss through IEEE min/max comparisons.
pub fn slab_textbook(ray: &Ray, b: &Aabb) -> bool {
    let mut entry = ray.t_min;
    let mut exit = ray.t_max;
    for a in 0..3 {
        let inv = 1.0 / ray.dir[a];
        let t0 = (b.min[a] - ray.origin[a]) * inv;
        let t1 = (b.max[a] - ray.origin[a]) * inv;
        let (lo, hi) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
        // Written as comparisons, as in most code: a NaN lo/hi makes both false and drops the axis or,
        // with the opposite operand order, poisons the interval.
        entry = if lo > entry { lo } else { entry };
        exit = if hi < exit { hi } else { exit };
    }
    entry <= exit
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(DVec3::from(o), DVec3::from(d), 0.0, f64::INFINITY).unwrap()
    }
    fn unit_box() -> Aabb {
        Aabb::new(DVec3::ZERO, DVec3::ONE).unwrap()
    }

    #[test]
    fn straight_hit_gives_face_distances() {
        let h = slab_ref(&ray([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0]), &unit_box());
        assert!(h.hit);
        assert_eq!((h.t_entry, h.t_exit), (1.0, 2.0));
    }

    #[test]
    fn zero_direction_outside_slab_misses_for_both_signs_of_zero() {
        for z in [0.0, -0.0] {
            let h = slab_ref(&ray([-1.0, 2.0, 0.5], [1.0, z, 0.0]), &unit_box());
            assert!(!h.hit, "dir.y = {z:?}");
        }
    }

    #[test]
    fn origin_on_slab_plane_with_zero_direction_hits_where_textbook_misses() {
        // origin.y = 1 = box max.y, dir.y = 0: (1 - 1) * inf = NaN in the textbook code.
        let r = ray([-1.0, 1.0, 0.5], [1.0, 0.0, 0.0]);
        assert!(slab_ref(&r, &unit_box()).hit);
        assert!(!slab_textbook(&r, &unit_box()));
    }

    #[test]
    fn empty_box_is_never_hit() {
        let b = Aabb::new(DVec3::ONE, DVec3::ZERO).unwrap();
        assert!(!slab_ref(&ray([0.5, 0.5, -1.0], [0.0, 0.0, 1.0]), &b).hit);
    }
}
