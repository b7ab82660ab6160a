//! `BoundScale`: the last step of a plane's bound ([`super::bound::PlaneBound`]), bit for bit
//! `golden::plane::fix::scale_product`: the product `A * r` scaled by `2^(C - L)`, floored for an entry
//! and ceiled for an exit, saturated to a `T`-bit t code; 0 for a plane that is neither. Combinational;
//! a native model and hand-written Verilog (a variable arithmetic shift of a value over 32 bits is beyond
//! rust-hdl 0.46's `hdl_gen`), checked against each other by cross-simulation of the testers.
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
        let ninf = -(1i64 << (T - 1));
        let pinf = (1i64 << (T - 1)) - 1;
        let lit = |v: i64| {
            if v < 0 {
                format!("(-{}'sd{})", qw + 1, -v)
            } else {
                format!("{}'sd{}", qw + 1, v)
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
// A * r * 2^(C - L), floored for an entry, ceiled for an exit, saturated to a t code.
wire signed [{qw}:0] q = {{{{{ext}{{p[{pw1}]}}}}, p}} <<< c_left;
wire [7:0] sh = lead + c_right;
wire signed [{qw}:0] quot = is_exit ? -((-q) >>> sh) : (q >>> sh);
wire signed [{qw}:0] lo = is_exit ? {lo_ex} : {lo_en};
wire signed [{qw}:0] hi = is_exit ? {hi_ex} : {hi_en};
always @(*) begin
   if (!is_exit && !is_entry)
      y = {T}'d0;
   else if (quot < lo)
      y = lo[{t1}:0];
   else if (quot > hi)
      y = hi[{t1}:0];
   else
      y = quot[{t1}:0];
end
",
            pw1 = pw - 1,
            ext = qw + 1 - pw,
            t1 = T - 1,
            lo_ex = lit(ninf + 1),
            lo_en = lit(ninf),
            hi_ex = lit(pinf),
            hi_en = lit(pinf - 1),
        ))
    }
}
