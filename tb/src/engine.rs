//! One streaming interface over the three executable forms of a slab tester or a chained slab +
//! cull-plane tester, for either datapath: the bit-accurate model, the rust-hdl simulation and the exported
//! Verilog in Verilator. Results come back in input order.

use crate::dut::PipelinedDut;
use crate::plane::fix::CullFixCtx;
use crate::plane::float::CullFloatCtx;
use crate::rtl_sim::TesterSim;
use crate::xsim::{in_word, out_of_row, BlockCtx, TesterCtx};
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use golden::plane::fix::{CullFixFormat, NodeFixRay, PlaneFixOut};
use golden::plane::float::{CullFloatFormat, NodeFloatRay};
use golden::slab::float::SlabFloatOut;
use rtl::plane::fix::PlaneFixIo;
use rtl::plane::float::PlaneFloatIo;
use rtl::TesterIo;
use std::collections::VecDeque;
use std::path::Path;
use std::sync::mpsc::sync_channel;

/// Which form of the tester runs the vectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    /// The bit-accurate golden model, native.
    Model,
    /// The rust-hdl block, cycle by cycle.
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
pub type Keyed<K, C> = (K, <C as BlockCtx>::Ray, <C as BlockCtx>::Box);

/// Runs `tests` on the fixed tester of `fmt` (any format for the model; the presets for rtl and verilator).
pub fn run_fix<K, It, F>(
    engine: Engine,
    fmt: FixFormat,
    tests: It,
    verilator_dir: &Path,
    vcd: Option<&Path>,
    sink: F,
) -> Result<u64, String>
where
    K: Send + 'static,
    It: Iterator<Item = Keyed<K, FixFormat>> + Send + 'static,
    F: FnMut(
        K,
        &golden::format::fixed::FixRay,
        golden::slab::fix::SlabFixOut,
    ) -> Result<(), String>,
{
    if engine == Engine::Model {
        return run_model(fmt, tests, vcd, sink);
    }
    let module = rtl::names::slab_fix_module(&fmt);
    rtl::with_slab_fix!(&fmt, S, {
        run_block(
            engine,
            fmt,
            || S::new(&fmt),
            || rtl::export::slab_fix_verilog(&fmt),
            &module,
            tests,
            verilator_dir,
            vcd,
            sink,
        )
    })?
}

/// Runs `tests` on the float tester of format `f` (any format for the model; the instantiated ones for rtl
/// and verilator).
pub fn run_float<K, It, F>(
    engine: Engine,
    f: FloatFormat,
    tests: It,
    verilator_dir: &Path,
    vcd: Option<&Path>,
    sink: F,
) -> Result<u64, String>
where
    K: Send + 'static,
    It: Iterator<Item = Keyed<K, FloatFormat>> + Send + 'static,
    F: FnMut(
        K,
        &golden::slab::float::FloatRay,
        golden::slab::float::SlabFloatOut,
    ) -> Result<(), String>,
{
    if engine == Engine::Model {
        return run_model(f, tests, vcd, sink);
    }
    let module = rtl::names::slab_float_module(&f);
    rtl::with_slab_float!(&f, S, {
        run_block(
            engine,
            f,
            S::new,
            || rtl::export::slab_float_verilog(&f),
            &module,
            tests,
            verilator_dir,
            vcd,
            sink,
        )
    })?
}

/// Runs `tests` on the fixed chained slab + cull-plane tester of `ctx` (any format and `K` for the
/// model; the preset cull formats over b8, b12, b16 with `1 <= K <= 8` for rtl and verilator).
pub fn run_cull_fix<K, It, F>(
    engine: Engine,
    ctx: CullFixCtx,
    tests: It,
    verilator_dir: &Path,
    vcd: Option<&Path>,
    sink: F,
) -> Result<u64, String>
where
    K: Send + 'static,
    It: Iterator<Item = Keyed<K, CullFixCtx>> + Send + 'static,
    F: FnMut(K, &NodeFixRay, PlaneFixOut) -> Result<(), String>,
{
    if engine == Engine::Model {
        return run_model(ctx, tests, vcd, sink);
    }
    let base = ctx.cf.base;
    if ctx.cf != CullFixFormat::over(base) {
        return Err(format!(
            "the rtl and verilator engines take the preset cull formats, not {}",
            ctx.cf.name()
        ));
    }
    let a = (engine, ctx, tests, verilator_dir, vcd, sink);
    rtl::with_plane_fix!(&base, ctx.k, S, { cull_fix_block::<S, _, _, _>(a) })?
}

/// The arguments of [`run_cull_fix`], passed on to the block of the right type.
type CullFixArgs<'a, It, F> = (Engine, CullFixCtx, It, &'a Path, Option<&'a Path>, F);

fn cull_fix_block<S: PlaneFixIo, K, It, F>(
    (engine, ctx, tests, verilator_dir, vcd, sink): CullFixArgs<'_, It, F>,
) -> Result<u64, String>
where
    K: Send + 'static,
    It: Iterator<Item = Keyed<K, CullFixCtx>> + Send + 'static,
    F: FnMut(K, &NodeFixRay, PlaneFixOut) -> Result<(), String>,
{
    let module = ctx.name();
    run_block(
        engine,
        ctx,
        || S::for_format(&ctx.cf),
        || {
            Ok(rtl::verilog::verilog_named(
                &mut S::for_format(&ctx.cf),
                &module,
            ))
        },
        &module,
        tests,
        verilator_dir,
        vcd,
        sink,
    )
}

/// Runs `tests` on the float chained slab + cull-plane tester of `ctx` (any format and `K` for the
/// model; the instantiated ones for rtl and verilator: e5m10 with 1, 2, 4 or 8 planes, e8m7 and
/// e8m23 with 1, 2 or 4: `rtl::PLANE_FLOAT_CONFIGS`).
/// Runs on a thread with a large stack (a `PlaneFloat` block is a large value).
pub fn run_cull_float<K, It, F>(
    engine: Engine,
    ctx: CullFloatCtx,
    tests: It,
    verilator_dir: &Path,
    vcd: Option<&Path>,
    sink: F,
) -> Result<u64, String>
where
    K: Send + 'static,
    It: Iterator<Item = Keyed<K, CullFloatCtx>> + Send + 'static,
    F: FnMut(K, &NodeFloatRay, SlabFloatOut) -> Result<(), String> + Send,
{
    if engine == Engine::Model {
        return run_model(ctx, tests, vcd, sink);
    }
    if ctx.cf != CullFloatFormat::over(ctx.cf.f) {
        return Err(format!(
            "the rtl and verilator engines take the default table (R = min(M, 8)), not {}",
            ctx.cf.name()
        ));
    }
    let module = rtl::names::plane_float_module(&ctx.cf, ctx.k);
    let f = ctx.cf.f;
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(512 << 20)
            .spawn_scoped(s, move || {
                rtl::with_plane_float!(&f, ctx.k, P, {
                    run_block(
                        engine,
                        ctx,
                        P::make,
                        || rtl::export::plane_float_verilog(&f, ctx.k),
                        &module,
                        tests,
                        verilator_dir,
                        vcd,
                        sink,
                    )
                })?
            })
            .map_err(|e| format!("cannot start the simulation thread: {e}"))?
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e))
    })
}

fn run_model<C: TesterCtx, K, It, F>(
    ctx: C,
    tests: It,
    vcd: Option<&Path>,
    mut sink: F,
) -> Result<u64, String>
where
    It: Iterator<Item = Keyed<K, C>>,
    F: FnMut(K, &C::Ray, C::Out) -> Result<(), String>,
{
    if vcd.is_some() {
        return Err("a waveform (--vcd) needs the rtl engine".into());
    }
    let mut n = 0;
    for (k, r, b) in tests {
        sink(k, &r, ctx.model(&r, &b))?;
        n += 1;
    }
    Ok(n)
}

/// Runs `tests` on the rust-hdl block made by `make`, or on its Verilog (`verilog`, top module `module`) in
/// Verilator; `vcd` (rust-hdl only) is where to write a waveform of the whole run.
#[allow(clippy::too_many_arguments)]
pub fn run_block<C, S, K, It, F>(
    engine: Engine,
    ctx: C,
    make: impl Fn() -> S,
    verilog: impl FnOnce() -> Result<String, String>,
    module: &str,
    tests: It,
    verilator_dir: &Path,
    vcd: Option<&Path>,
    mut sink: F,
) -> Result<u64, String>
where
    C: TesterCtx,
    S: TesterIo<Ray = C::Ray, Box = C::Box, Out = C::Out>,
    K: Send + 'static,
    It: Iterator<Item = Keyed<K, C>> + Send + 'static,
    F: FnMut(K, &C::Ray, C::Out) -> Result<(), String>,
{
    let mut waiting: VecDeque<(K, C::Ray)> = VecDeque::new();
    let mut n = 0u64;
    match engine {
        Engine::Model => run_model(ctx, tests, vcd, sink),
        Engine::Rtl => {
            let mut dut = TesterSim::wrap(make());
            if let Some(p) = vcd {
                dut = dut.vcd_to(p).map_err(|e| format!("{}: {e}", p.display()))?;
            }
            let mut deliver = |out: Option<(u16, C::Out)>,
                               waiting: &mut VecDeque<(K, C::Ray)>|
             -> Result<(), String> {
                if let Some((_, res)) = out {
                    let (k, r) = waiting.pop_front().ok_or("a result with no test waiting")?;
                    n += 1;
                    sink(k, &r, res)?;
                }
                Ok(())
            };
            let mut tag = 0u16;
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
        Engine::Verilator => {
            if vcd.is_some() {
                return Err("a waveform (--vcd) needs the rtl engine".into());
            }
            let h = crate::verilator::build(&verilog()?, module, verilator_dir)?;
            let ports = h.inputs.clone();
            let (tx, rx) = sync_channel::<(K, C::Ray)>(1 << 16);
            let mut tag = 0u16;
            let records = tests
                .map(move |(k, r, b)| {
                    let v = Some((r, b));
                    let rec: Vec<u64> = ports
                        .iter()
                        .map(|p| in_word(&ctx, p, tag, &v).unwrap_or_else(|e| panic!("{e}")))
                        .collect();
                    tag = tag.wrapping_add(1);
                    tx.send((k, r)).expect("consumer alive");
                    rec
                })
                .chain(std::iter::repeat_n(
                    vec![0u64; h.inputs.len()],
                    S::LATENCY + 1,
                )); // flush bubbles
            let iv = h.output_index("valid_out").ok_or("no valid_out")?;
            h.stream(records, |_, out| {
                // The producer sends each test before the harness can see it; flush cycles send nothing.
                if let Ok(x) = rx.try_recv() {
                    waiting.push_back(x);
                }
                if out[iv] != 0 {
                    let (k, r) = waiting.pop_front().ok_or("a result with no test waiting")?;
                    n += 1;
                    sink(k, &r, out_of_row(&ctx, &h.outputs, out)?.1)?;
                }
                Ok(())
            })?;
            Ok(n)
        }
    }
}
