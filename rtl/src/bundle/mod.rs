//! The AllHit / AnyHit bundle blocks (models: `golden::bundle`).
//!
//! | block | file | model it matches |
//! | --- | --- | --- |
//! | [`edge_fix::BundleTest`] | `bundle/edge_fix.rs` | one fixed edge tester (AllHit or AnyHit), `golden::bundle::fix` |
//! | [`pair_fix::BundleFix`] | `bundle/pair_fix.rs` | the fixed pair, `golden::bundle::fix::decide_fix` |
//! | [`edge_le::EdgeLe`], [`dist_le::DistLe`], [`fold_diff::FoldDiff`] | `bundle/*.rs` | the fixed pair's comparisons |
//! | [`edge_float::BundleFloatTest`] | `bundle/edge_float.rs` | one float edge tester, `golden::bundle::float` |
//! | [`pair_float::BundleFloat`] | `bundle/pair_float.rs` | the float pair, `golden::bundle::float::decide_float` |
//! | [`ports::PairFixPorts`], [`ports::PairFloatPorts`] | `bundle/ports.rs` | the port codecs: what each port of the two pairs carries |
//! | [`split::BundleSplit`] | `bundle/split.rs` | the results processor, `golden::bundle::split` |
//! | [`stream::BundleStream`] | `bundle/stream.rs` | the results processor with jobs in flight, `golden::bundle::stream` |
//! | [`stream_ctl::StreamCtl`] | `bundle/stream_ctl.rs` | the control of both streaming processors |
//! | [`stream_float::BundleStreamFloat`] | `bundle/stream_float.rs` | the same around the float pair, `golden::bundle::stream` |
//! | [`ray_store::RayStore`] | `bundle/ray_store.rs` | the two-bank ray store of both processors |
//! | [`rebound::ReboundAcc`] | `bundle/rebound.rs` | re-bounding in the streaming processors (fixed, and float on [`rebound::OrderKeys`]), `golden::bundle::rebound` |
//!
//! Which configurations exist: [`registry`].

pub mod dist_le;
pub mod edge_fix;
pub mod edge_float;
pub mod edge_le;
pub mod fold_diff;
pub mod pair_fix;
pub mod pair_float;
pub mod ports;
pub mod ray_store;
pub mod rebound;
pub mod registry;
pub mod split;
pub mod stream;
pub mod stream_ctl;
pub mod stream_float;
