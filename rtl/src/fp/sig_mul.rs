//! `SigMul`: multiplies two `M + 1`-bit significands and normalises the product into the float blocks'
//! working window. Combinational, hand-written Verilog with a native simulation model, for the same
//! reasons as [`crate::slab::mul_round::MulRound`]: rust-hdl multiplies only 16x16 and stores values over 32
//! bits bit by bit, and the leading-one search needs loop-index constants its `hdl_gen` cannot express.
//!
//! The unit is combinational, or two steps: with `pipelined` (the cut point
//! [`crate::fp::mul::cut::RAW`]) the raw product `a * b` is registered (`p_q`, where a DSP block's
//! output register sits) and the leading-one search and the shift read the register in the next clock.
//!
//! # Inputs
//! `clock` (used only when `pipelined`); `a`, `b` (`N` bits, the low `M + 1` used): significands with
//! their hidden bits, nonzero.
//!
//! # Outputs (of this clock's inputs, or, `pipelined`, of the last clock's)
//! - `pos` (`N` bits): the index of the product's leading one (`0 ..= 2M + 1`);
//! - `sig` (`N` bits): the product shifted so that its leading one is at bit `M + 3` (three bits below the
//!   last place of an `M + 1`-bit result);
//! - `sticky`: some one bit of the product fell below `sig`.
//!
//! Cross-simulation of the exported float multiplier checks the Verilog against this model.

use rust_hdl::prelude::*;

/// Significand product, normalised; see the module documentation.
#[derive(LogicBlock)]
pub struct SigMul<const M: usize, const N: usize> {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<N>>,
    pub b: Signal<In, Bits<N>>,
    pub pos: Signal<Out, Bits<N>>,
    pub sig: Signal<Out, Bits<N>>,
    pub sticky: Signal<Out, Bit>,
    /// 1: the raw product is registered (`p_q`).
    pipelined: Constant<Bit>,
    /// The product register: [`SigMul::product`] of the last clock's operands, in the simulation and
    /// in the Verilog alike.
    p_q: Signal<Local, Bits<64>>,
}

impl<const M: usize, const N: usize> Default for SigMul<M, N> {
    fn default() -> Self {
        Self::new(false)
    }
}

impl<const M: usize, const N: usize> SigMul<M, N> {
    /// The unit, its raw product registered when `pipelined`.
    pub fn new(pipelined: bool) -> Self {
        assert!(
            M + 5 <= N && N <= 32,
            "SigMul<{M},{N}>: need M + 5 <= N <= 32"
        );
        Self {
            clock: Default::default(),
            pipelined: Constant::new(pipelined),
            p_q: Default::default(),
            a: Default::default(),
            b: Default::default(),
            pos: Default::default(),
            sig: Default::default(),
            sticky: Default::default(),
        }
    }

    /// The raw product of the low `M + 1` bits of `a` and `b` (the register word when `pipelined`).
    pub fn product(a: u64, b: u64) -> u64 {
        let mask = (1u64 << (M + 1)) - 1;
        (a & mask) * (b & mask)
    }

    /// The native model: `(pos, sig, sticky)` of `a * b`.
    pub fn eval(a: u64, b: u64) -> (u64, u64, bool) {
        Self::normalise(Self::product(a, b))
    }

    /// `(pos, sig, sticky)` of a raw product `p`: the leading-one search and the shift.
    pub fn normalise(p: u64) -> (u64, u64, bool) {
        if p == 0 {
            return (0, 0, false);
        }
        let pos = 63 - p.leading_zeros() as u64;
        let target = (M + 3) as u64;
        if pos >= target {
            let s = pos - target;
            (pos, p >> s, p & ((1u64 << s) - 1) != 0)
        } else {
            (pos, p << (target - pos), false)
        }
    }
}

impl<const M: usize, const N: usize> Logic for SigMul<M, N> {
    fn update(&mut self) {
        let p = Self::product(self.a.val().to_u64(), self.b.val().to_u64());
        if self.clock.pos_edge() {
            self.p_q.next = bits::<64>(p);
        }
        let p = if self.pipelined.val() {
            self.p_q.val().to_u64()
        } else {
            p
        };
        let (pos, sig, sticky) = Self::normalise(p);
        self.pos.next = bits::<N>(pos);
        self.sig.next = bits::<N>(sig);
        self.sticky.next = sticky;
    }

    fn connect(&mut self) {
        self.pos.connect();
        self.sig.connect();
        self.sticky.connect();
        self.p_q.connect();
    }

    fn hdl(&self) -> Verilog {
        let pw = 2 * M + 2; // product width
        let x = pw.max(N); // working width of the shifts
        let t = M + 3; // target position of the leading one
                       // Bits unused by design, folded into a signal Verilator's lint exempts by name (lowRISC idiom).
        let mut unused = format!(
            "a[{}:{}], b[{}:{}], p_q[63:{pw}]",
            N - 1,
            M + 1,
            N - 1,
            M + 1
        );
        if x > N {
            unused += &format!(", shifted[{}:{}]", x - 1, N);
        }
        Verilog::Custom(format!(
            "\
// p = a[{M}:0] * b[{M}:0]; pos = index of p's leading one; sig = p with that one moved to bit {t}.
// pipelined: the product is registered in p_q (rust-hdl declares it at 64 bits).
wire [{pwm1}:0] p_c = a[{M}:0] * b[{M}:0];
initial p_q = 64'd0;
always @(posedge clock) p_q <= {{{pad}'d0, p_c}};
wire [{pwm1}:0] p_n = pipelined ? p_q[{pwm1}:0] : p_c;
wire [{xm1}:0] p = {p_wide};
reg [{xm1}:0] shifted;
reg [{xm1}:0] low_mask;
integer i;
always @(*) begin
   pos = {N}'d0;
   for (i = 0; i < {pw}; i = i + 1)
      if (p[i]) pos = i[{nm1}:0];
   if (pos >= {N}'d{t}) begin
      shifted = p >> (pos - {N}'d{t});
      low_mask = ~({x}'d0) << (pos - {N}'d{t});
      sticky = |(p & ~low_mask);
   end else begin
      shifted = p << ({N}'d{t} - pos);
      low_mask = {x}'d0;
      sticky = 1'b0;
   end
   sig = shifted[{nm1}:0];
end
wire unused_bits = ^{{{unused}}};
",
            xm1 = x - 1,
            nm1 = N - 1,
            pwm1 = pw - 1,
            pad = 64 - pw,
            p_wide = if x > pw {
                format!("{{{}'d0, p_n}}", x - pw)
            } else {
                "p_n".to_string()
            },
        ))
    }
}
