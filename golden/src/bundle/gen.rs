//! Seeded generators of ray bundles with their rays and a box: uniform, adversarial (the cases where the
//! bundle tests can go wrong), and on-grid single rays whose quantisation is exact.
//!
//! A case is built from one or more *designed* rays (aimed at an edge, ending on a face, ...), the
//! smallest bundle around them, that bundle widened by a drawn spread, and further rays drawn inside it
//! (each component at either end or between), so the listed rays probe the corners of the bundle. Every
//! origin and box lies inside the scene bounds given to the generator, so it fits a grid built over them.
//! The same seed gives the same stream (`rand_pcg::Pcg64`).

use crate::bundle::edge::Bundle;
use crate::format::fixed::{ldexp, GridMap};
use crate::geom::{Aabb, Ray};
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// What a case is built to exercise.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BundleKind {
    /// A bundle aimed near the box, spreads drawn from zero to medium.
    Uniform,
    /// A designed ray through an edge or corner of the box, with a zero or tiny spread.
    Grazing,
    /// Direction components straddling zero on one to three axes (FIG. 7).
    MixedSign,
    /// One ray (zero-width bundle).
    OneRay,
    /// Origin spread up to half the scene, direction box up to several times the direction.
    Wide,
    /// Origins inside (or overlapping) the box.
    OriginInside,
    /// A designed ray whose `t_max` ends exactly on a face.
    TmaxAtFace,
    /// Zero direction components with no spread, origins sometimes on that slab's plane.
    ZeroComponent,
}

/// The adversarial kinds, drawn with equal probability.
pub const ADVERSARIAL: [BundleKind; 7] = [
    BundleKind::Grazing,
    BundleKind::MixedSign,
    BundleKind::OneRay,
    BundleKind::Wide,
    BundleKind::OriginInside,
    BundleKind::TmaxAtFace,
    BundleKind::ZeroComponent,
];

/// One case: a bundle, rays inside it, and a box.
#[derive(Clone, Debug, PartialEq)]
pub struct BundleCase {
    pub bundle: Bundle,
    pub rays: Vec<Ray>,
    pub bounds: Aabb,
    pub kind: BundleKind,
}

/// A seeded stream of cases inside the scene `[lo, hi]`.
pub struct BundleGen {
    rng: Pcg64,
    lo: DVec3,
    hi: DVec3,
    /// Fraction of adversarial cases.
    adversarial: f64,
}

impl BundleGen {
    /// `adversarial` is the fraction of adversarial cases (0: all uniform, 1: all adversarial).
    pub fn new(seed: u64, lo: DVec3, hi: DVec3, adversarial: f64) -> Self {
        BundleGen {
            rng: Pcg64::seed_from_u64(seed),
            lo,
            hi,
            adversarial: adversarial.clamp(0.0, 1.0),
        }
    }

    fn in_range(&mut self, lo: DVec3, hi: DVec3) -> DVec3 {
        DVec3::new(
            self.rng.gen_range(lo.x..=hi.x),
            self.rng.gen_range(lo.y..=hi.y),
            self.rng.gen_range(lo.z..=hi.z),
        )
    }

    fn extent(&self) -> f64 {
        (self.hi - self.lo).max_element()
    }

    fn aabb(&mut self) -> Aabb {
        let margin = (self.hi - self.lo) * 0.1;
        let c = self.in_range(self.lo + margin, self.hi - margin);
        let scale = self.extent() * [0.002, 0.02, 0.1][self.rng.gen_range(0..3)];
        let mut h = self.in_range(DVec3::splat(0.1 * scale), DVec3::splat(scale));
        if self.rng.gen_ratio(1, 20) {
            h[self.rng.gen_range(0..3)] = 0.0; // a flat box
        }
        Aabb {
            min: (c - h).max(self.lo),
            max: (c + h).min(self.hi),
        }
    }

    /// A point on the box with `fixed` coordinates at a bound (1: a face, 2: an edge, 3: a corner).
    fn on_box(&mut self, b: &Aabb, fixed: usize) -> DVec3 {
        let mut p = self.in_range(b.min, b.max);
        let mut axes = [0usize, 1, 2];
        axes.swap(0, self.rng.gen_range(0..3));
        axes.swap(1, self.rng.gen_range(1..3));
        for &a in &axes[..fixed] {
            p[a] = if self.rng.gen() { b.min[a] } else { b.max[a] };
        }
        p
    }

    fn nonzero(&mut self, d: DVec3) -> DVec3 {
        if d.abs().max_element() == 0.0 {
            let mut v = DVec3::ZERO;
            v[self.rng.gen_range(0..3)] = if self.rng.gen() { 1.0 } else { -1.0 };
            v
        } else {
            d
        }
    }

    fn t_far(&mut self) -> f64 {
        match self.rng.gen_range(0..3) {
            0 => f64::INFINITY,
            _ => self.rng.gen_range(0.0..3.0),
        }
    }

    /// A relative spread: zero, tiny, small or medium.
    fn spread(&mut self, wide: bool) -> f64 {
        if wide {
            return self.rng.gen_range(0.1..0.5);
        }
        match self.rng.gen_range(0..4) {
            0 => 0.0,
            1 => self.rng.gen_range(1e-9..1e-6),
            2 => self.rng.gen_range(1e-4..1e-2),
            _ => self.rng.gen_range(1e-2..0.1),
        }
    }

    /// Widens `b` on every axis by `so` (origins, scene units) and `sd` (directions, relative to the
    /// largest component), each end by its own random share; origins stay inside the scene.
    fn widen(&mut self, b: &mut Bundle, so: f64, sd: f64, keep_dir_axis: [bool; 3]) {
        let dmax = DVec3::from(b.d_hi)
            .abs()
            .max(DVec3::from(b.d_lo).abs())
            .max_element();
        for (a, keep) in keep_dir_axis.into_iter().enumerate() {
            b.o_lo[a] = (b.o_lo[a] - so * self.rng.gen::<f64>()).max(self.lo[a]);
            b.o_hi[a] = (b.o_hi[a] + so * self.rng.gen::<f64>()).min(self.hi[a]);
            if !keep {
                b.d_lo[a] -= sd * dmax * self.rng.gen::<f64>();
                b.d_hi[a] += sd * dmax * self.rng.gen::<f64>();
            }
        }
        if self.rng.gen() && b.t_hi.is_finite() {
            b.t_lo *= 1.0 - self.rng.gen_range(0.0..0.5);
            b.t_hi *= 1.0 + self.rng.gen_range(0.0..0.5);
        }
    }

    /// A value at an end of `[lo, hi]` (two thirds of the time) or between.
    fn corner(&mut self, lo: f64, hi: f64) -> f64 {
        match self.rng.gen_range(0..3) {
            0 => lo,
            1 => hi,
            _ if lo == hi => lo,
            _ => self.rng.gen_range(lo..=hi),
        }
    }

    /// `n` rays drawn inside `b`.
    fn rays_in(&mut self, b: &Bundle, n: usize) -> Vec<Ray> {
        (0..n)
            .map(|_| {
                let mut o = DVec3::ZERO;
                let mut d = DVec3::ZERO;
                for a in 0..3 {
                    o[a] = self.corner(b.o_lo[a], b.o_hi[a]);
                    d[a] = self.corner(b.d_lo[a], b.d_hi[a]);
                }
                let t = if b.t_hi.is_infinite() && self.rng.gen() {
                    f64::INFINITY
                } else {
                    self.corner(b.t_lo, b.t_hi.min(b.t_lo.max(1.0) * 4.0))
                };
                Ray {
                    origin: o,
                    dir: d,
                    t_min: 0.0,
                    t_max: t,
                }
            })
            .collect()
    }

    /// One case of the given kind.
    pub fn case(&mut self, kind: BundleKind) -> BundleCase {
        let bounds = self.aabb();
        let mut origin = self.in_range(self.lo, self.hi);
        let half = (bounds.max - bounds.min) * 0.5;
        let centre = bounds.min + half;
        let near = centre + half * self.in_range(DVec3::splat(-1.5), DVec3::splat(1.5));
        let mut t_max = self.t_far();
        let mut target = near;
        match kind {
            BundleKind::Grazing => {
                let fixed = self.rng.gen_range(2..=3);
                target = self.on_box(&bounds, fixed);
                if self.rng.gen() {
                    t_max = 1.0;
                }
            }
            BundleKind::TmaxAtFace => {
                target = self.on_box(&bounds, 1);
                t_max = 1.0;
            }
            BundleKind::OriginInside => origin = self.in_range(bounds.min, bounds.max),
            _ => {}
        }
        let mut dir = self.nonzero(target - origin);
        if kind == BundleKind::OriginInside {
            let v = self.in_range(DVec3::splat(-1.0), DVec3::ONE);
            dir = self.nonzero(v);
        }
        let mut keep = [false; 3];
        match kind {
            BundleKind::MixedSign => {
                for _ in 0..self.rng.gen_range(1..=3) {
                    dir[self.rng.gen_range(0..3)] = 0.0;
                }
                dir = self.nonzero(dir);
            }
            BundleKind::ZeroComponent => {
                for _ in 0..self.rng.gen_range(1..=2) {
                    let a = self.rng.gen_range(0..3);
                    dir[a] = if self.rng.gen() { 0.0 } else { -0.0 };
                    keep[a] = true;
                    match self.rng.gen_range(0..3) {
                        0 => origin[a] = bounds.min[a],
                        1 => origin[a] = bounds.max[a],
                        _ => {}
                    }
                }
                dir = self.nonzero(dir);
            }
            _ => {}
        }
        // A scale that keeps t = 1 at the target exact only for power-of-two factors.
        let s = [1.0, 0.5, 4.0, self.rng.gen_range(0.1..10.0)][self.rng.gen_range(0..4)];
        if t_max == 1.0 {
            t_max = 1.0 / s;
        }
        let designed = Ray {
            origin,
            dir: dir * s,
            t_min: 0.0,
            t_max,
        };
        let mut bundle = Bundle::around(&[designed]).expect("a valid designed ray");
        let (so, sd) = match kind {
            BundleKind::OneRay => (0.0, 0.0),
            BundleKind::Grazing | BundleKind::TmaxAtFace => {
                let s = if self.rng.gen() { 0.0 } else { 1e-7 };
                (s * self.extent(), s)
            }
            BundleKind::Wide => (
                self.spread(true) * self.extent(),
                self.rng.gen_range(0.5..3.0),
            ),
            BundleKind::MixedSign => (
                self.spread(false) * self.extent(),
                self.spread(false).max(1e-3),
            ),
            _ => (self.spread(false) * self.extent(), self.spread(false)),
        };
        if kind != BundleKind::OneRay {
            self.widen(&mut bundle, so, sd, keep);
        }
        if kind == BundleKind::OriginInside {
            for a in 0..3 {
                bundle.o_lo[a] = bundle.o_lo[a].max(bounds.min[a]);
                bundle.o_hi[a] = bundle.o_hi[a].min(bounds.max[a]).max(bundle.o_lo[a]);
            }
        }
        let mut rays = vec![designed];
        if kind != BundleKind::OneRay {
            let n = self.rng.gen_range(2..=8);
            rays.extend(self.rays_in(&bundle, n));
        }
        rays.retain(|r| bundle.contains(r));
        if rays.is_empty() {
            rays = self.rays_in(&bundle, 1);
        }
        BundleCase {
            bundle,
            rays,
            bounds,
            kind,
        }
    }

    /// The next case: adversarial with the generator's probability, the kind drawn uniformly.
    pub fn next_case(&mut self) -> BundleCase {
        let kind = if self.rng.gen_bool(self.adversarial) {
            ADVERSARIAL[self.rng.gen_range(0..ADVERSARIAL.len())]
        } else {
            BundleKind::Uniform
        };
        self.case(kind)
    }

    /// A one-ray case whose every input is exact on `map`'s grid and in the fixed formats with
    /// `FD >= 3`: integer grid box and origin, a small integer direction (components up to 8 in magnitude)
    /// scaled by a power of two, and an integer `t_max` that keeps the ray within the grid (or `+inf`).
    /// The ray grazes an edge or corner, ends on a face, starts inside, or has zero components, as drawn.
    pub fn grid_one_ray(&mut self, map: &GridMap) -> BundleCase {
        let (gmin, gmax) = (map.fmt.gmin(), map.fmt.gmax());
        let span = gmax - gmin;
        loop {
            let mut lo = [0i64; 3];
            let mut hi = [0i64; 3];
            for a in 0..3 {
                let w = self.rng.gen_range(0..=span / 4);
                lo[a] = self.rng.gen_range(gmin..=gmax - w);
                hi[a] = lo[a] + w;
            }
            let mut m = [0i64; 3];
            while m.iter().all(|&c| c == 0) {
                for c in m.iter_mut() {
                    *c = if self.rng.gen_ratio(1, 4) {
                        0
                    } else {
                        self.rng.gen_range(-8..=8)
                    };
                }
            }
            let mmax = m.iter().map(|c| c.abs()).max().unwrap_or(1);
            let n = self.rng.gen_range(1..=(span / 2 / mmax).max(1));
            let mut o = [0i64; 3];
            let t = match self.rng.gen_range(0..4) {
                // Aimed at an edge, corner or face point: o = p - n m, so the ray is at p when t = n.
                k @ 0..=2 => {
                    let fixed = [2, 3, 1][k];
                    let mut axes = [0usize, 1, 2];
                    axes.swap(0, self.rng.gen_range(0..3));
                    for a in 0..3 {
                        let p = if axes[..fixed].contains(&a) {
                            if self.rng.gen() {
                                lo[a]
                            } else {
                                hi[a]
                            }
                        } else {
                            self.rng.gen_range(lo[a]..=hi[a])
                        };
                        o[a] = p - n * m[a];
                    }
                    match self.rng.gen_range(0..4) {
                        0 => n - 1,
                        1 => n + 1,
                        2 => i64::MAX,
                        _ => n,
                    }
                }
                // Inside the box, or anywhere.
                _ => {
                    for a in 0..3 {
                        o[a] = if self.rng.gen() {
                            self.rng.gen_range(lo[a]..=hi[a])
                        } else {
                            self.rng.gen_range(gmin..=gmax)
                        };
                    }
                    if self.rng.gen() {
                        i64::MAX
                    } else {
                        n
                    }
                }
            };
            if o.iter().any(|&c| c < gmin || c > gmax) {
                continue;
            }
            let s = self.rng.gen_range(-3..=3);
            let w = |a: usize, q: i64| map.to_world(a, q);
            let ray = Ray {
                origin: DVec3::new(w(0, o[0]), w(1, o[1]), w(2, o[2])),
                dir: DVec3::new(m[0] as f64, m[1] as f64, m[2] as f64) * ldexp(1.0, map.k + s),
                t_min: 0.0,
                t_max: if t == i64::MAX {
                    f64::INFINITY
                } else {
                    ldexp(t.max(0) as f64, -s)
                },
            };
            let bounds = Aabb {
                min: DVec3::new(w(0, lo[0]), w(1, lo[1]), w(2, lo[2])),
                max: DVec3::new(w(0, hi[0]), w(1, hi[1]), w(2, hi[2])),
            };
            return BundleCase {
                bundle: Bundle::of_ray(&ray).expect("a valid ray"),
                rays: vec![ray],
                bounds,
                kind: BundleKind::OneRay,
            };
        }
    }
}

impl Iterator for BundleGen {
    type Item = BundleCase;
    fn next(&mut self) -> Option<BundleCase> {
        Some(self.next_case())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::fixed::FixFormat;

    fn scene() -> (DVec3, DVec3) {
        (DVec3::splat(-100.0), DVec3::new(100.0, 50.0, 120.0))
    }

    #[test]
    fn every_kind_gives_valid_cases_inside_the_scene_with_rays_in_the_bundle() {
        let (lo, hi) = scene();
        let mut g = BundleGen::new(3, lo, hi, 1.0);
        for kind in std::iter::once(BundleKind::Uniform).chain(ADVERSARIAL) {
            let mut straddling = 0;
            for _ in 0..2000 {
                let c = g.case(kind);
                c.bundle.validate().unwrap();
                c.bounds.validate().unwrap();
                assert!(!c.rays.is_empty(), "{kind:?}");
                for r in &c.rays {
                    r.validate().unwrap();
                    assert!(c.bundle.contains(r), "{kind:?} {r:?} {:?}", c.bundle);
                }
                for a in 0..3 {
                    assert!(
                        c.bundle.o_lo[a] >= lo[a] && c.bundle.o_hi[a] <= hi[a],
                        "{kind:?}"
                    );
                    assert!(
                        c.bounds.min[a] >= lo[a] && c.bounds.max[a] <= hi[a],
                        "{kind:?}"
                    );
                }
                straddling += usize::from(c.bundle.straddles());
                if kind == BundleKind::OneRay {
                    assert!(c.bundle.is_one_ray());
                }
            }
            if kind == BundleKind::MixedSign {
                assert!(straddling > 1500, "{straddling} of 2000 straddle");
            }
        }
    }

    #[test]
    fn same_seed_same_stream() {
        let (lo, hi) = scene();
        let a: Vec<_> = BundleGen::new(9, lo, hi, 0.5).take(200).collect();
        let b: Vec<_> = BundleGen::new(9, lo, hi, 0.5).take(200).collect();
        assert_eq!(a, b);
    }

    #[test]
    fn grid_rays_are_on_the_grid() {
        let (lo, hi) = scene();
        let map = GridMap::for_bounds(FixFormat::b8(), lo, hi).unwrap();
        let mut g = BundleGen::new(5, lo, hi, 1.0);
        for _ in 0..2000 {
            let c = g.grid_one_ray(&map);
            let r = c.rays[0];
            let q = map.quantize_ray(&r).unwrap();
            assert_eq!(q.o_lo, q.o_hi, "{r:?}");
            let b = map.quantize_box(&c.bounds).unwrap();
            for a in 0..3 {
                assert_eq!(map.to_world(a, b.lo[a]), c.bounds.min[a]);
                assert_eq!(map.to_world(a, b.hi[a]), c.bounds.max[a]);
            }
        }
    }
}
