//! `FpRound`: rounds a normalised significand with guard and sticky bits and packs a float of format
//! `E`/`M` under a fixed rounding mode. Combinational; shared by the float adder and multiplier.
//!
//! # Parameters
//! `E`, `M`: the format; `N = 1 + E + M` its width. The working significand (`M + 5` bits) lives in the low
//! bits of an `N`-bit word, which needs `E >= 4`: one width throughout, so no casts (rust-hdl writes a
//! widening cast as a mask at the wider width, which Verilator's lint flags).
//!
//! # Inputs
//! - `sign`; `zero`: the exact result is zero (then `y` is the zero of sign `sign`);
//! - `sig` (`N` bits, of which `M + 5` are used): the result's significand with the hidden bit at bit `M + 3`, three bits below
//!   its last place (`sig[2]` is the guard bit), bit `M + 4` clear;
//! - `bexp` (`N` bits, unsigned): the biased exponent of `sig`'s hidden-bit position, at least 1. A value
//!   below normal range arrives as `bexp = 1` with the hidden bit clear (a subnormal);
//! - `sticky`: some nonzero value lies below `sig`'s last bit.
//!
//! # Output
//! `y`: `round(sig * 2^(bexp - bias - M - 3))` packed, where rounding to nearest-even uses the guard bit
//! and the OR of the bits below it; toward -inf rounds a negative inexact magnitude up; toward +inf a
//! positive one. A rounding carry renormalises; an exponent reaching all ones overflows to infinity or to
//! the largest finite value as the mode and sign require (IEEE 754 section 7.4). This is the bit-level form
//! of `golden::format::float::FloatFormat::round_pack`.

use golden::format::float::Rounding;
use rust_hdl::prelude::*;

/// Rounding and packing; see the module documentation.
#[derive(LogicBlock)]
pub struct FpRound<const E: usize, const M: usize, const N: usize> {
    pub sign: Signal<In, Bit>,
    pub zero: Signal<In, Bit>,
    pub sig: Signal<In, Bits<N>>,
    pub bexp: Signal<In, Bits<N>>,
    pub sticky: Signal<In, Bit>,
    pub y: Signal<Out, Bits<N>>,
    rne: Constant<Bit>,
    rd: Constant<Bit>,
    ru: Constant<Bit>,
    low2: Constant<Bits<N>>,
    one_w: Constant<Bits<N>>,
    one_n: Constant<Bits<N>>,
    zero_n: Constant<Bits<N>>,
    below: Signal<Local, Bit>,
    carry: Constant<Bits<N>>,
    hidden: Constant<Bits<N>>,
    frac_mask: Constant<Bits<N>>,
    exp_ones: Constant<Bits<N>>,
    sign_n: Constant<Bits<N>>,
    inf: Constant<Bits<N>>,
    max_finite: Constant<Bits<N>>,
    kept: Signal<Local, Bits<N>>,
    up: Signal<Local, Bit>,
    inexact: Signal<Local, Bit>,
    rounded: Signal<Local, Bits<N>>,
    norm: Signal<Local, Bits<N>>,
    exp: Signal<Local, Bits<N>>,
    ovf: Signal<Local, Bits<N>>,
    frac_bits: Constant<Bits<8>>,
}

impl<const E: usize, const M: usize, const N: usize> FpRound<E, M, N> {
    pub fn new(mode: Rounding) -> Self {
        assert!(
            N == 1 + E + M && E >= 4 && N <= 32,
            "FpRound<{E},{M},{N}>: need N = 1+E+M <= 32 and E >= 4"
        );
        Self {
            sign: Default::default(),
            zero: Default::default(),
            sig: Default::default(),
            bexp: Default::default(),
            sticky: Default::default(),
            y: Default::default(),
            rne: Constant::new(mode == Rounding::NearestEven),
            rd: Constant::new(mode == Rounding::Down),
            ru: Constant::new(mode == Rounding::Up),
            low2: Constant::new(bits::<N>(3)),
            one_w: Constant::new(bits::<N>(1)),
            one_n: Constant::new(bits::<N>(1)),
            zero_n: Constant::new(bits::<N>(0)),
            below: Default::default(),
            carry: Constant::new(bits::<N>(1 << (M + 1))),
            hidden: Constant::new(bits::<N>(1 << M)),
            frac_mask: Constant::new(bits::<N>((1 << M) - 1)),
            exp_ones: Constant::new(bits::<N>((1 << E) - 1)),
            sign_n: Constant::new(bits::<N>(1 << (N - 1))),
            inf: Constant::new(bits::<N>(((1 << E) - 1) << M)),
            max_finite: Constant::new(bits::<N>((((1 << E) - 1) << M) - 1)),
            kept: Default::default(),
            up: Default::default(),
            inexact: Default::default(),
            rounded: Default::default(),
            norm: Default::default(),
            exp: Default::default(),
            ovf: Default::default(),
            frac_bits: Constant::new(bits::<8>(M as u64)),
        }
    }
}

impl<const E: usize, const M: usize, const N: usize> Logic for FpRound<E, M, N> {
    #[hdl_gen]
    fn update(&mut self) {
        self.kept.next = self.sig.val() >> 3;
        self.below.next = (self.sig.val() & self.low2.val()).any() | self.sticky.val();
        self.inexact.next = self.sig.val().get_bit(2) | self.below.val();
        // The increment of the kept magnitude, by mode.
        self.up.next = false;
        if self.rne.val() {
            self.up.next =
                self.sig.val().get_bit(2) & (self.below.val() | self.kept.val().get_bit(0));
        }
        if self.rd.val() {
            self.up.next = self.sign.val() & self.inexact.val();
        }
        if self.ru.val() {
            self.up.next = !self.sign.val() & self.inexact.val();
        }
        if self.up.val() {
            self.rounded.next = self.kept.val() + self.one_w.val();
        } else {
            self.rounded.next = self.kept.val();
        }
        // A carry out of the significand renormalises (the value is then exactly 2^(M+1)).
        if self.rounded.val() >= self.carry.val() {
            self.norm.next = self.rounded.val() >> 1;
            self.exp.next = self.bexp.val() + self.one_n.val();
        } else {
            self.norm.next = self.rounded.val();
            self.exp.next = self.bexp.val();
        }
        self.ovf.next = self.inf.val();
        if (self.rd.val() & !self.sign.val()) | (self.ru.val() & self.sign.val()) {
            self.ovf.next = self.max_finite.val();
        }
        if self.zero.val() {
            self.y.next = self.zero_n.val();
            if self.sign.val() {
                self.y.next = self.sign_n.val();
            }
        } else if self.exp.val() >= self.exp_ones.val() {
            // Overflow: infinity, unless the mode rounds this sign toward zero.
            self.y.next = self.ovf.val();
            if self.sign.val() {
                self.y.next = self.ovf.val() | self.sign_n.val();
            }
        } else if self.norm.val() < self.hidden.val() {
            // Subnormal (or zero after rounding): exponent field 0.
            self.y.next = self.norm.val() & self.frac_mask.val();
            if self.sign.val() {
                self.y.next = self.sign_n.val() | (self.norm.val() & self.frac_mask.val());
            }
        } else {
            self.y.next =
                (self.exp.val() << self.frac_bits.val()) | (self.norm.val() & self.frac_mask.val());
            if self.sign.val() {
                self.y.next = self.sign_n.val()
                    | (self.exp.val() << self.frac_bits.val())
                    | (self.norm.val() & self.frac_mask.val());
            }
        }
    }
}
