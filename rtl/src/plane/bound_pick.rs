//! `BoundPick`: the first step of a plane's bound ([`super::bound::PlaneBound`]), bit for bit
//! `golden::plane::fix::bound_pick` — the plane's class from the signs of its sums, the signed
//! numerator `A`, the reciprocal table's half, and the leading one and table index of the chosen `den`
//! magnitude. Combinational.
//!
//! A native model and hand-written Verilog (the leading-one search and the variable part-select are
//! beyond rust-hdl 0.46's `hdl_gen`), checked against each other by cross-simulation of the testers.
//!
//! # Inputs
//! `s` (`S_lo`, `SB` bits), `den_lo`, `den_hi` (`EB` bits), two's complement.
//! # Outputs
//! `is_exit`, `is_entry`, `par` (parallel cull); `a` (`SB` bits: `-S_lo` for an exit plane, else `S_lo`;
//! `|S_lo| < 2^(SB-1)` for every input word of [`super::sums::PlaneSums`], so `-S_lo` fits); `upper`;
//! `lead` (`L`, 8 bits); `idx` (the `R`-bit table index, zero-extended to 12 bits).

use crate::slab::fix::{code, sext};
use golden::plane::fix::bound_pick;
use rust_hdl::prelude::*;

/// Width of the `idx` port: the most table index bits a plane format may have.
pub const IDX_BITS: usize = 12;

/// One plane's class and reciprocal operands; see the module documentation.
#[derive(LogicBlock)]
pub struct BoundPick<const SB: usize, const EB: usize> {
    pub s: Signal<In, Bits<SB>>,
    pub den_lo: Signal<In, Bits<EB>>,
    pub den_hi: Signal<In, Bits<EB>>,
    pub is_exit: Signal<Out, Bit>,
    pub is_entry: Signal<Out, Bit>,
    pub par: Signal<Out, Bit>,
    pub a: Signal<Out, Bits<SB>>,
    pub upper: Signal<Out, Bit>,
    pub lead: Signal<Out, Bits<8>>,
    pub idx: Signal<Out, Bits<IDX_BITS>>,
    /// Table index bits `R`.
    r_bits: Constant<Bits<8>>,
}

impl<const SB: usize, const EB: usize> BoundPick<SB, EB> {
    /// A unit for a table of `2^r_bits` entries.
    pub fn new(r_bits: u32) -> Self {
        assert!((1..=IDX_BITS as u32).contains(&r_bits) && SB < 63 && EB < 63);
        Self {
            s: Default::default(),
            den_lo: Default::default(),
            den_hi: Default::default(),
            is_exit: Default::default(),
            is_entry: Default::default(),
            par: Default::default(),
            a: Default::default(),
            upper: Default::default(),
            lead: Default::default(),
            idx: Default::default(),
            r_bits: Constant::new(bits::<8>(r_bits as u64)),
        }
    }
}

impl<const SB: usize, const EB: usize> Logic for BoundPick<SB, EB> {
    fn update(&mut self) {
        let p = bound_pick(
            self.r_bits.val().to_u64() as u32,
            EB as u32,
            sext(self.s.val().to_u64(), SB),
            sext(self.den_lo.val().to_u64(), EB),
            sext(self.den_hi.val().to_u64(), EB),
        );
        self.is_exit.next = p.exit;
        self.is_entry.next = p.entry;
        self.par.next = p.cull;
        self.a.next = bits::<SB>(code(p.a, SB));
        self.upper.next = p.upper;
        self.lead.next = bits::<8>(p.lead as u64);
        self.idx.next = bits::<IDX_BITS>(p.idx);
    }

    fn connect(&mut self) {
        self.is_exit.connect();
        self.is_entry.connect();
        self.par.connect();
        self.a.connect();
        self.upper.connect();
        self.lead.connect();
        self.idx.connect();
    }

    fn hdl(&self) -> Verilog {
        let r = self.r_bits.val().to_u64() as usize;
        // Bits of an index into the (EB + R)-bit shifted magnitude.
        let lw = (usize::BITS - (EB + r - 1).leading_zeros()) as usize;
        let idx_pad = if r < IDX_BITS {
            format!("{{{}'d0, ix}}", IDX_BITS - r)
        } else {
            "ix".to_string()
        };
        Verilog::Custom(format!(
            "\
// Classification: an exit plane when den_lo > 0, an entry plane when den_hi < 0, a parallel cull when
// both are zero and s > 0.
wire s_neg = s[{sb1}];
wire s_pos = !s[{sb1}] && (s != {SB}'d0);
wire ex = !den_lo[{eb1}] && (den_lo != {EB}'d0);
wire en = !ex && den_hi[{eb1}];
wire [{eb1}:0] mag = ex ? (s_pos ? den_hi : den_lo) : (s_neg ? -den_hi : -den_lo);
// Leading one of the magnitude, and the R table-index bits below it.
reg [{lw1}:0] ld;
integer i;
always @(*) begin
   ld = {lw}'d0;
   for (i = 0; i < {EB}; i = i + 1)
      if (mag[i]) ld = i[{lw1}:0];
end
wire [{mw1}:0] mag_up = {{{{{r}{{1'b0}}}}, mag}} << r_bits;
wire [{r1}:0] ix = mag_up[ld +: {r}];
always @(*) begin
   is_exit = ex;
   is_entry = en;
   par = !ex && !en && (den_lo == {EB}'d0) && (den_hi == {EB}'d0) && s_pos;
   a = ex ? -s : s;
   // The larger bound takes the upper reciprocal: exit with A = -s >= 0, entry with A = s < 0.
   upper = ex ? !s_pos : s_neg;
   lead = {{{pad}'d0, ld}};
   idx = {idx_pad};
end
",
            sb1 = SB - 1,
            eb1 = EB - 1,
            mw1 = EB + r - 1,
            lw1 = lw - 1,
            pad = 8 - lw,
            r1 = r - 1,
        ))
    }
}
