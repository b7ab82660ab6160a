//! Stability where the textbook method fails, on the float datapath. Each named case of the catalogue
//! (`golden::stability::slab_cases`, shared with the fixed testbench) states the exact answer and the
//! formats in which the textbook slab test (round to nearest, `inv = 1/d`, `t0/t1` swap) gets it wrong;
//! the conservative float datapath must be right — no false miss, enclosing interval — in every format.
//! The grazing cases were found by searching rays aimed at corners of the unit box.

use golden::exact::slab_exact;
use golden::format::float::{FloatFormat, Rounding};
use golden::slab::check::Verdict;
use golden::slab::float::{
    judge_float, quantize_box, quantize_ray, slab_float, slab_float_textbook,
};
use golden::stability::{slab_cases, SlabCase, SLAB_FLOAT_FORMATS};

const FORMATS: [FloatFormat; 5] = SLAB_FLOAT_FORMATS;

/// The named corner cases: one catalogue, shared with the fixed testbench and `rtu stability`.
fn catalogue() -> Vec<SlabCase> {
    slab_cases()
}

/// True when the case's inputs are exactly values of `f` (origin, box, t range and inverse direction), so
/// the conservative datapath has nothing to round and must give the exact answer.
fn needs_no_rounding(f: &FloatFormat, c: &SlabCase) -> bool {
    let (r, b) = (
        quantize_ray(f, &c.ray).unwrap(),
        quantize_box(f, &c.bx).unwrap(),
    );
    let exact = |x: f64| x.is_infinite() || f.to_f64(f.from_f64(x, Rounding::NearestEven)) == x;
    r.o_lo == r.o_hi
        && r.m_lo == r.m_hi
        && b.lo
            .iter()
            .zip(c.bx.min.to_array())
            .all(|(q, x)| f.to_f64(*q) == x || c.bx.is_empty())
        && b.hi
            .iter()
            .zip(c.bx.max.to_array())
            .all(|(q, x)| f.to_f64(*q) == x || c.bx.is_empty())
        && exact(c.ray.t_min)
        && exact(c.ray.t_max)
}

#[test]
fn exact_oracle_gives_the_stated_answers() {
    for c in catalogue() {
        assert_eq!(slab_exact(&c.ray, &c.bx).hit, c.hit, "{}", c.name);
    }
}

#[test]
fn textbook_method_fails_exactly_where_stated() {
    for c in catalogue() {
        for f in FORMATS {
            assert_eq!(
                slab_float_textbook(&f, &c.ray, &c.bx) != c.hit,
                c.textbook_float_wrong_in.contains(&f),
                "{} {}: the textbook method was expected to {}",
                c.name,
                f.name(),
                if c.textbook_float_wrong_in.contains(&f) {
                    "fail"
                } else {
                    "succeed"
                }
            );
        }
    }
}

#[test]
fn conservative_datapath_is_right_in_every_format() {
    for c in catalogue() {
        let exact = slab_exact(&c.ray, &c.bx);
        for f in FORMATS {
            let out = slab_float(
                &f,
                &quantize_ray(&f, &c.ray).unwrap(),
                &quantize_box(&f, &c.bx).unwrap(),
            );
            let v = judge_float(&f, &out, &exact);
            assert!(
                !matches!(v, Verdict::Violation(_)),
                "{} {}: {v:?} {out:?}",
                c.name,
                f.name()
            );
            if !c.hit && needs_no_rounding(&f, &c) {
                assert!(
                    !out.hit,
                    "{} {}: a miss that needs no rounding was reported hit",
                    c.name,
                    f.name()
                );
            }
        }
    }
}
