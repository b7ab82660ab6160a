//! Tests of the float units (`rtl::fp`): rust-hdl against the model in every mode, and their exported Verilog.
//!
//! One test binary for the family; each file beside this one is a module of it.

mod cmp;
mod min_max;
mod unit_equivalence;
mod unit_verilog;
