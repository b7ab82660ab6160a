//! Tests of the bundle blocks (`rtl::bundle`, `golden::bundle`): the fixed and float pairs and the results processors (one job at a time, and streaming).
//!
//! One test binary for the family; each file beside this one is a module of it.

mod pair_fix;
mod pair_float;
mod shrinking;
mod split;
mod stream;
