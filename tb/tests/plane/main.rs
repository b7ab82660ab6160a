//! Tests of the cull-plane testers (`rtl::plane`, `golden::plane`): fixed (table and quotient options) and float, equivalence, Verilog, VCD, users' vectors.
//!
//! One test binary for the family; each file beside this one is a module of it.

mod bound_scale;
mod fix;
mod float_equivalence;
mod float_vcd;
mod float_verilog;
mod quot;
mod shrinking;
mod vectors;
