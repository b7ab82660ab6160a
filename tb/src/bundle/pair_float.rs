//! Testbench glue of the float bundle pair ([`rtl::bundle::pair_float::BundleFloat`]): the model as the
//! testbench sees it, vector streams (BundleGen bundles, single rays quantised as tiny bundles, two-ray
//! inputs and raw bit patterns, with bubbles), port encoding, and the cross-simulation loop that checks
//! Verilator against the rust-hdl simulation and the model.
//!
//! The fixed pair's loop ([`crate::bundle::pair_fix::bundle_xsim`]) is written for its format and vectors; this
//! one is the same check for the float pair: every output port of a valid cycle and `valid_out` of every
//! cycle against the model and, for the first cycles, against the rust-hdl simulation.

use crate::campaign::campaign_bounds;
use crate::dut::PipelinedDut;
use crate::rtl_sim::TesterSim;
use crate::slab::ports::{replay_vcd, XsimStats, XSIM_VCD_WINDOW};
use crate::verilator::Harness;
use golden::bundle::edge::{BoxPair, Bundle};
use golden::bundle::float::{quantize_box_pair, quantize_bundle, FloatBundle};
use golden::bundle::gen::BundleGen;
use golden::format::float::FloatFormat;
use golden::geom::{Aabb, Ray};
use golden::slab::float::FloatBox;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::bundle::pair_float::{BundleFloatIo, FloatPairInput};
use std::collections::VecDeque;
use std::sync::mpsc::sync_channel;

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

/// The value of input port `port` (a Verilog name such as `d_lo_1`) for one cycle (zero for a bubble's
/// data).
pub fn bundle_float_in_word(
    port: &str,
    tag: u16,
    v: &Option<FloatBundleVec>,
) -> Result<u64, String> {
    let (base, idx) = rtl::verilog::split_port(port);
    let idx = idx.unwrap_or(0);
    let Some((input, p)) = v else {
        return Ok(0);
    };
    let (a, r) = input.sides();
    Ok(match base {
        "valid_in" => 1,
        "rst" => 0,
        "tag_in" => tag as u64,
        "o_lo" => a.o_lo[idx] as u64,
        "o_hi" => a.o_hi[idx] as u64,
        "d_lo" => a.d_lo[idx] as u64,
        "d_hi" => a.d_hi[idx] as u64,
        "t_lo" => a.t_lo as u64,
        "t_hi" => a.t_hi as u64,
        "two_rays" => input.is_two_rays() as u64,
        "r_o_lo" => r.o_lo[idx] as u64,
        "r_o_hi" => r.o_hi[idx] as u64,
        "r_d_lo" => r.d_lo[idx] as u64,
        "r_d_hi" => r.d_hi[idx] as u64,
        "r_t" => r.t_hi as u64,
        "in_lo" => p.inner.lo[idx] as u64,
        "in_hi" => p.inner.hi[idx] as u64,
        "out_lo" => p.outer.lo[idx] as u64,
        "out_hi" => p.outer.hi[idx] as u64,
        _ => return Err(format!("unknown input port {port}")),
    })
}

/// The output word the model predicts for a port in a cycle whose due result is `due`.
fn expected_word(port: &str, due: Option<(u16, (bool, bool))>) -> Option<u64> {
    let (tag, (all_hit, all_miss)) = due?;
    Some(match port {
        "valid_out" => 1,
        "tag_out" => tag as u64,
        "all_hit" => all_hit as u64,
        "all_miss" => all_miss as u64,
        _ => return None,
    })
}

/// Streams `vectors` through the Verilator `harness` of a [`BundleFloatIo`] block and checks every output
/// record against the model (results, tags, latency, and `valid_out` low when nothing is due) and, for
/// the first `lockstep_cycles` cycles, against the rust-hdl simulation of the block made by `make` (every
/// port of a valid cycle, `valid_out` always). On a failure the last cycles are replayed into a VCD.
/// `XsimStats::hits` counts the tests with a decisive answer (`all_hit` or `all_miss` high).
pub fn bundle_float_xsim<S: BundleFloatIo, It>(
    make: impl Fn() -> S,
    harness: &Harness,
    vectors: It,
    lockstep_cycles: u64,
) -> Result<XsimStats, String>
where
    It: Iterator<Item = Option<FloatBundleVec>> + Send + 'static,
{
    let f = S::format();
    let ports: Vec<String> = harness.inputs.iter().map(|p| p.name.clone()).collect();
    let (tx, rx) = sync_channel::<(u16, Option<FloatBundleVec>)>(1 << 16);
    let lat = S::LATENCY as u64;
    let mut tag = 0u16;
    let records = vectors
        .chain(std::iter::repeat_n(None, lat as usize + 1))
        .map(move |v| {
            let t = tag;
            tag = tag.wrapping_add(v.is_some() as u16);
            let rec = ports
                .iter()
                .map(|p| bundle_float_in_word(p, t, &v).expect("known port"))
                .collect();
            tx.send((t, v)).expect("consumer alive");
            rec
        });
    let iv = harness
        .output_index("valid_out")
        .ok_or("no valid_out port")?;
    let mut rtl = (lockstep_cycles > 0).then(|| TesterSim::wrap(make()));
    let mut pending: VecDeque<(u64, u16, FloatBundleVec)> = VecDeque::new();
    let mut recent: VecDeque<(u16, Option<FloatBundleVec>)> = VecDeque::new();
    let mut stats = XsimStats::default();
    let mut last_cycle = 0u64;
    let cycles = harness
        .stream(records, |cycle, out| {
            let (tg, v) = rx.recv().map_err(|_| "producer ended early".to_string())?;
            last_cycle = cycle;
            recent.push_back((tg, v));
            if recent.len() > XSIM_VCD_WINDOW {
                recent.pop_front();
            }
            if let Some(x) = v {
                pending.push_back((cycle, tg, x));
            }
            let front = pending.front().filter(|p| p.0 + lat == cycle + 1);
            let due = front.map(|p| (p.1, bundle_float_model(&f, &p.2)));
            if cycle >= lockstep_cycles {
                rtl = None;
            }
            let sim_out = rtl.as_mut().map(|s| {
                s.step(v.as_ref().map(|x| (tg, x)));
                &s.uut
            });
            for (k, p) in harness.outputs.iter().enumerate() {
                if k != iv && out[iv] == 0 {
                    continue; // data ports are don't-care while not valid
                }
                let want = expected_word(&p.name, due).unwrap_or(0);
                let sim = sim_out.and_then(|u| u.output_word(&p.name));
                if out[k] != want || sim.is_some_and(|w| w != out[k]) {
                    return Err(format!(
                        "cycle {}: output {} is {:#x} in Verilator, {sim:?} in the rust-hdl simulation, \
                         {want:#x} in the model (latency {lat})\n  test due: {:?}",
                        cycle + 1,
                        p.name,
                        out[k],
                        front
                    ));
                }
            }
            if let Some((_, (all_hit, all_miss))) = due {
                pending.pop_front();
                stats.tests += 1;
                stats.hits += (all_hit || all_miss) as u64;
            }
            Ok(())
        })
        .map_err(|e| {
            let name = format!("xsim_bundle_float_{}_cycle{}.vcd", f.name(), last_cycle + 1);
            let path = crate::out_dir().join("vcd").join(name);
            match replay_vcd(&make, &recent, &path) {
                Ok(()) => format!(
                    "{e}\n  waveform of the last {} cycles (rust-hdl): {}",
                    recent.len(),
                    path.display()
                ),
                Err(w) => format!("{e}\n  (no waveform: {w})"),
            }
        })?;
    stats.cycles = cycles;
    if !pending.is_empty() {
        return Err(format!("{} results never left the pipeline", pending.len()));
    }
    Ok(stats)
}

/// The stream runner's view of a float bundle pair in simulation (for [`crate::dut::run_checked`]).
pub fn bundle_float_rtl<S: BundleFloatIo>() -> TesterSim<S> {
    TesterSim::wrap(S::for_format(&S::format()))
}
