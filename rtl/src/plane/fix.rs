//! `PlaneFix`: the fixed-point slab tester chained with `K` cull planes (Arm US 2025/0259373), fully
//! pipelined (one node test per clock), [`plane_fix_latency`] clocks: 6 by default
//! ([`PLANE_FIX_LATENCY`]), 11 in the deep configuration ([`PLANE_FIX_DEEP`]). Bit for bit
//! `golden::plane::fix::node_fix` (read `golden::plane::fix` for the arithmetic and the conservativeness
//! argument); ports mirror `golden::plane::fix::{NodeFixRay, FixNode}` and `PlaneFixOut`.
//!
//! # Parameters
//! `G, D, I, T`: the slab format ([`SlabFix`], `D = G + 1`); `N`: normal bits; `DB = FD + 3`: direction
//! bits; `WB = G + N + 4`: offset bits; `SB = G + N + 5`: `S` bits; `EB = N + FD + 4`: `den` bits; `K`:
//! planes per node, `1..=8`. Stable Rust cannot compute widths from widths, hence the list, checked
//! against the format by [`PlaneFix::new`]. `SCUTS`: the slab tester's cut points
//! ([`crate::slab::fix::cut`]); `PCUTS`: the plane path's, in the sums and the bound ([`cut`]).
//!
//! # Ports
//! The slab tester's (`ray_o_lo`, `ray_o_hi`, `ray_m_lo`, `ray_m_hi`, `ray_neg`, `ray_t_min`, `ray_t_max`,
//! `box_lo`, `box_hi`), plus `ray_d_lo`, `ray_d_hi` (the direction interval) and per plane `plane_nx`,
//! `plane_ny`, `plane_nz`, `plane_w`, `clock`, `rst` (synchronous: clears every valid bit), `valid_in`, `tag_in`; outputs `valid_out`, `tag_out`, `hit` (not culled), `t_entry`,
//! `t_exit`.
//!
//! # Stages
//! The slab tester runs in parallel with the plane arithmetic and the two meet at stage 5. Where the
//! slab tester's latency ([`crate::slab::fix::slab_fix_latency`]`(SCUTS)`) is shorter than the plane
//! path's to stage 4 (`4 +` [`PlaneSums::latency`]`(PCUTS) +` [`PlaneBound::latency`]`(PCUTS)`), its
//! results wait in up to five registers (`slab_*_qw`), so both arrive together; a configuration whose
//! slab path is the longer is refused by [`PlaneFix::new`].
//! 1. `_q1`: per plane, [`PlaneSums`] (its own cut points [`cut::TERMS`], [`cut::PRODUCTS`] inside):
//!    `S_lo`, `den_lo`, `den_hi`, the operands chosen by the sign of each normal component.
//! 2. `_q2`: per plane, [`PlaneBound`] (its own cut points [`cut::PICK`], [`cut::TABLE`],
//!    [`cut::PRODUCT`] inside): the entry bound (or `-inf`), the exit bound (or `+inf`), the
//!    parallel-cull flag.
//! 3. `_q3`, 4. `_q4`: two levels of the max (entries) and min (exits) trees over eight slots (slots from
//!    `K` on hold `-inf`/`+inf`, which synthesis removes).
//! 5. `_q5`: the last level merged with the slab tester's result (out at clock 4).
//! 6. `_q6`: `hit = slab hit && no parallel cull && t_entry <= t_exit`; these registers drive the outputs.

use crate::cut::Cut;
use crate::io::TesterIo;
use crate::plane::bound::PlaneBound;
use crate::plane::ports::PlaneFixPorts;
use crate::plane::sums::PlaneSums;
use crate::slab::fix::{slab_fix_latency, SlabFix, SLAB_FIX_CUTS, SLAB_FIX_CUTS_DEEP, TAG_BITS};
use golden::plane::fix::{CullFixFormat, FixNode, NodeFixRay, PlaneFixOut, MAX_PLANES};
use rust_hdl::prelude::*;

/// The cut points of the plane path, inside each plane's sums ([`PlaneSums`]) and bound
/// ([`PlaneBound`]): one bit each of `PlaneFix`'s `PCUTS`, a register where set, a wire where clear.
pub mod cut {
    /// After the class, `A`, the leading one and the table index (`_qk`).
    pub const PICK: usize = 1 << 0;
    /// After the reciprocal table read (`_qt`).
    pub const TABLE: usize = 1 << 1;
    /// After the product `A * r` (`_qm`), before the shift, rounding and saturation.
    pub const PRODUCT: usize = 1 << 2;
    /// The three bound cuts.
    pub const BOUND_STEPS: usize = PICK | TABLE | PRODUCT;
    /// In each plane's sums ([`PlaneSums`]), after the terms `2 p - lo - hi` (`_qo`).
    pub const TERMS: usize = 1 << 3;
    /// In each plane's sums, after the nine products, before the adds (`_qp`).
    pub const PRODUCTS: usize = 1 << 4;
    /// The two sums cuts.
    pub const SUM_STEPS: usize = TERMS | PRODUCTS;
    /// Every cut of the plane path.
    pub const ALL: usize = SUM_STEPS | BOUND_STEPS;
}

/// Most registers the slab tester's results may wait in for the plane path.
pub const MAX_SLAB_WAIT: usize = 5;

/// Registers the slab tester's results wait in for the plane path, for slab cuts `scuts` and plane
/// cuts `pcuts`: the plane path's clocks to stage 4 less the slab tester's latency.
pub const fn slab_wait(scuts: usize, pcuts: usize) -> usize {
    let plane =
        4 + PlaneSums::<1, 1, 1, 1, 1, 1>::latency(pcuts) + PlaneBound::<1, 1, 1>::latency(pcuts);
    let slab = slab_fix_latency(scuts);
    assert!(
        plane >= slab && plane - slab <= MAX_SLAB_WAIT,
        "PlaneFix: the slab tester must not be longer than the plane path, nor shorter by more than 5"
    );
    plane - slab
}

/// Clocks from a node test entering `PlaneFix` to its result leaving, for slab cuts `scuts` and plane
/// cuts `pcuts`: `6 +` the registers inside the sums and the bound.
pub const fn plane_fix_latency(scuts: usize, pcuts: usize) -> usize {
    slab_fix_latency(scuts) + slab_wait(scuts, pcuts) + 2
}

/// The plane cut points of the default tester: none (the bound in one clock).
pub const PLANE_FIX_CUTS: usize = 0;

/// The deep configuration: `(SCUTS, PCUTS)` = the 6-clock slab tester and every plane cut (11 clocks).
pub const PLANE_FIX_DEEP: (usize, usize) = (SLAB_FIX_CUTS_DEEP, cut::ALL);

/// Clocks from a node test entering the default `PlaneFix` to its result leaving.
pub const PLANE_FIX_LATENCY: usize = plane_fix_latency(SLAB_FIX_CUTS, PLANE_FIX_CUTS);

/// The pipeline depths that are exported: `(SCUTS, PCUTS, module-name suffix)`; the default has none.
pub const PLANE_FIX_DEPTHS: [(usize, usize, &str); 2] = [
    (SLAB_FIX_CUTS, PLANE_FIX_CUTS, ""),
    (PLANE_FIX_DEEP.0, PLANE_FIX_DEEP.1, "_p11"),
];

/// The chained fixed-point slab + cull-plane tester; see the module documentation.
#[derive(LogicBlock)]
pub struct PlaneFix<
    const G: usize,
    const D: usize,
    const I: usize,
    const T: usize,
    const N: usize,
    const DB: usize,
    const WB: usize,
    const SB: usize,
    const EB: usize,
    const K: usize,
    const SCUTS: usize = SLAB_FIX_CUTS,
    const PCUTS: usize = PLANE_FIX_CUTS,
> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub ray_o_lo: [Signal<In, Bits<G>>; 3],
    pub ray_o_hi: [Signal<In, Bits<G>>; 3],
    pub ray_m_lo: [Signal<In, Bits<I>>; 3],
    pub ray_m_hi: [Signal<In, Bits<I>>; 3],
    pub ray_neg: [Signal<In, Bit>; 3],
    pub ray_t_min: Signal<In, Bits<T>>,
    pub ray_t_max: Signal<In, Bits<T>>,
    pub ray_d_lo: [Signal<In, Bits<DB>>; 3],
    pub ray_d_hi: [Signal<In, Bits<DB>>; 3],
    pub box_lo: [Signal<In, Bits<G>>; 3],
    pub box_hi: [Signal<In, Bits<G>>; 3],
    pub plane_nx: [Signal<In, Bits<N>>; K],
    pub plane_ny: [Signal<In, Bits<N>>; K],
    pub plane_nz: [Signal<In, Bits<N>>; K],
    pub plane_w: [Signal<In, Bits<WB>>; K],
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub hit: Signal<Out, Bit>,
    pub t_entry: Signal<Out, Bits<T>>,
    pub t_exit: Signal<Out, Bits<T>>,
    // constants
    sign_n: Constant<Bits<N>>,
    sign_t: Constant<Bits<T>>,
    t_pinf: Constant<Bits<T>>,
    t_ninf: Constant<Bits<T>>,
    // the slab tester, in parallel
    slab: SlabFix<G, D, I, T, SCUTS>,
    // the slab tester's results waiting for the plane path
    slab_valid_qw: [Cut<Bit>; MAX_SLAB_WAIT],
    slab_tag_qw: [Cut<Bits<TAG_BITS>>; MAX_SLAB_WAIT],
    slab_hit_qw: [Cut<Bit>; MAX_SLAB_WAIT],
    slab_entry_qw: [Cut<Bits<T>>; MAX_SLAB_WAIT],
    slab_exit_qw: [Cut<Bits<T>>; MAX_SLAB_WAIT],
    // stage 1
    sums: [PlaneSums<G, N, DB, WB, SB, EB>; K],
    s_q1: [DFF<Bits<SB>>; K],
    dl_q1: [DFF<Bits<EB>>; K],
    dh_q1: [DFF<Bits<EB>>; K],
    // stage 2 (eight slots; those from K on are constants)
    bound: [PlaneBound<SB, EB, T>; K],
    en_q2: [DFF<Bits<T>>; MAX_PLANES],
    ex_q2: [DFF<Bits<T>>; MAX_PLANES],
    par_q2: [DFF<Bit>; MAX_PLANES],
    // stage 3, 4: tree levels
    en_q3: [DFF<Bits<T>>; 4],
    ex_q3: [DFF<Bits<T>>; 4],
    par_q3: DFF<Bit>,
    en_q4: [DFF<Bits<T>>; 2],
    ex_q4: [DFF<Bits<T>>; 2],
    par_q4: DFF<Bit>,
    // stage 5: merged with the slab result
    en_l5: Signal<Local, Bits<T>>,
    ex_l5: Signal<Local, Bits<T>>,
    entry_q5: DFF<Bits<T>>,
    exit_q5: DFF<Bits<T>>,
    live_q5: DFF<Bit>,
    valid_q5: DFF<Bit>,
    tag_q5: DFF<Bits<TAG_BITS>>,
    // stage 6
    entry_q6: DFF<Bits<T>>,
    exit_q6: DFF<Bits<T>>,
    hit_q6: DFF<Bit>,
    valid_q6: DFF<Bit>,
    tag_q6: DFF<Bits<TAG_BITS>>,
}

impl<
        const G: usize,
        const D: usize,
        const I: usize,
        const T: usize,
        const N: usize,
        const DB: usize,
        const WB: usize,
        const SB: usize,
        const EB: usize,
        const K: usize,
        const SCUTS: usize,
        const PCUTS: usize,
    > PlaneFix<G, D, I, T, N, DB, WB, SB, EB, K, SCUTS, PCUTS>
{
    /// A tester for `cf`, whose widths must equal the parameters.
    pub fn new(cf: &CullFixFormat) -> Self {
        assert!(
            cf.n as usize == N
                && cf.d_bits() as usize == DB
                && cf.w_bits() as usize == WB
                && cf.s_bits() as usize == SB
                && cf.den_bits() as usize == EB
                && (1..=MAX_PLANES).contains(&K),
            "PlaneFix<..,{N},{DB},{WB},{SB},{EB},{K}> does not match plane format {}",
            cf.name()
        );
        let wait = slab_wait(SCUTS, PCUTS);
        let t = T as u32;
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            ray_o_lo: Default::default(),
            ray_o_hi: Default::default(),
            ray_m_lo: Default::default(),
            ray_m_hi: Default::default(),
            ray_neg: Default::default(),
            ray_t_min: Default::default(),
            ray_t_max: Default::default(),
            ray_d_lo: Default::default(),
            ray_d_hi: Default::default(),
            box_lo: Default::default(),
            box_hi: Default::default(),
            plane_nx: std::array::from_fn(|_| Default::default()),
            plane_ny: std::array::from_fn(|_| Default::default()),
            plane_nz: std::array::from_fn(|_| Default::default()),
            plane_w: std::array::from_fn(|_| Default::default()),
            valid_out: Default::default(),
            tag_out: Default::default(),
            hit: Default::default(),
            t_entry: Default::default(),
            t_exit: Default::default(),
            sign_n: Constant::new(bits::<N>(1 << (N - 1))),
            sign_t: Constant::new(bits::<T>(1 << (t - 1))),
            t_pinf: Constant::new(bits::<T>((1 << (t - 1)) - 1)),
            t_ninf: Constant::new(bits::<T>(1 << (t - 1))),
            slab: SlabFix::new(&cf.base),
            slab_valid_qw: Cut::chain(wait),
            slab_tag_qw: Cut::chain(wait),
            slab_hit_qw: Cut::chain(wait),
            slab_entry_qw: Cut::chain(wait),
            slab_exit_qw: Cut::chain(wait),
            sums: std::array::from_fn(|_| PlaneSums::new(PCUTS)),
            s_q1: std::array::from_fn(|_| Default::default()),
            dl_q1: std::array::from_fn(|_| Default::default()),
            dh_q1: std::array::from_fn(|_| Default::default()),
            bound: std::array::from_fn(|_| PlaneBound::new(cf.r, cf.c_shift(), PCUTS)),
            en_q2: Default::default(),
            ex_q2: Default::default(),
            par_q2: Default::default(),
            en_q3: Default::default(),
            ex_q3: Default::default(),
            par_q3: Default::default(),
            en_q4: Default::default(),
            ex_q4: Default::default(),
            par_q4: Default::default(),
            en_l5: Default::default(),
            ex_l5: Default::default(),
            entry_q5: Default::default(),
            exit_q5: Default::default(),
            live_q5: Default::default(),
            valid_q5: Default::default(),
            tag_q5: Default::default(),
            entry_q6: Default::default(),
            exit_q6: Default::default(),
            hit_q6: Default::default(),
            valid_q6: Default::default(),
            tag_q6: Default::default(),
        }
    }
}

/// A chained fixed tester of any width and plane count, built for a plane format.
pub trait PlaneFixIo: TesterIo<Ray = NodeFixRay, Box = FixNode, Out = PlaneFixOut> {
    /// Planes per node.
    const PLANES: usize;
    /// The slab tester's cut points (`SCUTS`).
    const SLAB_CUTS: usize;
    /// The plane bound's cut points (`PCUTS`).
    const CUTS: usize;
    /// A tester for `cf` (whose widths must match the block's).
    fn for_format(cf: &CullFixFormat) -> Self;
}

impl<
        const G: usize,
        const D: usize,
        const I: usize,
        const T: usize,
        const N: usize,
        const DB: usize,
        const WB: usize,
        const SB: usize,
        const EB: usize,
        const K: usize,
        const SCUTS: usize,
        const PCUTS: usize,
    > PlaneFixIo for PlaneFix<G, D, I, T, N, DB, WB, SB, EB, K, SCUTS, PCUTS>
{
    const PLANES: usize = K;
    const SLAB_CUTS: usize = SCUTS;
    const CUTS: usize = PCUTS;
    fn for_format(cf: &CullFixFormat) -> Self {
        Self::new(cf)
    }
}

impl<
        const G: usize,
        const D: usize,
        const I: usize,
        const T: usize,
        const N: usize,
        const DB: usize,
        const WB: usize,
        const SB: usize,
        const EB: usize,
        const K: usize,
        const SCUTS: usize,
        const PCUTS: usize,
    > TesterIo for PlaneFix<G, D, I, T, N, DB, WB, SB, EB, K, SCUTS, PCUTS>
{
    type Ray = NodeFixRay;
    type Box = FixNode;
    type Out = PlaneFixOut;
    const LATENCY: usize = plane_fix_latency(SCUTS, PCUTS);
    type Ports = PlaneFixPorts;

    fn ports() -> PlaneFixPorts {
        PlaneFixPorts
    }

    crate::tester_ports!(
        inputs: ray_o_lo, ray_o_hi, ray_m_lo, ray_m_hi, ray_neg, ray_t_min, ray_t_max, box_lo, box_hi,
            ray_d_lo, ray_d_hi, plane_nx, plane_ny, plane_nz, plane_w;
        outputs: hit, t_entry, t_exit
    );
}

impl<
        const G: usize,
        const D: usize,
        const I: usize,
        const T: usize,
        const N: usize,
        const DB: usize,
        const WB: usize,
        const SB: usize,
        const EB: usize,
        const K: usize,
        const SCUTS: usize,
        const PCUTS: usize,
    > Logic for PlaneFix<G, D, I, T, N, DB, WB, SB, EB, K, SCUTS, PCUTS>
{
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..K {
            self.sums[k].clock.next = self.clock.val();
            self.s_q1[k].clock.next = self.clock.val();
            self.dl_q1[k].clock.next = self.clock.val();
            self.dh_q1[k].clock.next = self.clock.val();
        }
        for k in 0..MAX_PLANES {
            self.en_q2[k].clock.next = self.clock.val();
            self.ex_q2[k].clock.next = self.clock.val();
            self.par_q2[k].clock.next = self.clock.val();
        }
        for k in 0..4 {
            self.en_q3[k].clock.next = self.clock.val();
            self.ex_q3[k].clock.next = self.clock.val();
        }
        for k in 0..2 {
            self.en_q4[k].clock.next = self.clock.val();
            self.ex_q4[k].clock.next = self.clock.val();
        }
        dff_setup!(
            self, clock, par_q3, par_q4, entry_q5, exit_q5, live_q5, valid_q5, tag_q5, entry_q6,
            exit_q6, hit_q6, valid_q6, tag_q6
        );

        // The slab tester, on the same inputs.
        self.slab.clock.next = self.clock.val();
        self.slab.valid_in.next = self.valid_in.val();
        self.slab.rst.next = self.rst.val();
        self.slab.tag_in.next = self.tag_in.val();
        for a in 0..3 {
            self.slab.ray_o_lo[a].next = self.ray_o_lo[a].val();
            self.slab.ray_o_hi[a].next = self.ray_o_hi[a].val();
            self.slab.ray_m_lo[a].next = self.ray_m_lo[a].val();
            self.slab.ray_m_hi[a].next = self.ray_m_hi[a].val();
            self.slab.ray_neg[a].next = self.ray_neg[a].val();
            self.slab.box_lo[a].next = self.box_lo[a].val();
            self.slab.box_hi[a].next = self.box_hi[a].val();
        }
        self.slab.ray_t_min.next = self.ray_t_min.val();
        self.slab.ray_t_max.next = self.ray_t_max.val();
        for w in 0..MAX_SLAB_WAIT {
            self.slab_valid_qw[w].clock.next = self.clock.val();
            self.slab_tag_qw[w].clock.next = self.clock.val();
            self.slab_hit_qw[w].clock.next = self.clock.val();
            self.slab_entry_qw[w].clock.next = self.clock.val();
            self.slab_exit_qw[w].clock.next = self.clock.val();
        }
        self.slab_valid_qw[0].d.next = self.slab.valid_out.val() & !self.rst.val();
        self.slab_tag_qw[0].d.next = self.slab.tag_out.val();
        self.slab_hit_qw[0].d.next = self.slab.hit.val();
        self.slab_entry_qw[0].d.next = self.slab.t_entry.val();
        self.slab_exit_qw[0].d.next = self.slab.t_exit.val();
        self.slab_valid_qw[1].d.next = self.slab_valid_qw[0].q.val() & !self.rst.val();
        self.slab_tag_qw[1].d.next = self.slab_tag_qw[0].q.val();
        self.slab_hit_qw[1].d.next = self.slab_hit_qw[0].q.val();
        self.slab_entry_qw[1].d.next = self.slab_entry_qw[0].q.val();
        self.slab_exit_qw[1].d.next = self.slab_exit_qw[0].q.val();
        self.slab_valid_qw[2].d.next = self.slab_valid_qw[1].q.val() & !self.rst.val();
        self.slab_tag_qw[2].d.next = self.slab_tag_qw[1].q.val();
        self.slab_hit_qw[2].d.next = self.slab_hit_qw[1].q.val();
        self.slab_entry_qw[2].d.next = self.slab_entry_qw[1].q.val();
        self.slab_exit_qw[2].d.next = self.slab_exit_qw[1].q.val();
        self.slab_valid_qw[3].d.next = self.slab_valid_qw[2].q.val() & !self.rst.val();
        self.slab_tag_qw[3].d.next = self.slab_tag_qw[2].q.val();
        self.slab_hit_qw[3].d.next = self.slab_hit_qw[2].q.val();
        self.slab_entry_qw[3].d.next = self.slab_entry_qw[2].q.val();
        self.slab_exit_qw[3].d.next = self.slab_exit_qw[2].q.val();
        self.slab_valid_qw[4].d.next = self.slab_valid_qw[3].q.val() & !self.rst.val();
        self.slab_tag_qw[4].d.next = self.slab_tag_qw[3].q.val();
        self.slab_hit_qw[4].d.next = self.slab_hit_qw[3].q.val();
        self.slab_entry_qw[4].d.next = self.slab_entry_qw[3].q.val();
        self.slab_exit_qw[4].d.next = self.slab_exit_qw[3].q.val();

        // Stage 1: each plane's sums, operands chosen by the sign of its normal components.
        for k in 0..K {
            self.sums[k].n0.next = self.plane_nx[k].val();
            self.sums[k].n1.next = self.plane_ny[k].val();
            self.sums[k].n2.next = self.plane_nz[k].val();
            self.sums[k].w.next = self.plane_w[k].val();
            self.sums[k].lo0.next = self.box_lo[0].val();
            self.sums[k].lo1.next = self.box_lo[1].val();
            self.sums[k].lo2.next = self.box_lo[2].val();
            self.sums[k].hi0.next = self.box_hi[0].val();
            self.sums[k].hi1.next = self.box_hi[1].val();
            self.sums[k].hi2.next = self.box_hi[2].val();
            if (self.plane_nx[k].val() & self.sign_n.val()).any() {
                self.sums[k].p0.next = self.ray_o_hi[0].val();
                self.sums[k].dl0.next = self.ray_d_hi[0].val();
                self.sums[k].dh0.next = self.ray_d_lo[0].val();
            } else {
                self.sums[k].p0.next = self.ray_o_lo[0].val();
                self.sums[k].dl0.next = self.ray_d_lo[0].val();
                self.sums[k].dh0.next = self.ray_d_hi[0].val();
            }
            if (self.plane_ny[k].val() & self.sign_n.val()).any() {
                self.sums[k].p1.next = self.ray_o_hi[1].val();
                self.sums[k].dl1.next = self.ray_d_hi[1].val();
                self.sums[k].dh1.next = self.ray_d_lo[1].val();
            } else {
                self.sums[k].p1.next = self.ray_o_lo[1].val();
                self.sums[k].dl1.next = self.ray_d_lo[1].val();
                self.sums[k].dh1.next = self.ray_d_hi[1].val();
            }
            if (self.plane_nz[k].val() & self.sign_n.val()).any() {
                self.sums[k].p2.next = self.ray_o_hi[2].val();
                self.sums[k].dl2.next = self.ray_d_hi[2].val();
                self.sums[k].dh2.next = self.ray_d_lo[2].val();
            } else {
                self.sums[k].p2.next = self.ray_o_lo[2].val();
                self.sums[k].dl2.next = self.ray_d_lo[2].val();
                self.sums[k].dh2.next = self.ray_d_hi[2].val();
            }
            self.s_q1[k].d.next = self.sums[k].s.val();
            self.dl_q1[k].d.next = self.sums[k].den_lo.val();
            self.dh_q1[k].d.next = self.sums[k].den_hi.val();
        }

        // Stage 2: each plane's bound; unused slots hold -inf / +inf.
        for k in 0..MAX_PLANES {
            self.en_q2[k].d.next = self.t_ninf.val();
            self.ex_q2[k].d.next = self.t_pinf.val();
            self.par_q2[k].d.next = false;
        }
        for k in 0..K {
            self.bound[k].clock.next = self.clock.val();
            self.bound[k].s.next = self.s_q1[k].q.val();
            self.bound[k].den_lo.next = self.dl_q1[k].q.val();
            self.bound[k].den_hi.next = self.dh_q1[k].q.val();
            if self.bound[k].is_entry.val() {
                self.en_q2[k].d.next = self.bound[k].y.val();
            }
            if self.bound[k].is_exit.val() {
                self.ex_q2[k].d.next = self.bound[k].y.val();
            }
            self.par_q2[k].d.next = self.bound[k].par.val();
        }

        // Stage 3: eight slots to four.
        if (self.en_q2[1].q.val() ^ self.sign_t.val()) > (self.en_q2[0].q.val() ^ self.sign_t.val())
        {
            self.en_q3[0].d.next = self.en_q2[1].q.val();
        } else {
            self.en_q3[0].d.next = self.en_q2[0].q.val();
        }
        if (self.en_q2[3].q.val() ^ self.sign_t.val()) > (self.en_q2[2].q.val() ^ self.sign_t.val())
        {
            self.en_q3[1].d.next = self.en_q2[3].q.val();
        } else {
            self.en_q3[1].d.next = self.en_q2[2].q.val();
        }
        if (self.en_q2[5].q.val() ^ self.sign_t.val()) > (self.en_q2[4].q.val() ^ self.sign_t.val())
        {
            self.en_q3[2].d.next = self.en_q2[5].q.val();
        } else {
            self.en_q3[2].d.next = self.en_q2[4].q.val();
        }
        if (self.en_q2[7].q.val() ^ self.sign_t.val()) > (self.en_q2[6].q.val() ^ self.sign_t.val())
        {
            self.en_q3[3].d.next = self.en_q2[7].q.val();
        } else {
            self.en_q3[3].d.next = self.en_q2[6].q.val();
        }
        if (self.ex_q2[1].q.val() ^ self.sign_t.val()) < (self.ex_q2[0].q.val() ^ self.sign_t.val())
        {
            self.ex_q3[0].d.next = self.ex_q2[1].q.val();
        } else {
            self.ex_q3[0].d.next = self.ex_q2[0].q.val();
        }
        if (self.ex_q2[3].q.val() ^ self.sign_t.val()) < (self.ex_q2[2].q.val() ^ self.sign_t.val())
        {
            self.ex_q3[1].d.next = self.ex_q2[3].q.val();
        } else {
            self.ex_q3[1].d.next = self.ex_q2[2].q.val();
        }
        if (self.ex_q2[5].q.val() ^ self.sign_t.val()) < (self.ex_q2[4].q.val() ^ self.sign_t.val())
        {
            self.ex_q3[2].d.next = self.ex_q2[5].q.val();
        } else {
            self.ex_q3[2].d.next = self.ex_q2[4].q.val();
        }
        if (self.ex_q2[7].q.val() ^ self.sign_t.val()) < (self.ex_q2[6].q.val() ^ self.sign_t.val())
        {
            self.ex_q3[3].d.next = self.ex_q2[7].q.val();
        } else {
            self.ex_q3[3].d.next = self.ex_q2[6].q.val();
        }
        self.par_q3.d.next = self.par_q2[0].q.val()
            | self.par_q2[1].q.val()
            | self.par_q2[2].q.val()
            | self.par_q2[3].q.val()
            | self.par_q2[4].q.val()
            | self.par_q2[5].q.val()
            | self.par_q2[6].q.val()
            | self.par_q2[7].q.val();

        // Stage 4: four to two.
        if (self.en_q3[1].q.val() ^ self.sign_t.val()) > (self.en_q3[0].q.val() ^ self.sign_t.val())
        {
            self.en_q4[0].d.next = self.en_q3[1].q.val();
        } else {
            self.en_q4[0].d.next = self.en_q3[0].q.val();
        }
        if (self.en_q3[3].q.val() ^ self.sign_t.val()) > (self.en_q3[2].q.val() ^ self.sign_t.val())
        {
            self.en_q4[1].d.next = self.en_q3[3].q.val();
        } else {
            self.en_q4[1].d.next = self.en_q3[2].q.val();
        }
        if (self.ex_q3[1].q.val() ^ self.sign_t.val()) < (self.ex_q3[0].q.val() ^ self.sign_t.val())
        {
            self.ex_q4[0].d.next = self.ex_q3[1].q.val();
        } else {
            self.ex_q4[0].d.next = self.ex_q3[0].q.val();
        }
        if (self.ex_q3[3].q.val() ^ self.sign_t.val()) < (self.ex_q3[2].q.val() ^ self.sign_t.val())
        {
            self.ex_q4[1].d.next = self.ex_q3[3].q.val();
        } else {
            self.ex_q4[1].d.next = self.ex_q3[2].q.val();
        }
        self.par_q4.d.next = self.par_q3.q.val();

        // Stage 5: the last level, merged with the slab tester's interval.
        self.en_l5.next = self.en_q4[0].q.val();
        if (self.en_q4[1].q.val() ^ self.sign_t.val()) > (self.en_q4[0].q.val() ^ self.sign_t.val())
        {
            self.en_l5.next = self.en_q4[1].q.val();
        }
        self.ex_l5.next = self.ex_q4[0].q.val();
        if (self.ex_q4[1].q.val() ^ self.sign_t.val()) < (self.ex_q4[0].q.val() ^ self.sign_t.val())
        {
            self.ex_l5.next = self.ex_q4[1].q.val();
        }
        if (self.en_l5.val() ^ self.sign_t.val())
            > (self.slab_entry_qw[4].q.val() ^ self.sign_t.val())
        {
            self.entry_q5.d.next = self.en_l5.val();
        } else {
            self.entry_q5.d.next = self.slab_entry_qw[4].q.val();
        }
        if (self.ex_l5.val() ^ self.sign_t.val())
            < (self.slab_exit_qw[4].q.val() ^ self.sign_t.val())
        {
            self.exit_q5.d.next = self.ex_l5.val();
        } else {
            self.exit_q5.d.next = self.slab_exit_qw[4].q.val();
        }
        self.live_q5.d.next = self.slab_hit_qw[4].q.val() & !self.par_q4.q.val();
        self.valid_q5.d.next = self.slab_valid_qw[4].q.val() & !self.rst.val();
        self.tag_q5.d.next = self.slab_tag_qw[4].q.val();

        // Stage 6: the cull decision.
        self.entry_q6.d.next = self.entry_q5.q.val();
        self.exit_q6.d.next = self.exit_q5.q.val();
        self.hit_q6.d.next = self.live_q5.q.val()
            & ((self.entry_q5.q.val() ^ self.sign_t.val())
                <= (self.exit_q5.q.val() ^ self.sign_t.val()));
        self.valid_q6.d.next = self.valid_q5.q.val() & !self.rst.val();
        self.tag_q6.d.next = self.tag_q5.q.val();

        self.valid_out.next = self.valid_q6.q.val();
        self.tag_out.next = self.tag_q6.q.val();
        self.hit.next = self.hit_q6.q.val();
        self.t_entry.next = self.entry_q6.q.val();
        self.t_exit.next = self.exit_q6.q.val();
    }
}
