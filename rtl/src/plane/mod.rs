//! The cull-plane testers: the slab tester chained with `K` planes (models: `golden::plane`).
//!
//! | block | file | model it matches |
//! | --- | --- | --- |
//! | [`fix::PlaneFix`] | `plane/fix.rs` | `golden::plane::fix::node_fix` |
//! | [`sums::PlaneSums`] | `plane/sums.rs` | `golden::plane::fix::plane_sums` |
//! | [`bound::PlaneBound`] | `plane/bound.rs` | `golden::plane::fix::bound_from_sums` |
//! | [`bound_pick::BoundPick`] | `plane/bound_pick.rs` | `golden::plane::fix::bound_pick` |
//! | [`bound_table::BoundTable`] | `plane/bound_table.rs` | `golden::plane::fix::recip_entry` |
//! | [`bound_mul::BoundMul`] | `plane/bound_mul.rs` | the product `A * r` of `golden::plane::fix::scale_bound` |
//! | [`bound_scale::BoundScale`] | `plane/bound_scale.rs` | `golden::plane::fix::scale_product` |
//! | [`float::PlaneFloat`] | `plane/float.rs` | `golden::plane::float::cull_float` |
//! | [`recip::FpRecip`] | `plane/recip.rs` | `golden::plane::float::recip_float` |
//! | [`quot::PlaneQuot`] | `plane/quot.rs` | `golden::plane::quot::node_quot` (the quotient option: bounds kept as exact quotients) |
//! | [`quot_bound::PlaneQuotBound`] | `plane/quot_bound.rs` | `golden::plane::fix::cull_fix_quotients` |
//! | [`quot_cmp::QuotCmp`], [`quot_code_cmp::CodeQuotCmp`], [`quot_pick::QuotPick`], [`quot_tree::QuotTree`] | `plane/quot_*.rs` | orderings of quotients by cross-multiplication |
//! | [`ports::PlaneFixPorts`], [`ports::PlaneQuotPorts`], [`ports::PlaneFloatPorts`] | `plane/ports.rs` | the port codecs: what each port of the three testers carries |
//!
//! Which configurations exist, and the dispatch over them: [`registry`].

pub mod bound;
pub mod bound_mul;
pub mod bound_pick;
pub mod bound_scale;
pub mod bound_table;
pub mod fix;
pub mod float;
pub mod ports;
pub mod quot;
pub mod quot_bound;
pub mod quot_cmp;
pub mod quot_code_cmp;
pub mod quot_pick;
pub mod quot_tree;
pub mod recip;
pub mod registry;
pub mod sums;
