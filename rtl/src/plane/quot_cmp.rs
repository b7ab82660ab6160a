//! `QuotCmp`: the order of two fractions with positive denominators by cross-multiplication, no
//! division: `a/ma < b/mb` iff `a * mb < b * ma`. Combinational. The comparison of the fraction option
//! of the cull-plane tester ([`crate::plane::quot`]).
//!
//! # Inputs
//! - `a_num`, `b_num`: signed numerators, `AB` bits two's complement;
//! - `a_den`, `b_den`: unsigned denominators, `MB` bits (positive for the order to mean anything: the
//!   caller only compares fractions whose denominators it knows to be positive).
//!
//! # Outputs
//! `lt` (`a < b`; swap the operands for `>`), exact: both products are kept at full width
//! (`|a * mb| < 2^(AB-1) * 2^MB`), so the comparison never rounds.
//!
//! Two signed `AB x (MB + 1)`-bit products are beyond rust-hdl 0.46 (16x16 multiplies only, values over
//! 32 bits stored bit by bit), so, like [`crate::slab::mul_round::MulRound`], this leaf has a native model
//! ([`quot_lt`]) and hand-written Verilog; cross-simulation checks that they agree.
//!
//! ```
//! use rust_hdl::prelude::*;
//! use rtl::plane::quot_cmp::QuotCmp;
//! let mut u = QuotCmp::<8, 6>::default();
//! u.connect_all();
//! u.a_num.next = bits::<8>(1); // 1/3
//! u.a_den.next = bits::<6>(3);
//! u.b_num.next = bits::<8>(2); // 2/5
//! u.b_den.next = bits::<6>(5);
//! simulate(&mut u, 10);
//! assert!(u.lt.val());
//! ```

use crate::slab::fix::sext;
use golden::plane::quot::quot_lt;
use rust_hdl::prelude::*;

/// Cross-multiplied comparison of two fractions; see the module documentation.
#[derive(LogicBlock)]
pub struct QuotCmp<const AB: usize, const MB: usize> {
    pub a_num: Signal<In, Bits<AB>>,
    pub a_den: Signal<In, Bits<MB>>,
    pub b_num: Signal<In, Bits<AB>>,
    pub b_den: Signal<In, Bits<MB>>,
    pub lt: Signal<Out, Bit>,
}

impl<const AB: usize, const MB: usize> Default for QuotCmp<AB, MB> {
    fn default() -> Self {
        assert!(
            AB + MB < 126,
            "QuotCmp<{AB},{MB}>: products must fit an i128"
        );
        Self {
            a_num: Default::default(),
            a_den: Default::default(),
            b_num: Default::default(),
            b_den: Default::default(),
            lt: Default::default(),
        }
    }
}

impl<const AB: usize, const MB: usize> Logic for QuotCmp<AB, MB> {
    fn update(&mut self) {
        let a = sext(self.a_num.val().to_u64(), AB);
        let b = sext(self.b_num.val().to_u64(), AB);
        let (ma, mb) = (self.a_den.val().to_u64(), self.b_den.val().to_u64());
        self.lt.next = quot_lt(a, ma, b, mb);
    }

    fn connect(&mut self) {
        self.lt.connect();
    }

    fn hdl(&self) -> Verilog {
        let w = AB + MB + 1; // a signed AB-bit times a signed (MB + 1)-bit operand
        Verilog::Custom(format!(
            "\
// a_num / a_den against b_num / b_den: full-width cross products, compared exactly.
wire signed [{ab1}:0] an = a_num;
wire signed [{ab1}:0] bn = b_num;
wire signed [{w1}:0] pa = an * $signed({{1'b0, b_den}});
wire signed [{w1}:0] pb = bn * $signed({{1'b0, a_den}});
always @(*) lt = pa < pb;
",
            ab1 = AB - 1,
            w1 = w - 1,
        ))
    }
}
