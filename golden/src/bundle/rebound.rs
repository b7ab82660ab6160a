//! Re-bounding on the fixed datapath (the float datapath's simpler rule is in its own section below):
//! the bundle a results processor can gather around the rays a split keeps, from the rays as they sit in its ray store (quantised tiny bundles), while they stream through
//! the pair. This is the rule the hardware can follow bit for bit; [`crate::bundle::traverse`] re-bounds
//! in world units instead (`Bundle::around` of the kept rays, then quantised).
//!
//! # Why the direction scale must be kept
//! A ray is quantised with the direction scale of its own largest component: `d * 2^j`, with `j` from
//! [`crate::format::fixed::dir_scale_exp`], and its t codes in the unit of that scaled direction
//! (`t * 2^(FT - k - j)`, see [`crate::bundle::fix`]). The pair never needs `j` (the test is the same for
//! `d * 2^j` and `t * 2^-j`), so a store that only feeds the pair need not hold it; but the codes of two rays with different
//! `j` are on different scales, and their componentwise minimum means nothing. Re-bounding therefore
//! needs each kept ray's `j` ([`ScaledBundle`]).
//!
//! # The rule
//! The hull of two scaled bundles takes the smaller exponent `j' = min(j1, j2)` (the larger direction)
//! and brings the other one onto it ([`ScaledBundle::rescaled`], `s = j - j'` bits):
//! - direction codes shift right by `s`, `d_lo` rounding down (an arithmetic shift) and `d_hi` up;
//! - t codes shift left by `s` (exact), saturating at the largest finite code for `t_lo` and at `+inf`
//!   for `t_hi`; the `+inf` code stays `+inf`, and a negative code (never a quantised ray's) stays as it
//!   is;
//! - origin codes are on the grid already.
//!
//! then takes `min` of every `lo` and `max` of every `hi`. [`rebound_fix`] folds the kept rays in any
//! order (the fold is associative and commutative, since floor of a floor is the floor of the whole shift),
//! one ray at a time, as hardware gathering the answers of a split would.
//!
//! # How it relates to re-bounding in world units
//! With `B = Bundle::around(kept rays)` and `q = quantize_bundle(B)`: the exponent is the same
//! (`dir_scale_exp` of the hull is the smallest of the rays'), the origin and direction codes are equal
//! (floor and ceil are monotone, and `floor(floor(x 2^a) / 2^s) = floor(x 2^(a-s))`), and the t range of
//! the hull contains `q`'s (`floor(y) 2^s <= floor(y 2^s)`): never narrower, so every answer of the pair on
//! the hull stays sound, and equal when all the kept rays share one `j`. The tests below check all three.
//!
//! # On the float datapath: one scale per bundle, no rescaling
//! A float keeps its relative precision under a power-of-two scale, so the float processor's rays need
//! not each be on their own direction scale: the rays of a bundle are stored on the bundle's scale
//! ([`crate::bundle::float::quantize_bundle_at`] with the bundle's exponent), and a re-bounded bundle
//! stays on it, down the whole traversal. The hull of two float bundles on one scale is then the
//! componentwise `min` of the `lo` fields and `max` of the `hi` fields ([`float_hull`], [`rebound_float`]),
//! with no exponent to carry and nothing to shift. It is exact: rounding is monotone, so the `min` of the
//! rays' rounded-down values is the rounded-down `min` (the hull equals the world bundle around the kept
//! rays quantised on the same scale, as values). It is sound on any stored rays, whatever their scale:
//! each ray's own tuple (origin, scaled direction, scaled `t`) lies inside its tiny bundle, hence inside
//! the hull; only its tightness needs one scale.
//!
//! The order is the numeric one with `-0` below `+0` ([`float_order_key`]), so that `min` and `max` are
//! defined on bit patterns and the fold is associative and commutative bit for bit (a NaN code, which
//! no quantisation yields, orders beyond the infinity of its sign).

use crate::bundle::edge::Bundle;
use crate::bundle::fix::{bundle_dir_exp, quantize_bundle, BundleFixFormat, FixBundle};
use crate::bundle::float::FloatBundle;
use crate::error::Error;
use crate::format::fixed::GridMap;
use crate::format::float::FloatFormat;

/// Bits of a direction exponent `j` on a processor's ports (two's complement): `-128..=127`, directions
/// whose largest component is within `2^-127 .. 2^129` (`j = -floor(log2 max |d_a|)`).
pub const J_BITS: usize = 8;

/// Whether `j` fits [`J_BITS`].
pub fn j_fits(j: i32) -> bool {
    (-(1 << (J_BITS - 1))..1 << (J_BITS - 1)).contains(&j)
}

/// A bundle (or one ray's tiny bundle) on the fixed datapath with the exponent `j` of its direction
/// scale `2^j`; see the module documentation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ScaledBundle {
    pub q: FixBundle,
    pub j: i32,
}

/// Quantises `b` as [`quantize_bundle`] does and keeps its direction exponent.
pub fn quantize_scaled(
    bf: &BundleFixFormat,
    map: &GridMap,
    b: &Bundle,
) -> Result<ScaledBundle, Error> {
    Ok(ScaledBundle {
        q: quantize_bundle(bf, map, b)?,
        j: bundle_dir_exp(b),
    })
}

/// `x / 2^s` rounded down (an arithmetic shift; any `s`).
fn shr_floor(x: i64, s: u32) -> i64 {
    x >> s.min(63)
}

/// `x / 2^s` rounded up.
fn shr_ceil(x: i64, s: u32) -> i64 {
    -shr_floor(-x, s)
}

/// `t * 2^s` for a t code `0 <= t`, the `+inf` code `pinf` kept; a finite result past the finite codes
/// becomes `sat`. A negative code (quantisation never yields one: a ray's t values are `>= 0`; raw codes
/// may hold one) is kept as it is, so that the rule is defined, and monotone, for every code.
fn shl_t(t: i64, s: u32, pinf: i64, sat: i64) -> i64 {
    if t >= pinf {
        return pinf;
    }
    if t <= 0 {
        return t;
    }
    match t.checked_shl(s) {
        Some(v) if s < 63 && v >> s == t && v < pinf => v,
        _ => sat,
    }
}

impl ScaledBundle {
    /// This bundle on the direction scale `2^to`, `to <= self.j` (a larger scale is refused: it would
    /// need bits the codes do not have). See the module documentation.
    pub fn rescaled(&self, bf: &BundleFixFormat, to: i32) -> ScaledBundle {
        assert!(
            to <= self.j,
            "rescaling from 2^{} to the finer 2^{to}",
            self.j
        );
        let s = (self.j - to).unsigned_abs();
        if s == 0 {
            return *self;
        }
        let pinf = bf.base.t_pos_inf();
        let q = &self.q;
        ScaledBundle {
            q: FixBundle {
                o_lo: q.o_lo,
                o_hi: q.o_hi,
                d_lo: q.d_lo.map(|d| shr_floor(d, s)),
                d_hi: q.d_hi.map(|d| shr_ceil(d, s)),
                t_lo: shl_t(q.t_lo, s, pinf, pinf - 1),
                t_hi: shl_t(q.t_hi, s, pinf, pinf),
            },
            j: to,
        }
    }

    /// The smallest scaled bundle on the smaller of the two scales holding both.
    pub fn hull(&self, bf: &BundleFixFormat, other: &ScaledBundle) -> ScaledBundle {
        let j = self.j.min(other.j);
        let (a, b) = (self.rescaled(bf, j).q, other.rescaled(bf, j).q);
        let lo = |x: [i64; 3], y: [i64; 3]| std::array::from_fn(|i| x[i].min(y[i]));
        let hi = |x: [i64; 3], y: [i64; 3]| std::array::from_fn(|i| x[i].max(y[i]));
        ScaledBundle {
            q: FixBundle {
                o_lo: lo(a.o_lo, b.o_lo),
                o_hi: hi(a.o_hi, b.o_hi),
                d_lo: lo(a.d_lo, b.d_lo),
                d_hi: hi(a.d_hi, b.d_hi),
                t_lo: a.t_lo.min(b.t_lo),
                t_hi: a.t_hi.max(b.t_hi),
            },
            j,
        }
    }
}

/// The re-bounded bundle around `kept` (one ray at a time, in the order given), `None` when nothing is
/// kept.
pub fn rebound_fix(
    bf: &BundleFixFormat,
    kept: impl IntoIterator<Item = ScaledBundle>,
) -> Option<ScaledBundle> {
    kept.into_iter().fold(None, |acc: Option<ScaledBundle>, r| {
        Some(acc.map_or(r, |a| a.hull(bf, &r)))
    })
}

/// The order key of a float code of `f`: its magnitude bits when the sign is clear, else `-1 -` its
/// magnitude bits. Keys compare as the numbers do, except that `-0` (key `-1`) is below `+0` (key 0).
/// As an `N`-bit two's-complement word it is the code with its magnitude bits inverted when the sign
/// is set, which is how the hardware compares float codes as signed integers.
pub fn float_order_key(f: &FloatFormat, x: u32) -> i64 {
    let sign = f.sign_bit();
    let mag = i64::from(x & (sign - 1));
    if x & sign != 0 {
        -1 - mag
    } else {
        mag
    }
}

/// The hull of two float bundles on one direction scale: `min` of every `lo` field and `max` of every
/// `hi` field in the order of [`float_order_key`]; see the module documentation.
pub fn float_hull(f: &FloatFormat, a: &FloatBundle, b: &FloatBundle) -> FloatBundle {
    let key = |x: u32| float_order_key(f, x);
    let lo = |x: u32, y: u32| if key(y) < key(x) { y } else { x };
    let hi = |x: u32, y: u32| if key(y) > key(x) { y } else { x };
    FloatBundle {
        o_lo: std::array::from_fn(|i| lo(a.o_lo[i], b.o_lo[i])),
        o_hi: std::array::from_fn(|i| hi(a.o_hi[i], b.o_hi[i])),
        d_lo: std::array::from_fn(|i| lo(a.d_lo[i], b.d_lo[i])),
        d_hi: std::array::from_fn(|i| hi(a.d_hi[i], b.d_hi[i])),
        t_lo: lo(a.t_lo, b.t_lo),
        t_hi: hi(a.t_hi, b.t_hi),
    }
}

/// The float re-bounded bundle around `kept` (tiny float bundles, in any order), `None` when nothing is
/// kept.
pub fn rebound_float(
    f: &FloatFormat,
    kept: impl IntoIterator<Item = FloatBundle>,
) -> Option<FloatBundle> {
    kept.into_iter().fold(None, |acc: Option<FloatBundle>, r| {
        Some(acc.map_or(r, |a| float_hull(f, &a, &r)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bundle::edge::ray_hits_exact;
    use crate::bundle::fix::{all_hit_fix, all_miss_fix, quantize_box_pair};
    use crate::bundle::gen::BundleGen;
    use crate::geom::Ray;
    use glam::DVec3;
    use rand::seq::SliceRandom;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    const LO: DVec3 = DVec3::new(-8.0, -4.0, -2.0);
    const HI: DVec3 = DVec3::new(8.0, 4.0, 6.0);

    fn scaled_rays(bf: &BundleFixFormat, map: &GridMap, rays: &[Ray]) -> Option<Vec<ScaledBundle>> {
        rays.iter()
            .map(|r| quantize_scaled(bf, map, &Bundle::of_ray(r).ok()?).ok())
            .collect()
    }

    #[test]
    fn shifts_round_the_way_they_say() {
        assert_eq!((shr_floor(-5, 1), shr_ceil(-5, 1)), (-3, -2));
        assert_eq!((shr_floor(5, 1), shr_ceil(5, 1)), (2, 3));
        assert_eq!((shr_floor(-1, 70), shr_ceil(1, 70)), (-1, 1));
        assert_eq!((shr_floor(1, 70), shr_ceil(-1, 70)), (0, 0));
        let pinf = 1000;
        assert_eq!(shl_t(3, 2, pinf, pinf - 1), 12);
        assert_eq!(shl_t(300, 2, pinf, pinf - 1), pinf - 1);
        assert_eq!(shl_t(300, 2, pinf, pinf), pinf);
        assert_eq!(shl_t(pinf, 1, pinf, pinf - 1), pinf);
        assert_eq!(shl_t(1, 64, pinf, pinf), pinf);
        assert_eq!(shl_t(0, 64, pinf, pinf - 1), 0);
        assert_eq!(shl_t(-3, 2, pinf, pinf - 1), -3);
        assert_eq!(shl_t(-pinf - 1, 5, pinf, pinf), -pinf - 1);
    }

    /// Against re-bounding in world units, on BundleGen cases with random subsets kept: the same exponent,
    /// origin and direction codes, a t range never narrower (and equal when every kept ray has one `j`);
    /// folding in a shuffled order gives the same hull. Both kinds of kept set must occur.
    #[test]
    fn the_hull_is_the_quantised_world_hull_with_a_t_range_never_narrower() {
        for (i, bf) in BundleFixFormat::presets().into_iter().enumerate() {
            let map = GridMap::for_bounds(bf.base, LO, HI).unwrap();
            let mut gen = BundleGen::new(300 + i as u64, LO, HI, 0.6);
            let mut rng = Pcg64::seed_from_u64(7 + i as u64);
            let (mut mixed, mut same, mut wider) = (0, 0, 0);
            let mut n = 0;
            while n < 3_000 {
                let c = gen.next_case();
                let Some(rays) = scaled_rays(&bf, &map, &c.rays) else {
                    continue;
                };
                let keep: Vec<usize> = (0..rays.len()).filter(|_| rng.gen_bool(0.6)).collect();
                if keep.is_empty() {
                    continue;
                }
                let kept_world: Vec<Ray> = keep.iter().map(|&k| c.rays[k]).collect();
                let Ok(world) =
                    Bundle::around(&kept_world).and_then(|b| quantize_scaled(&bf, &map, &b))
                else {
                    continue;
                };
                n += 1;
                let mut kept: Vec<ScaledBundle> = keep.iter().map(|&k| rays[k]).collect();
                let h = rebound_fix(&bf, kept.iter().copied()).unwrap();
                kept.shuffle(&mut rng);
                assert_eq!(rebound_fix(&bf, kept.iter().copied()), Some(h));
                let ctx = || {
                    format!(
                        "{}: kept {kept_world:?}\n  hull {h:?}\n  world {world:?}",
                        bf.name()
                    )
                };
                assert_eq!(h.j, world.j, "{}", ctx());
                assert_eq!(
                    (h.q.o_lo, h.q.o_hi, h.q.d_lo, h.q.d_hi),
                    (world.q.o_lo, world.q.o_hi, world.q.d_lo, world.q.d_hi),
                    "{}",
                    ctx()
                );
                assert!(
                    h.q.t_lo <= world.q.t_lo && h.q.t_hi >= world.q.t_hi,
                    "{}",
                    ctx()
                );
                if kept.iter().all(|r| r.j == h.j) {
                    same += 1;
                    assert_eq!(h.q, world.q, "{}", ctx());
                } else {
                    mixed += 1;
                    wider += (h.q != world.q) as usize;
                }
            }
            assert!(
                mixed > 100 && same > 100 && wider > 0,
                "{}: kept sets with mixed / one exponent {mixed} / {same}, wider t ranges {wider}",
                bf.name()
            );
        }
    }

    /// Directions spanning many scales (lengths 2^-20 to 2^20): the fold still contains every ray's
    /// tiny bundle once brought onto its scale, and shifts past the code width do not wrap.
    #[test]
    fn directions_of_very_different_lengths_fold_without_wrapping() {
        let bf = BundleFixFormat::presets()[1];
        let map = GridMap::for_bounds(bf.base, LO, HI).unwrap();
        let mut rng = Pcg64::seed_from_u64(11);
        let mut n = 0;
        for _ in 0..2_000 {
            let rays: Vec<Ray> = (0..5)
                .map(|_| {
                    let o = DVec3::new(rng.gen_range(-7.0..7.0), rng.gen_range(-3.0..3.0), 0.5);
                    let d = DVec3::new(
                        rng.gen_range(-1.0..1.0),
                        rng.gen_range(-1.0..1.0),
                        rng.gen_range(-1.0..1.0),
                    ) * 2f64.powi(rng.gen_range(-20..=20));
                    Ray::new(o, d, 0.0, rng.gen_range(0.1..50.0)).unwrap()
                })
                .collect();
            let Some(sr) = scaled_rays(&bf, &map, &rays) else {
                continue;
            };
            n += 1;
            let h = rebound_fix(&bf, sr.iter().copied()).unwrap();
            for r in &sr {
                let o = r.rescaled(&bf, h.j).q;
                for a in 0..3 {
                    assert!(h.q.o_lo[a] <= o.o_lo[a] && o.o_hi[a] <= h.q.o_hi[a]);
                    assert!(h.q.d_lo[a] <= o.d_lo[a] && o.d_hi[a] <= h.q.d_hi[a]);
                    assert!(h.q.d_lo[a] <= h.q.d_hi[a]);
                }
                assert!(h.q.t_lo <= o.t_lo && o.t_hi <= h.q.t_hi);
            }
        }
        assert!(n > 1_000, "only {n} ray sets quantised");
    }

    /// Checks the pair's answers `(all_hit, all_miss)` on the hull of the rays `keep` of case `c`
    /// against their exact hits, and counts the outcome (all hit, all miss, neither).
    fn judge(
        c: &crate::bundle::gen::BundleCase,
        keep: &[usize],
        (all_hit, all_miss): (bool, bool),
        outcomes: &mut [usize; 3],
        what: impl Fn() -> String,
    ) {
        let hits: Vec<bool> = keep
            .iter()
            .map(|&k| ray_hits_exact(&c.rays[k], &c.bounds).unwrap())
            .collect();
        let ctx = || format!("{}\n  box {:?}\n  hits {hits:?}", what(), c.bounds);
        assert!(!all_miss || hits.iter().all(|&x| !x), "{}", ctx());
        assert!(!all_hit || hits.iter().all(|&x| x), "{}", ctx());
        outcomes[if all_hit {
            0
        } else if all_miss {
            1
        } else {
            2
        }] += 1;
    }

    /// The pair's answers on the hull are sound for the rays kept: "all miss" only if none of them hits,
    /// "all hit" only if every one does (exact oracle), with both answers and undecided ones occurring.
    #[test]
    fn the_pair_on_the_hull_never_contradicts_a_kept_ray() {
        for (i, bf) in BundleFixFormat::presets().into_iter().enumerate() {
            let map = GridMap::for_bounds(bf.base, LO, HI).unwrap();
            let mut gen = BundleGen::new(500 + i as u64, LO, HI, 0.6);
            let mut rng = Pcg64::seed_from_u64(17 + i as u64);
            let mut outcomes = [0usize; 3];
            let mut n = 0;
            while n < 3_000 {
                let c = gen.next_case();
                let (Some(rays), Ok(boxes)) = (
                    scaled_rays(&bf, &map, &c.rays),
                    quantize_box_pair(&map, &c.bounds),
                ) else {
                    continue;
                };
                let keep: Vec<usize> = (0..rays.len()).filter(|_| rng.gen_bool(0.5)).collect();
                let Some(h) = rebound_fix(&bf, keep.iter().map(|&k| rays[k])) else {
                    continue;
                };
                n += 1;
                let answers = (
                    all_hit_fix(&bf, &h.q, &boxes.inner),
                    all_miss_fix(&bf, &h.q, &boxes.outer),
                );
                judge(&c, &keep, answers, &mut outcomes, || {
                    format!("{}: hull {h:?}", bf.name())
                });
            }
            assert!(
                outcomes.iter().all(|&c| c > 100),
                "{}: outcomes (all hit, all miss, neither) {outcomes:?}",
                bf.name()
            );
        }
    }

    /// Keys order every non-NaN code of binary16 as its value does, with `-0` just below `+0`, and
    /// are distinct and fit 16 bits (two's complement).
    #[test]
    fn float_order_keys_are_the_numeric_order_with_minus_zero_below_plus_zero() {
        let f = FloatFormat::FP16;
        let codes: Vec<u32> = (0..1u32 << 16).filter(|&x| !f.is_nan(x)).collect();
        let mut by_key = codes.clone();
        by_key.sort_by_key(|&x| float_order_key(&f, x));
        for w in by_key.windows(2) {
            let (a, b) = (f.to_f64(w[0]), f.to_f64(w[1]));
            assert!(
                a < b || (a == 0.0 && b == 0.0 && w[0] == f.zero(true) && w[1] == f.zero(false)),
                "{:#x} ({a}) before {:#x} ({b})",
                w[0],
                w[1]
            );
        }
        assert_eq!(float_order_key(&f, f.zero(true)), -1);
        assert_eq!(float_order_key(&f, f.zero(false)), 0);
        assert!(codes
            .iter()
            .all(|&x| (-(1 << 15)..1 << 15).contains(&float_order_key(&f, x))));
    }

    fn float_formats() -> [FloatFormat; 3] {
        [FloatFormat::FP16, FloatFormat::BF16, FloatFormat::FP32]
    }

    /// Each ray of `rays` as a tiny float bundle on the direction scale `2^j` (`None`: its own scale).
    fn float_rays(f: &FloatFormat, rays: &[Ray], j: Option<i32>) -> Option<Vec<FloatBundle>> {
        rays.iter()
            .map(|r| {
                let b = Bundle::of_ray(r).ok()?;
                let j = j.unwrap_or_else(|| bundle_dir_exp(&b));
                crate::bundle::float::quantize_bundle_at(f, &b, j).ok()
            })
            .collect()
    }

    /// Rays on their bundle's scale: the hull is the world bundle around the kept rays quantised on that
    /// scale (every field equal as a value), holds every kept ray's tiny bundle, and does not depend on
    /// the order of the fold (bit for bit).
    #[test]
    fn the_float_hull_is_the_quantised_world_hull_on_one_scale() {
        use crate::bundle::float::quantize_bundle_at;
        for (i, f) in float_formats().into_iter().enumerate() {
            let mut gen = BundleGen::new(700 + i as u64, LO, HI, 0.6);
            let mut rng = Pcg64::seed_from_u64(27 + i as u64);
            let (mut n, mut mixed) = (0, 0);
            while n < 3_000 {
                let c = gen.next_case();
                let j = bundle_dir_exp(&c.bundle);
                let Some(rays) = float_rays(&f, &c.rays, Some(j)) else {
                    continue;
                };
                let keep: Vec<usize> = (0..rays.len()).filter(|_| rng.gen_bool(0.6)).collect();
                if keep.is_empty() {
                    continue;
                }
                let kept_world: Vec<Ray> = keep.iter().map(|&k| c.rays[k]).collect();
                let Ok(world) =
                    Bundle::around(&kept_world).and_then(|b| quantize_bundle_at(&f, &b, j))
                else {
                    continue;
                };
                n += 1;
                let mut kept: Vec<FloatBundle> = keep.iter().map(|&k| rays[k]).collect();
                let h = rebound_float(&f, kept.iter().copied()).unwrap();
                kept.shuffle(&mut rng);
                assert_eq!(rebound_float(&f, kept.iter().copied()), Some(h));
                mixed += kept_world
                    .iter()
                    .any(|r| bundle_dir_exp(&Bundle::of_ray(r).unwrap()) != j)
                    as usize;
                let ctx = || {
                    format!(
                        "{}: kept {kept_world:?}\n  hull {h:?}\n  world {world:?}",
                        f.name()
                    )
                };
                let fields = |b: &FloatBundle| {
                    let mut v = vec![b.t_lo, b.t_hi];
                    for a in [b.o_lo, b.o_hi, b.d_lo, b.d_hi] {
                        v.extend(a);
                    }
                    v
                };
                for (x, y) in fields(&h).into_iter().zip(fields(&world)) {
                    assert!(f.eq(x, y), "{}", ctx());
                }
                for r in &kept {
                    assert_eq!(rebound_float(&f, [h, *r]), Some(h), "{}", ctx());
                }
            }
            assert!(
                mixed > 100,
                "{}: only {mixed} kept sets with rays of another scale",
                f.name()
            );
        }
    }

    /// The pair's answers on the float hull are sound for the rays kept (exact oracle), with the rays on
    /// their bundle's scale and on their own scales, and every outcome occurs.
    #[test]
    fn the_pair_on_the_float_hull_never_contradicts_a_kept_ray() {
        use crate::bundle::float::{all_hit_float, all_miss_float, quantize_box_pair};
        for (i, f) in float_formats().into_iter().enumerate() {
            let mut gen = BundleGen::new(900 + i as u64, LO, HI, 0.6);
            let mut rng = Pcg64::seed_from_u64(37 + i as u64);
            let mut outcomes = [0usize; 3];
            let mut n = 0;
            while n < 3_000 {
                let c = gen.next_case();
                let own = n % 2 == 1;
                let j = (!own).then(|| bundle_dir_exp(&c.bundle));
                let (Some(rays), Ok(boxes)) =
                    (float_rays(&f, &c.rays, j), quantize_box_pair(&f, &c.bounds))
                else {
                    continue;
                };
                let keep: Vec<usize> = (0..rays.len()).filter(|_| rng.gen_bool(0.5)).collect();
                let Some(h) = rebound_float(&f, keep.iter().map(|&k| rays[k])) else {
                    continue;
                };
                n += 1;
                let answers = (
                    all_hit_float(&f, &h, &boxes.inner),
                    all_miss_float(&f, &h, &boxes.outer),
                );
                judge(&c, &keep, answers, &mut outcomes, || {
                    format!("{}: hull {h:?}", f.name())
                });
            }
            assert!(
                outcomes.iter().all(|&c| c > 100),
                "{}: outcomes (all hit, all miss, neither) {outcomes:?}",
                f.name()
            );
        }
    }

    #[test]
    #[should_panic(expected = "finer")]
    fn a_finer_scale_is_refused() {
        let bf = BundleFixFormat::presets()[0];
        ScaledBundle::default().rescaled(&bf, 1);
    }
}
