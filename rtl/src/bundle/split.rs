//! `BundleSplit`: the results processor around one fixed-point bundle pair ([`BundleFix`]). A job is one
//! bundle against one node box: the bundle goes through the pair once; if the pair decides it (all hit or
//! all miss) the job is done, otherwise the job's active rays, read from a ray store, go through the same
//! pair two per clock in two-ray mode and their answers are collected into a hit mask (the results
//! processing of US 11,682,160: an undecided bundle is broken into its rays, which the same pair of testing
//! blocks takes two at a time).
//!
//! Bit for bit `golden::bundle::split::split_fix` (mask, `all_hit`, `all_miss`, `split`, pair cycles); the
//! clocks of a job are [`split_clocks`].
//!
//! # Parameters
//! `G`, `V = G + 1`, `D = FD + 3`, `T`, as [`BundleFix`]; presets [`crate::BundleSplitB8`],
//! [`crate::BundleSplitB12`], [`crate::BundleSplitB16`]. The ray store holds [`SPLIT_RAYS`] = 16 rays.
//!
//! # Inputs
//! - `clock`; `rst` (synchronous reset: high at a clock edge, the job in progress and the pair's answers
//!   in flight are dropped, no `done` follows, and `ready` is high after that edge; a `start` in a clock
//!   with `rst` high is not taken, a ray store write is; the ray store is not cleared);
//! - ray store write port: `ray_we`, `ray_addr` (4 bits), `ray_o_lo`, `ray_o_hi`, `ray_d_lo`, `ray_d_hi`
//!   (arrays over x, y, z), `ray_t` (the ray's `t_hi`): ray `ray_addr` as a quantised tiny bundle
//!   (`golden::bundle::fix::quantize_bundle` of `Bundle::of_ray`; its `t_lo` is not needed). Written at the
//!   end of the clock; writes are accepted at any time;
//! - job port: `start` (taken when `ready`), the bundle `o_lo`, `o_hi`, `d_lo`, `d_hi`, `t_lo`, `t_hi`,
//!   the inner box `in_lo`, `in_hi`, the outer box `out_lo`, `out_hi`, and `active` (16 bits, bit `i`:
//!   test ray `i` if the bundle is undecided). All are sampled in the start clock only; the outer box
//!   and `active` are held inside for the split.
//!
//! Contract: the rays a job may read (its active ones) are written no later than its start clock and not
//! written again until its `done`. Back-to-back jobs over the same rays (one bundle against several
//! boxes) need no reloading.
//!
//! # Outputs
//! - `ready`: no job in progress; a `start` in this clock is taken. High again in the clock of `done`,
//!   so a job may start in the clock its predecessor reports;
//! - `done`: one-clock pulse; with it, and held until the next `done`: `all_hit`, `all_miss`, `split`,
//!   `mask` (16 bits, bit `i`: ray `i` may hit), `cycles` (8 bits: clocks the job used the pair's input,
//!   `golden::bundle::split::SplitResult::pair_cycles`), `clocks` (8 bits: clocks from the start clock to
//!   the `done` clock, [`split_clocks`]).
//!
//! # Sequencing (`L` = [`BUNDLE_FIX_LATENCY`] = 3, start in clock `s`)
//! ```text
//! s            the bundle enters the pair (bundle mode); outer box and active mask registered
//! s+L          the pair's answer: decided, or no active ray -> report (done in s+L+1);
//!              undecided -> address the two lowest active rays in the ray store
//! s+L+1 ..     each clock one pair of rays enters the pair (two-ray mode) while the next pair is
//! s+L+k        read; k = ceil(popcount(active) / 2); an odd count leaves the last B slot empty
//! s+2L+1 ..    the answers return, tagged with the rays' indices, and are ORed into the mask
//! s+2L+k       the last pair's answer (tagged "last") -> report (done in s+2L+k+1)
//! ```
//! So a decided job takes `L + 1 = 4` clocks and a split one `2L + 1 + k = 7 + k` clocks from start to
//! done; the pair is free in the other clocks of a job (a second job in flight would use them: not done
//! here).
//!
//! # Structure
//! The ray store ([`RayStore`]) is two copies of 16 words (banks A and B, written together), each field a
//! `rust_hdl::widgets::ramrom::ram::RAM` (synchronous read and write, one clock read latency: block RAM or
//! LUT RAM in synthesis): bank A feeds the pair's bundle ports (ray A), bank B its ray B ports, so any two
//! rays are read in one clock. The remaining-ray mask `rem_q` gives the next two rays by isolating its
//! lowest set bits (`x & -x`); their indices, a "B present" flag and the kind of test ride through the
//! pair in its 16-bit tag (`[3:0]` A, `[7:4]` B, bit 8 B present, `[15:9]` kind: 0 the bundle, 1 a pair
//! of rays, 2 the job's last pair), and on return the indices are decoded back to mask bits by shifting. Every input of the pair is taken
//! from a port, a register or a RAM output (never from logic of this block), so the exported Verilog has
//! no combinational path through the pair (Verilator UNOPTFLAT).

use crate::bundle::pair_fix::{BundleFix, BUNDLE_FIX_LATENCY};
use crate::bundle::ray_store::RayStore;
use crate::slab::fix::{code, TAG_BITS};
use golden::bundle::edge::BoxPair;
use golden::bundle::fix::{BundleFixFormat, FixBundle};
use golden::bundle::split::SplitResult;
use golden::format::fixed::FixBox;
use rust_hdl::prelude::*;

/// Rays in the ray store (the width of `active` and `mask`).
pub const SPLIT_RAYS: usize = 16;
/// Address bits of the ray store.
pub const SPLIT_ADDR_BITS: usize = 4;

/// Tag layout: `[3:0]` ray A, `[7:4]` ray B, bit 8 ray B present, `[15:9]` the kind of test.
const TAG_B: u64 = 1 << 8;
/// (Also written as the literal 9 in `update`: a const name would reach the Verilog as is.)
const KIND_AT: usize = 9;
/// Kinds: 0 the bundle, 1 a pair of rays, 2 the job's last pair of rays.
const KIND_RAYS: u64 = 1;
const KIND_LAST: u64 = 2;

/// Clocks from a job's start clock to its `done` clock: `L + 1` for a decided bundle (or one with no
/// active ray), `2L + 1 + k` for a split over `k = pair_cycles - 1` clocks of ray pairs.
pub fn split_clocks(r: &SplitResult) -> u32 {
    let l = BUNDLE_FIX_LATENCY as u32;
    match r.pair_cycles {
        1 => l + 1,
        c => 2 * l + c,
    }
}

/// The results processor; see the module documentation.
#[derive(LogicBlock)]
pub struct BundleSplit<const G: usize, const V: usize, const D: usize, const T: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge, the job in progress and every answer in flight are
    /// dropped (no `done` follows) and the block is ready; the ray store and result registers keep
    /// their contents.
    pub rst: Signal<In, Bit>,
    // ray store write port
    pub ray_we: Signal<In, Bit>,
    pub ray_addr: Signal<In, Bits<SPLIT_ADDR_BITS>>,
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
    pub active: Signal<In, Bits<SPLIT_RAYS>>,
    // results
    pub ready: Signal<Out, Bit>,
    pub done: Signal<Out, Bit>,
    pub all_hit: Signal<Out, Bit>,
    pub all_miss: Signal<Out, Bit>,
    pub split: Signal<Out, Bit>,
    pub mask: Signal<Out, Bits<SPLIT_RAYS>>,
    pub cycles: Signal<Out, Bits<8>>,
    pub clocks: Signal<Out, Bits<8>>,
    // the pair and the ray store (bank A: ray A, bank B: ray B)
    pair: BundleFix<G, V, D, T>,
    store: RayStore<G, D, T, SPLIT_ADDR_BITS>,
    // constants
    one16: Constant<Bits<SPLIT_RAYS>>,
    zero16: Constant<Bits<SPLIT_RAYS>>,
    one8: Constant<Bits<8>>,
    /// `k` as a ray store address.
    addr_k: [Constant<Bits<SPLIT_ADDR_BITS>>; SPLIT_RAYS],
    /// `k` in the A field of the tag.
    tag_ak: [Constant<Bits<TAG_BITS>>; SPLIT_RAYS],
    /// `k` in the B field of the tag.
    tag_bk: [Constant<Bits<TAG_BITS>>; SPLIT_RAYS],
    tag_b: Constant<Bits<TAG_BITS>>,
    tag_ray: Constant<Bits<TAG_BITS>>,
    tag_last: Constant<Bits<TAG_BITS>>,
    kind_bundle: Constant<Bits<7>>,
    kind_rays: Constant<Bits<7>>,
    kind_last: Constant<Bits<7>>,
    // job state
    /// A job is in progress.
    busy_q: DFF<Bit>,
    /// The bundle was undecided: ray pairs are being issued and collected.
    rays_q: DFF<Bit>,
    box_lo_q: [DFF<Bits<G>>; 3],
    box_hi_q: [DFF<Bits<G>>; 3],
    active_q: DFF<Bits<SPLIT_RAYS>>,
    /// Active rays not yet addressed.
    rem_q: DFF<Bits<SPLIT_RAYS>>,
    /// Answers collected so far.
    mask_q: DFF<Bits<SPLIT_RAYS>>,
    /// The ray store outputs hold a pair to issue this clock, with this tag.
    issue_q: DFF<Bit>,
    issue_tag_q: DFF<Bits<TAG_BITS>>,
    cycles_q: DFF<Bits<8>>,
    clocks_q: DFF<Bits<8>>,
    // result registers
    done_q: DFF<Bit>,
    all_hit_q: DFF<Bit>,
    all_miss_q: DFF<Bit>,
    split_q: DFF<Bit>,
    mask_out_q: DFF<Bits<SPLIT_RAYS>>,
    cycles_out_q: DFF<Bits<8>>,
    clocks_out_q: DFF<Bits<8>>,
    // logic
    take_job: Signal<Local, Bit>,
    hot_a: Signal<Local, Bits<SPLIT_RAYS>>,
    rem_b: Signal<Local, Bits<SPLIT_RAYS>>,
    hot_b: Signal<Local, Bits<SPLIT_RAYS>>,
    rem_next: Signal<Local, Bits<SPLIT_RAYS>>,
    addr_a: Signal<Local, Bits<SPLIT_ADDR_BITS>>,
    addr_b: Signal<Local, Bits<SPLIT_ADDR_BITS>>,
    tag_a: Signal<Local, Bits<TAG_BITS>>,
    tag_bb: Signal<Local, Bits<TAG_BITS>>,
    tag_flags: Signal<Local, Bits<TAG_BITS>>,
    advance: Signal<Local, Bit>,
    ret_tag: Signal<Local, Bits<TAG_BITS>>,
    ret_a: Signal<Local, Bits<SPLIT_ADDR_BITS>>,
    ret_b: Signal<Local, Bits<SPLIT_ADDR_BITS>>,
    ret_kind: Signal<Local, Bits<7>>,
    bundle_back: Signal<Local, Bit>,
    rays_back: Signal<Local, Bit>,
    undecided: Signal<Local, Bit>,
    got_a: Signal<Local, Bits<SPLIT_RAYS>>,
    got_b: Signal<Local, Bits<SPLIT_RAYS>>,
    finish_bundle: Signal<Local, Bit>,
    finish_rays: Signal<Local, Bit>,
}

impl<const G: usize, const V: usize, const D: usize, const T: usize> BundleSplit<G, V, D, T> {
    /// The results processor for `bf`, whose widths must equal the parameters.
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
            ready: Default::default(),
            done: Default::default(),
            all_hit: Default::default(),
            all_miss: Default::default(),
            split: Default::default(),
            mask: Default::default(),
            cycles: Default::default(),
            clocks: Default::default(),
            pair: BundleFix::new(bf),
            store: Default::default(),
            one16: Constant::new(bits(1)),
            zero16: Constant::new(bits(0)),
            one8: Constant::new(bits(1)),
            addr_k: std::array::from_fn(|k| Constant::new(bits(k as u64))),
            tag_ak: std::array::from_fn(|k| Constant::new(bits(k as u64))),
            tag_bk: std::array::from_fn(|k| Constant::new(bits((k as u64) << 4))),
            tag_b: Constant::new(bits(TAG_B)),
            tag_ray: Constant::new(bits(KIND_RAYS << KIND_AT)),
            tag_last: Constant::new(bits(KIND_LAST << KIND_AT)),
            kind_bundle: Constant::new(bits(0)),
            kind_rays: Constant::new(bits(KIND_RAYS)),
            kind_last: Constant::new(bits(KIND_LAST)),
            busy_q: Default::default(),
            rays_q: Default::default(),
            box_lo_q: Default::default(),
            box_hi_q: Default::default(),
            active_q: Default::default(),
            rem_q: Default::default(),
            mask_q: Default::default(),
            issue_q: Default::default(),
            issue_tag_q: Default::default(),
            cycles_q: Default::default(),
            clocks_q: Default::default(),
            done_q: Default::default(),
            all_hit_q: Default::default(),
            all_miss_q: Default::default(),
            split_q: Default::default(),
            mask_out_q: Default::default(),
            cycles_out_q: Default::default(),
            clocks_out_q: Default::default(),
            take_job: Default::default(),
            hot_a: Default::default(),
            rem_b: Default::default(),
            hot_b: Default::default(),
            rem_next: Default::default(),
            addr_a: Default::default(),
            addr_b: Default::default(),
            tag_a: Default::default(),
            tag_bb: Default::default(),
            tag_flags: Default::default(),
            advance: Default::default(),
            ret_tag: Default::default(),
            ret_a: Default::default(),
            ret_b: Default::default(),
            ret_kind: Default::default(),
            bundle_back: Default::default(),
            rays_back: Default::default(),
            undecided: Default::default(),
            got_a: Default::default(),
            got_b: Default::default(),
            finish_bundle: Default::default(),
            finish_rays: Default::default(),
        }
    }
}

impl<const G: usize, const V: usize, const D: usize, const T: usize> Logic
    for BundleSplit<G, V, D, T>
{
    #[hdl_gen]
    fn update(&mut self) {
        // Clocks.
        self.pair.clock.next = self.clock.val();
        self.pair.rst.next = self.rst.val();
        for i in 0..3 {
            self.box_lo_q[i].clock.next = self.clock.val();
            self.box_hi_q[i].clock.next = self.clock.val();
        }
        dff_setup!(
            self,
            clock,
            busy_q,
            rays_q,
            active_q,
            rem_q,
            mask_q,
            issue_q,
            issue_tag_q,
            cycles_q,
            clocks_q,
            done_q,
            all_hit_q,
            all_miss_q,
            split_q,
            mask_out_q,
            cycles_out_q,
            clocks_out_q
        );

        // The ray store: both banks written together (bank A is read at addr_a, bank B at addr_b, below:
        // a local is read only after it is written, or rust-hdl reports a logic loop).
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

        // The pair's inputs, from ports, registers and the ray store only: the bundle in the start
        // clock, a pair of rays when issue_q.
        self.pair.valid_in.next = (self.start.val() & !self.busy_q.q.val()) | self.issue_q.q.val();
        self.pair.two_rays.next = self.issue_q.q.val();
        self.pair.t_lo.next = self.t_lo.val();
        if self.issue_q.q.val() {
            self.pair.tag_in.next = self.issue_tag_q.q.val();
            self.pair.t_hi.next = self.store.a_t.val();
        } else {
            self.pair.tag_in.next = self.zero16.val();
            self.pair.t_hi.next = self.t_hi.val();
        }
        self.pair.r_t.next = self.store.b_t.val();
        for i in 0..3 {
            if self.issue_q.q.val() {
                self.pair.o_lo[i].next = self.store.a_o_lo[i].val();
                self.pair.o_hi[i].next = self.store.a_o_hi[i].val();
                self.pair.d_lo[i].next = self.store.a_d_lo[i].val();
                self.pair.d_hi[i].next = self.store.a_d_hi[i].val();
            } else {
                self.pair.o_lo[i].next = self.o_lo[i].val();
                self.pair.o_hi[i].next = self.o_hi[i].val();
                self.pair.d_lo[i].next = self.d_lo[i].val();
                self.pair.d_hi[i].next = self.d_hi[i].val();
            }
            self.pair.r_o_lo[i].next = self.store.b_o_lo[i].val();
            self.pair.r_o_hi[i].next = self.store.b_o_hi[i].val();
            self.pair.r_d_lo[i].next = self.store.b_d_lo[i].val();
            self.pair.r_d_hi[i].next = self.store.b_d_hi[i].val();
            self.pair.in_lo[i].next = self.in_lo[i].val();
            self.pair.in_hi[i].next = self.in_hi[i].val();
            if self.busy_q.q.val() {
                self.pair.out_lo[i].next = self.box_lo_q[i].q.val();
                self.pair.out_hi[i].next = self.box_hi_q[i].q.val();
            } else {
                self.pair.out_lo[i].next = self.out_lo[i].val();
                self.pair.out_hi[i].next = self.out_hi[i].val();
            }
        }

        // The next two rays: the lowest set bits of rem_q, as one-hot masks, addresses and tag fields.
        self.hot_a.next = self.rem_q.q.val() & (!self.rem_q.q.val() + self.one16.val());
        self.rem_b.next = self.rem_q.q.val() & !self.hot_a.val();
        self.hot_b.next = self.rem_b.val() & (!self.rem_b.val() + self.one16.val());
        self.rem_next.next = self.rem_b.val() & !self.hot_b.val();
        self.addr_a.next = self.addr_k[0].val();
        self.addr_b.next = self.addr_k[0].val();
        self.tag_a.next = self.zero16.val();
        self.tag_bb.next = self.zero16.val();
        for k in 0..16 {
            if self.hot_a.val().get_bit(k) {
                self.addr_a.next = self.addr_k[k].val();
                self.tag_a.next = self.tag_ak[k].val();
            }
            if self.hot_b.val().get_bit(k) {
                self.addr_b.next = self.addr_k[k].val();
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

        // What the pair returns this clock.
        self.ret_tag.next = self.pair.tag_out.val();
        self.ret_a.next = self.ret_tag.val().get_bits::<4>(0);
        self.ret_b.next = self.ret_tag.val().get_bits::<4>(4);
        self.ret_kind.next = self.ret_tag.val().get_bits::<7>(9);
        self.bundle_back.next =
            self.pair.valid_out.val() & (self.ret_kind.val() == self.kind_bundle.val());
        self.rays_back.next = self.pair.valid_out.val()
            & ((self.ret_kind.val() == self.kind_rays.val())
                | (self.ret_kind.val() == self.kind_last.val()));
        self.undecided.next = !self.pair.all_hit.val() & !self.pair.all_miss.val();
        // Two-ray mode: all_hit = ray A may hit, all_miss = ray B misses.
        if self.pair.all_hit.val() {
            self.got_a.next = self.one16.val() << self.ret_a.val();
        } else {
            self.got_a.next = self.zero16.val();
        }
        if !self.pair.all_miss.val() & self.ret_tag.val().get_bit(8) {
            self.got_b.next = self.one16.val() << self.ret_b.val();
        } else {
            self.got_b.next = self.zero16.val();
        }
        self.finish_bundle.next =
            self.bundle_back.val() & (!self.undecided.val() | !self.rem_q.q.val().any());
        self.finish_rays.next =
            self.pair.valid_out.val() & (self.ret_kind.val() == self.kind_last.val());
        // Address the next pair: in the clock the bundle comes back undecided, then while rays remain.
        self.advance.next = (self.bundle_back.val() & self.undecided.val())
            | (self.rays_q.q.val() & self.rem_q.q.val().any());
        self.take_job.next = self.start.val() & !self.busy_q.q.val() & !self.rst.val();

        // Registers: hold by default.
        self.busy_q.d.next = self.busy_q.q.val();
        self.rays_q.d.next = self.rays_q.q.val();
        self.active_q.d.next = self.active_q.q.val();
        self.rem_q.d.next = self.rem_q.q.val();
        self.mask_q.d.next = self.mask_q.q.val();
        self.cycles_q.d.next = self.cycles_q.q.val();
        self.clocks_q.d.next = self.clocks_q.q.val() + self.one8.val();
        for i in 0..3 {
            self.box_lo_q[i].d.next = self.box_lo_q[i].q.val();
            self.box_hi_q[i].d.next = self.box_hi_q[i].q.val();
        }
        self.issue_q.d.next = self.advance.val() & self.hot_a.val().any();
        self.issue_tag_q.d.next = self.tag_a.val() | self.tag_bb.val() | self.tag_flags.val();
        self.done_q.d.next = false;
        self.all_hit_q.d.next = self.all_hit_q.q.val();
        self.all_miss_q.d.next = self.all_miss_q.q.val();
        self.split_q.d.next = self.split_q.q.val();
        self.mask_out_q.d.next = self.mask_out_q.q.val();
        self.cycles_out_q.d.next = self.cycles_out_q.q.val();
        self.clocks_out_q.d.next = self.clocks_out_q.q.val();

        if self.take_job.val() {
            self.busy_q.d.next = true;
            self.rays_q.d.next = false;
            self.active_q.d.next = self.active.val();
            self.rem_q.d.next = self.active.val();
            self.mask_q.d.next = self.zero16.val();
            self.cycles_q.d.next = self.one8.val();
            self.clocks_q.d.next = self.one8.val();
            for i in 0..3 {
                self.box_lo_q[i].d.next = self.out_lo[i].val();
                self.box_hi_q[i].d.next = self.out_hi[i].val();
            }
        }
        if self.advance.val() {
            self.rays_q.d.next = true;
            self.rem_q.d.next = self.rem_next.val();
        }
        if self.issue_q.q.val() {
            self.cycles_q.d.next = self.cycles_q.q.val() + self.one8.val();
        }
        if self.rays_back.val() {
            self.mask_q.d.next = self.mask_q.q.val() | self.got_a.val() | self.got_b.val();
        }
        if self.finish_bundle.val() {
            self.busy_q.d.next = false;
            self.rays_q.d.next = false;
            self.done_q.d.next = true;
            self.all_hit_q.d.next = self.pair.all_hit.val();
            self.all_miss_q.d.next = self.pair.all_miss.val();
            self.split_q.d.next = self.undecided.val();
            if self.pair.all_hit.val() {
                self.mask_out_q.d.next = self.active_q.q.val();
            } else {
                self.mask_out_q.d.next = self.zero16.val();
            }
            self.cycles_out_q.d.next = self.cycles_q.q.val();
            self.clocks_out_q.d.next = self.clocks_q.q.val() + self.one8.val();
        }
        if self.finish_rays.val() {
            self.busy_q.d.next = false;
            self.rays_q.d.next = false;
            self.done_q.d.next = true;
            self.all_hit_q.d.next = false;
            self.all_miss_q.d.next = false;
            self.split_q.d.next = true;
            self.mask_out_q.d.next = self.mask_q.q.val() | self.got_a.val() | self.got_b.val();
            self.cycles_out_q.d.next = self.cycles_q.q.val();
            self.clocks_out_q.d.next = self.clocks_q.q.val() + self.one8.val();
        }

        if self.rst.val() {
            self.busy_q.d.next = false;
            self.rays_q.d.next = false;
            self.issue_q.d.next = false;
            self.done_q.d.next = false;
        }

        self.ready.next = !self.busy_q.q.val();
        self.done.next = self.done_q.q.val();
        self.all_hit.next = self.all_hit_q.q.val();
        self.all_miss.next = self.all_miss_q.q.val();
        self.split.next = self.split_q.q.val();
        self.mask.next = self.mask_out_q.q.val();
        self.cycles.next = self.cycles_out_q.q.val();
        self.clocks.next = self.clocks_out_q.q.val();
    }
}

/// A job on the job port: the bundle, its box pair and the active rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SplitJob {
    pub bundle: FixBundle,
    pub boxes: BoxPair<FixBox>,
    pub active: u16,
}

/// The inputs of one clock: a ray store write and a start, each optional.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SplitIn {
    /// `(address, ray)`: `ray_we` high with the ray (its `o`, `d` ends and `t_hi`).
    pub write: Option<(usize, FixBundle)>,
    /// `start` high with the job (ignored by the block unless `ready`).
    pub start: Option<SplitJob>,
    /// `rst` high.
    pub reset: bool,
}

/// The outputs of one clock.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SplitOut {
    pub ready: bool,
    pub done: bool,
    pub all_hit: bool,
    pub all_miss: bool,
    pub split: bool,
    pub mask: u16,
    pub cycles: u8,
    pub clocks: u8,
}

impl SplitOut {
    /// The job's result as the golden model states it.
    pub fn result(&self) -> SplitResult {
        SplitResult {
            all_hit: self.all_hit,
            all_miss: self.all_miss,
            split: self.split,
            mask: self.mask as u64,
            pair_cycles: self.cycles as u32,
        }
    }
}

/// A results processor of any width, seen from a testbench.
pub trait BundleSplitIo: Block {
    /// The block for `bf` (whose widths must match the block's).
    fn for_format(bf: &BundleFixFormat) -> Self;
    /// Sets the clock input.
    fn set_clock(&mut self, high: bool);
    /// Drives one clock's inputs (data ports of an absent write or start are driven to zero).
    fn drive(&mut self, input: &SplitIn);
    /// Reads the outputs.
    fn outputs(&self) -> SplitOut;
    /// The value of an output port by its Verilog name (for cross-simulation).
    fn output_word(&self, port: &str) -> Option<u64> {
        let o = self.outputs();
        Some(match port {
            "ready" => o.ready as u64,
            "done" => o.done as u64,
            "all_hit" => o.all_hit as u64,
            "all_miss" => o.all_miss as u64,
            "split" => o.split as u64,
            "mask" => o.mask as u64,
            "cycles" => o.cycles as u64,
            "clocks" => o.clocks as u64,
            _ => return None,
        })
    }
}

impl<const G: usize, const V: usize, const D: usize, const T: usize> BundleSplitIo
    for BundleSplit<G, V, D, T>
{
    fn for_format(bf: &BundleFixFormat) -> Self {
        Self::new(bf)
    }

    fn set_clock(&mut self, high: bool) {
        self.clock.next = Clock { clk: high };
    }

    fn drive(&mut self, input: &SplitIn) {
        let (addr, r) = input.write.unwrap_or_default();
        self.ray_we.next = input.write.is_some();
        self.rst.next = input.reset;
        self.ray_addr.next = bits::<SPLIT_ADDR_BITS>(addr as u64);
        let j = input.start.unwrap_or_default();
        let b = &j.bundle;
        let p = &j.boxes;
        self.start.next = input.start.is_some();
        self.active.next = bits::<SPLIT_RAYS>(j.active as u64);
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

    fn outputs(&self) -> SplitOut {
        SplitOut {
            ready: self.ready.val(),
            done: self.done.val(),
            all_hit: self.all_hit.val(),
            all_miss: self.all_miss.val(),
            split: self.split.val(),
            mask: self.mask.val().to_u64() as u16,
            cycles: self.cycles.val().to_u64() as u8,
            clocks: self.clocks.val().to_u64() as u8,
        }
    }
}
