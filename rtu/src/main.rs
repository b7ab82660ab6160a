//! `rtu`: the command-line front door of the ray-tracing-unit intersection model.
//!
//! With no subcommand it runs the main job on the built-in default scene (see [`main_job`]).

mod bench;
mod bundle_cmd;
mod campaign_cmd;
mod chart;
mod cull_cmd;
mod encode_cmd;
mod export_cmd;
mod fit_cmd;
mod float_check;
mod formal_cmd;
mod main_job;
mod out_file;
mod run_bundles;
mod run_vectors;
mod scene;
mod stability_cmd;
mod stream_cmd;
mod sweep_cmd;
mod synth;
mod trace_cmd;

use clap::{Parser, Subcommand};
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
    Scene {
        /// Image width in rays.
        #[arg(long, default_value_t = 48)]
        width: usize,
        /// Image height in rays.
        #[arg(long, default_value_t = 32)]
        height: usize,
        /// Instead of the default room of boxes, a triangle scene: a built-in name (room, grass, mesh,
        /// soup) or an OBJ file; the boxes are its BVH's first 48 nodes, the rays its camera's, and the
        /// small sweep runs on it.
        #[arg(long)]
        scene: Option<String>,
    },
    /// Write one Verilog file per block and preset configuration into <out>/verilog, each with its
    /// datasheet (<module>.md) and FuseSoC core file (<module>.core).
    Export(export_cmd::Args),
    /// Run a file of rays and boxes (JSON lines or CSV) through a tester and write the results.
    Run {
        /// Input vectors (`.csv` is CSV, anything else JSON lines; `-` reads JSON lines from stdin).
        input: PathBuf,
        /// Where to write results (same format as the input); stdout when absent.
        #[arg(long, short)]
        output: Option<PathBuf>,
        /// model, rtl or verilator.
        #[arg(long, default_value = "model")]
        engine: tb::engine::Engine,
        /// Format: fixed b8, b12, b16 or G,I,FI,T,FT; float fp32, fp16, bf16 or eXmY. The rtl and verilator
        /// engines take the instantiated ones (fixed presets; e8m23, e8m15, e8m7, e5m10, e6m5).
        #[arg(long, default_value = "b16")]
        format: String,
        /// Run the chained slab + cull-plane tester with this many planes per node (0 to 8; the rtl and
        /// verilator engines take 1 to 8 with b8, b12, b16 and 1, 2, 4 with fp16, bf16, fp32); each
        /// vector's planes (`planes` in JSON, `p0_nx..p7_w` in CSV) are fitted outward into the format.
        #[arg(long)]
        planes: Option<usize>,
        /// Fixed formats: scene bounds `x0,y0,z0,x1,y1,z1` for the grid; by default the bounds of the file's
        /// origins and boxes.
        #[arg(long)]
        bounds: Option<String>,
        /// Write a waveform of the run here (rtl engine).
        #[arg(long)]
        vcd: Option<PathBuf>,
        /// The input is bundle vectors (JSON lines: a bundle by its rays or its bounds, and a box) for the
        /// AllHit / AnyHit pair and the results processor (model engine; rtl engine on b8, b12, b16).
        #[arg(long)]
        bundles: bool,
    },
    /// World-space vectors (the files of `run`) as the words on an exported core's ports: one line per
    /// test, a hex word per port (<prefix>.in.hex), the model's expected output words (<prefix>.out.hex)
    /// and the packed words for $readmemh (<prefix>.mem).
    Encode(encode_cmd::EncodeArgs),
    /// Output words captured from a simulation of an exported core, back to world-space results, written
    /// as `run` writes them.
    Decode(encode_cmd::DecodeArgs),
    /// Write generated vectors (uniform, adversarial or mixed) to a file, for `run` or other tools.
    Gen {
        #[arg(long, default_value = "mixed")]
        kind: golden::slab::gen::GenKind,
        #[arg(long, short, default_value_t = 1000)]
        n: u64,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output file (`.csv` for CSV); stdout when absent.
        #[arg(long, short)]
        output: Option<PathBuf>,
    },
    /// Conservativeness against the exact oracle and cross-simulation in Verilator, at scale.
    Campaign(campaign_cmd::Args),
    /// The float model against half, native f32 and exact rounding, at campaign scale.
    FloatCheck(float_check::Args),
    /// Throughput of the model, the rust-hdl simulation and Verilator, measured in one run.
    Bench(bench::Args),
    /// Cull planes: the models against the exact clip and an exact ray-triangle test, at scale.
    CullCampaign {
        /// Cases per datapath, format and K (half uniform, half adversarial).
        #[arg(long, default_value_t = 1_000_000)]
        vectors: u64,
        /// Planes per node, comma separated.
        #[arg(long, default_value = "4")]
        k: String,
        /// Fixed formats (b8, b12, b16), comma separated; empty for none.
        #[arg(long, default_value = "b8,b12,b16")]
        fixed: String,
        /// Float formats (fp32, bf16, fp16, eXmY), comma separated; empty for none.
        #[arg(long, default_value = "fp32,bf16,fp16")]
        float: String,
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
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
    CullScenes {
        /// Scenes, comma-separated: built-in names (grass, room, mesh, soup) or OBJ files (`*.obj`).
        #[arg(long, default_value = "grass,room,mesh")]
        scenes: String,
        #[arg(long, default_value = "1,2,4,8")]
        k: String,
        #[arg(long, default_value = "b12,b16")]
        fixed: String,
        #[arg(long, default_value = "bf16,fp16,fp32")]
        float: String,
        #[arg(long, default_value_t = 64)]
        width: usize,
        #[arg(long, default_value_t = 48)]
        height: usize,
    },
}

/// The items of a comma-separated option, each parsed (blank items skipped).
pub(crate) fn list<T>(
    s: &str,
    parse: impl Fn(&str) -> Result<T, String>,
) -> Result<Vec<T>, String> {
    s.split(',')
        .map(str::trim)
        .filter(|x| !x.is_empty())
        .map(parse)
        .collect()
}

fn parse_k(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(k) if (1..=golden::plane::fix::MAX_PLANES).contains(&k) => Ok(k),
        _ => Err(format!(
            "K = `{s}`: planes per node must be a number in 1..=8"
        )),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let r = match cli.cmd.unwrap_or(Cmd::Scene {
        width: 48,
        height: 32,
        scene: None,
    }) {
        Cmd::Scene {
            width,
            height,
            scene: tri,
        } => {
            let scene = match &tri {
                None => Ok(scene::room(width, height)),
                Some(name) => sweep_cmd::load_scene(name, 1)
                    .and_then(|ts| scene::from_tri(&ts, width, height, 48)),
            };
            scene
                .and_then(|scene| main_job::run(&scene, &cli.out))
                .map(|(rows, _)| {
                    println!("\n{}", main_job::table(&rows));
                    println!(
                        "wrote {}/report.md, {}/summary.csv, {}/verilog/, {}/vcd/",
                        cli.out.display(),
                        cli.out.display(),
                        cli.out.display(),
                        cli.out.display()
                    );
                    if rows
                        .iter()
                        .any(|r| r.violations > 0 || r.rtl_model_mismatches > 0)
                    {
                        return Err(
                            "conservativeness violations or RTL/model mismatches: see above"
                                .to_string(),
                        );
                    }
                    // The small version of the sweep: speed against accuracy on the triangle room.
                    let mut sweep = sweep_cmd::Args::small();
                    if let Some(name) = &tri {
                        sweep.scenes = name.clone();
                    }
                    let dir = cli.out.join("sweep");
                    sweep_cmd::run(&sweep, &dir).map(|t| {
                        println!(
                            "\nSpeed against accuracy (small sweep: {}):\n\n{t}",
                            sweep.describe()
                        );
                        println!(
                            "wrote {}/sweep.csv, sweep.md and the charts sweep_*.svg",
                            dir.display()
                        );
                    })
                })
                .and_then(|x| x)
        }
        Cmd::Export(a) => export_cmd::export(&cli.out.join("verilog"), a.datasheets.as_deref())
            .map(|ps| {
                for p in ps {
                    println!("{}", p.display());
                }
            }),
        Cmd::Run {
            input,
            output,
            engine,
            format,
            planes,
            bounds,
            vcd,
            bundles: true,
        } => (|| {
            if planes.is_some() {
                return Err("--bundles does not take --planes".to_string());
            }
            let grid = bounds
                .as_deref()
                .map(run_vectors::parse_bounds)
                .transpose()?;
            run_bundles::run(
                &input,
                output.as_deref(),
                engine,
                &format,
                grid,
                vcd.as_deref(),
            )
        })(),
        Cmd::Run {
            input,
            output,
            engine,
            format,
            planes,
            bounds,
            vcd,
            bundles: false,
        } => run_vectors::run(
            &input,
            output.as_deref(),
            engine,
            &format,
            planes,
            bounds.as_deref(),
            vcd.as_deref(),
            &cli.out,
        ),
        Cmd::Gen {
            kind,
            n,
            seed,
            output,
        } => run_vectors::gen(kind, n, seed, output.as_deref()),
        Cmd::Encode(a) => encode_cmd::encode(&a, &cli.out).map(|s| eprintln!("{s}")),
        Cmd::Decode(a) => encode_cmd::decode(&a),
        Cmd::Campaign(a) => campaign_cmd::run(&a, &cli.out),
        Cmd::FloatCheck(a) => float_check::run(&a, &cli.out),
        Cmd::Bench(a) => bench::run(&a, &cli.out),
        Cmd::CullCampaign {
            vectors,
            k,
            fixed,
            float,
            seed,
        } => (|| {
            let ks = list(&k, parse_k)?;
            let fx = list(&fixed, |s| {
                golden::format::fixed::FixFormat::parse(s).map_err(|e| e.to_string())
            })?;
            let fl = list(&float, |s| {
                golden::format::float::FloatFormat::parse(s).map_err(|e| e.to_string())
            })?;
            let t = cull_cmd::campaign(vectors, &ks, &fx, &fl, seed)?;
            print!("{t}");
            std::fs::create_dir_all(&cli.out).map_err(|e| format!("{}: {e}", cli.out.display()))?;
            crate::out_file::write_file(&cli.out.join("cull_campaign.md"), t)
        })(),
        Cmd::BundleScenes(a) => bundle_cmd::scenes(&a, &cli.out).and_then(|t| {
            print!("{t}");
            crate::out_file::write_file(&cli.out.join("bundle_scenes.md"), t)
        }),
        Cmd::Fit(a) => fit_cmd::run(&a, &cli.out).map(|t| print!("{t}")),
        Cmd::Formal(a) => formal_cmd::run(&a, &cli.out).map(|t| print!("{t}")),
        Cmd::Stability => stability_cmd::run(&cli.out).map(|t| print!("{t}")),
        Cmd::Sweep(a) => sweep_cmd::run(&a, &cli.out).map(|t| print!("{t}")),
        Cmd::Trace(a) => trace_cmd::run(&a, &cli.out).map(|t| print!("{t}")),
        Cmd::BundleStream(a) => stream_cmd::run(&a, &cli.out).map(|t| print!("{t}")),
        Cmd::BundleCampaign(a) => bundle_cmd::campaign(&a, &cli.out).map(|t| print!("{t}")),
        Cmd::CullScenes {
            scenes,
            k,
            fixed,
            float,
            width,
            height,
        } => (|| {
            let ks = list(&k, parse_k)?;
            let fx = list(&fixed, |s| {
                golden::format::fixed::FixFormat::parse(s).map_err(|e| e.to_string())
            })?;
            let fl = list(&float, |s| {
                golden::format::float::FloatFormat::parse(s).map_err(|e| e.to_string())
            })?;
            let names = list(&scenes, |s| Ok(s.to_string()))?;
            let t = cull_cmd::scenes(&names, &ks, &fx, &fl, width, height, &cli.out)?;
            print!("{t}");
            crate::out_file::write_file(&cli.out.join("cull_scenes.md"), t)
        })(),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rtu: {e}");
            ExitCode::FAILURE
        }
    }
}
