//! proptest strategies over quantised slab vectors: raw codes (shrinking toward zero), format extremes,
//! and quantised world vectors from the adversarial generator.

use crate::campaign::{campaign_map, world_gen};
use crate::slab::ctx::SlabVec;
use golden::format::fixed::{FixBox, FixFormat, FixRay};
use golden::slab::gen::GenKind;
use proptest::prelude::*;

fn grid(fmt: FixFormat) -> impl Strategy<Value = i64> {
    prop_oneof![
        Just(fmt.gmin()),
        Just(fmt.gmax()),
        Just(0i64),
        Just(-1i64),
        fmt.gmin()..=fmt.gmax()
    ]
}

fn inv(fmt: FixFormat) -> impl Strategy<Value = u64> {
    prop_oneof![
        Just(fmt.inv_inf()),
        Just(fmt.inv_inf() - 1),
        Just(0u64),
        Just(1u64),
        0..=fmt.inv_inf()
    ]
}

fn tcode(fmt: FixFormat) -> impl Strategy<Value = i64> {
    prop_oneof![
        Just(fmt.t_neg_inf()),
        Just(fmt.t_pos_inf()),
        Just(fmt.t_neg_inf() + 1),
        Just(fmt.t_pos_inf() - 1),
        Just(0i64),
        fmt.t_neg_inf()..=fmt.t_pos_inf()
    ]
}

/// Any quantised vector, field by field.
pub fn raw_case(fmt: FixFormat) -> impl Strategy<Value = (FixRay, FixBox)> {
    let axis = || {
        (
            grid(fmt),
            grid(fmt),
            inv(fmt),
            inv(fmt),
            any::<bool>(),
            grid(fmt),
            grid(fmt),
        )
    };
    ([axis(), axis(), axis()], tcode(fmt), tcode(fmt)).prop_map(|(axes, t_min, t_max)| {
        let mut r = FixRay {
            t_min,
            t_max,
            ..FixRay::default()
        };
        let mut b = FixBox::default();
        for (a, (olo, ohi, mlo, mhi, neg, lo, hi)) in axes.into_iter().enumerate() {
            (r.o_lo[a], r.o_hi[a], r.m_lo[a], r.m_hi[a], r.neg[a]) = (olo, ohi, mlo, mhi, neg);
            (b.lo[a], b.hi[a]) = (lo, hi);
        }
        (r, b)
    })
}

/// A quantised world vector from the uniform or adversarial generator, drawn by seed.
pub fn world_case(fmt: FixFormat) -> impl Strategy<Value = (FixRay, FixBox)> {
    (any::<u64>(), any::<bool>()).prop_map(move |(seed, adv)| {
        let map = campaign_map(fmt);
        let kind = if adv {
            GenKind::Adversarial
        } else {
            GenKind::Uniform
        };
        let (r, b) = world_gen(&map, kind, seed).next().expect("endless");
        (
            map.quantize_ray(&r).expect("fits"),
            map.quantize_box(&b).expect("fits"),
        )
    })
}

/// One slab vector of either kind.
pub fn slab_case(fmt: FixFormat) -> impl Strategy<Value = (FixRay, FixBox)> {
    prop_oneof![raw_case(fmt), world_case(fmt)]
}

/// A short burst of 1 to 8 tests, back to back or separated by bubbles.
pub fn slab_burst(fmt: FixFormat) -> impl Strategy<Value = Vec<SlabVec>> {
    prop::collection::vec((slab_case(fmt), 0..3usize), 1..=8).prop_map(|v| {
        let mut out = vec![];
        for (case, bubbles) in v {
            out.push(Some(case));
            // Mostly back to back; sometimes one or two bubbles.
            out.extend(std::iter::repeat_n(None, if bubbles == 2 { 1 } else { 0 }));
        }
        out
    })
}

/// Any float pattern of format `f`, with specials (zeros, infinities, NaN, extremes) weighted up.
fn float_code(f: golden::format::float::FloatFormat) -> impl Strategy<Value = u32> {
    let specials = f.specials();
    prop_oneof![prop::sample::select(specials), 0..=f.mask()]
}

/// A float slab vector: every field any pattern of the format (NaN included).
pub fn raw_float_case(
    f: golden::format::float::FloatFormat,
) -> impl Strategy<Value = (golden::slab::float::FloatRay, golden::slab::float::FloatBox)> {
    let axis = move || {
        (
            float_code(f),
            float_code(f),
            float_code(f),
            float_code(f),
            any::<bool>(),
            float_code(f),
            float_code(f),
        )
    };
    ([axis(), axis(), axis()], float_code(f), float_code(f)).prop_map(|(axes, t_min, t_max)| {
        let mut r = golden::slab::float::FloatRay {
            t_min,
            t_max,
            ..Default::default()
        };
        let mut b = golden::slab::float::FloatBox::default();
        for (a, (olo, ohi, mlo, mhi, neg, lo, hi)) in axes.into_iter().enumerate() {
            (r.o_lo[a], r.o_hi[a], r.m_lo[a], r.m_hi[a], r.neg[a]) = (olo, ohi, mlo, mhi, neg);
            (b.lo[a], b.hi[a]) = (lo, hi);
        }
        (r, b)
    })
}

/// A world vector from the uniform or adversarial generator quantised into format `f`.
pub fn world_float_case(
    f: golden::format::float::FloatFormat,
) -> impl Strategy<Value = (golden::slab::float::FloatRay, golden::slab::float::FloatBox)> {
    (any::<u64>(), any::<bool>()).prop_map(move |(seed, adv)| {
        let (lo, hi) = crate::campaign::campaign_bounds();
        let kind = if adv {
            GenKind::Adversarial
        } else {
            GenKind::Uniform
        };
        let (r, b) = golden::slab::gen::SlabGen::new(kind, lo, hi, 1.0 / 64.0, seed)
            .next()
            .expect("endless");
        (
            golden::slab::float::quantize_ray(&f, &r).expect("fits"),
            golden::slab::float::quantize_box(&f, &b).expect("fits"),
        )
    })
}

/// A burst of 1 to 8 float slab tests, back to back or with bubbles.
pub fn float_burst(
    f: golden::format::float::FloatFormat,
) -> impl Strategy<Value = Vec<Option<(golden::slab::float::FloatRay, golden::slab::float::FloatBox)>>>
{
    prop::collection::vec(
        (
            prop_oneof![raw_float_case(f), world_float_case(f)],
            0..3usize,
        ),
        1..=8,
    )
    .prop_map(|v| {
        let mut out = vec![];
        for (case, bubbles) in v {
            out.push(Some(case));
            if bubbles == 2 {
                out.push(None);
            }
        }
        out
    })
}
