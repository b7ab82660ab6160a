//! The fixed slab tester's testbench glue: port encoding for the Verilator harness, and the
//! cross-simulation loop that checks Verilator against the rust-hdl simulation and the model.

use crate::dut::PipelinedDut;
use crate::rtl_sim::SlabFixRtl;
use crate::verilator::Harness;
use golden::fixed::{FixBox, FixFormat, FixRay};
use golden::slab_fix::slab_fix;
use rtl::slab_fix::{code, SlabFixIo};
use std::collections::VecDeque;
use std::sync::mpsc::sync_channel;

/// One slab test for the pipeline: `None` is a bubble.
pub type SlabVec = Option<(FixRay, FixBox)>;

/// The value of input port `port` (a Verilog name such as `ray_o_lo$1`) for one cycle.
pub fn in_word(fmt: &FixFormat, port: &str, tag: u16, v: &SlabVec) -> Result<u64, String> {
    let (base, idx) = match port.split_once('$') {
        Some((b, i)) => (
            b,
            i.parse::<usize>()
                .map_err(|e| format!("port {port}: {e}"))?,
        ),
        None => (port, 0),
    };
    let (g, t) = (fmt.g as usize, fmt.t as usize);
    let Some((r, b)) = v else {
        return Ok(0); // a bubble: valid_in low, data don't care (driven as zero)
    };
    Ok(match base {
        "valid_in" => 1,
        "tag_in" => tag as u64,
        "ray_o_lo" => code(r.o_lo[idx], g),
        "ray_o_hi" => code(r.o_hi[idx], g),
        "ray_m_lo" => r.m_lo[idx],
        "ray_m_hi" => r.m_hi[idx],
        "ray_neg" => r.neg[idx] as u64,
        "ray_t_min" => code(r.t_min, t),
        "ray_t_max" => code(r.t_max, t),
        "box_lo" => code(b.lo[idx], g),
        "box_hi" => code(b.hi[idx], g),
        _ => return Err(format!("unknown input port {port}")),
    })
}

/// Cycles replayed into the VCD written when a cross-simulation cycle fails.
pub const XSIM_VCD_WINDOW: usize = 32;

/// Drives `cycles` (tag and vector, or bubble) through block `S` writing a VCD at `path`.
pub fn replay_vcd<S: SlabFixIo>(
    fmt: FixFormat,
    cycles: &VecDeque<(u16, SlabVec)>,
    path: &std::path::Path,
) -> std::io::Result<()> {
    let mut sim = SlabFixRtl::<S>::with_vcd(&fmt, path)?;
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
    pub hits: u64,
}

/// Streams `vectors` through the Verilator `harness` and checks every output record: each valid result
/// against the bit-accurate model (with tag order and latency), and, when `lockstep_rtl`, `valid_out` of
/// every cycle and every other output port of every valid cycle against the rust-hdl simulation of block
/// `S` driven with the same inputs.
/// `progress(tests)` is called every 65,536 cycles.
pub fn xsim<S, It>(
    fmt: FixFormat,
    harness: &Harness,
    vectors: It,
    lockstep_rtl: bool,
    mut progress: impl FnMut(u64),
) -> Result<XsimStats, String>
where
    S: SlabFixIo,
    It: Iterator<Item = SlabVec> + Send + 'static,
{
    let ports: Vec<String> = harness.inputs.iter().map(|p| p.name.clone()).collect();
    let (tx, rx) = sync_channel::<(u16, SlabVec)>(1 << 16);
    let mut tag = 0u16;
    let lat = rtl::SLAB_FIX_LATENCY as u64;
    // Flush the pipeline after the last vector.
    let records = vectors
        .chain(std::iter::repeat_n(None, lat as usize + 1))
        .map(move |v| {
            let t = tag;
            if v.is_some() {
                tag = tag.wrapping_add(1);
            }
            let rec = ports
                .iter()
                .map(|p| in_word(&fmt, p, t, &v).expect("known port"))
                .collect();
            tx.send((t, v)).expect("consumer alive");
            rec
        });
    let iv = harness
        .output_index("valid_out")
        .ok_or("no valid_out port")?;
    let it = harness.output_index("tag_out").ok_or("no tag_out port")?;
    let ih = harness.output_index("hit").ok_or("no hit port")?;
    let ien = harness.output_index("t_entry").ok_or("no t_entry port")?;
    let iex = harness.output_index("t_exit").ok_or("no t_exit port")?;
    let mut rtl = if lockstep_rtl {
        Some(SlabFixRtl::<S>::new(&fmt))
    } else {
        None
    };
    let mut pending: VecDeque<(u64, u16, FixRay, FixBox)> = VecDeque::new();
    let mut stats = XsimStats::default();
    let t = fmt.t as usize;
    // The last cycles' inputs, replayed into a VCD when a cycle fails.
    let mut recent: VecDeque<(u16, SlabVec)> = VecDeque::new();
    let mut last_cycle = 0u64;
    let cycles = harness.stream(records, |cycle, out| {
        let (tg, v) = rx.recv().map_err(|_| "producer ended early".to_string())?;
        last_cycle = cycle;
        recent.push_back((tg, v));
        if recent.len() > XSIM_VCD_WINDOW {
            recent.pop_front();
        }
        if let Some((r, b)) = v {
            pending.push_back((cycle, tg, r, b));
        }
        if let Some(sim) = rtl.as_mut() {
            sim.step(v.as_ref().map(|x| (tg, x)));
            // valid_out every cycle; the data ports only while valid (they are don't-care otherwise).
            for (k, p) in harness.outputs.iter().enumerate() {
                let w = sim.uut.output_word(&p.name).ok_or_else(|| format!("no output {}", p.name))?;
                if (k == iv || out[iv] != 0) && w != out[k] {
                    return Err(format!(
                        "cycle {}: output {} is {:#x} in Verilator and {:#x} in the rust-hdl simulation (input {v:?})",
                        cycle + 1,
                        p.name,
                        out[k],
                        w
                    ));
                }
            }
        }
        let due = pending.front().map(|p| p.0 + lat == cycle + 1).unwrap_or(false);
        match (out[iv] != 0, due) {
            (false, false) => {}
            (true, true) => {
                let (_, etag, r, b) = pending.pop_front().unwrap();
                let exp = slab_fix(&fmt, &r, &b);
                let got = (out[it] as u16, out[ih] != 0, out[ien], out[iex]);
                let want = (etag, exp.hit, code(exp.t_entry, t), code(exp.t_exit, t));
                if got != want {
                    return Err(format!(
                        "cycle {}: Verilator gives (tag, hit, entry, exit) = {got:?}, the model {want:?}\n  ray {r:?}\n  box {b:?}",
                        cycle + 1
                    ));
                }
                stats.tests += 1;
                stats.hits += exp.hit as u64;
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
        let name = format!("xsim_{}_cycle{}.vcd", fmt.name(), last_cycle + 1);
        let path = crate::out_dir().join("vcd").join(name);
        match replay_vcd::<S>(fmt, &recent, &path) {
            Ok(()) => format!("{e}\n  waveform of the last {} cycles (rust-hdl): {}", recent.len(), path.display()),
            Err(w) => format!("{e}\n  (no waveform: {w})"),
        }
    })?;
    stats.cycles = cycles;
    if !pending.is_empty() {
        return Err(format!("{} results never left the pipeline", pending.len()));
    }
    Ok(stats)
}
