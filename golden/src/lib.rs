//! Plain-Rust models of the rtu intersection testers, one folder per block family.
//!
//! | family | float reference (f64) | exact oracle (rationals) | bit-accurate fixed point | bit-accurate float | also |
//! | --- | --- | --- | --- | --- | --- |
//! | [`slab`] | [`slab::reference`] | [`exact`] | [`slab::fix`] | [`slab::float`] | judge [`slab::check`], generators [`slab::gen`], files [`slab::vectors`] |
//! | [`plane`] | [`plane::clip`] | [`plane::clip`] | [`plane::fix`] | [`plane::float`] | generators [`plane::gen`], plane generation [`plane::generate`] |
//! | [`bundle`] | [`bundle::edge`] | [`bundle::edge`] | [`bundle::fix`] | [`bundle::float`] | results processor [`bundle::split`], builder [`bundle::build`], on scenes [`bundle::traverse`], generators [`bundle::gen`], checks [`bundle::check`], files [`bundle::vectors`] |
//!
//! The float reference gives the meaning of a test and the accuracy yardstick, the exact oracle the
//! truth, and the bit-accurate models stand in for the RTL (`rtl` matches them bit for bit).
//!
//! Shared by every family: [`format`](mod@format) (the fixed-point grid, the float format, the exact check of
//! rounding), [`exact`] (rational arithmetic and the slab tester's exact oracle), [`geom`] (world rays
//! and boxes), [`error`] (one error type). Scenes: [`scene`] (triangle scenes and OBJ, the exact
//! triangle test, BVH, the closest-hit traversal, the sweeps' traversal model). [`stability`]: the
//! catalogue of inputs on which the textbook methods of all three testers fail.

pub mod bundle;
pub mod error;
pub mod exact;
pub mod format;
pub mod geom;
pub mod plane;
pub mod scene;
pub mod slab;
pub mod stability;
pub mod text;

pub use error::Error;
pub use geom::{Aabb, Ray};
