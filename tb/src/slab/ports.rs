//! Testbench glue shared by the slab testers of both datapaths: port encoding for the Verilator harness,
//! and the cross-simulation loop that checks Verilator against the rust-hdl simulation and the model.

use crate::dut::PipelinedDut;
use crate::rtl_sim::TesterSim;
use crate::verilator::Harness;
use golden::format::fixed::{FixBox, FixFormat, FixRay};
use golden::format::float::FloatFormat;
use golden::slab::fix::{slab_fix, SlabFixOut};
use golden::slab::float::{slab_float, FloatBox, FloatRay, SlabFloatOut};
use rtl::slab::fix::code;
use rtl::TesterIo;
use std::collections::VecDeque;
use std::fmt::Debug;
use std::sync::mpsc::sync_channel;

/// One fixed slab test for the pipeline: `None` is a bubble.
pub type SlabVec = Option<(FixRay, FixBox)>;

/// What a testbench must know of a tester's configuration: how a test becomes port values, the
/// bit-accurate model, and the fields of a result as port values. Implemented by `FixFormat` and
/// `FloatFormat` (the slab testers), `tb::plane::fix::CullFixCtx` and `tb::plane::float::CullFloatCtx`
/// (the cull-plane testers), and the quotient option's context in its tests.
pub trait TesterCtx: Copy + Send + Sync + Debug + 'static {
    type Ray: Clone + Copy + Debug + PartialEq + Send + 'static;
    type Box: Clone + Copy + Debug + PartialEq + Send + 'static;
    type Out: Clone + Copy + Debug + PartialEq;
    /// Name of the format, for messages and files.
    fn name(&self) -> String;
    /// Value of data input `base[idx]` (`ray_o_lo`, `box_hi`, ...; `idx` 0 for scalars).
    fn port_value(&self, base: &str, idx: usize, r: &Self::Ray, b: &Self::Box) -> Option<u64>;
    /// The bit-accurate model.
    fn model(&self, r: &Self::Ray, b: &Self::Box) -> Self::Out;
    /// `(hit, t_entry, t_exit)` of a result, as port values.
    fn out_fields(&self, o: &Self::Out) -> (bool, u64, u64);
    /// A result from its port values.
    fn out_from_fields(&self, hit: bool, t_entry: u64, t_exit: u64) -> Self::Out;
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

impl TesterCtx for FixFormat {
    type Ray = FixRay;
    type Box = FixBox;
    type Out = SlabFixOut;
    fn name(&self) -> String {
        FixFormat::name(self)
    }
    fn port_value(&self, base: &str, idx: usize, r: &FixRay, b: &FixBox) -> Option<u64> {
        let (g, t) = (self.g as usize, self.t as usize);
        Some(match base {
            "ray_o_lo" => code(r.o_lo[idx], g),
            "ray_o_hi" => code(r.o_hi[idx], g),
            "ray_m_lo" => r.m_lo[idx],
            "ray_m_hi" => r.m_hi[idx],
            "ray_neg" => r.neg[idx] as u64,
            "ray_t_min" => code(r.t_min, t),
            "ray_t_max" => code(r.t_max, t),
            "box_lo" => code(b.lo[idx], g),
            "box_hi" => code(b.hi[idx], g),
            _ => return None,
        })
    }
    fn model(&self, r: &FixRay, b: &FixBox) -> SlabFixOut {
        slab_fix(self, r, b)
    }
    fn out_fields(&self, o: &SlabFixOut) -> (bool, u64, u64) {
        let t = self.t as usize;
        (o.hit, code(o.t_entry, t), code(o.t_exit, t))
    }
    fn out_from_fields(&self, hit: bool, t_entry: u64, t_exit: u64) -> SlabFixOut {
        let t = self.t as usize;
        SlabFixOut {
            hit,
            t_entry: rtl::slab::fix::sext(t_entry, t),
            t_exit: rtl::slab::fix::sext(t_exit, t),
        }
    }
    fn world(&self, r: &FixRay, o: &SlabFixOut) -> (bool, f64, f64) {
        (
            o.hit,
            r.t_entry_f64(self, o.t_entry),
            r.t_exit_f64(self, o.t_exit),
        )
    }
    fn judge(
        &self,
        r: &FixRay,
        o: &SlabFixOut,
        exact: &golden::exact::ExactHit,
    ) -> golden::slab::check::Verdict {
        golden::slab::check::judge_fix(self, r, o, exact)
    }
}

impl TesterCtx for FloatFormat {
    type Ray = FloatRay;
    type Box = FloatBox;
    type Out = SlabFloatOut;
    fn name(&self) -> String {
        FloatFormat::name(self)
    }
    fn port_value(&self, base: &str, idx: usize, r: &FloatRay, b: &FloatBox) -> Option<u64> {
        Some(match base {
            "ray_o_lo" => r.o_lo[idx] as u64,
            "ray_o_hi" => r.o_hi[idx] as u64,
            "ray_m_lo" => r.m_lo[idx] as u64,
            "ray_m_hi" => r.m_hi[idx] as u64,
            "ray_neg" => r.neg[idx] as u64,
            "ray_t_min" => r.t_min as u64,
            "ray_t_max" => r.t_max as u64,
            "box_lo" => b.lo[idx] as u64,
            "box_hi" => b.hi[idx] as u64,
            _ => return None,
        })
    }
    fn model(&self, r: &FloatRay, b: &FloatBox) -> SlabFloatOut {
        slab_float(self, r, b)
    }
    fn out_fields(&self, o: &SlabFloatOut) -> (bool, u64, u64) {
        (o.hit, o.t_entry as u64, o.t_exit as u64)
    }
    fn out_from_fields(&self, hit: bool, t_entry: u64, t_exit: u64) -> SlabFloatOut {
        SlabFloatOut {
            hit,
            t_entry: t_entry as u32,
            t_exit: t_exit as u32,
        }
    }
    fn world(&self, _: &FloatRay, o: &SlabFloatOut) -> (bool, f64, f64) {
        (o.hit, self.to_f64(o.t_entry), self.to_f64(o.t_exit))
    }
    fn judge(
        &self,
        _: &FloatRay,
        o: &SlabFloatOut,
        exact: &golden::exact::ExactHit,
    ) -> golden::slab::check::Verdict {
        golden::slab::float::judge_float(self, o, exact)
    }
}

/// The value of input port `port` (a Verilog name such as `ray_o_lo_1`) for one cycle.
pub fn in_word<C: TesterCtx>(
    ctx: &C,
    port: &str,
    tag: u16,
    v: &Option<(C::Ray, C::Box)>,
) -> Result<u64, String> {
    let (base, idx) = rtl::verilog::split_port(port);
    let idx = idx.unwrap_or(0);
    let Some((r, b)) = v else {
        return Ok(0); // a bubble: valid_in low, data don't care (driven as zero)
    };
    match base {
        "valid_in" => Ok(1),
        "rst" => Ok(0),
        "tag_in" => Ok(tag as u64),
        _ => ctx
            .port_value(base, idx, r, b)
            .ok_or_else(|| format!("unknown input port {port}")),
    }
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
    pub hits: u64,
}

/// Streams `vectors` through the Verilator `harness` and checks every output record: each valid result
/// against the bit-accurate model (with tag order and latency), and, for the first `lockstep_cycles`
/// cycles, `valid_out` of every cycle and every other output port of every valid cycle against the
/// rust-hdl simulation of the block made by `make`, driven with the same inputs.
/// `progress(tests)` is called every 65,536 cycles.
pub fn xsim<C, S, It>(
    fmt: C,
    make: impl Fn() -> S,
    harness: &Harness,
    vectors: It,
    lockstep_cycles: u64,
    mut progress: impl FnMut(u64),
) -> Result<XsimStats, String>
where
    C: TesterCtx,
    S: TesterIo<Ray = C::Ray, Box = C::Box, Out = C::Out>,
    It: Iterator<Item = Option<(C::Ray, C::Box)>> + Send + 'static,
{
    let ports: Vec<String> = harness.inputs.iter().map(|p| p.name.clone()).collect();
    let (tx, rx) = sync_channel::<(u16, Option<(C::Ray, C::Box)>)>(1 << 16);
    let mut tag = 0u16;
    let lat = S::LATENCY as u64;
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
    let mut rtl = if lockstep_cycles > 0 {
        Some(TesterSim::wrap(make()))
    } else {
        None
    };
    let mut pending: VecDeque<(u64, u16, C::Ray, C::Box)> = VecDeque::new();
    let mut stats = XsimStats::default();
    // The last cycles' inputs, replayed into a VCD when a cycle fails.
    let mut recent: VecDeque<(u16, Option<(C::Ray, C::Box)>)> = VecDeque::new();
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
        if cycle >= lockstep_cycles {
            rtl = None;
        }
        if let Some(sim) = rtl.as_mut() {
            sim.step(v.as_ref().map(|x| (tg, x)));
            // valid_out every cycle; the data ports only while valid (they are don't-care otherwise).
            for (k, p) in harness.outputs.iter().enumerate() {
                let w = sim.uut.output_word(&p.name).ok_or_else(|| format!("no output {}", p.name))?;
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
        let due = pending.front().map(|p| p.0 + lat == cycle + 1).unwrap_or(false);
        match (out[iv] != 0, due) {
            (false, false) => {}
            (true, true) => {
                let (_, etag, r, b) = pending.pop_front().unwrap();
                let exp = fmt.model(&r, &b);
                let (hit, en, ex) = fmt.out_fields(&exp);
                let got = (out[it] as u16, out[ih] != 0, out[ien], out[iex]);
                let want = (etag, hit, en, ex);
                if got != want {
                    return Err(format!(
                        "cycle {}: Verilator gives (tag, hit, entry, exit) = {got:?}, the model {want:?}\n  ray {r:?}\n  box {b:?}",
                        cycle + 1
                    ));
                }
                stats.tests += 1;
                stats.hits += hit as u64;
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
        match replay_vcd(&make, &recent, &path) {
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
