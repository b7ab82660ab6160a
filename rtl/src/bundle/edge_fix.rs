//! `BundleTest`: one of the pair of fixed-point bundle testers, AllHit or AnyHit (a constructor
//! argument: the two share this structure and differ only in which bounds they take), fully pipelined
//! (one test per clock), [`bundle_test_latency`]`(CUTS)` clocks of latency (3, or 5 with every cut
//! point). The AllHit tester can be switched to AnyHit bounds test by test (`any_mode`): in two-ray
//! mode the pair runs AnyHit on both testers.
//!
//! Bit for bit `golden::bundle::edge::conditions_hold` in `golden::bundle::fix::FixArith` with `t_min = 0`:
//! [`BundleTest::all_hit`] computes `golden::bundle::fix::all_hit_fix` on the inner box and `t_lo`
//! (with `any_mode` high, what the AnyHit tester computes), [`BundleTest::any_hit`] computes
//! `!golden::bundle::fix::all_miss_fix` on the outer box and `t_hi` (`pass` low means every ray of the
//! bundle misses). Read `golden/src/bundle/edge.rs` for the conditions and
//! their proofs; [`crate::bundle::pair_fix::BundleFix`] pairs the two on one bundle.
//!
//! # Parameters
//! | name | meaning | b8 / b12 / b16 |
//! | --- | --- | --- |
//! | `G` | grid bits (signed origin and box coordinates) | 8 / 12 / 16 |
//! | `V` | difference bits `e`, `x`, must be `G + 1` | 9 / 13 / 17 |
//! | `D` | direction code bits `FD + 3` (signed, `FD` fraction bits) | 9 / 13 / 17 |
//! | `T` | t code bits (signed, `FT` fraction bits; the most positive code is `+inf`) | 14 / 20 / 24 |
//!
//! `FD + FT` enters only as the distance shift, a constructor argument ([`BundleTest::new`] checks the
//! widths against a `BundleFixFormat`).
//!
//! # Inputs
//! - `clock`; `rst` (synchronous reset: high at a clock edge, every valid bit is cleared and no test in flight leaves; data registers are not reset); `valid_in`, `tag_in` (16 bits, opaque, returned with the result);
//! - `o_lo`, `o_hi`, `d_lo`, `d_hi` (arrays over x, y, z) and `t_max`: the bundle, fields of
//!   `golden::bundle::fix::FixBundle` (`t_max` is its `t_lo` for AllHit, `t_hi` for AnyHit);
//! - `box_lo`, `box_hi`: the box (`inner` for AllHit, `outer` for AnyHit);
//! - `any_mode`: AnyHit bounds for this test even in the AllHit tester. The mode of a test is AllHit
//!   exactly when the constructor chose AllHit and `any_mode` is low; it is registered with the test
//!   (`sure_q1`) and used in stages 1 and 2, so the bit may change every clock. The AnyHit tester
//!   ignores it.
//!
//! Input contract (what the quantisers produce): direction codes of magnitude at most `2^(D-2)` (so that
//! `-d` fits `D` bits). Every other code is taken as it comes.
//!
//! # Outputs (registered, [`bundle_test_latency`]`(CUTS)` clocks after the inputs)
//! - `valid_out`, `tag_out`, `pass`: all fifteen conditions hold.
//!
//! # Stages
//! 1. `_q1` fold: per axis a [`FoldDiff`] (the differences of both folds, `V` bits, with the origin ends
//!    that make `e` largest and `x` smallest for AllHit, the reverse for AnyHit); the sign class of
//!    `[d_lo, d_hi]` (positive, negative, straddling) and the AnyHit half rule pick `e`, `x` and
//!    `[u_lo, u_hi]` (`D` bits, `-d` by subtraction from zero); `N`, the box check `lo <= hi`.
//! 2. `_q2` bounds: for each of the six edges `E_ac` the multiplier of `e_a` (`u_lo` or `u_hi` of axis
//!    `c`, by the sign of `e_a`) and of `x_c` (by the sign of `x_c`); for each distance the multiplier of
//!    `t_max` (by the sign of `t_max`); the sign checks `D` (`x >= 0`) folded into one flag with `N`.
//! 3. `_q3` decide: six [`EdgeLe`] (products `V + D` bits, 34 for b16), three [`DistLe`] (products
//!    `T + D` bits, 41 for b16) and the AND of everything. Two optional cut points ([`cut`]) split it:
//!    [`cut::PRODUCT`] registers the products inside each compare (side data `_qp`), [`cut::COMPARE`]
//!    the nine compares' answers (`le_qc`, side data `_qc`) before their AND.
//!
//! The products and their compares share stage 3 so that no signal wider than `T` bits is a rust-hdl
//! register (wide values simulate bit by bit); stage 2 is light and a synthesis flow may retime into it.
//! Signed compares in the `#[hdl_gen]` code are unsigned compares of sign-flipped codes, as in
//! [`crate::slab::fix::SlabFix`].

use crate::bundle::dist_le::DistLe;
use crate::bundle::edge_le::EdgeLe;
use crate::bundle::fold_diff::FoldDiff;
use crate::cut::Cut;
use crate::slab::fix::TAG_BITS;
use golden::bundle::fix::BundleFixFormat;
use rust_hdl::prelude::*;

/// The optional cut points of the bundle tester (stage 3), one bit each of its `CUTS` parameter: a
/// register where the bit is set, a wire where it is clear ([`crate::cut::Cut`]). Stages 1, 2 and 3's
/// output register are always there.
pub mod cut {
    /// After the products, inside each compare ([`crate::bundle::edge_le::EdgeLe`]'s `lhs_q`,
    /// `rhs_q`, [`crate::bundle::dist_le::DistLe`]'s `prod_q`, `side_q`; side data `_qp`).
    pub const PRODUCT: usize = 1 << 0;
    /// After the compares: their nine answers (`le_qc`) and the side data (`_qc`), before the AND.
    pub const COMPARE: usize = 1 << 1;
    /// Every cut point.
    pub const ALL: usize = (1 << 2) - 1;
}

/// The cut points of the 3-clock tester (the default of [`BundleTest`]'s `CUTS`): none, a whole
/// multiply, compare and AND in the last clock.
pub const BUNDLE_TEST_CUTS: usize = 0;

/// The cut points of the 5-clock tester: products and compares registered.
pub const BUNDLE_TEST_CUTS_DEEP: usize = cut::ALL;

/// Clocks from a test entering a `BundleTest` with cut points `cuts` to its result leaving: three, and
/// one per cut.
pub const fn bundle_test_latency(cuts: usize) -> usize {
    3 + (cuts & cut::ALL).count_ones() as usize
}

/// Clocks from a test entering the default [`BundleTest`] to its result leaving.
pub const BUNDLE_TEST_LATENCY: usize = bundle_test_latency(BUNDLE_TEST_CUTS);

/// One bundle tester; see the module documentation.
#[derive(LogicBlock)]
pub struct BundleTest<
    const G: usize,
    const V: usize,
    const D: usize,
    const T: usize,
    const CUTS: usize = BUNDLE_TEST_CUTS,
> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub o_lo: [Signal<In, Bits<G>>; 3],
    pub o_hi: [Signal<In, Bits<G>>; 3],
    pub d_lo: [Signal<In, Bits<D>>; 3],
    pub d_hi: [Signal<In, Bits<D>>; 3],
    pub t_max: Signal<In, Bits<T>>,
    pub box_lo: [Signal<In, Bits<G>>; 3],
    pub box_hi: [Signal<In, Bits<G>>; 3],
    /// 1: AnyHit bounds whatever the constructor chose (the AllHit tester judging one ray in two-ray mode).
    pub any_mode: Signal<In, Bit>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub pass: Signal<Out, Bit>,
    // constants
    /// 1 for AllHit (bounds against the conditions), 0 for AnyHit.
    sure: Constant<Bit>,
    sign_v: Constant<Bits<V>>,
    sign_d: Constant<Bits<D>>,
    sign_t: Constant<Bits<T>>,
    zero_d: Constant<Bits<D>>,
    // stage 1
    /// `sure & !any_mode`: the mode of this test, carried with it to stage 2.
    sure_eff: Signal<Local, Bit>,
    sure_q1: DFF<Bit>,
    diff: [FoldDiff<G, V>; 3],
    nd_lo: [Signal<Local, Bits<D>>; 3],
    nd_hi: [Signal<Local, Bits<D>>; 3],
    e_le: [Signal<Local, Bit>; 3],
    x_le: [Signal<Local, Bit>; 3],
    e_pick: [Signal<Local, Bits<V>>; 3],
    x_pick: [Signal<Local, Bits<V>>; 3],
    u_max: [Signal<Local, Bits<D>>; 3],
    empty: Signal<Local, Bit>,
    e_q1: [DFF<Bits<V>>; 3],
    x_q1: [DFF<Bits<V>>; 3],
    ulo_q1: [DFF<Bits<D>>; 3],
    uhi_q1: [DFF<Bits<D>>; 3],
    t_q1: DFF<Bits<T>>,
    empty_q1: DFF<Bit>,
    valid_q1: DFF<Bit>,
    tag_q1: DFF<Bits<TAG_BITS>>,
    // stage 2
    e_lo_sel: [Signal<Local, Bit>; 3],
    x_lo_sel: [Signal<Local, Bit>; 3],
    t_neg: Signal<Local, Bit>,
    ok: Signal<Local, Bit>,
    e_q2: [DFF<Bits<V>>; 3],
    x_q2: [DFF<Bits<V>>; 3],
    /// Multiplier of `e_a` in edge `k`.
    me_q2: [DFF<Bits<D>>; 6],
    /// Multiplier of `x_c` in edge `k`.
    mx_q2: [DFF<Bits<D>>; 6],
    /// Multiplier of `t_max` in distance check `a`.
    mt_q2: [DFF<Bits<D>>; 3],
    t_q2: DFF<Bits<T>>,
    ok_q2: DFF<Bit>,
    valid_q2: DFF<Bit>,
    tag_q2: DFF<Bits<TAG_BITS>>,
    // stage 3: edges k = 0..6 are (a, c) = (0,1), (0,2), (1,0), (1,2), (2,0), (2,1)
    edge_cmp: [EdgeLe<V, D>; 6],
    dist_cmp: [DistLe<V, T, D>; 3],
    /// 1 where the product cut is a register: the valid bit there is cleared by `rst` (a wire passes
    /// it on to the next register, which is).
    reg_p: Constant<Bit>,
    ok_qp: Cut<Bit>,
    valid_qp: Cut<Bit>,
    tag_qp: Cut<Bits<TAG_BITS>>,
    /// 1 where the compare cut is a register.
    reg_c: Constant<Bit>,
    /// The compares' answers: edges 0..6, then distances.
    le_qc: [Cut<Bit>; 9],
    ok_qc: Cut<Bit>,
    valid_qc: Cut<Bit>,
    tag_qc: Cut<Bits<TAG_BITS>>,
    all: Signal<Local, Bit>,
    pass_q3: DFF<Bit>,
    valid_q3: DFF<Bit>,
    tag_q3: DFF<Bits<TAG_BITS>>,
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize>
    BundleTest<G, V, D, T, CUTS>
{
    /// The AllHit tester (`all_hit = true`) or the AnyHit tester for `bf`, whose widths must equal the
    /// parameters.
    pub fn new(bf: &BundleFixFormat, all_hit: bool) -> Self {
        assert!(
            CUTS & !cut::ALL == 0,
            "BundleTest cut points {CUTS:#x}: only the cuts of rtl::bundle::edge_fix::cut exist"
        );
        let (p, c) = (CUTS & cut::PRODUCT != 0, CUTS & cut::COMPARE != 0);
        assert!(
            bf.base.g as usize == G
                && V == G + 1
                && bf.dir_bits() as usize == D
                && bf.base.t as usize == T,
            "BundleTest<{G},{V},{D},{T}> does not match format {}",
            bf.name()
        );
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            o_lo: Default::default(),
            o_hi: Default::default(),
            d_lo: Default::default(),
            d_hi: Default::default(),
            t_max: Default::default(),
            box_lo: Default::default(),
            box_hi: Default::default(),
            any_mode: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            pass: Default::default(),
            sure: Constant::new(all_hit),
            sign_v: Constant::new(bits::<V>(1 << (V - 1))),
            sign_d: Constant::new(bits::<D>(1 << (D - 1))),
            sign_t: Constant::new(bits::<T>(1 << (T - 1))),
            zero_d: Constant::new(bits::<D>(0)),
            sure_eff: Default::default(),
            sure_q1: Default::default(),
            diff: Default::default(),
            nd_lo: Default::default(),
            nd_hi: Default::default(),
            e_le: Default::default(),
            x_le: Default::default(),
            e_pick: Default::default(),
            x_pick: Default::default(),
            u_max: Default::default(),
            empty: Default::default(),
            e_q1: Default::default(),
            x_q1: Default::default(),
            ulo_q1: Default::default(),
            uhi_q1: Default::default(),
            t_q1: Default::default(),
            empty_q1: Default::default(),
            valid_q1: Default::default(),
            tag_q1: Default::default(),
            e_lo_sel: Default::default(),
            x_lo_sel: Default::default(),
            t_neg: Default::default(),
            ok: Default::default(),
            e_q2: Default::default(),
            x_q2: Default::default(),
            me_q2: Default::default(),
            mx_q2: Default::default(),
            mt_q2: Default::default(),
            t_q2: Default::default(),
            ok_q2: Default::default(),
            valid_q2: Default::default(),
            tag_q2: Default::default(),
            edge_cmp: std::array::from_fn(|_| EdgeLe::new(p)),
            dist_cmp: std::array::from_fn(|_| DistLe::with_register(bf.dist_shift() as usize, p)),
            reg_p: Constant::new(p),
            ok_qp: Cut::new(p),
            valid_qp: Cut::new(p),
            tag_qp: Cut::new(p),
            reg_c: Constant::new(c),
            le_qc: Cut::array(c),
            ok_qc: Cut::new(c),
            valid_qc: Cut::new(c),
            tag_qc: Cut::new(c),
            all: Default::default(),
            pass_q3: Default::default(),
            valid_q3: Default::default(),
            tag_q3: Default::default(),
        }
    }

    /// The AllHit tester for `bf`.
    pub fn all_hit(bf: &BundleFixFormat) -> Self {
        Self::new(bf, true)
    }

    /// The AnyHit tester for `bf`.
    pub fn any_hit(bf: &BundleFixFormat) -> Self {
        Self::new(bf, false)
    }
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize> Logic
    for BundleTest<G, V, D, T, CUTS>
{
    #[hdl_gen]
    fn update(&mut self) {
        // Clocks of every register.
        for i in 0..3 {
            self.e_q1[i].clock.next = self.clock.val();
            self.x_q1[i].clock.next = self.clock.val();
            self.ulo_q1[i].clock.next = self.clock.val();
            self.uhi_q1[i].clock.next = self.clock.val();
            self.e_q2[i].clock.next = self.clock.val();
            self.x_q2[i].clock.next = self.clock.val();
            self.mt_q2[i].clock.next = self.clock.val();
            self.dist_cmp[i].clock.next = self.clock.val();
        }
        for k in 0..6 {
            self.me_q2[k].clock.next = self.clock.val();
            self.mx_q2[k].clock.next = self.clock.val();
            self.edge_cmp[k].clock.next = self.clock.val();
        }
        for j in 0..9 {
            self.le_qc[j].clock.next = self.clock.val();
        }
        self.ok_qp.clock.next = self.clock.val();
        self.valid_qp.clock.next = self.clock.val();
        self.tag_qp.clock.next = self.clock.val();
        self.ok_qc.clock.next = self.clock.val();
        self.valid_qc.clock.next = self.clock.val();
        self.tag_qc.clock.next = self.clock.val();
        dff_setup!(
            self, clock, t_q1, empty_q1, valid_q1, tag_q1, sure_q1, t_q2, ok_q2, valid_q2, tag_q2,
            pass_q3, valid_q3, tag_q3
        );

        // Stage 1: both folds of every axis, the fold picked by the sign class of the direction. The
        // effective mode: AllHit bounds only for the AllHit tester and `any_mode` low.
        self.sure_eff.next = self.sure.val() & !self.any_mode.val();
        self.empty.next = false;
        for i in 0..3 {
            self.diff[i].lo.next = self.box_lo[i].val();
            self.diff[i].hi.next = self.box_hi[i].val();
            // e largest and x smallest for AllHit, the reverse for AnyHit. (The mode is spelled out
            // from the port here, not read from `sure_eff`: a child input computed from a local of this
            // block makes Verilator see a combinational loop through the child, UNOPTFLAT.)
            if self.sure.val() & !self.any_mode.val() {
                self.diff[i].o_e.next = self.o_lo[i].val();
                self.diff[i].o_x.next = self.o_hi[i].val();
            } else {
                self.diff[i].o_e.next = self.o_hi[i].val();
                self.diff[i].o_x.next = self.o_lo[i].val();
            }
            if self.diff[i].empty.val() {
                self.empty.next = true;
            }
            self.nd_lo[i].next = self.zero_d.val() - self.d_lo[i].val();
            self.nd_hi[i].next = self.zero_d.val() - self.d_hi[i].val();
            // Straddling: e at its bound over both folds (largest for AllHit), x likewise, |d| to the
            // larger end.
            self.e_le[i].next = (self.diff[i].e_pos.val() ^ self.sign_v.val())
                <= (self.diff[i].e_neg.val() ^ self.sign_v.val());
            self.x_le[i].next = (self.diff[i].x_pos.val() ^ self.sign_v.val())
                <= (self.diff[i].x_neg.val() ^ self.sign_v.val());
            if self.e_le[i].val() == self.sure_eff.val() {
                self.e_pick[i].next = self.diff[i].e_neg.val();
            } else {
                self.e_pick[i].next = self.diff[i].e_pos.val();
            }
            if self.x_le[i].val() != self.sure_eff.val() {
                self.x_pick[i].next = self.diff[i].x_neg.val();
            } else {
                self.x_pick[i].next = self.diff[i].x_pos.val();
            }
            if self.nd_lo[i].val() <= self.d_hi[i].val() {
                self.u_max[i].next = self.d_hi[i].val();
            } else {
                self.u_max[i].next = self.nd_lo[i].val();
            }
            if self.d_lo[i].val() < self.sign_d.val() {
                // positive: d_lo >= 0
                self.e_q1[i].d.next = self.diff[i].e_pos.val();
                self.x_q1[i].d.next = self.diff[i].x_pos.val();
                self.ulo_q1[i].d.next = self.d_lo[i].val();
                self.uhi_q1[i].d.next = self.d_hi[i].val();
            } else if (self.d_hi[i].val() ^ self.sign_d.val()) <= self.sign_d.val() {
                // negative: d_hi <= 0
                self.e_q1[i].d.next = self.diff[i].e_neg.val();
                self.x_q1[i].d.next = self.diff[i].x_neg.val();
                self.ulo_q1[i].d.next = self.nd_hi[i].val();
                self.uhi_q1[i].d.next = self.nd_lo[i].val();
            } else if !self.sure_eff.val() & (self.diff[i].x_pos.val() >= self.sign_v.val()) {
                // AnyHit, straddling, no ray moving up reaches the far plane: keep the lower half.
                self.e_q1[i].d.next = self.diff[i].e_neg.val();
                self.x_q1[i].d.next = self.diff[i].x_neg.val();
                self.ulo_q1[i].d.next = self.zero_d.val();
                self.uhi_q1[i].d.next = self.nd_lo[i].val();
            } else if !self.sure_eff.val() & (self.diff[i].x_neg.val() >= self.sign_v.val()) {
                // AnyHit, straddling, the mirror case: keep the upper half.
                self.e_q1[i].d.next = self.diff[i].e_pos.val();
                self.x_q1[i].d.next = self.diff[i].x_pos.val();
                self.ulo_q1[i].d.next = self.zero_d.val();
                self.uhi_q1[i].d.next = self.d_hi[i].val();
            } else {
                self.e_q1[i].d.next = self.e_pick[i].val();
                self.x_q1[i].d.next = self.x_pick[i].val();
                self.ulo_q1[i].d.next = self.zero_d.val();
                self.uhi_q1[i].d.next = self.u_max[i].val();
            }
        }
        self.t_q1.d.next = self.t_max.val();
        self.empty_q1.d.next = self.empty.val();
        self.valid_q1.d.next = self.valid_in.val() & !self.rst.val();
        self.tag_q1.d.next = self.tag_in.val();
        self.sure_q1.d.next = self.sure_eff.val();

        // Stage 2: the bound of each product. An upper bound of v * u takes u_hi for v >= 0 and u_lo for
        // v < 0, a lower bound the reverse; e-products are upper bounds for AllHit, x- and t-products
        // lower bounds.
        self.ok.next = !self.empty_q1.q.val();
        self.t_neg.next = self.t_q1.q.val() >= self.sign_t.val();
        for i in 0..3 {
            self.e_lo_sel[i].next =
                (self.e_q1[i].q.val() >= self.sign_v.val()) == self.sure_q1.q.val();
            self.x_lo_sel[i].next =
                (self.x_q1[i].q.val() >= self.sign_v.val()) != self.sure_q1.q.val();
            if self.x_q1[i].q.val() >= self.sign_v.val() {
                self.ok.next = false; // D: the far plane is behind
            }
            if self.t_neg.val() != self.sure_q1.q.val() {
                self.mt_q2[i].d.next = self.ulo_q1[i].q.val();
            } else {
                self.mt_q2[i].d.next = self.uhi_q1[i].q.val();
            }
            self.e_q2[i].d.next = self.e_q1[i].q.val();
            self.x_q2[i].d.next = self.x_q1[i].q.val();
        }
        // Edge k = (a, c): me = u of axis c chosen by e_a, mx = u of axis a chosen by x_c.
        if self.e_lo_sel[0].val() {
            self.me_q2[0].d.next = self.ulo_q1[1].q.val();
            self.me_q2[1].d.next = self.ulo_q1[2].q.val();
        } else {
            self.me_q2[0].d.next = self.uhi_q1[1].q.val();
            self.me_q2[1].d.next = self.uhi_q1[2].q.val();
        }
        if self.e_lo_sel[1].val() {
            self.me_q2[2].d.next = self.ulo_q1[0].q.val();
            self.me_q2[3].d.next = self.ulo_q1[2].q.val();
        } else {
            self.me_q2[2].d.next = self.uhi_q1[0].q.val();
            self.me_q2[3].d.next = self.uhi_q1[2].q.val();
        }
        if self.e_lo_sel[2].val() {
            self.me_q2[4].d.next = self.ulo_q1[0].q.val();
            self.me_q2[5].d.next = self.ulo_q1[1].q.val();
        } else {
            self.me_q2[4].d.next = self.uhi_q1[0].q.val();
            self.me_q2[5].d.next = self.uhi_q1[1].q.val();
        }
        // x_c for c = 0 serves edges (1,0) and (2,0); c = 1 edges (0,1), (2,1); c = 2 edges (0,2), (1,2).
        if self.x_lo_sel[0].val() {
            self.mx_q2[2].d.next = self.ulo_q1[1].q.val();
            self.mx_q2[4].d.next = self.ulo_q1[2].q.val();
        } else {
            self.mx_q2[2].d.next = self.uhi_q1[1].q.val();
            self.mx_q2[4].d.next = self.uhi_q1[2].q.val();
        }
        if self.x_lo_sel[1].val() {
            self.mx_q2[0].d.next = self.ulo_q1[0].q.val();
            self.mx_q2[5].d.next = self.ulo_q1[2].q.val();
        } else {
            self.mx_q2[0].d.next = self.uhi_q1[0].q.val();
            self.mx_q2[5].d.next = self.uhi_q1[2].q.val();
        }
        if self.x_lo_sel[2].val() {
            self.mx_q2[1].d.next = self.ulo_q1[0].q.val();
            self.mx_q2[3].d.next = self.ulo_q1[1].q.val();
        } else {
            self.mx_q2[1].d.next = self.uhi_q1[0].q.val();
            self.mx_q2[3].d.next = self.uhi_q1[1].q.val();
        }
        self.t_q2.d.next = self.t_q1.q.val();
        self.ok_q2.d.next = self.ok.val();
        self.valid_q2.d.next = self.valid_q1.q.val() & !self.rst.val();
        self.tag_q2.d.next = self.tag_q1.q.val();

        // Stage 3: products (cut PRODUCT inside each compare), compares (cut COMPARE), and the AND of all
        // conditions.
        self.edge_cmp[0].a.next = self.e_q2[0].q.val();
        self.edge_cmp[0].b.next = self.x_q2[1].q.val();
        self.edge_cmp[1].a.next = self.e_q2[0].q.val();
        self.edge_cmp[1].b.next = self.x_q2[2].q.val();
        self.edge_cmp[2].a.next = self.e_q2[1].q.val();
        self.edge_cmp[2].b.next = self.x_q2[0].q.val();
        self.edge_cmp[3].a.next = self.e_q2[1].q.val();
        self.edge_cmp[3].b.next = self.x_q2[2].q.val();
        self.edge_cmp[4].a.next = self.e_q2[2].q.val();
        self.edge_cmp[4].b.next = self.x_q2[0].q.val();
        self.edge_cmp[5].a.next = self.e_q2[2].q.val();
        self.edge_cmp[5].b.next = self.x_q2[1].q.val();
        for k in 0..6 {
            self.edge_cmp[k].m.next = self.me_q2[k].q.val();
            self.edge_cmp[k].n.next = self.mx_q2[k].q.val();
            self.le_qc[k].d.next = self.edge_cmp[k].le.val();
        }
        for i in 0..3 {
            self.dist_cmp[i].e.next = self.e_q2[i].q.val();
            self.dist_cmp[i].t.next = self.t_q2.q.val();
            self.dist_cmp[i].u.next = self.mt_q2[i].q.val();
            self.le_qc[6 + i].d.next = self.dist_cmp[i].le.val();
        }
        // Side data through the cuts; a valid bit is cleared by rst where a cut is a register.
        self.ok_qp.d.next = self.ok_q2.q.val();
        self.tag_qp.d.next = self.tag_q2.q.val();
        if self.reg_p.val() {
            self.valid_qp.d.next = self.valid_q2.q.val() & !self.rst.val();
        } else {
            self.valid_qp.d.next = self.valid_q2.q.val();
        }
        self.ok_qc.d.next = self.ok_qp.q.val();
        self.tag_qc.d.next = self.tag_qp.q.val();
        if self.reg_c.val() {
            self.valid_qc.d.next = self.valid_qp.q.val() & !self.rst.val();
        } else {
            self.valid_qc.d.next = self.valid_qp.q.val();
        }
        self.all.next = self.ok_qc.q.val();
        for j in 0..9 {
            if !self.le_qc[j].q.val() {
                self.all.next = false;
            }
        }
        self.pass_q3.d.next = self.all.val();
        self.valid_q3.d.next = self.valid_qc.q.val() & !self.rst.val();
        self.tag_q3.d.next = self.tag_qc.q.val();

        self.valid_out.next = self.valid_q3.q.val();
        self.tag_out.next = self.tag_q3.q.val();
        self.pass.next = self.pass_q3.q.val();
    }
}
