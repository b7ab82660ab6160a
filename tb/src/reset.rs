//! Reset checks of the pipelined testers: `rst` raised at chosen clocks while tests stream through,
//! in the rust-hdl simulation and (optionally) in Verilator on the exported Verilog, clock by clock.
//!
//! The rule checked (the ports' documentation in `rtl`): `rst` is synchronous and clears every valid bit.
//! A test that enters in clock `c` of a block of latency `L` leaves in clock `c + L - 1` (its result is
//! on the outputs after that clock's edge) exactly when `rst` is low in every clock `c ..= c + L - 1`;
//! otherwise no result of it ever leaves. A result that leaves equals the bit-accurate model's, with the
//! test's tag. Data registers are not reset, so the data outputs are compared only while `valid_out`.

use crate::rtl_sim::TesterSim;
use crate::verilator::{Harness, Port};
use crate::xsim::{in_word, BlockCtx};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rtl::TesterIo;
use std::collections::VecDeque;
use std::path::Path;

/// One clock of a reset check: `rst`, and a test or a bubble.
pub type ResetClock<R, B> = (bool, Option<(R, B)>);

/// What a reset check covered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ResetStats {
    /// Clocks driven (flush included).
    pub clocks: u64,
    /// Tests driven.
    pub tests: u64,
    /// Tests whose results left.
    pub results: u64,
    /// Tests dropped by a reset.
    pub dropped: u64,
    /// Clocks with `rst` high.
    pub resets: u64,
}

impl ResetStats {
    /// Every test either left or was dropped, at least four were dropped and more than half left:
    /// a stream that exercised both sides of the rule.
    pub fn both_sides(&self) -> Result<(), String> {
        if self.results + self.dropped == self.tests
            && self.dropped >= 4
            && self.results > self.tests / 2
        {
            Ok(())
        } else {
            Err(format!(
                "the stream did not exercise both sides of the reset rule: {self:?}"
            ))
        }
    }
}

/// A reset stream of `tests` (all of them, in order): each clock a test with probability 3/4 (a bubble
/// otherwise) and `rst` high with probability `1 / (3 * latency)` (so about a quarter of the tests meet
/// a reset); `rst` is low in the first `latency + 2` clocks, so
/// the pipeline is full when the first reset comes, and high for four clocks in a row from clock
/// `4 * latency + 2`, tests still driven.
pub fn reset_stream<R: Copy, B: Copy>(
    tests: &[(R, B)],
    latency: usize,
    seed: u64,
) -> Vec<ResetClock<R, B>> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let long = 4 * latency + 2..4 * latency + 6;
    let mut out = vec![];
    let mut next = 0;
    while next < tests.len() {
        let n = out.len();
        let rst = if n < latency + 2 {
            false
        } else {
            long.contains(&n) || rng.gen_ratio(1, 3 * latency.max(1) as u32)
        };
        let v = if rng.gen_ratio(3, 4) {
            next += 1;
            Some(tests[next - 1])
        } else {
            None
        };
        out.push((rst, v));
    }
    out
}

/// Runs the reset check of the block made by `make` on `clocks` (then `L + 1` bubbles without reset):
/// the rust-hdl simulation against the rule of the module documentation and `model`, writing its VCD
/// at `vcd`; with `verilator`, the exported Verilog in the harness against the rust-hdl simulation,
/// every output port in every clock (the data ports while `valid_out`). `in_word(port, tag, test)` is
/// the block's input encoding (its `rst` port is driven here).
pub fn reset_check<S, M>(
    make: impl Fn() -> S,
    model: M,
    clocks: &[ResetClock<S::Ray, S::Box>],
    vcd: &Path,
    verilator: Option<(
        &Harness,
        &dyn Fn(&Port, u16, &Option<(S::Ray, S::Box)>) -> Result<u64, String>,
    )>,
) -> Result<ResetStats, String>
where
    S: TesterIo,
    M: Fn(&S::Ray, &S::Box) -> S::Out,
{
    use crate::dut::PipelinedDut;
    let lat = S::LATENCY;
    let mut sim = TesterSim::wrap(make())
        .vcd_to(vcd)
        .map_err(|e| format!("{}: {e}", vcd.display()))?;
    let outputs: Vec<String> = match verilator {
        Some((h, _)) => h.outputs.iter().map(|p| p.name.clone()).collect(),
        None => vec![],
    };
    let mut words: Vec<Vec<u64>> = vec![];
    let mut stats = ResetStats::default();
    // Tests in flight: (entry clock, tag, survives so far, test).
    let mut flight: VecDeque<(usize, u16, bool, S::Ray, S::Box)> = VecDeque::new();
    let mut tag = 0u16;
    let mut tags = vec![];
    let flush = std::iter::repeat_n((false, None), lat + 1);
    for (c, (rst, v)) in clocks.iter().cloned().chain(flush).enumerate() {
        let t = tag;
        tags.push(t);
        if let Some((r, b)) = v {
            flight.push_back((c, t, true, r, b));
            tag = tag.wrapping_add(1);
            stats.tests += 1;
        }
        if rst {
            stats.resets += 1;
            for f in flight.iter_mut() {
                f.2 = false;
            }
        }
        sim.uut.set_reset(rst);
        let got = sim.step(v.as_ref().map(|x| (t, x)));
        words.push(
            outputs
                .iter()
                .map(|p| {
                    sim.uut
                        .output_word(p)
                        .ok_or_else(|| format!("no output {p}"))
                })
                .collect::<Result<_, _>>()?,
        );
        let due = match flight.front() {
            Some(f) if f.0 + lat - 1 == c => flight.pop_front(),
            _ => None,
        };
        match (due, got) {
            (Some((_, et, true, r, b)), Some((gt, o))) => {
                let want = model(&r, &b);
                if (gt, o) != (et, want) {
                    return Err(format!(
                        "clock {c}: result (tag {gt}) {o:?}, the model's (tag {et}) {want:?}\n  ray {r:?}\n  box {b:?}"
                    ));
                }
                stats.results += 1;
            }
            (Some((e, et, true, ..)), None) => {
                return Err(format!(
                    "clock {c}: no result for the test of clock {e} (tag {et}), which no reset met"
                ))
            }
            (Some((e, et, false, ..)), Some((gt, _))) => {
                return Err(format!(
                    "clock {c}: a result (tag {gt}) left for the test of clock {e} (tag {et}), which a reset dropped"
                ))
            }
            (Some((_, _, false, ..)), None) => stats.dropped += 1,
            (None, Some((gt, _))) => {
                return Err(format!("clock {c}: a result (tag {gt}) left, none due"))
            }
            (None, None) => {}
        }
        stats.clocks += 1;
    }
    if let Some(f) = flight.front() {
        return Err(format!("the test of clock {} never left", f.0));
    }
    drop(sim);
    let Some((h, in_word)) = verilator else {
        return Ok(stats);
    };
    let iv = h.output_index("valid_out").ok_or("no valid_out port")?;
    let mut records = vec![];
    let flush = std::iter::repeat_n((false, None), lat + 1);
    for (c, (rst, v)) in clocks.iter().cloned().chain(flush).enumerate() {
        let rec = h
            .inputs
            .iter()
            .map(|p| {
                if p.name == "rst" {
                    Ok(rst as u64)
                } else if v.is_none() {
                    Ok(0)
                } else {
                    in_word(p, tags[c], &v)
                }
            })
            .collect::<Result<Vec<u64>, String>>()?;
        records.push(rec);
    }
    let n = h.stream(records.into_iter(), |c, out| {
        let want = &words[c as usize];
        for (k, p) in h.outputs.iter().enumerate() {
            if (k == iv || out[iv] != 0) && out[k] != want[k] {
                return Err(format!(
                    "clock {c}: output {} is {:#x} in Verilator and {:#x} in the rust-hdl simulation (rst {})",
                    p.name,
                    out[k],
                    want[k],
                    clocks.get(c as usize).map(|x| x.0).unwrap_or(false)
                ));
            }
        }
        Ok(())
    })?;
    if n != stats.clocks {
        return Err(format!(
            "Verilator ran {n} clocks, the rust-hdl simulation {}",
            stats.clocks
        ));
    }
    Ok(stats)
}

/// The reset check of a block that has a [`BlockCtx`] (every pipelined tester): the stream
/// [`reset_stream`] of `tests`, the block made by `make` against `ctx`'s model, and its exported
/// `verilog` (module `module`) built into a Verilator harness against the rust-hdl simulation; the VCD
/// goes to `out/vcd/reset_<module>.vcd`.
pub fn check_block<C, S>(
    ctx: C,
    make: impl Fn() -> S,
    tests: &[(C::Ray, C::Box)],
    module: &str,
    verilog: &str,
    seed: u64,
) -> Result<ResetStats, String>
where
    C: BlockCtx,
    S: TesterIo<Ray = C::Ray, Box = C::Box, Out = C::Out>,
{
    let h = crate::verilator::build(verilog, module, &crate::out_dir().join("verilator"))?;
    let clocks = reset_stream(tests, S::LATENCY, seed);
    let vcd = crate::out_dir()
        .join("vcd")
        .join(format!("reset_{module}.vcd"));
    let word = |p: &Port, t: u16, x: &Option<(C::Ray, C::Box)>| in_word(&ctx, p, t, x);
    reset_check(
        make,
        |r, b| ctx.model(r, b),
        &clocks,
        &vcd,
        Some((&h, &word)),
    )
    .map_err(|e| format!("{module}: {e}\n  waveform (rust-hdl): {}", vcd.display()))
}
