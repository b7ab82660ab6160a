//! The library behind the `rtu` command: every measurement, report and file writer of the command
//! lives here, with its tests; `src/main.rs` only parses the command line and calls one function per
//! command.
//!
//! | module | command | what it measures or writes |
//! | --- | --- | --- |
//! | [`main_job`] | (none), `scene` | the default scene through every preset slab tester, then the small sweep |
//! | [`export_cmd`] | `export` | Verilog, datasheets and FuseSoC cores of every exported module |
//! | [`run_vectors`], [`run_bundles`] | `run`, `gen` | users' vector files through a tester |
//! | [`encode_cmd`] | `encode`, `decode` | world-space vectors as an exported core's port words, and back |
//! | [`campaign_cmd`], [`float_check`], [`cull_cmd`], [`bundle_cmd`] | `campaign`, `float-check`, `cull-campaign`, `cull-scenes`, `bundle-campaign`, `bundle-scenes` | conservativeness and cross-simulation at scale |
//! | [`bench`] | `bench` | throughput of the model, rust-hdl and Verilator |
//! | [`stream_cmd`] | `bundle-stream` | scene job streams through the streaming results processor |
//! | [`sweep_cmd`], [`fit_cmd`], [`synth`], [`chart`] | `sweep`, `fit` | speed against accuracy, the area table, Pareto fronts, format fitting |
//! | [`formal_cmd`], [`stability_cmd`], [`trace_cmd`] | `formal`, `stability`, `trace` | proofs, the textbook methods' failure cases, per-ray traces |
//!
//! Shared: [`opts`] (option parsing the commands share), [`out_file`] (outputs complete or absent),
//! [`scene`] (the main job's scenes).

pub mod bench;
pub mod bundle_cmd;
pub mod campaign_cmd;
pub mod chart;
pub mod cull_cmd;
pub mod encode_cmd;
pub mod export_cmd;
pub mod fit_cmd;
pub mod float_check;
pub mod formal_cmd;
pub mod main_job;
pub mod opts;
pub mod out_file;
pub mod run_bundles;
pub mod run_vectors;
pub mod scene;
pub mod stability_cmd;
pub mod stream_cmd;
pub mod sweep_cmd;
pub mod synth;
pub mod trace_cmd;
