//! Testbench glue of the float bundle pair ([`rtl::bundle::pair_float::BundleFloat`]): the model as the
//! testbench sees it, vector streams (BundleGen bundles, single rays quantised as tiny bundles, two-ray
//! inputs and raw bit patterns, with bubbles), and [`PairFloatCtx`], the [`BlockCtx`] that the one
//! cross-simulation loop ([`crate::xsim::xsim`]) and the port-word files use.

use crate::campaign::campaign_bounds;
use crate::rtl_sim::TesterSim;
use crate::xsim::BlockCtx;
use golden::bundle::edge::{BoxPair, Bundle};
use golden::bundle::float::{quantize_box_pair, quantize_bundle, FloatBundle};
use golden::bundle::gen::BundleGen;
use golden::format::float::FloatFormat;
use golden::geom::{Aabb, Ray};
use golden::slab::float::FloatBox;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::bundle::pair_float::{BundleFloatIo, FloatPairInput};
use rtl::bundle::ports::PairFloatPorts;

/// One test of the float pair: a bundle (or two rays) and the box pair.
pub type FloatBundleVec = (FloatPairInput, BoxPair<FloatBox>);

/// The bit-accurate model of the pair: `(all_hit, all_miss)`.
pub fn bundle_float_model(f: &FloatFormat, v: &FloatBundleVec) -> (bool, bool) {
    v.0.model(f, &v.1)
}

/// A single ray quantised into `f` as the pair takes it: the tiny bundle of `Bundle::of_ray`.
pub fn ray_bundle(f: &FloatFormat, r: &Ray) -> Result<FloatBundle, golden::Error> {
    quantize_bundle(f, &Bundle::of_ray(r)?)
}

/// A world bundle and box quantised into `f`, or `None` when they do not fit the format.
pub fn quantised(
    f: &FloatFormat,
    b: &Bundle,
    bx: &Aabb,
) -> Option<(FloatBundle, BoxPair<FloatBox>)> {
    Some((quantize_bundle(f, b).ok()?, quantize_box_pair(f, bx).ok()?))
}

/// A pattern of `f`: one of its specials (zeros, subnormals, one, the largest finite, infinities, NaN
/// and neighbours) one time in four, else any pattern (NaN included).
fn raw_code<R: Rng>(f: &FloatFormat, specials: &[u32], rng: &mut R) -> u32 {
    if rng.gen_ratio(1, 4) {
        specials[rng.gen_range(0..specials.len())]
    } else {
        rng.gen::<u32>() & f.mask()
    }
}

/// A bundle with every field any pattern of `f` (specials weighted up; ends equal one time in four, so
/// zero-width intervals and their special values occur): the RTL must match the model on all of them,
/// NaN and infinities included (the model is defined on every pattern).
pub fn raw_float_bundle<R: Rng>(f: &FloatFormat, rng: &mut R) -> FloatBundle {
    let sp = f.specials();
    let mut b = FloatBundle::default();
    for a in 0..3 {
        b.o_lo[a] = raw_code(f, &sp, rng);
        b.o_hi[a] = if rng.gen_ratio(1, 4) {
            b.o_lo[a]
        } else {
            raw_code(f, &sp, rng)
        };
        b.d_lo[a] = raw_code(f, &sp, rng);
        b.d_hi[a] = if rng.gen_ratio(1, 4) {
            b.d_lo[a]
        } else {
            raw_code(f, &sp, rng)
        };
    }
    b.t_lo = raw_code(f, &sp, rng);
    b.t_hi = raw_code(f, &sp, rng);
    b
}

/// A raw test: a [`raw_float_bundle`] (or two) and raw boxes (the outer box equal to the inner one half
/// of the time).
pub fn raw_float_vec<R: Rng>(f: &FloatFormat, rng: &mut R) -> FloatBundleVec {
    let sp = f.specials();
    let bx = |rng: &mut R| {
        let mut b = FloatBox::default();
        for a in 0..3 {
            b.lo[a] = raw_code(f, &sp, rng);
            b.hi[a] = raw_code(f, &sp, rng);
        }
        b
    };
    let inner = bx(rng);
    let outer = if rng.gen() { inner } else { bx(rng) };
    let input = if rng.gen_ratio(1, 4) {
        FloatPairInput::TwoRays(raw_float_bundle(f, rng), raw_float_bundle(f, rng))
    } else {
        FloatPairInput::Bundle(raw_float_bundle(f, rng))
    };
    (input, BoxPair { inner, outer })
}

/// Draws BundleGen cases until one quantises into `f`.
fn next_quantised(
    f: &FloatFormat,
    gen: &mut BundleGen,
) -> (
    golden::bundle::gen::BundleCase,
    FloatBundle,
    BoxPair<FloatBox>,
) {
    loop {
        let c = gen.next_case();
        if let Some((b, p)) = quantised(f, &c.bundle, &c.bounds) {
            return (c, b, p);
        }
    }
}

/// One of a case's rays quantised as a tiny bundle (the case's first ray when none quantises).
fn case_ray(
    f: &FloatFormat,
    c: &golden::bundle::gen::BundleCase,
    rng: &mut Pcg64,
) -> Option<FloatBundle> {
    let r = &c.rays[rng.gen_range(0..c.rays.len())];
    ray_bundle(f, r)
        .ok()
        .or_else(|| ray_bundle(f, &c.rays[0]).ok())
}

/// `n` pipeline tests for `f`, seeded: BundleGen cases over the campaign bounds (60% adversarial)
/// quantised into `f`; one in eight a single ray of a case (a tiny bundle, judged as a bundle); one in
/// eight two rays of one case against its box (one time in four the same ray twice; a side is the case's
/// whole bundle one time in eight); one in eight [`raw_float_vec`]; when `bubbles`, about one cycle in
/// eight is a bubble.
pub fn bundle_float_vectors(
    f: FloatFormat,
    seed: u64,
    n: u64,
    bubbles: bool,
) -> impl Iterator<Item = Option<FloatBundleVec>> + Send + 'static {
    two_ray_share_vectors(f, seed, n, bubbles, 1)
}

/// As [`bundle_float_vectors`], with `two_rays` eighths of the tests two-ray inputs (0 to 8; they take
/// the place of the bundles first, then of the single rays, then of the raw tests).
pub fn two_ray_share_vectors(
    f: FloatFormat,
    seed: u64,
    n: u64,
    bubbles: bool,
    two_rays: u32,
) -> impl Iterator<Item = Option<FloatBundleVec>> + Send + 'static {
    let (lo, hi) = campaign_bounds();
    let mut gen = BundleGen::new(seed, lo, hi, 0.6);
    let mut rng = Pcg64::seed_from_u64(seed ^ 0x9e37_79b9);
    let two_rays = two_rays.min(8);
    let mut left = n;
    std::iter::from_fn(move || {
        if left == 0 {
            return None;
        }
        if bubbles && rng.gen_ratio(1, 8) {
            return Some(None);
        }
        left -= 1;
        let k = rng.gen_range(0..8u32);
        Some(Some(if k < two_rays {
            loop {
                let (c, whole, p) = next_quantised(&f, &mut gen);
                // A side is the case's whole bundle one time in eight: the pair judges any bundle on
                // either side with AnyHit's bounds, so the AllHit tester's runtime mode meets
                // straddling and wide bundles too.
                let side = |rng: &mut Pcg64| {
                    if rng.gen_ratio(1, 8) {
                        Some(whole)
                    } else {
                        case_ray(&f, &c, rng)
                    }
                };
                let Some(a) = side(&mut rng) else {
                    continue;
                };
                let b = if rng.gen_ratio(1, 4) {
                    a
                } else {
                    match side(&mut rng) {
                        Some(b) => b,
                        None => continue,
                    }
                };
                break (FloatPairInput::TwoRays(a, b), p);
            }
        } else if k == 7 {
            raw_float_vec(&f, &mut rng)
        } else if k == 6 {
            loop {
                let (c, _, p) = next_quantised(&f, &mut gen);
                if let Some(a) = case_ray(&f, &c, &mut rng) {
                    break (FloatPairInput::Bundle(a), p);
                }
            }
        } else {
            let (_, b, p) = next_quantised(&f, &mut gen);
            (FloatPairInput::Bundle(b), p)
        }))
    })
}

/// The float pair's configuration as the testbenches see it (its format).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PairFloatCtx(pub FloatFormat);

impl BlockCtx for PairFloatCtx {
    type Ray = FloatPairInput;
    type Box = BoxPair<FloatBox>;
    type Out = (bool, bool);
    type Ports = PairFloatPorts;
    fn name(&self) -> String {
        format!("bundle_float_{}", self.0.name())
    }
    fn ports(&self) -> PairFloatPorts {
        PairFloatPorts
    }
    fn model(&self, r: &FloatPairInput, b: &BoxPair<FloatBox>) -> (bool, bool) {
        r.model(&self.0, b)
    }
    /// A decisive answer: all hit or all miss.
    fn counts_as_hit(&self, o: &(bool, bool)) -> bool {
        o.0 || o.1
    }
}

/// The stream runner's view of a float bundle pair in simulation (for [`crate::dut::run_checked`]).
pub fn bundle_float_rtl<S: BundleFloatIo>() -> TesterSim<S> {
    TesterSim::wrap(S::for_format(&S::format()))
}
