//! Clock-by-clock model of the streaming bundle results processor (`rtl::bundle::stream::BundleStream`):
//! the results processor of [`crate::bundle::split`] with jobs in flight. A new job (a bundle against a
//! node's box pair) enters the pair in any clock the pair's input is free; an undecided bundle's active
//! rays queue up and go through the same pair two per clock, taking the input before new bundles (the
//! splitter and results processor of US 11,308,683 / US 11,682,160, which keep the testing blocks fed
//! with bundles and rays of several jobs at once). Each job leaves with its tag; results may leave in
//! another order than the jobs came.
//!
//! The model is written as the block is built (one state per register group), so that it predicts every
//! output in every clock, for any input sequence, also ray store writes that break the contract below;
//! [`StreamModel::step`] is one clock. What a job computes is [`crate::bundle::split::split_with`] on the
//! rays as read from the store (see the tests: under the contract, every job's result equals
//! [`crate::bundle::split::split_fix`] of its rays at start). The pair's datapath is a parameter
//! ([`PairDatapath`]): the fixed one ([`BundleFixFormat`]) and the float one ([`FloatFormat`]).
//!
//! # The block, one clock (`L` = the pair's latency)
//! - `ready` = no ray pair is issued this clock, and the split queue has room for every bundle in
//!   flight and the new one (`queued + in flight <` [`stream_queue`]`(L)`). A `start` while `ready` is taken: the
//!   bundle enters the pair, its tag, active mask, ray set and outer box ride a delay line beside it.
//! - A ray pair is issued (the pair in two-ray mode) in the clock after the engine addressed it.
//! - The pair's answer `L` clocks after entry: a decided bundle, or one with no active ray, is loaded
//!   into the report stage and reports (`done`) two clocks after its answer; an undecided one joins the
//!   split queue (visible the next clock). Ray
//!   answers are ORed into one accumulator (ray pairs come back in the order they went, one job after
//!   another); the job's last pair reports. Each ray rides beside the pair as it was read from the
//!   store; the kept ones (answer "may hit") are folded into the job's re-bounded bundle
//!   ([`PairDatapath::gather`]: the hull of [`crate::bundle::rebound`], on the fixed datapath with its
//!   rescaling, on the float one a `min`/`max` of the fields; both folds are associative and
//!   commutative, so the block may gather a pair's two rays first), which reports with the job.
//! - The report stage: a job answered in a clock is held in the report registers for one clock and
//!   reaches the result ports in the next (`done` high there). The clock between is what lets the block
//!   fold a pair's answer into the re-bounded bundle from registers (the pair's answer registered
//!   beside the gatherer) instead of in the answer's own clock.
//! - The engine holds one job: each clock it addresses the next two active rays in the store (indices
//!   and set), and loads the queue's head in the clock it addresses its job's last pair (or whenever it
//!   is idle), so that consecutive split jobs issue without a gap.
//! - `rst` (synchronous): drops every job in flight, queued, being split or in the report stage, and
//!   the accumulator; the ray store and the result registers keep their contents (a job answered in the
//!   `rst` clock still loads the report registers, and its fields reach the result ports a clock
//!   later, with `done` low).
//!
//! Latency: a decided job reports [`decided_latency`]`(L) = L + 2` clocks after its start (`done` in
//! that clock); a split job with `k` pair clocks at least [`split_latency`]`(L, k) = 2L + 4 + k`, more
//! when it waits for the engine.
//!
//! Contract (as `BundleSplit`'s): the rays a job may read (its active ones in its set) are written no
//! later than its start clock and not again until its `done`.

use crate::bundle::edge::BoxPair;
use crate::bundle::fix::{all_hit_fix, all_miss_fix, BundleFixFormat, FixBundle};
use crate::bundle::float::{all_hit_float, all_miss_float, FloatBundle};
use crate::bundle::rebound::{float_hull, ScaledBundle};
use crate::format::fixed::FixBox;
use crate::format::float::FloatFormat;
use crate::slab::float::FloatBox;
use std::collections::VecDeque;

/// Rays in one ray set (the width of `active` and `mask`).
pub const STREAM_RAYS: usize = 16;
/// Ray sets in the store (jobs of this many bundles may be in flight over different rays).
pub const STREAM_SETS: usize = 4;
/// Entries of the split queue of a processor over a pair of up to 7 clocks.
pub const STREAM_QUEUE: usize = 8;

/// Entries of the split queue over a pair of `latency` clocks: [`STREAM_QUEUE`], or the next power of
/// two above the latency when that is more. `ready` needs the queue plus the bundles in the pair below
/// this, and the pair holds up to `latency` bundles, so a stream of decided jobs enters every clock.
pub const fn stream_queue(latency: usize) -> usize {
    let q = (latency + 1).next_power_of_two();
    if q > STREAM_QUEUE {
        q
    } else {
        STREAM_QUEUE
    }
}
/// Bits of a job's tag.
pub const STREAM_TAG_BITS: usize = 8;

/// Clocks from a decided job's start to its `done` over a pair of `latency` clocks: the pair, the
/// answer's clock and the report stage.
pub const fn decided_latency(latency: usize) -> usize {
    latency + 2
}

/// The fewest clocks from a split job's start to its `done` over a pair of `latency` clocks, with `k`
/// clocks of ray pairs: the bundle's trip through the pair, the queue, the engine and the store's read
/// (3 clocks), the first ray pair's trip, the `k - 1` pairs behind it, the last answer's clock and the
/// report stage.
pub const fn split_latency(latency: usize, k: usize) -> usize {
    2 * latency + 4 + k
}

/// A datapath of the pair, as the results processor uses it.
pub trait PairDatapath {
    /// A bundle in the datapath's format.
    type Bundle: Copy + Default + std::fmt::Debug + PartialEq + Send + Sync + 'static;
    /// A ray as the ray store holds it: its tiny bundle, and on the fixed datapath its direction
    /// exponent (for re-bounding).
    type Ray: Copy + Default + std::fmt::Debug + PartialEq + Send + Sync + 'static;
    /// A re-bounded bundle as the processor reports it.
    type Hull: Copy + Default + std::fmt::Debug + PartialEq + Eq + Send + Sync + 'static;
    /// A box in the datapath's format.
    type Box: Copy + Default + std::fmt::Debug + PartialEq + Send + Sync + 'static;
    /// The bundle test: `(all_hit, all_miss)`.
    fn decide(&self, b: &Self::Bundle, boxes: &BoxPair<Self::Box>) -> (bool, bool);
    /// The two-ray mode answer for one ray: it may hit the outer box.
    fn may_hit(&self, ray: &Self::Ray, outer: &Self::Box) -> bool;
    /// The re-bounded bundle gathered so far, `acc`, with the kept ray `ray` folded in; `None` on a
    /// datapath whose processor does not re-bound.
    fn gather(&self, acc: Option<Self::Hull>, ray: &Self::Ray) -> Option<Self::Hull>;
}

impl PairDatapath for BundleFixFormat {
    type Bundle = FixBundle;
    type Ray = ScaledBundle;
    type Hull = ScaledBundle;
    type Box = FixBox;
    fn decide(&self, b: &FixBundle, boxes: &BoxPair<FixBox>) -> (bool, bool) {
        (
            all_hit_fix(self, b, &boxes.inner),
            all_miss_fix(self, b, &boxes.outer),
        )
    }
    fn may_hit(&self, ray: &ScaledBundle, outer: &FixBox) -> bool {
        !all_miss_fix(self, &ray.q, outer)
    }
    /// [`ScaledBundle::hull`], the rule of [`crate::bundle::rebound`].
    fn gather(&self, acc: Option<ScaledBundle>, ray: &ScaledBundle) -> Option<ScaledBundle> {
        Some(acc.map_or(*ray, |a| a.hull(self, ray)))
    }
}

impl PairDatapath for FloatFormat {
    type Bundle = FloatBundle;
    type Ray = FloatBundle;
    type Hull = FloatBundle;
    type Box = FloatBox;
    fn decide(&self, b: &FloatBundle, boxes: &BoxPair<FloatBox>) -> (bool, bool) {
        (
            all_hit_float(self, b, &boxes.inner),
            all_miss_float(self, b, &boxes.outer),
        )
    }
    fn may_hit(&self, ray: &FloatBundle, outer: &FloatBox) -> bool {
        !all_miss_float(self, ray, outer)
    }
    /// [`float_hull`], the float rule of [`crate::bundle::rebound`].
    fn gather(&self, acc: Option<FloatBundle>, ray: &FloatBundle) -> Option<FloatBundle> {
        Some(acc.map_or(*ray, |a| float_hull(self, &a, ray)))
    }
}

/// The clock's inputs of a processor over datapath `P`.
pub type StreamInOf<P> =
    StreamIn<<P as PairDatapath>::Bundle, <P as PairDatapath>::Box, <P as PairDatapath>::Ray>;
/// The outputs of a processor over datapath `P`.
pub type StreamOutOf<P> = StreamOut<<P as PairDatapath>::Hull>;
/// A job of a processor over datapath `P`.
pub type StreamJobOf<P> = StreamJob<<P as PairDatapath>::Bundle, <P as PairDatapath>::Box>;

/// A job on the job port.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct StreamJob<B, X> {
    pub bundle: B,
    pub boxes: BoxPair<X>,
    /// Bit `i`: test ray `i` of the set if the bundle is undecided.
    pub active: u16,
    /// The ray set (`0..STREAM_SETS`).
    pub set: u8,
    /// Returned with the job's result.
    pub tag: u8,
}

/// The inputs of one clock (`R`: a ray as the store holds it, [`PairDatapath::Ray`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct StreamIn<B, X, R = B> {
    /// `(set, index, ray)`: a ray store write.
    pub write: Option<(u8, u8, R)>,
    /// `start` high with the job (taken only when `ready`).
    pub start: Option<StreamJob<B, X>>,
    /// `rst` high.
    pub reset: bool,
}

/// The outputs of one clock (the result fields hold their value until the next `done`; `H`: a
/// re-bounded bundle, [`PairDatapath::Hull`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct StreamOut<H = ScaledBundle> {
    pub ready: bool,
    pub done: bool,
    pub tag: u8,
    pub all_hit: bool,
    pub all_miss: bool,
    pub split: bool,
    pub mask: u16,
    /// The re-bounded bundle of a split job's kept rays ([`PairDatapath::gather`] over the rays whose
    /// `mask` bit is set, as they were read from the store); `None` for a decided job and a split one
    /// that kept no ray.
    pub rebound: Option<H>,
}

/// What enters the pair in one clock, with its answer.
#[derive(Clone, Copy, Debug)]
enum Entry<R, X> {
    Bundle {
        tag: u8,
        active: u16,
        set: u8,
        outer: X,
        all_hit: bool,
        all_miss: bool,
    },
    Rays {
        tag: u8,
        /// Ray A's index and answer, and the ray (which rides beside the pair for re-bounding).
        a: (u8, bool, R),
        /// Ray B's, when present.
        b: Option<(u8, bool, R)>,
        last: bool,
    },
}

/// A split job waiting for, or held by, the engine.
#[derive(Clone, Copy, Debug)]
struct Queued<X> {
    tag: u8,
    /// Rays not yet addressed.
    rem: u16,
    set: u8,
    outer: X,
}

/// A ray pair read from the store, entering the pair in the next clock.
#[derive(Clone, Copy, Debug)]
struct Issue<B, X> {
    tag: u8,
    a: (u8, B),
    b: Option<(u8, B)>,
    last: bool,
    outer: X,
}

/// The block's state, clock by clock; see the module doc.
#[derive(Clone, Debug)]
pub struct StreamModel<P: PairDatapath> {
    pair: P,
    store: Vec<[P::Ray; STREAM_RAYS]>,
    /// The pair's contents: `line[0]` entered in the last clock, `line[latency - 1]` answers now.
    line: VecDeque<Option<Entry<P::Ray, P::Box>>>,
    queue: VecDeque<Queued<P::Box>>,
    /// Entries of the split queue ([`stream_queue`] of the latency).
    queue_len: usize,
    engine: Option<Queued<P::Box>>,
    issue: Option<Issue<P::Ray, P::Box>>,
    acc: u16,
    /// The re-bounded bundle of the kept rays answered so far of the job being answered.
    hull: Option<P::Hull>,
    /// The report registers: the job answered in the last clock (`done` set), or the last one's
    /// fields.
    stage: StreamOut<P::Hull>,
    out: StreamOut<P::Hull>,
    /// Clocks the pair's input was used, and clocks run.
    pub busy_clocks: u64,
    pub clocks: u64,
    /// The split queue's largest occupancy.
    pub max_queued: usize,
}

/// The lowest set bit of `x` as an index.
fn lowest(x: u16) -> Option<u8> {
    (x != 0).then(|| x.trailing_zeros() as u8)
}

impl<P: PairDatapath> StreamModel<P> {
    /// The block after reset over `pair`, whose answers come `latency` clocks after entry, with a split
    /// queue of [`stream_queue`]`(latency)` entries; the ray store holds zero rays.
    pub fn new(pair: P, latency: usize) -> Self {
        assert!(latency >= 1, "the pair takes at least one clock");
        StreamModel {
            pair,
            store: vec![[P::Ray::default(); STREAM_RAYS]; STREAM_SETS],
            line: (0..latency).map(|_| None).collect(),
            queue: VecDeque::new(),
            queue_len: stream_queue(latency),
            engine: None,
            issue: None,
            acc: 0,
            hull: None,
            stage: StreamOut::default(),
            out: StreamOut {
                ready: true,
                ..Default::default()
            },
            busy_clocks: 0,
            clocks: 0,
            max_queued: 0,
        }
    }

    /// Bundles in the pair (entered, not yet answered).
    fn bundles_in_flight(&self) -> usize {
        self.line
            .iter()
            .filter(|e| matches!(e, Some(Entry::Bundle { .. })))
            .count()
    }

    /// `ready` in this clock: a start now is taken.
    pub fn ready(&self) -> bool {
        self.issue.is_none() && self.queue.len() + self.bundles_in_flight() < self.queue_len
    }

    /// The outputs in this clock.
    pub fn outputs(&self) -> StreamOut<P::Hull> {
        StreamOut {
            ready: self.ready(),
            ..self.out
        }
    }

    /// One clock with `input`; afterwards [`StreamModel::outputs`] are the next clock's.
    pub fn step(&mut self, input: &StreamInOf<P>) {
        let take = self.ready() && !input.reset && input.start.is_some();
        // The pair's input in this clock.
        let entering = if let Some(is) = self.issue {
            self.busy_clocks += 1;
            Some(Entry::Rays {
                tag: is.tag,
                a: (is.a.0, self.pair.may_hit(&is.a.1, &is.outer), is.a.1),
                b: is.b.map(|(i, r)| (i, self.pair.may_hit(&r, &is.outer), r)),
                last: is.last,
            })
        } else if take {
            self.busy_clocks += 1;
            let j = input.start.expect("taken");
            let (all_hit, all_miss) = self.pair.decide(&j.bundle, &j.boxes);
            Some(Entry::Bundle {
                tag: j.tag,
                active: j.active,
                set: j.set % STREAM_SETS as u8,
                outer: j.boxes.outer,
                all_hit,
                all_miss,
            })
        } else {
            None
        };
        // The pair's answer in this clock.
        let answer = self.line.pop_back().expect("the line has `latency` stages");
        self.line.push_front(entering);
        let mut done = None;
        let mut push = None;
        match answer {
            Some(Entry::Bundle {
                tag,
                active,
                set,
                outer,
                all_hit,
                all_miss,
            }) => {
                if all_hit || all_miss || active == 0 {
                    let mask = if all_hit { active } else { 0 };
                    done = Some((tag, all_hit, all_miss, mask, None));
                } else {
                    push = Some(Queued {
                        tag,
                        rem: active,
                        set,
                        outer,
                    });
                }
            }
            Some(Entry::Rays { tag, a, b, last }) => {
                let got = (a.1 as u16) << a.0 | b.map_or(0, |(i, m, _)| (m as u16) << i);
                for (_, kept, r) in [Some(a), b].into_iter().flatten() {
                    if kept {
                        self.hull = self.pair.gather(self.hull, &r);
                    }
                }
                if last {
                    done = Some((tag, false, false, self.acc | got, self.hull));
                    self.acc = 0;
                    self.hull = None;
                } else {
                    self.acc |= got;
                }
            }
            None => {}
        }
        // The engine addresses the next two rays of its job (the store read before this clock's write)
        // and takes the queue's head when its job is addressed in full.
        let mut free = true;
        self.issue = None;
        if let Some(mut e) = self.engine {
            let a = lowest(e.rem).expect("the engine holds a job with rays left");
            e.rem &= e.rem - 1;
            let b = lowest(e.rem);
            if b.is_some() {
                e.rem &= e.rem - 1;
            }
            let set = &self.store[e.set as usize];
            self.issue = Some(Issue {
                tag: e.tag,
                a: (a, set[a as usize]),
                b: b.map(|i| (i, set[i as usize])),
                last: e.rem == 0,
                outer: e.outer,
            });
            free = e.rem == 0;
            self.engine = (!free).then_some(e);
        }
        if free {
            self.engine = self.queue.pop_front();
        }
        if let Some(q) = push {
            self.queue.push_back(q);
        }
        assert!(
            self.queue.len() <= self.queue_len,
            "split queue overflow: `ready` must prevent it"
        );
        self.max_queued = self.max_queued.max(self.queue.len());
        if let Some((set, i, r)) = input.write {
            self.store[set as usize % STREAM_SETS][i as usize % STREAM_RAYS] = r;
        }
        // The report stage moves on to the result ports; this clock's answer loads it.
        self.out = StreamOut {
            ready: false,
            ..self.stage
        };
        self.stage.done = false;
        if let Some((tag, all_hit, all_miss, mask, rebound)) = done {
            self.stage = StreamOut {
                ready: false,
                done: true,
                tag,
                all_hit,
                all_miss,
                split: !(all_hit || all_miss),
                mask,
                rebound,
            };
        }
        if input.reset {
            self.line.iter_mut().for_each(|e| *e = None);
            self.queue.clear();
            self.engine = None;
            self.issue = None;
            self.acc = 0;
            self.hull = None;
            self.stage.done = false;
            self.out.done = false;
        }
        self.clocks += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A toy datapath: a "bundle" is a pair (all_hit, all_miss), a ray is its may-hit bit.
    #[derive(Clone, Copy, Debug)]
    struct Toy;
    impl PairDatapath for Toy {
        type Bundle = (bool, bool);
        type Ray = (bool, bool);
        type Hull = ();
        type Box = u8;
        fn decide(&self, b: &(bool, bool), _: &BoxPair<u8>) -> (bool, bool) {
            *b
        }
        fn may_hit(&self, r: &(bool, bool), _: &u8) -> bool {
            r.0
        }
        fn gather(&self, _: Option<()>, _: &(bool, bool)) -> Option<()> {
            None
        }
    }

    fn job(decide: (bool, bool), active: u16, tag: u8) -> StreamIn<(bool, bool), u8> {
        StreamIn {
            start: Some(StreamJob {
                bundle: decide,
                boxes: BoxPair::default(),
                active,
                set: 0,
                tag,
            }),
            ..Default::default()
        }
    }

    /// Runs `inputs` then idles until quiet; returns per clock (ready before the clock, done after).
    fn run(m: &mut StreamModel<Toy>, inputs: &[StreamIn<(bool, bool), u8>]) -> Vec<StreamOut<()>> {
        let mut outs = vec![];
        for k in 0..inputs.len() + 40 {
            m.step(inputs.get(k).unwrap_or(&StreamIn::default()));
            outs.push(m.outputs());
        }
        outs
    }

    #[test]
    fn decided_jobs_enter_every_clock_and_report_l_plus_two_clocks_later() {
        let mut m = StreamModel::new(Toy, 3);
        let inputs: Vec<_> = (0..10u8)
            .map(|t| job((t % 2 == 0, t % 2 == 1), 0xff, t))
            .collect();
        let outs = run(&mut m, &inputs);
        // Start in clock k (step k) -> answered in step k + 3, done visible after step k + 4 (clock
        // k + 5 = start + L + 2).
        for t in 0..10usize {
            let o = outs[t + decided_latency(3) - 1];
            assert!(o.done, "job {t}: {outs:?}");
            assert_eq!(o.tag as usize, t);
            assert_eq!(o.mask, if t % 2 == 0 { 0xff } else { 0 });
        }
        assert_eq!(outs.iter().filter(|o| o.done).count(), 10);
        assert_eq!(m.busy_clocks, 10);
    }

    #[test]
    fn split_jobs_issue_back_to_back_and_block_new_bundles_while_rays_go() {
        let mut m = StreamModel::new(Toy, 3);
        // Rays 0..16 of set 0: ray i may hit when i is odd.
        for i in 0..16u8 {
            m.step(&StreamIn {
                write: Some((0, i, (i % 2 == 1, false))),
                ..Default::default()
            });
        }
        let inputs = vec![
            job((false, false), 0b1111, 1),
            job((false, false), 0b111, 2),
            job((true, false), 0b1, 3),
        ];
        let outs = run(&mut m, &inputs);
        let dones: Vec<_> = outs
            .iter()
            .enumerate()
            .filter(|(_, o)| o.done)
            .map(|(k, o)| (k, o.tag, o.mask, o.split))
            .collect();
        // Job 3 (decided) leaves first; jobs 1 and 2 split: 2 + 2 pair clocks issued back to back.
        assert_eq!(dones[0], (6, 3, 1, false));
        assert_eq!((dones[1].1, dones[1].2, dones[1].3), (1, 0b1010, true));
        assert_eq!((dones[2].1, dones[2].2, dones[2].3), (2, 0b10, true));
        // Job 1: bundle answer after step 3, queued (visible after step 3), engine loads in step 4,
        // addresses in steps 5, 6; issues in steps 6, 7; answers in steps 9, 10; the report stage in
        // step 11 -> done after step 11.
        assert_eq!(dones[1].0, 11);
        assert_eq!(dones[1].0 + 1, split_latency(3, 2), "job 1 never waits");
        assert_eq!(dones[2].0, 13);
        assert_eq!(m.busy_clocks, 3 + 4);
        // ready was low exactly in the clocks a pair was issued (steps 6..9 read ready before them).
        let low: Vec<_> = (0..outs.len()).filter(|&k| !outs[k].ready).collect();
        assert_eq!(low, vec![5, 6, 7, 8]);
    }

    #[test]
    fn the_queue_holds_every_bundle_in_the_pair_plus_one() {
        assert_eq!(stream_queue(3), 8);
        assert_eq!(stream_queue(5), 8);
        assert_eq!(stream_queue(7), 8);
        assert_eq!(stream_queue(8), 16);
        assert_eq!(stream_queue(9), 16);
        assert_eq!(stream_queue(13), 16);
        assert_eq!(stream_queue(16), 32);
    }

    /// A 9-clock pair takes a decided job every clock (the queue's room covers the pair).
    #[test]
    fn a_deep_pair_takes_decided_jobs_every_clock() {
        let mut m = StreamModel::new(Toy, 9);
        let inputs: Vec<_> = (0..40u8).map(|t| job((true, false), 1, t)).collect();
        let outs = run(&mut m, &inputs);
        assert_eq!(outs.iter().filter(|o| o.done).count(), 40);
        assert_eq!(m.busy_clocks, 40);
        assert!(outs[..40].iter().all(|o| o.ready), "{outs:?}");
    }

    #[test]
    fn reset_drops_every_job_in_flight() {
        let mut m = StreamModel::new(Toy, 3);
        m.step(&job((false, false), 0xffff, 1));
        m.step(&job((true, false), 1, 2));
        for _ in 0..3 {
            m.step(&StreamIn::default());
        }
        m.step(&StreamIn {
            reset: true,
            ..Default::default()
        });
        let outs = run(&mut m, &[]);
        assert!(outs.iter().all(|o| !o.done && o.ready), "{outs:?}");
        assert_eq!(m.outputs().tag, 2, "result registers keep their contents");
    }
}
