//! `FpAdd`: floating-point addition of format `E`/`M` under a fixed rounding mode, fully pipelined (one
//! addition per clock), [`FP_ADD_LATENCY`] clocks by default and [`fp_add_latency`]`(cuts)` with the
//! optional cut points [`cut`]. Subtraction is addition of `b` with its sign flipped.
//! Bit for bit `golden::format::float::FloatFormat::add` (subnormals kept, canonical NaN).
//!
//! # Parameters
//! `E >= 4`, `M`: the format; `N = 1 + E + M` (at most 32). The working significand, `M + 5` bits (hidden
//! bit at `M + 3`, three bits below the last place, one carry bit), lives in an `N`-bit word ([`FpRound`]).
//! The rounding mode and the optional cut points are constructor arguments ([`FpAdd::new`],
//! [`FpAdd::with_cuts`]).
//!
//! # Inputs / outputs
//! `clock`, `rst` (synchronous, clears the valid bits), `valid_in`, `tag_in` (16 bits), `a`, `b` in; `valid_out`, `tag_out`, `y` out (registered).
//!
//! # Stages
//! 1. `_q1`: unpack; order the operands by magnitude; exponent difference; the special cases (NaN, infinities,
//!    zeros) resolved to their result.
//! 2. `_q2`: align the smaller significand by the exponent difference, OR-ing what falls off into a sticky
//!    bit; cut [`cut::ALIGN`] (`_qa`, optional); add or subtract (a sticky subtrahend borrows one, so the
//!    sticky bit stays non-negative).
//! 3. `_q3`: renormalise a carry to the right; normalise left by the leading zeros, found by conditional
//!    shifts of 16, 8, 4, 2 and 1 places, or by fewer where the exponent would leave the normal range
//!    (the result then subnormal), chosen after both shifts; cut [`cut::NORM`] (`_qn`, optional); round and pack ([`FpRound`]).
//!
//! The two optional cuts split the two longest steps where the post-route timing of the float slab
//! tester put its critical path (`exp_q2` / `sum_q2` to `y_q3`: normalise and round in one clock).
//!
//! Three bits below the last place and a sticky bit suffice for a correctly rounded sum (Goldberg, "What
//! every computer scientist should know about floating-point arithmetic", ACM Computing Surveys 1991,
//! section 1.3 on guard digits); the random and exhaustive equivalence tests against the exact-rounding
//! model are the evidence here.

use crate::cut::Cut;
use crate::fp::round::FpRound;
use crate::TAG_BITS;
use golden::format::float::Rounding;
use rust_hdl::prelude::*;

/// The optional cut points of the adder, one bit each of the `cuts` argument of [`FpAdd::with_cuts`]: a
/// register where the bit is set, a wire where it is clear ([`crate::cut::Cut`]).
pub mod cut {
    /// After the alignment shift, before the add (`_qa`).
    pub const ALIGN: usize = 1 << 0;
    /// After the normalisation, before the rounding (`_qn`).
    pub const NORM: usize = 1 << 1;
    /// Every optional cut.
    pub const ALL: usize = ALIGN | NORM;
}

/// Clocks from operands in to sum out with the optional cut points `cuts`: three, and one per cut.
pub const fn fp_add_latency(cuts: usize) -> usize {
    3 + (cuts & cut::ALL).count_ones() as usize
}

/// Clocks from operands in to sum out (no optional cut).
pub const FP_ADD_LATENCY: usize = fp_add_latency(0);

/// Pipelined float adder; see the module documentation.
#[derive(LogicBlock)]
pub struct FpAdd<const E: usize, const M: usize, const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub y: Signal<Out, Bits<N>>,
    // constants
    rd: Constant<Bit>,
    one_n: Constant<Bits<N>>,
    zero_n: Constant<Bits<N>>,
    one_w: Constant<Bits<N>>,
    k16: Constant<Bits<N>>,
    k8: Constant<Bits<N>>,
    k4: Constant<Bits<N>>,
    k2: Constant<Bits<N>>,
    k1: Constant<Bits<N>>,
    frac_bits: Constant<Bits<8>>,
    sign_n: Constant<Bits<N>>,
    mag_mask: Constant<Bits<N>>,
    exp_mask: Constant<Bits<N>>,
    frac_mask: Constant<Bits<N>>,
    hidden_n: Constant<Bits<N>>,
    inf_n: Constant<Bits<N>>,
    nan_n: Constant<Bits<N>>,
    width_n: Constant<Bits<N>>,
    ones_w: Constant<Bits<N>>,
    carry_w: Constant<Bits<N>>,
    top16: Constant<Bits<N>>,
    top8: Constant<Bits<N>>,
    top4: Constant<Bits<N>>,
    top2: Constant<Bits<N>>,
    top1: Constant<Bits<N>>,
    // stage 1
    larger: Signal<Local, Bits<N>>,
    smaller: Signal<Local, Bits<N>>,
    exp_big: Signal<Local, Bits<N>>,
    exp_small: Signal<Local, Bits<N>>,
    special: Signal<Local, Bit>,
    special_val: Signal<Local, Bits<N>>,
    sig_big_q1: DFF<Bits<N>>,
    sig_small_q1: DFF<Bits<N>>,
    exp_q1: DFF<Bits<N>>,
    diff_q1: DFF<Bits<N>>,
    sign_q1: DFF<Bit>,
    sub_q1: DFF<Bit>,
    special_q1: DFF<Bit>,
    special_val_q1: DFF<Bits<N>>,
    valid_q1: DFF<Bit>,
    tag_q1: DFF<Bits<TAG_BITS>>,
    // stage 2
    shift: Signal<Local, Bits<N>>,
    small_aligned: Signal<Local, Bits<N>>,
    lost: Signal<Local, Bit>,
    big_qa: Cut<Bits<N>>,
    small_qa: Cut<Bits<N>>,
    lost_qa: Cut<Bit>,
    sub_qa: Cut<Bit>,
    exp_qa: Cut<Bits<N>>,
    sign_qa: Cut<Bit>,
    special_qa: Cut<Bit>,
    special_val_qa: Cut<Bits<N>>,
    valid_qa: Cut<Bit>,
    tag_qa: Cut<Bits<TAG_BITS>>,
    sum_q2: DFF<Bits<N>>,
    sticky_q2: DFF<Bit>,
    exp_q2: DFF<Bits<N>>,
    sign_q2: DFF<Bit>,
    special_q2: DFF<Bit>,
    special_val_q2: DFF<Bits<N>>,
    valid_q2: DFF<Bit>,
    tag_q2: DFF<Bits<TAG_BITS>>,
    // stage 3
    s0: Signal<Local, Bits<N>>,
    s1: Signal<Local, Bits<N>>,
    s2: Signal<Local, Bits<N>>,
    s3: Signal<Local, Bits<N>>,
    s4: Signal<Local, Bits<N>>,
    s5: Signal<Local, Bits<N>>,
    e0: Signal<Local, Bits<N>>,
    e5: Signal<Local, Bits<N>>,
    lz: Signal<Local, Bits<N>>,
    lim: Signal<Local, Bits<N>>,
    full: Signal<Local, Bits<N>>,
    st0: Signal<Local, Bit>,
    sig_qn: Cut<Bits<N>>,
    bexp_qn: Cut<Bits<N>>,
    sticky_qn: Cut<Bit>,
    zero_qn: Cut<Bit>,
    sign_qn: Cut<Bit>,
    special_qn: Cut<Bit>,
    special_val_qn: Cut<Bits<N>>,
    valid_qn: Cut<Bit>,
    tag_qn: Cut<Bits<TAG_BITS>>,
    round: FpRound<E, M, N>,
    y_q3: DFF<Bits<N>>,
    valid_q3: DFF<Bit>,
    tag_q3: DFF<Bits<TAG_BITS>>,
}

/// The bits `[M+3 .. M+4-k]` of the working significand (all of `[M+3 .. 0]` when `k > M + 4`).
fn top_mask(m: usize, k: usize) -> u64 {
    let k = k.min(m + 4);
    ((1u64 << k) - 1) << (m + 4 - k)
}

impl<const E: usize, const M: usize, const N: usize> FpAdd<E, M, N> {
    /// The 3-clock adder (no optional cut) rounding in `mode`.
    pub fn new(mode: Rounding) -> Self {
        Self::with_cuts(mode, 0)
    }

    /// The adder rounding in `mode` with the optional cut points `cuts` ([`cut`]);
    /// [`fp_add_latency`]`(cuts)` clocks.
    pub fn with_cuts(mode: Rounding, cuts: usize) -> Self {
        assert!(
            cuts & !cut::ALL == 0,
            "FpAdd: unknown cut bits {:#x} (known: {:#x})",
            cuts & !cut::ALL,
            cut::ALL
        );
        let a = cuts & cut::ALIGN != 0;
        let n = cuts & cut::NORM != 0;
        assert!(
            N == 1 + E + M && E >= 4 && (8..=32).contains(&N),
            "FpAdd<{E},{M},{N}>: need N = 1+E+M in 8..=32 and E >= 4"
        );
        let c = |v: u64| Constant::new(bits::<N>(v));
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            a: Default::default(),
            b: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            y: Default::default(),
            rd: Constant::new(mode == Rounding::Down),
            one_n: c(1),
            zero_n: c(0),
            one_w: c(1),
            k16: c(16),
            k8: c(8),
            k4: c(4),
            k2: c(2),
            k1: c(1),
            frac_bits: Constant::new(bits::<8>(M as u64)),
            sign_n: c(1 << (N - 1)),
            mag_mask: c((1 << (N - 1)) - 1),
            exp_mask: c((1 << E) - 1),
            frac_mask: c((1 << M) - 1),
            hidden_n: c(1 << M),
            inf_n: c(((1 << E) - 1) << M),
            nan_n: c((((1 << E) - 1) << M) | (1 << (M - 1))),
            width_n: c(M as u64 + 5),
            ones_w: c((1u64 << N) - 1),
            carry_w: c(1 << (M + 4)),
            top16: c(top_mask(M, 16)),
            top8: c(top_mask(M, 8)),
            top4: c(top_mask(M, 4)),
            top2: c(top_mask(M, 2)),
            top1: c(top_mask(M, 1)),
            larger: Default::default(),
            smaller: Default::default(),
            exp_big: Default::default(),
            exp_small: Default::default(),
            special: Default::default(),
            special_val: Default::default(),
            sig_big_q1: Default::default(),
            sig_small_q1: Default::default(),
            exp_q1: Default::default(),
            diff_q1: Default::default(),
            sign_q1: Default::default(),
            sub_q1: Default::default(),
            special_q1: Default::default(),
            special_val_q1: Default::default(),
            valid_q1: Default::default(),
            tag_q1: Default::default(),
            shift: Default::default(),
            small_aligned: Default::default(),
            lost: Default::default(),
            big_qa: Cut::new(a),
            small_qa: Cut::new(a),
            lost_qa: Cut::new(a),
            sub_qa: Cut::new(a),
            exp_qa: Cut::new(a),
            sign_qa: Cut::new(a),
            special_qa: Cut::new(a),
            special_val_qa: Cut::new(a),
            valid_qa: Cut::new(a),
            tag_qa: Cut::new(a),
            sum_q2: Default::default(),
            sticky_q2: Default::default(),
            exp_q2: Default::default(),
            sign_q2: Default::default(),
            special_q2: Default::default(),
            special_val_q2: Default::default(),
            valid_q2: Default::default(),
            tag_q2: Default::default(),
            s0: Default::default(),
            s1: Default::default(),
            s2: Default::default(),
            s3: Default::default(),
            s4: Default::default(),
            s5: Default::default(),
            e0: Default::default(),
            e5: Default::default(),
            lz: Default::default(),
            lim: Default::default(),
            full: Default::default(),
            st0: Default::default(),
            sig_qn: Cut::new(n),
            bexp_qn: Cut::new(n),
            sticky_qn: Cut::new(n),
            zero_qn: Cut::new(n),
            sign_qn: Cut::new(n),
            special_qn: Cut::new(n),
            special_val_qn: Cut::new(n),
            valid_qn: Cut::new(n),
            tag_qn: Cut::new(n),
            round: FpRound::new(mode),
            y_q3: Default::default(),
            valid_q3: Default::default(),
            tag_q3: Default::default(),
        }
    }
}

impl<const E: usize, const M: usize, const N: usize> Logic for FpAdd<E, M, N> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            sig_big_q1,
            sig_small_q1,
            exp_q1,
            diff_q1,
            sign_q1,
            sub_q1,
            special_q1,
            special_val_q1,
            valid_q1,
            tag_q1,
            sum_q2,
            sticky_q2,
            exp_q2,
            sign_q2,
            special_q2,
            special_val_q2,
            valid_q2,
            tag_q2,
            y_q3,
            valid_q3,
            tag_q3
        );
        self.big_qa.clock.next = self.clock.val();
        self.small_qa.clock.next = self.clock.val();
        self.lost_qa.clock.next = self.clock.val();
        self.sub_qa.clock.next = self.clock.val();
        self.exp_qa.clock.next = self.clock.val();
        self.sign_qa.clock.next = self.clock.val();
        self.special_qa.clock.next = self.clock.val();
        self.special_val_qa.clock.next = self.clock.val();
        self.valid_qa.clock.next = self.clock.val();
        self.tag_qa.clock.next = self.clock.val();
        self.sig_qn.clock.next = self.clock.val();
        self.bexp_qn.clock.next = self.clock.val();
        self.sticky_qn.clock.next = self.clock.val();
        self.zero_qn.clock.next = self.clock.val();
        self.sign_qn.clock.next = self.clock.val();
        self.special_qn.clock.next = self.clock.val();
        self.special_val_qn.clock.next = self.clock.val();
        self.valid_qn.clock.next = self.clock.val();
        self.tag_qn.clock.next = self.clock.val();

        // Stage 1: order by magnitude, unpack, resolve special operands.
        if (self.a.val() & self.mag_mask.val()) >= (self.b.val() & self.mag_mask.val()) {
            self.larger.next = self.a.val();
            self.smaller.next = self.b.val();
        } else {
            self.larger.next = self.b.val();
            self.smaller.next = self.a.val();
        }
        self.exp_big.next = (self.larger.val() >> self.frac_bits.val()) & self.exp_mask.val();
        self.exp_small.next = (self.smaller.val() >> self.frac_bits.val()) & self.exp_mask.val();
        if !self.exp_big.val().any() {
            self.sig_big_q1.d.next = self.larger.val() & self.frac_mask.val();
            self.exp_q1.d.next = self.one_n.val();
        } else {
            self.sig_big_q1.d.next =
                (self.larger.val() & self.frac_mask.val()) | self.hidden_n.val();
            self.exp_q1.d.next = self.exp_big.val();
        }
        if !self.exp_small.val().any() {
            self.sig_small_q1.d.next = self.smaller.val() & self.frac_mask.val();
            if !self.exp_big.val().any() {
                self.diff_q1.d.next = self.zero_n.val();
            } else {
                self.diff_q1.d.next = self.exp_big.val() - self.one_n.val();
            }
        } else {
            self.sig_small_q1.d.next =
                (self.smaller.val() & self.frac_mask.val()) | self.hidden_n.val();
            self.diff_q1.d.next = self.exp_big.val() - self.exp_small.val();
        }
        self.sign_q1.d.next = (self.larger.val() & self.sign_n.val()).any();
        self.sub_q1.d.next = ((self.larger.val() ^ self.smaller.val()) & self.sign_n.val()).any();
        // Specials, in the order of golden::format::float::FloatFormat::add.
        self.special.next = true;
        if ((self.a.val() & self.mag_mask.val()) > self.inf_n.val())
            | ((self.b.val() & self.mag_mask.val()) > self.inf_n.val())
        {
            self.special_val.next = self.nan_n.val();
        } else if ((self.a.val() & self.mag_mask.val()) == self.inf_n.val())
            & ((self.b.val() & self.mag_mask.val()) == self.inf_n.val())
        {
            if !((self.a.val() ^ self.b.val()) & self.sign_n.val()).any() {
                self.special_val.next = self.a.val();
            } else {
                self.special_val.next = self.nan_n.val();
            }
        } else if (self.a.val() & self.mag_mask.val()) == self.inf_n.val() {
            self.special_val.next = self.a.val();
        } else if (self.b.val() & self.mag_mask.val()) == self.inf_n.val() {
            self.special_val.next = self.b.val();
        } else if !(self.a.val() & self.mag_mask.val()).any()
            & !(self.b.val() & self.mag_mask.val()).any()
        {
            if !((self.a.val() ^ self.b.val()) & self.sign_n.val()).any() {
                self.special_val.next = self.a.val();
            } else if self.rd.val() {
                self.special_val.next = self.sign_n.val();
            } else {
                self.special_val.next = self.zero_n.val();
            }
        } else if !(self.a.val() & self.mag_mask.val()).any() {
            self.special_val.next = self.b.val();
        } else if !(self.b.val() & self.mag_mask.val()).any() {
            self.special_val.next = self.a.val();
        } else {
            self.special.next = false;
            self.special_val.next = self.zero_n.val();
        }
        self.special_q1.d.next = self.special.val();
        self.special_val_q1.d.next = self.special_val.val();
        self.valid_q1.d.next = self.valid_in.val() & !self.rst.val();
        self.tag_q1.d.next = self.tag_in.val();

        // Stage 2: align with sticky, add or subtract.
        if self.diff_q1.q.val() > self.width_n.val() {
            self.shift.next = self.width_n.val();
        } else {
            self.shift.next = self.diff_q1.q.val();
        }
        self.small_aligned.next = (self.sig_small_q1.q.val() << 3) >> self.shift.val();
        self.lost.next =
            ((self.sig_small_q1.q.val() << 3) & !(self.ones_w.val() << self.shift.val())).any();
        // Cut ALIGN: the aligned operands and the side data.
        self.big_qa.d.next = self.sig_big_q1.q.val() << 3;
        self.small_qa.d.next = self.small_aligned.val();
        self.lost_qa.d.next = self.lost.val();
        self.sub_qa.d.next = self.sub_q1.q.val();
        self.exp_qa.d.next = self.exp_q1.q.val();
        self.sign_qa.d.next = self.sign_q1.q.val();
        self.special_qa.d.next = self.special_q1.q.val();
        self.special_val_qa.d.next = self.special_val_q1.q.val();
        self.valid_qa.d.next = self.valid_q1.q.val() & !self.rst.val();
        self.tag_qa.d.next = self.tag_q1.q.val();
        if self.sub_qa.q.val() {
            if self.lost_qa.q.val() {
                self.sum_q2.d.next = self.big_qa.q.val() - self.small_qa.q.val() - self.one_w.val();
            } else {
                self.sum_q2.d.next = self.big_qa.q.val() - self.small_qa.q.val();
            }
        } else {
            self.sum_q2.d.next = self.big_qa.q.val() + self.small_qa.q.val();
        }
        self.sticky_q2.d.next = self.lost_qa.q.val();
        self.exp_q2.d.next = self.exp_qa.q.val();
        self.sign_q2.d.next = self.sign_qa.q.val();
        self.special_q2.d.next = self.special_qa.q.val();
        self.special_val_q2.d.next = self.special_val_qa.q.val();
        self.valid_q2.d.next = self.valid_qa.q.val() & !self.rst.val();
        self.tag_q2.d.next = self.tag_qa.q.val();

        // Stage 3: renormalise, normalise left while the exponent stays normal, round.
        if self.sum_q2.q.val() >= self.carry_w.val() {
            self.s0.next = self.sum_q2.q.val() >> 1;
            self.e0.next = self.exp_q2.q.val() + self.one_n.val();
            self.st0.next = self.sticky_q2.q.val() | self.sum_q2.q.val().get_bit(0);
        } else {
            self.s0.next = self.sum_q2.q.val();
            self.e0.next = self.exp_q2.q.val();
            self.st0.next = self.sticky_q2.q.val();
        }
        // Normalise left by min(lz, e0 - 1) places, lz the leading zeros of s0 in the working window:
        // the shifts of 16, 8, 4, 2, 1 of the full normalisation find lz bit by bit, with no exponent
        // in the chain; the shift by e0 - 1 (taken when lz > e0 - 1, the result then subnormal with
        // exponent 1) runs beside it. This equals shifting by k wherever the top k bits are zero and the
        // exponent stays above k, for k = 16, 8, 4, 2, 1 in turn (the greedy steps spell min(lz, e0 - 1)
        // in binary, as lz < 32); for s0 = 0 (an exact zero, packed from `zero` alone) both are unused.
        self.lz.next = self.zero_n.val();
        if !(self.s0.val() & self.top16.val()).any() {
            self.s1.next = self.s0.val() << 16;
            self.lz.next = self.lz.val() | self.k16.val();
        } else {
            self.s1.next = self.s0.val();
        }
        if !(self.s1.val() & self.top8.val()).any() {
            self.s2.next = self.s1.val() << 8;
            self.lz.next = self.lz.val() | self.k8.val();
        } else {
            self.s2.next = self.s1.val();
        }
        if !(self.s2.val() & self.top4.val()).any() {
            self.s3.next = self.s2.val() << 4;
            self.lz.next = self.lz.val() | self.k4.val();
        } else {
            self.s3.next = self.s2.val();
        }
        if !(self.s3.val() & self.top2.val()).any() {
            self.s4.next = self.s3.val() << 2;
            self.lz.next = self.lz.val() | self.k2.val();
        } else {
            self.s4.next = self.s3.val();
        }
        if !(self.s4.val() & self.top1.val()).any() {
            self.full.next = self.s4.val() << 1;
            self.lz.next = self.lz.val() | self.k1.val();
        } else {
            self.full.next = self.s4.val();
        }
        self.lim.next = self.e0.val() - self.one_n.val();
        if self.lz.val() <= self.lim.val() {
            self.s5.next = self.full.val();
            self.e5.next = self.e0.val() - self.lz.val();
        } else {
            self.s5.next = self.s0.val() << self.lim.val();
            self.e5.next = self.one_n.val();
        }
        // Cut NORM: the normalised significand, its exponent and the side data.
        self.sig_qn.d.next = self.s5.val();
        self.bexp_qn.d.next = self.e5.val();
        self.sticky_qn.d.next = self.st0.val();
        // An exact zero from cancellation is +0, or -0 when rounding toward -inf.
        self.zero_qn.d.next = !self.sum_q2.q.val().any() & !self.sticky_q2.q.val();
        if !self.sum_q2.q.val().any() & !self.sticky_q2.q.val() {
            self.sign_qn.d.next = self.rd.val();
        } else {
            self.sign_qn.d.next = self.sign_q2.q.val();
        }
        self.special_qn.d.next = self.special_q2.q.val();
        self.special_val_qn.d.next = self.special_val_q2.q.val();
        self.valid_qn.d.next = self.valid_q2.q.val() & !self.rst.val();
        self.tag_qn.d.next = self.tag_q2.q.val();
        self.round.sig.next = self.sig_qn.q.val();
        self.round.bexp.next = self.bexp_qn.q.val();
        self.round.sticky.next = self.sticky_qn.q.val();
        self.round.zero.next = self.zero_qn.q.val();
        self.round.sign.next = self.sign_qn.q.val();
        if self.special_qn.q.val() {
            self.y_q3.d.next = self.special_val_qn.q.val();
        } else {
            self.y_q3.d.next = self.round.y.val();
        }
        self.valid_q3.d.next = self.valid_qn.q.val() & !self.rst.val();
        self.tag_q3.d.next = self.tag_qn.q.val();

        self.valid_out.next = self.valid_q3.q.val();
        self.tag_out.next = self.tag_q3.q.val();
        self.y.next = self.y_q3.q.val();
    }
}
