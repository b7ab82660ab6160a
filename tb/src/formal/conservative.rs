//! Conservativeness of the slab testers, proven end to end on the exported Verilog: for every input the
//! tester accepts, every ray the quantised input stands for that hits the box exactly is reported as a
//! hit, with an interval that encloses the exact one.
//!
//! # The fixed tester ([`slab_fix_proofs`])
//! The quantised ray of `golden::format::fixed` stands for every ray whose origin lies in
//! `[o_lo, o_hi]` (grid units) and whose inverse direction magnitude `mu` (times `2^FI`) lies in
//! `[m_lo, m_hi]` per axis, with `m_hi` all ones meaning "no upper bound" (a component too small for the
//! code, but not zero) and both all ones meaning the component is zero (the datasheet's encoding). The
//! harness holds the tester's inputs and a **witness** per axis free (`anyconst`):
//! - an origin `ow` with `o_lo <= ow <= o_hi`;
//! - either a finite inverse `mw` (two bits wider than the code) with `m_lo <= mw`, `mw <= m_hi` when
//!   `m_hi` is finite, and `m_lo` not all ones; or a zero direction `dz`, when both are all ones.
//!
//! A zero direction belongs to the both-all-ones code only: with `m_lo` finite and the origin on the
//! near plane the tester's entry is `0 * m_lo = 0`, right for every nonzero component, while a zero one
//! would leave the axis unconstrained (a false miss when `t_min < 0`). The first run of this proof, with
//! `dz` allowed whenever `m_hi` was all ones, found exactly that input; the encoding rules it out.
//!
//! The exact test of the witness ray is written without division, in wide integers, on the t code's
//! scale times `2^S` (`S = FI - FT`): per axis, with the distances taken in the direction of travel
//! (`near - ow`, `far - ow` for a positive direction, `ow - near`, `ow - far` for a negative one), the
//! entry and exit are the distances times `mw`; a zero direction leaves the axis unconstrained when the
//! origin lies in the slab and empties it otherwise. Entry is the largest of `t_min` and the axes'
//! entries, exit the smallest of `t_max` and their exits, and the exact ray hits when the box is not
//! empty and some real `t` lies in `[entry, exit]` (`entry <= exit`, `entry` not `+inf`, `exit` not
//! `-inf`). The property, `L` clocks after the inputs: an exact hit implies `hit`, `t_entry <= entry`
//! and `t_exit >= exit`.
//!
//! Why integer witnesses prove it for every real ray in the intervals: per axis, the exact entry and
//! exit are bilinear in the origin and the inverse, so over the box `[o_lo, o_hi] x [m_lo, m_hi]` each
//! attains its least and greatest value at a corner, and the corners are integer codes the witness
//! takes. With `m_hi` unbounded, the far "corner" is a limit: the tester takes that end only where the
//! distance's sign sends the bound to `-inf` (entry) or `+inf` (exit), which holds for every finite `mu`. The
//! tester's entry is one number for the whole box, so it is at most the least exact entry, which is a
//! witness's; likewise the exit. The ray's hit follows per ray from the enclosure of every axis:
//! `t_entry = max(..) <= max of the exact entries <= min of the exact exits <= t_exit`.
//!
//! # Why the solver finishes: the exact products in expanded form
//! Written directly, the exact entry `en * mw` and the tester's `floor(e * m_c / 2^S)` are products of
//! different operands, and "`e * m_c <= en * mw` when `e <= en` and `m_c <= mw`" is a monotonicity fact
//! a bit-level solver does not settle: Boolector ran out of 5 minutes on that lemma alone at 8 x 11
//! bits, and the end-to-end harness written that way out of 15 minutes at `G = 6`. The harness
//! therefore
//! - probes the operands `(a, m)` of the tester's six multiply-round units (the proof's `probes`, wired
//!   in after flattening) and **asserts** that they are the distance `eh` and inverse end `m_c` the
//!   interval rule names, computed by the harness from the ports (`eh = lo - o_hi` or `o_lo - hi`, `m_c =
//!   eh >= 0 ? m_lo : m_hi`, and for the exit `xh`, `xh >= 0 ? m_hi : m_lo`);
//! - writes the witness's exact product through a ring identity around the probed product `P = eh *
//!   m_c`, which it computes by the unit's own expression (so Yosys merges the two multipliers): with
//!   `en = eh + de`, `de >= 0`, and `dm = |mw - m_c|`,
//!   `en * mw = P + |eh| * dm + de * mw` (for `eh >= 0`, `m_c = m_lo <= mw`; for `eh < 0`,
//!   `m_c = m_hi >= mw`), and for the exit, with `ex = xh - dx`, `ex * mw = P - |xh| * dm - dx * mw`.
//!   The added terms are products of non-negative numbers, so the solver is left with adders and
//!   compares. The identity holds with the all-ones code taken as a number, so the unbounded end
//!   needs no case of its own (the tester answers `+-inf` there).
//!
//! Given the operand assertions, which the proof also checks, the expanded value equals the exact
//! product, so nothing is assumed about the tester's arithmetic.
//!
//! Since the tester is a feed-forward pipeline and its inputs are held, its outputs after `L` clocks
//! are a function of the inputs alone (the pipeline proofs show the latency for any stream), so the
//! bounded check of depth `L + 1` is the claim for every input.
//!
//! Mutants: the floor of axis 0's entry made a ceiling (a rounding direction flipped), the inverse
//! bound of axis 0's entry for a negative distance taken from the wrong end of the interval (caught by
//! the operand assertion), and the final compare made strict (a grazing ray missed).

use super::{module_body, mutant_with, mutate, Engine, Proof};
use golden::format::fixed::FixFormat;

/// `text` with the single occurrence of `find` inside module `module` replaced.
pub fn mutate_in(text: &str, module: &str, find: &str, replace: &str) -> Result<String, String> {
    let (start, body) = module_body(text, module).ok_or_else(|| format!("no module {module}"))?;
    let changed = mutate(body, find, replace).map_err(|e| format!("{module}: {e}"))?;
    Ok(format!(
        "{}{}{}",
        &text[..start],
        changed,
        &text[start + body.len()..]
    ))
}

/// The conservativeness proof of the fixed slab tester `module` (Verilog `text`, latency `lat`) for
/// `fmt`, with its three mutants where `mutants`.
pub fn slab_fix_proofs(
    fmt: &FixFormat,
    module: &str,
    text: &str,
    lat: usize,
    quick: bool,
    mutants: bool,
) -> Result<Vec<Proof>, String> {
    let p = Proof {
        name: format!("cons_{module}"),
        property: "conservative: every ray of the quantised intervals that hits exactly is a hit, \
                   and [t_entry, t_exit] encloses its exact interval"
            .into(),
        format: fmt.name(),
        engine: Engine::Bmc(lat + 1),
        harness: slab_fix_harness(fmt, module, lat),
        probes: slab_fix_probes(),
        quick,
        ..Proof::on(&module, text.into())
    };
    let mut v = vec![p.clone()];
    if mutants {
        let err = |e: String| format!("mutant of {module}: {e}");
        let s = fmt.shift();
        let changed = mutate_in(
            text,
            &format!("{module}_mul_entry_0"),
            "'sd0) >>> shift;",
            &format!("'sd{}) >>> shift;", (1u64 << s) - 1),
        )
        .map_err(err)?;
        v.push(mutant_with(
            &p,
            "ceil",
            "rounding direction flipped: axis 0's entry rounded up",
            changed,
        ));
        let changed =
            mutate(text, "em_qo_0_d = m_hi_q1_0_q;", "em_qo_0_d = m_lo_q1_0_q;").map_err(err)?;
        v.push(mutant_with(
            &p,
            "mend",
            "wrong interval end: axis 0's entry for a negative distance multiplied by m_lo",
            changed,
        ));
        let changed = mutate(
            text,
            "((entry ^ sign_t) <= (exit ^ sign_t))",
            "((entry ^ sign_t) < (exit ^ sign_t))",
        )
        .map_err(err)?;
        v.push(mutant_with(
            &p,
            "strict",
            "hit on entry < exit: a grazing ray (entry = exit) missed",
            changed,
        ));
    }
    Ok(v)
}

/// The harness of [`slab_fix_proofs`]: the tester's inputs and the witnesses free and held, the
/// multipliers' operands probed and checked, the exact test of the witness ray in the expanded form of
/// the module documentation, the property at clock `lat`.
fn slab_fix_harness(fmt: &FixFormat, module: &str, lat: usize) -> String {
    let (g, i, t, s) = (fmt.g, fmt.i, fmt.t, fmt.shift());
    let mut decl = String::new();
    let mut ports = String::new();
    let mut axes = String::new();
    for a in 0..3 {
        decl += &format!(
            "  (* anyconst *) reg signed [G-1:0] o_lo{a}, o_hi{a}, lo{a}, hi{a}, ow{a};
  (* anyconst *) reg [I-1:0] m_lo{a}, m_hi{a}, mw{a};
  (* anyconst *) reg neg{a}, dz{a}, big{a};
  (* keep *) wire [D-1:0] pa_e{a}, pa_x{a};
  (* keep *) wire [I-1:0] pm_e{a}, pm_x{a};
"
        );
        ports += &format!(
            "    .ray_o_lo_{a}(o_lo{a}), .ray_o_hi_{a}(o_hi{a}), .ray_m_lo_{a}(m_lo{a}), \
             .ray_m_hi_{a}(m_hi{a}), .ray_neg_{a}(neg{a}), .box_lo_{a}(lo{a}), .box_hi_{a}(hi{a}),\n"
        );
        axes += &format!(
            "  // Axis {a}. The witness ray lies in the quantised intervals: a zero direction for the
  // both-all-ones code, an inverse beyond every code (big) or a finite code mw otherwise.
  always @(*) assume(o_lo{a} <= ow{a} && ow{a} <= o_hi{a});
  always @(*) assume(dz{a} ? (&m_lo{a} && &m_hi{a} && !big{a})
                   : big{a} ? (!(&m_lo{a}) && &m_hi{a})
                   : (!(&m_lo{a}) && m_lo{a} <= mw{a} && ((&m_hi{a}) ? !(&mw{a}) : mw{a} <= m_hi{a})));
  // The witness's distances in the direction of travel, and the tester's (origin interval ends).
  wire signed [G+1:0] en{a} = neg{a} ? ow{a} - hi{a} : lo{a} - ow{a};
  wire signed [G+1:0] ex{a} = neg{a} ? ow{a} - lo{a} : hi{a} - ow{a};
  wire signed [G+1:0] eh{a} = neg{a} ? o_lo{a} - hi{a} : lo{a} - o_hi{a};
  wire signed [G+1:0] xh{a} = neg{a} ? o_hi{a} - lo{a} : hi{a} - o_lo{a};
  wire [I-1:0] mce{a} = eh{a} >= 0 ? m_lo{a} : m_hi{a};
  wire [I-1:0] mcx{a} = xh{a} >= 0 ? m_hi{a} : m_lo{a};
  always @(*) if (clocks == L) begin
    assert($signed(pa_e{a}) == eh{a} && pm_e{a} == mce{a});
    assert($signed(pa_x{a}) == xh{a} && pm_x{a} == mcx{a});
  end
  // en = eh + de and ex = xh - dx, de and dx >= 0; mw = mc + or - dm, dm >= 0 (see the module docs).
  wire [G:0] de{a} = neg{a} ? ow{a} - o_lo{a} : o_hi{a} - ow{a};
  wire [G:0] dx{a} = neg{a} ? o_hi{a} - ow{a} : ow{a} - o_lo{a};
  wire [G:0] eu{a} = eh{a} >= 0 ? eh{a} : -eh{a};
  wire [G:0] xu{a} = xh{a} >= 0 ? xh{a} : -xh{a};
  wire [I-1:0] dme{a} = eh{a} >= 0 ? mw{a} - mce{a} : mce{a} - mw{a};
  wire [I-1:0] dmx{a} = xh{a} >= 0 ? mcx{a} - mw{a} : mw{a} - mcx{a};
  // The products on the probed operands, by the multiply-round unit's own expression.
  wire signed [D+I-1:0] pe{a} = $signed(pa_e{a}) * $signed({{1'b0, pm_e{a}}});
  wire signed [D+I-1:0] px{a} = $signed(pa_x{a}) * $signed({{1'b0, pm_x{a}}});
  wire [D+I-1:0] ne1{a} = eu{a} * dme{a};
  wire [D+I-1:0] ne2{a} = de{a} * mw{a};
  wire [D+I-1:0] nx1{a} = xu{a} * dmx{a};
  wire [D+I-1:0] nx2{a} = dx{a} * mw{a};
  wire signed [W-1:0] fe{a} = pe{a} + $signed({{1'b0, ne1{a}}}) + $signed({{1'b0, ne2{a}}});
  wire signed [W-1:0] fx{a} = px{a} - $signed({{1'b0, nx1{a}}}) - $signed({{1'b0, nx2{a}}});
  wire inside{a} = en{a} <= 0 && ex{a} >= 0;
  wire signed [W-1:0] ent{a} = dz{a} ? (inside{a} ? NINF : PINF)
                          : big{a} ? (en{a} > 0 ? PINF : en{a} < 0 ? NINF : 0) : fe{a};
  wire signed [W-1:0] ext{a} = dz{a} ? (inside{a} ? PINF : NINF)
                          : big{a} ? (ex{a} > 0 ? PINF : ex{a} < 0 ? NINF : 0) : fx{a};
"
        );
    }
    format!(
        "\
module formal_top(input clock);
  localparam G = {g}, D = {d}, I = {i}, T = {t}, S = {s}, L = {lat}, W = 48;
  localparam signed [W-1:0] PINF = 48'sd1 <<< 44;
  localparam signed [W-1:0] NINF = -PINF;
  reg [7:0] clocks = 8'd0;
  always @(posedge clock) if (clocks < L) clocks <= clocks + 8'd1;
{decl}  (* anyconst *) reg [T-1:0] t_min, t_max;
  wire valid_out, hit;
  wire [15:0] tag_out;
  wire [T-1:0] t_entry, t_exit;
  {module} dut(.clock(clock), .rst(1'b0), .valid_in(1'b1), .tag_in(16'd0),
{ports}    .ray_t_min(t_min), .ray_t_max(t_max),
    .valid_out(valid_out), .tag_out(tag_out), .hit(hit), .t_entry(t_entry), .t_exit(t_exit));
  // A t code on the scale 2^S of the exact products; the end codes are -inf and +inf.
  function signed [W-1:0] tx(input [T-1:0] c);
    tx = (c == {{1'b1, {{(T-1){{1'b0}}}}}}) ? NINF
       : (c == {{1'b0, {{(T-1){{1'b1}}}}}}) ? PINF : ($signed(c) <<< S);
  endfunction
{axes}  wire signed [W-1:0] e01 = ent0 > ent1 ? ent0 : ent1;
  wire signed [W-1:0] e2m = ent2 > tx(t_min) ? ent2 : tx(t_min);
  wire signed [W-1:0] entry = e01 > e2m ? e01 : e2m;
  wire signed [W-1:0] x01 = ext0 < ext1 ? ext0 : ext1;
  wire signed [W-1:0] x2m = ext2 < tx(t_max) ? ext2 : tx(t_max);
  wire signed [W-1:0] exit = x01 < x2m ? x01 : x2m;
  wire empty = lo0 > hi0 || lo1 > hi1 || lo2 > hi2;
  wire exact_hit = !empty && entry <= exit && entry != PINF && exit != NINF;
  always @(*) if (clocks == L && exact_hit) begin
    assert(hit);
    assert(tx(t_entry) <= entry);
    assert(tx(t_exit) >= exit);
  end
endmodule
",
        d = g + 1,
    )
}

/// The probes of [`slab_fix_harness`]: the operands of the six multiply-round units.
fn slab_fix_probes() -> Vec<(String, String)> {
    let mut v = vec![];
    for a in 0..3 {
        for (h, unit) in [("e", "entry"), ("x", "exit")] {
            v.push((format!("pa_{h}{a}"), format!("dut.mul_{unit}_{a}.a")));
            v.push((format!("pm_{h}{a}"), format!("dut.mul_{unit}_{a}.m")));
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formal::Expect;

    #[test]
    fn every_slab_fix_mutant_changes_the_module() {
        let fmt = FixFormat::grid(6).unwrap();
        let (module, text, lat) = rtl::export::slab_fix_ladder_default(&fmt).unwrap();
        let v = slab_fix_proofs(&fmt, &module, &text, lat, false, true).unwrap();
        assert_eq!(v.len(), 4);
        for m in &v[1..] {
            assert_eq!(m.expect, Expect::Fails);
            assert_ne!(m.sources[0].1, text, "{}", m.name);
        }
        assert!(v[0].harness.contains(&format!("{module} dut(")));
    }

    #[test]
    fn mutate_in_stays_inside_the_module() {
        let t = "module a(x);\n y = 1;\nendmodule\nmodule b(x);\n y = 1;\nendmodule\n";
        let c = mutate_in(t, "b", "y = 1;", "y = 2;").unwrap();
        assert_eq!(
            c,
            t.replacen("module b(x);\n y = 1;", "module b(x);\n y = 2;", 1)
        );
        assert!(mutate_in(t, "c", "y = 1;", "y = 2;").is_err());
    }
}
