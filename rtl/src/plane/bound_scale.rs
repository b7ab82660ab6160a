//! `BoundScale`: the last step of a plane's bound ([`super::bound::PlaneBound`]), bit for bit
//! `golden::plane::fix::scale_product`: the product `A * r` scaled by `2^(C - L)`, floored for an entry
//! and ceiled for an exit, saturated to a `T`-bit t code; 0 for a plane that is neither. Combinational;
//! a native model and hand-written Verilog (a variable arithmetic shift of a value over 32 bits is beyond
//! rust-hdl 0.46's `hdl_gen`), checked against each other on every input of small units in Icarus
//! (`tb/tests/plane/bound_scale.rs`) and by cross-simulation of the testers.
//!
//! The ceiling is the floor plus one when the shift drops a set bit (not two negations around the
//! shift), and the saturation is decided on the floor beside that increment, so the clock holds one
//! shift and one short carry chain after it: post-route (ECP5) this took the 11-clock tester from 71.8
//! to 90.2 MHz (K1), and its limit moved to the first step of the bound, [`super::bound_pick::BoundPick`].
//!
//! # Inputs
//! `prod` ([`super::bound_mul::BoundMul`]'s word: the product in its low `pw` bits), `lead` (`L`),
//! `is_exit`, `is_entry`.
//! # Outputs
//! `y`: the bound as a t code (an entry saturates into `[-inf, largest finite]`, an exit into
//! `[smallest finite, +inf]`).

use crate::slab::fix::{code, sext};
use golden::plane::fix::scale_product;
use rust_hdl::prelude::*;

/// The scale, rounding and saturation; see the module documentation.
#[derive(LogicBlock)]
pub struct BoundScale<const T: usize> {
    pub prod: Signal<In, Bits<64>>,
    pub lead: Signal<In, Bits<8>>,
    pub is_exit: Signal<In, Bit>,
    pub is_entry: Signal<In, Bit>,
    pub y: Signal<Out, Bits<T>>,
    /// Bits of the product.
    pw: Constant<Bits<8>>,
    /// `max(C, 0)` and `max(-C, 0)`, `C` the scale exponent.
    c_left: Constant<Bits<8>>,
    c_right: Constant<Bits<8>>,
}

impl<const T: usize> BoundScale<T> {
    /// A unit for `pw`-bit products and scale exponent `c_shift`.
    pub fn new(pw: usize, c_shift: i32) -> Self {
        assert!(T <= 32 && (2..=64).contains(&pw) && c_shift.abs() < 64);
        Self {
            prod: Default::default(),
            lead: Default::default(),
            is_exit: Default::default(),
            is_entry: Default::default(),
            y: Default::default(),
            pw: Constant::new(bits::<8>(pw as u64)),
            c_left: Constant::new(bits::<8>(c_shift.max(0) as u64)),
            c_right: Constant::new(bits::<8>((-c_shift).max(0) as u64)),
        }
    }
}

impl<const T: usize> Logic for BoundScale<T> {
    fn update(&mut self) {
        let (ex, en) = (self.is_exit.val(), self.is_entry.val());
        let y = if ex || en {
            let pw = self.pw.val().to_u64() as usize;
            let c = self.c_left.val().to_u64() as i32 - self.c_right.val().to_u64() as i32;
            let q = sext(self.prod.val().to_u64(), pw) as i128;
            scale_product(c, T as u32, q, self.lead.val().to_u64() as u32, ex)
        } else {
            0
        };
        self.y.next = bits::<T>(code(y, T));
    }

    fn connect(&mut self) {
        self.y.connect();
    }

    fn hdl(&self) -> Verilog {
        let pw = self.pw.val().to_u64() as usize;
        let cl = self.c_left.val().to_u64() as usize;
        let qw = pw + cl;
        // The shifted value and the comparisons are at `w` bits: the product's, or one more than the t
        // code's when that is wider, so every saturation end is a literal of the width.
        let w = (qw + 1).max(T + 1);
        let ninf = -(1i64 << (T - 1));
        let pinf = (1i64 << (T - 1)) - 1;
        let lit = |v: i64| {
            if v < 0 {
                format!("(-{w}'sd{})", -v)
            } else {
                format!("{w}'sd{v}")
            }
        };
        let unused = if pw < 64 {
            format!(
                "// Product bits above pw are zero by construction.\nwire unused_prod = ^prod[63:{pw}];\n"
            )
        } else {
            String::new()
        };
        Verilog::Custom(format!(
            "\
{unused}wire signed [{pw1}:0] p = prod[pw - 8'd1:0];
// A * r * 2^(C - L), floored for an entry, ceiled for an exit, saturated to a t code. The ceiling is
// the floor plus one when the shift drops a set bit, and the saturation is decided on the floor beside
// that increment (not after it).
wire signed [{wm1}:0] q = {{{{{ext}{{p[{pw1}]}}}}, p}} <<< c_left;
wire [7:0] sh = lead + c_right;
wire signed [{wm1}:0] fl = q >>> sh;
wire [{wm1}:0] dropped = ~({{{w}{{1'b1}}}} << sh);
wire sticky = |(q & dropped);
wire up = is_exit & sticky;
// Unsaturated, the result is a t code: the increment needs only its T bits.
wire [{t1}:0] quot = fl[{t1}:0] + {{{{{t1}{{1'b0}}}}, up}};
// Exit: ceil < -inf + 1, ceil > +inf; entry: floor < -inf, floor > +inf - 1.
wire under = is_exit ? (fl < {ninf_l}) || (fl == {ninf_l} && !sticky) : (fl < {ninf_l});
wire over = is_exit ? (fl > {pinf_l}) || (fl == {pinf_l} && sticky) : (fl > {pinf1_l});
always @(*) begin
   if (!is_exit && !is_entry)
      y = {T}'d0;
   else if (under)
      y = is_exit ? {T}'d{lo_ex} : {T}'d{lo_en};
   else if (over)
      y = is_exit ? {T}'d{hi_ex} : {T}'d{hi_en};
   else
      y = quot[{t1}:0];
end
",
            pw1 = pw - 1,
            wm1 = w - 1,
            ext = w - pw,
            t1 = T - 1,
            ninf_l = lit(ninf),
            pinf_l = lit(pinf),
            pinf1_l = lit(pinf - 1),
            lo_ex = code(ninf + 1, T),
            lo_en = code(ninf, T),
            hi_ex = code(pinf, T),
            hi_en = code(pinf - 1, T),
        ))
    }
}
