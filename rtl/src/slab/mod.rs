//! The AABB slab testers (models: `golden::slab`):
//!
//! | block | file | model it matches |
//! | --- | --- | --- |
//! | [`fix::SlabFix`] | `slab/fix.rs` | `golden::slab::fix::slab_fix` |
//! | [`axis_dist::AxisDist`] | `slab/axis_dist.rs` | `golden::slab::fix::axis_distances` |
//! | [`mul_round::MulRound`] | `slab/mul_round.rs` | `golden::slab::fix::{mul_floor, mul_ceil}` |
//! | [`float::SlabFloat`] | `slab/float.rs` | `golden::slab::float::slab_float` |
//! | [`ports::SlabFixPorts`], [`ports::SlabFloatPorts`] | `slab/ports.rs` | the port codecs: what each port of the two testers carries |
//!
//! Which configurations exist: [`registry`] (presets, the main job's float formats, dispatch) and
//! [`ladder`] (the format ladder of the fit).

pub mod axis_dist;
pub mod fix;
pub mod float;
pub mod ladder;
pub mod mul_round;
pub mod ports;
pub mod registry;
