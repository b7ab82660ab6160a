//! Testbench glue of the fixed-point chained slab + cull-plane tester: its context [`CullFixCtx`]
//! ([`BlockCtx`] for the cross-simulation loop and the port words, [`TesterCtx`] for the judge), vector
//! streams, and the conservativeness campaign against the
//! exact clip and an exact ray-triangle test.

use crate::xsim::{BlockCtx, TesterCtx};
use glam::DVec3;
use golden::error::Error;
use golden::exact::ExactHit;
use golden::format::fixed::{FixFormat, GridMap};
use golden::plane::clip::{clip_exact, ExactPlane};
use golden::plane::fix::{
    self as plane_fix, cull_fix_quotients, node_fix, CullFixFormat, FixNode, FixPlane, NodeFixRay,
    PlaneFixOut,
};
use golden::plane::gen::{CullCase, CullGen};
use golden::scene::tri::{tri_hit, Triangle};
use golden::slab::check::{judge, Verdict};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::plane::ports::PlaneFixPorts;

/// Scene bounds of the cull-plane campaigns: cases lie in `[-CULL_R, CULL_R]^3`.
pub const CULL_R: f64 = 64.0;

/// The fixed chained tester's context: its plane format and plane count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CullFixCtx {
    pub cf: CullFixFormat,
    pub k: usize,
}

impl BlockCtx for CullFixCtx {
    type Ray = NodeFixRay;
    type Box = FixNode;
    type Out = PlaneFixOut;
    type Ports = PlaneFixPorts;
    fn name(&self) -> String {
        rtl::names::plane_fix_module(&self.cf, self.k)
    }
    fn ports(&self) -> PlaneFixPorts {
        PlaneFixPorts
    }
    fn model(&self, r: &NodeFixRay, n: &FixNode) -> PlaneFixOut {
        node_fix(&self.cf, self.k, r, n)
    }
    fn counts_as_hit(&self, o: &PlaneFixOut) -> bool {
        o.hit
    }
}

impl TesterCtx for CullFixCtx {
    fn world(&self, r: &NodeFixRay, o: &PlaneFixOut) -> (bool, f64, f64) {
        let f = &self.cf.base;
        (
            o.hit,
            r.ray.t_entry_f64(f, o.t_entry),
            r.ray.t_exit_f64(f, o.t_exit),
        )
    }
    fn judge(&self, r: &NodeFixRay, o: &PlaneFixOut, exact: &ExactHit) -> Verdict {
        let f = &self.cf.base;
        judge(exact, o.hit, || {
            Some((r.ray.t_world(f, o.t_entry), r.ray.t_world(f, o.t_exit)))
        })
    }
}

/// The grid of the cull-plane campaigns for a slab format.
pub fn cull_map(fmt: FixFormat) -> GridMap {
    GridMap::for_bounds(fmt, DVec3::splat(-CULL_R), DVec3::splat(CULL_R)).expect("finite bounds")
}

/// A case quantised for the fixed tester: the ray, the node (planes fitted to the case's triangle, or an
/// offset at the format's limit), and the stored planes as exact half-spaces.
pub fn fix_case(
    cf: &CullFixFormat,
    map: &GridMap,
    c: &CullCase,
) -> Result<(NodeFixRay, FixNode, Vec<ExactPlane>), Error> {
    let r = NodeFixRay {
        ray: map.quantize_ray(&c.ray)?,
        dir: plane_fix::quantize_dir(cf, &c.ray)?,
    };
    let mut node = FixNode {
        b: map.quantize_box(&c.bounds)?,
        ..Default::default()
    };
    for (k, n) in c.normals.iter().enumerate() {
        node.planes[k] = plane_fix::fit_plane(cf, map, &node.b, *n, &c.tri)?;
    }
    if let Some((k, top)) = c.extreme_w {
        let (lo, hi) = cf.w_range();
        node.planes[k].w = if top { hi } else { lo };
        if node.planes[k].n == [0; 3] {
            node.planes[k].n = [1, 0, 0];
        }
    }
    let exact = node.planes[..c.normals.len()]
        .iter()
        .map(|p| p.to_exact(map, &node.b))
        .collect();
    Ok((r, node, exact))
}

/// A node test with every field uniform over its code range: the RTL must match the model on all inputs.
pub fn raw_node_fix<R: Rng>(cf: &CullFixFormat, rng: &mut R) -> (NodeFixRay, FixNode) {
    let (ray, b) = crate::campaign::raw_fix_vector(&cf.base, rng);
    let d = |rng: &mut R| rng.gen_range(-(1i64 << (cf.d_bits() - 1))..(1i64 << (cf.d_bits() - 1)));
    let mut r = NodeFixRay {
        ray,
        ..Default::default()
    };
    for a in 0..3 {
        r.dir.lo[a] = d(rng);
        r.dir.hi[a] = if rng.gen() { r.dir.lo[a] } else { d(rng) };
    }
    let nmax = 1i64 << (cf.n - 1);
    let (wlo, whi) = cf.w_range();
    let mut node = FixNode {
        b,
        ..Default::default()
    };
    for p in node.planes.iter_mut() {
        *p = FixPlane {
            n: std::array::from_fn(|_| rng.gen_range(-nmax..nmax)),
            w: match rng.gen_range(0..6) {
                0 => wlo,
                1 => whi,
                _ => rng.gen_range(wlo..=whi),
            },
        };
    }
    (r, node)
}

/// A user's vector (a world ray, box and planes) quantised for the fixed tester of `cf` on `map`: each
/// plane fitted outward to the part of the box on its non-empty side
/// ([`golden::plane::clip::region_points`]), so the stored node encloses the world node (slots beyond the
/// vector's planes stay unused). An empty box keeps no planes (it misses anyway).
pub fn fix_vector(
    cf: &CullFixFormat,
    map: &GridMap,
    v: &golden::slab::vectors::Vector,
) -> Result<(NodeFixRay, FixNode), Error> {
    let r = NodeFixRay {
        ray: map.quantize_ray(&v.ray)?,
        dir: plane_fix::quantize_dir(cf, &v.ray)?,
    };
    let mut node = FixNode {
        b: map.quantize_box(&v.bx)?,
        ..Default::default()
    };
    if !v.bx.is_empty() {
        for (i, p) in v.planes.iter().enumerate() {
            let pts = golden::plane::clip::region_points(&v.bx, p);
            node.planes[i] = plane_fix::fit_plane(cf, map, &node.b, p.n, &pts)?;
        }
    }
    Ok((r, node))
}

/// A stream of `n` node tests for the pipeline: cases from [`CullGen`] (mixed uniform and adversarial),
/// one in eight replaced by a raw vector, and (when `bubbles`) about one cycle in eight a bubble.
pub fn node_fix_vectors(
    ctx: CullFixCtx,
    seed: u64,
    n: u64,
    bubbles: bool,
) -> impl Iterator<Item = Option<(NodeFixRay, FixNode)>> + Send + 'static {
    let map = cull_map(ctx.cf.base);
    let mut gen = CullGen::new(seed, 0.5, ctx.k, CULL_R);
    let mut rng = Pcg64::seed_from_u64(seed ^ 0x5851_f42d_4c95_7f2d);
    let mut left = n;
    std::iter::from_fn(move || {
        if left == 0 {
            return None;
        }
        if bubbles && rng.gen_ratio(1, 8) {
            return Some(None);
        }
        left -= 1;
        if rng.gen_ratio(1, 8) {
            return Some(Some(raw_node_fix(&ctx.cf, &mut rng)));
        }
        loop {
            let c = gen.case();
            if let Ok((r, node, _)) = fix_case(&ctx.cf, &map, &c) {
                return Some(Some((r, node)));
            }
        }
    })
}

/// What a cull-plane campaign saw.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CullStats {
    pub vectors: u64,
    /// Cases the exact clip culls (no point of the ray in the box on the non-empty side of every plane).
    pub exact_culled: u64,
    /// Cases the datapath culls.
    pub culled: u64,
    /// Cases the exact-fraction variant of the datapath culls (fixed point only).
    pub culled_fractions: u64,
    /// Cases whose ray truly hits the node's triangle within its t range.
    pub tri_hits: u64,
    /// False misses, non-enclosing intervals, culled triangle hits: correctness bugs.
    pub violations: u64,
}

impl CullStats {
    pub fn add(&mut self, o: &CullStats) {
        self.vectors += o.vectors;
        self.exact_culled += o.exact_culled;
        self.culled += o.culled;
        self.culled_fractions += o.culled_fractions;
        self.tri_hits += o.tri_hits;
        self.violations += o.violations;
    }
}

/// Judges one result: the interval contract against the exact clip by the stored planes, and — when the
/// planes were fitted to the triangle — that a ray truly hitting the triangle is not culled.
pub fn judge_case(
    case: &CullCase,
    exact: &ExactHit,
    hit: bool,
    interval: impl FnOnce() -> Option<(golden::exact::Ext, golden::exact::Ext)>,
) -> (Verdict, bool) {
    let v = judge(exact, hit, interval);
    let tri = Triangle { v: case.tri };
    let tri_hit_now = case.extreme_w.is_none() && tri_hit(&case.ray, &tri).is_some();
    if tri_hit_now && !hit {
        return (
            Verdict::Violation("a ray hitting the node's triangle was culled".into()),
            true,
        );
    }
    (v, tri_hit_now)
}

/// One case run through a datapath: the exact clip by its stored planes, its cull decision, its interval
/// (exact world values, `None` for a NaN), and the exact-fraction variant's decision where there is one.
pub struct CaseRun {
    pub exact: ExactHit,
    pub hit: bool,
    pub interval: Option<(golden::exact::Ext, golden::exact::Ext)>,
    pub fraction_hit: Option<bool>,
    pub detail: String,
}

/// The campaign loop shared by both datapaths: `n` cases from [`CullGen`], each quantised and run by
/// `run` (`None`: the case does not fit the format, skipped), judged by [`judge_case`]. The first violation
/// is returned as an error naming the case.
fn campaign_loop(
    name: &str,
    k: usize,
    seed: u64,
    n: u64,
    adversarial: f64,
    mut run: impl FnMut(&CullCase) -> Option<CaseRun>,
    mut progress: impl FnMut(u64),
) -> Result<CullStats, String> {
    let mut gen = CullGen::new(seed, adversarial, k, CULL_R);
    let mut st = CullStats::default();
    while st.vectors < n {
        let c = gen.case();
        let Some(r) = run(&c) else {
            continue;
        };
        let (v, th) = judge_case(&c, &r.exact, r.hit, || r.interval.clone());
        st.vectors += 1;
        st.exact_culled += u64::from(!r.exact.hit);
        st.culled += u64::from(!r.hit);
        st.culled_fractions += u64::from(r.fraction_hit == Some(false));
        st.tri_hits += u64::from(th);
        if let Verdict::Violation(why) = v {
            st.violations += 1;
            return Err(format!(
                "{name} k{k}: case {} ({:?}): {why}\n  ray {:?}\n  box {:?}\n  tri {:?}\n  {}",
                st.vectors, c.kind, c.ray, c.bounds, c.tri, r.detail
            ));
        }
        if st.vectors % 65536 == 0 {
            progress(st.vectors);
        }
    }
    Ok(st)
}

/// Runs `n` cases through the fixed model of `ctx` against the exact clip and the exact triangle test,
/// counting also what the exact-fraction variant ([`cull_fix_quotients`]) would cull.
pub fn cull_fix_campaign(
    ctx: CullFixCtx,
    seed: u64,
    n: u64,
    adversarial: f64,
    progress: impl FnMut(u64),
) -> Result<CullStats, String> {
    let map = cull_map(ctx.cf.base);
    let f = ctx.cf.base;
    let run = |c: &CullCase| {
        let (r, node, exact_planes) = fix_case(&ctx.cf, &map, c).ok()?;
        let out = ctx.model(&r, &node);
        let slab = golden::slab::fix::slab_fix(&f, &r.ray, &node.b);
        let (quot_hit, _, _) = cull_fix_quotients(
            &ctx.cf,
            &r.ray,
            &r.dir,
            &node.b,
            &node.planes[..ctx.k],
            &slab,
        );
        Some(CaseRun {
            exact: clip_exact(&c.ray, &c.bounds, &exact_planes),
            hit: out.hit,
            interval: Some((
                r.ray.t_world(&f, out.t_entry),
                r.ray.t_world(&f, out.t_exit),
            )),
            fraction_hit: Some(quot_hit),
            detail: format!("node {node:?}\n  out {out:?}"),
        })
    };
    campaign_loop(&ctx.name(), ctx.k, seed, n, adversarial, run, progress)
}

/// A case quantised for the float tester of format `cf` with `k` planes (as [`fix_case`]).
pub fn float_case(
    cf: &golden::plane::float::CullFloatFormat,
    c: &CullCase,
) -> Result<
    (
        golden::plane::float::NodeFloatRay,
        golden::plane::float::FloatNode,
        Vec<ExactPlane>,
    ),
    Error,
> {
    use golden::plane::float as pf;
    let f = &cf.f;
    let r = pf::NodeFloatRay {
        ray: golden::slab::float::quantize_ray(f, &c.ray)?,
        dir: pf::quantize_dir(cf, &c.ray)?,
    };
    let mut node = pf::FloatNode {
        b: golden::slab::float::quantize_box(f, &c.bounds)?,
        ..Default::default()
    };
    for (k, n) in c.normals.iter().enumerate() {
        node.planes[k] = pf::fit_plane(cf, &node.b, *n, &c.tri)?;
    }
    if let Some((k, top)) = c.extreme_w {
        node.planes[k].w = if top {
            f.max_finite(false)
        } else {
            f.max_finite(true)
        };
        if node.planes[k].n == [0; 3] {
            node.planes[k].n[0] = f.from_f64(1.0, golden::format::float::Rounding::NearestEven);
        }
    }
    let exact = node.planes[..c.normals.len()]
        .iter()
        .map(|p| p.to_exact(f, &node.b))
        .collect();
    Ok((r, node, exact))
}

/// The float counterpart of [`cull_fix_campaign`] (no fraction variant: `culled_fractions` stays 0).
pub fn cull_float_campaign(
    cf: golden::plane::float::CullFloatFormat,
    k: usize,
    seed: u64,
    n: u64,
    adversarial: f64,
    progress: impl FnMut(u64),
) -> Result<CullStats, String> {
    let f = cf.f;
    let run = |c: &CullCase| {
        let (r, node, exact_planes) = float_case(&cf, c).ok()?;
        let out = golden::plane::float::node_float(&cf, k, &r, &node);
        Some(CaseRun {
            exact: clip_exact(&c.ray, &c.bounds, &exact_planes),
            hit: out.hit,
            interval: golden::plane::float::out_interval(&f, &out),
            fraction_hit: None,
            detail: format!("node {node:?}\n  out {out:?}"),
        })
    };
    campaign_loop(&cf.name(), k, seed, n, adversarial, run, progress)
}
