//! Tests of the AABB slab testers (`rtl::slab`, `golden::slab`): fixed and float, equivalence, conservativeness, corner cases, Verilog and VCD.
//!
//! One test binary for the family; each file beside this one is a module of it.

mod fix_conservative;
mod fix_corners;
mod fix_equivalence;
mod fix_verilog;
mod float_conservative;
mod float_corners;
mod float_equivalence;
mod float_verilog;
mod mul_round;
mod reset;
mod vcd;
