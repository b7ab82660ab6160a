//! Testbench glue of the fixed-point bundle pair ([`rtl::bundle::pair_fix::BundleFix`]): the model as the
//! testbench sees it, vector streams (BundleGen bundles, on-grid single rays, two-ray inputs of on-grid
//! and off-grid quantised rays, and raw codes, with bubbles), port encoding, and the cross-simulation
//! loop that checks Verilator against the rust-hdl simulation and the model.
//!
//! The slab testers' loop ([`crate::slab::ports::xsim`]) is written around `hit`, `t_entry`, `t_exit`; this
//! one compares whole output records instead (every output port of a valid cycle, `valid_out` of every
//! cycle), so it serves any block whose model gives its output ports' values.

use crate::campaign::{campaign_bounds, campaign_map, raw_fix_vector};
use crate::dut::PipelinedDut;
use crate::rtl_sim::TesterSim;
use crate::slab::ports::{replay_vcd, XsimStats, XSIM_VCD_WINDOW};
use crate::verilator::Harness;
use golden::bundle::edge::{BoxPair, Bundle};
use golden::bundle::fix::{quantize_box_pair, quantize_bundle, BundleFixFormat, FixBundle};
use golden::bundle::gen::{BundleCase, BundleGen};
use golden::format::fixed::{FixBox, GridMap};
use golden::geom::Ray;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::bundle::pair_fix::{BundleFixIo, PairInput};
use rtl::slab::fix::code;
use std::collections::VecDeque;
use std::sync::mpsc::sync_channel;

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

/// The value of input port `port` (a Verilog name such as `d_lo_1`) for one cycle (zero for a bubble's
/// data).
pub fn bundle_in_word(
    bf: &BundleFixFormat,
    port: &str,
    tag: u16,
    v: &Option<BundleVec>,
) -> Result<u64, String> {
    let (base, idx) = rtl::verilog::split_port(port);
    let idx = idx.unwrap_or(0);
    let Some((input, p)) = v else {
        return Ok(0);
    };
    let (b, r) = input.sides();
    let (g, d, t) = (
        bf.base.g as usize,
        bf.dir_bits() as usize,
        bf.base.t as usize,
    );
    Ok(match base {
        "valid_in" => 1,
        "rst" => 0,
        "tag_in" => tag as u64,
        "o_lo" => code(b.o_lo[idx], g),
        "o_hi" => code(b.o_hi[idx], g),
        "d_lo" => code(b.d_lo[idx], d),
        "d_hi" => code(b.d_hi[idx], d),
        "t_lo" => code(b.t_lo, t),
        "t_hi" => code(b.t_hi, t),
        "two_rays" => matches!(input, PairInput::TwoRays(..)) as u64,
        "r_o_lo" => code(r.o_lo[idx], g),
        "r_o_hi" => code(r.o_hi[idx], g),
        "r_d_lo" => code(r.d_lo[idx], d),
        "r_d_hi" => code(r.d_hi[idx], d),
        "r_t" => code(r.t_hi, t),
        "in_lo" => code(p.inner.lo[idx], g),
        "in_hi" => code(p.inner.hi[idx], g),
        "out_lo" => code(p.outer.lo[idx], g),
        "out_hi" => code(p.outer.hi[idx], g),
        _ => return Err(format!("unknown input port {port}")),
    })
}

/// The output record the model predicts for a cycle: `valid_out`, and for a valid cycle every port.
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

/// Streams `vectors` through the Verilator `harness` of a [`BundleFixIo`] block and checks every output
/// record against the model (results, tags, latency, and `valid_out` low when nothing is due) and, for
/// the first `lockstep_cycles` cycles, against the rust-hdl simulation of the block made by `make` (every
/// port of a valid cycle, `valid_out` always). On a failure the last cycles are replayed into a VCD.
/// `XsimStats::hits` counts the tests with a decisive answer (all hit or all miss).
pub fn bundle_xsim<S: BundleFixIo, It>(
    bf: BundleFixFormat,
    make: impl Fn() -> S,
    harness: &Harness,
    vectors: It,
    lockstep_cycles: u64,
) -> Result<XsimStats, String>
where
    It: Iterator<Item = Option<BundleVec>> + Send + 'static,
{
    let ports: Vec<String> = harness.inputs.iter().map(|p| p.name.clone()).collect();
    let (tx, rx) = sync_channel::<(u16, Option<BundleVec>)>(1 << 16);
    let lat = S::LATENCY as u64;
    let mut tag = 0u16;
    let records = vectors
        .chain(std::iter::repeat_n(None, lat as usize + 1))
        .map(move |v| {
            let t = tag;
            tag = tag.wrapping_add(v.is_some() as u16);
            let rec = ports
                .iter()
                .map(|p| bundle_in_word(&bf, p, t, &v).expect("known port"))
                .collect();
            tx.send((t, v)).expect("consumer alive");
            rec
        });
    let iv = harness
        .output_index("valid_out")
        .ok_or("no valid_out port")?;
    let mut rtl = (lockstep_cycles > 0).then(|| TesterSim::wrap(make()));
    let mut pending: VecDeque<(u64, u16, BundleVec)> = VecDeque::new();
    let mut recent: VecDeque<(u16, Option<BundleVec>)> = VecDeque::new();
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
            let due = pending
                .front()
                .filter(|p| p.0 + lat == cycle + 1)
                .map(|p| (p.1, bundle_model(&bf, &p.2)));
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
                        pending.front().filter(|p| p.0 + lat == cycle + 1)
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
            let name = format!("xsim_bundle_fix_{}_cycle{}.vcd", bf.name(), last_cycle + 1);
            let path = crate::out_dir().join("vcd").join(name);
            match replay_vcd(&make, &recent, &path) {
                Ok(()) => format!("{e}\n  waveform of the last {} cycles (rust-hdl): {}", recent.len(), path.display()),
                Err(w) => format!("{e}\n  (no waveform: {w})"),
            }
        })?;
    stats.cycles = cycles;
    if !pending.is_empty() {
        return Err(format!("{} results never left the pipeline", pending.len()));
    }
    Ok(stats)
}

/// The stream runner's view of a bundle pair in simulation (for [`crate::dut::run_checked`]).
pub fn bundle_rtl<S: BundleFixIo>(bf: &BundleFixFormat) -> TesterSim<S> {
    TesterSim::wrap(S::for_format(bf))
}
