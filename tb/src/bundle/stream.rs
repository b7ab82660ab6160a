//! Testbench glue of the streaming results processor ([`rtl::bundle::stream::BundleStream`]): a rust-hdl
//! driver with optional VCD, a seeded open-loop stimulus, a checker that runs the clock-by-clock model
//! (`golden::bundle::stream::StreamModel`) beside the block and compares every output in every clock,
//! and the same over the Verilated Verilog (with the rust-hdl simulation in lockstep for a prefix).
//!
//! The stimulus (see [`StreamStim`]) loads ray sets (BundleGen cases' rays quantised as tiny bundles,
//! padded up to 16, now and then raw codes) into the four sets one ray a clock, while jobs against the
//! loaded sets start in bursts (a start every clock, which the block takes only when `ready`) and
//! quieter phases; garbage rays land at random addresses now and then, and, with resets on, `rst` comes
//! at random. The model predicts the block exactly for any inputs, so writes that break the ray-store
//! contract are still checked bit for bit; the functional meaning of a job (its mask is `split_fix` of
//! its rays) is checked where the contract holds, by [`check_results`].

use crate::bundle::pair_fix::{quantised_case, raw_bundle};
use crate::bundle::pair_float::{quantised, raw_float_bundle, ray_bundle};
use crate::campaign::{campaign_bounds, campaign_map};
use crate::rtl_sim::Clocked;
use crate::verilator::Harness;
use crate::xsim::clocked_xsim;
use golden::bundle::edge::BoxPair;
use golden::bundle::edge::Bundle;
use golden::bundle::fix::{bundle_dir_exp, BundleFixFormat};
use golden::bundle::float::quantize_bundle_at;
use golden::bundle::gen::BundleGen;
use golden::bundle::rebound::{quantize_scaled, ScaledBundle, J_BITS};
use golden::bundle::stream::{
    PairDatapath, StreamInOf, StreamJob, StreamModel, StreamOutOf, STREAM_RAYS, STREAM_SETS,
};
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::bundle::stream::BundleStreamIo;
use std::collections::VecDeque;
use std::path::Path;

/// A case for the processor: the bundle, its box pair and its rays, each quantised as a tiny bundle (as
/// the ray store holds it, [`PairDatapath::Ray`]).
pub type StreamCase<P> = (
    <P as PairDatapath>::Bundle,
    BoxPair<<P as PairDatapath>::Box>,
    Vec<<P as PairDatapath>::Ray>,
);

/// What the stimulus needs of a pair datapath: cases and raw rays in its format.
pub trait StreamCases: PairDatapath + Copy + std::fmt::Debug + Send + Sync + 'static {
    /// The format's name, for messages.
    fn label(&self) -> String;
    /// Whether the processor re-bounds (reports `StreamOut::rebound`).
    const REBOUNDS: bool;
    /// A case from `gen` (its next case, or with `one_ray` a single ray on a grid) in the format, or
    /// `None` when the bundle, the box or a ray does not fit it.
    fn case(&self, gen: &mut BundleGen, one_ray: bool) -> Option<StreamCase<Self>>;
    /// A ray of raw codes of the format (a pattern no quantisation yields).
    fn raw_ray(&self, rng: &mut Pcg64) -> Self::Ray;
}

impl StreamCases for BundleFixFormat {
    const REBOUNDS: bool = true;
    fn label(&self) -> String {
        self.name()
    }
    fn case(&self, gen: &mut BundleGen, one_ray: bool) -> Option<StreamCase<Self>> {
        let map = campaign_map(self.base);
        let c = if one_ray {
            gen.grid_one_ray(&map)
        } else {
            gen.next_case()
        };
        let (b, p, _) = quantised_case(self, &map, &c)?;
        let rays = c
            .rays
            .iter()
            .map(|r| quantize_scaled(self, &map, &Bundle::of_ray(r).ok()?).ok())
            .collect::<Option<Vec<_>>>()?;
        Some((b, p, rays))
    }
    /// Raw codes, with a direction exponent near 0 (rays of one scale and neighbouring ones) half the
    /// time, else anywhere in its range (shifts up to and past every code width).
    fn raw_ray(&self, rng: &mut Pcg64) -> Self::Ray {
        let half = 1i32 << (J_BITS - 1);
        ScaledBundle {
            q: *raw_bundle(self, rng).0.sides().0,
            j: if rng.gen() {
                rng.gen_range(-3..=3)
            } else {
                rng.gen_range(-half..half)
            },
        }
    }
}

impl StreamCases for FloatFormat {
    const REBOUNDS: bool = true;
    fn label(&self) -> String {
        self.name()
    }
    /// One-ray cases are on the b8 campaign grid (integer coordinates, exact in every float format).
    /// Most cases store their rays on the bundle's direction scale (what float re-bounding needs to be
    /// tight), the others (those whose `t_hi` code is a multiple of 3, never an infinite one: about two
    /// in nine) each ray on its own.
    fn case(&self, gen: &mut BundleGen, one_ray: bool) -> Option<StreamCase<Self>> {
        let c = if one_ray {
            gen.grid_one_ray(&campaign_map(FixFormat::b8()))
        } else {
            gen.next_case()
        };
        let (b, p) = quantised(self, &c.bundle, &c.bounds)?;
        let j = bundle_dir_exp(&c.bundle);
        // Chosen from the case itself, so that the stimulus stays a function of the generator's seed.
        let own = c.bundle.t_hi.to_bits() % 3 == 0;
        let rays = c
            .rays
            .iter()
            .map(|r| {
                if own {
                    ray_bundle(self, r).ok()
                } else {
                    quantize_bundle_at(self, &Bundle::of_ray(r).ok()?, j).ok()
                }
            })
            .collect::<Option<Vec<_>>>()?;
        Some((b, p, rays))
    }
    fn raw_ray(&self, rng: &mut Pcg64) -> Self::Bundle {
        raw_float_bundle(self, rng)
    }
}

/// Draws `gen`'s cases until one fits `dp` (a single grid ray when `one_ray`).
fn fitting_case<P: StreamCases>(dp: &P, gen: &mut BundleGen, one_ray: bool) -> StreamCase<P> {
    loop {
        if let Some(c) = dp.case(gen, one_ray) {
            return c;
        }
    }
}

/// The model of processor `S` over `dp`.
pub fn stream_model<S: BundleStreamIo>(dp: &S::Dp) -> StreamModel<S::Dp> {
    StreamModel::new(*dp, S::PAIR_LATENCY)
}

/// A streaming processor in simulation ([`Clocked`]).
pub struct StreamRtl<S: BundleStreamIo>(Clocked<S>);

impl<S: BundleStreamIo> StreamRtl<S> {
    /// The block for `dp`, connected.
    pub fn new(dp: &S::Dp) -> Self {
        StreamRtl(Clocked::new(S::for_format(dp)))
    }

    /// Starts writing every signal of the block to a VCD file at `path`.
    pub fn vcd_to(self, path: &Path) -> std::io::Result<Self> {
        Ok(StreamRtl(self.0.vcd_to(path)?))
    }

    /// The outputs in this clock.
    pub fn outputs(&self) -> StreamOutOf<S::Dp> {
        self.0.uut.outputs()
    }

    /// One clock: drive the inputs, clock, and return the outputs of the next clock.
    pub fn step(&mut self, input: &StreamInOf<S::Dp>) -> StreamOutOf<S::Dp> {
        self.0.uut.drive(input);
        self.0.clock(S::set_clock);
        self.0.uut.outputs()
    }
}

/// A seeded open-loop stimulus (see the module doc), `clocks` clocks long, for a processor over `P`.
pub struct StreamStim<P: StreamCases> {
    dp: P,
    gen: BundleGen,
    rng: Pcg64,
    /// Per set: the bundle and box pair of the case loaded into it, and its ray count.
    sets: [(P::Bundle, BoxPair<P::Box>, usize); STREAM_SETS],
    pending: VecDeque<(u8, u8, P::Ray)>,
    clocks_left: u64,
    /// Start probability in this phase, in 1/16, and the clocks left in the phase.
    phase: (u32, u32),
    tag: u8,
    resets: bool,
}

impl<P: StreamCases> StreamStim<P> {
    pub fn new(dp: P, seed: u64, clocks: u64) -> Self {
        let (lo, hi) = campaign_bounds();
        StreamStim {
            dp,
            gen: BundleGen::new(seed, lo, hi, 0.6),
            rng: Pcg64::seed_from_u64(seed ^ 0x5eed_57ea),
            sets: [(P::Bundle::default(), BoxPair::default(), 0); STREAM_SETS],
            pending: VecDeque::new(),
            clocks_left: clocks,
            phase: (16, 0),
            tag: 0,
            resets: false,
        }
    }

    /// The same with `rst` high in one clock in 400, at random.
    pub fn with_resets(mut self) -> Self {
        self.resets = true;
        self
    }

    fn draw_case(&mut self) -> StreamCase<P> {
        let one_ray = self.rng.gen_ratio(1, 8);
        fitting_case(&self.dp, &mut self.gen, one_ray)
    }

    /// Queues a new ray set for set `s`: a case's rays, sometimes padded to 16, sometimes with raw
    /// codes among them.
    fn load_set(&mut self, s: u8) {
        let (b, p, mut rays) = self.draw_case();
        if self.rng.gen_ratio(1, 3) {
            while rays.len() < STREAM_RAYS {
                let more = self.draw_case().2;
                rays.extend(more);
            }
        }
        rays.truncate(STREAM_RAYS);
        if self.rng.gen_ratio(1, 10) {
            for r in rays.iter_mut() {
                if self.rng.gen_ratio(1, 3) {
                    *r = self.dp.raw_ray(&mut self.rng);
                }
            }
        }
        for (i, r) in rays.iter().enumerate() {
            self.pending.push_back((s, i as u8, *r));
        }
        self.sets[s as usize] = (b, p, rays.len());
    }

    fn job(&mut self) -> StreamJob<P::Bundle, P::Box> {
        let set = self.rng.gen_range(0..STREAM_SETS) as u8;
        let (bundle, mut boxes, n) = self.sets[set as usize];
        if self.rng.gen_ratio(1, 3) {
            boxes = self.draw_case().1;
        }
        let all = ((1u32 << n) - 1) as u16;
        let active = match self.rng.gen_range(0..16) {
            0 => 0,
            1..=5 => all,
            6 | 7 if n > 0 => 1 << self.rng.gen_range(0..n),
            _ => self.rng.gen::<u16>() & all,
        };
        self.tag = self.tag.wrapping_add(1);
        StreamJob {
            bundle,
            boxes,
            active,
            set,
            tag: self.tag,
        }
    }
}

impl<P: StreamCases> Iterator for StreamStim<P> {
    type Item = StreamInOf<P>;
    fn next(&mut self) -> Option<StreamInOf<P>> {
        if self.clocks_left == 0 {
            return None;
        }
        self.clocks_left -= 1;
        if self.phase.1 == 0 {
            let p = [16, 16, 12, 8, 3][self.rng.gen_range(0..5)];
            self.phase = (p, self.rng.gen_range(20..300));
        }
        self.phase.1 -= 1;
        if self.pending.is_empty() && self.rng.gen_ratio(1, 24) {
            let s = self.rng.gen_range(0..STREAM_SETS) as u8;
            self.load_set(s);
        }
        let mut input = StreamInOf::<P>::default();
        if !self.pending.is_empty() && self.rng.gen_ratio(3, 4) {
            input.write = self.pending.pop_front();
        } else if self.rng.gen_ratio(1, 32) {
            let r = self.dp.raw_ray(&mut self.rng);
            input.write = Some((
                self.rng.gen_range(0..STREAM_SETS) as u8,
                self.rng.gen_range(0..STREAM_RAYS) as u8,
                r,
            ));
        }
        if self.rng.gen_ratio(self.phase.0, 16) {
            input.start = Some(self.job());
        }
        input.reset = self.resets && self.rng.gen_ratio(1, 400);
        Some(input)
    }
}

/// What a run covered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StreamStats {
    pub clocks: u64,
    /// Jobs taken (start while ready, no reset).
    pub taken: u64,
    pub done: u64,
    pub all_hit: u64,
    pub all_miss: u64,
    pub split: u64,
    /// Split jobs of 16 active rays.
    pub full_splits: u64,
    /// Reports that overtook an earlier job still in flight.
    pub overtakes: u64,
    /// Clocks with `start` high and `ready` low.
    pub refused: u64,
    /// Clocks the pair's input was used.
    pub busy: u64,
    /// The split queue's largest occupancy.
    pub max_queued: u64,
    pub resets: u64,
    /// Reports with a re-bounded bundle.
    pub rebounds: u64,
}

/// The model beside a block: steps both with each input and compares outputs, counting coverage.
pub struct StreamChecker<P: PairDatapath> {
    model: StreamModel<P>,
    /// Tags of the jobs in flight, oldest first, with their active counts.
    in_flight: VecDeque<(u8, u32)>,
    pub stats: StreamStats,
}

impl<P: PairDatapath> StreamChecker<P> {
    /// The checker of processor `S` over `dp` (its model: [`stream_model`]).
    pub fn of<S: BundleStreamIo<Dp = P>>(dp: &P) -> Self {
        Self::with_model(stream_model::<S>(dp))
    }

    /// A checker with another model (to show that a wrong one is caught).
    pub fn with_model(model: StreamModel<P>) -> Self {
        StreamChecker {
            model,
            in_flight: VecDeque::new(),
            stats: StreamStats::default(),
        }
    }

    /// The model's outputs in this clock.
    pub fn expected(&self) -> StreamOutOf<P> {
        self.model.outputs()
    }

    /// One clock of `input`; `got` is the block's outputs after it. Errors name the clock and both.
    pub fn check(&mut self, input: &StreamInOf<P>, got: &StreamOutOf<P>) -> Result<(), String> {
        let s = &mut self.stats;
        let ready = self.model.ready();
        if let Some(j) = input.start.as_ref().filter(|_| !input.reset) {
            if ready {
                s.taken += 1;
                self.in_flight.push_back((j.tag, j.active.count_ones()));
            } else {
                s.refused += 1;
            }
        }
        self.model.step(input);
        let want = self.model.outputs();
        s.clocks += 1;
        s.busy = self.model.busy_clocks;
        s.max_queued = self.model.max_queued as u64;
        if input.reset {
            s.resets += 1;
            self.in_flight.clear();
        }
        if *got != want {
            return Err(format!(
                "clock {}: got {got:?}\n  model {want:?}\n  input {input:?}",
                s.clocks
            ));
        }
        if want.done {
            s.done += 1;
            let k = self
                .in_flight
                .iter()
                .position(|&(t, _)| t == want.tag)
                .ok_or_else(|| format!("clock {}: done with an unknown tag", s.clocks))?;
            s.overtakes += (k > 0) as u64;
            let (_, n) = self.in_flight.remove(k).expect("found");
            s.rebounds += want.rebound.is_some() as u64;
            if want.all_hit {
                s.all_hit += 1;
            } else if want.all_miss {
                s.all_miss += 1;
            } else {
                s.split += 1;
                s.full_splits += (n == STREAM_RAYS as u32) as u64;
            }
        }
        Ok(())
    }
}

/// Runs `stim` through the rust-hdl simulation with the checker's model beside it; every clock compared.
pub fn run_stream<S: BundleStreamIo>(
    mut ck: StreamChecker<S::Dp>,
    dut: &mut StreamRtl<S>,
    stim: impl IntoIterator<Item = StreamInOf<S::Dp>>,
) -> Result<StreamStats, String> {
    for input in stim {
        let got = dut.step(&input);
        ck.check(&input, &got)?;
    }
    Ok(ck.stats)
}

/// Streams `stim` through the Verilator `harness`, the model beside it (every clock compared), and for
/// the first `lockstep` clocks the rust-hdl simulation too.
pub fn stream_xsim<S: BundleStreamIo, It>(
    dp: S::Dp,
    harness: &Harness,
    stim: It,
    lockstep: u64,
) -> Result<StreamStats, String>
where
    It: Iterator<Item = StreamInOf<S::Dp>> + Send + 'static,
{
    let mut rtl = (lockstep > 0).then(|| StreamRtl::<S>::new(&dp));
    let mut ck = StreamChecker::of::<S>(&dp);
    clocked_xsim(
        harness,
        stim,
        move |port, input| {
            S::in_word(&dp, port, input).ok_or_else(|| format!("unknown input port {port}"))
        },
        |word| {
            S::decode_out(&dp, word).ok_or_else(|| {
                "an output port of the processor is missing from the harness".to_string()
            })
        },
        |_, input, got| ck.check(input, got),
        lockstep,
        |input| rtl.as_mut().expect("built for lockstep").step(input),
    )?;
    Ok(ck.stats)
}

/// One job of a program for [`stream_shrinking`], in the terms proptest shrinks: smaller numbers and
/// `None` are simpler jobs.
#[derive(Clone, Debug)]
pub struct StreamStep {
    /// Seed of the job's BundleGen case: its bundle and box pair are the job's, its rays the set loaded.
    pub case: u64,
    /// The job's ray set.
    pub set: u8,
    /// Load this many rays (one less than the value) of the case into the set first, one a clock.
    /// `None`: use what the set holds.
    pub load: Option<u8>,
    pub active: u16,
    /// Clocks `start` is held high (1 + value): a start while not `ready` is refused, and one held
    /// while `ready` is taken again.
    pub hold: u8,
    /// Idle clocks after it (0: the next job's start follows at once).
    pub gap: u8,
}

/// Programs of 1 to 10 jobs.
pub fn stream_program() -> impl proptest::strategy::Strategy<Value = Vec<StreamStep>> {
    use proptest::prelude::*;
    let step = (
        any::<u64>(),
        0..STREAM_SETS as u8,
        proptest::option::of(0..STREAM_RAYS as u8),
        prop_oneof![3 => any::<u16>(), 1 => Just(u16::MAX), 1 => (0..16u32).prop_map(|b| 1u16 << b)],
        0..3u8,
        0..4u8,
    )
        .prop_map(|(case, set, load, active, hold, gap)| StreamStep {
            case,
            set,
            load,
            active,
            hold,
            gap,
        });
    proptest::collection::vec(step, 1..=10)
}

/// The clocks of `program`, then enough idle clocks for every job to report.
pub fn plan_stream<P: StreamCases>(dp: &P, program: &[StreamStep]) -> Vec<StreamInOf<P>> {
    let (lo, hi) = campaign_bounds();
    let mut clocks = vec![];
    for (k, step) in program.iter().enumerate() {
        let mut gen = BundleGen::new(step.case, lo, hi, 0.6);
        let mut case = || fitting_case(dp, &mut gen, step.case % 8 == 0);
        let (bundle, boxes, mut rays) = case();
        if let Some(n) = step.load {
            let n = n as usize + 1;
            while rays.len() < n {
                rays.extend(case().2);
            }
            for (i, r) in rays.iter().take(n).enumerate() {
                clocks.push(StreamInOf::<P> {
                    write: Some((step.set, i as u8, *r)),
                    ..Default::default()
                });
            }
        }
        let job = StreamJob {
            bundle,
            boxes,
            active: step.active,
            set: step.set,
            tag: k as u8,
        };
        for _ in 0..=step.hold {
            clocks.push(StreamInOf::<P> {
                start: Some(job),
                ..Default::default()
            });
        }
        clocks.extend((0..step.gap).map(|_| StreamInOf::<P>::default()));
    }
    clocks.extend((0..120).map(|_| StreamInOf::<P>::default()));
    clocks
}

/// proptest with shrinking for the streaming processor `S` ([`crate::prop::shrinking_check`]): `cases`
/// programs ([`stream_program`]), each on a fresh block, checked clock by clock against `model()`; a
/// failing program is shrunk, replayed with a VCD, and reported. Returns what the programs covered.
pub fn stream_shrinking<S: BundleStreamIo>(
    name: &str,
    dp: S::Dp,
    cases: u32,
    model: impl Fn() -> StreamModel<S::Dp>,
) -> StreamStats
where
    S::Dp: StreamCases,
{
    let mut total = StreamStats::default();
    crate::prop::shrinking_check(
        name,
        cases,
        stream_program(),
        |program| {
            let s = run_stream(
                StreamChecker::with_model(model()),
                &mut StreamRtl::<S>::new(&dp),
                plan_stream(&dp, program),
            )?;
            total.taken += s.taken;
            total.done += s.done;
            total.split += s.split;
            total.all_hit += s.all_hit;
            total.all_miss += s.all_miss;
            total.full_splits += s.full_splits;
            total.overtakes += s.overtakes;
            total.refused += s.refused;
            total.clocks += s.clocks;
            total.rebounds += s.rebounds;
            Ok(())
        },
        |program, path| {
            let mut d = StreamRtl::<S>::new(&dp).vcd_to(path).expect("VCD");
            let _ = run_stream(
                StreamChecker::with_model(model()),
                &mut d,
                plan_stream(&dp, program),
            );
        },
        |program| format!("job program {program:?}"),
    );
    total
}
