//! `SlabFix`: the fixed-point AABB slab tester, fully pipelined (one test per clock), 4 clocks of latency.
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
//! - `clock`; `valid_in`, `tag_in` (16 bits, opaque, returned with the result);
//! - `ray_*`: the fields of [`FixRay`] — origin interval `ray_o_lo`, `ray_o_hi`, inverse interval
//!   `ray_m_lo`, `ray_m_hi`, signs `ray_neg` (arrays over x, y, z), `ray_t_min`, `ray_t_max`;
//! - `box_*`: the fields of [`FixBox`] — `box_lo`, `box_hi`.
//!
//! rust-hdl 0.46's `LogicInterface` cannot hold arrays, so the grouping is by name prefix in the ports and
//! by type in the Rust API: [`SlabFix::drive`] takes a [`FixRay`] and a [`FixBox`], [`SlabFix::result`]
//! gives a [`SlabFixOut`].
//!
//! # Outputs (registered, [`SLAB_FIX_LATENCY`] clocks after the inputs)
//! - `valid_out`, `tag_out`, `hit`, `t_entry`, `t_exit`.
//!
//! # Stages
//! 1. `_q1`: per axis ([`AxisDist`]) the distances `e`, `x` to the near and far planes in `D` bits, and
//!    the empty-box flag.
//! 2. `_q2`: six [`MulRound`] units: `entry_a` floored, `exit_a` ceiled, the inverse bound chosen by the
//!    sign of the distance.
//! 3. `_q3`: first level of the max/min trees with `t_min`/`t_max`.
//! 4. `_q4`: final max/min and the hit decision; these registers drive the outputs.
//!
//! Signed comparisons are unsigned comparisons of the sign-flipped codes: rust-hdl's `Signed` compares
//! through big integers in simulation and emits unsized `$signed` casts in Verilog.

use crate::io::SlabIo;
use crate::slab::axis_dist::AxisDist;
use crate::slab::mul_round::MulRound;
use golden::format::fixed::{FixBox, FixFormat, FixRay};
use golden::slab::fix::SlabFixOut;
use rust_hdl::prelude::*;

/// Clocks from a test entering `SlabFix` to its result leaving.
pub const SLAB_FIX_LATENCY: usize = 4;

/// Width of the opaque tag that travels with every test.
pub const TAG_BITS: usize = 16;

/// Two's complement code of `v` in `n` bits.
pub fn code(v: i64, n: usize) -> u64 {
    (v as u64) & if n == 64 { u64::MAX } else { (1u64 << n) - 1 }
}

/// Sign-extends an `n`-bit two's complement code.
pub fn sext(v: u64, n: usize) -> i64 {
    ((v << (64 - n)) as i64) >> (64 - n)
}

/// The fixed-point slab tester; see the module documentation.
#[derive(LogicBlock)]
pub struct SlabFix<const G: usize, const D: usize, const I: usize, const T: usize> {
    pub clock: Signal<In, Clock>,
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
    // stage 1
    axis: [AxisDist<G, D>; 3],
    empty: Signal<Local, Bit>,
    e_q1: [DFF<Bits<D>>; 3],
    x_q1: [DFF<Bits<D>>; 3],
    m_lo_q1: [DFF<Bits<I>>; 3],
    m_hi_q1: [DFF<Bits<I>>; 3],
    t_min_q1: DFF<Bits<T>>,
    t_max_q1: DFF<Bits<T>>,
    empty_q1: DFF<Bit>,
    valid_q1: DFF<Bit>,
    tag_q1: DFF<Bits<TAG_BITS>>,
    // stage 2
    mul_entry: [MulRound<D, I, T>; 3],
    mul_exit: [MulRound<D, I, T>; 3],
    entry_q2: [DFF<Bits<T>>; 3],
    exit_q2: [DFF<Bits<T>>; 3],
    t_min_q2: DFF<Bits<T>>,
    t_max_q2: DFF<Bits<T>>,
    empty_q2: DFF<Bit>,
    valid_q2: DFF<Bit>,
    tag_q2: DFF<Bits<TAG_BITS>>,
    // stage 3
    entry_a_q3: DFF<Bits<T>>,
    entry_b_q3: DFF<Bits<T>>,
    exit_a_q3: DFF<Bits<T>>,
    exit_b_q3: DFF<Bits<T>>,
    empty_q3: DFF<Bit>,
    valid_q3: DFF<Bit>,
    tag_q3: DFF<Bits<TAG_BITS>>,
    // stage 4
    entry: Signal<Local, Bits<T>>,
    exit: Signal<Local, Bits<T>>,
    entry_q4: DFF<Bits<T>>,
    exit_q4: DFF<Bits<T>>,
    hit_q4: DFF<Bit>,
    valid_q4: DFF<Bit>,
    tag_q4: DFF<Bits<TAG_BITS>>,
}

impl<const G: usize, const D: usize, const I: usize, const T: usize> SlabFix<G, D, I, T> {
    /// A tester for `fmt`, whose widths must equal the parameters (`D = G + 1`).
    pub fn new(fmt: &FixFormat) -> Self {
        assert!(
            fmt.g as usize == G && D == G + 1 && fmt.i as usize == I && fmt.t as usize == T,
            "SlabFix<{G},{D},{I},{T}> does not match format {}",
            fmt.name()
        );
        let mr = |ceil| std::array::from_fn(|_| MulRound::new(ceil, fmt.shift() as usize));
        Self {
            clock: Default::default(),
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
            axis: Default::default(),
            empty: Default::default(),
            e_q1: Default::default(),
            x_q1: Default::default(),
            m_lo_q1: Default::default(),
            m_hi_q1: Default::default(),
            t_min_q1: Default::default(),
            t_max_q1: Default::default(),
            empty_q1: Default::default(),
            valid_q1: Default::default(),
            tag_q1: Default::default(),
            mul_entry: mr(false),
            mul_exit: mr(true),
            entry_q2: Default::default(),
            exit_q2: Default::default(),
            t_min_q2: Default::default(),
            t_max_q2: Default::default(),
            empty_q2: Default::default(),
            valid_q2: Default::default(),
            tag_q2: Default::default(),
            entry_a_q3: Default::default(),
            entry_b_q3: Default::default(),
            exit_a_q3: Default::default(),
            exit_b_q3: Default::default(),
            empty_q3: Default::default(),
            valid_q3: Default::default(),
            tag_q3: Default::default(),
            entry: Default::default(),
            exit: Default::default(),
            entry_q4: Default::default(),
            exit_q4: Default::default(),
            hit_q4: Default::default(),
            valid_q4: Default::default(),
            tag_q4: Default::default(),
        }
    }
}

/// A fixed slab tester of any width, built for a format, so drivers need not spell the widths.
pub trait SlabFixIo: SlabIo<Ray = FixRay, Box = FixBox, Out = SlabFixOut> {
    /// A tester for `fmt` (whose widths must match the block's).
    fn for_format(fmt: &FixFormat) -> Self;
}

impl<const G: usize, const D: usize, const I: usize, const T: usize> SlabFixIo
    for SlabFix<G, D, I, T>
{
    fn for_format(fmt: &FixFormat) -> Self {
        Self::new(fmt)
    }
}

impl<const G: usize, const D: usize, const I: usize, const T: usize> SlabIo
    for SlabFix<G, D, I, T>
{
    type Ray = FixRay;
    type Box = FixBox;
    type Out = SlabFixOut;
    const LATENCY: usize = SLAB_FIX_LATENCY;

    fn set_clock(&mut self, high: bool) {
        self.clock.next = Clock { clk: high };
    }

    fn drive(&mut self, test: Option<(u16, &FixRay, &FixBox)>) {
        match test {
            Some((tag, r, b)) => {
                self.valid_in.next = true;
                self.tag_in.next = bits::<TAG_BITS>(tag as u64);
                for a in 0..3 {
                    self.ray_o_lo[a].next = bits::<G>(code(r.o_lo[a], G));
                    self.ray_o_hi[a].next = bits::<G>(code(r.o_hi[a], G));
                    self.ray_m_lo[a].next = bits::<I>(r.m_lo[a]);
                    self.ray_m_hi[a].next = bits::<I>(r.m_hi[a]);
                    self.ray_neg[a].next = r.neg[a];
                    self.box_lo[a].next = bits::<G>(code(b.lo[a], G));
                    self.box_hi[a].next = bits::<G>(code(b.hi[a], G));
                }
                self.ray_t_min.next = bits::<T>(code(r.t_min, T));
                self.ray_t_max.next = bits::<T>(code(r.t_max, T));
            }
            None => self.valid_in.next = false,
        }
    }

    fn result(&self) -> Option<(u16, SlabFixOut)> {
        if !self.valid_out.val() {
            return None;
        }
        Some((
            self.tag_out.val().to_u64() as u16,
            SlabFixOut {
                hit: self.hit.val(),
                t_entry: sext(self.t_entry.val().to_u64(), T),
                t_exit: sext(self.t_exit.val().to_u64(), T),
            },
        ))
    }

    fn output_word(&self, port: &str) -> Option<u64> {
        Some(match port {
            "valid_out" => self.valid_out.val() as u64,
            "tag_out" => self.tag_out.val().to_u64(),
            "hit" => self.hit.val() as u64,
            "t_entry" => self.t_entry.val().to_u64(),
            "t_exit" => self.t_exit.val().to_u64(),
            _ => return None,
        })
    }
}

impl<const G: usize, const D: usize, const I: usize, const T: usize> Logic for SlabFix<G, D, I, T> {
    #[hdl_gen]
    fn update(&mut self) {
        // Clocks of every register.
        for i in 0..3 {
            self.e_q1[i].clock.next = self.clock.val();
            self.x_q1[i].clock.next = self.clock.val();
            self.m_lo_q1[i].clock.next = self.clock.val();
            self.m_hi_q1[i].clock.next = self.clock.val();
            self.entry_q2[i].clock.next = self.clock.val();
            self.exit_q2[i].clock.next = self.clock.val();
        }
        dff_setup!(
            self, clock, t_min_q1, t_max_q1, empty_q1, valid_q1, tag_q1, t_min_q2, t_max_q2,
            empty_q2, valid_q2, tag_q2, entry_a_q3, entry_b_q3, exit_a_q3, exit_b_q3, empty_q3,
            valid_q3, tag_q3, entry_q4, exit_q4, hit_q4, valid_q4, tag_q4
        );

        // Stage 1: distances in the direction of travel, empty-box flag.
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
        self.valid_q1.d.next = self.valid_in.val();
        self.tag_q1.d.next = self.tag_in.val();

        // Stage 2: scaled products, the inverse bound picked by the sign of the distance.
        for i in 0..3 {
            self.mul_entry[i].a.next = self.e_q1[i].q.val();
            self.mul_exit[i].a.next = self.x_q1[i].q.val();
            if self.e_q1[i].q.val() >= self.sign_d.val() {
                self.mul_entry[i].m.next = self.m_hi_q1[i].q.val();
            } else {
                self.mul_entry[i].m.next = self.m_lo_q1[i].q.val();
            }
            if self.x_q1[i].q.val() >= self.sign_d.val() {
                self.mul_exit[i].m.next = self.m_lo_q1[i].q.val();
            } else {
                self.mul_exit[i].m.next = self.m_hi_q1[i].q.val();
            }
            self.entry_q2[i].d.next = self.mul_entry[i].y.val();
            self.exit_q2[i].d.next = self.mul_exit[i].y.val();
        }
        self.t_min_q2.d.next = self.t_min_q1.q.val();
        self.t_max_q2.d.next = self.t_max_q1.q.val();
        self.empty_q2.d.next = self.empty_q1.q.val();
        self.valid_q2.d.next = self.valid_q1.q.val();
        self.tag_q2.d.next = self.tag_q1.q.val();

        // Stage 3: first level of the max (entry) and min (exit) trees.
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
        self.valid_q3.d.next = self.valid_q2.q.val();
        self.tag_q3.d.next = self.tag_q2.q.val();

        // Stage 4: final max/min and the hit decision.
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
        self.hit_q4.d.next = !self.empty_q3.q.val()
            & ((self.entry.val() ^ self.sign_t.val()) <= (self.exit.val() ^ self.sign_t.val()))
            & (self.entry.val() != self.t_pinf.val())
            & (self.exit.val() != self.t_ninf.val());
        self.valid_q4.d.next = self.valid_q3.q.val();
        self.tag_q4.d.next = self.tag_q3.q.val();

        self.valid_out.next = self.valid_q4.q.val();
        self.tag_out.next = self.tag_q4.q.val();
        self.hit.next = self.hit_q4.q.val();
        self.t_entry.next = self.entry_q4.q.val();
        self.t_exit.next = self.exit_q4.q.val();
    }
}
