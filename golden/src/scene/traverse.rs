//! BVH traversal that counts its work, with pluggable node testers.
//!
//! [`closest_hit`] is the usual stack-based, front-to-back closest-hit traversal (e.g. Pharr, Jakob and
//! Humphreys, *Physically Based Rendering*, 3rd ed., §4.4.2): a node's children are both tested, the
//! nearer (by the tester's entry `lo`) is visited first, and a popped node whose `lo` lies beyond the
//! closest hit so far is skipped. The ray's `t_max` shrinks to the closest hit found so far: the hit `t`
//! is exact ([`BigRational`]), and the rays handed to the tester and to the triangle test carry it
//! rounded *up* to f64, so nothing at or before the hit is ever cut off by the shrink.
//!
//! Triangles are tested with [`tri_hit`], which always equals the exact test, so the result depends only
//! on the tester's culling. The hit reported is the smallest `(t, triangle index)`: the smallest exact
//! `t`, ties to the lowest triangle index. With a conservative tester (one that never culls a node whose
//! geometry the ray meets in its range, and whose `[lo, hi]` encloses where it does) the result is
//! exactly [`brute_force_closest`]'s, whatever the tree; [`AabbOnly`] is such a tester. [`PlaneRef`],
//! the f64 reference of the cull-plane tester, rounds to nearest and is *not* guaranteed conservative:
//! measuring how often it differs is one of the things this module is for.

use crate::error::Error;
use crate::exact::{slab_exact, Ext};
use crate::geom::{Aabb, Ray};
use crate::plane::clip::{clip_ref, Plane, PlaneNode};
use crate::scene::bvh::{Bvh, NodeKind};
use crate::scene::tri::{round_up, tri_hit, Triangle};
use crate::scene::tri_scene::TriScene;
use num_rational::BigRational;

/// A node test as the traversal sees it.
pub trait NodeTester {
    /// `None`: the node is culled (no geometry of it can be hit by the ray in its t range).
    /// `Some((lo, hi))`: conservative world-t bounds of where the ray may meet the node's geometry.
    fn test(&mut self, ray: &Ray, node: usize) -> Option<(f64, f64)>;
}

/// Work counters of one or more traversals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraversalStats {
    /// Rays traced.
    pub rays: u64,
    /// Calls of the node tester (the root included).
    pub node_tests: u64,
    /// Node tests that culled the node.
    pub nodes_culled: u64,
    /// Leaves whose triangles were tested.
    pub leaves_visited: u64,
    /// Ray-triangle tests.
    pub tri_tests: u64,
    /// Rays that hit something.
    pub hits: u64,
}

impl TraversalStats {
    /// Adds another set of counters to this one.
    pub fn add(&mut self, o: &TraversalStats) {
        self.rays += o.rays;
        self.node_tests += o.node_tests;
        self.nodes_culled += o.nodes_culled;
        self.leaves_visited += o.leaves_visited;
        self.tri_tests += o.tri_tests;
        self.hits += o.hits;
    }
}

/// A hit: the triangle's index in the scene and the exact ray parameter.
pub type Hit = (usize, BigRational);

/// True when `(t, i)` comes before `best` in the tie rule (smaller t, then smaller index).
fn better(t: &BigRational, i: usize, best: &Option<Hit>) -> bool {
    match best {
        None => true,
        Some((bi, bt)) => t < bt || (t == bt && i < *bi),
    }
}

fn test_counted<T: NodeTester>(
    tester: &mut T,
    ray: &Ray,
    node: usize,
    stats: &mut TraversalStats,
) -> Option<(f64, f64)> {
    stats.node_tests += 1;
    let r = tester.test(ray, node);
    if r.is_none() {
        stats.nodes_culled += 1;
    }
    r
}

/// The closest hit of `ray` among `tris` (which `bvh` was built over), as in the module doc.
pub fn closest_hit<T: NodeTester>(
    bvh: &Bvh,
    tris: &[Triangle],
    ray: &Ray,
    tester: &mut T,
    stats: &mut TraversalStats,
) -> Option<Hit> {
    stats.rays += 1;
    let mut best: Option<Hit> = None;
    let mut cur = *ray;
    let mut stack: Vec<(usize, f64)> = Vec::with_capacity(64);
    if let Some((lo, _)) = test_counted(tester, &cur, 0, stats) {
        stack.push((0, lo));
    }
    while let Some((n, lo)) = stack.pop() {
        if lo > cur.t_max {
            continue;
        }
        match bvh.nodes[n].kind {
            NodeKind::Leaf { .. } => {
                stats.leaves_visited += 1;
                for &ti in bvh.leaf_tris(n) {
                    stats.tri_tests += 1;
                    if let Some(t) = tri_hit(&cur, &tris[ti]) {
                        if better(&t, ti, &best) {
                            cur.t_max = round_up(&t).min(ray.t_max);
                            best = Some((ti, t));
                        }
                    }
                }
            }
            NodeKind::Inner { left, right } => {
                let l = test_counted(tester, &cur, left, stats);
                let r = test_counted(tester, &cur, right, stats);
                match (l, r) {
                    (Some((ll, _)), Some((rl, _))) => {
                        // Far child first on the stack, so the near one is popped first.
                        if rl < ll {
                            stack.push((left, ll));
                            stack.push((right, rl));
                        } else {
                            stack.push((right, rl));
                            stack.push((left, ll));
                        }
                    }
                    (Some((ll, _)), None) => stack.push((left, ll)),
                    (None, Some((rl, _))) => stack.push((right, rl)),
                    (None, None) => {}
                }
            }
        }
    }
    if best.is_some() {
        stats.hits += 1;
    }
    best
}

/// Whether `ray` hits anything in its range (shadow rays): stops at the first hit found.
pub fn any_hit<T: NodeTester>(
    bvh: &Bvh,
    tris: &[Triangle],
    ray: &Ray,
    tester: &mut T,
    stats: &mut TraversalStats,
) -> bool {
    stats.rays += 1;
    let mut stack: Vec<usize> = Vec::with_capacity(64);
    if test_counted(tester, ray, 0, stats).is_some() {
        stack.push(0);
    }
    while let Some(n) = stack.pop() {
        match bvh.nodes[n].kind {
            NodeKind::Leaf { .. } => {
                stats.leaves_visited += 1;
                for &ti in bvh.leaf_tris(n) {
                    stats.tri_tests += 1;
                    if tri_hit(ray, &tris[ti]).is_some() {
                        stats.hits += 1;
                        return true;
                    }
                }
            }
            NodeKind::Inner { left, right } => {
                if test_counted(tester, ray, right, stats).is_some() {
                    stack.push(right);
                }
                if test_counted(tester, ray, left, stats).is_some() {
                    stack.push(left);
                }
            }
        }
    }
    false
}

/// The exact closest hit by testing every triangle (same tie rule), for checking traversals.
pub fn brute_force_closest(tris: &[Triangle], ray: &Ray) -> Option<Hit> {
    let mut best = None;
    for (i, t) in tris.iter().enumerate() {
        if let Some(h) = tri_hit(ray, t) {
            if better(&h, i, &best) {
                best = Some((i, h));
            }
        }
    }
    best
}

// ---------------------------------------------------------------------------------------------------
// Testers.

/// A conservative f64 slab test: the slab method of [`crate::slab::reference`] with every per-axis distance
/// widened outward by `4 eps |t| + MIN_POSITIVE`. Each distance `(b - o) * (1 / d)` has three roundings,
/// a relative error below `3.01 u = 1.51 eps`, so the widened interval encloses the exact one (and the
/// widening's own rounding is covered by the slack). When a distance is not finite (a tiny `d` whose
/// inverse overflows) it falls back to [`slab_exact`], rounded outward. `None` only when the exact
/// test misses.
pub fn slab_conservative(ray: &Ray, b: &Aabb) -> Option<(f64, f64)> {
    if b.is_empty() {
        return None;
    }
    let (mut lo, mut hi) = (ray.t_min, ray.t_max);
    for a in 0..3 {
        let (o, d) = (ray.origin[a], ray.dir[a]);
        if d == 0.0 {
            if !(b.min[a] <= o && o <= b.max[a]) {
                return None;
            }
            continue;
        }
        let inv = 1.0 / d;
        let (mut t0, mut t1) = ((b.min[a] - o) * inv, (b.max[a] - o) * inv);
        if !(t0.is_finite() && t1.is_finite()) {
            return slab_exact_outward(ray, b);
        }
        if inv < 0.0 {
            std::mem::swap(&mut t0, &mut t1);
        }
        let slack = 4.0 * f64::EPSILON;
        lo = lo.max(t0 - (t0.abs() * slack + f64::MIN_POSITIVE));
        hi = hi.min(t1 + (t1.abs() * slack + f64::MIN_POSITIVE));
    }
    (lo <= hi).then_some((lo, hi))
}

/// The exact slab test with its interval rounded outward to f64.
pub fn slab_exact_outward(ray: &Ray, b: &Aabb) -> Option<(f64, f64)> {
    let h = slab_exact(ray, b);
    h.hit
        .then(|| (Ext::down_f64(&h.entry), Ext::up_f64(&h.exit)))
}

/// The box-only tester: [`slab_conservative`] on the node's bounds (conservative).
pub struct AabbOnly<'a> {
    pub bvh: &'a Bvh,
}

impl<'a> AabbOnly<'a> {
    pub fn new(bvh: &'a Bvh) -> Self {
        AabbOnly { bvh }
    }
}

impl NodeTester for AabbOnly<'_> {
    fn test(&mut self, ray: &Ray, node: usize) -> Option<(f64, f64)> {
        slab_conservative(ray, &self.bvh.nodes[node].bounds)
    }
}

/// The cull-plane reference tester: [`clip_ref`] (f64, round to nearest) with each node's planes. Not
/// guaranteed conservative.
pub struct PlaneRef {
    pub nodes: Vec<PlaneNode>,
}

impl PlaneRef {
    /// One [`PlaneNode`] per BVH node. Error when `planes` does not have one entry per node or a plane
    /// is not finite (the error names the node).
    pub fn new(bvh: &Bvh, planes: &[Vec<Plane>]) -> Result<PlaneRef, Error> {
        if planes.len() != bvh.nodes.len() {
            return Err(Error::Io(format!(
                "cull planes: {} plane lists for a BVH of {} nodes",
                planes.len(),
                bvh.nodes.len()
            )));
        }
        let mut nodes = Vec::with_capacity(planes.len());
        for (i, (n, ps)) in bvh.nodes.iter().zip(planes).enumerate() {
            for (k, p) in ps.iter().enumerate() {
                p.validate(&format!("node {i} plane {k}"))?;
            }
            nodes.push(PlaneNode {
                bounds: n.bounds,
                planes: ps.clone(),
            });
        }
        Ok(PlaneRef { nodes })
    }
}

impl NodeTester for PlaneRef {
    fn test(&mut self, ray: &Ray, node: usize) -> Option<(f64, f64)> {
        let c = clip_ref(ray, &self.nodes[node]);
        (!c.culled).then_some((c.t_entry, c.t_exit))
    }
}

// ---------------------------------------------------------------------------------------------------
// Batches.

/// Closest hits of every ray, with the summed counters.
pub fn trace<T: NodeTester>(
    bvh: &Bvh,
    tris: &[Triangle],
    rays: &[Ray],
    tester: &mut T,
) -> (Vec<Option<Hit>>, TraversalStats) {
    let mut stats = TraversalStats::default();
    let hits = rays
        .iter()
        .map(|r| closest_hit(bvh, tris, r, tester, &mut stats))
        .collect();
    (hits, stats)
}

/// The work of tracing `rays` through `scene` (closest hit) with `tester` on `bvh` (built over
/// `scene.tris`; the cull planes, if any, live in the tester).
pub fn measure<T: NodeTester>(
    scene: &TriScene,
    rays: &[Ray],
    bvh: &Bvh,
    tester: &mut T,
) -> TraversalStats {
    trace(bvh, &scene.tris, rays, tester).1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plane::generate::generate;
    use crate::scene::tri::{random_point, random_triangle, random_unit, ray_at_triangle};
    use crate::scene::tri_scene::{self as scene, primary_rays, secondary_rays};
    use glam::DVec3;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    #[test]
    fn conservative_slab_encloses_the_exact_interval() {
        let mut rng = Pcg64::seed_from_u64(2);
        let mut hits = 0;
        for i in 0..50_000 {
            let lo = random_point(&mut rng, DVec3::splat(-10.0), DVec3::splat(10.0));
            let b = Aabb::new(
                lo,
                lo + random_point(&mut rng, DVec3::ZERO, DVec3::splat(5.0)),
            )
            .unwrap();
            let origin = random_point(&mut rng, DVec3::splat(-20.0), DVec3::splat(20.0));
            // Aim at a corner or an edge point half of the time (grazing), else anywhere near the box.
            let target = if i % 2 == 0 {
                let mut p = DVec3::ZERO;
                for a in 0..3 {
                    p[a] = if rng.gen_bool(0.5) {
                        b.min[a]
                    } else {
                        b.max[a]
                    };
                }
                if i % 4 == 0 {
                    p.x = rng.gen_range(b.min.x..=b.max.x);
                }
                p
            } else {
                random_point(&mut rng, b.min - 1.0, b.max + 1.0)
            };
            let mut dir = target - origin;
            if i % 7 == 0 {
                dir.y = 0.0;
            }
            if dir == DVec3::ZERO {
                continue;
            }
            let t_max = if i % 3 == 0 { 1.0 } else { f64::INFINITY };
            let r = Ray::new(origin, dir, 0.0, t_max).unwrap();
            let e = slab_exact(&r, &b);
            let c = slab_conservative(&r, &b);
            if e.hit {
                hits += 1;
                let (l, h) = c.unwrap_or_else(|| panic!("culled a true hit: {r:?} {b:?}"));
                assert!(Ext::from_f64(l) <= e.entry && e.exit <= Ext::from_f64(h));
            }
        }
        assert!(hits > 10_000);
        // Subnormal direction: the inverse overflows, the exact fallback answers.
        let b = Aabb::new(DVec3::ZERO, DVec3::ONE).unwrap();
        let r = Ray::new(
            DVec3::new(0.5, 0.5, -1.0),
            DVec3::new(1e-310, 0.0, 1.0),
            0.0,
            10.0,
        )
        .unwrap();
        assert!(slab_conservative(&r, &b).is_some());
    }

    fn small_scene(seed: u64, n: usize) -> Vec<Triangle> {
        let mut rng = Pcg64::seed_from_u64(seed);
        (0..n)
            .map(|_| random_triangle(&mut rng, DVec3::splat(-5.0), DVec3::splat(5.0), 1.5))
            .collect()
    }

    #[test]
    fn aabb_only_traversal_equals_brute_force() {
        let mut rng = Pcg64::seed_from_u64(9);
        for seed in 0..6 {
            let mut tris = small_scene(seed, 150);
            // Shared vertices and duplicate triangles, to exercise the tie rule.
            tris.push(tris[0]);
            tris.push(Triangle::new(tris[1].v[0], tris[1].v[1], tris[2].v[2]));
            let bvh = Bvh::build(&tris, 1 + seed as usize % 4).unwrap();
            let mut tester = AabbOnly::new(&bvh);
            let mut stats = TraversalStats::default();
            for i in 0..400 {
                let r = if i % 2 == 0 {
                    let tri = tris[rng.gen_range(0..tris.len())];
                    ray_at_triangle(&mut rng, &tri, 8.0, i % 4 == 0)
                } else {
                    let o = random_point(&mut rng, DVec3::splat(-8.0), DVec3::splat(8.0));
                    Ray::new(o, random_unit(&mut rng), 0.0, rng.gen_range(1.0..20.0)).unwrap()
                };
                let want = brute_force_closest(&tris, &r);
                let got = closest_hit(&bvh, &tris, &r, &mut tester, &mut stats);
                assert_eq!(got, want, "seed {seed} ray {i}: {r:?}");
                let any = any_hit(&bvh, &tris, &r, &mut tester, &mut TraversalStats::default());
                assert_eq!(any, want.is_some());
            }
            // The tree saves work against brute force.
            assert!(stats.tri_tests < 400 * tris.len() as u64 / 4, "{stats:?}");
        }
        // The duplicate triangle: the lower index wins.
        let tris = small_scene(0, 150);
        let mut dup = tris.clone();
        dup.push(tris[0]);
        let c = tris[0].centroid();
        let r = Ray::new(c + tris[0].normal(), -tris[0].normal(), 0.0, f64::INFINITY).unwrap();
        let bvh = Bvh::build(&dup, 2).unwrap();
        let h = closest_hit(
            &bvh,
            &dup,
            &r,
            &mut AabbOnly::new(&bvh),
            &mut TraversalStats::default(),
        );
        assert_eq!(
            h.as_ref().map(|h| h.0),
            brute_force_closest(&dup, &r).map(|h| h.0)
        );
        assert_ne!(h.map(|h| h.0), Some(150));
    }

    #[test]
    fn plane_ref_does_fewer_triangle_tests_on_grass() {
        let s = scene::grass(1, 1500);
        let bvh = Bvh::build(&s.tris, 4).unwrap();
        let planes = generate(&bvh, &s.tris, 4).unwrap();
        let rays = primary_rays(&s, 32, 24);
        let (want, aabb) = trace(&bvh, &s.tris, &rays, &mut AabbOnly::new(&bvh));
        let mut pr = PlaneRef::new(&bvh, &planes).unwrap();
        let (got, with) = trace(&bvh, &s.tris, &rays, &mut pr);
        let differ = want.iter().zip(&got).filter(|(a, b)| a != b).count();
        eprintln!(
            "grass 32x24: AabbOnly {aabb:?}\n PlaneRef K=4 {with:?}\n differing hits {differ}"
        );
        assert!(with.tri_tests < aabb.tri_tests, "{with:?} vs {aabb:?}");
        assert!(
            differ * 20 < rays.len(),
            "{differ} of {} hits differ",
            rays.len()
        );
        // Secondary rays run too, and any_hit agrees with closest_hit on shadow rays for AabbOnly.
        let sec = secondary_rays(&s, &rays, &want, 4);
        let mut st = TraversalStats::default();
        for r in sec.shadow.iter().take(100) {
            let a = any_hit(&bvh, &s.tris, r, &mut AabbOnly::new(&bvh), &mut st);
            assert_eq!(a, brute_force_closest(&s.tris, r).is_some());
        }
    }

    #[test]
    fn plane_ref_rejects_mismatched_planes() {
        let tris = small_scene(1, 20);
        let bvh = Bvh::build(&tris, 4).unwrap();
        assert!(PlaneRef::new(&bvh, &[]).is_err());
        let mut planes = vec![Vec::new(); bvh.nodes.len()];
        planes[0].push(Plane {
            n: DVec3::new(f64::NAN, 0.0, 0.0),
            w: 0.0,
        });
        let e = PlaneRef::new(&bvh, &planes).err().unwrap().to_string();
        assert!(e.contains("node 0 plane 0"), "{e}");
    }

    /// On every built-in scene, the exact cull planes (1 and 4 per node, `PlaneRef`) keep every closest
    /// hit of the AABB-only traversal, primary and bounce rays, and save triangle tests (the per-format
    /// figures are `rtu cull-scenes`).
    #[test]
    fn exact_planes_keep_every_closest_hit_and_save_triangle_tests() {
        for name in ["grass", "room", "mesh", "soup"] {
            let s = scene::by_name(name, 1, None).unwrap();
            let bvh = Bvh::build(&s.tris, 4).unwrap();
            let prim = primary_rays(&s, 24, 16);
            let (want, aabb) = trace(&bvh, &s.tris, &prim, &mut AabbOnly::new(&bvh));
            let sec = secondary_rays(&s, &prim, &want, 2);
            let (want_b, aabb_b) = trace(&bvh, &s.tris, &sec.bounce, &mut AabbOnly::new(&bvh));
            assert!(aabb.hits > 0 && aabb_b.hits > 0, "{name}: rays that hit");
            for k in [1, 4] {
                let planes = generate(&bvh, &s.tris, k).unwrap();
                let mut pr = PlaneRef::new(&bvh, &planes).unwrap();
                let (got, st) = trace(&bvh, &s.tris, &prim, &mut pr);
                let (got_b, st_b) = trace(&bvh, &s.tris, &sec.bounce, &mut pr);
                assert_eq!(got, want, "{name} K={k}: primary closest hits");
                assert_eq!(got_b, want_b, "{name} K={k}: bounce closest hits");
                assert!(
                    st.tri_tests + st_b.tri_tests < aabb.tri_tests + aabb_b.tri_tests,
                    "{name} K={k}: {} + {} triangle tests, AABB only {} + {}",
                    st.tri_tests,
                    st_b.tri_tests,
                    aabb.tri_tests,
                    aabb_b.tri_tests
                );
            }
        }
    }
}
