//! `EdgeLe`: one silhouette-edge condition of the bundle testers, `a * m <= b * n` on signed operands,
//! combinational (`golden::bundle::edge`'s `E_ab`: `e_a u_b <= x_b u_a` with each `u` already chosen as the
//! bound the test needs).
//!
//! # Inputs
//! - `a`, `b`: signed differences, two's complement, `V` bits;
//! - `m`, `n`: direction magnitudes, two's complement `U` bits (non-negative in use, but any code is
//!   multiplied as signed).
//!
//! # Outputs
//! - `le`: `a * m <= b * n`, the products exact at `V + U` bits (the golden model's `i128`).
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
    pub a: Signal<In, Bits<V>>,
    pub m: Signal<In, Bits<U>>,
    pub b: Signal<In, Bits<V>>,
    pub n: Signal<In, Bits<U>>,
    pub le: Signal<Out, Bit>,
}

impl<const V: usize, const U: usize> Default for EdgeLe<V, U> {
    fn default() -> Self {
        assert!(V + U <= 63, "EdgeLe<{V},{U}>: products exceed 63 bits");
        Self {
            a: Default::default(),
            m: Default::default(),
            b: Default::default(),
            n: Default::default(),
            le: Default::default(),
        }
    }
}

impl<const V: usize, const U: usize> EdgeLe<V, U> {
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

impl<const V: usize, const U: usize> Logic for EdgeLe<V, U> {
    fn update(&mut self) {
        self.le.next = Self::eval(
            self.a.val().to_u64(),
            self.m.val().to_u64(),
            self.b.val().to_u64(),
            self.n.val().to_u64(),
        );
    }

    fn connect(&mut self) {
        self.le.connect();
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
        v += "always @(*) le = lhs <= rhs;\n";
        Verilog::Custom(v)
    }
}
