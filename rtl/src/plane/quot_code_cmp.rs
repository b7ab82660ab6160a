//! `CodeQuotCmp`: the order of a t code `c` and a fraction `num * 2^E / den` (`den > 0`) by
//! cross-multiplication: `c < num 2^E / den` iff `c * den < num * 2^E`. Combinational. It merges the
//! slab tester's t codes with the plane bounds of the fraction option ([`crate::plane::quot`]).
//!
//! # Inputs
//! - `c`: signed t code, `T` bits (read as a finite integer: the caller handles the codes of `+-inf`);
//! - `num`: signed numerator, `AB` bits; `den`: unsigned denominator, `MB` bits;
//! - the constants `E` (the bound's scale, `FD + FT - 1` in the cull-plane tester, at least 1) and
//!   `greater` (which order `y` reports).
//!
//! # Outputs
//! `y`: `c > fraction` when `greater`, else `c < fraction`; exact: `c * den` is kept at `T + MB + 1` bits
//! and `num * 2^E` is a wired shift.
//!
//! A leaf with a native model ([`code_quot_cmp`]) and hand-written Verilog, as
//! [`crate::plane::quot_cmp::QuotCmp`].

use crate::slab::fix::sext;
use golden::plane::quot::code_quot_cmp;
use rust_hdl::prelude::*;
use std::cmp::Ordering;

/// Cross-multiplied comparison of a t code with a scaled fraction; see the module documentation.
#[derive(LogicBlock)]
pub struct CodeQuotCmp<const T: usize, const AB: usize, const MB: usize> {
    pub c: Signal<In, Bits<T>>,
    pub num: Signal<In, Bits<AB>>,
    pub den: Signal<In, Bits<MB>>,
    pub y: Signal<Out, Bit>,
    /// The scale exponent `E`.
    e: Constant<Bits<8>>,
    /// 1: `y = c > fraction`; 0: `y = c < fraction`.
    greater: Constant<Bit>,
}

impl<const T: usize, const AB: usize, const MB: usize> CodeQuotCmp<T, AB, MB> {
    /// A comparator of `c` with `num * 2^e / den`, telling `c > fraction` (`greater`) or `c < fraction`.
    pub fn new(e: u32, greater: bool) -> Self {
        assert!(
            e >= 1 && T + MB < 126 && AB + (e as usize) < 126,
            "CodeQuotCmp<{T},{AB},{MB}> E {e}: products must fit an i128"
        );
        Self {
            c: Default::default(),
            num: Default::default(),
            den: Default::default(),
            y: Default::default(),
            e: Constant::new(bits::<8>(e as u64)),
            greater: Constant::new(greater),
        }
    }
}

/// `name` = the signed `from`-bit wire `src` sign-extended to `to` bits, as a Verilog declaration.
fn sign_extend(name: &str, src: &str, from: usize, to: usize) -> String {
    if to == from {
        format!("wire signed [{}:0] {name} = {src};\n", to - 1)
    } else {
        format!(
            "wire signed [{}:0] {name} = {{{{{}{{{src}[{}]}}}}, {src}}};\n",
            to - 1,
            to - from,
            from - 1
        )
    }
}

impl<const T: usize, const AB: usize, const MB: usize> Logic for CodeQuotCmp<T, AB, MB> {
    fn update(&mut self) {
        let o = code_quot_cmp(
            self.e.val().to_u64() as u32,
            sext(self.c.val().to_u64(), T),
            sext(self.num.val().to_u64(), AB),
            self.den.val().to_u64(),
        );
        self.y.next = o
            == if self.greater.val() {
                Ordering::Greater
            } else {
                Ordering::Less
            };
    }

    fn connect(&mut self) {
        self.y.connect();
    }

    fn hdl(&self) -> Verilog {
        let e = self.e.val().to_u64() as usize;
        let p = T + MB + 1; // a signed T-bit times a signed (MB + 1)-bit operand
        let q = AB + e;
        let w = p.max(q);
        let mut v = String::from("// c * den against num * 2^E, both exact at full width.\n");
        v += &format!("wire signed [{}:0] cs = c;\n", T - 1);
        v += &format!(
            "wire signed [{}:0] pc = cs * $signed({{1'b0, den}});\n",
            p - 1
        );
        v += &format!(
            "wire signed [{}:0] pn = $signed({{num, {{e{{1'b0}}}}}});\n",
            q - 1
        );
        v += &sign_extend("xc", "pc", p, w);
        v += &sign_extend("xn", "pn", q, w);
        v += "always @(*) y = greater ? xn < xc : xc < xn;\n";
        Verilog::Custom(v)
    }
}
