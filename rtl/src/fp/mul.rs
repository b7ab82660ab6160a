//! `FpMul`: floating-point multiplication of format `E`/`M` under a fixed rounding mode, fully pipelined,
//! [`FP_MUL_LATENCY`] clocks by default and [`fp_mul_latency`]`(cuts)` with the optional cut points
//! [`cut`]. Bit for bit `golden::format::float::FloatFormat::mul` (subnormals kept, canonical
//! NaN).
//!
//! # Parameters
//! `E >= 4`, `M`: the format; `N = 1 + E + M` (at most 32). The rounding mode is a constructor argument.
//!
//! # Inputs / outputs
//! `clock`, `rst` (synchronous, clears the valid bits), `valid_in`, `tag_in` (16 bits), `a`, `b` in; `valid_out`, `tag_out`, `y` out (registered).
//!
//! # Stages
//! 1. `_q1`: unpack (subnormals take exponent 1 and no hidden bit); sum of exponents; special operands
//!    (NaN, `inf x 0`, infinities, zeros) resolved to their result.
//! 2. `_q2`: significand product (cut [`cut::RAW`], optional: the product inside [`SigMul`], side data
//!    `_qr`), normalised ([`SigMul`]); cut [`cut::PRODUCT`] (`_qp`, optional); the result's biased exponent
//!    `pos + e_a + e_b - bias - 2M`; below 1, the significand is shifted right into the subnormal range
//!    with a sticky bit.
//! 3. `_q3`: round and pack ([`FpRound`]).

use crate::cut::Cut;
use crate::fp::round::FpRound;
use crate::fp::sig_mul::SigMul;
use crate::TAG_BITS;
use golden::format::float::Rounding;
use rust_hdl::prelude::*;

/// The optional cut points of the multiplier, one bit each of the `cuts` argument of
/// [`FpMul::with_cuts`]: a register where the bit is set, a wire where it is clear.
pub mod cut {
    /// After the raw significand product, before its leading-one search (in [`super::SigMul`]; side
    /// data `_qr`).
    pub const RAW: usize = 1 << 0;
    /// After the normalised significand product, before the exponent and the subnormal shift (`_qp`).
    pub const PRODUCT: usize = 1 << 1;
    /// Every optional cut.
    pub const ALL: usize = RAW | PRODUCT;
}

/// Clocks from operands in to product out with the optional cut points `cuts`: three, and one per cut.
pub const fn fp_mul_latency(cuts: usize) -> usize {
    3 + (cuts & cut::ALL).count_ones() as usize
}

/// Clocks from operands in to product out (no optional cut).
pub const FP_MUL_LATENCY: usize = fp_mul_latency(0);

/// Pipelined float multiplier; see the module documentation.
#[derive(LogicBlock)]
pub struct FpMul<const E: usize, const M: usize, const N: usize> {
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
    frac_bits: Constant<Bits<8>>,
    sign_n: Constant<Bits<N>>,
    mag_mask: Constant<Bits<N>>,
    exp_mask: Constant<Bits<N>>,
    frac_mask: Constant<Bits<N>>,
    hidden_n: Constant<Bits<N>>,
    inf_n: Constant<Bits<N>>,
    nan_n: Constant<Bits<N>>,
    zero_n: Constant<Bits<N>>,
    one_n: Constant<Bits<N>>,
    ones_n: Constant<Bits<N>>,
    window_n: Constant<Bits<N>>,
    k_n: Constant<Bits<N>>,
    k1_n: Constant<Bits<N>>,
    false_bit: Constant<Bit>,
    // stage 1
    exp_a: Signal<Local, Bits<N>>,
    exp_b: Signal<Local, Bits<N>>,
    special: Signal<Local, Bit>,
    special_val: Signal<Local, Bits<N>>,
    sig_a_q1: DFF<Bits<N>>,
    sig_b_q1: DFF<Bits<N>>,
    exp_sum_q1: DFF<Bits<N>>,
    sign_q1: DFF<Bit>,
    special_q1: DFF<Bit>,
    special_val_q1: DFF<Bits<N>>,
    valid_q1: DFF<Bit>,
    tag_q1: DFF<Bits<TAG_BITS>>,
    // stage 2
    exp_sum_qr: Cut<Bits<N>>,
    sign_qr: Cut<Bit>,
    special_qr: Cut<Bit>,
    special_val_qr: Cut<Bits<N>>,
    valid_qr: Cut<Bit>,
    tag_qr: Cut<Bits<TAG_BITS>>,
    prod: SigMul<M, N>,
    pos_qp: Cut<Bits<N>>,
    sig_qp: Cut<Bits<N>>,
    sticky_qp: Cut<Bit>,
    exp_sum_qp: Cut<Bits<N>>,
    sign_qp: Cut<Bit>,
    special_qp: Cut<Bit>,
    special_val_qp: Cut<Bits<N>>,
    valid_qp: Cut<Bit>,
    tag_qp: Cut<Bits<TAG_BITS>>,
    t: Signal<Local, Bits<N>>,
    shift: Signal<Local, Bits<N>>,
    sig_q2: DFF<Bits<N>>,
    sticky_q2: DFF<Bit>,
    bexp_q2: DFF<Bits<N>>,
    sign_q2: DFF<Bit>,
    special_q2: DFF<Bit>,
    special_val_q2: DFF<Bits<N>>,
    valid_q2: DFF<Bit>,
    tag_q2: DFF<Bits<TAG_BITS>>,
    // stage 3
    round: FpRound<E, M, N>,
    y_q3: DFF<Bits<N>>,
    valid_q3: DFF<Bit>,
    tag_q3: DFF<Bits<TAG_BITS>>,
}

impl<const E: usize, const M: usize, const N: usize> FpMul<E, M, N> {
    /// The 3-clock multiplier (no optional cut) rounding in `mode`.
    pub fn new(mode: Rounding) -> Self {
        Self::with_cuts(mode, 0)
    }

    /// The multiplier rounding in `mode` with the optional cut points `cuts` ([`cut`]);
    /// [`fp_mul_latency`]`(cuts)` clocks.
    pub fn with_cuts(mode: Rounding, cuts: usize) -> Self {
        assert!(
            cuts & !cut::ALL == 0,
            "FpMul: unknown cut bits {:#x} (known: {:#x})",
            cuts & !cut::ALL,
            cut::ALL
        );
        let r = cuts & cut::RAW != 0;
        let p = cuts & cut::PRODUCT != 0;
        assert!(
            N == 1 + E + M && E >= 4 && (8..=32).contains(&N),
            "FpMul<{E},{M},{N}>: need N = 1+E+M in 8..=32 and E >= 4"
        );
        let c = |v: u64| Constant::new(bits::<N>(v));
        let bias = (1u64 << (E - 1)) - 1;
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
            frac_bits: Constant::new(bits::<8>(M as u64)),
            sign_n: c(1 << (N - 1)),
            mag_mask: c((1 << (N - 1)) - 1),
            exp_mask: c((1 << E) - 1),
            frac_mask: c((1 << M) - 1),
            hidden_n: c(1 << M),
            inf_n: c(((1 << E) - 1) << M),
            nan_n: c((((1 << E) - 1) << M) | (1 << (M - 1))),
            zero_n: c(0),
            one_n: c(1),
            ones_n: c((1u64 << N) - 1),
            window_n: c(M as u64 + 5),
            k_n: c(bias + 2 * M as u64),
            k1_n: c(bias + 2 * M as u64 + 1),
            false_bit: Constant::new(false),
            exp_a: Default::default(),
            exp_b: Default::default(),
            special: Default::default(),
            special_val: Default::default(),
            sig_a_q1: Default::default(),
            sig_b_q1: Default::default(),
            exp_sum_q1: Default::default(),
            sign_q1: Default::default(),
            special_q1: Default::default(),
            special_val_q1: Default::default(),
            valid_q1: Default::default(),
            tag_q1: Default::default(),
            exp_sum_qr: Cut::new(r),
            sign_qr: Cut::new(r),
            special_qr: Cut::new(r),
            special_val_qr: Cut::new(r),
            valid_qr: Cut::new(r),
            tag_qr: Cut::new(r),
            prod: SigMul::new(r),
            pos_qp: Cut::new(p),
            sig_qp: Cut::new(p),
            sticky_qp: Cut::new(p),
            exp_sum_qp: Cut::new(p),
            sign_qp: Cut::new(p),
            special_qp: Cut::new(p),
            special_val_qp: Cut::new(p),
            valid_qp: Cut::new(p),
            tag_qp: Cut::new(p),
            t: Default::default(),
            shift: Default::default(),
            sig_q2: Default::default(),
            sticky_q2: Default::default(),
            bexp_q2: Default::default(),
            sign_q2: Default::default(),
            special_q2: Default::default(),
            special_val_q2: Default::default(),
            valid_q2: Default::default(),
            tag_q2: Default::default(),
            round: FpRound::new(mode),
            y_q3: Default::default(),
            valid_q3: Default::default(),
            tag_q3: Default::default(),
        }
    }
}

impl<const E: usize, const M: usize, const N: usize> Logic for FpMul<E, M, N> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            sig_a_q1,
            sig_b_q1,
            exp_sum_q1,
            sign_q1,
            special_q1,
            special_val_q1,
            valid_q1,
            tag_q1,
            sig_q2,
            sticky_q2,
            bexp_q2,
            sign_q2,
            special_q2,
            special_val_q2,
            valid_q2,
            tag_q2,
            y_q3,
            valid_q3,
            tag_q3
        );
        self.exp_sum_qr.clock.next = self.clock.val();
        self.sign_qr.clock.next = self.clock.val();
        self.special_qr.clock.next = self.clock.val();
        self.special_val_qr.clock.next = self.clock.val();
        self.valid_qr.clock.next = self.clock.val();
        self.tag_qr.clock.next = self.clock.val();
        self.prod.clock.next = self.clock.val();
        self.pos_qp.clock.next = self.clock.val();
        self.sig_qp.clock.next = self.clock.val();
        self.sticky_qp.clock.next = self.clock.val();
        self.exp_sum_qp.clock.next = self.clock.val();
        self.sign_qp.clock.next = self.clock.val();
        self.special_qp.clock.next = self.clock.val();
        self.special_val_qp.clock.next = self.clock.val();
        self.valid_qp.clock.next = self.clock.val();
        self.tag_qp.clock.next = self.clock.val();

        // Stage 1: unpack, exponent sum, special operands.
        self.exp_a.next = (self.a.val() >> self.frac_bits.val()) & self.exp_mask.val();
        self.exp_b.next = (self.b.val() >> self.frac_bits.val()) & self.exp_mask.val();
        if self.exp_a.val().any() {
            self.sig_a_q1.d.next = (self.a.val() & self.frac_mask.val()) | self.hidden_n.val();
        } else {
            self.sig_a_q1.d.next = self.a.val() & self.frac_mask.val();
        }
        if self.exp_b.val().any() {
            self.sig_b_q1.d.next = (self.b.val() & self.frac_mask.val()) | self.hidden_n.val();
        } else {
            self.sig_b_q1.d.next = self.b.val() & self.frac_mask.val();
        }
        if self.exp_a.val().any() & self.exp_b.val().any() {
            self.exp_sum_q1.d.next = self.exp_a.val() + self.exp_b.val();
        } else if self.exp_a.val().any() {
            self.exp_sum_q1.d.next = self.exp_a.val() + self.one_n.val();
        } else if self.exp_b.val().any() {
            self.exp_sum_q1.d.next = self.exp_b.val() + self.one_n.val();
        } else {
            self.exp_sum_q1.d.next = self.one_n.val() + self.one_n.val();
        }
        self.sign_q1.d.next = ((self.a.val() ^ self.b.val()) & self.sign_n.val()).any();
        self.special.next = true;
        // NaN: a NaN operand, or inf x 0.
        if ((self.a.val() & self.mag_mask.val()) > self.inf_n.val())
            | ((self.b.val() & self.mag_mask.val()) > self.inf_n.val())
            | (((self.a.val() & self.mag_mask.val()) == self.inf_n.val())
                & !(self.b.val() & self.mag_mask.val()).any())
            | (((self.b.val() & self.mag_mask.val()) == self.inf_n.val())
                & !(self.a.val() & self.mag_mask.val()).any())
        {
            self.special_val.next = self.nan_n.val();
        } else if ((self.a.val() & self.mag_mask.val()) == self.inf_n.val())
            | ((self.b.val() & self.mag_mask.val()) == self.inf_n.val())
        {
            self.special_val.next =
                self.inf_n.val() | ((self.a.val() ^ self.b.val()) & self.sign_n.val());
        } else if !(self.a.val() & self.mag_mask.val()).any()
            | !(self.b.val() & self.mag_mask.val()).any()
        {
            self.special_val.next = (self.a.val() ^ self.b.val()) & self.sign_n.val();
        } else {
            self.special.next = false;
            self.special_val.next = self.zero_n.val();
        }
        self.special_q1.d.next = self.special.val();
        self.special_val_q1.d.next = self.special_val.val();
        self.valid_q1.d.next = self.valid_in.val() & !self.rst.val();
        self.tag_q1.d.next = self.tag_in.val();

        // Stage 2: normalised product; exponent; right shift into the subnormal range with sticky.
        self.prod.a.next = self.sig_a_q1.q.val();
        self.prod.b.next = self.sig_b_q1.q.val();
        // Cut RAW (the product's own register is inside SigMul): the side data.
        self.exp_sum_qr.d.next = self.exp_sum_q1.q.val();
        self.sign_qr.d.next = self.sign_q1.q.val();
        self.special_qr.d.next = self.special_q1.q.val();
        self.special_val_qr.d.next = self.special_val_q1.q.val();
        self.valid_qr.d.next = self.valid_q1.q.val() & !self.rst.val();
        self.tag_qr.d.next = self.tag_q1.q.val();
        // Cut PRODUCT: the normalised product and the side data.
        self.pos_qp.d.next = self.prod.pos.val();
        self.sig_qp.d.next = self.prod.sig.val();
        self.sticky_qp.d.next = self.prod.sticky.val();
        self.exp_sum_qp.d.next = self.exp_sum_qr.q.val();
        self.sign_qp.d.next = self.sign_qr.q.val();
        self.special_qp.d.next = self.special_qr.q.val();
        self.special_val_qp.d.next = self.special_val_qr.q.val();
        self.valid_qp.d.next = self.valid_qr.q.val() & !self.rst.val();
        self.tag_qp.d.next = self.tag_qr.q.val();
        self.t.next = self.pos_qp.q.val() + self.exp_sum_qp.q.val();
        if self.t.val() > self.k_n.val() {
            self.bexp_q2.d.next = self.t.val() - self.k_n.val();
            self.sig_q2.d.next = self.sig_qp.q.val();
            self.sticky_q2.d.next = self.sticky_qp.q.val();
            self.shift.next = self.zero_n.val();
        } else {
            if (self.k1_n.val() - self.t.val()) > self.window_n.val() {
                self.shift.next = self.window_n.val();
            } else {
                self.shift.next = self.k1_n.val() - self.t.val();
            }
            self.bexp_q2.d.next = self.one_n.val();
            self.sig_q2.d.next = self.sig_qp.q.val() >> self.shift.val();
            self.sticky_q2.d.next = self.sticky_qp.q.val()
                | (self.sig_qp.q.val() & !(self.ones_n.val() << self.shift.val())).any();
        }
        self.sign_q2.d.next = self.sign_qp.q.val();
        self.special_q2.d.next = self.special_qp.q.val();
        self.special_val_q2.d.next = self.special_val_qp.q.val();
        self.valid_q2.d.next = self.valid_qp.q.val() & !self.rst.val();
        self.tag_q2.d.next = self.tag_qp.q.val();

        // Stage 3: round and pack.
        self.round.sign.next = self.sign_q2.q.val();
        self.round.zero.next = self.false_bit.val();
        self.round.sig.next = self.sig_q2.q.val();
        self.round.bexp.next = self.bexp_q2.q.val();
        self.round.sticky.next = self.sticky_q2.q.val();
        if self.special_q2.q.val() {
            self.y_q3.d.next = self.special_val_q2.q.val();
        } else {
            self.y_q3.d.next = self.round.y.val();
        }
        self.valid_q3.d.next = self.valid_q2.q.val() & !self.rst.val();
        self.tag_q3.d.next = self.tag_q2.q.val();

        self.valid_out.next = self.valid_q3.q.val();
        self.tag_out.next = self.tag_q3.q.val();
        self.y.next = self.y_q3.q.val();
    }
}
