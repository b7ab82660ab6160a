//! The bit-accurate model of the fraction option of the fixed cull-plane tester
//! (`rtl::plane::quot::PlaneQuot`): the slab test chained with `K` planes whose bounds are never
//! rounded, each kept as the exact fraction `t* = num * 2^E / den` (t code units, `E = FD + FT - 1`) and
//! ordered against the others and against the slab's t codes by cross-multiplication.
//!
//! [`node_quot`] is the model of the whole tester (it also fixes the tie-breaking); [`quot_effect`],
//! [`quot_lt`], [`code_quot_cmp`] and [`quot_order_tree`] model its parts bit for bit. Its values are
//! [`cull_fix_quotients`](crate::plane::fix::cull_fix_quotients)' (the exact model of record) for every
//! node whose `den` intervals are not inverted.

use crate::exact::{dyadic, Ext};
use crate::format::fixed::{code, sext};
use crate::plane::fix::{plane_sums, CullFixFormat, FixNode, NodeFixRay, MAX_PLANES};
use crate::slab::fix::slab_fix;
use std::cmp::Ordering;

/// Slots of the tree.
pub const QUOT_TREE_SLOTS: usize = 8;

/// A bound as the fraction option outputs it: `den != 0`, the plane bound `num * 2^E / den` in t code
/// units; `den == 0`, the slab's t code `num`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Quot {
    pub num: i64,
    pub den: u64,
}

/// Output of the fraction option: the cull decision and the interval as chosen fractions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct PlaneQuotOut {
    pub hit: bool,
    pub t_entry: Quot,
    pub t_exit: Quot,
}

/// The bound scale exponent `E = FD + FT - 1`: a fraction `num / den` is `num * 2^E / den` t code units.
pub fn quot_scale(cf: &CullFixFormat) -> u32 {
    cf.fd + cf.base.ft - 1
}

/// Denominator bits `MB = EB - 1` of the fraction option.
pub fn quot_den_bits(cf: &CullFixFormat) -> u32 {
    cf.den_bits() - 1
}

/// The exact value of a [`Quot`] in t code units, as [`cull_fix_quotients`](crate::plane::fix::cull_fix_quotients) returns it.
pub fn quot_value(cf: &CullFixFormat, f: &Quot) -> Ext {
    let fmt = &cf.base;
    if f.den != 0 {
        Ext::Fin(dyadic(f.num, quot_scale(cf) as i32) / dyadic(f.den as i64, 0))
    } else if f.num == fmt.t_neg_inf() {
        Ext::NegInf
    } else if f.num == fmt.t_pos_inf() {
        Ext::PosInf
    } else {
        Ext::Fin(dyadic(f.num, 0))
    }
}

/// The order of a t code and a plane fraction, the `+-inf` codes as infinities.
fn code_vs(cf: &CullFixFormat, c: i64, (num, den): (i64, u64)) -> Ordering {
    if c == cf.base.t_neg_inf() {
        Ordering::Less
    } else if c == cf.base.t_pos_inf() {
        Ordering::Greater
    } else {
        code_quot_cmp(quot_scale(cf), c, num, den)
    }
}

/// The bit-accurate model of `rtl::plane::quot::PlaneQuot` (and of every tie it breaks): slab test then `k` planes, the
/// bounds as fractions. Its values are `cull_fix_quotients`' for every node whose `den` intervals are
/// not inverted (all that quantisation produces; the model of record has no value for a zero `den`).
pub fn node_quot(cf: &CullFixFormat, k: usize, r: &NodeFixRay, n: &FixNode) -> PlaneQuotOut {
    let slab = slab_fix(&cf.base, &r.ray, &n.b);
    let (sb, eb) = (cf.s_bits() as usize, cf.den_bits() as usize);
    let mb = quot_den_bits(cf) as usize;
    let (mut en, mut ex, mut par) = ([None; MAX_PLANES], [None; MAX_PLANES], false);
    for (i, p) in n.planes[..k].iter().enumerate() {
        let (s, dl, dh) = plane_sums(&r.ray, &r.dir, &n.b, p);
        // The sums as the RTL's registers hold them.
        let e = quot_effect(
            sb,
            mb,
            sext(code(s, sb), sb),
            sext(code(dl, eb), eb),
            sext(code(dh, eb), eb),
        );
        let f = (e.num, e.den);
        en[i] = e.is_entry.then_some(f);
        ex[i] = e.is_exit.then_some(f);
        par |= e.par;
    }
    let pe = quot_order_tree(false, en);
    let px = quot_order_tree(true, ex);
    let entry = match pe {
        Some(f) if code_vs(cf, slab.t_entry, f) == Ordering::Less => Quot { num: f.0, den: f.1 },
        _ => Quot {
            num: slab.t_entry,
            den: 0,
        },
    };
    let exit = match px {
        Some(f) if code_vs(cf, slab.t_exit, f) == Ordering::Greater => Quot { num: f.0, den: f.1 },
        _ => Quot {
            num: slab.t_exit,
            den: 0,
        },
    };
    PlaneQuotOut {
        hit: slab.hit && !par && quot_value(cf, &entry) <= quot_value(cf, &exit),
        t_entry: entry,
        t_exit: exit,
    }
}

/// What `rtl::plane::quot_bound::PlaneQuotBound` outputs, as native values (`num` sign-extended).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QuotEffect {
    pub is_entry: bool,
    pub is_exit: bool,
    pub par: bool,
    pub num: i64,
    pub den: u64,
}

/// The native model of `rtl::plane::quot_bound::PlaneQuotBound` with `sb` numerator and `mb` denominator bits, bit for bit the
/// Verilog.
pub fn quot_effect(sb: usize, mb: usize, s: i64, dl: i64, dh: i64) -> QuotEffect {
    let ex = dl > 0;
    let en = !ex && dh < 0;
    let mag = match (ex, s > 0, s < 0) {
        (true, true, _) => dh,
        (true, false, _) => dl,
        (false, _, true) => -dh,
        (false, _, false) => -dl,
    };
    QuotEffect {
        is_entry: en,
        is_exit: ex,
        par: !ex && !en && dl == 0 && dh == 0 && s > 0,
        num: sext(code(if ex { -s } else { s }, sb), sb),
        den: code(mag, mb),
    }
}

/// `a_num / a_den < b_num / b_den` by cross-multiplication, exactly (the model of
/// `rtl::plane::quot_cmp::QuotCmp`).
pub fn quot_lt(a_num: i64, a_den: u64, b_num: i64, b_den: u64) -> bool {
    (a_num as i128) * (b_den as i128) < (b_num as i128) * (a_den as i128)
}

/// The order of `c * den` and `num * 2^e`, exactly (the model of `rtl::plane::quot_code_cmp::CodeQuotCmp`).
pub fn code_quot_cmp(e: u32, c: i64, num: i64, den: u64) -> Ordering {
    ((c as i128) * (den as i128)).cmp(&((num as i128) << e))
}

/// The native model of `rtl::plane::quot_tree::QuotTree`: the winner of `slots` (`None` empty, else `(num, den)`), pairwise
/// in the tree's order, the higher slot of a pair winning only when strictly better.
pub fn quot_order_tree(
    want_min: bool,
    slots: [Option<(i64, u64)>; QUOT_TREE_SLOTS],
) -> Option<(i64, u64)> {
    let better = |x: (i64, u64), y: (i64, u64)| {
        if want_min {
            quot_lt(x.0, x.1, y.0, y.1)
        } else {
            quot_lt(y.0, y.1, x.0, x.1)
        }
    };
    let mut level = slots.to_vec();
    while level.len() > 1 {
        level = level
            .chunks(2)
            .map(|p| match (p[0], p[1]) {
                (a, None) => a,
                (None, b) => b,
                (Some(a), Some(b)) => Some(if better(b, a) { b } else { a }),
            })
            .collect();
    }
    level[0]
}
