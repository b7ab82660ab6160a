//! The bundle builder (software): groups a stream of rays into bundles for the AllHit / AnyHit pair
//! ([`crate::bundle::edge`]), and the splitting metric that says when a bundle is better tested ray by ray.
//!
//! # Grouping (after the open-bundle scheme of US 11,308,683, FIG. 10)
//! The builder keeps up to `open_slots` *open* bundles. Each incoming ray is offered to every open bundle
//! that can take it: fewer than `max_rays` rays, and after adding the ray the bundle's origin box is at most
//! `origin_spread` wide and its direction box at most `dir_spread` wide on every axis (and its `t_max`
//! range at most `t_spread` wide). Of those the *best match* takes the ray: the bundle whose boxes grow
//! least, growth measured as the sum over axes of the origin growth over `origin_spread` plus the
//! direction growth over `dir_spread` (ties: the bundle opened first). A ray no open bundle can take opens
//! a new one; when every slot is taken, the bundle opened first is closed (emitted) to make room. A bundle
//! that reaches `max_rays` is closed at once; the rest are closed at the end of the stream, oldest first.
//! The order of the output is the order of closing, and every ray lands in exactly one bundle.
//!
//! Rays must start at their origin (`t_min = 0`, as [`Bundle::around`] requires). Directions are taken as
//! they come (the scene generators give unit directions, so `dir_spread` is in units of a unit vector's
//! components).
//!
//! # Splitting metric
//! Testing a bundle costs one pair cycle and decides nothing when its rays straddle the box's silhouette;
//! then its rays are tested two per cycle anyway. [`SplitMetric`] predicts that case from the bundle's size
//! and spread and sends the rays straight to the ray-by-ray path: a bundle with at most `min_rays` active
//! rays (testing them takes at most as many cycles as the bundle test saves), or whose *footprint* at the
//! box (per axis: origin extent plus direction extent times the distance to the box's far corner) exceeds
//! `max_footprint` times the box's largest extent. The metric only chooses a path: both paths give sound
//! answers, so it changes cycle counts, never results.

use crate::bundle::edge::Bundle;
use crate::error::Error;
use crate::geom::{Aabb, Ray};

/// Thresholds of the builder; see the module doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildParams {
    /// Rays per bundle at most (1..=64; 64 is the width of a ray mask).
    pub max_rays: usize,
    /// Widest origin box per axis, world units (>= 0).
    pub origin_spread: f64,
    /// Widest direction box per axis (>= 0).
    pub dir_spread: f64,
    /// Widest range of `t_max` (>= 0, may be `+inf`).
    pub t_spread: f64,
    /// Open bundles at once (>= 1).
    pub open_slots: usize,
}

/// Largest `max_rays`: a bundle's rays are tracked in one 64-bit mask.
pub const MAX_BUNDLE_RAYS: usize = 64;

impl BuildParams {
    /// Checks every threshold, naming the first bad one.
    pub fn validate(&self) -> Result<(), Error> {
        if self.max_rays == 0 || self.max_rays > MAX_BUNDLE_RAYS {
            return Err(Error::BadFormat {
                param: "max_rays",
                value: self.max_rays as i64,
                why: format!("rays per bundle must be 1..={MAX_BUNDLE_RAYS}"),
            });
        }
        if self.open_slots == 0 {
            return Err(Error::BadFormat {
                param: "open_slots",
                value: 0,
                why: "the builder needs at least one open bundle".into(),
            });
        }
        for (what, v) in [
            ("origin_spread", self.origin_spread),
            ("dir_spread", self.dir_spread),
            ("t_spread", self.t_spread),
        ] {
            if v.is_nan() || v < 0.0 {
                return Err(Error::bad_value(
                    format!("bundle builder {what}"),
                    v,
                    "a spread threshold must be a number >= 0",
                ));
            }
        }
        Ok(())
    }
}

/// One bundle the builder closed: the indices of its rays in the input stream, and the smallest bundle
/// holding them.
#[derive(Clone, Debug, PartialEq)]
pub struct Built {
    pub rays: Vec<usize>,
    pub bundle: Bundle,
}

struct Open {
    rays: Vec<usize>,
    bundle: Bundle,
}

/// The origin and direction extents of a bundle, each the largest over the axes.
pub fn spread(b: &Bundle) -> (f64, f64) {
    (0..3).fold((0.0f64, 0.0f64), |(o, d), a| {
        (o.max(b.o_hi[a] - b.o_lo[a]), d.max(b.d_hi[a] - b.d_lo[a]))
    })
}

fn t_range(b: &Bundle) -> f64 {
    if b.t_lo == b.t_hi {
        0.0
    } else {
        b.t_hi - b.t_lo
    }
}

/// The growth cost of taking `g` for `b` (see the module doc); `None` when `g` breaks a threshold.
fn growth(p: &BuildParams, b: &Bundle, g: &Bundle) -> Option<f64> {
    let (os, ds) = spread(g);
    if os > p.origin_spread || ds > p.dir_spread || t_range(g) > p.t_spread {
        return None;
    }
    let norm = |x: f64, s: f64| if s > 0.0 { x / s } else { 0.0 };
    Some((0..3).fold(0.0, |c, a| {
        c + norm(
            (g.o_hi[a] - g.o_lo[a]) - (b.o_hi[a] - b.o_lo[a]),
            p.origin_spread,
        ) + norm(
            (g.d_hi[a] - g.d_lo[a]) - (b.d_hi[a] - b.d_lo[a]),
            p.dir_spread,
        )
    }))
}

/// Groups `rays` into bundles; see the module doc. Errors name a bad threshold or the first ray that is
/// invalid or does not start at its origin.
pub fn build(rays: &[Ray], p: &BuildParams) -> Result<Vec<Built>, Error> {
    p.validate()?;
    let mut open: Vec<Open> = Vec::new();
    let mut out = Vec::new();
    for (i, r) in rays.iter().enumerate() {
        let one = Bundle::of_ray(r).map_err(|e| Error::Io(format!("ray {i}: {e}")))?;
        let best = open
            .iter()
            .enumerate()
            .filter(|(_, o)| o.rays.len() < p.max_rays)
            .filter_map(|(k, o)| {
                let g = o.bundle.grown(r);
                growth(p, &o.bundle, &g).map(|c| (k, c, g))
            })
            // Strictly smaller cost wins, so ties keep the bundle opened first.
            .fold(None, |best: Option<(usize, f64, Bundle)>, c| match best {
                Some(b) if b.1 <= c.1 => Some(b),
                _ => Some(c),
            });
        let k = match best {
            Some((k, _, g)) => {
                open[k].rays.push(i);
                open[k].bundle = g;
                k
            }
            None => {
                if open.len() == p.open_slots {
                    let o = open.remove(0);
                    out.push(Built {
                        rays: o.rays,
                        bundle: o.bundle,
                    });
                }
                open.push(Open {
                    rays: vec![i],
                    bundle: one,
                });
                open.len() - 1
            }
        };
        if open[k].rays.len() == p.max_rays {
            let o = open.remove(k);
            out.push(Built {
                rays: o.rays,
                bundle: o.bundle,
            });
        }
    }
    out.extend(open.into_iter().map(|o| Built {
        rays: o.rays,
        bundle: o.bundle,
    }));
    Ok(out)
}

/// Square tiles of `tile x tile` pixels over a `w x h` image whose rays are given row by row (as
/// [`crate::scene::tri_scene::primary_rays`] makes them): the natural bundles of camera rays. Edge tiles are smaller.
pub fn tiles(rays: &[Ray], w: usize, h: usize, tile: usize) -> Result<Vec<Built>, Error> {
    if tile == 0 || tile > 8 {
        return Err(Error::BadFormat {
            param: "tile",
            value: tile as i64,
            why: format!("a tile of tile x tile rays must hold 1..={MAX_BUNDLE_RAYS} rays"),
        });
    }
    if w.checked_mul(h) != Some(rays.len()) {
        return Err(Error::Io(format!(
            "{} rays do not form a {w} x {h} image",
            rays.len()
        )));
    }
    let mut out = Vec::new();
    for ty in (0..h).step_by(tile) {
        for tx in (0..w).step_by(tile) {
            let idx: Vec<usize> = (ty..(ty + tile).min(h))
                .flat_map(|y| (tx..(tx + tile).min(w)).map(move |x| y * w + x))
                .collect();
            let group: Vec<Ray> = idx.iter().map(|&i| rays[i]).collect();
            let bundle = Bundle::around(&group)
                .map_err(|e| Error::Io(format!("tile at ({tx}, {ty}): {e}")))?;
            out.push(Built { rays: idx, bundle });
        }
    }
    Ok(out)
}

/// When a bundle goes straight to the ray-by-ray path; see the module doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitMetric {
    /// Bundles with at most this many active rays are split without a bundle test.
    pub min_rays: usize,
    /// Largest footprint at the box, in units of the box's largest extent (`+inf`: never split early).
    pub max_footprint: f64,
}

impl SplitMetric {
    /// Always test the bundle first.
    pub const NEVER: SplitMetric = SplitMetric {
        min_rays: 0,
        max_footprint: f64::INFINITY,
    };

    /// The bundle's footprint at `b` over the box's largest extent (see the module doc); `0` for a box
    /// of no extent is avoided by measuring against at least the footprint's own scale.
    pub fn footprint(bundle: &Bundle, b: &Aabb) -> f64 {
        let mut far = 0.0f64;
        for cx in [b.min.x, b.max.x] {
            for cy in [b.min.y, b.max.y] {
                for cz in [b.min.z, b.max.z] {
                    let c = [cx, cy, cz];
                    let d2: f64 = (0..3)
                        .map(|a| {
                            let o = 0.5 * (bundle.o_lo[a] + bundle.o_hi[a]);
                            (c[a] - o) * (c[a] - o)
                        })
                        .sum();
                    far = far.max(d2.sqrt());
                }
            }
        }
        let foot = (0..3)
            .map(|a| (bundle.o_hi[a] - bundle.o_lo[a]) + far * (bundle.d_hi[a] - bundle.d_lo[a]))
            .fold(0.0f64, f64::max);
        let ext = (b.max - b.min).max_element().max(0.0);
        if ext > 0.0 {
            foot / ext
        } else if foot > 0.0 {
            f64::INFINITY
        } else {
            0.0
        }
    }

    /// True when the bundle's `active` rays should be tested one by one against `b` without a bundle
    /// test.
    pub fn split_first(&self, bundle: &Bundle, active: usize, b: &Aabb) -> bool {
        active <= self.min_rays || Self::footprint(bundle, b) > self.max_footprint
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray {
            origin: DVec3::from(o),
            dir: DVec3::from(d).normalize(),
            t_min: 0.0,
            t_max: f64::INFINITY,
        }
    }

    fn params(max_rays: usize, os: f64, ds: f64, slots: usize) -> BuildParams {
        BuildParams {
            max_rays,
            origin_spread: os,
            dir_spread: ds,
            t_spread: f64::INFINITY,
            open_slots: slots,
        }
    }

    fn random_rays(n: usize, seed: u64) -> Vec<Ray> {
        let mut rng = Pcg64::seed_from_u64(seed);
        (0..n)
            .map(|_| {
                let o = [(); 3].map(|_| rng.gen_range(-1.0..1.0));
                let d = [(); 3].map(|_| rng.gen_range(-1.0..1.0));
                ray(o, d)
            })
            .collect()
    }

    #[test]
    fn every_ray_lands_in_one_bundle_within_the_thresholds() {
        let rays = random_rays(3000, 7);
        for p in [
            params(16, 0.5, 0.4, 8),
            params(4, 0.1, 0.1, 1),
            params(64, 2.0, 2.0, 3),
        ] {
            let out = build(&rays, &p).unwrap();
            let mut seen = vec![0u32; rays.len()];
            for b in &out {
                assert!(!b.rays.is_empty() && b.rays.len() <= p.max_rays);
                let group: Vec<Ray> = b.rays.iter().map(|&i| rays[i]).collect();
                assert_eq!(Bundle::around(&group).unwrap(), b.bundle);
                let (os, ds) = spread(&b.bundle);
                assert!(
                    os <= p.origin_spread && ds <= p.dir_spread,
                    "{p:?}: {os} {ds}"
                );
                for &i in &b.rays {
                    seen[i] += 1;
                }
            }
            assert!(seen.iter().all(|&c| c == 1), "{p:?}");
        }
    }

    #[test]
    fn best_match_takes_the_ray_that_grows_a_bundle_least() {
        // Two open bundles, at x = 0 and at x = 1.5; a ray at x = 0.8 fits either (origin spread 1) and
        // joins the second, which grows less, although the first was opened earlier.
        let rays = [
            ray([0.0; 3], [1.0, 0.0, 0.0]),
            ray([1.5, 0.0, 0.0], [1.0, 0.0, 0.0]),
            ray([0.8, 0.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        let out = build(&rays, &params(8, 1.0, 2.0, 4)).unwrap();
        assert_eq!(out.len(), 2);
        assert_eq!(out[0].rays, vec![0]);
        assert_eq!(out[1].rays, vec![1, 2]);
    }

    #[test]
    fn full_slots_close_the_oldest_and_full_bundles_close_at_once() {
        let rays = [
            ray([0.0; 3], [1.0, 0.0, 0.0]),
            ray([0.0; 3], [0.0, 1.0, 0.0]),
            ray([0.0; 3], [0.0, 0.0, 1.0]),
            ray([0.0; 3], [0.0, 0.0, 1.0]),
        ];
        let out = build(&rays, &params(2, 1.0, 0.5, 2)).unwrap();
        let order: Vec<Vec<usize>> = out.iter().map(|b| b.rays.clone()).collect();
        // Ray 2 finds both slots busy and closes the +x bundle; ray 3 fills ray 2's bundle, which closes.
        assert_eq!(order, vec![vec![0], vec![2, 3], vec![1]]);
    }

    #[test]
    fn coherent_rays_form_full_bundles() {
        // Sixteen rays per pixel-sized cone, interleaved across four cones: the builder separates them.
        let mut rays = Vec::new();
        for k in 0..16 {
            for c in 0..4 {
                let base = [c as f64, 1.0, 0.2 * c as f64];
                rays.push(ray(
                    [0.0; 3],
                    [base[0] + 0.001 * k as f64, base[1], base[2]],
                ));
            }
        }
        let out = build(&rays, &params(16, 0.0, 0.05, 4)).unwrap();
        assert_eq!(out.len(), 4);
        assert!(out.iter().all(|b| b.rays.len() == 16));
    }

    #[test]
    fn bad_thresholds_and_rays_are_named() {
        let rays = random_rays(4, 1);
        for (p, name) in [
            (params(0, 1.0, 1.0, 1), "max_rays"),
            (params(65, 1.0, 1.0, 1), "max_rays"),
            (params(4, 1.0, 1.0, 0), "open_slots"),
            (params(4, f64::NAN, 1.0, 1), "origin_spread"),
            (params(4, 1.0, -1.0, 1), "dir_spread"),
        ] {
            let e = build(&rays, &p).unwrap_err().to_string();
            assert!(e.contains(name), "{e}");
        }
        let mut bad = rays.clone();
        bad[2].t_min = 0.5;
        let e = build(&bad, &params(4, 1.0, 1.0, 2))
            .unwrap_err()
            .to_string();
        assert!(e.contains("ray 2") && e.contains("t_min"), "{e}");
    }

    #[test]
    fn tiles_cover_the_image() {
        let rays = random_rays(10 * 7, 3);
        let out = tiles(&rays, 10, 7, 4).unwrap();
        assert_eq!(out.len(), 3 * 2);
        assert_eq!(out[0].rays.len(), 16);
        assert_eq!(out[2].rays, vec![8, 9, 18, 19, 28, 29, 38, 39]);
        assert_eq!(out.iter().map(|b| b.rays.len()).sum::<usize>(), 70);
        assert!(tiles(&rays, 10, 7, 9).is_err());
        assert!(tiles(&rays, 10, 6, 4).is_err());
    }

    #[test]
    fn split_metric_by_size_and_footprint() {
        let b = Aabb {
            min: DVec3::new(9.0, -1.0, -1.0),
            max: DVec3::new(11.0, 1.0, 1.0),
        };
        let narrow = Bundle::around(&[
            ray([0.0; 3], [1.0, 0.0, 0.0]),
            ray([0.0; 3], [1.0, 0.01, 0.0]),
        ])
        .unwrap();
        let wide = Bundle::around(&[
            ray([0.0; 3], [1.0, -0.5, 0.0]),
            ray([0.0; 3], [1.0, 0.5, 0.0]),
        ])
        .unwrap();
        let m = SplitMetric {
            min_rays: 2,
            max_footprint: 1.0,
        };
        assert!(SplitMetric::footprint(&narrow, &b) < 0.1);
        assert!(SplitMetric::footprint(&wide, &b) > 1.0);
        assert!(!m.split_first(&narrow, 16, &b));
        assert!(m.split_first(&wide, 16, &b));
        assert!(m.split_first(&narrow, 2, &b));
        assert!(!SplitMetric::NEVER.split_first(&wide, 1, &b));
    }
}
