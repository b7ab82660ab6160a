//! Testbench glue of the cull-plane testers: fixed ([`fix`], with the cull-plane campaigns) and float
//! ([`float`]).

pub mod fix;
pub mod float;
