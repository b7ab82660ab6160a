//! Cull-plane generation for a BVH, in world f64 with exact offsets.
//!
//! Follows Arm's application US 2025/0259373, paragraphs 0217-0238: a node's box gets up to `K` planes,
//! each a normal `n` pointing at the empty side and an offset `w` from the box centroid
//! `c = (min + max) / 2`, such that all of the node's geometry satisfies `n . (p - c) <= w`
//! ([`crate::plane::clip::Plane`]). The steps:
//!
//! 1. **Directions.** The candidate normals are the 98 primitive integer vectors with components in
//!    `-2..=2` ([`directions`]): every non-zero vector of `{-2..2}^3` whose components have gcd 1, so no
//!    two point the same way. They include the 6 axes (which cut nothing the box does not already cut,
//!    unless the box is re-used by a parent), the 12 face diagonals, the 8 space diagonals and the 72
//!    in-between directions with a 2. Integer normals keep `n . p` nearly exact in f64 and cheap in
//!    hardware.
//! 2. **Fit.** For a direction `n` the tightest offset is `w = max over the vertices of n . (p - c)`.
//!    The maximising vertex is found with an f64 comparison that falls back to exact dyadic arithmetic
//!    when two candidates are within the f64 error bound, and `w` is computed exactly and rounded *up*
//!    to f64 ([`fit_offset`]): every vertex satisfies `n . (p - c) <= w` exactly. Triangles are convex
//!    hulls of their vertices, so the whole triangle is then on the non-empty side.
//! 3. **Score.** A plane is worth the empty part of the box it cuts off,
//!    `{p in box : n . (p - c) > w}`, measured by [`empty_fraction`] (its share of the box) with the
//!    closed form for a box cut by a half-space (inclusion-exclusion over the box's corners, e.g.
//!    Barrow and Smith, "Spline notation applied to a volume problem", Amer. Math. Monthly 86(1), 1979:
//!    the volume of `{x in prod [0, a_i] : sum x_i <= s}` is
//!    `1/d! * sum over corners v of (-1)^|v| max(0, s - a . v)^d` after scaling each axis by `n_i`). Axes
//!    on which the box is flat, or along which `n` is zero, factor out, so a flat box (a wall made of
//!    axis-aligned triangles) is scored by area instead of by a volume that would be zero.
//! 4. **Leaves.** For every one of the 8 octants of normal sign patterns (bit `a` of the octant is set
//!    when `n[a] < 0`; a zero component counts as positive) the direction with the largest empty
//!    fraction; of these 8 the `K` best, dropping every plane that cuts nothing (`w` not below the
//!    largest `n . (p - c)` over the box, decided exactly).
//! 5. **Inner nodes.** Candidates are the normals of the children's planes (the patent's propagation
//!    towards the root); each is re-fitted over all vertices of the subtree and scored in the node's own
//!    box; the `K` best that cut something are kept.
//!
//! Ties in scores go to the lower direction index, so generation is deterministic. Output: one
//! `Vec<Plane>` per BVH node, indexed like [`crate::scene::bvh::Bvh::nodes`] (empty: no planes).

use crate::error::Error;
use crate::geom::Aabb;
use crate::plane::clip::Plane;
use crate::scene::bvh::{Bvh, NodeKind};
use crate::scene::tri::{round_up, Dyadic, Triangle};
use glam::DVec3;
use std::cmp::Ordering;

/// Most planes a node may get.
pub const MAX_PLANES: usize = 8;

/// Number of candidate directions.
pub const NUM_DIRECTIONS: usize = 98;

fn gcd(a: i32, b: i32) -> i32 {
    if b == 0 {
        a.abs()
    } else {
        gcd(b, a % b)
    }
}

/// The 98 primitive integer directions with components in `-2..=2`, in a fixed order (x slowest).
pub fn directions() -> Vec<DVec3> {
    let mut out = Vec::with_capacity(NUM_DIRECTIONS);
    for x in -2..=2 {
        for y in -2..=2 {
            for z in -2..=2 {
                if gcd(gcd(x, y), z) == 1 {
                    out.push(DVec3::new(x as f64, y as f64, z as f64));
                }
            }
        }
    }
    out
}

/// The octant of a normal: bit `a` set when `n[a] < 0` (zero counts as positive).
pub fn octant(n: DVec3) -> usize {
    (0..3).filter(|&a| n[a] < 0.0).map(|a| 1 << a).sum()
}

fn dy3(p: DVec3) -> [Dyadic; 3] {
    [
        Dyadic::from_f64(p.x),
        Dyadic::from_f64(p.y),
        Dyadic::from_f64(p.z),
    ]
}

fn dy_dot(n: DVec3, p: &[Dyadic; 3]) -> Dyadic {
    let nd = dy3(n);
    nd[0]
        .mul(&p[0])
        .add(&nd[1].mul(&p[1]))
        .add(&nd[2].mul(&p[2]))
}

/// `n . p` in f64 and a bound on its error (the products by small integers are exact unless they
/// overflow; two additions round).
fn approx_dot(n: DVec3, p: DVec3) -> (f64, f64) {
    let t = n * p;
    let v = t.x + t.y + t.z;
    let mag = t.x.abs() + t.y.abs() + t.z.abs();
    (v, 3.0 * f64::EPSILON * mag + 1e-300)
}

/// Compares `n . p` with `n . q` exactly (f64 first, exact dyadics when too close to call).
fn cmp_along(n: DVec3, p: DVec3, q: DVec3) -> Ordering {
    let (a, ea) = approx_dot(n, p);
    let (b, eb) = approx_dot(n, q);
    if a.is_finite() && b.is_finite() && ea.is_finite() && eb.is_finite() {
        if a - ea > b + eb {
            return Ordering::Greater;
        }
        if a + ea < b - eb {
            return Ordering::Less;
        }
    }
    dy_dot(n, &dy3(p)).cmp(&dy_dot(n, &dy3(q)))
}

fn centroid_dy(b: &Aabb) -> [Dyadic; 3] {
    let half = Dyadic::from_f64(0.5);
    let (lo, hi) = (dy3(b.min), dy3(b.max));
    [
        lo[0].add(&hi[0]).mul(&half),
        lo[1].add(&hi[1]).mul(&half),
        lo[2].add(&hi[2]).mul(&half),
    ]
}

/// `n . (p - c)` for the exact centroid `c` of `b`, rounded up to f64.
fn offset_up(n: DVec3, p: DVec3, b: &Aabb) -> f64 {
    let c = centroid_dy(b);
    let pd = dy3(p);
    let diff = [pd[0].sub(&c[0]), pd[1].sub(&c[1]), pd[2].sub(&c[2])];
    round_up(&dy_dot(n, &diff).to_rational())
}

/// The tightest conservative offset: `max over points of n . (p - c)`, `c` the centroid of `b`, computed
/// exactly and rounded up to f64. `points` must be non-empty and finite.
pub fn fit_offset(n: DVec3, points: &[DVec3], b: &Aabb) -> f64 {
    let best = points
        .iter()
        .copied()
        .reduce(|a, p| {
            if cmp_along(n, p, a) == Ordering::Greater {
                p
            } else {
                a
            }
        })
        .expect("fit_offset needs at least one point");
    offset_up(n, best, b)
}

/// True when the plane removes some part of the box: `w` is below the largest `n . (p - c)` over the
/// box, `sum |n_a| (max_a - min_a) / 2`, decided exactly.
pub fn cuts_something(b: &Aabb, p: &Plane) -> bool {
    let half = Dyadic::from_f64(0.5);
    let (lo, hi) = (dy3(b.min), dy3(b.max));
    let mut reach = Dyadic::from_f64(0.0);
    for a in 0..3 {
        let ext = hi[a].sub(&lo[a]).mul(&half);
        reach = reach.add(&Dyadic::from_f64(p.n[a].abs()).mul(&ext));
    }
    Dyadic::from_f64(p.w).cmp(&reach) == Ordering::Less
}

/// Volume of `{y in prod [0, a_i] : sum y_i <= s}` divided by `prod a_i` (all `a_i > 0`).
fn simplex_cut_fraction(a: &[f64], s: f64) -> f64 {
    let d = a.len();
    let total: f64 = a.iter().sum();
    if s <= 0.0 {
        return 0.0;
    }
    if s >= total {
        return 1.0;
    }
    let mut fact = 1.0;
    let mut prod = 1.0;
    for (i, ai) in a.iter().enumerate() {
        fact *= (i + 1) as f64;
        prod *= ai;
    }
    let mut sum = 0.0;
    for mask in 0..(1usize << d) {
        let mut off = 0.0;
        let mut sign = 1.0;
        for (i, ai) in a.iter().enumerate() {
            if mask >> i & 1 == 1 {
                off += ai;
                sign = -sign;
            }
        }
        let r = s - off;
        if r > 0.0 {
            sum += sign * r.powi(d as i32);
        }
    }
    (sum / (fact * prod)).clamp(0.0, 1.0)
}

/// Share of the box on the empty side of the plane, in `[0, 1]`: `|{p in box : n . (p - c) > w}|`
/// divided by `|box|`, where `|.|` is the volume over the axes on which the box is not flat (area for a
/// flat box, length for a segment; a point box: 1 when `w < 0`, else 0). f64, for ranking and reports.
pub fn empty_fraction(b: &Aabb, p: &Plane) -> f64 {
    if b.is_empty() {
        return 0.0;
    }
    let ext = b.max - b.min;
    // Scaled axis lengths a_i = |n_i| L_i over the axes that matter.
    let a: Vec<f64> = (0..3)
        .filter(|&i| ext[i] > 0.0 && p.n[i] != 0.0)
        .map(|i| p.n[i].abs() * ext[i])
        .collect();
    let total: f64 = a.iter().sum();
    // Non-empty side: sum y_i <= s with s = w + total / 2 (after flipping axes so that n_i > 0).
    let s = p.w + total * 0.5;
    if a.is_empty() {
        return if p.w < 0.0 { 1.0 } else { 0.0 };
    }
    // Evaluate whichever side is the smaller region, for accuracy (symmetry y -> a - y).
    if s <= total * 0.5 {
        1.0 - simplex_cut_fraction(&a, s)
    } else {
        simplex_cut_fraction(&a, total - s)
    }
}

/// The empty volume `|{p in box : n . (p - c) > w}|` in world units cubed (zero for a flat box).
pub fn empty_volume(b: &Aabb, p: &Plane) -> f64 {
    if b.is_empty() {
        return 0.0;
    }
    let e = b.max - b.min;
    let vol = e.x * e.y * e.z;
    if vol == 0.0 {
        0.0
    } else {
        empty_fraction(b, p) * vol
    }
}

/// Per node and direction: the vertex of the node's subtree that maximises `n . p` (exactly).
fn extreme_points(bvh: &Bvh, tris: &[Triangle], dirs: &[DVec3]) -> Vec<Vec<DVec3>> {
    let mut ext: Vec<Vec<DVec3>> = vec![Vec::new(); bvh.nodes.len()];
    // Children have larger indices than their parent: walk backwards.
    for i in (0..bvh.nodes.len()).rev() {
        let row: Vec<DVec3> = match bvh.nodes[i].kind {
            NodeKind::Leaf { .. } => {
                let verts: Vec<DVec3> = bvh.leaf_tris(i).iter().flat_map(|&t| tris[t].v).collect();
                dirs.iter()
                    .map(|&n| {
                        verts
                            .iter()
                            .copied()
                            .reduce(|a, p| {
                                if cmp_along(n, p, a) == Ordering::Greater {
                                    p
                                } else {
                                    a
                                }
                            })
                            .unwrap_or(DVec3::ZERO)
                    })
                    .collect()
            }
            NodeKind::Inner { left, right } => dirs
                .iter()
                .enumerate()
                .map(|(j, &n)| {
                    let (p, q) = (ext[left][j], ext[right][j]);
                    if cmp_along(n, q, p) == Ordering::Greater {
                        q
                    } else {
                        p
                    }
                })
                .collect(),
        };
        ext[i] = row;
    }
    ext
}

/// A scored candidate: direction index and empty fraction (with the f64 offset).
struct Cand {
    j: usize,
    frac: f64,
}

fn best_k(mut cands: Vec<Cand>, k: usize) -> Vec<usize> {
    // Stable sort by fraction, descending; ties keep the lower direction index first.
    cands.sort_by_key(|c| c.j);
    cands.sort_by(|a, b| b.frac.total_cmp(&a.frac));
    cands.into_iter().take(k).map(|c| c.j).collect()
}

/// The best direction of each of the 8 octants by `score` (ties: lower index), then the `K` best.
fn octant_best(dirs: &[DVec3], score: impl Fn(usize) -> f64) -> Vec<Cand> {
    let mut best: [Option<Cand>; 8] = Default::default();
    for (j, &n) in dirs.iter().enumerate() {
        let frac = score(j);
        let o = octant(n);
        if best[o].as_ref().is_none_or(|b| frac > b.frac) {
            best[o] = Some(Cand { j, frac });
        }
    }
    best.into_iter().flatten().collect()
}

fn check_args(bvh: &Bvh, tris: &[Triangle], k: usize) -> Result<(), Error> {
    if !(1..=MAX_PLANES).contains(&k) {
        return Err(Error::BadFormat {
            param: "planes per node",
            value: k as i64,
            why: format!("the number of cull planes per node must be in 1..={MAX_PLANES}"),
        });
    }
    if bvh.tri_index.len() != tris.len() || bvh.tri_index.iter().any(|&t| t >= tris.len()) {
        return Err(Error::Io(format!(
            "plane generation: the BVH covers {} triangles but the scene has {}",
            bvh.tri_index.len(),
            tris.len()
        )));
    }
    Ok(())
}

/// The plane of direction `j` fitted tightly (rounded up) to node `i`'s subtree.
fn fitted(bvh: &Bvh, ext: &[Vec<DVec3>], dirs: &[DVec3], i: usize, j: usize) -> Plane {
    let n = dirs[j];
    Plane {
        n,
        w: offset_up(n, ext[i][j], &bvh.nodes[i].bounds),
    }
}

/// The share of node `i`'s box that direction `j`'s tight plane cuts off (f64, for ranking).
fn fraction(bvh: &Bvh, ext: &[Vec<DVec3>], dirs: &[DVec3], i: usize, j: usize) -> f64 {
    let b = bvh.nodes[i].bounds;
    let c = (b.min + b.max) * 0.5;
    let n = dirs[j];
    empty_fraction(
        &b,
        &Plane {
            n,
            w: n.dot(ext[i][j] - c),
        },
    )
}

/// Generates up to `k` planes for every node of `bvh` (built over `tris`). Errors: `k` outside
/// `1..=MAX_PLANES`, or a tree that does not match the triangles.
pub fn generate(bvh: &Bvh, tris: &[Triangle], k: usize) -> Result<Vec<Vec<Plane>>, Error> {
    check_args(bvh, tris, k)?;
    let dirs = directions();
    let ext = extreme_points(bvh, tris, &dirs);
    let mut chosen: Vec<Vec<usize>> = vec![Vec::new(); bvh.nodes.len()];
    let mut planes: Vec<Vec<Plane>> = vec![Vec::new(); bvh.nodes.len()];
    for i in (0..bvh.nodes.len()).rev() {
        let score = |j: usize| Cand {
            j,
            frac: fraction(bvh, &ext, &dirs, i, j),
        };
        let cands: Vec<Cand> = match bvh.nodes[i].kind {
            NodeKind::Leaf { .. } => octant_best(&dirs, |j| score(j).frac),
            NodeKind::Inner { left, right } => {
                let mut js: Vec<usize> =
                    chosen[left].iter().chain(&chosen[right]).copied().collect();
                js.sort_unstable();
                js.dedup();
                js.into_iter().map(score).collect()
            }
        };
        let mut keep = Vec::new();
        for j in best_k(
            cands.into_iter().filter(|c| c.frac > 0.0).collect(),
            MAX_PLANES,
        ) {
            if keep.len() == k {
                break;
            }
            let p = fitted(bvh, &ext, &dirs, i, j);
            if cuts_something(&bvh.nodes[i].bounds, &p) {
                keep.push(j);
                planes[i].push(p);
            }
        }
        chosen[i] = keep;
    }
    Ok(planes)
}

/// Planes with one normal set per pair of siblings (claim 8 of US 2025/0259373: sibling nodes share
/// their cull-plane normals, so a node stores only its offsets and the pair stores the normals once).
///
/// For the two children of every inner node, the candidates are all 98 directions scored by the sum of
/// the two children's empty fractions; the best per octant, then the `k` best that cut something from at
/// least one child. Both children get every chosen normal, each with its own tight offset, in the same
/// slot order (a plane that cuts nothing from one child is still stored there: it never culls, and a
/// fixed-point fit turns it into the unused plane). The root, without a sibling, chooses alone. Every
/// offset is fitted as in [`generate`], so geometry never lies on an empty side.
pub fn generate_shared(bvh: &Bvh, tris: &[Triangle], k: usize) -> Result<Vec<Vec<Plane>>, Error> {
    check_args(bvh, tris, k)?;
    let dirs = directions();
    let ext = extreme_points(bvh, tris, &dirs);
    let mut planes: Vec<Vec<Plane>> = vec![Vec::new(); bvh.nodes.len()];
    let mut groups: Vec<Vec<usize>> = vec![vec![0]];
    for nd in &bvh.nodes {
        if let NodeKind::Inner { left, right } = nd.kind {
            groups.push(vec![left, right]);
        }
    }
    for g in groups {
        let cands = octant_best(&dirs, |j| {
            g.iter().map(|&i| fraction(bvh, &ext, &dirs, i, j)).sum()
        });
        let mut taken = 0;
        for j in best_k(
            cands.into_iter().filter(|c| c.frac > 0.0).collect(),
            MAX_PLANES,
        ) {
            if taken == k {
                break;
            }
            let ps: Vec<Plane> = g.iter().map(|&i| fitted(bvh, &ext, &dirs, i, j)).collect();
            if g.iter()
                .zip(&ps)
                .any(|(&i, p)| cuts_something(&bvh.nodes[i].bounds, p))
            {
                for (&i, p) in g.iter().zip(ps) {
                    planes[i].push(p);
                }
                taken += 1;
            }
        }
    }
    Ok(planes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::rat;
    use crate::plane::clip::ExactPlane;
    use crate::scene::tri::{random_point, random_triangle};
    use num_traits::Signed;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    #[test]
    fn there_are_98_distinct_directions_in_every_octant() {
        let d = directions();
        assert_eq!(d.len(), 98);
        for (i, a) in d.iter().enumerate() {
            for b in &d[i + 1..] {
                // Not parallel with the same orientation.
                let same = a.cross(*b) == DVec3::ZERO && a.dot(*b) > 0.0;
                assert!(!same, "{a} {b}");
            }
        }
        let mut per = [0; 8];
        for n in &d {
            per[octant(*n)] += 1;
        }
        assert!(per.iter().all(|&c| c > 0), "{per:?}");
        assert_eq!(octant(DVec3::new(0.0, -1.0, 2.0)), 2);
    }

    #[test]
    fn empty_fraction_matches_monte_carlo() {
        let mut rng = Pcg64::seed_from_u64(3);
        let dirs = directions();
        for case in 0..40 {
            let lo = random_point(&mut rng, DVec3::splat(-5.0), DVec3::splat(5.0));
            let mut ext = random_point(&mut rng, DVec3::splat(0.1), DVec3::splat(4.0));
            if case % 5 == 0 {
                ext.y = 0.0; // flat box: scored by area
            }
            let b = Aabb::new(lo, lo + ext).unwrap();
            let n = dirs[rng.gen_range(0..dirs.len())];
            let reach = n.abs().dot(ext) * 0.5;
            let p = Plane {
                n,
                w: rng.gen_range(-reach..reach),
            };
            let f = empty_fraction(&b, &p);
            let c = (b.min + b.max) * 0.5;
            let m = 100_000;
            let hits = (0..m)
                .filter(|_| n.dot(random_point(&mut rng, b.min, b.max) - c) > p.w)
                .count();
            let mc = hits as f64 / m as f64;
            assert!(
                (f - mc).abs() < 0.006,
                "case {case}: {f} vs {mc} {b:?} {p:?}"
            );
            if ext.y > 0.0 {
                let v = empty_volume(&b, &p);
                assert!((v - f * ext.x * ext.y * ext.z).abs() <= 1e-9 * v.max(1.0));
            }
        }
        // Whole-box and nothing.
        let b = Aabb::new(DVec3::ZERO, DVec3::ONE).unwrap();
        let n = DVec3::new(1.0, 1.0, 1.0);
        assert_eq!(empty_fraction(&b, &Plane { n, w: 1.5 }), 0.0);
        assert_eq!(empty_fraction(&b, &Plane { n, w: -1.5 }), 1.0);
        // The corner tetrahedron beyond x + y + z = 2.5 (w = 1) is 1/48 of the unit cube.
        assert!((empty_fraction(&b, &Plane { n, w: 1.0 }) - 1.0 / 48.0).abs() < 1e-15);
        assert!(cuts_something(&b, &Plane { n, w: 1.4999 }));
        assert!(!cuts_something(&b, &Plane { n, w: 1.5 }));
    }

    /// Every vertex of a node's subtree on the non-empty side of each of its planes (exactly); with
    /// `must_cut`, every plane cuts something from its box. Returns the number of planes that cut.
    fn check_all_vertices_inside(
        bvh: &Bvh,
        tris: &[Triangle],
        planes: &[Vec<Plane>],
        must_cut: bool,
    ) -> usize {
        let mut n = 0;
        for (i, ps) in planes.iter().enumerate() {
            let b = bvh.nodes[i].bounds;
            let verts: Vec<DVec3> = bvh
                .subtree_tris(i)
                .iter()
                .flat_map(|&t| tris[t].v)
                .collect();
            for p in ps {
                let cuts = cuts_something(&b, p);
                assert!(cuts || !must_cut, "node {i} plane {p:?} cuts nothing");
                let e = ExactPlane::from_world(p, &b);
                for v in &verts {
                    assert!(!e.side(*v).is_positive(), "node {i} plane {p:?} vertex {v}");
                }
                n += usize::from(cuts);
            }
        }
        n
    }

    #[test]
    fn every_vertex_is_on_the_non_empty_side_of_every_plane() {
        let mut rng = Pcg64::seed_from_u64(5);
        let tris: Vec<Triangle> = (0..400)
            .map(|_| random_triangle(&mut rng, DVec3::splat(-20.0), DVec3::splat(20.0), 2.0))
            .collect();
        for k in [1, 4, 8] {
            let bvh = Bvh::build(&tris, 4).unwrap();
            let planes = generate(&bvh, &tris, k).unwrap();
            assert_eq!(planes.len(), bvh.nodes.len());
            assert!(planes.iter().all(|p| p.len() <= k));
            let n = check_all_vertices_inside(&bvh, &tris, &planes, true);
            assert!(n > bvh.nodes.len() / 2, "only {n} planes");
        }
        // Scenes with exact ties and flat boxes (axis-aligned walls) and grass.
        for s in [
            crate::scene::tri_scene::room(1, 30),
            crate::scene::tri_scene::grass(1, 300),
        ] {
            let bvh = Bvh::build(&s.tris, 4).unwrap();
            let planes = generate(&bvh, &s.tris, 4).unwrap();
            check_all_vertices_inside(&bvh, &s.tris, &planes, true);
        }
    }

    #[test]
    fn siblings_share_normals_and_keep_their_geometry_inside() {
        let s = crate::scene::tri_scene::grass(1, 300);
        let bvh = Bvh::build(&s.tris, 4).unwrap();
        for k in [1, 4] {
            let shared = generate_shared(&bvh, &s.tris, k).unwrap();
            let cutting = check_all_vertices_inside(&bvh, &s.tris, &shared, false);
            assert!(cutting > bvh.nodes.len() / 2, "only {cutting} planes cut");
            for nd in &bvh.nodes {
                if let NodeKind::Inner { left, right } = nd.kind {
                    let (a, b) = (&shared[left], &shared[right]);
                    assert!(a.len() <= k && a.len() == b.len());
                    for (p, q) in a.iter().zip(b) {
                        assert_eq!(p.n, q.n, "siblings {left} {right}");
                        assert!(
                            cuts_something(&bvh.nodes[left].bounds, p)
                                || cuts_something(&bvh.nodes[right].bounds, q)
                        );
                    }
                }
            }
            // The pair's normals are a compromise, but not a degenerate one: summed over the nodes, the
            // best plane's empty fraction keeps at least half of what each node's own choice reaches.
            let own = generate(&bvh, &s.tris, k).unwrap();
            let best = |ps: &[Vec<Plane>]| -> f64 {
                ps.iter()
                    .enumerate()
                    .map(|(i, p)| {
                        p.iter()
                            .map(|p| empty_fraction(&bvh.nodes[i].bounds, p))
                            .fold(0.0, f64::max)
                    })
                    .sum()
            };
            assert!(
                best(&shared) > 0.5 * best(&own),
                "{} vs {}",
                best(&shared),
                best(&own)
            );
        }
    }

    #[test]
    fn fit_offset_is_tight_and_rounded_up() {
        // Vertices whose n . (p - c) is not representable: w must be the smallest f64 above it.
        let pts = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(0.7, 0.1, 0.05),
            DVec3::new(0.3, 0.9, 0.2),
        ];
        let b = Aabb::new(
            pts[0].min(pts[1]).min(pts[2]),
            pts[0].max(pts[1]).max(pts[2]),
        )
        .unwrap();
        for n in directions() {
            let w = fit_offset(n, &pts, &b);
            let e = ExactPlane::from_world(&Plane { n, w }, &b);
            let worst = pts.iter().map(|p| e.side(*p)).max().unwrap();
            assert!(!worst.is_positive());
            // One step down violates some vertex (unless exactly representable, then zero slack).
            let e2 = ExactPlane::from_world(
                &Plane {
                    n,
                    w: w.next_down(),
                },
                &b,
            );
            let worst2 = pts.iter().map(|p| e2.side(*p)).max().unwrap();
            assert!(worst2.is_positive() || worst == rat(0.0));
        }
    }

    #[test]
    fn a_thin_diagonal_triangle_gets_planes_that_cut_off_most_of_its_box() {
        // A blade from (0,0,0) to (3,3,3), 0.02 wide.
        let t = Triangle::new(
            DVec3::new(-0.01, 0.0, 0.01),
            DVec3::new(0.01, 0.0, -0.01),
            DVec3::new(3.0, 3.0, 3.0),
        );
        let bvh = Bvh::build(&[t], 4).unwrap();
        let planes = generate(&bvh, &[t], 8).unwrap();
        let b = bvh.nodes[0].bounds;
        assert!(planes[0].len() >= 4, "{:?}", planes[0]);
        let best = planes[0]
            .iter()
            .map(|p| empty_fraction(&b, p))
            .fold(0.0, f64::max);
        assert!(best > 0.4, "best single plane cuts {best}");
        // All planes together leave little: Monte Carlo estimate of the surviving fraction.
        let mut rng = Pcg64::seed_from_u64(1);
        let c = (b.min + b.max) * 0.5;
        let m = 50_000;
        let kept = (0..m)
            .filter(|_| {
                let p = random_point(&mut rng, b.min, b.max);
                planes[0].iter().all(|pl| pl.n.dot(p - c) <= pl.w)
            })
            .count();
        assert!((kept as f64 / m as f64) < 0.2, "kept {kept} of {m}");
        check_all_vertices_inside(&bvh, &[t], &planes, true);
    }

    #[test]
    fn bad_k_is_an_error() {
        let t = [Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y)];
        let bvh = Bvh::build(&t, 4).unwrap();
        assert!(generate(&bvh, &t, 0).is_err());
        assert!(generate(&bvh, &t, 9).is_err());
        let other = [t[0], t[0]];
        assert!(generate(&bvh, &other, 2).is_err());
    }
}
