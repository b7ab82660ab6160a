//! Re-bounding in the streaming processors ([`crate::bundle::stream::BundleStream`],
//! [`crate::bundle::stream_float::BundleStreamFloat`]): while a split job's rays stream through the
//! pair, [`ReboundAcc`] gathers the hull of the rays the pair keeps and reports it with the job, bit for
//! bit the rule of `golden::bundle::rebound` (the model: `golden::bundle::stream::StreamModel`, which
//! folds each kept ray with `ScaledBundle::hull` or `float_hull`).
//!
//! # On the float datapath
//! The float rule needs no rescaling (the rays of a bundle are stored on one direction scale): it is a
//! `min`/`max` of every field in the numeric order with `-0` below `+0`. [`OrderKeys`] turns each code
//! into a key that compares as a two's-complement integer in that order, so the float processor uses
//! [`ReboundAcc`] as it is, on keys, with every exponent 0: [`Hull2`] then shifts by 0 and is a signed
//! `min`/`max`. Synthesis removes the shifters: in `bundle_stream_e5m10_n16x4` no shift cell of the
//! gatherer is left after Yosys's `proc; flatten; opt -full; opt_dff -sat` (all 188 that remain are the
//! pair's).
//!
//! A bundle here is a tiny bundle with its direction exponent `j` (a ray's, as the store holds it, or a
//! hull's), its fields as arrays: `o` (origin codes `lo` x, y, z then `hi` x, y, z, `G` bits), `d`
//! (direction codes, the same order, `D` bits), `t` (`t_lo`, `t_hi`, `T` bits), `j` ([`J_BITS`]), all
//! two's complement.
//!
//! # Blocks
//! - [`Hull2`]: the hull of two bundles: the one with the larger `j` brought onto the other's scale, then
//!   `min` of every `lo`, `max` of every `hi` (combinational);
//! - [`ItemLine`]: a bundle delayed by a number of clocks; [`ItemSel`]: a choice of two bundles or zero;
//! - [`ReboundAcc`]: the gatherer;
//! - [`OrderKeys`]: float codes as signed keys, so that [`ReboundAcc`] gathers float bundles too (see
//!   "On the float datapath").
//!
//! # Timing of [`ReboundAcc`] (`L` = the pair's latency, at least 2)
//! The gatherer folds one clock behind the pair's answer, loading its result registers in the clock
//! the processor's report stage moves to the result ports (so `rb_*` come with `done`). The two rays
//! that enter the pair in a clock (from the store's read ports) ride a line of `L - 1` clocks beside it;
//! the hull of the two is formed from the line's end and registered with them, so in the answer's clock
//! the answer only chooses ray A, ray B or their hull into the operand register `op` (with whether it
//! kept any, the end of the job, and `rst`); in the next clock `op` is folded, and the one loop
//! (accumulator -> [`Hull2`] -> accumulator) holds a single rescale and starts and ends at the
//! gatherer's own registers. The fold is associative and commutative, so folding a pair's hull equals
//! folding its rays one at a time, as the model does.
//!
//! On ECP5 (`scripts/timing`, seed 1) this loop, with the pair's answer choosing the bundle before the
//! fold, limited the b12 processor to 58.4 MHz and the one over the 5-clock pair to 57.5 MHz while
//! [`Hull2`] clamped the shift amount and subtracted it from the width in front of its shifters; with
//! the masks made beside the shifts instead, the b12 processor reaches 63.0 MHz, limited by the pair's
//! own edge test, and the 5-clock one 60.8 MHz, still in this loop, whose path began at the pair's
//! answer register (the fp16 processor over the 13-clock pair: 68.9 MHz, 89% of the path routing).
//! Two variants were slower: folding the accumulator with all three candidates from registers and
//! letting the answer choose after the fold (50.6 MHz, 11,863 LUT4 against 7,880), and rescaling both
//! operands of [`Hull2`] by their own clamped differences instead of swapping them (50.1 MHz, 8,918
//! LUT4). Hence the clock between the answer and the fold (the report stage of
//! `golden::bundle::stream`). With the answer and the choice registered (the fold's operand still
//! chosen by two multiplexers behind the answer's registers) the 5-clock processor reached 63.6 MHz,
//! from the registered answer through the choice and the hull into the result registers; so the choice
//! moved in front of the register (`op`), and only the hull and the accumulator's multiplexers are left
//! in the loop.

use crate::cut::Line;
pub use golden::bundle::rebound::J_BITS;
use rust_hdl::prelude::*;

/// Bits of a shift amount: the difference of two exponents of [`J_BITS`].
pub const S_BITS: usize = J_BITS;

/// The hull of bundles `x` and `y` (see the module documentation), combinational: the one with the
/// larger exponent is rescaled by `s`, the difference of the exponents (direction codes divided by
/// `2^s`, `lo` rounding down and `hi` up; t codes times `2^s`, the `+inf` code and codes `<= 0` kept, a
/// result past the finite codes saturating at the largest finite code for `t_lo` and at `+inf` for
/// `t_hi`), then `min` of every `lo` and `max` of every `hi`, signed.
///
/// One leaf with no children: with the shifters as child blocks, the parent's single `always` block
/// both drives their inputs and reads their outputs, which Verilator's lint reports as a combinational
/// loop (`UNOPTFLAT`).
#[derive(LogicBlock)]
pub struct Hull2<const G: usize, const D: usize, const T: usize> {
    pub x_o: [Signal<In, Bits<G>>; 6],
    pub x_d: [Signal<In, Bits<D>>; 6],
    pub x_t: [Signal<In, Bits<T>>; 2],
    pub x_j: Signal<In, Bits<J_BITS>>,
    pub y_o: [Signal<In, Bits<G>>; 6],
    pub y_d: [Signal<In, Bits<D>>; 6],
    pub y_t: [Signal<In, Bits<T>>; 2],
    pub y_j: Signal<In, Bits<J_BITS>>,
    pub h_o: [Signal<Out, Bits<G>>; 6],
    pub h_d: [Signal<Out, Bits<D>>; 6],
    pub h_t: [Signal<Out, Bits<T>>; 2],
    pub h_j: Signal<Out, Bits<J_BITS>>,
    msb_g: Constant<Bits<G>>,
    msb_d: Constant<Bits<D>>,
    msb_t: Constant<Bits<T>>,
    msb_j: Constant<Bits<J_BITS>>,
    one_d: Constant<Bits<D>>,
    ones_d: Constant<Bits<D>>,
    pinf: Constant<Bits<T>>,
    /// Where each t code saturates: the largest finite code, `+inf`.
    sat: [Constant<Bits<T>>; 2],
    /// `x` has the larger exponent: `x` is the one rescaled.
    x_big: Signal<Local, Bit>,
    /// The difference of the exponents, unclamped (a shift by `D` or more leaves a direction code 0 or
    /// -1, as any larger one would).
    s: Signal<Local, Bits<S_BITS>>,
    /// The direction bits a shift by `s` drops; the t bits whose shift by `s` passes the finite codes.
    lost_d: Signal<Local, Bits<D>>,
    over_t: Signal<Local, Bits<T>>,
    big_d: [Signal<Local, Bits<D>>; 6],
    small_d: [Signal<Local, Bits<D>>; 6],
    floor_d: [Signal<Local, Bits<D>>; 6],
    scaled_d: [Signal<Local, Bits<D>>; 6],
    big_t: [Signal<Local, Bits<T>>; 2],
    small_t: [Signal<Local, Bits<T>>; 2],
    shl_t: [Signal<Local, Bits<T>>; 2],
    scaled_t: [Signal<Local, Bits<T>>; 2],
}

impl<const G: usize, const D: usize, const T: usize> Default for Hull2<G, D, T> {
    fn default() -> Self {
        let pinf = (1u64 << (T - 1)) - 1;
        Self {
            x_o: Default::default(),
            x_d: Default::default(),
            x_t: Default::default(),
            x_j: Default::default(),
            y_o: Default::default(),
            y_d: Default::default(),
            y_t: Default::default(),
            y_j: Default::default(),
            h_o: Default::default(),
            h_d: Default::default(),
            h_t: Default::default(),
            h_j: Default::default(),
            msb_g: Constant::new(bits(1 << (G - 1))),
            msb_d: Constant::new(bits(1 << (D - 1))),
            msb_t: Constant::new(bits(1 << (T - 1))),
            msb_j: Constant::new(bits(1 << (J_BITS - 1))),
            one_d: Constant::new(bits(1)),
            ones_d: Constant::new(bits((1u64 << D) - 1)),
            pinf: Constant::new(bits(pinf)),
            sat: [Constant::new(bits(pinf - 1)), Constant::new(bits(pinf))],
            x_big: Default::default(),
            s: Default::default(),
            lost_d: Default::default(),
            over_t: Default::default(),
            big_d: Default::default(),
            small_d: Default::default(),
            floor_d: Default::default(),
            scaled_d: Default::default(),
            big_t: Default::default(),
            small_t: Default::default(),
            shl_t: Default::default(),
            scaled_t: Default::default(),
        }
    }
}

impl<const G: usize, const D: usize, const T: usize> Logic for Hull2<G, D, T> {
    #[hdl_gen]
    fn update(&mut self) {
        // Signed comparisons: codes with the sign bit flipped compare as unsigned.
        self.x_big.next = (self.x_j.val() ^ self.msb_j.val()) > (self.y_j.val() ^ self.msb_j.val());
        if self.x_big.val() {
            self.s.next = self.x_j.val() - self.y_j.val();
            self.h_j.next = self.y_j.val();
        } else {
            self.s.next = self.y_j.val() - self.x_j.val();
            self.h_j.next = self.x_j.val();
        }
        // Masks made from `s` beside the shifts (not a clamp or a difference in front of them): the low
        // `s` direction bits, and the top `s` of the `T - 1` value bits of a t code.
        self.lost_d.next = !(self.ones_d.val() << self.s.val());
        self.over_t.next = !(self.pinf.val() >> self.s.val());
        // Directions: an arithmetic shift (a negative code is the complement of a non-negative one; a
        // shift by `D` or more leaves 0 or -1); a `hi` code rounds up when a bit shifted out is set.
        for i in 0..6 {
            if self.x_big.val() {
                self.big_d[i].next = self.x_d[i].val();
                self.small_d[i].next = self.y_d[i].val();
            } else {
                self.big_d[i].next = self.y_d[i].val();
                self.small_d[i].next = self.x_d[i].val();
            }
            if (self.big_d[i].val() & self.msb_d.val()).any() {
                self.floor_d[i].next = !((!self.big_d[i].val()) >> self.s.val());
            } else {
                self.floor_d[i].next = self.big_d[i].val() >> self.s.val();
            }
            self.scaled_d[i].next = self.floor_d[i].val();
        }
        for i in 3..6 {
            if (self.big_d[i].val() & self.lost_d.val()).any() {
                self.scaled_d[i].next = self.floor_d[i].val() + self.one_d.val();
            }
        }
        // t codes: for 0 < t < 2^(T-1), t 2^s >= 2^(T-1) exactly when t has a bit at T - 1 - s or above
        // (`over_t`, every value bit once s >= T - 1). A result equal to the +inf code (odd) needs s = 0,
        // where t is kept anyway.
        for i in 0..2 {
            if self.x_big.val() {
                self.big_t[i].next = self.x_t[i].val();
                self.small_t[i].next = self.y_t[i].val();
            } else {
                self.big_t[i].next = self.y_t[i].val();
                self.small_t[i].next = self.x_t[i].val();
            }
            self.shl_t[i].next = self.big_t[i].val() << self.s.val();
            self.scaled_t[i].next = self.shl_t[i].val();
            if (self.big_t[i].val() & self.over_t.val()).any() {
                self.scaled_t[i].next = self.sat[i].val();
            }
            if (self.big_t[i].val() & self.msb_t.val()).any() | !self.big_t[i].val().any() {
                self.scaled_t[i].next = self.big_t[i].val();
            }
            if self.big_t[i].val() == self.pinf.val() {
                self.scaled_t[i].next = self.pinf.val();
            }
        }
        // lo: the smaller; hi: the larger.
        for i in 0..3 {
            if (self.x_o[i].val() ^ self.msb_g.val()) < (self.y_o[i].val() ^ self.msb_g.val()) {
                self.h_o[i].next = self.x_o[i].val();
            } else {
                self.h_o[i].next = self.y_o[i].val();
            }
            if (self.scaled_d[i].val() ^ self.msb_d.val())
                < (self.small_d[i].val() ^ self.msb_d.val())
            {
                self.h_d[i].next = self.scaled_d[i].val();
            } else {
                self.h_d[i].next = self.small_d[i].val();
            }
        }
        for i in 3..6 {
            if (self.x_o[i].val() ^ self.msb_g.val()) > (self.y_o[i].val() ^ self.msb_g.val()) {
                self.h_o[i].next = self.x_o[i].val();
            } else {
                self.h_o[i].next = self.y_o[i].val();
            }
            if (self.scaled_d[i].val() ^ self.msb_d.val())
                > (self.small_d[i].val() ^ self.msb_d.val())
            {
                self.h_d[i].next = self.scaled_d[i].val();
            } else {
                self.h_d[i].next = self.small_d[i].val();
            }
        }
        if (self.scaled_t[0].val() ^ self.msb_t.val()) < (self.small_t[0].val() ^ self.msb_t.val())
        {
            self.h_t[0].next = self.scaled_t[0].val();
        } else {
            self.h_t[0].next = self.small_t[0].val();
        }
        if (self.scaled_t[1].val() ^ self.msb_t.val()) > (self.small_t[1].val() ^ self.msb_t.val())
        {
            self.h_t[1].next = self.scaled_t[1].val();
        } else {
            self.h_t[1].next = self.small_t[1].val();
        }
    }
}

/// A bundle delayed by `regs` clocks ([`Line`]s).
#[derive(LogicBlock)]
pub struct ItemLine<const G: usize, const D: usize, const T: usize> {
    pub clock: Signal<In, Clock>,
    pub d_o: [Signal<In, Bits<G>>; 6],
    pub d_d: [Signal<In, Bits<D>>; 6],
    pub d_t: [Signal<In, Bits<T>>; 2],
    pub d_j: Signal<In, Bits<J_BITS>>,
    pub q_o: [Signal<Out, Bits<G>>; 6],
    pub q_d: [Signal<Out, Bits<D>>; 6],
    pub q_t: [Signal<Out, Bits<T>>; 2],
    pub q_j: Signal<Out, Bits<J_BITS>>,
    l_o: [Line<Bits<G>>; 6],
    l_d: [Line<Bits<D>>; 6],
    l_t: [Line<Bits<T>>; 2],
    l_j: Line<Bits<J_BITS>>,
}

impl<const G: usize, const D: usize, const T: usize> ItemLine<G, D, T> {
    pub fn new(regs: usize) -> Self {
        Self {
            clock: Default::default(),
            d_o: Default::default(),
            d_d: Default::default(),
            d_t: Default::default(),
            d_j: Default::default(),
            q_o: Default::default(),
            q_d: Default::default(),
            q_t: Default::default(),
            q_j: Default::default(),
            l_o: Line::array(regs),
            l_d: Line::array(regs),
            l_t: Line::array(regs),
            l_j: Line::new(regs),
        }
    }
}

impl<const G: usize, const D: usize, const T: usize> Logic for ItemLine<G, D, T> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..6 {
            self.l_o[i].clock.next = self.clock.val();
            self.l_o[i].d.next = self.d_o[i].val();
            self.q_o[i].next = self.l_o[i].q.val();
            self.l_d[i].clock.next = self.clock.val();
            self.l_d[i].d.next = self.d_d[i].val();
            self.q_d[i].next = self.l_d[i].q.val();
        }
        for i in 0..2 {
            self.l_t[i].clock.next = self.clock.val();
            self.l_t[i].d.next = self.d_t[i].val();
            self.q_t[i].next = self.l_t[i].q.val();
        }
        self.l_j.clock.next = self.clock.val();
        self.l_j.d.next = self.d_j.val();
        self.q_j.next = self.l_j.q.val();
    }
}

/// `y` = zero when `clear`, else `a` when `sel`, else `b` (combinational).
#[derive(LogicBlock)]
pub struct ItemSel<const G: usize, const D: usize, const T: usize> {
    pub sel: Signal<In, Bit>,
    pub clear: Signal<In, Bit>,
    pub a_o: [Signal<In, Bits<G>>; 6],
    pub a_d: [Signal<In, Bits<D>>; 6],
    pub a_t: [Signal<In, Bits<T>>; 2],
    pub a_j: Signal<In, Bits<J_BITS>>,
    pub b_o: [Signal<In, Bits<G>>; 6],
    pub b_d: [Signal<In, Bits<D>>; 6],
    pub b_t: [Signal<In, Bits<T>>; 2],
    pub b_j: Signal<In, Bits<J_BITS>>,
    pub y_o: [Signal<Out, Bits<G>>; 6],
    pub y_d: [Signal<Out, Bits<D>>; 6],
    pub y_t: [Signal<Out, Bits<T>>; 2],
    pub y_j: Signal<Out, Bits<J_BITS>>,
    zero_g: Constant<Bits<G>>,
    zero_d: Constant<Bits<D>>,
    zero_t: Constant<Bits<T>>,
    zero_j: Constant<Bits<J_BITS>>,
}

impl<const G: usize, const D: usize, const T: usize> Default for ItemSel<G, D, T> {
    fn default() -> Self {
        Self {
            sel: Default::default(),
            clear: Default::default(),
            a_o: Default::default(),
            a_d: Default::default(),
            a_t: Default::default(),
            a_j: Default::default(),
            b_o: Default::default(),
            b_d: Default::default(),
            b_t: Default::default(),
            b_j: Default::default(),
            y_o: Default::default(),
            y_d: Default::default(),
            y_t: Default::default(),
            y_j: Default::default(),
            zero_g: Constant::new(bits(0)),
            zero_d: Constant::new(bits(0)),
            zero_t: Constant::new(bits(0)),
            zero_j: Constant::new(bits(0)),
        }
    }
}

impl<const G: usize, const D: usize, const T: usize> Logic for ItemSel<G, D, T> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..6 {
            self.y_o[i].next = self.zero_g.val();
            self.y_d[i].next = self.zero_d.val();
            if !self.clear.val() {
                if self.sel.val() {
                    self.y_o[i].next = self.a_o[i].val();
                    self.y_d[i].next = self.a_d[i].val();
                } else {
                    self.y_o[i].next = self.b_o[i].val();
                    self.y_d[i].next = self.b_d[i].val();
                }
            }
        }
        for i in 0..2 {
            self.y_t[i].next = self.zero_t.val();
            if !self.clear.val() {
                if self.sel.val() {
                    self.y_t[i].next = self.a_t[i].val();
                } else {
                    self.y_t[i].next = self.b_t[i].val();
                }
            }
        }
        self.y_j.next = self.zero_j.val();
        if !self.clear.val() {
            if self.sel.val() {
                self.y_j.next = self.a_j.val();
            } else {
                self.y_j.next = self.b_j.val();
            }
        }
    }
}

/// The order key of every field of a float bundle (`N`-bit codes; arrays as [`ReboundAcc`]'s, without
/// `j`), combinational: the code with its magnitude bits inverted when its sign is set
/// (`golden::bundle::rebound::float_order_key`). Keys compare as two's-complement integers in the
/// numeric order of the codes, `-0` below `+0`, so the fixed datapath's signed `min` and `max` are the
/// float hull's; the map is its own inverse, so the same block turns a hull of keys back into codes.
#[derive(LogicBlock)]
pub struct OrderKeys<const N: usize> {
    pub x_o: [Signal<In, Bits<N>>; 6],
    pub x_d: [Signal<In, Bits<N>>; 6],
    pub x_t: [Signal<In, Bits<N>>; 2],
    pub k_o: [Signal<Out, Bits<N>>; 6],
    pub k_d: [Signal<Out, Bits<N>>; 6],
    pub k_t: [Signal<Out, Bits<N>>; 2],
    msb: Constant<Bits<N>>,
    mag: Constant<Bits<N>>,
}

impl<const N: usize> Default for OrderKeys<N> {
    fn default() -> Self {
        Self {
            x_o: Default::default(),
            x_d: Default::default(),
            x_t: Default::default(),
            k_o: Default::default(),
            k_d: Default::default(),
            k_t: Default::default(),
            msb: Constant::new(bits(1 << (N - 1))),
            mag: Constant::new(bits((1 << (N - 1)) - 1)),
        }
    }
}

impl<const N: usize> Logic for OrderKeys<N> {
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..6 {
            self.k_o[i].next = self.x_o[i].val();
            if (self.x_o[i].val() & self.msb.val()).any() {
                self.k_o[i].next = self.x_o[i].val() ^ self.mag.val();
            }
            self.k_d[i].next = self.x_d[i].val();
            if (self.x_d[i].val() & self.msb.val()).any() {
                self.k_d[i].next = self.x_d[i].val() ^ self.mag.val();
            }
        }
        for i in 0..2 {
            self.k_t[i].next = self.x_t[i].val();
            if (self.x_t[i].val() & self.msb.val()).any() {
                self.k_t[i].next = self.x_t[i].val() ^ self.mag.val();
            }
        }
    }
}

/// The gatherer of a split job's re-bounded bundle; see the module documentation.
///
/// # Inputs
/// - `clock`, `rst` (synchronous, registered as the answer is: the bundle being gathered is dropped
///   once the clock's answer is folded, in the next clock; the result registers keep their contents, except that a job
///   whose last answer comes in the `rst` clock still loads them, as the control's report stage and
///   the model do);
/// - `a_*`, `b_*`: the rays entering the pair in this clock (rays A and B of a ray pair);
/// - the pair's answer in this clock, from the control (it chooses the bundle to fold into a register,
///   folded in the next clock):
///   `rays_back` (a ray pair's), `keep_a`, `keep_b` (ray A, ray B present and may hit), `last_back` (a
///   job's last pair's), `bundle_done` (a bundle's that reports without a split).
///
/// # Outputs
/// Result registers, loaded in the clock after the answer, when the control's report stage moves to
/// its result ports (the job's `done` in the next clock):
/// `rb_valid` (a split job that kept a ray) and the hull `rb_o`, `rb_d`, `rb_t`, `rb_j`; all zero
/// otherwise.
#[derive(LogicBlock)]
pub struct ReboundAcc<const G: usize, const D: usize, const T: usize> {
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    pub a_o: [Signal<In, Bits<G>>; 6],
    pub a_d: [Signal<In, Bits<D>>; 6],
    pub a_t: [Signal<In, Bits<T>>; 2],
    pub a_j: Signal<In, Bits<J_BITS>>,
    pub b_o: [Signal<In, Bits<G>>; 6],
    pub b_d: [Signal<In, Bits<D>>; 6],
    pub b_t: [Signal<In, Bits<T>>; 2],
    pub b_j: Signal<In, Bits<J_BITS>>,
    pub rays_back: Signal<In, Bit>,
    pub keep_a: Signal<In, Bit>,
    pub keep_b: Signal<In, Bit>,
    pub last_back: Signal<In, Bit>,
    pub bundle_done: Signal<In, Bit>,
    pub rb_valid: Signal<Out, Bit>,
    pub rb_o: [Signal<Out, Bits<G>>; 6],
    pub rb_d: [Signal<Out, Bits<D>>; 6],
    pub rb_t: [Signal<Out, Bits<T>>; 2],
    pub rb_j: Signal<Out, Bits<J_BITS>>,
    /// Rays A and B beside the pair, then (`pa`, `pb`, `pab`) rays A, B and their hull in the answer's
    /// clock.
    la: ItemLine<G, D, T>,
    lb: ItemLine<G, D, T>,
    pa: ItemLine<G, D, T>,
    pb: ItemLine<G, D, T>,
    pab: ItemLine<G, D, T>,
    hull_ab: Hull2<G, D, T>,
    /// The bundle to fold: B's alone or the pair's hull (`kept`), then A's when B is not kept (`fold`),
    /// chosen by the answer and registered (`op`), folded in the next clock.
    kept: ItemSel<G, D, T>,
    fold: ItemSel<G, D, T>,
    op: ItemLine<G, D, T>,
    /// The accumulator with this clock's bundle folded in, and the accumulator's next value.
    hull_acc: Hull2<G, D, T>,
    folded: ItemSel<G, D, T>,
    acc_next: ItemSel<G, D, T>,
    acc: ItemLine<G, D, T>,
    acc_valid: DFF<Bit>,
    res_next: ItemSel<G, D, T>,
    res: ItemLine<G, D, T>,
    res_valid: DFF<Bit>,
    /// The pair's answer (`op` holds a kept ray or pair) and `rst`, registered: the gatherer folds a
    /// clock behind the control.
    kept_q: DFF<Bit>,
    last_back_q: DFF<Bit>,
    bundle_done_q: DFF<Bit>,
    rst_q: DFF<Bit>,
    any_kept: Signal<Local, Bit>,
    valid_next: Signal<Local, Bit>,
}

impl<const G: usize, const D: usize, const T: usize> ReboundAcc<G, D, T> {
    /// The gatherer beside a pair of `latency` clocks (at least 2).
    pub fn new(latency: usize) -> Self {
        assert!(latency >= 2, "re-bounding needs a pair of 2 clocks or more");
        Self {
            clock: Default::default(),
            rst: Default::default(),
            a_o: Default::default(),
            a_d: Default::default(),
            a_t: Default::default(),
            a_j: Default::default(),
            b_o: Default::default(),
            b_d: Default::default(),
            b_t: Default::default(),
            b_j: Default::default(),
            rays_back: Default::default(),
            keep_a: Default::default(),
            keep_b: Default::default(),
            last_back: Default::default(),
            bundle_done: Default::default(),
            rb_valid: Default::default(),
            rb_o: Default::default(),
            rb_d: Default::default(),
            rb_t: Default::default(),
            rb_j: Default::default(),
            la: ItemLine::new(latency - 1),
            lb: ItemLine::new(latency - 1),
            pa: ItemLine::new(1),
            pb: ItemLine::new(1),
            pab: ItemLine::new(1),
            hull_ab: Default::default(),
            kept: Default::default(),
            fold: Default::default(),
            op: ItemLine::new(1),
            hull_acc: Default::default(),
            folded: Default::default(),
            acc_next: Default::default(),
            acc: ItemLine::new(1),
            acc_valid: Default::default(),
            res_next: Default::default(),
            res: ItemLine::new(1),
            res_valid: Default::default(),
            kept_q: Default::default(),
            last_back_q: Default::default(),
            bundle_done_q: Default::default(),
            rst_q: Default::default(),
            any_kept: Default::default(),
            valid_next: Default::default(),
        }
    }
}

impl<const G: usize, const D: usize, const T: usize> Logic for ReboundAcc<G, D, T> {
    #[hdl_gen]
    fn update(&mut self) {
        self.la.clock.next = self.clock.val();
        self.lb.clock.next = self.clock.val();
        self.pa.clock.next = self.clock.val();
        self.pb.clock.next = self.clock.val();
        self.pab.clock.next = self.clock.val();
        self.acc.clock.next = self.clock.val();
        self.op.clock.next = self.clock.val();
        self.res.clock.next = self.clock.val();
        dff_setup!(
            self,
            clock,
            acc_valid,
            res_valid,
            kept_q,
            last_back_q,
            bundle_done_q,
            rst_q
        );
        self.kept_q.d.next = self.rays_back.val() & (self.keep_a.val() | self.keep_b.val());
        self.last_back_q.d.next = self.last_back.val();
        self.bundle_done_q.d.next = self.bundle_done.val();
        self.rst_q.d.next = self.rst.val();

        // Beside the pair; the pair's hull formed one clock before the answer.
        for i in 0..6 {
            self.la.d_o[i].next = self.a_o[i].val();
            self.la.d_d[i].next = self.a_d[i].val();
            self.lb.d_o[i].next = self.b_o[i].val();
            self.lb.d_d[i].next = self.b_d[i].val();
            self.pa.d_o[i].next = self.la.q_o[i].val();
            self.pa.d_d[i].next = self.la.q_d[i].val();
            self.pb.d_o[i].next = self.lb.q_o[i].val();
            self.pb.d_d[i].next = self.lb.q_d[i].val();
            self.hull_ab.x_o[i].next = self.la.q_o[i].val();
            self.hull_ab.x_d[i].next = self.la.q_d[i].val();
            self.hull_ab.y_o[i].next = self.lb.q_o[i].val();
            self.hull_ab.y_d[i].next = self.lb.q_d[i].val();
            self.pab.d_o[i].next = self.hull_ab.h_o[i].val();
            self.pab.d_d[i].next = self.hull_ab.h_d[i].val();
        }
        for i in 0..2 {
            self.la.d_t[i].next = self.a_t[i].val();
            self.lb.d_t[i].next = self.b_t[i].val();
            self.pa.d_t[i].next = self.la.q_t[i].val();
            self.pb.d_t[i].next = self.lb.q_t[i].val();
            self.hull_ab.x_t[i].next = self.la.q_t[i].val();
            self.hull_ab.y_t[i].next = self.lb.q_t[i].val();
            self.pab.d_t[i].next = self.hull_ab.h_t[i].val();
        }
        self.la.d_j.next = self.a_j.val();
        self.lb.d_j.next = self.b_j.val();
        self.pa.d_j.next = self.la.q_j.val();
        self.pb.d_j.next = self.lb.q_j.val();
        self.hull_ab.x_j.next = self.la.q_j.val();
        self.hull_ab.y_j.next = self.lb.q_j.val();
        self.pab.d_j.next = self.hull_ab.h_j.val();

        // What the answer keeps, registered: both rays (their hull), or the one kept; folded in the next
        // clock.
        self.any_kept.next = self.kept_q.q.val();
        self.valid_next.next = self.acc_valid.q.val() | self.any_kept.val();
        self.kept.sel.next = self.keep_a.val();
        self.kept.clear.next = false;
        self.fold.sel.next = self.keep_b.val();
        self.fold.clear.next = false;
        // Into the accumulator (or as the first bundle of the job), and the results.
        self.folded.sel.next = self.acc_valid.q.val();
        self.folded.clear.next = false;
        self.acc_next.sel.next = self.any_kept.val();
        self.acc_next.clear.next = false;
        self.res_next.sel.next = self.last_back_q.q.val() | self.bundle_done_q.q.val();
        self.res_next.clear.next =
            self.bundle_done_q.q.val() | (self.last_back_q.q.val() & !self.valid_next.val());
        for i in 0..6 {
            self.kept.a_o[i].next = self.pab.q_o[i].val();
            self.kept.a_d[i].next = self.pab.q_d[i].val();
            self.kept.b_o[i].next = self.pb.q_o[i].val();
            self.kept.b_d[i].next = self.pb.q_d[i].val();
            self.fold.a_o[i].next = self.kept.y_o[i].val();
            self.fold.a_d[i].next = self.kept.y_d[i].val();
            self.fold.b_o[i].next = self.pa.q_o[i].val();
            self.fold.b_d[i].next = self.pa.q_d[i].val();
            self.hull_acc.x_o[i].next = self.acc.q_o[i].val();
            self.hull_acc.x_d[i].next = self.acc.q_d[i].val();
            self.op.d_o[i].next = self.fold.y_o[i].val();
            self.hull_acc.y_o[i].next = self.op.q_o[i].val();
            self.op.d_d[i].next = self.fold.y_d[i].val();
            self.hull_acc.y_d[i].next = self.op.q_d[i].val();
            self.folded.a_o[i].next = self.hull_acc.h_o[i].val();
            self.folded.a_d[i].next = self.hull_acc.h_d[i].val();
            self.folded.b_o[i].next = self.op.q_o[i].val();
            self.folded.b_d[i].next = self.op.q_d[i].val();
            self.acc_next.a_o[i].next = self.folded.y_o[i].val();
            self.acc_next.a_d[i].next = self.folded.y_d[i].val();
            self.acc_next.b_o[i].next = self.acc.q_o[i].val();
            self.acc_next.b_d[i].next = self.acc.q_d[i].val();
            self.acc.d_o[i].next = self.acc_next.y_o[i].val();
            self.acc.d_d[i].next = self.acc_next.y_d[i].val();
            self.res_next.a_o[i].next = self.acc_next.y_o[i].val();
            self.res_next.a_d[i].next = self.acc_next.y_d[i].val();
            self.res_next.b_o[i].next = self.res.q_o[i].val();
            self.res_next.b_d[i].next = self.res.q_d[i].val();
            self.res.d_o[i].next = self.res_next.y_o[i].val();
            self.res.d_d[i].next = self.res_next.y_d[i].val();
            self.rb_o[i].next = self.res.q_o[i].val();
            self.rb_d[i].next = self.res.q_d[i].val();
        }
        for i in 0..2 {
            self.kept.a_t[i].next = self.pab.q_t[i].val();
            self.kept.b_t[i].next = self.pb.q_t[i].val();
            self.fold.a_t[i].next = self.kept.y_t[i].val();
            self.fold.b_t[i].next = self.pa.q_t[i].val();
            self.hull_acc.x_t[i].next = self.acc.q_t[i].val();
            self.op.d_t[i].next = self.fold.y_t[i].val();
            self.hull_acc.y_t[i].next = self.op.q_t[i].val();
            self.folded.a_t[i].next = self.hull_acc.h_t[i].val();
            self.folded.b_t[i].next = self.op.q_t[i].val();
            self.acc_next.a_t[i].next = self.folded.y_t[i].val();
            self.acc_next.b_t[i].next = self.acc.q_t[i].val();
            self.acc.d_t[i].next = self.acc_next.y_t[i].val();
            self.res_next.a_t[i].next = self.acc_next.y_t[i].val();
            self.res_next.b_t[i].next = self.res.q_t[i].val();
            self.res.d_t[i].next = self.res_next.y_t[i].val();
            self.rb_t[i].next = self.res.q_t[i].val();
        }
        self.kept.a_j.next = self.pab.q_j.val();
        self.kept.b_j.next = self.pb.q_j.val();
        self.fold.a_j.next = self.kept.y_j.val();
        self.fold.b_j.next = self.pa.q_j.val();
        self.hull_acc.x_j.next = self.acc.q_j.val();
        self.op.d_j.next = self.fold.y_j.val();
        self.hull_acc.y_j.next = self.op.q_j.val();
        self.folded.a_j.next = self.hull_acc.h_j.val();
        self.folded.b_j.next = self.op.q_j.val();
        self.acc_next.a_j.next = self.folded.y_j.val();
        self.acc_next.b_j.next = self.acc.q_j.val();
        self.acc.d_j.next = self.acc_next.y_j.val();
        self.res_next.a_j.next = self.acc_next.y_j.val();
        self.res_next.b_j.next = self.res.q_j.val();
        self.res.d_j.next = self.res_next.y_j.val();
        self.rb_j.next = self.res.q_j.val();

        self.acc_valid.d.next = self.valid_next.val();
        self.res_valid.d.next = self.res_valid.q.val();
        if self.last_back_q.q.val() {
            self.acc_valid.d.next = false;
            self.res_valid.d.next = self.valid_next.val();
        }
        if self.bundle_done_q.q.val() {
            self.res_valid.d.next = false;
        }
        if self.rst_q.q.val() {
            self.acc_valid.d.next = false;
        }
        self.rb_valid.next = self.res_valid.q.val();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::slab::fix::{code, sext};
    use golden::bundle::fix::{BundleFixFormat, FixBundle};
    use golden::bundle::rebound::ScaledBundle;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    /// A bundle of raw codes weighted to the edges: t codes `+inf`, `-inf`, 0, 1, the largest finite
    /// ones, negative; direction codes at the extremes; exponents equal, near, far and at the ends.
    fn raw(bf: &BundleFixFormat, rng: &mut Pcg64, j0: i32) -> ScaledBundle {
        let (g, d, t) = (bf.base.g, bf.fd + 3, bf.base.t);
        let pick = |rng: &mut Pcg64, bits: u32, special: &[i64]| {
            if rng.gen_ratio(1, 3) {
                special[rng.gen_range(0..special.len())]
            } else {
                rng.gen_range(-(1i64 << (bits - 1))..1i64 << (bits - 1))
            }
        };
        let pinf = bf.base.t_pos_inf();
        let t_sp = [pinf, pinf - 1, pinf >> 3, 0, 1, 2, -1, -pinf - 1];
        let dm = 1i64 << (bf.fd + 1);
        let d_sp = [dm, -dm, 0, 1, -1, dm - 1, -(1i64 << (d - 1))];
        let g_sp = [0, -(1i64 << (g - 1)), (1i64 << (g - 1)) - 1];
        let half = 1i32 << (J_BITS - 1);
        ScaledBundle {
            q: FixBundle {
                o_lo: std::array::from_fn(|_| pick(rng, g, &g_sp)),
                o_hi: std::array::from_fn(|_| pick(rng, g, &g_sp)),
                d_lo: std::array::from_fn(|_| pick(rng, d, &d_sp)),
                d_hi: std::array::from_fn(|_| pick(rng, d, &d_sp)),
                t_lo: pick(rng, t, &t_sp),
                t_hi: pick(rng, t, &t_sp),
            },
            j: match rng.gen_range(0..6) {
                0 => j0,
                1 => (j0 + rng.gen_range(-2..=2)).clamp(-half, half - 1),
                2 => -half,
                3 => half - 1,
                _ => rng.gen_range(-half..half),
            },
        }
    }

    fn hull_rtl<const G: usize, const D: usize, const T: usize>(
        u: &mut Hull2<G, D, T>,
        x: &ScaledBundle,
        y: &ScaledBundle,
    ) -> ScaledBundle {
        let set = |u: &mut Hull2<G, D, T>, v: &ScaledBundle, first: bool| {
            let (o, dd, t, j) = if first {
                (&mut u.x_o, &mut u.x_d, &mut u.x_t, &mut u.x_j)
            } else {
                (&mut u.y_o, &mut u.y_d, &mut u.y_t, &mut u.y_j)
            };
            for a in 0..3 {
                o[a].next = bits::<G>(code(v.q.o_lo[a], G));
                o[a + 3].next = bits::<G>(code(v.q.o_hi[a], G));
                dd[a].next = bits::<D>(code(v.q.d_lo[a], D));
                dd[a + 3].next = bits::<D>(code(v.q.d_hi[a], D));
            }
            t[0].next = bits::<T>(code(v.q.t_lo, T));
            t[1].next = bits::<T>(code(v.q.t_hi, T));
            j.next = bits::<J_BITS>(code(v.j as i64, J_BITS));
        };
        set(u, x, true);
        set(u, y, false);
        assert!(simulate(u, 50), "the hull settles");
        let o = |k: usize| sext(u.h_o[k].val().to_u64(), G);
        let d = |k: usize| sext(u.h_d[k].val().to_u64(), D);
        ScaledBundle {
            q: FixBundle {
                o_lo: [o(0), o(1), o(2)],
                o_hi: [o(3), o(4), o(5)],
                d_lo: [d(0), d(1), d(2)],
                d_hi: [d(3), d(4), d(5)],
                t_lo: sext(u.h_t[0].val().to_u64(), T),
                t_hi: sext(u.h_t[1].val().to_u64(), T),
            },
            j: sext(u.h_j.val().to_u64(), J_BITS) as i32,
        }
    }

    fn hull_matches<const G: usize, const D: usize, const T: usize>(
        bf: BundleFixFormat,
        seed: u64,
    ) {
        let mut u = Hull2::<G, D, T>::default();
        u.connect_all();
        let mut rng = Pcg64::seed_from_u64(seed);
        let (mut shifted, mut saturated) = (0, 0);
        for k in 0..20_000 {
            let x = raw(&bf, &mut rng, 0);
            let y = raw(&bf, &mut rng, x.j);
            let want = x.hull(&bf, &y);
            let got = hull_rtl(&mut u, &x, &y);
            assert_eq!(got, want, "{}: case {k}: {x:?} hull {y:?}", bf.name());
            shifted += (x.j != y.j) as usize;
            // Saturation that the shift made (an input already at the largest finite code does not count).
            let sat = bf.base.t_pos_inf() - 1;
            saturated += (want.q.t_lo == sat && x.q.t_lo != sat && y.q.t_lo != sat) as usize;
        }
        println!(
            "{}: {shifted} shifted, {saturated} saturated t_lo",
            bf.name()
        );
        assert!(shifted > 10_000 && saturated > 100, "{shifted} {saturated}");
    }

    /// The float gatherer's hull (`OrderKeys` of both bundles, `Hull2` at one scale, `OrderKeys` back)
    /// equals `golden::bundle::rebound::float_hull` on binary16 codes weighted to the edges: both
    /// zeros, infinities, NaN codes, subnormals, the largest finite values, either sign.
    #[test]
    fn float_keys_and_hull2_are_the_model_float_hull() {
        use golden::bundle::float::FloatBundle;
        use golden::bundle::rebound::float_hull;
        use golden::format::float::FloatFormat;
        const N: usize = 16;
        let f = FloatFormat::FP16;
        let mut keys = OrderKeys::<N>::default();
        keys.connect_all();
        let mut hull = Hull2::<N, N, N>::default();
        hull.connect_all();
        let special = [
            0x0000, 0x8000, 0x7c00, 0xfc00, 0x7e01, 0x0001, 0x8001, 0x7bff, 0xfbff, 0x3c00,
        ];
        let mut rng = Pcg64::seed_from_u64(3);
        let pick = |rng: &mut Pcg64| -> u32 {
            if rng.gen_ratio(1, 2) {
                special[rng.gen_range(0..special.len())]
            } else {
                rng.gen_range(0..1u32 << N)
            }
        };
        let random = |rng: &mut Pcg64| FloatBundle {
            o_lo: std::array::from_fn(|_| pick(rng)),
            o_hi: std::array::from_fn(|_| pick(rng)),
            d_lo: std::array::from_fn(|_| pick(rng)),
            d_hi: std::array::from_fn(|_| pick(rng)),
            t_lo: pick(rng),
            t_hi: pick(rng),
        };
        // A bundle's fields in the gatherer's order (o: lo x y z, hi x y z; d likewise; t: lo, hi).
        let fields = |b: &FloatBundle| -> ([u32; 6], [u32; 6], [u32; 2]) {
            (
                [
                    b.o_lo[0], b.o_lo[1], b.o_lo[2], b.o_hi[0], b.o_hi[1], b.o_hi[2],
                ],
                [
                    b.d_lo[0], b.d_lo[1], b.d_lo[2], b.d_hi[0], b.d_hi[1], b.d_hi[2],
                ],
                [b.t_lo, b.t_hi],
            )
        };
        let map = |keys: &mut OrderKeys<N>, v: ([u32; 6], [u32; 6], [u32; 2])| {
            for i in 0..6 {
                keys.x_o[i].next = bits::<N>(v.0[i] as u64);
                keys.x_d[i].next = bits::<N>(v.1[i] as u64);
            }
            for i in 0..2 {
                keys.x_t[i].next = bits::<N>(v.2[i] as u64);
            }
            assert!(simulate(keys, 50), "the keys settle");
            let w = |x: Bits<N>| x.to_u64() as u32;
            (
                std::array::from_fn(|i| w(keys.k_o[i].val())),
                std::array::from_fn(|i| w(keys.k_d[i].val())),
                std::array::from_fn(|i| w(keys.k_t[i].val())),
            )
        };
        let mut ties = 0;
        for k in 0..20_000 {
            let (x, y) = (random(&mut rng), random(&mut rng));
            let (kx, ky) = (map(&mut keys, fields(&x)), map(&mut keys, fields(&y)));
            for i in 0..6 {
                hull.x_o[i].next = bits::<N>(kx.0[i] as u64);
                hull.x_d[i].next = bits::<N>(kx.1[i] as u64);
                hull.y_o[i].next = bits::<N>(ky.0[i] as u64);
                hull.y_d[i].next = bits::<N>(ky.1[i] as u64);
            }
            for i in 0..2 {
                hull.x_t[i].next = bits::<N>(kx.2[i] as u64);
                hull.y_t[i].next = bits::<N>(ky.2[i] as u64);
            }
            hull.x_j.next = bits::<J_BITS>(0);
            hull.y_j.next = bits::<J_BITS>(0);
            assert!(simulate(&mut hull, 50), "the hull settles");
            let w = |x: Bits<N>| x.to_u64() as u32;
            let kh: ([u32; 6], [u32; 6], [u32; 2]) = (
                std::array::from_fn(|i| w(hull.h_o[i].val())),
                std::array::from_fn(|i| w(hull.h_d[i].val())),
                std::array::from_fn(|i| w(hull.h_t[i].val())),
            );
            let got = map(&mut keys, kh);
            let want = float_hull(&f, &x, &y);
            assert_eq!(got, fields(&want), "case {k}: {x:x?} hull {y:x?}");
            ties += (x.o_lo[0] ^ y.o_lo[0] == 0x8000 && x.o_lo[0] & 0x7fff == 0) as usize;
        }
        assert!(ties > 50, "only {ties} cases of -0 against +0");
    }

    /// `Hull2` equals `ScaledBundle::hull` (the model's rule) on raw codes weighted to every edge, for
    /// the b8 and b12 widths.
    #[test]
    fn hull2_is_the_model_hull() {
        let [b8, b12, _] = BundleFixFormat::presets();
        hull_matches::<8, 9, 14>(b8, 1);
        hull_matches::<12, 13, 20>(b12, 2);
    }
}
