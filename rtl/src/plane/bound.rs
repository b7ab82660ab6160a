//! `PlaneBound`: what one cull plane does to the ray's interval, from its sums — the entry or exit bound
//! `t*` through the directed reciprocal table, or a parallel cull (`golden::plane::fix::bound_from_sums`,
//! which documents the arithmetic and why every bound is conservative). Combinational.
//!
//! Inside: classification by the signs of `den_lo`, `den_hi`; the magnitude and the table half (upper or
//! lower bound of `1/m`) chosen by the sign of `A`; a leading-one search; the `2^R`-entry table; the
//! product `A * r`, shifted by `C - L` with floor (entry) or ceil (exit); saturation to a t code. The wide
//! signed product and the variable shift are beyond rust-hdl 0.46 (16x16 multiplies, values over 32 bits
//! stored bit by bit), so, like [`crate::slab::mul_round::MulRound`], the block has a native model and
//! hand-written Verilog, checked against each other by cross-simulation.
//!
//! Outputs: `is_entry`, `is_exit`, `par` (parallel and on the empty side: cull) and `y`, the bound as a
//! `T`-bit t code (0 when the plane is neither an entry nor an exit plane).

use crate::slab::fix::{code, sext};
use golden::plane::fix::{bound_from_sums, recip_entry, PlaneEffect};
use rust_hdl::prelude::*;

/// One plane's effect; see the module documentation.
#[derive(LogicBlock)]
pub struct PlaneBound<const SB: usize, const EB: usize, const T: usize> {
    pub s: Signal<In, Bits<SB>>,
    pub den_lo: Signal<In, Bits<EB>>,
    pub den_hi: Signal<In, Bits<EB>>,
    pub y: Signal<Out, Bits<T>>,
    pub is_entry: Signal<Out, Bit>,
    pub is_exit: Signal<Out, Bit>,
    pub par: Signal<Out, Bit>,
    /// Table index bits `R`.
    r_bits: Constant<Bits<8>>,
    /// `max(C, 0)` and `max(-C, 0)`, `C` the scale exponent.
    c_left: Constant<Bits<8>>,
    c_right: Constant<Bits<8>>,
}

impl<const SB: usize, const EB: usize, const T: usize> PlaneBound<SB, EB, T> {
    /// A unit with a `2^r_bits`-entry table and scale exponent `c_shift`.
    pub fn new(r_bits: u32, c_shift: i32) -> Self {
        assert!((1..=12).contains(&r_bits) && T <= 32 && SB < 63 && EB < 63);
        Self {
            s: Default::default(),
            den_lo: Default::default(),
            den_hi: Default::default(),
            y: Default::default(),
            is_entry: Default::default(),
            is_exit: Default::default(),
            par: Default::default(),
            r_bits: Constant::new(bits::<8>(r_bits as u64)),
            c_left: Constant::new(bits::<8>(c_shift.max(0) as u64)),
            c_right: Constant::new(bits::<8>((-c_shift).max(0) as u64)),
        }
    }

    fn c_shift(&self) -> i32 {
        self.c_left.val().to_u64() as i32 - self.c_right.val().to_u64() as i32
    }
}

impl<const SB: usize, const EB: usize, const T: usize> Logic for PlaneBound<SB, EB, T> {
    fn update(&mut self) {
        let e = bound_from_sums(
            self.r_bits.val().to_u64() as u32,
            self.c_shift(),
            T as u32,
            EB as u32,
            sext(self.s.val().to_u64(), SB),
            sext(self.den_lo.val().to_u64(), EB),
            sext(self.den_hi.val().to_u64(), EB),
        );
        let (en, ex, par, y) = match e {
            PlaneEffect::None => (false, false, false, 0),
            PlaneEffect::Entry(t) => (true, false, false, t),
            PlaneEffect::Exit(t) => (false, true, false, t),
            PlaneEffect::Cull => (false, false, true, 0),
        };
        self.is_entry.next = en;
        self.is_exit.next = ex;
        self.par.next = par;
        self.y.next = bits::<T>(code(y, T));
    }

    fn connect(&mut self) {
        self.y.connect();
        self.is_entry.connect();
        self.is_exit.connect();
        self.par.connect();
    }

    fn hdl(&self) -> Verilog {
        let r = self.r_bits.val().to_u64() as usize;
        let cl = self.c_left.val().to_u64() as usize;
        let pw = SB + 1 + r + 3; // signed A (SB+1) times signed {0, r} (R+3)
        let qw = pw + cl;
        // Bits of an index into the (EB + R)-bit shifted magnitude.
        let lw = (usize::BITS - (EB + r - 1).leading_zeros()) as usize;
        let ninf = -(1i64 << (T - 1));
        let pinf = (1i64 << (T - 1)) - 1;
        let lit = |v: i64| {
            if v < 0 {
                format!("(-{}'sd{})", qw + 1, -v)
            } else {
                format!("{}'sd{}", qw + 1, v)
            }
        };
        let mut table = String::new();
        for i in 0..(1u64 << r) {
            let (lo, hi) = recip_entry(r as u32, i);
            table += &format!(
                "      {r}'d{i}: begin rl = {w}'d{lo}; rh = {w}'d{hi}; end\n",
                w = r + 2
            );
        }
        let widen = if qw > pw {
            format!("{{{{{}{{prod[{}]}}}}, prod}}", qw - pw, pw - 1)
        } else {
            "prod".to_string()
        };
        Verilog::Custom(format!(
            "\
// Classification: an exit plane when den_lo > 0, an entry plane when den_hi < 0, a parallel cull when
// both are zero and s > 0.
wire s_neg = s[{sb1}];
wire s_pos = !s[{sb1}] && (s != {SB}'d0);
wire ex = !den_lo[{eb1}] && (den_lo != {EB}'d0);
wire en = !ex && den_hi[{eb1}];
wire signed [{SB}:0] sx = {{s[{sb1}], s}};
wire signed [{SB}:0] a = ex ? -sx : sx;
wire [{eb1}:0] mag = ex ? (s_pos ? den_hi : den_lo) : (s_neg ? -den_hi : -den_lo);
wire upper = (!a[{SB}]) == ex;
// Leading one of the magnitude, and the R table-index bits below it.
reg [{lw1}:0] lead;
integer i;
always @(*) begin
   lead = {lw}'d0;
   for (i = 0; i < {EB}; i = i + 1)
      if (mag[i]) lead = i[{lw1}:0];
end
wire [{mw1}:0] mag_up = {{{{{r}{{1'b0}}}}, mag}} << r_bits;
wire [{r1}:0] idx = mag_up[lead +: {r}];
reg [{r21}:0] rl;
reg [{r21}:0] rh;
always @(*) begin
   case (idx)
{table}      default: begin rl = {r2}'d0; rh = {r2}'d0; end
   endcase
end
wire [{r21}:0] rv = upper ? rh : rl;
// A * r * 2^(C - lead), floored for an entry, ceiled for an exit, saturated to a t code.
wire signed [{pw1}:0] prod = a * $signed({{1'b0, rv}});
wire signed [{qw1}:0] prod_w = {widen};
wire signed [{qw}:0] q = {{prod_w[{qw1}], prod_w}} <<< c_left;
wire [7:0] sh = {{{{{pad}{{1'b0}}}}, lead}} + c_right;
wire signed [{qw}:0] quot = ex ? -((-q) >>> sh) : (q >>> sh);
wire signed [{qw}:0] lo = ex ? {lo_ex} : {lo_en};
wire signed [{qw}:0] hi = ex ? {hi_ex} : {hi_en};
always @(*) begin
   is_exit = ex;
   is_entry = en;
   par = !ex && !en && (den_lo == {EB}'d0) && (den_hi == {EB}'d0) && s_pos;
   if (!ex && !en)
      y = {T}'d0;
   else if (quot < lo)
      y = lo[{t1}:0];
   else if (quot > hi)
      y = hi[{t1}:0];
   else
      y = quot[{t1}:0];
end
",
            sb1 = SB - 1,
            eb1 = EB - 1,
            mw1 = EB + r - 1,
            lw = lw,
            lw1 = lw - 1,
            pad = 8 - lw,
            r1 = r - 1,
            r2 = r + 2,
            r21 = r + 1,
            pw1 = pw - 1,
            qw1 = qw - 1,
            t1 = T - 1,
            lo_ex = lit(ninf + 1),
            lo_en = lit(ninf),
            hi_ex = lit(pinf),
            hi_en = lit(pinf - 1),
        ))
    }
}
