//! `FpAdd`: floating-point addition of format `E`/`M` under a fixed rounding mode, fully pipelined (one
//! addition per clock), [`FP_ADD_LATENCY`] clocks. Subtraction is addition of `b` with its sign flipped.
//! Bit for bit `golden::format::float::FloatFormat::add` (subnormals kept, canonical NaN).
//!
//! # Parameters
//! `E >= 4`, `M`: the format; `N = 1 + E + M` (at most 32). The working significand, `M + 5` bits (hidden
//! bit at `M + 3`, three bits below the last place, one carry bit), lives in an `N`-bit word ([`FpRound`]).
//! The rounding mode is a constructor argument.
//!
//! # Inputs / outputs
//! `clock`, `valid_in`, `tag_in` (16 bits), `a`, `b` in; `valid_out`, `tag_out`, `y` out (registered).
//!
//! # Stages
//! 1. `_q1`: unpack; order the operands by magnitude; exponent difference; the special cases (NaN, infinities,
//!    zeros) resolved to their result.
//! 2. `_q2`: align the smaller significand by the exponent difference, OR-ing what falls off into a sticky
//!    bit; add or subtract (a sticky subtrahend borrows one, so the sticky bit stays non-negative).
//! 3. `_q3`: renormalise a carry to the right; normalise left by conditional shifts of 16, 8, 4, 2 and 1
//!    places, each taken only while the exponent stays normal (so results below the normal range come out
//!    subnormal); round and pack ([`FpRound`]).
//!
//! Three bits below the last place and a sticky bit suffice for a correctly rounded sum (Goldberg, "What
//! every computer scientist should know about floating-point arithmetic", ACM Computing Surveys 1991,
//! section 1.3 on guard digits); the random and exhaustive equivalence tests against the exact-rounding
//! model are the evidence here.

use crate::fp::round::FpRound;
use crate::TAG_BITS;
use golden::format::float::Rounding;
use rust_hdl::prelude::*;

/// Clocks from operands in to sum out.
pub const FP_ADD_LATENCY: usize = 3;

/// Pipelined float adder; see the module documentation.
#[derive(LogicBlock)]
pub struct FpAdd<const E: usize, const M: usize, const N: usize> {
    pub clock: Signal<In, Clock>,
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
    e1: Signal<Local, Bits<N>>,
    e2: Signal<Local, Bits<N>>,
    e3: Signal<Local, Bits<N>>,
    e4: Signal<Local, Bits<N>>,
    e5: Signal<Local, Bits<N>>,
    st0: Signal<Local, Bit>,
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
    pub fn new(mode: Rounding) -> Self {
        assert!(
            N == 1 + E + M && E >= 4 && (8..=32).contains(&N),
            "FpAdd<{E},{M},{N}>: need N = 1+E+M in 8..=32 and E >= 4"
        );
        let c = |v: u64| Constant::new(bits::<N>(v));
        Self {
            clock: Default::default(),
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
            e1: Default::default(),
            e2: Default::default(),
            e3: Default::default(),
            e4: Default::default(),
            e5: Default::default(),
            st0: Default::default(),
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
        self.valid_q1.d.next = self.valid_in.val();
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
        if self.sub_q1.q.val() {
            if self.lost.val() {
                self.sum_q2.d.next =
                    (self.sig_big_q1.q.val() << 3) - self.small_aligned.val() - self.one_w.val();
            } else {
                self.sum_q2.d.next = (self.sig_big_q1.q.val() << 3) - self.small_aligned.val();
            }
        } else {
            self.sum_q2.d.next = (self.sig_big_q1.q.val() << 3) + self.small_aligned.val();
        }
        self.sticky_q2.d.next = self.lost.val();
        self.exp_q2.d.next = self.exp_q1.q.val();
        self.sign_q2.d.next = self.sign_q1.q.val();
        self.special_q2.d.next = self.special_q1.q.val();
        self.special_val_q2.d.next = self.special_val_q1.q.val();
        self.valid_q2.d.next = self.valid_q1.q.val();
        self.tag_q2.d.next = self.tag_q1.q.val();

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
        if !(self.s0.val() & self.top16.val()).any() & (self.e0.val() > self.k16.val()) {
            self.s1.next = self.s0.val() << 16;
            self.e1.next = self.e0.val() - self.k16.val();
        } else {
            self.s1.next = self.s0.val();
            self.e1.next = self.e0.val();
        }
        if !(self.s1.val() & self.top8.val()).any() & (self.e1.val() > self.k8.val()) {
            self.s2.next = self.s1.val() << 8;
            self.e2.next = self.e1.val() - self.k8.val();
        } else {
            self.s2.next = self.s1.val();
            self.e2.next = self.e1.val();
        }
        if !(self.s2.val() & self.top4.val()).any() & (self.e2.val() > self.k4.val()) {
            self.s3.next = self.s2.val() << 4;
            self.e3.next = self.e2.val() - self.k4.val();
        } else {
            self.s3.next = self.s2.val();
            self.e3.next = self.e2.val();
        }
        if !(self.s3.val() & self.top2.val()).any() & (self.e3.val() > self.k2.val()) {
            self.s4.next = self.s3.val() << 2;
            self.e4.next = self.e3.val() - self.k2.val();
        } else {
            self.s4.next = self.s3.val();
            self.e4.next = self.e3.val();
        }
        if !(self.s4.val() & self.top1.val()).any() & (self.e4.val() > self.k1.val()) {
            self.s5.next = self.s4.val() << 1;
            self.e5.next = self.e4.val() - self.k1.val();
        } else {
            self.s5.next = self.s4.val();
            self.e5.next = self.e4.val();
        }
        self.round.sig.next = self.s5.val();
        self.round.bexp.next = self.e5.val();
        self.round.sticky.next = self.st0.val();
        // An exact zero from cancellation is +0, or -0 when rounding toward -inf.
        self.round.zero.next = !self.sum_q2.q.val().any() & !self.sticky_q2.q.val();
        if !self.sum_q2.q.val().any() & !self.sticky_q2.q.val() {
            self.round.sign.next = self.rd.val();
        } else {
            self.round.sign.next = self.sign_q2.q.val();
        }
        if self.special_q2.q.val() {
            self.y_q3.d.next = self.special_val_q2.q.val();
        } else {
            self.y_q3.d.next = self.round.y.val();
        }
        self.valid_q3.d.next = self.valid_q2.q.val();
        self.tag_q3.d.next = self.tag_q2.q.val();

        self.valid_out.next = self.valid_q3.q.val();
        self.tag_out.next = self.tag_q3.q.val();
        self.y.next = self.y_q3.q.val();
    }
}
