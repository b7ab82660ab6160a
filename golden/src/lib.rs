//! Plain-Rust models of the rtu intersection testers.
//!
//! Every tester has three models here (see `shared/design/ARCHITECTURE.md`):
//!
//! | model | slab tester | cull-plane tester | bundle testers | role |
//! | --- | --- | --- | --- | --- |
//! | float reference (f64) | [`slab_ref`] | [`plane`] | [`bundle`] | meaning of the test, accuracy yardstick |
//! | exact oracle (rationals) | [`exact`] | [`plane`] | [`bundle`] | the truth |
//! | bit-accurate fixed point | [`slab_fix`] | [`plane_fix`] | [`bundle_fix`] | native stand-in for the RTL, bit for bit |
//! | bit-accurate float | [`slab_float`] | [`plane_float`] | [`bundle_float`] | the same |
//! | results processor (bit-accurate) | | | [`bundle_split`] | a bundle job: the bundle test, then its rays two per clock |
//!
//! Scenes, BVH, plane generation and traversal for the scene measurements: [`scene`], [`bvh`],
//! [`planegen`], [`traverse`], [`tri`]; bundles on scenes: [`bundle_build`] (the builder and splitting
//! metric), [`bundle_trav`] (bundle traversal, decided vs ideal, cycles); case generators [`gen`],
//! [`cull_gen`], [`bundle_gen`], and the bundle campaign's checks [`bundle_check`].
//!
//! The number formats and the outward quantisation that feeds the bit-accurate models live in [`fixed`];
//! random and adversarial vector generators in [`gen`]; reading and writing user vector files in
//! [`vectors`].

pub mod bundle;
pub mod bundle_build;
pub mod bundle_check;
pub mod bundle_fix;
pub mod bundle_float;
pub mod bundle_gen;
pub mod bundle_split;
pub mod bundle_trav;
pub mod bundle_vectors;
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
pub mod stability;
pub mod vectors;

pub use error::Error;
pub use geom::{Aabb, Ray};
pub mod bvh;
pub mod planegen;
pub mod scene;
pub mod scene_trav;
pub mod traverse;
pub mod tri;
