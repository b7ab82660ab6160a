//! `DistLe`: one distance condition of the bundle testers, `e * 2^S <= t * u`
//! (`golden::bundle::edge`'s `T_a`: `e_a <= t_max u_a`, in `golden::bundle::fix::FixArith`'s arithmetic).
//!
//! The unit is one clock or none, as [`EdgeLe`](crate::bundle::edge_le::EdgeLe): with `pipelined` the
//! product `t * u` (`prod_q`) and the side word (the special cases' verdict and `e * 2^S`, `side_q`) are
//! registered and compared in the next clock.
//!
//! # Inputs
//! - `clock` (used only when `pipelined`);
//! - `e`: signed difference, two's complement, `V` bits (grid units);
//! - `t`: t code, `T` bits signed (`FT` fraction bits); the most positive code means `+inf`, the most
//!   negative `-inf`;
//! - `u`: direction magnitude, `U` bits signed (`FD` fraction bits), the bound the test chose.
//!
//! # Outputs
//! - `le`, with `S = FD + FT` (a constructor argument) bringing `e` to the scale of `t * u`:
//!   `u = 0`: `e <= 0` (`t * 0 = 0` for every `t`, infinite included); else `t = +inf`: true;
//!   `t = -inf`: false; else `e * 2^S <= t * u`, exact at `T + U` bits; of this clock's inputs (or,
//!   `pipelined`, of the last clock's).
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

use crate::bundle::edge_le::{product_register, sext_wire};
use crate::slab::fix::sext;
use rust_hdl::prelude::*;

/// Scaled distance compare; see the module documentation.
#[derive(LogicBlock)]
pub struct DistLe<const V: usize, const T: usize, const U: usize> {
    pub clock: Signal<In, Clock>,
    pub e: Signal<In, Bits<V>>,
    pub t: Signal<In, Bits<T>>,
    pub u: Signal<In, Bits<U>>,
    pub le: Signal<Out, Bit>,
    /// Left shift `S = FD + FT` of `e`.
    shift: Constant<Bits<8>>,
    /// 1: the product and the side word are registered (`prod_q`, `side_q`).
    pipelined: Constant<Bit>,
    /// The registers: [`DistLe::words`] of the last clock's inputs, in the simulation and the Verilog.
    prod_q: Signal<Local, Bits<64>>,
    side_q: Signal<Local, Bits<64>>,
}

impl<const V: usize, const T: usize, const U: usize> DistLe<V, T, U> {
    /// A combinational compare with `e` shifted left by `shift` bits, which must keep it within `T + U`
    /// bits.
    pub fn new(shift: usize) -> Self {
        Self::with_register(shift, false)
    }

    /// The same, with its product and side word registered when `pipelined`.
    pub fn with_register(shift: usize, pipelined: bool) -> Self {
        assert!(
            T + U <= 62 && V + shift <= T + U && T <= 32,
            "DistLe<{V},{T},{U}> shift {shift}: widths out of range"
        );
        Self {
            clock: Default::default(),
            e: Default::default(),
            t: Default::default(),
            u: Default::default(),
            le: Default::default(),
            shift: Constant::new(bits::<8>(shift as u64)),
            pipelined: Constant::new(pipelined),
            prod_q: Default::default(),
            side_q: Default::default(),
        }
    }

    /// The register words for inputs `e`, `t`, `u` (as in the Verilog): the product `t * u` in the low
    /// `T + U` bits; and the side word, `e * 2^shift` in the low `T + U` bits, then the special
    /// cases' verdict, then the flag "a special case" (`u = 0`, or `t` infinite).
    pub fn words(shift: usize, e: u64, t: u64, u: u64) -> (u64, u64) {
        let p = T + U;
        let mask = (1u64 << p) - 1;
        let (e, t, u) = (sext(e, V), sext(t, T), sext(u, U));
        let pinf = (1i64 << (T - 1)) - 1;
        let special = if u == 0 {
            Some(e <= 0)
        } else if t == pinf {
            Some(true)
        } else if t == -pinf - 1 {
            Some(false)
        } else {
            None
        };
        let side = ((e << shift) as u64 & mask)
            | ((special == Some(true)) as u64) << p
            | (special.is_some() as u64) << (p + 1);
        ((t * u) as u64 & mask, side)
    }

    /// The compare of the register words ([`DistLe::words`]).
    pub fn decide(prod: u64, side: u64) -> bool {
        let p = T + U;
        if side >> (p + 1) & 1 == 1 {
            side >> p & 1 == 1
        } else {
            sext(side & ((1u64 << p) - 1), p) <= sext(prod, p)
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
        let (prod, side) = Self::words(
            self.shift.val().index(),
            self.e.val().to_u64(),
            self.t.val().to_u64(),
            self.u.val().to_u64(),
        );
        if self.clock.pos_edge() {
            self.prod_q.next = bits::<64>(prod);
            self.side_q.next = bits::<64>(side);
        }
        self.le.next = if self.pipelined.val() {
            Self::decide(self.prod_q.val().to_u64(), self.side_q.val().to_u64())
        } else {
            Self::decide(prod, side)
        };
    }

    fn connect(&mut self) {
        self.le.connect();
        self.prod_q.connect();
        self.side_q.connect();
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
// The special cases' verdict: special_c set for u = 0 or t infinite, verdict_c their answer.
reg special_c;
reg verdict_c;
always @(*) begin
   special_c = 1'b1;
   verdict_c = 1'b0;
   if (u == {U}'d0)
      verdict_c = e[{vm1}] || (e == {V}'d0);
   else if (t == {T}'d{pinf})
      verdict_c = 1'b1;
   else if (t == {T}'d{ninf})
      verdict_c = 1'b0;
   else
      special_c = 1'b0;
end
wire signed [{p1}:0] side = {{special_c, verdict_c, lift}};
",
            vm1 = V - 1,
            p1 = p + 1,
            pinf = (1u64 << (T - 1)) - 1,
            ninf = 1u64 << (T - 1),
        );
        v += &product_register(&["prod"], p);
        v += &product_register(&["side"], p + 2);
        v += &format!(
            "always @(*) le = side_u[{p1}] ? side_u[{p}] : $signed(side_u[{pm1}:0]) <= prod_u;\n",
            p1 = p + 1,
            pm1 = p - 1
        );
        Verilog::Custom(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The registered path (product and side word, then [`DistLe::decide`]) answers as the statement
    /// ([`DistLe::eval`]), on random codes and every special case: `u = 0`, `t` at both infinite ends.
    #[test]
    fn register_words_decide_as_the_statement() {
        fn check<const V: usize, const T: usize, const U: usize>(shift: usize, seed: u64) {
            let mut r = rand_pcg::Pcg64::seed_from_u64(seed);
            let pinf = (1u64 << (T - 1)) - 1;
            let mut specials = [0u64; 3];
            for _ in 0..30_000 {
                let e = r.gen::<u64>() & ((1 << V) - 1);
                let mut t = r.gen::<u64>() & ((1 << T) - 1);
                let mut u = r.gen::<u64>() & ((1 << U) - 1);
                match r.gen_range(0..5) {
                    0 => u = 0,
                    1 => t = pinf,
                    2 => t = pinf + 1,
                    _ => {}
                }
                let (p, s) = DistLe::<V, T, U>::words(shift, e, t, u);
                let special = s >> (T + U + 1) & 1 == 1;
                specials[(u == 0) as usize + special as usize] += 1;
                assert_eq!(
                    DistLe::<V, T, U>::decide(p, s),
                    DistLe::<V, T, U>::eval(shift, e, t, u),
                    "e {e:#x} t {t:#x} u {u:#x}"
                );
            }
            assert!(specials.iter().all(|&c| c > 1_000), "{specials:?}");
        }
        check::<9, 14, 9>(10, 1);
        check::<13, 20, 13>(16, 2);
        check::<17, 24, 17>(20, 3);
    }
}
