//! Testbench glue of the bundle blocks: the fixed pair ([`pair_fix`]), the float pair ([`pair_float`]) and
//! the results processors ([`split`], one job at a time; [`stream`], jobs in flight).

pub mod pair_fix;
pub mod pair_float;
pub mod split;
pub mod stream;
pub mod stream_scene;
