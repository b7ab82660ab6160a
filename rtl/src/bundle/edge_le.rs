//! `EdgeLe`: one silhouette-edge condition of the bundle testers, `a * m <= b * n` on signed operands
//! (`golden::bundle::edge`'s `E_ab`: `e_a u_b <= x_b u_a` with each `u` already chosen as the bound the
//! test needs).
//!
//! The unit is one clock or none: with `pipelined` (the product cut point of the tester,
//! [`crate::bundle::edge_fix::cut::PRODUCT`]) both products are registered (`lhs_q`, `rhs_q`, the clock
//! a DSP block's output register would take) and compared in the next clock; without, the unit is
//! combinational.
//!
//! # Inputs
//! - `clock` (used only when `pipelined`);
//! - `a`, `b`: signed differences, two's complement, `V` bits;
//! - `m`, `n`: direction magnitudes, two's complement `U` bits (non-negative in use, but any code is
//!   multiplied as signed).
//!
//! # Outputs
//! - `le`: `a * m <= b * n`, the products exact at `V + U` bits (the golden model's `i128`), of this
//!   clock's operands (or, `pipelined`, of the last clock's).
//!
//! rust-hdl 0.46 multiplies only 16x16 unsigned and stores values over 32 bits bit by bit, so the products
//! never become rust-hdl signals: the leaf has a native model ([`EdgeLe::eval`]) and hand-written Verilog
//! whose operands are sign-extended to the product width before multiplying (an unsized `$signed` would
//! let Verilog size the products by the narrow operands). Cross-simulation of the exported Verilog checks
//! that the two agree.
//!
//! ```
//! use rust_hdl::prelude::*;
//! use rtl::bundle::edge_le::EdgeLe;
//! let mut u = EdgeLe::<9, 9>::default();
//! u.connect_all();
//! u.a.next = bits::<9>(0x1ff); // -1
//! u.m.next = bits::<9>(200);
//! u.b.next = bits::<9>(0x1fe); // -2
//! u.n.next = bits::<9>(100);
//! simulate(&mut u, 10);
//! assert!(u.le.val()); // -200 <= -200
//! ```

use crate::slab::fix::sext;
use rust_hdl::prelude::*;

/// Signed product compare; see the module documentation.
#[derive(LogicBlock)]
pub struct EdgeLe<const V: usize, const U: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<V>>,
    pub m: Signal<In, Bits<U>>,
    pub b: Signal<In, Bits<V>>,
    pub n: Signal<In, Bits<U>>,
    pub le: Signal<Out, Bit>,
    /// 1: the products are registered (`lhs_q`, `rhs_q`).
    pipelined: Constant<Bit>,
    /// The product registers: [`EdgeLe::product_word`] of the last clock's operands, in the simulation
    /// and in the Verilog alike.
    lhs_q: Signal<Local, Bits<64>>,
    rhs_q: Signal<Local, Bits<64>>,
}

impl<const V: usize, const U: usize> Default for EdgeLe<V, U> {
    /// The combinational unit.
    fn default() -> Self {
        Self::new(false)
    }
}

impl<const V: usize, const U: usize> EdgeLe<V, U> {
    /// A compare with its products registered when `pipelined`.
    pub fn new(pipelined: bool) -> Self {
        assert!(V + U <= 63, "EdgeLe<{V},{U}>: products exceed 63 bits");
        Self {
            clock: Default::default(),
            a: Default::default(),
            m: Default::default(),
            b: Default::default(),
            n: Default::default(),
            le: Default::default(),
            pipelined: Constant::new(pipelined),
            lhs_q: Default::default(),
            rhs_q: Default::default(),
        }
    }

    /// The register word of a product `x * y` of `V`- and `U`-bit codes (as in the Verilog): the
    /// `V + U`-bit two's complement product in the low bits, zeros above.
    pub fn product_word(x: u64, y: u64) -> u64 {
        (sext(x, V) * sext(y, U)) as u64 & ((1u64 << (V + U)) - 1)
    }

    /// The compare of two product words ([`EdgeLe::product_word`]).
    pub fn compare_words(l: u64, r: u64) -> bool {
        sext(l, V + U) <= sext(r, V + U)
    }

    /// The native model on port codes.
    pub fn eval(a: u64, m: u64, b: u64, n: u64) -> bool {
        sext(a, V) * sext(m, U) <= sext(b, V) * sext(n, U)
    }
}

/// `wire signed [to-1:0] dst` = the `w`-bit port `src` sign-extended to `to` bits.
pub(crate) fn sext_wire(dst: &str, src: &str, w: usize, to: usize) -> String {
    if to == w {
        return format!("wire signed [{}:0] {dst} = {src};\n", to - 1);
    }
    format!(
        "wire signed [{}:0] {dst} = {{{{{}{{{src}[{}]}}}}, {src}}};\n",
        to - 1,
        to - w,
        w - 1
    )
}

/// The optional product registers of a compare leaf (the block's `pipelined` localparam chooses): for
/// each `p`-bit signed wire `x` of `names`, a 64-bit register `x_q` (declared by rust-hdl as the
/// simulation's local) that takes `x` zero-padded every clock, and the wire `x_u`, the register's low
/// bits when `pipelined` and `x` itself otherwise.
pub(crate) fn product_register(names: &[&str], p: usize) -> String {
    let mut v = String::from(
        "// pipelined: the products are registered (x_q) and compared a clock later.\n",
    );
    for x in names {
        v += &format!("initial {x}_q = 64'd0;\n");
        let pad = if p < 64 {
            format!("{}'d0, ", 64 - p)
        } else {
            String::new()
        };
        v += &format!("always @(posedge clock) {x}_q <= {{{pad}{x}}};\n");
        v += &format!(
            "wire signed [{pm1}:0] {x}_u = pipelined ? $signed({x}_q[{pm1}:0]) : {x};\n",
            pm1 = p - 1
        );
        if p < 64 {
            // The word's pad; a name with `unused` is Verilator's waiver.
            v += &format!("wire {x}_q_pad_unused = |{x}_q[63:{p}];\n");
        }
    }
    v
}

impl<const V: usize, const U: usize> Logic for EdgeLe<V, U> {
    fn update(&mut self) {
        let (a, m, b, n) = (
            self.a.val().to_u64(),
            self.m.val().to_u64(),
            self.b.val().to_u64(),
            self.n.val().to_u64(),
        );
        if self.clock.pos_edge() {
            self.lhs_q.next = bits::<64>(Self::product_word(a, m));
            self.rhs_q.next = bits::<64>(Self::product_word(b, n));
        }
        self.le.next = if self.pipelined.val() {
            Self::compare_words(self.lhs_q.val().to_u64(), self.rhs_q.val().to_u64())
        } else {
            Self::eval(a, m, b, n)
        };
    }

    fn connect(&mut self) {
        self.le.connect();
        self.lhs_q.connect();
        self.rhs_q.connect();
    }

    fn hdl(&self) -> Verilog {
        let p = V + U;
        let mut v = format!("// a * m <= b * n, signed, both products exact at {p} bits.\n");
        v += &sext_wire("a_x", "a", V, p);
        v += &sext_wire("m_x", "m", U, p);
        v += &sext_wire("b_x", "b", V, p);
        v += &sext_wire("n_x", "n", U, p);
        v += &format!("wire signed [{}:0] lhs = a_x * m_x;\n", p - 1);
        v += &format!("wire signed [{}:0] rhs = b_x * n_x;\n", p - 1);
        v += &product_register(&["lhs", "rhs"], p);
        v += "always @(*) le = lhs_u <= rhs_u;\n";
        Verilog::Custom(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The registered path (product words, then their compare) answers as the statement does, on
    /// random codes and the extremes of every operand; a product word one bit short would not.
    #[test]
    fn product_words_compare_as_the_products() {
        fn check<const V: usize, const U: usize>(seed: u64) {
            let mut r = rand_pcg::Pcg64::seed_from_u64(seed);
            let ends = |w: usize| [0u64, 1, (1 << (w - 1)) - 1, 1 << (w - 1), (1 << w) - 1];
            let mut cases = vec![];
            for a in ends(V) {
                for m in ends(U) {
                    cases.push((
                        a,
                        m,
                        r.gen::<u64>() & ((1 << V) - 1),
                        r.gen::<u64>() & ((1 << U) - 1),
                    ));
                }
            }
            for _ in 0..20_000 {
                cases.push((
                    r.gen::<u64>() & ((1 << V) - 1),
                    r.gen::<u64>() & ((1 << U) - 1),
                    r.gen::<u64>() & ((1 << V) - 1),
                    r.gen::<u64>() & ((1 << U) - 1),
                ));
            }
            for (a, m, b, n) in cases {
                for (x, y, z, w) in [(a, m, b, n), (b, n, a, m), (a, m, a, m)] {
                    let words = EdgeLe::<V, U>::compare_words(
                        EdgeLe::<V, U>::product_word(x, y),
                        EdgeLe::<V, U>::product_word(z, w),
                    );
                    assert_eq!(
                        words,
                        EdgeLe::<V, U>::eval(x, y, z, w),
                        "{x:#x} {y:#x} {z:#x} {w:#x}"
                    );
                }
            }
        }
        check::<9, 9>(1);
        check::<13, 13>(2);
        check::<17, 17>(3);
    }
}
