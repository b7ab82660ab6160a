//! The fraction option of the fixed cull-plane tester (`rtl::plane::quot::PlaneQuot`): the rust-hdl
//! simulation bit for bit against its model `node_quot` (latency, tag order, bubbles), every result's
//! values equal to `golden::plane::fix::cull_fix_quotients` (the option's model of record), and the exported
//! Verilog (lint, Icarus, Verilator cross-simulation against rust-hdl and the model). Vectors: cases from
//! `golden::plane::gen` (uniform and adversarial) with one in eight raw.

use golden::exact::{ExactHit, Ext};
use golden::format::fixed::FixFormat;
use golden::plane::fix::{cull_fix_quotients, CullFixFormat, FixNode, NodeFixRay};
use golden::plane::quot::{node_quot, quot_value, PlaneQuotOut, Quot};
use golden::slab::fix::slab_fix;
use rtl::plane::ports::PlaneQuotPorts;
use rtl::plane::quot::PlaneQuotIo;
use std::cell::Cell;
use tb::dut::run_checked;
use tb::plane::fix::{node_fix_vectors, CullFixCtx};
use tb::rtl_sim::TesterSim;
use tb::xsim::{xsim, BlockCtx, TesterCtx};

/// The fraction option's testbench context: the plane format and plane count of [`CullFixCtx`], the
/// model [`node_quot`], results as the packed fraction words of the ports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct QuotCtx(CullFixCtx);

impl QuotCtx {
    fn new(fmt: FixFormat, k: usize) -> Self {
        QuotCtx(CullFixCtx {
            cf: CullFixFormat::over(fmt),
            k,
        })
    }
    fn cf(&self) -> &CullFixFormat {
        &self.0.cf
    }
    /// The interval of a result in exact world units.
    fn interval(&self, r: &NodeFixRay, o: &PlaneQuotOut) -> Option<(Ext, Ext)> {
        let w = |f: &Quot| match quot_value(self.cf(), f) {
            Ext::Fin(v) => Ext::Fin(v * golden::exact::dyadic(1, r.ray.t_exp)),
            inf => inf,
        };
        Some((w(&o.t_entry), w(&o.t_exit)))
    }
    fn vectors(&self, seed: u64, n: u64) -> impl Iterator<Item = Option<(NodeFixRay, FixNode)>> {
        node_fix_vectors(self.0, seed, n, true)
    }
}

/// Does `cull_fix_quotients` have a value for this node? Not for an inverted direction interval (only
/// raw vectors have one): it can make a chosen `den` zero.
fn fractions_defined(r: &NodeFixRay) -> bool {
    (0..3).all(|a| r.dir.lo[a] <= r.dir.hi[a])
}

/// `node_quot` against `cull_fix_quotients`: the same decision and the same interval, value for value.
fn agrees_with_fractions(
    c: &QuotCtx,
    r: &NodeFixRay,
    n: &FixNode,
    o: &PlaneQuotOut,
) -> Result<(), String> {
    let cf = c.cf();
    let slab = slab_fix(&cf.base, &r.ray, &n.b);
    let (hit, entry, exit) =
        cull_fix_quotients(cf, &r.ray, &r.dir, &n.b, &n.planes[..c.0.k], &slab);
    let got = (o.hit, quot_value(cf, &o.t_entry), quot_value(cf, &o.t_exit));
    if got == (hit, entry.clone(), exit.clone()) {
        Ok(())
    } else {
        Err(format!(
            "{}: node_quot {o:?} = {got:?}, cull_fix_quotients ({hit}, {entry:?}, {exit:?})\n  ray {r:?}\n  node {n:?}",
            c.name()
        ))
    }
}

impl BlockCtx for QuotCtx {
    type Ray = NodeFixRay;
    type Box = FixNode;
    type Out = PlaneQuotOut;
    type Ports = PlaneQuotPorts;
    fn name(&self) -> String {
        rtl::names::plane_quot_module(self.cf(), self.0.k)
    }
    fn ports(&self) -> PlaneQuotPorts {
        PlaneQuotPorts {
            sb: self.cf().s_bits() as usize,
            t: self.cf().base.t as usize,
        }
    }
    /// `node_quot`, checked against `cull_fix_quotients` wherever that has a value.
    fn model(&self, r: &NodeFixRay, n: &FixNode) -> PlaneQuotOut {
        let o = node_quot(self.cf(), self.0.k, r, n);
        if fractions_defined(r) {
            agrees_with_fractions(self, r, n, &o).unwrap_or_else(|e| panic!("{e}"));
        }
        o
    }
    fn counts_as_hit(&self, o: &PlaneQuotOut) -> bool {
        o.hit
    }
}

impl TesterCtx for QuotCtx {
    fn world(&self, r: &NodeFixRay, o: &PlaneQuotOut) -> (bool, f64, f64) {
        let w = |f: &Quot| quot_value(self.cf(), f).to_f64() * 2f64.powi(r.ray.t_exp);
        (o.hit, w(&o.t_entry), w(&o.t_exit))
    }
    fn judge(
        &self,
        r: &NodeFixRay,
        o: &PlaneQuotOut,
        exact: &ExactHit,
    ) -> golden::slab::check::Verdict {
        golden::slab::check::judge(exact, o.hit, || self.interval(r, o))
    }
}

/// Streams `n` vectors through the rust-hdl simulation of `S`, every result checked bit for bit against
/// `node_quot` and, through [`QuotCtx::model`], against `cull_fix_quotients`.
fn rtl_matches_model_and_fractions<S: PlaneQuotIo>(fmt: FixFormat, seed: u64) {
    const N: u64 = 12_000;
    let c = QuotCtx::new(fmt, S::PLANES);
    // Vectors checked against cull_fix_quotients, nodes the planes cull after the slab test kept them,
    // results with a plane's entry, with a plane's exit.
    let counts: [Cell<u64>; 4] = Default::default();
    let mut dut = TesterSim::wrap(S::for_format(c.cf()));
    let done = run_checked(&mut dut, c.vectors(seed, N), |v| {
        let o = c.model(&v.0, &v.1);
        let slab_hit = slab_fix(&c.cf().base, &v.0.ray, &v.1.b).hit;
        let seen = [
            fractions_defined(&v.0),
            slab_hit && !o.hit,
            o.t_entry.den != 0,
            o.t_exit.den != 0,
        ];
        for (n, yes) in counts.iter().zip(seen) {
            n.set(n.get() + u64::from(yes));
        }
        o
    })
    .unwrap_or_else(|e| panic!("{}: {e}", c.name()));
    assert_eq!(done, N as usize);
    let [exact, culled, entries, exits] = counts.map(|x| x.get());
    eprintln!(
        "{}: {N} vectors, {exact} of them against cull_fix_quotients; {culled} plane culls, {entries} \
         plane entries, {exits} plane exits",
        c.name()
    );
    assert!(
        exact >= 10_000,
        "only {exact} checked against cull_fix_quotients"
    );
    assert!(culled > 0 && entries > 0 && exits > 0, "degenerate vectors");
}

#[test]
fn rtl_matches_model_and_fractions_b12_k1() {
    rtl_matches_model_and_fractions::<rtl::PlaneQuotB12<1>>(FixFormat::b12(), 21);
}

#[test]
fn rtl_matches_model_and_fractions_b12_k4() {
    rtl_matches_model_and_fractions::<rtl::PlaneQuotB12<4>>(FixFormat::b12(), 22);
}

/// The model `node_quot` against `cull_fix_quotients` on more vectors than the RTL runs: every preset,
/// one to eight planes.
#[test]
fn model_equals_cull_fix_fractions_every_preset() {
    for fmt in FixFormat::presets() {
        for k in [1, 4, 8] {
            let c = QuotCtx::new(fmt, k);
            let checked = c
                .vectors(30 + k as u64, 40_000)
                .flatten()
                .filter(|(r, _)| fractions_defined(r))
                .map(|(r, n)| {
                    let o = node_quot(c.cf(), k, &r, &n);
                    agrees_with_fractions(&c, &r, &n, &o).unwrap_or_else(|e| panic!("{e}"))
                })
                .count();
            assert!(checked > 35_000, "{}: {checked}", c.name());
        }
    }
}

/// The fraction option is conservative: against the exact clip by the stored planes, nothing it culls
/// is truly kept and its interval encloses the exact one; no ray that truly hits the node's triangle is
/// culled (uniform and adversarial cases, b12 with four planes). It culls at least what the table culls.
#[test]
fn fraction_option_is_conservative() {
    let c = QuotCtx::new(FixFormat::b12(), 4);
    let map = tb::plane::fix::cull_map(c.cf().base);
    let mut gen = golden::plane::gen::CullGen::new(40, 0.5, 4, tb::plane::fix::CULL_R);
    let (mut n, mut culled, mut table_culled) = (0, 0, 0);
    while n < 20_000 {
        let case = gen.case();
        let Ok((r, node, planes)) = tb::plane::fix::fix_case(c.cf(), &map, &case) else {
            continue;
        };
        let o = c.model(&r, &node);
        let exact = golden::plane::clip::clip_exact(&case.ray, &case.bounds, &planes);
        let (verdict, _) = tb::plane::fix::judge_case(&case, &exact, o.hit, || c.interval(&r, &o));
        if let golden::slab::check::Verdict::Violation(why) = verdict {
            panic!("{why}: {case:?} {o:?}");
        }
        let table = c.0.model(&r, &node);
        assert!(
            table.hit || !o.hit,
            "the fractions keep what the table culls: {case:?}"
        );
        n += 1;
        culled += u64::from(!o.hit);
        table_culled += u64::from(!table.hit);
    }
    assert!(
        culled > 0 && culled >= table_culled,
        "{culled} {table_culled}"
    );
}

/// The checks can fail: a model with the planes ignored disagrees with the RTL, and the table option's
/// interval is not the fractions' (its bounds are rounded outward).
#[test]
fn a_wrong_model_is_caught() {
    let c = QuotCtx::new(FixFormat::b12(), 2);
    let mut dut = TesterSim::wrap(rtl::PlaneQuotB12::<2>::new(c.cf()));
    let wrong = QuotCtx(CullFixCtx { k: 0, ..c.0 });
    assert!(run_checked(&mut dut, c.vectors(5, 2_000), |v| node_quot(
        wrong.cf(),
        0,
        &v.0,
        &v.1
    ))
    .is_err());
    let table_differs = c.vectors(6, 2_000).flatten().any(|(r, n)| {
        let t = c.0.model(&r, &n);
        let as_quot = |code| Quot { num: code, den: 0 };
        let table = PlaneQuotOut {
            hit: t.hit,
            t_entry: as_quot(t.t_entry),
            t_exit: as_quot(t.t_exit),
        };
        fractions_defined(&r) && agrees_with_fractions(&c, &r, &n, &table).is_err()
    });
    assert!(table_differs);
}

fn export<S: PlaneQuotIo>(c: &QuotCtx) -> (String, std::path::PathBuf) {
    let name = c.name();
    let v = rtl::verilog::verilog_named(&mut S::for_format(c.cf()), &name);
    let path = tb::verilog_tools::write(&v, &name);
    (v, path)
}

#[test]
fn exported_verilog_is_lint_clean_and_accepted_by_icarus() {
    let c = QuotCtx::new(FixFormat::b12(), 4);
    let (_, path) = export::<rtl::PlaneQuotB12<4>>(&c);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
    tb::verilog_tools::icarus(&path).unwrap_or_else(|e| panic!("{e}"));
    let c = QuotCtx::new(FixFormat::b16(), 1);
    let (_, path) = export::<rtl::PlaneQuotB16<1>>(&c);
    tb::verilog_tools::lint(&path).unwrap_or_else(|e| panic!("{e}"));
}

/// Verilator on the exported Verilog: every cycle against the rust-hdl simulation for the first
/// `lockstep` cycles, every result against the model (and so against `cull_fix_quotients`).
fn cross_simulate<S: PlaneQuotIo>(fmt: FixFormat, n: u64, lockstep: u64, seed: u64) {
    let c = QuotCtx::new(fmt, S::PLANES);
    let (v, _) = export::<S>(&c);
    let h = tb::verilator::build(&v, &c.name(), &tb::out_dir().join("verilator"))
        .unwrap_or_else(|e| panic!("{e}"));
    let stats = xsim(
        c,
        || S::for_format(c.cf()),
        &h,
        c.vectors(seed, n),
        lockstep,
        |_| {},
    )
    .unwrap_or_else(|e| panic!("{}: {e}", c.name()));
    assert_eq!(stats.tests, n);
    assert!(
        stats.hits > 0 && stats.hits < stats.tests,
        "degenerate vectors: {stats:?}"
    );
}

#[test]
fn verilator_matches_rtl_and_model_b12_k1() {
    cross_simulate::<rtl::PlaneQuotB12<1>>(FixFormat::b12(), 100_000, 5_000, 23);
}

#[test]
fn verilator_matches_rtl_and_model_b12_k4() {
    cross_simulate::<rtl::PlaneQuotB12<4>>(FixFormat::b12(), 100_000, 5_000, 24);
}

#[test]
fn verilator_matches_rtl_and_model_b16_k4() {
    cross_simulate::<rtl::PlaneQuotB16<4>>(FixFormat::b16(), 50_000, 2_000, 25);
}

/// Synchronous reset of the fraction option (`tb::reset`), as for the table option.
#[test]
fn reset_clears_every_valid_bit_b12_k1() {
    let c = QuotCtx::new(FixFormat::b12(), 1);
    let (v, _) = export::<rtl::PlaneQuotB12<1>>(&c);
    let tests: Vec<_> = c.vectors(33, 400).flatten().collect();
    let s = tb::reset::check_block(
        c,
        || rtl::PlaneQuotB12::<1>::for_format(c.cf()),
        &tests,
        &c.name(),
        &v,
        33,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    s.both_sides()
        .unwrap_or_else(|e| panic!("{}: {e}", c.name()));
}
