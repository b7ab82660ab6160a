//! Datasheet text of the chained cull-plane testers (`plane_fix_*`, `plane_fix_frac_*`, `plane_float_*`),
//! the AllHit / AnyHit bundle pairs (`bundle_fix_*`, `bundle_float_*`) and the bundle results processor
//! (`bundle_split_*`), as data that [`super::datasheet::render`] turns into Markdown.
//!
//! Every width and code in the text is computed from the format, and every rule is the one the
//! quantisers and models apply: the grid map and ray quantisation of `golden::format::fixed`, the plane
//! format, fitting and bound of `golden::plane::fix` / `golden::plane::float` (the fraction option's
//! output packing of `rtl::plane::quot`), the float rounding of `golden::slab::float`, the bundle
//! quantisers and conditions of `golden::bundle::{fix, float, edge}`, the two-ray mode of
//! `rtl::bundle::pair_fix`, and the job protocol of `rtl::bundle::split`.

use crate::ip::datasheet::FamilyDoc;
use golden::bundle::fix::BundleFixFormat;
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use golden::plane::fix::CullFixFormat;
use golden::plane::float::CullFloatFormat;

const AXIS: &str = "axis: 0 = x, 1 = y, 2 = z";

fn param(name: &str, value: impl ToString, meaning: impl Into<String>) -> (String, String, String) {
    (name.into(), value.to_string(), meaning.into())
}

fn port(base: &str, meaning: impl Into<String>) -> (String, String) {
    (base.into(), meaning.into())
}

/// Index text of array ports over x, y, z: the first names the axes, the rest say "axis" (rendered as
/// `(axis: 1)` after the meaning).
fn axis_index(bases: &[&str]) -> Vec<(String, String)> {
    bases
        .iter()
        .enumerate()
        .map(|(n, b)| {
            (
                b.to_string(),
                if n == 0 { AXIS.into() } else { "axis".into() },
            )
        })
        .collect()
}

/// Index text of the per-plane ports of a `k`-plane tester.
fn plane_index(k: usize) -> Vec<(String, String)> {
    ["plane_nx", "plane_ny", "plane_nz", "plane_w"]
        .iter()
        .enumerate()
        .map(|(n, b)| {
            let what = if n == 0 {
                format!("plane, 0 .. {}", k - 1)
            } else {
                "plane".into()
            };
            (b.to_string(), what)
        })
        .collect()
}

/// `v` as a `bits`-bit two's complement word, in hex.
fn hex(v: i64, bits: u32) -> String {
    format!("0x{:x}", (v as u64) & ((1u64 << bits) - 1))
}

/// The slab format's parameters.
fn fix_params(fmt: &FixFormat) -> Vec<(String, String, String)> {
    vec![
        param("G", fmt.g, "grid bits: signed coordinates"),
        param("I", fmt.i, "inverse-direction bits (unsigned magnitude)"),
        param("FI", fmt.fi, "fraction bits of the inverse direction"),
        param("T", fmt.t, "t code bits (signed)"),
        param("FT", fmt.ft, "fraction bits of a t code"),
    ]
}

/// The grid map, direction scale and t code unit shared by the fixed slab, cull-plane and bundle
/// formats (`golden::format::fixed`).
fn fix_grid_text(fmt: &FixFormat) -> String {
    let (t, ft) = (fmt.t, fmt.ft);
    format!(
        "All words are two's complement where signed. `<name>_a` is axis `a` of an array port (0 = x, \
1 = y, 2 = z).

**Grid map** (one per scene, shared by every ray, box and plane of the scene, and the same map as the \
`slab_fix` tester of this format): a world coordinate `x` on axis `a` is the grid value \
`x_g = x / 2^k - c_a`, with an integer cell exponent `k` and integer centres `c_a` chosen so that the \
scene fits in `[{gmin}, {gmax}]` (`rtu encode` picks the finest `k` that holds the scene bounds and \
writes `k` and `c` in its files). Every conversion is an exact scaling by a power of two, so each \
`floor`/`ceil` below is of an exact value. A coordinate whose floor or ceiling falls outside \
`[{gmin}, {gmax}]` does not fit: the encoder refuses it.

**Direction scale**: per ray (per bundle), `j` is the integer with `2^j * max_a |d_a|` in `[1, 2)` \
(`j = 0` for a zero direction). `d_s = d * 2^j` is exact; it leaves the ray's points alone and sets its \
t unit.

**t codes** (signed {t}-bit, {ft} fraction bits, in the ray's own unit): \
`t_world = code * 2^(k + j - {ft})`. The most negative code `-2^{t1}` (`{tneg}`) means `-inf`, the most \
positive `2^{t1} - 1` (`{tpos}`) means `+inf`.",
        gmin = fmt.gmin(),
        gmax = fmt.gmax(),
        t1 = t - 1,
        tneg = hex(fmt.t_neg_inf(), t),
        tpos = hex(fmt.t_pos_inf(), t),
    )
}

/// The encoding of the fixed slab tester's inputs (`golden::format::fixed::GridMap::quantize_ray`,
/// `quantize_box`), as a Markdown list.
fn fix_slab_inputs_text(fmt: &FixFormat) -> String {
    let (i, fi, t, ft) = (fmt.i, fmt.fi, fmt.t, fmt.ft);
    let inf = fmt.inv_inf();
    format!(
        "- origin: `ray_o_lo_a = floor(o_a / 2^k) - c_a`, `ray_o_hi_a = ceil(o_a / 2^k) - c_a` (equal for \
an origin on the grid).
- inverse direction, with `v = 2^{fi} / |d_s,a|` (exact): `d_a = 0` (either sign) gives \
`ray_m_lo_a = ray_m_hi_a = 0x{inf:x}` (all ones: unbounded). Otherwise `ray_m_lo_a = min(floor(v), 2^{i} \
- 2)` and `ray_m_hi_a = ceil(v)`, or all ones when `ceil(v) >= 2^{i} - 1`; unsigned, {fi} fraction bits. \
A tiny non-zero component therefore gives `ray_m_lo_a = 0x{lo:x}`, `ray_m_hi_a = 0x{inf:x}`. Never set \
both to all ones for a non-zero component: that means exactly parallel, and the tester then misses the \
axis's slab unless the origin interval touches it.
- `ray_neg_a = 1` when `d_a` is negative or `-0`, else 0.
- t range: `ray_t_min = floor(t_min * 2^({ft} - k - j))`, the `-inf` code for `t_min = -inf` or a code \
at or below `-2^{t1}`, and `2^{t1} - 2` for a code at or above `2^{t1} - 1`. \
`ray_t_max = ceil(t_max * 2^({ft} - k - j))`, the `+inf` code for `t_max = +inf` or a code at or above \
`2^{t1} - 1`, and `-2^{t1} + 1` for a code at or below `-2^{t1}`.
- box: `box_lo_a = floor(min_a / 2^k) - c_a`, `box_hi_a = ceil(max_a / 2^k) - c_a`. An empty world box \
(`min_a > max_a` on some axis) is the canonical empty box `box_lo_a = {gmax}` (`{gmaxh}`), \
`box_hi_a = {gmin}` (`{gminh}`) on every axis, which never hits.",
        lo = inf - 1,
        t1 = t - 1,
        gmin = fmt.gmin(),
        gmax = fmt.gmax(),
        gmaxh = hex(fmt.gmax(), fmt.g),
        gminh = hex(fmt.gmin(), fmt.g),
    )
}

/// What the datasheet says of the fixed chained slab + cull-plane tester over `cf` with `k` planes:
/// the reciprocal-table option (`PlaneFix`, module `plane_fix_*`) when `frac` is false, the exact
/// fraction option (`PlaneQuot`, module `plane_fix_frac_*`) when it is true.
pub fn plane_fix_doc(cf: &CullFixFormat, k: usize, frac: bool) -> FamilyDoc {
    let fmt = &cf.base;
    let (g, t, ft) = (fmt.g, fmt.t, fmt.ft);
    let (n, fd, r) = (cf.n, cf.fd, cf.r);
    let (db, wb, sb, eb) = (cf.d_bits(), cf.w_bits(), cf.s_bits(), cf.den_bits());
    let mb = eb - 1;
    let fb = sb + mb;
    let e = fd + ft - 1;
    let (wmin, wmax) = cf.w_range();

    let how = if frac {
        "Each plane's bound is kept as an exact fraction and ordered against the others and the slab's \
         t codes by cross-multiplication (no division, no table, no rounding after quantisation), and \
         `t_entry` / `t_exit` leave as packed fractions."
    } else {
        "Each plane's bound is formed with a directed reciprocal table and rounded outward to a t code, \
         so `t_entry` / `t_exit` are t codes like the slab tester's."
    };
    let what = format!(
        "Tests a ray against a BVH node — an axis-aligned box plus K = {k} cull planes that bound the \
         node's empty space (Arm US 2025/0259373) — on a {g}-bit integer grid. The fixed slab tester's \
         interval is clipped by every plane: a plane the ray moves toward (into its empty side) lowers \
         the exit, one it moves away from raises the entry, one parallel to the ray with the origin on \
         its empty side culls the node; the node is culled when the clipped interval is empty. {how} \
         Every input is an outward bound of the world value and every step rounds outward, so the \
         result is conservative: whenever some point of the exact ray within `[t_min, t_max]` lies in \
         the box and on the non-empty side of every stored plane, `hit` is 1 and the reported interval \
         encloses the exact clipped one. A false hit is allowed; a false miss (a culled node that the \
         ray meets) is not."
    );

    let mut params = fix_params(fmt);
    params.extend([
        param("N", n, "bits of a plane normal component (signed)"),
        param("FD", fd, "fraction bits of the scaled direction interval"),
        param(
            "D",
            db,
            "bits of a direction code `ray_d_*` (signed), `FD + 3`",
        ),
        param(
            "W",
            wb,
            "bits of a plane offset `plane_w` (signed), `G + N + 4`",
        ),
        param("SB", sb, "bits of a plane's `S_lo` (signed), `G + N + 5`"),
        param(
            "K",
            k,
            "planes per node (ports `plane_*_0` .. `plane_*_{K-1}`)",
        ),
    ]);
    if frac {
        params.extend([
            param(
                "MB",
                mb,
                "bits of a bound's denominator (unsigned), `N + FD + 3`",
            ),
            param(
                "FB",
                fb,
                "bits of `t_entry` / `t_exit`: a packed fraction, `SB + MB`",
            ),
            param("E", e, "scale of a bound fraction, `FD + FT - 1`"),
        ]);
    } else {
        params.extend([
            param("R", r, "reciprocal table index bits (2^R entries)"),
            param("C", cf.c_shift(), "bound scale exponent `FD + FT - R - 2`"),
        ]);
    }

    // The slab ports mean what they mean in the slab tester of the same base format.
    let mut ports: Vec<(String, String)> = crate::ip::datasheet::slab_fix_doc(&cf.base)
        .ports
        .into_iter()
        .filter(|(b, _)| !matches!(b.as_str(), "hit" | "t_entry" | "t_exit"))
        .collect();
    ports.extend([
        port("ray_d_lo", format!("scaled direction, lower bound `floor(d_a * 2^(j + {fd}))`, signed {db} bits, {fd} fraction bits")),
        port("ray_d_hi", format!("scaled direction, upper bound `ceil(d_a * 2^(j + {fd}))`, signed {db} bits, {fd} fraction bits")),
        port("plane_nx", format!("plane normal, x component, signed {n}-bit integer (points at the empty side; 0 0 0 with `plane_w = 0` = unused slot)")),
        port("plane_ny", format!("plane normal, y component, signed {n}-bit integer")),
        port("plane_nz", format!("plane normal, z component, signed {n}-bit integer")),
        port("plane_w", format!("plane offset in half grid units from the box centre, signed {wb} bits: the node's geometry satisfies `n . (2 p_g - box_lo - box_hi) <= plane_w`")),
        port("hit", "1 when the node is not culled: the ray may meet the box on the non-empty side of every plane within its range (never 0 when it does)"),
    ]);
    if frac {
        ports.extend([
            port("t_entry", format!("entry, a lower bound of the exact clipped entry, as a packed fraction `{{den, num}}` ({mb} + {sb} bits, see Outputs)")),
            port("t_exit", format!("exit, an upper bound of the exact clipped exit, as a packed fraction `{{den, num}}` ({mb} + {sb} bits, see Outputs)")),
        ]);
    } else {
        ports.extend([
            port("t_entry", format!("entry, a lower bound of the exact clipped entry, signed {t}-bit t code (unit of `ray_t_min`)")),
            port("t_exit", format!("exit, an upper bound of the exact clipped exit, signed {t}-bit t code")),
        ]);
    }
    let mut idx = axis_index(&[
        "ray_o_lo", "ray_o_hi", "ray_m_lo", "ray_m_hi", "ray_neg", "ray_d_lo", "ray_d_hi",
        "box_lo", "box_hi",
    ]);
    idx.extend(plane_index(k));

    let bound_text = if frac {
        format!(
            "Each bound is kept exactly as the fraction `num * 2^{e} / den` t code units \
(`E = FD + FT - 1 = {e}`): an exit plane has `num = -S_lo`, `den = mag`, an entry plane `num = S_lo`, \
`den = mag`. The largest entry fraction and the smallest exit fraction are found by cross-multiplied \
comparisons and merged with the slab's t codes exactly."
        )
    } else {
        let c = cf.c_shift();
        format!(
            "The bound is formed with a directed reciprocal table of 2^{r} entries: `mag = m * 2^L` with \
`L` the position of its leading one and `idx` the {r} bits below it; the table holds \
`rl[idx] = floor(2^{r2} / (2^{r} + idx + 1))` and `rh[idx] = ceil(2^{r2} / (2^{r} + idx))`, bounds of \
`2^{r1} / m` over the whole bucket. With `A = -S_lo` (exit) or `A = S_lo` (entry), `rr = rh` for an exit \
with `A >= 0` or an entry with `A < 0`, `rr = rl` otherwise (each choice moves the bound outward), the \
bound is `A * rr * 2^(C - L)` with `C = FD + FT - R - 2 = {c}`, floored for an entry and ceiled for an \
exit, then saturated: an entry into `[-2^{t1}, 2^{t1} - 2]`, an exit into `[-2^{t1} + 1, 2^{t1} - 1]` \
(an entry never becomes `+inf`, an exit never `-inf`).",
            r1 = r + 1,
            r2 = 2 * r + 1,
            t1 = t - 1,
        )
    };
    let out_text = if frac {
        format!(
            "**Outputs**: `t_entry` and `t_exit` are {fb}-bit words `{{den, num}}`: bits [{fbh}:{sb}] \
`den` ({mb} bits, unsigned), bits [{sbh}:0] `num` ({sb} bits). `den != 0`: the value is the plane bound \
`num * 2^{e} / den` t code units (`num` two's complement), i.e. `t_world = num * 2^(k + j + {e2}) / den`; \
round it down (entry) or up (exit) to get a t code. `den = 0`: the value is the slab tester's t code, in \
bits [{th}:0] as a {t}-bit two's complement word (bits [{sbh}:{t}] are 0), the `-inf` / `+inf` codes \
included. The entry is the plane fraction only when it is strictly greater than the slab's entry, the \
exit only when strictly less than the slab's exit. `hit = slab hit and no parallel cull and \
t_entry <= t_exit`, compared exactly.",
            fbh = fb - 1,
            sbh = sb - 1,
            th = t - 1,
            e2 = fd - 1,
        )
    } else {
        "**Outputs**: `t_entry = max(slab entry, every entry bound)`, `t_exit = min(slab exit, every exit \
bound)`, both t codes; `hit = slab hit and no parallel cull and t_entry <= t_exit` (the slab hit is: box \
not empty, the slab interval non-empty, its entry not the +inf code and its exit not the -inf code)."
            .to_string()
    };
    let rules = format!(
        "{grid}

**Slab inputs** (as the `slab_fix` datasheet of format `{base}`):
{slab}

**Direction interval** (the plane test needs `d`, not `1/d`): with the same `j` as above, \
`ray_d_lo_a = floor(d_a * 2^(j + {fd}))`, `ray_d_hi_a = ceil(d_a * 2^(j + {fd}))`, signed {db}-bit \
(`|code| <= 2^{fd1}`); equal when `d_a * 2^(j + {fd})` is an integer. The t codes of the slab and the \
planes share one unit only when `ray_m`, `ray_d` and the t range use the same `j`.

**Planes** (plane `p` = ports `plane_nx_p`, `plane_ny_p`, `plane_nz_p`, `plane_w_p`): an integer normal \
`n` pointing at the node's empty side and an integer offset `w` in half grid units from the quantised \
box's centre. A stored plane is valid for a node when every point `p` of the node's geometry satisfies \
`n . (2 p_g - c2) <= w`, with `p_g` its exact grid coordinates and `c2_a = box_lo_a + box_hi_a` (the \
box ports of the same test, so the centre costs no storage and no rounding). The tester removes only \
what lies on the other side. Encoding a world plane of normal `m` over the node's vertices `v`:
- `n_a = round(m_a * {nmax} / max_b |m_b|)` (`2^{n1} - 1 = {nmax}`, round half away from zero). Any \
  {n}-bit normal is accepted; `w` must be fitted to the normal actually stored.
- `w = max over v of sum_a n_a * (q_a - 2 c_a - c2_a)`, where `q_a = ceil(v_a * 2^(1 - k))` when \
  `n_a > 0` and `floor(v_a * 2^(1 - k))` otherwise (each vertex bounded outward on the half grid). Any \
  larger `w` is also valid, only looser. `w > {wmax}` makes the plane useless: store the unused slot; \
  `w < {wmin}` is stored as `{wmin}`. A plane given as a half-space without geometry is fitted to the \
  part of the box on its non-empty side (the box corners there and the points where it crosses the box \
  edges), which is what `rtu encode` does.
- Unused slot: `n = 0 0 0`, `w = 0`. A zero normal with `w < 0` culls every ray (see `S_lo` below).

**Per plane** (exact integers, {sb}-bit `S_lo`, {eb}-bit `den`):
```text
S_lo   = sum_a n_a * (n_a >= 0 ? 2 ray_o_lo_a - c2_a : 2 ray_o_hi_a - c2_a) - w
den_lo = sum_a n_a * (n_a >= 0 ? ray_d_lo_a : ray_d_hi_a)
den_hi = sum_a n_a * (n_a >= 0 ? ray_d_hi_a : ray_d_lo_a)
```
A point at t code `t` is on the non-empty side when `S + t * den * 2^(1 - {fd} - {ft}) <= 0` for \
the exact `S` and `den` of the ray (`S_lo` is a lower bound of `S`, `den` lies in `[den_lo, den_hi]`); the \
bound that holds for every value of the intervals is:
- `den_lo > 0` (exit plane): `t <= -S_lo * 2^{e} / mag`, `mag = S_lo <= 0 ? den_lo : den_hi`;
- else `den_hi < 0` (entry plane): `t >= S_lo * 2^{e} / mag`, `mag = S_lo >= 0 ? -den_lo : -den_hi`;
- else `den_lo = den_hi = 0` and `S_lo > 0`: parallel on the empty side, the node is culled;
- else no effect (a `den` interval holding zero and something else).

{bound}

{out} On a culled node the t outputs carry no promise.",
        grid = fix_grid_text(fmt),
        base = fmt.name(),
        slab = fix_slab_inputs_text(fmt),
        fd1 = fd + 1,
        n1 = n - 1,
        nmax = cf.n_max(),
        bound = bound_text,
        out = out_text,
    );
    FamilyDoc {
        what,
        params,
        ports,
        index: idx,
        rules,
    }
}

/// The float format's parameters.
fn float_params(f: &FloatFormat) -> Vec<(String, String, String)> {
    vec![
        param("E", f.e, format!("exponent bits (bias {})", f.bias())),
        param("M", f.m, "fraction bits"),
        param("W", f.width(), "word width `1 + E + M`"),
    ]
}

/// The word layout of a float format.
fn float_layout_text(f: &FloatFormat) -> String {
    let w = f.width();
    format!(
        "Every value port is a {w}-bit word of {name}: bit {s} the sign, bits [{eh}:{m}] the biased \
exponent (bias {bias}), bits [{ml}:0] the fraction (IEEE 754 layout: exponent all ones with a zero \
fraction is infinity, `+inf` = `0x{inf:x}`, `-inf` = `0x{ninf:x}`; subnormals are values, not flushed; \
`-0` and `+0` compare equal). `RD` rounds the exact real value once toward -inf, `RU` toward +inf, `RN` \
to nearest even. NaN inputs are not allowed.",
        name = f.name(),
        s = w - 1,
        eh = w - 2,
        m = f.m,
        ml = f.m - 1,
        bias = f.bias(),
        inf = f.inf(false),
        ninf = f.inf(true),
    )
}

/// What the datasheet says of the float chained slab + cull-plane tester over `cf` with `k` planes.
pub fn plane_float_doc(cf: &CullFloatFormat, k: usize) -> FamilyDoc {
    let f = &cf.f;
    let r = cf.r;
    let what = format!(
        "Tests a ray against a BVH node — an axis-aligned box plus K = {k} cull planes that bound the \
         node's empty space (Arm US 2025/0259373) — in the floating-point format {name}, with t in world \
         units. The float slab tester's interval is clipped by every plane: a plane the ray moves toward \
         (into its empty side) lowers the exit, one it moves away from raises the entry, one parallel to \
         the ray with the origin on its empty side culls the node; the node is culled when the clipped \
         interval is empty. Inputs are rounded outward and every operation rounds in the direction \
         that widens the interval (a directed reciprocal table replaces the division), so the result is \
         conservative: whenever some point of the exact ray within `[t_min, t_max]` lies in the box and \
         on the non-empty side of every stored plane, `hit` is 1 and `[t_entry, t_exit]` encloses the \
         exact clipped interval. A false hit is allowed; a false miss is not.",
        name = f.name()
    );
    let mut params = float_params(f);
    params.extend([
        param("R", r, "reciprocal table index bits (2^R entries)"),
        param(
            "K",
            k,
            "planes per node (ports `plane_*_0` .. `plane_*_{K-1}`)",
        ),
    ]);
    let ports = vec![
        port("ray_o_lo", "origin rounded toward -inf: `RD(o_a)`"),
        port("ray_o_hi", "origin rounded toward +inf: `RU(o_a)`"),
        port("ray_m_lo", "inverse direction magnitude rounded toward -inf: `RD(1 / |d_a|)`; +inf for a zero component"),
        port("ray_m_hi", "inverse direction magnitude rounded toward +inf: `RU(1 / |d_a|)`; +inf for a zero or tiny component"),
        port("ray_neg", "direction sign: 1 when the component is negative (including -0)"),
        port("ray_t_min", "start of the ray's range, `RD(t_min)`; -inf allowed"),
        port("ray_t_max", "end of the ray's range, `RU(t_max)`; +inf allowed"),
        port("ray_d_lo", "direction rounded toward -inf: `RD(d_a)` (world direction, not scaled)"),
        port("ray_d_hi", "direction rounded toward +inf: `RU(d_a)`"),
        port("box_lo", "box minimum, `RD(min_a)`"),
        port("box_hi", "box maximum, `RU(max_a)`"),
        port("plane_nx", "plane normal, x component (points at the empty side; all four words 0 = unused slot)"),
        port("plane_ny", "plane normal, y component"),
        port("plane_nz", "plane normal, z component"),
        port("plane_w", "plane offset from the box centre `c`: the node's geometry satisfies `n . (p - c) <= plane_w`"),
        port("hit", "1 when the node is not culled: the ray may meet the box on the non-empty side of every plane within its range (never 0 when it does)"),
        port("t_entry", "entry in world units, a lower bound of the exact clipped entry"),
        port("t_exit", "exit in world units, an upper bound of the exact clipped exit"),
    ];
    let mut idx = axis_index(&[
        "ray_o_lo", "ray_o_hi", "ray_m_lo", "ray_m_hi", "ray_neg", "ray_d_lo", "ray_d_hi",
        "box_lo", "box_hi",
    ]);
    idx.extend(plane_index(k));
    let rules = format!(
        "{layout} t is in world units: no grid and no scaling. `<name>_a` is axis `a` (0 = x, 1 = y, \
2 = z), `plane_*_p` plane `p`.

**Slab inputs** (as the `slab_float` datasheet of {name}): `ray_o_lo_a = RD(o_a)`, `ray_o_hi_a = \
RU(o_a)`. `d_a = 0` (either sign) gives `ray_m_lo_a = ray_m_hi_a = +inf`; otherwise `ray_m_lo_a = \
RD(1 / |d_a|)`, `ray_m_hi_a = RU(1 / |d_a|)` of the exact quotient (a tiny component gives the largest \
finite value and `+inf`: never both `+inf` for a non-zero component). `ray_neg_a = 1` when `d_a` is \
negative or `-0`. `ray_t_min = RD(t_min)`, `ray_t_max = RU(t_max)` (infinities allowed). \
`box_lo_a = RD(min_a)`, `box_hi_a = RU(max_a)`; an empty world box (`min_a > max_a` on some axis) is \
`box_lo_a = +inf`, `box_hi_a = -inf` on every axis. An origin or box coordinate beyond the largest \
finite value does not fit: the encoder refuses it.

**Direction interval**: `ray_d_lo_a = RD(d_a)`, `ray_d_hi_a = RU(d_a)`, the same (unscaled) direction \
whose inverse is on `ray_m`.

**Planes**: a normal `n` (`plane_nx/ny/nz`) pointing at the node's empty side and an offset `w` \
(`plane_w`) from the centre `c_a = RN(RN(box_lo_a + box_hi_a) * 0.5)`, computed from the box ports of \
the same test exactly as the hardware does. A stored plane is valid for a node when every point `p` of \
its geometry satisfies `n . (p - c) <= w` in exact arithmetic on the stored values. Encoding a world \
plane of normal `m` over the node's vertices `v`:
- `n_a = RN(m_a / max_b |m_b|)` (the largest component becomes +-1; any normal is accepted, `w` must be \
  fitted to the stored one);
- `w` = the smallest value of the format with `w >= max over v of n . (v - c)`, computed exactly; any \
  larger `w` is valid, only looser. When that maximum is beyond the largest finite value, store the \
  unused slot;
- unused slot: all four words `+0` (`0x0`). A zero normal with a negative `w` culls every ray.

**Per plane** (every operation of the format, `n_a >= 0` counting either zero):
```text
ol_a   = RD(ray_o_lo_a - c_a)            oh_a = RU(ray_o_hi_a - c_a)
S_lo   = RD(RD(RD(u_0 + u_1) + u_2) - w)    u_a = RD(n_a * (n_a >= 0 ? ol_a : oh_a))
den_lo = RD(RD(l_0 + l_1) + l_2)            l_a = RD(n_a * (n_a >= 0 ? ray_d_lo_a : ray_d_hi_a))
den_hi = RU(RU(h_0 + h_1) + h_2)            h_a = RU(n_a * (n_a >= 0 ? ray_d_hi_a : ray_d_lo_a))
```
- `den_lo > 0` (exit plane): exit bound `RU(-S_lo * rr)`, `rr` an upper bound of `1 / den_lo` when \
  `S_lo <= 0`, a lower bound of `1 / den_hi` otherwise;
- else `den_hi < 0` (entry plane): entry bound `RD(S_lo * rr)`, `rr` a lower bound of `1 / |den_lo|` \
  when `S_lo >= 0`, an upper bound of `1 / |den_hi|` otherwise;
- else `den_lo = den_hi = 0` and `S_lo > 0`: parallel on the empty side, the node is culled;
- else (a `den` interval holding zero, a NaN) no effect. A NaN bound (`0 x inf`) is no bound.

The directed reciprocal of a normal `mag = 1.f * 2^e`: the top {r} bits of `f` index a table holding \
the format's values `RD(2^{r} / (2^{r} + idx + 1))` and `RU(2^{r} / (2^{r} + idx))`, and `rr` is the \
entry times `2^-e` by exponent arithmetic (a lower bound that underflows is `+0`, an upper bound that \
underflows the smallest normal; a lower bound that overflows is the largest finite value, an upper bound \
`+inf`). A zero or subnormal `mag` gives `[2^{b1}, +inf]`, `mag = +inf` gives `+0`.

**Outputs**: `t_entry = max(slab entry, every entry bound)`, `t_exit = min(slab exit, every exit \
bound)`, world units; `hit = slab hit and no parallel cull and t_entry <= t_exit`. On a culled node the \
t outputs carry no promise.",
        layout = float_layout_text(f),
        name = f.name(),
        b1 = f.bias() - 1,
    );
    FamilyDoc {
        what,
        params,
        ports,
        index: idx,
        rules,
    }
}

/// The bundle pair's data ports and their meanings, for either datapath: `o` the origin meaning,
/// `d` the direction, `t` the t range, `bx` a box corner.
struct PairText {
    o_lo: String,
    o_hi: String,
    d_lo: String,
    d_hi: String,
    t_lo: String,
    t_hi: String,
    r_t: String,
    in_lo: String,
    in_hi: String,
    out_lo: String,
    out_hi: String,
}

fn pair_ports(p: &PairText) -> Vec<(String, String)> {
    vec![
        port("o_lo", format!("bundle origin box, lower corner: {} (ray A in two-ray mode)", p.o_lo)),
        port("o_hi", format!("bundle origin box, upper corner: {}", p.o_hi)),
        port("d_lo", format!("bundle direction box, lower corner: {}", p.d_lo)),
        port("d_hi", format!("bundle direction box, upper corner: {}", p.d_hi)),
        port("t_lo", format!("smallest `t_max` of the bundle's rays: {} (AllHit; unused in two-ray mode)", p.t_lo)),
        port("t_hi", format!("largest `t_max` of the bundle's rays: {} (AnyHit; ray A's in two-ray mode)", p.t_hi)),
        port("two_rays", "0: one bundle, judged by both testers; 1: two single rays, A on the bundle ports and B on the `r_*` ports"),
        port("r_o_lo", "ray B's origin, lower bound, encoded as `o_lo` (two-ray mode only)"),
        port("r_o_hi", "ray B's origin, upper bound, encoded as `o_hi` (two-ray mode only)"),
        port("r_d_lo", "ray B's direction, lower bound, encoded as `d_lo` with ray B's own `j` (two-ray mode only)"),
        port("r_d_hi", "ray B's direction, upper bound, encoded as `d_hi` with ray B's own `j` (two-ray mode only)"),
        port("r_t", format!("ray B's `t_max`: {} (two-ray mode only)", p.r_t)),
        port("in_lo", format!("inner box (AllHit, bundle mode only), lower corner: {}", p.in_lo)),
        port("in_hi", format!("inner box (AllHit, bundle mode only), upper corner: {}", p.in_hi)),
        port("out_lo", format!("outer box (AnyHit; both testers in two-ray mode), lower corner: {}", p.out_lo)),
        port("out_hi", format!("outer box (AnyHit; both testers in two-ray mode), upper corner: {}", p.out_hi)),
        port("all_hit", "bundle mode: 1 = every ray of the bundle hits the box within `[0, t_max]`; two-ray mode: 1 = ray A may hit (0 = ray A surely misses)"),
        port("all_miss", "bundle mode: 1 = every ray of the bundle misses the box; two-ray mode: 1 = ray B surely misses"),
    ]
}

fn pair_index() -> Vec<(String, String)> {
    axis_index(&[
        "o_lo", "o_hi", "d_lo", "d_hi", "r_o_lo", "r_o_hi", "r_d_lo", "r_d_hi", "in_lo", "in_hi",
        "out_lo", "out_hi",
    ])
}

/// What a bundle is, what the two answers mean, and the two modes (both datapaths).
const BUNDLE_TEXT: &str = "**Bundle** (world): an origin box `[o_min, o_max]`, a direction box \
`[d_min, d_max]` and a range `[t_lo, t_hi]` of `t_max`, `0 <= t_lo <= t_hi` (`t_hi` may be `+inf`). It \
stands for every ray `o + t d`, `t in [0, t_max]`, with `o`, `d`, `t_max` in those boxes — not only the \
rays it was built from. Rays start at their origin: there is no `t_min` port (a ray with `t_min != 0` \
cannot be a bundle ray). A single ray is the bundle whose boxes are points.

**Modes**:
- `two_rays = 0` (bundle mode): AllHit judges the bundle on the inner box (`in_*`) with `t_lo`, AnyHit on \
  the outer box (`out_*`) with `t_hi`. `all_hit = 1`: every ray of the bundle hits the box; \
  `all_miss = 1`: every ray misses; both 0: undecided (test its rays). Both 1 only for inconsistent \
  inputs (an inner box not inside the outer one). The `r_*` ports are ignored.
- `two_rays = 1` (two single rays): ray A on `o_*`, `d_*`, `t_hi`; ray B on `r_o_*`, `r_d_*`, `r_t`; both \
  against the outer box (`in_*` and `t_lo` are ignored). Each ray, quantised as the bundle of that one ray \
  (a tiny bundle unless it is on the grid / exact in the format), gets AnyHit's bounds: `all_hit = 1` \
  means ray A *may hit* (0: ray A surely misses), `all_miss = 1` means ray B surely misses. Neither answer \
  is ever wrong for a ray that hits. (AllHit's bounds on a tiny bundle could call a hitting ray a miss, so \
  neither tester uses them in this mode.)";

/// The conditions both bundle datapaths evaluate (`golden::bundle::edge::conditions_hold`), with the
/// difference, product and distance rules given by the caller.
fn bundle_conditions_text(sub: &str, products: &str, dist: &str) -> String {
    format!(
        "**What is computed** (the division-free edge test of US 11,308,683, `golden/src/bundle/edge.rs`). \
Per axis, with the box `[lo, hi]` of the test and the origin ends `(o_e, o_x) = (o_lo, o_hi)` for \
AllHit, `(o_hi, o_lo)` for AnyHit: positive fold `e+ = lo - o_e`, `x+ = hi - o_x`; negative fold \
`e- = o_x - hi`, `x- = o_e - lo`. {sub} By the sign class of `[d_lo, d_hi]`:

| class | `e`, `x` | `[u_lo, u_hi]` |
|---|---|---|
| `d_lo >= 0` | `e+`, `x+` | `[d_lo, d_hi]` |
| `d_hi <= 0` (and `d_lo < 0`) | `e-`, `x-` | `[-d_hi, -d_lo]` |
| straddling, AllHit | `max(e+, e-)`, `min(x+, x-)` | `[0, max(-d_lo, d_hi)]` |
| straddling, AnyHit, `x+ < 0` | `e-`, `x-` | `[0, -d_lo]` |
| straddling, AnyHit, else `x- < 0` | `e+`, `x+` | `[0, d_hi]` |
| straddling, AnyHit, otherwise | `min(e+, e-)`, `max(x+, x-)` | `[0, max(-d_lo, d_hi)]` |

The test passes when all of these hold: `lo_a <= hi_a` (box not empty, 3), `x_a >= 0` (the far plane is \
ahead, 3), the distance check `e_a <= t * u_a` (3) and the silhouette edges `e_a * u_b <= x_b * u_a` \
for `a != b` (6). AllHit bounds every left side from above and every right side from below; AnyHit the \
reverse. {products} {dist} `all_hit` = AllHit passes; `all_miss` = AnyHit fails.",
    )
}

/// What the datasheet says of the fixed-point AllHit / AnyHit bundle pair of `bf`.
pub fn bundle_fix_doc(bf: &BundleFixFormat) -> FamilyDoc {
    let fmt = &bf.base;
    let (g, t, ft, fd) = (fmt.g, fmt.t, fmt.ft, bf.fd);
    let db = bf.dir_bits();
    let what = format!(
        "The pair of bundle testers of US 11,308,683 on a {g}-bit integer grid, one test per clock: \
         either one ray bundle (an origin box, a direction box and a range of `t_max`, standing for every \
         ray in them), judged by AllHit (\"every ray surely hits\") and AnyHit (\"every ray surely \
         misses\"), or two single rays, each answered \"may hit\" or \"surely misses\". The test is the \
         division-free edge form of the slab test, with the bounds of each product chosen by signs; \
         after the outward quantisation every product is exact at full width, so no answer is ever \
         wrong: `all_hit` is never 1 when some ray of the bundle misses, `all_miss` never 1 when some \
         ray hits, and a ray that hits is never reported missed. Both answers 0 means undecided. The \
         pair returns no t interval."
    );
    let mut params = vec![
        param("G", g, "grid bits: signed coordinates"),
        param("T", t, "t code bits (signed)"),
        param("FT", ft, "fraction bits of a t code"),
        param("FD", fd, "fraction bits of a scaled direction code"),
        param("D", db, "bits of a direction code (signed), `FD + 3`"),
        param(
            "I",
            fmt.i,
            "inverse-direction bits of the shared slab format (not used by this block)",
        ),
        param(
            "FI",
            fmt.fi,
            "inverse fraction bits of the shared slab format (not used by this block)",
        ),
    ];
    params.extend([
        param(
            "edge product",
            bf.edge_product_bits(),
            "bits of an edge product `(G + 1) x D`, exact",
        ),
        param(
            "distance product",
            bf.dist_product_bits(),
            "bits of a distance product `T x D`, exact",
        ),
    ]);
    let pt = PairText {
        o_lo: format!("`floor(o_min_g)`, signed {g}-bit grid coordinate"),
        o_hi: format!("`ceil(o_max_g)`, signed {g}-bit grid coordinate"),
        d_lo: format!("`floor(d_min * 2^(j + {fd}))`, signed {db} bits"),
        d_hi: format!("`ceil(d_max * 2^(j + {fd}))`, signed {db} bits"),
        t_lo: format!("`floor` in t codes, signed {t} bits"),
        t_hi: format!("`ceil` in t codes, signed {t} bits; the most positive code is +inf"),
        r_t: format!("`ceil` in ray B's t codes, signed {t} bits"),
        in_lo: format!("`ceil(min_g)` (rounded inward), signed {g} bits"),
        in_hi: format!("`floor(max_g)` (rounded inward), signed {g} bits"),
        out_lo: format!("`floor(min_g)` (rounded outward), signed {g} bits"),
        out_hi: format!("`ceil(max_g)` (rounded outward), signed {g} bits"),
    };
    let pinf = fmt.t_pos_inf();
    let rules = format!(
        "{grid}

{bundle}

**Encoding** (`golden::bundle::fix::quantize_bundle`, `quantize_box_pair`):
- origin box: `o_lo_a = floor(o_min_a / 2^k) - c_a`, `o_hi_a = ceil(o_max_a / 2^k) - c_a`.
- direction box: `j` from the largest magnitude of the whole box, `2^j * max_a max(|d_min_a|, \
|d_max_a|)` in `[1, 2)`; `d_lo_a = floor(d_min_a * 2^(j + {fd}))`, `d_hi_a = ceil(d_max_a * 2^(j + {fd}))`, \
signed {db}-bit, magnitudes at most `2^{fd1}`.
- `t_max` range, in t codes of this `j` (`2^({ft} - k - j)` codes per world unit): \
`t_lo = floor(t_lo_w * 2^({ft} - k - j))`, `2^{t1} - 2` (`{pfin}`, the largest finite code) when that is \
at or above `2^{t1} - 1`, and the `+inf` code `{pinfh}` only for `t_lo_w = +inf`. \
`t_hi = ceil(t_hi_w * 2^({ft} - k - j))`, the `+inf` code `{pinfh}` when `t_hi_w = +inf` or the code is \
at or above `2^{t1} - 1`. Both are `>= 0` (a negative code is never produced; the most negative one would \
mean `-inf`).
- box: inner `in_lo_a = ceil(min_a / 2^k) - c_a`, `in_hi_a = floor(max_a / 2^k) - c_a` (inward: \
`in_lo > in_hi` when the box is thinner than a cell, and AllHit then fails, as it must); outer \
`out_lo_a = floor(min_a / 2^k) - c_a`, `out_hi_a = ceil(max_a / 2^k) - c_a`. A box on the grid (a stored \
node box) has `in = out`. An empty world box is `lo_a = {gmax}`, `hi_a = {gmin}` on every axis, in both.
- two-ray mode: each ray (`t_min = 0`) is the bundle of that one ray, quantised as above with its own \
`j`: origin floored and ceiled, direction code floored and ceiled, and its `t_max` ceiled into `t_hi` \
(ray A) or `r_t` (ray B). A ray whose origin and scaled direction are on the grid is a point, and the \
answer is then the exact single-ray test.

{cond}",
        grid = fix_grid_text(fmt),
        bundle = BUNDLE_TEXT,
        fd1 = fd + 1,
        t1 = t - 1,
        pfin = hex(pinf - 1, t),
        pinfh = hex(pinf, t),
        gmax = fmt.gmax(),
        gmin = fmt.gmin(),
        cond = bundle_conditions_text(
            &format!("Differences are exact ({} bits).", g + 1),
            "The bound of `v * u` over `u in [u_lo, u_hi]` takes `u_hi` for an upper bound of a `v >= 0` \
and `u_lo` for `v < 0`, the reverse for a lower bound (so AllHit's edge check is \
`e_a * (e_a >= 0 ? u_hi_b : u_lo_b) <= x_b * (x_b >= 0 ? u_lo_a : u_hi_a)`); products are exact.",
            &format!(
                "The distance check is `e_a * 2^({fd} + {ft}) <= t * u`, with `t = t_lo`, `u = u_lo` \
for AllHit and `t = t_hi`, `u = u_hi` for AnyHit; `t * 0 = 0` for every `t`, and the `+inf` code \
times `u > 0` is `+inf`."
            ),
        ),
    );
    FamilyDoc {
        what,
        params,
        ports: pair_ports(&pt),
        index: pair_index(),
        rules,
    }
}

/// What the datasheet says of the float AllHit / AnyHit bundle pair of format `f`.
pub fn bundle_float_doc(f: &FloatFormat) -> FamilyDoc {
    let what = format!(
        "The pair of bundle testers of US 11,308,683 in the floating-point format {name}, one test per \
         clock: either one ray bundle (an origin box, a direction box and a range of `t_max`, standing \
         for every ray in them), judged by AllHit (\"every ray surely hits\") and AnyHit (\"every ray \
         surely misses\"), or two single rays, each answered \"may hit\" or \"surely misses\". The test \
         is the division-free edge form of the slab test; every difference and product is rounded in \
         the direction its check needs, so no answer is ever wrong: `all_hit` is never 1 when some ray \
         of the bundle misses, `all_miss` never 1 when some ray hits, and a ray that hits is never \
         reported missed. Both answers 0 means undecided. The pair returns no t interval.",
        name = f.name()
    );
    let pt = PairText {
        o_lo: "`RD(o_min_a)`".into(),
        o_hi: "`RU(o_max_a)`".into(),
        d_lo: "`RD(d_min_a * 2^j)` (scaled direction)".into(),
        d_hi: "`RU(d_max_a * 2^j)` (scaled direction)".into(),
        t_lo: "`RD(t_lo * 2^-j)` (scaled t)".into(),
        t_hi: "`RU(t_hi * 2^-j)` (scaled t); +inf allowed".into(),
        r_t: "`RU(t_max * 2^-j)` with ray B's own `j`".into(),
        in_lo: "`RU(min_a)` (rounded inward)".into(),
        in_hi: "`RD(max_a)` (rounded inward)".into(),
        out_lo: "`RD(min_a)` (rounded outward)".into(),
        out_hi: "`RU(max_a)` (rounded outward)".into(),
    };
    let rules = format!(
        "{layout} `<name>_a` is axis `a` (0 = x, 1 = y, 2 = z).

{bundle}

**Direction scale**: per bundle (per ray in two-ray mode), `j` is the integer with \
`2^j * max_a max(|d_min_a|, |d_max_a|)` in `[1, 2)` (`j = 0` for a zero direction box). Directions enter \
scaled by `2^j` and t values by `2^-j` (so a narrow format neither overflows nor flushes a direction); \
the scaling is exact in real arithmetic and rounded once. **t is therefore not in world units**: \
`t_world = t_port * 2^j`.

**Encoding** (`golden::bundle::float::quantize_bundle`, `quantize_box_pair`):
- origin box: `o_lo_a = RD(o_min_a)`, `o_hi_a = RU(o_max_a)`; a coordinate beyond the largest finite \
value does not fit: the encoder refuses it.
- direction box: `d_lo_a = RD(d_min_a * 2^j)`, `d_hi_a = RU(d_max_a * 2^j)`.
- `t_max` range: `t_lo = RD(t_lo_w * 2^-j)`, `t_hi = RU(t_hi_w * 2^-j)` (`+inf` stays `+inf`; a finite \
value beyond the format gives the largest finite value for `RD`, `+inf` for `RU`).
- box: inner `in_lo_a = RU(min_a)`, `in_hi_a = RD(max_a)`; outer `out_lo_a = RD(min_a)`, \
`out_hi_a = RU(max_a)`; a box exact in the format has `in = out`. An empty world box is `lo_a = +inf`, \
`hi_a = -inf` on every axis, in both.
- two-ray mode: each ray (`t_min = 0`) is the bundle of that one ray, with its own `j`: \
`[RD, RU](o_a)`, `[RD, RU](d_a * 2^j)`, and `RU(t_max * 2^-j)` into `t_hi` (ray A) or `r_t` (ray B).

{cond}",
        layout = float_layout_text(f),
        bundle = BUNDLE_TEXT,
        cond = bundle_conditions_text(
            "AllHit takes `e = RU(..)`, `x = RD(..)`; AnyHit `e = RD(..)`, `x = RU(..)` (negating a \
direction bound is exact).",
            "An upper bound of `v * u` over `u in [u_lo, u_hi]` is `RU(v * (v >= 0 ? u_hi : u_lo))`, a \
lower bound `RD(v * (v >= 0 ? u_lo : u_hi))`; an indeterminate `0 x inf` is `+inf` in an upper bound \
and `-inf` in a lower one.",
            "The distance check is `e_a <= RD(t_lo * u_lo)` for AllHit and `e_a <= RU(t_hi * u_hi)` for \
AnyHit, the product 0 when `u` is zero (either sign), even for `t = +inf`.",
        ),
    );
    FamilyDoc {
        what,
        params: float_params(f),
        ports: pair_ports(&pt),
        index: pair_index(),
        rules,
    }
}

/// The stored-ray ports of a results processor over `bf`.
fn store_ports(bf: &BundleFixFormat) -> Vec<(String, String)> {
    let (g, t, fd, db) = (bf.base.g, bf.base.t, bf.fd, bf.dir_bits());
    vec![
        port("ray_o_lo", format!("stored ray's origin, `floor(o_g)`, signed {g} bits")),
        port("ray_o_hi", format!("stored ray's origin, `ceil(o_g)`, signed {g} bits")),
        port("ray_d_lo", format!("stored ray's direction, `floor(d * 2^(j + {fd}))` with the ray's own `j`, signed {db} bits")),
        port("ray_d_hi", format!("stored ray's direction, `ceil(d * 2^(j + {fd}))`, signed {db} bits")),
        port("ray_t", format!("stored ray's `t_max`, `ceil` in the ray's t codes, signed {t} bits; the most positive code is +inf")),
    ]
}

/// The job's bundle and box ports of a results processor over `bf`.
fn job_ports(bf: &BundleFixFormat) -> Vec<(String, String)> {
    let (g, t, fd, db) = (bf.base.g, bf.base.t, bf.fd, bf.dir_bits());
    vec![
        port("o_lo", format!("job bundle's origin box, lower corner `floor(o_min_g)`, signed {g} bits")),
        port("o_hi", format!("job bundle's origin box, upper corner `ceil(o_max_g)`, signed {g} bits")),
        port("d_lo", format!("job bundle's direction box, lower corner `floor(d_min * 2^(j + {fd}))`, signed {db} bits")),
        port("d_hi", format!("job bundle's direction box, upper corner `ceil(d_max * 2^(j + {fd}))`, signed {db} bits")),
        port("t_lo", format!("job bundle's smallest `t_max`, `floor` in t codes, signed {t} bits")),
        port("t_hi", format!("job bundle's largest `t_max`, `ceil` in t codes, signed {t} bits; most positive code = +inf")),
        port("in_lo", format!("node box, inner (AllHit) lower corner `ceil(min_g)`, signed {g} bits")),
        port("in_hi", format!("node box, inner (AllHit) upper corner `floor(max_g)`, signed {g} bits")),
        port("out_lo", format!("node box, outer (AnyHit and the rays) lower corner `floor(min_g)`, signed {g} bits")),
        port("out_hi", format!("node box, outer (AnyHit and the rays) upper corner `ceil(max_g)`, signed {g} bits")),
    ]
}

/// How the job's bundle and boxes and the stored rays of a results processor over `bf` are encoded
/// (the same for the one-job and the streaming processor).
fn job_encoding(bf: &BundleFixFormat, stores_t_lo: bool) -> String {
    let fmt = &bf.base;
    format!(
        "**Encoding**: the job's bundle and box are encoded exactly as for the pair `bundle_fix_{name}` (its \
datasheet has the conditions): origin box `o_lo_a = floor(o_min_a / 2^k) - c_a`, \
`o_hi_a = ceil(o_max_a / 2^k) - c_a`; `j` from the largest magnitude of the direction box, \
`2^j * max_a max(|d_min_a|, |d_max_a|)` in `[1, 2)`, `d_lo_a = floor(d_min_a * 2^(j + {fd}))`, \
`d_hi_a = ceil(d_max_a * 2^(j + {fd}))`; `t_lo = floor(t_lo_w * 2^({ft} - k - j))` (at most \
`2^{t1} - 2` unless `t_lo_w = +inf`), `t_hi = ceil(t_hi_w * 2^({ft} - k - j))` (`2^{t1} - 1` = +inf when \
`t_hi_w = +inf` or the code reaches it); inner box `in_lo_a = ceil(min_a / 2^k) - c_a`, \
`in_hi_a = floor(max_a / 2^k) - c_a`, outer box `out_lo_a = floor(min_a / 2^k) - c_a`, \
`out_hi_a = ceil(max_a / 2^k) - c_a` (equal for a box on the grid; an empty world box is \
`lo_a = {gmax}`, `hi_a = {gmin}` in both). Each stored ray (`t_min = 0`) is the bundle of that one ray, \
with its own `j`: `ray_o_lo/hi` floored and ceiled, `ray_d_lo/hi = floor/ceil(d_a * 2^(j + {fd}))`, \
`ray_t = ceil(t_max * 2^({ft} - k - j))` (saturating to the +inf code); {t_lo} The rays of a job need \
not be the bundle's own rays, but only then does the report describe them.\n\n",
        t_lo = if stores_t_lo {
            format!(
                "for re-bounding, its floored `t_max` and its `j` are stored too: \
                 `ray_t_lo = floor(t_max * 2^({ft} - k - j))` (the largest finite code when a finite \
                 `t_max` reaches +inf, the +inf code for `t_max = +inf`), `ray_j = j` ({jb}-bit two's \
                 complement, `j = -floor(log2 max_a |d_a|)`, so a ray's largest direction component \
                 must lie in `[2^-{jmax}, 2^{jmin})`).",
                ft = fmt.ft,
                jb = rtl::bundle::rebound::J_BITS,
                jmax = (1 << (rtl::bundle::rebound::J_BITS - 1)) - 1,
                jmin = (1 << (rtl::bundle::rebound::J_BITS - 1)) + 1,
            )
        } else {
            "its floored `t_max` (`t_lo`) is not stored.".to_string()
        },
        name = bf.name(),
        fd = bf.fd,
        ft = fmt.ft,
        t1 = fmt.t - 1,
        gmax = fmt.gmax(),
        gmin = fmt.gmin(),
    )
}

/// What the datasheet says of the bundle results processor over the fixed pair of `bf`.
pub fn bundle_split_doc(bf: &BundleFixFormat) -> FamilyDoc {
    use rtl::bundle::pair_fix::BUNDLE_FIX_LATENCY as L;
    use rtl::bundle::split::{SPLIT_ADDR_BITS, SPLIT_RAYS};
    let fmt = &bf.base;
    let (g, t, fd) = (fmt.g, fmt.t, bf.fd);
    let db = bf.dir_bits();
    let (n, ab) = (SPLIT_RAYS, SPLIT_ADDR_BITS);
    let decided = L + 1;
    let split0 = 2 * L + 1;
    let what = format!(
        "The results processor around one fixed-point AllHit / AnyHit pair (`bundle_fix_{name}`): a job \
         is one ray bundle against one node box. The bundle goes through the pair once; when the pair \
         decides it (every ray hits, or every ray misses) the job is done, otherwise the job's active \
         rays, read from a {n}-entry ray store, go through the same pair two per clock and their answers \
         form a per-ray hit mask. The mask never drops a ray that hits. One job at a time: {decided} \
         clocks for a decided job, `{split0} + ceil(n / 2)` for a split one with `n` active rays \
         (US 11,682,160's results processing).",
        name = bf.name()
    );
    let params = vec![
        param("G", g, "grid bits: signed coordinates"),
        param("T", t, "t code bits (signed)"),
        param("FT", fmt.ft, "fraction bits of a t code"),
        param("FD", fd, "fraction bits of a scaled direction code"),
        param("D", db, "bits of a direction code (signed), `FD + 3`"),
        param(
            "rays",
            n,
            "entries of the ray store (width of `active` and `mask`)",
        ),
        param("pair latency", L, "clocks of the pair inside"),
    ];
    let mut ports = vec![
        port("ray_we", "ray store write enable: the ray on `ray_*` is written to entry `ray_addr` at the end of the clock"),
        port("ray_addr", format!("ray store address, 0 .. {} ({ab} bits): ray `i` is bit `i` of `active` and `mask`", n - 1)),
    ];
    ports.extend(store_ports(bf));
    ports.push(port("start", "start a job: taken in a clock with `ready = 1` and `rst = 0`; the job ports are sampled in that clock only"));
    ports.extend(job_ports(bf));
    ports.extend([
        port("active", format!("{n} bits: bit `i` = ray store entry `i` belongs to the job (tested one by one if the bundle is undecided)")),
        port("ready", "1 when no job is in progress: a `start` in this clock is taken; high again in the clock of `done`"),
        port("done", "one-clock pulse: the job's report is on the result ports from this clock until the next `done`"),
        port("all_hit", "report: the bundle test said every ray hits (then `mask = active`)"),
        port("all_miss", "report: the bundle test said every ray misses (then `mask = 0`)"),
        port("split", "report: the bundle was undecided and its active rays were tested one by one"),
        port("mask", format!("report, {n} bits: bit `i` = ray `i` may hit (only bits of `active` are ever set; never 0 for a ray that hits)")),
        port("cycles", "report, 8 bits: clocks the job used the pair's input, `1 + (split ? ceil(popcount(active) / 2) : 0)`"),
        port("clocks", format!("report, 8 bits: clocks from the start clock to the `done` clock ({decided}, or `{split0} + ceil(popcount(active) / 2)` when split with an active ray)")),
    ]);
    let idx = axis_index(&[
        "ray_o_lo", "ray_o_hi", "ray_d_lo", "ray_d_hi", "o_lo", "o_hi", "d_lo", "d_hi", "in_lo",
        "in_hi", "out_lo", "out_hi",
    ]);
    let rules = format!(
        "{grid}

{enc}**Job protocol** (clock `s` is the clock period whose ending rising edge samples the inputs; there is no \
`valid_in`/`tag_in`):
1. **Load rays**: in every clock with `ray_we = 1` the ray on `ray_o_lo` .. `ray_t` is written to entry \
`ray_addr` at the end of the clock — during a job and during `rst` too. A job's active rays must be \
written no later than its start clock and not rewritten until its `done`; the store keeps them, so one \
bundle against several boxes needs one load.
2. **Start**: in a clock with `ready = 1`, `start = 1` and `rst = 0` the block takes the job; the bundle \
ports, `in_*`, `out_*` and `active` are sampled in that clock only (the outer box and `active` are kept \
inside). A `start` while `ready = 0` is ignored, not queued.
3. **Bundle test**: the bundle goes through the pair in bundle mode and answers in clock `s + {l}`. If \
it is decided (`all_hit` or `all_miss`), or undecided with `active = 0`, `done` is high in clock \
`s + {decided}` (`clocks = {decided}`, `cycles = 1`; undecided with `active = 0` reports `split = 1`, `mask = 0`).
4. **Split**: otherwise the active rays go through the pair in two-ray mode, two per clock in index \
order (an odd count leaves the last clock's second slot empty), against the outer box held from the \
start clock; ray `i`'s answer is AnyHit's bounds on its tiny bundle (\"may hit\"). `done` is high in \
clock `s + {split0} + ceil(n / 2)`, `n = popcount(active)` (`clocks = {split0} + ceil(n / 2)`, \
`cycles = 1 + ceil(n / 2)`).
5. **Report**: `done` is high for one clock; `all_hit`, `all_miss`, `split`, `mask`, `cycles` and \
`clocks` are valid from that clock and held until the next `done`. `mask = active` when `all_hit`, `0` \
when `all_miss`, the OR of the rays' \"may hit\" answers when `split`. `ready` is high again in the \
`done` clock, so the next job may start there (back to back).

**Reset**: `rst` high in a clock drops the job in progress and the pair's answers in flight at the end \
of that clock: no `done` follows for it, and `ready` is 1 from the next clock. A `start` in a clock with \
`rst` high is not taken; a ray store write is. The ray store and the report registers keep their \
contents.",
        enc = job_encoding(bf, false),
        grid = fix_grid_text(fmt),
        l = L,
    );
    FamilyDoc {
        what,
        params,
        ports,
        index: idx,
        rules,
    }
}

/// What differs between the streaming processors' datasheets: the pair inside and its encoding.
struct StreamPairText {
    /// The pair's module name, e.g. `bundle_fix_<format>`.
    pair: String,
    /// "fixed-point" or "binary16 floating-point" and so on.
    kind: String,
    params: Vec<(String, String, String)>,
    store: Vec<(String, String)>,
    job: Vec<(String, String)>,
    /// The re-bounding result ports and rule.
    rebound: Option<(Vec<(String, String)>, String)>,
    /// The format's words (grid or float layout) and the encoding of jobs and rays.
    format: String,
    enc: String,
    /// The pair's latency.
    l: usize,
}

/// What the datasheet says of the streaming results processor over the fixed pair of `bf` with the cut
/// points `cuts`.
pub fn bundle_stream_doc(bf: &BundleFixFormat, cuts: usize) -> FamilyDoc {
    let fmt = &bf.base;
    stream_doc(StreamPairText {
        pair: rtl::names::bundle_fix_module_cuts(bf, cuts),
        kind: "fixed-point".into(),
        params: vec![
            param("G", fmt.g, "grid bits: signed coordinates"),
            param("T", fmt.t, "t code bits (signed)"),
            param("FT", fmt.ft, "fraction bits of a t code"),
            param("FD", bf.fd, "fraction bits of a scaled direction code"),
            param(
                "D",
                bf.dir_bits(),
                "bits of a direction code (signed), `FD + 3`",
            ),
        ],
        store: store_ports(bf)
            .into_iter()
            .chain([
                port("ray_t_lo", format!("stored ray's `t_max`, `floor` in the ray's t codes, signed {} bits (for re-bounding only)", fmt.t)),
                port("ray_j", format!("stored ray's direction exponent `j`, {}-bit two's complement (for re-bounding only)", rtl::bundle::rebound::J_BITS)),
            ])
            .collect(),
        job: job_ports(bf),
        rebound: Some(rebound_doc(bf)),
        format: fix_grid_text(fmt),
        enc: job_encoding(bf, true),
        l: rtl::bundle::pair_fix::bundle_fix_latency(cuts),
    })
}

/// What the datasheet says of the streaming results processor over the float pair in `f` with the cut
/// points `cuts`.
pub fn bundle_stream_float_doc(f: &FloatFormat, cuts: usize) -> FamilyDoc {
    let w = f.width();
    let pair = rtl::names::bundle_float_module_cuts(f, cuts);
    let word = |what: &str| format!("{what}, a {w}-bit word");
    stream_doc(StreamPairText {
        pair: pair.clone(),
        kind: format!("{} floating-point", f.name()),
        params: float_params(f),
        store: vec![
            port("ray_o_lo", word("stored ray's origin, `RD(o)`")),
            port("ray_o_hi", word("stored ray's origin, `RU(o)`")),
            port("ray_d_lo", word("stored ray's direction, `RD(d * 2^j)` on its bundle's scale `j` (see Encoding)")),
            port("ray_d_hi", word("stored ray's direction, `RU(d * 2^j)`")),
            port("ray_t", word("stored ray's `t_max`, `RU(t_max * 2^-j)`; +inf allowed")),
            port("ray_t_lo", word("stored ray's `t_max`, `RD(t_max * 2^-j)`, never above the true value (used only by re-bounding; a larger value can make the pair's \"all hit\" on a fed-back `rb_*` bundle wrong)")),
        ],
        job: vec![
            port("o_lo", word("job bundle's origin box, lower corner `RD(o_min)`")),
            port("o_hi", word("job bundle's origin box, upper corner `RU(o_max)`")),
            port("d_lo", word("job bundle's direction box, lower corner `RD(d_min * 2^j)`")),
            port("d_hi", word("job bundle's direction box, upper corner `RU(d_max * 2^j)`")),
            port("t_lo", word("job bundle's smallest `t_max`, `RD(t_lo * 2^-j)`")),
            port("t_hi", word("job bundle's largest `t_max`, `RU(t_hi * 2^-j)`; +inf allowed")),
            port("in_lo", word("node box, inner (AllHit) lower corner `RU(min)`")),
            port("in_hi", word("node box, inner (AllHit) upper corner `RD(max)`")),
            port("out_lo", word("node box, outer (AnyHit and the rays) lower corner `RD(min)`")),
            port("out_hi", word("node box, outer (AnyHit and the rays) upper corner `RU(max)`")),
        ],
        rebound: Some(rebound_float_doc()),
        format: float_layout_text(f),
        enc: format!(
            "**Encoding**: the job's bundle and box are encoded exactly as for the pair \
`{pair}` (its datasheet has the conditions and the direction scale `j`: **t is not in \
world units**, `t_world = t_port * 2^j`). Each stored ray (`t_min = 0`) is the bundle of that one ray \
on the direction scale `j` of the bundle it belongs to (the bundle a traversal starts with, whose \
largest direction magnitude `2^j` brings into `[1, 2)`): `ray_o_lo/hi = RD/RU(o_a)`, \
`ray_d_lo/hi = RD/RU(d_a * 2^j)`, `ray_t_lo/ray_t = RD/RU(t_max * 2^-j)`. The pair's answers hold \
for any `j` (a ray is the same for `d * 2^j` and `t * 2^-j`), so a ray on its own scale is also \
answered correctly, but the re-bounded bundle is tight only when the kept rays share one scale (a \
float keeps its precision under a power-of-two scale, so nothing is lost unless a value leaves the \
format's normal range, where it is still rounded outward). The rays of a job need not be the \
bundle's own rays, but only then does the report describe them.\n\n"
        ),
        l: rtl::bundle::pair_float::bundle_float_latency(cuts),
    })
}

/// The re-bounding ports and rule of the fixed streaming processor over `bf`.
fn rebound_doc(bf: &BundleFixFormat) -> (Vec<(String, String)>, String) {
    let (g, t, db) = (bf.base.g, bf.base.t, bf.dir_bits());
    let jb = rtl::bundle::rebound::J_BITS;
    let ports = vec![
        port("rb_valid", "report: 1 when the job was split and kept a ray; the `rb_*` ports then hold the re-bounded bundle of its kept rays, else every `rb_*` port is 0"),
        port("rb_o_lo", format!("re-bounded bundle's origin box, lower corner, signed {g} bits")),
        port("rb_o_hi", format!("re-bounded bundle's origin box, upper corner, signed {g} bits")),
        port("rb_d_lo", format!("re-bounded bundle's direction box, lower corner, on the scale `2^(rb_j + FD)`, signed {db} bits")),
        port("rb_d_hi", format!("re-bounded bundle's direction box, upper corner, signed {db} bits")),
        port("rb_t_lo", format!("re-bounded bundle's smallest `t_max` (`floor`), signed {t} bits")),
        port("rb_t_hi", format!("re-bounded bundle's largest `t_max` (`ceil`), signed {t} bits; most positive code = +inf")),
        port("rb_j", format!("re-bounded bundle's direction exponent, {jb}-bit two's complement: the smallest `ray_j` of the kept rays")),
    ];
    let rule = "6. **Re-bounding**: while a split job's rays go through the pair, the block gathers the \
bundle around the rays it keeps (mask bit set), from the rays as stored (`ray_*`, `ray_t_lo`, `ray_j`), \
and reports it with the job on `rb_*`, valid with `done` and held as the other report ports. The rule \
(`golden::bundle::rebound` in the repository): every kept ray is brought onto the smallest `j` among \
them, `j' = min j`, shifting by `s = j - j'`: direction codes shift right by `s`, `lo` rounding down \
and `hi` up; t codes shift left by `s`, exact, saturating at the largest finite code (`t_lo`) or at \
+inf (`t_hi`), the +inf code and negative codes unchanged; origin codes as they are. Then `rb_*_lo` is \
the minimum and `rb_*_hi` the maximum of every field (signed). The result contains every kept ray's \
tiny bundle, so the pair's answers on it hold for those rays: feed it back as the job bundle of the \
next node (with `active = mask`). It is on the same grid and t scale as the job's bundle when every \
kept ray had the job's `j`. A decided job, or a split one that kept no ray, reports `rb_valid = 0` \
and zeros. When every ray stays (`mask = active`) the caller may keep the job's own bundle instead \
(the traversal model in the repository does).\n"
        .to_string();
    (ports, rule)
}

/// The re-bounding ports and rule of the float streaming processor.
fn rebound_float_doc() -> (Vec<(String, String)>, String) {
    let ports = vec![
        port("rb_valid", "report: 1 when the job was split and kept a ray; the `rb_*` ports then hold the re-bounded bundle of its kept rays, else every `rb_*` port is 0"),
        port("rb_o_lo", "re-bounded bundle's origin box, lower corner"),
        port("rb_o_hi", "re-bounded bundle's origin box, upper corner"),
        port("rb_d_lo", "re-bounded bundle's direction box, lower corner, on the stored rays' scale `2^j`"),
        port("rb_d_hi", "re-bounded bundle's direction box, upper corner, on the stored rays' scale"),
        port("rb_t_lo", "re-bounded bundle's smallest `t_max`, rounded down, in the stored rays' t units (`t_world = t_port * 2^j`)"),
        port("rb_t_hi", "re-bounded bundle's largest `t_max`, rounded up, in the stored rays' t units"),
    ];
    let rule = "6. **Re-bounding**: while a split job's rays go through the pair, the block gathers the \
bundle around the rays it keeps (mask bit set), from the rays as stored (`ray_*`, `ray_t_lo`), and \
reports it with the job on `rb_*`, valid with `done` and held as the other report ports. The rule \
(`golden::bundle::rebound` in the repository): `rb_*_lo` is the minimum and `rb_*_hi` the maximum of \
every field over the kept rays, in the numeric order with `-0` below `+0` (a NaN code, which no \
quantisation yields, orders beyond the infinity of its sign). Nothing is rescaled or rounded, so on \
rays stored on one scale the result is exactly the bundle around the kept rays rounded outward on that \
scale; on rays of different scales it still contains every kept ray's tiny bundle, so the pair's \
answers on it hold for those rays. Feed it back as it is as the job bundle of the next node (with \
`active = mask`): it stays on the stored rays' scale `j` (directions times `2^j`, t in units of \
`2^j`), and the job port takes a bundle on any scale, the pair's answers being sound for every \
`j`. A decided job, or a split one that kept no ray, reports `rb_valid = 0` and zeros. \
When every ray stays (`mask = active`) the caller may keep the job's own bundle instead (the \
traversal model in the repository does).\n"
        .to_string();
    (ports, rule)
}

/// The streaming processor's datasheet around the pair `p`.
fn stream_doc(p: StreamPairText) -> FamilyDoc {
    use golden::bundle::stream::{stream_queue, STREAM_RAYS, STREAM_SETS, STREAM_TAG_BITS};
    use rtl::bundle::stream::STREAM_ADDR_BITS;
    let l = p.l;
    let (n, sets, q, tb, ab) = (
        STREAM_RAYS,
        STREAM_SETS,
        stream_queue(l),
        STREAM_TAG_BITS,
        STREAM_ADDR_BITS,
    );
    let decided = golden::bundle::stream::decided_latency(l);
    let split0 = golden::bundle::stream::split_latency(l, 0);
    let what = format!(
        "The results processor with jobs in flight, around one {kind} AllHit / AnyHit pair \
         (`{pair}`): a job is one ray bundle against one node box, with a tag. A job is taken \
         in any clock the pair's input is free, so the pair tests a new bundle every clock; a bundle the \
         pair does not decide joins a split queue, and its active rays, read from a ray store of {sets} \
         sets of {n} rays, go through the same pair two per clock ahead of new bundles. Each job reports \
         with its tag; **results may leave in another order than the jobs came** (a decided job overtakes \
         split ones). The mask never drops a ray that hits. A decided job reports {decided} clocks after \
         its start; a stream of decided jobs enters one a clock.",
        kind = p.kind,
        pair = p.pair,
    );
    let mut params = p.params;
    params.extend([
        param(
            "rays",
            n,
            "rays in one set of the ray store (width of `active` and `mask`)",
        ),
        param("sets", sets, "sets in the ray store"),
        param("queue", q, "entries of the split queue"),
        param("pair latency", l, "clocks of the pair inside"),
    ]);
    let mut ports = vec![
        port("ray_we", "ray store write enable: the ray on `ray_*` is written to entry `ray_addr` at the end of the clock"),
        port("ray_addr", format!("ray store address ({ab} bits): `[5:4]` the set, `[3:0]` the ray; ray `i` of a set is bit `i` of `active` and `mask`")),
    ];
    ports.extend(p.store);
    ports.push(port("start", "start a job: taken in a clock with `ready = 1` and `rst = 0`; the job ports are sampled in that clock only"));
    ports.extend(p.job);
    ports.extend([
        port("active", format!("{n} bits: bit `i` = ray `i` of the job's set belongs to the job (tested one by one if the bundle is undecided)")),
        port("job_set", format!("the job's ray set, 0 .. {}", sets - 1)),
        port("tag", format!("{tb} bits, opaque: returned on `done_tag` with the job's report")),
        port("ready", "1 when a `start` in this clock is taken: low in the clocks the pair takes a pair of rays, and while the split queue could not hold every bundle in flight plus one"),
        port("done", "one-clock pulse: a job's report is on the result ports from this clock until the next `done`"),
        port("done_tag", format!("report, {tb} bits: the `tag` of the job reporting")),
        port("all_hit", "report: the bundle test said every ray hits (then `mask = active`)"),
        port("all_miss", "report: the bundle test said every ray misses (then `mask = 0`)"),
        port("split", "report: the bundle was undecided and its active rays were tested one by one"),
        port("mask", format!("report, {n} bits: bit `i` = ray `i` may hit (only bits of `active` are ever set; never 0 for a ray that hits)")),
    ]);
    let (rb_ports, rb_rule) = p.rebound.unwrap_or_default();
    ports.extend(rb_ports);
    let mut idx = axis_index(&[
        "ray_o_lo", "ray_o_hi", "ray_d_lo", "ray_d_hi", "o_lo", "o_hi", "d_lo", "d_hi", "in_lo",
        "in_hi", "out_lo", "out_hi",
    ]);
    if !rb_rule.is_empty() {
        idx.extend(axis_index(&["rb_o_lo", "rb_o_hi", "rb_d_lo", "rb_d_hi"]));
    }
    let rules = format!(
        "{grid}

{enc}**Job protocol** (clock `s` is the clock period whose ending rising edge samples the inputs):
1. **Load rays**: in every clock with `ray_we = 1` the ray on the `ray_*` ports is written to entry \
`ray_addr` at the end of the clock, at any time (also during `rst`). A job's active rays (in its set) \
must be written no later than its start clock and not rewritten until its `done`; with {sets} sets, the \
rays of the next bundle can be written while jobs of the others run.
2. **Start**: in a clock with `ready = 1`, `start = 1` and `rst = 0` the block takes the job; every job \
port is sampled in that clock only. A `start` while `ready = 0` is ignored, not queued: hold it until \
`ready`. `ready` is low in the clocks the pair takes a pair of rays, and while the split queue (of {q}) \
could not take every bundle in flight plus this one; it depends on registers only, never on `start`.
3. **Bundle test**: the bundle enters the pair in clock `s` and is answered in clock `s + {l}`. Decided \
(`all_hit` or `all_miss`), or undecided with `active = 0`: `done` is high in clock `s + {decided}` \
(undecided with `active = 0` reports `split = 1`, `mask = 0`). Otherwise the job joins the split queue.
4. **Split**: one job at a time, in the order their bundles were answered, the active rays are read two \
per clock in index order (an odd count leaves the last pair's second slot empty) and go through the \
pair in two-ray mode in the next clock, against the outer box kept from the start clock; ray `i`'s \
answer is AnyHit's bounds on its tiny bundle (\"may hit\"). The next queued job follows without a gap. \
`done` is high {l} + 2 clocks after the job's last pair enters the pair: no earlier than \
`s + {split0} + ceil(n / 2)`, `n = popcount(active)`, later when the job waits in the queue.
5. **Report**: a job is answered in one clock, held in the report stage's registers in the next and \
reported in the one after. At most one job reports a clock. `done` is high for one clock; `done_tag`, `all_hit`, \
`all_miss`, `split` and `mask` are valid from that clock and held until the next `done`. `mask = active` \
when `all_hit`, `0` when `all_miss`, the OR of the rays' \"may hit\" answers when `split`. Tags are \
returned as given; keep the tags of jobs in flight distinct to tell their reports apart.
{rb_rule}
**Reset**: `rst` high in a clock drops, at the end of that clock, every job in flight (in the pair, \
queued, being split, or in the report stage): no `done` follows for any of them, and `ready` is 1 \
from the next clock. A `start` in a clock with `rst` high is not taken; a ray store write is. The ray \
store keeps its contents; so do the report registers{rb_too}, except that the fields of a job answered \
in the `rst` clock or the clock before still reach them (with `done` low).",
        rb_too = if rb_rule.is_empty() {
            ""
        } else {
            " (re-bounding's included)"
        },
        enc = p.enc,
        grid = p.format,
    );
    FamilyDoc {
        what,
        params,
        ports,
        index: idx,
        rules,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verilator::{parse_ports, Port};
    use rtl::export::{catalog, Exported, Family};
    use rtl::verilog::split_port;
    use std::collections::{BTreeSet, HashSet};

    const CONTROL: [&str; 6] = ["clock", "rst", "valid_in", "tag_in", "valid_out", "tag_out"];

    fn doc_of(e: &Exported) -> Option<FamilyDoc> {
        Some(match e.family {
            Family::PlaneFix { cf, k, .. } => plane_fix_doc(&cf, k, false),
            Family::PlaneQuot { cf, k } => plane_fix_doc(&cf, k, true),
            Family::PlaneFloat { cf, k } => plane_float_doc(&cf, k),
            Family::BundleFix { bf, .. } => bundle_fix_doc(&bf),
            Family::BundleFloat { f, .. } => bundle_float_doc(&f),
            Family::BundleSplit { bf } => bundle_split_doc(&bf),
            Family::BundleStream { bf, cuts } => bundle_stream_doc(&bf, cuts),
            Family::BundleStreamFloat { f, cuts } => bundle_stream_float_doc(&f, cuts),
            _ => return None,
        })
    }

    /// The catalogue's entries of these families with their ports, parsed from their Verilog.
    fn modules() -> Vec<(Exported, Vec<Port>)> {
        // The blocks are large values (every signal inline): build them on a big stack.
        crate::plane::float::with_big_stack(modules_here)
    }

    fn modules_here() -> Vec<(Exported, Vec<Port>)> {
        let mut out = vec![];
        for e in catalog() {
            if doc_of(&e).is_none() {
                continue;
            }
            let v = e.verilog();
            let ports =
                parse_ports(&v, &e.module).unwrap_or_else(|err| panic!("{}: {err}", e.module));
            out.push((e, ports));
        }
        out
    }

    #[test]
    fn every_data_port_is_described_and_every_description_names_a_port() {
        let mods = modules();
        let mut families = HashSet::new();
        for (e, ports) in &mods {
            families.insert(std::mem::discriminant(&e.family));
            let doc = doc_of(e).unwrap();
            let described: BTreeSet<&str> = doc.ports.iter().map(|(b, _)| b.as_str()).collect();
            assert_eq!(
                described.len(),
                doc.ports.len(),
                "{}: a port described twice",
                e.module
            );
            let mut bases = BTreeSet::new();
            let mut arrays = BTreeSet::new();
            for p in ports {
                if CONTROL.contains(&p.name.as_str()) {
                    continue;
                }
                let (base, idx) = split_port(&p.name);
                bases.insert(base);
                if idx.is_some() {
                    arrays.insert(base);
                }
                assert!(
                    described.contains(base),
                    "{}: port {} ({base}) has no description",
                    e.module,
                    p.name
                );
            }
            for b in &described {
                assert!(
                    bases.contains(b),
                    "{}: `{b}` is described but not a port",
                    e.module
                );
            }
            for (b, _) in &doc.index {
                assert!(
                    arrays.contains(b.as_str()),
                    "{}: index text for `{b}`, which is not an array port",
                    e.module
                );
            }
            for b in &arrays {
                assert!(
                    doc.index.iter().any(|(x, _)| x == b),
                    "{}: array port `{b}` has no index text",
                    e.module
                );
            }
            assert!(!doc.what.is_empty() && !doc.rules.is_empty() && !doc.params.is_empty());
        }
        // Every family of this file is in the catalogue.
        assert_eq!(families.len(), 8, "families found: {families:?}");
    }

    #[test]
    fn widths_in_the_text_match_the_verilog() {
        for (e, ports) in modules() {
            let doc = doc_of(&e).unwrap();
            let width = |name: &str| ports.iter().find(|p| p.name == name).map(|p| p.width);
            let param = |name: &str| {
                doc.params
                    .iter()
                    .find(|(n, _, _)| n == name)
                    .map(|(_, v, _)| v.parse::<usize>().unwrap())
            };
            match e.family {
                Family::PlaneFix { cf, k, .. } | Family::PlaneQuot { cf, k } => {
                    assert_eq!(width("ray_d_lo_0"), param("D"), "{}", e.module);
                    assert_eq!(width("plane_w_0"), param("W"), "{}", e.module);
                    assert_eq!(width("plane_nx_0"), param("N"), "{}", e.module);
                    assert_eq!(width("box_lo_0"), param("G"), "{}", e.module);
                    assert_eq!(param("K"), Some(k));
                    assert!(
                        width(&format!("plane_w_{}", k - 1)).is_some()
                            && width(&format!("plane_w_{k}")).is_none()
                    );
                    let out = if matches!(e.family, Family::PlaneQuot { .. }) {
                        param("FB")
                    } else {
                        param("T")
                    };
                    assert_eq!(width("t_entry"), out, "{}", e.module);
                    assert_eq!(width("t_exit"), out, "{}", e.module);
                    assert_eq!(param("N"), Some(cf.n as usize));
                }
                Family::PlaneFloat { cf, .. } => {
                    for p in ["ray_d_lo_0", "plane_w_0", "t_entry", "box_hi_2"] {
                        assert_eq!(width(p), Some(cf.f.width() as usize), "{} {p}", e.module);
                    }
                    assert_eq!(param("R"), Some(cf.r as usize));
                }
                Family::BundleStreamFloat { f, .. } => {
                    for p in ["o_lo_0", "d_hi_2", "ray_t", "out_hi_1", "ray_d_lo_0"] {
                        assert_eq!(width(p), param("W"), "{} {p}", e.module);
                    }
                    assert_eq!(param("W"), Some(f.width() as usize));
                    assert_eq!(width("mask"), param("rays"), "{}", e.module);
                    assert_eq!(width("active"), param("rays"), "{}", e.module);
                    assert_eq!(width("done_tag"), width("tag"), "{}", e.module);
                }
                Family::BundleStream { .. } => {
                    assert_eq!(width("d_lo_0"), param("D"), "{}", e.module);
                    assert_eq!(width("o_lo_0"), param("G"), "{}", e.module);
                    assert_eq!(width("mask"), param("rays"), "{}", e.module);
                    assert_eq!(width("active"), param("rays"), "{}", e.module);
                    assert_eq!(width("ray_t"), param("T"), "{}", e.module);
                    assert_eq!(width("done_tag"), width("tag"), "{}", e.module);
                }
                Family::BundleFix { .. } | Family::BundleSplit { .. } => {
                    assert_eq!(width("d_lo_0"), param("D"), "{}", e.module);
                    assert_eq!(width("o_lo_0"), param("G"), "{}", e.module);
                    assert_eq!(width("t_hi"), param("T"), "{}", e.module);
                    if matches!(e.family, Family::BundleSplit { .. }) {
                        assert_eq!(width("mask"), param("rays"), "{}", e.module);
                        assert_eq!(width("active"), param("rays"), "{}", e.module);
                        assert_eq!(width("ray_d_hi_2"), param("D"), "{}", e.module);
                        assert_eq!(width("ray_t"), param("T"), "{}", e.module);
                    } else {
                        assert_eq!(width("r_d_hi_2"), param("D"), "{}", e.module);
                    }
                }
                Family::BundleFloat { f, .. } => {
                    assert_eq!(width("d_lo_0"), param("W"), "{}", e.module);
                    assert_eq!(width("r_t"), Some(f.width() as usize));
                }
                _ => unreachable!(),
            }
        }
    }

    #[test]
    fn text_follows_the_format() {
        let b12 = FixFormat::b12();
        let cf = CullFixFormat::over(b12);
        for frac in [false, true] {
            let d = plane_fix_doc(&cf, 4, frac);
            // The +inf t code of b12 (T = 20) and the offset range (W = 24).
            assert!(
                d.rules.contains("0x7ffff") && d.rules.contains("-8388608"),
                "{}",
                d.rules
            );
            assert_eq!(d.rules.contains("reciprocal table of 2^8"), !frac);
            let te = &d.ports.iter().find(|(b, _)| b == "t_entry").unwrap().1;
            assert_eq!(te.contains("packed fraction"), frac, "{te}");
        }
        let b16 = CullFixFormat::over(FixFormat::b16());
        assert!(plane_fix_doc(&b16, 1, false).rules.contains("0x7fffff"));
        let fl = plane_float_doc(&CullFloatFormat::over(FloatFormat::FP16), 2);
        assert!(fl.rules.contains("0x7c00"), "{}", fl.rules);
        assert!(fl
            .index
            .iter()
            .any(|(b, w)| b == "plane_nx" && w == "plane, 0 .. 1"));
        let bf = BundleFixFormat::over(b12).unwrap();
        let bd = bundle_fix_doc(&bf);
        // t_lo saturates to the largest finite code 2^19 - 2, t_hi to the +inf code.
        assert!(
            bd.rules.contains("0x7fffe") && bd.rules.contains("0x7ffff"),
            "{}",
            bd.rules
        );
        let sd = bundle_split_doc(&bf);
        assert!(
            sd.what.contains("4 clocks for a decided job"),
            "{}",
            sd.what
        );
        assert!(sd.rules.contains("`s + 7 + ceil(n / 2)`"), "{}", sd.rules);
        let ff = bundle_float_doc(&FloatFormat::BF16);
        assert!(ff.rules.contains("not in world units") && ff.rules.contains("0x7f80"));
    }

    #[test]
    fn split_timing_in_the_text_is_the_model_s() {
        use golden::bundle::split::SplitResult;
        use rtl::bundle::split::split_clocks;
        // Decided, and split over 1 .. 16 active rays, as the text states them.
        let decided = SplitResult {
            pair_cycles: 1,
            ..Default::default()
        };
        assert_eq!(split_clocks(&decided), 4);
        for n in 1..=16u32 {
            let r = SplitResult {
                split: true,
                pair_cycles: 1 + n.div_ceil(2),
                ..Default::default()
            };
            assert_eq!(split_clocks(&r), 7 + n.div_ceil(2));
        }
    }
}
