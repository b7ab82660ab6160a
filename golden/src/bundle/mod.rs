//! The AllHit / AnyHit bundle testers (Imagination, US 11,308,683 family): the division-free edge test
//! with its f64 reference and exact oracle ([`edge`]), the bit-accurate pairs of both datapaths ([`fix`],
//! [`float`]), the results processor ([`split`]) and its streaming form ([`stream`]),
//! re-bounding around the rays a split keeps ([`rebound`]), the builder and splitting metric ([`build`]),
//! bundles on scenes ([`traverse`]), case generators ([`gen`]), the campaign's checks ([`check`]) and users'
//! bundle files ([`vectors`]).

pub mod build;
pub mod check;
pub mod edge;
pub mod fix;
pub mod float;
pub mod gen;
pub mod rebound;
pub mod split;
pub mod stream;
pub mod traverse;
pub mod vectors;
