//! Seeded generators of slab-test vectors: uniform, and adversarial (the cases where rounding bites).
//!
//! Every vector lies inside the scene bounds it is given, so it fits any grid built over those bounds.
//! The same seed gives the same stream on every machine (`rand_pcg::Pcg64`).

use crate::geom::{Aabb, Ray};
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Which kind of vectors to draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GenKind {
    /// Origins and boxes uniform in the bounds, directions uniform on the sphere.
    Uniform,
    /// The adversarial catalogue: see [`Adversity`].
    Adversarial,
    /// Half of each.
    Mixed,
}

impl std::str::FromStr for GenKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "uniform" => Ok(GenKind::Uniform),
            "adversarial" => Ok(GenKind::Adversarial),
            "mixed" => Ok(GenKind::Mixed),
            _ => Err(format!(
                "generator `{s}`: expected uniform, adversarial or mixed"
            )),
        }
    }
}

/// The adversarial cases, each drawn with equal probability.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Adversity {
    /// Aimed exactly at a box edge or corner, sometimes with `t_max` ending there.
    GrazingEdgeOrCorner,
    /// Origin on a face of the box.
    OriginOnFace,
    /// One or two direction components `+0` or `-0`, origin sometimes on the slab plane.
    ZeroComponent,
    /// Direction components of magnitude down to the smallest subnormal.
    TinyComponent,
    /// Direction scaled by a huge or tiny power of two.
    ExtremeMagnitude,
    /// A box flat on one to three axes (a face, an edge or a point).
    DegenerateBox,
    /// A box with `min > max` on an axis.
    EmptyBox,
    /// Origin and box at the scene bounds (the format's extremes).
    FormatLimits,
    /// Ray exactly parallel to a face and in its plane.
    ParallelInFacePlane,
    /// Point-like or negative t ranges.
    OddTRange,
}

const ADVERSITIES: [Adversity; 10] = [
    Adversity::GrazingEdgeOrCorner,
    Adversity::OriginOnFace,
    Adversity::ZeroComponent,
    Adversity::TinyComponent,
    Adversity::ExtremeMagnitude,
    Adversity::DegenerateBox,
    Adversity::EmptyBox,
    Adversity::FormatLimits,
    Adversity::ParallelInFacePlane,
    Adversity::OddTRange,
];

/// A seeded stream of `(Ray, Aabb)` vectors inside `[lo, hi]`.
pub struct SlabGen {
    kind: GenKind,
    lo: DVec3,
    hi: DVec3,
    /// Cell size used to put some coordinates exactly on the grid.
    cell: f64,
    rng: Pcg64,
}

impl SlabGen {
    /// `cell` is the world size of a grid cell (values are sometimes snapped to it); use the finest grid
    /// under test.
    pub fn new(kind: GenKind, lo: DVec3, hi: DVec3, cell: f64, seed: u64) -> Self {
        SlabGen {
            kind,
            lo,
            hi,
            cell,
            rng: Pcg64::seed_from_u64(seed),
        }
    }

    fn coord(&mut self, a: usize) -> f64 {
        let v = self.rng.gen_range(self.lo[a]..=self.hi[a]);
        if self.rng.gen_ratio(1, 4) {
            self.snap(a, v)
        } else {
            v
        }
    }

    fn snap(&self, a: usize, v: f64) -> f64 {
        ((v / self.cell).round() * self.cell).clamp(self.lo[a], self.hi[a])
    }

    fn point(&mut self) -> DVec3 {
        DVec3::new(self.coord(0), self.coord(1), self.coord(2))
    }

    fn unit_dir(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.rng.gen_range(-1.0..1.0),
                self.rng.gen_range(-1.0..1.0),
                self.rng.gen_range(-1.0..1.0),
            );
            let l = v.length();
            if l > 1e-3 && l <= 1.0 {
                return v / l;
            }
        }
    }

    fn aabb(&mut self) -> Aabb {
        let (p, q) = (self.point(), self.point());
        // Mostly small boxes, as in a BVH's lower levels.
        let (p, q) = if self.rng.gen_ratio(3, 4) {
            let s = self.rng.gen_range(0.01..0.3);
            (p, p + (q - p) * s)
        } else {
            (p, q)
        };
        Aabb {
            min: p.min(q),
            max: p.max(q),
        }
    }

    fn t_range(&mut self) -> (f64, f64) {
        match self.rng.gen_range(0..4) {
            0 => (0.0, f64::INFINITY),
            1 => (0.0, self.rng.gen_range(0.0..400.0)),
            2 => (self.rng.gen_range(-50.0..50.0), f64::INFINITY),
            _ => {
                let a = self.rng.gen_range(-100.0..300.0);
                (a, a + self.rng.gen_range(0.0..300.0))
            }
        }
    }

    /// One uniform vector.
    pub fn uniform(&mut self) -> (Ray, Aabb) {
        let b = self.aabb();
        let (t_min, t_max) = self.t_range();
        let ray = Ray {
            origin: self.point(),
            dir: self.unit_dir(),
            t_min,
            t_max,
        };
        (ray, b)
    }

    /// A point on the box: on an edge (two coordinates at bounds) or a corner.
    fn on_edge_or_corner(&mut self, b: &Aabb) -> DVec3 {
        let free = self.rng.gen_range(0..4); // 3 = corner
        let mut p = DVec3::ZERO;
        for a in 0..3 {
            p[a] = if a == free {
                self.rng.gen_range(b.min[a]..=b.max[a])
            } else if self.rng.gen() {
                b.min[a]
            } else {
                b.max[a]
            };
        }
        p
    }

    fn on_face(&mut self, b: &Aabb) -> DVec3 {
        let fixed = self.rng.gen_range(0..3);
        let mut p = DVec3::ZERO;
        for a in 0..3 {
            p[a] = if a == fixed {
                if self.rng.gen() {
                    b.min[a]
                } else {
                    b.max[a]
                }
            } else {
                self.rng.gen_range(b.min[a]..=b.max[a])
            };
        }
        p
    }

    /// One adversarial vector of the given case.
    pub fn adversarial_case(&mut self, case: Adversity) -> (Ray, Aabb) {
        let (mut ray, mut b) = self.uniform();
        match case {
            Adversity::GrazingEdgeOrCorner => {
                let target = self.on_edge_or_corner(&b);
                ray.dir = target - ray.origin;
                if ray.dir == DVec3::ZERO {
                    ray.dir = self.unit_dir();
                }
                ray.t_min = 0.0;
                ray.t_max = if self.rng.gen() { 1.0 } else { f64::INFINITY };
                if self.rng.gen() {
                    // Scale so that t = 1 is no longer exact in binary.
                    let s = self.rng.gen_range(0.1..10.0);
                    ray.dir *= s;
                    ray.t_max = if ray.t_max == 1.0 { 1.0 / s } else { ray.t_max };
                }
            }
            Adversity::OriginOnFace => ray.origin = self.on_face(&b),
            Adversity::ZeroComponent => {
                let n = self.rng.gen_range(1..=2);
                for _ in 0..n {
                    let a = self.rng.gen_range(0..3);
                    ray.dir[a] = if self.rng.gen() { 0.0 } else { -0.0 };
                    match self.rng.gen_range(0..3) {
                        0 => ray.origin[a] = b.min[a],
                        1 => ray.origin[a] = b.max[a],
                        _ => {}
                    }
                }
                if ray.dir == DVec3::ZERO || ray.dir == -DVec3::ZERO {
                    ray.dir[self.rng.gen_range(0..3)] = 1.0;
                }
            }
            Adversity::TinyComponent => {
                let a = self.rng.gen_range(0..3);
                let tiny = [5e-324, 1e-310, 1e-300, 1e-20, 1e-8][self.rng.gen_range(0..5)];
                ray.dir[a] = if self.rng.gen() { tiny } else { -tiny };
            }
            Adversity::ExtremeMagnitude => {
                let e = self.rng.gen_range(-1000..1000);
                ray.dir *= 2f64.powi(e);
                if !ray.dir.is_finite() || ray.dir == DVec3::ZERO {
                    ray.dir = self.unit_dir();
                }
            }
            Adversity::DegenerateBox => {
                let n = self.rng.gen_range(1..=3);
                for a in 0..n {
                    b.max[a] = b.min[a];
                }
                if self.rng.gen() {
                    let target = self.on_edge_or_corner(&b);
                    ray.dir = target - ray.origin;
                    if ray.dir == DVec3::ZERO {
                        ray.dir = self.unit_dir();
                    }
                }
            }
            Adversity::EmptyBox => {
                let a = self.rng.gen_range(0..3);
                std::mem::swap(&mut b.min[a], &mut b.max[a]);
                if b.min[a] == b.max[a] {
                    b.min[a] = self.hi[a];
                    b.max[a] = self.lo[a];
                }
            }
            Adversity::FormatLimits => {
                for a in 0..3 {
                    if self.rng.gen() {
                        ray.origin[a] = if self.rng.gen() {
                            self.lo[a]
                        } else {
                            self.hi[a]
                        };
                    }
                    if self.rng.gen() {
                        b.min[a] = self.lo[a];
                    }
                    if self.rng.gen() {
                        b.max[a] = self.hi[a];
                    }
                }
            }
            Adversity::ParallelInFacePlane => {
                let a = self.rng.gen_range(0..3);
                ray.origin[a] = if self.rng.gen() { b.min[a] } else { b.max[a] };
                ray.dir[a] = if self.rng.gen() { 0.0 } else { -0.0 };
                if ray.dir.abs().max_element() == 0.0 {
                    ray.dir[(a + 1) % 3] = 1.0;
                }
            }
            Adversity::OddTRange => {
                let t = self.rng.gen_range(-200.0..200.0);
                (ray.t_min, ray.t_max) = match self.rng.gen_range(0..3) {
                    0 => (t, t),
                    1 => (f64::NEG_INFINITY, t),
                    _ => (0.0, self.rng.gen_range(0.0..1e-6)),
                };
            }
        }
        (ray, b)
    }

    /// One adversarial vector, the case drawn uniformly.
    pub fn adversarial(&mut self) -> (Ray, Aabb) {
        let case = ADVERSITIES[self.rng.gen_range(0..ADVERSITIES.len())];
        self.adversarial_case(case)
    }
}

impl Iterator for SlabGen {
    type Item = (Ray, Aabb);
    fn next(&mut self) -> Option<(Ray, Aabb)> {
        let v = match self.kind {
            GenKind::Uniform => self.uniform(),
            GenKind::Adversarial => self.adversarial(),
            GenKind::Mixed => {
                if self.rng.gen() {
                    self.uniform()
                } else {
                    self.adversarial()
                }
            }
        };
        debug_assert!(v.0.validate().is_ok() && v.1.validate().is_ok(), "{v:?}");
        Some(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_case_yields_valid_vectors_inside_the_bounds() {
        let (lo, hi) = (DVec3::splat(-10.0), DVec3::new(10.0, 20.0, 30.0));
        let mut g = SlabGen::new(GenKind::Adversarial, lo, hi, 0.01, 7);
        for case in ADVERSITIES {
            for _ in 0..2000 {
                let (r, b) = g.adversarial_case(case);
                r.validate().unwrap();
                b.validate().unwrap();
                for a in 0..3 {
                    assert!(
                        r.origin[a] >= lo[a] && r.origin[a] <= hi[a],
                        "{case:?} {r:?}"
                    );
                    for v in [b.min[a], b.max[a]] {
                        assert!(v >= lo[a] && v <= hi[a], "{case:?} {b:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn same_seed_same_stream() {
        let mk = || SlabGen::new(GenKind::Mixed, DVec3::splat(-1.0), DVec3::ONE, 0.01, 42);
        let a: Vec<_> = mk().take(100).collect();
        let b: Vec<_> = mk().take(100).collect();
        assert_eq!(a, b);
    }
}
