//! One streaming interface over the three executable forms of the fixed slab tester: the bit-accurate
//! model, the rust-hdl simulation and the exported Verilog in Verilator. Results come back in input order.

use crate::dut::PipelinedDut;
use crate::rtl_sim::SlabFixRtl;
use crate::slab_tb::in_word;
use golden::fixed::{FixBox, FixFormat, FixRay};
use golden::slab_fix::{slab_fix, SlabFixOut};
use rtl::export::{slab_fix_module, slab_fix_verilog};
use rtl::slab_fix::{sext, SlabFixIo};
use std::collections::VecDeque;
use std::path::Path;
use std::sync::mpsc::sync_channel;

/// Which form of the tester runs the vectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    /// `golden::slab_fix::slab_fix`, native.
    Model,
    /// The rust-hdl `SlabFix` block, cycle by cycle.
    Rtl,
    /// The exported Verilog, compiled by Verilator.
    Verilator,
}

impl std::str::FromStr for Engine {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "model" => Ok(Engine::Model),
            "rtl" => Ok(Engine::Rtl),
            "verilator" => Ok(Engine::Verilator),
            _ => Err(format!("engine `{s}`: expected model, rtl or verilator")),
        }
    }
}

/// A test with the caller's own key `K` (returned with the result).
pub type Keyed<K> = (K, FixRay, FixBox);

/// Runs `tests` on `engine`, calling `sink(key, ray, result)` for each in input order; `verilator_dir` holds
/// harness builds; `vcd`, for the rust-hdl engine, is where to write a waveform of the whole run.
/// Returns the number of tests run.
pub fn run_engine<K, It, F>(
    engine: Engine,
    fmt: FixFormat,
    tests: It,
    verilator_dir: &Path,
    vcd: Option<&Path>,
    mut sink: F,
) -> Result<u64, String>
where
    K: Send + 'static,
    It: Iterator<Item = Keyed<K>> + Send + 'static,
    F: FnMut(K, &FixRay, SlabFixOut) -> Result<(), String>,
{
    match engine {
        _ if vcd.is_some() && engine != Engine::Rtl => {
            Err("a waveform (--vcd) needs the rtl engine".into())
        }
        Engine::Model => {
            let mut n = 0;
            for (k, r, b) in tests {
                sink(k, &r, slab_fix(&fmt, &r, &b))?;
                n += 1;
            }
            Ok(n)
        }
        Engine::Rtl => {
            rtl::with_slab_fix!(&fmt, S, { run_rtl::<S, K, It, F>(fmt, tests, vcd, sink) })?
        }
        Engine::Verilator => {
            let v = slab_fix_verilog(&fmt)?;
            let h = crate::verilator::build(&v, &slab_fix_module(&fmt), verilator_dir)?;
            let ports: Vec<String> = h.inputs.iter().map(|p| p.name.clone()).collect();
            let (tx, rx) = sync_channel::<(K, FixRay)>(1 << 16);
            let lat = rtl::SLAB_FIX_LATENCY;
            let mut tag = 0u16;
            let records = tests
                .map(move |(k, r, b)| {
                    let v = Some((r, b));
                    let rec: Vec<u64> = ports
                        .iter()
                        .map(|p| in_word(&fmt, p, tag, &v).expect("known port"))
                        .collect();
                    tag = tag.wrapping_add(1);
                    tx.send((k, r)).expect("consumer alive");
                    rec
                })
                .chain(std::iter::repeat_n(vec![0u64; h.inputs.len()], lat + 1)); // flush bubbles
            let (iv, ih, ien, iex) = (
                h.output_index("valid_out").ok_or("no valid_out")?,
                h.output_index("hit").ok_or("no hit")?,
                h.output_index("t_entry").ok_or("no t_entry")?,
                h.output_index("t_exit").ok_or("no t_exit")?,
            );
            let t = fmt.t as usize;
            let mut n = 0u64;
            let mut waiting: VecDeque<(K, FixRay)> = VecDeque::new();
            h.stream(records, |_, out| {
                // The producer sends each test before the harness can see it; flush cycles send nothing.
                if let Ok(x) = rx.try_recv() {
                    waiting.push_back(x);
                }
                if out[iv] != 0 {
                    let (k, r) = waiting.pop_front().ok_or("a result with no test waiting")?;
                    let res = SlabFixOut {
                        hit: out[ih] != 0,
                        t_entry: sext(out[ien], t),
                        t_exit: sext(out[iex], t),
                    };
                    n += 1;
                    sink(k, &r, res)?;
                }
                Ok(())
            })?;
            Ok(n)
        }
    }
}

fn run_rtl<S, K, It, F>(
    fmt: FixFormat,
    tests: It,
    vcd: Option<&Path>,
    mut sink: F,
) -> Result<u64, String>
where
    S: SlabFixIo,
    It: Iterator<Item = Keyed<K>>,
    F: FnMut(K, &FixRay, SlabFixOut) -> Result<(), String>,
{
    let mut dut = match vcd {
        Some(p) => {
            SlabFixRtl::<S>::with_vcd(&fmt, p).map_err(|e| format!("{}: {e}", p.display()))?
        }
        None => SlabFixRtl::<S>::new(&fmt),
    };
    let mut waiting: VecDeque<(K, FixRay)> = VecDeque::new();
    let mut n = 0u64;
    let mut tag = 0u16;
    let mut deliver = |out: Option<(u16, SlabFixOut)>,
                       waiting: &mut VecDeque<(K, FixRay)>|
     -> Result<(), String> {
        if let Some((_, res)) = out {
            let (k, r) = waiting.pop_front().ok_or("a result with no test waiting")?;
            n += 1;
            sink(k, &r, res)?;
        }
        Ok(())
    };
    for (k, r, b) in tests {
        waiting.push_back((k, r));
        let out = dut.step(Some((tag, &(r, b))));
        tag = tag.wrapping_add(1);
        deliver(out, &mut waiting)?;
    }
    for _ in 0..=dut.latency() {
        let out = dut.step(None);
        deliver(out, &mut waiting)?;
    }
    Ok(n)
}
