//! `FpMinMax`: IEEE 754-2019 `minimum` and `maximum` of two floats of width `N` — NaN if either operand
//! is NaN, `-0` below `+0` — registered, [`FP_MIN_MAX_LATENCY`] clock. Bit for bit
//! `golden::format::float::FloatFormat::{min, max}`.
//!
//! # Inputs / outputs
//! `clock`, `rst` (synchronous, clears the valid bits), `valid_in`, `tag_in` (16 bits), `a`, `b` in; `valid_out`, `tag_out`, `min`, `max` out.

use crate::fp::cmp::FpCmp;
use crate::TAG_BITS;
use golden::format::float::FloatFormat;
use rust_hdl::prelude::*;

/// Clocks from operands in to results out.
pub const FP_MIN_MAX_LATENCY: usize = 1;

/// Registered float minimum and maximum; see the module documentation.
#[derive(LogicBlock)]
pub struct FpMinMax<const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub min: Signal<Out, Bits<N>>,
    pub max: Signal<Out, Bits<N>>,
    mag_mask: Constant<Bits<N>>,
    sign_n: Constant<Bits<N>>,
    inf_n: Constant<Bits<N>>,
    nan_n: Constant<Bits<N>>,
    cmp: FpCmp<N>,
    min_q: DFF<Bits<N>>,
    max_q: DFF<Bits<N>>,
    valid_q: DFF<Bit>,
    tag_q: DFF<Bits<TAG_BITS>>,
}

impl<const N: usize> FpMinMax<N> {
    /// A unit for format `f` (whose width must be `N`).
    pub fn new(f: &FloatFormat) -> Self {
        assert_eq!(f.width() as usize, N, "FpMinMax<{N}> for {}", f.name());
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            a: Default::default(),
            b: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            min: Default::default(),
            max: Default::default(),
            mag_mask: Constant::new(bits::<N>((1 << (N - 1)) - 1)),
            sign_n: Constant::new(bits::<N>(1 << (N - 1))),
            inf_n: Constant::new(bits::<N>(f.inf(false) as u64)),
            nan_n: Constant::new(bits::<N>(f.nan() as u64)),
            cmp: FpCmp::new(f.inf(false) as u64),
            min_q: Default::default(),
            max_q: Default::default(),
            valid_q: Default::default(),
            tag_q: Default::default(),
        }
    }
}

impl<const N: usize> Logic for FpMinMax<N> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, min_q, max_q, valid_q, tag_q);
        self.cmp.a.next = self.a.val();
        self.cmp.b.next = self.b.val();
        if ((self.a.val() & self.mag_mask.val()) > self.inf_n.val())
            | ((self.b.val() & self.mag_mask.val()) > self.inf_n.val())
        {
            self.min_q.d.next = self.nan_n.val();
            self.max_q.d.next = self.nan_n.val();
        } else {
            // a is the minimum when a < b, or when they are equal and a carries the sign (-0 below +0).
            if self.cmp.lt.val() | (self.cmp.le.val() & (self.a.val() & self.sign_n.val()).any()) {
                self.min_q.d.next = self.a.val();
            } else {
                self.min_q.d.next = self.b.val();
            }
            // a is the maximum when b < a, or when they are equal and a is positive.
            if !self.cmp.le.val()
                | (self.cmp.le.val()
                    & !self.cmp.lt.val()
                    & !(self.a.val() & self.sign_n.val()).any())
            {
                self.max_q.d.next = self.a.val();
            } else {
                self.max_q.d.next = self.b.val();
            }
        }
        self.valid_q.d.next = self.valid_in.val() & !self.rst.val();
        self.tag_q.d.next = self.tag_in.val();
        self.valid_out.next = self.valid_q.q.val();
        self.tag_out.next = self.tag_q.q.val();
        self.min.next = self.min_q.q.val();
        self.max.next = self.max_q.q.val();
    }
}
