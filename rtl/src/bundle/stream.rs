//! `BundleStream`: the results processor with jobs in flight, around one fixed-point bundle pair
//! ([`BundleFix`]). A job (a bundle against a node's box pair, with its active rays, ray set and tag) is
//! taken in any clock the pair's input is free; an undecided bundle joins a split queue and its active
//! rays go through the same pair two per clock (two-ray mode), ahead of new bundles; each job leaves with
//! its tag. **Results may leave in another order than the jobs came**: a decided job overtakes split
//! ones; split jobs leave in the order their bundles were answered.
//!
//! Clock for clock `golden::bundle::stream::StreamModel` (ready, done, tag, result, in every clock, for
//! any input); what a job computes is `golden::bundle::split::split_fix` on its rays.
//!
//! # Parameters
//! `G`, `V = G + 1`, `D = FD + 3`, `T`, as [`BundleFix`]; presets [`crate::BundleStreamB8`],
//! [`crate::BundleStreamB12`], [`crate::BundleStreamB16`]. The ray store holds [`STREAM_SETS`] sets of
//! [`STREAM_RAYS`] rays; the split queue [`STREAM_QUEUE`] jobs.
//!
//! # Inputs
//! - `clock`; `rst` (synchronous: high at a clock edge, every job in flight, queued or being split is
//!   dropped and never reports; a `start` in that clock is not taken, a ray store write is; the ray
//!   store and the result registers keep their contents);
//! - ray store write port: `ray_we`, `ray_addr` (6 bits: `[5:4]` the set, `[3:0]` the ray), `ray_o_lo`,
//!   `ray_o_hi`, `ray_d_lo`, `ray_d_hi` (arrays over x, y, z), `ray_t` (the ray's `t_hi`): the ray as a
//!   quantised tiny bundle, as `BundleSplit`'s. Written at the end of the clock, at any time;
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
//!   `all_hit`, `all_miss`, `split`, `mask` (16 bits, bit `i`: ray `i` may hit), as `BundleSplit`'s.
//!
//! # Sequencing (`L` = [`BUNDLE_FIX_LATENCY`] = 3)
//! ```text
//! s           start taken: the bundle enters the pair; tag, active, set, outer box enter a delay line
//! s+L         the answer: decided, or no active ray -> done in s+L+1; undecided -> split queue
//! then        the engine takes the queue's head (in the clock it addresses its previous job's last
//!             pair, or when idle), addresses two rays a clock (bank A: ray A, bank B: ray B, address
//!             {set, ray}), each pair entering the pair in the next clock with the job's outer box
//! +L          each pair's answer, ORed into the accumulator; the job's last pair -> done next clock
//! ```
//! A decided job reports `L + 1` clocks after its start; a split job of `k` pair clocks no earlier
//! than `2L + 3 + k`. Every input of the pair comes from a port, a register or a RAM output, as in
//! `BundleSplit`.
//!
//! # Structure
//! Delay lines ([`Delay3`]) carry each entry's tag, active mask, set and outer box beside the pair; the
//! pair's 16-bit tag carries, for a ray pair, `[3:0]` ray A, `[7:4]` ray B, bit 8 B present, `[15:9]`
//! the kind (0 a bundle, 1 a ray pair, 2 a job's last pair). The split queue is a register file of
//! [`STREAM_QUEUE`] entries with head and tail pointers; `resv_q` counts the queue plus the bundles in
//! the pair, and `ready` needs `resv_q < STREAM_QUEUE`, so the queue cannot overflow.

use crate::bundle::pair_fix::{BundleFix, BUNDLE_FIX_LATENCY};
use crate::bundle::ray_store::{ray_job_word, RayStore};
use crate::delay::Delay3;
use crate::export::verilog_named;
use crate::slab::fix::{code, TAG_BITS};
use golden::bundle::fix::{BundleFixFormat, FixBundle};
use golden::bundle::stream::{
    StreamIn, StreamJob, StreamOut, STREAM_QUEUE, STREAM_RAYS, STREAM_SETS, STREAM_TAG_BITS,
};
use golden::format::fixed::FixBox;
use rust_hdl::prelude::*;

/// Address bits of the ray store: `{set, ray}`.
pub const STREAM_ADDR_BITS: usize = 6;
const SET_BITS: usize = 2;
const QPTR_BITS: usize = 3;
const QCOUNT_BITS: usize = 4;
const _: () = assert!(BUNDLE_FIX_LATENCY == 3, "the delay lines are Delay3");
const _: () = assert!(STREAM_SETS == 1 << SET_BITS && STREAM_RAYS == 16);
const _: () = assert!(STREAM_QUEUE == 1 << QPTR_BITS && STREAM_QUEUE < 1 << QCOUNT_BITS);

/// Kinds in the pair's tag `[15:9]`: 1 a ray pair, 2 a job's last pair (0 a bundle).
const KIND_RAYS: u64 = 1;
const KIND_LAST: u64 = 2;
const TAG_B: u64 = 1 << 8;

/// A fixed job on the job port.
pub type FixStreamJob = StreamJob<FixBundle, FixBox>;
/// A clock's inputs of the fixed processor.
pub type FixStreamIn = StreamIn<FixBundle, FixBox>;

/// The streaming results processor; see the module documentation.
#[derive(LogicBlock)]
pub struct BundleStream<const G: usize, const V: usize, const D: usize, const T: usize> {
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
    // the pair and the ray store (bank A: ray A, bank B: ray B)
    pair: BundleFix<G, V, D, T>,
    store: RayStore<G, D, T, STREAM_ADDR_BITS>,
    // the delay line beside the pair
    l_tag: Delay3<Bits<STREAM_TAG_BITS>>,
    l_active: Delay3<Bits<STREAM_RAYS>>,
    l_set: Delay3<Bits<SET_BITS>>,
    l_lo: [Delay3<Bits<G>>; 3],
    l_hi: [Delay3<Bits<G>>; 3],
    // the split queue
    q_tag: [DFF<Bits<STREAM_TAG_BITS>>; STREAM_QUEUE],
    q_active: [DFF<Bits<STREAM_RAYS>>; STREAM_QUEUE],
    q_set: [DFF<Bits<SET_BITS>>; STREAM_QUEUE],
    /// Entry `k`'s outer box, axis `i`, at `3k + i`.
    q_lo: [DFF<Bits<G>>; 24],
    q_hi: [DFF<Bits<G>>; 24],
    head_q: DFF<Bits<QPTR_BITS>>,
    tail_q: DFF<Bits<QPTR_BITS>>,
    count_q: DFF<Bits<QCOUNT_BITS>>,
    /// Queued jobs plus bundles in the pair.
    resv_q: DFF<Bits<QCOUNT_BITS>>,
    // the engine's job
    e_busy_q: DFF<Bit>,
    rem_q: DFF<Bits<STREAM_RAYS>>,
    e_set_q: DFF<Bits<SET_BITS>>,
    e_tag_q: DFF<Bits<STREAM_TAG_BITS>>,
    e_lo_q: [DFF<Bits<G>>; 3],
    e_hi_q: [DFF<Bits<G>>; 3],
    // the pair issued in this clock
    issue_q: DFF<Bit>,
    issue_tag_q: DFF<Bits<TAG_BITS>>,
    issue_utag_q: DFF<Bits<STREAM_TAG_BITS>>,
    issue_lo_q: [DFF<Bits<G>>; 3],
    issue_hi_q: [DFF<Bits<G>>; 3],
    acc_q: DFF<Bits<STREAM_RAYS>>,
    // result registers
    done_q: DFF<Bit>,
    done_tag_q: DFF<Bits<STREAM_TAG_BITS>>,
    all_hit_q: DFF<Bit>,
    all_miss_q: DFF<Bit>,
    split_q: DFF<Bit>,
    mask_q: DFF<Bits<STREAM_RAYS>>,
    // constants
    one16: Constant<Bits<STREAM_RAYS>>,
    zero16: Constant<Bits<STREAM_RAYS>>,
    one_q: Constant<Bits<QPTR_BITS>>,
    one_c: Constant<Bits<QCOUNT_BITS>>,
    zero_c: Constant<Bits<QCOUNT_BITS>>,
    full_c: Constant<Bits<QCOUNT_BITS>>,
    /// Set `k`, and its first address.
    set_k: [Constant<Bits<SET_BITS>>; STREAM_SETS],
    base_k: [Constant<Bits<STREAM_ADDR_BITS>>; STREAM_SETS],
    /// `k` as a queue index.
    slot_k: [Constant<Bits<QPTR_BITS>>; STREAM_QUEUE],
    /// `k` as a ray index in a store address.
    addr_k: [Constant<Bits<STREAM_ADDR_BITS>>; STREAM_RAYS],
    tag_ak: [Constant<Bits<TAG_BITS>>; STREAM_RAYS],
    tag_bk: [Constant<Bits<TAG_BITS>>; STREAM_RAYS],
    tag_b: Constant<Bits<TAG_BITS>>,
    tag_ray: Constant<Bits<TAG_BITS>>,
    tag_last: Constant<Bits<TAG_BITS>>,
    zero_tag: Constant<Bits<TAG_BITS>>,
    kind_bundle: Constant<Bits<7>>,
    kind_last: Constant<Bits<7>>,
    // logic
    take: Signal<Local, Bit>,
    head_tag: Signal<Local, Bits<STREAM_TAG_BITS>>,
    head_active: Signal<Local, Bits<STREAM_RAYS>>,
    head_set: Signal<Local, Bits<SET_BITS>>,
    head_lo: [Signal<Local, Bits<G>>; 3],
    head_hi: [Signal<Local, Bits<G>>; 3],
    hot_a: Signal<Local, Bits<STREAM_RAYS>>,
    rem_b: Signal<Local, Bits<STREAM_RAYS>>,
    hot_b: Signal<Local, Bits<STREAM_RAYS>>,
    rem_next: Signal<Local, Bits<STREAM_RAYS>>,
    set_base: Signal<Local, Bits<STREAM_ADDR_BITS>>,
    addr_a: Signal<Local, Bits<STREAM_ADDR_BITS>>,
    addr_b: Signal<Local, Bits<STREAM_ADDR_BITS>>,
    tag_a: Signal<Local, Bits<TAG_BITS>>,
    tag_bb: Signal<Local, Bits<TAG_BITS>>,
    tag_flags: Signal<Local, Bits<TAG_BITS>>,
    last_addr: Signal<Local, Bit>,
    load: Signal<Local, Bit>,
    ret_kind: Signal<Local, Bits<7>>,
    bundle_back: Signal<Local, Bit>,
    rays_back: Signal<Local, Bit>,
    last_back: Signal<Local, Bit>,
    decided: Signal<Local, Bit>,
    finish_bundle: Signal<Local, Bit>,
    push: Signal<Local, Bit>,
    got_a: Signal<Local, Bits<STREAM_RAYS>>,
    got_b: Signal<Local, Bits<STREAM_RAYS>>,
    count_a: Signal<Local, Bits<QCOUNT_BITS>>,
    resv_a: Signal<Local, Bits<QCOUNT_BITS>>,
    resv_b: Signal<Local, Bits<QCOUNT_BITS>>,
    ready_l: Signal<Local, Bit>,
}

impl<const G: usize, const V: usize, const D: usize, const T: usize> BundleStream<G, V, D, T> {
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
            pair: BundleFix::new(bf),
            store: Default::default(),
            l_tag: Default::default(),
            l_active: Default::default(),
            l_set: Default::default(),
            l_lo: Default::default(),
            l_hi: Default::default(),
            q_tag: Default::default(),
            q_active: Default::default(),
            q_set: Default::default(),
            q_lo: Default::default(),
            q_hi: Default::default(),
            head_q: Default::default(),
            tail_q: Default::default(),
            count_q: Default::default(),
            resv_q: Default::default(),
            e_busy_q: Default::default(),
            rem_q: Default::default(),
            e_set_q: Default::default(),
            e_tag_q: Default::default(),
            e_lo_q: Default::default(),
            e_hi_q: Default::default(),
            issue_q: Default::default(),
            issue_tag_q: Default::default(),
            issue_utag_q: Default::default(),
            issue_lo_q: Default::default(),
            issue_hi_q: Default::default(),
            acc_q: Default::default(),
            done_q: Default::default(),
            done_tag_q: Default::default(),
            all_hit_q: Default::default(),
            all_miss_q: Default::default(),
            split_q: Default::default(),
            mask_q: Default::default(),
            one16: Constant::new(bits(1)),
            zero16: Constant::new(bits(0)),
            one_q: Constant::new(bits(1)),
            one_c: Constant::new(bits(1)),
            zero_c: Constant::new(bits(0)),
            full_c: Constant::new(bits(STREAM_QUEUE as u64)),
            set_k: std::array::from_fn(|k| Constant::new(bits(k as u64))),
            base_k: std::array::from_fn(|k| Constant::new(bits((k * STREAM_RAYS) as u64))),
            slot_k: std::array::from_fn(|k| Constant::new(bits(k as u64))),
            addr_k: std::array::from_fn(|k| Constant::new(bits(k as u64))),
            tag_ak: std::array::from_fn(|k| Constant::new(bits(k as u64))),
            tag_bk: std::array::from_fn(|k| Constant::new(bits((k as u64) << 4))),
            tag_b: Constant::new(bits(TAG_B)),
            tag_ray: Constant::new(bits(KIND_RAYS << 9)),
            tag_last: Constant::new(bits(KIND_LAST << 9)),
            zero_tag: Constant::new(bits(0)),
            kind_bundle: Constant::new(bits(0)),
            kind_last: Constant::new(bits(KIND_LAST)),
            take: Default::default(),
            head_tag: Default::default(),
            head_active: Default::default(),
            head_set: Default::default(),
            head_lo: Default::default(),
            head_hi: Default::default(),
            hot_a: Default::default(),
            rem_b: Default::default(),
            hot_b: Default::default(),
            rem_next: Default::default(),
            set_base: Default::default(),
            addr_a: Default::default(),
            addr_b: Default::default(),
            tag_a: Default::default(),
            tag_bb: Default::default(),
            tag_flags: Default::default(),
            last_addr: Default::default(),
            load: Default::default(),
            ret_kind: Default::default(),
            bundle_back: Default::default(),
            rays_back: Default::default(),
            last_back: Default::default(),
            decided: Default::default(),
            finish_bundle: Default::default(),
            push: Default::default(),
            got_a: Default::default(),
            got_b: Default::default(),
            count_a: Default::default(),
            resv_a: Default::default(),
            resv_b: Default::default(),
            ready_l: Default::default(),
        }
    }
}

impl<const G: usize, const V: usize, const D: usize, const T: usize> Logic
    for BundleStream<G, V, D, T>
{
    #[hdl_gen]
    fn update(&mut self) {
        // Clocks.
        self.pair.clock.next = self.clock.val();
        self.pair.rst.next = self.rst.val();
        self.l_tag.clock.next = self.clock.val();
        self.l_active.clock.next = self.clock.val();
        self.l_set.clock.next = self.clock.val();
        for i in 0..3 {
            self.l_lo[i].clock.next = self.clock.val();
            self.l_hi[i].clock.next = self.clock.val();
            self.e_lo_q[i].clock.next = self.clock.val();
            self.e_hi_q[i].clock.next = self.clock.val();
            self.issue_lo_q[i].clock.next = self.clock.val();
            self.issue_hi_q[i].clock.next = self.clock.val();
        }
        for k in 0..8 {
            self.q_tag[k].clock.next = self.clock.val();
            self.q_active[k].clock.next = self.clock.val();
            self.q_set[k].clock.next = self.clock.val();
        }
        for k in 0..24 {
            self.q_lo[k].clock.next = self.clock.val();
            self.q_hi[k].clock.next = self.clock.val();
        }
        dff_setup!(
            self,
            clock,
            head_q,
            tail_q,
            count_q,
            resv_q,
            e_busy_q,
            rem_q,
            e_set_q,
            e_tag_q,
            issue_q,
            issue_tag_q,
            issue_utag_q,
            acc_q,
            done_q,
            done_tag_q,
            all_hit_q,
            all_miss_q,
            split_q,
            mask_q
        );

        // The ray store: both banks written together (read below, after the addresses are formed).
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

        // Taking a job: no ray pair this clock and room in the split queue for every bundle in flight.
        self.ready_l.next = !self.issue_q.q.val() & (self.resv_q.q.val() < self.full_c.val());
        self.take.next = self.start.val() & self.ready_l.val() & !self.rst.val();

        // The pair's inputs, from ports, registers and the ray store only: a ray pair when issue_q,
        // else the bundle of a start.
        self.pair.valid_in.next = self.issue_q.q.val() | self.take.val();
        self.pair.two_rays.next = self.issue_q.q.val();
        self.pair.t_lo.next = self.t_lo.val();
        if self.issue_q.q.val() {
            self.pair.tag_in.next = self.issue_tag_q.q.val();
            self.pair.t_hi.next = self.store.a_t.val();
        } else {
            self.pair.tag_in.next = self.zero_tag.val();
            self.pair.t_hi.next = self.t_hi.val();
        }
        self.pair.r_t.next = self.store.b_t.val();
        for i in 0..3 {
            if self.issue_q.q.val() {
                self.pair.o_lo[i].next = self.store.a_o_lo[i].val();
                self.pair.o_hi[i].next = self.store.a_o_hi[i].val();
                self.pair.d_lo[i].next = self.store.a_d_lo[i].val();
                self.pair.d_hi[i].next = self.store.a_d_hi[i].val();
                self.pair.out_lo[i].next = self.issue_lo_q[i].q.val();
                self.pair.out_hi[i].next = self.issue_hi_q[i].q.val();
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

        // The delay line beside the pair: the entry's tag; a bundle's active mask, set and outer box.
        if self.issue_q.q.val() {
            self.l_tag.d.next = self.issue_utag_q.q.val();
        } else {
            self.l_tag.d.next = self.tag.val();
        }
        self.l_active.d.next = self.active.val();
        self.l_set.d.next = self.job_set.val();
        for i in 0..3 {
            self.l_lo[i].d.next = self.out_lo[i].val();
            self.l_hi[i].d.next = self.out_hi[i].val();
        }

        // What the pair answers this clock.
        self.ret_kind.next = self.pair.tag_out.val().get_bits::<7>(9);
        self.bundle_back.next =
            self.pair.valid_out.val() & (self.ret_kind.val() == self.kind_bundle.val());
        self.rays_back.next =
            self.pair.valid_out.val() & (self.ret_kind.val() != self.kind_bundle.val());
        self.last_back.next =
            self.pair.valid_out.val() & (self.ret_kind.val() == self.kind_last.val());
        self.decided.next = self.pair.all_hit.val() | self.pair.all_miss.val();
        self.finish_bundle.next =
            self.bundle_back.val() & (self.decided.val() | !self.l_active.q.val().any());
        self.push.next = self.bundle_back.val() & !self.decided.val() & self.l_active.q.val().any();
        // Two-ray mode: all_hit = ray A may hit, all_miss = ray B misses.
        if self.pair.all_hit.val() {
            self.got_a.next = self.one16.val() << self.pair.tag_out.val().get_bits::<4>(0);
        } else {
            self.got_a.next = self.zero16.val();
        }
        if !self.pair.all_miss.val() & self.pair.tag_out.val().get_bit(8) {
            self.got_b.next = self.one16.val() << self.pair.tag_out.val().get_bits::<4>(4);
        } else {
            self.got_b.next = self.zero16.val();
        }

        // The queue's head.
        self.head_tag.next = self.q_tag[0].q.val();
        self.head_active.next = self.q_active[0].q.val();
        self.head_set.next = self.q_set[0].q.val();
        for i in 0..3 {
            self.head_lo[i].next = self.q_lo[i].q.val();
            self.head_hi[i].next = self.q_hi[i].q.val();
        }
        for k in 1..8 {
            if self.head_q.q.val() == self.slot_k[k].val() {
                self.head_tag.next = self.q_tag[k].q.val();
                self.head_active.next = self.q_active[k].q.val();
                self.head_set.next = self.q_set[k].q.val();
                for i in 0..3 {
                    self.head_lo[i].next = self.q_lo[3 * k + i].q.val();
                    self.head_hi[i].next = self.q_hi[3 * k + i].q.val();
                }
            }
        }

        // The engine: the next two rays of its job, as one-hot masks, store addresses and tag fields.
        self.hot_a.next = self.rem_q.q.val() & (!self.rem_q.q.val() + self.one16.val());
        self.rem_b.next = self.rem_q.q.val() & !self.hot_a.val();
        self.hot_b.next = self.rem_b.val() & (!self.rem_b.val() + self.one16.val());
        self.rem_next.next = self.rem_b.val() & !self.hot_b.val();
        self.set_base.next = self.base_k[0].val();
        for k in 0..4 {
            if self.e_set_q.q.val() == self.set_k[k].val() {
                self.set_base.next = self.base_k[k].val();
            }
        }
        self.addr_a.next = self.set_base.val();
        self.addr_b.next = self.set_base.val();
        self.tag_a.next = self.zero_tag.val();
        self.tag_bb.next = self.zero_tag.val();
        for k in 0..16 {
            if self.hot_a.val().get_bit(k) {
                self.addr_a.next = self.set_base.val() | self.addr_k[k].val();
                self.tag_a.next = self.tag_ak[k].val();
            }
            if self.hot_b.val().get_bit(k) {
                self.addr_b.next = self.set_base.val() | self.addr_k[k].val();
                self.tag_bb.next = self.tag_bk[k].val();
            }
        }
        self.store.addr_a.next = self.addr_a.val();
        self.store.addr_b.next = self.addr_b.val();
        if self.hot_b.val().any() {
            if self.rem_next.val().any() {
                self.tag_flags.next = self.tag_ray.val() | self.tag_b.val();
            } else {
                self.tag_flags.next = self.tag_b.val() | self.tag_last.val();
            }
        } else {
            self.tag_flags.next = self.tag_last.val();
        }
        self.last_addr.next = self.e_busy_q.q.val() & !self.rem_next.val().any();
        self.load.next =
            self.count_q.q.val().any() & (!self.e_busy_q.q.val() | self.last_addr.val());

        // Registers: hold by default.
        self.head_q.d.next = self.head_q.q.val();
        self.tail_q.d.next = self.tail_q.q.val();
        self.e_busy_q.d.next = self.e_busy_q.q.val();
        self.rem_q.d.next = self.rem_q.q.val();
        self.e_set_q.d.next = self.e_set_q.q.val();
        self.e_tag_q.d.next = self.e_tag_q.q.val();
        for i in 0..3 {
            self.e_lo_q[i].d.next = self.e_lo_q[i].q.val();
            self.e_hi_q[i].d.next = self.e_hi_q[i].q.val();
            self.issue_lo_q[i].d.next = self.e_lo_q[i].q.val();
            self.issue_hi_q[i].d.next = self.e_hi_q[i].q.val();
        }
        for k in 0..8 {
            self.q_tag[k].d.next = self.q_tag[k].q.val();
            self.q_active[k].d.next = self.q_active[k].q.val();
            self.q_set[k].d.next = self.q_set[k].q.val();
        }
        for k in 0..24 {
            self.q_lo[k].d.next = self.q_lo[k].q.val();
            self.q_hi[k].d.next = self.q_hi[k].q.val();
        }
        self.issue_q.d.next = self.e_busy_q.q.val();
        self.issue_tag_q.d.next = self.tag_a.val() | self.tag_bb.val() | self.tag_flags.val();
        self.issue_utag_q.d.next = self.e_tag_q.q.val();
        self.acc_q.d.next = self.acc_q.q.val();
        self.done_q.d.next = false;
        self.done_tag_q.d.next = self.done_tag_q.q.val();
        self.all_hit_q.d.next = self.all_hit_q.q.val();
        self.all_miss_q.d.next = self.all_miss_q.q.val();
        self.split_q.d.next = self.split_q.q.val();
        self.mask_q.d.next = self.mask_q.q.val();

        // The engine addresses its job's next pair, and takes the queue's head when free.
        if self.e_busy_q.q.val() {
            self.rem_q.d.next = self.rem_next.val();
            if self.last_addr.val() {
                self.e_busy_q.d.next = false;
            }
        }
        if self.load.val() {
            self.e_busy_q.d.next = true;
            self.rem_q.d.next = self.head_active.val();
            self.e_set_q.d.next = self.head_set.val();
            self.e_tag_q.d.next = self.head_tag.val();
            for i in 0..3 {
                self.e_lo_q[i].d.next = self.head_lo[i].val();
                self.e_hi_q[i].d.next = self.head_hi[i].val();
            }
            self.head_q.d.next = self.head_q.q.val() + self.one_q.val();
        }
        // An undecided bundle joins the queue.
        if self.push.val() {
            self.tail_q.d.next = self.tail_q.q.val() + self.one_q.val();
            for k in 0..8 {
                if self.tail_q.q.val() == self.slot_k[k].val() {
                    self.q_tag[k].d.next = self.l_tag.q.val();
                    self.q_active[k].d.next = self.l_active.q.val();
                    self.q_set[k].d.next = self.l_set.q.val();
                    for i in 0..3 {
                        self.q_lo[3 * k + i].d.next = self.l_lo[i].q.val();
                        self.q_hi[3 * k + i].d.next = self.l_hi[i].q.val();
                    }
                }
            }
        }
        self.count_a.next = self.count_q.q.val();
        if self.push.val() {
            self.count_a.next = self.count_q.q.val() + self.one_c.val();
        }
        self.count_q.d.next = self.count_a.val();
        if self.load.val() {
            self.count_q.d.next = self.count_a.val() - self.one_c.val();
        }
        self.resv_a.next = self.resv_q.q.val();
        if self.take.val() {
            self.resv_a.next = self.resv_q.q.val() + self.one_c.val();
        }
        self.resv_b.next = self.resv_a.val();
        if self.load.val() {
            self.resv_b.next = self.resv_a.val() - self.one_c.val();
        }
        self.resv_q.d.next = self.resv_b.val();
        if self.finish_bundle.val() {
            self.resv_q.d.next = self.resv_b.val() - self.one_c.val();
        }

        // Results.
        if self.rays_back.val() {
            self.acc_q.d.next = self.acc_q.q.val() | self.got_a.val() | self.got_b.val();
        }
        if self.finish_bundle.val() {
            self.done_q.d.next = true;
            self.done_tag_q.d.next = self.l_tag.q.val();
            self.all_hit_q.d.next = self.pair.all_hit.val();
            self.all_miss_q.d.next = self.pair.all_miss.val();
            self.split_q.d.next = !self.decided.val();
            if self.pair.all_hit.val() {
                self.mask_q.d.next = self.l_active.q.val();
            } else {
                self.mask_q.d.next = self.zero16.val();
            }
        }
        if self.last_back.val() {
            self.acc_q.d.next = self.zero16.val();
            self.done_q.d.next = true;
            self.done_tag_q.d.next = self.l_tag.q.val();
            self.all_hit_q.d.next = false;
            self.all_miss_q.d.next = false;
            self.split_q.d.next = true;
            self.mask_q.d.next = self.acc_q.q.val() | self.got_a.val() | self.got_b.val();
        }

        if self.rst.val() {
            self.head_q.d.next = self.slot_k[0].val();
            self.tail_q.d.next = self.slot_k[0].val();
            self.count_q.d.next = self.zero_c.val();
            self.resv_q.d.next = self.zero_c.val();
            self.e_busy_q.d.next = false;
            self.issue_q.d.next = false;
            self.acc_q.d.next = self.zero16.val();
            self.done_q.d.next = false;
        }

        self.ready.next = self.ready_l.val();
        self.done.next = self.done_q.q.val();
        self.done_tag.next = self.done_tag_q.q.val();
        self.all_hit.next = self.all_hit_q.q.val();
        self.all_miss.next = self.all_miss_q.q.val();
        self.split.next = self.split_q.q.val();
        self.mask.next = self.mask_q.q.val();
    }
}

/// Module name of the streaming processor for a format, e.g. `bundle_stream_g12_i16f11_t20f6_d10_n16x4`.
pub fn bundle_stream_module(bf: &BundleFixFormat) -> String {
    format!("bundle_stream_{}_n{STREAM_RAYS}x{STREAM_SETS}", bf.name())
}

/// `(module, Verilog, clocks of a decided job)` of the streaming processor over the presets b12 and b16
/// (for `crate::export::export_all`).
pub fn bundle_stream_verilog() -> Vec<(String, String, usize)> {
    let [_, b12, b16] = BundleFixFormat::presets();
    let decided = BUNDLE_FIX_LATENCY + 1;
    vec![
        (
            bundle_stream_module(&b12),
            verilog_named(
                &mut crate::BundleStreamB12::new(&b12),
                &bundle_stream_module(&b12),
            ),
            decided,
        ),
        (
            bundle_stream_module(&b16),
            verilog_named(
                &mut crate::BundleStreamB16::new(&b16),
                &bundle_stream_module(&b16),
            ),
            decided,
        ),
    ]
}

/// A streaming processor of any width, seen from a testbench.
pub trait BundleStreamIo: Block {
    /// The block for `bf` (whose widths must match the block's).
    fn for_format(bf: &BundleFixFormat) -> Self;
    /// Sets the clock input.
    fn set_clock(&mut self, high: bool);
    /// Drives one clock's inputs (data ports of an absent write or start are driven to zero).
    fn drive(&mut self, input: &FixStreamIn);
    /// Reads the outputs.
    fn outputs(&self) -> StreamOut;
}

/// The value of output port `port` (its Verilog name) in `o`.
pub fn stream_out_word(o: &StreamOut, port: &str) -> Option<u64> {
    Some(match port {
        "ready" => o.ready as u64,
        "done" => o.done as u64,
        "done_tag" => o.tag as u64,
        "all_hit" => o.all_hit as u64,
        "all_miss" => o.all_miss as u64,
        "split" => o.split as u64,
        "mask" => o.mask as u64,
        _ => return None,
    })
}

/// The value of input port `port` (a Verilog name such as `ray_d_lo_1`) in one clock, for a processor
/// over `bf`.
pub fn stream_in_word(bf: &BundleFixFormat, port: &str, input: &FixStreamIn) -> Option<u64> {
    let (base, idx) = crate::export::split_port(port);
    let (set, ray, r) = input.write.unwrap_or_default();
    let j = input.start.unwrap_or_default();
    Some(match base {
        "rst" => input.reset as u64,
        "ray_we" => input.write.is_some() as u64,
        "ray_addr" => ((set as u64 % STREAM_SETS as u64) << 4) | (ray as u64 % STREAM_RAYS as u64),
        "start" => input.start.is_some() as u64,
        "active" => j.active as u64,
        "job_set" => j.set as u64 % STREAM_SETS as u64,
        "tag" => j.tag as u64,
        _ => return ray_job_word(bf, base, idx.unwrap_or(0), &r, &j.bundle, &j.boxes),
    })
}

impl<const G: usize, const V: usize, const D: usize, const T: usize> BundleStreamIo
    for BundleStream<G, V, D, T>
{
    fn for_format(bf: &BundleFixFormat) -> Self {
        Self::new(bf)
    }

    fn set_clock(&mut self, high: bool) {
        self.clock.next = Clock { clk: high };
    }

    fn drive(&mut self, input: &FixStreamIn) {
        let (set, ray, r) = input.write.unwrap_or_default();
        self.rst.next = input.reset;
        self.ray_we.next = input.write.is_some();
        self.ray_addr.next = bits::<STREAM_ADDR_BITS>(
            ((set as u64 % STREAM_SETS as u64) << 4) | (ray as u64 % STREAM_RAYS as u64),
        );
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
        }
    }
}
