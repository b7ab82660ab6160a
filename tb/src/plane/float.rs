//! Testbench glue of the chained float node tester (`rtl::PlaneFloat`): its context [`CullFloatCtx`]
//! ([`BlockCtx`]: the port codec and the model `golden::plane::float::node_float`; [`TesterCtx`]: the
//! judge), and vector
//! streams — raw bit patterns (NaN and infinities included) and the cull-plane campaign's cases
//! ([`CullGen`], quantised with planes fitted by [`float_case`]).

use crate::plane::fix::{float_case, CULL_R};
use crate::xsim::{BlockCtx, TesterCtx};
use golden::exact::ExactHit;
use golden::plane::float::{
    node_float, out_interval, CullFloatFormat, FloatNode, FloatPlane, NodeFloatRay,
};
use golden::plane::gen::CullGen;
use golden::slab::float::SlabFloatOut;
use rand::Rng;
use rand_pcg::Pcg64;
use rtl::plane::ports::PlaneFloatPorts;

/// One test of the chained tester: `None` is a bubble.
pub type NodeVec = Option<(NodeFloatRay, FloatNode)>;

/// The cull format and plane count of a chained float tester.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CullFloatCtx {
    pub cf: CullFloatFormat,
    pub k: usize,
}

impl CullFloatCtx {
    pub fn new(cf: CullFloatFormat, k: usize) -> Self {
        CullFloatCtx { cf, k }
    }
}

impl BlockCtx for CullFloatCtx {
    type Ray = NodeFloatRay;
    type Box = FloatNode;
    type Out = SlabFloatOut;
    type Ports = PlaneFloatPorts;
    fn name(&self) -> String {
        format!("{}_k{}", self.cf.name(), self.k)
    }
    fn ports(&self) -> PlaneFloatPorts {
        PlaneFloatPorts
    }
    fn model(&self, r: &NodeFloatRay, b: &FloatNode) -> SlabFloatOut {
        node_float(&self.cf, self.k, r, b)
    }
    fn counts_as_hit(&self, o: &SlabFloatOut) -> bool {
        o.hit
    }
}

impl TesterCtx for CullFloatCtx {
    fn world(&self, _: &NodeFloatRay, o: &SlabFloatOut) -> (bool, f64, f64) {
        let f = &self.cf.f;
        (o.hit, f.to_f64(o.t_entry), f.to_f64(o.t_exit))
    }
    fn judge(
        &self,
        _: &NodeFloatRay,
        o: &SlabFloatOut,
        exact: &ExactHit,
    ) -> golden::slab::check::Verdict {
        golden::slab::check::judge(exact, o.hit, || out_interval(&self.cf.f, o))
    }
}

/// A float pattern: a special of the format one time in four, else any pattern.
fn code<R: Rng>(cf: &CullFloatFormat, specials: &[u32], rng: &mut R) -> u32 {
    if rng.gen_bool(0.25) {
        specials[rng.gen_range(0..specials.len())]
    } else {
        rng.gen_range(0..=cf.f.mask())
    }
}

/// A node test with every field any pattern of the format (NaN included), `k` planes.
pub fn raw_node<R: Rng>(cf: &CullFloatFormat, k: usize, rng: &mut R) -> (NodeFloatRay, FloatNode) {
    let sp = cf.f.specials();
    let mut r = NodeFloatRay::default();
    let mut n = FloatNode::default();
    for a in 0..3 {
        r.ray.o_lo[a] = code(cf, &sp, rng);
        r.ray.o_hi[a] = code(cf, &sp, rng);
        r.ray.m_lo[a] = code(cf, &sp, rng);
        r.ray.m_hi[a] = code(cf, &sp, rng);
        r.ray.neg[a] = rng.gen_bool(0.5);
        r.dir.lo[a] = code(cf, &sp, rng);
        r.dir.hi[a] = code(cf, &sp, rng);
        n.b.lo[a] = code(cf, &sp, rng);
        n.b.hi[a] = code(cf, &sp, rng);
    }
    r.ray.t_min = code(cf, &sp, rng);
    r.ray.t_max = code(cf, &sp, rng);
    for p in n.planes.iter_mut().take(k) {
        *p = FloatPlane {
            n: std::array::from_fn(|_| code(cf, &sp, rng)),
            w: code(cf, &sp, rng),
        };
    }
    (r, n)
}

/// A user's vector quantised for the float tester of `cf` (as [`crate::plane::fix::fix_vector`]).
pub fn float_vector(
    cf: &CullFloatFormat,
    v: &golden::slab::vectors::Vector,
) -> Result<(NodeFloatRay, FloatNode), golden::Error> {
    let r = NodeFloatRay {
        ray: golden::slab::float::quantize_ray(&cf.f, &v.ray)?,
        dir: golden::plane::float::quantize_dir(cf, &v.ray)?,
    };
    let mut node = FloatNode {
        b: golden::slab::float::quantize_box(&cf.f, &v.bx)?,
        ..Default::default()
    };
    if !v.bx.is_empty() {
        for (i, p) in v.planes.iter().enumerate() {
            let pts = golden::plane::clip::region_points(&v.bx, p);
            node.planes[i] = golden::plane::float::fit_plane(cf, &node.b, p.n, &pts)?;
        }
    }
    Ok((r, node))
}

/// An endless stream of node tests for `ctx`: cases of [`CullGen`] (half adversarial) quantised by
/// [`float_case`], and raw patterns (a raw one every
/// `raw_every` tests, none when 0), and a bubble every `bubble_every` cycles (none when 0).
pub fn node_stream(
    ctx: CullFloatCtx,
    seed: u64,
    raw_every: u64,
    bubble_every: u64,
) -> impl Iterator<Item = NodeVec> + Send + 'static {
    use rand::SeedableRng;
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut gen = CullGen::new(seed, 0.5, ctx.k, CULL_R);
    let mut i = 0u64;
    std::iter::from_fn(move || {
        i += 1;
        if bubble_every > 0 && i.is_multiple_of(bubble_every) {
            return Some(None);
        }
        if raw_every > 0 && i.is_multiple_of(raw_every) {
            return Some(Some(raw_node(&ctx.cf, ctx.k, &mut rng)));
        }
        loop {
            if let Ok((r, node, _)) = float_case(&ctx.cf, &gen.case()) {
                return Some(Some((r, node)));
            }
        }
    })
}

/// Runs `f` on a thread with a 512 MiB stack: a `PlaneFloat` block is a large value (every signal of
/// every unit inline), too large for a test thread's default stack once `K >= 2`. Panics propagate.
pub fn with_big_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    match std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(f)
        .expect("spawn a test thread")
        .join()
    {
        Ok(v) => v,
        Err(e) => std::panic::resume_unwind(e),
    }
}
