//! Named corner cases of the slab test. Each is run through the exact oracle (whose answer is stated
//! here), the float reference, the bit-accurate model of every preset width (which must be conservative)
//! and the RTL (which must equal the model). Where the textbook method goes wrong, that is asserted too.

use glam::DVec3;
use golden::check::{judge_fix, Verdict};
use golden::exact::slab_exact;
use golden::fixed::{FixFormat, GridMap};
use golden::slab_fix::slab_fix;
use golden::slab_ref::{slab_ref, slab_textbook};
use golden::{Aabb, Ray};
use tb::dut::run_checked;
use tb::rtl_sim::SlabFixRtl;

struct Case {
    name: &'static str,
    ray: Ray,
    bx: Aabb,
    hit: bool,
    /// The textbook slab test gets this case wrong.
    textbook_wrong: bool,
}

#[allow(clippy::too_many_arguments)]
fn case(
    name: &'static str,
    o: [f64; 3],
    d: [f64; 3],
    t: (f64, f64),
    bmin: [f64; 3],
    bmax: [f64; 3],
    hit: bool,
    textbook_wrong: bool,
) -> Case {
    Case {
        name,
        ray: Ray::new(o.into(), d.into(), t.0, t.1).unwrap(),
        bx: Aabb::new(bmin.into(), bmax.into()).unwrap(),
        hit,
        textbook_wrong,
    }
}

const INF: f64 = f64::INFINITY;

#[rustfmt::skip]
fn catalogue() -> Vec<Case> {
    let (u0, u1) = ([0.0; 3], [1.0; 3]);
    vec![
        case("origin_on_slab_plane_zero_dir", [-4.0, 1.0, 0.5], [1.0, 0.0, 0.0], (0.0, INF), u0, u1, true, true),
        // With -0 the NaN of 0 x -inf lands where the textbook comparisons ignore it: right by luck.
        case("origin_on_slab_plane_negative_zero_dir", [-4.0, 1.0, 0.5], [1.0, -0.0, 0.0], (0.0, INF), u0, u1, true, false),
        case("origin_on_lower_slab_plane_zero_dir", [-4.0, 0.0, 0.5], [1.0, 0.0, 0.0], (0.0, INF), u0, u1, true, true),
        case("parallel_outside_slab", [-4.0, 1.5, 0.5], [1.0, 0.0, 0.0], (0.0, INF), u0, u1, false, false),
        case("grazing_corner_diagonal", [-1.0, -1.0, -1.0], [0.3, 0.3, 0.3], (0.0, INF), u1, [2.0; 3], true, false),
        case("grazing_edge_shallow", [-3.0, 1.0, 0.25], [1.0, -1e-9, 0.1], (0.0, INF), u0, u1, true, false),
        case("leaving_edge_shallow", [-3.0, 1.0, 0.25], [1.0, 1e-9, 0.1], (0.0, INF), u0, u1, false, false),
        case("t_max_ends_on_entry_face", [-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], (0.0, 1.0), u0, u1, true, false),
        case("t_max_just_before_entry_face", [-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], (0.0, 0.999), u0, u1, false, false),
        case("origin_inside_box", [0.5, 0.5, 0.5], [0.6, -0.8, 0.0], (0.0, INF), u0, u1, true, false),
        case("point_box_hit_exactly", [-2.0, -2.0, 0.5], [1.0, 1.0, 0.0], (0.0, INF), [0.5; 3], [0.5; 3], true, false),
        case("flat_box_crossed", [0.5, -2.0, 0.5], [0.0, 1.0, 0.0], (0.0, INF), [0.0, 0.25, 0.0], [1.0, 0.25, 1.0], true, false),
        // The textbook swap of t0/t1 turns an inverted (empty) box into a valid one.
        case("empty_box", [-4.0, 0.5, 0.5], [1.0, 0.0, 0.0], (0.0, INF), u1, u0, false, true),
        case("subnormal_direction_component", [-4.0, 0.5, 0.5], [1.0, 5e-324, 0.0], (0.0, INF), u0, u1, true, false),
        case("huge_direction_magnitude", [-4.0, 0.5, 0.5], [1e300, 1e299, 0.0], (0.0, INF), u0, u1, true, false),
        case("tiny_direction_magnitude", [-4.0, 0.5, 0.5], [1e-300, 0.0, 0.0], (0.0, INF), u0, u1, true, false),
        case("pointing_away", [-4.0, 0.5, 0.5], [-1.0, 0.0, 0.0], (0.0, INF), u0, u1, false, false),
        case("negative_t_range_behind_origin", [4.0, 0.5, 0.5], [1.0, 0.0, 0.0], (-INF, 0.0), u0, u1, true, false),
        case("origin_at_scene_corner", [-8.0, -8.0, -8.0], [1.0, 1.0, 1.0], (0.0, INF), [7.0; 3], [8.0; 3], true, false),
        case("box_is_whole_scene", [0.1, 0.2, 0.3], [0.0, 0.0, -1.0], (0.0, INF), [-8.0; 3], [8.0; 3], true, false),
    ]
}

fn map(fmt: FixFormat) -> GridMap {
    GridMap::for_bounds(fmt, DVec3::splat(-8.0), DVec3::splat(8.0)).unwrap()
}

#[test]
fn exact_oracle_gives_the_stated_answers() {
    for c in catalogue() {
        assert_eq!(slab_exact(&c.ray, &c.bx).hit, c.hit, "{}", c.name);
    }
}

#[test]
fn float_reference_agrees_with_the_oracle_on_the_catalogue() {
    for c in catalogue() {
        assert_eq!(slab_ref(&c.ray, &c.bx).hit, c.hit, "{}", c.name);
    }
}

#[test]
fn textbook_method_fails_where_stated() {
    for c in catalogue() {
        let wrong = slab_textbook(&c.ray, &c.bx) != c.hit;
        assert_eq!(
            wrong,
            c.textbook_wrong,
            "{}: textbook {}",
            c.name,
            if wrong { "wrong" } else { "right" }
        );
    }
}

#[test]
fn fixed_model_is_conservative_on_every_case_and_width() {
    for fmt in FixFormat::presets() {
        let m = map(fmt);
        for c in catalogue() {
            let (fr, fb) = (
                m.quantize_ray(&c.ray).unwrap(),
                m.quantize_box(&c.bx).unwrap(),
            );
            let out = slab_fix(&fmt, &fr, &fb);
            let v = judge_fix(&fmt, &fr, &out, &slab_exact(&c.ray, &c.bx));
            assert!(
                !matches!(v, Verdict::Violation(_)),
                "{} {}: {v:?} {out:?}",
                c.name,
                fmt.name()
            );
        }
    }
}

#[test]
fn exact_inputs_get_exact_answers_where_the_grid_is_exact() {
    // Grid-aligned, axis-aligned cases: the quantised inputs are exact and so is the answer.
    let fmt = FixFormat::b12();
    let m = map(fmt);
    for name in [
        "origin_on_slab_plane_zero_dir",
        "parallel_outside_slab",
        "empty_box",
        "pointing_away",
        "t_max_ends_on_entry_face",
    ] {
        let c = catalogue().into_iter().find(|c| c.name == name).unwrap();
        let (fr, fb) = (
            m.quantize_ray(&c.ray).unwrap(),
            m.quantize_box(&c.bx).unwrap(),
        );
        assert_eq!(slab_fix(&fmt, &fr, &fb).hit, c.hit, "{name}");
    }
}

#[test]
fn rtl_equals_model_on_the_catalogue() {
    let fmt = FixFormat::b12();
    let m = map(fmt);
    let v: Vec<_> = catalogue()
        .iter()
        .map(|c| {
            Some((
                m.quantize_ray(&c.ray).unwrap(),
                m.quantize_box(&c.bx).unwrap(),
            ))
        })
        .collect();
    let n = v.len();
    let mut dut = SlabFixRtl::<rtl::SlabFixB12>::new(&fmt);
    assert_eq!(
        run_checked(&mut dut, v, |x| slab_fix(&fmt, &x.0, &x.1)).unwrap_or_else(|e| panic!("{e}")),
        n
    );
}
