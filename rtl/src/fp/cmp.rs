//! `FpCmp`: IEEE comparison of two floats of width `N` — `lt` and `le`, false when either is NaN, with
//! `-0 == +0`. Combinational; the sign-magnitude comparator of `golden::format::float::FloatFormat::{lt, le}`.
//!
//! # Inputs
//! `a`, `b` (`N` bits).
//! # Outputs
//! `lt` (`a < b`), `le` (`a <= b`).

use rust_hdl::prelude::*;

/// Float comparator; see the module documentation.
#[derive(LogicBlock)]
pub struct FpCmp<const N: usize> {
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    pub lt: Signal<Out, Bit>,
    pub le: Signal<Out, Bit>,
    mag_mask: Constant<Bits<N>>,
    sign_n: Constant<Bits<N>>,
    inf_n: Constant<Bits<N>>,
    less: Signal<Local, Bit>,
    equal: Signal<Local, Bit>,
}

impl<const N: usize> FpCmp<N> {
    /// A comparator for a format whose infinity pattern (positive) is `inf`.
    pub fn new(inf: u64) -> Self {
        Self {
            a: Default::default(),
            b: Default::default(),
            lt: Default::default(),
            le: Default::default(),
            mag_mask: Constant::new(bits::<N>((1 << (N - 1)) - 1)),
            sign_n: Constant::new(bits::<N>(1 << (N - 1))),
            inf_n: Constant::new(bits::<N>(inf)),
            less: Default::default(),
            equal: Default::default(),
        }
    }
}

impl<const N: usize> Logic for FpCmp<N> {
    #[hdl_gen]
    fn update(&mut self) {
        // Order of the magnitudes by sign: both positive, both negative, or mixed.
        self.equal.next = self.a.val() == self.b.val();
        if !(self.a.val() & self.mag_mask.val()).any() & !(self.b.val() & self.mag_mask.val()).any()
        {
            self.less.next = false;
            self.equal.next = true;
        } else if !(self.a.val() & self.sign_n.val()).any()
            & !(self.b.val() & self.sign_n.val()).any()
        {
            self.less.next = self.a.val() < self.b.val();
        } else if (self.a.val() & self.sign_n.val()).any()
            & (self.b.val() & self.sign_n.val()).any()
        {
            self.less.next =
                (self.b.val() & self.mag_mask.val()) < (self.a.val() & self.mag_mask.val());
        } else {
            self.less.next = (self.a.val() & self.sign_n.val()).any();
        }
        if ((self.a.val() & self.mag_mask.val()) > self.inf_n.val())
            | ((self.b.val() & self.mag_mask.val()) > self.inf_n.val())
        {
            self.lt.next = false;
            self.le.next = false;
        } else {
            self.lt.next = self.less.val();
            self.le.next = self.less.val() | self.equal.val();
        }
    }
}
