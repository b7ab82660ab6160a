//! `BundleStreamFloat`: the streaming results processor around the float bundle pair
//! ([`BundleFloat`]), in binary32, bfloat16 and binary16: the float counterpart of
//! [`crate::bundle::stream::BundleStream`], with the same control ([`crate::bundle::stream_ctl::StreamCtl`], here with a 16-entry split
//! queue), ports (names and
//! meaning), sequencing and contract; only the data ports carry float bit patterns (`N` bits each) in
//! place of grid codes, and `L` is the float pair's latency. **Results may leave in another order than
//! the jobs came.**
//!
//! Clock for clock `golden::bundle::stream::StreamModel` over the float datapath
//! (`golden::format::float::FloatFormat` as `PairDatapath`); what a job computes is the float pair's
//! bundle test and, for an undecided bundle, its two-ray answers ("may hit") on the job's active rays,
//! and the re-bounded bundle of the rays kept (`golden::bundle::rebound::rebound_float`).
//!
//! # Re-bounding
//! As the fixed processor, with the float rule of `golden::bundle::rebound`: the componentwise `min` of
//! the kept rays' `lo` fields and `max` of their `hi` fields, nothing rescaled (the rays of a bundle are
//! stored on one direction scale, where a float loses nothing). The gatherer is the fixed processor's
//! [`ReboundAcc`] on order keys ([`OrderKeys`]: a float code with its magnitude bits inverted when
//! negative compares as a two's-complement integer, `-0` below `+0`) with every exponent 0, where its
//! [`crate::bundle::rebound::Hull2`] rescales nothing and is a signed `min`/`max`; the hull's keys map
//! back to codes on the `rb_*` ports.
//!
//! # Parameters
//! `E`, `M`, `N = 1 + E + M`, `CUTS`, as [`BundleFloat`]; presets [`crate::BundleStreamFp32`],
//! [`crate::BundleStreamBf16`], [`crate::BundleStreamFp16`] over the 9-clock pair and
//! [`crate::BundleStreamFp16P13`] over the 13-clock one (module name `..._p13_n16x4`).
//!
//! # Inputs
//! As `BundleStream`'s: `clock`, `rst`; the ray store write port `ray_we`, `ray_addr` (`[5:4]` set,
//! `[3:0]` ray), `ray_o_lo`, `ray_o_hi`, `ray_d_lo`, `ray_d_hi` (arrays over x, y, z), `ray_t` (the ray
//! quantised as a tiny float bundle on its bundle's direction scale,
//! `golden::bundle::float::quantize_bundle_at` of a one-ray bundle: its `t_hi`), `ray_t_lo` (its `t_lo`,
//! for re-bounding); the job port `start`, `o_lo`, `o_hi`, `d_lo`, `d_hi`, `t_lo`, `t_hi`, `in_lo`, `in_hi`,
//! `out_lo`, `out_hi` (the bundle and box pair as the float pair takes them), `active` (16 bits),
//! `job_set` (2 bits), `tag` (8 bits).
//!
//! # Outputs
//! `ready`, `done`, `done_tag`, `all_hit`, `all_miss`, `split`, `mask`, as `BundleStream`'s; `rb_valid`
//! and the re-bounded bundle `rb_o_lo`, `rb_o_hi`, `rb_d_lo`, `rb_d_hi`, `rb_t_lo`, `rb_t_hi` (float
//! codes; no exponent), all zero when `rb_valid` is low.
//!
//! # Sequencing (`L` = [`bundle_float_latency`]`(CUTS)`: 9, or 13 for `_p13`)
//! A decided job reports `golden::bundle::stream::decided_latency(L) = L + 2` clocks after its start
//! (the pair, the answer's clock, the report stage); a split job of `k` pair clocks no earlier than
//! `golden::bundle::stream::split_latency(L, k) = 2L + 4 + k`. Up to `L` bundles are in the pair at once, so the split queue has 16 entries
//! (`golden::bundle::stream::stream_queue`): `ready` needs the queue plus the bundles in flight below
//! 16, which a stream of decided jobs never reaches, and the queue cannot overflow.

use crate::bundle::pair_float::{bundle_float_latency, BundleFloat, BUNDLE_FLOAT_DEPTHS};
use crate::bundle::ray_store::{ray_job_word_of, RayStore, TwinRam};
use crate::bundle::rebound::{OrderKeys, ReboundAcc, J_BITS};
use crate::bundle::stream::{
    decode_common_out, store_addr, stream_in_word_with, BundleStreamIo, STREAM_ADDR_BITS,
};
use crate::bundle::stream_ctl::{StreamCtl16, SET_BITS};
use golden::bundle::float::FloatBundle;
use golden::bundle::stream::{
    StreamIn, StreamJob, StreamOut, STREAM_RAYS, STREAM_SETS, STREAM_TAG_BITS,
};
use golden::format::float::FloatFormat;
use golden::slab::float::FloatBox;
use rust_hdl::prelude::*;

/// A float job on the job port.
pub type FloatStreamJob = StreamJob<FloatBundle, FloatBox>;
/// A clock's inputs of the float processor.
pub type FloatStreamIn = StreamIn<FloatBundle, FloatBox>;

/// The float streaming results processor; see the module documentation.
#[derive(LogicBlock)]
pub struct BundleStreamFloat<const E: usize, const M: usize, const N: usize, const CUTS: usize = 0>
{
    pub clock: Signal<In, Clock>,
    pub rst: Signal<In, Bit>,
    // ray store write port
    pub ray_we: Signal<In, Bit>,
    pub ray_addr: Signal<In, Bits<STREAM_ADDR_BITS>>,
    pub ray_o_lo: [Signal<In, Bits<N>>; 3],
    pub ray_o_hi: [Signal<In, Bits<N>>; 3],
    pub ray_d_lo: [Signal<In, Bits<N>>; 3],
    pub ray_d_hi: [Signal<In, Bits<N>>; 3],
    pub ray_t: Signal<In, Bits<N>>,
    pub ray_t_lo: Signal<In, Bits<N>>,
    // job port
    pub start: Signal<In, Bit>,
    pub o_lo: [Signal<In, Bits<N>>; 3],
    pub o_hi: [Signal<In, Bits<N>>; 3],
    pub d_lo: [Signal<In, Bits<N>>; 3],
    pub d_hi: [Signal<In, Bits<N>>; 3],
    pub t_lo: Signal<In, Bits<N>>,
    pub t_hi: Signal<In, Bits<N>>,
    pub in_lo: [Signal<In, Bits<N>>; 3],
    pub in_hi: [Signal<In, Bits<N>>; 3],
    pub out_lo: [Signal<In, Bits<N>>; 3],
    pub out_hi: [Signal<In, Bits<N>>; 3],
    pub active: Signal<In, Bits<STREAM_RAYS>>,
    pub job_set: Signal<In, Bits<SET_BITS>>,
    pub tag: Signal<In, Bits<STREAM_TAG_BITS>>,
    // results
    pub ready: Signal<Out, Bit>,
    pub done: Signal<Out, Bit>,
    pub done_tag: Signal<Out, Bits<STREAM_TAG_BITS>>,
    pub all_hit: Signal<Out, Bit>,
    pub all_miss: Signal<Out, Bit>,
    pub split: Signal<Out, Bit>,
    pub mask: Signal<Out, Bits<STREAM_RAYS>>,
    // the re-bounded bundle
    pub rb_valid: Signal<Out, Bit>,
    pub rb_o_lo: [Signal<Out, Bits<N>>; 3],
    pub rb_o_hi: [Signal<Out, Bits<N>>; 3],
    pub rb_d_lo: [Signal<Out, Bits<N>>; 3],
    pub rb_d_hi: [Signal<Out, Bits<N>>; 3],
    pub rb_t_lo: Signal<Out, Bits<N>>,
    pub rb_t_hi: Signal<Out, Bits<N>>,
    // the pair, the ray store (bank A: ray A, bank B: ray B), the control and the gatherer
    pair: BundleFloat<E, M, N, CUTS>,
    store: RayStore<N, N, N, STREAM_ADDR_BITS>,
    store_t_lo: TwinRam<N, STREAM_ADDR_BITS>,
    ctl: StreamCtl16<N>,
    /// The gatherer on order keys (one direction scale: every exponent 0), the keys of rays A and B
    /// as they enter the pair, and the hull's codes from its keys.
    rebound: ReboundAcc<N, N, N>,
    key_a: OrderKeys<N>,
    key_b: OrderKeys<N>,
    code_rb: OrderKeys<N>,
    zero_j: Constant<Bits<J_BITS>>,
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize>
    BundleStreamFloat<E, M, N, CUTS>
{
    /// The processor (the format is the parameters').
    pub fn new() -> Self {
        Self {
            clock: Default::default(),
            rst: Default::default(),
            ray_we: Default::default(),
            ray_addr: Default::default(),
            ray_o_lo: Default::default(),
            ray_o_hi: Default::default(),
            ray_d_lo: Default::default(),
            ray_d_hi: Default::default(),
            ray_t: Default::default(),
            ray_t_lo: Default::default(),
            start: Default::default(),
            o_lo: Default::default(),
            o_hi: Default::default(),
            d_lo: Default::default(),
            d_hi: Default::default(),
            t_lo: Default::default(),
            t_hi: Default::default(),
            in_lo: Default::default(),
            in_hi: Default::default(),
            out_lo: Default::default(),
            out_hi: Default::default(),
            active: Default::default(),
            job_set: Default::default(),
            tag: Default::default(),
            ready: Default::default(),
            done: Default::default(),
            done_tag: Default::default(),
            all_hit: Default::default(),
            all_miss: Default::default(),
            split: Default::default(),
            mask: Default::default(),
            rb_valid: Default::default(),
            rb_o_lo: Default::default(),
            rb_o_hi: Default::default(),
            rb_d_lo: Default::default(),
            rb_d_hi: Default::default(),
            rb_t_lo: Default::default(),
            rb_t_hi: Default::default(),
            pair: BundleFloat::new(),
            store: Default::default(),
            store_t_lo: Default::default(),
            ctl: StreamCtl16::new(bundle_float_latency(CUTS)),
            rebound: ReboundAcc::new(bundle_float_latency(CUTS)),
            key_a: Default::default(),
            key_b: Default::default(),
            code_rb: Default::default(),
            zero_j: Constant::new(bits(0)),
        }
    }

    /// The block's format.
    pub fn format() -> FloatFormat {
        FloatFormat::new(E as u32, M as u32).expect("valid format")
    }
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> Default
    for BundleStreamFloat<E, M, N, CUTS>
{
    fn default() -> Self {
        Self::new()
    }
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> Logic
    for BundleStreamFloat<E, M, N, CUTS>
{
    #[hdl_gen]
    fn update(&mut self) {
        self.pair.clock.next = self.clock.val();
        self.pair.rst.next = self.rst.val();
        self.ctl.clock.next = self.clock.val();
        self.ctl.rst.next = self.rst.val();

        // The ray store: both banks written together, read at the control's addresses.
        self.store.clock.next = self.clock.val();
        self.store.we.next = self.ray_we.val();
        self.store.waddr.next = self.ray_addr.val();
        self.store.w_t.next = self.ray_t.val();
        for i in 0..3 {
            self.store.w_o_lo[i].next = self.ray_o_lo[i].val();
            self.store.w_o_hi[i].next = self.ray_o_hi[i].val();
            self.store.w_d_lo[i].next = self.ray_d_lo[i].val();
            self.store.w_d_hi[i].next = self.ray_d_hi[i].val();
        }
        self.store.addr_a.next = self.ctl.addr_a.val();
        self.store.addr_b.next = self.ctl.addr_b.val();
        self.store_t_lo.clock.next = self.clock.val();
        self.store_t_lo.we.next = self.ray_we.val();
        self.store_t_lo.waddr.next = self.ray_addr.val();
        self.store_t_lo.w.next = self.ray_t_lo.val();
        self.store_t_lo.addr_a.next = self.ctl.addr_a.val();
        self.store_t_lo.addr_b.next = self.ctl.addr_b.val();

        // The gatherer: the rays' keys as they enter the pair, and the control's reading of its answer.
        for i in 0..3 {
            self.key_a.x_o[i].next = self.store.a_o_lo[i].val();
            self.key_a.x_o[i + 3].next = self.store.a_o_hi[i].val();
            self.key_a.x_d[i].next = self.store.a_d_lo[i].val();
            self.key_a.x_d[i + 3].next = self.store.a_d_hi[i].val();
            self.key_b.x_o[i].next = self.store.b_o_lo[i].val();
            self.key_b.x_o[i + 3].next = self.store.b_o_hi[i].val();
            self.key_b.x_d[i].next = self.store.b_d_lo[i].val();
            self.key_b.x_d[i + 3].next = self.store.b_d_hi[i].val();
        }
        self.key_a.x_t[0].next = self.store_t_lo.a.val();
        self.key_a.x_t[1].next = self.store.a_t.val();
        self.key_b.x_t[0].next = self.store_t_lo.b.val();
        self.key_b.x_t[1].next = self.store.b_t.val();
        self.rebound.clock.next = self.clock.val();
        self.rebound.rst.next = self.rst.val();
        for i in 0..6 {
            self.rebound.a_o[i].next = self.key_a.k_o[i].val();
            self.rebound.a_d[i].next = self.key_a.k_d[i].val();
            self.rebound.b_o[i].next = self.key_b.k_o[i].val();
            self.rebound.b_d[i].next = self.key_b.k_d[i].val();
            self.code_rb.x_o[i].next = self.rebound.rb_o[i].val();
            self.code_rb.x_d[i].next = self.rebound.rb_d[i].val();
        }
        for i in 0..2 {
            self.rebound.a_t[i].next = self.key_a.k_t[i].val();
            self.rebound.b_t[i].next = self.key_b.k_t[i].val();
            self.code_rb.x_t[i].next = self.rebound.rb_t[i].val();
        }
        self.rebound.a_j.next = self.zero_j.val();
        self.rebound.b_j.next = self.zero_j.val();
        self.rebound.rays_back.next = self.ctl.ans_rays.val();
        self.rebound.keep_a.next = self.ctl.ans_keep_a.val();
        self.rebound.keep_b.next = self.ctl.ans_keep_b.val();
        self.rebound.last_back.next = self.ctl.ans_last.val();
        self.rebound.bundle_done.next = self.ctl.ans_done.val();

        // The control: the job port's control fields and the pair's answer.
        self.ctl.start.next = self.start.val();
        self.ctl.active.next = self.active.val();
        self.ctl.job_set.next = self.job_set.val();
        self.ctl.tag.next = self.tag.val();
        for i in 0..3 {
            self.ctl.out_lo[i].next = self.out_lo[i].val();
            self.ctl.out_hi[i].next = self.out_hi[i].val();
        }
        self.ctl.p_valid.next = self.pair.valid_out.val();
        self.ctl.p_tag.next = self.pair.tag_out.val();
        self.ctl.p_all_hit.next = self.pair.all_hit.val();
        self.ctl.p_all_miss.next = self.pair.all_miss.val();

        // The pair's inputs: a ray pair (from the store's banks) when the control issues one, else the
        // job port's bundle.
        self.pair.valid_in.next = self.ctl.issue.val() | self.ctl.take.val();
        self.pair.two_rays.next = self.ctl.issue.val();
        self.pair.tag_in.next = self.ctl.issue_tag.val();
        self.pair.t_lo.next = self.t_lo.val();
        if self.ctl.issue.val() {
            self.pair.t_hi.next = self.store.a_t.val();
        } else {
            self.pair.t_hi.next = self.t_hi.val();
        }
        self.pair.r_t.next = self.store.b_t.val();
        for i in 0..3 {
            if self.ctl.issue.val() {
                self.pair.o_lo[i].next = self.store.a_o_lo[i].val();
                self.pair.o_hi[i].next = self.store.a_o_hi[i].val();
                self.pair.d_lo[i].next = self.store.a_d_lo[i].val();
                self.pair.d_hi[i].next = self.store.a_d_hi[i].val();
                self.pair.out_lo[i].next = self.ctl.issue_lo[i].val();
                self.pair.out_hi[i].next = self.ctl.issue_hi[i].val();
            } else {
                self.pair.o_lo[i].next = self.o_lo[i].val();
                self.pair.o_hi[i].next = self.o_hi[i].val();
                self.pair.d_lo[i].next = self.d_lo[i].val();
                self.pair.d_hi[i].next = self.d_hi[i].val();
                self.pair.out_lo[i].next = self.out_lo[i].val();
                self.pair.out_hi[i].next = self.out_hi[i].val();
            }
            self.pair.r_o_lo[i].next = self.store.b_o_lo[i].val();
            self.pair.r_o_hi[i].next = self.store.b_o_hi[i].val();
            self.pair.r_d_lo[i].next = self.store.b_d_lo[i].val();
            self.pair.r_d_hi[i].next = self.store.b_d_hi[i].val();
            self.pair.in_lo[i].next = self.in_lo[i].val();
            self.pair.in_hi[i].next = self.in_hi[i].val();
        }

        self.ready.next = self.ctl.ready.val();
        self.done.next = self.ctl.done.val();
        self.done_tag.next = self.ctl.done_tag.val();
        self.all_hit.next = self.ctl.all_hit.val();
        self.all_miss.next = self.ctl.all_miss.val();
        self.split.next = self.ctl.split.val();
        self.mask.next = self.ctl.mask.val();
        self.rb_valid.next = self.rebound.rb_valid.val();
        for i in 0..3 {
            self.rb_o_lo[i].next = self.code_rb.k_o[i].val();
            self.rb_o_hi[i].next = self.code_rb.k_o[i + 3].val();
            self.rb_d_lo[i].next = self.code_rb.k_d[i].val();
            self.rb_d_hi[i].next = self.code_rb.k_d[i + 3].val();
        }
        self.rb_t_lo.next = self.code_rb.k_t[0].val();
        self.rb_t_hi.next = self.code_rb.k_t[1].val();
    }
}

/// The re-bounded bundle on a float processor's `rb_*` ports (`word(base, axis)` a port's value): the
/// bundle when `rb_valid` is high, `None` when it is low and every field is zero (what the block drives
/// then). Fields that are not zero while `rb_valid` is low decode as a bundle with every field
/// `u32::MAX` (wider than a 16-bit code, and a NaN in binary32, which no hull of quantised rays holds),
/// so that a comparison with the model catches a wrong `rb_valid` in either direction. The outer
/// `None`: a port is missing.
pub fn decode_rebound_float(
    word: impl Fn(&str, usize) -> Option<u64>,
) -> Option<Option<FloatBundle>> {
    let arr = |base: &str| -> Option<[u32; 3]> {
        Some([
            word(base, 0)? as u32,
            word(base, 1)? as u32,
            word(base, 2)? as u32,
        ])
    };
    let fb = FloatBundle {
        o_lo: arr("rb_o_lo")?,
        o_hi: arr("rb_o_hi")?,
        d_lo: arr("rb_d_lo")?,
        d_hi: arr("rb_d_hi")?,
        t_lo: word("rb_t_lo", 0)? as u32,
        t_hi: word("rb_t_hi", 0)? as u32,
    };
    let valid = word("rb_valid", 0)? != 0;
    Some(if valid {
        Some(fb)
    } else if fb == FloatBundle::default() {
        None
    } else {
        Some(FloatBundle {
            o_lo: [u32::MAX; 3],
            o_hi: [u32::MAX; 3],
            d_lo: [u32::MAX; 3],
            d_hi: [u32::MAX; 3],
            t_lo: u32::MAX,
            t_hi: u32::MAX,
        })
    })
}

/// The value of input port `port` in one clock, for a float processor.
pub fn stream_float_in_word(port: &str, input: &FloatStreamIn) -> Option<u64> {
    stream_in_word_with(port, input, |base, i, r, j| {
        if base == "ray_t_lo" {
            return Some(r.t_lo as u64);
        }
        let (inner, outer) = (&j.boxes.inner, &j.boxes.outer);
        let w = |x: u32| x as u64;
        let boxes = [&inner.lo, &inner.hi, &outer.lo, &outer.hi];
        ray_job_word_of(base, i, r, &j.bundle, boxes, (w, w, w))
    })
}

impl<const E: usize, const M: usize, const N: usize, const CUTS: usize> BundleStreamIo
    for BundleStreamFloat<E, M, N, CUTS>
{
    type Dp = FloatFormat;
    const PAIR_LATENCY: usize = bundle_float_latency(CUTS);
    const CUTS: usize = CUTS;
    const PAIR_DEPTHS: &'static [(usize, &'static str)] = &BUNDLE_FLOAT_DEPTHS;

    fn for_format(f: &FloatFormat) -> Self {
        assert_eq!(
            *f,
            Self::format(),
            "BundleStreamFloat<{E},{M},{N},{CUTS}> is not for format {}",
            f.name()
        );
        Self::new()
    }

    fn format_name(f: &FloatFormat) -> String {
        f.name()
    }

    fn set_clock(&mut self, high: bool) {
        self.clock.next = Clock { clk: high };
    }

    fn drive(&mut self, input: &FloatStreamIn) {
        let w = |x: u32| bits::<N>(x as u64);
        let (set, ray, r) = input.write.unwrap_or_default();
        self.rst.next = input.reset;
        self.ray_we.next = input.write.is_some();
        self.ray_addr.next = bits::<STREAM_ADDR_BITS>(store_addr(set, ray));
        let j = input.start.unwrap_or_default();
        let (b, p) = (&j.bundle, &j.boxes);
        self.start.next = input.start.is_some();
        self.active.next = bits::<STREAM_RAYS>(j.active as u64);
        self.job_set.next = bits::<SET_BITS>(j.set as u64 % STREAM_SETS as u64);
        self.tag.next = bits::<STREAM_TAG_BITS>(j.tag as u64);
        for a in 0..3 {
            self.ray_o_lo[a].next = w(r.o_lo[a]);
            self.ray_o_hi[a].next = w(r.o_hi[a]);
            self.ray_d_lo[a].next = w(r.d_lo[a]);
            self.ray_d_hi[a].next = w(r.d_hi[a]);
            self.o_lo[a].next = w(b.o_lo[a]);
            self.o_hi[a].next = w(b.o_hi[a]);
            self.d_lo[a].next = w(b.d_lo[a]);
            self.d_hi[a].next = w(b.d_hi[a]);
            self.in_lo[a].next = w(p.inner.lo[a]);
            self.in_hi[a].next = w(p.inner.hi[a]);
            self.out_lo[a].next = w(p.outer.lo[a]);
            self.out_hi[a].next = w(p.outer.hi[a]);
        }
        self.ray_t.next = w(r.t_hi);
        self.ray_t_lo.next = w(r.t_lo);
        self.t_lo.next = w(b.t_lo);
        self.t_hi.next = w(b.t_hi);
    }

    fn outputs(&self) -> StreamOut<FloatBundle> {
        StreamOut {
            ready: self.ready.val(),
            done: self.done.val(),
            tag: self.done_tag.val().to_u64() as u8,
            all_hit: self.all_hit.val(),
            all_miss: self.all_miss.val(),
            split: self.split.val(),
            mask: self.mask.val().to_u64() as u16,
            rebound: decode_rebound_float(|base, i| {
                Some(match base {
                    "rb_valid" => self.rb_valid.val() as u64,
                    "rb_o_lo" => self.rb_o_lo[i].val().to_u64(),
                    "rb_o_hi" => self.rb_o_hi[i].val().to_u64(),
                    "rb_d_lo" => self.rb_d_lo[i].val().to_u64(),
                    "rb_d_hi" => self.rb_d_hi[i].val().to_u64(),
                    "rb_t_lo" => self.rb_t_lo.val().to_u64(),
                    "rb_t_hi" => self.rb_t_hi.val().to_u64(),
                    _ => return None,
                })
            })
            .expect("every re-bounding port"),
        }
    }

    fn decode_out(
        _: &FloatFormat,
        word: &dyn Fn(&str) -> Option<u64>,
    ) -> Option<StreamOut<FloatBundle>> {
        let rebound = decode_rebound_float(|base, i| match base {
            "rb_valid" | "rb_t_lo" | "rb_t_hi" => word(base),
            _ => word(&format!("{base}_{i}")),
        })?;
        Some(StreamOut {
            rebound,
            ..decode_common_out(word)?
        })
    }

    fn in_word(_: &FloatFormat, port: &str, input: &FloatStreamIn) -> Option<u64> {
        stream_float_in_word(port, input)
    }
}
