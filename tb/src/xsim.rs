//! What a testbench must know of a pipelined tester's configuration ([`BlockCtx`], [`TesterCtx`]), its
//! port words through the family's codec (`rtl::io::PortCodec`), and the one cross-simulation loop
//! ([`xsim`]) that serves every pipelined tester: the slab testers, the cull-plane testers (table,
//! quotient and float options) and the bundle pairs, on both datapaths.

use crate::dut::PipelinedDut;
use crate::rtl_sim::TesterSim;
use crate::verilator::{Harness, Port};
use rtl::io::{PortCodec, Word};
use rtl::TesterIo;
use std::collections::VecDeque;
use std::fmt::Debug;
use std::sync::mpsc::sync_channel;

/// A configuration of a pipelined tester, as the cross-simulation loop and the port-word files need it:
/// its name, its port codec and its bit-accurate model. Implemented by `FixFormat`, `FloatFormat`
/// (the slab testers), `tb::plane::fix::CullFixCtx`, `tb::plane::float::CullFloatCtx` (the
/// cull-plane testers), `BundleFixFormat` and `tb::bundle::pair_float::PairFloatCtx` (the pairs), and
/// the quotient option's context in its tests.
pub trait BlockCtx: Copy + Send + Sync + Debug + 'static {
    type Ray: Clone + Copy + Debug + PartialEq + Send + 'static;
    type Box: Clone + Copy + Debug + PartialEq + Send + 'static;
    type Out: Clone + Copy + Debug + PartialEq;
    /// The port codec of the configuration's blocks.
    type Ports: PortCodec<Ray = Self::Ray, Box = Self::Box, Out = Self::Out>;
    /// Name of the configuration, for messages and files.
    fn name(&self) -> String;
    /// The port codec.
    fn ports(&self) -> Self::Ports;
    /// The bit-accurate model.
    fn model(&self, r: &Self::Ray, b: &Self::Box) -> Self::Out;
    /// What [`XsimStats::hits`] counts: a hit (the slab and cull-plane testers), a decisive answer,
    /// all hit or all miss (the bundle pairs).
    fn counts_as_hit(&self, o: &Self::Out) -> bool;
}

/// A tester whose results are ray intervals judged against the exact oracle: the slab and cull-plane
/// testers.
pub trait TesterCtx: BlockCtx {
    /// `(hit, t_entry, t_exit)` with t in world units (exact; the end codes as infinities).
    fn world(&self, r: &Self::Ray, o: &Self::Out) -> (bool, f64, f64);
    /// The conservativeness verdict of a result against the exact oracle.
    fn judge(
        &self,
        r: &Self::Ray,
        o: &Self::Out,
        exact: &golden::exact::ExactHit,
    ) -> golden::slab::check::Verdict;
}

/// The word on input port `port` for one cycle: `valid_in`, `tag_in`, `rst` (low), or a data input
/// of the test through the codec. A bubble drives every input zero.
pub fn in_word<C: BlockCtx>(
    ctx: &C,
    port: &Port,
    tag: u16,
    v: &Option<(C::Ray, C::Box)>,
) -> Result<u64, String> {
    let Some((r, b)) = v else {
        return Ok(0); // a bubble: valid_in low, data don't care (driven as zero)
    };
    match port.name.as_str() {
        "valid_in" => Ok(1),
        "rst" => Ok(0),
        "tag_in" => Ok(Word::of(tag as i64, port.width).bits),
        name => {
            let (base, idx) = rtl::verilog::split_port(name);
            ctx.ports()
                .input(base, idx.unwrap_or(0), r, b)
                .map(|v| Word::of(v, port.width).bits)
                .ok_or_else(|| format!("{} has no input port {name}", ctx.name()))
        }
    }
}

/// The input words of one test, one per port of `cols`, with tag `tag`.
pub fn in_row<C: BlockCtx>(
    ctx: &C,
    cols: &[Port],
    tag: u16,
    r: &C::Ray,
    b: &C::Box,
) -> Result<Vec<u64>, String> {
    let v = Some((*r, *b));
    cols.iter().map(|p| in_word(ctx, p, tag, &v)).collect()
}

/// The output words of the result `o` with tag `tag`, one per port of `cols` (`valid_out` 1,
/// `tag_out`, and the data outputs through the codec). A value that does not fit its port (as an
/// unsigned or a two's complement number) is an error: the model gave what the port cannot carry.
pub fn out_row<C: BlockCtx>(
    ctx: &C,
    cols: &[Port],
    tag: u16,
    o: &C::Out,
) -> Result<Vec<u64>, String> {
    let data = ctx.ports().outputs(o);
    cols.iter()
        .map(|p| {
            let v = match p.name.as_str() {
                "valid_out" => Some(1),
                "tag_out" => Some(tag as i64),
                name => data.iter().find(|(n, _)| *n == name).map(|x| x.1),
            };
            let v = v.ok_or_else(|| format!("{} has no output port {}", ctx.name(), p.name))?;
            let w = Word::of(v, p.width);
            if w.bits as i64 == v || w.signed() == v {
                Ok(w.bits)
            } else {
                Err(format!(
                    "{}: the value {v} of output {} does not fit its {} bits",
                    ctx.name(),
                    p.name,
                    p.width
                ))
            }
        })
        .collect()
}

/// The tag and result of a row of output words (columns `cols`, as [`out_row`] writes them).
pub fn out_of_row<C: BlockCtx>(
    ctx: &C,
    cols: &[Port],
    row: &[u64],
) -> Result<(u16, C::Out), String> {
    let word = |name: &str| {
        cols.iter()
            .zip(row)
            .find(|(p, _)| p.name == name)
            .map(|(p, &bits)| Word {
                bits,
                width: p.width,
            })
    };
    let tag = word("tag_out").ok_or("no output port tag_out")?.bits as u16;
    Ok((tag, ctx.ports().result(&word)?))
}

/// Cycles replayed into the VCD written when a cross-simulation cycle fails.
pub const XSIM_VCD_WINDOW: usize = 32;

/// Drives `cycles` (tag and vector, or bubble) through a block made by `make`, writing a VCD at `path`.
pub fn replay_vcd<S: TesterIo>(
    make: impl Fn() -> S,
    cycles: &VecDeque<(u16, Option<(S::Ray, S::Box)>)>,
    path: &std::path::Path,
) -> std::io::Result<()> {
    let mut sim = TesterSim::wrap(make()).vcd_to(path)?;
    for (tag, v) in cycles {
        sim.step(v.as_ref().map(|x| (*tag, x)));
    }
    for _ in 0..=sim.latency() {
        sim.step(None);
    }
    Ok(())
}

/// What a cross-simulation run covered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct XsimStats {
    pub cycles: u64,
    pub tests: u64,
    /// Results that [`BlockCtx::counts_as_hit`].
    pub hits: u64,
}

/// Streams `vectors` through the Verilator `harness` and checks every output record: in every cycle
/// `valid_out` (high exactly when a result is due, [`TesterIo::LATENCY`] clocks after its test), and in
/// every valid cycle every output port against the model's result through the codec (with the tag,
/// so results leave in order); for the first `lockstep_cycles` cycles also every output port (the data
/// ports while valid) against the rust-hdl simulation of the block made by `make`, driven with the same
/// inputs. On a failure the last [`XSIM_VCD_WINDOW`] cycles are replayed into a VCD (rust-hdl), named
/// in the error. `progress(tests)` is called every 65,536 cycles.
pub fn xsim<C, S, It>(
    ctx: C,
    make: impl Fn() -> S,
    harness: &Harness,
    vectors: It,
    lockstep_cycles: u64,
    mut progress: impl FnMut(u64),
) -> Result<XsimStats, String>
where
    C: BlockCtx,
    S: TesterIo<Ray = C::Ray, Box = C::Box, Out = C::Out>,
    It: Iterator<Item = Option<(C::Ray, C::Box)>> + Send + 'static,
{
    let ports = harness.inputs.clone();
    let (tx, rx) = sync_channel::<(u16, Option<(C::Ray, C::Box)>)>(1 << 16);
    let mut tag = 0u16;
    let lat = S::LATENCY as u64;
    // Flush the pipeline after the last vector.
    let records = vectors
        .chain(std::iter::repeat_n(None, lat as usize + 1))
        .map(move |v| {
            let t = tag;
            tag = tag.wrapping_add(v.is_some() as u16);
            let rec = ports
                .iter()
                .map(|p| in_word(&ctx, p, t, &v).unwrap_or_else(|e| panic!("{e}")))
                .collect();
            tx.send((t, v)).expect("consumer alive");
            rec
        });
    let outs = harness.outputs.clone();
    let iv = harness
        .output_index("valid_out")
        .ok_or("no valid_out port")?;
    // Every output the checks read must be in the harness: the tag, and each data output the codec
    // reads (an error names the first one missing).
    harness.output_index("tag_out").ok_or("no tag_out port")?;
    ctx.ports().result(&|name| {
        harness.output_index(name).map(|k| Word {
            bits: 0,
            width: outs[k].width,
        })
    })?;
    let mut rtl = (lockstep_cycles > 0).then(|| TesterSim::wrap(make()));
    let mut pending: VecDeque<(u64, u16, C::Ray, C::Box)> = VecDeque::new();
    let mut stats = XsimStats::default();
    // The last cycles' inputs, replayed into a VCD when a cycle fails.
    let mut recent: VecDeque<(u16, Option<(C::Ray, C::Box)>)> = VecDeque::new();
    let mut last_cycle = 0u64;
    let cycles = harness
        .stream(records, |cycle, out| {
            let (tg, v) = rx.recv().map_err(|_| "producer ended early".to_string())?;
            last_cycle = cycle;
            recent.push_back((tg, v));
            if recent.len() > XSIM_VCD_WINDOW {
                recent.pop_front();
            }
            if let Some((r, b)) = v {
                pending.push_back((cycle, tg, r, b));
            }
            if cycle >= lockstep_cycles {
                rtl = None;
            }
            if let Some(sim) = rtl.as_mut() {
                sim.step(v.as_ref().map(|x| (tg, x)));
                // valid_out every cycle; the data ports only while valid (they are don't-care otherwise).
                for (k, p) in outs.iter().enumerate() {
                    let w = sim
                        .uut
                        .output_word(&p.name)
                        .ok_or_else(|| format!("no output {}", p.name))?;
                    if (k == iv || out[iv] != 0) && w != out[k] {
                        let due = pending.front().filter(|p| p.0 + lat == cycle + 1);
                        return Err(format!(
                            "cycle {}: output {} is {:#x} in Verilator and {:#x} in the rust-hdl simulation\n  result due for: {:?}",
                            cycle + 1,
                            p.name,
                            out[k],
                            w,
                            due.map(|p| (p.2, p.3))
                        ));
                    }
                }
            }
            let due = pending.front().is_some_and(|p| p.0 + lat == cycle + 1);
            match (out[iv] != 0, due) {
                (false, false) => {}
                (true, true) => {
                    let (_, etag, r, b) = pending.pop_front().expect("a result is due");
                    let exp = ctx.model(&r, &b);
                    let want = out_row(&ctx, &outs, etag, &exp)?;
                    if let Some(k) = (0..outs.len()).find(|&k| out[k] != want[k]) {
                        return Err(format!(
                            "cycle {}: output {} is {:#x} in Verilator, {:#x} in the model (tag {etag}: {exp:?})\n  ray {r:?}\n  box {b:?}",
                            cycle + 1,
                            outs[k].name,
                            out[k],
                            want[k]
                        ));
                    }
                    stats.tests += 1;
                    stats.hits += ctx.counts_as_hit(&exp) as u64;
                }
                (v, _) => {
                    return Err(format!(
                        "cycle {}: valid_out = {v} but a result {} due (latency {lat})",
                        cycle + 1,
                        if v { "was not" } else { "was" }
                    ))
                }
            }
            if cycle % 65536 == 0 {
                progress(stats.tests);
            }
            Ok(())
        })
        .map_err(|e| {
            let name = format!("xsim_{}_cycle{}.vcd", ctx.name(), last_cycle + 1);
            let path = crate::out_dir().join("vcd").join(name);
            match replay_vcd(&make, &recent, &path) {
                Ok(()) => format!(
                    "{e}\n  waveform of the last {} cycles (rust-hdl): {}",
                    recent.len(),
                    path.display()
                ),
                Err(w) => format!("{e}\n  (no waveform: {w})"),
            }
        })?;
    stats.cycles = cycles;
    if !pending.is_empty() {
        return Err(format!("{} results never left the pipeline", pending.len()));
    }
    Ok(stats)
}

/// The clock-by-clock loop of the blocks whose protocol is not one test a clock (the results
/// processors): streams `stim` through the Verilator `harness`, each clock's input words from
/// `in_word(port, input)`, decodes each clock's outputs with `decode(word)` (`word(port)` the value
/// of an output port), checks them with `check(clock, input, outputs)` (the model's checker), and for
/// the first `lockstep` clocks compares them with `rtl(input)`, the rust-hdl simulation of the block
/// stepped with the same input. Returns the clocks run.
pub fn clocked_xsim<I, O, It>(
    harness: &Harness,
    stim: It,
    in_word: impl Fn(&str, &I) -> Result<u64, String> + Send + 'static,
    decode: impl Fn(&dyn Fn(&str) -> Option<u64>) -> Result<O, String>,
    mut check: impl FnMut(u64, &I, &O) -> Result<(), String>,
    lockstep: u64,
    mut rtl: impl FnMut(&I) -> O,
) -> Result<u64, String>
where
    I: Send + 'static,
    O: PartialEq + Debug,
    It: Iterator<Item = I> + Send + 'static,
{
    let ports: Vec<String> = harness.inputs.iter().map(|p| p.name.clone()).collect();
    let (tx, rx) = sync_channel::<I>(1 << 14);
    let records = stim.map(move |input| {
        let rec = ports
            .iter()
            .map(|p| in_word(p, &input).unwrap_or_else(|e| panic!("{e}")))
            .collect();
        tx.send(input).expect("consumer alive");
        rec
    });
    let index: std::collections::HashMap<String, usize> = harness
        .outputs
        .iter()
        .enumerate()
        .map(|(k, p)| (p.name.clone(), k))
        .collect();
    harness.stream(records, |clock, out| {
        let input = rx.recv().map_err(|_| "producer ended early".to_string())?;
        let got = decode(&|name| index.get(name).map(|&k| out[k]))?;
        check(clock, &input, &got).map_err(|e| format!("Verilator: {e}"))?;
        if clock < lockstep {
            let s = rtl(&input);
            if s != got {
                return Err(format!(
                    "clock {}: Verilator {got:?}, rust-hdl simulation {s:?}",
                    clock + 1
                ));
            }
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use golden::bundle::fix::BundleFixFormat;
    use golden::format::fixed::FixFormat;
    use golden::plane::fix::CullFixFormat;
    use rtl::export::Exported;
    use std::cell::RefCell;
    use std::collections::BTreeSet;

    /// The data ports that `tester_ports!` lists for a block are exactly the data ports of its
    /// exported Verilog (an unlisted input would never be driven by the rust-hdl driver), and every
    /// output port of the Verilog is read back with its width.
    fn listed_ports_are_the_verilog_s<S: TesterIo>(e: Exported, mut block: S) {
        let v = e.verilog();
        let ports =
            crate::verilator::parse_ports(&v, &e.module).unwrap_or_else(|err| panic!("{err}"));
        let verilog: BTreeSet<(String, usize)> = ports
            .iter()
            .filter(|p| {
                p.input && !matches!(p.name.as_str(), "clock" | "rst" | "valid_in" | "tag_in")
            })
            .map(|p| {
                let (base, idx) = rtl::verilog::split_port(&p.name);
                (base.to_string(), idx.unwrap_or(0))
            })
            .collect();
        let listed = RefCell::new(BTreeSet::new());
        block.set_inputs(&|base, idx| {
            listed.borrow_mut().insert((base.to_string(), idx));
            0
        });
        assert_eq!(listed.into_inner(), verilog, "{}: data inputs", e.module);
        for p in ports.iter().filter(|p| !p.input) {
            let w = block
                .output(&p.name)
                .unwrap_or_else(|| panic!("{}: output {} is not read", e.module, p.name));
            assert_eq!(w.width, p.width, "{}: width of {}", e.module, p.name);
        }
        assert!(block.output("no_such_port").is_none());
    }

    /// The expected words fit their ports or are an error naming the port: a model value wider than its
    /// port is not truncated into a match.
    #[test]
    fn a_result_wider_than_its_port_is_an_error() {
        use golden::slab::fix::SlabFixOut;
        let port = |name: &str, width| Port {
            name: name.into(),
            width,
            input: false,
        };
        let cols = [
            port("tag_out", 16),
            port("hit", 1),
            port("t_entry", 4),
            port("t_exit", 4),
        ];
        let b8 = FixFormat::b8();
        let o = SlabFixOut {
            hit: true,
            t_entry: -3,
            t_exit: 15,
        };
        assert_eq!(out_row(&b8, &cols, 7, &o), Ok(vec![7, 1, 0xd, 0xf]));
        for bad in [17, -9] {
            let e = out_row(&b8, &cols, 7, &SlabFixOut { t_entry: bad, ..o }).unwrap_err();
            assert!(e.contains("t_entry") && e.contains("does not fit"), "{e}");
        }
    }

    #[test]
    fn every_tester_s_listed_ports_are_its_verilog_s() {
        crate::plane::float::with_big_stack(every_tester);
    }

    fn every_tester() {
        let b8 = FixFormat::b8();
        listed_ports_are_the_verilog_s(
            rtl::export::slab_fix::<rtl::SlabFixB8>(b8),
            rtl::SlabFixB8::new(&b8),
        );
        listed_ports_are_the_verilog_s(
            rtl::export::slab_float::<rtl::SlabFloatE5M10>(),
            rtl::SlabFloatE5M10::new(),
        );
        let cf = CullFixFormat::over(b8);
        listed_ports_are_the_verilog_s(
            rtl::export::plane_fix::<rtl::PlaneFixB8<4>>(cf),
            rtl::PlaneFixB8::<4>::new(&cf),
        );
        listed_ports_are_the_verilog_s(
            rtl::export::plane_quot::<rtl::PlaneQuotB8<4>>(cf),
            rtl::PlaneQuotB8::<4>::new(&cf),
        );
        listed_ports_are_the_verilog_s(
            rtl::export::plane_float::<rtl::PlaneFloatE5M10K4>(),
            rtl::PlaneFloatE5M10K4::new(),
        );
        let bf = BundleFixFormat::over(b8).expect("b8 pair");
        listed_ports_are_the_verilog_s(
            rtl::export::bundle_fix::<rtl::BundleFixB8>(bf),
            rtl::BundleFixB8::new(&bf),
        );
        listed_ports_are_the_verilog_s(
            rtl::export::bundle_float::<rtl::BundleFloatFp16>(),
            rtl::BundleFloatFp16::new(),
        );
    }
}
