//! `SlabFloat`: the float AABB slab tester of format `E`/`M`, fully pipelined (one test per clock),
//! [`SLAB_FLOAT_LATENCY`] (9) clocks by default, [`slab_float_latency`]`(CUTS)` with the optional cut
//! points of its units ([`cut`]; 13 clocks with all, [`SLAB_FLOAT_CUTS_DEEP`]). Bit for bit `golden::slab::float::slab_float` (read it for the arithmetic
//! and the conservativeness argument); ports mirror `golden::slab::float::{FloatRay, FloatBox,
//! SlabFloatOut}` as `SlabFix`'s mirror the fixed-point types, with `clock`, `rst` (synchronous: high at
//! a clock edge it clears every valid bit, units' included; data registers are not reset), `valid_in` and `tag_in`.
//!
//! # Parameters
//! `E >= 4`, `M`, `N = 1 + E + M <= 32`; `CUTS`, the optional cut points ([`cut`], default none).
//!
//! # Stages
//! Clock numbers are those of the default; each optional cut adds a clock to its unit.
//! 1. clocks 1-3: six [`FpAdd`] — `e` rounded down, `x` rounded up, near/far chosen by the direction's
//!    sign (cuts [`cut::ADD_ALIGN`], [`cut::ADD_NORM`]); the empty-box test ([`FpCmp`]); inverse bounds,
//!    t range and empty flag wait in [`Wait`] lines as long as the units take.
//! 2. clocks 4-6: six [`FpMul`] — `RD(e * m)`, `RU(x * m)`, the inverse bound chosen by the sign of `e`, `x`
//!    (either zero counts as non-negative) (cuts [`cut::MUL_RAW`], [`cut::MUL_PRODUCT`]).
//! 3. clock 7 (`_q7`): a NaN product (`0 x inf`) becomes `-inf` for an entry, `+inf` for an exit.
//! 4. clock 8 (`_q8`): first level of the max (entry) and min (exit) trees, `max(a, b) = a < b ? b : a`,
//!    `min(a, b) = b < a ? b : a`.
//! 5. clock 9 (`_q9`): last level, and the hit as the AND of the four pairwise `<=` of the first level's
//!    entries and exits; these registers drive the outputs.
//!
//! Every comparator reads registers only: a comparator fed from logic that reads other children in the
//! same `always` block is a combinational cycle at block granularity for Verilator (UNOPTFLAT).

use crate::cut::Wait;
use crate::fp::add::{fp_add_latency, FpAdd};
use crate::fp::cmp::FpCmp;
use crate::fp::mul::{fp_mul_latency, FpMul};
use crate::io::TesterIo;
use crate::slab::ports::SlabFloatPorts;
use crate::TAG_BITS;
use golden::format::float::{FloatFormat, Rounding};
use golden::slab::float::{FloatBox, FloatRay, SlabFloatOut};
use rust_hdl::prelude::*;

/// The optional cut points of the float slab tester: one bit each of its `CUTS` parameter, each the cut of
/// the same name in all six of its adders or multipliers (the float datapaths share them:
/// [`crate::fp::cuts`]).
pub use crate::fp::cuts as cut;

/// Clocks from a test entering a `SlabFloat` with cut points `cuts` to its result leaving.
pub const fn slab_float_latency(cuts: usize) -> usize {
    fp_add_latency(cut::add(cuts)) + fp_mul_latency(cut::mul(cuts)) + 3
}

/// Clocks from a test entering the default `SlabFloat` (no optional cut) to its result leaving.
pub const SLAB_FLOAT_LATENCY: usize = slab_float_latency(0);

/// The cut points of the deepest float slab tester: every optional cut (13 clocks).
pub const SLAB_FLOAT_CUTS_DEEP: usize = cut::ALL;

/// The configurations that are built (exported, tested, timed): `(cuts, name suffix)`; the module name
/// is `slab_float_<format><suffix>` (`crate::names::slab_float_module_cuts`).
pub const SLAB_FLOAT_DEPTHS: [(usize, &str); 2] = [(0, ""), (SLAB_FLOAT_CUTS_DEEP, "_p13")];

const _: () = assert!(slab_float_latency(SLAB_FLOAT_CUTS_DEEP) == 13);
const _: () = assert!(
    fp_add_latency(crate::fp::add::cut::ALL) + fp_mul_latency(crate::fp::mul::cut::ALL)
        <= crate::cut::MAX_WAIT
);

// Issue 3's goal: the binary32 tester within 12 clocks.
const _: () = assert!(SLAB_FLOAT_LATENCY <= 12);

/// The float slab tester; see the module documentation.
#[derive(LogicBlock)]
pub struct SlabFloat<const E: usize, const M: usize, const N: usize, const CUTS: usize = 0> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub ray_o_lo: [Signal<In, Bits<N>>; 3],
    pub ray_o_hi: [Signal<In, Bits<N>>; 3],
    pub ray_m_lo: [Signal<In, Bits<N>>; 3],
    pub ray_m_hi: [Signal<In, Bits<N>>; 3],
    pub ray_neg: [Signal<In, Bit>; 3],
    pub ray_t_min: Signal<In, Bits<N>>,
    pub ray_t_max: Signal<In, Bits<N>>,
    pub box_lo: [Signal<In, Bits<N>>; 3],
    pub box_hi: [Signal<In, Bits<N>>; 3],
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub hit: Signal<Out, Bit>,
    pub t_entry: Signal<Out, Bits<N>>,
    pub t_exit: Signal<Out, Bits<N>>,
    // constants
    sign_n: Constant<Bits<N>>,
    mag_mask: Constant<Bits<N>>,
    pinf: Constant<Bits<N>>,
    ninf: Constant<Bits<N>>,
    // stage 1: distances, empty test, side data delayed
    add_e: [FpAdd<E, M, N>; 3],
    add_x: [FpAdd<E, M, N>; 3],
    empty_cmp: [FpCmp<N>; 3],
    empty: Signal<Local, Bit>,
    m_lo_d: [Wait<Bits<N>>; 3],
    m_hi_d: [Wait<Bits<N>>; 3],
    t_min_d: Wait<Bits<N>>,
    t_max_d: Wait<Bits<N>>,
    empty_d: Wait<Bit>,
    // stage 2: products
    mul_e: [FpMul<E, M, N>; 3],
    mul_x: [FpMul<E, M, N>; 3],
    // stage 3: NaN products resolved
    en_q7: [DFF<Bits<N>>; 3],
    ex_q7: [DFF<Bits<N>>; 3],
    t_min_q7: DFF<Bits<N>>,
    t_max_q7: DFF<Bits<N>>,
    empty_q7: DFF<Bit>,
    valid_q7: DFF<Bit>,
    tag_q7: DFF<Bits<TAG_BITS>>,
    // stage 4: first tree level
    cmp8: [FpCmp<N>; 4],
    entry_a_q8: DFF<Bits<N>>,
    entry_b_q8: DFF<Bits<N>>,
    exit_a_q8: DFF<Bits<N>>,
    exit_b_q8: DFF<Bits<N>>,
    empty_q8: DFF<Bit>,
    valid_q8: DFF<Bit>,
    tag_q8: DFF<Bits<TAG_BITS>>,
    // stage 5: last tree level and the hit, from four pairwise comparisons
    cmp9: [FpCmp<N>; 6],
    entry: Signal<Local, Bits<N>>,
    exit: Signal<Local, Bits<N>>,
    entry_q9: DFF<Bits<N>>,
    exit_q9: DFF<Bits<N>>,
    hit_q9: DFF<Bit>,
    valid_q9: DFF<Bit>,
    tag_q9: DFF<Bits<TAG_BITS>>,
    // valid/tag outputs of the units that do not carry the test's own (lint: read, by name, as unused)
    unused_handshake: Signal<Local, Bit>,
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> SlabFloat<E, M, N, CUTS> {
    pub fn new() -> Self {
        assert!(
            CUTS & !cut::ALL == 0,
            "SlabFloat: unknown cut bits {:#x} (known: {:#x})",
            CUTS & !cut::ALL,
            cut::ALL
        );
        let (ac, mc) = (cut::add(CUTS), cut::mul(CUTS));
        let (la, lm) = (fp_add_latency(ac), fp_mul_latency(mc));
        let f = FloatFormat::new(E as u32, M as u32).expect("valid format");
        assert!(
            N as u32 == f.width() && E >= 4,
            "SlabFloat<{E},{M},{N}>: need N = 1+E+M and E >= 4"
        );
        let inf = f.inf(false) as u64;
        let adders = |mode| std::array::from_fn(|_| FpAdd::with_cuts(mode, ac));
        let muls = |mode| std::array::from_fn(|_| FpMul::with_cuts(mode, mc));
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            ray_o_lo: Default::default(),
            ray_o_hi: Default::default(),
            ray_m_lo: Default::default(),
            ray_m_hi: Default::default(),
            ray_neg: Default::default(),
            ray_t_min: Default::default(),
            ray_t_max: Default::default(),
            box_lo: Default::default(),
            box_hi: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            hit: Default::default(),
            t_entry: Default::default(),
            t_exit: Default::default(),
            sign_n: Constant::new(bits::<N>(1 << (N - 1))),
            mag_mask: Constant::new(bits::<N>((1 << (N - 1)) - 1)),
            pinf: Constant::new(bits::<N>(inf)),
            ninf: Constant::new(bits::<N>(f.inf(true) as u64)),
            add_e: adders(Rounding::Down),
            add_x: adders(Rounding::Up),
            empty_cmp: std::array::from_fn(|_| FpCmp::new(inf)),
            empty: Default::default(),
            m_lo_d: std::array::from_fn(|_| Wait::new(la)),
            m_hi_d: std::array::from_fn(|_| Wait::new(la)),
            t_min_d: Wait::new(la + lm),
            t_max_d: Wait::new(la + lm),
            empty_d: Wait::new(la + lm),
            mul_e: muls(Rounding::Down),
            mul_x: muls(Rounding::Up),
            en_q7: Default::default(),
            ex_q7: Default::default(),
            t_min_q7: Default::default(),
            t_max_q7: Default::default(),
            empty_q7: Default::default(),
            valid_q7: Default::default(),
            tag_q7: Default::default(),
            cmp8: std::array::from_fn(|_| FpCmp::new(inf)),
            entry_a_q8: Default::default(),
            entry_b_q8: Default::default(),
            exit_a_q8: Default::default(),
            exit_b_q8: Default::default(),
            empty_q8: Default::default(),
            valid_q8: Default::default(),
            tag_q8: Default::default(),
            cmp9: std::array::from_fn(|_| FpCmp::new(inf)),
            entry: Default::default(),
            exit: Default::default(),
            entry_q9: Default::default(),
            exit_q9: Default::default(),
            hit_q9: Default::default(),
            valid_q9: Default::default(),
            tag_q9: Default::default(),
            unused_handshake: Default::default(),
        }
    }
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> Default
    for SlabFloat<E, M, N, CUTS>
{
    fn default() -> Self {
        Self::new()
    }
}

/// A float slab tester of any format.
pub trait SlabFloatIo: TesterIo<Ray = FloatRay, Box = FloatBox, Out = SlabFloatOut> {
    /// The block's optional cut points ([`cut`]).
    const CUTS: usize;
    /// The format of the block.
    fn format() -> FloatFormat;
    /// A tester.
    fn make() -> Self;
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> SlabFloatIo
    for SlabFloat<E, M, N, CUTS>
{
    const CUTS: usize = CUTS;

    fn format() -> FloatFormat {
        FloatFormat::new(E as u32, M as u32).expect("valid format")
    }

    fn make() -> Self {
        Self::new()
    }
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> TesterIo
    for SlabFloat<E, M, N, CUTS>
{
    type Ray = FloatRay;
    type Box = FloatBox;
    type Out = SlabFloatOut;
    const LATENCY: usize = slab_float_latency(CUTS);
    type Ports = SlabFloatPorts;

    fn ports() -> SlabFloatPorts {
        SlabFloatPorts
    }

    crate::tester_ports!(
        inputs: ray_o_lo, ray_o_hi, ray_m_lo, ray_m_hi, ray_neg, ray_t_min, ray_t_max, box_lo, box_hi;
        outputs: hit, t_entry, t_exit
    );
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> Logic
    for SlabFloat<E, M, N, CUTS>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, t_min_q7, t_max_q7, empty_q7, valid_q7, tag_q7, entry_a_q8, entry_b_q8,
            exit_a_q8, exit_b_q8, empty_q8, valid_q8, tag_q8, entry_q9, exit_q9, hit_q9, valid_q9,
            tag_q9
        );
        self.t_min_d.clock.next = self.clock.val();
        self.t_max_d.clock.next = self.clock.val();
        self.empty_d.clock.next = self.clock.val();

        // Stage 1: distances (a - b is a + (-b)), the empty test, side data into delay lines.
        self.empty.next = false;
        for i in 0..3 {
            self.add_e[i].clock.next = self.clock.val();
            self.add_x[i].clock.next = self.clock.val();
            self.mul_e[i].clock.next = self.clock.val();
            self.mul_x[i].clock.next = self.clock.val();
            self.m_lo_d[i].clock.next = self.clock.val();
            self.m_hi_d[i].clock.next = self.clock.val();
            self.add_e[i].valid_in.next = self.valid_in.val();
            self.add_e[i].rst.next = self.rst.val();
            self.add_x[i].valid_in.next = self.valid_in.val();
            self.add_x[i].rst.next = self.rst.val();
            self.add_e[i].tag_in.next = self.tag_in.val();
            self.add_x[i].tag_in.next = self.tag_in.val();
            if self.ray_neg[i].val() {
                self.add_e[i].a.next = self.ray_o_lo[i].val();
                self.add_e[i].b.next = self.box_hi[i].val() ^ self.sign_n.val();
                self.add_x[i].a.next = self.ray_o_hi[i].val();
                self.add_x[i].b.next = self.box_lo[i].val() ^ self.sign_n.val();
            } else {
                self.add_e[i].a.next = self.box_lo[i].val();
                self.add_e[i].b.next = self.ray_o_hi[i].val() ^ self.sign_n.val();
                self.add_x[i].a.next = self.box_hi[i].val();
                self.add_x[i].b.next = self.ray_o_lo[i].val() ^ self.sign_n.val();
            }
            self.empty_cmp[i].a.next = self.box_hi[i].val();
            self.empty_cmp[i].b.next = self.box_lo[i].val();
            if self.empty_cmp[i].lt.val() {
                self.empty.next = true;
            }
            self.m_lo_d[i].d.next = self.ray_m_lo[i].val();
            self.m_hi_d[i].d.next = self.ray_m_hi[i].val();
        }
        self.t_min_d.d.next = self.ray_t_min.val();
        self.t_max_d.d.next = self.ray_t_max.val();
        self.empty_d.d.next = self.empty.val();

        // Stage 2: products, the inverse bound chosen by the sign of the distance.
        for i in 0..3 {
            self.mul_e[i].valid_in.next = self.add_e[i].valid_out.val();
            self.mul_e[i].rst.next = self.rst.val();
            self.mul_x[i].valid_in.next = self.add_x[i].valid_out.val();
            self.mul_x[i].rst.next = self.rst.val();
            self.mul_e[i].tag_in.next = self.add_e[i].tag_out.val();
            self.mul_x[i].tag_in.next = self.add_x[i].tag_out.val();
            self.mul_e[i].a.next = self.add_e[i].y.val();
            self.mul_x[i].a.next = self.add_x[i].y.val();
            if (self.add_e[i].y.val() & self.sign_n.val()).any()
                & (self.add_e[i].y.val() & self.mag_mask.val()).any()
            {
                self.mul_e[i].b.next = self.m_hi_d[i].q.val();
            } else {
                self.mul_e[i].b.next = self.m_lo_d[i].q.val();
            }
            if (self.add_x[i].y.val() & self.sign_n.val()).any()
                & (self.add_x[i].y.val() & self.mag_mask.val()).any()
            {
                self.mul_x[i].b.next = self.m_lo_d[i].q.val();
            } else {
                self.mul_x[i].b.next = self.m_hi_d[i].q.val();
            }
            // Stage 3: a NaN product (0 x inf) leaves the axis unconstrained.
            self.en_q7[i].clock.next = self.clock.val();
            self.ex_q7[i].clock.next = self.clock.val();
            if (self.mul_e[i].y.val() & self.mag_mask.val()) > self.pinf.val() {
                self.en_q7[i].d.next = self.ninf.val();
            } else {
                self.en_q7[i].d.next = self.mul_e[i].y.val();
            }
            if (self.mul_x[i].y.val() & self.mag_mask.val()) > self.pinf.val() {
                self.ex_q7[i].d.next = self.pinf.val();
            } else {
                self.ex_q7[i].d.next = self.mul_x[i].y.val();
            }
        }
        self.t_min_q7.d.next = self.t_min_d.q.val();
        self.t_max_q7.d.next = self.t_max_d.q.val();
        self.empty_q7.d.next = self.empty_d.q.val();
        self.valid_q7.d.next = self.mul_e[0].valid_out.val() & !self.rst.val();
        self.tag_q7.d.next = self.mul_e[0].tag_out.val();

        // Stage 4: first level of the trees (comparators read registers only).
        self.cmp8[0].a.next = self.t_min_q7.q.val();
        self.cmp8[0].b.next = self.en_q7[0].q.val();
        if self.cmp8[0].lt.val() {
            self.entry_a_q8.d.next = self.en_q7[0].q.val();
        } else {
            self.entry_a_q8.d.next = self.t_min_q7.q.val();
        }
        self.cmp8[1].a.next = self.en_q7[1].q.val();
        self.cmp8[1].b.next = self.en_q7[2].q.val();
        if self.cmp8[1].lt.val() {
            self.entry_b_q8.d.next = self.en_q7[2].q.val();
        } else {
            self.entry_b_q8.d.next = self.en_q7[1].q.val();
        }
        self.cmp8[2].a.next = self.ex_q7[0].q.val();
        self.cmp8[2].b.next = self.t_max_q7.q.val();
        if self.cmp8[2].lt.val() {
            self.exit_a_q8.d.next = self.ex_q7[0].q.val();
        } else {
            self.exit_a_q8.d.next = self.t_max_q7.q.val();
        }
        self.cmp8[3].a.next = self.ex_q7[2].q.val();
        self.cmp8[3].b.next = self.ex_q7[1].q.val();
        if self.cmp8[3].lt.val() {
            self.exit_b_q8.d.next = self.ex_q7[2].q.val();
        } else {
            self.exit_b_q8.d.next = self.ex_q7[1].q.val();
        }
        self.empty_q8.d.next = self.empty_q7.q.val();
        self.valid_q8.d.next = self.valid_q7.q.val() & !self.rst.val();
        self.tag_q8.d.next = self.tag_q7.q.val();

        // Stage 5: entry = max(ea, eb), exit = min(xa, xb); entry <= exit is the AND of the four pairwise
        // comparisons (equal to the model's le(entry, exit), NaN limits included: only t_min, t_max can be NaN).
        self.cmp9[0].a.next = self.entry_a_q8.q.val();
        self.cmp9[0].b.next = self.entry_b_q8.q.val();
        if self.cmp9[0].lt.val() {
            self.entry.next = self.entry_b_q8.q.val();
        } else {
            self.entry.next = self.entry_a_q8.q.val();
        }
        self.cmp9[1].a.next = self.exit_b_q8.q.val();
        self.cmp9[1].b.next = self.exit_a_q8.q.val();
        if self.cmp9[1].lt.val() {
            self.exit.next = self.exit_b_q8.q.val();
        } else {
            self.exit.next = self.exit_a_q8.q.val();
        }
        self.cmp9[2].a.next = self.entry_a_q8.q.val();
        self.cmp9[2].b.next = self.exit_a_q8.q.val();
        self.cmp9[3].a.next = self.entry_a_q8.q.val();
        self.cmp9[3].b.next = self.exit_b_q8.q.val();
        self.cmp9[4].a.next = self.entry_b_q8.q.val();
        self.cmp9[4].b.next = self.exit_a_q8.q.val();
        self.cmp9[5].a.next = self.entry_b_q8.q.val();
        self.cmp9[5].b.next = self.exit_b_q8.q.val();
        self.hit_q9.d.next = !self.empty_q8.q.val()
            & self.cmp9[2].le.val()
            & self.cmp9[3].le.val()
            & self.cmp9[4].le.val()
            & self.cmp9[5].le.val()
            & (self.entry.val() != self.pinf.val())
            & (self.exit.val() != self.ninf.val());
        self.entry_q9.d.next = self.entry.val();
        self.exit_q9.d.next = self.exit.val();
        self.valid_q9.d.next = self.valid_q8.q.val() & !self.rst.val();
        self.tag_q9.d.next = self.tag_q8.q.val();

        self.valid_out.next = self.valid_q9.q.val();
        self.tag_out.next = self.tag_q9.q.val();
        self.hit.next = self.hit_q9.q.val();
        self.t_entry.next = self.entry_q9.q.val();
        self.t_exit.next = self.exit_q9.q.val();

        // Outputs of the units that the test's own valid/tag do not follow, and unused comparator outputs.
        self.unused_handshake.next = self.add_e[1].valid_out.val()
            ^ self.add_e[2].valid_out.val()
            ^ self.add_x[0].valid_out.val()
            ^ self.add_x[1].valid_out.val()
            ^ self.add_x[2].valid_out.val()
            ^ self.mul_e[1].valid_out.val()
            ^ self.mul_e[2].valid_out.val()
            ^ self.mul_x[0].valid_out.val()
            ^ self.mul_x[1].valid_out.val()
            ^ self.mul_x[2].valid_out.val()
            ^ self.mul_e[1].tag_out.val().xor()
            ^ self.mul_e[2].tag_out.val().xor()
            ^ self.mul_x[0].tag_out.val().xor()
            ^ self.mul_x[1].tag_out.val().xor()
            ^ self.mul_x[2].tag_out.val().xor()
            ^ self.empty_cmp[0].le.val()
            ^ self.empty_cmp[1].le.val()
            ^ self.empty_cmp[2].le.val()
            ^ self.cmp8[0].le.val()
            ^ self.cmp8[1].le.val()
            ^ self.cmp8[2].le.val()
            ^ self.cmp8[3].le.val()
            ^ self.cmp9[0].le.val()
            ^ self.cmp9[1].le.val()
            ^ self.cmp9[2].lt.val()
            ^ self.cmp9[3].lt.val()
            ^ self.cmp9[4].lt.val()
            ^ self.cmp9[5].lt.val();
    }
}
