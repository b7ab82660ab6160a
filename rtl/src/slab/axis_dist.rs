//! `AxisDist`: one axis of the slab tester's first stage — distances to the near and far planes in the
//! direction of travel, and the empty-slab flag. Combinational.
//!
//! # Inputs
//! - `lo`, `hi`: the box slab, signed `G`-bit grid coordinates;
//! - `o_lo`, `o_hi`: the origin interval on this axis;
//! - `neg`: the direction component is negative.
//!
//! # Outputs
//! - `e`: `neg ? o_lo - hi : lo - o_hi` and `x`: `neg ? o_hi - lo : hi - o_lo`, signed `D = G + 1` bits;
//! - `empty`: `lo > hi` (signed).
//!
//! The differences are taken in offset binary, `(a ^ 2^(G-1)) - (b ^ 2^(G-1))` zero-extended to `D` bits,
//! which equals the two's complement difference and needs no sign extension (`golden::slab::fix::
//! axis_distances` is the model). It is a block of its own because rust-hdl 0.46 evaluates the argument of
//! `bit_cast` in Rust to find its width, which fails for an array element indexed by a loop variable.

use rust_hdl::prelude::*;

/// Per-axis distances and emptiness; see the module documentation.
#[derive(LogicBlock)]
pub struct AxisDist<const G: usize, const D: usize> {
    pub lo: Signal<In, Bits<G>>,
    pub hi: Signal<In, Bits<G>>,
    pub o_lo: Signal<In, Bits<G>>,
    pub o_hi: Signal<In, Bits<G>>,
    pub neg: Signal<In, Bit>,
    pub e: Signal<Out, Bits<D>>,
    pub x: Signal<Out, Bits<D>>,
    pub empty: Signal<Out, Bit>,
    sign_g: Constant<Bits<G>>,
}

impl<const G: usize, const D: usize> Default for AxisDist<G, D> {
    fn default() -> Self {
        assert_eq!(D, G + 1, "AxisDist<{G},{D}>: D must be G + 1");
        Self {
            lo: Default::default(),
            hi: Default::default(),
            o_lo: Default::default(),
            o_hi: Default::default(),
            neg: Default::default(),
            e: Default::default(),
            x: Default::default(),
            empty: Default::default(),
            sign_g: Constant::new(bits::<G>(1 << (G - 1))),
        }
    }
}

impl<const G: usize, const D: usize> Logic for AxisDist<G, D> {
    #[hdl_gen]
    fn update(&mut self) {
        if self.neg.val() {
            self.e.next = bit_cast::<D, G>(self.o_lo.val() ^ self.sign_g.val())
                - bit_cast::<D, G>(self.hi.val() ^ self.sign_g.val());
            self.x.next = bit_cast::<D, G>(self.o_hi.val() ^ self.sign_g.val())
                - bit_cast::<D, G>(self.lo.val() ^ self.sign_g.val());
        } else {
            self.e.next = bit_cast::<D, G>(self.lo.val() ^ self.sign_g.val())
                - bit_cast::<D, G>(self.o_hi.val() ^ self.sign_g.val());
            self.x.next = bit_cast::<D, G>(self.hi.val() ^ self.sign_g.val())
                - bit_cast::<D, G>(self.o_lo.val() ^ self.sign_g.val());
        }
        self.empty.next = (self.lo.val() ^ self.sign_g.val()) > (self.hi.val() ^ self.sign_g.val());
    }
}
