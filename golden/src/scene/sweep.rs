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
//! # Modes, order and hits
//! A parent tests both children (the pair on the bundle, or the single-ray tester per active ray); the
//! children are pushed far first, so the one with the lesser entry (the least entry of its kept rays, as
//! their testers reported it; a ray the pair keeps inherits its entry into the parent) is visited first.
//! [`Mode`] says what a hit does:
//! - **closest hit** (camera and bounce rays): each ray's `t_max` shrinks to its closest hit so far (the
//!   exact `t` rounded up to f64, so nothing at or before the hit is cut off); the rays handed to the
//!   testers, and the bundles re-bounded around them, carry the shrunk range, and a popped node is skipped
//!   for every ray whose entry lies beyond its `t_max` (an *entry skip*). A loose entry therefore costs
//!   node tests and triangle tests, and the cull planes' entry update saves them.
//! - **any hit** (shadow rays): a ray is finished at the first triangle it hits (the triangles of a leaf in
//!   order, the tests after the hit not counted); a bundle goes on with its other rays.
//! - **all hits**: nothing shrinks or stops; the nodes visited do not depend on the order.
//!
//! At a leaf every active ray tests the triangles exactly ([`crate::scene::tri::tri_hit`]). Every ray's
//! closest hit (closest and all hits: the smallest `(t, triangle)` over the leaves it reached) must equal
//! the exact reference's, and in any-hit mode whether it hits must, or the traversal returns an error. A
//! single-ray test is judged against the exact slab test of the ray's *current* range, so culling a box
//! that lies beyond the closest hit so far is no false miss.
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
/// world planes in rational arithmetic ([`clip_exact`]). Intervals are returned rounded outward to f64
/// (without planes, the slab interval of [`crate::scene::traverse::slab_conservative`]).
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
            // Rounded outward: a closest-hit traversal compares the entry with the hits so far, and an
            // entry rounded past a hit at the box's face would skip it.
            return Some(
                crate::scene::traverse::slab_conservative(ray, b).unwrap_or((ray.t_min, ray.t_max)),
            );
        }
        let h = clip_exact(ray, b, &self.planes[node]);
        h.hit.then(|| (h.entry.down_f64(), h.exit.up_f64()))
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
    /// Closest-hit mode: a ray's visits of a node skipped because its entry into the node (as its tester
    /// reported it) lies beyond the closest hit found so far.
    pub entry_skips: u64,
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
        self.entry_skips += o.entry_skips;
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
    memo: HashMap<(u32, u32), LeafHit>,
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

    /// Ray `i` against the triangles of leaf `node` (memoised).
    fn leaf_hit(&mut self, bvh: &Bvh, tris: &[Triangle], i: usize, node: usize) -> LeafHit {
        let ray = &self.rays[i];
        self.memo
            .entry((i as u32, node as u32))
            .or_insert_with(|| {
                let mut l = LeafHit::default();
                for (p, &ti) in bvh.leaf_tris(node).iter().enumerate() {
                    if let Some(t) = tri_hit(ray, &tris[ti]) {
                        l.first.get_or_insert(p);
                        if better(&t, ti, &l.closest) {
                            l.closest = Some((ti, t));
                        }
                    }
                }
                l
            })
            .clone()
    }
}

/// A ray against one leaf's triangles: its closest hit among them, and the position in the leaf of the
/// first triangle it hits (where an any-hit traversal stops).
#[derive(Clone, Debug, Default)]
struct LeafHit {
    closest: Option<Hit>,
    first: Option<usize>,
}

fn better(t: &num_rational::BigRational, i: usize, best: &Option<Hit>) -> bool {
    match best {
        None => true,
        Some((bi, bt)) => t < bt || (t == bt && i < *bi),
    }
}

/// How a traversal ends and what it returns, as a renderer runs its rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Closest hit (camera and bounce rays): nodes front to back by the tester's own entry, each ray's
    /// `t_max` shrinking to its closest hit so far, a node skipped for a ray whose entry lies beyond it.
    Closest,
    /// Any hit (shadow rays): a ray stops at the first triangle it hits within its range.
    Any,
    /// All hits: nothing shrinks and nothing stops early; every node any tester keeps is visited.
    All,
}

impl Mode {
    /// `closest`, `any` or `all`.
    pub fn parse(s: &str) -> Result<Mode, Error> {
        match s {
            "closest" => Ok(Mode::Closest),
            "any" => Ok(Mode::Any),
            "all" => Ok(Mode::All),
            _ => Err(Error::Io(format!(
                "traversal mode `{s}`: expected closest, any or all"
            ))),
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            Mode::Closest => "closest",
            Mode::Any => "any",
            Mode::All => "all",
        }
    }

    /// The mode a renderer runs a ray set in: any hit for shadow rays, closest hit otherwise.
    pub fn default_for(set: &str) -> Mode {
        if set == "shadow" {
            Mode::Any
        } else {
            Mode::Closest
        }
    }
}

/// A node tester that culls as one tester and reports the interval of another: `cull` decides, and on a
/// node it keeps the interval is `interval`'s (or `cull`'s own where `interval` culls). With `cull` a
/// format's tester and `interval` the exact tester of the same planes, a closest-hit traversal differs
/// from the format's own only by the looseness of the format's `t` interval; with `interval` the same
/// format's slab tester (no planes), only by the planes' entry/exit update.
pub struct Intervals<'t> {
    pub cull: &'t mut dyn NodeTester,
    pub interval: &'t mut dyn NodeTester,
}

impl NodeTester for Intervals<'_> {
    fn test(&mut self, ray: &Ray, node: usize) -> Option<(f64, f64)> {
        let c = self.cull.test(ray, node)?;
        Some(self.interval.test(ray, node).unwrap_or(c))
    }
}

/// A configuration: the single-ray tester and how many planes it tests per node (with none, a cull of a
/// node whose box the ray hits is a false miss, an error), the pair (`None`: single rays only),
/// re-bounding, and the traversal mode.
pub struct Machine<'t> {
    pub tester: &'t mut dyn NodeTester,
    pub planes: usize,
    pub pair: Option<&'t BundlePath>,
    pub rebound: bool,
    pub mode: Mode,
}

/// What one ray's traversal found and what it cost.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RayResult {
    /// The closest hit found (closest and all hits), or the first hit found (any hit).
    pub hit: Option<Hit>,
    /// The ray's entry into the leaf where `hit` was found, as its tester reported it (a ray the pair
    /// kept inherits its entry into the parent): at most the hit's `t` for a conservative tester.
    pub hit_entry: Option<f64>,
    /// Single-ray node tests of this ray, pair tests of a bundle it was active in, triangle tests.
    pub node_tests: u64,
    pub pair_tests: u64,
    pub tri_tests: u64,
}

/// A node on the traversal stack: the rays still active in it (a mask over the bundle's rays), the
/// bundle the pair tests, and each active ray's entry into the node as its tester reported it.
struct Pending {
    node: usize,
    mask: u64,
    bundle: Bundle,
    entry: Vec<f64>,
    /// The rays `bundle` was bounded around (all: the builder's bundle) and the value of
    /// [`Walk::shrinks`] then: when neither has changed, re-bounding would give `bundle` again.
    bounded: (u64, u64),
}

/// Traverses every bundle of `bundles` (indices into `set.rays`; one-ray bundles for `B = 1`) through
/// `bvh` on `m`, as in the module doc; errors on a wrong answer, naming the ray or node.
pub fn traverse(
    bvh: &Bvh,
    tris: &[Triangle],
    set: &mut RaySet,
    bundles: &[Built],
    m: &mut Machine,
    progress: impl FnMut(),
) -> Result<SceneStats, Error> {
    traverse_rays(bvh, tris, set, bundles, m, progress).map(|(st, _)| st)
}

/// The traversal state of one ray set under one machine.
struct Walk<'a, 'b, 'r, 'm, 't> {
    bvh: &'a Bvh,
    tris: &'a [Triangle],
    set: &'b mut RaySet<'r>,
    m: &'m mut Machine<'t>,
    st: SceneStats,
    /// Each ray's range as the traversal hands it on (its `t_max` shrinks in closest-hit mode).
    cur: Vec<Ray>,
    /// Set when a ray is finished (any-hit mode).
    done: Vec<bool>,
    /// How often a ray of the current bundle has had its `t_max` shrunk (closest-hit mode).
    shrinks: u64,
    out: Vec<RayResult>,
}

impl Walk<'_, '_, '_, '_, '_> {
    /// True when ray `i`, in its current range, hits the box of `node` (exactly).
    fn hits_now(&self, i: usize, node: usize) -> bool {
        self.set.exact.hits(i, node)
            && (self.cur[i].t_max == self.set.rays[i].t_max
                || crate::bundle::check::slab_hit(&self.cur[i], &self.bvh.nodes[node].bounds))
    }

    /// Tests `node` for the rays of `b` in `active` (entries `entry`, inherited from the parent): the pair
    /// on the bundle when more than one ray is active, else (or when it splits) the single-ray tester
    /// per ray. Returns the rays kept and their entries, checking every answer.
    fn test_node(
        &mut self,
        b: &Built,
        node: usize,
        active: u64,
        bundle: &Bundle,
        entry: &[f64],
    ) -> Result<(u64, Vec<f64>), Error> {
        let bx = self.bvh.nodes[node].bounds;
        let mut hits = 0u64;
        for (k, &i) in b.rays.iter().enumerate() {
            if active >> k & 1 == 1 && self.hits_now(i, node) {
                hits |= 1 << k;
            }
        }
        let at = |what: &str| Error::Io(format!("node {node}: {what}"));
        let mut entry = entry.to_vec();
        if active.count_ones() > 1 {
            if let Some(path) = self.m.pair {
                self.st.pair_tests += 1;
                for (k, &i) in b.rays.iter().enumerate() {
                    if active >> k & 1 == 1 {
                        self.out[i].pair_tests += 1;
                    }
                }
                if hits == active || hits == 0 {
                    self.st.pair_ideal += 1;
                }
                // The bundle tested stands for its active rays only when re-bounded; otherwise for the
                // original bundle, whose other rays may differ; check only what the answer claims of the
                // active rays, which is what the traversal relies on.
                let (all_hit, all_miss) = path.decide(bundle, &bx)?;
                if all_hit && hits != active {
                    return Err(at(
                        "the pair said \"all hit\" although an active ray misses",
                    ));
                }
                if all_miss && hits != 0 {
                    return Err(at("the pair said \"all miss\" although an active ray hits"));
                }
                if all_hit || all_miss {
                    self.st.pair_decided += 1;
                    // The pair reports no interval: the kept rays keep their entries into the parent.
                    return Ok((if all_hit { active } else { 0 }, entry));
                }
            }
        }
        let mut mask = 0u64;
        for (k, &i) in b.rays.iter().enumerate() {
            if active >> k & 1 == 0 {
                continue;
            }
            let ray = self.cur[i];
            self.st.box_tests += 1;
            self.out[i].node_tests += 1;
            let truth = hits >> k & 1 == 1;
            let r = self.m.tester.test(&ray, node);
            match (r, truth) {
                (Some(_), false) => {
                    self.st.true_box_misses += 1;
                    self.st.false_box_hits += 1;
                }
                (None, false) => self.st.true_box_misses += 1,
                (Some((lo, hi)), true) => {
                    let s = crate::slab::reference::slab_ref(&ray, &bx);
                    self.st.true_box_hits += 1;
                    // Within the ray's own range: a saturated code (t = inf) is no looser there.
                    let (lo, hi) = (lo.max(ray.t_min), hi.min(ray.t_max));
                    self.st.looseness_sum +=
                        (s.t_entry - lo).max(0.0) + (hi - s.t_exit.min(ray.t_max)).max(0.0);
                }
                (None, true) => {
                    if self.m.planes == 0 {
                        return Err(at(&format!(
                            "ray {i} hits the box but the slab tester culled it (false miss)"
                        )));
                    }
                    self.st.plane_culls += 1;
                    if let Some(&t) = self
                        .bvh
                        .subtree_tris(node)
                        .iter()
                        .find(|&&t| tri_hit(&ray, &self.tris[t]).is_some())
                    {
                        return Err(at(&format!(
                            "ray {i} culled although it hits triangle {t} below"
                        )));
                    }
                }
            }
            if let Some((lo, _)) = r {
                mask |= 1 << k;
                entry[k] = lo;
            }
        }
        Ok((mask, entry))
    }

    /// Tests the triangles of leaf `node` for the rays in `mask`, as the mode says.
    fn leaf(&mut self, b: &Built, node: usize, mask: u64, entry: &[f64]) {
        for (k, &i) in b.rays.iter().enumerate() {
            if mask >> k & 1 == 0 {
                continue;
            }
            self.st.leaf_visits += 1;
            let l = self.set.leaf_hit(self.bvh, self.tris, i, node);
            let tested = match (self.m.mode, l.first) {
                // Any hit stops at the first triangle it hits.
                (Mode::Any, Some(p)) => p + 1,
                _ => self.bvh.leaf_tris(node).len(),
            } as u64;
            self.st.tri_tests += tested;
            self.out[i].tri_tests += tested;
            let Some((ti, t)) = l.closest else { continue };
            match self.m.mode {
                Mode::Any => {
                    self.done[i] = true;
                    self.out[i].hit = Some((ti, t));
                    self.out[i].hit_entry = Some(entry[k]);
                }
                Mode::Closest | Mode::All => {
                    if better(&t, ti, &self.out[i].hit) {
                        if self.m.mode == Mode::Closest {
                            // Rounded up, so nothing at or before the hit is cut off.
                            self.cur[i].t_max =
                                crate::exact::round_up(&t).min(self.set.rays[i].t_max);
                            self.shrinks += 1;
                        }
                        self.out[i].hit = Some((ti, t));
                        self.out[i].hit_entry = Some(entry[k]);
                    }
                }
            }
        }
    }

    /// One bundle from the root down.
    fn bundle(&mut self, b: &Built) -> Result<(), Error> {
        let n = b.rays.len();
        let all = if n == 64 { u64::MAX } else { (1u64 << n) - 1 };
        let start: Vec<f64> = b.rays.iter().map(|&i| self.cur[i].t_min).collect();
        self.shrinks = 0;
        let (mask, entry) = self.test_node(b, 0, all, &b.bundle, &start)?;
        let mut stack = vec![Pending {
            node: 0,
            mask,
            bundle: b.bundle,
            entry,
            bounded: (all, 0),
        }];
        while let Some(p) = stack.pop() {
            let mut mask = p.mask;
            for (k, &i) in b.rays.iter().enumerate() {
                if mask >> k & 1 == 0 {
                    continue;
                }
                let drop = match self.m.mode {
                    Mode::Any => self.done[i],
                    Mode::Closest => p.entry[k] > self.cur[i].t_max,
                    Mode::All => false,
                };
                if drop {
                    mask &= !(1 << k);
                    if self.m.mode == Mode::Closest {
                        self.st.entry_skips += 1;
                    }
                }
            }
            if mask == 0 {
                continue;
            }
            match self.bvh.nodes[p.node].kind {
                NodeKind::Leaf { .. } => self.leaf(b, p.node, mask, &p.entry),
                NodeKind::Inner { left, right } => {
                    let now = (mask, self.shrinks);
                    let (next, bounded) = if self.m.rebound && now != p.bounded {
                        let kept: Vec<Ray> = b
                            .rays
                            .iter()
                            .enumerate()
                            .filter(|(k, _)| mask >> k & 1 == 1)
                            .map(|(_, &i)| self.cur[i])
                            .collect();
                        (Bundle::around(&kept)?, now)
                    } else {
                        (p.bundle, p.bounded)
                    };
                    let (lm, le) = self.test_node(b, left, mask, &next, &p.entry)?;
                    let (rm, re) = self.test_node(b, right, mask, &next, &p.entry)?;
                    // The bundle's entry into a child: the least entry of its kept rays.
                    let key = |m: u64, e: &[f64]| {
                        (0..n)
                            .filter(|k| m >> k & 1 == 1)
                            .map(|k| e[k])
                            .fold(f64::INFINITY, f64::min)
                    };
                    let (lk, rk) = (key(lm, &le), key(rm, &re));
                    let l = Pending {
                        node: left,
                        mask: lm,
                        bundle: next,
                        entry: le,
                        bounded,
                    };
                    let r = Pending {
                        node: right,
                        mask: rm,
                        bundle: next,
                        entry: re,
                        bounded,
                    };
                    // The far child first on the stack, so the near one is popped first (ties: left).
                    let (near, far) = if rk < lk { (r, l) } else { (l, r) };
                    for c in [far, near] {
                        if c.mask != 0 {
                            stack.push(c);
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// [`traverse`], also returning each ray's result and work (indexed as `set.rays`; rays in no bundle
/// keep the default).
pub fn traverse_rays(
    bvh: &Bvh,
    tris: &[Triangle],
    set: &mut RaySet,
    bundles: &[Built],
    m: &mut Machine,
    mut progress: impl FnMut(),
) -> Result<(SceneStats, Vec<RayResult>), Error> {
    let nr = set.rays.len();
    let cur = set.rays.to_vec();
    let mut w = Walk {
        bvh,
        tris,
        set,
        m,
        st: SceneStats::default(),
        cur,
        done: vec![false; nr],
        shrinks: 0,
        out: vec![RayResult::default(); nr],
    };
    let mut reached = vec![false; nr];
    for b in bundles {
        let n = b.rays.len();
        if n == 0 || n > 64 {
            return Err(Error::Io(format!("a bundle of {n} rays: 1..=64 expected")));
        }
        if let Some(&i) = b.rays.iter().find(|&&i| i >= nr) {
            return Err(Error::Io(format!(
                "a bundle names ray {i} of a set of {nr}"
            )));
        }
        w.st.bundles += 1;
        w.bundle(b)?;
        for &i in &b.rays {
            reached[i] = true;
        }
        progress();
    }
    let mode = w.m.mode;
    let (mut st, out) = (w.st, w.out);
    for (i, (got, want)) in out.iter().zip(&w.set.closest).enumerate() {
        if !reached[i] {
            continue;
        }
        st.rays += 1;
        if got.hit.is_some() {
            st.hits += 1;
        }
        let wrong = match mode {
            Mode::Any => got.hit.is_some() != want.is_some(),
            Mode::Closest | Mode::All => got.hit != *want,
        };
        if wrong {
            return Err(Error::Io(format!(
                "ray {i} ({} hit): found {:?}, the exact reference {:?}",
                mode.name(),
                got.hit.as_ref().map(|h| h.0),
                want.as_ref().map(|h| h.0)
            )));
        }
    }
    Ok((st, out))
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
                mode: Mode::All,
            },
            || {},
        )
        .unwrap();
        assert_eq!(st.rays, rays.len() as u64);
        assert_eq!(st.false_box_hits, 0);
        assert_eq!(st.plane_culls, 0);
        assert_eq!(st.pair_tests, 0);
        assert!(st.hits > 0 && st.true_box_misses > 0);
        // The exact tester's intervals are the reference's, rounded outward by a few ulps.
        assert!(st.looseness_sum < 1e-9 * st.true_box_hits as f64, "{st:?}");
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
                    mode: Mode::All,
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
                    mode: Mode::All,
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

    /// Runs `t` over `rays` (tiles of `b`) in `mode`, on the K-plane machine; the traversal's own checks
    /// (every closest hit, every any-hit verdict) must pass.
    #[allow(clippy::too_many_arguments)]
    fn run_mode(
        bvh: &Bvh,
        tris: &[Triangle],
        rays: &[Ray],
        t: &mut dyn NodeTester,
        k: usize,
        pair: Option<&BundlePath>,
        b: usize,
        mode: Mode,
    ) -> Result<(SceneStats, Vec<RayResult>), Error> {
        let mut set = RaySet::new(bvh, tris, rays);
        let built = if b == 1 {
            (0..rays.len())
                .map(|i| Built {
                    rays: vec![i],
                    bundle: Bundle::around(&rays[i..=i]).unwrap(),
                })
                .collect()
        } else {
            tiles(rays, 16, 12, b).unwrap()
        };
        let mut m = Machine {
            tester: t,
            planes: k,
            pair,
            rebound: true,
            mode,
        };
        traverse_rays(bvh, tris, &mut set, &built, &mut m, || {})
    }

    /// Closest hit finds every ray's closest hit with fewer triangle tests than all hits, skipping nodes
    /// by entry; any hit finds every verdict with fewer still on shadow rays; for the exact tester, a fixed
    /// format and bundles. Per-ray work adds up to the totals.
    #[test]
    fn closest_and_any_hit_find_the_reference_with_less_work() {
        let (sc, bvh, rays, map) = setup();
        let cf = CullFixFormat::over(FixFormat::b8());
        let pair = BundlePath::Fix(BundleFixFormat::over(FixFormat::b8()).unwrap(), map);
        for b in [1, 4] {
            let mut ex = ExactTester::new(&bvh, &[], 0);
            let mut fx = FixTester::new(cf, map, &bvh, &sc.tris, &[], 0).unwrap();
            let testers: [&mut dyn NodeTester; 2] = [&mut ex, &mut fx];
            for t in testers {
                let p = (b > 1).then_some(&pair);
                let (all, _) = run_mode(&bvh, &sc.tris, &rays, t, 0, p, b, Mode::All).unwrap();
                let (cl, per) = run_mode(&bvh, &sc.tris, &rays, t, 0, p, b, Mode::Closest).unwrap();
                let (any, _) = run_mode(&bvh, &sc.tris, &rays, t, 0, p, b, Mode::Any).unwrap();
                assert_eq!((cl.hits, any.hits), (all.hits, all.hits));
                assert!(cl.tri_tests < all.tri_tests, "B{b}: {cl:?} {all:?}");
                assert!(cl.entry_skips > 0 && all.entry_skips == 0, "B{b}: {cl:?}");
                assert!(any.tri_tests < cl.tri_tests, "B{b}: {any:?} {cl:?}");
                // A conservative tester enters the hit's leaf no later than the hit.
                for r in &per {
                    let (Some((_, t)), Some(e)) = (&r.hit, r.hit_entry) else {
                        panic!("B{b}: every ray of the room hits: {r:?}")
                    };
                    assert!(
                        e <= crate::exact::round_up(t),
                        "B{b}: entry {e} after the hit {t}"
                    );
                }
                let sum = |f: fn(&RayResult) -> u64| per.iter().map(f).sum::<u64>();
                assert_eq!(sum(|r| r.tri_tests), cl.tri_tests);
                assert_eq!(sum(|r| r.node_tests), cl.box_tests);
                if b == 1 {
                    assert_eq!(cl.pair_tests, 0);
                } else {
                    assert!(sum(|r| r.pair_tests) >= cl.pair_tests && cl.pair_tests > 0);
                }
            }
        }
    }

    /// A tester whose entry lies beyond the box (but that culls nothing) loses closest hits in closest-hit
    /// mode, and the traversal says so; in all-hits mode the entry is never used and it passes.
    #[test]
    fn a_late_entry_loses_closest_hits_and_is_an_error() {
        struct Late<'a>(ExactTester<'a>);
        impl NodeTester for Late<'_> {
            fn test(&mut self, r: &Ray, node: usize) -> Option<(f64, f64)> {
                self.0.test(r, node).map(|(_, hi)| (hi, hi))
            }
        }
        let sc = scene::by_name("mesh", 1, None).unwrap();
        let bvh = Bvh::build(&sc.tris, 4).unwrap();
        let rays = scene::primary_rays(&sc, 32, 24);
        let mut late = Late(ExactTester::new(&bvh, &[], 0));
        assert!(run_mode(&bvh, &sc.tris, &rays, &mut late, 0, None, 1, Mode::All).is_ok());
        let e = run_mode(&bvh, &sc.tris, &rays, &mut late, 0, None, 1, Mode::Closest)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("closest hit") && e.contains("exact reference"),
            "{e}"
        );
    }

    /// With a format's culls and the exact intervals, closest hit does no more node tests than the format
    /// alone; with planes' culls and the slab's entry, no fewer than with the planes' own entry.
    #[test]
    fn exact_intervals_save_work_and_plane_entries_are_no_worse_than_the_slab_entry() {
        let (sc, bvh, rays, map) = setup();
        let planes = crate::plane::generate::generate(&bvh, &sc.tris, 1).unwrap();
        let cf = CullFixFormat::over(FixFormat::b8());
        let mut fx = FixTester::new(cf, map, &bvh, &sc.tris, &planes, 1).unwrap();
        let mut slab = FixTester::new(cf, map, &bvh, &sc.tris, &planes, 0).unwrap();
        let mut ex = ExactTester::new(&bvh, &planes, 1);
        let run = |t: &mut dyn NodeTester| {
            run_mode(&bvh, &sc.tris, &rays, t, 1, None, 1, Mode::Closest)
                .unwrap()
                .0
        };
        let own = run(&mut fx);
        let exact_iv = run(&mut Intervals {
            cull: &mut fx,
            interval: &mut ex,
        });
        let slab_iv = run(&mut Intervals {
            cull: &mut fx,
            interval: &mut slab,
        });
        let work = |s: &SceneStats| (s.box_tests, s.tri_tests, s.entry_skips);
        eprintln!(
            "(node tests, triangle tests, entry skips): b8 K1 {:?}, exact intervals {:?}, slab entry {:?}",
            work(&own),
            work(&exact_iv),
            work(&slab_iv)
        );
        assert!(exact_iv.box_tests <= own.box_tests && exact_iv.tri_tests < own.tri_tests);
        assert!(slab_iv.box_tests >= own.box_tests && slab_iv.tri_tests >= own.tri_tests);
    }

    #[test]
    fn modes_parse_and_default_per_ray_set() {
        for m in [Mode::Closest, Mode::Any, Mode::All] {
            assert_eq!(Mode::parse(m.name()).unwrap(), m);
        }
        assert!(Mode::parse("first")
            .unwrap_err()
            .to_string()
            .contains("`first`"));
        assert_eq!(Mode::default_for("shadow"), Mode::Any);
        assert_eq!(Mode::default_for("bounce"), Mode::Closest);
    }
}
