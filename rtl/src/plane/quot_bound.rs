//! `PlaneQuotBound`: what one cull plane does to the ray's interval, from its sums, in the fraction
//! option: the bound `t* = num * 2^E / den` kept as the exact pair `(num, den)` instead of a t code
//! (`golden::plane::fix::cull_fix_quotients`; compare [`crate::plane::bound::PlaneBound`], the table
//! option). Combinational.
//!
//! From `S_lo`, `den_lo`, `den_hi` (`golden::plane::fix` documents why each choice is the conservative
//! one for every `den` of the interval):
//! - `den_lo > 0`, an exit plane: `num = -S_lo`, `den = S_lo > 0 ? den_hi : den_lo`;
//! - otherwise `den_hi < 0`, an entry plane: `num = S_lo`, `den = S_lo < 0 ? -den_hi : -den_lo`;
//! - `den_lo = den_hi = 0` and `S_lo > 0`: `par`, the ray is parallel on the empty side (a cull);
//! - anything else: no effect.
//!
//! There is no rounding, so nothing to direct: the bound is the model's fraction exactly.
//!
//! # Widths
//! `num` has `SB` bits like `S_lo`: `|S_lo| < 2^(SB-1)` for every input of the declared widths
//! (`3 * 2^(N-1) * 2^(G+1) + 2^(WB-1) < 2^(G+N+4)`), so `-S_lo` never overflows. `den` is the magnitude in
//! `MB = EB - 1` bits: `|den| <= 3 * 2^(N-1) * 2^(DB-1) < 2^(EB-1)`. For a `den` interval that quantisation
//! produces (`den_lo <= den_hi`) the chosen magnitude is positive; an inverted interval (never produced)
//! gives the same wrapped bits here and in [`PlaneQuotBound::eval`].
//!
//! Outputs `is_entry`, `is_exit`, `par`, `num`, `den` (the last two meaningful for an entry or exit plane).

use crate::slab::fix::{code, sext};
use golden::plane::quot::quot_effect;
use rust_hdl::prelude::*;

/// One plane's effect as a fraction; see the module documentation.
#[derive(LogicBlock)]
pub struct PlaneQuotBound<const SB: usize, const EB: usize, const MB: usize> {
    pub s: Signal<In, Bits<SB>>,
    pub den_lo: Signal<In, Bits<EB>>,
    pub den_hi: Signal<In, Bits<EB>>,
    pub num: Signal<Out, Bits<SB>>,
    pub den: Signal<Out, Bits<MB>>,
    pub is_entry: Signal<Out, Bit>,
    pub is_exit: Signal<Out, Bit>,
    pub par: Signal<Out, Bit>,
}

impl<const SB: usize, const EB: usize, const MB: usize> Default for PlaneQuotBound<SB, EB, MB> {
    fn default() -> Self {
        assert!(
            MB + 1 == EB && SB < 63 && EB < 63,
            "PlaneQuotBound<{SB},{EB},{MB}>: need MB = EB - 1"
        );
        Self {
            s: Default::default(),
            den_lo: Default::default(),
            den_hi: Default::default(),
            num: Default::default(),
            den: Default::default(),
            is_entry: Default::default(),
            is_exit: Default::default(),
            par: Default::default(),
        }
    }
}

impl<const SB: usize, const EB: usize, const MB: usize> Logic for PlaneQuotBound<SB, EB, MB> {
    fn update(&mut self) {
        let e = quot_effect(
            SB,
            MB,
            sext(self.s.val().to_u64(), SB),
            sext(self.den_lo.val().to_u64(), EB),
            sext(self.den_hi.val().to_u64(), EB),
        );
        self.is_entry.next = e.is_entry;
        self.is_exit.next = e.is_exit;
        self.par.next = e.par;
        self.num.next = bits::<SB>(code(e.num, SB));
        self.den.next = bits::<MB>(e.den);
    }

    fn connect(&mut self) {
        self.num.connect();
        self.den.connect();
        self.is_entry.connect();
        self.is_exit.connect();
        self.par.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(format!(
            "\
// An exit plane when den_lo > 0, an entry plane when den_hi < 0, a parallel cull when both are zero
// and s > 0; the bound is (num, den) = exit ? (-s, s > 0 ? den_hi : den_lo) : (s, s < 0 ? -den_hi : -den_lo).
wire s_neg = s[{sb1}];
wire s_pos = !s[{sb1}] && (s != {SB}'d0);
wire ex = !den_lo[{eb1}] && (den_lo != {EB}'d0);
wire en = !ex && den_hi[{eb1}];
wire [{sb1}:0] s_minus = -s;
// Magnitudes modulo 2^MB: the chosen one is below 2^MB (module documentation).
wire [{mb1}:0] lo_minus = -den_lo[{mb1}:0];
wire [{mb1}:0] hi_minus = -den_hi[{mb1}:0];
wire [{mb1}:0] mag = ex ? (s_pos ? den_hi[{mb1}:0] : den_lo[{mb1}:0]) : (s_neg ? hi_minus : lo_minus);
always @(*) begin
   is_exit = ex;
   is_entry = en;
   par = !ex && !en && (den_lo == {EB}'d0) && (den_hi == {EB}'d0) && s_pos;
   num = ex ? s_minus : s;
   den = mag;
end
",
            sb1 = SB - 1,
            eb1 = EB - 1,
            mb1 = MB - 1,
        ))
    }
}
