//! Ray bundles traversing a BVH with the AllHit / AnyHit pair: how many bundle-box tests the pair decides
//! without splitting, against the ideal, and how many tester cycles that takes against testing the rays
//! one by one.
//!
//! # The traversal
//! Every bundle starts at the root with all its rays active. At a node with active rays `A`, the *ideal*
//! is known from the exact single-ray test of each active ray ([`crate::exact::slab_exact`]): the test is
//! *decidable* when the active rays all hit the node's box or all miss it. The datapath then either
//! (a) tests the bundle on the pair: "all hit" keeps every active ray, "all miss" drops them all, neither
//! *splits* the bundle and tests its active rays two per cycle (the pair's two-ray mode), or (b) skips the
//! bundle test when the [`SplitMetric`] predicts a split, and tests the rays at once. The rays kept go on
//! to both children of an inner node, as one bundle again ([`Rebound`]): the original bundle, the smallest
//! world bundle around the rays kept, quantised again, or the hull of the kept rays' stored tiny bundles
//! ([`crate::bundle::rebound`], the rule a results processor can follow while the rays stream through the
//! pair during a split, at no extra cycle; the streaming processors `rtl::bundle::stream::BundleStream`
//! and `rtl::bundle::stream_float::BundleStreamFloat` do, bit for bit; on the float datapath the rays are
//! stored on the scale of their original bundle, and the pair's two-ray answers are those of the stored
//! rays; under `keep` and `world` the float path quantises each ray on its own scale instead, which gives
//! the same answers while no value leaves the format's normal range: in `rtu bundle-scenes` the float
//! `stored` rows equal the `world` rows in every count). Distances
//! are not shortened by hits (an "all hits" traversal), so the node visits do not depend on child order.
//!
//! Every answer is checked: "all hit" with a ray of the tested bundle that misses (every ray of the
//! original bundle, or of the re-bounded one), "all miss" with one that hits, or a ray dropped by the
//! single-ray test although it hits, is a correctness bug and returns an error.
//!
//! # Cycles
//! A bundle-box test costs one pair cycle, plus `ceil(|A| / 2)` when it splits; an early split costs
//! `ceil(|A| / 2)` (the results processor's count, [`crate::bundle::split::split_cycles`]). These are cycles
//! in which the pair is busy: the one-job RTL results processor (`rtl::bundle::split`) waits out the pair's
//! latency, so its clocks per job are more (4 for a decided job); the streaming one
//! (`rtl::bundle::stream`, model [`crate::bundle::stream`]) keeps other jobs in the pair meanwhile and
//! comes within 1% of these cycles on the scenes' job streams (`rtu bundle-stream`). Testing the rays one by one costs `|A|` cycles of a single-ray
//! tester (the yardstick) or `ceil(|A| / 2)` on the pair; [`BundleStats`] keeps both.

use crate::bundle::build::{Built, SplitMetric};
use crate::bundle::check::slab_hit;
use crate::bundle::edge::{decide_exact, Bundle};
use crate::bundle::fix::bundle_dir_exp;
use crate::bundle::fix::{decide_fix, decide_fix_quantised, BundleFixFormat};
use crate::bundle::float::{
    all_hit_float, all_miss_float, decide_float, quantize_box_pair as float_box_pair,
    quantize_bundle_at, FloatBundle,
};
use crate::bundle::rebound::{quantize_scaled, rebound_fix, rebound_float, ScaledBundle};
use crate::bundle::split::split_cycles;
use crate::error::Error;
use crate::format::fixed::GridMap;
use crate::format::float::FloatFormat;
use crate::geom::{Aabb, Ray};
use crate::scene::bvh::{Bvh, NodeKind};

/// The datapath a traversal runs the pair on.
#[derive(Clone, Debug)]
pub enum BundlePath {
    /// The exact oracle (rational arithmetic): what the bundle test can decide at all.
    Exact,
    /// The fixed-point datapath on a grid over the scene.
    Fix(BundleFixFormat, GridMap),
    /// The float datapath.
    Float(FloatFormat),
}

impl BundlePath {
    /// `exact`, the fixed format's name (`b16`) or the float format's (`fp16`).
    pub fn name(&self) -> String {
        match self {
            BundlePath::Exact => "exact".into(),
            BundlePath::Fix(bf, _) => short_name(&bf.base),
            BundlePath::Float(f) => f.name(),
        }
    }

    /// `fixed`, `float` or `exact`.
    pub fn kind(&self) -> &'static str {
        match self {
            BundlePath::Exact => "exact",
            BundlePath::Fix(..) => "fixed",
            BundlePath::Float(_) => "float",
        }
    }

    /// `(all_hit, all_miss)` of the pair on `b` against `bx`.
    pub fn decide(&self, b: &Bundle, bx: &Aabb) -> Result<(bool, bool), Error> {
        match self {
            BundlePath::Exact => decide_exact(b, bx),
            BundlePath::Fix(bf, map) => decide_fix(bf, map, b, bx),
            BundlePath::Float(f) => decide_float(f, b, bx),
        }
    }

    /// The pair's two-ray answer for one ray: it may hit `bx` (never false for a ray that hits).
    pub fn may_hit(&self, r: &Ray, bx: &Aabb) -> Result<bool, Error> {
        match self {
            BundlePath::Exact => Ok(slab_hit(r, bx)),
            _ => Ok(!self.decide(&Bundle::of_ray(r)?, bx)?.1),
        }
    }
}

/// A fixed format's preset name (`b16`), or its full name for other formats.
pub fn short_name(f: &crate::format::fixed::FixFormat) -> String {
    crate::format::fixed::FixFormat::presets()
        .iter()
        .zip(["b8", "b12", "b16"])
        .find(|(p, _)| *p == f)
        .map_or_else(|| f.name(), |(_, n)| n.to_string())
}

/// Counts of a set of bundle traversals; see the module doc.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BundleStats {
    pub bundles: u64,
    pub rays: u64,
    /// Bundle-box tests: node visits with at least one active ray.
    pub tests: u64,
    /// Tests whose active rays truly all hit or all miss.
    pub ideal: u64,
    /// Tests the pair decided without splitting ("all hit" or "all miss").
    pub decided: u64,
    /// Of those, "all hit".
    pub decided_hit: u64,
    /// Tests sent straight to the rays by the splitting metric.
    pub early_splits: u64,
    /// Pair cycles of the bundle path.
    pub pair_cycles: u64,
    /// Single-ray tester cycles to test the active rays one by one (`sum |A|`).
    pub ray_cycles: u64,
    /// Pair cycles to test the active rays two per cycle without bundles (`sum ceil(|A| / 2)`).
    pub ray_pair_cycles: u64,
    /// Rays kept at a node whose box they truly miss (the datapath's looseness).
    pub false_hits: u64,
    /// Sum over bundles of their largest direction extent (for the mean spread).
    pub dir_spread_sum: f64,
}

impl BundleStats {
    pub fn add(&mut self, o: &BundleStats) {
        self.bundles += o.bundles;
        self.rays += o.rays;
        self.tests += o.tests;
        self.ideal += o.ideal;
        self.decided += o.decided;
        self.decided_hit += o.decided_hit;
        self.early_splits += o.early_splits;
        self.pair_cycles += o.pair_cycles;
        self.ray_cycles += o.ray_cycles;
        self.ray_pair_cycles += o.ray_pair_cycles;
        self.false_hits += o.false_hits;
        self.dir_spread_sum += o.dir_spread_sum;
    }

    /// Decided without splitting over decidable (the "fraction of the ideal").
    pub fn decided_of_ideal(&self) -> f64 {
        self.decided as f64 / self.ideal.max(1) as f64
    }

    /// Single-ray tester cycles over the bundle path's pair cycles.
    pub fn speedup(&self) -> f64 {
        self.ray_cycles as f64 / self.pair_cycles.max(1) as f64
    }

    /// Pair cycles without bundles over pair cycles with them.
    pub fn pair_speedup(&self) -> f64 {
        self.ray_pair_cycles as f64 / self.pair_cycles.max(1) as f64
    }
}

/// The exact single-ray results of a ray set on a BVH, computed once and shared by every traversal of
/// those rays: for each ray, the nodes whose box it hits ([`crate::exact::slab_exact`]), found by an
/// exact traversal. A node below a box the ray misses is missed too (a child's box lies inside its
/// parent's), so a node not listed is a miss.
#[derive(Clone, Debug)]
pub struct ExactHits {
    hit: Vec<Vec<u32>>,
}

impl ExactHits {
    pub fn new(bvh: &Bvh, rays: &[Ray]) -> Self {
        let hit = rays
            .iter()
            .map(|r| {
                let mut nodes = vec![];
                let mut stack = vec![0usize];
                while let Some(n) = stack.pop() {
                    let nd = &bvh.nodes[n];
                    if !slab_hit(r, &nd.bounds) {
                        continue;
                    }
                    nodes.push(n as u32);
                    if let NodeKind::Inner { left, right } = nd.kind {
                        stack.push(left);
                        stack.push(right);
                    }
                }
                nodes.sort_unstable();
                nodes
            })
            .collect();
        ExactHits { hit }
    }

    /// True when ray `i` hits the box of `node`.
    pub fn hits(&self, i: usize, node: usize) -> bool {
        self.hit[i].binary_search(&(node as u32)).is_ok()
    }
}

/// How a traversal runs; see the module doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TravOptions {
    pub metric: SplitMetric,
    pub rebound: Rebound,
}

/// What bundle the rays kept at a node take on to its children.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rebound {
    /// The bundle tested (in the end, the original bundle around every ray).
    Keep,
    /// The smallest world bundle around the rays kept ([`Bundle::around`]), quantised again.
    World,
    /// The hull of the kept rays as the ray store holds them ([`crate::bundle::rebound::rebound_fix`],
    /// [`crate::bundle::rebound::rebound_float`]): the rule of a results processor; the fixed and float
    /// datapaths (the exact path has no stored rays).
    Stored,
}

impl Rebound {
    /// `keep`, `world` or `stored`.
    pub fn name(&self) -> &'static str {
        match self {
            Rebound::Keep => "keep",
            Rebound::World => "world",
            Rebound::Stored => "stored",
        }
    }

    /// Every rule, `Keep` first.
    pub const ALL: [Rebound; 3] = [Rebound::Keep, Rebound::World, Rebound::Stored];
}

/// A re-bounded bundle on a datapath's codes ([`Rebound::Stored`]).
#[derive(Clone, Copy, Debug)]
enum Stored {
    Fix(ScaledBundle),
    Float(FloatBundle),
}

fn mask_rays(rays: &[Ray], idx: &[usize], mask: u64) -> Vec<Ray> {
    idx.iter()
        .enumerate()
        .filter(|(k, _)| mask >> k & 1 == 1)
        .map(|(_, &i)| rays[i])
        .collect()
}

/// Traverses `bvh` with one bundle (`b.rays` index `rays`, at most 64), adding to `st`. Errors on a
/// wrong answer (see the module doc) or an input a datapath cannot take, naming the node.
pub fn traverse_bundle(
    bvh: &Bvh,
    rays: &[Ray],
    exact: &ExactHits,
    b: &Built,
    path: &BundlePath,
    opt: &TravOptions,
    st: &mut BundleStats,
) -> Result<(), Error> {
    let n = b.rays.len();
    if n == 0 || n > 64 {
        return Err(Error::Io(format!("a bundle of {n} rays: 1..=64 expected")));
    }
    st.bundles += 1;
    st.rays += n as u64;
    st.dir_spread_sum += crate::bundle::build::spread(&b.bundle).1;
    let all = if n == 64 { u64::MAX } else { (1u64 << n) - 1 };
    let fix = match path {
        BundlePath::Fix(bf, map) => Some((bf, map)),
        _ => None,
    };
    let stored_float = match path {
        BundlePath::Float(f) if opt.rebound == Rebound::Stored => Some(f),
        _ => None,
    };
    if opt.rebound == Rebound::Stored && fix.is_none() && stored_float.is_none() {
        return Err(Error::Io(format!(
            "{}: stored-ray re-bounding is a rule of the fixed and float datapaths",
            path.name()
        )));
    }
    // On the float datapath with stored rays: each ray on the scale of the original bundle, as the
    // float processor's store holds it.
    let root_j = bundle_dir_exp(&b.bundle);
    let float_ray = |f: &FloatFormat, r: &Ray| quantize_bundle_at(f, &Bundle::of_ray(r)?, root_j);
    // Each entry: node, active rays, the world bundle (the metric's, and the pair's unless `stored`
    // holds the bundle on the datapath's codes).
    let mut stack: Vec<(usize, u64, Bundle, Option<Stored>)> = vec![(0, all, b.bundle, None)];
    while let Some((node, active, bundle, stored)) = stack.pop() {
        let nd = &bvh.nodes[node];
        let bx = &nd.bounds;
        // Exact hits of every ray of the bundle; `hits` of the active ones. The bundle tested here stands for
        // its `members`: every ray of the original bundle, or (re-bounded) the active rays.
        let mut all_hits = 0u64;
        for (k, &i) in b.rays.iter().enumerate() {
            if exact.hits(i, node) {
                all_hits |= 1 << k;
            }
        }
        let hits = all_hits & active;
        let members = if opt.rebound == Rebound::Keep {
            all
        } else {
            active
        };
        let member_hits = all_hits & members;
        let count = active.count_ones() as u64;
        st.tests += 1;
        st.ray_cycles += count;
        st.ray_pair_cycles += count.div_ceil(2);
        if hits == active || hits == 0 {
            st.ideal += 1;
        }
        let at = |what: &str| format!("{} at node {node}: {what}", path.name());
        let split = |st: &mut BundleStats| -> Result<u64, Error> {
            // The rays' share of a split job's pair cycles (the bundle test's one is counted below).
            st.pair_cycles += u64::from(split_cycles(true, active) - split_cycles(false, active));
            let mut m = 0u64;
            let outer = stored_float.map(|f| float_box_pair(f, bx)).transpose()?;
            for (k, &i) in b.rays.iter().enumerate() {
                if active >> k & 1 == 0 {
                    continue;
                }
                let may_hit = match (stored_float, &outer) {
                    (Some(f), Some(p)) => !all_miss_float(f, &float_ray(f, &rays[i])?, &p.outer),
                    _ => path.may_hit(&rays[i], bx)?,
                };
                if may_hit {
                    m |= 1 << k;
                }
            }
            Ok(m)
        };
        let mask = if opt.metric.split_first(&bundle, count as usize, bx) {
            st.early_splits += 1;
            split(st)?
        } else {
            st.pair_cycles += u64::from(split_cycles(false, active));
            let (all_hit, all_miss) = match (&stored, path) {
                (Some(Stored::Fix(h)), BundlePath::Fix(bf, map)) => {
                    decide_fix_quantised(bf, map, &h.q, bx)?
                }
                (Some(Stored::Float(h)), BundlePath::Float(f)) => {
                    let p = float_box_pair(f, bx)?;
                    (
                        all_hit_float(f, h, &p.inner),
                        all_miss_float(f, h, &p.outer),
                    )
                }
                _ => path.decide(&bundle, bx)?,
            };
            if all_hit && all_miss {
                return Err(Error::Io(at("both \"all hit\" and \"all miss\"")));
            }
            if all_hit {
                if member_hits != members {
                    return Err(Error::Io(at(
                        "\"all hit\" although a ray of the bundle misses",
                    )));
                }
                st.decided += 1;
                st.decided_hit += 1;
                active
            } else if all_miss {
                if member_hits != 0 {
                    return Err(Error::Io(at(
                        "\"all miss\" although a ray of the bundle hits",
                    )));
                }
                st.decided += 1;
                0
            } else {
                split(st)?
            }
        };
        if mask & hits != hits {
            return Err(Error::Io(at("a ray that hits was dropped (false miss)")));
        }
        st.false_hits += u64::from((mask & !hits).count_ones());
        if mask == 0 {
            continue;
        }
        if let NodeKind::Inner { left, right } = nd.kind {
            let (next, next_stored) = if opt.rebound != Rebound::Keep && mask != active {
                let kept = mask_rays(rays, &b.rays, mask);
                let hull = match (opt.rebound, path) {
                    (Rebound::Stored, BundlePath::Fix(bf, map)) => {
                        let tiny = kept
                            .iter()
                            .map(|r| quantize_scaled(bf, map, &Bundle::of_ray(r)?))
                            .collect::<Result<Vec<_>, Error>>()?;
                        rebound_fix(bf, tiny).map(Stored::Fix)
                    }
                    (Rebound::Stored, BundlePath::Float(f)) => {
                        let tiny = kept
                            .iter()
                            .map(|r| float_ray(f, r))
                            .collect::<Result<Vec<_>, Error>>()?;
                        rebound_float(f, tiny).map(Stored::Float)
                    }
                    _ => None,
                };
                (Bundle::around(&kept)?, hull)
            } else {
                (bundle, stored)
            };
            stack.push((right, mask, next, next_stored));
            stack.push((left, mask, next, next_stored));
        }
    }
    Ok(())
}

/// [`traverse_bundle`] over every bundle of `built`.
pub fn traverse_all(
    bvh: &Bvh,
    rays: &[Ray],
    exact: &ExactHits,
    built: &[Built],
    path: &BundlePath,
    opt: &TravOptions,
    mut progress: impl FnMut(),
) -> Result<BundleStats, Error> {
    let mut st = BundleStats::default();
    for b in built {
        traverse_bundle(bvh, rays, exact, b, path, opt, &mut st)?;
        progress();
    }
    Ok(st)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bundle::build::{build, tiles, BuildParams};
    use crate::format::fixed::dir_scale_exp;
    use crate::format::fixed::FixFormat;
    use crate::scene::tri_scene as scene;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    fn setup() -> (scene::TriScene, Bvh, Vec<Ray>) {
        let sc = scene::by_name("room", 1, Some(6)).unwrap();
        let bvh = Bvh::build(&sc.tris, 4).unwrap();
        let rays = scene::primary_rays(&sc, 16, 12);
        (sc, bvh, rays)
    }

    fn map_for(sc: &scene::TriScene, f: FixFormat) -> GridMap {
        let (lo, hi) = sc.grid_bounds();
        GridMap::for_bounds(f, lo, hi).unwrap()
    }

    #[test]
    fn single_rays_are_always_decided_and_cost_one_cycle_each() {
        let (sc, bvh, rays) = setup();
        let ex_hits = ExactHits::new(&bvh, &rays);
        let built = tiles(&rays, 16, 12, 1).unwrap();
        let opt = TravOptions {
            metric: SplitMetric::NEVER,
            rebound: Rebound::Keep,
        };
        let map = map_for(&sc, FixFormat::b16());
        for path in [
            BundlePath::Exact,
            BundlePath::Fix(BundleFixFormat::over(FixFormat::b16()).unwrap(), map),
        ] {
            let st = traverse_all(&bvh, &rays, &ex_hits, &built, &path, &opt, || {}).unwrap();
            // A one-ray bundle's test is the single-ray test: every test is ideal, and the exact path
            // decides every one (the fixed one may keep a ray that misses: it then says neither).
            assert_eq!(st.ideal, st.tests);
            assert_eq!(st.ray_cycles, st.tests);
            if let BundlePath::Exact = path {
                assert_eq!(st.decided, st.tests);
                assert_eq!(st.pair_cycles, st.tests);
                assert_eq!(st.false_hits, 0);
            }
            assert!(st.decided <= st.ideal);
        }
    }

    #[test]
    fn tiles_decide_most_decidable_tests_and_save_cycles() {
        let (sc, bvh, rays) = setup();
        let ex_hits = ExactHits::new(&bvh, &rays);
        let built = tiles(&rays, 16, 12, 4).unwrap();
        let map = map_for(&sc, FixFormat::b16());
        for rebound in Rebound::ALL {
            let opt = TravOptions {
                metric: SplitMetric::NEVER,
                rebound,
            };
            // The exact path has no stored rays: its world re-bounding is the yardstick then.
            let ex_opt = TravOptions {
                rebound: if rebound == Rebound::Stored {
                    Rebound::World
                } else {
                    rebound
                },
                ..opt
            };
            let ex = traverse_all(
                &bvh,
                &rays,
                &ex_hits,
                &built,
                &BundlePath::Exact,
                &ex_opt,
                || {},
            )
            .unwrap();
            let fx = traverse_all(
                &bvh,
                &rays,
                &ex_hits,
                &built,
                &BundlePath::Fix(
                    BundleFixFormat::over(FixFormat::b16()).unwrap(),
                    map.clone(),
                ),
                &opt,
                || {},
            )
            .unwrap();
            for st in [&ex, &fx] {
                assert!(st.decided <= st.ideal && st.ideal <= st.tests);
                assert!(st.decided > 0 && st.pair_cycles < st.ray_cycles, "{st:?}");
            }
            assert!(fx.decided <= ex.decided + ex.tests / 50, "{fx:?} vs {ex:?}");
        }
    }

    /// Stored-ray re-bounding on room tiles, every answer checked by the traversal: on the fixed datapath
    /// with directions of one scale exponent it is world re-bounding exactly; with directions of many
    /// lengths it still never contradicts the exact tests (a looser t range may decide less). On the
    /// float datapath (rays on their bundle's scale) it is world re-bounding exactly in binary32, where
    /// no value leaves the normal range, and in binary16 on the camera rays; on the rays of many lengths
    /// binary16 is only checked. The exact path refuses it.
    #[test]
    fn stored_ray_rebounding_is_checked_on_the_fixed_and_float_datapaths() {
        let (sc, bvh, rays) = setup();
        let built = tiles(&rays, 16, 12, 4).unwrap();
        let run = |rays: &[Ray], path: &BundlePath, rebound| {
            let ex_hits = ExactHits::new(&bvh, rays);
            let opt = TravOptions {
                metric: SplitMetric::NEVER,
                rebound,
            };
            traverse_all(&bvh, rays, &ex_hits, &built, path, &opt, || {})
        };
        let mut rng = Pcg64::seed_from_u64(5);
        let long_and_short: Vec<Ray> = rays
            .iter()
            .map(|r| {
                let s = 2f64.powi(rng.gen_range(-6..=6));
                Ray {
                    dir: r.dir * s,
                    t_max: rng.gen_range(2.0..30.0) / s,
                    ..*r
                }
            })
            .collect();
        for f in [FixFormat::b12(), FixFormat::b16()] {
            let path = BundlePath::Fix(BundleFixFormat::over(f).unwrap(), map_for(&sc, f));
            let unit = rays
                .iter()
                .map(|r| dir_scale_exp(r.dir))
                .collect::<Vec<_>>();
            assert!(
                unit.iter().all(|&j| j == unit[0]),
                "the room's camera rays share one direction exponent"
            );
            assert_eq!(
                run(&rays, &path, Rebound::Stored).unwrap(),
                run(&rays, &path, Rebound::World).unwrap()
            );
            let stored = run(&long_and_short, &path, Rebound::Stored).unwrap();
            let world = run(&long_and_short, &path, Rebound::World).unwrap();
            assert!(stored.decided > 0 && stored.tests > 0, "{stored:?}");
            assert_eq!(stored.rays, world.rays);
        }
        for f in [FloatFormat::FP32, FloatFormat::FP16] {
            let path = BundlePath::Float(f);
            for rs in [&rays, &long_and_short] {
                let stored = run(rs, &path, Rebound::Stored).unwrap();
                let world = run(rs, &path, Rebound::World).unwrap();
                assert!(
                    stored.decided > 0 && stored.rays == world.rays,
                    "{stored:?}"
                );
                // Binary32 everywhere; binary16 on the room's camera rays (directions of one length).
                if f == FloatFormat::FP32 || std::ptr::eq(rs, &rays) {
                    assert_eq!(stored, world, "{}", f.name());
                }
            }
        }
        let e = run(&rays, &BundlePath::Exact, Rebound::Stored).unwrap_err();
        assert!(e.to_string().contains("fixed and float datapaths"), "{e}");
    }

    #[test]
    fn the_metric_changes_cycles_not_answers() {
        let (_sc, bvh, rays) = setup();
        let ex_hits = ExactHits::new(&bvh, &rays);
        let built = build(
            &rays,
            &BuildParams {
                max_rays: 16,
                origin_spread: 0.0,
                dir_spread: 0.2,
                t_spread: 0.0,
                open_slots: 4,
            },
        )
        .unwrap();
        let run = |metric| {
            traverse_all(
                &bvh,
                &rays,
                &ex_hits,
                &built,
                &BundlePath::Exact,
                &TravOptions {
                    metric,
                    rebound: Rebound::World,
                },
                || {},
            )
            .unwrap()
        };
        let never = run(SplitMetric::NEVER);
        let always = run(SplitMetric {
            min_rays: 64,
            max_footprint: 0.0,
        });
        assert_eq!(always.early_splits, always.tests);
        assert_eq!(always.decided, 0);
        assert_eq!(always.pair_cycles, always.ray_pair_cycles);
        assert_eq!(never.early_splits, 0);
        // The same rays reach the same nodes either way.
        assert_eq!(never.ray_cycles, always.ray_cycles);
    }
}
