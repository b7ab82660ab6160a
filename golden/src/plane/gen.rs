//! Seeded generators of cull-plane test cases: a node (its box, one triangle of geometry, plane normals)
//! and a ray, uniform or adversarial. Each datapath fits its own planes to the triangle
//! ([`crate::plane::fix::fit_plane`], [`crate::plane::float::fit_plane`]), so one case serves both; a case
//! may also ask for an offset at the format's limits, which replaces the fitted `w` (and then only the
//! interval contract, not the triangle, is checked).

use crate::geom::{Aabb, Ray};
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// One cull-plane test case in world space.
#[derive(Clone, Debug)]
pub struct CullCase {
    pub ray: Ray,
    pub bounds: Aabb,
    pub tri: [DVec3; 3],
    pub normals: Vec<DVec3>,
    /// `Some(k)`: plane `k`'s offset is set to a format limit (`true`: the largest, `false`: the smallest).
    pub extreme_w: Option<(usize, bool)>,
    pub kind: CullAdversity,
}

/// The adversarial cases.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CullAdversity {
    /// Uniform: random triangle, random integer normals, ray aimed into the box or at the triangle.
    Uniform,
    /// The ray exactly parallel to a plane (`n . d = 0`), on either side.
    Parallel,
    /// `n . d` a tiny fraction of `|d|`.
    NearParallel,
    /// The triangle's vertices at box corners, so fitted planes pass through corners and edges.
    CornerPlanes,
    /// Aimed exactly at a triangle vertex, sometimes with `t_max` ending there.
    AtVertex,
    /// The origin inside the box.
    OriginInside,
    /// An offset at the format's limits.
    ExtremeOffset,
}

const KINDS: [CullAdversity; 6] = [
    CullAdversity::Parallel,
    CullAdversity::NearParallel,
    CullAdversity::CornerPlanes,
    CullAdversity::AtVertex,
    CullAdversity::OriginInside,
    CullAdversity::ExtremeOffset,
];

/// A stream of cases inside `[-r, r]^3` (boxes and triangles within `[-r/2, r/2]^3`), `planes` normals each.
pub struct CullGen {
    rng: Pcg64,
    adversarial: f64,
    planes: usize,
    r: f64,
}

impl CullGen {
    /// `adversarial`: the fraction of adversarial cases (0 uniform, 1 all adversarial).
    pub fn new(seed: u64, adversarial: f64, planes: usize, r: f64) -> Self {
        CullGen {
            rng: Pcg64::seed_from_u64(seed),
            adversarial,
            planes: planes.max(1),
            r,
        }
    }

    fn int_dir(&mut self) -> DVec3 {
        loop {
            let n = DVec3::new(
                self.rng.gen_range(-2i32..=2) as f64,
                self.rng.gen_range(-2i32..=2) as f64,
                self.rng.gen_range(-2i32..=2) as f64,
            );
            if n != DVec3::ZERO {
                return n;
            }
        }
    }

    fn point(&mut self, lo: DVec3, hi: DVec3) -> DVec3 {
        DVec3::new(
            self.rng.gen_range(lo.x..=hi.x),
            self.rng.gen_range(lo.y..=hi.y),
            self.rng.gen_range(lo.z..=hi.z),
        )
    }

    /// The next case.
    pub fn case(&mut self) -> CullCase {
        let kind = if self.rng.gen_bool(self.adversarial) {
            KINDS[self.rng.gen_range(0..KINDS.len())]
        } else {
            CullAdversity::Uniform
        };
        let h = self.r / 2.0;
        let c = self.point(DVec3::splat(-h * 0.8), DVec3::splat(h * 0.8));
        let ext = self.point(DVec3::splat(h * 0.002), DVec3::splat(h * 0.2));
        let (lo, hi) = (c - ext, c + ext);
        let tri: [DVec3; 3] = if kind == CullAdversity::CornerPlanes {
            std::array::from_fn(|_| {
                DVec3::new(
                    if self.rng.gen() { lo.x } else { hi.x },
                    if self.rng.gen() { lo.y } else { hi.y },
                    if self.rng.gen() { lo.z } else { hi.z },
                )
            })
        } else {
            std::array::from_fn(|_| self.point(lo, hi))
        };
        let (mut bmin, mut bmax) = (tri[0], tri[0]);
        for v in &tri {
            bmin = bmin.min(*v);
            bmax = bmax.max(*v);
        }
        let normals: Vec<DVec3> = (0..self.planes).map(|_| self.int_dir()).collect();
        let w: [f64; 3] = std::array::from_fn(|_| self.rng.gen_range(0.0..1.0));
        let s = w[0] + w[1] + w[2];
        let on_tri = (tri[0] * w[0] + tri[1] * w[1] + tri[2] * w[2]) / s;
        let in_box = self.point(bmin, bmax);
        let far = self.point(DVec3::splat(-self.r * 0.95), DVec3::splat(self.r * 0.95));
        let mut origin = far;
        let mut t_max = if self.rng.gen_bool(0.3) {
            self.rng.gen_range(0.0..1.5)
        } else {
            f64::INFINITY
        };
        let target = if self.rng.gen() { on_tri } else { in_box };
        let mut dir = target - origin;
        match kind {
            CullAdversity::Parallel | CullAdversity::NearParallel => {
                // d = n x v: exactly perpendicular to n (small integers: exact in f64).
                let k = self.rng.gen_range(0..self.planes);
                let v = self.int_dir();
                dir = normals[k].cross(v);
                if dir == DVec3::ZERO {
                    dir = normals[k].cross(v + DVec3::X);
                }
                if dir == DVec3::ZERO {
                    dir = normals[k].cross(DVec3::Y);
                }
                if kind == CullAdversity::NearParallel {
                    dir += normals[k] * self.rng.gen_range(-1e-9..1e-9);
                }
                // Through a point of the box, from outside.
                origin =
                    target - dir * self.rng.gen_range(0.5..4.0) * (self.r * 0.1 / dir.length());
            }
            CullAdversity::AtVertex => {
                let v = tri[self.rng.gen_range(0..3)];
                dir = v - origin;
                if self.rng.gen_bool(0.5) {
                    t_max = 1.0;
                }
            }
            CullAdversity::OriginInside => {
                origin = in_box;
                dir = self.point(DVec3::splat(-1.0), DVec3::splat(1.0));
            }
            _ => {}
        }
        if dir == DVec3::ZERO || !dir.is_finite() {
            dir = DVec3::X;
        }
        let extreme_w = (kind == CullAdversity::ExtremeOffset)
            .then(|| (self.rng.gen_range(0..self.planes), self.rng.gen()));
        CullCase {
            ray: Ray::new(origin, dir, 0.0, t_max).expect("finite by construction"),
            bounds: Aabb::new(bmin, bmax).expect("finite"),
            tri,
            normals,
            extreme_w,
            kind,
        }
    }
}

impl Iterator for CullGen {
    type Item = CullCase;
    fn next(&mut self) -> Option<CullCase> {
        Some(self.case())
    }
}
