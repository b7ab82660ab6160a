//! The float units of the float datapaths, each bit for bit a function of `golden::format::float`:
//!
//! | block | file | what it does |
//! | --- | --- | --- |
//! | [`add::FpAdd`] | `fp/add.rs` | add and subtract, 3 clocks (up to 5 with its cut points), one rounding mode a unit |
//! | [`mul::FpMul`] | `fp/mul.rs` | multiply, 3 clocks (up to 5 with its cut points) |
//! | [`round::FpRound`] | `fp/round.rs` | the shared rounding of a normalised significand |
//! | [`sig_mul::SigMul`] | `fp/sig_mul.rs` | significand product and its leading one (hand-written Verilog) |
//! | [`cmp::FpCmp`] | `fp/cmp.rs` | compare |
//! | [`cuts`] | `fp/cuts.rs` | the optional cut points of a datapath of adders and multipliers |
//! | [`min_max`] | `fp/min_max.rs` | minimum and maximum |

pub mod add;
pub mod cmp;
pub mod cuts;
pub mod min_max;
pub mod mul;
pub mod round;
pub mod sig_mul;
