//! Testbenches of the rtu blocks: per block family the glue between its rust-hdl block, its model and
//! its exported Verilog (port encoding, vector streams, cross-simulation loops), and the machinery every
//! family shares.
//!
//! | module | what it does |
//! | --- | --- |
//! | [`xsim`] | what a testbench knows of a pipelined tester's configuration ([`xsim::BlockCtx`], [`xsim::TesterCtx`]), its port words through the block's codec (`rtl::io::PortCodec`), and the one cross-simulation loop of every pipelined tester |
//! | [`slab::ctx`] | the slab testers' formats as testbench contexts, both datapaths |
//! | [`slab::strategies`] | proptest strategies over quantised slab vectors |
//! | [`plane::fix`] | the fixed cull-plane tester's context, vector streams and the cull-plane campaigns |
//! | [`plane::float`] | the float cull-plane tester's context and vector streams |
//! | [`bundle::pair_fix`] | the fixed bundle pair's vector streams and context |
//! | [`bundle::pair_float`] | the float bundle pair's vector streams and context |
//! | [`bundle::split`] | the results processor's driver, clock-by-clock stimulus, checker and cross-simulation |
//! | [`engine`] | one streaming call over the model, the rust-hdl simulation and Verilator |
//! | [`formal`] | formal proofs on the exported Verilog (SymbiYosys): float units against `symfpu`, pipeline latency by k-induction, mutants |
//! | [`dut`] | the [`dut::PipelinedDut`] trait and a stream runner that checks results, tag order and latency |
//! | [`prop`] | proptest with shrinking and a VCD of the shrunk case for blocks with a random raw-input generator |
//! | [`reset`] | reset checks: `rst` raised while tests stream, rust-hdl against the rule and the model, Verilator against rust-hdl |
//! | [`rtl_sim`] | drives a rust-hdl block cycle by cycle (the fast direct loop), with optional VCD |
//! | [`vcd_read`] | reads a VCD back and measures when `valid` leaves a block |
//! | [`verilog_tools`] | Verilator lint and Icarus on exported Verilog |
//! | [`verilator`] | builds a C++ harness around exported Verilog and streams vectors through it |
//! | [`campaign`] | large streamed conservativeness and cross-simulation campaigns with progress |

pub mod bundle;
pub mod campaign;
pub mod dut;
pub mod engine;
pub mod formal;
pub mod ip;
pub mod plane;
pub mod prop;
pub mod reset;
pub mod rtl_sim;
pub mod slab;
pub mod vcd_plain;
pub mod vcd_read;
pub mod verilator;
pub mod verilog_tools;
pub mod xsim;

/// The project's output folder for generated artefacts (Verilog, VCD, reports, harness builds):
/// `$RTU_OUT`, or `out/` at the workspace root.
pub fn out_dir() -> std::path::PathBuf {
    match std::env::var_os("RTU_OUT") {
        Some(p) => p.into(),
        None => std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("..")
            .join("out"),
    }
}
