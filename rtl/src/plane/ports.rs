//! The port codecs of the cull-plane testers ([`crate::io`]): the slab ports as the slab testers'
//! codecs say ([`crate::slab::ports`]), plus the ray's direction interval `ray_d_lo/hi` and each
//! plane's `plane_nx/ny/nz/w` (arrays over the planes).

use crate::io::{PortCodec, Word};
use crate::slab::ports::{interval_outputs, interval_words, SlabFixPorts, SlabFloatPorts};
use golden::plane::fix::{FixNode, NodeFixRay, PlaneFixOut};
use golden::plane::float::{FloatNode, NodeFloatRay};
use golden::plane::quot::{PlaneQuotOut, Quot};
use golden::slab::float::SlabFloatOut;

/// The direction and plane inputs of a fixed node test (grid and plane codes).
fn fix_node_input(base: &str, idx: usize, r: &NodeFixRay, n: &FixNode) -> Option<i64> {
    let plane = n.planes.get(idx);
    match base {
        "ray_d_lo" => r.dir.lo.get(idx).copied(),
        "ray_d_hi" => r.dir.hi.get(idx).copied(),
        "plane_nx" => plane.map(|p| p.n[0]),
        "plane_ny" => plane.map(|p| p.n[1]),
        "plane_nz" => plane.map(|p| p.n[2]),
        "plane_w" => plane.map(|p| p.w),
        _ => SlabFixPorts.input(base, idx, &r.ray, &n.b),
    }
}

/// The fixed cull-plane tester's ports (`PlaneFix`, the table option): out `hit`, `t_entry`,
/// `t_exit` as the fixed slab tester's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PlaneFixPorts;

impl PortCodec for PlaneFixPorts {
    type Ray = NodeFixRay;
    type Box = FixNode;
    type Out = PlaneFixOut;

    fn input(&self, base: &str, idx: usize, r: &NodeFixRay, n: &FixNode) -> Option<i64> {
        fix_node_input(base, idx, r, n)
    }

    fn outputs(&self, o: &PlaneFixOut) -> Vec<(&'static str, i64)> {
        interval_outputs(o.hit, o.t_entry, o.t_exit)
    }

    fn result(&self, word: &dyn Fn(&str) -> Option<Word>) -> Result<PlaneFixOut, String> {
        let (hit, en, ex) = interval_words(word)?;
        Ok(PlaneFixOut {
            hit,
            t_entry: en.signed(),
            t_exit: ex.signed(),
        })
    }
}

/// The quotient option's ports (`PlaneQuot`): the inputs of [`PlaneFixPorts`]; `t_entry` and
/// `t_exit` each a packed fraction, the denominator above `sb` numerator bits, or, for a denominator
/// of zero (a slab bound), a `t`-bit t code in the low bits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlaneQuotPorts {
    /// Numerator bits (`CullFixFormat::s_bits`).
    pub sb: usize,
    /// t code bits.
    pub t: usize,
}

impl PlaneQuotPorts {
    /// The packed word of a fraction.
    pub fn pack(&self, f: &Quot) -> i64 {
        let low = Word::of(f.num, if f.den == 0 { self.t } else { self.sb }).bits;
        ((f.den << self.sb) | low) as i64
    }

    /// A packed word, unpacked.
    pub fn unpack(&self, word: u64) -> Quot {
        let den = word >> self.sb;
        let bits = if den == 0 { self.t } else { self.sb };
        Quot {
            num: Word::of(word as i64, bits).signed(),
            den,
        }
    }
}

impl PortCodec for PlaneQuotPorts {
    type Ray = NodeFixRay;
    type Box = FixNode;
    type Out = PlaneQuotOut;

    fn input(&self, base: &str, idx: usize, r: &NodeFixRay, n: &FixNode) -> Option<i64> {
        fix_node_input(base, idx, r, n)
    }

    fn outputs(&self, o: &PlaneQuotOut) -> Vec<(&'static str, i64)> {
        interval_outputs(o.hit, self.pack(&o.t_entry), self.pack(&o.t_exit))
    }

    fn result(&self, word: &dyn Fn(&str) -> Option<Word>) -> Result<PlaneQuotOut, String> {
        let (hit, en, ex) = interval_words(word)?;
        Ok(PlaneQuotOut {
            hit,
            t_entry: self.unpack(en.bits),
            t_exit: self.unpack(ex.bits),
        })
    }
}

/// The float cull-plane tester's ports (`PlaneFloat`): every data port a code of the format.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PlaneFloatPorts;

impl PortCodec for PlaneFloatPorts {
    type Ray = NodeFloatRay;
    type Box = FloatNode;
    type Out = SlabFloatOut;

    fn input(&self, base: &str, idx: usize, r: &NodeFloatRay, n: &FloatNode) -> Option<i64> {
        let plane = n.planes.get(idx);
        let code = |c: Option<u32>| c.map(|c| c as i64);
        match base {
            "ray_d_lo" => code(r.dir.lo.get(idx).copied()),
            "ray_d_hi" => code(r.dir.hi.get(idx).copied()),
            "plane_nx" => code(plane.map(|p| p.n[0])),
            "plane_ny" => code(plane.map(|p| p.n[1])),
            "plane_nz" => code(plane.map(|p| p.n[2])),
            "plane_w" => code(plane.map(|p| p.w)),
            _ => SlabFloatPorts.input(base, idx, &r.ray, &n.b),
        }
    }

    fn outputs(&self, o: &SlabFloatOut) -> Vec<(&'static str, i64)> {
        SlabFloatPorts.outputs(o)
    }

    fn result(&self, word: &dyn Fn(&str) -> Option<Word>) -> Result<SlabFloatOut, String> {
        SlabFloatPorts.result(word)
    }
}
