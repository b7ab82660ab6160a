//! `MulRound`: signed-by-unsigned multiply, scale by `2^-S` with directed rounding, saturate to a t code.
//!
//! rust-hdl 0.46 only implements 16x16 multiplies in `#[hdl_gen]` (measured on this toolchain),
//! and stores values wider than 32 bits bit by bit, so the wide product never becomes a rust-hdl signal:
//! this block has a hand-written simulation model (native i64) and hand-written Verilog with explicitly
//! signed, full-width operands. Cross-simulation of the exported Verilog checks that the two agree.
//!
//! The unit is one clock or two: with `pipelined` (a cut point of the tester, [`crate::cut`]) the
//! product `a * m` and the unbounded flag are registered (`p_q`, the clock a DSP block's output
//! register would take), and the shift, rounding and saturation use the registered product in the next
//! clock; without, the whole unit is combinational.
//!
//! # Inputs
//! - `clock` (used only when `pipelined`).
//! - `a`: signed distance, two's complement, `D` bits.
//! - `m`: unsigned inverse-direction magnitude, `I` bits; all ones means "unbounded".
//!
//! # Outputs
//! - `y`: t code, two's complement, `T` bits, of this clock's inputs (or, `pipelined`, of the last
//!   clock's):
//!   - floor mode (a lower bound): `m` unbounded gives `a > 0 ? +inf : -inf`, otherwise
//!     `clamp(floor(a * m / 2^S), -inf, +inf - 1)`;
//!   - ceil mode (an upper bound): `m` unbounded gives `a >= 0 ? +inf : -inf`, otherwise
//!     `clamp(ceil(a * m / 2^S), -inf + 1, +inf)`;
//!
//!   where `-inf` is the code `-2^(T-1)` and `+inf` the code `2^(T-1) - 1`. This is exactly
//!   `golden::slab::fix::{mul_floor, mul_ceil}`.
//!
//! ```
//! use rust_hdl::prelude::*;
//! use rtl::slab::mul_round::MulRound;
//! let mut u = MulRound::<9, 12, 14>::new(false, 4, false);
//! u.connect_all();
//! u.a.next = bits::<9>(3);
//! u.m.next = bits::<12>(100);
//! simulate(&mut u, 10);
//! assert_eq!(u.y.val().to_u64(), 18); // floor(300 / 16)
//! ```

use rust_hdl::prelude::*;

/// Scaled multiply with directed rounding and saturation; see the module documentation.
#[derive(LogicBlock)]
pub struct MulRound<const D: usize, const I: usize, const T: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<D>>,
    pub m: Signal<In, Bits<I>>,
    pub y: Signal<Out, Bits<T>>,
    /// 1 for ceil (upper bound), 0 for floor (lower bound).
    ceil: Constant<Bit>,
    /// Right shift `S` from product fraction bits to t fraction bits.
    shift: Constant<Bits<8>>,
    /// 1: the product is registered (`p_q`).
    pipelined: Constant<Bit>,
    /// The product register: [`MulRound::product_word`] of the last clock's operands, in the
    /// simulation and in the Verilog alike.
    p_q: Signal<Local, Bits<64>>,
}

impl<const D: usize, const I: usize, const T: usize> MulRound<D, I, T> {
    /// A unit rounding up (`ceil = true`) or down, shifting right by `shift` bits, with its product
    /// registered when `pipelined`.
    pub fn new(ceil: bool, shift: usize, pipelined: bool) -> Self {
        assert!(
            D + I <= 61 && T <= 32 && shift < D + I,
            "MulRound<{D},{I},{T}> shift {shift}: widths out of range"
        );
        Self {
            clock: Default::default(),
            a: Default::default(),
            m: Default::default(),
            y: Default::default(),
            ceil: Constant::new(ceil),
            shift: Constant::new(bits::<8>(shift as u64)),
            pipelined: Constant::new(pipelined),
            p_q: Default::default(),
        }
    }

    /// The register word of the product stage for operands `a`, `m` (as in the Verilog): the product
    /// in the low `D + I` bits (two's complement), then the flag "`a` positive" (`a > 0`, or `a >= 0`
    /// when rounding up), then the flag "`m` unbounded".
    pub fn product_word(ceil: bool, a: u64, m: u64) -> u64 {
        let p = D + I;
        let a = ((a << (64 - D)) as i64) >> (64 - D); // sign-extend
        let unbounded = m == (1u64 << I) - 1;
        let positive = a > 0 || (ceil && a == 0);
        ((a * m as i64) as u64 & ((1u64 << p) - 1))
            | (positive as u64) << p
            | (unbounded as u64) << (p + 1)
    }

    /// The t code of a product word ([`MulRound::product_word`]): the round and saturate stage.
    pub fn round_word(ceil: bool, shift: usize, w: u64) -> u64 {
        let p = D + I;
        let ninf = -(1i64 << (T - 1));
        let pinf = (1i64 << (T - 1)) - 1;
        let y = if w >> (p + 1) & 1 == 1 {
            if w >> p & 1 == 1 {
                pinf
            } else {
                ninf
            }
        } else {
            let prod = ((w << (64 - p)) as i64) >> (64 - p);
            if ceil {
                (-((-prod) >> shift)).clamp(ninf + 1, pinf)
            } else {
                (prod >> shift).clamp(ninf, pinf - 1)
            }
        };
        (y as u64) & ((1u64 << T) - 1)
    }

    /// The native model of the block: `round_word(product_word(a, m))`.
    pub fn eval(ceil: bool, shift: usize, a: u64, m: u64) -> u64 {
        Self::round_word(ceil, shift, Self::product_word(ceil, a, m))
    }
}

impl<const D: usize, const I: usize, const T: usize> Logic for MulRound<D, I, T> {
    fn update(&mut self) {
        let ceil = self.ceil.val();
        let w = Self::product_word(ceil, self.a.val().to_u64(), self.m.val().to_u64());
        if self.clock.pos_edge() {
            self.p_q.next = bits::<64>(w);
        }
        let w = if self.pipelined.val() {
            self.p_q.val().to_u64()
        } else {
            w
        };
        self.y.next = bits::<T>(Self::round_word(ceil, self.shift.val().index(), w));
    }

    fn connect(&mut self) {
        self.y.connect();
        self.p_q.connect();
    }

    fn hdl(&self) -> Verilog {
        // `ceil`, `shift` and `pipelined` are this block's constants, emitted by rust-hdl as
        // localparams; `p_q` is declared by rust-hdl as the local signal of the simulation.
        let p = D + I; // signed product width: |a * m| < 2^(D-1) * 2^I
        let (ceil, shift) = (self.ceil.val(), self.shift.val().index());
        let lit = |v: i128| {
            if v < 0 {
                format!("(-{}'sd{})", p + 1, -v)
            } else {
                format!("{}'sd{}", p + 1, v)
            }
        };
        // `prod_x op c`, or its constant value when `c` lies outside the product's range.
        let (pmin, pmax) = (-(1i128 << (p - 1)), (1i128 << (p - 1)) - 1);
        let cmp = |op: &str, c: i128| -> String {
            let always = match op {
                ">=" => (c <= pmin, c > pmax),
                ">" => (c < pmin, c >= pmax),
                "<" => (c > pmax, c <= pmin),
                _ => (c >= pmax, c < pmin), // "<="
            };
            match always {
                (true, _) => "1'b1".into(),
                (_, true) => "1'b0".into(),
                _ => format!("(prod_x {op} {})", lit(c)),
            }
        };
        let ninf = -(1i128 << (T - 1));
        let pinf = (1i128 << (T - 1)) - 1;
        // floor(p / 2^s) > pinf - 1 <=> p >= pinf * 2^s; floor(p / 2^s) < ninf <=> p < ninf * 2^s;
        // ceil(p / 2^s) > pinf <=> p > pinf * 2^s; ceil(p / 2^s) < ninf + 1 <=> p <= ninf * 2^s.
        let (over, under, hi, lo) = if ceil {
            (
                cmp(">", pinf << shift),
                cmp("<=", ninf << shift),
                pinf,
                ninf + 1,
            )
        } else {
            (
                cmp(">=", pinf << shift),
                cmp("<", ninf << shift),
                pinf - 1,
                ninf,
            )
        };
        let code = |v: i128| (v as u64) & ((1u64 << T) - 1);
        Verilog::Custom(format!(
            "\
// {mode}(a * m / 2^{shift}), saturated to a {T}-bit t code; m = all ones means unbounded.
// pipelined: the product, the flag `a positive` and the unbounded flag are registered in p_q.
wire signed [{pm1}:0] prod_c = $signed(a) * $signed({{1'b0, m}});
wire unbounded_c = (m == {{{I}{{1'b1}}}});
wire positive_c = !a[{dm1}] && (ceil || (a != {D}'d0));
initial p_q = 64'd0;
always @(posedge clock) p_q <= {{{pad}'d0, unbounded_c, positive_c, prod_c}};
wire signed [{pm1}:0] prod = pipelined ? $signed(p_q[{pm1}:0]) : prod_c;
wire unbounded = pipelined ? p_q[{p1}] : unbounded_c;
wire positive = pipelined ? p_q[{p}] : positive_c;
// The word's pad (rust-hdl declares p_q at 64 bits); a name with `unused` is Verilator's waiver.
wire p_q_pad_unused = |p_q[63:{p2}];
// floor(p / 2^s) = p >>> s, ceil(p / 2^s) = (p + 2^s - 1) >>> s; one more bit holds the sum.
wire signed [{p}:0] prod_x = {{prod[{pm1}], prod}};
wire signed [{qm1}:0] quot = (prod_x + {bias}) >>> shift;
{quot_pad}// Saturation, decided on the product beside the rounding (not after it).
wire over = {over};
wire under = {under};
always @(*) begin
   if (unbounded)
      y = positive ? {T}'d{pinf_code} : {T}'d{ninf_code};
   else if (under)
      y = {T}'d{lo_code};
   else if (over)
      y = {T}'d{hi_code};
   else
      y = quot[{tm1}:0];
end
",
            mode = if ceil { "ceil" } else { "floor" },
            bias = lit(if ceil { (1i128 << shift) - 1 } else { 0 }),
            pm1 = p - 1,
            p1 = p + 1,
            p2 = p + 2,
            // At least the t code's width, so that the code is the quotient's low bits; its bits
            // above the code are decided by `over` and `under` instead.
            qm1 = p.max(T - 1),
            quot_pad = if p >= T {
                format!("wire quot_high_unused = |quot[{p}:{T}];\n")
            } else {
                String::new()
            },
            pad = 64 - p - 2,
            dm1 = D - 1,
            tm1 = T - 1,
            pinf_code = code(pinf),
            ninf_code = code(ninf),
            lo_code = code(lo),
            hi_code = code(hi),
        ))
    }
}
