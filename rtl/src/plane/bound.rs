//! `PlaneBound`: what one cull plane does to the ray's interval, from its sums — the entry or exit bound
//! `t*` through the directed reciprocal table, or a parallel cull (`golden::plane::fix::bound_from_sums`,
//! which documents the arithmetic and why every bound is conservative).
//!
//! Four steps, each a leaf with its model in `golden::plane::fix`, with a cut point ([`crate::cut::Cut`])
//! after each of the first three, a register or a wire as the tester's configuration chooses
//! ([`super::fix::cut`]):
//! 1. [`BoundPick`]: classification by the signs of `den_lo`, `den_hi`; `A`, the magnitude and the table
//!    half chosen by the sign of `A`; the leading-one search and the table index. Cut
//!    [`super::fix::cut::PICK`] (`_qk`).
//! 2. [`BoundTable`]: the `2^R`-entry table read. Cut [`super::fix::cut::TABLE`] (`_qt`).
//! 3. [`BoundMul`]: the product `A * r`. Cut [`super::fix::cut::PRODUCT`] (`_qm`).
//! 4. [`BoundScale`]: the shift by `C - L` with floor (entry) or ceil (exit) and the saturation to a t
//!    code.
//!
//! Latency: the number of cuts that are registers, 0 to 3 ([`PlaneBound::latency`]).
//!
//! # Inputs
//! `clock`, `s`, `den_lo`, `den_hi`.
//! # Outputs
//! `is_entry`, `is_exit`, `par` (parallel and on the empty side: cull) and `y`, the bound as a `T`-bit t
//! code (0 when the plane is neither an entry nor an exit plane), of the inputs `latency` clocks ago.

use super::bound_mul::BoundMul;
use super::bound_pick::{BoundPick, IDX_BITS};
use super::bound_scale::BoundScale;
use super::bound_table::{BoundTable, RV_BITS};
use super::fix::cut;
use crate::cut::Cut;
use rust_hdl::prelude::*;

/// One plane's effect; see the module documentation.
#[derive(LogicBlock)]
pub struct PlaneBound<const SB: usize, const EB: usize, const T: usize> {
    pub clock: Signal<In, Clock>,
    pub s: Signal<In, Bits<SB>>,
    pub den_lo: Signal<In, Bits<EB>>,
    pub den_hi: Signal<In, Bits<EB>>,
    pub y: Signal<Out, Bits<T>>,
    pub is_entry: Signal<Out, Bit>,
    pub is_exit: Signal<Out, Bit>,
    pub par: Signal<Out, Bit>,
    // step 1 and its cut
    pick: BoundPick<SB, EB>,
    a_qk: Cut<Bits<SB>>,
    upper_qk: Cut<Bit>,
    lead_qk: Cut<Bits<8>>,
    idx_qk: Cut<Bits<IDX_BITS>>,
    ex_qk: Cut<Bit>,
    en_qk: Cut<Bit>,
    par_qk: Cut<Bit>,
    // step 2 and its cut
    rom: BoundTable,
    rv_qt: Cut<Bits<RV_BITS>>,
    a_qt: Cut<Bits<SB>>,
    lead_qt: Cut<Bits<8>>,
    ex_qt: Cut<Bit>,
    en_qt: Cut<Bit>,
    par_qt: Cut<Bit>,
    // step 3 and its cut
    mul: BoundMul<SB>,
    prod_qm: Cut<Bits<64>>,
    lead_qm: Cut<Bits<8>>,
    ex_qm: Cut<Bit>,
    en_qm: Cut<Bit>,
    par_qm: Cut<Bit>,
    // step 4
    scale: BoundScale<T>,
}

impl<const SB: usize, const EB: usize, const T: usize> PlaneBound<SB, EB, T> {
    /// A unit with a `2^r_bits`-entry table, scale exponent `c_shift`, and the registers `cuts` names
    /// (bits [`cut::PICK`], [`cut::TABLE`], [`cut::PRODUCT`]; others are ignored).
    pub fn new(r_bits: u32, c_shift: i32, cuts: usize) -> Self {
        let (k, t, m) = (
            cuts & cut::PICK != 0,
            cuts & cut::TABLE != 0,
            cuts & cut::PRODUCT != 0,
        );
        Self {
            clock: Default::default(),
            s: Default::default(),
            den_lo: Default::default(),
            den_hi: Default::default(),
            y: Default::default(),
            is_entry: Default::default(),
            is_exit: Default::default(),
            par: Default::default(),
            pick: BoundPick::new(r_bits),
            a_qk: Cut::new(k),
            upper_qk: Cut::new(k),
            lead_qk: Cut::new(k),
            idx_qk: Cut::new(k),
            ex_qk: Cut::new(k),
            en_qk: Cut::new(k),
            par_qk: Cut::new(k),
            rom: BoundTable::new(r_bits),
            rv_qt: Cut::new(t),
            a_qt: Cut::new(t),
            lead_qt: Cut::new(t),
            ex_qt: Cut::new(t),
            en_qt: Cut::new(t),
            par_qt: Cut::new(t),
            mul: BoundMul::new(r_bits),
            prod_qm: Cut::new(m),
            lead_qm: Cut::new(m),
            ex_qm: Cut::new(m),
            en_qm: Cut::new(m),
            par_qm: Cut::new(m),
            scale: BoundScale::new(BoundMul::<SB>::bits_for(r_bits), c_shift),
        }
    }

    /// Clocks from the sums in to the bound out for the cut points `cuts`.
    pub const fn latency(cuts: usize) -> usize {
        (cuts & cut::BOUND_STEPS).count_ones() as usize
    }
}

impl<const SB: usize, const EB: usize, const T: usize> Logic for PlaneBound<SB, EB, T> {
    #[hdl_gen]
    fn update(&mut self) {
        self.a_qk.clock.next = self.clock.val();
        self.upper_qk.clock.next = self.clock.val();
        self.lead_qk.clock.next = self.clock.val();
        self.idx_qk.clock.next = self.clock.val();
        self.ex_qk.clock.next = self.clock.val();
        self.en_qk.clock.next = self.clock.val();
        self.par_qk.clock.next = self.clock.val();
        self.rv_qt.clock.next = self.clock.val();
        self.a_qt.clock.next = self.clock.val();
        self.lead_qt.clock.next = self.clock.val();
        self.ex_qt.clock.next = self.clock.val();
        self.en_qt.clock.next = self.clock.val();
        self.par_qt.clock.next = self.clock.val();
        self.prod_qm.clock.next = self.clock.val();
        self.lead_qm.clock.next = self.clock.val();
        self.ex_qm.clock.next = self.clock.val();
        self.en_qm.clock.next = self.clock.val();
        self.par_qm.clock.next = self.clock.val();

        // Step 1: class, A, table half, leading one and index.
        self.pick.s.next = self.s.val();
        self.pick.den_lo.next = self.den_lo.val();
        self.pick.den_hi.next = self.den_hi.val();
        self.a_qk.d.next = self.pick.a.val();
        self.upper_qk.d.next = self.pick.upper.val();
        self.lead_qk.d.next = self.pick.lead.val();
        self.idx_qk.d.next = self.pick.idx.val();
        self.ex_qk.d.next = self.pick.is_exit.val();
        self.en_qk.d.next = self.pick.is_entry.val();
        self.par_qk.d.next = self.pick.par.val();

        // Step 2: the table read.
        self.rom.idx.next = self.idx_qk.q.val();
        self.rom.upper.next = self.upper_qk.q.val();
        self.rv_qt.d.next = self.rom.rv.val();
        self.a_qt.d.next = self.a_qk.q.val();
        self.lead_qt.d.next = self.lead_qk.q.val();
        self.ex_qt.d.next = self.ex_qk.q.val();
        self.en_qt.d.next = self.en_qk.q.val();
        self.par_qt.d.next = self.par_qk.q.val();

        // Step 3: the product.
        self.mul.a.next = self.a_qt.q.val();
        self.mul.rv.next = self.rv_qt.q.val();
        self.prod_qm.d.next = self.mul.prod.val();
        self.lead_qm.d.next = self.lead_qt.q.val();
        self.ex_qm.d.next = self.ex_qt.q.val();
        self.en_qm.d.next = self.en_qt.q.val();
        self.par_qm.d.next = self.par_qt.q.val();

        // Step 4: scale, round, saturate.
        self.scale.prod.next = self.prod_qm.q.val();
        self.scale.lead.next = self.lead_qm.q.val();
        self.scale.is_exit.next = self.ex_qm.q.val();
        self.scale.is_entry.next = self.en_qm.q.val();
        self.y.next = self.scale.y.val();
        self.is_exit.next = self.ex_qm.q.val();
        self.is_entry.next = self.en_qm.q.val();
        self.par.next = self.par_qm.q.val();
    }
}
