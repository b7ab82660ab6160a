//! Bit-accurate model of the bundle results processor: one bundle-box test on the pair of bundle testers,
//! and, when the bundle is undecided, its rays two per clock in the pair's two-ray mode ("split"), as in
//! the results processing of US 11,682,160 (a bundle that neither all hits nor all misses is broken into
//! its rays, which the same pair of testing blocks takes two at a time).
//!
//! # What one job does
//! 1. The bundle on the pair, one clock: `all_hit` (AllHit on the inner box) and `all_miss` (AnyHit on
//!    the outer box), [`crate::bundle::fix::all_hit_fix`] and [`crate::bundle::fix::all_miss_fix`].
//! 2. Decided (`all_hit` or `all_miss`): the mask is `active` for `all_hit` (every ray of the bundle hits;
//!    `all_hit` wins should both be set, which consistent quantised inputs never do), `0` for `all_miss`.
//! 3. Undecided (`split`): the active rays, packed two per clock in index order (an odd count leaves the
//!    last clock's second slot empty), each judged in two-ray mode: AnyHit bounds of the ray's tiny bundle
//!    on the outer box, so bit `i` of the mask says ray `i` *may hit* (`!all_miss_fix`), never missing a
//!    ray that hits (see `rtl::bundle::pair_fix`, two-ray mode). Which slot a ray takes does not change its
//!    answer: both testers compute the same AnyHit test in that mode.
//!
//! `pair_cycles` counts the clocks the job occupies the pair's input: `1`, plus `ceil(popcount(active)/2)`
//! when split. An undecided bundle with no active ray is still `split` and costs one clock.
//!
//! [`split_with`] is the same sequencing over any datapath (the float one too); [`split_fix`] runs it on
//! the fixed datapath and is what `rtl::bundle::split::BundleSplit` matches bit for bit.

use crate::bundle::edge::BoxPair;
use crate::bundle::fix::{all_hit_fix, all_miss_fix, BundleFixFormat, FixBundle};
use crate::format::fixed::FixBox;

/// The result of one job of the results processor; see the module doc.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Hash)]
pub struct SplitResult {
    /// The bundle test said every ray hits.
    pub all_hit: bool,
    /// The bundle test said every ray misses.
    pub all_miss: bool,
    /// Neither: the active rays were tested one by one.
    pub split: bool,
    /// Bit `i`: ray `i` may hit (only active rays are ever set).
    pub mask: u64,
    /// Clocks the job occupied the pair: 1 for the bundle, plus one per two active rays when split.
    pub pair_cycles: u32,
}

/// Clocks of the pair for a job: `1`, plus `ceil(popcount(active) / 2)` when `split`.
pub fn split_cycles(split: bool, active: u64) -> u32 {
    1 + if split {
        active.count_ones().div_ceil(2)
    } else {
        0
    }
}

/// The results processor over any datapath: `decide_bundle()` is the bundle test `(all_hit, all_miss)`,
/// `may_hit(i)` the two-ray-mode answer for ray `i` ("may hit"), called only when the bundle is
/// undecided, once per active ray, in index order.
pub fn split_with(
    decide_bundle: impl FnOnce() -> (bool, bool),
    mut may_hit: impl FnMut(usize) -> bool,
    active: u64,
) -> SplitResult {
    let (all_hit, all_miss) = decide_bundle();
    let split = !(all_hit || all_miss);
    let mask = if all_hit {
        active
    } else if all_miss {
        0
    } else {
        (0..64)
            .filter(|&i| active >> i & 1 == 1)
            .fold(0u64, |m, i| m | (may_hit(i) as u64) << i)
    };
    SplitResult {
        all_hit,
        all_miss,
        split,
        mask,
        pair_cycles: split_cycles(split, active),
    }
}

/// One bundle-box test on the pair, then, if undecided, the bundle's rays two per clock in two-ray mode.
/// `rays[i]` is ray i quantised (a tiny bundle); `active` masks which rays to test (bit i = rays[i]); mask
/// bit i = ray i may hit (only active rays can be set). Panics when `active` names a ray past `rays`.
pub fn split_fix(
    bf: &BundleFixFormat,
    bundle: &FixBundle,
    boxes: &BoxPair<FixBox>,
    rays: &[FixBundle],
    active: u64,
) -> SplitResult {
    assert!(
        rays.len() >= 64 || active >> rays.len() == 0,
        "active mask {active:#x} names rays past the {} given",
        rays.len()
    );
    split_with(
        || {
            (
                all_hit_fix(bf, bundle, &boxes.inner),
                all_miss_fix(bf, bundle, &boxes.outer),
            )
        },
        |i| !all_miss_fix(bf, &rays[i], &boxes.outer),
        active,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bundle::edge::{ray_hits_exact, Bundle};
    use crate::bundle::fix::{quantize_box_pair, quantize_bundle};
    use crate::bundle::gen::BundleGen;
    use crate::format::fixed::GridMap;
    use glam::DVec3;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    #[test]
    fn cycles_count_the_bundle_and_two_rays_a_clock() {
        assert_eq!(split_cycles(false, 0xffff), 1);
        assert_eq!(split_cycles(true, 0), 1);
        assert_eq!(split_cycles(true, 1), 2);
        assert_eq!(split_cycles(true, 0b11), 2);
        assert_eq!(split_cycles(true, 0b10101), 3);
        assert_eq!(split_cycles(true, u64::MAX), 33);
    }

    #[test]
    fn decided_bundles_skip_the_rays_and_undecided_ones_ask_each_active_ray_in_order() {
        let never = |_: usize| -> bool { panic!("a decided bundle must not test its rays") };
        let r = split_with(|| (true, false), never, 0b1011);
        assert_eq!(
            r,
            SplitResult {
                all_hit: true,
                all_miss: false,
                split: false,
                mask: 0b1011,
                pair_cycles: 1
            }
        );
        let r = split_with(|| (false, true), never, 0b1011);
        assert_eq!((r.mask, r.split, r.pair_cycles), (0, false, 1));
        // Both set (inconsistent inputs): all_hit wins.
        assert_eq!(split_with(|| (true, true), never, 0b110).mask, 0b110);
        let mut asked = vec![];
        let r = split_with(
            || (false, false),
            |i| {
                asked.push(i);
                i % 3 == 0
            },
            0b1_0110_1001,
        );
        assert_eq!(asked, vec![0, 3, 5, 6, 8]);
        assert_eq!(r.mask, 0b0_0100_1001);
        assert_eq!((r.split, r.pair_cycles), (true, 4));
        let r = split_with(|| (false, false), never, 0);
        assert_eq!((r.split, r.mask, r.pair_cycles), (true, 0, 1));
    }

    #[test]
    #[should_panic(expected = "past the")]
    fn an_active_bit_without_a_ray_is_refused() {
        let bf = BundleFixFormat::presets()[0];
        let b = FixBundle::default();
        split_fix(&bf, &b, &BoxPair::default(), &[b, b], 0b100);
    }

    /// On BundleGen cases (random and adversarial) with random active masks, the mask of `split_fix`
    /// covers every active ray that truly hits (exact oracle), sets no inactive bit, and the answers and
    /// cycles follow the module doc. Enough cases of each outcome are required.
    #[test]
    fn mask_covers_every_hitting_active_ray() {
        for (i, bf) in BundleFixFormat::presets().into_iter().enumerate() {
            let (lo, hi) = (DVec3::new(-8.0, -4.0, -2.0), DVec3::new(8.0, 4.0, 6.0));
            let map = GridMap::for_bounds(bf.base, lo, hi).unwrap();
            let mut gen = BundleGen::new(100 + i as u64, lo, hi, 0.6);
            let mut rng = Pcg64::seed_from_u64(i as u64);
            let mut outcomes = [0usize; 3];
            let mut dropped_by_split = 0;
            let mut n = 0;
            while n < 3_000 {
                let c = gen.next_case();
                let (Ok(b), Ok(p)) = (
                    quantize_bundle(&bf, &map, &c.bundle),
                    quantize_box_pair(&map, &c.bounds),
                ) else {
                    continue;
                };
                let Ok(rays) = c
                    .rays
                    .iter()
                    .map(|r| quantize_bundle(&bf, &map, &Bundle::of_ray(r).unwrap()))
                    .collect::<Result<Vec<_>, _>>()
                else {
                    continue;
                };
                n += 1;
                let all = (1u64 << rays.len()) - 1;
                let active = match rng.gen_range(0..4) {
                    0 => all,
                    _ => rng.gen::<u64>() & all,
                };
                let r = split_fix(&bf, &b, &p, &rays, active);
                assert_eq!(r.mask & !active, 0, "{r:?}");
                assert_eq!(r.split, !(r.all_hit || r.all_miss));
                assert_eq!(r.pair_cycles, split_cycles(r.split, active));
                if r.all_hit {
                    assert_eq!(r.mask, active);
                } else if r.all_miss {
                    assert_eq!(r.mask, 0);
                }
                outcomes[if r.all_hit {
                    0
                } else if r.all_miss {
                    1
                } else {
                    2
                }] += 1;
                for (k, ray) in c.rays.iter().enumerate() {
                    let hit = ray_hits_exact(ray, &c.bounds).unwrap();
                    if active >> k & 1 == 1 && hit {
                        assert!(
                            r.mask >> k & 1 == 1,
                            "{}: active ray {k} hits but its mask bit is clear\n  ray {ray:?}\n  \
                             box {:?}\n  {r:?}",
                            bf.name(),
                            c.bounds
                        );
                    }
                    if r.split && active >> k & 1 == 1 && !hit {
                        dropped_by_split += (r.mask >> k & 1 == 0) as usize;
                    }
                }
            }
            assert!(
                outcomes.iter().all(|&c| c > 150),
                "{}: outcomes (all hit, all miss, split) {outcomes:?}",
                bf.name()
            );
            assert!(
                dropped_by_split > 0,
                "{}: splitting culled no missing ray",
                bf.name()
            );
        }
    }
}
