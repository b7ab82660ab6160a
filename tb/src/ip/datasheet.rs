//! Datasheets of the exported cores: one Markdown page per module, generated with its Verilog.

/// What a datasheet says of a block family beyond the ports' names and widths (which come from the
/// Verilog): written per family and configuration.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FamilyDoc {
    /// One paragraph: what the block computes and what it guarantees.
    pub what: String,
    /// The configuration's parameters: `(name, value, meaning)`.
    pub params: Vec<(String, String, String)>,
    /// Meaning and encoding of each port, by the port's base name (`ray_o_lo` for `ray_o_lo_0..2`,
    /// whose index is given by `index`): `(base, meaning)`. Control ports (`clock`, `rst`,
    /// `valid_in`, `tag_in`, `valid_out`, `tag_out`) are described by the datasheet itself.
    pub ports: Vec<(String, String)>,
    /// What the index of an array port means, by base name (for example `x, y, z` or `plane k`).
    pub index: Vec<(String, String)>,
    /// The encoding rules as Markdown (formulas): how a user turns world-space values into port words
    /// and output words back into world-space values.
    pub rules: String,
}

use crate::verilator::Port;
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use rtl::export::{Exported, Family};

/// A worked example: one world-space vector, the options that map it, its input words and the output
/// words and world-space result the model gives.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Example {
    /// The vector as a line of `rtu run`'s JSON input.
    pub vector: String,
    /// How it was mapped (for example the grid bounds), as a sentence.
    pub mapping: String,
    /// `(port, word)` of every input column.
    pub ins: Vec<(String, u64)>,
    /// `(port, word)` of every output column.
    pub outs: Vec<(String, u64)>,
    /// The result in world units, as `rtu run` writes it.
    pub result: String,
}

/// The index of the slab testers' array ports: the axis.
fn slab_index() -> Vec<(String, String)> {
    let mut v = vec![(
        "ray_o_lo".to_string(),
        "axis: 0 = x, 1 = y, 2 = z".to_string(),
    )];
    for p in [
        "ray_o_hi", "ray_m_lo", "ray_m_hi", "ray_neg", "box_lo", "box_hi",
    ] {
        v.push((p.into(), "axis".into()));
    }
    v
}

/// What the datasheet says of the fixed slab tester of `fmt` (and of the slab ports of the chained
/// cull-plane tester over it).
pub fn slab_fix_doc(fmt: &FixFormat) -> FamilyDoc {
    let (g, i, fi, t, ft) = (fmt.g, fmt.i, fmt.fi, fmt.t, fmt.ft);
    FamilyDoc {
        what: format!(
            "Tests a ray against an axis-aligned box with the slab method on a {g}-bit integer grid and \
             reports whether they meet and the ray's entry and exit parameters. Every input is an \
             outward bound of the world-space value (origin and inverse direction as intervals, box \
             rounded outward, `t_min` floored, `t_max` ceiled), and every operation rounds outward, so \
             the result is conservative: whenever the exact world-space ray meets the exact box within \
             `[t_min, t_max]`, `hit` is 1 and `[t_entry, t_exit]` encloses the exact interval. A false \
             hit (a near miss reported as a hit) is allowed; a false miss is not."
        ),
        params: vec![
            ("G".into(), g.to_string(), "grid bits: signed coordinates".into()),
            ("I".into(), i.to_string(), "inverse-direction bits (unsigned magnitude)".into()),
            ("FI".into(), fi.to_string(), "fraction bits of the inverse direction".into()),
            ("T".into(), t.to_string(), "t bits (signed)".into()),
            ("FT".into(), ft.to_string(), "fraction bits of t".into()),
        ],
        ports: vec![
            ("ray_o_lo".into(), format!("origin, lower bound: `floor(o_g)`, signed {g}-bit grid coordinate")),
            ("ray_o_hi".into(), format!("origin, upper bound: `ceil(o_g)`, signed {g}-bit grid coordinate")),
            ("ray_m_lo".into(), format!("inverse direction magnitude, lower bound: `floor(2^{fi} / |d_s|)`, unsigned {i} bits, {fi} fraction bits")),
            ("ray_m_hi".into(), format!("inverse direction magnitude, upper bound: `ceil(2^{fi} / |d_s|)`, unsigned {i} bits; all ones = unbounded")),
            ("ray_neg".into(), "direction sign: 1 when the component is negative (including -0)".into()),
            ("ray_t_min".into(), format!("start of the ray's range: `floor(t_min * 2^{ft} / 2^(k+j))`, signed {t} bits; the most negative code is -inf")),
            ("ray_t_max".into(), format!("end of the ray's range: `ceil(t_max * 2^{ft} / 2^(k+j))`, signed {t} bits; the most positive code is +inf")),
            ("box_lo".into(), format!("box minimum: `floor(min_g)`, signed {g}-bit grid coordinate")),
            ("box_hi".into(), format!("box maximum: `ceil(max_g)`, signed {g}-bit grid coordinate")),
            ("hit".into(), "1 when the ray may meet the box within its range (never 0 for a true hit)".into()),
            ("t_entry".into(), format!("entry parameter, a lower bound of the exact entry, signed {t}-bit t code (same unit as `ray_t_min`)")),
            ("t_exit".into(), format!("exit parameter, an upper bound of the exact exit, signed {t}-bit t code")),
        ],
        index: slab_index(),
        rules: slab_fix_rules(fmt),
    }
}

fn slab_fix_rules(fmt: &FixFormat) -> String {
    let (g, i, fi, t, ft) = (fmt.g, fmt.i, fmt.fi, fmt.t, fmt.ft);
    let gmin = fmt.gmin();
    let gmax = fmt.gmax();
    let inf = fmt.inv_inf();
    format!(
        "All words are two's complement where signed. Axis `a` of an array port is port `<name>_a` \
(0 = x, 1 = y, 2 = z).

**Grid map** (chosen once per scene, shared by every ray and box): a world coordinate `x` on axis `a` \
maps to the grid value `x_g = x / 2^k - c_a`, with the cell exponent `k` (an integer) and the centre \
`c_a` (an integer) chosen so that the scene bounds fit in `[{gmin}, {gmax}]`: `rtu encode` picks the \
finest `k` that holds the bounds and prints `k` and `c` in its files. Every conversion is an exact \
scaling by a power of two, so the floors and ceilings below are exact.

**Direction scale**: per ray, `j` is the integer with `2^j * max_a |d_a|` in `[1, 2)`; the scaled \
direction is `d_s = d * 2^j` (exact). Only the direction's ratios matter, so the scale costs nothing.

**Inputs**:
- origin: `ray_o_lo_a = floor(o_a / 2^k) - c_a`, `ray_o_hi_a = ceil(o_a / 2^k) - c_a` (equal when the \
  origin lies on the grid). A coordinate outside `[{gmin}, {gmax}]` after the map does not fit: the \
  encoder refuses it.
- inverse direction, per axis, with `v = 2^{fi} / |d_s,a|`:
  - `d_a = 0` (either zero): `ray_m_lo_a = ray_m_hi_a = 0x{inf:x}` (all ones: unbounded).
  - `v > 0x{inf:x} - 1` (a tiny but non-zero component): `ray_m_lo_a = 0x{lo:x}` (the largest finite \
    code, `2^{i} - 2`) and `ray_m_hi_a = 0x{inf:x}` (unbounded). **Do not** set both ends to all ones \
    for a non-zero component: both all ones means exactly zero, and the tester then treats the axis as \
    parallel to the slabs, which can miss a box the ray meets.
  - otherwise `ray_m_lo_a = floor(v)`, `ray_m_hi_a = ceil(v)`, saturated: `ceil(v) >= 2^{i} - 1` gives \
    all ones. Unsigned, {fi} fraction bits.
  - `ray_neg_a = 1` when `d_a` is negative or `-0`, else 0.
- t range, in t codes (below): `ray_t_min = floor(t_min * 2^({ft} - k - j))`, \
  `ray_t_max = ceil(t_max * 2^({ft} - k - j))`. `t_min = -inf` (or any value below the code range) is \
  the code `-2^{t1}` (`0x{tneg:x}`), `t_max = +inf` (or above the range) is `2^{t1} - 1` \
  (`0x{tpos:x}`); a finite `t_min` above the range becomes `2^{t1} - 2`, a finite `t_max` below it \
  `-2^{t1} + 1`.
- box: `box_lo_a = floor(min_a / 2^k) - c_a`, `box_hi_a = ceil(max_a / 2^k) - c_a`. An empty world box \
  (`min_a > max_a` on some axis) is the canonical empty box `box_lo_a = {gmax}` (`0x{gmaxh:x}`), \
  `box_hi_a = {gmin}` (`0x{gminh:x}`) on every axis, which never hits.

**t codes** (inputs `ray_t_min`, `ray_t_max`, outputs `t_entry`, `t_exit`): signed {t}-bit, {ft} \
fraction bits, in the ray's own unit: `t_world = code * 2^(k + j - {ft})`. The most negative code \
`0x{tneg:x}` is `-inf`, the most positive `0x{tpos:x}` is `+inf`.

**Outputs**: `hit = 1` when the box is not empty, `t_entry <= t_exit`, `t_entry` is not the +inf code \
and `t_exit` is not the -inf code; `t_entry` is the maximum of \
`ray_t_min` and the three axes' entries, `t_exit` the minimum of `ray_t_max` and the three exits. An \
axis with an unbounded inverse does not constrain t when the origin interval touches its slab, and \
misses otherwise. On a miss `t_entry`/`t_exit` are still driven (the values the datapath computed) and \
carry no promise.",
        lo = inf - 1,
        t1 = t - 1,
        tneg = 1u64 << (t - 1),
        tpos = (1u64 << (t - 1)) - 1,
        gmaxh = gmax as u64,
        gminh = (gmin as u64) & ((1u64 << g) - 1),
    )
}

/// What the datasheet says of the float slab tester of `f`.
pub fn slab_float_doc(f: &FloatFormat) -> FamilyDoc {
    let (e, m, w) = (f.e, f.m, f.width());
    let inf = f.inf(false);
    let ninf = f.inf(true);
    FamilyDoc {
        what: format!(
            "Tests a ray against an axis-aligned box with the slab method in the floating-point \
             format {} (IEEE 754 layout: 1 sign bit, {e} exponent bits, {m} fraction bits, \
             subnormals supported) and reports whether they meet and the ray's entry and exit \
             parameters in world units. The inputs are outward bounds of the world-space values \
             (origin and inverse direction as intervals rounded toward -inf and +inf, box rounded \
             outward) and every operation rounds in the direction that widens the interval, so the \
             result is conservative: whenever the exact ray meets the exact box within `[t_min, \
             t_max]`, `hit` is 1 and `[t_entry, t_exit]` encloses the exact interval. A false hit is \
             allowed; a false miss is not.",
            f.name()
        ),
        params: vec![
            ("E".into(), e.to_string(), "exponent bits (bias 2^(E-1) - 1)".into()),
            ("M".into(), m.to_string(), "fraction bits".into()),
            ("W".into(), w.to_string(), "word width 1 + E + M".into()),
        ],
        ports: vec![
            ("ray_o_lo".into(), "origin rounded toward -inf: `RD(o_a)`".into()),
            ("ray_o_hi".into(), "origin rounded toward +inf: `RU(o_a)`".into()),
            ("ray_m_lo".into(), "inverse direction magnitude rounded toward -inf: `RD(1 / |d_a|)`".into()),
            ("ray_m_hi".into(), "inverse direction magnitude rounded toward +inf: `RU(1 / |d_a|)`".into()),
            ("ray_neg".into(), "direction sign: 1 when the component is negative (including -0)".into()),
            ("ray_t_min".into(), "start of the ray's range, `RD(t_min)`; -inf allowed".into()),
            ("ray_t_max".into(), "end of the ray's range, `RU(t_max)`; +inf allowed".into()),
            ("box_lo".into(), "box minimum, `RD(min_a)`".into()),
            ("box_hi".into(), "box maximum, `RU(max_a)`".into()),
            ("hit".into(), "1 when the ray may meet the box within its range (never 0 for a true hit)".into()),
            ("t_entry".into(), "entry parameter in world units, a lower bound of the exact entry".into()),
            ("t_exit".into(), "exit parameter in world units, an upper bound of the exact exit".into()),
        ],
        index: slab_index(),
        rules: format!(
            "Every value port is a {w}-bit word of {name}: bit {s} the sign, bits [{eh}:{m}] the biased \
exponent, bits [{ml}:0] the fraction (IEEE 754 layout; exponent all ones with a zero fraction is \
infinity; subnormals are values, not flushed). `RD` rounds toward -inf, `RU` toward +inf, each once from \
the exact value. t is in world units: no grid and no scaling.

**Inputs**: origin `ray_o_lo_a = RD(o_a)`, `ray_o_hi_a = RU(o_a)`. Inverse direction, per axis: \
`d_a = 0` (either zero) gives `ray_m_lo_a = ray_m_hi_a = +inf` (`0x{inf:x}`); otherwise `ray_m_lo_a = \
RD(1 / |d_a|)` and `ray_m_hi_a = RU(1 / |d_a|)` from the exact quotient (a tiny component gives \
`ray_m_hi_a = +inf` and `ray_m_lo_a` the largest finite value or a rounded-down finite value: never \
both +inf for a non-zero component). `ray_neg_a = 1` when `d_a` is negative or -0. `ray_t_min = \
RD(t_min)`, `ray_t_max = RU(t_max)` (-inf and +inf are allowed). Box: `box_lo_a = RD(min_a)`, \
`box_hi_a = RU(max_a)`; an empty world box (`min_a > max_a` on some axis) is the canonical empty box \
`box_lo_a = +inf` (`0x{inf:x}`), `box_hi_a = -inf` (`0x{ninf:x}`) on every axis. An origin or box \
coordinate beyond the format's largest finite value does not fit: the encoder refuses it. NaN inputs \
are not allowed.

**Datapath** (per axis, directed rounding; `0 x inf` leaves the axis unconstrained):
```text
d >= 0:  e = RD(near - o_hi)     x = RU(far - o_lo)
d <  0:  e = RD(o_lo - near)     x = RU(o_hi - far)
entry_a = RD(e * (e >= 0 ? m_lo : m_hi))      exit_a = RU(x * (x >= 0 ? m_hi : m_lo))
```
`t_entry = max(t_min, entry_x, entry_y, entry_z)`, `t_exit = min(t_max, exit_x, exit_y, exit_z)`; \
`hit = box not empty and t_entry <= t_exit and t_entry != +inf and t_exit != -inf`. On a miss the t \
outputs carry no promise.",
            name = f.name(),
            s = w - 1,
            eh = w - 2,
            ml = m - 1,
        ),
    }
}

/// The family text of a catalogue entry.
pub fn family_doc(e: &Exported) -> FamilyDoc {
    use super::family_docs as fd;
    match e.family {
        Family::SlabFix { fmt, .. } => slab_fix_doc(&fmt),
        Family::SlabFloat { f, .. } => slab_float_doc(&f),
        Family::PlaneFix { cf, k, .. } => fd::plane_fix_doc(&cf, k, false),
        Family::PlaneQuot { cf, k } => fd::plane_fix_doc(&cf, k, true),
        Family::PlaneFloat { cf, k } => fd::plane_float_doc(&cf, k),
        Family::BundleFix { bf, .. } => fd::bundle_fix_doc(&bf),
        Family::BundleFloat { f, .. } => fd::bundle_float_doc(&f),
        Family::BundleSplit { bf } => fd::bundle_split_doc(&bf),
        Family::BundleStream { bf, cuts } => fd::bundle_stream_doc(&bf, cuts),
        Family::BundleStreamFloat { f, cuts } => fd::bundle_stream_float_doc(&f, cuts),
    }
}

/// The meaning of a control port, shared by every pipelined core.
fn control_port(name: &str, e: &Exported) -> Option<String> {
    let l = e.latency;
    Some(match name {
        "clock" => "clock; every register samples on the rising edge".into(),
        "rst" if !e.pipelined() => "synchronous reset, active high: see the rules below".into(),
        "rst" => {
            "synchronous reset, active high: at a rising edge it clears every valid bit of the \
                  pipeline (data registers keep their values)"
                .into()
        }
        "valid_in" => {
            "high in a clock that carries a test; low for a bubble (data inputs are then \
                       ignored)"
                .into()
        }
        "tag_in" => "caller's tag of the test, returned unchanged on `tag_out`".into(),
        "valid_out" => format!(
            "high exactly {l} clocks after a test's clock (for every test not met by a reset), \
             low otherwise"
        ),
        "tag_out" => "`tag_in` of the test whose result is on the outputs".into(),
        _ => return None,
    })
}

/// The datasheet of `e` as Markdown: `ports` are the module's ports (parsed from its Verilog),
/// `figures` lines of area and speed from the project's tables, `example` a worked vector.
pub fn render(
    e: &Exported,
    ports: &[Port],
    doc: &FamilyDoc,
    figures: &[String],
    example: Option<&Example>,
) -> String {
    let mut s = format!("# `{}` — datasheet\n\n", e.module);
    s += &format!("{}\n\n", doc.what);
    s += "## Parameters\n\n| parameter | value | meaning |\n|---|---|---|\n";
    for (n, v, m) in &doc.params {
        s += &format!("| {n} | {v} | {m} |\n");
    }
    s += &format!(
        "| latency | {} | clocks from a test in to its result out |\n\n",
        e.latency
    );
    s += "## Timing\n\n";
    if e.pipelined() {
        s += &format!(
            "Fully pipelined: initiation interval 1 (a new test every clock, bubbles allowed), latency \
             {l} clocks: a test whose inputs are held, with `valid_in` high, during clock cycle `c` (and \
             sampled at the rising edge that ends it) has its result on the outputs during cycle \
             `c + {l}` ({lm} rising edges after the one that sampled it), with `valid_out` high, for one \
             cycle. Results leave in the order the tests entered. All outputs are registered.\n\n\
             **Reset**: `rst` is synchronous and active high. A test that meets `rst` high at any of its \
             {l} edges never leaves (`valid_out` stays low for it); every other test leaves on time. \
             Data registers are not reset: read the data outputs only when `valid_out` is high. \
             Registers start from their `initial` values in simulation, so no reset is needed before the \
             first test; on an FPGA or ASIC without initial values hold `rst` high for {l} clocks.\n\n",
            l = e.latency,
            lm = e.latency - 1
        );
    } else {
        s += &format!(
            "Not one test a clock: a job takes several clocks (see the rules below). A decided job takes \
             {} clocks from `start` to `done`.\n\n",
            e.latency
        );
    }
    s += "## Ports\n\n| port | dir | width | meaning |\n|---|---|---|---|\n";
    for p in ports {
        let (base, idx) = rtl::verilog::split_port(&p.name);
        let meaning = control_port(&p.name, e)
            .or_else(|| {
                doc.ports
                    .iter()
                    .find(|(b, _)| b == base || *b == p.name)
                    .map(
                        |(_, m)| match (idx, doc.index.iter().find(|(b, _)| b == base)) {
                            (Some(i), Some((_, what))) => format!("{m} ({what}: {i})"),
                            _ => m.clone(),
                        },
                    )
            })
            .unwrap_or_else(|| "(not described)".into());
        let range = if p.width > 1 {
            format!("[{}:0]", p.width - 1)
        } else {
            String::new()
        };
        s += &format!(
            "| `{}{range}` | {} | {} | {meaning} |\n",
            p.name,
            if p.input { "in" } else { "out" },
            p.width
        );
    }
    s += "\n## Encoding\n\n";
    s += &doc.rules;
    s += "\n\n";
    s += "## Worked example\n\n";
    match example {
        Some(x) => {
            s += &format!(
                "The vector\n\n```json\n{}\n```\n\n{}\n\n",
                x.vector, x.mapping
            );
            s += "| input port | word (hex) |\n|---|---|\n";
            for (p, w) in &x.ins {
                s += &format!("| `{p}` | `{w:x}` |\n");
            }
            s += "\ngives, after the latency,\n\n| output port | word (hex) |\n|---|---|\n";
            for (p, w) in &x.outs {
                s += &format!("| `{p}` | `{w:x}` |\n");
            }
            s += &format!("\nwhich decodes to `{}`.\n\n", x.result);
            s += "`rtu encode --module <module> vectors.jsonl` writes these words for a whole file \
                  (`.in.hex`, `.out.hex`, `.mem` for `$readmemh`); `rtu decode` turns captured output \
                  words back into world-space results.\n\n";
        }
        None => s += "No worked example for this family: `rtu encode` does not take it yet.\n\n",
    }
    s += "## Area and speed\n\n";
    if figures.is_empty() {
        s += "Not in the project's tables yet (`scripts/synth`, `scripts/timing` measure it).\n";
    } else {
        for f in figures {
            s += &format!("- {f}\n");
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The codes the fixed slab datasheet names are the format's (golden::format::fixed), and its hit rule
    /// has every condition of the model's (golden::slab::fix::slab_fix).
    #[test]
    fn the_fixed_slab_rules_name_the_formats_codes_and_the_models_hit_conditions() {
        for fmt in FixFormat::presets() {
            let r = slab_fix_doc(&fmt).rules;
            let mask = |v: i64, bits: u32| (v as u64) & ((1u64 << bits) - 1);
            for code in [
                format!("0x{:x}", fmt.inv_inf()),
                format!("0x{:x}", fmt.inv_inf() - 1),
                format!("0x{:x}", mask(fmt.t_pos_inf(), fmt.t)),
                format!("0x{:x}", mask(fmt.t_neg_inf(), fmt.t)),
                format!("0x{:x}", mask(fmt.gmax(), fmt.g)),
                format!("0x{:x}", mask(fmt.gmin(), fmt.g)),
                format!("[{}, {}]", fmt.gmin(), fmt.gmax()),
                format!("2^(k + j - {})", fmt.ft),
            ] {
                assert!(r.contains(&code), "{}: {code} missing", fmt.name());
            }
            for cond in [
                "the box is not empty",
                "`t_entry <= t_exit`",
                "`t_entry` is not the +inf code",
                "`t_exit` is not the -inf code",
            ] {
                assert!(r.contains(cond), "{}: {cond} missing", fmt.name());
            }
        }
    }

    #[test]
    fn the_float_slab_rules_name_the_formats_infinities() {
        for f in [FloatFormat::FP16, FloatFormat::FP32] {
            let r = slab_float_doc(&f).rules;
            assert!(r.contains(&format!("0x{:x}", f.inf(false))), "{}", f.name());
            assert!(r.contains(&format!("0x{:x}", f.inf(true))), "{}", f.name());
            assert!(
                r.contains("t_entry != +inf and t_exit != -inf"),
                "{}",
                f.name()
            );
        }
    }
}
