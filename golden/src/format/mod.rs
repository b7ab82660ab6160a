//! Number formats and outward quantisation: the fixed-point grid and t codes ([`fixed`]), the
//! bit-accurate float format in three rounding modes ([`float`]) and the exact characterisation of
//! correct rounding that checks it ([`float_check`]).

pub mod fixed;
pub mod float;
pub mod float_check;
