//! Testbench glue of the slab testers: port encoding and cross-simulation ([`ports`]), proptest
//! strategies ([`strategies`]).

pub mod ports;
pub mod strategies;
