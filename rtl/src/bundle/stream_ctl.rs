//! `StreamCtl`: the control of the streaming results processor, the same for every datapath of the
//! pair ([`crate::bundle::stream::BundleStream`] around the fixed pair,
//! [`crate::bundle::stream_float::BundleStreamFloat`] around the float pair). It decides what enters the
//! pair in each clock (a new job's bundle or a ray pair of a split job), keeps the side data of every
//! entry beside the pair for the pair's latency, queues the undecided bundles, walks a split job's
//! active rays two per clock (the ray store's read addresses), gathers the ray answers and reports each
//! job with its tag. It never sees a bundle or a ray: the datapath block wires the job port, the ray
//! store and the pair around it.
//!
//! Clock for clock `golden::bundle::stream::StreamModel` (through the datapath block).
//!
//! # Parameters
//! `C`: the width of a box coordinate (the outer box rides beside the pair and waits in the queue);
//! the pair's latency `L` is given to [`StreamCtl::new`] (at most [`crate::cut::MAX_LINE`]).
//!
//! # Inputs
//! - `clock`, `rst` (synchronous: drops every job in flight, queued, being split or in the report
//!   stage);
//! - the job port's control: `start`, `active` (16 bits), `job_set` (2 bits), `tag` (8 bits), and the
//!   job's outer box `out_lo`, `out_hi` (arrays over x, y, z), sampled when the job is taken;
//! - the pair's answer: `p_valid`, `p_tag` (the pair's 16-bit tag), `p_all_hit`, `p_all_miss`.
//!
//! # Outputs
//! - to the pair: `take` (the job port's bundle enters the pair this clock), `issue` (a ray pair enters
//!   it, the rays read from the store's banks in the previous clock), `issue_tag` (the pair's tag for
//!   either: 0 for a bundle), `issue_lo`, `issue_hi` (the outer box of the ray pair);
//! - to the ray store: `addr_a`, `addr_b` (`{set, ray}` of the next ray pair, read at the clock edge);
//! - `ready`, `done`, `done_tag`, `all_hit`, `all_miss`, `split`, `mask`: the processor's result ports
//!   (see [`crate::bundle::stream::BundleStream`]): a job answered in a clock is loaded into the report
//!   stage's registers and moves on to the result registers in the next clock, so `done` is high two
//!   clocks after the answer (the clock between lets the gatherer fold the answer from registers);
//! - the pair's answer in this clock, decoded: `ans_rays` (a ray pair's), `ans_keep_a`, `ans_keep_b`
//!   (ray A, ray B present and may hit), `ans_last` (a job's last pair's), `ans_done` (a bundle's that
//!   reports without a split), for [`crate::bundle::rebound::ReboundAcc`].
//!
//! # Structure
//! Delay lines ([`Line`], `L` clocks) carry each entry's tag, active mask, set and outer box beside the
//! pair; the pair's 16-bit tag carries, for a ray pair, `[3:0]` ray A, `[7:4]` ray B, bit 8 B present,
//! `[15:9]` the kind (0 a bundle, 1 a ray pair, 2 a job's last pair). The split queue is a register file
//! of [`STREAM_QUEUE`] entries with head and tail pointers; `resv_q` counts the queue plus the bundles in
//! the pair, and `ready` needs `resv_q < STREAM_QUEUE`, so the queue cannot overflow. The engine holds
//! one job: each clock it addresses the next two active rays and loads the queue's head in the clock it
//! addresses its job's last pair (or when idle). The pair it addresses is held in registers as one-hot
//! masks, picked a clock ahead from the job's remaining rays or, when it loads, taken from the queue's
//! head, whose active rays were split into their first pair and the rest when the bundle joined the
//! queue. So the store's read addresses decode registers, and the find-first-set chains end at
//! registers, never at the store or behind the queue's read (those paths limited the processors over
//! the deep pairs on ECP5, at 82.3 MHz for b12 over the 5-clock pair and 75.2 for fp16 over the 13-clock
//! one). Every input of the pair the datapath block forms from these outputs comes from a port, a
//! register or a RAM output.

use crate::cut::Line;
use crate::TAG_BITS;
use golden::bundle::stream::{
    stream_queue, STREAM_QUEUE, STREAM_RAYS, STREAM_SETS, STREAM_TAG_BITS,
};
use rust_hdl::prelude::*;

/// Address bits of the ray store: `{set, ray}`.
pub const STREAM_ADDR_BITS: usize = 6;
/// Bits of the `job_set` port.
pub const SET_BITS: usize = 2;
const _: () = assert!(STREAM_SETS == 1 << SET_BITS && STREAM_RAYS == 16);
const _: () = assert!(STREAM_QUEUE == 8);

/// The control with the 8-entry split queue (pairs of up to 7 clocks, [`stream_queue`]).
pub type StreamCtl8<const C: usize> = StreamCtl<C, 8, 24, 3, 4>;
/// The control with a 16-entry split queue (pairs of 8 to 15 clocks).
pub type StreamCtl16<const C: usize> = StreamCtl<C, 16, 48, 4, 5>;

/// Kinds in the pair's tag `[15:9]`: 1 a ray pair, 2 a job's last pair (0 a bundle).
const KIND_RAYS: u64 = 1;
const KIND_LAST: u64 = 2;
const TAG_B: u64 = 1 << 8;

/// The processor's control; see the module documentation. `Q` queue entries (a power of two,
/// [`stream_queue`] of the pair's latency), `Q3 = 3Q`, `PB = log2(Q)` pointer bits, `CB = PB + 1`
/// count bits; presets [`StreamCtl8`], [`StreamCtl16`].
#[derive(LogicBlock)]
pub struct StreamCtl<
    const C: usize,
    const Q: usize,
    const Q3: usize,
    const PB: usize,
    const CB: usize,
> {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub start: Signal<In, Bit>,
    pub active: Signal<In, Bits<STREAM_RAYS>>,
    pub job_set: Signal<In, Bits<SET_BITS>>,
    pub tag: Signal<In, Bits<STREAM_TAG_BITS>>,
    pub out_lo: [Signal<In, Bits<C>>; 3],
    pub out_hi: [Signal<In, Bits<C>>; 3],
    pub p_valid: Signal<In, Bit>,
    pub p_tag: Signal<In, Bits<TAG_BITS>>,
    pub p_all_hit: Signal<In, Bit>,
    pub p_all_miss: Signal<In, Bit>,
    // to the pair and the ray store
    pub take: Signal<Out, Bit>,
    pub issue: Signal<Out, Bit>,
    pub issue_tag: Signal<Out, Bits<TAG_BITS>>,
    pub issue_lo: [Signal<Out, Bits<C>>; 3],
    pub issue_hi: [Signal<Out, Bits<C>>; 3],
    pub addr_a: Signal<Out, Bits<STREAM_ADDR_BITS>>,
    pub addr_b: Signal<Out, Bits<STREAM_ADDR_BITS>>,
    // results
    pub ready: Signal<Out, Bit>,
    pub done: Signal<Out, Bit>,
    pub done_tag: Signal<Out, Bits<STREAM_TAG_BITS>>,
    pub all_hit: Signal<Out, Bit>,
    pub all_miss: Signal<Out, Bit>,
    pub split: Signal<Out, Bit>,
    pub mask: Signal<Out, Bits<STREAM_RAYS>>,
    // the pair's answer in this clock, decoded (for re-bounding)
    pub ans_rays: Signal<Out, Bit>,
    pub ans_keep_a: Signal<Out, Bit>,
    pub ans_keep_b: Signal<Out, Bit>,
    pub ans_last: Signal<Out, Bit>,
    pub ans_done: Signal<Out, Bit>,
    // the delay lines beside the pair
    l_tag: Line<Bits<STREAM_TAG_BITS>>,
    l_active: Line<Bits<STREAM_RAYS>>,
    l_set: Line<Bits<SET_BITS>>,
    l_lo: [Line<Bits<C>>; 3],
    l_hi: [Line<Bits<C>>; 3],
    // the split queue
    q_tag: [DFF<Bits<STREAM_TAG_BITS>>; Q],
    /// Entry `k`'s active rays as the engine takes them: its first pair (one-hot masks, B empty when
    /// there is none) and the rays after it, split when the bundle joins the queue.
    q_hot_a: [DFF<Bits<STREAM_RAYS>>; Q],
    q_hot_b: [DFF<Bits<STREAM_RAYS>>; Q],
    q_rest: [DFF<Bits<STREAM_RAYS>>; Q],
    q_set: [DFF<Bits<SET_BITS>>; Q],
    /// Entry `k`'s outer box, axis `i`, at `3k + i`.
    q_lo: [DFF<Bits<C>>; Q3],
    q_hi: [DFF<Bits<C>>; Q3],
    head_q: DFF<Bits<PB>>,
    tail_q: DFF<Bits<PB>>,
    count_q: DFF<Bits<CB>>,
    /// Queued jobs plus bundles in the pair.
    resv_q: DFF<Bits<CB>>,
    // the engine's job
    e_busy_q: DFF<Bit>,
    /// The pair the engine addresses this clock, as one-hot masks (ray B's empty when there is none),
    /// and the job's active rays after it: registered so that the store's addresses come straight from
    /// registers (the next pair is picked a clock ahead, from `rem_q` or the queue's head's split).
    hot_a_q: DFF<Bits<STREAM_RAYS>>,
    hot_b_q: DFF<Bits<STREAM_RAYS>>,
    rem_q: DFF<Bits<STREAM_RAYS>>,
    e_set_q: DFF<Bits<SET_BITS>>,
    e_tag_q: DFF<Bits<STREAM_TAG_BITS>>,
    e_lo_q: [DFF<Bits<C>>; 3],
    e_hi_q: [DFF<Bits<C>>; 3],
    // the pair issued in this clock
    issue_q: DFF<Bit>,
    issue_tag_q: DFF<Bits<TAG_BITS>>,
    issue_utag_q: DFF<Bits<STREAM_TAG_BITS>>,
    issue_lo_q: [DFF<Bits<C>>; 3],
    issue_hi_q: [DFF<Bits<C>>; 3],
    acc_q: DFF<Bits<STREAM_RAYS>>,
    // the report stage (loaded in the answer's clock), then the result registers behind the ports
    done_q: DFF<Bit>,
    done_tag_q: DFF<Bits<STREAM_TAG_BITS>>,
    all_hit_q: DFF<Bit>,
    all_miss_q: DFF<Bit>,
    split_q: DFF<Bit>,
    mask_q: DFF<Bits<STREAM_RAYS>>,
    out_done_q: DFF<Bit>,
    out_tag_q: DFF<Bits<STREAM_TAG_BITS>>,
    out_all_hit_q: DFF<Bit>,
    out_all_miss_q: DFF<Bit>,
    out_split_q: DFF<Bit>,
    out_mask_q: DFF<Bits<STREAM_RAYS>>,
    // constants
    one16: Constant<Bits<STREAM_RAYS>>,
    zero16: Constant<Bits<STREAM_RAYS>>,
    one_q: Constant<Bits<PB>>,
    one_c: Constant<Bits<CB>>,
    zero_c: Constant<Bits<CB>>,
    full_c: Constant<Bits<CB>>,
    /// Set `k`, and its first address.
    set_k: [Constant<Bits<SET_BITS>>; STREAM_SETS],
    base_k: [Constant<Bits<STREAM_ADDR_BITS>>; STREAM_SETS],
    /// `k` as a queue index.
    slot_k: [Constant<Bits<PB>>; Q],
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
    take_l: Signal<Local, Bit>,
    head_tag: Signal<Local, Bits<STREAM_TAG_BITS>>,
    head_hot_a: Signal<Local, Bits<STREAM_RAYS>>,
    head_hot_b: Signal<Local, Bits<STREAM_RAYS>>,
    head_rest: Signal<Local, Bits<STREAM_RAYS>>,
    head_set: Signal<Local, Bits<SET_BITS>>,
    head_lo: [Signal<Local, Bits<C>>; 3],
    head_hi: [Signal<Local, Bits<C>>; 3],
    /// The next pair of the job's remaining rays and what is left after it (`_r`), found every clock;
    /// `load` chooses between it and the queue head's pair, which was split as the bundle joined the
    /// queue (`push_`).
    hot_a_r: Signal<Local, Bits<STREAM_RAYS>>,
    rem_b_r: Signal<Local, Bits<STREAM_RAYS>>,
    hot_b_r: Signal<Local, Bits<STREAM_RAYS>>,
    push_hot_a: Signal<Local, Bits<STREAM_RAYS>>,
    push_rem_b: Signal<Local, Bits<STREAM_RAYS>>,
    push_hot_b: Signal<Local, Bits<STREAM_RAYS>>,
    set_base: Signal<Local, Bits<STREAM_ADDR_BITS>>,
    a_addr: Signal<Local, Bits<STREAM_ADDR_BITS>>,
    b_addr: Signal<Local, Bits<STREAM_ADDR_BITS>>,
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
    count_a: Signal<Local, Bits<CB>>,
    resv_a: Signal<Local, Bits<CB>>,
    resv_b: Signal<Local, Bits<CB>>,
    ready_l: Signal<Local, Bit>,
}

impl<const C: usize, const Q: usize, const Q3: usize, const PB: usize, const CB: usize>
    StreamCtl<C, Q, Q3, PB, CB>
{
    /// The control for a pair of `latency` clocks, whose queue must be [`stream_queue`]`(latency)`.
    pub fn new(latency: usize) -> Self {
        assert!(
            Q == stream_queue(latency) && Q3 == 3 * Q && Q == 1 << PB && CB == PB + 1,
            "StreamCtl<{C}, {Q}, {Q3}, {PB}, {CB}> is not the control of a {latency}-clock pair \
             (its queue has {} entries)",
            stream_queue(latency)
        );
        Self {
            clock: Default::default(),
            rst: Default::default(),
            start: Default::default(),
            active: Default::default(),
            job_set: Default::default(),
            tag: Default::default(),
            out_lo: Default::default(),
            out_hi: Default::default(),
            p_valid: Default::default(),
            p_tag: Default::default(),
            p_all_hit: Default::default(),
            p_all_miss: Default::default(),
            take: Default::default(),
            issue: Default::default(),
            issue_tag: Default::default(),
            issue_lo: Default::default(),
            issue_hi: Default::default(),
            addr_a: Default::default(),
            addr_b: Default::default(),
            ready: Default::default(),
            done: Default::default(),
            done_tag: Default::default(),
            all_hit: Default::default(),
            all_miss: Default::default(),
            split: Default::default(),
            mask: Default::default(),
            ans_rays: Default::default(),
            ans_keep_a: Default::default(),
            ans_keep_b: Default::default(),
            ans_last: Default::default(),
            ans_done: Default::default(),
            l_tag: Line::new(latency),
            l_active: Line::new(latency),
            l_set: Line::new(latency),
            l_lo: Line::array(latency),
            l_hi: Line::array(latency),
            q_tag: std::array::from_fn(|_| Default::default()),
            q_hot_a: std::array::from_fn(|_| Default::default()),
            q_hot_b: std::array::from_fn(|_| Default::default()),
            q_rest: std::array::from_fn(|_| Default::default()),
            q_set: std::array::from_fn(|_| Default::default()),
            q_lo: std::array::from_fn(|_| Default::default()),
            q_hi: std::array::from_fn(|_| Default::default()),
            head_q: Default::default(),
            tail_q: Default::default(),
            count_q: Default::default(),
            resv_q: Default::default(),
            e_busy_q: Default::default(),
            hot_a_q: Default::default(),
            hot_b_q: Default::default(),
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
            out_done_q: Default::default(),
            out_tag_q: Default::default(),
            out_all_hit_q: Default::default(),
            out_all_miss_q: Default::default(),
            out_split_q: Default::default(),
            out_mask_q: Default::default(),
            one16: Constant::new(bits(1)),
            zero16: Constant::new(bits(0)),
            one_q: Constant::new(bits(1)),
            one_c: Constant::new(bits(1)),
            zero_c: Constant::new(bits(0)),
            full_c: Constant::new(bits(Q as u64)),
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
            take_l: Default::default(),
            head_tag: Default::default(),
            head_hot_a: Default::default(),
            head_hot_b: Default::default(),
            head_rest: Default::default(),
            head_set: Default::default(),
            head_lo: Default::default(),
            head_hi: Default::default(),
            hot_a_r: Default::default(),
            rem_b_r: Default::default(),
            hot_b_r: Default::default(),
            push_hot_a: Default::default(),
            push_rem_b: Default::default(),
            push_hot_b: Default::default(),
            set_base: Default::default(),
            a_addr: Default::default(),
            b_addr: Default::default(),
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

impl<const C: usize, const Q: usize, const Q3: usize, const PB: usize, const CB: usize> Logic
    for StreamCtl<C, Q, Q3, PB, CB>
{
    #[hdl_gen]
    fn update(&mut self) {
        // Clocks.
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
        for k in 0..Q {
            self.q_tag[k].clock.next = self.clock.val();
            self.q_hot_a[k].clock.next = self.clock.val();
            self.q_hot_b[k].clock.next = self.clock.val();
            self.q_rest[k].clock.next = self.clock.val();
            self.q_set[k].clock.next = self.clock.val();
        }
        for k in 0..Q3 {
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
            hot_a_q,
            hot_b_q,
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
            mask_q,
            out_done_q,
            out_tag_q,
            out_all_hit_q,
            out_all_miss_q,
            out_split_q,
            out_mask_q
        );

        // Taking a job: no ray pair this clock and room in the split queue for every bundle in flight.
        self.ready_l.next = !self.issue_q.q.val() & (self.resv_q.q.val() < self.full_c.val());
        self.take_l.next = self.start.val() & self.ready_l.val() & !self.rst.val();
        self.take.next = self.take_l.val();
        self.issue.next = self.issue_q.q.val();
        if self.issue_q.q.val() {
            self.issue_tag.next = self.issue_tag_q.q.val();
        } else {
            self.issue_tag.next = self.zero_tag.val();
        }
        for i in 0..3 {
            self.issue_lo[i].next = self.issue_lo_q[i].q.val();
            self.issue_hi[i].next = self.issue_hi_q[i].q.val();
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
        self.ret_kind.next = self.p_tag.val().get_bits::<7>(9);
        self.bundle_back.next =
            self.p_valid.val() & (self.ret_kind.val() == self.kind_bundle.val());
        self.rays_back.next = self.p_valid.val() & (self.ret_kind.val() != self.kind_bundle.val());
        self.last_back.next = self.p_valid.val() & (self.ret_kind.val() == self.kind_last.val());
        self.decided.next = self.p_all_hit.val() | self.p_all_miss.val();
        self.finish_bundle.next =
            self.bundle_back.val() & (self.decided.val() | !self.l_active.q.val().any());
        self.push.next = self.bundle_back.val() & !self.decided.val() & self.l_active.q.val().any();
        // Two-ray mode: all_hit = ray A may hit, all_miss = ray B misses.
        if self.p_all_hit.val() {
            self.got_a.next = self.one16.val() << self.p_tag.val().get_bits::<4>(0);
        } else {
            self.got_a.next = self.zero16.val();
        }
        if !self.p_all_miss.val() & self.p_tag.val().get_bit(8) {
            self.got_b.next = self.one16.val() << self.p_tag.val().get_bits::<4>(4);
        } else {
            self.got_b.next = self.zero16.val();
        }

        // The queue's head.
        self.head_tag.next = self.q_tag[0].q.val();
        self.head_hot_a.next = self.q_hot_a[0].q.val();
        self.head_hot_b.next = self.q_hot_b[0].q.val();
        self.head_rest.next = self.q_rest[0].q.val();
        self.head_set.next = self.q_set[0].q.val();
        for i in 0..3 {
            self.head_lo[i].next = self.q_lo[i].q.val();
            self.head_hi[i].next = self.q_hi[i].q.val();
        }
        for k in 1..Q {
            if self.head_q.q.val() == self.slot_k[k].val() {
                self.head_tag.next = self.q_tag[k].q.val();
                self.head_hot_a.next = self.q_hot_a[k].q.val();
                self.head_hot_b.next = self.q_hot_b[k].q.val();
                self.head_rest.next = self.q_rest[k].q.val();
                self.head_set.next = self.q_set[k].q.val();
                for i in 0..3 {
                    self.head_lo[i].next = self.q_lo[3 * k + i].q.val();
                    self.head_hi[i].next = self.q_hi[3 * k + i].q.val();
                }
            }
        }

        // The engine: this clock's pair (registered one-hot masks) as store addresses and tag fields.
        self.set_base.next = self.base_k[0].val();
        for k in 0..4 {
            if self.e_set_q.q.val() == self.set_k[k].val() {
                self.set_base.next = self.base_k[k].val();
            }
        }
        self.a_addr.next = self.set_base.val();
        self.b_addr.next = self.set_base.val();
        self.tag_a.next = self.zero_tag.val();
        self.tag_bb.next = self.zero_tag.val();
        for k in 0..16 {
            if self.hot_a_q.q.val().get_bit(k) {
                self.a_addr.next = self.set_base.val() | self.addr_k[k].val();
                self.tag_a.next = self.tag_ak[k].val();
            }
            if self.hot_b_q.q.val().get_bit(k) {
                self.b_addr.next = self.set_base.val() | self.addr_k[k].val();
                self.tag_bb.next = self.tag_bk[k].val();
            }
        }
        self.addr_a.next = self.a_addr.val();
        self.addr_b.next = self.b_addr.val();
        if self.hot_b_q.q.val().any() {
            if self.rem_q.q.val().any() {
                self.tag_flags.next = self.tag_ray.val() | self.tag_b.val();
            } else {
                self.tag_flags.next = self.tag_b.val() | self.tag_last.val();
            }
        } else {
            self.tag_flags.next = self.tag_last.val();
        }
        self.last_addr.next = self.e_busy_q.q.val() & !self.rem_q.q.val().any();
        self.load.next =
            self.count_q.q.val().any() & (!self.e_busy_q.q.val() | self.last_addr.val());
        // The pair after this one: the next two rays of the job, or the queue head's first pair (split
        // when it joined the queue), so `load` only chooses between them.
        self.hot_a_r.next = self.rem_q.q.val() & (!self.rem_q.q.val() + self.one16.val());
        self.rem_b_r.next = self.rem_q.q.val() & !self.hot_a_r.val();
        self.hot_b_r.next = self.rem_b_r.val() & (!self.rem_b_r.val() + self.one16.val());
        // A bundle joining the queue: its first pair and the rest.
        self.push_hot_a.next = self.l_active.q.val() & (!self.l_active.q.val() + self.one16.val());
        self.push_rem_b.next = self.l_active.q.val() & !self.push_hot_a.val();
        self.push_hot_b.next = self.push_rem_b.val() & (!self.push_rem_b.val() + self.one16.val());

        // Registers: hold by default.
        self.head_q.d.next = self.head_q.q.val();
        self.tail_q.d.next = self.tail_q.q.val();
        self.e_busy_q.d.next = self.e_busy_q.q.val();
        self.hot_a_q.d.next = self.hot_a_q.q.val();
        self.hot_b_q.d.next = self.hot_b_q.q.val();
        self.rem_q.d.next = self.rem_q.q.val();
        self.e_set_q.d.next = self.e_set_q.q.val();
        self.e_tag_q.d.next = self.e_tag_q.q.val();
        for i in 0..3 {
            self.e_lo_q[i].d.next = self.e_lo_q[i].q.val();
            self.e_hi_q[i].d.next = self.e_hi_q[i].q.val();
            self.issue_lo_q[i].d.next = self.e_lo_q[i].q.val();
            self.issue_hi_q[i].d.next = self.e_hi_q[i].q.val();
        }
        for k in 0..Q {
            self.q_tag[k].d.next = self.q_tag[k].q.val();
            self.q_hot_a[k].d.next = self.q_hot_a[k].q.val();
            self.q_hot_b[k].d.next = self.q_hot_b[k].q.val();
            self.q_rest[k].d.next = self.q_rest[k].q.val();
            self.q_set[k].d.next = self.q_set[k].q.val();
        }
        for k in 0..Q3 {
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
        if self.load.val() {
            self.hot_a_q.d.next = self.head_hot_a.val();
            self.hot_b_q.d.next = self.head_hot_b.val();
            self.rem_q.d.next = self.head_rest.val();
        } else if self.e_busy_q.q.val() {
            self.hot_a_q.d.next = self.hot_a_r.val();
            self.hot_b_q.d.next = self.hot_b_r.val();
            self.rem_q.d.next = self.rem_b_r.val() & !self.hot_b_r.val();
        }
        if self.last_addr.val() {
            self.e_busy_q.d.next = false;
        }
        if self.load.val() {
            self.e_busy_q.d.next = true;
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
            for k in 0..Q {
                if self.tail_q.q.val() == self.slot_k[k].val() {
                    self.q_tag[k].d.next = self.l_tag.q.val();
                    self.q_hot_a[k].d.next = self.push_hot_a.val();
                    self.q_hot_b[k].d.next = self.push_hot_b.val();
                    self.q_rest[k].d.next = self.push_rem_b.val() & !self.push_hot_b.val();
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
        if self.take_l.val() {
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

        // The report stage: a job answered in this clock.
        if self.rays_back.val() {
            self.acc_q.d.next = self.acc_q.q.val() | self.got_a.val() | self.got_b.val();
        }
        if self.finish_bundle.val() {
            self.done_q.d.next = true;
            self.done_tag_q.d.next = self.l_tag.q.val();
            self.all_hit_q.d.next = self.p_all_hit.val();
            self.all_miss_q.d.next = self.p_all_miss.val();
            self.split_q.d.next = !self.decided.val();
            if self.p_all_hit.val() {
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

        // The report stage moves on to the result ports.
        self.out_done_q.d.next = self.done_q.q.val();
        self.out_tag_q.d.next = self.done_tag_q.q.val();
        self.out_all_hit_q.d.next = self.all_hit_q.q.val();
        self.out_all_miss_q.d.next = self.all_miss_q.q.val();
        self.out_split_q.d.next = self.split_q.q.val();
        self.out_mask_q.d.next = self.mask_q.q.val();

        if self.rst.val() {
            self.head_q.d.next = self.slot_k[0].val();
            self.tail_q.d.next = self.slot_k[0].val();
            self.count_q.d.next = self.zero_c.val();
            self.resv_q.d.next = self.zero_c.val();
            self.e_busy_q.d.next = false;
            self.issue_q.d.next = false;
            self.acc_q.d.next = self.zero16.val();
            self.done_q.d.next = false;
            self.out_done_q.d.next = false;
        }

        self.ready.next = self.ready_l.val();
        self.done.next = self.out_done_q.q.val();
        self.done_tag.next = self.out_tag_q.q.val();
        self.all_hit.next = self.out_all_hit_q.q.val();
        self.all_miss.next = self.out_all_miss_q.q.val();
        self.split.next = self.out_split_q.q.val();
        self.mask.next = self.out_mask_q.q.val();
        self.ans_rays.next = self.rays_back.val();
        self.ans_keep_a.next = self.rays_back.val() & self.p_all_hit.val();
        self.ans_keep_b.next =
            self.rays_back.val() & !self.p_all_miss.val() & self.p_tag.val().get_bit(8);
        self.ans_last.next = self.last_back.val();
        self.ans_done.next = self.finish_bundle.val();
    }
}
