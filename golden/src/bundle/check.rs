//! Checking the bundle datapaths against the truth: the exact per-ray results of a case's rays and the
//! exact bundle oracle ([`crate::bundle::edge::decide_exact`]), and the tally a campaign keeps. Shared by the
//! model tests (`golden/tests/bundle_models.rs`) and `rtu bundle-campaign`.
//!
//! The promises checked per bundle: never both "all hit" and "all miss"; "all hit" only when every listed
//! ray exactly hits, "all miss" only when every one exactly misses (a listed ray is any ray of the bundle:
//! the generator puts them at the bundle's corners and between); and neither answer where the exact
//! oracle on the same world bundle does not give it (a datapath never decides more than exact arithmetic
//! can).

use crate::bundle::edge::decide_exact;
use crate::bundle::gen::{BundleCase, BundleKind};
use crate::exact::slab_exact;
use crate::geom::{Aabb, Ray};
use std::fmt::Write as _;

/// The exact slab test's hit, fast: an f64 filter decides when the rounding cannot matter, and
/// [`slab_exact`] (rationals) decides the rest. The filter computes each axis's distances as
/// `(b - o) * (1 / d)`, whose relative error is at most about `3 eps` (three roundings; `1 / d` is off by up
/// to `2 eps` when it is subnormal, `|d| > 2^1022`; an underflowing product is covered by the absolute
/// `MIN_POSITIVE`, and anything that overflows goes to the exact test), and widens or narrows
/// them by `4 eps |t| + MIN_POSITIVE`: the widened interval encloses the exact one and the narrowed one lies
/// inside it, so "widened empty" is a sure miss and "narrowed non-empty" a sure hit (the argument of
/// [`crate::scene::traverse::slab_conservative`]). Zero direction components are tested exactly; a distance that
/// is not finite goes to the exact test.
pub fn slab_hit(ray: &Ray, b: &Aabb) -> bool {
    if b.is_empty() {
        return false;
    }
    let (mut lo_out, mut hi_out) = (ray.t_min, ray.t_max);
    let (mut lo_in, mut hi_in) = (ray.t_min, ray.t_max);
    for a in 0..3 {
        let (o, d) = (ray.origin[a], ray.dir[a]);
        if d == 0.0 {
            if !(b.min[a] <= o && o <= b.max[a]) {
                return false;
            }
            continue;
        }
        let inv = 1.0 / d;
        let (mut t0, mut t1) = ((b.min[a] - o) * inv, (b.max[a] - o) * inv);
        if !(t0.is_finite() && t1.is_finite()) {
            return slab_exact(ray, b).hit;
        }
        if inv < 0.0 {
            std::mem::swap(&mut t0, &mut t1);
        }
        let slack = |t: f64| t.abs() * (4.0 * f64::EPSILON) + f64::MIN_POSITIVE;
        lo_out = lo_out.max(t0 - slack(t0));
        hi_out = hi_out.min(t1 + slack(t1));
        lo_in = lo_in.max(t0 + slack(t0));
        hi_in = hi_in.min(t1 - slack(t1));
    }
    if lo_out > hi_out {
        false
    } else if lo_in <= hi_in {
        true
    } else {
        slab_exact(ray, b).hit
    }
}

/// The exact per-ray results of a case's listed rays.
pub fn truth(c: &BundleCase) -> Vec<bool> {
    c.rays.iter().map(|r| slab_hit(r, &c.bounds)).collect()
}

/// The exact oracle's `(all_hit, all_miss)` for a case (generated cases are always valid).
pub fn oracle(c: &BundleCase) -> (bool, bool) {
    decide_exact(&c.bundle, &c.bounds).expect("generated cases are valid")
}

/// What a datapath said of a bundle (`got`), checked against the listed rays' `truth` and, when given,
/// the exact oracle's answers. Returns a description of the first broken promise.
pub fn judge(
    c: &BundleCase,
    truth: &[bool],
    oracle: Option<(bool, bool)>,
    got: (bool, bool),
) -> Result<(), String> {
    let (all_hit, all_miss) = got;
    let ctx = || format!("{:?} bundle {:?} box {:?}", c.kind, c.bundle, c.bounds);
    if all_hit && all_miss {
        return Err(format!("both all-hit and all-miss: {}", ctx()));
    }
    let first = |want: bool| truth.iter().position(|&h| h == want).map(|i| c.rays[i]);
    if all_hit {
        if let Some(r) = first(false) {
            return Err(format!("false all-hit: ray {r:?} misses; {}", ctx()));
        }
    }
    if all_miss {
        if let Some(r) = first(true) {
            return Err(format!("false all-miss: ray {r:?} hits; {}", ctx()));
        }
    }
    if let Some(o) = oracle {
        if all_hit && !o.0 {
            return Err(format!("all-hit where the exact oracle is not: {}", ctx()));
        }
        if all_miss && !o.1 {
            return Err(format!("all-miss where the exact oracle is not: {}", ctx()));
        }
    }
    Ok(())
}

/// How many violation descriptions a tally keeps (all are counted).
pub const KEPT_VIOLATIONS: usize = 10;

/// Counts of one datapath over a campaign.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    pub bundles: u64,
    pub rays: u64,
    pub all_hit: u64,
    pub all_miss: u64,
    /// Bundles the oracle was run on, and its answers there.
    pub oracle_checked: u64,
    pub oracle_hit: u64,
    pub oracle_miss: u64,
    /// Bundles whose listed rays all hit / all miss.
    pub ideal_hit: u64,
    pub ideal_miss: u64,
    pub straddling: u64,
    pub adversarial: u64,
    /// Uniform (non-adversarial) bundles: count, all-hit, all-miss, listed all hit, listed all miss.
    pub uniform: [u64; 5],
    pub violation_count: u64,
    pub violations: Vec<String>,
}

impl Tally {
    /// Counts one bundle and checks it (see [`judge`]).
    pub fn add(
        &mut self,
        c: &BundleCase,
        t: &[bool],
        oracle: Option<(bool, bool)>,
        got: (bool, bool),
    ) {
        self.bundles += 1;
        self.rays += t.len() as u64;
        self.all_hit += u64::from(got.0);
        self.all_miss += u64::from(got.1);
        if let Some(o) = oracle {
            self.oracle_checked += 1;
            self.oracle_hit += u64::from(o.0);
            self.oracle_miss += u64::from(o.1);
        }
        let (ih, im) = (t.iter().all(|&h| h), t.iter().all(|&h| !h));
        self.ideal_hit += u64::from(ih);
        self.ideal_miss += u64::from(im);
        self.straddling += u64::from(c.bundle.straddles());
        if c.kind == BundleKind::Uniform {
            for (n, v) in self.uniform.iter_mut().zip([true, got.0, got.1, ih, im]) {
                *n += u64::from(v);
            }
        } else {
            self.adversarial += 1;
        }
        if let Err(e) = judge(c, t, oracle, got) {
            self.violation_count += 1;
            if self.violations.len() < KEPT_VIOLATIONS {
                self.violations.push(e);
            }
        }
    }

    /// Adds another tally of the same datapath (another thread's share).
    pub fn merge(&mut self, o: &Tally) {
        self.bundles += o.bundles;
        self.rays += o.rays;
        self.all_hit += o.all_hit;
        self.all_miss += o.all_miss;
        self.oracle_checked += o.oracle_checked;
        self.oracle_hit += o.oracle_hit;
        self.oracle_miss += o.oracle_miss;
        self.ideal_hit += o.ideal_hit;
        self.ideal_miss += o.ideal_miss;
        self.straddling += o.straddling;
        self.adversarial += o.adversarial;
        for (a, b) in self.uniform.iter_mut().zip(o.uniform) {
            *a += b;
        }
        self.violation_count += o.violation_count;
        for v in &o.violations {
            if self.violations.len() < KEPT_VIOLATIONS {
                self.violations.push(v.clone());
            }
        }
    }

    /// One line of counts, and one for the uniform bundles alone.
    pub fn report(&self, name: &str) -> String {
        let pct = |n: u64, of: u64| 100.0 * n as f64 / of.max(1) as f64;
        let mut s = format!(
            "{name}: {} bundles ({} adversarial, {} straddling), {} rays; all-hit {:.1}% (listed rays all hit \
             {:.1}%), all-miss {:.1}% (listed rays all miss {:.1}%)",
            self.bundles,
            self.adversarial,
            self.straddling,
            self.rays,
            pct(self.all_hit, self.bundles),
            pct(self.ideal_hit, self.bundles),
            pct(self.all_miss, self.bundles),
            pct(self.ideal_miss, self.bundles),
        );
        if self.oracle_checked > 0 {
            let _ = write!(
                s,
                "; exact oracle on {}: all-hit {:.1}%, all-miss {:.1}%",
                self.oracle_checked,
                pct(self.oracle_hit, self.oracle_checked),
                pct(self.oracle_miss, self.oracle_checked)
            );
        }
        let _ = write!(s, "; {} violations", self.violation_count);
        let u = &self.uniform;
        let _ = write!(
            s,
            "\n{name}: uniform bundles only ({}): all-hit {:.1}% (listed {:.1}%), all-miss {:.1}% (listed {:.1}%)",
            u[0],
            pct(u[1], u[0]),
            pct(u[3], u[0]),
            pct(u[2], u[0]),
            pct(u[4], u[0])
        );
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bundle::gen::BundleGen;
    use glam::DVec3;

    #[test]
    fn filtered_slab_hit_equals_the_exact_test() {
        let (lo, hi) = (DVec3::splat(-100.0), DVec3::splat(100.0));
        let mut g = BundleGen::new(5, lo, hi, 0.8);
        let (mut n, mut hits) = (0, 0);
        for _ in 0..20_000 {
            let c = g.next_case();
            for r in &c.rays {
                let e = slab_exact(r, &c.bounds).hit;
                assert_eq!(slab_hit(r, &c.bounds), e, "{r:?} {:?}", c.bounds);
                n += 1;
                hits += usize::from(e);
            }
        }
        // The adversarial kinds aim rays at edges and faces: both answers are frequent.
        assert!(hits > n / 10 && hits < n * 9 / 10, "{hits} of {n}");
        // The filter's edges: subnormal and huge components (1/d overflowing or subnormal), infinite
        // t_min, a face at t = 0, t_max ending exactly on a face, zero components of either sign.
        let unit = Aabb {
            min: DVec3::ZERO,
            max: DVec3::ONE,
        };
        let inf = f64::INFINITY;
        for (o, d, t0, t1) in [
            ([-4.0, 0.5, 0.5], [1.0, 1e-320, 0.0], 0.0, inf),
            ([-4.0, 0.5, 0.5], [1.7e308, 1e-320, -0.0], 0.0, inf),
            ([-4.0, 1.0, 0.5], [1.7e308, 1.7e308, 0.0], 0.0, inf),
            ([0.0, 0.5, 0.5], [-1.0, 0.0, 0.0], 0.0, inf),
            ([0.0, 0.5, 0.5], [-1.0, 0.0, 0.0], 1e-300, inf),
            ([2.0, 0.5, 0.5], [1.0, 0.0, 0.0], -inf, 0.0),
            ([2.0, 0.5, 0.5], [1.0, 0.0, 0.0], -inf, -1.0),
            ([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], 0.0, 1.0),
            ([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], 0.0, 1.0 - f64::EPSILON),
            ([-1.0, 0.5, 1.0], [1.0, 0.0, -0.0], 0.0, inf),
        ] {
            let r = Ray {
                origin: DVec3::from(o),
                dir: DVec3::from(d),
                t_min: t0,
                t_max: t1,
            };
            assert_eq!(slab_hit(&r, &unit), slab_exact(&r, &unit).hit, "{r:?}");
        }
    }

    #[test]
    fn judge_names_each_broken_promise() {
        let (lo, hi) = (DVec3::splat(-100.0), DVec3::splat(100.0));
        let mut g = BundleGen::new(9, lo, hi, 0.5);
        let c = loop {
            let c = g.next_case();
            let t = truth(&c);
            if t.iter().any(|&h| h) && t.iter().any(|&h| !h) {
                break c;
            }
        };
        let t = truth(&c);
        assert!(judge(&c, &t, None, (false, false)).is_ok());
        assert!(judge(&c, &t, None, (true, false))
            .unwrap_err()
            .contains("false all-hit"));
        assert!(judge(&c, &t, None, (false, true))
            .unwrap_err()
            .contains("false all-miss"));
        assert!(judge(&c, &t, None, (true, true))
            .unwrap_err()
            .contains("both"));
        let all_hit_case = (0..100_000)
            .map(|_| g.next_case())
            .find(|c| truth(c).iter().all(|&h| h) && !oracle(c).0);
        if let Some(c) = all_hit_case {
            let t = truth(&c);
            assert!(judge(&c, &t, Some(oracle(&c)), (true, false))
                .unwrap_err()
                .contains("exact oracle"));
        }
        let mut tally = Tally::default();
        tally.add(&c, &t, None, (true, false));
        tally.add(&c, &t, None, (false, false));
        assert_eq!((tally.bundles, tally.violation_count), (2, 1));
    }
}
