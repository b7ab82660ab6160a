//! Scene job streams through the streaming results processors: every bundle's traversal recorded as a
//! tree of jobs (bundle, node box pair, active rays, the model's mask) by the model of the processor's
//! datapath (`golden::bundle::split::split_with` on the quantised bundle, box pair and rays, as
//! `golden::bundle::traverse` runs it, without early splits (the RTL does not make them), and with or
//! without re-bounding: a job that drops rays hands its children the bundle the block re-bounds around
//! the rays it keeps, `Rebound::Stored`), then replayed closed-loop through the block: a job is started once its parent's
//! result has come back, up to four bundles at once (one per ray set, the next bundle's rays written
//! while the others run), and every result is checked against the recorded mask and re-bounded bundle
//! and every clock against the clock-by-clock model ([`StreamChecker`]). The fixed datapath
//! (`BundleStream`) and the float one (`BundleStreamFloat`) differ only in how a scene is quantised for
//! them ([`SceneDatapath`]).
//!
//! What it measures: clocks, and the clocks the pair's input was used (which equal the model's busy-pair
//! count, `BundleStats::pair_cycles`), so the pair-input utilisation is the model's busy-pair figure
//! over the RTL's clocks.

use super::stream::{StreamCases, StreamChecker, StreamRtl};
use glam::DVec3;
use golden::bundle::build::Built;
use golden::bundle::edge::{BoxPair, Bundle};
use golden::bundle::fix::{bundle_dir_exp, BundleFixFormat};
use golden::bundle::rebound::{j_fits, quantize_scaled, ScaledBundle, J_BITS};
use golden::bundle::split::split_with;
use golden::bundle::stream::{
    PairDatapath, StreamInOf, StreamJob, StreamJobOf, STREAM_RAYS, STREAM_SETS,
};
use golden::format::fixed::GridMap;
use golden::format::float::FloatFormat;
use golden::geom::{Aabb, Ray};
use golden::scene::bvh::{Bvh, NodeKind};
use rtl::bundle::stream::BundleStreamIo;

/// How a scene's bundles, node boxes and rays are quantised for a processor's datapath.
pub trait SceneDatapath: StreamCases {
    /// What quantisation needs of the scene: the grid over it (fixed), nothing (float).
    type Ctx: Clone;
    /// The context over a scene whose grid bounds are `lo`, `hi`.
    fn scene_ctx(&self, lo: DVec3, hi: DVec3) -> Result<Self::Ctx, String>;
    /// A node box, both ways.
    fn boxes(&self, ctx: &Self::Ctx, b: &Aabb) -> Result<BoxPair<Self::Box>, String>;
    /// A bundle as the job port takes it.
    fn job_bundle(&self, ctx: &Self::Ctx, b: &Bundle) -> Result<Self::Bundle, String>;
    /// Ray `r` of the bundle `root` as the ray store holds it: on its own direction scale with its
    /// exponent (fixed), on the scale of `root` (float; see `golden::bundle::rebound`).
    fn store_ray(&self, ctx: &Self::Ctx, root: &Bundle, r: &Ray) -> Result<Self::Ray, String>;
    /// A re-bounded bundle as the job port takes it.
    fn hull_bundle(h: &Self::Hull) -> Self::Bundle;
    /// Whether a one-job processor (`rtl::bundle::split::BundleSplit`) exists on this datapath.
    const ONE_JOB: bool;
}

impl SceneDatapath for BundleFixFormat {
    type Ctx = GridMap;
    fn scene_ctx(&self, lo: DVec3, hi: DVec3) -> Result<GridMap, String> {
        GridMap::for_bounds(self.base, lo, hi).map_err(|e| e.to_string())
    }
    fn boxes(&self, map: &GridMap, b: &Aabb) -> Result<BoxPair<Self::Box>, String> {
        golden::bundle::fix::quantize_box_pair(map, b)
            .map_err(|e| format!("a node box does not fit {}: {e}", self.name()))
    }
    fn job_bundle(&self, map: &GridMap, b: &Bundle) -> Result<Self::Bundle, String> {
        golden::bundle::fix::quantize_bundle(self, map, b).map_err(|e| e.to_string())
    }
    fn store_ray(&self, map: &GridMap, _: &Bundle, r: &Ray) -> Result<ScaledBundle, String> {
        let r = Bundle::of_ray(r)
            .and_then(|r| quantize_scaled(self, map, &r))
            .map_err(|e| e.to_string())?;
        if j_fits(r.j) {
            Ok(r)
        } else {
            Err(format!(
                "direction exponent {} does not fit the {J_BITS}-bit ray_j port (a direction too \
                 short or too long)",
                r.j
            ))
        }
    }
    fn hull_bundle(h: &ScaledBundle) -> Self::Bundle {
        h.q
    }
    const ONE_JOB: bool = true;
}

impl SceneDatapath for FloatFormat {
    type Ctx = ();
    fn scene_ctx(&self, _: DVec3, _: DVec3) -> Result<(), String> {
        Ok(())
    }
    fn boxes(&self, _: &(), b: &Aabb) -> Result<BoxPair<Self::Box>, String> {
        golden::bundle::float::quantize_box_pair(self, b)
            .map_err(|e| format!("a node box does not fit {}: {e}", self.name()))
    }
    fn job_bundle(&self, _: &(), b: &Bundle) -> Result<Self::Bundle, String> {
        golden::bundle::float::quantize_bundle(self, b).map_err(|e| e.to_string())
    }
    fn store_ray(&self, _: &(), root: &Bundle, r: &Ray) -> Result<Self::Ray, String> {
        Bundle::of_ray(r)
            .and_then(|r| golden::bundle::float::quantize_bundle_at(self, &r, bundle_dir_exp(root)))
            .map_err(|e| e.to_string())
    }
    fn hull_bundle(h: &Self::Hull) -> Self::Bundle {
        *h
    }
    const ONE_JOB: bool = false;
}

/// One job of a recorded traversal.
#[derive(Clone, Debug)]
pub struct TreeJob<P: PairDatapath> {
    /// Index of its bundle in [`JobTrees::bundles`].
    pub bundle: usize,
    /// The job (its `set` and `tag` are chosen when it is started).
    pub job: StreamJobOf<P>,
    /// The model's result: the rays that go on.
    pub mask: u16,
    /// Whether the pair decided the bundle.
    pub decided: bool,
    /// The re-bounded bundle the block reports with it: `golden::bundle::rebound::rebound_fix` or
    /// `rebound_float` of the rays kept by a split job (`None` for a decided job or one that kept none).
    pub rebound: Option<P::Hull>,
    /// The jobs released by its result (the children's, when `mask` is not empty).
    pub children: Vec<usize>,
}

/// Recorded traversals of a set of bundles.
#[derive(Clone, Debug)]
pub struct JobTrees<P: PairDatapath> {
    /// Per bundle: its rays as the store holds them and its root job.
    pub bundles: Vec<(Vec<P::Ray>, usize)>,
    pub jobs: Vec<TreeJob<P>>,
    /// The model's busy-pair count: `1 + ceil(|active| / 2)` per split job, 1 per decided one.
    pub pair_cycles: u64,
    /// Clocks the one-job processor (`rtl::bundle::split::BundleSplit`) takes for the same jobs back to
    /// back: `rtl::bundle::split::split_clocks` of each, summed; `None` on a datapath without one.
    pub one_job_clocks: Option<u64>,
}

impl<P: PairDatapath> Default for JobTrees<P> {
    fn default() -> Self {
        JobTrees {
            bundles: vec![],
            jobs: vec![],
            pair_cycles: 0,
            one_job_clocks: None,
        }
    }
}

/// Records the traversal of every bundle of `built` (at most [`STREAM_RAYS`] rays each) on `bvh` with
/// the datapath `dp` (quantised with `ctx`); with `rebound`, a job that drops rays passes the bundle the
/// block re-bounds around the rays it keeps to its children (`golden::bundle::traverse`'s
/// `Rebound::Stored`), else its own bundle. Errors name the bundle and what does not fit.
pub fn job_trees<P: SceneDatapath>(
    dp: &P,
    ctx: &P::Ctx,
    bvh: &Bvh,
    rays: &[Ray],
    built: &[Built],
    rebound: bool,
) -> Result<JobTrees<P>, String> {
    let mut t = JobTrees::<P> {
        one_job_clocks: P::ONE_JOB.then_some(0),
        ..Default::default()
    };
    let boxes: Vec<_> = bvh
        .nodes
        .iter()
        .map(|n| dp.boxes(ctx, &n.bounds))
        .collect::<Result<_, _>>()?;
    for (k, b) in built.iter().enumerate() {
        let n = b.rays.len();
        if n == 0 || n > STREAM_RAYS {
            return Err(format!(
                "bundle {k}: {n} rays; the ray store holds 1 to {STREAM_RAYS} a bundle"
            ));
        }
        let fb = dp
            .job_bundle(ctx, &b.bundle)
            .map_err(|e| format!("bundle {k}: {e}"))?;
        let sr: Vec<P::Ray> = b
            .rays
            .iter()
            .map(|&i| {
                dp.store_ray(ctx, &b.bundle, &rays[i])
                    .map_err(|e| format!("bundle {k}, ray {i}: {e}"))
            })
            .collect::<Result<_, String>>()?;
        let root = t.jobs.len();
        t.bundles.push((sr.clone(), root));
        // (node, active, the job that releases it, the bundle)
        let mut todo = vec![(0usize, ((1u32 << n) - 1) as u16, None::<usize>, fb)];
        while let Some((node, active, parent, fb)) = todo.pop() {
            let job = StreamJob {
                bundle: fb,
                boxes: boxes[node],
                active,
                set: 0,
                tag: 0,
            };
            let bx = &boxes[node];
            let r = split_with(
                || dp.decide(&fb, bx),
                |i| dp.may_hit(&sr[i], &bx.outer),
                active as u64,
            );
            t.pair_cycles += r.pair_cycles as u64;
            if let Some(c) = t.one_job_clocks.as_mut() {
                *c += rtl::bundle::split::split_clocks(&r) as u64;
            }
            let id = t.jobs.len();
            let hull = if r.split {
                (0..n)
                    .filter(|i| r.mask >> i & 1 == 1)
                    .fold(None, |acc, i| dp.gather(acc, &sr[i]))
            } else {
                None
            };
            t.jobs.push(TreeJob {
                bundle: k,
                job,
                mask: r.mask as u16,
                decided: !r.split,
                rebound: hull,
                children: vec![],
            });
            if let Some(p) = parent {
                t.jobs[p].children.push(id);
            }
            if r.mask != 0 {
                if let NodeKind::Inner { left, right } = bvh.nodes[node].kind {
                    let next = match hull {
                        Some(h) if rebound && r.mask as u16 != active => P::hull_bundle(&h),
                        _ => fb,
                    };
                    todo.push((right, r.mask as u16, Some(id), next));
                    todo.push((left, r.mask as u16, Some(id), next));
                }
            }
        }
    }
    Ok(t)
}

/// What a closed-loop run measured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StreamRun {
    pub bundles: u64,
    pub jobs: u64,
    pub decided: u64,
    pub clocks: u64,
    /// Clocks the pair's input was used.
    pub busy: u64,
    /// The model's busy-pair count of the same jobs.
    pub pair_cycles: u64,
}

impl StreamRun {
    /// Pair-input utilisation: busy clocks over clocks.
    pub fn utilisation(&self) -> f64 {
        self.busy as f64 / self.clocks.max(1) as f64
    }

    /// Clocks per job.
    pub fn clocks_per_job(&self) -> f64 {
        self.clocks as f64 / self.jobs.max(1) as f64
    }

    /// The model's busy-pair count over the RTL's clocks.
    pub fn of_model(&self) -> f64 {
        self.pair_cycles as f64 / self.clocks.max(1) as f64
    }
}

/// Per ray set: the bundle it holds, its rays still to write, its jobs released and not yet started
/// (last released first), and its jobs started and not yet reported.
struct SetState<R> {
    bundle: Option<usize>,
    writes: Vec<(u8, R)>,
    ready: Vec<usize>,
    in_flight: usize,
}

impl<R> Default for SetState<R> {
    fn default() -> Self {
        SetState {
            bundle: None,
            writes: vec![],
            ready: vec![],
            in_flight: 0,
        }
    }
}

/// Replays `trees` closed-loop through `dut` (see the module doc), `progress` called once per bundle
/// finished. Errors on any difference from the model or from a recorded mask.
pub fn run_trees<S: BundleStreamIo>(
    dp: &S::Dp,
    trees: &JobTrees<S::Dp>,
    dut: &mut StreamRtl<S>,
    mut progress: impl FnMut(),
) -> Result<StreamRun, String> {
    let mut ck = StreamChecker::of::<S>(dp);
    let mut sets: Vec<SetState<<S::Dp as PairDatapath>::Ray>> =
        (0..STREAM_SETS).map(|_| SetState::default()).collect();
    let mut next_bundle = 0;
    let mut tags: Vec<Option<usize>> = vec![None; 256];
    let mut next_tag = 0u8;
    let mut run = StreamRun {
        bundles: trees.bundles.len() as u64,
        pair_cycles: trees.pair_cycles,
        ..Default::default()
    };
    let mut ready = true;
    let mut finished = 0;
    while finished < trees.bundles.len() {
        // A free set takes the next bundle: its rays are written one a clock.
        for s in sets.iter_mut() {
            if s.bundle.is_none() && next_bundle < trees.bundles.len() {
                let rays = &trees.bundles[next_bundle].0;
                s.writes = rays
                    .iter()
                    .enumerate()
                    .rev()
                    .map(|(i, r)| (i as u8, *r))
                    .collect();
                s.bundle = Some(next_bundle);
                next_bundle += 1;
            }
        }
        let mut input = StreamInOf::<S::Dp>::default();
        // One write a clock, to the loading set of the oldest bundle; its root is released with its
        // last ray (the contract allows a start in that clock).
        if let Some((k, s)) = sets
            .iter_mut()
            .enumerate()
            .filter(|(_, s)| !s.writes.is_empty())
            .min_by_key(|(_, s)| s.bundle)
        {
            let (i, r) = s.writes.pop().expect("not empty");
            input.write = Some((k as u8, i, r));
            if s.writes.is_empty() {
                s.ready.push(trees.bundles[s.bundle.expect("loading")].1);
            }
        }
        // A start when the block is ready: the oldest bundle's last released job.
        if ready {
            if let Some((k, s)) = sets
                .iter_mut()
                .enumerate()
                .filter(|(_, s)| !s.ready.is_empty())
                .min_by_key(|(_, s)| s.bundle)
            {
                let id = s.ready.pop().expect("not empty");
                while tags[next_tag as usize].is_some() {
                    next_tag = next_tag.wrapping_add(1);
                }
                tags[next_tag as usize] = Some(id);
                s.in_flight += 1;
                input.start = Some(StreamJob {
                    set: k as u8,
                    tag: next_tag,
                    ..trees.jobs[id].job
                });
                run.jobs += 1;
            }
        }
        let out = dut.step(&input);
        ck.check(&input, &out)?;
        run.clocks += 1;
        ready = out.ready;
        if out.done {
            let id = tags[out.tag as usize].take().ok_or_else(|| {
                format!(
                    "clock {}: done with tag {} not in flight",
                    run.clocks, out.tag
                )
            })?;
            let tj = &trees.jobs[id];
            if out.mask != tj.mask {
                return Err(format!(
                    "clock {}: job {id} (bundle {}) reported mask {:#06x}, the model {:#06x}",
                    run.clocks, tj.bundle, out.mask, tj.mask
                ));
            }
            if out.rebound != tj.rebound {
                return Err(format!(
                    "clock {}: job {id} (bundle {}) reported the re-bounded bundle {:?}, the \
                     traversal's rule {:?}",
                    run.clocks, tj.bundle, out.rebound, tj.rebound
                ));
            }
            run.decided += tj.decided as u64;
            let s = sets
                .iter_mut()
                .find(|s| s.bundle == Some(tj.bundle))
                .expect("a job's bundle holds a set");
            s.in_flight -= 1;
            s.ready.extend(tj.children.iter().rev());
            if s.in_flight == 0 && s.ready.is_empty() && s.writes.is_empty() {
                s.bundle = None;
                finished += 1;
                progress();
            }
        }
        if run.clocks > 64 * (trees.pair_cycles + 1000) {
            return Err(format!("no progress after {} clocks", run.clocks));
        }
    }
    run.busy = ck.stats.busy;
    Ok(run)
}

/// Every decided job of `trees` as one independent stream (each job's rays loaded first, jobs started
/// whenever `ready`): bundle tests per clock when nothing waits on a result.
pub fn run_decided<S: BundleStreamIo>(
    dp: &S::Dp,
    trees: &JobTrees<S::Dp>,
    dut: &mut StreamRtl<S>,
) -> Result<StreamRun, String> {
    let mut ck = StreamChecker::of::<S>(dp);
    let jobs: Vec<&TreeJob<S::Dp>> = trees.jobs.iter().filter(|j| j.decided).collect();
    let mut run = StreamRun {
        jobs: jobs.len() as u64,
        decided: jobs.len() as u64,
        pair_cycles: jobs.len() as u64,
        ..Default::default()
    };
    let (mut next, mut ready, mut done) = (0, true, 0);
    while done < jobs.len() {
        let mut input = StreamInOf::<S::Dp>::default();
        if ready && next < jobs.len() {
            input.start = Some(StreamJob {
                tag: next as u8,
                ..jobs[next].job
            });
            next += 1;
        }
        let out = dut.step(&input);
        ck.check(&input, &out)?;
        run.clocks += 1;
        ready = out.ready;
        done += out.done as usize;
        if run.clocks > 4 * jobs.len() as u64 + 100 {
            return Err(format!("no progress after {} clocks", run.clocks));
        }
    }
    run.busy = ck.stats.busy;
    Ok(run)
}

/// The job streams of one scene: `(ray set, bundling, trees)` for the primary rays in `tile x tile`
/// tiles of a `w x h` image and the bounce and shadow rays bundled by the builder (`rays` per bundle at
/// most, direction spread `dir_spread`, origin spread a tenth of the scene's diagonal, 16 open
/// bundles), as `rtu bundle-scenes` makes them (same BVH, rays and seed), on the datapath `dp` (the
/// fixed one over the scene's grid); children get re-bounded bundles with `rebound` ([`job_trees`]).
#[allow(clippy::type_complexity)]
pub fn scene_streams<P: SceneDatapath>(
    scene: &golden::scene::tri_scene::TriScene,
    seed: u64,
    (w, h): (usize, usize),
    tile: usize,
    (rays, dir_spread): (usize, f64),
    dp: &P,
    rebound: bool,
) -> Result<Vec<(&'static str, String, JobTrees<P>)>, String> {
    use golden::bundle::build::{build, tiles, BuildParams};
    use golden::scene::traverse::{trace, AabbOnly};
    let bvh = Bvh::build(&scene.tris, 4).map_err(|e| e.to_string())?;
    let prim = golden::scene::tri_scene::primary_rays(scene, w, h);
    let (hits, _) = trace(&bvh, &scene.tris, &prim, &mut AabbOnly::new(&bvh));
    let sec = golden::scene::tri_scene::secondary_rays(scene, &prim, &hits, seed + 1);
    let b = scene.bounds();
    let diag = (b.max - b.min).length();
    let (lo, hi) = scene.grid_bounds();
    let ctx = dp.scene_ctx(lo, hi)?;
    let mut out = vec![];
    let built = tiles(&prim, w, h, tile).map_err(|e| e.to_string())?;
    out.push((
        "primary",
        format!("tile{tile}x{tile}"),
        job_trees(dp, &ctx, &bvh, &prim, &built, rebound)
            .map_err(|e| format!("primary rays: {e}"))?,
    ));
    let p = BuildParams {
        max_rays: rays,
        origin_spread: 0.1 * diag,
        dir_spread,
        t_spread: f64::INFINITY,
        open_slots: 16,
    };
    for (set, r) in [("bounce", &sec.bounce), ("shadow", &sec.shadow)] {
        let built = build(r, &p).map_err(|e| format!("{set} rays: {e}"))?;
        out.push((
            set,
            format!("build{rays}@{dir_spread}"),
            job_trees(dp, &ctx, &bvh, r, &built, rebound)
                .map_err(|e| format!("{set} rays: {e}"))?,
        ));
    }
    Ok(out)
}
