//! Testbench glue of the fixed-point bundle pair ([`rtl::bundle::pair_fix::BundleFix`]): the model as the
//! testbench sees it, vector streams (BundleGen bundles, on-grid single rays, two-ray inputs of on-grid
//! and off-grid quantised rays, and raw codes, with bubbles), and `BundleFixFormat` as the
//! [`BlockCtx`] that the one cross-simulation loop ([`crate::xsim::xsim`]) and the port-word files use.

use crate::campaign::{campaign_bounds, campaign_map, raw_fix_vector};
use crate::rtl_sim::TesterSim;
use crate::xsim::BlockCtx;
use golden::bundle::edge::{BoxPair, Bundle};
use golden::bundle::fix::{quantize_box_pair, quantize_bundle, BundleFixFormat, FixBundle};
use golden::bundle::gen::{BundleCase, BundleGen};
use golden::format::fixed::{FixBox, GridMap};
use golden::geom::Ray;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::bundle::pair_fix::{BundleFixIo, PairInput};
use rtl::bundle::ports::PairFixPorts;

/// One test of the pair: a bundle (or two rays) and the box pair.
pub type BundleVec = (PairInput, BoxPair<FixBox>);

/// The bit-accurate model of the pair: `(all_hit, all_miss)`.
pub fn bundle_model(bf: &BundleFixFormat, v: &BundleVec) -> (bool, bool) {
    v.0.model(bf, &v.1)
}

/// A single ray as a point bundle: the `lo` ends of `b`.
pub fn point_of(b: &FixBundle) -> FixBundle {
    FixBundle {
        o_hi: b.o_lo,
        d_hi: b.d_lo,
        t_hi: b.t_lo,
        ..*b
    }
}

/// A test with every code drawn over its range (origins, boxes and t codes of either sign and order,
/// `+-inf` t codes weighted up; direction codes within the quantiser's `[-2^(FD+1), 2^(FD+1)]`, ends
/// weighted up): the RTL must match the model on all of them.
pub fn raw_bundle<R: Rng>(bf: &BundleFixFormat, rng: &mut R) -> BundleVec {
    let fmt = &bf.base;
    let (r, inner) = raw_fix_vector(fmt, rng);
    let (_, outer) = raw_fix_vector(fmt, rng);
    let dm = 1i64 << (bf.fd + 1);
    let d = |rng: &mut R| match rng.gen_range(0..8) {
        0 => -dm,
        1 => dm,
        2 => 0,
        _ => rng.gen_range(-dm..=dm),
    };
    let t = |rng: &mut R| match rng.gen_range(0..8) {
        0 => fmt.t_pos_inf(),
        1 => fmt.t_neg_inf(),
        2 => 0,
        _ => rng.gen_range(fmt.t_neg_inf()..=fmt.t_pos_inf()),
    };
    let mut b = FixBundle {
        o_lo: r.o_lo,
        o_hi: r.o_hi,
        t_lo: t(rng),
        t_hi: t(rng),
        ..Default::default()
    };
    for a in 0..3 {
        b.d_lo[a] = d(rng);
        b.d_hi[a] = if rng.gen() { b.d_lo[a] } else { d(rng) };
    }
    let outer = if rng.gen() { inner } else { outer };
    // Two rays: raw tiny bundles (any codes) or raw points.
    let input = match rng.gen_range(0..8) {
        0 => PairInput::TwoRays(point_of(&b), point_of(raw_bundle(bf, rng).0.sides().0)),
        1 => PairInput::TwoRays(b, *raw_bundle(bf, rng).0.sides().1),
        _ => PairInput::Bundle(b),
    };
    (input, BoxPair { inner, outer })
}

/// A world ray quantised for the pair: the tiny bundle `quantize_bundle(Bundle::of_ray(ray))` (a point
/// bundle when every input of the ray is on the grid); `None` when it does not fit the grid.
pub fn quantised_ray(bf: &BundleFixFormat, map: &GridMap, ray: &Ray) -> Option<FixBundle> {
    quantize_bundle(bf, map, &Bundle::of_ray(ray).ok()?).ok()
}

/// A BundleGen case quantised for the pair: the bundle, the box pair and every listed ray of the case
/// (each as [`quantised_ray`]; `None` when the bundle, the box or a ray does not fit the grid).
pub fn quantised_case(
    bf: &BundleFixFormat,
    map: &GridMap,
    c: &BundleCase,
) -> Option<(FixBundle, BoxPair<FixBox>, Vec<FixBundle>)> {
    let b = quantize_bundle(bf, map, &c.bundle).ok()?;
    let p = quantize_box_pair(map, &c.bounds).ok()?;
    let rays = c
        .rays
        .iter()
        .map(|r| quantised_ray(bf, map, r))
        .collect::<Option<Vec<_>>>()?;
    Some((b, p, rays))
}

/// A two-ray test drawn from `gen`: ray A from a case (half the time an on-grid single ray, else one of
/// the listed rays of a BundleGen case, off the grid and so a tiny bundle), judged against that case's
/// box; ray B the same ray (one time in eight), another ray of the same case, or a ray of another case.
pub fn two_ray_vec(
    bf: &BundleFixFormat,
    map: &GridMap,
    gen: &mut BundleGen,
    rng: &mut Pcg64,
) -> BundleVec {
    let draw = |gen: &mut BundleGen, rng: &mut Pcg64| loop {
        let c = if rng.gen() {
            gen.grid_one_ray(map)
        } else {
            gen.next_case()
        };
        if let Some((_, p, rays)) = quantised_case(bf, map, &c) {
            break (p, rays);
        }
    };
    let (p, rays) = draw(gen, rng);
    let a = rays[rng.gen_range(0..rays.len())];
    let b = match rng.gen_range(0..8) {
        0 => a,
        1..=4 => rays[rng.gen_range(0..rays.len())],
        _ => {
            let other = draw(gen, rng).1;
            other[rng.gen_range(0..other.len())]
        }
    };
    (PairInput::TwoRays(a, b), p)
}

/// `n` pipeline tests for the preset `bf`, seeded: BundleGen cases (60% adversarial) quantised on the
/// campaign grid, one in eight an on-grid single ray, one in eight a [`two_ray_vec`] (on-grid and
/// off-grid quantised rays) and one in eight [`raw_bundle`]; when `bubbles`, about one cycle in eight is
/// a bubble.
pub fn bundle_vectors(
    bf: BundleFixFormat,
    seed: u64,
    n: u64,
    bubbles: bool,
) -> impl Iterator<Item = Option<BundleVec>> + Send + 'static {
    let map = campaign_map(bf.base);
    let (lo, hi) = campaign_bounds();
    let mut gen = BundleGen::new(seed, lo, hi, 0.6);
    let mut rng = Pcg64::seed_from_u64(seed ^ 0x5bd1_e995);
    let mut left = n;
    std::iter::from_fn(move || {
        if left == 0 {
            return None;
        }
        if bubbles && rng.gen_ratio(1, 8) {
            return Some(None);
        }
        left -= 1;
        // A case whose quantisation does not fit the grid is drawn again.
        let quantised = |gen: &mut BundleGen, one_ray: bool| loop {
            let c = if one_ray {
                gen.grid_one_ray(&map)
            } else {
                gen.next_case()
            };
            if let (Ok(b), Ok(p)) = (
                quantize_bundle(&bf, &map, &c.bundle),
                quantize_box_pair(&map, &c.bounds),
            ) {
                break (b, p);
            }
        };
        Some(Some(match rng.gen_range(0..8) {
            0 => raw_bundle(&bf, &mut rng),
            1 => two_ray_vec(&bf, &map, &mut gen, &mut rng),
            k => {
                let (b, p) = quantised(&mut gen, k == 2);
                (PairInput::Bundle(b), p)
            }
        }))
    })
}

impl BlockCtx for BundleFixFormat {
    type Ray = PairInput;
    type Box = BoxPair<FixBox>;
    type Out = (bool, bool);
    type Ports = PairFixPorts;
    fn name(&self) -> String {
        format!("bundle_fix_{}", BundleFixFormat::name(self))
    }
    fn ports(&self) -> PairFixPorts {
        PairFixPorts
    }
    fn model(&self, r: &PairInput, b: &BoxPair<FixBox>) -> (bool, bool) {
        r.model(self, b)
    }
    /// A decisive answer: all hit or all miss.
    fn counts_as_hit(&self, o: &(bool, bool)) -> bool {
        o.0 || o.1
    }
}

/// The stream runner's view of a bundle pair in simulation (for [`crate::dut::run_checked`]).
pub fn bundle_rtl<S: BundleFixIo>(bf: &BundleFixFormat) -> TesterSim<S> {
    TesterSim::wrap(S::for_format(bf))
}
