//! The cull-plane tester (Arm, US 2025/0259373): planes, node layouts, the f64 reference and the exact
//! clip ([`clip`]), the bit-accurate models of both datapaths ([`fix`], [`float`]) and of the fixed
//! tester's fraction option ([`quot`]), case generators
//! ([`gen`]) and plane generation for a BVH ([`generate`]).

pub mod clip;
pub mod fix;
pub mod float;
pub mod gen;
pub mod generate;
pub mod quot;
