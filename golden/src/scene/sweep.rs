//! One traversal model for the scene sweeps: a BVH whose nodes carry `K` cull planes, traversed by ray
//! bundles of size `B` (`B = 1`: single rays) with the bit-accurate models of the testers, counting the
//! work and checking every answer against the exact reference.
//!
//! # The machine it models
//! Two units: the single-ray node tester of a format (the slab tester, or the chained slab + `K` planes
//! tester) and, when `B > 1`, the AllHit / AnyHit pair of the same format. A bundle starts at the root with
//! all its rays active. At a node with more than one active ray the pair tests the bundle against the
//! node's box (one *pair test*): "all hit" keeps every active ray, "all miss" drops them all, neither
//! *splits*: each active ray is then tested on the single-ray tester. A node with one active ray (and every
//! node when `B = 1`) goes straight to the single-ray tester, one *box test* per ray. Planes therefore act
//! on the rays the single-ray tester sees; a bundle the pair calls "all hit" keeps its rays without them
//! (the pair tests boxes only), which is conservative. The rays kept go on to both children as one bundle,
//! re-bounded around the rays kept when `rebound` is set.
//!
//! # Order and hits
//! The traversal is an *all-hits* traversal: no ray's `t_max` shrinks at a hit, so the nodes visited do not
//! depend on child order and a bundle's rays never disagree on where to stop; that is what a bundle
//! traversal does, and using it for `B = 1` too keeps every configuration comparable (a front-to-back
//! closest-hit traversal, [`crate::scene::traverse::closest_hit`], does fewer triangle tests; the ratios between
//! configurations are what the sweep reports). At a leaf every active ray tests every triangle exactly
//! ([`crate::scene::tri::tri_hit`]); its closest hit is the smallest `(t, triangle)` over the leaves it reached,
//! and must equal the exact reference's for every ray, or the traversal returns an error.
//!
//! # What is counted
//! Box tests and pair tests (each one tester cycle, both units pipelined at one test per clock), pair
//! decisions against the ideal (tests whose active rays truly all hit or all miss the box), triangle
//! tests, *false box hits* (single-ray tests that keep a node whose box the ray misses, by the exact slab
//! test), *plane culls* (single-ray tests that cull a node whose box the ray hits; every one is checked
//! against the exact triangle test of the node's subtree and must hide no hit), and the *looseness* of the
//! returned interval on true box hits (how far it reaches beyond the f64 reference's slab interval, in
//! world units; planes may make it negative, counted as zero).

use crate::bundle::build::Built;
use crate::bundle::edge::Bundle;
use crate::bundle::traverse::{BundlePath, ExactHits};
use crate::error::Error;
use crate::format::fixed::GridMap;
use crate::geom::Ray;
use crate::plane::clip::{clip_exact, ExactPlane, Plane};
use crate::plane::fix::{self as plane_fix, CullFixFormat, FixNode, NodeFixRay};
use crate::plane::float::{self as plane_float, CullFloatFormat, FloatNode, NodeFloatRay};
use crate::scene::bvh::{Bvh, NodeKind};
use crate::scene::traverse::{Hit, NodeTester};
use crate::scene::tri::{tri_hit, Triangle};
use std::collections::HashMap;

/// The vertices of every triangle below `node`.
pub fn subtree_vertices(bvh: &Bvh, tris: &[Triangle], node: usize) -> Vec<glam::DVec3> {
    bvh.subtree_tris(node)
        .iter()
        .flat_map(|&t| tris[t].v)
        .collect()
}

/// The fixed-point node tester (slab + `k` planes) as a traversal's node test: every node's box and
/// planes stored in the format (planes fitted outward to the node's subtree), every ray quantised on the
/// way in. `k = 0` is the slab tester of the format.
pub struct FixTester {
    pub cf: CullFixFormat,
    pub k: usize,
    pub map: GridMap,
    pub nodes: Vec<FixNode>,
}

impl FixTester {
    /// Stores every node of `bvh` with the first `k` of its `planes`.
    pub fn new(
        cf: CullFixFormat,
        map: GridMap,
        bvh: &Bvh,
        tris: &[Triangle],
        planes: &[Vec<Plane>],
        k: usize,
    ) -> Result<Self, Error> {
        let mut nodes = Vec::with_capacity(bvh.nodes.len());
        for (i, nd) in bvh.nodes.iter().enumerate() {
            let mut n = FixNode {
                b: map.quantize_box(&nd.bounds)?,
                ..Default::default()
            };
            if k > 0 {
                let verts = subtree_vertices(bvh, tris, i);
                for (j, p) in planes[i].iter().take(k).enumerate() {
                    n.planes[j] = plane_fix::fit_plane(&cf, &map, &n.b, p.n, &verts)?;
                }
            }
            nodes.push(n);
        }
        Ok(FixTester { cf, k, map, nodes })
    }
}

impl FixTester {
    /// A world ray as the tester takes it: quantised onto the grid, direction for the planes.
    fn quantize(&self, r: &Ray) -> Result<NodeFixRay, Error> {
        Ok(NodeFixRay {
            ray: self.map.quantize_ray(r)?,
            dir: plane_fix::quantize_dir(&self.cf, r)?,
        })
    }

    /// Checks that every ray of `rays` fits the format (its grid and direction widths), so that
    /// [`NodeTester::test`] cannot fail on them; the error names the first ray that does not.
    pub fn check_rays(&self, rays: &[Ray]) -> Result<(), Error> {
        for (i, r) in rays.iter().enumerate() {
            self.quantize(r).map_err(|e| {
                Error::Io(format!("ray {i} does not fit {}: {e}", self.cf.base.name()))
            })?;
        }
        Ok(())
    }
}

impl NodeTester for FixTester {
    fn test(&mut self, ray: &Ray, node: usize) -> Option<(f64, f64)> {
        let r = self
            .quantize(ray)
            .expect("a ray the format cannot hold: see check_rays");
        let out = plane_fix::node_fix(&self.cf, self.k, &r, &self.nodes[node]);
        out.hit.then(|| {
            (
                r.ray.t_entry_f64(&self.cf.base, out.t_entry),
                r.ray.t_exit_f64(&self.cf.base, out.t_exit),
            )
        })
    }
}

/// The float counterpart of [`FixTester`].
pub struct FloatTester {
    pub cf: CullFloatFormat,
    pub k: usize,
    pub nodes: Vec<FloatNode>,
}

impl FloatTester {
    /// Stores every node of `bvh` with the first `k` of its `planes`.
    pub fn new(
        cf: CullFloatFormat,
        bvh: &Bvh,
        tris: &[Triangle],
        planes: &[Vec<Plane>],
        k: usize,
    ) -> Result<Self, Error> {
        let mut nodes = Vec::with_capacity(bvh.nodes.len());
        for (i, nd) in bvh.nodes.iter().enumerate() {
            let mut n = FloatNode {
                b: crate::slab::float::quantize_box(&cf.f, &nd.bounds)?,
                ..Default::default()
            };
            if k > 0 {
                let verts = subtree_vertices(bvh, tris, i);
                for (j, p) in planes[i].iter().take(k).enumerate() {
                    n.planes[j] = plane_float::fit_plane(&cf, &n.b, p.n, &verts)?;
                }
            }
            nodes.push(n);
        }
        Ok(FloatTester { cf, k, nodes })
    }

    /// A world ray as the tester takes it: in the format, direction for the planes.
    fn quantize(&self, r: &Ray) -> Result<NodeFloatRay, Error> {
        Ok(NodeFloatRay {
            ray: crate::slab::float::quantize_ray(&self.cf.f, r)?,
            dir: plane_float::quantize_dir(&self.cf, r)?,
        })
    }

    /// The float counterpart of [`FixTester::check_rays`].
    pub fn check_rays(&self, rays: &[Ray]) -> Result<(), Error> {
        for (i, r) in rays.iter().enumerate() {
            self.quantize(r).map_err(|e| {
                Error::Io(format!("ray {i} does not fit {}: {e}", self.cf.f.name()))
            })?;
        }
        Ok(())
    }
}

impl NodeTester for FloatTester {
    fn test(&mut self, ray: &Ray, node: usize) -> Option<(f64, f64)> {
        let f = &self.cf.f;
        let r = self
            .quantize(ray)
            .expect("a ray the format cannot hold: see check_rays");
        let out = plane_float::node_float(&self.cf, self.k, &r, &self.nodes[node]);
        out.hit
            .then(|| (f.to_f64(out.t_entry), f.to_f64(out.t_exit)))
    }
}

/// The exact reference node tester: the exact slab test of the world box, then the node's first `k`
/// world planes in rational arithmetic ([`clip_exact`]). Intervals are returned rounded to f64.
pub struct ExactTester<'a> {
    bvh: &'a Bvh,
    k: usize,
    planes: Vec<Vec<ExactPlane>>,
}

impl<'a> ExactTester<'a> {
    /// The first `k` of every node's `planes` (none when `planes` is empty), converted exactly.
    pub fn new(bvh: &'a Bvh, planes: &[Vec<Plane>], k: usize) -> Self {
        let planes = bvh
            .nodes
            .iter()
            .enumerate()
            .map(|(i, nd)| {
                planes
                    .get(i)
                    .map(|ps| {
                        ps.iter()
                            .take(k)
                            .map(|p| ExactPlane::from_world(p, &nd.bounds))
                            .collect()
                    })
                    .unwrap_or_default()
            })
            .collect();
        ExactTester { bvh, k, planes }
    }
}

impl NodeTester for ExactTester<'_> {
    fn test(&mut self, ray: &Ray, node: usize) -> Option<(f64, f64)> {
        let b = &self.bvh.nodes[node].bounds;
        if !crate::bundle::check::slab_hit(ray, b) {
            return None;
        }
        if self.k == 0 {
            let s = crate::slab::reference::slab_ref(ray, b);
            return Some((s.t_entry, s.t_exit));
        }
        let h = clip_exact(ray, b, &self.planes[node]);
        h.hit.then(|| (h.entry.to_f64(), h.exit.to_f64()))
    }
}

/// Counts of one configuration on one ray set; see the module doc.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SceneStats {
    pub rays: u64,
    pub bundles: u64,
    /// Single-ray node tests.
    pub box_tests: u64,
    /// Bundle tests on the pair.
    pub pair_tests: u64,
    /// Pair tests whose active rays truly all hit or all miss.
    pub pair_ideal: u64,
    /// Pair tests answered "all hit" or "all miss".
    pub pair_decided: u64,
    /// Single-ray tests that kept a node whose box the ray misses.
    pub false_box_hits: u64,
    /// Single-ray tests of a node whose box the ray misses.
    pub true_box_misses: u64,
    /// Single-ray tests that culled a node whose box the ray hits (planes), each checked.
    pub plane_culls: u64,
    /// Single-ray tests kept on a true box hit, and the sum of their looseness (world units).
    pub true_box_hits: u64,
    pub looseness_sum: f64,
    /// Leaf visits (per ray) and ray-triangle tests.
    pub leaf_visits: u64,
    pub tri_tests: u64,
    /// Rays with a hit.
    pub hits: u64,
}

impl SceneStats {
    /// Adds another set of counters.
    pub fn add(&mut self, o: &SceneStats) {
        self.rays += o.rays;
        self.bundles += o.bundles;
        self.box_tests += o.box_tests;
        self.pair_tests += o.pair_tests;
        self.pair_ideal += o.pair_ideal;
        self.pair_decided += o.pair_decided;
        self.false_box_hits += o.false_box_hits;
        self.true_box_misses += o.true_box_misses;
        self.plane_culls += o.plane_culls;
        self.true_box_hits += o.true_box_hits;
        self.looseness_sum += o.looseness_sum;
        self.leaf_visits += o.leaf_visits;
        self.tri_tests += o.tri_tests;
        self.hits += o.hits;
    }

    /// Tester cycles (box tests plus pair tests) per ray.
    pub fn cycles_per_ray(&self) -> f64 {
        (self.box_tests + self.pair_tests) as f64 / self.rays.max(1) as f64
    }

    /// False box hits per true box miss of the single-ray tests.
    pub fn false_hit_rate(&self) -> f64 {
        self.false_box_hits as f64 / self.true_box_misses.max(1) as f64
    }

    /// Mean looseness of the single-ray tester's interval on true box hits (world units).
    pub fn mean_looseness(&self) -> f64 {
        self.looseness_sum / self.true_box_hits.max(1) as f64
    }
}

/// The exact facts about a ray set that every configuration shares: which node boxes each ray hits, its
/// closest hit (the reference every traversal must reproduce), and a memo of leaf triangle tests.
pub struct RaySet<'a> {
    pub rays: &'a [Ray],
    pub exact: ExactHits,
    pub closest: Vec<Option<Hit>>,
    memo: HashMap<(u32, u32), Option<Hit>>,
}

impl<'a> RaySet<'a> {
    /// Exact box hits of every ray and node, and every ray's closest hit by brute force over `tris`.
    pub fn new(bvh: &Bvh, tris: &[Triangle], rays: &'a [Ray]) -> Self {
        let closest = rays
            .iter()
            .map(|r| crate::scene::traverse::brute_force_closest(tris, r))
            .collect();
        RaySet {
            rays,
            exact: ExactHits::new(bvh, rays),
            closest,
            memo: HashMap::new(),
        }
    }

    /// The closest hit of ray `i` among the triangles of leaf `node` (memoised).
    fn leaf_hit(&mut self, bvh: &Bvh, tris: &[Triangle], i: usize, node: usize) -> Option<Hit> {
        let ray = &self.rays[i];
        self.memo
            .entry((i as u32, node as u32))
            .or_insert_with(|| {
                let mut best: Option<Hit> = None;
                for &ti in bvh.leaf_tris(node) {
                    if let Some(t) = tri_hit(ray, &tris[ti]) {
                        if better(&t, ti, &best) {
                            best = Some((ti, t));
                        }
                    }
                }
                best
            })
            .clone()
    }
}

fn better(t: &num_rational::BigRational, i: usize, best: &Option<Hit>) -> bool {
    match best {
        None => true,
        Some((bi, bt)) => t < bt || (t == bt && i < *bi),
    }
}

/// A configuration: the single-ray tester and how many planes it tests per node (with none, a cull of a
/// node whose box the ray hits is a false miss, an error), the pair (`None`: single rays only) and
/// re-bounding.
pub struct Machine<'t> {
    pub tester: &'t mut dyn NodeTester,
    pub planes: usize,
    pub pair: Option<&'t BundlePath>,
    pub rebound: bool,
}

/// Traverses every bundle of `bundles` (indices into `set.rays`; one-ray bundles for `B = 1`) through
/// `bvh` on `m`, as in the module doc; errors on a wrong answer, naming the ray or node.
pub fn traverse(
    bvh: &Bvh,
    tris: &[Triangle],
    set: &mut RaySet,
    bundles: &[Built],
    m: &mut Machine,
    mut progress: impl FnMut(),
) -> Result<SceneStats, Error> {
    let mut st = SceneStats::default();
    let mut best: Vec<Option<Hit>> = vec![None; set.rays.len()];
    let mut reached = vec![false; set.rays.len()];
    for b in bundles {
        let n = b.rays.len();
        if n == 0 || n > 64 {
            return Err(Error::Io(format!("a bundle of {n} rays: 1..=64 expected")));
        }
        st.bundles += 1;
        let all = if n == 64 { u64::MAX } else { (1u64 << n) - 1 };
        let mut stack = vec![(0usize, all, b.bundle)];
        while let Some((node, active, bundle)) = stack.pop() {
            let nd = &bvh.nodes[node];
            let bx = &nd.bounds;
            let mut hits = 0u64;
            for (k, &i) in b.rays.iter().enumerate() {
                if active >> k & 1 == 1 && set.exact.hits(i, node) {
                    hits |= 1 << k;
                }
            }
            let count = active.count_ones();
            let at = |what: &str| Error::Io(format!("node {node}: {what}"));
            let mut single = true;
            let mut mask = 0u64;
            if count > 1 {
                if let Some(path) = m.pair {
                    st.pair_tests += 1;
                    if hits == active || hits == 0 {
                        st.pair_ideal += 1;
                    }
                    // The bundle tested stands for its active rays only when re-bounded; otherwise for
                    // the original bundle, whose other rays may differ; check only what the answer claims
                    // of the active rays, which is what the traversal relies on.
                    let (all_hit, all_miss) = path.decide(&bundle, bx)?;
                    if all_hit && hits != active {
                        return Err(at(
                            "the pair said \"all hit\" although an active ray misses",
                        ));
                    }
                    if all_miss && hits != 0 {
                        return Err(at("the pair said \"all miss\" although an active ray hits"));
                    }
                    if all_hit || all_miss {
                        st.pair_decided += 1;
                        single = false;
                        mask = if all_hit { active } else { 0 };
                    }
                }
            }
            if single {
                for (k, &i) in b.rays.iter().enumerate() {
                    if active >> k & 1 == 0 {
                        continue;
                    }
                    let ray = &set.rays[i];
                    st.box_tests += 1;
                    let truth = hits >> k & 1 == 1;
                    let r = m.tester.test(ray, node);
                    match (r, truth) {
                        (Some(_), false) => {
                            st.true_box_misses += 1;
                            st.false_box_hits += 1;
                        }
                        (None, false) => st.true_box_misses += 1,
                        (Some((lo, hi)), true) => {
                            let s = crate::slab::reference::slab_ref(ray, bx);
                            st.true_box_hits += 1;
                            // Within the ray's own range: a saturated code (t = inf) is no looser there.
                            let (lo, hi) = (lo.max(ray.t_min), hi.min(ray.t_max));
                            st.looseness_sum +=
                                (s.t_entry - lo).max(0.0) + (hi - s.t_exit.min(ray.t_max)).max(0.0);
                        }
                        (None, true) => {
                            if m.planes == 0 {
                                return Err(at(&format!(
                                    "ray {i} hits the box but the slab tester culled it (false miss)"
                                )));
                            }
                            st.plane_culls += 1;
                            if let Some(&t) = bvh
                                .subtree_tris(node)
                                .iter()
                                .find(|&&t| tri_hit(ray, &tris[t]).is_some())
                            {
                                return Err(at(&format!(
                                    "ray {i} culled although it hits triangle {t} below"
                                )));
                            }
                        }
                    }
                    if r.is_some() {
                        mask |= 1 << k;
                    }
                }
            }
            if mask == 0 {
                continue;
            }
            match nd.kind {
                NodeKind::Leaf { .. } => {
                    for (k, &i) in b.rays.iter().enumerate() {
                        if mask >> k & 1 == 0 {
                            continue;
                        }
                        st.leaf_visits += 1;
                        st.tri_tests += bvh.leaf_tris(node).len() as u64;
                        if let Some((ti, t)) = set.leaf_hit(bvh, tris, i, node) {
                            if better(&t, ti, &best[i]) {
                                best[i] = Some((ti, t));
                            }
                        }
                    }
                }
                NodeKind::Inner { left, right } => {
                    let next = if m.rebound && mask != active {
                        let kept: Vec<Ray> = b
                            .rays
                            .iter()
                            .enumerate()
                            .filter(|(k, _)| mask >> k & 1 == 1)
                            .map(|(_, &i)| set.rays[i])
                            .collect();
                        Bundle::around(&kept)?
                    } else {
                        bundle
                    };
                    stack.push((right, mask, next));
                    stack.push((left, mask, next));
                }
            }
        }
        for &i in &b.rays {
            reached[i] = true;
        }
        progress();
    }
    for (i, (got, want)) in best.iter().zip(&set.closest).enumerate() {
        if !reached[i] {
            continue;
        }
        st.rays += 1;
        if got.is_some() {
            st.hits += 1;
        }
        if got != want {
            return Err(Error::Io(format!(
                "ray {i}: closest hit {:?} differs from the exact reference {:?}",
                got.as_ref().map(|h| h.0),
                want.as_ref().map(|h| h.0)
            )));
        }
    }
    Ok(st)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bundle::build::tiles;
    use crate::bundle::fix::BundleFixFormat;
    use crate::format::fixed::FixFormat;
    use crate::scene::tri_scene as scene;

    fn setup() -> (scene::TriScene, Bvh, Vec<Ray>, GridMap) {
        let sc = scene::by_name("room", 1, Some(6)).unwrap();
        let bvh = Bvh::build(&sc.tris, 4).unwrap();
        let rays = scene::primary_rays(&sc, 16, 12);
        let (lo, hi) = sc.grid_bounds();
        let map = GridMap::for_bounds(FixFormat::b8(), lo, hi).unwrap();
        (sc, bvh, rays, map)
    }

    #[test]
    fn exact_single_rays_make_no_false_hits_and_find_every_closest_hit() {
        let (sc, bvh, rays, _) = setup();
        let mut set = RaySet::new(&bvh, &sc.tris, &rays);
        let singles = tiles(&rays, 16, 12, 1).unwrap();
        let mut ex = ExactTester::new(&bvh, &[], 0);
        let st = traverse(
            &bvh,
            &sc.tris,
            &mut set,
            &singles,
            &mut Machine {
                tester: &mut ex,
                planes: 0,
                pair: None,
                rebound: false,
            },
            || {},
        )
        .unwrap();
        assert_eq!(st.rays, rays.len() as u64);
        assert_eq!(st.false_box_hits, 0);
        assert_eq!(st.plane_culls, 0);
        assert_eq!(st.pair_tests, 0);
        assert!(st.hits > 0 && st.true_box_misses > 0);
        // The exact tester's intervals are the reference's: no looseness.
        assert_eq!(st.looseness_sum, 0.0);
    }

    #[test]
    fn a_coarse_format_does_more_work_and_bundles_cut_cycles() {
        let (sc, bvh, rays, map) = setup();
        let mut set = RaySet::new(&bvh, &sc.tris, &rays);
        let singles = tiles(&rays, 16, 12, 1).unwrap();
        let quads = tiles(&rays, 16, 12, 4).unwrap();
        let cf = CullFixFormat::over(FixFormat::b8());
        let mut fx = FixTester::new(cf, map.clone(), &bvh, &sc.tris, &[], 0).unwrap();
        let mut ex = ExactTester::new(&bvh, &[], 0);
        let run = |set: &mut RaySet, t: &mut dyn NodeTester, pair: Option<&BundlePath>, b| {
            traverse(
                &bvh,
                &sc.tris,
                set,
                b,
                &mut Machine {
                    tester: t,
                    planes: 0,
                    pair,
                    rebound: true,
                },
                || {},
            )
            .unwrap()
        };
        let exact = run(&mut set, &mut ex, None, &singles);
        let fixed = run(&mut set, &mut fx, None, &singles);
        assert!(fixed.box_tests > exact.box_tests, "{fixed:?} {exact:?}");
        assert!(fixed.false_box_hits > 0 && fixed.mean_looseness() > 0.0);
        assert_eq!(fixed.hits, exact.hits);
        let pair = BundlePath::Fix(BundleFixFormat::over(FixFormat::b8()).unwrap(), map);
        let bundled = run(&mut set, &mut fx, Some(&pair), &quads);
        assert!(bundled.pair_decided > 0 && bundled.pair_decided <= bundled.pair_ideal);
        assert!(
            bundled.cycles_per_ray() < fixed.cycles_per_ray(),
            "{bundled:?}"
        );
        assert_eq!(bundled.hits, exact.hits);
    }

    #[test]
    fn a_tester_that_culls_a_hit_node_is_an_error() {
        struct CullsAll;
        impl NodeTester for CullsAll {
            fn test(&mut self, _: &Ray, node: usize) -> Option<(f64, f64)> {
                (node == 0).then_some((0.0, f64::INFINITY))
            }
        }
        let (sc, bvh, rays, _) = setup();
        let mut set = RaySet::new(&bvh, &sc.tris, &rays);
        let singles = tiles(&rays, 16, 12, 1).unwrap();
        let mut run = |planes| {
            traverse(
                &bvh,
                &sc.tris,
                &mut set,
                &singles,
                &mut Machine {
                    tester: &mut CullsAll,
                    planes,
                    pair: None,
                    rebound: false,
                },
                || {},
            )
            .unwrap_err()
            .to_string()
        };
        // With planes, a cull is allowed unless it hides a triangle hit; without, any cull of a node the
        // ray's box test hits is a false miss.
        let e = run(1);
        assert!(e.contains("culled although it hits"), "{e}");
        let e = run(0);
        assert!(e.contains("false miss"), "{e}");
    }
}
