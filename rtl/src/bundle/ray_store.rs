//! `RayStore`: the ray store of the results processors, two banks of `2^A` rays (written together, one
//! ray a clock), so that any two rays are read in one clock: bank A at `addr_a`, bank B at `addr_b`.
//! Each field is a `rust_hdl::widgets::ramrom::ram::RAM` (synchronous read and write, one clock of read
//! latency, read before write: a read and a write of the same entry in one clock read the old ray),
//! block RAM or LUT RAM in synthesis. A ray is a quantised tiny bundle (`golden::bundle::fix::FixBundle`):
//! origin and direction floored and ceiled, and its `t_hi` (its `t_lo` is not needed in two-ray mode).
//!
//! # Inputs
//! `clock`; write port `we`, `waddr`, `w_o_lo`, `w_o_hi`, `w_d_lo`, `w_d_hi` (arrays over x, y, z),
//! `w_t` (written at the end of the clock); read addresses `addr_a`, `addr_b`.
//! # Outputs
//! `a_o_lo` .. `a_t`: bank A's entry `addr_a` of the previous clock; `b_o_lo` .. `b_t`: bank B's at
//! `addr_b`.

use rust_hdl::prelude::*;
use rust_hdl::widgets::ramrom::ram::RAM;

/// The two-bank ray store; see the module documentation.
#[derive(LogicBlock, Default)]
pub struct RayStore<const G: usize, const D: usize, const T: usize, const A: usize> {
    pub clock: Signal<In, Clock>,
    pub we: Signal<In, Bit>,
    pub waddr: Signal<In, Bits<A>>,
    pub w_o_lo: [Signal<In, Bits<G>>; 3],
    pub w_o_hi: [Signal<In, Bits<G>>; 3],
    pub w_d_lo: [Signal<In, Bits<D>>; 3],
    pub w_d_hi: [Signal<In, Bits<D>>; 3],
    pub w_t: Signal<In, Bits<T>>,
    pub addr_a: Signal<In, Bits<A>>,
    pub addr_b: Signal<In, Bits<A>>,
    pub a_o_lo: [Signal<Out, Bits<G>>; 3],
    pub a_o_hi: [Signal<Out, Bits<G>>; 3],
    pub a_d_lo: [Signal<Out, Bits<D>>; 3],
    pub a_d_hi: [Signal<Out, Bits<D>>; 3],
    pub a_t: Signal<Out, Bits<T>>,
    pub b_o_lo: [Signal<Out, Bits<G>>; 3],
    pub b_o_hi: [Signal<Out, Bits<G>>; 3],
    pub b_d_lo: [Signal<Out, Bits<D>>; 3],
    pub b_d_hi: [Signal<Out, Bits<D>>; 3],
    pub b_t: Signal<Out, Bits<T>>,
    ra_o_lo: [RAM<Bits<G>, A>; 3],
    ra_o_hi: [RAM<Bits<G>, A>; 3],
    ra_d_lo: [RAM<Bits<D>, A>; 3],
    ra_d_hi: [RAM<Bits<D>, A>; 3],
    ra_t: RAM<Bits<T>, A>,
    rb_o_lo: [RAM<Bits<G>, A>; 3],
    rb_o_hi: [RAM<Bits<G>, A>; 3],
    rb_d_lo: [RAM<Bits<D>, A>; 3],
    rb_d_hi: [RAM<Bits<D>, A>; 3],
    rb_t: RAM<Bits<T>, A>,
}

impl<const G: usize, const D: usize, const T: usize, const A: usize> Logic
    for RayStore<G, D, T, A>
{
    #[hdl_gen]
    fn update(&mut self) {
        for i in 0..3 {
            self.ra_o_lo[i].read_clock.next = self.clock.val();
            self.ra_o_lo[i].write_clock.next = self.clock.val();
            self.ra_o_lo[i].write_enable.next = self.we.val();
            self.ra_o_lo[i].write_address.next = self.waddr.val();
            self.ra_o_lo[i].write_data.next = self.w_o_lo[i].val();
            self.ra_o_lo[i].read_address.next = self.addr_a.val();
            self.a_o_lo[i].next = self.ra_o_lo[i].read_data.val();
            self.ra_o_hi[i].read_clock.next = self.clock.val();
            self.ra_o_hi[i].write_clock.next = self.clock.val();
            self.ra_o_hi[i].write_enable.next = self.we.val();
            self.ra_o_hi[i].write_address.next = self.waddr.val();
            self.ra_o_hi[i].write_data.next = self.w_o_hi[i].val();
            self.ra_o_hi[i].read_address.next = self.addr_a.val();
            self.a_o_hi[i].next = self.ra_o_hi[i].read_data.val();
            self.ra_d_lo[i].read_clock.next = self.clock.val();
            self.ra_d_lo[i].write_clock.next = self.clock.val();
            self.ra_d_lo[i].write_enable.next = self.we.val();
            self.ra_d_lo[i].write_address.next = self.waddr.val();
            self.ra_d_lo[i].write_data.next = self.w_d_lo[i].val();
            self.ra_d_lo[i].read_address.next = self.addr_a.val();
            self.a_d_lo[i].next = self.ra_d_lo[i].read_data.val();
            self.ra_d_hi[i].read_clock.next = self.clock.val();
            self.ra_d_hi[i].write_clock.next = self.clock.val();
            self.ra_d_hi[i].write_enable.next = self.we.val();
            self.ra_d_hi[i].write_address.next = self.waddr.val();
            self.ra_d_hi[i].write_data.next = self.w_d_hi[i].val();
            self.ra_d_hi[i].read_address.next = self.addr_a.val();
            self.a_d_hi[i].next = self.ra_d_hi[i].read_data.val();
            self.rb_o_lo[i].read_clock.next = self.clock.val();
            self.rb_o_lo[i].write_clock.next = self.clock.val();
            self.rb_o_lo[i].write_enable.next = self.we.val();
            self.rb_o_lo[i].write_address.next = self.waddr.val();
            self.rb_o_lo[i].write_data.next = self.w_o_lo[i].val();
            self.rb_o_lo[i].read_address.next = self.addr_b.val();
            self.b_o_lo[i].next = self.rb_o_lo[i].read_data.val();
            self.rb_o_hi[i].read_clock.next = self.clock.val();
            self.rb_o_hi[i].write_clock.next = self.clock.val();
            self.rb_o_hi[i].write_enable.next = self.we.val();
            self.rb_o_hi[i].write_address.next = self.waddr.val();
            self.rb_o_hi[i].write_data.next = self.w_o_hi[i].val();
            self.rb_o_hi[i].read_address.next = self.addr_b.val();
            self.b_o_hi[i].next = self.rb_o_hi[i].read_data.val();
            self.rb_d_lo[i].read_clock.next = self.clock.val();
            self.rb_d_lo[i].write_clock.next = self.clock.val();
            self.rb_d_lo[i].write_enable.next = self.we.val();
            self.rb_d_lo[i].write_address.next = self.waddr.val();
            self.rb_d_lo[i].write_data.next = self.w_d_lo[i].val();
            self.rb_d_lo[i].read_address.next = self.addr_b.val();
            self.b_d_lo[i].next = self.rb_d_lo[i].read_data.val();
            self.rb_d_hi[i].read_clock.next = self.clock.val();
            self.rb_d_hi[i].write_clock.next = self.clock.val();
            self.rb_d_hi[i].write_enable.next = self.we.val();
            self.rb_d_hi[i].write_address.next = self.waddr.val();
            self.rb_d_hi[i].write_data.next = self.w_d_hi[i].val();
            self.rb_d_hi[i].read_address.next = self.addr_b.val();
            self.b_d_hi[i].next = self.rb_d_hi[i].read_data.val();
        }
        self.ra_t.read_clock.next = self.clock.val();
        self.ra_t.write_clock.next = self.clock.val();
        self.ra_t.write_enable.next = self.we.val();
        self.ra_t.write_address.next = self.waddr.val();
        self.ra_t.write_data.next = self.w_t.val();
        self.ra_t.read_address.next = self.addr_a.val();
        self.a_t.next = self.ra_t.read_data.val();
        self.rb_t.read_clock.next = self.clock.val();
        self.rb_t.write_clock.next = self.clock.val();
        self.rb_t.write_enable.next = self.we.val();
        self.rb_t.write_address.next = self.waddr.val();
        self.rb_t.write_data.next = self.w_t.val();
        self.rb_t.read_address.next = self.addr_b.val();
        self.b_t.next = self.rb_t.read_data.val();
    }
}

/// One more field of every stored ray in two banks, as [`RayStore`] holds its fields (written together
/// at `waddr`, read at `addr_a` and `addr_b` with one clock of latency, read before write): what only
/// re-bounding needs (a ray's `t_lo`, its direction exponent).
#[derive(LogicBlock, Default)]
pub struct TwinRam<const W: usize, const A: usize> {
    pub clock: Signal<In, Clock>,
    pub we: Signal<In, Bit>,
    pub waddr: Signal<In, Bits<A>>,
    pub w: Signal<In, Bits<W>>,
    pub addr_a: Signal<In, Bits<A>>,
    pub addr_b: Signal<In, Bits<A>>,
    pub a: Signal<Out, Bits<W>>,
    pub b: Signal<Out, Bits<W>>,
    ra: RAM<Bits<W>, A>,
    rb: RAM<Bits<W>, A>,
}

impl<const W: usize, const A: usize> Logic for TwinRam<W, A> {
    #[hdl_gen]
    fn update(&mut self) {
        self.ra.read_clock.next = self.clock.val();
        self.ra.write_clock.next = self.clock.val();
        self.ra.write_enable.next = self.we.val();
        self.ra.write_address.next = self.waddr.val();
        self.ra.write_data.next = self.w.val();
        self.ra.read_address.next = self.addr_a.val();
        self.a.next = self.ra.read_data.val();
        self.rb.read_clock.next = self.clock.val();
        self.rb.write_clock.next = self.clock.val();
        self.rb.write_enable.next = self.we.val();
        self.rb.write_address.next = self.waddr.val();
        self.rb.write_data.next = self.w.val();
        self.rb.read_address.next = self.addr_b.val();
        self.b.next = self.rb.read_data.val();
    }
}

/// The value of a stored-ray or job input port shared by the results processors (`ray_o_lo` .. `ray_t`,
/// `o_lo` .. `t_hi`, `in_lo` .. `out_hi`), by base name and axis, for a processor over `bf`: `ray` is the
/// ray on the write port, `bundle` and `boxes` the job's. `None` for any other port.
pub fn ray_job_word(
    bf: &golden::bundle::fix::BundleFixFormat,
    base: &str,
    axis: usize,
    ray: &golden::bundle::fix::FixBundle,
    bundle: &golden::bundle::fix::FixBundle,
    boxes: &golden::bundle::edge::BoxPair<golden::format::fixed::FixBox>,
) -> Option<u64> {
    use crate::slab::fix::code;
    let (g, d, t) = (
        bf.base.g as usize,
        bf.dir_bits() as usize,
        bf.base.t as usize,
    );
    let (inner, outer) = (&boxes.inner, &boxes.outer);
    ray_job_word_of(
        base,
        axis,
        ray,
        bundle,
        [&inner.lo, &inner.hi, &outer.lo, &outer.hi],
        (|x| code(x, g), |x| code(x, d), |x| code(x, t)),
    )
}

/// [`ray_job_word`] for any datapath: `boxes` are the job's inner box's low and high corners and the
/// outer box's; `enc` turns an origin or box coordinate, a direction and a `t` into their port words.
pub fn ray_job_word_of<V: Copy, T: Copy>(
    base: &str,
    axis: usize,
    ray: &golden::bundle::edge::BundleOf<V, T>,
    bundle: &golden::bundle::edge::BundleOf<V, T>,
    boxes: [&[V; 3]; 4],
    enc: (impl Fn(V) -> u64, impl Fn(V) -> u64, impl Fn(T) -> u64),
) -> Option<u64> {
    let (r, b, i) = (ray, bundle, axis);
    let (g, d, t) = enc;
    Some(match base {
        "ray_o_lo" => g(r.o_lo[i]),
        "ray_o_hi" => g(r.o_hi[i]),
        "ray_d_lo" => d(r.d_lo[i]),
        "ray_d_hi" => d(r.d_hi[i]),
        "ray_t" => t(r.t_hi),
        "o_lo" => g(b.o_lo[i]),
        "o_hi" => g(b.o_hi[i]),
        "d_lo" => d(b.d_lo[i]),
        "d_hi" => d(b.d_hi[i]),
        "t_lo" => t(b.t_lo),
        "t_hi" => t(b.t_hi),
        "in_lo" => g(boxes[0][i]),
        "in_hi" => g(boxes[1][i]),
        "out_lo" => g(boxes[2][i]),
        "out_hi" => g(boxes[3][i]),
        _ => return None,
    })
}
