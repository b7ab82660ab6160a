//! Stability where the textbook method fails, on the float datapath. Each named case states the exact
//! answer and the formats in which the textbook slab test (round to nearest, `inv = 1/d`, `t0/t1` swap)
//! gets it wrong; the conservative float datapath must be right — no false miss, enclosing interval — in
//! every format. The grazing cases were found by searching rays aimed at corners of the unit box.

use golden::check::Verdict;
use golden::exact::slab_exact;
use golden::float::FloatFormat;
use golden::slab_float::{
    judge_float, quantize_box, quantize_ray, slab_float, slab_float_textbook,
};
use golden::{Aabb, Ray};

const FORMATS: [FloatFormat; 5] = [
    FloatFormat::FP32,
    FloatFormat::E8M15,
    FloatFormat::BF16,
    FloatFormat::FP16,
    FloatFormat { e: 6, m: 5 },
];

struct Case {
    name: &'static str,
    ray: Ray,
    bx: Aabb,
    hit: bool,
    /// Formats in which the textbook method is wrong on this case.
    textbook_wrong_in: Vec<FloatFormat>,
}

fn case(
    name: &'static str,
    o: [f64; 3],
    d: [f64; 3],
    bmin: [f64; 3],
    bmax: [f64; 3],
    hit: bool,
    wrong: &[FloatFormat],
) -> Case {
    Case {
        name,
        ray: Ray::new(o.into(), d.into(), 0.0, f64::INFINITY).unwrap(),
        bx: Aabb::new(bmin.into(), bmax.into()).unwrap(),
        hit,
        textbook_wrong_in: wrong.to_vec(),
    }
}

#[rustfmt::skip]
fn catalogue() -> Vec<Case> {
    let (u0, u1) = ([0.0; 3], [1.0; 3]);
    vec![
        // (0 - 0) * inf = NaN; the swap puts +inf into the entry.
        case("nan_origin_on_lower_slab_plane_zero_dir", [-4.0, 0.0, 0.5], [1.0, 0.0, 0.0], u0, u1, true, &FORMATS),
        // (1 - 1) * inf = NaN; the swap puts -inf into the exit.
        case("nan_origin_on_upper_slab_plane_zero_dir", [-4.0, 1.0, 0.5], [1.0, 0.0, 0.0], u0, u1, true, &FORMATS),
        // With -0 the NaNs land where the comparisons ignore them: right by luck.
        case("signed_zero_dir_on_upper_plane", [-4.0, 1.0, 0.5], [1.0, -0.0, 0.0], u0, u1, true, &[]),
        case("signed_zero_dir_on_lower_plane", [-4.0, 0.0, 0.5], [1.0, -0.0, 0.0], u0, u1, true, &[]),
        // Aimed at the corner (1, 1, 1): round-to-nearest puts the entry past the exit.
        case("grazing_corner_fp16", [-3.5, 1.9, -0.9], [4.5, -0.9, 1.9], u0, u1, true, &[FloatFormat::FP16]),
        case("grazing_corner_fp32", [-3.0, -2.0, 1.2], [4.0, 3.0, -0.2], u0, u1, true, &[FloatFormat::FP32]),
        // The swap turns an inverted (empty) box into a valid one.
        case("inverted_box", [-4.0, 0.5, 0.5], [1.0, 0.0, 0.0], u1, u0, false, &FORMATS),
        // 1/d overflows the small formats; both methods must still find the box straight ahead.
        case("tiny_direction_component", [-4.0, 0.5, 0.5], [1.0, 1e-9, 0.0], u0, u1, true, &[]),
    ]
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
            if c.textbook_wrong_in.contains(&f) {
                assert_ne!(
                    slab_float_textbook(&f, &c.ray, &c.bx),
                    c.hit,
                    "{} {}: the textbook method was expected to fail",
                    c.name,
                    f.name()
                );
            }
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
            if !c.hit {
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
