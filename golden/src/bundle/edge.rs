//! Ray bundles against a box without division: the single-ray edge test, and the AllHit / AnyHit bundle
//! tests, as the float reference (f64) and the exact oracle (rationals). The bit-accurate datapaths
//! ([`crate::bundle::fix`], [`crate::bundle::float`]) run the same logic, [`conditions_hold`], in their own
//! arithmetic.
//!
//! Source: Imagination Technologies, US 11,308,683 and its family (the continuations US 11,715,255 "using
//! ray bundle vectors" and US 11,682,160 "using multiple ray bundle intersection tests"): a bundle of rays is
//! tested against a box through its silhouette edges, one bounding vector per edge, with no division; a
//! first testing block decides "every ray hits" and a second "every ray misses", and a pair of blocks takes
//! either one bundle or two single rays (claims of US 11,682,160). FIG. 16 of US 11,308,683
//! gives the bounds: external bound and box shrunk by the origin spread for AllHit, internal bound
//! and enlarged box for AnyHit; FIG. 7 the bundles whose directions straddle an axis. The single-ray
//! conditions follow the division-free tests of the same family (US 11,741,655 and US 11,741,659, whose
//! claims also round conservatively). The algebra and proofs below are this project's own, written from
//! those ideas; paragraph numbers are not cited because they were not checked against the text.
//!
//! # The single-ray test (and why it is the slab test)
//! A ray `o + t d`, `t in [t0, t1]` (`t0` may be `-inf`, `t1` `+inf`, `t0 <= t1`), and a closed box
//! `[lo, hi]`. The ray hits when some real `t in [t0, t1]` has `lo <= o + t d <= hi`: exactly the slab
//! tester's semantics ([`crate::slab::reference`], [`crate::exact::slab_exact`]), zero direction components and
//! empty boxes included.
//!
//! Fold each axis by the sign `s_a` of `d_a` (`+` for a zero component: either sign works there):
//! `u_a = s_a d_a >= 0`, and with the near and far planes `near_a = s_a > 0 ? lo_a : hi_a`, `far_a` the other,
//! `e_a = s_a (near_a - o_a)`, `x_a = s_a (far_a - o_a)`. Then `lo_a <= o_a + t d_a <= hi_a` is
//! `e_a <= t u_a <= x_a`. The test is, with `t * 0 = 0` for every `t` (infinite ones too) and
//! `(+-inf) * u = +-inf` for `u > 0`:
//!
//! ```text
//! N_a      lo_a <= hi_a                        box not empty                  (3)
//! E_ab     e_a u_b <= x_b u_a      (a != b)    silhouette edge (near_a, far_b)  (6)
//! D_a      t0 u_a <= x_a                       direction: the far plane is ahead (3; t0 = 0: x_a >= 0)
//! T_a      e_a <= t1 u_a                       distance: the near plane is within t1 (3)
//! ```
//!
//! Unfolded, `E_ab` is `s_a s_b ((near_a - o_a) d_b - (far_b - o_b) d_a) <= 0`: the patent's
//! `(p_i - o_i) d_j <= (p_j - o_j) d_i` with the comparison turned by the signs.
//!
//! **Theorem 1.** The ray hits the box if and only if all fifteen conditions hold.
//!
//! *Only if.* Let `t*` be a hit. For every axis `e_a <= t* u_a <= x_a` (so `lo <= hi`: `N`). For `a != b`,
//! multiplying by `u_b >= 0` and `u_a >= 0`: `e_a u_b <= t* u_a u_b <= x_b u_a` (`E`). `t0 <= t*` and
//! `u_a >= 0` give `t0 u_a <= t* u_a <= x_a` (`D`; for `u_a = 0` both sides are 0; for `t0 = -inf`,
//! `u_a > 0` the left is `-inf`). Likewise `e_a <= t* u_a <= t1 u_a` (`T`).
//!
//! *If.* Let `A` be the axes with `u_a > 0` and `Z` the others. If `A` is empty, `D` and `T` read
//! `0 <= x_a` and `e_a <= 0`, so the origin is in the box and any real `t in [t0, t1]` (one exists:
//! `t0 < +inf`, `t1 > -inf`, `t0 <= t1`) hits. Otherwise pick `c in A`: for `a in Z`, `E_ac` reads
//! `e_a u_c <= 0`, so `e_a <= 0`, and `E_ca` reads `0 <= x_a u_c`, so `x_a >= 0`: every `t` satisfies axis
//! `a`. The remaining constraints are the lower bounds `t0` and `e_a / u_a` and the upper bounds `t1` and
//! `x_b / u_b` (`a, b in A`); at least one of each is finite. The largest lower bound `L` is at most the
//! smallest upper bound `U` because every pair is in order: `e_a / u_a <= x_b / u_b` is `E_ab` (`a != b`)
//! or `N_a` (`a = b`, as `e_a <= x_a` iff `lo_a <= hi_a`); `t0 <= x_b / u_b` is `D_b`; `e_a / u_a <= t1` is
//! `T_a`; `t0 <= t1` is given. So `t = L` is real, lies in `[t0, t1]` and satisfies every axis. ∎
//!
//! # Bundles
//! A bundle ([`BundleOf`]) is an origin box `[o_lo, o_hi]`, a direction box `[d_lo, d_hi]` and a range
//! `[t_lo, t_hi]` of `t_max` (`0 <= t_lo <= t_hi`, `t_hi` may be `+inf`); its rays are every
//! `o + t d`, `t in [0, t_max]`, with `o`, `d`, `t_max` in those boxes. It stands for every such ray, not
//! only the listed rays it was built from: both answers below hold for the whole set.
//!
//! Per axis the direction interval is *positive* (`d_lo >= 0`), *negative* (`d_hi <= 0`) or *straddling*
//! (`d_lo < 0 < d_hi`, FIG. 7). For a fixed sign the folded quantities of a ray are `u_a` in
//! `[u_lo, u_hi] = [d_lo, d_hi]` (or `[-d_hi, -d_lo]`) and `e_a`, `x_a` over the origin interval. A
//! straddling axis takes both signs: each ray has its own `s_a`; the test lets `s_a` range over both signs
//! independently of the rest (`e_a`, `x_a` over both folds, `u_a in [0, max(-d_lo, d_hi)]`), a superset of
//! the real rays that costs some tightness but no soundness, and keeps one datapath for every bundle (no
//! sign-case split, no second pass). One refinement keeps AnyHit useful for the common straddling bundle
//! that passes beside a box: when the upper bound of `x_a` in one fold is negative, every ray of that half
//! fails `D_a` and misses, so "all miss" reduces to the other half, whose fold alone is used (with
//! `u_a in [0, -d_lo]` or `[0, d_hi]`; the rays with `d_a = 0` belong to both halves).
//!
//! Every condition is `lhs <= rhs` with `lhs`, `rhs` each a product of one bounded quantity and a
//! non-negative one (`e_a u_b`, `x_b u_a`, `t u_a`), or a single quantity. Over intervals
//! `v in [v_lo, v_hi]`, `u in [u_lo, u_hi] >= 0`, `t in [t_lo, t_hi] >= 0`:
//! `max(v u) = v_hi (v_hi >= 0 ? u_hi : u_lo)`, `min(v u) = v_lo (v_lo >= 0 ? u_lo : u_hi)`,
//! `min(t u) = t_lo u_lo`, `max(t u) = t_hi u_hi` (with `t * 0 = 0`): each one product with its operands
//! chosen by a sign — the patent's "external" and "internal" bounding vectors.
//!
//! **AllHit** ([`Test::AllHit`]) evaluates every condition with an upper bound of `lhs` and a lower bound of
//! `rhs`: `e` at its largest and `x` at its smallest over the origin box (the box shrunk by the origin
//! spread), `t_max` at `t_lo`. **Theorem 2a.** If every condition passes, every ray of the bundle hits:
//! each ray's own `lhs <= upper bound <= lower bound <= rhs`, so all its conditions hold (with its own fold,
//! which the superset contains), and Theorem 1 applies. Without a straddling axis it is also exact in exact
//! arithmetic: a condition's two sides depend on disjoint inputs (`e_a u_b` on `o_a`, `d_b`; `x_b u_a` on
//! `o_b`, `d_a`), so both bounds are reached at once by one corner ray of the bundle, which then fails that
//! condition and misses; "every ray hits" is the conjunction over conditions of "every ray passes it".
//!
//! **AnyHit** ([`Test::AnyHit`]) evaluates every condition with a lower bound of `lhs` and an upper bound of
//! `rhs` (`e` smallest, `x` largest: the box enlarged by the origin spread, `t_max` at `t_hi`).
//! **Theorem 2b.** If some condition fails there, every ray of the bundle misses: each ray's
//! `lhs >= lower bound > upper bound >= rhs`, so that condition fails for it, and Theorem 1 applies. The
//! converse does not hold (rays may miss for different reasons), so AnyHit answers "all miss" or "maybe".
//!
//! For a bundle of one ray every interval is a point, both tests compute Theorem 1's conditions, and
//! `all_hit = hit = !all_miss` in exact arithmetic. The f64 reference rounds to nearest and is the meaning
//! of the test, not a bound; the exact oracle ([`ExactArith`]) is sound by the theorems above; the
//! datapaths keep soundness by bounding each difference and product in the direction the test needs.

use crate::error::Error;
use crate::exact::{rat, Ext};
use crate::geom::{Aabb, Ray};
use glam::DVec3;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

const AXES: [&str; 3] = ["x", "y", "z"];

/// A bundle in some number representation; see the module doc. Rays start at their origin (`t_min = 0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct BundleOf<V, T> {
    pub o_lo: [V; 3],
    pub o_hi: [V; 3],
    pub d_lo: [V; 3],
    pub d_hi: [V; 3],
    /// Smallest `t_max` of the bundle's rays.
    pub t_lo: T,
    /// Largest `t_max` of the bundle's rays (may be `+inf`).
    pub t_hi: T,
}

/// A bundle in world units (f64).
pub type Bundle = BundleOf<f64, f64>;

impl<V, T> BundleOf<V, T> {
    /// The same bundle with every coordinate mapped by `fv` and both t values by `ft`.
    pub fn map<W, U>(&self, fv: impl Fn(&V) -> W, ft: impl Fn(&T) -> U) -> BundleOf<W, U> {
        let m = |a: &[V; 3]| std::array::from_fn(|i| fv(&a[i]));
        BundleOf {
            o_lo: m(&self.o_lo),
            o_hi: m(&self.o_hi),
            d_lo: m(&self.d_lo),
            d_hi: m(&self.d_hi),
            t_lo: ft(&self.t_lo),
            t_hi: ft(&self.t_hi),
        }
    }
}

/// A box as the pair of corner arrays `(lo, hi)` the tests take.
pub type BoxArrays<V> = ([V; 3], [V; 3]);

/// A box as given to the two tests: `inner` rounded inward (AllHit needs every ray to hit the true box,
/// so it may only shrink it), `outer` rounded outward (AnyHit's "all miss" may only grow it). For a box
/// already on the format's grid they are equal: the hardware stores node boxes quantised, so the pair of
/// blocks takes one box; the models keep both so that a world box off the grid is still judged against
/// itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct BoxPair<B> {
    pub inner: B,
    pub outer: B,
}

impl Bundle {
    /// Builds a bundle and checks it (see [`Bundle::validate`]).
    pub fn new(o: (DVec3, DVec3), d: (DVec3, DVec3), t_lo: f64, t_hi: f64) -> Result<Self, Error> {
        let b = Bundle {
            o_lo: o.0.into(),
            o_hi: o.1.into(),
            d_lo: d.0.into(),
            d_hi: d.1.into(),
            t_lo,
            t_hi,
        };
        b.validate()?;
        Ok(b)
    }

    /// Checks the bundle: finite origin and direction bounds with `lo <= hi`, and
    /// `0 <= t_lo <= t_hi` (no NaN; `+inf` allowed). The error names the offending bound.
    pub fn validate(&self) -> Result<(), Error> {
        for (a, axis) in AXES.iter().enumerate() {
            for (what, lo, hi) in [
                ("origin", self.o_lo[a], self.o_hi[a]),
                ("direction", self.d_lo[a], self.d_hi[a]),
            ] {
                for (end, v) in [("min", lo), ("max", hi)] {
                    if !v.is_finite() {
                        return Err(Error::bad_value(
                            format!("bundle {what} {end}.{axis}"),
                            v,
                            "bundle origins and directions must be finite",
                        ));
                    }
                }
                if lo > hi {
                    return Err(Error::bad_value(
                        format!("bundle {what} min.{axis}"),
                        lo,
                        "a bundle's min must not exceed its max",
                    ));
                }
            }
        }
        if self.t_lo.is_nan() || self.t_lo < 0.0 {
            return Err(Error::bad_value(
                "bundle t_max min",
                self.t_lo,
                "t_max must be a number >= 0 (rays start at their origin)",
            ));
        }
        if self.t_hi.is_nan() || self.t_hi < self.t_lo {
            return Err(Error::bad_value(
                "bundle t_max max",
                self.t_hi,
                "must be a number at least the bundle's smallest t_max",
            ));
        }
        Ok(())
    }

    /// The one-ray bundle of `ray`, which must start at its origin (`t_min = 0`).
    pub fn of_ray(ray: &Ray) -> Result<Self, Error> {
        Self::around(std::slice::from_ref(ray))
    }

    /// The smallest bundle holding `rays`: all valid, with `t_min = 0`, at least one.
    pub fn around(rays: &[Ray]) -> Result<Self, Error> {
        let first = rays
            .first()
            .ok_or_else(|| Error::Io("a bundle needs at least one ray".into()))?;
        let mut b = Bundle {
            o_lo: first.origin.into(),
            o_hi: first.origin.into(),
            d_lo: first.dir.into(),
            d_hi: first.dir.into(),
            t_lo: first.t_max,
            t_hi: first.t_max,
        };
        for r in rays {
            r.validate()?;
            if r.t_min != 0.0 {
                return Err(Error::bad_value(
                    "ray t_min",
                    r.t_min,
                    "a bundle's rays start at their origin (t_min = 0)",
                ));
            }
            b = b.grown(r);
        }
        b.validate()?;
        Ok(b)
    }

    /// The smallest bundle holding this one and `r` (no validation).
    pub fn grown(&self, r: &Ray) -> Self {
        let mut g = *self;
        for a in 0..3 {
            g.o_lo[a] = g.o_lo[a].min(r.origin[a]);
            g.o_hi[a] = g.o_hi[a].max(r.origin[a]);
            g.d_lo[a] = g.d_lo[a].min(r.dir[a]);
            g.d_hi[a] = g.d_hi[a].max(r.dir[a]);
        }
        g.t_lo = g.t_lo.min(r.t_max);
        g.t_hi = g.t_hi.max(r.t_max);
        g
    }

    /// True when `ray` is one of the bundle's rays.
    pub fn contains(&self, ray: &Ray) -> bool {
        ray.t_min == 0.0
            && self.t_lo <= ray.t_max
            && ray.t_max <= self.t_hi
            && (0..3).all(|a| {
                self.o_lo[a] <= ray.origin[a]
                    && ray.origin[a] <= self.o_hi[a]
                    && self.d_lo[a] <= ray.dir[a]
                    && ray.dir[a] <= self.d_hi[a]
            })
    }

    /// True when the bundle is a single ray (every interval a point).
    pub fn is_one_ray(&self) -> bool {
        self.o_lo == self.o_hi && self.d_lo == self.d_hi && self.t_lo == self.t_hi
    }

    /// True when some axis's direction interval straddles zero (`d_lo < 0 < d_hi`).
    pub fn straddles(&self) -> bool {
        (0..3).any(|a| self.d_lo[a] < 0.0 && 0.0 < self.d_hi[a])
    }
}

/// Which of the pair of testers: see the module doc.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Test {
    /// Bounds against the conditions: passing means every ray hits.
    AllHit,
    /// Bounds in favour of the conditions: failing means every ray misses.
    AnyHit,
}

/// The arithmetic of one model: how differences and products are bounded. `up` asks for a result at or
/// above the exact value, `!up` at or below it; exact arithmetics ignore it. Implemented by the f64
/// reference ([`F64Arith`]), the exact oracle ([`ExactArith`]), and the fixed and float datapaths.
pub trait BoundArith {
    /// Coordinates, differences, direction components and their products.
    type V: Clone;
    /// t values (`+inf` allowed; a single ray's `t_min` may be `-inf`).
    type T;
    /// What a distance check compares: products `t * u` and differences lifted to their scale.
    type P;
    /// `a - b`, bounded.
    fn sub(&self, a: &Self::V, b: &Self::V, up: bool) -> Self::V;
    /// `v * u` for a direction magnitude `u >= 0`, bounded.
    fn mul(&self, v: &Self::V, u: &Self::V, up: bool) -> Self::V;
    /// `a <= b`.
    fn le(&self, a: &Self::V, b: &Self::V) -> bool;
    /// `a < 0` (a negative zero is not negative).
    fn is_neg(&self, a: &Self::V) -> bool;
    /// `-a`, exactly.
    fn neg(&self, a: &Self::V) -> Self::V;
    /// Zero.
    fn zero(&self) -> Self::V;
    /// `t < 0`.
    fn t_is_neg(&self, t: &Self::T) -> bool;
    /// `t * u` for `u >= 0`, bounded, with `t * 0 = 0` for every `t`, infinite included.
    fn t_mul(&self, t: &Self::T, u: &Self::V, up: bool) -> Self::P;
    /// A difference at the scale of [`BoundArith::t_mul`]'s products, exactly.
    fn lift(&self, v: &Self::V) -> Self::P;
    /// `a <= b`.
    fn le_p(&self, a: &Self::P, b: &Self::P) -> bool;
}

/// One axis folded by its direction's sign (see the module doc): `e`, `x` bounded for the test at hand,
/// and the interval of `u = |d|`.
struct Folded<V> {
    e: V,
    x: V,
    u_lo: V,
    u_hi: V,
}

/// The larger (`larger`) or smaller of two values.
fn pick<A: BoundArith>(ar: &A, p: A::V, q: A::V, larger: bool) -> A::V {
    if ar.le(&p, &q) == larger {
        q
    } else {
        p
    }
}

/// Folds axis `a`. `sure` (AllHit) bounds `e` from above and `x` from below; otherwise the reverse.
fn fold<A: BoundArith>(
    ar: &A,
    b: &BundleOf<A::V, A::T>,
    lo: &A::V,
    hi: &A::V,
    a: usize,
    sure: bool,
) -> Folded<A::V> {
    // The origin end that makes `e = lo - o` (positive fold) largest when `sure`, and `x = hi - o` smallest.
    let (o_e, o_x) = if sure {
        (&b.o_lo[a], &b.o_hi[a])
    } else {
        (&b.o_hi[a], &b.o_lo[a])
    };
    let (e_pos, x_pos) = (ar.sub(lo, o_e, sure), ar.sub(hi, o_x, !sure));
    // Negative fold: `e = o - hi`, `x = o - lo`, the origin ends swapped.
    let (e_neg, x_neg) = (ar.sub(o_x, hi, sure), ar.sub(o_e, lo, !sure));
    let (d_lo, d_hi) = (&b.d_lo[a], &b.d_hi[a]);
    let zero = ar.zero();
    if !ar.is_neg(d_lo) {
        Folded {
            e: e_pos,
            x: x_pos,
            u_lo: d_lo.clone(),
            u_hi: d_hi.clone(),
        }
    } else if ar.le(d_hi, &zero) {
        Folded {
            e: e_neg,
            x: x_neg,
            u_lo: ar.neg(d_hi),
            u_hi: ar.neg(d_lo),
        }
    } else if !sure && ar.is_neg(&x_pos) {
        // Straddling, and no ray moving up the axis reaches the far plane: they all miss (D), so AnyHit
        // keeps the other half, |d| in [0, -d_lo].
        Folded {
            e: e_neg,
            x: x_neg,
            u_lo: zero,
            u_hi: ar.neg(d_lo),
        }
    } else if !sure && ar.is_neg(&x_neg) {
        Folded {
            e: e_pos,
            x: x_pos,
            u_lo: zero,
            u_hi: d_hi.clone(),
        }
    } else {
        // Straddling: either fold, |d| from 0 to the larger end.
        Folded {
            e: pick(ar, e_pos, e_neg, sure),
            x: pick(ar, x_pos, x_neg, !sure),
            u_lo: zero,
            u_hi: pick(ar, ar.neg(d_lo), d_hi.clone(), true),
        }
    }
}

/// The bound of `v * u` over `u in [u_lo, u_hi]`: the upper one (`up`) takes `u_hi` for `v >= 0` and
/// `u_lo` for `v < 0`; the lower one the reverse.
fn bound_mul<A: BoundArith>(ar: &A, v: &A::V, u: &Folded<A::V>, up: bool) -> A::V {
    let m = if ar.is_neg(v) == up { &u.u_lo } else { &u.u_hi };
    ar.mul(v, m, up)
}

/// The same for `t * u`, by the sign of `t`.
fn bound_t_mul<A: BoundArith>(ar: &A, t: &A::T, u: &Folded<A::V>, up: bool) -> A::P {
    let m = if ar.t_is_neg(t) == up {
        &u.u_lo
    } else {
        &u.u_hi
    };
    ar.t_mul(t, m, up)
}

/// The fifteen conditions of the module doc, each with the bounds of `test`, over the bundle `b` and the
/// box `[lo, hi]`. `t_min` is the rays' common `t_min` (`None`: 0, the bundle case, where the direction
/// checks are sign checks). AllHit: `true` means every ray hits. AnyHit: `false` means every ray misses.
pub fn conditions_hold<A: BoundArith>(
    ar: &A,
    b: &BundleOf<A::V, A::T>,
    t_min: Option<&A::T>,
    lo: &[A::V; 3],
    hi: &[A::V; 3],
    test: Test,
) -> bool {
    let sure = test == Test::AllHit;
    // N: box not empty.
    if (0..3).any(|a| !ar.le(&lo[a], &hi[a])) {
        return false;
    }
    let f: [Folded<A::V>; 3] = std::array::from_fn(|a| fold(ar, b, &lo[a], &hi[a], a, sure));
    let t_max = if sure { &b.t_lo } else { &b.t_hi };
    for fa in &f {
        // D: t_min u <= x (a sign check for t_min = 0).
        let direction = match t_min {
            None => !ar.is_neg(&fa.x),
            Some(t0) => ar.le_p(&bound_t_mul(ar, t0, fa, sure), &ar.lift(&fa.x)),
        };
        // T: e <= t_max u.
        let distance = ar.le_p(&ar.lift(&fa.e), &bound_t_mul(ar, t_max, fa, !sure));
        if !direction || !distance {
            return false;
        }
    }
    // E: the six silhouette edges, e_a u_b <= x_b u_a.
    for a in 0..3 {
        for c in (0..3).filter(|&c| c != a) {
            let lhs = bound_mul(ar, &f[a].e, &f[c], sure);
            let rhs = bound_mul(ar, &f[c].x, &f[a], !sure);
            if !ar.le(&lhs, &rhs) {
                return false;
            }
        }
    }
    true
}

/// AllHit and AnyHit of one bundle on one box pair, in any arithmetic: `(all_hit, all_miss)`.
pub fn decide<A: BoundArith>(
    ar: &A,
    b: &BundleOf<A::V, A::T>,
    boxes: &BoxPair<BoxArrays<A::V>>,
) -> (bool, bool) {
    let (il, ih) = &boxes.inner;
    let (ol, oh) = &boxes.outer;
    (
        conditions_hold(ar, b, None, il, ih, Test::AllHit),
        !conditions_hold(ar, b, None, ol, oh, Test::AnyHit),
    )
}

/// f64 with round-to-nearest: the float reference, the meaning of the test (not a bound).
#[derive(Clone, Copy, Debug, Default)]
pub struct F64Arith;

impl BoundArith for F64Arith {
    type V = f64;
    type T = f64;
    type P = f64;
    fn sub(&self, a: &f64, b: &f64, _up: bool) -> f64 {
        a - b
    }
    fn mul(&self, v: &f64, u: &f64, _up: bool) -> f64 {
        v * u
    }
    fn le(&self, a: &f64, b: &f64) -> bool {
        a <= b
    }
    fn is_neg(&self, a: &f64) -> bool {
        *a < 0.0
    }
    fn neg(&self, a: &f64) -> f64 {
        -a
    }
    fn zero(&self) -> f64 {
        0.0
    }
    fn t_is_neg(&self, t: &f64) -> bool {
        *t < 0.0
    }
    fn t_mul(&self, t: &f64, u: &f64, _up: bool) -> f64 {
        if *u == 0.0 {
            0.0
        } else {
            t * u
        }
    }
    fn lift(&self, v: &f64) -> f64 {
        *v
    }
    fn le_p(&self, a: &f64, b: &f64) -> bool {
        a <= b
    }
}

/// Rational arithmetic: the exact oracle.
#[derive(Clone, Copy, Debug, Default)]
pub struct ExactArith;

impl BoundArith for ExactArith {
    type V = BigRational;
    type T = Ext;
    type P = Ext;
    fn sub(&self, a: &BigRational, b: &BigRational, _up: bool) -> BigRational {
        a - b
    }
    fn mul(&self, v: &BigRational, u: &BigRational, _up: bool) -> BigRational {
        v * u
    }
    fn le(&self, a: &BigRational, b: &BigRational) -> bool {
        a <= b
    }
    fn is_neg(&self, a: &BigRational) -> bool {
        a.is_negative()
    }
    fn neg(&self, a: &BigRational) -> BigRational {
        -a
    }
    fn zero(&self) -> BigRational {
        BigRational::zero()
    }
    fn t_is_neg(&self, t: &Ext) -> bool {
        *t < Ext::Fin(BigRational::zero())
    }
    fn t_mul(&self, t: &Ext, u: &BigRational, _up: bool) -> Ext {
        match t {
            _ if u.is_zero() => Ext::Fin(BigRational::zero()),
            Ext::Fin(t) => Ext::Fin(t * u),
            inf => inf.clone(),
        }
    }
    fn lift(&self, v: &BigRational) -> Ext {
        Ext::Fin(v.clone())
    }
    fn le_p(&self, a: &Ext, b: &Ext) -> bool {
        a <= b
    }
}

/// The same box inside and out (a box that needs no rounding).
fn same<V: Clone>(lh: BoxArrays<V>) -> BoxPair<BoxArrays<V>> {
    BoxPair {
        inner: lh.clone(),
        outer: lh,
    }
}

/// A world box's corners as f64 arrays.
fn world_box(b: &Aabb) -> BoxArrays<f64> {
    (b.min.into(), b.max.into())
}

/// A world box's corners as exact rationals.
pub fn exact_box(b: &Aabb) -> BoxArrays<BigRational> {
    (b.min.to_array().map(rat), b.max.to_array().map(rat))
}

/// The exact values of a world bundle.
pub fn exact_bundle(b: &Bundle) -> BundleOf<BigRational, Ext> {
    b.map(|&v| rat(v), |&t| Ext::from_f64(t))
}

/// A ray as a point bundle (its `t_min` goes separately to [`conditions_hold`]).
fn point_bundle(r: &Ray) -> Bundle {
    BundleOf {
        o_lo: r.origin.into(),
        o_hi: r.origin.into(),
        d_lo: r.dir.into(),
        d_hi: r.dir.into(),
        t_lo: r.t_max,
        t_hi: r.t_max,
    }
}

/// The division-free single-ray test in f64 (round to nearest): the reference, which may differ from the
/// exact answer on grazing rays. Errors on an invalid ray or box.
pub fn ray_hits_ref(ray: &Ray, b: &Aabb) -> Result<bool, Error> {
    ray.validate()?;
    b.validate()?;
    let (lo, hi) = world_box(b);
    let p = point_bundle(ray);
    Ok(conditions_hold(
        &F64Arith,
        &p,
        Some(&ray.t_min),
        &lo,
        &hi,
        Test::AllHit,
    ))
}

/// The division-free single-ray test in exact arithmetic: equal to [`crate::exact::slab_exact`]'s hit by
/// Theorem 1. Errors on an invalid ray or box.
pub fn ray_hits_exact(ray: &Ray, b: &Aabb) -> Result<bool, Error> {
    ray.validate()?;
    b.validate()?;
    let (lo, hi) = exact_box(b);
    let p = exact_bundle(&point_bundle(ray));
    Ok(conditions_hold(
        &ExactArith,
        &p,
        Some(&Ext::from_f64(ray.t_min)),
        &lo,
        &hi,
        Test::AllHit,
    ))
}

/// AllHit and AnyHit in f64 (the reference): `(all_hit, all_miss)`. Errors on an invalid bundle or box.
pub fn decide_ref(bundle: &Bundle, b: &Aabb) -> Result<(bool, bool), Error> {
    bundle.validate()?;
    b.validate()?;
    Ok(decide(&F64Arith, bundle, &same(world_box(b))))
}

/// AllHit and AnyHit in exact arithmetic: `(all_hit, all_miss)`, sound by Theorems 2a and 2b, and
/// `all_hit` exact for bundles with no straddling axis. Errors on an invalid bundle or box.
pub fn decide_exact(bundle: &Bundle, b: &Aabb) -> Result<(bool, bool), Error> {
    bundle.validate()?;
    b.validate()?;
    Ok(decide(
        &ExactArith,
        &exact_bundle(bundle),
        &same(exact_box(b)),
    ))
}

/// Exact AllHit: `true` means every ray of the bundle hits the box.
pub fn all_hit_exact(bundle: &Bundle, b: &Aabb) -> Result<bool, Error> {
    decide_exact(bundle, b).map(|d| d.0)
}

/// Exact AnyHit's verdict: `true` means every ray of the bundle misses the box.
pub fn all_miss_exact(bundle: &Bundle, b: &Aabb) -> Result<bool, Error> {
    decide_exact(bundle, b).map(|d| d.1)
}

/// Bundles shared by the unit tests of the bundle modules.
#[cfg(test)]
pub(crate) mod fixtures {
    use super::Bundle;
    use glam::DVec3;

    /// FIG. 7's case: a bundle above the unit box, aimed down (`-z`), whose directions straddle zero on
    /// x and y by `+-spread`; origins in `[0.4, 0.6]` on x and y (plus `x_offset` on x), z = 3, t_max 10.
    pub fn fig7_bundle(x_offset: f64, spread: f64) -> Bundle {
        Bundle::new(
            (
                DVec3::new(0.4 + x_offset, 0.4, 3.0),
                DVec3::new(0.6 + x_offset, 0.6, 3.0),
            ),
            (
                DVec3::new(-spread, -spread, -1.0),
                DVec3::new(spread, spread, -1.0),
            ),
            10.0,
            10.0,
        )
        .expect("a valid bundle")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::slab_exact;

    fn unit_box() -> Aabb {
        Aabb::new(DVec3::ZERO, DVec3::ONE).unwrap()
    }
    fn ray(o: [f64; 3], d: [f64; 3], t0: f64, t1: f64) -> Ray {
        Ray::new(o.into(), d.into(), t0, t1).unwrap()
    }

    #[test]
    fn single_ray_cases_match_the_slab_oracle() {
        let inf = f64::INFINITY;
        let cases = [
            // straight through, and pointing away
            ray([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], 0.0, inf),
            ray([-1.0, 0.5, 0.5], [-1.0, 0.0, 0.0], 0.0, inf),
            // t_max ending exactly on the entry face, and just before it
            ray([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], 0.0, 1.0),
            ray([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0], 0.0, 0.999),
            // exactly through the corner (1, 1, 1), and a hair beside it
            ray([2.0, 2.0, 2.0], [-1.0, -1.0, -1.0], 0.0, inf),
            ray([2.0, 2.0, 2.0 + 1e-15], [-1.0, -1.0, -1.0], 0.0, inf),
            // grazing an edge: x = 1, y = 0 line, moving in z
            ray([1.0, 0.0, -3.0], [0.0, 0.0, 1.0], 0.0, inf),
            ray([1.0, -0.0, -3.0], [0.0, -0.0, 1.0], 0.0, inf),
            // origin inside, any direction, zero range
            ray([0.5, 0.5, 0.5], [0.0, 0.0, 0.0], 0.0, 0.0),
            ray([0.5, 0.5, 0.5], [0.3, -0.7, 0.1], 0.0, 0.0),
            // zero component with the origin outside that slab
            ray([-1.0, 1.5, 0.5], [1.0, 0.0, 0.0], 0.0, inf),
            // negative and infinite t ranges
            ray([2.0, 0.5, 0.5], [1.0, 0.0, 0.0], f64::NEG_INFINITY, -1.0),
            ray([2.0, 0.5, 0.5], [1.0, 0.0, 0.0], f64::NEG_INFINITY, -1.5),
            ray([2.0, 0.5, 0.5], [1.0, 0.0, 0.0], -2.0, -1.0),
            ray([0.5, 2.0, 0.5], [0.0, 0.0, 0.0], f64::NEG_INFINITY, inf),
        ];
        for (n, r) in cases.iter().enumerate() {
            let truth = slab_exact(r, &unit_box()).hit;
            assert_eq!(
                ray_hits_exact(r, &unit_box()).unwrap(),
                truth,
                "case {n}: {r:?}"
            );
            assert_eq!(
                ray_hits_ref(r, &unit_box()).unwrap(),
                truth,
                "case {n}: {r:?}"
            );
        }
    }

    #[test]
    fn one_ray_bundle_gives_the_exact_answer_from_both_tests() {
        for (r, hit) in [
            (ray([2.0, 2.0, 2.0], [-1.0, -1.0, -1.0], 0.0, 1.0), true),
            (ray([2.0, 2.0, 2.0], [-1.0, -1.0, -1.0], 0.0, 0.5), false),
            (ray([2.0, 2.0, 2.0], [-1.0, -1.0, -0.3], 0.0, 9.0), false),
        ] {
            let b = Bundle::of_ray(&r).unwrap();
            assert_eq!(decide_exact(&b, &unit_box()).unwrap(), (hit, !hit), "{r:?}");
        }
    }

    #[test]
    fn straddling_bundle_is_decided_both_ways() {
        use super::fixtures::fig7_bundle;
        let b = fig7_bundle(0.0, 0.05);
        assert!(b.straddles());
        assert_eq!(decide_exact(&b, &unit_box()).unwrap(), (true, false));
        // Moved beside the box: every ray misses (the AnyHit half rule of a straddling axis).
        assert_eq!(
            decide_exact(&fig7_bundle(5.0, 0.05), &unit_box()).unwrap(),
            (false, true)
        );
        // Wide enough that some rays escape past a side: neither.
        assert_eq!(
            decide_exact(&fig7_bundle(0.0, 0.5), &unit_box()).unwrap(),
            (false, false)
        );
    }

    #[test]
    fn bundle_with_a_zero_direction_axis_needs_its_origins_in_that_slab() {
        let mk = |ylo: f64, yhi: f64| {
            Bundle::new(
                (DVec3::new(-2.0, ylo, 0.5), DVec3::new(-2.0, yhi, 0.5)),
                (DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0)),
                f64::INFINITY,
                f64::INFINITY,
            )
            .unwrap()
        };
        assert_eq!(
            decide_exact(&mk(0.0, 1.0), &unit_box()).unwrap(),
            (true, false)
        );
        assert_eq!(
            decide_exact(&mk(1.5, 2.0), &unit_box()).unwrap(),
            (false, true)
        );
        assert_eq!(
            decide_exact(&mk(0.5, 2.0), &unit_box()).unwrap(),
            (false, false)
        );
    }

    #[test]
    fn bad_inputs_are_named_errors() {
        let ok = Bundle::of_ray(&ray([0.0; 3], [1.0, 0.0, 0.0], 0.0, 1.0)).unwrap();
        let mut nan = ok;
        nan.o_hi[1] = f64::NAN;
        let e = decide_exact(&nan, &unit_box()).unwrap_err().to_string();
        assert!(e.contains("bundle origin max.y"), "{e}");
        let mut neg_t = ok;
        neg_t.t_lo = -1.0;
        assert!(neg_t.validate().is_err());
        let late = ray([0.0; 3], [1.0, 0.0, 0.0], 0.5, 1.0);
        let e = Bundle::of_ray(&late).unwrap_err().to_string();
        assert!(e.contains("t_min"), "{e}");
        assert!(Bundle::around(&[]).is_err());
        let bad_box = Aabb {
            min: DVec3::ZERO,
            max: DVec3::new(1.0, f64::INFINITY, 1.0),
        };
        assert!(ray_hits_exact(&ray([0.0; 3], [1.0; 3], 0.0, 1.0), &bad_box).is_err());
    }
}
