//! The fixed bundle pair's comparisons proven against full-width reference expressions: every
//! silhouette-edge compare (`rtl::bundle::edge_le`, `a * m <= b * n` on signed operands) and every
//! distance compare (`rtl::bundle::dist_le`, `e * 2^S <= t * u` with the t code's infinite ends and the
//! zero direction) of an exported pair, taken from the pair's own Verilog.
//!
//! The reference is the statement of the leaf's documentation written over 64-bit signed integers (the
//! operands are at most 63 bits together, so every product is exact there): for the edge compare
//! `le = a * m <= b * n`; for the distance compare `le = u == 0 ? e <= 0 : t == +inf ? 1 : t == -inf ? 0 :
//! e * 2^S <= t * u`. As for the multiply-round units, Yosys reduces the reference's products and the
//! leaf's (each an exact product of the same sign-extended operands) to one multiplier, so what the
//! solver settles is that the leaf's widths keep every product exact (a product one bit narrower is
//! refuted), its compare and its special cases. A combinational leaf (the 3-clock pair's) is checked at
//! depth 1 over free operands, which is the claim for every input; a leaf with its products registered
//! (the 5-clock pair's, `localparam pipelined = 1'b1`) holds its operands (`anyconst`) and is checked
//! one clock later, when its registers hold their products: again every input. The pair instantiates
//! each leaf several times (six edge compares and three distance compares per test); instances whose
//! bodies differ only in their names are one proof, and the row names how many instances it covers.
//!
//! Mutants: the left product declared one bit narrower (its top bit lost), the compare made strict, the
//! distance compare's shift one short, and its zero-direction case dropped.

use super::{module_body, mutant_of, Engine, Proof};

/// `(name, width)` of every `input`/`output` port declared in `body` (`input wire  [8:0] a;`).
fn port_widths(body: &str) -> Vec<(String, usize)> {
    body.lines()
        .filter_map(|l| {
            let l = l.trim();
            let rest = l
                .strip_prefix("input wire")
                .or_else(|| l.strip_prefix("output reg"))?;
            let rest = rest.trim();
            let (w, name) = match rest.strip_prefix('[') {
                Some(r) => {
                    let (range, name) = r.split_once(']')?;
                    let hi: usize = range.split(':').next()?.trim().parse().ok()?;
                    (hi + 1, name)
                }
                None => (1, rest),
            };
            Some((name.trim().trim_end_matches(';').to_string(), w))
        })
        .collect()
}

/// The width of port `p` among `w` (from [`port_widths`]), or an error naming `module`.
fn port_width(w: &[(String, usize)], module: &str, p: &str) -> Result<usize, String> {
    w.iter()
        .find(|(n, _)| n == p)
        .map(|x| x.1)
        .ok_or_else(|| format!("{module}: no port {p}"))
}

/// The leaf modules of `text` whose names end in `_<kind>_<k>`, grouped by their body with the name
/// taken out: `(first module, its standalone Verilog, instances covered)`.
fn leaf_groups(text: &str, kind: &str) -> Vec<(String, String, usize)> {
    let mut groups: Vec<(String, String, String, usize)> = vec![];
    for line in text.lines() {
        let Some(rest) = line.strip_prefix("module ") else {
            continue;
        };
        let Some((name, _)) = rest.split_once('(') else {
            continue;
        };
        let Some((_, k)) = name.rsplit_once(&format!("_{kind}_")) else {
            continue;
        };
        if k.is_empty() || !k.chars().all(|c| c.is_ascii_digit()) {
            continue;
        }
        let Some((_, body)) = module_body(text, name) else {
            continue;
        };
        let key = body.replace(name, "M");
        match groups.iter_mut().find(|g| g.2 == key) {
            Some(g) => g.3 += 1,
            None => groups.push((name.to_string(), format!("{body}endmodule\n"), key, 1)),
        }
    }
    groups.into_iter().map(|(n, v, _, c)| (n, v, c)).collect()
}

/// The comparison proofs of the fixed bundle pair `pair` (its exported Verilog `text`), with their
/// mutants where `mutants`; an error when the pair has no edge or distance compare.
pub fn pair_compare_proofs(
    pair: &str,
    text: &str,
    quick: bool,
    mutants: bool,
) -> Result<Vec<Proof>, String> {
    let mut v = vec![];
    let edges = leaf_groups(text, "edge_cmp");
    let dists = leaf_groups(text, "dist_cmp");
    if edges.is_empty() || dists.is_empty() {
        return Err(format!("{pair}: no edge_cmp or dist_cmp modules"));
    }
    for (module, body, n) in edges {
        let reg = registered(&body);
        let w = port_widths(&body);
        let width = |p: &str| port_width(&w, &module, p);
        let (vb, ub) = (width("a")?, width("m")?);
        let p = Proof {
            name: format!("edge_{module}"),
            property: format!(
                "edge compare: le = a * m <= b * n, signed, exact ({n} instances in {pair})"
            ),
            format: format!("a, b {vb} bits; m, n {ub} bits"),
            harness: edge_harness(&module, vb, ub, reg),
            engine: Engine::Bmc(1 + reg as usize),
            quick,
            ..Proof::on(&module, body.clone())
        };
        if mutants {
            let pw = vb + ub;
            v.push(mutant_of(
                &p,
                "narrow",
                "the left product one bit narrower (its top bit lost)",
                &format!("wire signed [{}:0] lhs = a_x * m_x;", pw - 1),
                &format!("wire signed [{}:0] lhs = a_x * m_x;", pw - 2),
            ));
            v.push(mutant_of(
                &p,
                "strict",
                "le computed as lt: equal products not less-or-equal",
                "le = lhs_u <= rhs_u;",
                "le = lhs_u < rhs_u;",
            ));
        }
        v.insert(v.len() - if mutants { 2 } else { 0 }, p);
    }
    for (module, body, n) in dists {
        let reg = registered(&body);
        let w = port_widths(&body);
        let width = |p: &str| port_width(&w, &module, p);
        let (vb, tb, ub) = (width("e")?, width("t")?, width("u")?);
        let shift_line = body
            .lines()
            .map(str::trim)
            .find(|l| l.starts_with("localparam  shift = 8'h"))
            .ok_or_else(|| format!("{module}: no `localparam shift`"))?
            .to_string();
        let s = shift_line
            .trim_start_matches("localparam  shift = 8'h")
            .trim_end_matches(';');
        let s = usize::from_str_radix(s, 16).map_err(|_| format!("{module}: `{shift_line}`"))?;
        let p = Proof {
            name: format!("dist_{module}"),
            property: format!(
                "distance compare: le = u == 0 ? e <= 0 : t == +inf ? 1 : t == -inf ? 0 : e * 2^{s} <= t * u, exact ({n} instances in {pair})"
            ),
            format: format!("e {vb} bits, t {tb} bits, u {ub} bits"),
            harness: dist_harness(&module, vb, tb, ub, s, reg),
            engine: Engine::Bmc(1 + reg as usize),
            quick,
            ..Proof::on(&module, body.clone())
        };
        if mutants {
            v.push(mutant_of(
                &p,
                "shift",
                "the shift one short: e * 2^(S-1) compared",
                &shift_line,
                &format!("localparam  shift = 8'h{:x};", s - 1),
            ));
            v.push(mutant_of(
                &p,
                "zero",
                "the zero-direction case dropped (t * 0 with t infinite)",
                &format!("if (u == {ub}'d0)"),
                "if (1'b0)",
            ));
        }
        v.insert(v.len() - if mutants { 2 } else { 0 }, p);
    }
    Ok(v)
}

/// The leaf registers its products (its `pipelined` localparam is set).
fn registered(body: &str) -> bool {
    body.lines()
        .any(|l| l.trim() == "localparam  pipelined = 1'b1;")
}

/// `past`, high from the first clock on, and the guard of the assertions: always for a combinational
/// leaf, from the first clock on for a registered one.
fn checked_when(reg: bool) -> (&'static str, &'static str) {
    (
        "  reg past = 1'b0;\n  always @(posedge clock) past <= 1'b1;\n",
        if reg { "if (past) " } else { "" },
    )
}

fn edge_harness(module: &str, vb: usize, ub: usize, reg: bool) -> String {
    let (past, when) = checked_when(reg);
    format!(
        "\
module formal_top(input clock);
  (* anyconst *) reg signed [{v1}:0] a, b;
  (* anyconst *) reg signed [{u1}:0] m, n;
  wire le;
{past}  {module} dut(.clock(clock), .a(a), .m(m), .b(b), .n(n), .le(le));
  wire signed [63:0] l = a * m;
  wire signed [63:0] r = b * n;
  always @(*) {when}assert(le == (l <= r));
endmodule
",
        v1 = vb - 1,
        u1 = ub - 1,
    )
}

fn dist_harness(module: &str, vb: usize, tb: usize, ub: usize, s: usize, reg: bool) -> String {
    let (past, when) = checked_when(reg);
    format!(
        "\
module formal_top(input clock);
  (* anyconst *) reg signed [{v1}:0] e;
  (* anyconst *) reg signed [{t1}:0] t;
  (* anyconst *) reg signed [{u1}:0] u;
  wire le;
{past}  {module} dut(.clock(clock), .e(e), .t(t), .u(u), .le(le));
  localparam signed [63:0] PINF = (64'sd1 <<< {t1}) - 1;
  localparam signed [63:0] NINF = -(64'sd1 <<< {t1});
  wire signed [63:0] lhs = e * (64'sd1 <<< {s});
  wire signed [63:0] rhs = t * u;
  wire want = (u == 0) ? (e <= 0) : (t == PINF) ? 1'b1 : (t == NINF) ? 1'b0 : (lhs <= rhs);
  always @(*) {when}assert(le == want);
endmodule
",
        v1 = vb - 1,
        t1 = tb - 1,
        u1 = ub - 1,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formal::Expect;

    #[test]
    fn port_widths_reads_declarations() {
        let b = "module m(a,le);\n    input wire  [8:0] a;\n    output reg  le;\n";
        assert_eq!(
            port_widths(b),
            vec![("a".to_string(), 9), ("le".to_string(), 1)]
        );
    }

    #[test]
    fn a_pair_gives_one_proof_per_distinct_compare_with_mutants() {
        let fmt = golden::format::fixed::FixFormat::b8();
        let e = rtl::export::find(&format!("bundle_fix_{}_d6", fmt.name())).unwrap();
        let text = e.verilog();
        let v = pair_compare_proofs(&e.module, &text, false, true).unwrap();
        let proofs: Vec<_> = v.iter().filter(|p| p.mutant.is_none()).collect();
        assert!(proofs.iter().any(|p| p.name.starts_with("edge_")));
        assert!(proofs.iter().any(|p| p.name.starts_with("dist_")));
        // Every instance is covered: 6 edge and 3 distance compares in each of the two tests.
        let covered = |kind: &str| -> usize {
            proofs
                .iter()
                .filter(|p| p.name.starts_with(kind))
                .map(|p| {
                    let s = p.property.rsplit_once('(').unwrap().1;
                    s.split(' ').next().unwrap().parse::<usize>().unwrap()
                })
                .sum()
        };
        assert_eq!(covered("edge_"), 12);
        assert_eq!(covered("dist_"), 6);
        assert_eq!(v.len(), proofs.len() * 3);
        for m in v.iter().filter(|p| p.mutant.is_some()) {
            assert_eq!(m.expect, Expect::Fails);
        }
    }
}
