//! `MulRound`: signed-by-unsigned multiply, scale by `2^-S` with directed rounding, saturate to a t code.
//!
//! rust-hdl 0.46 only implements 16x16 multiplies in `#[hdl_gen]` (measured on this toolchain),
//! and stores values wider than 32 bits bit by bit, so the wide product never becomes a rust-hdl signal:
//! this block has a hand-written simulation model (native i64) and hand-written Verilog with explicitly
//! signed, full-width operands. Cross-simulation of the exported Verilog checks that the two agree.
//!
//! # Inputs
//! - `a`: signed distance, two's complement, `D` bits.
//! - `m`: unsigned inverse-direction magnitude, `I` bits; all ones means "unbounded".
//!
//! # Outputs
//! - `y`: t code, two's complement, `T` bits, combinational:
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
//! let mut u = MulRound::<9, 12, 14>::new(false, 4);
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
    pub a: Signal<In, Bits<D>>,
    pub m: Signal<In, Bits<I>>,
    pub y: Signal<Out, Bits<T>>,
    /// 1 for ceil (upper bound), 0 for floor (lower bound).
    ceil: Constant<Bit>,
    /// Right shift `S` from product fraction bits to t fraction bits.
    shift: Constant<Bits<8>>,
}

impl<const D: usize, const I: usize, const T: usize> MulRound<D, I, T> {
    /// A unit rounding up (`ceil = true`) or down, shifting right by `shift` bits.
    pub fn new(ceil: bool, shift: usize) -> Self {
        assert!(
            D + I <= 63 && T <= 32 && shift < D + I,
            "MulRound<{D},{I},{T}> shift {shift}: widths out of range"
        );
        Self {
            a: Default::default(),
            m: Default::default(),
            y: Default::default(),
            ceil: Constant::new(ceil),
            shift: Constant::new(bits::<8>(shift as u64)),
        }
    }

    /// The native model of the block (also used by the Rust simulation).
    pub fn eval(ceil: bool, shift: usize, a: u64, m: u64) -> u64 {
        let a = ((a << (64 - D)) as i64) >> (64 - D); // sign-extend
        let ninf = -(1i64 << (T - 1));
        let pinf = (1i64 << (T - 1)) - 1;
        let y = if m == (1u64 << I) - 1 {
            if a > 0 || (ceil && a == 0) {
                pinf
            } else {
                ninf
            }
        } else {
            let p = a * m as i64;
            if ceil {
                (-((-p) >> shift)).clamp(ninf + 1, pinf)
            } else {
                (p >> shift).clamp(ninf, pinf - 1)
            }
        };
        (y as u64) & ((1u64 << T) - 1)
    }
}

impl<const D: usize, const I: usize, const T: usize> Logic for MulRound<D, I, T> {
    fn update(&mut self) {
        let y = Self::eval(
            self.ceil.val(),
            self.shift.val().index(),
            self.a.val().to_u64(),
            self.m.val().to_u64(),
        );
        self.y.next = bits::<T>(y);
    }

    fn connect(&mut self) {
        self.y.connect();
    }

    fn hdl(&self) -> Verilog {
        // `ceil` and `shift` are this block's constants, emitted by rust-hdl as localparams.
        let p = D + I; // signed product width: |a * m| < 2^(D-1) * 2^I
        let sat = |v: i64| {
            if v < 0 {
                format!("(-{}'sd{})", p + 1, -v)
            } else {
                format!("{}'sd{}", p + 1, v)
            }
        };
        let ninf = -(1i64 << (T - 1));
        let pinf = (1i64 << (T - 1)) - 1;
        Verilog::Custom(format!(
            "\
// ceil ? ceil(a * m / 2^shift) : floor(a * m / 2^shift), saturated to a {T}-bit t code.
// m = all ones means unbounded. ceil(p) = -floor(-p); one extra bit keeps -p from overflowing.
wire signed [{pm1}:0] prod = $signed(a) * $signed({{1'b0, m}});
wire signed [{p}:0] prod_x = {{prod[{pm1}], prod}};
wire signed [{p}:0] quot = ceil ? -((-prod_x) >>> shift) : (prod_x >>> shift);
wire signed [{p}:0] lo = ceil ? {lo_ceil} : {lo_floor};
wire signed [{p}:0] hi = ceil ? {hi_ceil} : {hi_floor};
wire positive = !a[{dm1}] && (ceil || (a != {D}'d0));
always @(*) begin
   if (m == {{{I}{{1'b1}}}})
      y = positive ? {T}'d{pinf} : {T}'d{ninf_code};
   else if (quot < lo)
      y = lo[{tm1}:0];
   else if (quot > hi)
      y = hi[{tm1}:0];
   else
      y = quot[{tm1}:0];
end
",
            pm1 = p - 1,
            dm1 = D - 1,
            tm1 = T - 1,
            ninf_code = 1u64 << (T - 1),
            lo_ceil = sat(ninf + 1),
            lo_floor = sat(ninf),
            hi_ceil = sat(pinf),
            hi_floor = sat(pinf - 1),
        ))
    }
}
