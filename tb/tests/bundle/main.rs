//! Tests of the bundle blocks (`rtl::bundle`, `golden::bundle`): the fixed and float pairs and the results processor.
//!
//! One test binary for the family; each file beside this one is a module of it.

mod pair_fix;
mod pair_float;
mod shrinking;
mod split;
