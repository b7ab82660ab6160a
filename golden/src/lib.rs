//! Plain-Rust models of the rtu intersection testers.
//!
//! Every tester has three models here (see `shared/design/ARCHITECTURE.md`):
//!
//! | model | module | role |
//! | --- | --- | --- |
//! | float reference (f64) | [`slab_ref`] | meaning of the test, accuracy yardstick |
//! | exact oracle (rationals) | [`exact`] | the truth |
//! | bit-accurate fixed-point model | [`slab_fix`] | native stand-in for the RTL, bit for bit |
//!
//! The number formats and the outward quantisation that feeds the bit-accurate models live in [`fixed`];
//! random and adversarial vector generators in [`gen`]; reading and writing user vector files in
//! [`vectors`].

pub mod check;
pub mod cull_gen;
pub mod error;
pub mod exact;
pub mod fixed;
pub mod float;
pub mod floatcheck;
pub mod gen;
pub mod geom;
pub mod plane;
pub mod plane_fix;
pub mod plane_float;
pub mod slab_fix;
pub mod slab_float;
pub mod slab_ref;
pub mod vectors;

pub use error::Error;
pub use geom::{Aabb, Ray};
pub mod bvh;
pub mod planegen;
pub mod scene;
pub mod traverse;
pub mod tri;
