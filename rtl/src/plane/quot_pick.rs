//! `QuotPick`: the larger (or smaller) of two optional fractions, one node of a [`crate::plane::quot_tree`].
//! Combinational.
//!
//! # Inputs
//! `v0`, `n0`, `d0` and `v1`, `n1`, `d1`: two slots, each a flag (the slot holds a fraction), a signed
//! `AB`-bit numerator and a positive `MB`-bit denominator; a constant chooses min or max.
//!
//! # Outputs
//! `v`, `n`, `d`: slot 1 when it is full and slot 0 is empty or strictly worse ([`QuotCmp`], exact),
//! slot 0 otherwise. An empty slot is `-inf` for a max and `+inf` for a min.

use crate::plane::quot_cmp::QuotCmp;
use rust_hdl::prelude::*;

/// The better of two optional fractions; see the module documentation.
#[derive(LogicBlock)]
pub struct QuotPick<const AB: usize, const MB: usize> {
    pub v0: Signal<In, Bit>,
    pub n0: Signal<In, Bits<AB>>,
    pub d0: Signal<In, Bits<MB>>,
    pub v1: Signal<In, Bit>,
    pub n1: Signal<In, Bits<AB>>,
    pub d1: Signal<In, Bits<MB>>,
    pub v: Signal<Out, Bit>,
    pub n: Signal<Out, Bits<AB>>,
    pub d: Signal<Out, Bits<MB>>,
    /// 1: the smaller wins; 0: the larger.
    want_min: Constant<Bit>,
    cmp: QuotCmp<AB, MB>,
}

impl<const AB: usize, const MB: usize> QuotPick<AB, MB> {
    /// A min (`want_min`) or max node.
    pub fn new(want_min: bool) -> Self {
        Self {
            v0: Default::default(),
            n0: Default::default(),
            d0: Default::default(),
            v1: Default::default(),
            n1: Default::default(),
            d1: Default::default(),
            v: Default::default(),
            n: Default::default(),
            d: Default::default(),
            want_min: Constant::new(want_min),
            cmp: Default::default(),
        }
    }
}

impl<const AB: usize, const MB: usize> Logic for QuotPick<AB, MB> {
    #[hdl_gen]
    fn update(&mut self) {
        // `lt`: slot 1 is strictly better (min: n1/d1 < n0/d0; max: n0/d0 < n1/d1).
        self.cmp.a_num.next = self.n0.val();
        self.cmp.a_den.next = self.d0.val();
        self.cmp.b_num.next = self.n1.val();
        self.cmp.b_den.next = self.d1.val();
        if self.want_min.val() {
            self.cmp.a_num.next = self.n1.val();
            self.cmp.a_den.next = self.d1.val();
            self.cmp.b_num.next = self.n0.val();
            self.cmp.b_den.next = self.d0.val();
        }
        self.v.next = self.v0.val();
        self.n.next = self.n0.val();
        self.d.next = self.d0.val();
        if self.v1.val() & (!self.v0.val() | self.cmp.lt.val()) {
            self.v.next = true;
            self.n.next = self.n1.val();
            self.d.next = self.d1.val();
        }
    }
}
