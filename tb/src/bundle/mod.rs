//! Testbench glue of the bundle blocks: the fixed pair ([`pair_fix`]), the float pair ([`pair_float`]) and
//! the results processor ([`split`]).

pub mod pair_fix;
pub mod pair_float;
pub mod split;
