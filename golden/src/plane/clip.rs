//! Cull planes: empty-space planes inside a BVH node's box, the f64 reference of the cull-plane tester and
//! its exact oracle.
//!
//! Arm's application US 2025/0259373 (paragraphs 0217-0238, FIG. 12-13) gives a node, beside its AABB, a
//! few planes that bound the empty regions of the box. Each plane is a normal `n` pointing at the empty
//! side and an offset `w` from the box centroid `c`: all of the node's geometry satisfies
//! `n . (p - c) <= w` (the closed non-empty side). A ray `o + t d` that survives the slab test is clipped by
//! every plane:
//!
//! ```text
//! s0 = n . (o - c) - w        den = n . d        (the ray's point at t is on the empty side iff s0 + t den > 0)
//! den > 0: t_exit  = min(t_exit,  -s0 / den)
//! den < 0: t_entry = max(t_entry, -s0 / den)
//! den = 0: the whole ray is on one side: culled when s0 > 0
//! ```
//!
//! and the node is culled when the clipped interval is empty. This is the patent's front-side and
//! back-side culling in one rule: a plane facing the ray (`den < 0`) pushes the entry forward, one facing
//! away (`den > 0`) pulls the exit back.
//!
//! Contract: a node is culled only if no point of the ray within its t range lies inside
//! the box on the non-empty side of every plane; the reported interval encloses the exact clipped one.
//! The datapaths store their planes in their own formats ([`crate::plane::fix`], [`crate::plane::float`]);
//! each stored plane is an exact real half-space ([`ExactPlane`]), which the oracle clips with.

use crate::error::Error;
use crate::exact::{rat, slab_exact, ExactHit, Ext};
use crate::geom::{Aabb, Ray};
use glam::DVec3;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

/// Points whose convex hull contains the part of box `b` on the non-empty side of `p`
/// (`{x in b : n . (x - c) <= w}`), for fitting a stored plane to a plane given without geometry (a user's
/// vector file): the box corners on that side, and on each box edge that the plane crosses the crossing
/// point, moved outward (onto the plane or into the empty side) until an exact check confirms it, so
/// the hull of the points contains the exact region however the crossing rounds. When no part of the box
/// is on the non-empty side, the one corner nearest to it (any stored plane is conservative there).
pub fn region_points(b: &Aabb, p: &Plane) -> Vec<DVec3> {
    let e = ExactPlane::from_world(p, b);
    let corner = |m: usize| {
        DVec3::new(
            if m & 1 == 0 { b.min.x } else { b.max.x },
            if m & 2 == 0 { b.min.y } else { b.max.y },
            if m & 4 == 0 { b.min.z } else { b.max.z },
        )
    };
    let sides: Vec<BigRational> = (0..8).map(|m| e.side(corner(m))).collect();
    let mut pts: Vec<DVec3> = (0..8)
        .filter(|&m| !sides[m].is_positive())
        .map(corner)
        .collect();
    if pts.is_empty() {
        let m = (0..8)
            .min_by(|&i, &j| sides[i].cmp(&sides[j]))
            .expect("8 corners");
        return vec![corner(m)];
    }
    let c = (b.min + b.max) * 0.5;
    for m in 0..8usize {
        for a in 0..3 {
            let m2 = m | (1 << a);
            // Each edge once (from its low end), crossing from the non-empty to the empty side.
            if m2 == m || sides[m].is_positive() == sides[m2].is_positive() {
                continue;
            }
            let (inside, outside) = if sides[m].is_positive() {
                (m2, m)
            } else {
                (m, m2)
            };
            let (q0, q1) = (corner(inside), corner(outside));
            // n_a (x_a - c_a) = w - sum over the other axes; n_a is nonzero since the sides differ.
            let mut rest = p.w;
            for o in 0..3 {
                if o != a {
                    rest -= p.n[o] * (q0[o] - c[o]);
                }
            }
            let mut x = q0;
            x[a] = (c[a] + rest / p.n[a]).clamp(b.min[a], b.max[a]);
            let toward = q1[a] > q0[a];
            for _ in 0..64 {
                if !e.side(x).is_negative() || x[a] == q1[a] {
                    break;
                }
                x[a] = if toward {
                    x[a].next_up()
                } else {
                    x[a].next_down()
                };
            }
            if e.side(x).is_negative() {
                x = q1; // still short of the plane after 64 steps: the whole edge is kept
            }
            pts.push(x);
        }
    }
    pts
}

/// What a node of a cull-plane datapath stores, in bits: its box, and per plane a normal (three
/// components) and an offset. The storage figures of the node format come from here.
///
/// Two layouts:
/// * **own normals**: each node stores its box and `K` whole planes;
/// * **shared normals** (claim 8 of US 2025/0259373): the `s` children of a node use one set of `K`
///   normals, stored once for the group (beside the children's pointer in the parent, or in the first
///   child), and each child stores only its box and `K` offsets. [`crate::plane::generate::generate_shared`]
///   makes such planes.
///
/// Every record is rounded up to whole bytes: a node record, and a group's normal set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeLayout {
    /// The six box coordinates.
    pub box_bits: u32,
    /// One normal (three components).
    pub normal_bits: u32,
    /// One offset.
    pub offset_bits: u32,
}

impl NodeLayout {
    /// Bytes of a node with `k` planes of its own.
    pub fn own_bytes(&self, k: u32) -> u32 {
        (self.box_bits + k * (self.normal_bits + self.offset_bits)).div_ceil(8)
    }
    /// Bytes per node when groups of `siblings` nodes share one set of `k` normals: the node's box and
    /// offsets plus its share of the group's normal set.
    pub fn shared_bytes(&self, k: u32, siblings: u32) -> f64 {
        let node = (self.box_bits + k * self.offset_bits).div_ceil(8);
        let normals = (k * self.normal_bits).div_ceil(8);
        f64::from(node) + f64::from(normals) / f64::from(siblings.max(1))
    }
}

/// A plane in world space: geometry of the node satisfies `n . (p - c) <= w`, `c` the box centroid.
/// A zero normal is an unused plane slot (it culls nothing).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub n: DVec3,
    pub w: f64,
}

/// A node as the cull-plane tester sees it: its box and its planes (offsets from the box's centroid).
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneNode {
    pub bounds: Aabb,
    pub planes: Vec<Plane>,
}

impl Plane {
    /// Checks that the plane is finite; the error names the field.
    pub fn validate(&self, what: &str) -> Result<(), Error> {
        for a in 0..3 {
            if !self.n[a].is_finite() {
                return Err(Error::bad_value(
                    format!("{what} normal.{}", ["x", "y", "z"][a]),
                    self.n[a],
                    "plane normals must be finite",
                ));
            }
        }
        if !self.w.is_finite() {
            return Err(Error::bad_value(
                format!("{what} offset w"),
                self.w,
                "plane offsets must be finite",
            ));
        }
        Ok(())
    }
}

/// Output of the f64 reference: `culled`, and the clipped interval when not culled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipRef {
    pub culled: bool,
    pub t_entry: f64,
    pub t_exit: f64,
}

/// The f64 reference: the slab test of [`crate::slab::reference`], then every plane as in the module doc.
/// Round-to-nearest everywhere, so it is the meaning of the test, not a conservative datapath.
pub fn clip_ref(ray: &Ray, node: &PlaneNode) -> ClipRef {
    let s = crate::slab::reference::slab_ref(ray, &node.bounds);
    let c = (node.bounds.min + node.bounds.max) * 0.5;
    let (mut entry, mut exit) = (s.t_entry, s.t_exit);
    let mut culled = !s.hit;
    for p in &node.planes {
        let s0 = p.n.dot(ray.origin - c) - p.w;
        let den = p.n.dot(ray.dir);
        if den > 0.0 {
            exit = exit.min(-s0 / den);
        } else if den < 0.0 {
            entry = entry.max(-s0 / den);
        } else if s0 > 0.0 {
            culled = true;
        }
    }
    ClipRef {
        culled: culled || entry > exit,
        t_entry: entry,
        t_exit: exit,
    }
}

/// A half-space `n . p <= h` in world coordinates, exactly (a stored plane of some datapath, converted).
#[derive(Clone, Debug, PartialEq)]
pub struct ExactPlane {
    pub n: [BigRational; 3],
    pub h: BigRational,
}

impl ExactPlane {
    /// The world plane `n . (p - c) <= w` with `c` the centroid of `b`, exactly.
    pub fn from_world(p: &Plane, b: &Aabb) -> ExactPlane {
        let two = rat(2.0);
        let n = [rat(p.n.x), rat(p.n.y), rat(p.n.z)];
        let mut h = rat(p.w);
        for (a, na) in n.iter().enumerate() {
            h += na * (rat(b.min[a]) + rat(b.max[a])) / &two;
        }
        ExactPlane { n, h }
    }

    /// `n . p - h` at a world point, exactly (positive on the empty side).
    pub fn side(&self, p: DVec3) -> BigRational {
        let mut s = -self.h.clone();
        for a in 0..3 {
            s += &self.n[a] * rat(p[a]);
        }
        s
    }
}

/// The exact clip: the slab test on the world box, then every half-space, in rational arithmetic.
/// `hit` is false exactly when the node must be culled; `entry`/`exit` are the true clipped interval.
pub fn clip_exact(ray: &Ray, b: &Aabb, planes: &[ExactPlane]) -> ExactHit {
    let mut h = slab_exact(ray, b);
    if !h.hit {
        return h;
    }
    let o = [rat(ray.origin.x), rat(ray.origin.y), rat(ray.origin.z)];
    let d = [rat(ray.dir.x), rat(ray.dir.y), rat(ray.dir.z)];
    for p in planes {
        let mut s0 = -p.h.clone();
        let mut den = BigRational::zero();
        for a in 0..3 {
            s0 += &p.n[a] * &o[a];
            den += &p.n[a] * &d[a];
        }
        if den.is_zero() {
            if s0.is_positive() {
                h.hit = false;
            }
            continue;
        }
        let t = Ext::Fin(-s0 / &den);
        if den.is_positive() {
            h.exit = h.exit.min(t);
        } else {
            h.entry = h.entry.max(t);
        }
    }
    h.hit &= h.entry <= h.exit;
    h
}

/// The exact clip with the planes of a world node (for the reference's own checks).
pub fn clip_exact_world(ray: &Ray, node: &PlaneNode) -> ExactHit {
    let planes: Vec<ExactPlane> = node
        .planes
        .iter()
        .map(|p| ExactPlane::from_world(p, &node.bounds))
        .collect();
    clip_exact(ray, &node.bounds, &planes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(planes: Vec<Plane>) -> PlaneNode {
        PlaneNode {
            bounds: Aabb::new(DVec3::ZERO, DVec3::splat(2.0)).unwrap(),
            planes,
        }
    }

    #[test]
    fn region_points_enclose_the_box_part_on_the_non_empty_side() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(12);
        let mut kept = 0;
        for case in 0..300 {
            let lo = DVec3::new(
                rng.gen_range(-3.0..3.0),
                rng.gen_range(-3.0..3.0),
                rng.gen_range(-3.0..3.0),
            );
            let b = Aabb::new(lo, lo + DVec3::new(rng.gen_range(0.1..2.0), 0.7, 1.3)).unwrap();
            let n = DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                if case % 3 == 0 {
                    0.0
                } else {
                    rng.gen_range(-1.0..1.0)
                },
            );
            let p = Plane {
                n,
                w: rng.gen_range(-1.5..1.5),
            };
            let pts = region_points(&b, &p);
            assert!(!pts.is_empty());
            // The tightest plane of normal n over the points is never below w where the region is
            // non-empty (a hull inside the half-space would give a smaller offset than the true region).
            let c = (b.min + b.max) * 0.5;
            let e = ExactPlane::from_world(&p, &b);
            let inside: Vec<DVec3> = (0..200)
                .map(|_| b.min + (b.max - b.min) * DVec3::new(rng.gen(), rng.gen(), rng.gen()))
                .filter(|x| !e.side(*x).is_positive())
                .collect();
            kept += inside.len();
            // Every sampled point of the region is within the hull: check against random planes
            // through the hull's support (any direction u: max over points of u . x bounds u . sample).
            for _ in 0..20 {
                let u = DVec3::new(
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                );
                let hull = pts
                    .iter()
                    .map(|x| u.dot(*x - c))
                    .fold(f64::NEG_INFINITY, f64::max);
                for x in &inside {
                    assert!(
                        u.dot(*x - c) <= hull + 1e-12,
                        "case {case}: {x} outside the hull along {u}"
                    );
                }
            }
        }
        assert!(kept > 10_000, "{kept}");
    }

    #[test]
    fn node_bytes_with_own_and_shared_normals() {
        // b16 cull format: G = 16, N = 8, W = 28. Box 96 bits; a plane 24 + 28 bits.
        let l =
            crate::plane::fix::CullFixFormat::over(crate::format::fixed::FixFormat::b16()).layout();
        assert_eq!((l.box_bits, l.normal_bits, l.offset_bits), (96, 24, 28));
        assert_eq!(l.own_bytes(0), 12);
        assert_eq!(l.own_bytes(4), 38); // 304 bits
                                        // Siblings of a binary tree: 96 + 4 * 28 = 208 bits (26 bytes), plus half of 12 bytes of normals.
        assert_eq!(l.shared_bytes(4, 2), 32.0);
        assert_eq!(l.shared_bytes(1, 2), 16.0 + 1.5); // 124 bits round up to 16 bytes
                                                      // fp16: everything 16 bits; K = 2 own: 6 + 8 values, 28 bytes; shared by 4: 16 + 12 / 4.
        let f = crate::plane::float::CullFloatFormat::over(crate::format::float::FloatFormat::FP16)
            .layout();
        assert_eq!(f.own_bytes(2), 28);
        assert_eq!(f.shared_bytes(2, 4), 19.0);
    }

    #[test]
    fn a_diagonal_plane_cuts_the_empty_corner_off() {
        // Geometry lies on x + y <= 2 (the lower-left half of the box seen along z).
        let n = node(vec![Plane {
            n: DVec3::new(1.0, 1.0, 0.0),
            w: 0.0,
        }]);
        // Along -x at y = 1.75, through the empty upper corner.
        let r = Ray::new(
            DVec3::new(3.0, 1.75, 1.0),
            DVec3::new(-1.0, 0.0, 0.0),
            0.0,
            f64::INFINITY,
        )
        .unwrap();
        // Enters the box at x = 2 (t = 1) and the non-empty side at x = 0.25 (t = 2.75), leaves at t = 3.
        let c = clip_ref(&r, &n);
        assert!(!c.culled);
        assert_eq!((c.t_entry, c.t_exit), (2.75, 3.0));
        // With t_max = 2.5 the surviving part is gone: culled, and the oracle agrees.
        let short = Ray { t_max: 2.5, ..r };
        assert!(clip_ref(&short, &n).culled);
        assert!(!clip_exact_world(&short, &n).hit);
        let e = clip_exact_world(&r, &n);
        assert!(e.hit && e.entry == Ext::Fin(rat(2.75)) && e.exit == Ext::Fin(rat(3.0)));
    }

    #[test]
    fn a_ray_parallel_to_a_plane_is_culled_only_on_the_empty_side() {
        let n = node(vec![Plane {
            n: DVec3::new(0.0, 1.0, 0.0),
            w: 0.5,
        }]);
        let along = |y: f64| Ray::new(DVec3::new(-1.0, y, 1.0), DVec3::X, 0.0, 10.0).unwrap();
        assert!(clip_ref(&along(1.9), &n).culled);
        assert!(!clip_exact_world(&along(1.9), &n).hit);
        // On the plane itself (closed non-empty side): kept.
        assert!(!clip_ref(&along(1.5), &n).culled);
        assert!(clip_exact_world(&along(1.5), &n).hit);
    }
}
