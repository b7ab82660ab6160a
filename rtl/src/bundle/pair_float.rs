//! `BundleFloat`: the pair of float bundle testers of format `E`/`M`, AllHit and AnyHit side by side
//! ([`BundleFloatTest`] twice), fully pipelined (one test per clock), [`bundle_float_latency`]`(CUTS)`
//! clocks of latency: 9 by default, 13 for the deep configuration (`CUTS` = [`crate::fp::cuts::ALL`],
//! every optional cut of the adders and multipliers; module names end in `_p13`). [`BUNDLE_FLOAT_DEPTHS`]
//! lists the built ones. Per clock the pair takes either one bundle, which both testers judge, or two single rays, one
//! per tester (the pair of testing blocks of US 11,308,683 and the "one bundle or two rays" claims of
//! US 11,682,160); the float counterpart of [`crate::bundle::pair_fix::BundleFix`].
//!
//! Bit for bit `golden::bundle::float::{all_hit_float, all_miss_float}` ([`FloatPairInput::model`] says
//! which inputs; the conditions, their bounds and proofs are in `golden/src/bundle/edge.rs` and
//! `golden/src/bundle/float.rs`). The ports mirror `golden::bundle::float::FloatBundle` and
//! `golden::bundle::edge::BoxPair<FloatBox>`; for a node box stored in the format the two boxes are equal.
//!
//! # Two rays
//! A ray quantised into a float format is not a point: its origin is `[RD(o), RU(o)]`, its direction
//! `[RD, RU]` of the scaled direction, its `t_max` `[RD, RU]` (`golden::bundle::float::quantize_bundle` of
//! `Bundle::of_ray`), a tiny bundle. AllHit's bounds on it answer "every ray of this tiny bundle hits",
//! which may be false for a ray that hits (a grazing one); what a traversal needs of a single ray is the
//! sound "may hit", which is AnyHit's pass. So in two-ray mode both testers run AnyHit's bounds on the
//! outer box with their ray's `t_hi` (the AllHit tester through its `any_mode` input), and
//! `all_hit` = "ray A may hit" (AnyHit passes for A), `all_miss` = "ray B misses" (AnyHit fails for B):
//! both low means "descend for B but not A" and so on; neither answer is ever wrong for a ray that hits.
//!
//! # Parameters
//! `E >= 4`, `M`, `N = 1 + E + M <= 32`; `CUTS`, the optional cut points ([`crate::fp::cuts`], default
//! none). The presets are [`crate::BundleFloatFp32`], [`crate::BundleFloatBf16`],
//! [`crate::BundleFloatFp16`] and at 13 clocks [`crate::BundleFloatFp32P13`], [`crate::BundleFloatBf16P13`],
//! [`crate::BundleFloatFp16P13`].
//!
//! # Inputs
//! - `clock`; `rst` (synchronous reset: high at a clock edge, every valid bit is cleared and no test in flight leaves; data registers are not reset); `valid_in`, `tag_in` (16 bits, opaque, returned with the result);
//! - `o_lo`, `o_hi`, `d_lo`, `d_hi` (arrays over x, y, z), `t_lo`, `t_hi`: the bundle (ray A in two-ray
//!   mode, where `t_lo` is unused);
//! - `two_rays`: two single rays instead of a bundle; ray B is `r_o_lo`, `r_o_hi`, `r_d_lo`, `r_d_hi`
//!   (arrays) and `r_t` (its `t_hi`);
//! - `in_lo`, `in_hi`: the inner box (AllHit in bundle mode; unused in two-ray mode); `out_lo`, `out_hi`:
//!   the outer box (AnyHit, and both testers in two-ray mode).
//!
//! # Outputs (registered, [`bundle_float_latency`]`(CUTS)` clocks after the inputs)
//! - `valid_out`, `tag_out`;
//! - `all_hit`: every ray of the bundle hits (bundle mode); ray A may hit (two-ray mode);
//! - `all_miss`: every ray of the bundle misses (bundle mode); ray B misses (two-ray mode).
//!   For a bundle both low means "some may hit": descend.
//!
//! Both testers carry their own valid and tag; the outputs take the AND of the two sides' (they are
//! equal), so that no child output is left unused.

use crate::bundle::edge_float::{bundle_float_test_latency, BundleFloatTest};
use crate::bundle::ports::PairFloatPorts;
use crate::io::TesterIo;
use crate::TAG_BITS;
use golden::bundle::edge::BoxPair;
use golden::bundle::float::{all_hit_float, all_miss_float, FloatBundle};
use golden::format::float::FloatFormat;
use golden::slab::float::FloatBox;
use rust_hdl::prelude::*;

/// Clocks from a test entering a `BundleFloat` with cut points `cuts` ([`crate::fp::cuts`]) to its result
/// leaving.
pub const fn bundle_float_latency(cuts: usize) -> usize {
    bundle_float_test_latency(cuts)
}

/// Clocks from a test entering the default `BundleFloat` to its result leaving.
pub const BUNDLE_FLOAT_LATENCY: usize = bundle_float_latency(0);

/// The configurations that are built (exported, tested, timed): `(cuts, name suffix)`; the module name
/// is `bundle_float_<format><suffix>` (`crate::names::bundle_float_module_cuts`).
pub const BUNDLE_FLOAT_DEPTHS: [(usize, &str); 2] = [(0, ""), (crate::fp::cuts::ALL, "_p13")];

const _: () = assert!(bundle_float_latency(crate::fp::cuts::ALL) == 13);

/// The AllHit + AnyHit pair; see the module documentation.
#[derive(LogicBlock)]
pub struct BundleFloat<const E: usize, const M: usize, const N: usize, const CUTS: usize = 0> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub o_lo: [Signal<In, Bits<N>>; 3],
    pub o_hi: [Signal<In, Bits<N>>; 3],
    pub d_lo: [Signal<In, Bits<N>>; 3],
    pub d_hi: [Signal<In, Bits<N>>; 3],
    pub t_lo: Signal<In, Bits<N>>,
    pub t_hi: Signal<In, Bits<N>>,
    pub two_rays: Signal<In, Bit>,
    pub r_o_lo: [Signal<In, Bits<N>>; 3],
    pub r_o_hi: [Signal<In, Bits<N>>; 3],
    pub r_d_lo: [Signal<In, Bits<N>>; 3],
    pub r_d_hi: [Signal<In, Bits<N>>; 3],
    pub r_t: Signal<In, Bits<N>>,
    pub in_lo: [Signal<In, Bits<N>>; 3],
    pub in_hi: [Signal<In, Bits<N>>; 3],
    pub out_lo: [Signal<In, Bits<N>>; 3],
    pub out_hi: [Signal<In, Bits<N>>; 3],
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub all_hit: Signal<Out, Bit>,
    pub all_miss: Signal<Out, Bit>,
    all_hit_test: BundleFloatTest<E, M, N, CUTS>,
    any_hit_test: BundleFloatTest<E, M, N, CUTS>,
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> BundleFloat<E, M, N, CUTS> {
    /// The pair (the format is the parameters').
    pub fn new() -> Self {
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
            all_hit_test: BundleFloatTest::all_hit(),
            any_hit_test: BundleFloatTest::any_hit(),
        }
    }
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> Default
    for BundleFloat<E, M, N, CUTS>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> Logic
    for BundleFloat<E, M, N, CUTS>
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
        // Two rays: both testers take AnyHit's bounds (the AnyHit tester always does).
        self.all_hit_test.any_mode.next = self.two_rays.val();
        self.any_hit_test.any_mode.next = self.two_rays.val();
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
        // all_hit is AllHit's pass in bundle mode and AnyHit's pass ("may hit") for ray A.
        self.all_hit.next = self.all_hit_test.pass.val();
        self.all_miss.next = !self.any_hit_test.pass.val();
    }
}

/// What the pair takes in one clock.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FloatPairInput {
    /// One bundle, judged by both testers.
    Bundle(FloatBundle),
    /// Two single rays, each quantised as a tiny bundle: A to the AllHit tester, B to the AnyHit tester,
    /// both judged with AnyHit's bounds on the outer box and `t_hi`.
    TwoRays(FloatBundle, FloatBundle),
}

impl FloatPairInput {
    /// The bundles the AllHit and the AnyHit tester judge.
    pub fn sides(&self) -> (&FloatBundle, &FloatBundle) {
        match self {
            FloatPairInput::Bundle(b) => (b, b),
            FloatPairInput::TwoRays(a, b) => (a, b),
        }
    }

    /// True for two rays.
    pub fn is_two_rays(&self) -> bool {
        matches!(self, FloatPairInput::TwoRays(..))
    }

    /// The bit-accurate model, `(all_hit, all_miss)`: for a bundle `(all_hit_float` on the inner box,
    /// `all_miss_float` on the outer box`)`; for two rays `(!all_miss_float(A)`, `all_miss_float(B))`, both
    /// on the outer box.
    pub fn model(&self, f: &FloatFormat, boxes: &BoxPair<FloatBox>) -> (bool, bool) {
        match self {
            FloatPairInput::Bundle(b) => (
                all_hit_float(f, b, &boxes.inner),
                all_miss_float(f, b, &boxes.outer),
            ),
            FloatPairInput::TwoRays(a, b) => (
                !all_miss_float(f, a, &boxes.outer),
                all_miss_float(f, b, &boxes.outer),
            ),
        }
    }
}

/// A float bundle pair of any format, so drivers need not spell the widths.
pub trait BundleFloatIo:
    TesterIo<Ray = FloatPairInput, Box = BoxPair<FloatBox>, Out = (bool, bool)>
{
    /// The block's cut points ([`crate::fp::cuts`]).
    const CUTS: usize;
    /// The format of the block.
    fn format() -> FloatFormat;
    /// The pair for `f`, which must be the block's format.
    fn for_format(f: &FloatFormat) -> Self;
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> BundleFloatIo
    for BundleFloat<E, M, N, CUTS>
{
    const CUTS: usize = CUTS;
    fn format() -> FloatFormat {
        FloatFormat::new(E as u32, M as u32).expect("valid format")
    }

    fn for_format(f: &FloatFormat) -> Self {
        assert_eq!(
            *f,
            <Self as BundleFloatIo>::format(),
            "BundleFloat<{E},{M},{N},{CUTS}> is not for format {}",
            f.name()
        );
        Self::new()
    }
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> TesterIo
    for BundleFloat<E, M, N, CUTS>
{
    type Ray = FloatPairInput;
    type Box = BoxPair<FloatBox>;
    /// `(all_hit, all_miss)`, as [`FloatPairInput::model`].
    type Out = (bool, bool);
    const LATENCY: usize = bundle_float_latency(CUTS);
    type Ports = PairFloatPorts;

    fn ports() -> PairFloatPorts {
        PairFloatPorts
    }

    crate::tester_ports!(
        inputs: o_lo, o_hi, d_lo, d_hi, t_lo, t_hi, two_rays, r_o_lo, r_o_hi, r_d_lo, r_d_hi, r_t,
            in_lo, in_hi, out_lo, out_hi;
        outputs: all_hit, all_miss
    );
}
