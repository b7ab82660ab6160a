//! The AABB slab tester: the f64 reference and the textbook method ([`reference`](mod@reference)), the bit-accurate
//! models of both datapaths ([`fix`], [`float`]), the conservativeness judge ([`check`]), vector
//! generators ([`gen`]) and users' vector files ([`vectors`]). Its exact oracle is [`crate::exact`]; its
//! number formats are in [`crate::format`].

pub mod check;
pub mod fix;
pub mod float;
pub mod gen;
pub mod reference;
pub mod vectors;
