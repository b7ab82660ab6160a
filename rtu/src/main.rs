//! `rtu`: the command-line front door of the ray-tracing-unit intersection model.
//!
//! With no subcommand it runs the main job on the built-in default scene (`rtu::main_job`). This file only
//! parses the command line and calls one library function per command (the library: `src/lib.rs`).

use clap::{Parser, Subcommand};
use rtu::*;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "rtu",
    version,
    about = "Cycle-accurate RTL model of a ray-tracing unit's intersection testers"
)]
struct Cli {
    /// Output folder for Verilog, VCD, reports and harness builds.
    #[arg(long, global = true, default_value = "out")]
    out: PathBuf,
    #[command(subcommand)]
    cmd: Option<Cmd>,
}

#[derive(Subcommand)]
enum Cmd {
    /// The main job: the default scene through the RTL slab tester of every preset width (the default).
    Scene(main_job::Args),
    /// Write one Verilog file per block and preset configuration into <out>/verilog, each with its
    /// datasheet (<module>.md) and FuseSoC core file (<module>.core).
    Export(export_cmd::Args),
    /// Run a file of rays and boxes (JSON lines or CSV) through a tester and write the results.
    Run(run_vectors::RunArgs),
    /// World-space vectors (the files of `run`) as the words on an exported core's ports: one line per
    /// test, a hex word per port (<prefix>.in.hex), the model's expected output words (<prefix>.out.hex)
    /// and the packed words for $readmemh (<prefix>.mem).
    Encode(encode_cmd::EncodeArgs),
    /// Output words captured from a simulation of an exported core, back to world-space results, written
    /// as `run` writes them.
    Decode(encode_cmd::DecodeArgs),
    /// Write generated vectors (uniform, adversarial or mixed) to a file, for `run` or other tools.
    Gen(run_vectors::GenArgs),
    /// Conservativeness against the exact oracle and cross-simulation in Verilator, at scale.
    Campaign(campaign_cmd::Args),
    /// The float model against half, native f32 and exact rounding, at campaign scale.
    FloatCheck(float_check::Args),
    /// Throughput of the model, the rust-hdl simulation and Verilator, measured in one run.
    Bench(bench::Args),
    /// Cull planes: the models against the exact clip and an exact ray-triangle test, at scale.
    CullCampaign(cull_cmd::CampaignArgs),
    /// Ray bundles on scenes with the AllHit / AnyHit pair: bundle-box tests decided without splitting
    /// against the ideal, and tester cycles against testing the rays one by one (writes
    /// bundle_scenes.csv and bundle_scenes.md).
    BundleScenes(bundle_cmd::Args),
    /// The bundle pair's conservativeness campaign: random and adversarial bundles on every datapath
    /// against the exact per-ray results and the exact oracle (writes bundle_campaign.md).
    BundleCampaign(bundle_cmd::CampaignArgs),
    /// Scene job streams through the streaming results processor's RTL (rust-hdl, checked clock by
    /// clock): clocks, pair-input utilisation against the model's busy-pair count, clocks per job
    /// (writes bundle_stream_<format>.csv and .md, the format as bundle-scenes names it: b12, e5m10).
    BundleStream(stream_cmd::Args),
    /// The smallest fixed-point and float formats whose slab tester meets a budget of extra tester cycles
    /// on each scene and ray set, their area and latency against fp32, and their Verilog (writes
    /// fit/fit.csv, fit/fit.md, fit/*.v; --synth runs Yosys on fitted formats not in the area table).
    Fit(fit_cmd::Args),
    /// Formal proofs on the exported Verilog (SymbiYosys): the float units against symfpu's correctly
    /// rounded reference, every tester's latency, valid and tag by k-induction, each with a mutant that
    /// must fail (writes formal/formal.csv, formal/formal.md, formal/cex/*.vcd).
    Formal(formal_cmd::Args),
    /// Synthesise exported modules with Yosys (generic, iCE40 with logic depth, Xilinx 7-series; all
    /// flattened): area and depth per module (writes synth/report.csv and synth/report.md).
    Synth(synth::Args),
    /// The failure cases of the textbook methods across the three testers, naive against ours (writes
    /// stability.csv and stability.md).
    Stability,
    /// Speed against accuracy on scenes: every datapath, format, planes per node and bundle size through
    /// one traversal model, against the exact machine, joined with the synthesis table; writes sweep.csv,
    /// sweep.md and per scene two SVG charts with the Pareto front.
    Sweep(sweep_cmd::Args),
    /// Per-ray results of one configuration on one scene (ray, closest triangle and its OBJ line, t, the
    /// work it took) as CSV, every hit checked against brute force: compare with another renderer.
    Trace(trace_cmd::Args),
    /// Cull planes on scenes: triangle tests saved against AABB-only traversal (the same format with no
    /// planes, and exact), with each node's own normals or normals shared by siblings, bytes per node,
    /// closest hits compared with the exact reference.
    CullScenes(cull_cmd::ScenesArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let out = &cli.out;
    let r = match cli.cmd.unwrap_or(Cmd::Scene(main_job::Args::default())) {
        Cmd::Scene(a) => main_job::front_door(&a, out),
        Cmd::Export(a) => {
            export_cmd::export(&out.join("verilog"), a.datasheets.as_deref()).map(|ps| {
                for p in ps {
                    println!("{}", p.display());
                }
            })
        }
        Cmd::Run(a) => run_vectors::run_cmd(&a, out),
        Cmd::Gen(a) => run_vectors::gen_cmd(&a),
        Cmd::Encode(a) => encode_cmd::encode(&a, out).map(|s| eprintln!("{s}")),
        Cmd::Decode(a) => encode_cmd::decode(&a),
        Cmd::Campaign(a) => campaign_cmd::run(&a, out),
        Cmd::FloatCheck(a) => float_check::run(&a, out),
        Cmd::Bench(a) => bench::run(&a, out),
        Cmd::CullCampaign(a) => cull_cmd::campaign_cmd(&a, out),
        Cmd::BundleScenes(a) => bundle_cmd::scenes(&a, out).and_then(|t| {
            print!("{t}");
            out_file::write_file(&out.join("bundle_scenes.md"), t)
        }),
        Cmd::Fit(a) => fit_cmd::run(&a, out).map(|t| print!("{t}")),
        Cmd::Formal(a) => formal_cmd::run(&a, out).map(|t| print!("{t}")),
        Cmd::Synth(a) => synth::run(&a, out).map(|t| print!("{t}")),
        Cmd::Stability => stability_cmd::run(out).map(|t| print!("{t}")),
        Cmd::Sweep(a) => sweep_cmd::run(&a, out).map(|t| print!("{t}")),
        Cmd::Trace(a) => trace_cmd::run(&a, out).map(|t| print!("{t}")),
        Cmd::BundleStream(a) => stream_cmd::run(&a, out).map(|t| print!("{t}")),
        Cmd::BundleCampaign(a) => bundle_cmd::campaign(&a, out).map(|t| print!("{t}")),
        Cmd::CullScenes(a) => cull_cmd::scenes_cmd(&a, out),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rtu: {e}");
            ExitCode::FAILURE
        }
    }
}
