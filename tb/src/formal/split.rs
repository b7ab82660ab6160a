//! The bundle results processor's job accounting, proven by k-induction on its exported Verilog
//! (`rtl::bundle::split`): a job is taken exactly when `start` meets `ready` without `rst`, and every
//! taken job reports `done` exactly once, within the longest job's clocks, unless a reset drops it; no
//! `done` comes without a job in progress; `ready` is low exactly while a job is in progress (and high in
//! the clock of its `done`); and the `clocks` field of a `done` is the clocks since its start.
//!
//! The harness keeps a shadow of one job: `busy` (taken, not yet reported) and `age` (clocks since the
//! start clock). `rst`, `start` and every data input (the job's bundle, boxes and active mask, the ray
//! store's writes) are free in every clock, so any ray set may be split. The properties, asserted every clock:
//! - `done` implies `busy` (no report without a job: no duplicate, no spurious `done`);
//! - `ready == !busy || done` (a start while a job runs is refused, not taken over it);
//! - `busy` implies `1 <= age <= 2L + 1 + R/2` (`L` the pair's latency, `R` the ray store's rays: the
//!   longest job, [`rtl::bundle::split::split_clocks`] of a split of every ray): a taken job is never
//!   dropped, its `done` comes in time;
//! - with `done`, `clocks == age`.
//!
//! The pair's two answer bits (`all_hit`, `all_miss`, which in two-ray mode are ray A's and B's hits)
//! are **cut points**: free in every clock, whatever the pair's datapath would answer. That is an
//! over-approximation (every behaviour of the real pair is among them), so the safety properties proven
//! on it hold for the processor; it takes the pair's multipliers out of the solver's problem (with them,
//! the base case alone ran past 4 minutes at step 19). The pair's valid and tag path, which carries the
//! rays' indices and the job's "last" mark back, stays as built.
//!
//! Two strengthening invariants make the properties inductive (without them the induction step
//! starts from unreachable states, such as a "last pair" answer in flight with no job, that feed each
//! other across back-to-back jobs): an idle processor (`busy_q` low) has no valid entry in the pair
//! and neither issues rays nor is in rays mode, and the pair's two tests (AllHit, AnyHit) hold the same
//! valid and tag in every stage. They are asserted, so proven with the rest; the harness reads them
//! through probes.
//!
//! k-induction of depth `2L + 1 + R/2 + 5` proves them in every reachable state. Mutants: a start taken
//! while a job runs (the running job overwritten, its `done` lost), a split job's `done` never raised,
//! and a decided job that leaves the processor busy.

use super::{mutant_of, Engine, Proof};

/// The longest job in clocks: a split of all `rays` rays, `2L + 1 + rays/2` (`L` the pair's latency).
pub fn longest_job(pair_latency: usize, rays: usize) -> usize {
    2 * pair_latency + 1 + rays.div_ceil(2)
}

/// The job-accounting proof of the results processor `module` (Verilog `text`), with its three mutants
/// where `mutants`.
pub fn split_proofs(
    module: &str,
    text: &str,
    quick: bool,
    mutants: bool,
) -> Result<Vec<Proof>, String> {
    let max = longest_job(
        rtl::bundle::pair_fix::BUNDLE_FIX_LATENCY,
        rtl::bundle::split::SPLIT_RAYS,
    );
    let p = Proof {
        name: format!("jobs_{module}"),
        property: format!(
            "every job taken (start with ready, no rst) reports done exactly once within {max} clocks unless reset, \
             no done without a job, ready low exactly while a job runs, clocks = its clocks"
        ),
        engine: Engine::Induction(max + 5),
        harness: split_harness(module, max),
        probes: split_probes(),
        cuts: vec!["dut.pair_all_hit".into(), "dut.pair_all_miss".into()],
        quick,
        ..Proof::on(&module, text.into())
    };
    let mut v = vec![p.clone()];
    if mutants {
        v.push(mutant_of(
            &p,
            "take",
            "a start taken while a job runs: the running job overwritten, its done lost",
            "take_job = start & ~busy_q_q & ~rst;",
            "take_job = start & ~rst;",
        ));
        v.push(mutant_of(
            &p,
            "nodone",
            "a split job's done never raised: the job dropped",
            "done_q_d = 1'b1;\n            all_hit_q_d = 1'b0;",
            "done_q_d = 1'b0;\n            all_hit_q_d = 1'b0;",
        ));
        v.push(mutant_of(
            &p,
            "busy",
            "a decided job leaves the processor busy: no job taken after it",
            "if (finish_bundle) begin\n            busy_q_d = 1'b0;",
            "if (finish_bundle) begin\n            busy_q_d = 1'b1;",
        ));
    }
    Ok(v)
}

/// The probes of [`split_harness`]: the processor's flags and the pair's valid and tag registers.
fn split_probes() -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = ["busy", "issue", "rays"]
        .iter()
        .map(|r| (format!("{r}_q"), format!("dut.{r}_q_q")))
        .collect();
    for (h, test) in [("a", "all_hit_test"), ("n", "any_hit_test")] {
        for k in 1..=3 {
            v.push((format!("v{h}{k}"), format!("dut.pair.{test}.valid_q{k}_q")));
            v.push((format!("t{h}{k}"), format!("dut.pair.{test}.tag_q{k}_q")));
        }
    }
    v
}

fn split_harness(module: &str, max: usize) -> String {
    format!(
        "\
module formal_top(input clock, input rst, input start);
  localparam MAXC = {max};
  wire ready, done, all_hit, all_miss, split;
  wire [15:0] mask;
  wire [7:0] cycles, clocks;
  {module} dut(.clock(clock), .rst(rst), .start(start),
    .ready(ready), .done(done), .all_hit(all_hit), .all_miss(all_miss), .split(split),
    .mask(mask), .cycles(cycles), .clocks(clocks));
  wire taken = start && ready && !rst;
  // The shadow job: taken and not yet reported, and its clocks since the start clock.
  reg busy = 1'b0;
  reg [7:0] age = 8'd0;
  always @(posedge clock) begin
    if (rst) begin
      busy <= 1'b0;
      age <= 8'd0;
    end else if (taken) begin
      busy <= 1'b1;
      age <= 8'd1;
    end else if (done) begin
      busy <= 1'b0;
      age <= 8'd0;
    end else if (busy)
      age <= age + 8'd1;
  end
  // The processor's own state (probes): its busy flag, the ray issue and rays-mode flags, and the valid
  // and tag registers of the pair's two tests.
  (* keep *) wire busy_q, issue_q, rays_q;
  (* keep *) wire va1, va2, va3, vn1, vn2, vn3;
  (* keep *) wire [15:0] ta1, ta2, ta3, tn1, tn2, tn3;
  always @(*) begin
    // Strengthening invariants: an idle processor has nothing in flight, and the pair's two tests
    // carry the same stream.
    if (!busy_q) assert(!issue_q && !rays_q && !va1 && !va2 && !va3);
    assert(va1 == vn1 && va2 == vn2 && va3 == vn3);
    assert(ta1 == tn1 && ta2 == tn2 && ta3 == tn3);
    assert(!done || busy);
    assert(ready == (!busy || done));
    assert(!busy || (age >= 1 && age <= MAXC));
    if (done) assert(clocks == age);
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
    fn the_longest_job_is_a_split_of_every_ray() {
        // L = 3, 16 rays: 8 pairs of rays after 2L + 1 clocks (the module documentation's 7 + k).
        assert_eq!(longest_job(3, 16), 15);
        assert_eq!(longest_job(3, 15), 15);
    }

    #[test]
    fn every_split_mutant_finds_its_site() {
        let e = rtl::export::catalog()
            .into_iter()
            .find(|e| matches!(e.family, rtl::export::Family::BundleSplit { .. }))
            .unwrap();
        let (module, text) = (e.module.clone(), e.verilog());
        let v = split_proofs(&module, &text, false, true).unwrap();
        assert_eq!(v.len(), 4);
        for m in &v[1..] {
            assert_eq!(m.expect, Expect::Fails);
            assert_ne!(m.sources[0].1, text, "{}", m.name);
        }
    }
}
