//! Testbench glue of the slab testers: their configurations as testbench contexts ([`ctx`]), proptest
//! strategies ([`strategies`]). The cross-simulation loop is [`crate::xsim`].

pub mod ctx;
pub mod strategies;
