//! The conservativeness check of a bit-accurate result against the exact oracle.
//!
//! Contract: a ray that truly hits must be reported as a hit, and the reported
//! `[t_entry, t_exit]` must enclose the true interval. A reported hit that is truly a miss is a false hit:
//! allowed, counted as extra work.

use crate::exact::{slab_exact, ExactHit, Ext};
use crate::format::fixed::{FixBox, FixFormat, FixRay, GridMap};
use crate::geom::{Aabb, Ray};
use crate::slab::fix::{slab_fix, SlabFixOut};

/// How one vector compared with the truth.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Both agree on the hit, and the interval encloses the exact one.
    Agree,
    /// The datapath reports a hit that is truly a miss (allowed: extra work).
    FalseHit,
    /// A true hit reported as a miss, or an interval that does not enclose the truth: a correctness bug.
    Violation(String),
}

/// Judges a result against the exact oracle, for any datapath: `hit`, and `interval` — the reported
/// `[t_entry, t_exit]` as exact world values, computed only for a reported hit, `None` when it has no value
/// (a NaN).
pub fn judge(
    exact: &ExactHit,
    hit: bool,
    interval: impl FnOnce() -> Option<(Ext, Ext)>,
) -> Verdict {
    match (exact.hit, hit) {
        (false, false) => Verdict::Agree,
        (false, true) => Verdict::FalseHit,
        (true, false) => Verdict::Violation("false miss".into()),
        (true, true) => match interval() {
            None => Verdict::Violation("NaN in a hit's interval".into()),
            Some((en, _)) if en > exact.entry => Verdict::Violation(format!(
                "t_entry {} is after the exact entry {}",
                en.to_f64(),
                exact.entry.to_f64()
            )),
            Some((_, ex)) if ex < exact.exit => Verdict::Violation(format!(
                "t_exit {} is before the exact exit {}",
                ex.to_f64(),
                exact.exit.to_f64()
            )),
            Some(_) => Verdict::Agree,
        },
    }
}

/// Compares a fixed-point result with the exact oracle.
pub fn judge_fix(fmt: &FixFormat, fr: &FixRay, out: &SlabFixOut, exact: &ExactHit) -> Verdict {
    judge(exact, out.hit, || {
        Some((fr.t_world(fmt, out.t_entry), fr.t_world(fmt, out.t_exit)))
    })
}

/// Quantises one world vector, runs the bit-accurate model and the exact oracle, and judges.
/// Returns the quantised inputs and output too, for reporting a failure.
pub fn check_fix(
    map: &GridMap,
    ray: &Ray,
    b: &Aabb,
) -> Result<(FixRay, FixBox, SlabFixOut, Verdict), crate::Error> {
    let fr = map.quantize_ray(ray)?;
    let fb = map.quantize_box(b)?;
    let out = slab_fix(&map.fmt, &fr, &fb);
    let v = judge_fix(&map.fmt, &fr, &out, &slab_exact(ray, b));
    Ok((fr, fb, out, v))
}
