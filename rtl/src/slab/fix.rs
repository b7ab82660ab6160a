//! `SlabFix`: the fixed-point AABB slab tester, fully pipelined (one test per clock), of 4 clocks
//! ([`SLAB_FIX_CUTS`]) to 6 clocks ([`SLAB_FIX_CUTS_DEEP`]) of latency as its `CUTS` parameter chooses.
//!
//! Bit for bit the datapath of `golden::slab::fix::slab_fix` (read its documentation for the
//! arithmetic and the conservativeness argument); the ports mirror `golden::format::fixed::{FixRay, FixBox}` and
//! `golden::slab::fix::SlabFixOut`.
//!
//! # Parameters
//! | name | meaning |
//! | --- | --- |
//! | `G` | grid bits (signed box and origin coordinates) |
//! | `D` | distance bits, must be `G + 1` |
//! | `I` | inverse-direction magnitude bits (unsigned; all ones = unbounded) |
//! | `T` | t code bits (signed; most negative = `-inf`, most positive = `+inf`) |
//!
//! The fraction bits `FI`, `FT` only enter as the product shift `FI - FT`, a constructor argument. Stable
//! Rust cannot write `Bits<{G + 1}>`, hence `D` as a separate parameter, checked by [`SlabFix::new`].
//!
//! # Inputs
//! - `clock`; `rst` (synchronous reset: high at a clock edge, every valid bit is cleared and no test in flight leaves; data registers are not reset); `valid_in`, `tag_in` (16 bits, opaque, returned with the result);
//! - `ray_*`: the fields of [`FixRay`] — origin interval `ray_o_lo`, `ray_o_hi`, inverse interval
//!   `ray_m_lo`, `ray_m_hi`, signs `ray_neg` (arrays over x, y, z), `ray_t_min`, `ray_t_max`;
//! - `box_*`: the fields of [`FixBox`] — `box_lo`, `box_hi`.
//!
//! rust-hdl 0.46's `LogicInterface` cannot hold arrays, so the grouping is by name prefix in the ports and
//! by type in the Rust API: `TesterIo::drive` takes a [`FixRay`] and a [`FixBox`], `TesterIo::result`
//! gives a [`SlabFixOut`], both through the port codec [`crate::slab::ports::SlabFixPorts`].
//!
//! # Outputs (registered, [`slab_fix_latency`]`(CUTS)` clocks after the inputs: 4 by default)
//! - `valid_out`, `tag_out`, `hit`, `t_entry`, `t_exit`.
//!
//! # Pipeline
//! Six steps of logic, each followed by a cut point ([`cut`]); `CUTS` sets which are registers, one
//! clock each (the outputs always are), so the latency is the number of set bits:
//! 1. per axis ([`AxisDist`]) the distances `e`, `x` to the near and far planes in `D` bits, and the
//!    empty-box flag; cut [`cut::DIST`] (`_q1`);
//! 2. each product's inverse bound chosen by the sign of its distance; cut [`cut::OPERANDS`] (`_qo`);
//! 3. six multiplies ([`MulRound`]); cut [`cut::PRODUCT`] (inside each `MulRound`; side data `_qp`);
//! 4. the products scaled, rounded (`entry` floored, `exit` ceiled) and saturated to t codes; cut
//!    [`cut::BOUND`] (`_q2`);
//! 5. the first level of the max/min trees with `t_min`/`t_max`; cut [`cut::TREE`] (`_q3`);
//! 6. the final max/min and the hit decision; cut [`cut::OUT`] (`_q4`), which drives the outputs. With
//!    [`cut::PRODUCT`] set the decision compares the four tree halves side by side (one comparison
//!    deep, not a comparison behind the max and min), because this clock is then the tester's limit;
//!    without it the multiply-and-round clock is, and the chained form takes half the LUT4s there.
//!
//! The default (4 clocks) puts steps 2 to 4, a whole multiply-and-round, in one clock, the critical path
//! of the tester on an FPGA; the deep configuration (6 clocks) gives the multiplies a clock of their own,
//! registered operands in front and a registered product behind, as a DSP block's input and output
//! registers would be.
//!
//! Measured after place and route on ECP5 (`scripts/timing slab_fix_`, `docs/timing/timing.md`): the
//! deep configuration runs at 130-180 MHz, limited by the multiplies themselves (flip-flop, DSP,
//! flip-flop); `scripts/ceiling/` measures that path alone at about 190 MHz for one `MULT18X18D` and
//! 143 MHz for the two of the 16-bit grid's product.
//!
//! Signed comparisons are unsigned comparisons of the sign-flipped codes: rust-hdl's `Signed` compares
//! through big integers in simulation and emits unsized `$signed` casts in Verilog.

use crate::cut::Cut;
use crate::io::TesterIo;
use crate::slab::axis_dist::AxisDist;
use crate::slab::mul_round::MulRound;
use crate::slab::ports::SlabFixPorts;
use golden::format::fixed::{FixBox, FixFormat, FixRay};
use golden::slab::fix::SlabFixOut;
use rust_hdl::prelude::*;

/// The cut points of the fixed slab tester: one bit each of its `CUTS` parameter, a register where the
/// bit is set and a wire where it is clear ([`crate::cut::Cut`]). In pipeline order, with the names of
/// their registers:
pub mod cut {
    /// After the distances (`_q1`).
    pub const DIST: usize = 1 << 0;
    /// After the choice of each product's inverse bound: the multipliers' operands (`_qo`).
    pub const OPERANDS: usize = 1 << 1;
    /// After the multiplies: the products, inside each `MulRound` (`p_q`; the side data `_qp`).
    pub const PRODUCT: usize = 1 << 2;
    /// After the rounding and saturation to t codes (`_q2`).
    pub const BOUND: usize = 1 << 3;
    /// After the first level of the max/min trees (`_q3`).
    pub const TREE: usize = 1 << 4;
    /// The outputs (`_q4`): always a register, so that every output is registered.
    pub const OUT: usize = 1 << 5;
    /// Every cut point.
    pub const ALL: usize = (1 << 6) - 1;
}

/// The cut points of the 4-clock tester (the default of [`SlabFix`]'s `CUTS`): distances, bounds, tree,
/// outputs. A whole multiply, round and saturate is one clock.
pub const SLAB_FIX_CUTS: usize = cut::DIST | cut::BOUND | cut::TREE | cut::OUT;

/// The cut points of the 6-clock tester: every cut, the multipliers' operands and products registered.
pub const SLAB_FIX_CUTS_DEEP: usize = cut::ALL;

/// Clocks from a test entering a `SlabFix` with cut points `cuts` to its result leaving: one per cut.
pub const fn slab_fix_latency(cuts: usize) -> usize {
    (cuts & cut::ALL).count_ones() as usize
}

/// Clocks from a test entering the default `SlabFix` ([`SLAB_FIX_CUTS`]) to its result leaving.
pub const SLAB_FIX_LATENCY: usize = slab_fix_latency(SLAB_FIX_CUTS);

/// The configurations that are built (exported, tested, timed): `(cuts, name suffix)`; the module name
/// of a configuration is the format's with this suffix (none for the default).
pub const SLAB_FIX_DEPTHS: [(usize, &str); 2] = [(SLAB_FIX_CUTS, ""), (SLAB_FIX_CUTS_DEEP, "_p6")];

/// Width of the opaque tag that travels with every test.
pub const TAG_BITS: usize = 16;

pub use golden::format::fixed::{code, sext};

/// The fixed-point slab tester; see the module documentation. `CUTS` chooses its registers ([`cut`]).
#[derive(LogicBlock)]
pub struct SlabFix<
    const G: usize,
    const D: usize,
    const I: usize,
    const T: usize,
    const CUTS: usize = SLAB_FIX_CUTS,
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
    pub box_lo: [Signal<In, Bits<G>>; 3],
    pub box_hi: [Signal<In, Bits<G>>; 3],
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub hit: Signal<Out, Bit>,
    pub t_entry: Signal<Out, Bits<T>>,
    pub t_exit: Signal<Out, Bits<T>>,
    // constants
    sign_d: Constant<Bits<D>>,
    sign_t: Constant<Bits<T>>,
    t_pinf: Constant<Bits<T>>,
    t_ninf: Constant<Bits<T>>,
    /// The hit decision one comparison deep (with [`cut::PRODUCT`]); see the last step of `update`.
    hit_flat: Constant<Bit>,
    // distances
    axis: [AxisDist<G, D>; 3],
    empty: Signal<Local, Bit>,
    e_q1: [Cut<Bits<D>>; 3],
    x_q1: [Cut<Bits<D>>; 3],
    m_lo_q1: [Cut<Bits<I>>; 3],
    m_hi_q1: [Cut<Bits<I>>; 3],
    t_min_q1: Cut<Bits<T>>,
    t_max_q1: Cut<Bits<T>>,
    empty_q1: Cut<Bit>,
    valid_q1: Cut<Bit>,
    tag_q1: Cut<Bits<TAG_BITS>>,
    // operands
    ea_qo: [Cut<Bits<D>>; 3],
    em_qo: [Cut<Bits<I>>; 3],
    xa_qo: [Cut<Bits<D>>; 3],
    xm_qo: [Cut<Bits<I>>; 3],
    t_min_qo: Cut<Bits<T>>,
    t_max_qo: Cut<Bits<T>>,
    empty_qo: Cut<Bit>,
    valid_qo: Cut<Bit>,
    tag_qo: Cut<Bits<TAG_BITS>>,
    // products (inside the MulRounds) and bounds
    mul_entry: [MulRound<D, I, T>; 3],
    mul_exit: [MulRound<D, I, T>; 3],
    t_min_qp: Cut<Bits<T>>,
    t_max_qp: Cut<Bits<T>>,
    empty_qp: Cut<Bit>,
    valid_qp: Cut<Bit>,
    tag_qp: Cut<Bits<TAG_BITS>>,
    entry_q2: [Cut<Bits<T>>; 3],
    exit_q2: [Cut<Bits<T>>; 3],
    t_min_q2: Cut<Bits<T>>,
    t_max_q2: Cut<Bits<T>>,
    empty_q2: Cut<Bit>,
    valid_q2: Cut<Bit>,
    tag_q2: Cut<Bits<TAG_BITS>>,
    // tree
    entry_a_q3: Cut<Bits<T>>,
    entry_b_q3: Cut<Bits<T>>,
    exit_a_q3: Cut<Bits<T>>,
    exit_b_q3: Cut<Bits<T>>,
    empty_q3: Cut<Bit>,
    valid_q3: Cut<Bit>,
    tag_q3: Cut<Bits<TAG_BITS>>,
    // outputs
    entry: Signal<Local, Bits<T>>,
    exit: Signal<Local, Bits<T>>,
    entry_q4: Cut<Bits<T>>,
    exit_q4: Cut<Bits<T>>,
    hit_q4: Cut<Bit>,
    valid_q4: Cut<Bit>,
    tag_q4: Cut<Bits<TAG_BITS>>,
}

impl<const G: usize, const D: usize, const I: usize, const T: usize, const CUTS: usize>
    SlabFix<G, D, I, T, CUTS>
{
    /// A tester for `fmt`, whose widths must equal the parameters (`D = G + 1`).
    pub fn new(fmt: &FixFormat) -> Self {
        assert!(
            fmt.g as usize == G && D == G + 1 && fmt.i as usize == I && fmt.t as usize == T,
            "SlabFix<{G},{D},{I},{T}> does not match format {}",
            fmt.name()
        );
        assert!(
            CUTS & cut::OUT != 0 && CUTS & !cut::ALL == 0,
            "SlabFix cut points {CUTS:#x}: the outputs must be registered, and only the cuts of \
             rtl::slab::fix::cut exist"
        );
        let on = |c: usize| CUTS & c != 0;
        let mr = |ceil| {
            std::array::from_fn(|_| MulRound::new(ceil, fmt.shift() as usize, on(cut::PRODUCT)))
        };
        let (d, o, p, b, t, q) = (
            on(cut::DIST),
            on(cut::OPERANDS),
            on(cut::PRODUCT),
            on(cut::BOUND),
            on(cut::TREE),
            on(cut::OUT),
        );
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
            valid_out: Default::default(),
            tag_out: Default::default(),
            hit: Default::default(),
            t_entry: Default::default(),
            t_exit: Default::default(),
            sign_d: Constant::new(bits::<D>(1 << (D - 1))),
            sign_t: Constant::new(bits::<T>(1 << (T - 1))),
            t_pinf: Constant::new(bits::<T>((1 << (T - 1)) - 1)),
            t_ninf: Constant::new(bits::<T>(1 << (T - 1))),
            hit_flat: Constant::new(p),
            axis: Default::default(),
            empty: Default::default(),
            e_q1: Cut::array(d),
            x_q1: Cut::array(d),
            m_lo_q1: Cut::array(d),
            m_hi_q1: Cut::array(d),
            t_min_q1: Cut::new(d),
            t_max_q1: Cut::new(d),
            empty_q1: Cut::new(d),
            valid_q1: Cut::new(d),
            tag_q1: Cut::new(d),
            ea_qo: Cut::array(o),
            em_qo: Cut::array(o),
            xa_qo: Cut::array(o),
            xm_qo: Cut::array(o),
            t_min_qo: Cut::new(o),
            t_max_qo: Cut::new(o),
            empty_qo: Cut::new(o),
            valid_qo: Cut::new(o),
            tag_qo: Cut::new(o),
            mul_entry: mr(false),
            mul_exit: mr(true),
            t_min_qp: Cut::new(p),
            t_max_qp: Cut::new(p),
            empty_qp: Cut::new(p),
            valid_qp: Cut::new(p),
            tag_qp: Cut::new(p),
            entry_q2: Cut::array(b),
            exit_q2: Cut::array(b),
            t_min_q2: Cut::new(b),
            t_max_q2: Cut::new(b),
            empty_q2: Cut::new(b),
            valid_q2: Cut::new(b),
            tag_q2: Cut::new(b),
            entry_a_q3: Cut::new(t),
            entry_b_q3: Cut::new(t),
            exit_a_q3: Cut::new(t),
            exit_b_q3: Cut::new(t),
            empty_q3: Cut::new(t),
            valid_q3: Cut::new(t),
            tag_q3: Cut::new(t),
            entry: Default::default(),
            exit: Default::default(),
            entry_q4: Cut::new(q),
            exit_q4: Cut::new(q),
            hit_q4: Cut::new(q),
            valid_q4: Cut::new(q),
            tag_q4: Cut::new(q),
        }
    }
}

/// A fixed slab tester of any width, built for a format, so drivers need not spell the widths.
pub trait SlabFixIo: TesterIo<Ray = FixRay, Box = FixBox, Out = SlabFixOut> {
    /// The block's cut points ([`cut`]).
    const CUTS: usize;
    /// A tester for `fmt` (whose widths must match the block's).
    fn for_format(fmt: &FixFormat) -> Self;
}

impl<const G: usize, const D: usize, const I: usize, const T: usize, const CUTS: usize> SlabFixIo
    for SlabFix<G, D, I, T, CUTS>
{
    const CUTS: usize = CUTS;
    fn for_format(fmt: &FixFormat) -> Self {
        Self::new(fmt)
    }
}

impl<const G: usize, const D: usize, const I: usize, const T: usize, const CUTS: usize> TesterIo
    for SlabFix<G, D, I, T, CUTS>
{
    type Ray = FixRay;
    type Box = FixBox;
    type Out = SlabFixOut;
    const LATENCY: usize = slab_fix_latency(CUTS);
    type Ports = SlabFixPorts;

    fn ports() -> SlabFixPorts {
        SlabFixPorts
    }

    crate::tester_ports!(
        inputs: ray_o_lo, ray_o_hi, ray_m_lo, ray_m_hi, ray_neg, ray_t_min, ray_t_max, box_lo, box_hi;
        outputs: hit, t_entry, t_exit
    );
}

impl<const G: usize, const D: usize, const I: usize, const T: usize, const CUTS: usize> Logic
    for SlabFix<G, D, I, T, CUTS>
{
    #[hdl_gen]
    fn update(&mut self) {
        // Clocks of every register.
        for i in 0..3 {
            self.e_q1[i].clock.next = self.clock.val();
            self.x_q1[i].clock.next = self.clock.val();
            self.m_lo_q1[i].clock.next = self.clock.val();
            self.m_hi_q1[i].clock.next = self.clock.val();
            self.ea_qo[i].clock.next = self.clock.val();
            self.em_qo[i].clock.next = self.clock.val();
            self.xa_qo[i].clock.next = self.clock.val();
            self.xm_qo[i].clock.next = self.clock.val();
            self.mul_entry[i].clock.next = self.clock.val();
            self.mul_exit[i].clock.next = self.clock.val();
            self.entry_q2[i].clock.next = self.clock.val();
            self.exit_q2[i].clock.next = self.clock.val();
        }
        dff_setup!(
            self, clock, t_min_q1, t_max_q1, empty_q1, valid_q1, tag_q1, t_min_qo, t_max_qo,
            empty_qo, valid_qo, tag_qo, t_min_qp, t_max_qp, empty_qp, valid_qp, tag_qp, t_min_q2,
            t_max_q2, empty_q2, valid_q2, tag_q2, entry_a_q3, entry_b_q3, exit_a_q3, exit_b_q3,
            empty_q3, valid_q3, tag_q3, entry_q4, exit_q4, hit_q4, valid_q4, tag_q4
        );

        // Distances in the direction of travel, empty-box flag.
        self.empty.next = false;
        for i in 0..3 {
            self.axis[i].lo.next = self.box_lo[i].val();
            self.axis[i].hi.next = self.box_hi[i].val();
            self.axis[i].o_lo.next = self.ray_o_lo[i].val();
            self.axis[i].o_hi.next = self.ray_o_hi[i].val();
            self.axis[i].neg.next = self.ray_neg[i].val();
            self.e_q1[i].d.next = self.axis[i].e.val();
            self.x_q1[i].d.next = self.axis[i].x.val();
            if self.axis[i].empty.val() {
                self.empty.next = true;
            }
            self.m_lo_q1[i].d.next = self.ray_m_lo[i].val();
            self.m_hi_q1[i].d.next = self.ray_m_hi[i].val();
        }
        self.t_min_q1.d.next = self.ray_t_min.val();
        self.t_max_q1.d.next = self.ray_t_max.val();
        self.empty_q1.d.next = self.empty.val();
        self.valid_q1.d.next = self.valid_in.val() & !self.rst.val();
        self.tag_q1.d.next = self.tag_in.val();

        // Operands: the inverse bound of each product picked by the sign of its distance.
        for i in 0..3 {
            self.ea_qo[i].d.next = self.e_q1[i].q.val();
            self.xa_qo[i].d.next = self.x_q1[i].q.val();
            if self.e_q1[i].q.val() >= self.sign_d.val() {
                self.em_qo[i].d.next = self.m_hi_q1[i].q.val();
            } else {
                self.em_qo[i].d.next = self.m_lo_q1[i].q.val();
            }
            if self.x_q1[i].q.val() >= self.sign_d.val() {
                self.xm_qo[i].d.next = self.m_lo_q1[i].q.val();
            } else {
                self.xm_qo[i].d.next = self.m_hi_q1[i].q.val();
            }
        }
        self.t_min_qo.d.next = self.t_min_q1.q.val();
        self.t_max_qo.d.next = self.t_max_q1.q.val();
        self.empty_qo.d.next = self.empty_q1.q.val();
        self.valid_qo.d.next = self.valid_q1.q.val() & !self.rst.val();
        self.tag_qo.d.next = self.tag_q1.q.val();

        // Products (registered inside the MulRounds at the product cut), rounded and saturated bounds.
        for i in 0..3 {
            self.mul_entry[i].a.next = self.ea_qo[i].q.val();
            self.mul_entry[i].m.next = self.em_qo[i].q.val();
            self.mul_exit[i].a.next = self.xa_qo[i].q.val();
            self.mul_exit[i].m.next = self.xm_qo[i].q.val();
            self.entry_q2[i].d.next = self.mul_entry[i].y.val();
            self.exit_q2[i].d.next = self.mul_exit[i].y.val();
        }
        self.t_min_qp.d.next = self.t_min_qo.q.val();
        self.t_max_qp.d.next = self.t_max_qo.q.val();
        self.empty_qp.d.next = self.empty_qo.q.val();
        self.valid_qp.d.next = self.valid_qo.q.val() & !self.rst.val();
        self.tag_qp.d.next = self.tag_qo.q.val();
        self.t_min_q2.d.next = self.t_min_qp.q.val();
        self.t_max_q2.d.next = self.t_max_qp.q.val();
        self.empty_q2.d.next = self.empty_qp.q.val();
        self.valid_q2.d.next = self.valid_qp.q.val() & !self.rst.val();
        self.tag_q2.d.next = self.tag_qp.q.val();

        // First level of the max (entry) and min (exit) trees.
        if (self.t_min_q2.q.val() ^ self.sign_t.val())
            > (self.entry_q2[0].q.val() ^ self.sign_t.val())
        {
            self.entry_a_q3.d.next = self.t_min_q2.q.val();
        } else {
            self.entry_a_q3.d.next = self.entry_q2[0].q.val();
        }
        if (self.entry_q2[1].q.val() ^ self.sign_t.val())
            > (self.entry_q2[2].q.val() ^ self.sign_t.val())
        {
            self.entry_b_q3.d.next = self.entry_q2[1].q.val();
        } else {
            self.entry_b_q3.d.next = self.entry_q2[2].q.val();
        }
        if (self.t_max_q2.q.val() ^ self.sign_t.val())
            < (self.exit_q2[0].q.val() ^ self.sign_t.val())
        {
            self.exit_a_q3.d.next = self.t_max_q2.q.val();
        } else {
            self.exit_a_q3.d.next = self.exit_q2[0].q.val();
        }
        if (self.exit_q2[1].q.val() ^ self.sign_t.val())
            < (self.exit_q2[2].q.val() ^ self.sign_t.val())
        {
            self.exit_b_q3.d.next = self.exit_q2[1].q.val();
        } else {
            self.exit_b_q3.d.next = self.exit_q2[2].q.val();
        }
        self.empty_q3.d.next = self.empty_q2.q.val();
        self.valid_q3.d.next = self.valid_q2.q.val() & !self.rst.val();
        self.tag_q3.d.next = self.tag_q2.q.val();

        // Final max/min and the hit decision.
        if (self.entry_a_q3.q.val() ^ self.sign_t.val())
            > (self.entry_b_q3.q.val() ^ self.sign_t.val())
        {
            self.entry.next = self.entry_a_q3.q.val();
        } else {
            self.entry.next = self.entry_b_q3.q.val();
        }
        if (self.exit_a_q3.q.val() ^ self.sign_t.val())
            < (self.exit_b_q3.q.val() ^ self.sign_t.val())
        {
            self.exit.next = self.exit_a_q3.q.val();
        } else {
            self.exit.next = self.exit_b_q3.q.val();
        }
        self.entry_q4.d.next = self.entry.val();
        self.exit_q4.d.next = self.exit.val();
        // The hit decision. With the multiplies in a clock of their own (cut::PRODUCT) this clock is
        // the tester's limit, so it reads the four tree halves side by side, one comparison deep:
        // max(ea, eb) <= min(xa, xb) is the four comparisons ea <= xa, ea <= xb, eb <= xa, eb <= xb;
        // the max is +inf when either half is, the min -inf when either half is. Otherwise the
        // multiply-and-round clock is the limit and the decision reads the max and min just chosen
        // (two comparisons deep, fewer LUTs).
        if self.hit_flat.val() {
            self.hit_q4.d.next = !self.empty_q3.q.val()
                & ((self.entry_a_q3.q.val() ^ self.sign_t.val())
                    <= (self.exit_a_q3.q.val() ^ self.sign_t.val()))
                & ((self.entry_a_q3.q.val() ^ self.sign_t.val())
                    <= (self.exit_b_q3.q.val() ^ self.sign_t.val()))
                & ((self.entry_b_q3.q.val() ^ self.sign_t.val())
                    <= (self.exit_a_q3.q.val() ^ self.sign_t.val()))
                & ((self.entry_b_q3.q.val() ^ self.sign_t.val())
                    <= (self.exit_b_q3.q.val() ^ self.sign_t.val()))
                & (self.entry_a_q3.q.val() != self.t_pinf.val())
                & (self.entry_b_q3.q.val() != self.t_pinf.val())
                & (self.exit_a_q3.q.val() != self.t_ninf.val())
                & (self.exit_b_q3.q.val() != self.t_ninf.val());
        } else {
            self.hit_q4.d.next = !self.empty_q3.q.val()
                & ((self.entry.val() ^ self.sign_t.val()) <= (self.exit.val() ^ self.sign_t.val()))
                & (self.entry.val() != self.t_pinf.val())
                & (self.exit.val() != self.t_ninf.val());
        }
        self.valid_q4.d.next = self.valid_q3.q.val() & !self.rst.val();
        self.tag_q4.d.next = self.tag_q3.q.val();

        self.valid_out.next = self.valid_q4.q.val();
        self.tag_out.next = self.tag_q4.q.val();
        self.hit.next = self.hit_q4.q.val();
        self.t_entry.next = self.entry_q4.q.val();
        self.t_exit.next = self.exit_q4.q.val();
    }
}
