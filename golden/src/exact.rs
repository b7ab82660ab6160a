//! The exact oracle: the slab test in rational arithmetic on the real-valued inputs.
//!
//! Every finite f64 is a dyadic rational, so `BigRational::from_float` represents the inputs exactly and
//! the oracle's entry and exit are the true ones. Special cases follow [`crate::slab::reference`]: a zero
//! direction component leaves the axis unconstrained when the origin is inside the closed slab and
//! misses otherwise; an empty box is never hit.

use crate::geom::{Aabb, Ray};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Signed;
use std::cmp::Ordering;

/// An extended rational: `-inf`, a finite rational, or `+inf`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Ext {
    NegInf,
    Fin(BigRational),
    PosInf,
}

impl Ext {
    /// Exact value of a non-NaN f64.
    pub fn from_f64(x: f64) -> Ext {
        if x == f64::INFINITY {
            Ext::PosInf
        } else if x == f64::NEG_INFINITY {
            Ext::NegInf
        } else {
            Ext::Fin(rat(x))
        }
    }

    /// `m * 2^e` exactly.
    pub fn dyadic(m: i64, e: i32) -> Ext {
        Ext::Fin(dyadic(m, e))
    }

    /// The largest f64 `<= self`: `-inf` stays `-inf`, and a finite value above the largest finite f64
    /// gives that, not `+inf` (the directed rounding of an interval's lower end).
    pub fn down_f64(&self) -> f64 {
        match self {
            Ext::NegInf => f64::NEG_INFINITY,
            Ext::PosInf => f64::INFINITY,
            Ext::Fin(r) => round_down(r),
        }
    }

    /// The smallest f64 `>= self` (the directed rounding of an interval's upper end).
    pub fn up_f64(&self) -> f64 {
        match self {
            Ext::NegInf => f64::NEG_INFINITY,
            Ext::PosInf => f64::INFINITY,
            Ext::Fin(r) => round_up(r),
        }
    }

    /// The nearest f64 (for printing and CSV output only).
    pub fn to_f64(&self) -> f64 {
        match self {
            Ext::NegInf => f64::NEG_INFINITY,
            Ext::PosInf => f64::INFINITY,
            Ext::Fin(r) => {
                use num_traits::ToPrimitive;
                r.to_f64().unwrap_or(f64::NAN)
            }
        }
    }
}

impl PartialOrd for Ext {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Ext {
    fn cmp(&self, other: &Self) -> Ordering {
        use Ext::*;
        match (self, other) {
            (NegInf, NegInf) | (PosInf, PosInf) => Ordering::Equal,
            (NegInf, _) | (_, PosInf) => Ordering::Less,
            (_, NegInf) | (PosInf, _) => Ordering::Greater,
            (Fin(a), Fin(b)) => a.cmp(b),
        }
    }
}

/// Exact rational of a finite f64.
pub fn rat(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite f64")
}

/// The largest f64 `<= r`; beyond the f64 range `-inf` below and the largest finite f64 above.
pub fn round_down(r: &BigRational) -> f64 {
    use num_traits::ToPrimitive;
    let x = r.to_f64().unwrap_or(f64::NAN);
    if x.is_nan() {
        return if r.is_negative() {
            f64::NEG_INFINITY
        } else {
            f64::MAX
        };
    }
    if x.is_infinite() {
        return if x > 0.0 { f64::MAX } else { f64::NEG_INFINITY };
    }
    if &rat(x) > r {
        x.next_down()
    } else {
        x
    }
}

/// The smallest f64 `>= r`; beyond the f64 range `+inf` above and the most negative finite f64 below.
pub fn round_up(r: &BigRational) -> f64 {
    -round_down(&-r)
}

/// `m * 2^e` as an exact rational.
pub fn dyadic(m: i64, e: i32) -> BigRational {
    let m = BigInt::from(m);
    if e >= 0 {
        BigRational::from_integer(m << (e as usize))
    } else {
        BigRational::new(m, BigInt::from(1) << ((-e) as usize))
    }
}

/// The exact slab result: `hit`, and the true `[entry, exit]` (meaningful when hit).
#[derive(Clone, Debug, PartialEq)]
pub struct ExactHit {
    pub hit: bool,
    pub entry: Ext,
    pub exit: Ext,
}

/// Exact slab test. Inputs must have passed validation (no NaN, finite origin, direction and box).
pub fn slab_exact(ray: &Ray, b: &Aabb) -> ExactHit {
    let mut entry = Ext::from_f64(ray.t_min);
    let mut exit = Ext::from_f64(ray.t_max);
    let mut inside = !b.is_empty();
    for a in 0..3 {
        let (o, d) = (ray.origin[a], ray.dir[a]);
        if d == 0.0 {
            inside &= b.min[a] <= o && o <= b.max[a];
            continue;
        }
        let (ro, rd) = (rat(o), rat(d));
        let t0 = (rat(b.min[a]) - &ro) / &rd;
        let t1 = (rat(b.max[a]) - &ro) / &rd;
        let (lo, hi) = if rd.is_negative() { (t1, t0) } else { (t0, t1) };
        entry = entry.max(Ext::Fin(lo));
        exit = exit.min(Ext::Fin(hi));
    }
    let hit = inside && entry <= exit;
    ExactHit { hit, entry, exit }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn ext_orders_infinities_around_finite_values() {
        assert!(Ext::NegInf < Ext::dyadic(-5, 100));
        assert!(Ext::dyadic(5, 100) < Ext::PosInf);
        assert!(Ext::dyadic(1, -1) < Ext::dyadic(1, 0));
    }

    #[test]
    fn exact_finds_grazing_corner_hit() {
        // The ray passes exactly through the corner (1,1,1) of the unit box.
        let r = Ray::new(
            DVec3::new(-1.0, -1.0, -1.0),
            DVec3::new(0.1, 0.1, 0.1) * 3.0,
            0.0,
            f64::INFINITY,
        )
        .unwrap();
        let b = Aabb::new(DVec3::ONE, DVec3::splat(2.0)).unwrap();
        let h = slab_exact(&r, &b);
        assert!(h.hit);
        // All three axes enter at 2 / d and leave at 3 / d, d being the f64 nearest 0.3.
        let d = rat(0.1 * 3.0);
        assert_eq!(h.entry, Ext::Fin(rat(2.0) / &d));
        assert_eq!(h.exit, Ext::Fin(rat(3.0) / &d));
    }
}
