//! The fixed-point cull-plane datapath: plane storage format, plane fitting onto the grid, the ray's
//! direction interval, and the bit-accurate model of the tester (`rtl::plane::fix::PlaneFix` matches it bit
//! for bit).
//!
//! # Plane format
//! A stored plane is an integer normal `n` (`N`-bit signed components) and an integer offset `w` (`W`
//! bits, `W = G + N + 4`) in half grid units from the quantised box's centroid: the node's geometry
//! satisfies `n . (2 p - c2) <= w` with `p` in grid units and `c2 = lo + hi` (twice the centroid, an
//! integer, so the centroid costs no storage and no rounding). [`fit_plane`] quantises a world normal and
//! re-fits `w` over the geometry's vertices with outward rounding, so no vertex ever falls on the empty
//! side (planes are re-fitted after their normal is quantised). A zero normal is an
//! unused slot.
//!
//! # The ray's direction
//! The plane test needs `d`, not `1/d`: [`quantize_dir`] stores `d * 2^j` (the slab format's scaling,
//! [`crate::format::fixed::dir_scale_exp`], so t codes share one unit) with `FD` fraction bits as an interval
//! `[floor, ceil]`, `D = FD + 3` bits signed (the leading component's ceiling can reach `2^(FD+1)`).
//!
//! # The test (per plane, every value an exact integer)
//! ```text
//! S_lo   = sum_a n_a * (n_a >= 0 ? 2 o_lo - c2 : 2 o_hi - c2) - w     lower bound of 2 s0 in half grid units
//! den_lo = sum_a n_a * (n_a >= 0 ? d_lo : d_hi)                       bounds of n . d * 2^FD
//! den_hi = sum_a n_a * (n_a >= 0 ? d_hi : d_lo)
//! ```
//! A ray point at t code `t` is on the non-empty side iff `S + t den 2^(1-FD-FT) <= 0` for the true `S`,
//! `den`; over the intervals, only `S_lo` can matter (the side is `<= 0`), and the bound that holds for
//! every `den` in the interval is
//! - `den_lo > 0` (an exit plane): `t <= A / mag * 2^(FD+FT-1)` with `A = -S_lo` and `mag = A >= 0 ? den_lo
//!   : den_hi` (the smallest magnitude when `A` is non-negative, the largest otherwise);
//! - `den_hi < 0` (an entry plane): `t >= A / mag * 2^(FD+FT-1)` with `A = S_lo` and `mag = A >= 0 ? -den_lo
//!   : -den_hi`;
//! - `den_lo = den_hi = 0` (parallel): the node is culled when `S_lo > 0`;
//! - a `den` interval that holds zero and something else: the plane is skipped (no tightening — the set
//!   of t it allows is two rays, which a single interval cannot hold more tightly than everything).
//!
//! # How `t*` is formed: a directed reciprocal table ([`recip`])
//! `mag = m * 2^L` with `m` in `[1, 2)`; the `R` fraction bits of `m` below its leading one index a table of
//! `R + 2`-bit bounds of `1/m` with `F = R + 1` fraction bits, rounded down (`rl`) and up (`rh`) over the whole
//! bucket. A bound is `A * r * 2^(C - L)`, `C = FD + FT - R - 2`, taken with `rh` when that makes it larger
//! (exit, `A >= 0`; entry, `A < 0`) and `rl` otherwise, floored for an entry and ceiled for an exit, and
//! saturated like the slab's products (an entry into `[-inf, largest finite]`, an exit into `[smallest
//! finite, +inf]`). The result is a t code, so merging it with the slab's interval is a comparison. The
//! other option measured, cross-multiplied fractions ([`cull_fix_quotients`]), is exact but keeps the
//! interval as fractions; the figures that decided between them are in the README.
//!
//! Then `t_entry = max(slab entry, entry bounds)`, `t_exit = min(slab exit, exit bounds)`, and
//! `hit = slab hit && no parallel cull && t_entry <= t_exit`.

use crate::error::Error;
use crate::exact::{dyadic, Ext};
use crate::format::fixed::{
    ceil_pow2, dir_scale_exp, floor_pow2, FixBox, FixFormat, FixRay, GridMap,
};
use crate::geom::Ray;
use crate::plane::clip::ExactPlane;
use crate::slab::fix::SlabFixOut;
use glam::DVec3;
use num_bigint::BigInt;
use num_rational::BigRational;

const AXES: [&str; 3] = ["x", "y", "z"];

/// Widths of the fixed-point cull-plane datapath, on top of the slab format it extends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CullFixFormat {
    pub base: FixFormat,
    /// Normal component bits `N` (signed).
    pub n: u32,
    /// Direction fraction bits `FD`; the direction is `D = FD + 3` bits signed.
    pub fd: u32,
    /// Reciprocal table index bits `R` (`2^R` entries).
    pub r: u32,
}

impl CullFixFormat {
    /// Checks the widths: `2 <= N <= 12`, `1 <= FD <= 24`, `1 <= R <= 12`, and the products within 63 bits.
    pub fn new(base: FixFormat, n: u32, fd: u32, r: u32) -> Result<Self, Error> {
        let bad = |param, value: u32, why: &str| Error::BadFormat {
            param,
            value: value as i64,
            why: why.into(),
        };
        if !(2..=12).contains(&n) {
            return Err(bad("N (normal bits)", n, "must be in 2..=12"));
        }
        if !(1..=24).contains(&fd) {
            return Err(bad("FD (direction fraction bits)", fd, "must be in 1..=24"));
        }
        if !(1..=12).contains(&r) {
            return Err(bad("R (reciprocal table bits)", r, "must be in 1..=12"));
        }
        let f = CullFixFormat { base, n, fd, r };
        if f.s_bits() + f.r + 3 + f.c_shift().max(0) as u32 > 63 {
            return Err(bad(
                "FD (direction fraction bits)",
                fd,
                "the bound's product S * r * 2^C exceeds 63 bits",
            ));
        }
        Ok(f)
    }

    /// The default plane format over a slab format: `N = 8`, `FD = FI`, `R = 8`.
    pub fn over(base: FixFormat) -> Self {
        Self::try_over(base).expect("the presets fit")
    }

    /// [`Self::over`] for any slab format: an error when the default plane widths do not fit over it.
    pub fn try_over(base: FixFormat) -> Result<Self, Error> {
        Self::new(base, 8, base.fi.min(24), 8)
    }

    /// A plane format over `base` for a tester with no planes (`K = 0`), whose plane widths are never
    /// used: the default when it fits, else the narrowest one.
    pub fn slab_only(base: FixFormat) -> Result<Self, Error> {
        Self::try_over(base).or_else(|_| Self::new(base, 2, 1, 1))
    }

    /// Parses `b12` (the default over a preset) or `b12,N,FD,R`.
    pub fn parse(s: &str) -> Result<Self, Error> {
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        let base = FixFormat::parse(parts[0])?;
        match parts.len() {
            1 => Ok(Self::over(base)),
            4 => {
                let mut v = [0u32; 3];
                for (k, (p, name)) in parts[1..].iter().zip(["N", "FD", "R"]).enumerate() {
                    v[k] = p.parse().map_err(|_| {
                        Error::Io(format!("plane format `{s}`: {name} = `{p}` is not a number"))
                    })?;
                }
                Self::new(base, v[0], v[1], v[2])
            }
            _ => Err(Error::Io(format!(
                "plane format `{s}`: expected a slab preset (b8, b12, b16) optionally followed by ,N,FD,R"
            ))),
        }
    }

    /// Name for reports and Verilog modules, e.g. `g12_i16f11_t20f6_n8_fd11_r8`.
    pub fn name(&self) -> String {
        format!("{}_n{}_fd{}_r{}", self.base.name(), self.n, self.fd, self.r)
    }
    /// Offset bits `W = G + N + 4`: holds `n . (2p - c2)` for every `p` in the grid.
    pub fn w_bits(&self) -> u32 {
        self.base.g + self.n + 4
    }
    /// Bits of `S_lo` (signed).
    pub fn s_bits(&self) -> u32 {
        self.base.g + self.n + 5
    }
    /// Direction bits `D = FD + 3` (signed): the leading component's ceiling can reach `2^(FD+1)`.
    pub fn d_bits(&self) -> u32 {
        self.fd + 3
    }
    /// Bits of `den` (signed); a magnitude takes one bit less.
    pub fn den_bits(&self) -> u32 {
        self.n + self.fd + 4
    }
    /// The bound's scale exponent `C = FD + FT - R - 2` (before subtracting the leading-one position).
    pub fn c_shift(&self) -> i32 {
        self.fd as i32 + self.base.ft as i32 - self.r as i32 - 2
    }
    /// Largest normal component.
    pub fn n_max(&self) -> i64 {
        (1i64 << (self.n - 1)) - 1
    }
    /// Smallest and largest offset.
    pub fn w_range(&self) -> (i64, i64) {
        (
            -(1i64 << (self.w_bits() - 1)),
            (1i64 << (self.w_bits() - 1)) - 1,
        )
    }
    /// What a node stores: a box of six `G`-bit grid coordinates, per plane an `N`-bit normal
    /// component times three and a `W`-bit offset.
    pub fn layout(&self) -> crate::plane::clip::NodeLayout {
        crate::plane::clip::NodeLayout {
            box_bits: 6 * self.base.g,
            normal_bits: 3 * self.n,
            offset_bits: self.w_bits(),
        }
    }
}

/// The ray's scaled direction as an interval, `[floor, ceil](d * 2^(j + FD))` per axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FixDir {
    pub lo: [i64; 3],
    pub hi: [i64; 3],
}

/// A stored plane: integer normal and offset (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FixPlane {
    pub n: [i64; 3],
    pub w: i64,
}

/// Output of the fixed cull-plane tester: t codes as in [`crate::format::fixed`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct PlaneFixOut {
    pub hit: bool,
    pub t_entry: i64,
    pub t_exit: i64,
}

/// Quantises the direction of a ray (already validated by the slab quantiser) for the plane tester.
pub fn quantize_dir(cf: &CullFixFormat, ray: &Ray) -> Result<FixDir, Error> {
    ray.validate()?;
    let e = dir_scale_exp(ray.dir) + cf.fd as i32;
    let mut out = FixDir::default();
    for a in 0..3 {
        // |d * 2^j| < 2, so both are at most 2^(FD+1) in magnitude and fit D bits.
        out.lo[a] = floor_pow2(ray.dir[a], e).expect("scaled direction below 2");
        out.hi[a] = ceil_pow2(ray.dir[a], e).expect("scaled direction below 2");
    }
    Ok(out)
}

/// Fits a plane of world normal `normal` to the vertices of a node whose quantised box is `b`: the normal
/// is rounded to `N`-bit integers (largest component `2^(N-1) - 1`), and `w` is the smallest integer with
/// `n . (2p - c2) <= w` for every vertex, each vertex's coordinates bounded outward on the half grid.
/// An offset above the format's range makes the plane useless and returns the unused (zero) plane; one
/// below it is raised to the smallest offset (a looser, still valid plane).
///
/// Errors name the bad input: a non-finite or zero normal, no vertices, a vertex off the grid.
pub fn fit_plane(
    cf: &CullFixFormat,
    map: &GridMap,
    b: &FixBox,
    normal: DVec3,
    vertices: &[DVec3],
) -> Result<FixPlane, Error> {
    let nmax = normal.abs().max_element();
    if !normal.is_finite() || nmax == 0.0 {
        return Err(Error::bad_value(
            "plane normal",
            nmax,
            "a plane needs a finite, nonzero normal",
        ));
    }
    if vertices.is_empty() {
        return Err(Error::Io("plane fit: the node has no vertices".into()));
    }
    let scale = cf.n_max() as f64 / nmax;
    let n: [i64; 3] = std::array::from_fn(|a| (normal[a] * scale).round() as i64);
    let mut w = i64::MIN;
    for (vi, v) in vertices.iter().enumerate() {
        let mut s = 0i64;
        for a in 0..3 {
            let what = || format!("vertex {vi}.{}", AXES[a]);
            if !v[a].is_finite() {
                return Err(Error::bad_value(what(), v[a], "vertices must be finite"));
            }
            // 2 p_g = v * 2^(1-k) - 2 C, bounded outward.
            let up = n[a] > 0;
            let q = if up {
                ceil_pow2(v[a], 1 - map.k)
            } else {
                floor_pow2(v[a], 1 - map.k)
            };
            let two_p = match q {
                Some(q) => q - 2 * map.c[a],
                None => {
                    return Err(Error::DoesNotFit {
                        what: what(),
                        value: v[a],
                        why: "outside the grid".into(),
                    })
                }
            };
            if two_p < 2 * map.fmt.gmin() - 1 || two_p > 2 * map.fmt.gmax() + 1 {
                return Err(Error::DoesNotFit {
                    what: what(),
                    value: v[a],
                    why: format!("outside the {}-bit grid", map.fmt.g),
                });
            }
            s += n[a] * (two_p - (b.lo[a] + b.hi[a]));
        }
        w = w.max(s);
    }
    let (wmin, wmax) = cf.w_range();
    if w > wmax {
        return Ok(FixPlane::default());
    }
    Ok(FixPlane { n, w: w.max(wmin) })
}

impl FixPlane {
    /// The stored plane as an exact world half-space: `n . (2 p_g - c2) <= w` with `2 p_g = p 2^(1-k) - 2C`.
    pub fn to_exact(&self, map: &GridMap, b: &FixBox) -> ExactPlane {
        let mut h = BigRational::from_integer(BigInt::from(self.w));
        for a in 0..3 {
            h += BigRational::from_integer(BigInt::from(
                self.n[a] * (2 * map.c[a] + b.lo[a] + b.hi[a]),
            ));
        }
        ExactPlane {
            n: std::array::from_fn(|a| dyadic(self.n[a], 1 - map.k)),
            h,
        }
    }
}

/// The directed reciprocal table of `R` index bits: `(rl[i], rh[i])` bound `2^(R+1) / m` for every `m` in
/// `[1 + i/2^R, 1 + (i+1)/2^R)`, rounded down and up.
pub fn recip_entry(r: u32, i: u64) -> (u64, u64) {
    let num = 1u64 << (2 * r + 1);
    let base = 1u64 << r;
    (num / (base + i + 1), num.div_ceil(base + i))
}

/// The reciprocal bound of a magnitude `mag`: `(r, L)` with `mag = m 2^L`, `m` in `[1, 2)`, and `r` the
/// table's upper (`upper = true`) or lower bound of `2^(R+1) / m`.
pub fn recip(r: u32, mag: u64, upper: bool) -> (u64, u32) {
    let (l, idx) = lead_and_index(r, mag);
    let (lo, hi) = recip_entry(r, idx);
    (if upper { hi } else { lo }, l)
}

/// `(L, index)` of a magnitude: its leading-one position and the `r` bits below the leading one. A zero
/// magnitude (only from inputs no quantisation produces) reads entry 0 with `L = 0`, as the RTL.
#[inline]
pub fn lead_and_index(r: u32, mag: u64) -> (u32, u64) {
    let l = 63u32.saturating_sub(mag.leading_zeros());
    let mask = (1u64 << r) - 1;
    let idx = if l >= r {
        (mag >> (l - r)) & mask
    } else {
        (mag << (r - l)) & mask
    };
    (l, idx)
}

/// What one plane does to the interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlaneEffect {
    /// No tightening (unused slot, or a `den` interval holding zero).
    None,
    /// The entry is at least this t code.
    Entry(i64),
    /// The exit is at most this t code.
    Exit(i64),
    /// Parallel and on the empty side: the node is culled.
    Cull,
}

/// `S_lo`, `den_lo`, `den_hi` of one plane (module doc), as the RTL's first stages compute them.
#[inline(always)]
pub fn plane_sums(r: &FixRay, d: &FixDir, b: &FixBox, p: &FixPlane) -> (i64, i64, i64) {
    let (mut s, mut dl, mut dh) = (-p.w, 0i64, 0i64);
    for a in 0..3 {
        let c2 = b.lo[a] + b.hi[a];
        let n = p.n[a];
        if n >= 0 {
            s += n * (2 * r.o_lo[a] - c2);
            dl += n * d.lo[a];
            dh += n * d.hi[a];
        } else {
            s += n * (2 * r.o_hi[a] - c2);
            dl += n * d.hi[a];
            dh += n * d.lo[a];
        }
    }
    (s, dl, dh)
}

/// The scaled, rounded, saturated bound `A * r * 2^(c_shift - L)` in `t_bits`-bit t codes: floor for an
/// entry, ceil for an exit (the slab's saturation: an entry into `[-inf, largest finite]`, an exit into
/// `[smallest finite, +inf]`).
#[inline(always)]
pub fn scale_bound(c_shift: i32, t_bits: u32, a: i64, r: u64, l: u32, exit: bool) -> i64 {
    scale_product(c_shift, t_bits, a as i128 * r as i128, l, exit)
}

/// The last step of [`scale_bound`], on the product `q = A * r` (the RTL's `BoundScale`, after the
/// product's cut point).
#[inline(always)]
pub fn scale_product(c_shift: i32, t_bits: u32, q: i128, l: u32, exit: bool) -> i64 {
    let sh = c_shift - l as i32;
    let v = if sh >= 0 {
        q << sh
    } else if exit {
        -((-q) >> (-sh))
    } else {
        q >> (-sh)
    };
    let ninf = -(1i128 << (t_bits - 1));
    let pinf = (1i128 << (t_bits - 1)) - 1;
    (if exit {
        v.clamp(ninf + 1, pinf)
    } else {
        v.clamp(ninf, pinf - 1)
    }) as i64
}

/// The first step of a plane's bound from its sums (the RTL's `BoundPick`): the plane's class, the
/// signed numerator `A`, the table half and the reciprocal's operands `L` and index. Every field is
/// defined for every input, as the hardware computes it: for a plane that is neither an entry nor an
/// exit plane `a`, `upper`, `lead` and `idx` are what the datapath carries (and the bound ignores).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BoundPick {
    /// `den_lo > 0`: the plane bounds the exit.
    pub exit: bool,
    /// Not an exit plane and `den_hi < 0`: the plane bounds the entry.
    pub entry: bool,
    /// Parallel (`den_lo = den_hi = 0`) with the origin box on the empty side (`S_lo > 0`): cull.
    pub cull: bool,
    /// `A`: `-S_lo` for an exit plane, else `S_lo`.
    pub a: i64,
    /// The upper half of the reciprocal table (the larger bound: exit with `A >= 0`, entry with `A < 0`).
    pub upper: bool,
    /// `L`: the magnitude's leading-one position (0 for a zero magnitude).
    pub lead: u32,
    /// The table index: the `R` magnitude bits below the leading one.
    pub idx: u64,
}

/// [`BoundPick`] of sums `(s, dl, dh)` for `r_bits` table bits and `den_bits`-bit `den` values. The
/// magnitude is `den_bits` bits unsigned: only an inverted `den` interval (which quantisation never
/// produces) can make the chosen one negative, and the RTL wraps it the same way.
#[inline]
pub fn bound_pick(r_bits: u32, den_bits: u32, s: i64, dl: i64, dh: i64) -> BoundPick {
    let exit = dl > 0;
    let entry = !exit && dh < 0;
    let cull = !exit && !entry && dl == 0 && dh == 0 && s > 0;
    let a = if exit { -s } else { s };
    let mag = if exit {
        if s > 0 {
            dh
        } else {
            dl
        }
    } else if s < 0 {
        -dh
    } else {
        -dl
    };
    let (lead, idx) = lead_and_index(r_bits, mag as u64 & ((1u64 << den_bits) - 1));
    BoundPick {
        exit,
        entry,
        cull,
        a,
        upper: (a >= 0) == exit,
        lead,
        idx,
    }
}

/// What a plane with sums `(S_lo, den_lo, den_hi)` does (module doc), for table bits `r_bits`, scale
/// exponent `c_shift`, `t_bits`-bit t codes and `den_bits`-bit `den` values: [`bound_pick`], the table
/// read ([`recip_entry`]), the product `A r` and [`scale_product`], the steps of the RTL's `PlaneBound`.
#[inline]
pub fn bound_from_sums(
    r_bits: u32,
    c_shift: i32,
    t_bits: u32,
    den_bits: u32,
    s: i64,
    dl: i64,
    dh: i64,
) -> PlaneEffect {
    let p = bound_pick(r_bits, den_bits, s, dl, dh);
    if p.cull {
        return PlaneEffect::Cull;
    }
    if !p.exit && !p.entry {
        return PlaneEffect::None;
    }
    let (lo, hi) = recip_entry(r_bits, p.idx);
    let rv = if p.upper { hi } else { lo };
    let t = scale_bound(c_shift, t_bits, p.a, rv, p.lead, p.exit);
    if p.exit {
        PlaneEffect::Exit(t)
    } else {
        PlaneEffect::Entry(t)
    }
}

/// What one plane does, bit for bit as the RTL computes it.
#[inline]
pub fn plane_effect(
    cf: &CullFixFormat,
    r: &FixRay,
    d: &FixDir,
    b: &FixBox,
    p: &FixPlane,
) -> PlaneEffect {
    let (s, dl, dh) = plane_sums(r, d, b, p);
    bound_from_sums(cf.r, cf.c_shift(), cf.base.t, cf.den_bits(), s, dl, dh)
}

/// The fixed-point cull-plane test, chained after the slab test's result `slab` on the same ray and box.
pub fn cull_fix(
    cf: &CullFixFormat,
    r: &FixRay,
    d: &FixDir,
    b: &FixBox,
    planes: &[FixPlane],
    slab: &SlabFixOut,
) -> PlaneFixOut {
    let (mut entry, mut exit, mut cull) = (slab.t_entry, slab.t_exit, !slab.hit);
    for p in planes {
        match plane_effect(cf, r, d, b, p) {
            PlaneEffect::None => {}
            PlaneEffect::Entry(t) => entry = entry.max(t),
            PlaneEffect::Exit(t) => exit = exit.min(t),
            PlaneEffect::Cull => cull = true,
        }
    }
    PlaneFixOut {
        hit: !cull && entry <= exit,
        t_entry: entry,
        t_exit: exit,
    }
}

/// The other option for forming `t*`: the same bounds as exact fractions `A 2^(FD+FT-1) / mag` (what a
/// division-free datapath carrying the interval as numerator/denominator pairs, compared by cross
/// multiplication, computes), merged with the slab interval exactly. Returns `(hit, entry, exit)` in t code
/// units. Used to measure what the reciprocal table's rounding costs.
pub fn cull_fix_quotients(
    cf: &CullFixFormat,
    r: &FixRay,
    d: &FixDir,
    b: &FixBox,
    planes: &[FixPlane],
    slab: &SlabFixOut,
) -> (bool, Ext, Ext) {
    let fmt = &cf.base;
    let code = |c: i64| {
        if c == fmt.t_neg_inf() {
            Ext::NegInf
        } else if c == fmt.t_pos_inf() {
            Ext::PosInf
        } else {
            Ext::Fin(BigRational::from_integer(c.into()))
        }
    };
    let (mut entry, mut exit, mut cull) = (code(slab.t_entry), code(slab.t_exit), !slab.hit);
    let scale = dyadic(1, fmt.ft as i32 + cf.fd as i32 - 1);
    for p in planes {
        let (s, dl, dh) = plane_sums(r, d, b, p);
        if dl > 0 {
            let mag = if s <= 0 { dl } else { dh };
            exit = exit.min(Ext::Fin(BigRational::new((-s).into(), mag.into()) * &scale));
        } else if dh < 0 {
            let mag = if s >= 0 { -dl } else { -dh };
            entry = entry.max(Ext::Fin(BigRational::new(s.into(), mag.into()) * &scale));
        } else if dl == 0 && dh == 0 && s > 0 {
            cull = true;
        }
    }
    (!cull && entry <= exit, entry, exit)
}

/// The most planes a node carries in the testbenches' vector types (the RTL takes `K <= MAX_PLANES`).
pub const MAX_PLANES: usize = 8;

/// A ray as the chained slab + cull-plane tester takes it: the slab ray and the direction interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct NodeFixRay {
    pub ray: FixRay,
    pub dir: FixDir,
}

/// A node as the chained tester takes it: the box and up to [`MAX_PLANES`] planes (unused ones zero; a
/// tester with `K` planes reads the first `K`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct FixNode {
    pub b: FixBox,
    pub planes: [FixPlane; MAX_PLANES],
}

/// Slab test then `k` planes, bit for bit as the chained RTL computes it.
pub fn node_fix(cf: &CullFixFormat, k: usize, r: &NodeFixRay, n: &FixNode) -> PlaneFixOut {
    let slab = crate::slab::fix::slab_fix(&cf.base, &r.ray, &n.b);
    cull_fix(cf, &r.ray, &r.dir, &n.b, &n.planes[..k], &slab)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::{rat, Ext};
    use crate::geom::Aabb;
    use crate::plane::clip::clip_exact;
    use crate::slab::fix::slab_fix;

    #[test]
    fn reciprocal_table_brackets_every_significand_of_its_bucket() {
        for r in [1, 3, 8] {
            for idx in 0..(1u64 << r) {
                let (lo, hi) = recip_entry(r, idx);
                let f = (1u64 << (r + 1)) as f64;
                let m_lo = 1.0 + idx as f64 / (1u64 << r) as f64;
                let m_hi = 1.0 + (idx + 1) as f64 / (1u64 << r) as f64;
                assert!(hi as f64 >= f / m_lo && (lo as f64) < f / m_hi * (1.0 + 1e-12));
                assert!(hi < 1 << (r + 2));
            }
        }
        // A power of two is exact in the upper table: 2^(R+1) / 1.
        assert_eq!(recip(8, 1 << 20, true), (512, 20));
    }

    fn setup() -> (CullFixFormat, GridMap) {
        let cf = CullFixFormat::over(FixFormat::b12());
        let map = GridMap::for_bounds(cf.base, DVec3::splat(-8.0), DVec3::splat(8.0)).unwrap();
        (cf, map)
    }

    #[test]
    fn fitted_plane_keeps_every_vertex_on_the_non_empty_side() {
        let (cf, map) = setup();
        let verts = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.9, 0.05, 0.7),
            DVec3::new(0.3, 1.7, 1.99),
        ];
        let b = map
            .quantize_box(&Aabb::new(DVec3::ZERO, DVec3::splat(2.0)).unwrap())
            .unwrap();
        for n in [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(-0.3, 0.7, 0.1),
            DVec3::Z,
        ] {
            let p = fit_plane(&cf, &map, &b, n, &verts).unwrap();
            let e = p.to_exact(&map, &b);
            let sides: Vec<_> = verts.iter().map(|v| e.side(*v)).collect();
            assert!(sides
                .iter()
                .all(|s| *s <= BigRational::from_integer(0.into())));
            // Tight within one half-grid unit of |n|_1.
            assert!(
                sides.iter().any(|s| *s > rat(-(3 * 128) as f64)),
                "{sides:?}"
            );
        }
        assert!(fit_plane(&cf, &map, &b, DVec3::ZERO, &verts).is_err());
        assert!(fit_plane(&cf, &map, &b, DVec3::X, &[]).is_err());
        let off = fit_plane(&cf, &map, &b, DVec3::X, &[DVec3::new(50.0, 0.0, 0.0)]);
        assert!(off.unwrap_err().to_string().contains("vertex 0.x"));
    }

    #[test]
    fn diagonal_plane_culls_the_empty_corner_and_bounds_enclose_the_exact_clip() {
        let (cf, map) = setup();
        let wb = Aabb::new(DVec3::ZERO, DVec3::splat(2.0)).unwrap();
        let b = map.quantize_box(&wb).unwrap();
        // Geometry in the lower-left half: x + y <= 2.
        let verts = [
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 2.0),
            DVec3::new(0.0, 2.0, 1.0),
        ];
        let p = fit_plane(&cf, &map, &b, DVec3::new(1.0, 1.0, 0.0), &verts).unwrap();
        let exact = [p.to_exact(&map, &b)];
        for (y, t_max, culled) in [(1.75, 10.0, false), (1.75, 2.5, true), (1.9, 2.85, true)] {
            let ray = Ray::new(DVec3::new(3.0, y, 1.0), DVec3::NEG_X, 0.0, t_max).unwrap();
            let fr = map.quantize_ray(&ray).unwrap();
            let fd = quantize_dir(&cf, &ray).unwrap();
            let out = cull_fix(&cf, &fr, &fd, &b, &[p], &slab_fix(&cf.base, &fr, &b));
            let ex = clip_exact(&ray, &wb, &exact);
            assert_eq!(out.hit, !culled, "y {y} t_max {t_max} {out:?} {p:?} {ex:?}");
            assert_eq!(ex.hit, !culled);
            if out.hit {
                assert!(fr.t_world(&cf.base, out.t_entry) <= ex.entry);
                assert!(fr.t_world(&cf.base, out.t_exit) >= ex.exit);
                // The entry is pulled in from the box face (t = 1) to near the plane (t = 2.75).
                assert!(fr.t_world(&cf.base, out.t_entry) > Ext::Fin(rat(2.7)));
            }
        }
    }

    #[test]
    fn parallel_ray_on_the_empty_side_is_culled() {
        let (cf, map) = setup();
        let wb = Aabb::new(DVec3::ZERO, DVec3::splat(2.0)).unwrap();
        let b = map.quantize_box(&wb).unwrap();
        let verts = [DVec3::ZERO, DVec3::new(2.0, 1.0, 2.0)];
        let p = fit_plane(&cf, &map, &b, DVec3::Y, &verts).unwrap();
        let run = |y: f64| {
            let ray = Ray::new(DVec3::new(-1.0, y, 1.0), DVec3::X, 0.0, 10.0).unwrap();
            let fr = map.quantize_ray(&ray).unwrap();
            let fd = quantize_dir(&cf, &ray).unwrap();
            plane_effect(&cf, &fr, &fd, &b, &p)
        };
        assert_eq!(run(1.5), PlaneEffect::Cull);
        assert_eq!(run(1.0), PlaneEffect::None);
    }

    #[test]
    fn bad_plane_formats_are_errors() {
        assert!(CullFixFormat::new(FixFormat::b12(), 1, 11, 8).is_err());
        assert!(CullFixFormat::new(FixFormat::b12(), 8, 0, 8).is_err());
        assert!(CullFixFormat::new(FixFormat::b12(), 8, 11, 13).is_err());
        assert!(CullFixFormat::parse("b12,8,11").is_err());
        assert_eq!(
            CullFixFormat::parse("b16,6,10,5").unwrap(),
            CullFixFormat::new(FixFormat::b16(), 6, 10, 5).unwrap()
        );
    }
}
