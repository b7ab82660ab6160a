//! Stability where the textbook methods fail: one catalogue of named inputs for the three testers (slab,
//! cull planes, bundles), each run through the exact oracle, the naive method it breaks, and our
//! conservative models in every preset format, and one table of the failures ([`table`]).
//!
//! # The naive methods
//! * **Slab.** The textbook slab test (Kay and Kajiya, SIGGRAPH 1986, written with `inv = 1/d` as in
//!   Williams et al., "An Efficient and Robust Ray-Box Intersection Algorithm", JGT 2005), in f64
//!   ([`crate::slab::reference::slab_textbook`]) and rounded to nearest in a float format
//!   ([`crate::slab::float::slab_float_textbook`]). Williams et al. point out the `0 x inf = NaN` of an origin
//!   on a slab plane with a zero direction component, and Ize ("Robust BVH Ray Traversal", JCGT 2013) that
//!   round-to-nearest makes a grazing ray's entry overtake its exit; both show up below.
//! * **Cull planes.** The f64 reference [`crate::plane::clip::clip_ref`] (round to nearest, `t* = -s0 / den`, a
//!   parallel branch for `den == 0`), and [`clip_textbook`]: the same clip with no parallel branch, letting
//!   IEEE infinities classify `den = 0` (the parametric clip of Cyrus and Beck, "Generalized two- and
//!   three-dimensional clipping", Computers & Graphics 1978, as used for rays against convex polyhedra by
//!   Haines, "Fast Ray-Convex Polyhedron Intersection", Graphics Gems II, 1991 — which keeps the branch; the
//!   branch-free form is the one that fails).
//! * **Bundles.** The f64 reference [`crate::bundle::edge::decide_ref`] (the bundle edge test of
//!   [`crate::bundle::edge`], rounded to nearest), and [`corner_rays_textbook`]: the bundle's corner rays, each
//!   through the textbook slab test, "all hit" when every one hits and "all miss" when none does.
//!
//! # What is checked
//! For every case: the exact oracle gives the answer the catalogue states; the naive method marked wrong
//! is wrong (a false miss, a culled node the exact clip keeps, a false "all hit" or "all miss", shown
//! against the exact answer or an exact witness ray); and our models — fixed `b8`, `b12`, `b16` on a grid
//! over bounds enclosing the case, float `fp32`, `bf16`, `fp16` — are conservative (no
//! false miss, an enclosing interval, no node culled that the exact clip keeps, no false "all hit" or "all
//! miss"). A case on which one of our models is not conservative makes [`table`] return an error: it is a
//! correctness bug, never a row.
//!
//! The slab cases are the named corner cases of the slab testbenches (`tb/tests/slab/fix_corners.rs`,
//! `tb/tests/slab/float_corners.rs`, which read them from here); the cull-plane and bundle cases were
//! found by construction and by seeded searches (rays through the line where two planes meet, origins
//! within an ulp of a plane, rays aimed at box edges with normalised directions) and frozen as literals.

use crate::bundle::edge::{decide_exact, decide_ref, Bundle};
use crate::error::Error;
use crate::exact::{slab_exact, ExactHit};
use crate::format::fixed::{FixFormat, GridMap};
use crate::format::float::FloatFormat;
use crate::geom::{Aabb, Ray};
use crate::plane::clip::{clip_exact, clip_exact_world, clip_ref, region_points, Plane, PlaneNode};
use crate::slab::check::{judge, Verdict};
use crate::slab::reference::slab_textbook;
use glam::DVec3;

const INF: f64 = f64::INFINITY;

/// The float formats of the slab testbench's textbook comparison (`tb/tests/slab/float_corners.rs`).
pub const SLAB_FLOAT_FORMATS: [FloatFormat; 5] = [
    FloatFormat::FP32,
    FloatFormat::E8M15,
    FloatFormat::BF16,
    FloatFormat::FP16,
    FloatFormat { e: 6, m: 5 },
];

/// The float presets of the table's columns, with their names.
pub const FLOAT_PRESETS: [(&str, FloatFormat); 3] = [
    ("fp32", FloatFormat::FP32),
    ("bf16", FloatFormat::BF16),
    ("fp16", FloatFormat::FP16),
];

/// The table's model columns: fixed presets, then float presets.
pub fn format_names() -> Vec<String> {
    ["b8", "b12", "b16"]
        .iter()
        .chain(FLOAT_PRESETS.iter().map(|(n, _)| n))
        .map(|s| s.to_string())
        .collect()
}

// ------------------------------------------------------------------------------------------------
// The catalogue
// ------------------------------------------------------------------------------------------------

/// A named slab corner case.
#[derive(Clone, Debug, PartialEq)]
pub struct SlabCase {
    pub name: &'static str,
    /// Why the textbook method fails (or what the case probes, when it does not).
    pub why: &'static str,
    pub ray: Ray,
    pub bx: Aabb,
    /// The exact answer.
    pub hit: bool,
    /// The f64 textbook slab test gets this case wrong.
    pub textbook_f64_wrong: bool,
    /// The f64 reference [`crate::slab::reference::slab_ref`] (special cases right, round to nearest) gets this
    /// case wrong: a grazing ray.
    pub ref_f64_wrong: bool,
    /// The formats of [`SLAB_FLOAT_FORMATS`] in which the float textbook test gets it wrong.
    pub textbook_float_wrong_in: Vec<FloatFormat>,
}

/// A named cull-plane case: a world ray, box and planes (offsets from the box centroid).
#[derive(Clone, Debug, PartialEq)]
pub struct CullCase {
    pub name: &'static str,
    pub why: &'static str,
    pub ray: Ray,
    pub node: PlaneNode,
    /// The exact clip keeps the node.
    pub kept: bool,
    /// [`clip_ref`] culls it although the exact clip keeps it.
    pub ref_wrong: bool,
    /// [`clip_textbook`] culls it although the exact clip keeps it.
    pub textbook_wrong: bool,
}

/// A named bundle case, with a witness ray of the bundle that contradicts the naive answer.
#[derive(Clone, Debug, PartialEq)]
pub struct BundleCase {
    pub name: &'static str,
    pub why: &'static str,
    pub bundle: Bundle,
    pub bx: Aabb,
    /// The exact oracle's `(all_hit, all_miss)`.
    pub exact: (bool, bool),
    /// A ray of the bundle, and whether it exactly hits.
    pub witness: Ray,
    pub witness_hits: bool,
    /// [`decide_ref`] answers "all hit" or "all miss" wrongly.
    pub ref_wrong: bool,
    /// [`corner_rays_textbook`] answers "all hit" or "all miss" wrongly.
    pub corners_wrong: bool,
}

fn ray(o: [f64; 3], d: [f64; 3], t: (f64, f64)) -> Ray {
    Ray::new(o.into(), d.into(), t.0, t.1).expect("catalogue rays are valid")
}

fn aabb(lo: [f64; 3], hi: [f64; 3]) -> Aabb {
    Aabb::new(lo.into(), hi.into()).expect("catalogue boxes are valid")
}

#[allow(clippy::too_many_arguments)]
fn slab(
    name: &'static str,
    why: &'static str,
    o: [f64; 3],
    d: [f64; 3],
    t: (f64, f64),
    lo: [f64; 3],
    hi: [f64; 3],
    hit: bool,
    f64_wrong: bool,
    ref_wrong: bool,
    float_wrong: &[FloatFormat],
) -> SlabCase {
    SlabCase {
        name,
        why,
        ray: ray(o, d, t),
        bx: aabb(lo, hi),
        hit,
        textbook_f64_wrong: f64_wrong,
        ref_f64_wrong: ref_wrong,
        textbook_float_wrong_in: float_wrong.to_vec(),
    }
}

/// The slab corner cases: the one catalogue of `tb/tests/slab/fix_corners.rs` and
/// `tb/tests/slab/float_corners.rs`. Each line: name, why, origin, direction, t range, box, then the
/// exact hit, whether the f64 textbook test and the f64 reference are wrong, and the float formats in
/// which the textbook test is wrong.
#[rustfmt::skip]
pub fn slab_cases() -> Vec<SlabCase> {
    let (u0, u1) = ([0.0; 3], [1.0; 3]);
    let all = &SLAB_FLOAT_FORMATS;
    let none: &[FloatFormat] = &[];
    let r = (0.0, INF);
    vec![
        // (1 - 1) * inf = NaN on y; the comparisons then put -inf into the exit.
        slab("origin_on_slab_plane_zero_dir", "origin on the upper y plane, dir.y = +0: (1 - 1) * inf = NaN becomes a miss",
            [-4.0, 1.0, 0.5], [1.0, 0.0, 0.0], r, u0, u1, true, true, false, all),
        // With -0 the NaN of 0 x -inf lands where the textbook comparisons ignore it: right by luck.
        slab("origin_on_slab_plane_negative_zero_dir", "as above with dir.y = -0: the NaN lands where the comparisons ignore it",
            [-4.0, 1.0, 0.5], [1.0, -0.0, 0.0], r, u0, u1, true, false, false, none),
        // (0 - 0) * inf = NaN; the swap puts +inf into the entry.
        slab("origin_on_lower_slab_plane_zero_dir", "origin on the lower y plane, dir.y = +0: (0 - 0) * inf = NaN becomes a miss",
            [-4.0, 0.0, 0.5], [1.0, 0.0, 0.0], r, u0, u1, true, true, false, all),
        slab("origin_on_lower_slab_plane_negative_zero_dir", "as above with dir.y = -0: right by luck",
            [-4.0, 0.0, 0.5], [1.0, -0.0, 0.0], r, u0, u1, true, false, false, none),
        slab("parallel_outside_slab", "zero direction component outside the slab",
            [-4.0, 1.5, 0.5], [1.0, 0.0, 0.0], r, u0, u1, false, false, false, none),
        slab("grazing_corner_diagonal", "diagonal ray through the corner (1, 1, 1)",
            [-1.0, -1.0, -1.0], [0.3, 0.3, 0.3], r, u1, [2.0; 3], true, false, false, none),
        slab("grazing_edge_shallow", "shallow ray along the top face, sinking into it",
            [-3.0, 1.0, 0.25], [1.0, -1e-9, 0.1], r, u0, u1, true, false, false, none),
        slab("leaving_edge_shallow", "shallow ray along the top face, rising off it",
            [-3.0, 1.0, 0.25], [1.0, 1e-9, 0.1], r, u0, u1, false, false, false, none),
        slab("t_max_ends_on_entry_face", "t_max ends exactly on the entry face",
            [-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], (0.0, 1.0), u0, u1, true, false, false, none),
        // bfloat16 and e6m5 round t_max = 0.999 to nearest, 1.0: a false hit (harmless; ours round t_max up
        // and report the same extra work).
        slab("t_max_just_before_entry_face", "t_max = 0.999 rounds to nearest 1.0 in the short formats: a false hit",
            [-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], (0.0, 0.999), u0, u1, false, false, false,
            &[FloatFormat::BF16, FloatFormat { e: 6, m: 5 }]),
        slab("origin_inside_box", "origin inside the box",
            [0.5, 0.5, 0.5], [0.6, -0.8, 0.0], r, u0, u1, true, false, false, none),
        slab("point_box_hit_exactly", "a point box on the ray",
            [-2.0, -2.0, 0.5], [1.0, 1.0, 0.0], r, [0.5; 3], [0.5; 3], true, false, false, none),
        slab("flat_box_crossed", "a box of zero thickness crossed",
            [0.5, -2.0, 0.5], [0.0, 1.0, 0.0], r, [0.0, 0.25, 0.0], [1.0, 0.25, 1.0], true, false, false, none),
        // The textbook swap of t0/t1 turns an inverted (empty) box into a valid one.
        slab("empty_box", "an inverted (empty) box: the t0/t1 swap makes it a valid one",
            [-4.0, 0.5, 0.5], [1.0, 0.0, 0.0], r, u1, u0, false, true, false, all),
        slab("subnormal_direction_component", "a subnormal direction component (1/d overflows)",
            [-4.0, 0.5, 0.5], [1.0, 5e-324, 0.0], r, u0, u1, true, false, false, none),
        slab("huge_direction_magnitude", "a direction near the top of f64's range",
            [-4.0, 0.5, 0.5], [1e300, 1e299, 0.0], r, u0, u1, true, false, false, none),
        slab("tiny_direction_magnitude", "a direction near the bottom of f64's range",
            [-4.0, 0.5, 0.5], [1e-300, 0.0, 0.0], r, u0, u1, true, false, false, none),
        slab("pointing_away", "the box behind the origin",
            [-4.0, 0.5, 0.5], [-1.0, 0.0, 0.0], r, u0, u1, false, false, false, none),
        slab("negative_t_range_behind_origin", "a t range behind the origin",
            [4.0, 0.5, 0.5], [1.0, 0.0, 0.0], (-INF, 0.0), u0, u1, true, false, false, none),
        slab("origin_at_scene_corner", "origin at the corner of the scene",
            [-8.0, -8.0, -8.0], [1.0, 1.0, 1.0], r, [7.0; 3], [8.0; 3], true, false, false, none),
        slab("box_is_whole_scene", "the box is the whole scene",
            [0.1, 0.2, 0.3], [0.0, 0.0, -1.0], r, [-8.0; 3], [8.0; 3], true, false, false, none),
        // Aimed at the corner (1, 1, 1); found by searching rays aimed at the unit box's corners (for
        // binary16): round-to-nearest puts the entry past the exit (Ize 2013), in f64 too (reference and textbook).
        slab("grazing_corner_fp16", "aimed at the corner (1, 1, 1): round-to-nearest puts the entry past the exit",
            [-3.5, 1.9, -0.9], [4.5, -0.9, 1.9], r, u0, u1, true, true, true,
            &[FloatFormat::FP16, FloatFormat { e: 6, m: 5 }]),
        // The same, found for binary32; the formats with 7 to 15 fraction bits miss it too (rounding the
        // inputs to nearest moves the ray off the corner, rounding the quotients does the rest).
        slab("grazing_corner_fp32", "aimed at the corner (1, 1, 1): round-to-nearest puts the entry past the exit",
            [-3.0, -2.0, 1.2], [4.0, 3.0, -0.2], r, u0, u1, true, false, false,
            &[FloatFormat::FP32, FloatFormat::E8M15, FloatFormat::BF16, FloatFormat::FP16]),
        // 1/d overflows the small formats; both methods must still find the box straight ahead.
        slab("tiny_direction_component", "1/d overflows the small formats",
            [-4.0, 0.5, 0.5], [1.0, 1e-9, 0.0], r, u0, u1, true, false, false, none),
    ]
}

fn plane(n: [f64; 3], w: f64) -> Plane {
    Plane { n: n.into(), w }
}

#[allow(clippy::too_many_arguments)]
fn cull(
    name: &'static str,
    why: &'static str,
    r: Ray,
    bx: Aabb,
    planes: Vec<Plane>,
    kept: bool,
    ref_wrong: bool,
    textbook_wrong: bool,
) -> CullCase {
    CullCase {
        name,
        why,
        ray: r,
        node: PlaneNode { bounds: bx, planes },
        kept,
        ref_wrong,
        textbook_wrong,
    }
}

/// The cull-plane failure cases.
#[rustfmt::skip]
pub fn cull_cases() -> Vec<CullCase> {
    let unit = aabb([0.0; 3], [1.0; 3]);
    let tiny = f64::powi(2.0, -60);
    vec![
        // n = (1, 1, 1), d = (1, -2^-60, -1): f64 sums 1 + (-2^-60) to 1 and then 1 - 1 to 0, so the plane
        // looks parallel, and the origin lies 2^-70 on its empty side: culled. Truly den = -2^-60: an entry
        // plane the ray crosses at t = 2^-70 / 2^-60 = 2^-10, and it stays in the box until t = 0.5.
        cull("den_rounds_to_zero",
            "n.d = 1 - 2^-60 - 1 rounds to 0: the plane looks parallel with the origin on its empty side, but the ray crosses it at t = 2^-10",
            ray([0.5; 3], [1.0, -tiny, -1.0], (0.0, INF)), unit,
            vec![plane([1.0; 3], -f64::powi(2.0, -70))], true, true, true),
        // Found by a seeded search (Pcg64 seed 2024, origins in the unit box, normals in [-1, 1]^3):
        // d = (n_y, -n_x, 0), so n.d = 0 exactly in both arithmetics, and w is
        // n.(o - c) rounded up, so the whole ray lies on the closed non-empty side. The rounded dot product
        // lands above w: s0 > 0, parallel on the empty side, culled — a whole segment [0, 1.03] lost.
        cull("parallel_ray_in_plane",
            "ray parallel to the plane, origin on it within an ulp: round-to-nearest makes s0 > 0 and the node is culled",
            ray([0.4907443903060372, 0.17515983066121166, 0.05299824813606624],
                [-0.4754791586189846, 0.3457004907404322, 0.0], (0.0, INF)), unit,
            vec![plane([-0.3457004907404322, -0.4754791586189846, 0.43471968961331164], -3.666606361073544e-2)],
            true, true, true),
        // Found by the same search: the origin is on the plane within an ulp (w = n.(o - c) rounded up),
        // the ray leaves into the empty side (den > 0). Truly the exit is t* = +1.7e-17 >= 0 = entry;
        // s0 rounds above zero, t* = -s0 / den = -1.8e-17 < 0: culled.
        cull("origin_on_plane_leaving",
            "origin on the plane within an ulp, leaving to the empty side: s0 rounds positive, t* < 0 = entry",
            ray([0.6624235116073713, 0.8189216074354158, 0.6679510529959723],
                [-0.652972121202783, 0.46023108172400695, 0.4227744557657047], (0.0, INF)), unit,
            vec![plane([-0.3194449786559832, 0.30248178518674607, -0.3721644594931588], -1.7922810906508307e-2)],
            true, true, true),
        // Found by a seeded search (Pcg64 seed 2024, short dyadic directions, normals in [-1, 1]^3): two
        // planes through the point c + (1/8, 0, 0), which the ray reaches at t = 1 (o and d are short
        // dyadics, so that is exact); one faces the ray (entry), one faces away (exit). Truly entry = exit = 1, a touching hit; s0 rounds in each plane's dot product and the
        // two quotients land one ulp apart, entry above exit: culled.
        cull("two_planes_meet_on_the_ray",
            "the ray crosses the line where an entry and an exit plane meet: the two rounded quotients cross",
            ray([1.1875, 1.169921875, -0.1953125], [-0.5625, -0.669921875, 0.6953125], (0.0, INF)), unit,
            vec![
                plane([0.9453960187387982, 0.8929299620320297, -0.04389481616780344], 0.9453960187387982 / 8.0),
                plane([-0.7764399865122869, 0.42220886804369995, 0.061233694032448494], -0.7764399865122869 / 8.0),
            ],
            true, true, true),
        // n = (-0, 1, -0), d = (1, -0, 0): every product n_a d_a is -0 and so is their sum. The branch-free
        // clip sends den = -0 to the exit side (-0 < 0 is false) and divides: -s0 / -0 = -inf with the
        // origin on the non-empty side (s0 = -0.25): exit = -inf, culled. The reference's den == 0 branch
        // is right.
        cull("negative_zero_den",
            "n.d = -0 (signed zeros): the branch-free clip computes -s0 / -0 = -inf as an exit and culls a parallel ray on the kept side",
            ray([-1.0, 0.25, 0.5], [1.0, -0.0, 0.0], (0.0, INF)), unit,
            vec![plane([-0.0, 1.0, -0.0], 0.0)], true, false, true),
    ]
}

/// The bundle failure cases.
#[rustfmt::skip]
pub fn bundle_cases() -> Vec<BundleCase> {
    let bx = aabb([0.1, 0.2, 0.3], [0.7, 0.9, 1.3]);
    let unit = aabb([0.0; 3], [1.0; 3]);
    let one = |o: [f64; 3], d: [f64; 3]| {
        let r = ray(o, d, (0.0, INF));
        (Bundle::of_ray(&r).expect("valid"), r)
    };
    let (b1, r1) = one([0.08055125741050695, -0.25863546762251666, -3.430578468071138],
        [0.13745780289558787, 0.1017727850182434, 0.9852652701951632]);
    let (b2, r2) = one([-0.1665720134972677, 2.2779736899854655, -1.6968057771085086],
        [0.326465786891572, -0.5191273870032574, 0.7898904012914936]);
    let fig7 = Bundle::new(
        (DVec3::new(0.45, 0.45, 3.0), DVec3::new(0.55, 0.55, 3.0)),
        (DVec3::new(-0.5, -0.05, -1.0), DVec3::new(0.5, 0.05, -1.0)),
        10.0, 10.0).expect("valid");
    let on_plane = Bundle::new(
        (DVec3::new(0.25, 1.0, 3.0), DVec3::new(0.5, 1.0, 3.0)),
        (DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.1, 0.0, -1.0)),
        10.0, 10.0).expect("valid");
    vec![
        // Found by a seeded search (Pcg64 seed 2024: origins in [-4, 4]^3, normalised directions aimed at
        // points of the box's z-parallel edges): aimed at the edge x = 0.7, y = 0.2, the ray passes it on
        // the outside (the exact test misses), and the rounded edge products say it hits.
        BundleCase { name: "grazing_edge_false_all_hit",
            why: "a one-ray bundle aimed at a silhouette edge, passing just outside: the rounded edge products say it hits",
            bundle: b1, bx, exact: (false, true), witness: r1, witness_hits: false,
            ref_wrong: true, corners_wrong: true },
        // Found by the same search: aimed at the edge x = 0.7, y = 0.9, the ray passes it on the inside (the
        // exact test hits), and the rounded differences and products make one edge condition fail.
        BundleCase { name: "grazing_edge_false_all_miss",
            why: "a one-ray bundle aimed at a silhouette edge, passing just inside: rounding fails one edge condition",
            bundle: b2, bx, exact: (true, false), witness: r2, witness_hits: true,
            ref_wrong: true, corners_wrong: true },
        // FIG. 7's straddling bundle, wide in x: the corner directions d.x = +-0.5 pass left and right of
        // the box, the straight-down ray of the middle hits. Sampling the corners says "all miss".
        BundleCase { name: "straddling_axis_corners_miss",
            why: "directions straddle x = 0: every corner ray passes beside the box, the middle ray (d.x = 0) hits",
            bundle: fig7, bx: unit, exact: (false, false),
            witness: ray([0.5, 0.5, 3.0], [0.0, 0.0, -1.0], (0.0, 10.0)), witness_hits: true,
            ref_wrong: false, corners_wrong: true },
        // Origins on the plane y = 1 with d.y = 0: every corner ray computes (1 - 1) * inf = NaN in the
        // textbook slab test and misses; every ray of the bundle hits.
        BundleCase { name: "zero_dir_on_slab_plane",
            why: "origins on the top y plane with d.y = 0: (1 - 1) * inf = NaN makes every corner ray miss",
            bundle: on_plane, bx: unit, exact: (true, false),
            witness: ray([0.25, 1.0, 3.0], [0.0, 0.0, -1.0], (0.0, 10.0)), witness_hits: true,
            ref_wrong: false, corners_wrong: true },
    ]
}

// ------------------------------------------------------------------------------------------------
// The naive methods not already in the crate
// ------------------------------------------------------------------------------------------------

/// The branch-free textbook plane clip (module doc): the reference slab interval, then per plane
/// `t = -s0 / den`, an entry when `den < 0` and an exit otherwise, merged with comparisons, with no
/// special case for `den = 0` (IEEE infinities are meant to do that work). Returns `true` when the node
/// is culled.
pub fn clip_textbook(ray: &Ray, node: &PlaneNode) -> bool {
    let s = crate::slab::reference::slab_ref(ray, &node.bounds);
    if !s.hit {
        return true;
    }
    let c = (node.bounds.min + node.bounds.max) * 0.5;
    let (mut entry, mut exit) = (s.t_entry, s.t_exit);
    for p in &node.planes {
        let s0 = p.n.dot(ray.origin - c) - p.w;
        let den = p.n.dot(ray.dir);
        let t = -s0 / den;
        if den < 0.0 {
            entry = if t > entry { t } else { entry };
        } else {
            exit = if t < exit { t } else { exit };
        }
    }
    entry > exit
}

/// The corner rays of a bundle: every corner of its origin box with every corner of its direction box,
/// with `t_max` = `t` (skipping the zero direction).
pub fn corner_rays(b: &Bundle, t: f64) -> Vec<Ray> {
    let mut out = Vec::new();
    for mo in 0..8 {
        for md in 0..8 {
            let pick = |lo: &[f64; 3], hi: &[f64; 3], m: usize| {
                DVec3::from(std::array::from_fn::<f64, 3, _>(|a| {
                    if m >> a & 1 == 0 {
                        lo[a]
                    } else {
                        hi[a]
                    }
                }))
            };
            let d = pick(&b.d_lo, &b.d_hi, md);
            if d == DVec3::ZERO {
                continue;
            }
            if let Ok(r) = Ray::new(pick(&b.o_lo, &b.o_hi, mo), d, 0.0, t) {
                if !out.contains(&r) {
                    out.push(r);
                }
            }
        }
    }
    out
}

/// The textbook per-ray loop over a bundle: its corner rays ([`corner_rays`]) through the f64 textbook
/// slab test, `(all_hit, all_miss)` = (every one hits with `t_max = t_lo`, none hits with `t_max = t_hi`).
pub fn corner_rays_textbook(b: &Bundle, bx: &Aabb) -> (bool, bool) {
    (
        corner_rays(b, b.t_lo).iter().all(|r| slab_textbook(r, bx)),
        !corner_rays(b, b.t_hi).iter().any(|r| slab_textbook(r, bx)),
    )
}

// ------------------------------------------------------------------------------------------------
// Running our models
// ------------------------------------------------------------------------------------------------

/// The finest grid of `fmt` over the smallest box holding `points`.
pub fn enclosing_map(fmt: FixFormat, points: &[DVec3]) -> Result<GridMap, Error> {
    let lo = points.iter().fold(DVec3::INFINITY, |a, p| a.min(*p));
    let hi = points.iter().fold(DVec3::NEG_INFINITY, |a, p| a.max(*p));
    GridMap::for_bounds(fmt, lo, hi)
}

fn fixed_presets() -> [(&'static str, FixFormat); 3] {
    [
        ("b8", FixFormat::b8()),
        ("b12", FixFormat::b12()),
        ("b16", FixFormat::b16()),
    ]
}

fn not_conservative(tester: &str, case: &str, fmt: &str, what: String) -> Error {
    Error::Io(format!(
        "stability catalogue: {tester} case `{case}` in {fmt}: our model is not conservative: {what}"
    ))
}

/// A model's answer against the exact one, once checked conservative.
fn cell(same: bool, looser: &str) -> String {
    if same {
        "ok".into()
    } else {
        format!("ok ({looser})")
    }
}

/// Our slab models on a case, one cell per format of [`format_names`]; an error when one is not
/// conservative.
pub fn slab_ours(c: &SlabCase) -> Result<Vec<String>, Error> {
    let exact = slab_exact(&c.ray, &c.bx);
    let pts = [c.ray.origin, c.bx.min, c.bx.max];
    let mut out = Vec::new();
    let verdict = |fmt: &str, v: Verdict| match v {
        Verdict::Agree => Ok("ok".to_string()),
        Verdict::FalseHit => Ok("ok (false hit)".to_string()),
        Verdict::Violation(why) => Err(not_conservative("slab", c.name, fmt, why)),
    };
    for (name, fmt) in fixed_presets() {
        let map = enclosing_map(fmt, &pts)?;
        let (_, _, _, v) = crate::slab::check::check_fix(&map, &c.ray, &c.bx)?;
        out.push(verdict(name, v)?);
    }
    for (name, f) in FLOAT_PRESETS {
        let o = crate::slab::float::slab_float(
            &f,
            &crate::slab::float::quantize_ray(&f, &c.ray)?,
            &crate::slab::float::quantize_box(&f, &c.bx)?,
        );
        out.push(verdict(
            name,
            crate::slab::float::judge_float(&f, &o, &exact),
        )?);
    }
    Ok(out)
}

/// Judges a cull-plane model: `hit` is its answer, `stored` the exact clip by its stored planes, with the
/// interval as exact world values. `world_kept` is the exact clip by the world planes.
fn judge_cull(
    case: &str,
    fmt: &str,
    world_kept: bool,
    stored: &ExactHit,
    hit: bool,
    interval: impl FnOnce() -> Option<(crate::exact::Ext, crate::exact::Ext)>,
) -> Result<String, Error> {
    if world_kept && !hit {
        return Err(not_conservative(
            "cull-plane",
            case,
            fmt,
            "culls a node the exact clip keeps".into(),
        ));
    }
    if let Verdict::Violation(why) = judge(stored, hit, interval) {
        return Err(not_conservative("cull-plane", case, fmt, why));
    }
    Ok(cell(hit == world_kept, "kept"))
}

/// Our cull-plane models on a case (planes fitted outward to the part of the box on their non-empty side,
/// as `rtu run --k` does); an error when one is not conservative.
pub fn cull_ours(c: &CullCase) -> Result<Vec<String>, Error> {
    use crate::plane::fix::{self as pf, CullFixFormat, FixNode, NodeFixRay};
    use crate::plane::float::{self as pl, CullFloatFormat, FloatNode, NodeFloatRay};
    let b = &c.node.bounds;
    let world_kept = clip_exact_world(&c.ray, &c.node).hit;
    let k = c.node.planes.len();
    let pts: Vec<Vec<DVec3>> = c.node.planes.iter().map(|p| region_points(b, p)).collect();
    let mut out = Vec::new();
    for (name, fmt) in fixed_presets() {
        let cf = CullFixFormat::over(fmt);
        let map = enclosing_map(fmt, &[c.ray.origin, b.min, b.max])?;
        let r = NodeFixRay {
            ray: map.quantize_ray(&c.ray)?,
            dir: pf::quantize_dir(&cf, &c.ray)?,
        };
        let mut node = FixNode {
            b: map.quantize_box(b)?,
            ..Default::default()
        };
        for (i, p) in c.node.planes.iter().enumerate() {
            node.planes[i] = pf::fit_plane(&cf, &map, &node.b, p.n, &pts[i])?;
        }
        let exact: Vec<_> = node.planes[..k]
            .iter()
            .map(|p| p.to_exact(&map, &node.b))
            .collect();
        let stored = clip_exact(&c.ray, b, &exact);
        let o = pf::node_fix(&cf, k, &r, &node);
        out.push(judge_cull(
            c.name,
            name,
            world_kept,
            &stored,
            o.hit,
            || {
                Some((
                    r.ray.t_world(&fmt, o.t_entry),
                    r.ray.t_world(&fmt, o.t_exit),
                ))
            },
        )?);
    }
    for (name, f) in FLOAT_PRESETS {
        let cf = CullFloatFormat::over(f);
        let r = NodeFloatRay {
            ray: crate::slab::float::quantize_ray(&f, &c.ray)?,
            dir: pl::quantize_dir(&cf, &c.ray)?,
        };
        let mut node = FloatNode {
            b: crate::slab::float::quantize_box(&f, b)?,
            ..Default::default()
        };
        for (i, p) in c.node.planes.iter().enumerate() {
            node.planes[i] = pl::fit_plane(&cf, &node.b, p.n, &pts[i])?;
        }
        let exact: Vec<_> = node.planes[..k]
            .iter()
            .map(|p| p.to_exact(&f, &node.b))
            .collect();
        let stored = clip_exact(&c.ray, b, &exact);
        let o = pl::node_float(&cf, k, &r, &node);
        out.push(judge_cull(
            c.name,
            name,
            world_kept,
            &stored,
            o.hit,
            || pl::out_interval(&f, &o),
        )?);
    }
    Ok(out)
}

/// The rays a bundle answer is checked against: the witness and the corner rays, each with its exact hit.
fn bundle_truth(c: &BundleCase) -> Vec<(Ray, bool)> {
    let mut rays = vec![c.witness];
    rays.extend(corner_rays(&c.bundle, c.bundle.t_lo));
    rays.extend(corner_rays(&c.bundle, c.bundle.t_hi));
    rays.into_iter()
        .map(|r| (r, slab_exact(&r, &c.bx).hit))
        .collect()
}

/// Checks a bundle answer `got = (all_hit, all_miss)` against the exact oracle `exact` and the rays
/// `truth`: an error message for a broken promise.
fn bundle_broken(got: (bool, bool), exact: (bool, bool), truth: &[(Ray, bool)]) -> Option<String> {
    let (all_hit, all_miss) = got;
    if all_hit && all_miss {
        return Some("both all hit and all miss".into());
    }
    if all_hit {
        if let Some((r, _)) = truth.iter().find(|(_, h)| !h) {
            return Some(format!("all hit, but the ray {r:?} misses"));
        }
        if !exact.0 {
            return Some("all hit where the exact oracle is not".into());
        }
    }
    if all_miss {
        if let Some((r, _)) = truth.iter().find(|(_, h)| *h) {
            return Some(format!("all miss, but the ray {r:?} hits"));
        }
        if !exact.1 {
            return Some("all miss where the exact oracle is not".into());
        }
    }
    None
}

/// Our bundle models on a case; an error when one is not conservative.
pub fn bundle_ours(c: &BundleCase) -> Result<Vec<String>, Error> {
    use crate::bundle::fix::{decide_fix, BundleFixFormat};
    let exact = decide_exact(&c.bundle, &c.bx)?;
    let truth = bundle_truth(c);
    let pts = [
        DVec3::from(c.bundle.o_lo),
        DVec3::from(c.bundle.o_hi),
        c.bx.min,
        c.bx.max,
    ];
    let mut out = Vec::new();
    let mut judge_one = |fmt: &str, got: (bool, bool)| -> Result<(), Error> {
        if let Some(why) = bundle_broken(got, exact, &truth) {
            return Err(not_conservative("bundle", c.name, fmt, why));
        }
        out.push(cell(got == exact, "undecided"));
        Ok(())
    };
    for ((name, _), bf) in fixed_presets().into_iter().zip(BundleFixFormat::presets()) {
        let map = enclosing_map(bf.base, &pts)?;
        judge_one(name, decide_fix(&bf, &map, &c.bundle, &c.bx)?)?;
    }
    for (name, f) in FLOAT_PRESETS {
        judge_one(
            name,
            crate::bundle::float::decide_float(&f, &c.bundle, &c.bx)?,
        )?;
    }
    Ok(out)
}

// ------------------------------------------------------------------------------------------------
// The table
// ------------------------------------------------------------------------------------------------

/// One row of the stability table: a case on which a naive method fails.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub tester: &'static str,
    pub case: &'static str,
    pub why: &'static str,
    /// The exact answer.
    pub exact: String,
    /// The naive methods that fail, with their answers.
    pub naive: String,
    /// Our models, one cell per [`format_names`] column: `ok` (the exact answer), `ok (...)`
    /// (conservative, looser: a false hit, a kept node, an undecided bundle).
    pub ours: Vec<String>,
}

/// `fp32`, `bf16`, `fp16` for the presets, `eXmY` otherwise.
pub fn float_label(f: &FloatFormat) -> String {
    FLOAT_PRESETS
        .iter()
        .find(|(_, g)| g == f)
        .map_or_else(|| f.name(), |(n, _)| n.to_string())
}

fn hit_word(h: bool) -> &'static str {
    if h {
        "hit"
    } else {
        "miss"
    }
}

fn kept_word(k: bool) -> &'static str {
    if k {
        "kept"
    } else {
        "culled"
    }
}

fn bundle_word(d: (bool, bool)) -> &'static str {
    match d {
        (true, false) => "all hit",
        (false, true) => "all miss",
        (false, false) => "undecided",
        (true, true) => "both (invalid)",
    }
}

/// Is a naive bundle answer contradicted by the exact oracle or the witness?
fn bundle_naive_wrong(c: &BundleCase, got: (bool, bool), exact: (bool, bool)) -> bool {
    (got.0 && (!exact.0 || !c.witness_hits)) || (got.1 && (!exact.1 || c.witness_hits))
}

/// Every failure case of the catalogue as a row, our models run and checked on each. Also runs our models
/// on the slab cases where no naive method fails (they must be conservative there too), without a row.
/// An error when a model is not conservative, or an input does not quantise.
pub fn table() -> Result<Vec<Row>, Error> {
    let mut rows = Vec::new();
    for c in slab_cases() {
        let ours = slab_ours(&c)?;
        let exact = slab_exact(&c.ray, &c.bx).hit;
        let mut naive = Vec::new();
        let rf = crate::slab::reference::slab_ref(&c.ray, &c.bx).hit;
        if rf != exact {
            naive.push(format!("f64 reference: {}", hit_word(rf)));
        }
        let tb = slab_textbook(&c.ray, &c.bx);
        if tb != exact {
            naive.push(format!("textbook f64: {}", hit_word(tb)));
        }
        let wrong: Vec<String> = SLAB_FLOAT_FORMATS
            .iter()
            .filter(|f| crate::slab::float::slab_float_textbook(f, &c.ray, &c.bx) != exact)
            .map(float_label)
            .collect();
        if !wrong.is_empty() {
            naive.push(format!(
                "textbook {}: {}",
                wrong.join("/"),
                hit_word(!exact)
            ));
        }
        if naive.is_empty() {
            continue;
        }
        rows.push(Row {
            tester: "slab",
            case: c.name,
            why: c.why,
            exact: hit_word(exact).into(),
            naive: naive.join("; "),
            ours,
        });
    }
    for c in cull_cases() {
        let ours = cull_ours(&c)?;
        let kept = clip_exact_world(&c.ray, &c.node).hit;
        let mut naive = Vec::new();
        let r = clip_ref(&c.ray, &c.node);
        if (r.culled && kept) || r.t_entry.is_nan() || r.t_exit.is_nan() {
            naive.push(format!("f64 reference: {}", kept_word(!r.culled)));
        }
        let t = clip_textbook(&c.ray, &c.node);
        if t && kept {
            naive.push(format!("branch-free textbook: {}", kept_word(!t)));
        }
        if naive.is_empty() {
            continue;
        }
        rows.push(Row {
            tester: "cull-plane",
            case: c.name,
            why: c.why,
            exact: kept_word(kept).into(),
            naive: naive.join("; "),
            ours,
        });
    }
    for c in bundle_cases() {
        let ours = bundle_ours(&c)?;
        let exact = decide_exact(&c.bundle, &c.bx)?;
        let mut naive = Vec::new();
        let r = decide_ref(&c.bundle, &c.bx)?;
        if bundle_naive_wrong(&c, r, exact) {
            naive.push(format!("f64 reference: {}", bundle_word(r)));
        }
        let k = corner_rays_textbook(&c.bundle, &c.bx);
        if bundle_naive_wrong(&c, k, exact) {
            naive.push(format!("corner rays, textbook: {}", bundle_word(k)));
        }
        if naive.is_empty() {
            continue;
        }
        rows.push(Row {
            tester: "bundle",
            case: c.name,
            why: c.why,
            exact: format!(
                "{}; witness ray {}",
                bundle_word(exact),
                if c.witness_hits { "hits" } else { "misses" }
            ),
            naive: naive.join("; "),
            ours,
        });
    }
    Ok(rows)
}

fn header() -> Vec<String> {
    let mut h: Vec<String> = [
        "tester",
        "case",
        "why naive fails",
        "exact",
        "naive (wrong)",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    h.extend(format_names());
    h
}

fn fields(r: &Row) -> Vec<String> {
    let mut f = vec![
        r.tester.to_string(),
        r.case.to_string(),
        r.why.to_string(),
        r.exact.clone(),
        r.naive.clone(),
    ];
    f.extend(r.ours.iter().cloned());
    f
}

/// The table in Markdown.
pub fn render_markdown(rows: &[Row]) -> String {
    let line = |f: Vec<String>| format!("| {} |\n", f.join(" | ").replace('\n', " "));
    let h = header();
    let mut s = line(h.clone());
    s += &line(h.iter().map(|_| "---".to_string()).collect());
    for r in rows {
        s += &line(
            fields(r)
                .into_iter()
                .map(|x| x.replace('|', "\\|"))
                .collect(),
        );
    }
    s
}

/// The table as CSV (RFC 4180 quoting).
pub fn render_csv(rows: &[Row]) -> Result<String, Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let io = |e: csv::Error| Error::Io(format!("stability CSV: {e}"));
    w.write_record(header()).map_err(io)?;
    for r in rows {
        w.write_record(fields(r)).map_err(io)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| Error::Io(format!("stability CSV: {e}")))?;
    String::from_utf8(bytes).map_err(|e| Error::Io(format!("stability CSV: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slab_exact_oracle_gives_the_stated_answers() {
        for c in slab_cases() {
            assert_eq!(slab_exact(&c.ray, &c.bx).hit, c.hit, "{}", c.name);
        }
    }

    #[test]
    fn slab_textbook_fails_exactly_where_stated() {
        for c in slab_cases() {
            assert_eq!(
                slab_textbook(&c.ray, &c.bx) != c.hit,
                c.textbook_f64_wrong,
                "{}: f64 textbook",
                c.name
            );
            assert_eq!(
                crate::slab::reference::slab_ref(&c.ray, &c.bx).hit != c.hit,
                c.ref_f64_wrong,
                "{}: f64 reference",
                c.name
            );
            for f in SLAB_FLOAT_FORMATS {
                assert_eq!(
                    crate::slab::float::slab_float_textbook(&f, &c.ray, &c.bx) != c.hit,
                    c.textbook_float_wrong_in.contains(&f),
                    "{}: float textbook in {}",
                    c.name,
                    f.name()
                );
            }
        }
    }

    #[test]
    fn slab_names_are_unique_and_every_case_fits_the_float_presets() {
        let cases = slab_cases();
        for (i, c) in cases.iter().enumerate() {
            assert!(cases[..i].iter().all(|o| o.name != c.name), "{}", c.name);
            assert!(slab_ours(c).is_ok(), "{}", c.name);
        }
    }

    #[test]
    fn cull_exact_clip_gives_the_stated_answers() {
        for c in cull_cases() {
            assert_eq!(clip_exact_world(&c.ray, &c.node).hit, c.kept, "{}", c.name);
        }
    }

    #[test]
    fn cull_naive_methods_fail_exactly_where_stated() {
        for c in cull_cases() {
            let r = clip_ref(&c.ray, &c.node);
            assert_eq!(r.culled && c.kept, c.ref_wrong, "{}: reference", c.name);
            let t = clip_textbook(&c.ray, &c.node);
            assert_eq!(t && c.kept, c.textbook_wrong, "{}: textbook", c.name);
            assert!(c.ref_wrong || c.textbook_wrong, "{}: nothing fails", c.name);
        }
    }

    #[test]
    fn textbook_clip_is_right_on_plain_cases() {
        // A node the clip keeps, one it culls by an entry plane, and a parallel ray on the empty side.
        let node = PlaneNode {
            bounds: aabb([0.0; 3], [2.0; 3]),
            planes: vec![plane([1.0, 1.0, 0.0], 0.0)],
        };
        let along = |y: f64, t: f64| ray([3.0, y, 1.0], [-1.0, 0.0, 0.0], (0.0, t));
        assert!(!clip_textbook(&along(1.75, 10.0), &node));
        assert!(clip_textbook(&along(1.75, 2.5), &node));
        let par = PlaneNode {
            bounds: node.bounds,
            planes: vec![plane([0.0, 1.0, 0.0], 0.5)],
        };
        assert!(clip_textbook(
            &ray([-1.0, 1.9, 1.0], [1.0, 0.0, 0.0], (0.0, 10.0)),
            &par
        ));
        assert!(!clip_textbook(
            &ray([-1.0, 1.4, 1.0], [1.0, 0.0, 0.0], (0.0, 10.0)),
            &par
        ));
    }

    #[test]
    fn bundle_exact_oracle_and_witness_give_the_stated_answers() {
        for c in bundle_cases() {
            assert_eq!(
                decide_exact(&c.bundle, &c.bx).unwrap(),
                c.exact,
                "{}",
                c.name
            );
            assert!(c.bundle.contains(&c.witness), "{}: witness outside", c.name);
            assert_eq!(
                slab_exact(&c.witness, &c.bx).hit,
                c.witness_hits,
                "{}",
                c.name
            );
            // The oracle's decision agrees with the witness (Theorems 2a and 2b of crate::bundle::edge).
            assert!(
                !c.exact.0 || c.witness_hits,
                "{}: all hit, witness misses",
                c.name
            );
            assert!(
                !c.exact.1 || !c.witness_hits,
                "{}: all miss, witness hits",
                c.name
            );
        }
    }

    #[test]
    fn bundle_naive_methods_fail_exactly_where_stated() {
        for c in bundle_cases() {
            let r = decide_ref(&c.bundle, &c.bx).unwrap();
            let k = corner_rays_textbook(&c.bundle, &c.bx);
            assert_eq!(
                bundle_naive_wrong(&c, r, c.exact),
                c.ref_wrong,
                "{}: ref {r:?}",
                c.name
            );
            assert_eq!(
                bundle_naive_wrong(&c, k, c.exact),
                c.corners_wrong,
                "{}: corners {k:?}",
                c.name
            );
            // Wrong means contradicted by the witness itself, not only by the (incomplete) oracle.
            for (wrong, got) in [(c.ref_wrong, r), (c.corners_wrong, k)] {
                if wrong {
                    assert!(
                        (got.0 && !c.witness_hits) || (got.1 && c.witness_hits),
                        "{}: {got:?} against the witness",
                        c.name
                    );
                }
            }
        }
    }

    #[test]
    fn corner_rays_are_rays_of_the_bundle() {
        for c in bundle_cases() {
            let rays = corner_rays(&c.bundle, c.bundle.t_lo);
            assert!(!rays.is_empty());
            assert!(rays.iter().all(|r| c.bundle.contains(r)), "{}", c.name);
        }
    }

    #[test]
    fn bundle_check_catches_a_false_answer() {
        let c = &bundle_cases()[0];
        let truth = bundle_truth(c);
        assert!(bundle_broken((true, false), c.exact, &truth).is_some());
        assert!(bundle_broken((true, true), c.exact, &truth).is_some());
        assert!(bundle_broken((false, false), c.exact, &truth).is_none());
    }

    #[test]
    fn cull_check_catches_a_culled_node() {
        let c = &cull_cases()[0];
        let stored = clip_exact_world(&c.ray, &c.node);
        assert!(judge_cull(c.name, "x", true, &stored, false, || None).is_err());
    }

    #[test]
    fn ours_are_conservative_on_every_case_and_the_table_lists_every_failure() {
        let rows = table().unwrap_or_else(|e| panic!("{e}"));
        let slab_failures = slab_cases()
            .iter()
            .filter(|c| {
                c.textbook_f64_wrong || c.ref_f64_wrong || !c.textbook_float_wrong_in.is_empty()
            })
            .count();
        assert_eq!(
            rows.len(),
            slab_failures + cull_cases().len() + bundle_cases().len()
        );
        for r in &rows {
            assert_eq!(r.ours.len(), format_names().len());
            assert!(r.ours.iter().all(|c| c.starts_with("ok")), "{r:?}");
            assert!(!r.naive.is_empty());
        }
        let md = render_markdown(&rows);
        assert_eq!(md.lines().count(), rows.len() + 2);
        let csv = render_csv(&rows).unwrap();
        let mut rd = csv::Reader::from_reader(csv.as_bytes());
        assert_eq!(rd.records().count(), rows.len());
    }
}
