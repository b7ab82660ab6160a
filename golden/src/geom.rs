//! World-space ray and axis-aligned box, in f64, with input validation.
//!
//! Following obvhs' `Ray`, a ray carries its parameter range `[t_min, t_max]`; the testers report the
//! part of that range spent inside the box. Points of the ray are `origin + t * dir`.

use crate::error::Error;
use glam::DVec3;

const AXES: [&str; 3] = ["x", "y", "z"];

/// A ray in world space. `t_max` may be `+inf` and `t_min` may be `-inf`; nothing may be NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
    pub t_min: f64,
    pub t_max: f64,
}

/// An axis-aligned box. `min > max` on any axis makes the box empty: it is hit by no ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Ray {
    /// Builds a ray and checks it: finite origin and direction, `t_min <= t_max`, no NaN.
    pub fn new(origin: DVec3, dir: DVec3, t_min: f64, t_max: f64) -> Result<Self, Error> {
        let r = Ray {
            origin,
            dir,
            t_min,
            t_max,
        };
        r.validate()?;
        Ok(r)
    }

    /// Checks the ray; the error names the offending component.
    pub fn validate(&self) -> Result<(), Error> {
        for a in 0..3 {
            let o = self.origin[a];
            if !o.is_finite() {
                return Err(Error::bad_value(
                    format!("ray origin.{}", AXES[a]),
                    o,
                    "origins must be finite",
                ));
            }
            let d = self.dir[a];
            if !d.is_finite() {
                return Err(Error::bad_value(
                    format!("ray dir.{}", AXES[a]),
                    d,
                    "directions must be finite",
                ));
            }
        }
        if self.t_min.is_nan() || self.t_min == f64::INFINITY {
            return Err(Error::bad_value(
                "ray t_min",
                self.t_min,
                "t_min must be a number below +inf",
            ));
        }
        if self.t_max.is_nan() || self.t_max == f64::NEG_INFINITY {
            return Err(Error::bad_value(
                "ray t_max",
                self.t_max,
                "t_max must be a number above -inf",
            ));
        }
        if self.t_min > self.t_max {
            return Err(Error::bad_value(
                "ray t_min",
                self.t_min,
                "t_min must not exceed t_max",
            ));
        }
        Ok(())
    }
}

impl Aabb {
    /// Builds a box and checks that every bound is finite. `min > max` is allowed and means empty.
    pub fn new(min: DVec3, max: DVec3) -> Result<Self, Error> {
        let b = Aabb { min, max };
        b.validate()?;
        Ok(b)
    }

    /// Checks the box; the error names the offending bound.
    pub fn validate(&self) -> Result<(), Error> {
        for a in 0..3 {
            for (name, v) in [("min", self.min[a]), ("max", self.max[a])] {
                if !v.is_finite() {
                    return Err(Error::bad_value(
                        format!("box {name}.{}", AXES[a]),
                        v,
                        "box bounds must be finite",
                    ));
                }
            }
        }
        Ok(())
    }

    /// True when some axis has `min > max`.
    pub fn is_empty(&self) -> bool {
        (0..3).any(|a| self.min[a] > self.max[a])
    }
}

/// Result of a slab test in world units: `hit`, and when hit the part `[t_entry, t_exit]` of the ray's
/// range inside the box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlabHit {
    pub hit: bool,
    pub t_entry: f64,
    pub t_exit: f64,
}
