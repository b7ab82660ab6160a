//! `FpRound`: rounds a normalised significand with guard and sticky bits and packs a float of format
//! `E`/`M` under a fixed rounding mode. Combinational; shared by the float adder and multiplier.
//!
//! # Parameters
//! `E`, `M`: the format; `N = 1 + E + M` its width; `W = M + 5` the working significand width.
//!
//! # Inputs
//! - `sign`; `zero`: the exact result is zero (then `y` is the zero of sign `sign`);
//! - `sig` (`W` bits): the result's significand with the hidden bit at bit `M + 3`, three bits below
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
//! of `golden::float::FloatFormat::round_pack`.

use golden::float::Rounding;
use rust_hdl::prelude::*;

/// Code of a rounding mode in the `mode` constants of the float blocks.
pub fn mode_code(m: Rounding) -> u64 {
    match m {
        Rounding::NearestEven => 0,
        Rounding::Down => 1,
        Rounding::Up => 2,
    }
}

/// Rounding and packing; see the module documentation.
#[derive(LogicBlock)]
pub struct FpRound<const E: usize, const M: usize, const N: usize, const W: usize> {
    pub sign: Signal<In, Bit>,
    pub zero: Signal<In, Bit>,
    pub sig: Signal<In, Bits<W>>,
    pub bexp: Signal<In, Bits<N>>,
    pub sticky: Signal<In, Bit>,
    pub y: Signal<Out, Bits<N>>,
    mode: Constant<Bits<2>>,
    carry: Constant<Bits<W>>,
    hidden: Constant<Bits<W>>,
    frac_mask: Constant<Bits<W>>,
    exp_ones: Constant<Bits<N>>,
    sign_n: Constant<Bits<N>>,
    inf: Constant<Bits<N>>,
    max_finite: Constant<Bits<N>>,
    kept: Signal<Local, Bits<W>>,
    up: Signal<Local, Bit>,
    inexact: Signal<Local, Bit>,
    rounded: Signal<Local, Bits<W>>,
    norm: Signal<Local, Bits<W>>,
    exp: Signal<Local, Bits<N>>,
    ovf: Signal<Local, Bits<N>>,
    frac_bits: Constant<Bits<8>>,
}

impl<const E: usize, const M: usize, const N: usize, const W: usize> FpRound<E, M, N, W> {
    pub fn new(mode: Rounding) -> Self {
        assert!(N == 1 + E + M && W == M + 5 && N <= 32, "FpRound<{E},{M},{N},{W}>: need N = 1+E+M <= 32, W = M+5");
        Self {
            sign: Default::default(),
            zero: Default::default(),
            sig: Default::default(),
            bexp: Default::default(),
            sticky: Default::default(),
            y: Default::default(),
            mode: Constant::new(bits::<2>(mode_code(mode))),
            carry: Constant::new(bits::<W>(1 << (M + 1))),
            hidden: Constant::new(bits::<W>(1 << M)),
            frac_mask: Constant::new(bits::<W>((1 << M) - 1)),
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

impl<const E: usize, const M: usize, const N: usize, const W: usize> Logic for FpRound<E, M, N, W> {
    #[hdl_gen]
    fn update(&mut self) {
        self.kept.next = self.sig.val() >> 3;
        self.inexact.next = self.sig.val().get_bit(2) | ((self.sig.val() & 3) != 0) | self.sticky.val();
        // The increment of the kept magnitude, by mode.
        self.up.next = false;
        if self.mode.val() == 0 {
            self.up.next = self.sig.val().get_bit(2)
                & (((self.sig.val() & 3) != 0) | self.sticky.val() | self.kept.val().get_bit(0));
        }
        if self.mode.val() == 1 {
            self.up.next = self.sign.val() & self.inexact.val();
        }
        if self.mode.val() == 2 {
            self.up.next = !self.sign.val() & self.inexact.val();
        }
        self.rounded.next = self.kept.val() + self.up.val();
        // A carry out of the significand renormalises (the value is then exactly 2^(M+1)).
        if self.rounded.val() >= self.carry.val() {
            self.norm.next = self.rounded.val() >> 1;
            self.exp.next = self.bexp.val() + 1;
        } else {
            self.norm.next = self.rounded.val();
            self.exp.next = self.bexp.val();
        }
        self.ovf.next = self.inf.val();
        if ((self.mode.val() == 1) & !self.sign.val()) | ((self.mode.val() == 2) & self.sign.val()) {
            self.ovf.next = self.max_finite.val();
        }
        if self.zero.val() {
            self.y.next = 0.into();
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
            self.y.next = bit_cast::<N, W>(self.norm.val() & self.frac_mask.val());
            if self.sign.val() {
                self.y.next = self.sign_n.val() | bit_cast::<N, W>(self.norm.val() & self.frac_mask.val());
            }
        } else {
            self.y.next = (self.exp.val() << self.frac_bits.val()) | bit_cast::<N, W>(self.norm.val() & self.frac_mask.val());
            if self.sign.val() {
                self.y.next =
                    self.sign_n.val() | (self.exp.val() << self.frac_bits.val()) | bit_cast::<N, W>(self.norm.val() & self.frac_mask.val());
            }
        }
    }
}
