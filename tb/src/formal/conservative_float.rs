//! Conservativeness of the float slab tester, proven end to end on its exported Verilog in a small
//! format (E5M3, the smallest of the float ladder): for every input the tester accepts, every ray of the
//! input's intervals that hits the box exactly is reported as a hit, with an interval that encloses the
//! exact one. The fixed tester's proof ([`super::conservative`]) explains the method; this is its float
//! form.
//!
//! # Inputs accepted, witnesses, exact test
//! The inputs are free and held: no NaN anywhere, finite origin ends with `o_lo <= o_hi`, inverse ends
//! non-negative with `m_lo <= m_hi` (`+inf` allowed: `m_lo = m_hi = +inf` is a zero direction, `m_hi =
//! +inf` alone an inverse beyond the format), box faces anything but NaN (infinite faces and empty boxes
//! included), `t_min`, `t_max` anything but NaN. Per axis the witness ray has a finite origin `ow` of the
//! format in `[o_lo, o_hi]` and either a zero direction (the both-infinite code), an inverse beyond
//! every value (`m_hi` infinite), or a finite inverse `mw` of the format in `[m_lo, m_hi]` (`+0` only as
//! the limit when `m_lo` is `+0`). Format values are the corners of the intervals, so as in the fixed
//! proof the bilinear exact entry and exit take their extremes at witnesses.
//!
//! The exact test works in integers: a finite value of the format is `sig * 2^(e' - 1)` units of
//! `2^-F` (`F = bias - 1 + M`, the smallest subnormal), products are in units of `2^-2F`, and the
//! infinities are sentinels beyond every finite value. Distances to an infinite face are infinite
//! whatever the (positive) inverse; a zero direction leaves the axis unconstrained when the origin lies
//! in the slab and empties it otherwise.
//!
//! # The chain the harness checks
//! The tester computes `e = RD(near - o_hi)` (or `RD(o_lo - near)`), then `RD(e * m_c)` with `m_c =
//! e >= 0 ? m_lo : m_hi` (`-0` counts as non-negative), `0 x inf` as `-inf`; the exit likewise with RU
//! and the other ends. Through probes on the adders' results and the multipliers' operands the harness
//! asserts: the adder's result is not NaN and lies on its side of the exact difference (`e <= near -
//! o_hi`, `x >= far - o_lo`), and each multiplier receives that result and the interval rule's inverse
//! end. The witness's exact entry is then written as `P + |e| * |mw - m_c| + de * mw` with `P = e * m_c`
//! and `de = (near - ow) - e >= 0` (the exit as `P - |x| * |mw - m_c| - dx * mw`), a ring identity, so
//! the solver compares adders rather than products; where `e` or `m_c` is infinite the exact product is
//! taken directly (the tester answers `-inf`/`+inf` there). Every product has a format significand
//! (`M + 1` bits) as one factor.
//!
//! The property, `L` clocks after the inputs (a feed-forward pipeline with held inputs): an exact hit
//! implies `hit`, `t_entry <= entry` and `t_exit >= exit`, and the outputs are never NaN.
//!
//! # A chain of proofs ([`Piece`])
//! One harness, three groups of assertions, eight proofs; each proof asserts its group and assumes the
//! groups before it:
//! 1. `stages`: the stage facts above (adders, operands, no NaN out);
//! 2. `axis<a><e|x>`, six proofs: given the stage facts, axis `a`'s entry product (NaN taken as `-inf`)
//!    is at most the witness's exact entry, or its exit product at least the exact exit;
//! 3. `result`: given the stage facts and all six axis facts, the property.
//!
//! The composition is sound because no proof assumes what it or a later one asserts: `stages` assumes
//! nothing, each axis proof only the stage facts, `result` the facts the seven before it prove, all for
//! every input and witness of the same harness. Split this way each proof takes 1 to 2.5 minutes; the
//! axis and result facts asserted together (with the stage facts assumed) ran past 4 minutes without a
//! verdict.
//!
//! Mutants: axis 0's entry adder rounding up (RU in place of RD), axis 0's entry multiplier taking the
//! wrong inverse end, and the final compare made strict.

use super::{mutant_with, mutate, Engine, Proof};
use golden::format::float::FloatFormat;

/// What a piece of the chain asserts; the pieces before it are assumed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Piece {
    /// The stage facts: adders on their side and not NaN, multipliers' operands by the interval rule,
    /// outputs not NaN.
    Stages,
    /// One axis's entry (`false`) or exit (`true`) product encloses the witness's exact one.
    Axis(usize, bool),
    /// The tester's `hit` and interval, given the stage facts and every axis.
    Result,
}

impl Piece {
    /// Every piece, in the order of the chain.
    pub fn all() -> Vec<Piece> {
        let mut v = vec![Piece::Stages];
        for a in 0..3 {
            v.push(Piece::Axis(a, false));
            v.push(Piece::Axis(a, true));
        }
        v.push(Piece::Result);
        v
    }

    fn tag(&self) -> String {
        match *self {
            Piece::Stages => "stages".into(),
            Piece::Axis(a, exit) => format!("axis{a}{}", if exit { "x" } else { "e" }),
            Piece::Result => "result".into(),
        }
    }

    fn property(&self) -> String {
        match *self {
            Piece::Stages => "conservative, stage facts: RD/RU differences on their side, never NaN; \
                              each multiplier gets its difference and the interval rule's inverse end; \
                              no NaN out"
                .into(),
            Piece::Axis(a, exit) => format!(
                "conservative, axis {a} {}: the tester's {} product (0 x inf as {}) {} the exact one \
                 of every witness ray (given the stage facts)",
                if exit { "exit" } else { "entry" },
                if exit { "RU" } else { "RD" },
                if exit { "+inf" } else { "-inf" },
                if exit { "at least" } else { "at most" },
            ),
            Piece::Result => "conservative: every ray of the input intervals that hits exactly is a \
                              hit, [t_entry, t_exit] encloses its exact interval (given the stage facts \
                              and every axis)"
                .into(),
        }
    }
}

/// The conservativeness proofs of the float slab tester `module` (Verilog `text`, latency `lat`) in
/// format `f`: one proof per [`Piece`] of the chain, with the mutants where `mutants` (the entry
/// difference rounded up and the wrong inverse end, refuted by the stage facts; axis 0's entry product
/// rounded up, refuted by its axis; the strict final compare, refuted by the result).
pub fn slab_float_proofs(
    f: &FloatFormat,
    module: &str,
    text: &str,
    lat: usize,
    quick: bool,
    mutants: bool,
) -> Result<Vec<Proof>, String> {
    let err = |e: String| format!("mutant of {module}: {e}");
    let mut v = vec![];
    for piece in Piece::all() {
        let p = Proof {
            name: format!("cons_{module}_{}", piece.tag()),
            property: piece.property(),
            format: f.name(),
            engine: Engine::Bmc(lat + 1),
            harness: slab_float_harness(f, module, lat, piece),
            probes: slab_float_probes(),
            quick,
            ..Proof::on(&module, text.into())
        };
        v.push(p.clone());
        if !mutants {
            continue;
        }
        let flip = |unit: &str| {
            super::conservative::mutate_in(
                text,
                &format!("{module}_{unit}_round"),
                "localparam  rd = 1'b1;\n    localparam  ru = 1'b0;",
                "localparam  rd = 1'b0;\n    localparam  ru = 1'b1;",
            )
            .map_err(err)
        };
        match piece {
            Piece::Stages => {
                v.push(mutant_with(
                    &p,
                    "ru",
                    "rounding direction flipped: axis 0's entry difference rounded up",
                    flip("add_e_0")?,
                ));
                let changed = mutate(text, "mul_e_0_b = m_hi_d_0_q;", "mul_e_0_b = m_lo_d_0_q;")
                    .map_err(err)?;
                v.push(mutant_with(
                    &p,
                    "mend",
                    "wrong interval end: axis 0's entry for a negative distance multiplied by m_lo",
                    changed,
                ));
            }
            Piece::Axis(0, false) => v.push(mutant_with(
                &p,
                "ru",
                "rounding direction flipped: axis 0's entry product rounded up",
                flip("mul_e_0")?,
            )),
            Piece::Result => {
                let changed = mutate(text, "cmp9_2_le & ", "cmp9_2_lt & ").map_err(err)?;
                v.push(mutant_with(
                    &p,
                    "strict",
                    "hit on entry < exit: a grazing ray (entry = exit) missed",
                    changed,
                ));
            }
            _ => {}
        }
    }
    Ok(v)
}

/// The probes: each axis's two adders' results and two multipliers' operands.
fn slab_float_probes() -> Vec<(String, String)> {
    let mut v = vec![];
    for a in 0..3 {
        for h in ["e", "x"] {
            v.push((format!("y{h}{a}"), format!("dut.add_{h}_{a}.y")));
            v.push((format!("ma{h}{a}"), format!("dut.mul_{h}_{a}.a")));
            v.push((format!("mb{h}{a}"), format!("dut.mul_{h}_{a}.b")));
            v.push((format!("z{h}{a}"), format!("dut.mul_{h}_{a}.y")));
        }
    }
    v
}

fn slab_float_harness(f: &FloatFormat, module: &str, lat: usize, piece: Piece) -> String {
    // Each group of properties is asserted by its piece, assumed by the pieces after it, left out by
    // those before.
    let kw = |group: u8| -> &'static str {
        let at = match piece {
            Piece::Stages => 0,
            Piece::Axis(..) => 1,
            Piece::Result => 2,
        };
        match group.cmp(&at) {
            std::cmp::Ordering::Less => "assume",
            std::cmp::Ordering::Equal => "assert",
            std::cmp::Ordering::Greater => "//",
        }
    };
    let (st, fin) = (kw(0), kw(2));
    let axis_kw = |a: usize, exit: bool| match piece {
        Piece::Axis(b, x) if (b, x) == (a, exit) => "assert",
        Piece::Axis(..) | Piece::Stages => "//",
        Piece::Result => "assume",
    };
    let (e, m) = (f.e as usize, f.m as usize);
    let n = 1 + e + m;
    let bias = (1usize << (e - 1)) - 1;
    let fr = bias - 1 + m;
    let mut decl = String::new();
    let mut ports = String::new();
    let mut axes = String::new();
    for a in 0..3 {
        decl += &format!(
            "  (* anyconst *) reg [N-1:0] o_lo{a}, o_hi{a}, lo{a}, hi{a}, m_lo{a}, m_hi{a}, ow{a}, mw{a};
  (* anyconst *) reg neg{a}, dz{a}, big{a};
  (* keep *) wire [N-1:0] ye{a}, yx{a}, mae{a}, max{a}, mbe{a}, mbx{a}, ze{a}, zx{a};
  // The products as the tester takes them: 0 x inf (NaN) as -inf for an entry, +inf for an exit.
  wire [N-1:0] zfe{a} = nan(ze{a}) ? {{1'b1, {{(N-M-1){{1'b1}}}}, {{M{{1'b0}}}}}} : ze{a};
  wire [N-1:0] zfx{a} = nan(zx{a}) ? {{1'b0, {{(N-M-1){{1'b1}}}}, {{M{{1'b0}}}}}} : zx{a};
"
        );
        ports += &format!(
            "    .ray_o_lo_{a}(o_lo{a}), .ray_o_hi_{a}(o_hi{a}), .ray_m_lo_{a}(m_lo{a}), \
             .ray_m_hi_{a}(m_hi{a}), .ray_neg_{a}(neg{a}), .box_lo_{a}(lo{a}), .box_hi_{a}(hi{a}),\n"
        );
        axes += &format!(
            "  // Axis {a}: accepted inputs and the witness.
  always @(*) begin
    assume(!nan(o_lo{a}) && !nan(o_hi{a}) && !nan(lo{a}) && !nan(hi{a}) && !nan(m_lo{a}) && !nan(m_hi{a}));
    assume(!inf(o_lo{a}) && !inf(o_hi{a}) && fx(o_lo{a}) <= fx(o_hi{a}));
    assume(!m_lo{a}[N-1] && !m_hi{a}[N-1] && fx(m_lo{a}) <= fx(m_hi{a}));
    assume(!nan(ow{a}) && !inf(ow{a}) && fx(o_lo{a}) <= fx(ow{a}) && fx(ow{a}) <= fx(o_hi{a}));
    assume(dz{a} ? (inf(m_lo{a}) && !big{a}) : big{a} ? (!inf(m_lo{a}) && inf(m_hi{a}))
      : (!inf(m_lo{a}) && !nan(mw{a}) && !inf(mw{a}) && !mw{a}[N-1]
         && fx(m_lo{a}) <= fx(mw{a}) && fx(mw{a}) <= fx(m_hi{a})));
  end
  // Exact distances (units 2^-F; infinite faces give sentinels): the witness's and the tester's.
  wire signed [W-1:0] en{a} = neg{a} ? sub(ow{a}, hi{a}) : sub(lo{a}, ow{a});
  wire signed [W-1:0] ex{a} = neg{a} ? sub(ow{a}, lo{a}) : sub(hi{a}, ow{a});
  wire signed [W-1:0] eh{a} = neg{a} ? sub(o_lo{a}, hi{a}) : sub(lo{a}, o_hi{a});
  wire signed [W-1:0] xh{a} = neg{a} ? sub(o_hi{a}, lo{a}) : sub(hi{a}, o_lo{a});
  wire [N-1:0] mce{a} = nonneg(ye{a}) ? m_lo{a} : m_hi{a};
  wire [N-1:0] mcx{a} = nonneg(yx{a}) ? m_hi{a} : m_lo{a};
  always @(*) if (clocks == L) begin
    {st}(!nan(ye{a}) && fx(ye{a}) <= eh{a});
    {st}(!nan(yx{a}) && fx(yx{a}) >= xh{a});
    {st}(mae{a} == ye{a} && mbe{a} == mce{a});
    {st}(max{a} == yx{a} && mbx{a} == mcx{a});
  end
  // The witness's exact entry and exit (units 2^-2F).
  wire signed [W-1:0] dme{a} = fx(mw{a}) >= fx(mce{a}) ? fx(mw{a}) - fx(mce{a}) : fx(mce{a}) - fx(mw{a});
  wire signed [W-1:0] dmx{a} = fx(mw{a}) >= fx(mcx{a}) ? fx(mw{a}) - fx(mcx{a}) : fx(mcx{a}) - fx(mw{a});
  wire signed [W-1:0] fe{a} = prod(ye{a}, mce{a}) + fmul(ye{a}, dme{a}, 1'b1) + fmul(mw{a}, en{a} - fx(ye{a}), 1'b0);
  wire signed [W-1:0] fxx{a} = prod(yx{a}, mcx{a}) - fmul(yx{a}, dmx{a}, 1'b1) - fmul(mw{a}, fx(yx{a}) - ex{a}, 1'b0);
  wire expand_e{a} = !inf(ye{a}) && !inf(mce{a});
  wire expand_x{a} = !inf(yx{a}) && !inf(mcx{a});
  wire inside{a} = en{a} <= 0 && ex{a} >= 0;
  wire signed [W-1:0] ent{a} = dz{a} ? (inside{a} ? NINF : PINF)
    : big{a} ? (en{a} > 0 ? PINF : en{a} < 0 ? NINF : 0)
    : (en{a} == PINF || en{a} == NINF) ? en{a}
    : expand_e{a} ? fe{a} : fmul(mw{a}, en{a}, 1'b0);
  wire signed [W-1:0] ext{a} = dz{a} ? (inside{a} ? PINF : NINF)
    : big{a} ? (ex{a} > 0 ? PINF : ex{a} < 0 ? NINF : 0)
    : (ex{a} == PINF || ex{a} == NINF) ? ex{a}
    : expand_x{a} ? fxx{a} : fmul(mw{a}, ex{a}, 1'b0);
  always @(*) if (clocks == L) begin
    {ke}(tx(zfe{a}) <= ent{a});
    {kx}(tx(zfx{a}) >= ext{a});
  end
",
            ke = axis_kw(a, false),
            kx = axis_kw(a, true),
        );
    }
    format!(
        "\
module formal_top(input clock);
  localparam N = {n}, M = {m}, F = {fr}, L = {lat}, W = 80;
  localparam signed [W-1:0] PINF = 80'sd1 <<< 76;
  localparam signed [W-1:0] NINF = -PINF;
  reg [7:0] clocks = 8'd0;
  always @(posedge clock) if (clocks < L) clocks <= clocks + 8'd1;
  function nan(input [N-1:0] c);
    nan = (&c[N-2:M]) && (|c[M-1:0]);
  endfunction
  function inf(input [N-1:0] c);
    inf = (&c[N-2:M]) && !(|c[M-1:0]);
  endfunction
  function nonneg(input [N-1:0] c);
    nonneg = !c[N-1] || !(|c[N-2:0]);
  endfunction
  function [M:0] sig(input [N-1:0] c);
    sig = (|c[N-2:M]) ? {{1'b1, c[M-1:0]}} : {{1'b0, c[M-1:0]}};
  endfunction
  function [7:0] sh(input [N-1:0] c);
    sh = (|c[N-2:M]) ? c[N-2:M] - 1 : 0;
  endfunction
  // The value of a code in units of 2^-F; infinities as sentinels.
  function signed [W-1:0] fx(input [N-1:0] c);
    reg signed [W-1:0] mag;
    begin
      mag = $signed({{{{(W-M-1){{1'b0}}}}, sig(c)}}) <<< sh(c);
      fx = inf(c) ? (c[N-1] ? NINF : PINF) : (c[N-1] ? -mag : mag);
    end
  endfunction
  // a - b exactly (units 2^-F), -inf/+inf when either is infinite (never both here: one is an origin).
  function signed [W-1:0] sub(input [N-1:0] a, input [N-1:0] b);
    sub = inf(a) ? fx(a) : inf(b) ? -fx(b) : fx(a) - fx(b);
  endfunction
  // a * b for finite codes, exactly (units 2^-2F).
  function signed [W-1:0] prod(input [N-1:0] a, input [N-1:0] b);
    reg [2*M+1:0] pp;
    reg signed [W-1:0] mag;
    begin
      pp = sig(a) * sig(b);
      mag = $signed({{{{(W-2*M-2){{1'b0}}}}, pp}}) <<< (sh(a) + sh(b));
      prod = (a[N-1] ^ b[N-1]) ? -mag : mag;
    end
  endfunction
  // |code| * v (abs) or code * v (units 2^-F times 2^-F); v finite.
  function signed [W-1:0] fmul(input [N-1:0] c, input signed [W-1:0] v, input abs);
    reg signed [W-1:0] mag;
    begin
      mag = (v * $signed({{1'b0, sig(c)}})) <<< sh(c);
      fmul = (!abs && c[N-1]) ? -mag : mag;
    end
  endfunction
  function signed [W-1:0] tx(input [N-1:0] c);
    tx = inf(c) ? fx(c) : (fx(c) <<< F);
  endfunction
{decl}  (* anyconst *) reg [N-1:0] t_min, t_max;
  always @(*) assume(!nan(t_min) && !nan(t_max));
  wire valid_out, hit;
  wire [15:0] tag_out;
  wire [N-1:0] t_entry, t_exit;
  {module} dut(.clock(clock), .rst(1'b0), .valid_in(1'b1), .tag_in(16'd0),
{ports}    .ray_t_min(t_min), .ray_t_max(t_max),
    .valid_out(valid_out), .tag_out(tag_out), .hit(hit), .t_entry(t_entry), .t_exit(t_exit));
{axes}  wire signed [W-1:0] e01 = ent0 > ent1 ? ent0 : ent1;
  wire signed [W-1:0] e2m = ent2 > tx(t_min) ? ent2 : tx(t_min);
  wire signed [W-1:0] entry = e01 > e2m ? e01 : e2m;
  wire signed [W-1:0] x01 = ext0 < ext1 ? ext0 : ext1;
  wire signed [W-1:0] x2m = ext2 < tx(t_max) ? ext2 : tx(t_max);
  wire signed [W-1:0] exit = x01 < x2m ? x01 : x2m;
  wire empty = fx(lo0) > fx(hi0) || fx(lo1) > fx(hi1) || fx(lo2) > fx(hi2);
  wire exact_hit = !empty && entry <= exit && entry != PINF && exit != NINF;
  always @(*) if (clocks == L) begin
    {st}(!nan(t_entry) && !nan(t_exit));
    if (exact_hit) begin
      {fin}(hit);
      {fin}(tx(t_entry) <= entry);
      {fin}(tx(t_exit) >= exit);
    end
  end
endmodule
"
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formal::Expect;

    #[test]
    fn every_slab_float_mutant_changes_the_module() {
        let f = FloatFormat { e: 5, m: 3 };
        let (module, text, lat) = rtl::export::slab_float_ladder_default(&f).unwrap();
        let v = slab_float_proofs(&f, &module, &text, lat, false, true).unwrap();
        assert_eq!(v.iter().filter(|p| p.mutant.is_none()).count(), 8);
        assert_eq!(v.iter().filter(|p| p.mutant.is_some()).count(), 4);
        for m in v.iter().filter(|p| p.mutant.is_some()) {
            assert_eq!(m.expect, Expect::Fails);
            assert_ne!(m.sources[0].1, text, "{}", m.name);
        }
        // Each piece asserts its own group and assumes the earlier ones.
        let stages = &v[0].harness;
        assert!(stages.contains("    assert(mae0 == ye0") && stages.contains("    //(tx(zfe0)"));
        let result = v.iter().find(|p| p.name.ends_with("_result")).unwrap();
        assert!(result.harness.contains("    assume(mae0 == ye0"));
        assert!(result.harness.contains("    assume(tx(zfx2) >= ext2)"));
        assert!(result.harness.contains("      assert(hit);"));
    }
}
