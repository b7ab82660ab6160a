//! `FpRecip`: the directed reciprocal of the float cull-plane datapath, bit for bit
//! `golden::plane::float::recip_float` — a table lookup and exponent arithmetic, no division. Registered,
//! [`FP_RECIP_LATENCY`] clock; one result per clock.
//!
//! # Parameters
//! `E >= 4`, `M`, `N = 1 + E + M <= 32`: the format. The table's index bits `R` are a constructor argument,
//! `1 <= R <= min(M, 8)` (`golden::plane::float::CullFloatFormat::over` picks `min(M, 8)`).
//!
//! # Inputs / outputs
//! `clock`, `rst` (synchronous, clears the valid bits), `valid_in`, `tag_in` (16 bits); `mag` (the sign bit is ignored: the model's `recip_float` reads
//! exponent and fraction only), `upper` (1: an upper bound of `1/mag`, 0: a lower bound). Out, registered:
//! `valid_out`, `tag_out`, `r`.
//!
//! # Datapath
//! Two ROMs of `2^R` entries (rust-hdl's `ROM` widget, a `case` in Verilog), indexed by the top `R` fraction
//! bits: the lower-bound half and the upper-bound half of `golden::plane::float::recip_table_entry`, each
//! entry `M + 1` bits (bit `M`: the entry's exponent is `-1`, else `0`; bits `M-1..0`: its fraction). With
//! `be` the biased exponent of `mag` and `k = 2 bias + delta` (`2^E - 2` or `2^E - 3`), the result's biased
//! exponent is `k - be`, at most `2^E - 3` (never overflows); `be >= k` underflows to `+0` (lower) or the
//! smallest normal (upper). Specials: NaN gives the canonical NaN, `inf` gives `+0`, a zero or subnormal
//! gives `+inf` (upper) or `2^(bias-1)` (lower).

use crate::TAG_BITS;
use golden::format::float::FloatFormat;
use golden::plane::float::{recip_table_entry, CullFloatFormat};
use rust_hdl::prelude::*;
use rust_hdl::widgets::prelude::ROM;
use std::collections::BTreeMap;

/// Clocks from `mag` in to `r` out.
pub const FP_RECIP_LATENCY: usize = 1;

/// Address width of the tables (`R <= 8`).
pub const RECIP_ADDR_BITS: usize = 8;

/// Registered directed reciprocal; see the module documentation.
#[derive(LogicBlock)]
pub struct FpRecip<const E: usize, const M: usize, const N: usize> {
    pub clock: Signal<In, Clock>,
    /// Synchronous reset: high at a clock edge clears every valid bit (data registers keep their values).
    pub rst: Signal<In, Bit>,
    pub valid_in: Signal<In, Bit>,
    pub tag_in: Signal<In, Bits<TAG_BITS>>,
    pub mag: Signal<In, Bits<N>>,
    pub upper: Signal<In, Bit>,
    pub valid_out: Signal<Out, Bit>,
    pub tag_out: Signal<Out, Bits<TAG_BITS>>,
    pub r: Signal<Out, Bits<N>>,
    // constants
    frac_bits: Constant<Bits<8>>,
    idx_shift: Constant<Bits<8>>,
    mag_mask: Constant<Bits<N>>,
    frac_mask: Constant<Bits<N>>,
    exp_mask: Constant<Bits<N>>,
    delta_bit: Constant<Bits<N>>,
    inf_n: Constant<Bits<N>>,
    nan_n: Constant<Bits<N>>,
    zero_n: Constant<Bits<N>>,
    min_normal: Constant<Bits<N>>,
    sub_lower: Constant<Bits<N>>,
    k0: Constant<Bits<N>>,
    k1: Constant<Bits<N>>,
    // tables
    rom_lo: ROM<Bits<N>, RECIP_ADDR_BITS>,
    rom_hi: ROM<Bits<N>, RECIP_ADDR_BITS>,
    // datapath
    be: Signal<Local, Bits<N>>,
    idx: Signal<Local, Bits<N>>,
    // the index's upper bits are zero by construction (lint: read, by name, as unused)
    unused_idx: Signal<Local, Bit>,
    entry: Signal<Local, Bits<N>>,
    k: Signal<Local, Bits<N>>,
    rbe: Signal<Local, Bits<N>>,
    r_q: DFF<Bits<N>>,
    valid_q: DFF<Bit>,
    tag_q: DFF<Bits<TAG_BITS>>,
}

impl<const E: usize, const M: usize, const N: usize> FpRecip<E, M, N> {
    /// A unit with `r_bits` table index bits (`1 <= r_bits <= min(M, 8)`).
    pub fn new(r_bits: u32) -> Self {
        let f = FloatFormat::new(E as u32, M as u32).expect("valid format");
        assert!(
            N as u32 == f.width() && E >= 4 && N <= 32,
            "FpRecip<{E},{M},{N}>: need N = 1+E+M <= 32 and E >= 4"
        );
        assert!(
            r_bits >= 1 && r_bits as usize <= M.min(RECIP_ADDR_BITS),
            "FpRecip<{E},{M},{N}>: R = {r_bits} must be in 1..=min(M, 8)"
        );
        let cf = CullFloatFormat::new(f, r_bits).expect("R in range");
        let c = |v: u64| Constant::new(bits::<N>(v));
        let table = |upper: bool| {
            let mut t = BTreeMap::new();
            for i in 0..(1u64 << r_bits) {
                let (delta, frac) = recip_table_entry(&cf.f, cf.r, i)[usize::from(upper)];
                assert!(delta == 0 || delta == -1, "table exponent {delta}");
                let word = ((u64::from(delta == -1)) << M) | frac as u64;
                t.insert(bits::<RECIP_ADDR_BITS>(i), bits::<N>(word));
            }
            ROM::new(t)
        };
        let two_bias = (2 * f.bias()) as u64;
        Self {
            clock: Default::default(),
            rst: Default::default(),
            valid_in: Default::default(),
            tag_in: Default::default(),
            mag: Default::default(),
            upper: Default::default(),
            valid_out: Default::default(),
            tag_out: Default::default(),
            r: Default::default(),
            frac_bits: Constant::new(bits::<8>(M as u64)),
            idx_shift: Constant::new(bits::<8>((M - r_bits as usize) as u64)),
            mag_mask: c((1 << (N - 1)) - 1),
            frac_mask: c((1 << M) - 1),
            exp_mask: c((1 << E) - 1),
            delta_bit: c(1 << M),
            inf_n: c(f.inf(false) as u64),
            nan_n: c(f.nan() as u64),
            zero_n: c(0),
            min_normal: c(f.pack(false, 1, 0) as u64),
            sub_lower: c(f.pack(false, (2 * f.bias() - 1) as u32, 0) as u64),
            k0: c(two_bias),
            k1: c(two_bias - 1),
            rom_lo: table(false),
            rom_hi: table(true),
            be: Default::default(),
            idx: Default::default(),
            unused_idx: Default::default(),
            entry: Default::default(),
            k: Default::default(),
            rbe: Default::default(),
            r_q: Default::default(),
            valid_q: Default::default(),
            tag_q: Default::default(),
        }
    }
}

impl<const E: usize, const M: usize, const N: usize> Logic for FpRecip<E, M, N> {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, r_q, valid_q, tag_q);
        self.be.next = (self.mag.val() >> self.frac_bits.val()) & self.exp_mask.val();
        self.idx.next = (self.mag.val() & self.frac_mask.val()) >> self.idx_shift.val();
        self.rom_lo.address.next = self.idx.val().get_bits::<8>(0);
        self.rom_hi.address.next = self.idx.val().get_bits::<8>(0);
        self.unused_idx.next = self.idx.val().any();
        if self.upper.val() {
            self.entry.next = self.rom_hi.data.val();
        } else {
            self.entry.next = self.rom_lo.data.val();
        }
        if (self.entry.val() & self.delta_bit.val()).any() {
            self.k.next = self.k1.val();
        } else {
            self.k.next = self.k0.val();
        }
        self.rbe.next = self.k.val() - self.be.val();
        if (self.mag.val() & self.mag_mask.val()) > self.inf_n.val() {
            self.r_q.d.next = self.nan_n.val();
        } else if (self.mag.val() & self.mag_mask.val()) == self.inf_n.val() {
            self.r_q.d.next = self.zero_n.val();
        } else if !self.be.val().any() {
            if self.upper.val() {
                self.r_q.d.next = self.inf_n.val();
            } else {
                self.r_q.d.next = self.sub_lower.val();
            }
        } else if self.be.val() >= self.k.val() {
            if self.upper.val() {
                self.r_q.d.next = self.min_normal.val();
            } else {
                self.r_q.d.next = self.zero_n.val();
            }
        } else {
            self.r_q.d.next = (self.rbe.val() << self.frac_bits.val())
                | (self.entry.val() & self.frac_mask.val());
        }
        self.valid_q.d.next = self.valid_in.val() & !self.rst.val();
        self.tag_q.d.next = self.tag_in.val();
        self.valid_out.next = self.valid_q.q.val();
        self.tag_out.next = self.tag_q.q.val();
        self.r.next = self.r_q.q.val();
    }
}
