//! Testbench glue of the bundle results processor ([`rtl::bundle::split::BundleSplit`]): a rust-hdl driver
//! with optional VCD, a seeded clock-by-clock stimulus with the outputs the model predicts for every
//! clock, a checker, Verilator port encoding and a cross-simulation loop.
//!
//! The stimulus is job-level and open-loop: it plans each job from the model (`split_fix` and
//! `rtl::bundle::split::split_clocks`), so it knows in which clock `ready` must be low and in which clock
//! `done` must pulse; the same records then drive the rust-hdl simulation and the Verilated Verilog.
//! A job loads a ray set (BundleGen case rays quantised as tiny bundles, sometimes padded to 16 with rays
//! of other cases, sometimes with raw codes) one ray a clock in random order with idle clocks between, or
//! reuses the loaded set back to back (the next start in the clock of `done`) with a new box and active
//! mask. While a job runs, the stimulus writes garbage to ray addresses outside the set and asserts
//! `start` with a junk job, both of which the block must ignore.

use crate::bundle::pair_fix::{quantised_case, raw_bundle};
use crate::campaign::{campaign_bounds, campaign_map};
use crate::rtl_sim::Clocked;
use crate::verilator::Harness;
use crate::xsim::clocked_xsim;
use golden::bundle::fix::{BundleFixFormat, FixBundle};
use golden::bundle::gen::BundleGen;
use golden::bundle::split::{split_fix, SplitResult};
use golden::format::fixed::GridMap;
use proptest::prelude::{any, Strategy};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::bundle::split::{split_clocks, BundleSplitIo, SplitIn, SplitJob, SplitOut, SPLIT_RAYS};
use std::collections::VecDeque;
use std::path::Path;

/// The ray store as the model sees it.
pub type RayStore = [FixBundle; SPLIT_RAYS];

/// A results processor in simulation ([`Clocked`]).
pub struct SplitRtl<S: BundleSplitIo>(Clocked<S>);

impl<S: BundleSplitIo> SplitRtl<S> {
    /// The block for `bf`, connected.
    pub fn new(bf: &BundleFixFormat) -> Self {
        SplitRtl(Clocked::new(S::for_format(bf)))
    }

    /// Starts writing every signal of the block to a VCD file at `path`.
    pub fn vcd_to(self, path: &Path) -> std::io::Result<Self> {
        Ok(SplitRtl(self.0.vcd_to(path)?))
    }

    /// One clock: drive the inputs of this cycle, clock, and return the outputs of the next cycle.
    pub fn step(&mut self, input: &SplitIn) -> SplitOut {
        self.0.uut.drive(input);
        self.0.clock(S::set_clock);
        self.0.uut.outputs()
    }
}

/// A job's report as the model predicts it, with what produced it.
#[derive(Clone, Debug)]
pub struct SplitDone {
    pub job: SplitJob,
    /// The ray store when the job started.
    pub store: Box<RayStore>,
    pub result: SplitResult,
    /// Clocks from start to done.
    pub clocks: u32,
    /// The job started in the clock its predecessor reported.
    pub back_to_back: bool,
}

/// The outputs the model predicts after one clock: `ready`, and the report when `done` pulses.
#[derive(Clone, Debug)]
pub struct SplitExpect {
    pub ready: bool,
    pub done: Option<SplitDone>,
}

/// The model of one job over the ray store: `golden::bundle::split::split_fix`.
pub fn split_model(bf: &BundleFixFormat, job: &SplitJob, store: &RayStore) -> SplitResult {
    split_fix(bf, &job.bundle, &job.boxes, store, job.active as u64)
}

/// A clock-by-clock stimulus under construction, with the outputs `model` predicts for every clock: ray
/// writes, idle clocks, and jobs, each followed by the clocks the block is busy with it. The plan keeps
/// the ray store as the model sees it (every write, also those while a job runs) and knows whether a
/// start comes in the clock of its predecessor's `done`.
pub struct SplitPlan<M> {
    bf: BundleFixFormat,
    model: M,
    store: RayStore,
    queue: VecDeque<(SplitIn, SplitExpect)>,
    /// The running job's report and its busy clocks still to come.
    running: Option<(SplitDone, u32)>,
    /// The last clock planned is a job's `done` clock.
    after_done: bool,
}

const IDLE: SplitExpect = SplitExpect {
    ready: true,
    done: None,
};

impl<M: Fn(&BundleFixFormat, &SplitJob, &RayStore) -> SplitResult> SplitPlan<M> {
    pub fn new(bf: BundleFixFormat, model: M) -> Self {
        SplitPlan {
            bf,
            model,
            store: [FixBundle::default(); SPLIT_RAYS],
            queue: VecDeque::new(),
            running: None,
            after_done: false,
        }
    }

    fn push(&mut self, input: SplitIn, exp: SplitExpect) {
        if let Some((a, r)) = input.write {
            self.store[a] = r;
        }
        self.after_done = exp.done.is_some();
        self.queue.push_back((input, exp));
    }

    fn idle_clock(&mut self, input: SplitIn) {
        assert!(self.running.is_none(), "a job is still running");
        self.push(input, IDLE);
    }

    /// `clocks` idle clocks.
    pub fn idle(&mut self, clocks: usize) {
        for _ in 0..clocks {
            self.idle_clock(SplitIn::default());
        }
    }

    /// One clock writing ray `r` to address `a`.
    pub fn write(&mut self, a: usize, r: FixBundle) {
        self.idle_clock(SplitIn {
            write: Some((a, r)),
            start: None,
            reset: false,
        });
    }

    /// A start clock of `job` (with `write`, which the job sees, in the same clock); returns the clocks
    /// from start to done, all of which but the start clock the caller plans with [`SplitPlan::busy`].
    pub fn start(&mut self, job: SplitJob, write: Option<(usize, FixBundle)>) -> u32 {
        assert!(self.running.is_none(), "a job is still running");
        if let Some((a, r)) = write {
            self.store[a] = r;
        }
        let result = (self.model)(&self.bf, &job, &self.store);
        let clocks = split_clocks(&result);
        let done = SplitDone {
            job,
            store: Box::new(self.store),
            result,
            clocks,
            back_to_back: self.after_done,
        };
        self.push(
            SplitIn {
                write,
                start: Some(job),
                reset: false,
            },
            SplitExpect {
                ready: false,
                done: None,
            },
        );
        self.running = Some((done, clocks - 1));
        clocks
    }

    /// One clock of the running job with `input` (writes outside the job's active rays, starts the
    /// block must ignore); the last one reports.
    pub fn busy(&mut self, input: SplitIn) {
        let (done, left) = self.running.take().expect("no job running");
        let exp = if left == 1 {
            SplitExpect {
                ready: true,
                done: Some(done),
            }
        } else {
            self.running = Some((done, left - 1));
            SplitExpect {
                ready: false,
                done: None,
            }
        };
        self.push(input, exp);
    }

    /// Starts `job` and plans its busy clocks, each with the input `noise` gives it.
    pub fn run_job(
        &mut self,
        job: SplitJob,
        write: Option<(usize, FixBundle)>,
        mut noise: impl FnMut() -> SplitIn,
    ) {
        for _ in 1..self.start(job, write) {
            let input = noise();
            self.busy(input);
        }
    }

    /// A reset clock with `input` (`rst` set high here; its write is taken, its start is not): the
    /// running job, if any, is dropped and never reports.
    pub fn reset(&mut self, mut input: SplitIn) {
        input.reset = true;
        self.running = None;
        self.push(input, IDLE);
    }

    /// Starts `job`, plans `busy` of its busy clocks (fewer than it needs) with the input `noise` gives
    /// each, then a reset clock with `noise`'s input, which drops the job: the reset comes at the latest
    /// in the clock that would have reported.
    pub fn run_job_reset(
        &mut self,
        job: SplitJob,
        write: Option<(usize, FixBundle)>,
        busy: u32,
        mut noise: impl FnMut() -> SplitIn,
    ) {
        let clocks = self.start(job, write);
        for _ in 0..busy.min(clocks - 2) {
            let input = noise();
            self.busy(input);
        }
        let input = noise();
        self.reset(input);
    }

    /// The next planned clock.
    pub fn pop(&mut self) -> Option<(SplitIn, SplitExpect)> {
        self.queue.pop_front()
    }

    /// Every planned clock.
    pub fn into_clocks(self) -> Vec<(SplitIn, SplitExpect)> {
        assert!(self.running.is_none(), "a job is still running");
        self.queue.into()
    }
}

/// The input of one busy clock with noise the block must ignore, drawn from `rng`: a quarter of the
/// clocks a raw ray written to an address at or above `n` (outside the loaded set, when there is
/// room), an eighth a start of a raw job.
pub fn busy_noise<R: Rng>(bf: &BundleFixFormat, n: usize, rng: &mut R) -> SplitIn {
    let mut input = SplitIn::default();
    if n < SPLIT_RAYS && rng.gen_ratio(1, 4) {
        let a = rng.gen_range(n..SPLIT_RAYS);
        input.write = Some((a, *raw_bundle(bf, rng).0.sides().0));
    }
    if rng.gen_ratio(1, 8) {
        let (p, boxes) = raw_bundle(bf, rng);
        input.start = Some(SplitJob {
            bundle: *p.sides().0,
            boxes,
            active: rng.gen(),
        });
    }
    input
}

/// A seeded clock-by-clock stimulus of `jobs` jobs with the outputs `model` predicts (see the module
/// doc). `quiet` leaves out the junk starts and garbage writes (for waveforms that count `start`).
pub struct SplitStim<M> {
    bf: BundleFixFormat,
    map: GridMap,
    gen: BundleGen,
    rng: Pcg64,
    /// Rays of the loaded set, and its bundle.
    n: usize,
    bundle: FixBundle,
    jobs_left: u64,
    plan: SplitPlan<M>,
    quiet: bool,
    /// One job in six cut short by a reset ([`SplitStim::with_resets`]).
    resets: bool,
}

impl<M: Fn(&BundleFixFormat, &SplitJob, &RayStore) -> SplitResult> SplitStim<M> {
    pub fn new(bf: BundleFixFormat, seed: u64, jobs: u64, quiet: bool, model: M) -> Self {
        let (lo, hi) = campaign_bounds();
        SplitStim {
            bf,
            map: campaign_map(bf.base),
            gen: BundleGen::new(seed, lo, hi, 0.6),
            rng: Pcg64::seed_from_u64(seed ^ 0x9e37_79b9),
            n: 0,
            bundle: FixBundle::default(),
            jobs_left: jobs,
            plan: SplitPlan::new(bf, model),
            quiet,
            resets: false,
        }
    }

    /// The same stimulus with one job in six dropped by a reset in a random clock of it (its start
    /// clock excluded, its report clock included), and now and then a reset between jobs.
    pub fn with_resets(mut self) -> Self {
        self.resets = true;
        self
    }

    /// A quantised case: bundle, box pair, rays (1 to 16).
    fn draw_case(
        &mut self,
    ) -> (
        FixBundle,
        golden::bundle::edge::BoxPair<golden::format::fixed::FixBox>,
        Vec<FixBundle>,
    ) {
        loop {
            let c = if self.rng.gen_ratio(1, 8) {
                self.gen.grid_one_ray(&self.map)
            } else {
                self.gen.next_case()
            };
            if let Some(q) = quantised_case(&self.bf, &self.map, &c) {
                return q;
            }
        }
    }

    /// A new ray set: a case's rays, sometimes padded to 16 with rays of other cases, sometimes with
    /// some rays replaced by raw codes.
    fn draw_set(
        &mut self,
    ) -> (
        FixBundle,
        golden::bundle::edge::BoxPair<golden::format::fixed::FixBox>,
        Vec<FixBundle>,
    ) {
        let (b, p, mut rays) = self.draw_case();
        if self.rng.gen_ratio(1, 5) {
            while rays.len() < SPLIT_RAYS {
                let more = self.draw_case().2;
                rays.extend(more);
            }
        }
        rays.truncate(SPLIT_RAYS);
        if self.rng.gen_ratio(1, 10) {
            for r in rays.iter_mut() {
                if self.rng.gen_ratio(1, 3) {
                    *r = *raw_bundle(&self.bf, &mut self.rng).0.sides().0;
                }
            }
        }
        (b, p, rays)
    }

    fn active_mask(&mut self) -> u16 {
        let all = ((1u32 << self.n) - 1) as u16;
        match self.rng.gen_range(0..16) {
            0 => 0,
            1..=4 => all,
            5 | 6 => 1 << self.rng.gen_range(0..self.n),
            _ => self.rng.gen::<u16>() & all,
        }
    }

    fn plan_job(&mut self) {
        let reuse = self.n > 0 && self.rng.gen_ratio(1, 3);
        let boxes;
        // The last ray written in the start clock itself, sometimes (the contract allows it).
        let mut held = None;
        if reuse {
            boxes = self.draw_case().1;
        } else {
            let (b, p, rays) = self.draw_set();
            let mut order: Vec<usize> = (0..rays.len()).collect();
            order.shuffle(&mut self.rng);
            let hold = self.rng.gen_ratio(1, 4);
            for (k, &a) in order.iter().enumerate() {
                if self.rng.gen_ratio(1, 4) {
                    let gap = self.rng.gen_range(1..=3);
                    self.plan.idle(gap);
                }
                if hold && k == order.len() - 1 {
                    held = Some((a, rays[a]));
                } else {
                    self.plan.write(a, rays[a]);
                }
            }
            self.n = rays.len();
            self.bundle = b;
            boxes = p;
        }
        if self.rng.gen_ratio(1, if reuse { 3 } else { 2 }) {
            if let Some((a, r)) = held.take() {
                self.plan.write(a, r);
            }
            let gap = self.rng.gen_range(1..=3);
            self.plan.idle(gap);
        }
        let job = SplitJob {
            bundle: self.bundle,
            boxes,
            active: self.active_mask(),
        };
        let cut = self.resets && self.rng.gen_ratio(1, 6);
        let busy = self.rng.gen_range(0..24);
        if self.resets && self.rng.gen_ratio(1, 12) {
            self.plan.reset(SplitIn::default());
        }
        let (bf, n, quiet, rng) = (&self.bf, self.n, self.quiet, &mut self.rng);
        let noise = || {
            if quiet {
                SplitIn::default()
            } else {
                busy_noise(bf, n, rng)
            }
        };
        if cut {
            self.plan.run_job_reset(job, held, busy, noise);
        } else {
            self.plan.run_job(job, held, noise);
        }
    }
}

impl<M: Fn(&BundleFixFormat, &SplitJob, &RayStore) -> SplitResult> Iterator for SplitStim<M> {
    type Item = (SplitIn, SplitExpect);
    fn next(&mut self) -> Option<Self::Item> {
        if let Some(c) = self.plan.pop() {
            return Some(c);
        }
        if self.jobs_left == 0 {
            return None;
        }
        self.jobs_left -= 1;
        self.plan_job();
        self.plan.pop()
    }
}

/// What a run covered: jobs by outcome, rays tested one by one, odd ray counts, back-to-back starts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SplitStats {
    pub cycles: u64,
    pub jobs: u64,
    pub all_hit: u64,
    pub all_miss: u64,
    pub split: u64,
    pub split_rays: u64,
    pub odd_splits: u64,
    pub full_splits: u64,
    pub back_to_back: u64,
    /// Clocks with `rst` high.
    pub resets: u64,
}

impl SplitStats {
    /// Adds the counts of `o`.
    pub fn add(&mut self, o: &SplitStats) {
        self.cycles += o.cycles;
        self.jobs += o.jobs;
        self.all_hit += o.all_hit;
        self.all_miss += o.all_miss;
        self.split += o.split;
        self.split_rays += o.split_rays;
        self.odd_splits += o.odd_splits;
        self.full_splits += o.full_splits;
        self.back_to_back += o.back_to_back;
        self.resets += o.resets;
    }

    fn count(&mut self, d: &SplitDone) {
        self.jobs += 1;
        let r = &d.result;
        if r.all_hit {
            self.all_hit += 1;
        } else if r.all_miss {
            self.all_miss += 1;
        } else {
            self.split += 1;
            let n = d.job.active.count_ones() as u64;
            self.split_rays += n;
            self.odd_splits += n % 2;
            self.full_splits += (n == SPLIT_RAYS as u64) as u64;
        }
        self.back_to_back += d.back_to_back as u64;
    }
}

/// Compares one clock's outputs with the expectation: `ready` and `done` always, the report with `done`.
fn check_out(cycle: u64, got: &SplitOut, exp: &SplitExpect) -> Result<(), String> {
    let ok = got.ready == exp.ready
        && got.done == exp.done.is_some()
        && exp
            .done
            .as_ref()
            .is_none_or(|d| got.result() == d.result && got.clocks as u32 == d.clocks);
    if ok {
        return Ok(());
    }
    Err(format!(
        "cycle {}: got {got:?}\n  expected ready {} done {}\n{}",
        cycle + 1,
        exp.ready,
        exp.done.is_some(),
        match &exp.done {
            Some(d) => format!(
                "  expected {:?} in {} clocks\n  job {:?}\n  active rays {:?}",
                d.result,
                d.clocks,
                d.job,
                (0..SPLIT_RAYS)
                    .filter(|i| d.job.active >> i & 1 == 1)
                    .map(|i| (i, d.store[i]))
                    .collect::<Vec<_>>()
            ),
            None => "  (no report due)".into(),
        }
    ))
}

/// Runs `stim` through the rust-hdl simulation and checks every clock.
pub fn run_split<S: BundleSplitIo>(
    dut: &mut SplitRtl<S>,
    stim: impl IntoIterator<Item = (SplitIn, SplitExpect)>,
) -> Result<SplitStats, String> {
    let mut stats = SplitStats::default();
    for (cycle, (input, exp)) in stim.into_iter().enumerate() {
        let got = dut.step(&input);
        check_out(cycle as u64, &got, &exp)?;
        if let Some(d) = &exp.done {
            stats.count(d);
        }
        stats.resets += input.reset as u64;
        stats.cycles += 1;
    }
    Ok(stats)
}

/// The value of input port `port` (a Verilog name such as `ray_d_lo_1`) in one clock.
pub fn split_in_word(bf: &BundleFixFormat, port: &str, input: &SplitIn) -> Result<u64, String> {
    let (base, idx) = rtl::verilog::split_port(port);
    let (addr, r) = input.write.unwrap_or_default();
    let j = input.start.unwrap_or_default();
    Ok(match base {
        "ray_we" => input.write.is_some() as u64,
        "ray_addr" => addr as u64,
        "start" => input.start.is_some() as u64,
        "rst" => input.reset as u64,
        "active" => j.active as u64,
        _ => rtl::bundle::ray_store::ray_job_word(
            bf,
            base,
            idx.unwrap_or(0),
            &r,
            &j.bundle,
            &j.boxes,
        )
        .ok_or_else(|| format!("unknown input port {port}"))?,
    })
}

/// Streams `stim` through the Verilator `harness` and checks every clock against the model's
/// expectation, and, for the first `lockstep_cycles` clocks, every output port against the rust-hdl
/// simulation of the block driven with the same inputs.
pub fn split_xsim<S: BundleSplitIo, It>(
    bf: BundleFixFormat,
    harness: &Harness,
    stim: It,
    lockstep_cycles: u64,
) -> Result<SplitStats, String>
where
    It: Iterator<Item = (SplitIn, SplitExpect)> + Send + 'static,
{
    let mut rtl = (lockstep_cycles > 0).then(|| SplitRtl::<S>::new(&bf));
    let mut stats = SplitStats::default();
    let cycles = clocked_xsim(
        harness,
        stim,
        move |port, (input, _): &(SplitIn, SplitExpect)| split_in_word(&bf, port, input),
        |word| {
            let w = |name: &str| word(name).ok_or_else(|| format!("no output port {name}"));
            Ok(SplitOut {
                ready: w("ready")? != 0,
                done: w("done")? != 0,
                all_hit: w("all_hit")? != 0,
                all_miss: w("all_miss")? != 0,
                split: w("split")? != 0,
                mask: w("mask")? as u16,
                cycles: w("cycles")? as u8,
                clocks: w("clocks")? as u8,
            })
        },
        |cycle, (input, exp), got| {
            check_out(cycle, got, exp)?;
            if let Some(d) = &exp.done {
                stats.count(d);
            }
            stats.resets += input.reset as u64;
            Ok(())
        },
        lockstep_cycles,
        |(input, _)| rtl.as_mut().expect("built for lockstep").step(input),
    )?;
    stats.cycles = cycles;
    Ok(stats)
}

/// A directed stimulus: `rays` written to addresses 0.. one a clock, then `jobs` back to back (each
/// started in the clock its predecessor reports), with the outputs `model` predicts.
pub fn directed(
    bf: &BundleFixFormat,
    rays: &[FixBundle],
    jobs: &[SplitJob],
    model: impl Fn(&BundleFixFormat, &SplitJob, &RayStore) -> SplitResult,
) -> Vec<(SplitIn, SplitExpect)> {
    let mut plan = SplitPlan::new(*bf, model);
    for (a, r) in rays.iter().enumerate().take(SPLIT_RAYS) {
        plan.write(a, *r);
    }
    for job in jobs {
        plan.run_job(*job, None, SplitIn::default);
    }
    plan.into_clocks()
}

/// One job of a program for [`split_shrinking`], in the terms proptest shrinks: smaller numbers and
/// `None` are simpler jobs.
#[derive(Clone, Debug)]
pub struct SplitStep {
    /// Seed of the job's BundleGen case: its bundle and box pair are the job's, its rays the set loaded.
    pub case: u64,
    /// Load a new set of this many rays (one less than the value, 1 to 16) before the job, written to
    /// addresses 0.. one a clock: the case's rays, padded with rays of the cases that follow it. `None`:
    /// reuse the loaded set.
    pub load: Option<u8>,
    /// Idle clocks before the start (0 starts in the clock of the previous job's `done`).
    pub gap: u8,
    /// Active rays (this mask within the loaded set).
    pub active: u16,
    /// Noise while the job runs ([`busy_noise`]), drawn from this seed.
    pub noise: Option<u64>,
}

/// Programs of 1 to 4 jobs.
pub fn split_program() -> impl Strategy<Value = Vec<SplitStep>> {
    let step = (
        any::<u64>(),
        proptest::option::of(0..SPLIT_RAYS as u8),
        0..3u8,
        // Any mask, all rays (a full set of 16 is a split of 8 pair clocks), one ray.
        proptest::prop_oneof![
            3 => any::<u16>(),
            1 => proptest::strategy::Just(u16::MAX),
            1 => (0..16u32).prop_map(|b| 1u16 << b),
        ],
        proptest::option::of(any::<u64>()),
    )
        .prop_map(|(case, load, gap, active, noise)| SplitStep {
            case,
            load,
            gap,
            active,
            noise,
        });
    proptest::collection::vec(step, 1..=4)
}

/// The clocks of `program` with the outputs `model` predicts.
pub fn plan_program(
    bf: &BundleFixFormat,
    program: &[SplitStep],
    model: impl Fn(&BundleFixFormat, &SplitJob, &RayStore) -> SplitResult,
) -> Vec<(SplitIn, SplitExpect)> {
    let map = campaign_map(bf.base);
    let (lo, hi) = campaign_bounds();
    let mut plan = SplitPlan::new(*bf, model);
    let mut n = 0;
    for step in program {
        let mut gen = BundleGen::new(step.case, lo, hi, 0.6);
        let mut case = || loop {
            let c = if step.case % 8 == 0 {
                gen.grid_one_ray(&map)
            } else {
                gen.next_case()
            };
            if let Some(q) = quantised_case(bf, &map, &c) {
                return q;
            }
        };
        let (bundle, boxes, mut rays) = case();
        if let Some(k) = step.load {
            let k = k as usize + 1;
            while rays.len() < k {
                rays.extend(case().2);
            }
            for (a, r) in rays.iter().take(k).enumerate() {
                plan.write(a, *r);
            }
            n = k;
        }
        plan.idle(step.gap as usize);
        let job = SplitJob {
            bundle,
            boxes,
            active: step.active & ((1u32 << n) - 1) as u16,
        };
        let mut rng = step.noise.map(Pcg64::seed_from_u64);
        plan.run_job(job, None, || match rng.as_mut() {
            Some(r) => busy_noise(bf, n, r),
            None => SplitIn::default(),
        });
    }
    plan.into_clocks()
}

/// proptest with shrinking for the results processor `S` ([`crate::prop::shrinking_check`]): `cases`
/// programs ([`split_program`]), each on a fresh block, checked clock by clock against `model`
/// ([`run_split`]); a failing program is shrunk, replayed with a VCD, and reported. Returns what the
/// programs covered.
pub fn split_shrinking<S: BundleSplitIo>(
    name: &str,
    bf: BundleFixFormat,
    cases: u32,
    model: impl Fn(&BundleFixFormat, &SplitJob, &RayStore) -> SplitResult + Copy,
) -> SplitStats {
    let mut total = SplitStats::default();
    crate::prop::shrinking_check(
        name,
        cases,
        split_program(),
        |program| {
            let s = run_split(
                &mut SplitRtl::<S>::new(&bf),
                plan_program(&bf, program, model),
            )?;
            total.add(&s);
            Ok(())
        },
        |program, path| {
            let mut d = SplitRtl::<S>::new(&bf).vcd_to(path).expect("VCD");
            let _ = run_split(&mut d, plan_program(&bf, program, model));
        },
        |program| format!("job program {program:?}"),
    );
    total
}
