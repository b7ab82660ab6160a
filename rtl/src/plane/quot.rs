//! `PlaneQuot`: the fraction option of the fixed-point cull-plane tester — the slab tester chained with
//! `K` cull planes whose bounds are never rounded: each is kept as the exact fraction
//! `t* = num * 2^E / den` (t code units, `E = FD + FT - 1`) and ordered against the others and against
//! the slab's t codes by cross-multiplication, so no division, reciprocal table or rounding appears
//! anywhere. Fully pipelined (one node test per clock), [`PLANE_QUOT_LATENCY`] clocks. Its result is
//! `golden::plane::fix::cull_fix_quotients` exactly (value for value; [`node_quot`](golden::plane::quot::node_quot) is the bit-accurate
//! model, which also fixes the tie-breaking); compare [`crate::plane::fix::PlaneFix`], the table option,
//! built on the same front end.
//!
//! # Why it is conservative
//! Each fraction is the bound that holds for every `den` of the plane's interval (`golden::plane::fix`
//! derives it; [`PlaneQuotBound`] forms it) and it is never rounded, so the entry it gives is the
//! exact largest lower bound and the exit the exact smallest upper bound the stored planes allow. A node
//! is culled only when `max(entries) > min(exits)` exactly, i.e. when the clipped interval is truly empty
//! for the quantised inputs (the quantisation itself is outward). The table option can only lose culls
//! against it, never gain one.
//!
//! # Parameters
//! Those of [`crate::plane::fix::PlaneFix`] (`G, D, I, T, N, DB, WB, SB, EB, K`), plus `MB = EB - 1`
//! (denominator bits) and `FB = SB + MB` (a packed fraction), checked by [`PlaneQuot::new`].
//!
//! # Ports
//! Inputs: those of `PlaneFix`. Outputs: `valid_out`, `tag_out`, `hit` (not culled), and `t_entry`,
//! `t_exit`, each a fraction packed as `{den, num}` (`den` in the top `MB` bits, `num` in the low `SB`):
//! `den != 0` is the plane bound `num * 2^E / den`; `den = 0` is the slab's t code in the low `T` bits of
//! `num` (`+-inf` codes included). [`Quot`](golden::plane::quot::Quot) is the unpacked form ([`crate::plane::ports::PlaneQuotPorts`] packs and unpacks).
//!
//! # Stages
//! 1. `_q1`: per plane, [`PlaneSums`] (as `PlaneFix`); the slab tester runs in parallel (out at clock 4).
//! 2. `_q2`: per plane, [`PlaneQuotBound`]: entry/exit flags, the fraction, the parallel-cull flag.
//! 3. to 5. two [`QuotTree`]s: the largest entry and the smallest exit fraction over eight slots (slots
//!    from `K` on are empty constants, which synthesis removes), one cross-multiplied comparison per level;
//!    the slab's result and the OR of the parallel culls wait in registers.
//! 6. `_q6`: the merge with the slab's codes and the cull decision, all comparisons in parallel:
//!    `entry = max(slab entry, plane entry)` and `exit = min(slab exit, plane exit)` ([`CodeQuotCmp`]),
//!    and `hit = slab hit && no parallel cull && entry <= exit`, where `entry <= exit` is the AND of the
//!    four pairwise `<=` of {slab entry, plane entry} against {slab exit, plane exit} (one [`QuotCmp`],
//!    two `CodeQuotCmp`s and a t-code comparison), so the merge's result is not waited for.

use crate::delay::Delay3;
use crate::io::TesterIo;
use crate::plane::ports::PlaneQuotPorts;
use crate::plane::quot_bound::PlaneQuotBound;
use crate::plane::quot_cmp::QuotCmp;
use crate::plane::quot_code_cmp::CodeQuotCmp;
use crate::plane::quot_tree::QuotTree;
use crate::plane::sums::PlaneSums;
use crate::slab::fix::{SlabFix, TAG_BITS};
use golden::plane::fix::{CullFixFormat, FixNode, NodeFixRay, MAX_PLANES};
use golden::plane::quot::{quot_den_bits, quot_scale, PlaneQuotOut};
use rust_hdl::prelude::*;

/// Clocks from a node test entering `PlaneQuot` to its result leaving.
pub const PLANE_QUOT_LATENCY: usize = 6;

/// The fraction option of the chained fixed tester; see the module documentation.
#[derive(LogicBlock)]
pub struct PlaneQuot<
    const G: usize,
    const D: usize,
    const I: usize,
    const T: usize,
    const N: usize,
    const DB: usize,
    const WB: usize,
    const SB: usize,
    const EB: usize,
    const MB: usize,
    const FB: usize,
    const K: usize,
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
    pub t_entry: Signal<Out, Bits<FB>>,
    pub t_exit: Signal<Out, Bits<FB>>,
    // constants
    sign_n: Constant<Bits<N>>,
    sign_t: Constant<Bits<T>>,
    t_pinf: Constant<Bits<T>>,
    t_ninf: Constant<Bits<T>>,
    zero_t: Constant<Bits<T>>,
    zero_s: Constant<Bits<SB>>,
    zero_m: Constant<Bits<MB>>,
    num_bits: Constant<Bits<8>>,
    // the slab tester, in parallel
    slab: SlabFix<G, D, I, T>,
    // stage 1
    sums: [PlaneSums<G, N, DB, WB, SB, EB>; K],
    s_q1: [DFF<Bits<SB>>; K],
    dl_q1: [DFF<Bits<EB>>; K],
    dh_q1: [DFF<Bits<EB>>; K],
    // stage 2 (eight slots; those from K on are constants)
    bound: [PlaneQuotBound<SB, EB, MB>; K],
    en_q2: [DFF<Bit>; MAX_PLANES],
    ex_q2: [DFF<Bit>; MAX_PLANES],
    num_q2: [DFF<Bits<SB>>; MAX_PLANES],
    den_q2: [DFF<Bits<MB>>; MAX_PLANES],
    par_q2: [DFF<Bit>; MAX_PLANES],
    // stages 3-5
    par_l3: Signal<Local, Bit>,
    tree_en: QuotTree<SB, MB>,
    tree_ex: QuotTree<SB, MB>,
    par_d5: Delay3<Bit>,
    slab_en_q5: DFF<Bits<T>>,
    slab_ex_q5: DFF<Bits<T>>,
    slab_hit_q5: DFF<Bit>,
    valid_q5: DFF<Bit>,
    tag_q5: DFF<Bits<TAG_BITS>>,
    // stage 6: `c` the slab's codes, `p` the planes' fractions; `e` entry, `x` exit
    ce_ninf: Signal<Local, Bit>,
    ce_pinf: Signal<Local, Bit>,
    cx_ninf: Signal<Local, Bit>,
    cx_pinf: Signal<Local, Bit>,
    ce_pe: CodeQuotCmp<T, SB, MB>,
    ce_px: CodeQuotCmp<T, SB, MB>,
    cx_pe: CodeQuotCmp<T, SB, MB>,
    cx_px: CodeQuotCmp<T, SB, MB>,
    px_pe: QuotCmp<SB, MB>,
    entry_n_q6: DFF<Bits<SB>>,
    entry_d_q6: DFF<Bits<MB>>,
    exit_n_q6: DFF<Bits<SB>>,
    exit_d_q6: DFF<Bits<MB>>,
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
        const MB: usize,
        const FB: usize,
        const K: usize,
    > PlaneQuot<G, D, I, T, N, DB, WB, SB, EB, MB, FB, K>
{
    /// A tester for `cf`, whose widths must equal the parameters.
    pub fn new(cf: &CullFixFormat) -> Self {
        assert!(
            cf.n as usize == N
                && cf.d_bits() as usize == DB
                && cf.w_bits() as usize == WB
                && cf.s_bits() as usize == SB
                && cf.den_bits() as usize == EB
                && quot_den_bits(cf) as usize == MB
                && FB == SB + MB
                && FB <= 64
                && (1..=MAX_PLANES).contains(&K),
            "PlaneQuot<..,{N},{DB},{WB},{SB},{EB},{MB},{FB},{K}> does not match plane format {}",
            cf.name()
        );
        let t = T as u32;
        let e = quot_scale(cf);
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
            zero_t: Constant::new(bits::<T>(0)),
            zero_s: Constant::new(bits::<SB>(0)),
            zero_m: Constant::new(bits::<MB>(0)),
            num_bits: Constant::new(bits::<8>(SB as u64)),
            slab: SlabFix::new(&cf.base),
            sums: std::array::from_fn(|_| PlaneSums::new(0)),
            s_q1: std::array::from_fn(|_| Default::default()),
            dl_q1: std::array::from_fn(|_| Default::default()),
            dh_q1: std::array::from_fn(|_| Default::default()),
            bound: std::array::from_fn(|_| Default::default()),
            en_q2: Default::default(),
            ex_q2: Default::default(),
            num_q2: Default::default(),
            den_q2: Default::default(),
            par_q2: Default::default(),
            par_l3: Default::default(),
            tree_en: QuotTree::new(false),
            tree_ex: QuotTree::new(true),
            par_d5: Default::default(),
            slab_en_q5: Default::default(),
            slab_ex_q5: Default::default(),
            slab_hit_q5: Default::default(),
            valid_q5: Default::default(),
            tag_q5: Default::default(),
            ce_ninf: Default::default(),
            ce_pinf: Default::default(),
            cx_ninf: Default::default(),
            cx_pinf: Default::default(),
            ce_pe: CodeQuotCmp::new(e, false),
            ce_px: CodeQuotCmp::new(e, true),
            cx_pe: CodeQuotCmp::new(e, false),
            cx_px: CodeQuotCmp::new(e, true),
            px_pe: Default::default(),
            entry_n_q6: Default::default(),
            entry_d_q6: Default::default(),
            exit_n_q6: Default::default(),
            exit_d_q6: Default::default(),
            hit_q6: Default::default(),
            valid_q6: Default::default(),
            tag_q6: Default::default(),
        }
    }
}

/// The fraction option of any width and plane count, built for a plane format.
pub trait PlaneQuotIo: TesterIo<Ray = NodeFixRay, Box = FixNode, Out = PlaneQuotOut> {
    /// Planes per node.
    const PLANES: usize;
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
        const MB: usize,
        const FB: usize,
        const K: usize,
    > PlaneQuotIo for PlaneQuot<G, D, I, T, N, DB, WB, SB, EB, MB, FB, K>
{
    const PLANES: usize = K;
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
        const MB: usize,
        const FB: usize,
        const K: usize,
    > TesterIo for PlaneQuot<G, D, I, T, N, DB, WB, SB, EB, MB, FB, K>
{
    type Ray = NodeFixRay;
    type Box = FixNode;
    type Out = PlaneQuotOut;
    const LATENCY: usize = PLANE_QUOT_LATENCY;
    type Ports = PlaneQuotPorts;

    fn ports() -> PlaneQuotPorts {
        PlaneQuotPorts { sb: SB, t: T }
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
        const MB: usize,
        const FB: usize,
        const K: usize,
    > Logic for PlaneQuot<G, D, I, T, N, DB, WB, SB, EB, MB, FB, K>
{
    #[hdl_gen]
    fn update(&mut self) {
        for k in 0..K {
            self.s_q1[k].clock.next = self.clock.val();
            self.dl_q1[k].clock.next = self.clock.val();
            self.dh_q1[k].clock.next = self.clock.val();
        }
        for k in 0..MAX_PLANES {
            self.en_q2[k].clock.next = self.clock.val();
            self.ex_q2[k].clock.next = self.clock.val();
            self.num_q2[k].clock.next = self.clock.val();
            self.den_q2[k].clock.next = self.clock.val();
            self.par_q2[k].clock.next = self.clock.val();
        }
        dff_setup!(
            self,
            clock,
            slab_en_q5,
            slab_ex_q5,
            slab_hit_q5,
            valid_q5,
            tag_q5,
            entry_n_q6,
            entry_d_q6,
            exit_n_q6,
            exit_d_q6,
            hit_q6,
            valid_q6,
            tag_q6
        );
        self.tree_en.clock.next = self.clock.val();
        self.tree_ex.clock.next = self.clock.val();
        self.par_d5.clock.next = self.clock.val();

        // The slab tester, on the same inputs.
        self.slab.clock.next = self.clock.val();
        self.slab.valid_in.next = self.valid_in.val();
        self.slab.rst.next = self.rst.val();
        self.slab.tag_in.next = self.tag_in.val();
        self.slab.ray_t_min.next = self.ray_t_min.val();
        self.slab.ray_t_max.next = self.ray_t_max.val();
        for a in 0..3 {
            self.slab.ray_o_lo[a].next = self.ray_o_lo[a].val();
            self.slab.ray_o_hi[a].next = self.ray_o_hi[a].val();
            self.slab.ray_m_lo[a].next = self.ray_m_lo[a].val();
            self.slab.ray_m_hi[a].next = self.ray_m_hi[a].val();
            self.slab.ray_neg[a].next = self.ray_neg[a].val();
            self.slab.box_lo[a].next = self.box_lo[a].val();
            self.slab.box_hi[a].next = self.box_hi[a].val();
        }

        // Stage 1: each plane's sums; a negative normal component takes o_hi and swaps the d bounds.
        for k in 0..K {
            self.sums[k].clock.next = self.clock.val();
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
            self.sums[k].p0.next = self.ray_o_lo[0].val();
            self.sums[k].dl0.next = self.ray_d_lo[0].val();
            self.sums[k].dh0.next = self.ray_d_hi[0].val();
            self.sums[k].p1.next = self.ray_o_lo[1].val();
            self.sums[k].dl1.next = self.ray_d_lo[1].val();
            self.sums[k].dh1.next = self.ray_d_hi[1].val();
            self.sums[k].p2.next = self.ray_o_lo[2].val();
            self.sums[k].dl2.next = self.ray_d_lo[2].val();
            self.sums[k].dh2.next = self.ray_d_hi[2].val();
            if (self.plane_nx[k].val() & self.sign_n.val()).any() {
                self.sums[k].p0.next = self.ray_o_hi[0].val();
                self.sums[k].dl0.next = self.ray_d_hi[0].val();
                self.sums[k].dh0.next = self.ray_d_lo[0].val();
            }
            if (self.plane_ny[k].val() & self.sign_n.val()).any() {
                self.sums[k].p1.next = self.ray_o_hi[1].val();
                self.sums[k].dl1.next = self.ray_d_hi[1].val();
                self.sums[k].dh1.next = self.ray_d_lo[1].val();
            }
            if (self.plane_nz[k].val() & self.sign_n.val()).any() {
                self.sums[k].p2.next = self.ray_o_hi[2].val();
                self.sums[k].dl2.next = self.ray_d_hi[2].val();
                self.sums[k].dh2.next = self.ray_d_lo[2].val();
            }
            self.s_q1[k].d.next = self.sums[k].s.val();
            self.dl_q1[k].d.next = self.sums[k].den_lo.val();
            self.dh_q1[k].d.next = self.sums[k].den_hi.val();
        }

        // Stage 2: each plane's bound as a fraction; unused slots are empty.
        for k in 0..MAX_PLANES {
            self.en_q2[k].d.next = false;
            self.ex_q2[k].d.next = false;
            self.num_q2[k].d.next = self.zero_s.val();
            self.den_q2[k].d.next = self.zero_m.val();
            self.par_q2[k].d.next = false;
        }
        for k in 0..K {
            self.bound[k].s.next = self.s_q1[k].q.val();
            self.bound[k].den_lo.next = self.dl_q1[k].q.val();
            self.bound[k].den_hi.next = self.dh_q1[k].q.val();
            self.en_q2[k].d.next = self.bound[k].is_entry.val();
            self.ex_q2[k].d.next = self.bound[k].is_exit.val();
            self.num_q2[k].d.next = self.bound[k].num.val();
            self.den_q2[k].d.next = self.bound[k].den.val();
            self.par_q2[k].d.next = self.bound[k].par.val();
        }

        // Stages 3-5: the trees; the parallel culls and the slab's result wait.
        self.par_l3.next = false;
        for k in 0..MAX_PLANES {
            self.tree_en.v[k].next = self.en_q2[k].q.val();
            self.tree_en.n[k].next = self.num_q2[k].q.val();
            self.tree_en.d[k].next = self.den_q2[k].q.val();
            self.tree_ex.v[k].next = self.ex_q2[k].q.val();
            self.tree_ex.n[k].next = self.num_q2[k].q.val();
            self.tree_ex.d[k].next = self.den_q2[k].q.val();
            if self.par_q2[k].q.val() {
                self.par_l3.next = true;
            }
        }
        self.par_d5.d.next = self.par_l3.val();
        self.slab_en_q5.d.next = self.slab.t_entry.val();
        self.slab_ex_q5.d.next = self.slab.t_exit.val();
        self.slab_hit_q5.d.next = self.slab.hit.val();
        self.valid_q5.d.next = self.slab.valid_out.val() & !self.rst.val();
        self.tag_q5.d.next = self.slab.tag_out.val();

        // Stage 6: the merge with the slab's codes and the cull decision, comparisons in parallel.
        self.ce_ninf.next = self.slab_en_q5.q.val() == self.t_ninf.val();
        self.ce_pinf.next = self.slab_en_q5.q.val() == self.t_pinf.val();
        self.cx_ninf.next = self.slab_ex_q5.q.val() == self.t_ninf.val();
        self.cx_pinf.next = self.slab_ex_q5.q.val() == self.t_pinf.val();
        self.ce_pe.c.next = self.slab_en_q5.q.val();
        self.ce_pe.num.next = self.tree_en.n_out.val();
        self.ce_pe.den.next = self.tree_en.d_out.val();
        self.ce_px.c.next = self.slab_en_q5.q.val();
        self.ce_px.num.next = self.tree_ex.n_out.val();
        self.ce_px.den.next = self.tree_ex.d_out.val();
        self.cx_pe.c.next = self.slab_ex_q5.q.val();
        self.cx_pe.num.next = self.tree_en.n_out.val();
        self.cx_pe.den.next = self.tree_en.d_out.val();
        self.cx_px.c.next = self.slab_ex_q5.q.val();
        self.cx_px.num.next = self.tree_ex.n_out.val();
        self.cx_px.den.next = self.tree_ex.d_out.val();
        self.px_pe.a_num.next = self.tree_ex.n_out.val();
        self.px_pe.a_den.next = self.tree_ex.d_out.val();
        self.px_pe.b_num.next = self.tree_en.n_out.val();
        self.px_pe.b_den.next = self.tree_en.d_out.val();
        // The slab's code, zero-extended (bit_cast of `x ^ 0`: see the lint waiver), with den = 0.
        self.entry_n_q6.d.next = bit_cast::<SB, T>(self.slab_en_q5.q.val() ^ self.zero_t.val());
        self.entry_d_q6.d.next = self.zero_m.val();
        if self.tree_en.v_out.val()
            & (self.ce_ninf.val() | (!self.ce_pinf.val() & self.ce_pe.y.val()))
        {
            self.entry_n_q6.d.next = self.tree_en.n_out.val();
            self.entry_d_q6.d.next = self.tree_en.d_out.val();
        }
        self.exit_n_q6.d.next = bit_cast::<SB, T>(self.slab_ex_q5.q.val() ^ self.zero_t.val());
        self.exit_d_q6.d.next = self.zero_m.val();
        if self.tree_ex.v_out.val()
            & (self.cx_pinf.val() | (!self.cx_ninf.val() & self.cx_px.y.val()))
        {
            self.exit_n_q6.d.next = self.tree_ex.n_out.val();
            self.exit_d_q6.d.next = self.tree_ex.d_out.val();
        }
        // entry <= exit: slab entry <= slab exit, slab entry <= plane exit, plane entry <= slab exit,
        // plane entry <= plane exit (an empty plane slot is -inf / +inf: its terms hold).
        self.hit_q6.d.next = self.slab_hit_q5.q.val()
            & !self.par_d5.q.val()
            & ((self.slab_en_q5.q.val() ^ self.sign_t.val())
                <= (self.slab_ex_q5.q.val() ^ self.sign_t.val()))
            & (!self.tree_ex.v_out.val()
                | self.ce_ninf.val()
                | (!self.ce_pinf.val() & !self.ce_px.y.val()))
            & (!self.tree_en.v_out.val()
                | self.cx_pinf.val()
                | (!self.cx_ninf.val() & !self.cx_pe.y.val()))
            & (!self.tree_en.v_out.val() | !self.tree_ex.v_out.val() | !self.px_pe.lt.val());
        self.valid_q6.d.next = self.valid_q5.q.val() & !self.rst.val();
        self.tag_q6.d.next = self.tag_q5.q.val();

        self.valid_out.next = self.valid_q6.q.val();
        self.tag_out.next = self.tag_q6.q.val();
        self.hit.next = self.hit_q6.q.val();
        self.t_entry.next = (bit_cast::<FB, MB>(self.entry_d_q6.q.val() ^ self.zero_m.val())
            << self.num_bits.val())
            | bit_cast::<FB, SB>(self.entry_n_q6.q.val() ^ self.zero_s.val());
        self.t_exit.next = (bit_cast::<FB, MB>(self.exit_d_q6.q.val() ^ self.zero_m.val())
            << self.num_bits.val())
            | bit_cast::<FB, SB>(self.exit_n_q6.q.val() ^ self.zero_s.val());
    }
}
