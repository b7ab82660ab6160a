//! Named corner cases of the slab test (the catalogue is `golden::stability::slab_cases`). Each is run
//! through the exact oracle (whose answer the catalogue states), the float reference, the bit-accurate
//! model of every preset width (which must be conservative) and the RTL (which must equal the model).
//! Where the f64 textbook method goes wrong, that is asserted too.

use glam::DVec3;
use golden::exact::slab_exact;
use golden::format::fixed::{FixFormat, GridMap};
use golden::slab::check::{judge_fix, Verdict};
use golden::slab::fix::slab_fix;
use golden::slab::reference::{slab_ref, slab_textbook};
use golden::stability::{slab_cases, SlabCase};
use tb::dut::run_checked;
use tb::rtl_sim::SlabFixRtl;

/// The named corner cases: one catalogue, shared with the float testbench and `rtu stability`.
fn catalogue() -> Vec<SlabCase> {
    slab_cases()
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
fn float_reference_agrees_with_the_oracle_except_where_stated() {
    for c in catalogue() {
        // Round to nearest in f64: right everywhere but on the grazing rays the catalogue marks.
        assert_eq!(
            slab_ref(&c.ray, &c.bx).hit != c.hit,
            c.ref_f64_wrong,
            "{}",
            c.name
        );
    }
}

#[test]
fn textbook_method_fails_where_stated() {
    for c in catalogue() {
        let wrong = slab_textbook(&c.ray, &c.bx) != c.hit;
        assert_eq!(
            wrong,
            c.textbook_f64_wrong,
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
