//! The bundle models against the truth: the single-ray edge test against the slab oracle, the exact bundle
//! oracle against its rays, and both datapaths (fixed-point presets, float formats) against the exact
//! oracle and the exact per-ray results, on random and adversarial bundles. Each test prints its counts
//! (run with `--nocapture`).

use glam::DVec3;
use golden::bundle::check::{judge, oracle, truth, Tally};
use golden::bundle::edge::{
    conditions_hold, decide_exact, exact_box, exact_bundle, ray_hits_exact, ray_hits_ref, Bundle,
    BundleOf, ExactArith, Test,
};
use golden::bundle::fix::{self as bundle_fix, BundleFixFormat};
use golden::bundle::float as bundle_float;
use golden::bundle::gen::{BundleCase, BundleGen};
use golden::exact::slab_exact;
use golden::format::fixed::GridMap;
use golden::format::float::FloatFormat;
use golden::geom::{Aabb, Ray};
use golden::slab::gen::{GenKind, SlabGen};
use golden::slab::reference::slab_ref;
use std::time::Instant;

/// Bundles per datapath campaign (each against the exact per-ray results and the exact oracle).
const BUNDLES: usize = 100_000;

fn scene() -> (DVec3, DVec3) {
    (DVec3::splat(-100.0), DVec3::splat(100.0))
}

fn campaign(seed: u64) -> impl Iterator<Item = BundleCase> {
    let (lo, hi) = scene();
    BundleGen::new(seed, lo, hi, 0.6)
}

/// Asserts a campaign found no violation and is not vacuous: both answers are given on a real share of
/// the bundles.
fn assert_clean(name: &str, t: &Tally) {
    assert_eq!(
        t.violation_count, 0,
        "{name}: {} violations, first: {}",
        t.violation_count, t.violations[0]
    );
    let min = t.bundles / 20;
    assert!(t.all_hit > min && t.all_miss > min, "{name}: {t:?}");
}

#[test]
fn bundle_single_ray_edge_test_equals_the_slab_oracle() {
    let (lo, hi) = scene();
    let n = 200_000;
    let (mut hits, mut edge_wrong, mut slab_wrong) = (0, 0, 0);
    let start = Instant::now();
    for (ray, b) in SlabGen::new(GenKind::Mixed, lo, hi, 1.0 / 64.0, 11).take(n) {
        let truth = slab_exact(&ray, &b).hit;
        hits += usize::from(truth);
        assert_eq!(
            ray_hits_exact(&ray, &b).unwrap(),
            truth,
            "edge test disagrees with the slab oracle: {ray:?} {b:?}"
        );
        edge_wrong += usize::from(ray_hits_ref(&ray, &b).unwrap() != truth);
        slab_wrong += usize::from(slab_ref(&ray, &b).hit != truth);
    }
    println!(
        "single ray: {n} rays ({hits} hits), exact edge test == slab oracle on all; wrong in f64 (round to \
         nearest): edge test {edge_wrong}, slab {slab_wrong}; {:.1} s",
        start.elapsed().as_secs_f64()
    );
    assert!(hits > n / 10 && hits < n * 9 / 10);
    // Away from grazing configurations the f64 reference is the truth.
    for (ray, b) in SlabGen::new(GenKind::Uniform, lo, hi, 1.0 / 64.0, 12).take(n / 4) {
        assert_eq!(
            ray_hits_ref(&ray, &b).unwrap(),
            slab_exact(&ray, &b).hit,
            "{ray:?} {b:?}"
        );
    }
}

#[test]
fn bundle_f64_reference_is_exact_when_every_product_is() {
    // Small integers: every difference and product is exact in f64, so the reference is the oracle.
    let (lo, hi) = (DVec3::splat(-16.0), DVec3::splat(16.0));
    let mut g = BundleGen::new(21, lo, hi, 0.7);
    let round = |v: f64| v.round();
    for _ in 0..20_000 {
        let c = g.next_case();
        let b = c.bundle;
        let b = Bundle {
            o_lo: b.o_lo.map(f64::floor),
            o_hi: b.o_hi.map(f64::ceil),
            d_lo: b.d_lo.map(|d| (d * 4.0).floor()),
            d_hi: b.d_hi.map(|d| (d * 4.0).ceil()),
            t_lo: round(b.t_lo).min(64.0),
            t_hi: if b.t_hi.is_finite() {
                round(b.t_hi).max(round(b.t_lo)).min(64.0)
            } else {
                b.t_hi
            },
        };
        let bx = Aabb {
            min: c.bounds.min.floor(),
            max: c.bounds.max.ceil(),
        };
        assert_eq!(
            golden::bundle::edge::decide_ref(&b, &bx).unwrap(),
            decide_exact(&b, &bx).unwrap(),
            "{b:?} {bx:?}"
        );
    }
}

/// The 2^7 corner rays of a bundle (each origin and direction component and t_max at an end).
fn corner_rays(b: &Bundle) -> Vec<Ray> {
    (0..128u32)
        .map(|k| {
            let bit = |i: u32| k >> i & 1 == 1;
            let pick = |lo: f64, hi: f64, i: u32| if bit(i) { hi } else { lo };
            Ray {
                origin: DVec3::from_array(std::array::from_fn(|a| {
                    pick(b.o_lo[a], b.o_hi[a], a as u32)
                })),
                dir: DVec3::from_array(std::array::from_fn(|a| {
                    pick(b.d_lo[a], b.d_hi[a], 3 + a as u32)
                })),
                t_min: 0.0,
                t_max: pick(b.t_lo, b.t_hi, 6),
            }
        })
        .collect()
}

#[test]
fn bundle_exact_oracle_is_sound_and_allhit_is_exact_without_straddling() {
    let start = Instant::now();
    let mut tally = Tally::default();
    let (mut exact_checked, mut straddling_missed) = (0, 0);
    for c in campaign(31).take(6_000) {
        let corners = corner_rays(&c.bundle);
        let corner_truth: Vec<bool> = corners
            .iter()
            .map(|r| slab_exact(r, &c.bounds).hit)
            .collect();
        let t = truth(&c);
        let oracle = oracle(&c);
        tally.add(&c, &t, Some(oracle), oracle);
        // Sound on the corners too (the listed rays are checked by the tally).
        let every = corner_truth.iter().all(|&h| h);
        assert!(!oracle.0 || every, "false all-hit on a corner ray: {c:?}");
        assert!(
            !oracle.1 || corner_truth.iter().all(|&h| !h),
            "false all-miss on a corner ray: {c:?}"
        );
        // Exact: without a straddling axis, AllHit fails only when some corner ray misses.
        if c.bundle.straddles() {
            straddling_missed += usize::from(every && !oracle.0);
        } else {
            exact_checked += 1;
            assert_eq!(
                oracle.0, every,
                "AllHit not exact on a non-straddling bundle: {c:?}"
            );
        }
    }
    println!(
        "{}; {:.1} s",
        tally.report("exact oracle"),
        start.elapsed().as_secs_f64()
    );
    println!(
        "exact oracle: AllHit == 'all 128 corner rays hit' on {exact_checked} non-straddling bundles; \
         {straddling_missed} straddling bundles with every corner hitting were not decided"
    );
    assert_clean("exact oracle", &tally);
}

#[test]
fn bundle_one_ray_bundles_are_exact_on_the_fixed_datapath() {
    let (lo, hi) = scene();
    let start = Instant::now();
    for bf in BundleFixFormat::presets() {
        let map = GridMap::for_bounds(bf.base, lo, hi).unwrap();
        let mut g = BundleGen::new(41, lo, hi, 1.0);
        let (mut hits, n) = (0, 30_000);
        for _ in 0..n {
            let c = g.grid_one_ray(&map);
            let hit = slab_exact(&c.rays[0], &c.bounds).hit;
            hits += usize::from(hit);
            let q = bundle_fix::quantize_bundle(&bf, &map, &c.bundle).unwrap();
            let p = bundle_fix::quantize_box_pair(&map, &c.bounds).unwrap();
            assert!(
                q.o_lo == q.o_hi && q.d_lo == q.d_hi && q.t_lo == q.t_hi,
                "not exact: {q:?} {c:?}"
            );
            assert_eq!(p.inner, p.outer);
            let got = (
                bundle_fix::all_hit_fix(&bf, &q, &p.inner),
                bundle_fix::all_miss_fix(&bf, &q, &p.outer),
            );
            assert_eq!(got, (hit, !hit), "{} {c:?} {q:?}", bf.name());
            assert_eq!(
                decide_exact(&c.bundle, &c.bounds).unwrap(),
                (hit, !hit),
                "{c:?}"
            );
            assert_eq!(ray_hits_exact(&c.rays[0], &c.bounds).unwrap(), hit, "{c:?}");
        }
        println!("{}: {n} on-grid single rays ({hits} hits) exact", bf.name());
        assert!(hits > n / 10 && hits < n * 9 / 10, "{hits} of {n}");
    }
    println!("one-ray exactness: {:.1} s", start.elapsed().as_secs_f64());
}

/// A named datapath: `(all_hit, all_miss)` of a case.
type Datapath<'a> = (String, Box<dyn Fn(&BundleCase) -> (bool, bool) + 'a>);

/// Runs datapaths over one campaign against the exact oracle and the listed rays, and checks each.
fn run_datapaths(seed: u64, dps: &[Datapath]) {
    let start = Instant::now();
    let mut tallies: Vec<Tally> = dps.iter().map(|_| Tally::default()).collect();
    for c in campaign(seed).take(BUNDLES) {
        let t = truth(&c);
        let oracle = oracle(&c);
        for ((_, dp), tally) in dps.iter().zip(&mut tallies) {
            tally.add(&c, &t, Some(oracle), dp(&c));
        }
    }
    let secs = start.elapsed().as_secs_f64();
    for ((name, _), tally) in dps.iter().zip(&tallies) {
        println!("{}; {secs:.1} s", tally.report(name));
    }
    for ((name, _), tally) in dps.iter().zip(&tallies) {
        assert_clean(name, tally);
    }
}

/// A datapath as a boxed closure with its name.
fn datapath<'a>(name: String, dp: impl Fn(&BundleCase) -> (bool, bool) + 'a) -> Datapath<'a> {
    (name, Box::new(dp))
}

#[test]
fn bundle_fixed_datapath_is_conservative() {
    let (lo, hi) = scene();
    let dps: Vec<Datapath> = BundleFixFormat::presets()
        .into_iter()
        .map(|bf| {
            let map = GridMap::for_bounds(bf.base, lo, hi).unwrap();
            datapath(format!("fixed {}", bf.name()), move |c| {
                bundle_fix::decide_fix(&bf, &map, &c.bundle, &c.bounds).unwrap()
            })
        })
        .collect();
    run_datapaths(51, &dps);
}

#[test]
fn bundle_float_datapath_is_conservative() {
    let dps: Vec<Datapath> = [FloatFormat::FP16, FloatFormat::BF16, FloatFormat::FP32]
        .into_iter()
        .map(|f| {
            datapath(format!("float {}", f.name()), move |c| {
                bundle_float::decide_float(&f, &c.bundle, &c.bounds).unwrap()
            })
        })
        .collect();
    run_datapaths(61, &dps);
}

#[test]
fn bundle_fixed_datapath_equals_exact_arithmetic_on_its_own_inputs() {
    let (lo, hi) = scene();
    let bf = BundleFixFormat::presets()[0];
    let map = GridMap::for_bounds(bf.base, lo, hi).unwrap();
    for c in campaign(71).take(20_000) {
        let q = bundle_fix::quantize_bundle(&bf, &map, &c.bundle).unwrap();
        let p = bundle_fix::quantize_box_pair(&map, &c.bounds).unwrap();
        let e = bundle_fix::exact_of_fix(&bf, &q);
        for (test, bx) in [(Test::AllHit, &p.inner), (Test::AnyHit, &p.outer)] {
            let (l, h) = bundle_fix::exact_of_fix_box(bx);
            let fix = conditions_hold(&bundle_fix::FixArith(bf), &q, None, &bx.lo, &bx.hi, test);
            assert_eq!(
                fix,
                conditions_hold(&ExactArith, &e, None, &l, &h, test),
                "{test:?} {q:?} {bx:?}"
            );
        }
    }
}

/// Runs a wrong variant until the per-ray truth catches it; returns how many bundles that took.
fn caught_after(seed: u64, wrong: impl Fn(&BundleCase) -> (bool, bool)) -> Option<usize> {
    campaign(seed)
        .take(20_000)
        .position(|c| judge(&c, &truth(&c), None, wrong(&c)).is_err())
}

#[test]
fn bundle_deliberately_wrong_variants_are_caught() {
    let exact = |b: &Bundle, bx: &Aabb, test| {
        let (l, h) = exact_box(bx);
        conditions_hold(&ExactArith, &exact_bundle(b), None, &l, &h, test)
    };
    // AllHit with AnyHit's bounds (internal bound, enlarged box).
    let swapped_hit = caught_after(81, |c| (exact(&c.bundle, &c.bounds, Test::AnyHit), false));
    // AnyHit's verdict with AllHit's bounds.
    let swapped_miss = caught_after(82, |c| (false, !exact(&c.bundle, &c.bounds, Test::AllHit)));
    // A straddling axis treated as positive (the negative half of the bundle ignored).
    let no_straddle = caught_after(83, |c| {
        let mut b: BundleOf<f64, f64> = c.bundle;
        for a in 0..3 {
            b.d_lo[a] = b.d_lo[a].max(0.0);
            b.d_hi[a] = b.d_hi[a].max(0.0);
        }
        (exact(&b, &c.bounds, Test::AllHit), false)
    });
    // The fixed datapath's AllHit on the outward-rounded box.
    let (lo, hi) = scene();
    let bf = BundleFixFormat::presets()[0];
    let map = GridMap::for_bounds(bf.base, lo, hi).unwrap();
    let outer_for_allhit = caught_after(84, |c| {
        let q = bundle_fix::quantize_bundle(&bf, &map, &c.bundle).unwrap();
        let p = bundle_fix::quantize_box_pair(&map, &c.bounds).unwrap();
        (bundle_fix::all_hit_fix(&bf, &q, &p.outer), false)
    });
    println!(
        "wrong variants caught after: swapped AllHit bounds {swapped_hit:?}, swapped AnyHit bounds \
         {swapped_miss:?}, straddle ignored {no_straddle:?}, outer box for AllHit {outer_for_allhit:?} bundles"
    );
    assert!(swapped_hit.is_some() && swapped_miss.is_some());
    assert!(no_straddle.is_some() && outer_for_allhit.is_some());
}
