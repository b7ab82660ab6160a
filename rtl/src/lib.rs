//! rust-hdl blocks of the rtu testers, one folder per block family, one block a file, and their Verilog
//! export.
//!
//! | family | what | bit-accurate models |
//! | --- | --- | --- |
//! | [`fp`] | float units: adder, multiplier, rounding, comparator, min/max | `golden::format::float` |
//! | [`slab`] | the AABB slab testers, fixed and float | `golden::slab` |
//! | [`plane`] | the cull-plane testers, fixed (table and quotient options) and float | `golden::plane` |
//! | [`bundle`] | the AllHit / AnyHit edge testers, the pairs and the results processor | `golden::bundle` |
//!
//! Shared: [`io`] (the port interface of every pipelined tester: [`io::TesterIo`], [`io::PortCodec`], [`tester_ports!`]), [`cut`] (pipeline cut points and
//! waits), [`delay`], [`dispatch`] (the configuration tables' shared machinery), [`verilog`] (a block's Verilog text with plain names), [`names`] (every exported
//! module's name, made in one place), [`export`] (Verilog export of every configuration and the catalogue
//! of exported modules). Blocks import neither [`names`] nor [`export`]; those two read the blocks.
//!
//! Which configurations exist is said once per datapath of a family, by one table macro in the family's
//! `registry` ([`slab::registry`], [`plane::registry`], [`bundle::registry`]; the slab tester's format
//! ladder in [`slab::ladder`]): a row per format gives its type aliases (one per depth), and from the same
//! rows come the format lists, the per-format dispatch macros (`with_slab_fix!`, `with_plane_float!`, ...)
//! and the export catalogue's rows ([`export::catalog`]). Aliases, lists and macros are re-exported here.

pub mod bundle;
pub mod cut;
pub mod delay;
pub mod dispatch;
pub mod export;
pub mod fp;
pub mod io;
pub mod names;
pub mod plane;
pub mod slab;
pub mod verilog;

pub use bundle::registry::*;
pub use fp::add::FpAdd;
pub use fp::mul::FpMul;
pub use io::TesterIo;
pub use plane::float::{PlaneFloat, PLANE_FLOAT_LATENCY};
pub use plane::registry::*;
pub use slab::fix::{SlabFix, SLAB_FIX_LATENCY, TAG_BITS};
pub use slab::float::{SlabFloat, SLAB_FLOAT_LATENCY};
pub use slab::ladder::*;
pub use slab::registry::*;
