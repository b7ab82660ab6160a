//! `BundleFix`: the pair of fixed-point bundle testers, AllHit and AnyHit side by side ([`BundleTest`]
//! twice), fully pipelined (one test per clock), [`bundle_fix_latency`]`(CUTS)` clocks of latency: 3 for the
//! default, 5 for the deep configuration (`CUTS` = [`BUNDLE_TEST_CUTS_DEEP`], the products and the
//! compares registered; module names end in `_p5`). [`BUNDLE_FIX_DEPTHS`] lists the built ones. Per clock the
//! pair takes either one bundle, which both testers judge, or two single rays, one per tester (the pair of
//! testing blocks of US 11,308,683 and the "one bundle or two rays" claims of US 11,682,160).
//!
//! Bit for bit `golden::bundle::fix::{all_hit_fix, all_miss_fix}` ([`PairInput::model`] says which
//! inputs). With a bundle, `all_hit` is AllHit on the inner box with `t_lo` and `all_miss` the negation of
//! AnyHit's pass on the outer box with `t_hi` (the conditions, their bounds and proofs are in
//! `golden/src/bundle/edge.rs`). The ports mirror `golden::bundle::fix::FixBundle` and
//! `golden::bundle::edge::BoxPair<FixBox>`; for a node box stored on the grid the two boxes are equal.
//!
//! # Two-ray mode
//! A world ray quantised by `golden::bundle::fix::quantize_bundle` (of `Bundle::of_ray`) is a tiny bundle
//! (origin floored and ceiled, direction code floored and ceiled, `t_max` floored and ceiled) unless every
//! input is on the grid. AllHit bounds on such a bundle may say "misses" for a ray that hits (a false
//! miss, which would drop a hit). So in two-ray mode both testers run AnyHit bounds on the outer box with
//! their ray's `t_hi` (the AllHit tester through its `any_mode` input): ray A is the bundle ports (all of
//! them, as quantised), ray B the `r_*` ports. Each answer is sound by Theorem 2b for every ray of the
//! tiny bundle, so for the world ray inside it: "misses" is never said of a ray that hits. For a ray on
//! the grid (a point bundle) AnyHit is the exact single-ray test (Theorem 1).
//!
//! # Parameters
//! `G`, `V = G + 1`, `D = FD + 3`, `T`, as [`BundleTest`]; the presets are [`crate::BundleFixB8`],
//! [`crate::BundleFixB12`], [`crate::BundleFixB16`] (`FD = G - 2`, so `D = V`).
//!
//! # Inputs
//! - `clock`; `rst` (synchronous reset: high at a clock edge, every valid bit is cleared and no test in flight leaves; data registers are not reset); `valid_in`, `tag_in` (16 bits, opaque, returned with the result);
//! - `o_lo`, `o_hi`, `d_lo`, `d_hi` (arrays over x, y, z), `t_lo`, `t_hi`: the bundle (in two-ray mode
//!   ray A, whose `t_lo` is not used);
//! - `two_rays`: two-ray mode;
//! - `r_o_lo`, `r_o_hi`, `r_d_lo`, `r_d_hi` (arrays), `r_t`: ray B (its `t_hi`), used in two-ray mode only;
//! - `in_lo`, `in_hi`: the inner box (AllHit, bundle mode only); `out_lo`, `out_hi`: the outer box.
//!
//! # Outputs (registered, [`bundle_fix_latency`]`(CUTS)` clocks after the inputs)
//! - `valid_out`, `tag_out`;
//! - `all_hit`: every ray of the bundle hits; in two-ray mode: ray A *may hit* (AnyHit passes);
//! - `all_miss`: every ray of the bundle misses; in two-ray mode: ray B misses.
//!
//! For a bundle both low means "some may hit": descend.
//!
//! Both testers carry their own valid and tag; the outputs take the AllHit side's and the AnyHit side's
//! AND (they are equal), so that no child output is left unused.

use crate::bundle::edge_fix::{
    bundle_test_latency, BundleTest, BUNDLE_TEST_CUTS, BUNDLE_TEST_CUTS_DEEP,
};
use crate::bundle::ports::PairFixPorts;
use crate::io::TesterIo;
use crate::slab::fix::TAG_BITS;
use golden::bundle::edge::BoxPair;
use golden::bundle::fix::{all_hit_fix, all_miss_fix, BundleFixFormat, FixBundle};
use golden::format::fixed::FixBox;
use rust_hdl::prelude::*;

/// Clocks from a test entering a `BundleFix` with cut points `cuts` (those of
/// [`crate::bundle::edge_fix::cut`]) to its result leaving.
pub const fn bundle_fix_latency(cuts: usize) -> usize {
    bundle_test_latency(cuts)
}

/// Clocks from a test entering the default `BundleFix` to its result leaving.
pub const BUNDLE_FIX_LATENCY: usize = bundle_fix_latency(BUNDLE_TEST_CUTS);

/// The configurations that are built (exported, tested, timed): `(cuts, name suffix)`; the module name
/// of a configuration is the format's with this suffix (none for the default).
pub const BUNDLE_FIX_DEPTHS: [(usize, &str); 2] =
    [(BUNDLE_TEST_CUTS, ""), (BUNDLE_TEST_CUTS_DEEP, "_p5")];

/// The AllHit + AnyHit pair; see the module documentation.
#[derive(LogicBlock)]
pub struct BundleFix<
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
    pub t_lo: Signal<In, Bits<T>>,
    pub t_hi: Signal<In, Bits<T>>,
    pub two_rays: Signal<In, Bit>,
    pub r_o_lo: [Signal<In, Bits<G>>; 3],
    pub r_o_hi: [Signal<In, Bits<G>>; 3],
    pub r_d_lo: [Signal<In, Bits<D>>; 3],
    pub r_d_hi: [Signal<In, Bits<D>>; 3],
    pub r_t: Signal<In, Bits<T>>,
    pub in_lo: [Signal<In, Bits<G>>; 3],
    pub in_hi: [Signal<In, Bits<G>>; 3],
    pub out_lo: [Signal<In, Bits<G>>; 3],
    pub out_hi: [Signal<In, Bits<G>>; 3],
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub all_hit: Signal<Out, Bit>,
    pub all_miss: Signal<Out, Bit>,
    all_hit_test: BundleTest<G, V, D, T, CUTS>,
    any_hit_test: BundleTest<G, V, D, T, CUTS>,
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize>
    BundleFix<G, V, D, T, CUTS>
{
    /// The pair for `bf`, whose widths must equal the parameters.
    pub fn new(bf: &BundleFixFormat) -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            o_lo: Default::default(),
            o_hi: Default::default(),
            d_lo: Default::default(),
            d_hi: Default::default(),
            t_lo: Default::default(),
            t_hi: Default::default(),
            two_rays: Default::default(),
            r_o_lo: Default::default(),
            r_o_hi: Default::default(),
            r_d_lo: Default::default(),
            r_d_hi: Default::default(),
            r_t: Default::default(),
            in_lo: Default::default(),
            in_hi: Default::default(),
            out_lo: Default::default(),
            out_hi: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            all_hit: Default::default(),
            all_miss: Default::default(),
            all_hit_test: BundleTest::all_hit(bf),
            any_hit_test: BundleTest::any_hit(bf),
        }
    }
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize> Logic
    for BundleFix<G, V, D, T, CUTS>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.all_hit_test.clock.next = self.clock.val();
        self.any_hit_test.clock.next = self.clock.val();
        self.all_hit_test.valid_in.next = self.valid_in.val();
        self.all_hit_test.rst.next = self.rst.val();
        self.any_hit_test.valid_in.next = self.valid_in.val();
        self.any_hit_test.rst.next = self.rst.val();
        self.all_hit_test.tag_in.next = self.tag_in.val();
        self.any_hit_test.tag_in.next = self.tag_in.val();
        // Two-ray mode: AnyHit bounds on the outer box with t_hi on both sides.
        self.all_hit_test.any_mode.next = self.two_rays.val();
        self.any_hit_test.any_mode.next = false;
        for i in 0..3 {
            self.all_hit_test.o_lo[i].next = self.o_lo[i].val();
            self.all_hit_test.o_hi[i].next = self.o_hi[i].val();
            self.all_hit_test.d_lo[i].next = self.d_lo[i].val();
            self.all_hit_test.d_hi[i].next = self.d_hi[i].val();
            if self.two_rays.val() {
                self.all_hit_test.box_lo[i].next = self.out_lo[i].val();
                self.all_hit_test.box_hi[i].next = self.out_hi[i].val();
                self.any_hit_test.o_lo[i].next = self.r_o_lo[i].val();
                self.any_hit_test.o_hi[i].next = self.r_o_hi[i].val();
                self.any_hit_test.d_lo[i].next = self.r_d_lo[i].val();
                self.any_hit_test.d_hi[i].next = self.r_d_hi[i].val();
            } else {
                self.all_hit_test.box_lo[i].next = self.in_lo[i].val();
                self.all_hit_test.box_hi[i].next = self.in_hi[i].val();
                self.any_hit_test.o_lo[i].next = self.o_lo[i].val();
                self.any_hit_test.o_hi[i].next = self.o_hi[i].val();
                self.any_hit_test.d_lo[i].next = self.d_lo[i].val();
                self.any_hit_test.d_hi[i].next = self.d_hi[i].val();
            }
            self.any_hit_test.box_lo[i].next = self.out_lo[i].val();
            self.any_hit_test.box_hi[i].next = self.out_hi[i].val();
        }
        if self.two_rays.val() {
            self.all_hit_test.t_max.next = self.t_hi.val();
            self.any_hit_test.t_max.next = self.r_t.val();
        } else {
            self.all_hit_test.t_max.next = self.t_lo.val();
            self.any_hit_test.t_max.next = self.t_hi.val();
        }
        self.valid_out.next = self.all_hit_test.valid_out.val() & self.any_hit_test.valid_out.val();
        self.tag_out.next = self.all_hit_test.tag_out.val() & self.any_hit_test.tag_out.val();
        self.all_hit.next = self.all_hit_test.pass.val();
        self.all_miss.next = !self.any_hit_test.pass.val();
    }
}

/// What the pair takes in one clock.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairInput {
    /// One bundle, judged by both testers.
    Bundle(FixBundle),
    /// Two single rays, each quantised as a tiny bundle (`quantize_bundle` of `Bundle::of_ray`; a point
    /// bundle for a ray on the grid): A on the AllHit tester, B on the AnyHit tester, both with AnyHit
    /// bounds on the outer box and their `t_hi` (their `t_lo` is not used).
    TwoRays(FixBundle, FixBundle),
}

impl PairInput {
    /// The bundles the AllHit and the AnyHit tester judge.
    pub fn sides(&self) -> (&FixBundle, &FixBundle) {
        match self {
            PairInput::Bundle(b) => (b, b),
            PairInput::TwoRays(a, b) => (a, b),
        }
    }

    /// True for two rays.
    pub fn is_two_rays(&self) -> bool {
        matches!(self, PairInput::TwoRays(..))
    }

    /// The bit-accurate model, `(all_hit, all_miss)`: for a bundle `(all_hit_fix` on the inner box,
    /// `all_miss_fix` on the outer box`)`; for two rays `(!all_miss_fix(A)`, `all_miss_fix(B))`, both on
    /// the outer box ("A may hit", "B misses").
    pub fn model(&self, bf: &BundleFixFormat, boxes: &BoxPair<FixBox>) -> (bool, bool) {
        match self {
            PairInput::Bundle(b) => (
                all_hit_fix(bf, b, &boxes.inner),
                all_miss_fix(bf, b, &boxes.outer),
            ),
            PairInput::TwoRays(a, b) => (
                !all_miss_fix(bf, a, &boxes.outer),
                all_miss_fix(bf, b, &boxes.outer),
            ),
        }
    }
}

/// A bundle pair of any width, built for a format, so drivers need not spell the widths.
pub trait BundleFixIo:
    TesterIo<Ray = PairInput, Box = BoxPair<FixBox>, Out = (bool, bool)>
{
    /// The block's cut points (those of [`crate::bundle::edge_fix::cut`]).
    const CUTS: usize;
    /// The pair for `bf` (whose widths must match the block's).
    fn for_format(bf: &BundleFixFormat) -> Self;
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize> BundleFixIo
    for BundleFix<G, V, D, T, CUTS>
{
    const CUTS: usize = CUTS;
    fn for_format(bf: &BundleFixFormat) -> Self {
        Self::new(bf)
    }
}

impl<const G: usize, const V: usize, const D: usize, const T: usize, const CUTS: usize> TesterIo
    for BundleFix<G, V, D, T, CUTS>
{
    type Ray = PairInput;
    type Box = BoxPair<FixBox>;
    /// `(all_hit, all_miss)`, as `golden::bundle::fix::decide_fix`.
    type Out = (bool, bool);
    const LATENCY: usize = bundle_fix_latency(CUTS);
    type Ports = PairFixPorts;

    fn ports() -> PairFixPorts {
        PairFixPorts
    }

    crate::tester_ports!(
        inputs: o_lo, o_hi, d_lo, d_hi, t_lo, t_hi, two_rays, r_o_lo, r_o_hi, r_d_lo, r_d_hi, r_t,
            in_lo, in_hi, out_lo, out_hi;
        outputs: all_hit, all_miss
    );
}
