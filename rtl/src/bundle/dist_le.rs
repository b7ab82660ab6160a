//! `DistLe`: one distance condition of the bundle testers, `e * 2^S <= t * u`, combinational
//! (`golden::bundle::edge`'s `T_a`: `e_a <= t_max u_a`, in `golden::bundle::fix::FixArith`'s arithmetic).
//!
//! # Inputs
//! - `e`: signed difference, two's complement, `V` bits (grid units);
//! - `t`: t code, `T` bits signed (`FT` fraction bits); the most positive code means `+inf`, the most
//!   negative `-inf`;
//! - `u`: direction magnitude, `U` bits signed (`FD` fraction bits), the bound the test chose.
//!
//! # Outputs
//! - `le`, with `S = FD + FT` (a constructor argument) bringing `e` to the scale of `t * u`:
//!   `u = 0`: `e <= 0` (`t * 0 = 0` for every `t`, infinite included); else `t = +inf`: true;
//!   `t = -inf`: false; else `e * 2^S <= t * u`, exact at `T + U` bits.
//!
//! Like [`crate::bundle::edge_le::EdgeLe`], a leaf with a native model ([`DistLe::eval`]) and hand-written Verilog
//! with operands sign-extended to the product width.
//!
//! ```
//! use rust_hdl::prelude::*;
//! use rtl::bundle::dist_le::DistLe;
//! let mut u = DistLe::<9, 14, 9>::new(10);
//! u.connect_all();
//! u.e.next = bits::<9>(3);
//! u.t.next = bits::<14>(48); // 3 * 2^4
//! u.u.next = bits::<9>(64); // 2^6
//! simulate(&mut u, 10);
//! assert!(u.le.val()); // 3 * 2^10 <= 48 * 64
//! ```

use crate::bundle::edge_le::sext_wire;
use crate::slab::fix::sext;
use rust_hdl::prelude::*;

/// Scaled distance compare; see the module documentation.
#[derive(LogicBlock)]
pub struct DistLe<const V: usize, const T: usize, const U: usize> {
    pub e: Signal<In, Bits<V>>,
    pub t: Signal<In, Bits<T>>,
    pub u: Signal<In, Bits<U>>,
    pub le: Signal<Out, Bit>,
    /// Left shift `S = FD + FT` of `e`.
    shift: Constant<Bits<8>>,
}

impl<const V: usize, const T: usize, const U: usize> DistLe<V, T, U> {
    /// A compare with `e` shifted left by `shift` bits, which must keep it within `T + U` bits.
    pub fn new(shift: usize) -> Self {
        assert!(
            T + U <= 63 && V + shift <= T + U && T <= 32,
            "DistLe<{V},{T},{U}> shift {shift}: widths out of range"
        );
        Self {
            e: Default::default(),
            t: Default::default(),
            u: Default::default(),
            le: Default::default(),
            shift: Constant::new(bits::<8>(shift as u64)),
        }
    }

    /// The native model on port codes.
    pub fn eval(shift: usize, e: u64, t: u64, u: u64) -> bool {
        let (e, t, u) = (sext(e, V), sext(t, T), sext(u, U));
        let pinf = (1i64 << (T - 1)) - 1;
        if u == 0 {
            e <= 0
        } else if t == pinf {
            true
        } else if t == -pinf - 1 {
            false
        } else {
            e << shift <= t * u
        }
    }
}

impl<const V: usize, const T: usize, const U: usize> Logic for DistLe<V, T, U> {
    fn update(&mut self) {
        self.le.next = Self::eval(
            self.shift.val().index(),
            self.e.val().to_u64(),
            self.t.val().to_u64(),
            self.u.val().to_u64(),
        );
    }

    fn connect(&mut self) {
        self.le.connect();
    }

    fn hdl(&self) -> Verilog {
        // `shift` is this block's constant, emitted by rust-hdl as a localparam.
        let p = T + U;
        let mut v = format!(
            "// u == 0 ? e <= 0 : t == +inf ? 1 : t == -inf ? 0 : (e <<< shift) <= t * u, exact at {p} bits.\n"
        );
        v += &sext_wire("e_x", "e", V, p);
        v += &sext_wire("t_x", "t", T, p);
        v += &sext_wire("u_x", "u", U, p);
        v += &format!("wire signed [{}:0] prod = t_x * u_x;\n", p - 1);
        v += &format!("wire signed [{}:0] lift = e_x <<< shift;\n", p - 1);
        v += &format!(
            "\
always @(*) begin
   if (u == {U}'d0)
      le = e[{vm1}] || (e == {V}'d0);
   else if (t == {T}'d{pinf})
      le = 1'b1;
   else if (t == {T}'d{ninf})
      le = 1'b0;
   else
      le = lift <= prod;
end
",
            vm1 = V - 1,
            pinf = (1u64 << (T - 1)) - 1,
            ninf = 1u64 << (T - 1),
        );
        Verilog::Custom(v)
    }
}
