//! Ray-triangle intersection: an exact rational test, the f64 Möller–Trumbore test, and a filtered test
//! that is fast on clear misses and exact in effect.
//!
//! All three solve the same system. With `e1 = v1 - v0`, `e2 = v2 - v0`, a point of the ray
//! `o + t d` lies on the triangle's plane at barycentric `(u, v)` when `o + t d = v0 + u e1 + v e2`.
//! Cramer's rule gives, as in Möller and Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection"
//! (JGT 2(1), 1997):
//!
//! ```text
//! p = d x e2    det = e1 . p    s = o - v0    q = s x e1
//! u = (s . p) / det    v = (d . q) / det    t = (e2 . q) / det
//! ```
//!
//! The closed triangle is hit when `u >= 0`, `v >= 0`, `u + v <= 1` and `t_min <= t <= t_max`.
//!
//! Defined special cases (all three tests agree on them):
//! - `det = 0`: the ray is parallel to the triangle's plane, or the triangle has zero area (collinear or
//!   repeated vertices). Both are misses, including a ray lying in the triangle's plane: a triangle is a
//!   surface, and a ray grazing along it is not counted.
//! - `t_min = -inf` / `t_max = +inf` leave that side of the range open.
//!
//! [`tri_exact`] computes every quantity exactly. Every finite f64 is a dyadic rational `m * 2^e`, and
//! the formulas above use only `+`, `-` and `*` before the final division, so the numerators and `det`
//! are exact dyadics (`Dyadic` below, a big-integer mantissa and a binary exponent, no gcd) and the
//! hit decision compares them without dividing; only the returned `t` becomes a [`BigRational`].
//!
//! [`tri_hit`] first evaluates the same formulas in f64 while carrying a rigorous bound on the absolute
//! error of every intermediate (the running error analysis of Higham, *Accuracy and Stability of
//! Numerical Algorithms*, 2nd ed., §3.3, with unit roundoff `u = 2^-53`, plus an absolute term for
//! underflow). When some condition fails by more than its error bound the ray certainly misses and the
//! answer is `None` without any big-number work; otherwise (a possible hit, a near-grazing case, or an
//! overflow) it calls [`tri_exact`]. Its result therefore always equals [`tri_exact`]'s.

use crate::geom::Ray;
use glam::DVec3;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rand::Rng;
use std::cmp::Ordering;

/// A triangle with vertices `v[0]`, `v[1]`, `v[2]` (either winding; both sides are hit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub v: [DVec3; 3],
}

impl Triangle {
    pub fn new(a: DVec3, b: DVec3, c: DVec3) -> Triangle {
        Triangle { v: [a, b, c] }
    }

    /// `(v1 - v0) x (v2 - v0)` in f64 (not normalised; zero for a degenerate triangle).
    pub fn normal(&self) -> DVec3 {
        (self.v[1] - self.v[0]).cross(self.v[2] - self.v[0])
    }

    /// The centroid in f64.
    pub fn centroid(&self) -> DVec3 {
        (self.v[0] + self.v[1] + self.v[2]) / 3.0
    }

    /// Component-wise min and max of the vertices (exact: min/max do not round).
    pub fn min_max(&self) -> (DVec3, DVec3) {
        (
            self.v[0].min(self.v[1]).min(self.v[2]),
            self.v[0].max(self.v[1]).max(self.v[2]),
        )
    }

    /// True when every coordinate is finite.
    pub fn is_finite(&self) -> bool {
        self.v.iter().all(|p| p.is_finite())
    }
}

// ---------------------------------------------------------------------------------------------------
// Exact dyadic arithmetic.

/// An exact dyadic rational `m * 2^e`. Sums align exponents, products add them; nothing is reduced, so
/// no gcd is ever taken. Private to the exact tests of this crate.
#[derive(Clone, Debug)]
pub(crate) struct Dyadic {
    m: BigInt,
    e: i32,
}

impl Dyadic {
    /// The exact value of a finite f64.
    pub(crate) fn from_f64(x: f64) -> Dyadic {
        debug_assert!(x.is_finite());
        if x == 0.0 {
            return Dyadic {
                m: BigInt::zero(),
                e: 0,
            };
        }
        let bits = x.to_bits();
        let sign = bits >> 63;
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1u64 << 52) - 1);
        let (mant, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1u64 << 52), exp - 1075)
        };
        let m = BigInt::from(mant);
        Dyadic {
            m: if sign == 1 { -m } else { m },
            e,
        }
    }

    fn align(a: &Dyadic, b: &Dyadic) -> (BigInt, BigInt, i32) {
        match a.e.cmp(&b.e) {
            Ordering::Equal => (a.m.clone(), b.m.clone(), a.e),
            Ordering::Greater => (&a.m << ((a.e - b.e) as usize), b.m.clone(), b.e),
            Ordering::Less => (a.m.clone(), &b.m << ((b.e - a.e) as usize), a.e),
        }
    }

    pub(crate) fn add(&self, o: &Dyadic) -> Dyadic {
        let (x, y, e) = Dyadic::align(self, o);
        Dyadic { m: x + y, e }
    }

    pub(crate) fn sub(&self, o: &Dyadic) -> Dyadic {
        let (x, y, e) = Dyadic::align(self, o);
        Dyadic { m: x - y, e }
    }

    pub(crate) fn mul(&self, o: &Dyadic) -> Dyadic {
        Dyadic {
            m: &self.m * &o.m,
            e: self.e + o.e,
        }
    }

    pub(crate) fn neg(&self) -> Dyadic {
        Dyadic {
            m: -&self.m,
            e: self.e,
        }
    }

    pub(crate) fn signum(&self) -> i32 {
        if self.m.is_zero() {
            0
        } else if self.m.is_positive() {
            1
        } else {
            -1
        }
    }

    pub(crate) fn cmp(&self, o: &Dyadic) -> Ordering {
        self.sub(o).signum().cmp(&0)
    }

    pub(crate) fn to_rational(&self) -> BigRational {
        if self.e >= 0 {
            BigRational::from_integer(&self.m << (self.e as usize))
        } else {
            BigRational::new(self.m.clone(), BigInt::one() << ((-self.e) as usize))
        }
    }
}

type DVec = [Dyadic; 3];

fn dv(p: DVec3) -> DVec {
    [
        Dyadic::from_f64(p.x),
        Dyadic::from_f64(p.y),
        Dyadic::from_f64(p.z),
    ]
}

fn dsub(a: &DVec, b: &DVec) -> DVec {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

fn ddot(a: &DVec, b: &DVec) -> Dyadic {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}

fn dcross(a: &DVec, b: &DVec) -> DVec {
    [
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}

/// The exact test: `Some(t)` with the exact parameter of the hit when the closed triangle is hit with
/// `t` in `[t_min, t_max]`; `None` otherwise (and for `det = 0`, see the module doc). Inputs must be
/// finite (a validated [`Ray`] and a triangle with finite vertices); a non-finite vertex is a miss.
pub fn tri_exact(ray: &Ray, tri: &Triangle) -> Option<BigRational> {
    if !tri.is_finite() {
        return None;
    }
    let v0 = dv(tri.v[0]);
    let e1 = dsub(&dv(tri.v[1]), &v0);
    let e2 = dsub(&dv(tri.v[2]), &v0);
    let d = dv(ray.dir);
    let p = dcross(&d, &e2);
    let mut det = ddot(&e1, &p);
    let sd = det.signum();
    if sd == 0 {
        return None;
    }
    let s = dsub(&dv(ray.origin), &v0);
    let mut u = ddot(&s, &p);
    if sd < 0 {
        u = u.neg();
        det = det.neg();
    }
    if u.signum() < 0 || u.cmp(&det) == Ordering::Greater {
        return None;
    }
    let q = dcross(&s, &e1);
    let mut v = ddot(&d, &q);
    if sd < 0 {
        v = v.neg();
    }
    if v.signum() < 0 || u.add(&v).cmp(&det) == Ordering::Greater {
        return None;
    }
    let mut t = ddot(&e2, &q);
    if sd < 0 {
        t = t.neg();
    }
    if ray.t_min.is_finite() && t.cmp(&Dyadic::from_f64(ray.t_min).mul(&det)) == Ordering::Less {
        return None;
    }
    if ray.t_max.is_finite() && t.cmp(&Dyadic::from_f64(ray.t_max).mul(&det)) == Ordering::Greater {
        return None;
    }
    Some(t.to_rational() / det.to_rational())
}

// ---------------------------------------------------------------------------------------------------
// f64 Möller–Trumbore.

/// The textbook Möller–Trumbore test in f64 (round to nearest, no epsilon): `Some(t)` on a hit.
/// Not conservative near edges; kept as the speed yardstick and for comparison.
pub fn tri_f64(ray: &Ray, tri: &Triangle) -> Option<f64> {
    let e1 = tri.v[1] - tri.v[0];
    let e2 = tri.v[2] - tri.v[0];
    let p = ray.dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let s = ray.origin - tri.v[0];
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = ray.dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t >= ray.t_min && t <= ray.t_max).then_some(t)
}

// ---------------------------------------------------------------------------------------------------
// Filtered test.

/// Unit roundoff of f64.
const U: f64 = f64::EPSILON / 2.0;
/// Slack on propagated error terms: covers the rounding of the error arithmetic itself (a few `u`).
const SLACK: f64 = 1.0 + 1e-6;
/// Absolute term per operation: covers underflow (at most `2^-1074` per rounding).
const TINY: f64 = 1e-300;

/// A computed value and a bound on its absolute error against the true real value.
#[derive(Clone, Copy, Debug)]
struct Approx {
    x: f64,
    e: f64,
}

impl Approx {
    fn exact(x: f64) -> Approx {
        Approx { x, e: 0.0 }
    }
    fn add(self, o: Approx) -> Approx {
        let x = self.x + o.x;
        Approx {
            x,
            e: (self.e + o.e) * SLACK + 2.0 * U * x.abs() + TINY,
        }
    }
    fn sub(self, o: Approx) -> Approx {
        self.add(Approx { x: -o.x, e: o.e })
    }
    fn mul(self, o: Approx) -> Approx {
        let x = self.x * o.x;
        Approx {
            x,
            e: (self.x.abs() * o.e + o.x.abs() * self.e + self.e * o.e) * SLACK
                + 2.0 * U * x.abs()
                + TINY,
        }
    }
    fn neg(self) -> Approx {
        Approx {
            x: -self.x,
            e: self.e,
        }
    }
    /// True when the real value is certainly negative.
    fn surely_neg(self) -> bool {
        self.x + self.e < 0.0 && self.x.is_finite() && self.e.is_finite()
    }
}

type AVec = [Approx; 3];

fn av(p: DVec3) -> AVec {
    [Approx::exact(p.x), Approx::exact(p.y), Approx::exact(p.z)]
}
fn asub(a: &AVec, b: &AVec) -> AVec {
    [a[0].sub(b[0]), a[1].sub(b[1]), a[2].sub(b[2])]
}
fn adot(a: &AVec, b: &AVec) -> Approx {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}
fn across(a: &AVec, b: &AVec) -> AVec {
    [
        a[1].mul(b[2]).sub(a[2].mul(b[1])),
        a[2].mul(b[0]).sub(a[0].mul(b[2])),
        a[0].mul(b[1]).sub(a[1].mul(b[0])),
    ]
}

/// Outcome of the f64 filter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// Certainly no hit in the ray's range.
    Miss,
    /// Undecided in f64 (a possible hit, a near-grazing case, or an overflow): ask the exact test.
    Unsure,
}

/// The f64 filter with rigorous error bounds (see the module doc). `Miss` is always right.
pub fn tri_filter(ray: &Ray, tri: &Triangle) -> Filter {
    let v0 = av(tri.v[0]);
    let e1 = asub(&av(tri.v[1]), &v0);
    let e2 = asub(&av(tri.v[2]), &v0);
    let d = av(ray.dir);
    let p = across(&d, &e2);
    let det = adot(&e1, &p);
    if !(det.x.is_finite() && det.e.is_finite()) || det.x.abs() <= det.e {
        return Filter::Unsure;
    }
    let flip = |a: Approx| if det.x < 0.0 { a.neg() } else { a };
    let detp = flip(det);
    let s = asub(&av(ray.origin), &v0);
    let u = flip(adot(&s, &p));
    if u.surely_neg() || detp.sub(u).surely_neg() {
        return Filter::Miss;
    }
    let q = across(&s, &e1);
    let v = flip(adot(&d, &q));
    if v.surely_neg() || detp.sub(u).sub(v).surely_neg() {
        return Filter::Miss;
    }
    let t = flip(adot(&e2, &q));
    if ray.t_min.is_finite() && t.sub(Approx::exact(ray.t_min).mul(detp)).surely_neg() {
        return Filter::Miss;
    }
    if ray.t_max.is_finite() && Approx::exact(ray.t_max).mul(detp).sub(t).surely_neg() {
        return Filter::Miss;
    }
    Filter::Unsure
}

/// Fast and exact in effect: the f64 filter rejects clear misses, [`tri_exact`] decides the rest.
/// Always returns exactly what [`tri_exact`] returns.
pub fn tri_hit(ray: &Ray, tri: &Triangle) -> Option<BigRational> {
    match tri_filter(ray, tri) {
        Filter::Miss => None,
        Filter::Unsure => tri_exact(ray, tri),
    }
}

// ---------------------------------------------------------------------------------------------------
// Rounding exact values to f64.

pub use crate::exact::{round_down, round_up};

// ---------------------------------------------------------------------------------------------------
// Random triangles and rays (for tests and benchmarks).

/// A random point in `[lo, hi]` (component-wise).
pub fn random_point<R: Rng>(rng: &mut R, lo: DVec3, hi: DVec3) -> DVec3 {
    DVec3::new(
        rng.gen_range(lo.x..=hi.x),
        rng.gen_range(lo.y..=hi.y),
        rng.gen_range(lo.z..=hi.z),
    )
}

/// A random unit vector, uniform on the sphere.
pub fn random_unit<R: Rng>(rng: &mut R) -> DVec3 {
    loop {
        let p = random_point(rng, DVec3::splat(-1.0), DVec3::ONE);
        let l = p.length_squared();
        if l > 1e-6 && l <= 1.0 {
            return p / l.sqrt();
        }
    }
}

/// A random triangle: a centre uniform in `[lo, hi]`, vertices within `size` of it.
pub fn random_triangle<R: Rng>(rng: &mut R, lo: DVec3, hi: DVec3, size: f64) -> Triangle {
    let c = random_point(rng, lo, hi);
    let mut v = [DVec3::ZERO; 3];
    for p in v.iter_mut() {
        *p = c + random_unit(rng) * size * rng.gen_range(0.05..1.0);
    }
    Triangle { v }
}

/// A ray from a random origin at distance about `dist` aimed at a point of `tri`. With `grazing`, the
/// target is a vertex or a point on an edge (half of the time exactly a vertex), the cases where f64
/// rounding decides; otherwise a random interior point.
pub fn ray_at_triangle<R: Rng>(rng: &mut R, tri: &Triangle, dist: f64, grazing: bool) -> Ray {
    let target = if grazing {
        let i = rng.gen_range(0..3);
        if rng.gen_bool(0.5) {
            tri.v[i]
        } else {
            let a: f64 = rng.gen();
            tri.v[i] + (tri.v[(i + 1) % 3] - tri.v[i]) * a
        }
    } else {
        let (mut a, mut b): (f64, f64) = (rng.gen(), rng.gen());
        if a + b > 1.0 {
            a = 1.0 - a;
            b = 1.0 - b;
        }
        tri.v[0] + (tri.v[1] - tri.v[0]) * a + (tri.v[2] - tri.v[0]) * b
    };
    let origin = target + random_unit(rng) * dist;
    let dir = target - origin;
    let t_max = if rng.gen_bool(0.2) {
        // Sometimes end the ray right at the target.
        1.0
    } else {
        f64::INFINITY
    };
    Ray {
        origin,
        dir: if dir == DVec3::ZERO { DVec3::X } else { dir },
        t_min: 0.0,
        t_max,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::rat;
    use rand::SeedableRng;
    use rand_pcg::Pcg64;

    fn ray(o: DVec3, d: DVec3) -> Ray {
        Ray::new(o, d, 0.0, f64::INFINITY).unwrap()
    }

    #[test]
    fn exact_hits_interior_edges_and_vertices_of_the_closed_triangle() {
        let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
        let down = DVec3::new(0.0, 0.0, -1.0);
        // Interior, at t = 2.
        assert_eq!(
            tri_exact(&ray(DVec3::new(0.25, 0.25, 2.0), down), &t),
            Some(rat(2.0))
        );
        // Exactly on the hypotenuse and on a vertex: closed triangle, hit.
        assert!(tri_exact(&ray(DVec3::new(0.5, 0.5, 1.0), down), &t).is_some());
        assert!(tri_exact(&ray(DVec3::new(1.0, 0.0, 1.0), down), &t).is_some());
        // Just outside the hypotenuse.
        let out = 0.5f64.next_up();
        assert!(tri_exact(&ray(DVec3::new(out, 0.5, 1.0), down), &t).is_none());
        // Behind the origin and beyond t_max.
        assert!(tri_exact(&ray(DVec3::new(0.25, 0.25, -1.0), down), &t).is_none());
        let short = Ray::new(DVec3::new(0.25, 0.25, 2.0), down, 0.0, 1.5).unwrap();
        assert!(tri_exact(&short, &t).is_none());
        // t_max exactly at the hit: closed range, hit.
        let exact_end = Ray::new(DVec3::new(0.25, 0.25, 2.0), down, 0.0, 2.0).unwrap();
        assert_eq!(tri_exact(&exact_end, &t), Some(rat(2.0)));
    }

    #[test]
    fn degenerate_triangles_and_parallel_rays_miss() {
        let line = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::X * 2.0);
        let r = ray(DVec3::new(1.0, 0.0, 1.0), DVec3::new(0.0, 0.0, -1.0));
        assert!(tri_exact(&r, &line).is_none());
        assert!(tri_hit(&r, &line).is_none());
        let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
        let inplane = ray(DVec3::new(-1.0, 0.25, 0.0), DVec3::X);
        assert!(tri_exact(&inplane, &t).is_none());
        assert!(tri_hit(&inplane, &t).is_none());
    }

    #[test]
    fn exact_t_is_the_true_rational() {
        // Plane z = 1/3 is not representable; the triangle sits at z = 0.1 (f64), ray from z = 1 with
        // direction -0.3: t = (1 - 0.1) / 0.3 in exact arithmetic of the f64 values.
        let z = 0.1f64;
        let t = Triangle::new(
            DVec3::new(-1.0, -1.0, z),
            DVec3::new(3.0, -1.0, z),
            DVec3::new(-1.0, 3.0, z),
        );
        let r = ray(DVec3::new(0.0, 0.0, 1.0), DVec3::new(0.0, 0.0, -0.3));
        let want = (rat(1.0) - rat(z)) / rat(0.3);
        assert_eq!(tri_exact(&r, &t), Some(want.clone()));
        assert_eq!(tri_hit(&r, &t), Some(want));
    }

    #[test]
    fn filtered_test_equals_exact_on_random_and_grazing_cases() {
        let mut rng = Pcg64::seed_from_u64(7);
        let (lo, hi) = (DVec3::splat(-10.0), DVec3::splat(10.0));
        let (mut hits, mut filtered, mut f64_disagree) = (0, 0, 0);
        for i in 0..40_000 {
            let size = [1e-3, 0.1, 1.0, 5.0][i % 4];
            let tri = random_triangle(&mut rng, lo, hi, size);
            let r = match i % 3 {
                0 => {
                    let o = random_point(&mut rng, lo, hi);
                    Ray::new(o, random_unit(&mut rng), 0.0, f64::INFINITY).unwrap()
                }
                1 => ray_at_triangle(&mut rng, &tri, 3.0, false),
                _ => ray_at_triangle(&mut rng, &tri, 3.0, true),
            };
            let exact = tri_exact(&r, &tri);
            assert_eq!(tri_hit(&r, &tri), exact, "case {i}: {r:?} {tri:?}");
            hits += exact.is_some() as u32;
            filtered += (tri_filter(&r, &tri) == Filter::Miss) as u32;
            f64_disagree += (tri_f64(&r, &tri).is_some() != exact.is_some()) as u32;
        }
        // The corpus exercises both sides and the filter does its job.
        assert!(hits > 10_000, "hits {hits}");
        assert!(filtered > 10_000, "filtered {filtered}");
        // Grazing cases make plain f64 disagree at least sometimes (that is why the exact test exists).
        assert!(f64_disagree > 0);
    }

    #[test]
    fn filter_agrees_with_exact_on_shared_edges() {
        // Pairs of triangles sharing an edge, rays aimed at (the f64 rounding of) a point of the
        // shared edge: the hardest cases for the filter, which must agree with the exact test.
        let mut rng = Pcg64::seed_from_u64(11);
        for _ in 0..2000 {
            let a = random_unit(&mut rng);
            let b = random_unit(&mut rng);
            let c = random_unit(&mut rng);
            let t1 = Triangle::new(DVec3::ZERO, a, b);
            let t2 = Triangle::new(DVec3::ZERO, b, c);
            let s: f64 = rng.gen();
            let target = b * s;
            let o = target + random_unit(&mut rng) * 2.0;
            let r = ray(o, target - o);
            let h1 = tri_hit(&r, &t1);
            let h2 = tri_hit(&r, &t2);
            assert_eq!(h1, tri_exact(&r, &t1));
            assert_eq!(h2, tri_exact(&r, &t2));
        }
    }

    #[test]
    fn rounding_brackets_the_rational() {
        let third = BigRational::new(BigInt::from(1), BigInt::from(3));
        let (d, u) = (round_down(&third), round_up(&third));
        assert!(rat(d) < third && third < rat(u));
        assert_eq!(d.next_up(), u);
        assert_eq!(round_down(&rat(0.5)), 0.5);
        assert_eq!(round_up(&rat(0.5)), 0.5);
        let neg = -third;
        assert!(rat(round_down(&neg)) < neg && neg < rat(round_up(&neg)));
    }
}
