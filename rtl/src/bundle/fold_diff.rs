//! `FoldDiff`: the four differences of one axis of a bundle tester, for both folds, and the empty-slab
//! flag, combinational (`golden::bundle::edge`'s `fold`, its two `sub` pairs).
//!
//! # Inputs
//! - `lo`, `hi`: the box slab, signed `G`-bit grid coordinates;
//! - `o_e`, `o_x`: the origin ends that bound `e` and `x` (AllHit: `o_lo`, `o_hi`; AnyHit: swapped).
//!
//! # Outputs
//! - `e_pos = lo - o_e`, `x_pos = hi - o_x` (positive fold), `e_neg = o_x - hi`, `x_neg = o_e - lo`
//!   (negative fold), signed `V = G + 1` bits, exact;
//! - `empty`: `lo > hi` (signed).
//!
//! A leaf with a native model ([`FoldDiff::eval`]) and hand-written Verilog because a `G`-to-`V`-bit
//! sign extension written in `#[hdl_gen]` (`bit_cast` of an offset-binary code, as
//! [`crate::slab::axis_dist::AxisDist`] does) comes out as a width-mismatched XOR that Verilator's lint flags.
//!
//! ```
//! use rust_hdl::prelude::*;
//! use rtl::bundle::fold_diff::FoldDiff;
//! let mut u = FoldDiff::<8, 9>::default();
//! u.connect_all();
//! u.lo.next = bits::<8>(0x80); // -128
//! u.hi.next = bits::<8>(127);
//! u.o_e.next = bits::<8>(127);
//! u.o_x.next = bits::<8>(0x80);
//! simulate(&mut u, 10);
//! assert_eq!(u.e_pos.val().to_u64(), 0x101); // -255 in 9 bits
//! assert_eq!(u.x_pos.val().to_u64(), 255);
//! assert!(!u.empty.val());
//! ```

use crate::bundle::edge_le::sext_wire;
use crate::slab::fix::{code, sext};
use rust_hdl::prelude::*;

/// Per-axis differences of both folds; see the module documentation.
#[derive(LogicBlock)]
pub struct FoldDiff<const G: usize, const V: usize> {
    pub lo: Signal<In, Bits<G>>,
    pub hi: Signal<In, Bits<G>>,
    pub o_e: Signal<In, Bits<G>>,
    pub o_x: Signal<In, Bits<G>>,
    pub e_pos: Signal<Out, Bits<V>>,
    pub x_pos: Signal<Out, Bits<V>>,
    pub e_neg: Signal<Out, Bits<V>>,
    pub x_neg: Signal<Out, Bits<V>>,
    pub empty: Signal<Out, Bit>,
}

impl<const G: usize, const V: usize> Default for FoldDiff<G, V> {
    fn default() -> Self {
        assert_eq!(V, G + 1, "FoldDiff<{G},{V}>: V must be G + 1");
        Self {
            lo: Default::default(),
            hi: Default::default(),
            o_e: Default::default(),
            o_x: Default::default(),
            e_pos: Default::default(),
            x_pos: Default::default(),
            e_neg: Default::default(),
            x_neg: Default::default(),
            empty: Default::default(),
        }
    }
}

impl<const G: usize, const V: usize> FoldDiff<G, V> {
    /// The native model on port codes: `([e_pos, x_pos, e_neg, x_neg], empty)`.
    pub fn eval(lo: u64, hi: u64, o_e: u64, o_x: u64) -> ([u64; 4], bool) {
        let [lo, hi, o_e, o_x] = [lo, hi, o_e, o_x].map(|v| sext(v, G));
        (
            [lo - o_e, hi - o_x, o_x - hi, o_e - lo].map(|d| code(d, V)),
            lo > hi,
        )
    }
}

impl<const G: usize, const V: usize> Logic for FoldDiff<G, V> {
    fn update(&mut self) {
        let (d, empty) = Self::eval(
            self.lo.val().to_u64(),
            self.hi.val().to_u64(),
            self.o_e.val().to_u64(),
            self.o_x.val().to_u64(),
        );
        self.e_pos.next = bits::<V>(d[0]);
        self.x_pos.next = bits::<V>(d[1]);
        self.e_neg.next = bits::<V>(d[2]);
        self.x_neg.next = bits::<V>(d[3]);
        self.empty.next = empty;
    }

    fn connect(&mut self) {
        self.e_pos.connect();
        self.x_pos.connect();
        self.e_neg.connect();
        self.x_neg.connect();
        self.empty.connect();
    }

    fn hdl(&self) -> Verilog {
        let mut v = format!("// Differences of both folds, operands sign-extended to {V} bits.\n");
        for p in ["lo", "hi", "o_e", "o_x"] {
            v += &sext_wire(&format!("{p}_x"), p, G, V);
        }
        v += "always @(*) begin\n";
        v += "   e_pos = lo_x - o_e_x;\n   x_pos = hi_x - o_x_x;\n";
        v += "   e_neg = o_x_x - hi_x;\n   x_neg = o_e_x - lo_x;\n";
        v += "   empty = lo_x > hi_x;\nend\n";
        Verilog::Custom(v)
    }
}
