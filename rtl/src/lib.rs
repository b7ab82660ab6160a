//! rust-hdl blocks of the rtu testers, one block a file, and their Verilog export.
//!
//! | block | file | model it matches |
//! | --- | --- | --- |
//! | [`axis_dist::AxisDist`] | `axis_dist.rs` | `golden::slab_fix::axis_distances` |
//! | [`mul_round::MulRound`] | `mul_round.rs` | `golden::slab_fix::{mul_floor, mul_ceil}` |
//! | [`slab_fix::SlabFix`] | `slab_fix.rs` | `golden::slab_fix::slab_fix` |

pub mod axis_dist;
pub mod delay;
pub mod export;
pub mod fp_add;
pub mod fp_cmp;
pub mod fp_min_max;
pub mod fp_mul;
pub mod fp_round;
pub mod mul_round;
pub mod plane_bound;
pub mod plane_fix;
pub mod plane_sums;
pub mod sig_mul;
pub mod slab_fix;
pub mod slab_float;
pub mod slab_io;

pub use fp_add::FpAdd;
pub use fp_mul::FpMul;
pub use slab_fix::{SlabFix, SLAB_FIX_LATENCY, TAG_BITS};
pub use slab_float::{SlabFloat, SLAB_FLOAT_LATENCY};
pub use slab_io::SlabIo;

/// The slab tester for `golden::fixed::FixFormat::b8()` (the same type as the ladder's `SlabFixG8`).
pub type SlabFixB8 = SlabFix<8, 9, 12, 14>;
/// The slab tester for `golden::fixed::FixFormat::b12()` (the same type as `SlabFixG12`).
pub type SlabFixB12 = SlabFix<12, 13, 16, 20>;
/// The slab tester for `golden::fixed::FixFormat::b16()` (the same type as `SlabFixG16`).
pub type SlabFixB16 = SlabFix<16, 17, 20, 24>;

/// The chained slab + cull-plane tester over b12 with the default plane format (`N = 8`, `FD = 11`,
/// `R = 8`) and `K` planes.
pub type PlaneFixB12<const K: usize> = plane_fix::PlaneFix<12, 13, 16, 20, 8, 14, 24, 25, 23, K>;
/// The same over b8 (`FD = 8`).
pub type PlaneFixB8<const K: usize> = plane_fix::PlaneFix<8, 9, 12, 14, 8, 11, 20, 21, 20, K>;
/// The same over b16 (`FD = 14`).
pub type PlaneFixB16<const K: usize> = plane_fix::PlaneFix<16, 17, 20, 24, 8, 17, 28, 29, 26, K>;

// The format ladder: `SlabFixG6` .. `SlabFixG20`, `SlabFloatE5M3` .. `SlabFloatE8M23` (binary32 is
// `SlabFloatE8M23`, bfloat16 `SlabFloatE8M7`, binary16 `SlabFloatE5M10`), `SLAB_FIX_LADDER`,
// `SLAB_FLOAT_LADDER`.
pub mod ladder;
pub use ladder::*;

/// Runs `$body` with `$t` bound to the `SlabFix` type of a preset format, or returns an error for a
/// format without an instantiated block (const generics need the widths at compile time).
#[macro_export]
macro_rules! with_slab_fix {
    ($fmt:expr, $t:ident, $body:block) => {{
        let f: &golden::fixed::FixFormat = $fmt;
        if *f == golden::fixed::FixFormat::b8() {
            type $t = $crate::SlabFixB8;
            Ok($body)
        } else if *f == golden::fixed::FixFormat::b12() {
            type $t = $crate::SlabFixB12;
            Ok($body)
        } else if *f == golden::fixed::FixFormat::b16() {
            type $t = $crate::SlabFixB16;
            Ok($body)
        } else {
            Err(format!(
                "no RTL instance for format {}: the RTL is instantiated for the presets b8, b12, b16 \
                 (add a type alias in rtl/src/lib.rs for another)",
                f.name()
            ))
        }
    }};
}

/// Like [`with_slab_fix!`] for every format on the grid ladder
/// (`golden::fixed::FixFormat::grid(g)` for `g` in 6..=20, which includes the presets b8, b12, b16), or
/// returns an error for a format without an instantiated block (const generics need the widths at compile
/// time). `$body` is compiled once per ladder format.
#[macro_export]
macro_rules! with_slab_fix_ladder {
    ($fmt:expr, $t:ident, $body:block) => {{
        let f: &golden::fixed::FixFormat = $fmt;
        $crate::slab_fix_ladder!(__with_slab_fix_arms!(f, $t, $body))
    }};
}

/// The dispatch arms of `with_slab_fix!` (callback of `slab_fix_ladder!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_slab_fix_arms {
    ($f:ident, $t:ident, $body:block
        [$(($g:literal, $d:literal, $i:literal, $tb:literal, $alias:ident)),* $(,)?]) => {
        match $f.g {
            $(
                $g if *$f == golden::fixed::FixFormat::grid($g).expect("a ladder format") => {
                    type $t = $crate::$alias;
                    Ok($body)
                }
            )*
            _ => Err(format!(
                "no RTL instance for format {}: the RTL is instantiated for the grid ladder g6 .. g20 \
                 (golden::fixed::FixFormat::grid; b8, b12, b16 among them) \
                 (add a type alias in rtl/src/ladder.rs for another)",
                $f.name()
            )),
        }
    };
}

/// The float formats of the main job, `export::export_all` and the synthesis report: the five
/// instantiated before the format ladder. Every format of [`SLAB_FLOAT_LADDER`] has a block.
pub const SLAB_FLOAT_FORMATS: [golden::float::FloatFormat; 5] = [
    golden::float::FloatFormat::FP32,
    golden::float::FloatFormat::E8M15,
    golden::float::FloatFormat::BF16,
    golden::float::FloatFormat::FP16,
    golden::float::FloatFormat { e: 6, m: 5 },
];

/// Runs `$body` with `$t` bound to the `SlabFloat` type of a float format, or returns an error for a
/// format without an instantiated block.
#[macro_export]
macro_rules! with_slab_float {
    ($f:expr, $t:ident, $body:block) => {{
        let f: &golden::float::FloatFormat = $f;
        match (f.e, f.m) {
            (8, 23) => {
                type $t = $crate::SlabFloatE8M23;
                Ok($body)
            }
            (8, 15) => {
                type $t = $crate::SlabFloatE8M15;
                Ok($body)
            }
            (8, 7) => {
                type $t = $crate::SlabFloatE8M7;
                Ok($body)
            }
            (5, 10) => {
                type $t = $crate::SlabFloatE5M10;
                Ok($body)
            }
            (6, 5) => {
                type $t = $crate::SlabFloatE6M5;
                Ok($body)
            }
            _ => Err(format!(
                "no RTL instance for float format {}: instantiated are e8m23, e8m15, e8m7, e5m10, e6m5 \
                 (add a type alias in rtl/src/lib.rs for another)",
                f.name()
            )),
        }
    }};
}

/// Like [`with_slab_float!`] for every float format of the ladder
/// ([`SLAB_FLOAT_LADDER`], `golden::float::FloatFormat::LADDER`), or returns an error for a format without
/// an instantiated block. `$body` is compiled once per ladder format.
#[macro_export]
macro_rules! with_slab_float_ladder {
    ($f:expr, $t:ident, $body:block) => {{
        let f: &golden::float::FloatFormat = $f;
        $crate::slab_float_ladder!(__with_slab_float_arms!(f, $t, $body))
    }};
}

/// The dispatch arms of `with_slab_float!` (callback of `slab_float_ladder!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_slab_float_arms {
    ($f:ident, $t:ident, $body:block
        [$(($e:literal, $m:literal, $n:literal, $alias:ident)),* $(,)?]) => {
        match ($f.e, $f.m) {
            $(
                ($e, $m) => {
                    type $t = $crate::$alias;
                    Ok($body)
                }
            )*
            _ => Err(format!(
                "no RTL instance for float format {}: instantiated are the float ladder \
                 (E5 M3..=10, E6 M3..=10, 12, 15, E8 M7, 10, 12, 15, 23; golden::float::FloatFormat::LADDER) \
                 (add a type alias in rtl/src/ladder.rs for another)",
                $f.name()
            )),
        }
    };
}

pub mod fp_recip;
pub mod plane_float;
pub mod plane_float_export;

pub use plane_float::{PlaneFloat, PLANE_FLOAT_LATENCY};

/// The chained float node tester (slab + 1 cull plane) in binary16.
pub type PlaneFloatE5M10K1 = PlaneFloat<5, 10, 16, 1>;
/// The chained float node tester (slab + 2 cull planes) in binary16.
pub type PlaneFloatE5M10K2 = PlaneFloat<5, 10, 16, 2>;
/// The chained float node tester (slab + 4 cull planes) in binary16.
pub type PlaneFloatE5M10K4 = PlaneFloat<5, 10, 16, 4>;
/// The chained float node tester (slab + 8 cull planes, the most) in binary16.
pub type PlaneFloatE5M10K8 = PlaneFloat<5, 10, 16, 8>;
/// The chained float node tester (slab + 1 cull plane) in bfloat16.
pub type PlaneFloatE8M7K1 = PlaneFloat<8, 7, 16, 1>;
/// The chained float node tester (slab + 2 cull planes) in bfloat16.
pub type PlaneFloatE8M7K2 = PlaneFloat<8, 7, 16, 2>;
/// The chained float node tester (slab + 4 cull planes) in bfloat16.
pub type PlaneFloatE8M7K4 = PlaneFloat<8, 7, 16, 4>;
/// The chained float node tester (slab + 1 cull plane) in binary32.
pub type PlaneFloatE8M23K1 = PlaneFloat<8, 23, 32, 1>;
/// The chained float node tester (slab + 2 cull planes) in binary32.
pub type PlaneFloatE8M23K2 = PlaneFloat<8, 23, 32, 2>;
/// The chained float node tester (slab + 4 cull planes) in binary32.
pub type PlaneFloatE8M23K4 = PlaneFloat<8, 23, 32, 4>;

pub mod code_frac_cmp;
pub mod frac_cmp;
pub mod frac_pick;
pub mod frac_tree;
pub mod plane_frac;
pub mod plane_frac_bound;

/// The fraction option of the chained tester ([`plane_frac::PlaneFrac`]) over b12 (`N = 8`, `FD = 11`)
/// with `K` planes.
pub type PlaneFracB12<const K: usize> =
    plane_frac::PlaneFrac<12, 13, 16, 20, 8, 14, 24, 25, 23, 22, 47, K>;
/// The same over b8 (`FD = 8`).
pub type PlaneFracB8<const K: usize> =
    plane_frac::PlaneFrac<8, 9, 12, 14, 8, 11, 20, 21, 20, 19, 40, K>;
/// The same over b16 (`FD = 14`).
pub type PlaneFracB16<const K: usize> =
    plane_frac::PlaneFrac<16, 17, 20, 24, 8, 17, 28, 29, 26, 25, 54, K>;

pub mod bundle_fix;
pub mod bundle_test;
pub mod dist_le;
pub mod edge_le;
pub mod fold_diff;

/// The fixed-point AllHit + AnyHit bundle pair over b8 (`FD = 6`).
pub type BundleFixB8 = bundle_fix::BundleFix<8, 9, 9, 14>;
/// The same over b12 (`FD = 10`).
pub type BundleFixB12 = bundle_fix::BundleFix<12, 13, 13, 20>;
/// The same over b16 (`FD = 14`).
pub type BundleFixB16 = bundle_fix::BundleFix<16, 17, 17, 24>;

pub mod bundle_float;
pub mod bundle_float_test;

/// The float AllHit + AnyHit bundle pair in binary32.
pub type BundleFloatFp32 = bundle_float::BundleFloat<8, 23, 32>;
/// The same in bfloat16.
pub type BundleFloatBf16 = bundle_float::BundleFloat<8, 7, 16>;
/// The same in binary16.
pub type BundleFloatFp16 = bundle_float::BundleFloat<5, 10, 16>;

/// The float formats with an instantiated float bundle pair (`with_bundle_float!`).
pub const BUNDLE_FLOAT_FORMATS: [golden::float::FloatFormat; 3] = [
    golden::float::FloatFormat::FP32,
    golden::float::FloatFormat::BF16,
    golden::float::FloatFormat::FP16,
];

pub mod bundle_split;

/// The bundle results processor ([`bundle_split::BundleSplit`], 16 rays) over b8 (`FD = 6`).
pub type BundleSplitB8 = bundle_split::BundleSplit<8, 9, 9, 14>;
/// The same over b12 (`FD = 10`).
pub type BundleSplitB12 = bundle_split::BundleSplit<12, 13, 13, 20>;
/// The same over b16 (`FD = 14`).
pub type BundleSplitB16 = bundle_split::BundleSplit<16, 17, 17, 24>;
