//! `BundleFloatTest`: one of the pair of float bundle testers of format `E`/`M`, fully pipelined (one test
//! per clock), [`bundle_float_test_latency`]`(CUTS)` clocks of latency: [`BUNDLE_FLOAT_TEST_LATENCY`] (9)
//! by default, one more per optional cut point of its units ([`crate::fp::cuts`]; 13 with all). Which bounds it takes, AllHit's or
//! AnyHit's, is chosen per test: a constructor constant ORed with the input `any_mode`, which travels with
//! its test through every stage that uses it. So the tester built as AllHit runs AnyHit's bounds for the
//! tests that ask for them: in two-ray mode [`crate::bundle::pair_float::BundleFloat`] needs both testers to
//! answer "may hit" soundly, and a ray quantised into a float format is a tiny bundle (its `RD`/`RU`
//! ends), which only AnyHit's bounds judge soundly in that direction.
//!
//! Bit for bit `golden::bundle::edge::conditions_hold` in `golden::bundle::float::FloatArith` with `t_min = 0`:
//! with `any_mode` low, [`BundleFloatTest::all_hit`] computes `golden::bundle::float::all_hit_float` (given
//! the inner box and `t_lo`); with either the constant or `any_mode` set, `pass` is
//! `!golden::bundle::float::all_miss_float` (given the outer box and `t_hi`: `pass` low means every ray of
//! the bundle misses). Read `golden/src/bundle/edge.rs` for the conditions and their proofs and
//! `golden/src/bundle/float.rs` for their float bounds. Every input pattern is accepted (infinities, NaN,
//! `lo > hi`) and gives the model's answer.
//!
//! # Parameters
//! `E >= 4`, `M`, `N = 1 + E + M <= 32`: the format. `CUTS`: the optional cut points of its adders and
//! multipliers ([`crate::fp::cuts`], default none). The presets are in [`crate::bundle::pair_float`].
//!
//! # Inputs
//! - `clock`; `rst` (synchronous reset: high at a clock edge, every valid bit is cleared and no test in flight leaves; data registers are not reset); `valid_in`, `tag_in` (16 bits, opaque, returned with the result);
//! - `any_mode`: take AnyHit's bounds for this test (ORed with the constructor's choice);
//! - `o_lo`, `o_hi`, `d_lo`, `d_hi` (arrays over x, y, z) and `t_max`: the bundle, fields of
//!   `golden::bundle::float::FloatBundle` (`t_max` is its `t_lo` for AllHit, `t_hi` for AnyHit);
//! - `box_lo`, `box_hi`: the box (`inner` for AllHit, `outer` for AnyHit).
//!
//! # Outputs (registered, [`bundle_float_test_latency`]`(CUTS)` clocks after the inputs)
//! - `valid_out`, `tag_out`, `pass`: all fifteen conditions hold with the test's bounds.
//!
//! # Arithmetic: one rounding direction for every unit
//! The model rounds each difference and product up or down as the test needs; here every [`FpAdd`] and
//! [`FpMul`] rounds down, and an upward result is taken as `RU(x) = -RD(-x)` (a sign flip of an operand and
//! of the result). For the differences this halves the adders: with `o_e`, `o_x` the origin ends of the
//! model (`o_lo`, `o_hi` for AllHit, swapped for AnyHit), `e_pos = lo - o_e` and `x_neg = o_e - lo` are
//! negatives of each other and rounded in opposite directions, so one `RD` serves both, and likewise
//! `x_pos`, `e_neg`:
//!
//! ```text
//!           A (adder a)        B (adder b)        e_pos  x_pos  e_neg  x_neg
//! AllHit    RD(o_lo - lo)      RD(hi - o_hi)      -A     B      -B     A
//! AnyHit    RD(lo - o_hi)      RD(o_lo - hi)      A      -B     B      -A
//! ```
//!
//! A flipped result differs from the model's only in the sign of a zero or of a NaN, and no later step
//! looks at either: comparisons take `-0 == +0` and are false on NaN, `is_neg` is false on both, a zero or
//! NaN factor gives a zero or a NaN product whatever its sign, and a NaN product becomes `-inf` before
//! the flip (`mul_lower`), so `+inf` after it (`mul_upper`).
//!
//! # Stages (clock at whose end a value is registered; the numbers are the default's, each optional cut adds
//! a clock to its units and to the [`Wait`] lines beside them)
//! 1. clocks 1-3: per axis two [`FpAdd`] (`A`, `B` above); the box check `lo <= hi` and the straddling
//!    `|d|` choice `-d_lo <= d_hi` ([`FpCmp`] on the inputs); directions, `t_max`, the mode and the box
//!    flag wait in [`Wait`] lines as long as the adders take.
//! 2. clock 4 (`_q4`) fold: `e_pos`, `x_pos`, `e_neg`, `x_neg` by sign flips; the sign class of
//!    `[d_lo, d_hi]` (positive: `d_lo >= 0`, negative: `d_hi <= 0`, else straddling) and, for AnyHit, the
//!    half rule (a straddling axis whose `x_pos` or `x_neg` is negative keeps the other fold) choose `e`,
//!    `x`, `u_lo`, `u_hi`; a straddling axis otherwise takes `e` at its bound over both folds
//!    (`le(e_pos, e_neg)` is `le(B, A)` for AllHit and `le(A, B)` for AnyHit, the same for `x`) and
//!    `u in [0, max(-d_lo, d_hi)]`.
//! 3. clocks 5-7: fifteen [`FpMul`]: for each edge `(a, c)` the upper (AllHit) or lower (AnyHit) bound of
//!    `e_a * u_c` and the other bound of `x_c * u_a`, the factor `u_lo` or `u_hi` chosen by the sign of
//!    `e_a`, `x_c`; for each axis the bound of `t_max * u_a`, `u` chosen by the sign of `t_max`. The sign
//!    checks `D` (`x >= 0`) join the box flag; `e`, the flag and the mode wait in [`Wait`] lines.
//! 4. clock 8 (`_q8`): a NaN product (`inf x 0`) becomes `-inf`, then the sign flip of an upward bound;
//!    `t * u` is `+0` when `u` is zero.
//! 5. clock 9 (`_q9`): six edge compares `e_a u_c <= x_c u_a`, three distance compares `e_a <= t u_a`
//!    ([`FpCmp`], reading registers only: Verilator UNOPTFLAT otherwise, see `rtl/src/slab/float.rs`), ANDed with
//!    the flag; these registers drive the outputs.

use crate::cut::Wait;
use crate::fp::add::{fp_add_latency, FpAdd};
use crate::fp::cmp::FpCmp;
use crate::fp::cuts;
use crate::fp::mul::{fp_mul_latency, FpMul};
use crate::TAG_BITS;
use golden::format::float::{FloatFormat, Rounding};
use rust_hdl::prelude::*;

/// Clocks from a test entering a [`BundleFloatTest`] with cut points `cuts` ([`crate::fp::cuts`]) to its
/// result leaving: the adders', the fold, the multipliers', and two.
pub const fn bundle_float_test_latency(cuts: usize) -> usize {
    fp_add_latency(cuts::add(cuts)) + 1 + fp_mul_latency(cuts::mul(cuts)) + 2
}

/// Clocks from a test entering the default [`BundleFloatTest`] (no optional cut) to its result leaving (9).
pub const BUNDLE_FLOAT_TEST_LATENCY: usize = bundle_float_test_latency(0);

const _: () = assert!(BUNDLE_FLOAT_TEST_LATENCY == 9);
const _: () = assert!(bundle_float_test_latency(cuts::ALL) == 13);

/// One float bundle tester; see the module documentation.
#[derive(LogicBlock)]
pub struct BundleFloatTest<const E: usize, const M: usize, const N: usize, const CUTS: usize = 0> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub any_mode: Signal<In, Bit>,
    pub o_lo: [Signal<In, Bits<N>>; 3],
    pub o_hi: [Signal<In, Bits<N>>; 3],
    pub d_lo: [Signal<In, Bits<N>>; 3],
    pub d_hi: [Signal<In, Bits<N>>; 3],
    pub t_max: Signal<In, Bits<N>>,
    pub box_lo: [Signal<In, Bits<N>>; 3],
    pub box_hi: [Signal<In, Bits<N>>; 3],
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub pass: Signal<Out, Bit>,
    // constants
    /// 1 for the AnyHit tester: AnyHit's bounds whatever `any_mode` says.
    any_const: Constant<Bit>,
    sign_n: Constant<Bits<N>>,
    mag_mask: Constant<Bits<N>>,
    pinf: Constant<Bits<N>>,
    ninf: Constant<Bits<N>>,
    zero_n: Constant<Bits<N>>,
    // stage 1 (clocks 1-3): differences, box check, side data delayed
    any: Signal<Local, Bit>,
    sub_a: [FpAdd<E, M, N>; 3],
    sub_b: [FpAdd<E, M, N>; 3],
    box_cmp: [FpCmp<N>; 3],
    umax_cmp: [FpCmp<N>; 3],
    empty: Signal<Local, Bit>,
    d_lo_d: [Wait<Bits<N>>; 3],
    d_hi_d: [Wait<Bits<N>>; 3],
    /// `-d_lo <= d_hi`: a straddling axis's `u_hi` is `d_hi`.
    umax_d: [Wait<Bit>; 3],
    t_d: Wait<Bits<N>>,
    any_d: Wait<Bit>,
    empty_d: Wait<Bit>,
    // stage 2 (clock 4): fold
    flip_e3: Signal<Local, Bits<N>>,
    flip_x3: Signal<Local, Bits<N>>,
    e_pos: [Signal<Local, Bits<N>>; 3],
    x_pos: [Signal<Local, Bits<N>>; 3],
    e_neg: [Signal<Local, Bits<N>>; 3],
    x_neg: [Signal<Local, Bits<N>>; 3],
    nd_lo: [Signal<Local, Bits<N>>; 3],
    nd_hi: [Signal<Local, Bits<N>>; 3],
    u_max: [Signal<Local, Bits<N>>; 3],
    d_pos: [Signal<Local, Bit>; 3],
    d_neg: [Signal<Local, Bit>; 3],
    x_pos_neg: [Signal<Local, Bit>; 3],
    x_neg_neg: [Signal<Local, Bit>; 3],
    /// `le(A, B)`, `le(B, A)`.
    ab_cmp: [FpCmp<N>; 3],
    ba_cmp: [FpCmp<N>; 3],
    /// `le(e_pos, e_neg)` (equal to `le(x_pos, x_neg)`).
    pick_le: [Signal<Local, Bit>; 3],
    e_q4: [DFF<Bits<N>>; 3],
    x_q4: [DFF<Bits<N>>; 3],
    ulo_q4: [DFF<Bits<N>>; 3],
    uhi_q4: [DFF<Bits<N>>; 3],
    t_q4: DFF<Bits<N>>,
    any_q4: DFF<Bit>,
    ok_q4: DFF<Bit>,
    valid_q4: DFF<Bit>,
    tag_q4: DFF<Bits<TAG_BITS>>,
    // stage 3 (clocks 5-7): products
    flip_e4: Signal<Local, Bits<N>>,
    flip_x4: Signal<Local, Bits<N>>,
    e_is_neg: [Signal<Local, Bit>; 3],
    x_is_neg: [Signal<Local, Bit>; 3],
    e_lo_sel: [Signal<Local, Bit>; 3],
    x_lo_sel: [Signal<Local, Bit>; 3],
    t_is_neg: Signal<Local, Bit>,
    mt: [Signal<Local, Bits<N>>; 3],
    ok: Signal<Local, Bit>,
    /// Edge `k` = `(a, c)` in `(0,1), (0,2), (1,0), (1,2), (2,0), (2,1)`: `e_a * u_c`.
    mul_e: [FpMul<E, M, N>; 6],
    /// ... and `x_c * u_a`.
    mul_x: [FpMul<E, M, N>; 6],
    /// `t_max * u_a`.
    mul_t: [FpMul<E, M, N>; 3],
    e_d: [Wait<Bits<N>>; 3],
    mt_zero_d: [Wait<Bit>; 3],
    ok_d: Wait<Bit>,
    any_d2: Wait<Bit>,
    // stage 4 (clock 8): NaN products and upward bounds
    flip_e7: Signal<Local, Bits<N>>,
    flip_x7: Signal<Local, Bits<N>>,
    lhs_q8: [DFF<Bits<N>>; 6],
    rhs_q8: [DFF<Bits<N>>; 6],
    tu_q8: [DFF<Bits<N>>; 3],
    e_q8: [DFF<Bits<N>>; 3],
    ok_q8: DFF<Bit>,
    valid_q8: DFF<Bit>,
    tag_q8: DFF<Bits<TAG_BITS>>,
    // stage 5 (clock 9): compares
    edge_cmp: [FpCmp<N>; 6],
    dist_cmp: [FpCmp<N>; 3],
    all: Signal<Local, Bit>,
    pass_q9: DFF<Bit>,
    valid_q9: DFF<Bit>,
    tag_q9: DFF<Bits<TAG_BITS>>,
    // valid/tag outputs of the units the test's own do not follow, unused comparator outputs (lint)
    unused_handshake: Signal<Local, Bit>,
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize>
    BundleFloatTest<E, M, N, CUTS>
{
    /// The AllHit tester (`all_hit = true`; AnyHit's bounds only when `any_mode` is high) or the AnyHit
    /// tester (always AnyHit's bounds).
    pub fn new(all_hit: bool) -> Self {
        let f = FloatFormat::new(E as u32, M as u32).expect("valid format");
        assert!(
            N as u32 == f.width() && E >= 4,
            "BundleFloatTest<{E},{M},{N}>: need N = 1+E+M and E >= 4"
        );
        assert!(
            CUTS & !cuts::ALL == 0,
            "BundleFloatTest: unknown cut bits {:#x} (known: {:#x})",
            CUTS & !cuts::ALL,
            cuts::ALL
        );
        let (ac, mc) = (cuts::add(CUTS), cuts::mul(CUTS));
        let (la, lm) = (fp_add_latency(ac), fp_mul_latency(mc));
        let c = |v: u32| Constant::new(bits::<N>(v as u64));
        let inf = f.inf(false) as u64;
        fn cmps<const N: usize, const K: usize>(inf: u64) -> [FpCmp<N>; K] {
            std::array::from_fn(|_| FpCmp::new(inf))
        }
        fn muls<const E: usize, const M: usize, const N: usize, const K: usize>(
            mc: usize,
        ) -> [FpMul<E, M, N>; K] {
            std::array::from_fn(|_| FpMul::with_cuts(Rounding::Down, mc))
        }
        let adders = || std::array::from_fn(|_| FpAdd::with_cuts(Rounding::Down, ac));
        fn waits<T: Synth, const K: usize>(regs: usize) -> [Wait<T>; K] {
            std::array::from_fn(|_| Wait::new(regs))
        }
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            any_mode: Default::default(),
            o_lo: Default::default(),
            o_hi: Default::default(),
            d_lo: Default::default(),
            d_hi: Default::default(),
            t_max: Default::default(),
            box_lo: Default::default(),
            box_hi: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            pass: Default::default(),
            any_const: Constant::new(!all_hit),
            sign_n: c(f.sign_bit()),
            mag_mask: c(f.mask() & !f.sign_bit()),
            pinf: c(f.inf(false)),
            ninf: c(f.inf(true)),
            zero_n: c(0),
            any: Default::default(),
            sub_a: adders(),
            sub_b: adders(),
            box_cmp: cmps(inf),
            umax_cmp: cmps(inf),
            empty: Default::default(),
            d_lo_d: waits(la),
            d_hi_d: waits(la),
            umax_d: waits(la),
            t_d: Wait::new(la),
            any_d: Wait::new(la),
            empty_d: Wait::new(la),
            flip_e3: Default::default(),
            flip_x3: Default::default(),
            e_pos: Default::default(),
            x_pos: Default::default(),
            e_neg: Default::default(),
            x_neg: Default::default(),
            nd_lo: Default::default(),
            nd_hi: Default::default(),
            u_max: Default::default(),
            d_pos: Default::default(),
            d_neg: Default::default(),
            x_pos_neg: Default::default(),
            x_neg_neg: Default::default(),
            ab_cmp: cmps(inf),
            ba_cmp: cmps(inf),
            pick_le: Default::default(),
            e_q4: Default::default(),
            x_q4: Default::default(),
            ulo_q4: Default::default(),
            uhi_q4: Default::default(),
            t_q4: Default::default(),
            any_q4: Default::default(),
            ok_q4: Default::default(),
            valid_q4: Default::default(),
            tag_q4: Default::default(),
            flip_e4: Default::default(),
            flip_x4: Default::default(),
            e_is_neg: Default::default(),
            x_is_neg: Default::default(),
            e_lo_sel: Default::default(),
            x_lo_sel: Default::default(),
            t_is_neg: Default::default(),
            mt: Default::default(),
            ok: Default::default(),
            mul_e: muls(mc),
            mul_x: muls(mc),
            mul_t: muls(mc),
            e_d: waits(lm),
            mt_zero_d: waits(lm),
            ok_d: Wait::new(lm),
            any_d2: Wait::new(lm),
            flip_e7: Default::default(),
            flip_x7: Default::default(),
            lhs_q8: Default::default(),
            rhs_q8: Default::default(),
            tu_q8: Default::default(),
            e_q8: Default::default(),
            ok_q8: Default::default(),
            valid_q8: Default::default(),
            tag_q8: Default::default(),
            edge_cmp: cmps(inf),
            dist_cmp: cmps(inf),
            all: Default::default(),
            pass_q9: Default::default(),
            valid_q9: Default::default(),
            tag_q9: Default::default(),
            unused_handshake: Default::default(),
        }
    }

    /// The AllHit tester: AllHit's bounds, AnyHit's for a test with `any_mode` high.
    pub fn all_hit() -> Self {
        Self::new(true)
    }

    /// The AnyHit tester: AnyHit's bounds for every test.
    pub fn any_hit() -> Self {
        Self::new(false)
    }
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> Logic
    for BundleFloatTest<E, M, N, CUTS>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self, clock, t_q4, any_q4, ok_q4, valid_q4, tag_q4, ok_q8, valid_q8, tag_q8, pass_q9,
            valid_q9, tag_q9
        );
        self.t_d.clock.next = self.clock.val();
        self.any_d.clock.next = self.clock.val();
        self.empty_d.clock.next = self.clock.val();
        self.ok_d.clock.next = self.clock.val();
        self.any_d2.clock.next = self.clock.val();
        for i in 0..3 {
            self.sub_a[i].clock.next = self.clock.val();
            self.sub_b[i].clock.next = self.clock.val();
            self.d_lo_d[i].clock.next = self.clock.val();
            self.d_hi_d[i].clock.next = self.clock.val();
            self.umax_d[i].clock.next = self.clock.val();
            self.e_q4[i].clock.next = self.clock.val();
            self.x_q4[i].clock.next = self.clock.val();
            self.ulo_q4[i].clock.next = self.clock.val();
            self.uhi_q4[i].clock.next = self.clock.val();
            self.mul_t[i].clock.next = self.clock.val();
            self.e_d[i].clock.next = self.clock.val();
            self.mt_zero_d[i].clock.next = self.clock.val();
            self.tu_q8[i].clock.next = self.clock.val();
            self.e_q8[i].clock.next = self.clock.val();
        }
        for k in 0..6 {
            self.mul_e[k].clock.next = self.clock.val();
            self.mul_x[k].clock.next = self.clock.val();
            self.lhs_q8[k].clock.next = self.clock.val();
            self.rhs_q8[k].clock.next = self.clock.val();
        }

        // Stage 1: A and B of every axis (a - b is a + (-b)), rounded down; the box check; side data.
        self.any.next = self.any_const.val() | self.any_mode.val();
        self.empty.next = false;
        for i in 0..3 {
            self.sub_a[i].valid_in.next = self.valid_in.val();
            self.sub_a[i].rst.next = self.rst.val();
            self.sub_b[i].valid_in.next = self.valid_in.val();
            self.sub_b[i].rst.next = self.rst.val();
            self.sub_a[i].tag_in.next = self.tag_in.val();
            self.sub_b[i].tag_in.next = self.tag_in.val();
            if self.any.val() {
                // A = RD(lo - o_hi), B = RD(o_lo - hi)
                self.sub_a[i].a.next = self.box_lo[i].val();
                self.sub_a[i].b.next = self.o_hi[i].val() ^ self.sign_n.val();
                self.sub_b[i].a.next = self.o_lo[i].val();
                self.sub_b[i].b.next = self.box_hi[i].val() ^ self.sign_n.val();
            } else {
                // A = RD(o_lo - lo), B = RD(hi - o_hi)
                self.sub_a[i].a.next = self.o_lo[i].val();
                self.sub_a[i].b.next = self.box_lo[i].val() ^ self.sign_n.val();
                self.sub_b[i].a.next = self.box_hi[i].val();
                self.sub_b[i].b.next = self.o_hi[i].val() ^ self.sign_n.val();
            }
            // N: lo <= hi.
            self.box_cmp[i].a.next = self.box_lo[i].val();
            self.box_cmp[i].b.next = self.box_hi[i].val();
            if !self.box_cmp[i].le.val() {
                self.empty.next = true;
            }
            self.umax_cmp[i].a.next = self.d_lo[i].val() ^ self.sign_n.val();
            self.umax_cmp[i].b.next = self.d_hi[i].val();
            self.umax_d[i].d.next = self.umax_cmp[i].le.val();
            self.d_lo_d[i].d.next = self.d_lo[i].val();
            self.d_hi_d[i].d.next = self.d_hi[i].val();
        }
        self.t_d.d.next = self.t_max.val();
        self.any_d.d.next = self.any.val();
        self.empty_d.d.next = self.empty.val();

        // Stage 2: the fold. AllHit flips e (upward), AnyHit flips x.
        if self.any_d.q.val() {
            self.flip_e3.next = self.zero_n.val();
            self.flip_x3.next = self.sign_n.val();
        } else {
            self.flip_e3.next = self.sign_n.val();
            self.flip_x3.next = self.zero_n.val();
        }
        for i in 0..3 {
            self.e_pos[i].next = self.sub_a[i].y.val() ^ self.flip_e3.val();
            self.x_neg[i].next = self.sub_a[i].y.val() ^ self.flip_x3.val();
            self.e_neg[i].next = self.sub_b[i].y.val() ^ self.flip_e3.val();
            self.x_pos[i].next = self.sub_b[i].y.val() ^ self.flip_x3.val();
            self.ab_cmp[i].a.next = self.sub_a[i].y.val();
            self.ab_cmp[i].b.next = self.sub_b[i].y.val();
            self.ba_cmp[i].a.next = self.sub_b[i].y.val();
            self.ba_cmp[i].b.next = self.sub_a[i].y.val();
            // le(e_pos, e_neg) = le(-A, -B) = le(B, A) for AllHit, le(A, B) for AnyHit.
            if self.any_d.q.val() {
                self.pick_le[i].next = self.ab_cmp[i].le.val();
            } else {
                self.pick_le[i].next = self.ba_cmp[i].le.val();
            }
            self.nd_lo[i].next = self.d_lo_d[i].q.val() ^ self.sign_n.val();
            self.nd_hi[i].next = self.d_hi_d[i].q.val() ^ self.sign_n.val();
            if self.umax_d[i].q.val() {
                self.u_max[i].next = self.d_hi_d[i].q.val();
            } else {
                self.u_max[i].next = self.nd_lo[i].val();
            }
            // Positive: !(d_lo < 0). Negative: d_hi <= 0 (not NaN; zero or sign set).
            self.d_pos[i].next = !((self.d_lo_d[i].q.val() & self.sign_n.val()).any()
                & (self.d_lo_d[i].q.val() & self.mag_mask.val()).any()
                & ((self.d_lo_d[i].q.val() & self.mag_mask.val()) <= self.pinf.val()));
            self.d_neg[i].next = ((self.d_hi_d[i].q.val() & self.mag_mask.val())
                <= self.pinf.val())
                & ((self.d_hi_d[i].q.val() & self.sign_n.val()).any()
                    | !(self.d_hi_d[i].q.val() & self.mag_mask.val()).any());
            self.x_pos_neg[i].next = (self.x_pos[i].val() & self.sign_n.val()).any()
                & (self.x_pos[i].val() & self.mag_mask.val()).any()
                & ((self.x_pos[i].val() & self.mag_mask.val()) <= self.pinf.val());
            self.x_neg_neg[i].next = (self.x_neg[i].val() & self.sign_n.val()).any()
                & (self.x_neg[i].val() & self.mag_mask.val()).any()
                & ((self.x_neg[i].val() & self.mag_mask.val()) <= self.pinf.val());
            if self.d_pos[i].val() {
                self.e_q4[i].d.next = self.e_pos[i].val();
                self.x_q4[i].d.next = self.x_pos[i].val();
                self.ulo_q4[i].d.next = self.d_lo_d[i].q.val();
                self.uhi_q4[i].d.next = self.d_hi_d[i].q.val();
            } else if self.d_neg[i].val() {
                self.e_q4[i].d.next = self.e_neg[i].val();
                self.x_q4[i].d.next = self.x_neg[i].val();
                self.ulo_q4[i].d.next = self.nd_hi[i].val();
                self.uhi_q4[i].d.next = self.nd_lo[i].val();
            } else if self.any_d.q.val() & self.x_pos_neg[i].val() {
                // AnyHit, straddling, no ray moving up the axis reaches the far plane: the lower half.
                self.e_q4[i].d.next = self.e_neg[i].val();
                self.x_q4[i].d.next = self.x_neg[i].val();
                self.ulo_q4[i].d.next = self.zero_n.val();
                self.uhi_q4[i].d.next = self.nd_lo[i].val();
            } else if self.any_d.q.val() & self.x_neg_neg[i].val() {
                // AnyHit, straddling, the mirror case: the upper half.
                self.e_q4[i].d.next = self.e_pos[i].val();
                self.x_q4[i].d.next = self.x_pos[i].val();
                self.ulo_q4[i].d.next = self.zero_n.val();
                self.uhi_q4[i].d.next = self.d_hi_d[i].q.val();
            } else {
                // Straddling: e at its bound over both folds (largest for AllHit), x likewise (smallest
                // for AllHit), |d| from 0 to the larger end.
                if self.pick_le[i].val() != self.any_d.q.val() {
                    self.e_q4[i].d.next = self.e_neg[i].val();
                } else {
                    self.e_q4[i].d.next = self.e_pos[i].val();
                }
                if self.pick_le[i].val() == self.any_d.q.val() {
                    self.x_q4[i].d.next = self.x_neg[i].val();
                } else {
                    self.x_q4[i].d.next = self.x_pos[i].val();
                }
                self.ulo_q4[i].d.next = self.zero_n.val();
                self.uhi_q4[i].d.next = self.u_max[i].val();
            }
        }
        self.t_q4.d.next = self.t_d.q.val();
        self.any_q4.d.next = self.any_d.q.val();
        self.ok_q4.d.next = !self.empty_d.q.val();
        self.valid_q4.d.next = self.sub_a[0].valid_out.val() & !self.rst.val();
        self.tag_q4.d.next = self.sub_a[0].tag_out.val();

        // Stage 3: the products, all rounded down; an upward bound multiplies the negated operand. An
        // upper bound of v * u takes u_hi for v >= 0 and u_lo for v < 0, a lower bound the reverse;
        // e-products are upper bounds for AllHit, x- and t-products lower bounds.
        if self.any_q4.q.val() {
            self.flip_e4.next = self.zero_n.val();
            self.flip_x4.next = self.sign_n.val();
        } else {
            self.flip_e4.next = self.sign_n.val();
            self.flip_x4.next = self.zero_n.val();
        }
        self.t_is_neg.next = (self.t_q4.q.val() & self.sign_n.val()).any()
            & (self.t_q4.q.val() & self.mag_mask.val()).any()
            & ((self.t_q4.q.val() & self.mag_mask.val()) <= self.pinf.val());
        self.ok.next = self.ok_q4.q.val();
        for i in 0..3 {
            self.e_is_neg[i].next = (self.e_q4[i].q.val() & self.sign_n.val()).any()
                & (self.e_q4[i].q.val() & self.mag_mask.val()).any()
                & ((self.e_q4[i].q.val() & self.mag_mask.val()) <= self.pinf.val());
            self.x_is_neg[i].next = (self.x_q4[i].q.val() & self.sign_n.val()).any()
                & (self.x_q4[i].q.val() & self.mag_mask.val()).any()
                & ((self.x_q4[i].q.val() & self.mag_mask.val()) <= self.pinf.val());
            if self.x_is_neg[i].val() {
                self.ok.next = false; // D: the far plane is behind
            }
            // e_lo_sel: e < 0 == (upper bound, i.e. AllHit); x_lo_sel: x < 0 == (upper bound, AnyHit).
            self.e_lo_sel[i].next = self.e_is_neg[i].val() != self.any_q4.q.val();
            self.x_lo_sel[i].next = self.x_is_neg[i].val() == self.any_q4.q.val();
            // t * u is an upper bound for AnyHit: u_lo when t < 0 == AnyHit.
            if self.t_is_neg.val() == self.any_q4.q.val() {
                self.mt[i].next = self.ulo_q4[i].q.val();
            } else {
                self.mt[i].next = self.uhi_q4[i].q.val();
            }
            self.mul_t[i].valid_in.next = self.valid_q4.q.val();
            self.mul_t[i].rst.next = self.rst.val();
            self.mul_t[i].tag_in.next = self.tag_q4.q.val();
            self.mul_t[i].a.next = self.t_q4.q.val() ^ self.flip_x4.val();
            self.mul_t[i].b.next = self.mt[i].val();
            self.mt_zero_d[i].d.next = !(self.mt[i].val() & self.mag_mask.val()).any();
            self.e_d[i].d.next = self.e_q4[i].q.val();
        }
        for k in 0..6 {
            self.mul_e[k].valid_in.next = self.valid_q4.q.val();
            self.mul_e[k].rst.next = self.rst.val();
            self.mul_x[k].valid_in.next = self.valid_q4.q.val();
            self.mul_x[k].rst.next = self.rst.val();
            self.mul_e[k].tag_in.next = self.tag_q4.q.val();
            self.mul_x[k].tag_in.next = self.tag_q4.q.val();
        }
        // e_a for edges (a, c): k = 0, 1 (a = 0), 2, 3 (a = 1), 4, 5 (a = 2).
        self.mul_e[0].a.next = self.e_q4[0].q.val() ^ self.flip_e4.val();
        self.mul_e[1].a.next = self.e_q4[0].q.val() ^ self.flip_e4.val();
        self.mul_e[2].a.next = self.e_q4[1].q.val() ^ self.flip_e4.val();
        self.mul_e[3].a.next = self.e_q4[1].q.val() ^ self.flip_e4.val();
        self.mul_e[4].a.next = self.e_q4[2].q.val() ^ self.flip_e4.val();
        self.mul_e[5].a.next = self.e_q4[2].q.val() ^ self.flip_e4.val();
        // x_c: c = 1 for k = 0, 5; c = 2 for k = 1, 3; c = 0 for k = 2, 4.
        self.mul_x[0].a.next = self.x_q4[1].q.val() ^ self.flip_x4.val();
        self.mul_x[1].a.next = self.x_q4[2].q.val() ^ self.flip_x4.val();
        self.mul_x[2].a.next = self.x_q4[0].q.val() ^ self.flip_x4.val();
        self.mul_x[3].a.next = self.x_q4[2].q.val() ^ self.flip_x4.val();
        self.mul_x[4].a.next = self.x_q4[0].q.val() ^ self.flip_x4.val();
        self.mul_x[5].a.next = self.x_q4[1].q.val() ^ self.flip_x4.val();
        // The factor of e_a is u of axis c, chosen by e_a.
        if self.e_lo_sel[0].val() {
            self.mul_e[0].b.next = self.ulo_q4[1].q.val();
            self.mul_e[1].b.next = self.ulo_q4[2].q.val();
        } else {
            self.mul_e[0].b.next = self.uhi_q4[1].q.val();
            self.mul_e[1].b.next = self.uhi_q4[2].q.val();
        }
        if self.e_lo_sel[1].val() {
            self.mul_e[2].b.next = self.ulo_q4[0].q.val();
            self.mul_e[3].b.next = self.ulo_q4[2].q.val();
        } else {
            self.mul_e[2].b.next = self.uhi_q4[0].q.val();
            self.mul_e[3].b.next = self.uhi_q4[2].q.val();
        }
        if self.e_lo_sel[2].val() {
            self.mul_e[4].b.next = self.ulo_q4[0].q.val();
            self.mul_e[5].b.next = self.ulo_q4[1].q.val();
        } else {
            self.mul_e[4].b.next = self.uhi_q4[0].q.val();
            self.mul_e[5].b.next = self.uhi_q4[1].q.val();
        }
        // The factor of x_c is u of axis a, chosen by x_c: c = 0 serves edges (1,0) and (2,0); c = 1
        // edges (0,1), (2,1); c = 2 edges (0,2), (1,2).
        if self.x_lo_sel[0].val() {
            self.mul_x[2].b.next = self.ulo_q4[1].q.val();
            self.mul_x[4].b.next = self.ulo_q4[2].q.val();
        } else {
            self.mul_x[2].b.next = self.uhi_q4[1].q.val();
            self.mul_x[4].b.next = self.uhi_q4[2].q.val();
        }
        if self.x_lo_sel[1].val() {
            self.mul_x[0].b.next = self.ulo_q4[0].q.val();
            self.mul_x[5].b.next = self.ulo_q4[2].q.val();
        } else {
            self.mul_x[0].b.next = self.uhi_q4[0].q.val();
            self.mul_x[5].b.next = self.uhi_q4[2].q.val();
        }
        if self.x_lo_sel[2].val() {
            self.mul_x[1].b.next = self.ulo_q4[0].q.val();
            self.mul_x[3].b.next = self.ulo_q4[1].q.val();
        } else {
            self.mul_x[1].b.next = self.uhi_q4[0].q.val();
            self.mul_x[3].b.next = self.uhi_q4[1].q.val();
        }
        self.ok_d.d.next = self.ok.val();
        self.any_d2.d.next = self.any_q4.q.val();

        // Stage 4: a NaN product becomes -inf (mul_lower), then an upward bound flips its sign (so a NaN
        // becomes +inf: mul_upper); t * u is zero for a zero u.
        if self.any_d2.q.val() {
            self.flip_e7.next = self.zero_n.val();
            self.flip_x7.next = self.sign_n.val();
        } else {
            self.flip_e7.next = self.sign_n.val();
            self.flip_x7.next = self.zero_n.val();
        }
        for k in 0..6 {
            if (self.mul_e[k].y.val() & self.mag_mask.val()) > self.pinf.val() {
                self.lhs_q8[k].d.next = self.ninf.val() ^ self.flip_e7.val();
            } else {
                self.lhs_q8[k].d.next = self.mul_e[k].y.val() ^ self.flip_e7.val();
            }
            if (self.mul_x[k].y.val() & self.mag_mask.val()) > self.pinf.val() {
                self.rhs_q8[k].d.next = self.ninf.val() ^ self.flip_x7.val();
            } else {
                self.rhs_q8[k].d.next = self.mul_x[k].y.val() ^ self.flip_x7.val();
            }
        }
        for i in 0..3 {
            if self.mt_zero_d[i].q.val() {
                self.tu_q8[i].d.next = self.zero_n.val();
            } else if (self.mul_t[i].y.val() & self.mag_mask.val()) > self.pinf.val() {
                self.tu_q8[i].d.next = self.ninf.val() ^ self.flip_x7.val();
            } else {
                self.tu_q8[i].d.next = self.mul_t[i].y.val() ^ self.flip_x7.val();
            }
            self.e_q8[i].d.next = self.e_d[i].q.val();
        }
        self.ok_q8.d.next = self.ok_d.q.val();
        self.valid_q8.d.next = self.mul_e[0].valid_out.val() & !self.rst.val();
        self.tag_q8.d.next = self.mul_e[0].tag_out.val();

        // Stage 5: E (e_a u_c <= x_c u_a), T (e_a <= t u_a), ANDed with N and D.
        self.all.next = self.ok_q8.q.val();
        for k in 0..6 {
            self.edge_cmp[k].a.next = self.lhs_q8[k].q.val();
            self.edge_cmp[k].b.next = self.rhs_q8[k].q.val();
            if !self.edge_cmp[k].le.val() {
                self.all.next = false;
            }
        }
        for i in 0..3 {
            self.dist_cmp[i].a.next = self.e_q8[i].q.val();
            self.dist_cmp[i].b.next = self.tu_q8[i].q.val();
            if !self.dist_cmp[i].le.val() {
                self.all.next = false;
            }
        }
        self.pass_q9.d.next = self.all.val();
        self.valid_q9.d.next = self.valid_q8.q.val() & !self.rst.val();
        self.tag_q9.d.next = self.tag_q8.q.val();

        self.valid_out.next = self.valid_q9.q.val();
        self.tag_out.next = self.tag_q9.q.val();
        self.pass.next = self.pass_q9.q.val();

        // Read, for lint, the outputs nothing else reads.
        self.unused_handshake.next = false;
        for i in 0..3 {
            if self.sub_b[i].valid_out.val()
                | self.sub_b[i].tag_out.val().any()
                | self.mul_t[i].valid_out.val()
                | self.mul_t[i].tag_out.val().any()
                | self.box_cmp[i].lt.val()
                | self.umax_cmp[i].lt.val()
                | self.ab_cmp[i].lt.val()
                | self.ba_cmp[i].lt.val()
                | self.dist_cmp[i].lt.val()
            {
                self.unused_handshake.next = true;
            }
        }
        if self.sub_a[1].valid_out.val()
            | self.sub_a[1].tag_out.val().any()
            | self.sub_a[2].valid_out.val()
            | self.sub_a[2].tag_out.val().any()
            | self.mul_e[1].valid_out.val()
            | self.mul_e[1].tag_out.val().any()
            | self.mul_e[2].valid_out.val()
            | self.mul_e[2].tag_out.val().any()
            | self.mul_e[3].valid_out.val()
            | self.mul_e[3].tag_out.val().any()
            | self.mul_e[4].valid_out.val()
            | self.mul_e[4].tag_out.val().any()
            | self.mul_e[5].valid_out.val()
            | self.mul_e[5].tag_out.val().any()
        {
            self.unused_handshake.next = true;
        }
        for k in 0..6 {
            if self.mul_x[k].valid_out.val()
                | self.mul_x[k].tag_out.val().any()
                | self.edge_cmp[k].lt.val()
            {
                self.unused_handshake.next = true;
            }
        }
    }
}
