//! The slab testers that exist: the preset aliases of the fixed tester, the five float formats of the
//! main job, and the per-format dispatch macros (`with_slab_fix!`, `with_slab_float!` and their ladder
//! forms). The format ladder's aliases are in [`super::ladder`].

use super::fix::SlabFix;

/// The slab tester for `golden::format::fixed::FixFormat::b8()` (the same type as the ladder's `SlabFixG8`).
pub type SlabFixB8 = SlabFix<8, 9, 12, 14>;
/// The slab tester for `golden::format::fixed::FixFormat::b12()` (the same type as `SlabFixG12`).
pub type SlabFixB12 = SlabFix<12, 13, 16, 20>;
/// The slab tester for `golden::format::fixed::FixFormat::b16()` (the same type as `SlabFixG16`).
pub type SlabFixB16 = SlabFix<16, 17, 20, 24>;

/// The 6-clock slab tester for b8 ([`super::fix::SLAB_FIX_CUTS_DEEP`]: multiplies with registered
/// operands and products).
pub type SlabFixB8P6 = SlabFix<8, 9, 12, 14, { super::fix::SLAB_FIX_CUTS_DEEP }>;
/// The 6-clock slab tester for b12.
pub type SlabFixB12P6 = SlabFix<12, 13, 16, 20, { super::fix::SLAB_FIX_CUTS_DEEP }>;
/// The 6-clock slab tester for b16.
pub type SlabFixB16P6 = SlabFix<16, 17, 20, 24, { super::fix::SLAB_FIX_CUTS_DEEP }>;

/// Runs `$body` with `$t` bound to the `SlabFix` type of a preset format, or returns an error for a
/// format without an instantiated block (const generics need the widths at compile time).
#[macro_export]
macro_rules! with_slab_fix {
    ($fmt:expr, $t:ident, $body:block) => {{
        let f: &golden::format::fixed::FixFormat = $fmt;
        if *f == golden::format::fixed::FixFormat::b8() {
            type $t = $crate::SlabFixB8;
            Ok($body)
        } else if *f == golden::format::fixed::FixFormat::b12() {
            type $t = $crate::SlabFixB12;
            Ok($body)
        } else if *f == golden::format::fixed::FixFormat::b16() {
            type $t = $crate::SlabFixB16;
            Ok($body)
        } else {
            Err(format!(
                "no RTL instance for format {}: the RTL is instantiated for the presets b8, b12, b16 \
                 (add a type alias in rtl/src/slab/registry.rs for another)",
                f.name()
            ))
        }
    }};
}

/// Like `with_slab_fix!` for every format on the grid ladder
/// (`golden::format::fixed::FixFormat::grid(g)` for `g` in 6..=20, which includes the presets b8, b12, b16), or
/// returns an error for a format without an instantiated block (const generics need the widths at compile
/// time). `$body` is compiled once per ladder format.
#[macro_export]
macro_rules! with_slab_fix_ladder {
    ($fmt:expr, $t:ident, $body:block) => {{
        let f: &golden::format::fixed::FixFormat = $fmt;
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
                $g if *$f == golden::format::fixed::FixFormat::grid($g).expect("a ladder format") => {
                    type $t = $crate::$alias;
                    Ok($body)
                }
            )*
            _ => Err(format!(
                "no RTL instance for format {}: the RTL is instantiated for the grid ladder g6 .. g20 \
                 (golden::format::fixed::FixFormat::grid; b8, b12, b16 among them) \
                 (add a type alias in rtl/src/slab/ladder.rs for another)",
                $f.name()
            )),
        }
    };
}

/// The float formats of the main job, `export::export_all` and the synthesis report: the five
/// instantiated before the format ladder. Every format of [`SLAB_FLOAT_LADDER`] has a block.
pub const SLAB_FLOAT_FORMATS: [golden::format::float::FloatFormat; 5] = [
    golden::format::float::FloatFormat::FP32,
    golden::format::float::FloatFormat::E8M15,
    golden::format::float::FloatFormat::BF16,
    golden::format::float::FloatFormat::FP16,
    golden::format::float::FloatFormat { e: 6, m: 5 },
];

/// The 13-clock float slab tester in binary32 ([`super::float::SLAB_FLOAT_CUTS_DEEP`]: adders cut after the
/// alignment and after the normalisation, multipliers after the raw and after the normalised product).
pub type SlabFloatE8M23P13 =
    super::float::SlabFloat<8, 23, 32, { super::float::SLAB_FLOAT_CUTS_DEEP }>;
/// The 13-clock float slab tester in E8M15.
pub type SlabFloatE8M15P13 =
    super::float::SlabFloat<8, 15, 24, { super::float::SLAB_FLOAT_CUTS_DEEP }>;
/// The 13-clock float slab tester in bfloat16.
pub type SlabFloatE8M7P13 =
    super::float::SlabFloat<8, 7, 16, { super::float::SLAB_FLOAT_CUTS_DEEP }>;
/// The 13-clock float slab tester in binary16.
pub type SlabFloatE5M10P13 =
    super::float::SlabFloat<5, 10, 16, { super::float::SLAB_FLOAT_CUTS_DEEP }>;
/// The 13-clock float slab tester in E6M5.
pub type SlabFloatE6M5P13 =
    super::float::SlabFloat<6, 5, 12, { super::float::SLAB_FLOAT_CUTS_DEEP }>;

/// Runs `$body` with `$t` bound to the `SlabFloat` type of a float format, or returns an error for a
/// format without an instantiated block.
#[macro_export]
macro_rules! with_slab_float {
    ($f:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
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
                 (add a type alias in rtl/src/slab/registry.rs for another)",
                f.name()
            )),
        }
    }};
}

/// Like `with_slab_float!` for every float format of the ladder
/// (`SLAB_FLOAT_LADDER`, `golden::format::float::FloatFormat::LADDER`), or returns an error for a format without
/// an instantiated block. `$body` is compiled once per ladder format.
#[macro_export]
macro_rules! with_slab_float_ladder {
    ($f:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
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
                 (E5 M3..=10, E6 M3..=10, 12, 15, E8 M7, 10, 12, 15, 23; golden::format::float::FloatFormat::LADDER) \
                 (add a type alias in rtl/src/slab/ladder.rs for another)",
                $f.name()
            )),
        }
    };
}
