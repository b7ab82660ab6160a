//! `BundleStream`: the results processor with jobs in flight, around one fixed-point bundle pair
//! ([`BundleFix`]). A job (a bundle against a node's box pair, with its active rays, ray set and tag) is
//! taken in any clock the pair's input is free; an undecided bundle joins a split queue and its active
//! rays go through the same pair two per clock (two-ray mode), ahead of new bundles; each job leaves with
//! its tag. **Results may leave in another order than the jobs came**: a decided job overtakes split
//! ones; split jobs leave in the order their bundles were answered.
//!
//! While a split job's rays stream through the pair, the block gathers the bundle around the rays it
//! keeps (re-bounding, [`crate::bundle::rebound::ReboundAcc`]) and reports it with the job.
//!
//! Clock for clock `golden::bundle::stream::StreamModel` (ready, done, tag, result, the re-bounded
//! bundle, in every clock, for any input); what a job computes is `golden::bundle::split::split_fix` on
//! its rays, and its re-bounded bundle `golden::bundle::rebound::rebound_fix` of the rays kept.
//!
//! # Parameters
//! `G`, `V = G + 1`, `D = FD + 3`, `T`, `CUTS`, as [`BundleFix`]; presets [`crate::BundleStreamB8`],
//! [`crate::BundleStreamB12`], [`crate::BundleStreamB16`] over the 3-clock pair and
//! [`crate::BundleStreamB12P5`] over the 5-clock one (module name `..._p5_n16x4`). The ray store holds
//! [`STREAM_SETS`] sets of [`STREAM_RAYS`] rays; the split queue [`golden::bundle::stream::STREAM_QUEUE`]
//! (8) jobs.
//!
//! # Inputs
//! - `clock`; `rst` (synchronous: high at a clock edge, every job in flight, queued or being split is
//!   dropped and never reports; a `start` in that clock is not taken, a ray store write is; the ray
//!   store and the result registers keep their contents, except that a job answered in the `rst` clock
//!   itself still loads them, with no `done`, as the model does);
//! - ray store write port: `ray_we`, `ray_addr` (6 bits: `[5:4]` the set, `[3:0]` the ray), `ray_o_lo`,
//!   `ray_o_hi`, `ray_d_lo`, `ray_d_hi` (arrays over x, y, z), `ray_t` (the ray's `t_hi`): the ray as a
//!   quantised tiny bundle, as `BundleSplit`'s; and for re-bounding `ray_t_lo` (its `t_lo`) and `ray_j`
//!   (its direction exponent, [`J_BITS`] bits, two's complement). Written at the end of the clock, at
//!   any time;
//! - job port: `start` (taken when `ready`), the bundle `o_lo`, `o_hi`, `d_lo`, `d_hi`, `t_lo`, `t_hi`,
//!   the inner box `in_lo`, `in_hi`, the outer box `out_lo`, `out_hi`, `active` (16 bits: rays of the
//!   set to test if the bundle is undecided), `job_set` (2 bits: the ray set; `set` is a reserved word
//!   of SystemVerilog), `tag` (8 bits, returned with
//!   the result). All sampled in the start clock only.
//!
//! Contract: the rays a job may read (its active ones in its set) are written no later than its start
//! clock and not again until its `done`. With four sets, four bundles' rays may be in use at once.
//!
//! # Outputs
//! - `ready`: a `start` in this clock is taken. Low in the clocks the pair takes a ray pair, and while
//!   the split queue could not hold every bundle in flight plus one;
//! - `done`: one-clock pulse; with it, and held until the next `done`: `done_tag` (the job's `tag`),
//!   `all_hit`, `all_miss`, `split`, `mask` (16 bits, bit `i`: ray `i` may hit), as `BundleSplit`'s;
//!   `rb_valid` (the job was split and kept a ray) and the re-bounded bundle `rb_o_lo`, `rb_o_hi`,
//!   `rb_d_lo`, `rb_d_hi`, `rb_t_lo`, `rb_t_hi`, `rb_j` (all zero when `rb_valid` is low).
//!
//! # Sequencing (`L` = the pair's latency, [`bundle_fix_latency`]`(CUTS)`: 3, or 5 for `_p5`)
//! ```text
//! s           start taken: the bundle enters the pair; tag, active, set, outer box enter a delay line
//! s+L         the answer: decided, or no active ray -> report stage in s+L+1, done in s+L+2;
//!             undecided -> split queue
//! then        the engine takes the queue's head (in the clock it addresses its previous job's last
//!             pair, or when idle), addresses two rays a clock (bank A: ray A, bank B: ray B, address
//!             {set, ray}), each pair entering the pair in the next clock with the job's outer box
//! +L          each pair's answer, ORed into the accumulator; the job's last pair -> report stage in
//!             the next clock (the gatherer folds the last rays there), done in the one after
//! ```
//! A decided job reports `golden::bundle::stream::decided_latency(L) = L + 2` clocks after its start;
//! a split job of `k` pair clocks no earlier than `golden::bundle::stream::split_latency(L, k) =
//! 2L + 4 + k`. Every input of the pair comes from a port, a register or a RAM output, as in
//! `BundleSplit`.
//!
//! # Structure
//! [`crate::bundle::stream_ctl::StreamCtl`] (the control: delay lines, split queue, engine, accumulator, result registers; shared
//! with the float processor) beside the pair and the ray store ([`RayStore`], and a [`TwinRam`] each for
//! the rays' `t_lo` and `j`), and the gatherer [`ReboundAcc`], which takes the rays as they enter the
//! pair and the control's reading of each answer; this block only wires the job port, the store's banks
//! and the control's choice into the pair.

use crate::bundle::edge_fix::BUNDLE_TEST_CUTS;
use crate::bundle::pair_fix::{bundle_fix_latency, BundleFix, BUNDLE_FIX_DEPTHS};
use crate::bundle::ray_store::{ray_job_word, RayStore, TwinRam};
use crate::bundle::rebound::{ReboundAcc, J_BITS};
pub use crate::bundle::stream_ctl::STREAM_ADDR_BITS;
use crate::bundle::stream_ctl::{StreamCtl8, SET_BITS};
use crate::slab::fix::{code, sext};
use golden::bundle::fix::{BundleFixFormat, FixBundle};
use golden::bundle::rebound::ScaledBundle;
use golden::bundle::stream::{
    PairDatapath, StreamIn, StreamInOf, StreamJob, StreamOut, StreamOutOf, STREAM_RAYS,
    STREAM_SETS, STREAM_TAG_BITS,
};
use golden::format::fixed::FixBox;
use rust_hdl::prelude::*;

/// A fixed job on the job port.
pub type FixStreamJob = StreamJob<FixBundle, FixBox>;
/// A clock's inputs of the fixed processor.
pub type FixStreamIn = StreamIn<FixBundle, FixBox, ScaledBundle>;

/// The streaming results processor; see the module documentation.
#[derive(LogicBlock)]
pub struct BundleStream<
    const G: usize,
    const V: usize,
    const D: usize,
    const T: usize,
    const CUTS: usize = BUNDLE_TEST_CUTS,
> {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    // ray store write port
    pub ray_we: Signal<In, Bit>,
    pub ray_addr: Signal<In, Bits<STREAM_ADDR_BITS>>,
    pub ray_o_lo: [Signal<In, Bits<G>>; 3],
    pub ray_o_hi: [Signal<In, Bits<G>>; 3],
    pub ray_d_lo: [Signal<In, Bits<D>>; 3],
    pub ray_d_hi: [Signal<In, Bits<D>>; 3],
    pub ray_t: Signal<In, Bits<T>>,
    pub ray_t_lo: Signal<In, Bits<T>>,
    pub ray_j: Signal<In, Bits<J_BITS>>,
    // job port
    pub start: Signal<In, Bit>,
    pub o_lo: [Signal<In, Bits<G>>; 3],
    pub o_hi: [Signal<In, Bits<G>>; 3],
    pub d_lo: [Signal<In, Bits<D>>; 3],
    pub d_hi: [Signal<In, Bits<D>>; 3],
    pub t_lo: Signal<In, Bits<T>>,
    pub t_hi: Signal<In, Bits<T>>,
    pub in_lo: [Signal<In, Bits<G>>; 3],
    pub in_hi: [Signal<In, Bits<G>>; 3],
    pub out_lo: [Signal<In, Bits<G>>; 3],
    pub out_hi: [Signal<In, Bits<G>>; 3],
    pub active: Signal<In, Bits<STREAM_RAYS>>,
    pub job_set: Signal<In, Bits<SET_BITS>>,
    pub tag: Signal<In, Bits<STREAM_TAG_BITS>>,
    // results
    pub ready: Signal<Out, Bit>,
    pub done: Signal<Out, Bit>,
    pub done_tag: Signal<Out, Bits<STREAM_TAG_BITS>>,
    pub all_hit: Signal<Out, Bit>,
    pub all_miss: Signal<Out, Bit>,
    pub split: Signal<Out, Bit>,
    pub mask: Signal<Out, Bits<STREAM_RAYS>>,
    // the re-bounded bundle
    pub rb_valid: Signal<Out, Bit>,
    pub rb_o_lo: [Signal<Out, Bits<G>>; 3],
    pub rb_o_hi: [Signal<Out, Bits<G>>; 3],
    pub rb_d_lo: [Signal<Out, Bits<D>>; 3],
    pub rb_d_hi: [Signal<Out, Bits<D>>; 3],
    pub rb_t_lo: Signal<Out, Bits<T>>,
    pub rb_t_hi: Signal<Out, Bits<T>>,
    pub rb_j: Signal<Out, Bits<J_BITS>>,
    // the pair, the ray store (bank A: ray A, bank B: ray B), the control and the gatherer
    pair: BundleFix<G, V, D, T, CUTS>,
    store: RayStore<G, D, T, STREAM_ADDR_BITS>,
    store_t_lo: TwinRam<T, STREAM_ADDR_BITS>,
    store_j: TwinRam<J_BITS, STREAM_ADDR_BITS>,
    ctl: StreamCtl8<G>,
    rebound: ReboundAcc<G, D, T>,
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize>
    BundleStream<G, V, D, T, CUTS>
{
    /// Clocks of the pair inside.
    pub const PAIR_LATENCY: usize = bundle_fix_latency(CUTS);

    /// The processor for `bf`, whose widths must equal the parameters.
    pub fn new(bf: &BundleFixFormat) -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            ray_we: Default::default(),
            ray_addr: Default::default(),
            ray_o_lo: Default::default(),
            ray_o_hi: Default::default(),
            ray_d_lo: Default::default(),
            ray_d_hi: Default::default(),
            ray_t: Default::default(),
            ray_t_lo: Default::default(),
            ray_j: Default::default(),
            start: Default::default(),
            o_lo: Default::default(),
            o_hi: Default::default(),
            d_lo: Default::default(),
            d_hi: Default::default(),
            t_lo: Default::default(),
            t_hi: Default::default(),
            in_lo: Default::default(),
            in_hi: Default::default(),
            out_lo: Default::default(),
            out_hi: Default::default(),
            active: Default::default(),
            job_set: Default::default(),
            tag: Default::default(),
            ready: Default::default(),
            done: Default::default(),
            done_tag: Default::default(),
            all_hit: Default::default(),
            all_miss: Default::default(),
            split: Default::default(),
            mask: Default::default(),
            rb_valid: Default::default(),
            rb_o_lo: Default::default(),
            rb_o_hi: Default::default(),
            rb_d_lo: Default::default(),
            rb_d_hi: Default::default(),
            rb_t_lo: Default::default(),
            rb_t_hi: Default::default(),
            rb_j: Default::default(),
            pair: BundleFix::new(bf),
            store: Default::default(),
            store_t_lo: Default::default(),
            store_j: Default::default(),
            ctl: StreamCtl8::new(Self::PAIR_LATENCY),
            rebound: ReboundAcc::new(Self::PAIR_LATENCY),
        }
    }
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize> Logic
    for BundleStream<G, V, D, T, CUTS>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.pair.clock.next = self.clock.val();
        self.pair.rst.next = self.rst.val();
        self.ctl.clock.next = self.clock.val();
        self.ctl.rst.next = self.rst.val();

        // The ray store: both banks written together, read at the control's addresses.
        self.store.clock.next = self.clock.val();
        self.store.we.next = self.ray_we.val();
        self.store.waddr.next = self.ray_addr.val();
        self.store.w_t.next = self.ray_t.val();
        for i in 0..3 {
            self.store.w_o_lo[i].next = self.ray_o_lo[i].val();
            self.store.w_o_hi[i].next = self.ray_o_hi[i].val();
            self.store.w_d_lo[i].next = self.ray_d_lo[i].val();
            self.store.w_d_hi[i].next = self.ray_d_hi[i].val();
        }
        self.store.addr_a.next = self.ctl.addr_a.val();
        self.store.addr_b.next = self.ctl.addr_b.val();
        self.store_t_lo.clock.next = self.clock.val();
        self.store_t_lo.we.next = self.ray_we.val();
        self.store_t_lo.waddr.next = self.ray_addr.val();
        self.store_t_lo.w.next = self.ray_t_lo.val();
        self.store_t_lo.addr_a.next = self.ctl.addr_a.val();
        self.store_t_lo.addr_b.next = self.ctl.addr_b.val();
        self.store_j.clock.next = self.clock.val();
        self.store_j.we.next = self.ray_we.val();
        self.store_j.waddr.next = self.ray_addr.val();
        self.store_j.w.next = self.ray_j.val();
        self.store_j.addr_a.next = self.ctl.addr_a.val();
        self.store_j.addr_b.next = self.ctl.addr_b.val();

        // The gatherer: the rays as they enter the pair, and the control's reading of its answer.
        self.rebound.clock.next = self.clock.val();
        self.rebound.rst.next = self.rst.val();
        for i in 0..3 {
            self.rebound.a_o[i].next = self.store.a_o_lo[i].val();
            self.rebound.a_o[i + 3].next = self.store.a_o_hi[i].val();
            self.rebound.a_d[i].next = self.store.a_d_lo[i].val();
            self.rebound.a_d[i + 3].next = self.store.a_d_hi[i].val();
            self.rebound.b_o[i].next = self.store.b_o_lo[i].val();
            self.rebound.b_o[i + 3].next = self.store.b_o_hi[i].val();
            self.rebound.b_d[i].next = self.store.b_d_lo[i].val();
            self.rebound.b_d[i + 3].next = self.store.b_d_hi[i].val();
        }
        self.rebound.a_t[0].next = self.store_t_lo.a.val();
        self.rebound.a_t[1].next = self.store.a_t.val();
        self.rebound.a_j.next = self.store_j.a.val();
        self.rebound.b_t[0].next = self.store_t_lo.b.val();
        self.rebound.b_t[1].next = self.store.b_t.val();
        self.rebound.b_j.next = self.store_j.b.val();
        self.rebound.rays_back.next = self.ctl.ans_rays.val();
        self.rebound.keep_a.next = self.ctl.ans_keep_a.val();
        self.rebound.keep_b.next = self.ctl.ans_keep_b.val();
        self.rebound.last_back.next = self.ctl.ans_last.val();
        self.rebound.bundle_done.next = self.ctl.ans_done.val();

        // The control: the job port's control fields and the pair's answer.
        self.ctl.start.next = self.start.val();
        self.ctl.active.next = self.active.val();
        self.ctl.job_set.next = self.job_set.val();
        self.ctl.tag.next = self.tag.val();
        for i in 0..3 {
            self.ctl.out_lo[i].next = self.out_lo[i].val();
            self.ctl.out_hi[i].next = self.out_hi[i].val();
        }
        self.ctl.p_valid.next = self.pair.valid_out.val();
        self.ctl.p_tag.next = self.pair.tag_out.val();
        self.ctl.p_all_hit.next = self.pair.all_hit.val();
        self.ctl.p_all_miss.next = self.pair.all_miss.val();

        // The pair's inputs: a ray pair (from the store's banks) when the control issues one, else the
        // job port's bundle.
        self.pair.valid_in.next = self.ctl.issue.val() | self.ctl.take.val();
        self.pair.two_rays.next = self.ctl.issue.val();
        self.pair.tag_in.next = self.ctl.issue_tag.val();
        self.pair.t_lo.next = self.t_lo.val();
        if self.ctl.issue.val() {
            self.pair.t_hi.next = self.store.a_t.val();
        } else {
            self.pair.t_hi.next = self.t_hi.val();
        }
        self.pair.r_t.next = self.store.b_t.val();
        for i in 0..3 {
            if self.ctl.issue.val() {
                self.pair.o_lo[i].next = self.store.a_o_lo[i].val();
                self.pair.o_hi[i].next = self.store.a_o_hi[i].val();
                self.pair.d_lo[i].next = self.store.a_d_lo[i].val();
                self.pair.d_hi[i].next = self.store.a_d_hi[i].val();
                self.pair.out_lo[i].next = self.ctl.issue_lo[i].val();
                self.pair.out_hi[i].next = self.ctl.issue_hi[i].val();
            } else {
                self.pair.o_lo[i].next = self.o_lo[i].val();
                self.pair.o_hi[i].next = self.o_hi[i].val();
                self.pair.d_lo[i].next = self.d_lo[i].val();
                self.pair.d_hi[i].next = self.d_hi[i].val();
                self.pair.out_lo[i].next = self.out_lo[i].val();
                self.pair.out_hi[i].next = self.out_hi[i].val();
            }
            self.pair.r_o_lo[i].next = self.store.b_o_lo[i].val();
            self.pair.r_o_hi[i].next = self.store.b_o_hi[i].val();
            self.pair.r_d_lo[i].next = self.store.b_d_lo[i].val();
            self.pair.r_d_hi[i].next = self.store.b_d_hi[i].val();
            self.pair.in_lo[i].next = self.in_lo[i].val();
            self.pair.in_hi[i].next = self.in_hi[i].val();
        }

        self.ready.next = self.ctl.ready.val();
        self.done.next = self.ctl.done.val();
        self.done_tag.next = self.ctl.done_tag.val();
        self.all_hit.next = self.ctl.all_hit.val();
        self.all_miss.next = self.ctl.all_miss.val();
        self.split.next = self.ctl.split.val();
        self.mask.next = self.ctl.mask.val();
        self.rb_valid.next = self.rebound.rb_valid.val();
        for i in 0..3 {
            self.rb_o_lo[i].next = self.rebound.rb_o[i].val();
            self.rb_o_hi[i].next = self.rebound.rb_o[i + 3].val();
            self.rb_d_lo[i].next = self.rebound.rb_d[i].val();
            self.rb_d_hi[i].next = self.rebound.rb_d[i + 3].val();
        }
        self.rb_t_lo.next = self.rebound.rb_t[0].val();
        self.rb_t_hi.next = self.rebound.rb_t[1].val();
        self.rb_j.next = self.rebound.rb_j.val();
    }
}

/// A streaming processor of any datapath and width, seen from a testbench.
pub trait BundleStreamIo: Block {
    /// The pair's datapath (its format).
    type Dp: PairDatapath + Copy + std::fmt::Debug + Send + Sync + 'static;
    /// Clocks of the pair inside.
    const PAIR_LATENCY: usize;
    /// The block for `dp` (which must match the block's widths).
    fn for_format(dp: &Self::Dp) -> Self;
    /// The pair's cut points.
    const CUTS: usize;
    /// The pair's list of built depths `(cut points, module-name suffix)`, for the module name
    /// (`crate::names::bundle_stream_of`).
    const PAIR_DEPTHS: &'static [(usize, &'static str)];
    /// The name of the format `dp`, as the module name carries it (`g12_i16f11_t20f6_d10`, `e5m10`).
    fn format_name(dp: &Self::Dp) -> String;
    /// Sets the clock input.
    fn set_clock(&mut self, high: bool);
    /// Drives one clock's inputs (data ports of an absent write or start are driven to zero).
    fn drive(&mut self, input: &StreamInOf<Self::Dp>);
    /// Reads the outputs.
    fn outputs(&self) -> StreamOutOf<Self::Dp>;
    /// The outputs from the values of the output ports (`word`: a port's value by its Verilog name, such
    /// as `rb_d_lo_1`); `None` when a port is missing.
    fn decode_out(
        dp: &Self::Dp,
        word: &dyn Fn(&str) -> Option<u64>,
    ) -> Option<StreamOutOf<Self::Dp>>;
    /// The value of input port `port` (a Verilog name such as `ray_d_lo_1`) in one clock.
    fn in_word(dp: &Self::Dp, port: &str, input: &StreamInOf<Self::Dp>) -> Option<u64>;
}

/// The result ports every processor has (`ready` .. `mask`) from their values by name; `rebound` is
/// `None`.
pub fn decode_common_out<H>(word: &dyn Fn(&str) -> Option<u64>) -> Option<StreamOut<H>> {
    Some(StreamOut {
        ready: word("ready")? != 0,
        done: word("done")? != 0,
        tag: word("done_tag")? as u8,
        all_hit: word("all_hit")? != 0,
        all_miss: word("all_miss")? != 0,
        split: word("split")? != 0,
        mask: word("mask")? as u16,
        rebound: None,
    })
}

/// The re-bounded bundle on a fixed processor's `rb_*` ports (widths `g`, `d`, `t`; `word(base,
/// axis)` a port's value): the bundle when `rb_valid` is high, `None` when it is low and every field is
/// zero (what the block drives then). Fields that are not zero while `rb_valid` is low decode as the
/// bundle with the impossible exponent `i32::MAX`, so that a comparison with the model catches a wrong
/// `rb_valid` in either direction. The outer `None`: a port is missing.
pub fn decode_rebound(
    g: usize,
    d: usize,
    t: usize,
    word: impl Fn(&str, usize) -> Option<u64>,
) -> Option<Option<ScaledBundle>> {
    let arr = |base: &str, w: usize| -> Option<[i64; 3]> {
        Some([
            sext(word(base, 0)?, w),
            sext(word(base, 1)?, w),
            sext(word(base, 2)?, w),
        ])
    };
    let sb = ScaledBundle {
        q: FixBundle {
            o_lo: arr("rb_o_lo", g)?,
            o_hi: arr("rb_o_hi", g)?,
            d_lo: arr("rb_d_lo", d)?,
            d_hi: arr("rb_d_hi", d)?,
            t_lo: sext(word("rb_t_lo", 0)?, t),
            t_hi: sext(word("rb_t_hi", 0)?, t),
        },
        j: sext(word("rb_j", 0)?, J_BITS) as i32,
    };
    let valid = word("rb_valid", 0)? != 0;
    Some(if valid {
        Some(sb)
    } else if sb == ScaledBundle::default() {
        None
    } else {
        Some(ScaledBundle { j: i32::MAX, ..sb })
    })
}

/// The store address `{set, ray}` of a write.
pub(crate) fn store_addr(set: u8, ray: u8) -> u64 {
    ((set as u64 % STREAM_SETS as u64) << 4) | (ray as u64 % STREAM_RAYS as u64)
}

/// The value of input port `port` (a Verilog name such as `ray_d_lo_1`) in one clock, for either
/// datapath: the control ports here, the ray and job data by `data(base, axis, ray, job)`.
pub fn stream_in_word_with<B: Copy + Default, X: Copy + Default, R: Copy + Default>(
    port: &str,
    input: &StreamIn<B, X, R>,
    data: impl Fn(&str, usize, &R, &StreamJob<B, X>) -> Option<u64>,
) -> Option<u64> {
    let (base, idx) = crate::verilog::split_port(port);
    let (set, ray, r) = input.write.unwrap_or_default();
    let j = input.start.unwrap_or_default();
    Some(match base {
        "rst" => input.reset as u64,
        "ray_we" => input.write.is_some() as u64,
        "ray_addr" => store_addr(set, ray),
        "start" => input.start.is_some() as u64,
        "active" => j.active as u64,
        "job_set" => j.set as u64 % STREAM_SETS as u64,
        "tag" => j.tag as u64,
        _ => return data(base, idx.unwrap_or(0), &r, &j),
    })
}

/// The value of input port `port` in one clock, for a fixed processor over `bf`.
pub fn stream_in_word(bf: &BundleFixFormat, port: &str, input: &FixStreamIn) -> Option<u64> {
    stream_in_word_with(port, input, |base, i, r, j| match base {
        "ray_t_lo" => Some(code(r.q.t_lo, bf.base.t as usize)),
        "ray_j" => Some(code(r.j as i64, J_BITS)),
        _ => ray_job_word(bf, base, i, &r.q, &j.bundle, &j.boxes),
    })
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize>
    BundleStreamIo for BundleStream<G, V, D, T, CUTS>
{
    type Dp = BundleFixFormat;
    const PAIR_LATENCY: usize = bundle_fix_latency(CUTS);
    const CUTS: usize = CUTS;
    const PAIR_DEPTHS: &'static [(usize, &'static str)] = &BUNDLE_FIX_DEPTHS;

    fn for_format(bf: &BundleFixFormat) -> Self {
        Self::new(bf)
    }

    fn format_name(bf: &BundleFixFormat) -> String {
        bf.name()
    }

    fn set_clock(&mut self, high: bool) {
        self.clock.next = Clock { clk: high };
    }

    fn drive(&mut self, input: &FixStreamIn) {
        let (set, ray, sr) = input.write.unwrap_or_default();
        let (r, rj) = (sr.q, sr.j);
        self.rst.next = input.reset;
        self.ray_we.next = input.write.is_some();
        self.ray_addr.next = bits::<STREAM_ADDR_BITS>(store_addr(set, ray));
        let j = input.start.unwrap_or_default();
        let (b, p) = (&j.bundle, &j.boxes);
        self.start.next = input.start.is_some();
        self.active.next = bits::<STREAM_RAYS>(j.active as u64);
        self.job_set.next = bits::<SET_BITS>(j.set as u64 % STREAM_SETS as u64);
        self.tag.next = bits::<STREAM_TAG_BITS>(j.tag as u64);
        for a in 0..3 {
            self.ray_o_lo[a].next = bits::<G>(code(r.o_lo[a], G));
            self.ray_o_hi[a].next = bits::<G>(code(r.o_hi[a], G));
            self.ray_d_lo[a].next = bits::<D>(code(r.d_lo[a], D));
            self.ray_d_hi[a].next = bits::<D>(code(r.d_hi[a], D));
            self.o_lo[a].next = bits::<G>(code(b.o_lo[a], G));
            self.o_hi[a].next = bits::<G>(code(b.o_hi[a], G));
            self.d_lo[a].next = bits::<D>(code(b.d_lo[a], D));
            self.d_hi[a].next = bits::<D>(code(b.d_hi[a], D));
            self.in_lo[a].next = bits::<G>(code(p.inner.lo[a], G));
            self.in_hi[a].next = bits::<G>(code(p.inner.hi[a], G));
            self.out_lo[a].next = bits::<G>(code(p.outer.lo[a], G));
            self.out_hi[a].next = bits::<G>(code(p.outer.hi[a], G));
        }
        self.ray_t.next = bits::<T>(code(r.t_hi, T));
        self.ray_t_lo.next = bits::<T>(code(r.t_lo, T));
        self.ray_j.next = bits::<J_BITS>(code(rj as i64, J_BITS));
        self.t_lo.next = bits::<T>(code(b.t_lo, T));
        self.t_hi.next = bits::<T>(code(b.t_hi, T));
    }

    fn outputs(&self) -> StreamOut {
        StreamOut {
            ready: self.ready.val(),
            done: self.done.val(),
            tag: self.done_tag.val().to_u64() as u8,
            all_hit: self.all_hit.val(),
            all_miss: self.all_miss.val(),
            split: self.split.val(),
            mask: self.mask.val().to_u64() as u16,
            rebound: decode_rebound(G, D, T, |base, i| {
                Some(match base {
                    "rb_valid" => self.rb_valid.val() as u64,
                    "rb_o_lo" => self.rb_o_lo[i].val().to_u64(),
                    "rb_o_hi" => self.rb_o_hi[i].val().to_u64(),
                    "rb_d_lo" => self.rb_d_lo[i].val().to_u64(),
                    "rb_d_hi" => self.rb_d_hi[i].val().to_u64(),
                    "rb_t_lo" => self.rb_t_lo.val().to_u64(),
                    "rb_t_hi" => self.rb_t_hi.val().to_u64(),
                    "rb_j" => self.rb_j.val().to_u64(),
                    _ => return None,
                })
            })
            .expect("every re-bounding port"),
        }
    }

    fn decode_out(bf: &BundleFixFormat, word: &dyn Fn(&str) -> Option<u64>) -> Option<StreamOut> {
        let (g, d, t) = (bf.base.g as usize, bf.fd as usize + 3, bf.base.t as usize);
        let rebound = decode_rebound(g, d, t, |base, i| match base {
            "rb_valid" | "rb_t_lo" | "rb_t_hi" | "rb_j" => word(base),
            _ => word(&format!("{base}_{i}")),
        })?;
        Some(StreamOut {
            rebound,
            ..decode_common_out(word)?
        })
    }

    fn in_word(bf: &BundleFixFormat, port: &str, input: &FixStreamIn) -> Option<u64> {
        stream_in_word(bf, port, input)
    }
}
