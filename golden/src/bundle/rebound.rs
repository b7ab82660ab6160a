//! Re-bounding on the fixed datapath: the bundle a results processor can gather around the rays a split
//! keeps, from the rays as they sit in its ray store (quantised tiny bundles), while they stream through
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

use crate::bundle::edge::Bundle;
use crate::bundle::fix::{bundle_dir_exp, quantize_bundle, BundleFixFormat, FixBundle};
use crate::error::Error;
use crate::format::fixed::GridMap;

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
                let hits: Vec<bool> = keep
                    .iter()
                    .map(|&k| ray_hits_exact(&c.rays[k], &c.bounds).unwrap())
                    .collect();
                let all_hit = all_hit_fix(&bf, &h.q, &boxes.inner);
                let all_miss = all_miss_fix(&bf, &h.q, &boxes.outer);
                let ctx = || {
                    format!(
                        "{}: box {:?}\n  hull {h:?}\n  hits {hits:?}",
                        bf.name(),
                        c.bounds
                    )
                };
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
            assert!(
                outcomes.iter().all(|&c| c > 100),
                "{}: outcomes (all hit, all miss, neither) {outcomes:?}",
                bf.name()
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
