//! `PlaneFloat`: the chained float node tester — the float slab test, then `K` cull planes (`1 <= K <= 8`) —
//! fully pipelined (one test per clock), [`PLANE_FLOAT_LATENCY`] clocks for every `K`. Bit for bit
//! `golden::plane::float::node_float(cf, K, ray, node)` (read `golden::plane::float` for the arithmetic and
//! the conservativeness argument); ports mirror `NodeFloatRay`, `FloatNode` and `SlabFloatOut`.
//!
//! # Parameters
//! `E >= 4`, `M`, `N = 1 + E + M <= 32` (the format), `K` (planes); the reciprocal table's index bits `R`
//! are a constructor argument ([`PlaneFloat::with_r`]), `R = min(M, 8)` by default ([`PlaneFloat::new`],
//! `CullFloatFormat::over`), `1 <= R <= min(M, 8)`.
//!
//! # Ports
//! The [`SlabFloat`] ports (`ray_o_lo`, `ray_o_hi`, `ray_m_lo`, `ray_m_hi`, `ray_neg`, `ray_t_min`,
//! `ray_t_max`, `box_lo`, `box_hi`), the direction interval `ray_d_lo`, `ray_d_hi` (3 each), the planes
//! `plane_nx`, `plane_ny`, `plane_nz`, `plane_w` (`K` each); `clock`, `rst` (synchronous: clears every valid bit), `valid_in`, `tag_in` (16 bits). Out
//! (registered): `valid_out`, `tag_out`, `hit`, `t_entry`, `t_exit`.
//!
//! # Stages (clock at whose end a value is registered)
//! * 1-9: the [`SlabFloat`] tester, in parallel with everything below; its result waits in a delay line
//!   until clock 29.
//! * 1-3: `RN(lo + hi)`; 4-6: `c = RN(x * 0.5)` ([`FpAdd`], [`FpMul`]); 7-9: `ol = RD(o_lo - c)`,
//!   `oh = RU(o_hi - c)`. Origin and direction wait in [`Delay3`] lines.
//! * 10-25: one [`PlaneUnit`] per plane (its module doc): products, the three sums `S_lo`, `den_lo`,
//!   `den_hi` (clock 21), the case decision and the reciprocal (clock 22, [`FpRecip`]), and the bound
//!   `RU(-S_lo * r)` (clock 25; an entry bound is its negation, since `RD(x) = -RU(-x)`).
//! * 26 (`leaf_*`): a NaN bound (`0 x inf`) becomes "no bound"; the `K` bounds are padded to 8 leaves with
//!   `-inf` (entries) and `+inf` (exits), which leave a max / min alone; the parallel culls ORed.
//! * 27-29 (`l1_*`, `l2_*`, `l3_*`): max (entries) and min (exits) trees over the 8 leaves.
//! * 30 (`_q30`): `entry = max(slab entry, planes)`, `exit = min(slab exit, planes)`, and
//!   `hit = slab hit && !cull && entry <= exit` as the AND of the four pairwise `<=` (only the slab's values
//!   can be NaN); these registers drive the outputs.
//!
//! The model folds `fmax(a, b) = a < b ? b : a` left to right, slab first; a balanced tree with the slab
//! leftmost gives the same bits: both return the leftmost of the maximal values (`-0`/`+0` ties), and a NaN
//! slab entry (the only possible NaN) wins every comparison it is the left operand of.
//!
//! Every comparator reads registers only (Verilator UNOPTFLAT otherwise; see `rtl/src/slab/float.rs`).

use crate::delay::Delay3;
use crate::fp::add::{FpAdd, FP_ADD_LATENCY};
use crate::fp::cmp::FpCmp;
use crate::fp::mul::{FpMul, FP_MUL_LATENCY};
use crate::io::TesterIo;
use crate::plane::ports::PlaneFloatPorts;
use crate::plane::recip::{FpRecip, FP_RECIP_LATENCY};
use crate::slab::float::{SlabFloat, SLAB_FLOAT_LATENCY};
use crate::TAG_BITS;
use golden::format::float::{FloatFormat, Rounding};
use golden::plane::float::{CullFloatFormat, FloatNode, NodeFloatRay};
use golden::slab::float::SlabFloatOut;
use rust_hdl::prelude::*;

/// The most planes of one tester.
pub const PLANE_FLOAT_MAX_K: usize = 8;

/// Clocks from `ol`/`oh` into a [`PlaneUnit`] to its bound out.
pub const PLANE_UNIT_LATENCY: usize = 3 * FP_ADD_LATENCY + 2 * FP_MUL_LATENCY + FP_RECIP_LATENCY;

/// Clocks from the centroid's start to `ol`/`oh`.
const CENTROID_LATENCY: usize = 2 * FP_ADD_LATENCY + FP_MUL_LATENCY;

/// Clocks from a test entering `PlaneFloat` to its result leaving (30).
pub const PLANE_FLOAT_LATENCY: usize = CENTROID_LATENCY + PLANE_UNIT_LATENCY + 1 + 3 + 1;

const _: () = assert!(PLANE_FLOAT_LATENCY == 30);
const _: () = assert!(PLANE_FLOAT_LATENCY > SLAB_FLOAT_LATENCY + 1);

/// One cull plane of [`PlaneFloat`]: from the centroid offsets to the plane's raw bound.
///
/// # Inputs
/// At clock 0 of the node test: `n_0`, `n_1`, `n_2`, `w` (delayed here by 9 and 18 clocks). Nine clocks later
/// (`PlaneFloat`'s clock 9): `valid_in`, `tag_in`, `ol_*`, `oh_*`, `d_lo_*`, `d_hi_*` (axes 0-2; scalar
/// ports, since rust-hdl cannot write `planes[k].ol[a]` from the parent).
/// # Outputs
/// [`PLANE_UNIT_LATENCY`] (16) clocks after `ol`: `valid_out`, `tag_out`, `p = RU(-S_lo * r)` (possibly
/// NaN), `is_exit` (`den_lo > 0`: the exit bound is `p`), `is_entry` (`den_hi < 0`: the entry bound is
/// `-p`), `par` (parallel cull).
/// # Stages (relative to `ol`)
/// 1-3: nine [`FpMul`] `u_a = RD(n_a * (n_a >= 0 ? ol_a : oh_a))`, `l_a`, `h_a`; 4-6, 7-9: the sums
/// `RD(RD(u_0 + u_1) + u_2)` and the two `den`s; 10-12: `S_lo = RD(s - w)` (the `den`s wait); 13 (`_q13`):
/// the case, `-S_lo`, and [`FpRecip`] of `den_lo`/`den_hi` in the chosen direction; 14-16: `RU(-S_lo * r)`.
#[derive(LogicBlock)]
pub struct PlaneUnit<const E: usize, const M: usize, const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub n_0: Signal<In, Bits<N>>,
    pub n_1: Signal<In, Bits<N>>,
    pub n_2: Signal<In, Bits<N>>,
    pub w: Signal<In, Bits<N>>,
    pub ol_0: Signal<In, Bits<N>>,
    pub ol_1: Signal<In, Bits<N>>,
    pub ol_2: Signal<In, Bits<N>>,
    pub oh_0: Signal<In, Bits<N>>,
    pub oh_1: Signal<In, Bits<N>>,
    pub oh_2: Signal<In, Bits<N>>,
    pub d_lo_0: Signal<In, Bits<N>>,
    pub d_lo_1: Signal<In, Bits<N>>,
    pub d_lo_2: Signal<In, Bits<N>>,
    pub d_hi_0: Signal<In, Bits<N>>,
    pub d_hi_1: Signal<In, Bits<N>>,
    pub d_hi_2: Signal<In, Bits<N>>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub p: Signal<Out, Bits<N>>,
    pub is_exit: Signal<Out, Bit>,
    pub is_entry: Signal<Out, Bit>,
    pub par: Signal<Out, Bit>,
    // constants
    sign_n: Constant<Bits<N>>,
    mag_mask: Constant<Bits<N>>,
    inf_n: Constant<Bits<N>>,
    // plane values waiting for the offsets
    n_d1: [Delay3<Bits<N>>; 3],
    n_d2: [Delay3<Bits<N>>; 3],
    n_d3: [Delay3<Bits<N>>; 3],
    w_d: [Delay3<Bits<N>>; 6],
    pos: [Signal<Local, Bit>; 3],
    ol_v: [Signal<Local, Bits<N>>; 3],
    oh_v: [Signal<Local, Bits<N>>; 3],
    d_lo_v: [Signal<Local, Bits<N>>; 3],
    d_hi_v: [Signal<Local, Bits<N>>; 3],
    // products
    mul_u: [FpMul<E, M, N>; 3],
    mul_l: [FpMul<E, M, N>; 3],
    mul_h: [FpMul<E, M, N>; 3],
    u2_d: Delay3<Bits<N>>,
    l2_d: Delay3<Bits<N>>,
    h2_d: Delay3<Bits<N>>,
    // sums
    add_s1: FpAdd<E, M, N>,
    add_l1: FpAdd<E, M, N>,
    add_h1: FpAdd<E, M, N>,
    add_s2: FpAdd<E, M, N>,
    add_l2: FpAdd<E, M, N>,
    add_h2: FpAdd<E, M, N>,
    add_s3: FpAdd<E, M, N>,
    dl_d: Delay3<Bits<N>>,
    dh_d: Delay3<Bits<N>>,
    // the case and the reciprocal
    dl_pos: Signal<Local, Bit>,
    dh_neg: Signal<Local, Bit>,
    s_nan: Signal<Local, Bit>,
    s_zero: Signal<Local, Bit>,
    s_neg: Signal<Local, Bit>,
    recip: FpRecip<E, M, N>,
    sneg_q13: DFF<Bits<N>>,
    exit_q13: DFF<Bit>,
    entry_q13: DFF<Bit>,
    par_q13: DFF<Bit>,
    // the bound
    mul_t: FpMul<E, M, N>,
    exit_d: Delay3<Bit>,
    entry_d: Delay3<Bit>,
    par_d: Delay3<Bit>,
    unused_handshake: Signal<Local, Bit>,
}

impl<const E: usize, const M: usize, const N: usize> PlaneUnit<E, M, N> {
    /// A plane unit with `r_bits` reciprocal index bits.
    pub fn new(r_bits: u32) -> Self {
        let f = FloatFormat::new(E as u32, M as u32).expect("valid format");
        let muls = |mode| std::array::from_fn(|_| FpMul::new(mode));
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            n_0: Default::default(),
            n_1: Default::default(),
            n_2: Default::default(),
            w: Default::default(),
            ol_0: Default::default(),
            ol_1: Default::default(),
            ol_2: Default::default(),
            oh_0: Default::default(),
            oh_1: Default::default(),
            oh_2: Default::default(),
            d_lo_0: Default::default(),
            d_lo_1: Default::default(),
            d_lo_2: Default::default(),
            d_hi_0: Default::default(),
            d_hi_1: Default::default(),
            d_hi_2: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            p: Default::default(),
            is_exit: Default::default(),
            is_entry: Default::default(),
            par: Default::default(),
            sign_n: Constant::new(bits::<N>(1 << (N - 1))),
            mag_mask: Constant::new(bits::<N>((1 << (N - 1)) - 1)),
            inf_n: Constant::new(bits::<N>(f.inf(false) as u64)),
            n_d1: Default::default(),
            n_d2: Default::default(),
            n_d3: Default::default(),
            w_d: Default::default(),
            pos: Default::default(),
            ol_v: Default::default(),
            oh_v: Default::default(),
            d_lo_v: Default::default(),
            d_hi_v: Default::default(),
            mul_u: muls(Rounding::Down),
            mul_l: muls(Rounding::Down),
            mul_h: muls(Rounding::Up),
            u2_d: Default::default(),
            l2_d: Default::default(),
            h2_d: Default::default(),
            add_s1: FpAdd::new(Rounding::Down),
            add_l1: FpAdd::new(Rounding::Down),
            add_h1: FpAdd::new(Rounding::Up),
            add_s2: FpAdd::new(Rounding::Down),
            add_l2: FpAdd::new(Rounding::Down),
            add_h2: FpAdd::new(Rounding::Up),
            add_s3: FpAdd::new(Rounding::Down),
            dl_d: Default::default(),
            dh_d: Default::default(),
            dl_pos: Default::default(),
            dh_neg: Default::default(),
            s_nan: Default::default(),
            s_zero: Default::default(),
            s_neg: Default::default(),
            recip: FpRecip::new(r_bits),
            sneg_q13: Default::default(),
            exit_q13: Default::default(),
            entry_q13: Default::default(),
            par_q13: Default::default(),
            mul_t: FpMul::new(Rounding::Up),
            exit_d: Default::default(),
            entry_d: Default::default(),
            par_d: Default::default(),
            unused_handshake: Default::default(),
        }
    }
}

impl<const E: usize, const M: usize, const N: usize> Logic for PlaneUnit<E, M, N> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, sneg_q13, exit_q13, entry_q13, par_q13);
        // The plane waits 9 clocks for the offsets (w 18 for the last sum).
        for i in 0..3 {
            self.n_d1[i].clock.next = self.clock.val();
            self.n_d2[i].clock.next = self.clock.val();
            self.n_d3[i].clock.next = self.clock.val();
            self.n_d2[i].d.next = self.n_d1[i].q.val();
            self.n_d3[i].d.next = self.n_d2[i].q.val();
        }
        self.n_d1[0].d.next = self.n_0.val();
        self.n_d1[1].d.next = self.n_1.val();
        self.n_d1[2].d.next = self.n_2.val();
        self.ol_v[0].next = self.ol_0.val();
        self.ol_v[1].next = self.ol_1.val();
        self.ol_v[2].next = self.ol_2.val();
        self.oh_v[0].next = self.oh_0.val();
        self.oh_v[1].next = self.oh_1.val();
        self.oh_v[2].next = self.oh_2.val();
        self.d_lo_v[0].next = self.d_lo_0.val();
        self.d_lo_v[1].next = self.d_lo_1.val();
        self.d_lo_v[2].next = self.d_lo_2.val();
        self.d_hi_v[0].next = self.d_hi_0.val();
        self.d_hi_v[1].next = self.d_hi_1.val();
        self.d_hi_v[2].next = self.d_hi_2.val();
        for i in 0..6 {
            self.w_d[i].clock.next = self.clock.val();
        }
        self.w_d[0].d.next = self.w.val();
        self.w_d[1].d.next = self.w_d[0].q.val();
        self.w_d[2].d.next = self.w_d[1].q.val();
        self.w_d[3].d.next = self.w_d[2].q.val();
        self.w_d[4].d.next = self.w_d[3].q.val();
        self.w_d[5].d.next = self.w_d[4].q.val();

        // Products: n >= 0 (either zero) takes the low end for the lower bounds.
        for i in 0..3 {
            self.mul_u[i].clock.next = self.clock.val();
            self.mul_l[i].clock.next = self.clock.val();
            self.mul_h[i].clock.next = self.clock.val();
            self.mul_u[i].valid_in.next = self.valid_in.val();
            self.mul_u[i].rst.next = self.rst.val();
            self.mul_l[i].valid_in.next = self.valid_in.val();
            self.mul_l[i].rst.next = self.rst.val();
            self.mul_h[i].valid_in.next = self.valid_in.val();
            self.mul_h[i].rst.next = self.rst.val();
            self.mul_u[i].tag_in.next = self.tag_in.val();
            self.mul_l[i].tag_in.next = self.tag_in.val();
            self.mul_h[i].tag_in.next = self.tag_in.val();
            self.pos[i].next = !(self.n_d3[i].q.val() & self.sign_n.val()).any()
                | !(self.n_d3[i].q.val() & self.mag_mask.val()).any();
            self.mul_u[i].a.next = self.n_d3[i].q.val();
            self.mul_l[i].a.next = self.n_d3[i].q.val();
            self.mul_h[i].a.next = self.n_d3[i].q.val();
            if self.pos[i].val() {
                self.mul_u[i].b.next = self.ol_v[i].val();
                self.mul_l[i].b.next = self.d_lo_v[i].val();
                self.mul_h[i].b.next = self.d_hi_v[i].val();
            } else {
                self.mul_u[i].b.next = self.oh_v[i].val();
                self.mul_l[i].b.next = self.d_hi_v[i].val();
                self.mul_h[i].b.next = self.d_lo_v[i].val();
            }
        }

        // Sums, left to right as the model associates them.
        self.u2_d.clock.next = self.clock.val();
        self.l2_d.clock.next = self.clock.val();
        self.h2_d.clock.next = self.clock.val();
        self.u2_d.d.next = self.mul_u[2].y.val();
        self.l2_d.d.next = self.mul_l[2].y.val();
        self.h2_d.d.next = self.mul_h[2].y.val();
        self.add_s1.clock.next = self.clock.val();
        self.add_l1.clock.next = self.clock.val();
        self.add_h1.clock.next = self.clock.val();
        self.add_s2.clock.next = self.clock.val();
        self.add_l2.clock.next = self.clock.val();
        self.add_h2.clock.next = self.clock.val();
        self.add_s3.clock.next = self.clock.val();
        self.add_s1.valid_in.next = self.mul_u[0].valid_out.val();
        self.add_s1.rst.next = self.rst.val();
        self.add_l1.valid_in.next = self.mul_l[0].valid_out.val();
        self.add_l1.rst.next = self.rst.val();
        self.add_h1.valid_in.next = self.mul_h[0].valid_out.val();
        self.add_h1.rst.next = self.rst.val();
        self.add_s1.tag_in.next = self.mul_u[0].tag_out.val();
        self.add_l1.tag_in.next = self.mul_l[0].tag_out.val();
        self.add_h1.tag_in.next = self.mul_h[0].tag_out.val();
        self.add_s1.a.next = self.mul_u[0].y.val();
        self.add_s1.b.next = self.mul_u[1].y.val();
        self.add_l1.a.next = self.mul_l[0].y.val();
        self.add_l1.b.next = self.mul_l[1].y.val();
        self.add_h1.a.next = self.mul_h[0].y.val();
        self.add_h1.b.next = self.mul_h[1].y.val();
        self.add_s2.valid_in.next = self.add_s1.valid_out.val();
        self.add_s2.rst.next = self.rst.val();
        self.add_l2.valid_in.next = self.add_l1.valid_out.val();
        self.add_l2.rst.next = self.rst.val();
        self.add_h2.valid_in.next = self.add_h1.valid_out.val();
        self.add_h2.rst.next = self.rst.val();
        self.add_s2.tag_in.next = self.add_s1.tag_out.val();
        self.add_l2.tag_in.next = self.add_l1.tag_out.val();
        self.add_h2.tag_in.next = self.add_h1.tag_out.val();
        self.add_s2.a.next = self.add_s1.y.val();
        self.add_s2.b.next = self.u2_d.q.val();
        self.add_l2.a.next = self.add_l1.y.val();
        self.add_l2.b.next = self.l2_d.q.val();
        self.add_h2.a.next = self.add_h1.y.val();
        self.add_h2.b.next = self.h2_d.q.val();
        self.add_s3.valid_in.next = self.add_s2.valid_out.val();
        self.add_s3.rst.next = self.rst.val();
        self.add_s3.tag_in.next = self.add_s2.tag_out.val();
        self.add_s3.a.next = self.add_s2.y.val();
        self.add_s3.b.next = self.w_d[5].q.val() ^ self.sign_n.val();
        self.dl_d.clock.next = self.clock.val();
        self.dh_d.clock.next = self.clock.val();
        self.dl_d.d.next = self.add_l2.y.val();
        self.dh_d.d.next = self.add_h2.y.val();

        // The case: den_lo > 0 an exit plane, den_hi < 0 an entry plane, else a parallel cull when both
        // are zero and S_lo > 0 (NaNs compare false).
        self.dl_pos.next = !(self.dl_d.q.val() & self.sign_n.val()).any()
            & (self.dl_d.q.val() & self.mag_mask.val()).any()
            & ((self.dl_d.q.val() & self.mag_mask.val()) <= self.inf_n.val());
        self.dh_neg.next = (self.dh_d.q.val() & self.sign_n.val()).any()
            & (self.dh_d.q.val() & self.mag_mask.val()).any()
            & ((self.dh_d.q.val() & self.mag_mask.val()) <= self.inf_n.val());
        self.s_nan.next = (self.add_s3.y.val() & self.mag_mask.val()) > self.inf_n.val();
        self.s_zero.next = !(self.add_s3.y.val() & self.mag_mask.val()).any();
        self.s_neg.next = (self.add_s3.y.val() & self.sign_n.val()).any();
        self.recip.clock.next = self.clock.val();
        self.recip.valid_in.next = self.add_s3.valid_out.val();
        self.recip.rst.next = self.rst.val();
        self.recip.tag_in.next = self.add_s3.tag_out.val();
        self.sneg_q13.d.next = self.add_s3.y.val() ^ self.sign_n.val();
        self.exit_q13.d.next = false;
        self.entry_q13.d.next = false;
        self.par_q13.d.next = false;
        if self.dl_pos.val() {
            // Exit: r an upper bound of 1/den_lo when S_lo <= 0, else a lower bound of 1/den_hi.
            self.exit_q13.d.next = true;
            self.recip.upper.next = !self.s_nan.val() & (self.s_neg.val() | self.s_zero.val());
            if !self.s_nan.val() & (self.s_neg.val() | self.s_zero.val()) {
                self.recip.mag.next = self.dl_d.q.val();
            } else {
                self.recip.mag.next = self.dh_d.q.val();
            }
        } else if self.dh_neg.val() {
            // Entry: r a lower bound of 1/|den_lo| when S_lo >= 0, else an upper bound of 1/|den_hi|.
            self.entry_q13.d.next = true;
            self.recip.upper.next = !(!self.s_nan.val() & (!self.s_neg.val() | self.s_zero.val()));
            if !self.s_nan.val() & (!self.s_neg.val() | self.s_zero.val()) {
                self.recip.mag.next = self.dl_d.q.val();
            } else {
                self.recip.mag.next = self.dh_d.q.val();
            }
        } else {
            self.recip.upper.next = false;
            self.recip.mag.next = self.dl_d.q.val();
            self.par_q13.d.next = !(self.dl_d.q.val() & self.mag_mask.val()).any()
                & !(self.dh_d.q.val() & self.mag_mask.val()).any()
                & !self.s_nan.val()
                & !self.s_neg.val()
                & !self.s_zero.val();
        }

        // The bound RU(-S_lo * r); the case flags wait for it.
        self.mul_t.clock.next = self.clock.val();
        self.mul_t.valid_in.next = self.recip.valid_out.val();
        self.mul_t.rst.next = self.rst.val();
        self.mul_t.tag_in.next = self.recip.tag_out.val();
        self.mul_t.a.next = self.sneg_q13.q.val();
        self.mul_t.b.next = self.recip.r.val();
        self.exit_d.clock.next = self.clock.val();
        self.entry_d.clock.next = self.clock.val();
        self.par_d.clock.next = self.clock.val();
        self.exit_d.d.next = self.exit_q13.q.val();
        self.entry_d.d.next = self.entry_q13.q.val();
        self.par_d.d.next = self.par_q13.q.val();

        self.valid_out.next = self.mul_t.valid_out.val();
        self.tag_out.next = self.mul_t.tag_out.val();
        self.p.next = self.mul_t.y.val();
        self.is_exit.next = self.exit_d.q.val();
        self.is_entry.next = self.entry_d.q.val();
        self.par.next = self.par_d.q.val();

        self.unused_handshake.next = self.mul_u[1].valid_out.val()
            ^ self.mul_u[2].valid_out.val()
            ^ self.mul_l[1].valid_out.val()
            ^ self.mul_l[2].valid_out.val()
            ^ self.mul_h[1].valid_out.val()
            ^ self.mul_h[2].valid_out.val()
            ^ self.mul_u[1].tag_out.val().xor()
            ^ self.mul_u[2].tag_out.val().xor()
            ^ self.mul_l[1].tag_out.val().xor()
            ^ self.mul_l[2].tag_out.val().xor()
            ^ self.mul_h[1].tag_out.val().xor()
            ^ self.mul_h[2].tag_out.val().xor()
            ^ self.add_l2.valid_out.val()
            ^ self.add_h2.valid_out.val()
            ^ self.add_l2.tag_out.val().xor()
            ^ self.add_h2.tag_out.val().xor();
    }
}

/// The chained float node tester; see the module documentation.
#[derive(LogicBlock)]
pub struct PlaneFloat<const E: usize, const M: usize, const N: usize, const K: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub ray_o_lo: [Signal<In, Bits<N>>; 3],
    pub ray_o_hi: [Signal<In, Bits<N>>; 3],
    pub ray_m_lo: [Signal<In, Bits<N>>; 3],
    pub ray_m_hi: [Signal<In, Bits<N>>; 3],
    pub ray_neg: [Signal<In, Bit>; 3],
    pub ray_t_min: Signal<In, Bits<N>>,
    pub ray_t_max: Signal<In, Bits<N>>,
    pub box_lo: [Signal<In, Bits<N>>; 3],
    pub box_hi: [Signal<In, Bits<N>>; 3],
    pub ray_d_lo: [Signal<In, Bits<N>>; 3],
    pub ray_d_hi: [Signal<In, Bits<N>>; 3],
    pub plane_nx: [Signal<In, Bits<N>>; K],
    pub plane_ny: [Signal<In, Bits<N>>; K],
    pub plane_nz: [Signal<In, Bits<N>>; K],
    pub plane_w: [Signal<In, Bits<N>>; K],
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub hit: Signal<Out, Bit>,
    pub t_entry: Signal<Out, Bits<N>>,
    pub t_exit: Signal<Out, Bits<N>>,
    // constants
    sign_n: Constant<Bits<N>>,
    mag_mask: Constant<Bits<N>>,
    inf_n: Constant<Bits<N>>,
    ninf_n: Constant<Bits<N>>,
    half_n: Constant<Bits<N>>,
    // the slab test and its result's delay line (clock 9 to 29)
    slab: SlabFloat<E, M, N>,
    slab_hit_d: [Delay3<Bit>; 6],
    slab_en_d: [Delay3<Bits<N>>; 6],
    slab_ex_d: [Delay3<Bits<N>>; 6],
    slab_hit_q28: DFF<Bit>,
    slab_en_q28: DFF<Bits<N>>,
    slab_ex_q28: DFF<Bits<N>>,
    slab_hit_q29: DFF<Bit>,
    slab_en_q29: DFF<Bits<N>>,
    slab_ex_q29: DFF<Bits<N>>,
    // centroid and offsets
    add_c: [FpAdd<E, M, N>; 3],
    mul_c: [FpMul<E, M, N>; 3],
    add_ol: [FpAdd<E, M, N>; 3],
    add_oh: [FpAdd<E, M, N>; 3],
    o_lo_d1: [Delay3<Bits<N>>; 3],
    o_lo_d2: [Delay3<Bits<N>>; 3],
    o_hi_d1: [Delay3<Bits<N>>; 3],
    o_hi_d2: [Delay3<Bits<N>>; 3],
    d_lo_d1: [Delay3<Bits<N>>; 3],
    d_lo_d2: [Delay3<Bits<N>>; 3],
    d_lo_d3: [Delay3<Bits<N>>; 3],
    d_hi_d1: [Delay3<Bits<N>>; 3],
    d_hi_d2: [Delay3<Bits<N>>; 3],
    d_hi_d3: [Delay3<Bits<N>>; 3],
    // the planes
    planes: [PlaneUnit<E, M, N>; K],
    // leaves (clock 26)
    par_any: Signal<Local, Bit>,
    leaf_en: [DFF<Bits<N>>; 8],
    leaf_ex: [DFF<Bits<N>>; 8],
    par_q26: DFF<Bit>,
    valid_q26: DFF<Bit>,
    tag_q26: DFF<Bits<TAG_BITS>>,
    // trees (clocks 27-29)
    cmp_l1_en: [FpCmp<N>; 4],
    cmp_l1_ex: [FpCmp<N>; 4],
    l1_en: [DFF<Bits<N>>; 4],
    l1_ex: [DFF<Bits<N>>; 4],
    par_q27: DFF<Bit>,
    valid_q27: DFF<Bit>,
    tag_q27: DFF<Bits<TAG_BITS>>,
    cmp_l2_en: [FpCmp<N>; 2],
    cmp_l2_ex: [FpCmp<N>; 2],
    l2_en: [DFF<Bits<N>>; 2],
    l2_ex: [DFF<Bits<N>>; 2],
    par_q28: DFF<Bit>,
    valid_q28: DFF<Bit>,
    tag_q28: DFF<Bits<TAG_BITS>>,
    cmp_l3_en: FpCmp<N>,
    cmp_l3_ex: FpCmp<N>,
    l3_en: DFF<Bits<N>>,
    l3_ex: DFF<Bits<N>>,
    par_q29: DFF<Bit>,
    valid_q29: DFF<Bit>,
    tag_q29: DFF<Bits<TAG_BITS>>,
    // the merge with the slab and the hit (clock 30)
    cmp_en: FpCmp<N>,
    cmp_ex: FpCmp<N>,
    cmp_hit: [FpCmp<N>; 4],
    entry_q30: DFF<Bits<N>>,
    exit_q30: DFF<Bits<N>>,
    hit_q30: DFF<Bit>,
    valid_q30: DFF<Bit>,
    tag_q30: DFF<Bits<TAG_BITS>>,
    unused_handshake: Signal<Local, Bit>,
    unused_planes: [Signal<Local, Bit>; K],
}

impl<const E: usize, const M: usize, const N: usize, const K: usize> PlaneFloat<E, M, N, K> {
    /// The tester with the default table, `R = min(M, 8)`.
    pub fn new() -> Self {
        Self::with_r(Self::cull_format().r)
    }

    /// The default cull format of the block: `CullFloatFormat::over` its float format.
    pub fn cull_format() -> CullFloatFormat {
        CullFloatFormat::over(FloatFormat::new(E as u32, M as u32).expect("valid format"))
    }

    /// The tester with `r_bits` reciprocal index bits (`1 <= r_bits <= min(M, 8)`).
    pub fn with_r(r_bits: u32) -> Self {
        let f = FloatFormat::new(E as u32, M as u32).expect("valid format");
        assert!(
            N as u32 == f.width() && E >= 4 && (1..=PLANE_FLOAT_MAX_K).contains(&K),
            "PlaneFloat<{E},{M},{N},{K}>: need N = 1+E+M, E >= 4, 1 <= K <= 8"
        );
        let c = |v: u64| Constant::new(bits::<N>(v));
        let inf = f.inf(false) as u64;
        let adders = |mode| std::array::from_fn(|_| FpAdd::new(mode));
        let cmps4 = || std::array::from_fn(|_| FpCmp::new(inf));
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
            box_lo: Default::default(),
            box_hi: Default::default(),
            ray_d_lo: Default::default(),
            ray_d_hi: Default::default(),
            plane_nx: std::array::from_fn(|_| Default::default()),
            plane_ny: std::array::from_fn(|_| Default::default()),
            plane_nz: std::array::from_fn(|_| Default::default()),
            plane_w: std::array::from_fn(|_| Default::default()),
            valid_out: Default::default(),
            tag_out: Default::default(),
            hit: Default::default(),
            t_entry: Default::default(),
            t_exit: Default::default(),
            sign_n: c(1 << (N - 1)),
            mag_mask: c((1 << (N - 1)) - 1),
            inf_n: c(inf),
            ninf_n: c(f.inf(true) as u64),
            half_n: c(f.from_f64(0.5, Rounding::NearestEven) as u64),
            slab: SlabFloat::new(),
            slab_hit_d: Default::default(),
            slab_en_d: Default::default(),
            slab_ex_d: Default::default(),
            slab_hit_q28: Default::default(),
            slab_en_q28: Default::default(),
            slab_ex_q28: Default::default(),
            slab_hit_q29: Default::default(),
            slab_en_q29: Default::default(),
            slab_ex_q29: Default::default(),
            add_c: adders(Rounding::NearestEven),
            mul_c: std::array::from_fn(|_| FpMul::new(Rounding::NearestEven)),
            add_ol: adders(Rounding::Down),
            add_oh: adders(Rounding::Up),
            o_lo_d1: Default::default(),
            o_lo_d2: Default::default(),
            o_hi_d1: Default::default(),
            o_hi_d2: Default::default(),
            d_lo_d1: Default::default(),
            d_lo_d2: Default::default(),
            d_lo_d3: Default::default(),
            d_hi_d1: Default::default(),
            d_hi_d2: Default::default(),
            d_hi_d3: Default::default(),
            planes: std::array::from_fn(|_| PlaneUnit::new(r_bits)),
            par_any: Default::default(),
            leaf_en: Default::default(),
            leaf_ex: Default::default(),
            par_q26: Default::default(),
            valid_q26: Default::default(),
            tag_q26: Default::default(),
            cmp_l1_en: cmps4(),
            cmp_l1_ex: cmps4(),
            l1_en: Default::default(),
            l1_ex: Default::default(),
            par_q27: Default::default(),
            valid_q27: Default::default(),
            tag_q27: Default::default(),
            cmp_l2_en: std::array::from_fn(|_| FpCmp::new(inf)),
            cmp_l2_ex: std::array::from_fn(|_| FpCmp::new(inf)),
            l2_en: Default::default(),
            l2_ex: Default::default(),
            par_q28: Default::default(),
            valid_q28: Default::default(),
            tag_q28: Default::default(),
            cmp_l3_en: FpCmp::new(inf),
            cmp_l3_ex: FpCmp::new(inf),
            l3_en: Default::default(),
            l3_ex: Default::default(),
            par_q29: Default::default(),
            valid_q29: Default::default(),
            tag_q29: Default::default(),
            cmp_en: FpCmp::new(inf),
            cmp_ex: FpCmp::new(inf),
            cmp_hit: cmps4(),
            entry_q30: Default::default(),
            exit_q30: Default::default(),
            hit_q30: Default::default(),
            valid_q30: Default::default(),
            tag_q30: Default::default(),
            unused_handshake: Default::default(),
            unused_planes: std::array::from_fn(|_| Default::default()),
        }
    }
}

impl<const E: usize, const M: usize, const N: usize, const K: usize> Default
    for PlaneFloat<E, M, N, K>
{
    fn default() -> Self {
        Self::new()
    }
}

/// A chained float node tester of any format and plane count.
pub trait PlaneFloatIo: TesterIo<Ray = NodeFloatRay, Box = FloatNode, Out = SlabFloatOut> {
    /// The float format of the block.
    fn format() -> FloatFormat;
    /// Planes per node.
    fn planes() -> usize;
    /// The cull format of a block made by [`PlaneFloatIo::make`] (`R = min(M, 8)`).
    fn cull_format() -> CullFloatFormat;
    /// A tester with the default table.
    fn make() -> Self;
}

impl<const E: usize, const M: usize, const N: usize, const K: usize> PlaneFloatIo
    for PlaneFloat<E, M, N, K>
{
    fn format() -> FloatFormat {
        FloatFormat::new(E as u32, M as u32).expect("valid format")
    }
    fn planes() -> usize {
        K
    }
    fn cull_format() -> CullFloatFormat {
        Self::cull_format()
    }
    fn make() -> Self {
        Self::new()
    }
}

impl<const E: usize, const M: usize, const N: usize, const K: usize> TesterIo
    for PlaneFloat<E, M, N, K>
{
    type Ray = NodeFloatRay;
    type Box = FloatNode;
    type Out = SlabFloatOut;
    const LATENCY: usize = PLANE_FLOAT_LATENCY;
    type Ports = PlaneFloatPorts;

    fn ports() -> PlaneFloatPorts {
        PlaneFloatPorts
    }

    crate::tester_ports!(
        inputs: ray_o_lo, ray_o_hi, ray_m_lo, ray_m_hi, ray_neg, ray_t_min, ray_t_max, box_lo, box_hi,
            ray_d_lo, ray_d_hi, plane_nx, plane_ny, plane_nz, plane_w;
        outputs: hit, t_entry, t_exit
    );
}

impl<const E: usize, const M: usize, const N: usize, const K: usize> Logic
    for PlaneFloat<E, M, N, K>
{
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            slab_hit_q28,
            slab_en_q28,
            slab_ex_q28,
            slab_hit_q29,
            slab_en_q29,
            slab_ex_q29,
            par_q26,
            valid_q26,
            tag_q26,
            par_q27,
            valid_q27,
            tag_q27,
            par_q28,
            valid_q28,
            tag_q28,
            l3_en,
            l3_ex,
            par_q29,
            valid_q29,
            tag_q29,
            entry_q30,
            exit_q30,
            hit_q30,
            valid_q30,
            tag_q30
        );

        // The slab test, and its result's wait.
        self.slab.clock.next = self.clock.val();
        self.slab.valid_in.next = self.valid_in.val();
        self.slab.rst.next = self.rst.val();
        self.slab.tag_in.next = self.tag_in.val();
        for i in 0..3 {
            self.slab.ray_o_lo[i].next = self.ray_o_lo[i].val();
            self.slab.ray_o_hi[i].next = self.ray_o_hi[i].val();
            self.slab.ray_m_lo[i].next = self.ray_m_lo[i].val();
            self.slab.ray_m_hi[i].next = self.ray_m_hi[i].val();
            self.slab.ray_neg[i].next = self.ray_neg[i].val();
            self.slab.box_lo[i].next = self.box_lo[i].val();
            self.slab.box_hi[i].next = self.box_hi[i].val();
        }
        self.slab.ray_t_min.next = self.ray_t_min.val();
        self.slab.ray_t_max.next = self.ray_t_max.val();
        for i in 0..6 {
            self.slab_hit_d[i].clock.next = self.clock.val();
            self.slab_en_d[i].clock.next = self.clock.val();
            self.slab_ex_d[i].clock.next = self.clock.val();
        }
        self.slab_hit_d[0].d.next = self.slab.hit.val();
        self.slab_en_d[0].d.next = self.slab.t_entry.val();
        self.slab_ex_d[0].d.next = self.slab.t_exit.val();
        self.slab_hit_d[1].d.next = self.slab_hit_d[0].q.val();
        self.slab_en_d[1].d.next = self.slab_en_d[0].q.val();
        self.slab_ex_d[1].d.next = self.slab_ex_d[0].q.val();
        self.slab_hit_d[2].d.next = self.slab_hit_d[1].q.val();
        self.slab_en_d[2].d.next = self.slab_en_d[1].q.val();
        self.slab_ex_d[2].d.next = self.slab_ex_d[1].q.val();
        self.slab_hit_d[3].d.next = self.slab_hit_d[2].q.val();
        self.slab_en_d[3].d.next = self.slab_en_d[2].q.val();
        self.slab_ex_d[3].d.next = self.slab_ex_d[2].q.val();
        self.slab_hit_d[4].d.next = self.slab_hit_d[3].q.val();
        self.slab_en_d[4].d.next = self.slab_en_d[3].q.val();
        self.slab_ex_d[4].d.next = self.slab_ex_d[3].q.val();
        self.slab_hit_d[5].d.next = self.slab_hit_d[4].q.val();
        self.slab_en_d[5].d.next = self.slab_en_d[4].q.val();
        self.slab_ex_d[5].d.next = self.slab_ex_d[4].q.val();
        self.slab_hit_q28.d.next = self.slab_hit_d[5].q.val();
        self.slab_en_q28.d.next = self.slab_en_d[5].q.val();
        self.slab_ex_q28.d.next = self.slab_ex_d[5].q.val();
        self.slab_hit_q29.d.next = self.slab_hit_q28.q.val();
        self.slab_en_q29.d.next = self.slab_en_q28.q.val();
        self.slab_ex_q29.d.next = self.slab_ex_q28.q.val();

        // Centroid c = RN(RN(lo + hi) * 0.5), then the offsets ol = RD(o_lo - c), oh = RU(o_hi - c).
        for i in 0..3 {
            self.add_c[i].clock.next = self.clock.val();
            self.mul_c[i].clock.next = self.clock.val();
            self.add_ol[i].clock.next = self.clock.val();
            self.add_oh[i].clock.next = self.clock.val();
            self.o_lo_d1[i].clock.next = self.clock.val();
            self.o_lo_d2[i].clock.next = self.clock.val();
            self.o_hi_d1[i].clock.next = self.clock.val();
            self.o_hi_d2[i].clock.next = self.clock.val();
            self.d_lo_d1[i].clock.next = self.clock.val();
            self.d_lo_d2[i].clock.next = self.clock.val();
            self.d_lo_d3[i].clock.next = self.clock.val();
            self.d_hi_d1[i].clock.next = self.clock.val();
            self.d_hi_d2[i].clock.next = self.clock.val();
            self.d_hi_d3[i].clock.next = self.clock.val();
            self.add_c[i].valid_in.next = self.valid_in.val();
            self.add_c[i].rst.next = self.rst.val();
            self.add_c[i].tag_in.next = self.tag_in.val();
            self.add_c[i].a.next = self.box_lo[i].val();
            self.add_c[i].b.next = self.box_hi[i].val();
            self.mul_c[i].valid_in.next = self.add_c[i].valid_out.val();
            self.mul_c[i].rst.next = self.rst.val();
            self.mul_c[i].tag_in.next = self.add_c[i].tag_out.val();
            self.mul_c[i].a.next = self.add_c[i].y.val();
            self.mul_c[i].b.next = self.half_n.val();
            self.o_lo_d1[i].d.next = self.ray_o_lo[i].val();
            self.o_lo_d2[i].d.next = self.o_lo_d1[i].q.val();
            self.o_hi_d1[i].d.next = self.ray_o_hi[i].val();
            self.o_hi_d2[i].d.next = self.o_hi_d1[i].q.val();
            self.add_ol[i].valid_in.next = self.mul_c[i].valid_out.val();
            self.add_ol[i].rst.next = self.rst.val();
            self.add_oh[i].valid_in.next = self.mul_c[i].valid_out.val();
            self.add_oh[i].rst.next = self.rst.val();
            self.add_ol[i].tag_in.next = self.mul_c[i].tag_out.val();
            self.add_oh[i].tag_in.next = self.mul_c[i].tag_out.val();
            self.add_ol[i].a.next = self.o_lo_d2[i].q.val();
            self.add_ol[i].b.next = self.mul_c[i].y.val() ^ self.sign_n.val();
            self.add_oh[i].a.next = self.o_hi_d2[i].q.val();
            self.add_oh[i].b.next = self.mul_c[i].y.val() ^ self.sign_n.val();
            self.d_lo_d1[i].d.next = self.ray_d_lo[i].val();
            self.d_lo_d2[i].d.next = self.d_lo_d1[i].q.val();
            self.d_lo_d3[i].d.next = self.d_lo_d2[i].q.val();
            self.d_hi_d1[i].d.next = self.ray_d_hi[i].val();
            self.d_hi_d2[i].d.next = self.d_hi_d1[i].q.val();
            self.d_hi_d3[i].d.next = self.d_hi_d2[i].q.val();
        }

        // The planes.
        for k in 0..K {
            self.planes[k].clock.next = self.clock.val();
            self.planes[k].valid_in.next = self.add_ol[0].valid_out.val();
            self.planes[k].rst.next = self.rst.val();
            self.planes[k].tag_in.next = self.add_ol[0].tag_out.val();
            self.planes[k].n_0.next = self.plane_nx[k].val();
            self.planes[k].n_1.next = self.plane_ny[k].val();
            self.planes[k].n_2.next = self.plane_nz[k].val();
            self.planes[k].w.next = self.plane_w[k].val();
            self.planes[k].ol_0.next = self.add_ol[0].y.val();
            self.planes[k].ol_1.next = self.add_ol[1].y.val();
            self.planes[k].ol_2.next = self.add_ol[2].y.val();
            self.planes[k].oh_0.next = self.add_oh[0].y.val();
            self.planes[k].oh_1.next = self.add_oh[1].y.val();
            self.planes[k].oh_2.next = self.add_oh[2].y.val();
            self.planes[k].d_lo_0.next = self.d_lo_d3[0].q.val();
            self.planes[k].d_lo_1.next = self.d_lo_d3[1].q.val();
            self.planes[k].d_lo_2.next = self.d_lo_d3[2].q.val();
            self.planes[k].d_hi_0.next = self.d_hi_d3[0].q.val();
            self.planes[k].d_hi_1.next = self.d_hi_d3[1].q.val();
            self.planes[k].d_hi_2.next = self.d_hi_d3[2].q.val();
        }

        // Leaves: a NaN bound is no bound; an entry bound is -p. Unused leaves are -inf / +inf.
        self.par_any.next = false;
        for k in 0..K {
            self.leaf_en[k].clock.next = self.clock.val();
            self.leaf_ex[k].clock.next = self.clock.val();
            if self.planes[k].is_entry.val()
                & ((self.planes[k].p.val() & self.mag_mask.val()) <= self.inf_n.val())
            {
                self.leaf_en[k].d.next = self.planes[k].p.val() ^ self.sign_n.val();
            } else {
                self.leaf_en[k].d.next = self.ninf_n.val();
            }
            if self.planes[k].is_exit.val()
                & ((self.planes[k].p.val() & self.mag_mask.val()) <= self.inf_n.val())
            {
                self.leaf_ex[k].d.next = self.planes[k].p.val();
            } else {
                self.leaf_ex[k].d.next = self.inf_n.val();
            }
            if self.planes[k].par.val() {
                self.par_any.next = true;
            }
        }
        for k in K..8 {
            self.leaf_en[k].clock.next = self.clock.val();
            self.leaf_ex[k].clock.next = self.clock.val();
            self.leaf_en[k].d.next = self.ninf_n.val();
            self.leaf_ex[k].d.next = self.inf_n.val();
        }
        self.par_q26.d.next = self.par_any.val();
        self.valid_q26.d.next = self.planes[0].valid_out.val() & !self.rst.val();
        self.tag_q26.d.next = self.planes[0].tag_out.val();

        // Level 1: max(a, b) = a < b ? b : a on entries, min(a, b) = b < a ? b : a on exits.
        for j in 0..4 {
            self.l1_en[j].clock.next = self.clock.val();
            self.l1_ex[j].clock.next = self.clock.val();
        }
        self.cmp_l1_en[0].a.next = self.leaf_en[0].q.val();
        self.cmp_l1_en[0].b.next = self.leaf_en[1].q.val();
        self.cmp_l1_en[1].a.next = self.leaf_en[2].q.val();
        self.cmp_l1_en[1].b.next = self.leaf_en[3].q.val();
        self.cmp_l1_en[2].a.next = self.leaf_en[4].q.val();
        self.cmp_l1_en[2].b.next = self.leaf_en[5].q.val();
        self.cmp_l1_en[3].a.next = self.leaf_en[6].q.val();
        self.cmp_l1_en[3].b.next = self.leaf_en[7].q.val();
        self.cmp_l1_ex[0].a.next = self.leaf_ex[1].q.val();
        self.cmp_l1_ex[0].b.next = self.leaf_ex[0].q.val();
        self.cmp_l1_ex[1].a.next = self.leaf_ex[3].q.val();
        self.cmp_l1_ex[1].b.next = self.leaf_ex[2].q.val();
        self.cmp_l1_ex[2].a.next = self.leaf_ex[5].q.val();
        self.cmp_l1_ex[2].b.next = self.leaf_ex[4].q.val();
        self.cmp_l1_ex[3].a.next = self.leaf_ex[7].q.val();
        self.cmp_l1_ex[3].b.next = self.leaf_ex[6].q.val();
        if self.cmp_l1_en[0].lt.val() {
            self.l1_en[0].d.next = self.leaf_en[1].q.val();
        } else {
            self.l1_en[0].d.next = self.leaf_en[0].q.val();
        }
        if self.cmp_l1_ex[0].lt.val() {
            self.l1_ex[0].d.next = self.leaf_ex[1].q.val();
        } else {
            self.l1_ex[0].d.next = self.leaf_ex[0].q.val();
        }
        if self.cmp_l1_en[1].lt.val() {
            self.l1_en[1].d.next = self.leaf_en[3].q.val();
        } else {
            self.l1_en[1].d.next = self.leaf_en[2].q.val();
        }
        if self.cmp_l1_ex[1].lt.val() {
            self.l1_ex[1].d.next = self.leaf_ex[3].q.val();
        } else {
            self.l1_ex[1].d.next = self.leaf_ex[2].q.val();
        }
        if self.cmp_l1_en[2].lt.val() {
            self.l1_en[2].d.next = self.leaf_en[5].q.val();
        } else {
            self.l1_en[2].d.next = self.leaf_en[4].q.val();
        }
        if self.cmp_l1_ex[2].lt.val() {
            self.l1_ex[2].d.next = self.leaf_ex[5].q.val();
        } else {
            self.l1_ex[2].d.next = self.leaf_ex[4].q.val();
        }
        if self.cmp_l1_en[3].lt.val() {
            self.l1_en[3].d.next = self.leaf_en[7].q.val();
        } else {
            self.l1_en[3].d.next = self.leaf_en[6].q.val();
        }
        if self.cmp_l1_ex[3].lt.val() {
            self.l1_ex[3].d.next = self.leaf_ex[7].q.val();
        } else {
            self.l1_ex[3].d.next = self.leaf_ex[6].q.val();
        }
        self.par_q27.d.next = self.par_q26.q.val();
        self.valid_q27.d.next = self.valid_q26.q.val() & !self.rst.val();
        self.tag_q27.d.next = self.tag_q26.q.val();

        // Level 2.
        for j in 0..2 {
            self.l2_en[j].clock.next = self.clock.val();
            self.l2_ex[j].clock.next = self.clock.val();
        }
        self.cmp_l2_en[0].a.next = self.l1_en[0].q.val();
        self.cmp_l2_en[0].b.next = self.l1_en[1].q.val();
        self.cmp_l2_en[1].a.next = self.l1_en[2].q.val();
        self.cmp_l2_en[1].b.next = self.l1_en[3].q.val();
        self.cmp_l2_ex[0].a.next = self.l1_ex[1].q.val();
        self.cmp_l2_ex[0].b.next = self.l1_ex[0].q.val();
        self.cmp_l2_ex[1].a.next = self.l1_ex[3].q.val();
        self.cmp_l2_ex[1].b.next = self.l1_ex[2].q.val();
        if self.cmp_l2_en[0].lt.val() {
            self.l2_en[0].d.next = self.l1_en[1].q.val();
        } else {
            self.l2_en[0].d.next = self.l1_en[0].q.val();
        }
        if self.cmp_l2_ex[0].lt.val() {
            self.l2_ex[0].d.next = self.l1_ex[1].q.val();
        } else {
            self.l2_ex[0].d.next = self.l1_ex[0].q.val();
        }
        if self.cmp_l2_en[1].lt.val() {
            self.l2_en[1].d.next = self.l1_en[3].q.val();
        } else {
            self.l2_en[1].d.next = self.l1_en[2].q.val();
        }
        if self.cmp_l2_ex[1].lt.val() {
            self.l2_ex[1].d.next = self.l1_ex[3].q.val();
        } else {
            self.l2_ex[1].d.next = self.l1_ex[2].q.val();
        }
        self.par_q28.d.next = self.par_q27.q.val();
        self.valid_q28.d.next = self.valid_q27.q.val() & !self.rst.val();
        self.tag_q28.d.next = self.tag_q27.q.val();

        // Level 3.
        self.cmp_l3_en.a.next = self.l2_en[0].q.val();
        self.cmp_l3_en.b.next = self.l2_en[1].q.val();
        self.cmp_l3_ex.a.next = self.l2_ex[1].q.val();
        self.cmp_l3_ex.b.next = self.l2_ex[0].q.val();
        if self.cmp_l3_en.lt.val() {
            self.l3_en.d.next = self.l2_en[1].q.val();
        } else {
            self.l3_en.d.next = self.l2_en[0].q.val();
        }
        if self.cmp_l3_ex.lt.val() {
            self.l3_ex.d.next = self.l2_ex[1].q.val();
        } else {
            self.l3_ex.d.next = self.l2_ex[0].q.val();
        }
        self.par_q29.d.next = self.par_q28.q.val();
        self.valid_q29.d.next = self.valid_q28.q.val() & !self.rst.val();
        self.tag_q29.d.next = self.tag_q28.q.val();

        // Merge with the slab (leftmost), and the hit as the AND of the four pairwise comparisons.
        self.cmp_en.a.next = self.slab_en_q29.q.val();
        self.cmp_en.b.next = self.l3_en.q.val();
        self.cmp_ex.a.next = self.l3_ex.q.val();
        self.cmp_ex.b.next = self.slab_ex_q29.q.val();
        if self.cmp_en.lt.val() {
            self.entry_q30.d.next = self.l3_en.q.val();
        } else {
            self.entry_q30.d.next = self.slab_en_q29.q.val();
        }
        if self.cmp_ex.lt.val() {
            self.exit_q30.d.next = self.l3_ex.q.val();
        } else {
            self.exit_q30.d.next = self.slab_ex_q29.q.val();
        }
        self.cmp_hit[0].a.next = self.slab_en_q29.q.val();
        self.cmp_hit[0].b.next = self.slab_ex_q29.q.val();
        self.cmp_hit[1].a.next = self.slab_en_q29.q.val();
        self.cmp_hit[1].b.next = self.l3_ex.q.val();
        self.cmp_hit[2].a.next = self.l3_en.q.val();
        self.cmp_hit[2].b.next = self.slab_ex_q29.q.val();
        self.cmp_hit[3].a.next = self.l3_en.q.val();
        self.cmp_hit[3].b.next = self.l3_ex.q.val();
        self.hit_q30.d.next = self.slab_hit_q29.q.val()
            & !self.par_q29.q.val()
            & self.cmp_hit[0].le.val()
            & self.cmp_hit[1].le.val()
            & self.cmp_hit[2].le.val()
            & self.cmp_hit[3].le.val();
        self.valid_q30.d.next = self.valid_q29.q.val() & !self.rst.val();
        self.tag_q30.d.next = self.tag_q29.q.val();

        self.valid_out.next = self.valid_q30.q.val();
        self.tag_out.next = self.tag_q30.q.val();
        self.hit.next = self.hit_q30.q.val();
        self.t_entry.next = self.entry_q30.q.val();
        self.t_exit.next = self.exit_q30.q.val();

        // Handshakes of the units the test's own valid/tag do not follow, unused comparator outputs.
        for k in 0..K {
            self.unused_planes[k].next =
                self.planes[k].valid_out.val() ^ self.planes[k].tag_out.val().xor();
        }
        self.unused_handshake.next = self.slab.valid_out.val()
            ^ self.slab.tag_out.val().xor()
            ^ self.add_c[1].valid_out.val()
            ^ self.add_c[2].valid_out.val()
            ^ self.mul_c[1].valid_out.val()
            ^ self.mul_c[2].valid_out.val()
            ^ self.mul_c[1].tag_out.val().xor()
            ^ self.mul_c[2].tag_out.val().xor()
            ^ self.add_ol[1].valid_out.val()
            ^ self.add_ol[2].valid_out.val()
            ^ self.add_oh[0].valid_out.val()
            ^ self.add_oh[1].valid_out.val()
            ^ self.add_oh[2].valid_out.val()
            ^ self.add_ol[1].tag_out.val().xor()
            ^ self.add_ol[2].tag_out.val().xor()
            ^ self.add_oh[0].tag_out.val().xor()
            ^ self.add_oh[1].tag_out.val().xor()
            ^ self.add_oh[2].tag_out.val().xor()
            ^ self.cmp_l1_en[0].le.val()
            ^ self.cmp_l1_en[1].le.val()
            ^ self.cmp_l1_en[2].le.val()
            ^ self.cmp_l1_en[3].le.val()
            ^ self.cmp_l1_ex[0].le.val()
            ^ self.cmp_l1_ex[1].le.val()
            ^ self.cmp_l1_ex[2].le.val()
            ^ self.cmp_l1_ex[3].le.val()
            ^ self.cmp_l2_en[0].le.val()
            ^ self.cmp_l2_en[1].le.val()
            ^ self.cmp_l2_ex[0].le.val()
            ^ self.cmp_l2_ex[1].le.val()
            ^ self.cmp_l3_en.le.val()
            ^ self.cmp_l3_ex.le.val()
            ^ self.cmp_en.le.val()
            ^ self.cmp_ex.le.val()
            ^ self.cmp_hit[0].lt.val()
            ^ self.cmp_hit[1].lt.val()
            ^ self.cmp_hit[2].lt.val()
            ^ self.cmp_hit[3].lt.val();
    }
}
