//! `QuotTree`: the largest (or smallest) of eight optional fractions, a pipelined tree of
//! cross-multiplied comparisons ([`QuotCmp`]), three clocks. The entry (max) and exit (min) trees of the
//! fraction option of the cull-plane tester ([`crate::plane::quot`]).
//!
//! # Inputs
//! `clock`; per slot `i < 8`: `v[i]` (the slot holds a fraction), `n[i]` (signed numerator, `AB` bits),
//! `d[i]` (positive denominator, `MB` bits). An empty slot stands for `-inf` in a max tree and `+inf` in
//! a min tree: it never wins against a full one.
//!
//! # Outputs (three clocks after the inputs)
//! `v_out`, `n_out`, `d_out`: the winning slot, exactly (no rounding anywhere). Ties go to the lower slot;
//! [`quot_order_tree`](golden::plane::quot::quot_order_tree) is the native model, with the same tie-breaking.
//!
//! # Structure
//! Seven [`QuotPick`] nodes, each followed by a register (`_q`): nodes 0-3 compare slot pairs, 4-5 the
//! registers of 0-3, 6 those of 4-5. Every comparator reads registers or inputs only (a comparator fed
//! through logic that reads other children in the same `always` block is a combinational cycle at block
//! granularity for Verilator, UNOPTFLAT). Slots that a parent ties to constants (unused planes) take
//! their comparators with them in synthesis.

use crate::plane::quot_pick::QuotPick;
pub use golden::plane::quot::QUOT_TREE_SLOTS;
use rust_hdl::prelude::*;

/// Clocks from the slots in to the result out.
pub const QUOT_TREE_LATENCY: usize = 3;

/// Pipelined max or min of eight fractions; see the module documentation.
#[derive(LogicBlock)]
pub struct QuotTree<const AB: usize, const MB: usize> {
    pub clock: Signal<In, Clock>,
    pub v: [Signal<In, Bit>; QUOT_TREE_SLOTS],
    pub n: [Signal<In, Bits<AB>>; QUOT_TREE_SLOTS],
    pub d: [Signal<In, Bits<MB>>; QUOT_TREE_SLOTS],
    pub v_out: Signal<Out, Bit>,
    pub n_out: Signal<Out, Bits<AB>>,
    pub d_out: Signal<Out, Bits<MB>>,
    pick: [QuotPick<AB, MB>; 7],
    v_q: [DFF<Bit>; 7],
    n_q: [DFF<Bits<AB>>; 7],
    d_q: [DFF<Bits<MB>>; 7],
}

impl<const AB: usize, const MB: usize> QuotTree<AB, MB> {
    /// A min tree (`want_min`) or a max tree.
    pub fn new(want_min: bool) -> Self {
        Self {
            clock: Default::default(),
            v: Default::default(),
            n: Default::default(),
            d: Default::default(),
            v_out: Default::default(),
            n_out: Default::default(),
            d_out: Default::default(),
            pick: std::array::from_fn(|_| QuotPick::new(want_min)),
            v_q: Default::default(),
            n_q: Default::default(),
            d_q: Default::default(),
        }
    }
}

impl<const AB: usize, const MB: usize> Logic for QuotTree<AB, MB> {
    #[hdl_gen]
    fn update(&mut self) {
        for j in 0..7 {
            self.v_q[j].clock.next = self.clock.val();
            self.n_q[j].clock.next = self.clock.val();
            self.d_q[j].clock.next = self.clock.val();
            self.v_q[j].d.next = self.pick[j].v.val();
            self.n_q[j].d.next = self.pick[j].n.val();
            self.d_q[j].d.next = self.pick[j].d.val();
        }
        // Level 1: slot pairs.
        for j in 0..4 {
            self.pick[j].v0.next = self.v[2 * j].val();
            self.pick[j].n0.next = self.n[2 * j].val();
            self.pick[j].d0.next = self.d[2 * j].val();
            self.pick[j].v1.next = self.v[2 * j + 1].val();
            self.pick[j].n1.next = self.n[2 * j + 1].val();
            self.pick[j].d1.next = self.d[2 * j + 1].val();
        }
        // Levels 2 and 3: node 4 + j compares the registers of nodes 2j and 2j + 1.
        for j in 0..3 {
            self.pick[4 + j].v0.next = self.v_q[2 * j].q.val();
            self.pick[4 + j].n0.next = self.n_q[2 * j].q.val();
            self.pick[4 + j].d0.next = self.d_q[2 * j].q.val();
            self.pick[4 + j].v1.next = self.v_q[2 * j + 1].q.val();
            self.pick[4 + j].n1.next = self.n_q[2 * j + 1].q.val();
            self.pick[4 + j].d1.next = self.d_q[2 * j + 1].q.val();
        }
        self.v_out.next = self.v_q[6].q.val();
        self.n_out.next = self.n_q[6].q.val();
        self.d_out.next = self.d_q[6].q.val();
    }
}
