//! The slab testers that exist, one table per datapath: [`slab_fix_presets!`](crate::slab_fix_presets)
//! (the preset fixed formats, each at the default and the 6-clock depth) and
//! [`slab_float_presets!`](crate::slab_float_presets) (the five float formats of the main job, each at
//! the default and the 13-clock depth). From each table come the type aliases and the format list below,
//! the per-format dispatch (`with_slab_fix!`, `with_slab_float!`) and the export catalogue's rows
//! (`rtl/src/export.rs`), so a configuration is added by one row. The format ladder (every grid width,
//! every ladder float format, default depth) has its own tables in [`super::ladder`].

/// Calls `$crate::$cb!(args... [(preset, [G, D, I, T], Alias, DeepAlias), ...])` with the fixed slab
/// testers over the presets (`golden::format::fixed::FixFormat::b8()`, ...): `Alias` is
/// `SlabFix<G, D, I, T>` (the default depth, the same type as the ladder's `SlabFixG<G>`), `DeepAlias`
/// the 6-clock tester ([`super::fix::SLAB_FIX_CUTS_DEEP`]: multiplies with registered operands and
/// products).
#[doc(hidden)]
#[macro_export]
macro_rules! slab_fix_presets {
    ($($call:tt)*) => {
        $crate::__call_with_rows! {
            $($call)* [
                (b8, [8, 9, 12, 14], SlabFixB8, SlabFixB8P6),
                (b12, [12, 13, 16, 20], SlabFixB12, SlabFixB12P6),
                (b16, [16, 17, 20, 24], SlabFixB16, SlabFixB16P6),
            ]
        }
    };
}

/// Calls `$crate::$cb!(args... [(E, M, N, Alias, DeepAlias), ...])` with the five float formats of the
/// main job, the export and the synthesis report: `Alias` is the ladder's default-depth tester
/// (`rtl/src/slab/ladder.rs`), `DeepAlias` the 13-clock one ([`super::float::SLAB_FLOAT_CUTS_DEEP`]:
/// adders cut after the alignment and after the normalisation, multipliers after the raw and after the
/// normalised product).
#[doc(hidden)]
#[macro_export]
macro_rules! slab_float_presets {
    ($($call:tt)*) => {
        $crate::__call_with_rows! {
            $($call)* [
                (8, 23, 32, SlabFloatE8M23, SlabFloatE8M23P13),
                (8, 15, 24, SlabFloatE8M15, SlabFloatE8M15P13),
                (8, 7, 16, SlabFloatE8M7, SlabFloatE8M7P13),
                (5, 10, 16, SlabFloatE5M10, SlabFloatE5M10P13),
                (6, 5, 12, SlabFloatE6M5, SlabFloatE6M5P13),
            ]
        }
    };
}

/// Declares the preset fixed testers' aliases (callback of `slab_fix_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __slab_fix_preset_items {
    ([$(($p:ident, [$($w:literal),*], $alias:ident, $deep:ident)),* $(,)?]) => {
        $(
            #[doc = concat!(
                "The slab tester for `golden::format::fixed::FixFormat::", stringify!($p),
                "()`: `SlabFix<", stringify!($($w),*), ">` (the ladder's alias of the same width is the same type)."
            )]
            pub type $alias = $crate::SlabFix<$($w),*>;
            #[doc = concat!(
                "The 6-clock slab tester for ", stringify!($p),
                " (`rtl::slab::fix::SLAB_FIX_CUTS_DEEP`: multiplies with registered operands and products)."
            )]
            pub type $deep = $crate::SlabFix<$($w,)* { $crate::slab::fix::SLAB_FIX_CUTS_DEEP }>;
        )*
    };
}

/// Declares the float presets' deep aliases and [`SLAB_FLOAT_FORMATS`] (callback of
/// `slab_float_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __slab_float_preset_items {
    ([$(($e:literal, $m:literal, $n:literal, $alias:ident, $deep:ident)),* $(,)?]) => {
        $(
            #[doc = concat!(
                "The 13-clock float slab tester in E", stringify!($e), "M", stringify!($m),
                " (`rtl::slab::float::SLAB_FLOAT_CUTS_DEEP`)."
            )]
            pub type $deep =
                $crate::SlabFloat<$e, $m, $n, { $crate::slab::float::SLAB_FLOAT_CUTS_DEEP }>;
        )*

        /// The float formats of the main job, `export::catalog` and the synthesis report (the rows of
        /// `slab_float_presets!`); every format of [`SLAB_FLOAT_LADDER`] has a default-depth block.
        pub const SLAB_FLOAT_FORMATS: [golden::format::float::FloatFormat; [$($e),*].len()] =
            [$(golden::format::float::FloatFormat { e: $e, m: $m }),*];
    };
}

crate::slab_fix_presets!(__slab_fix_preset_items!());
crate::slab_float_presets!(__slab_float_preset_items!());

/// The float formats the stability study compares with the textbook test
/// (`golden::stability::SLAB_FLOAT_FORMATS`, which cannot see this crate) are exactly the instantiated
/// presets: the testbench runs that comparison on these blocks.
const _: () = {
    let (a, b) = (&SLAB_FLOAT_FORMATS, &golden::stability::SLAB_FLOAT_FORMATS);
    assert!(a.len() == b.len());
    let mut i = 0;
    while i < a.len() {
        assert!(a[i].e == b[i].e && a[i].m == b[i].m);
        i += 1;
    }
};

/// Runs `$body` with `$t` bound to the default `SlabFix` type of a preset format, or returns an error for
/// a format without an instantiated block (const generics need the widths at compile time). `$body` is
/// compiled once per preset.
#[macro_export]
macro_rules! with_slab_fix {
    ($fmt:expr, $t:ident, $body:block) => {{
        let f: &golden::format::fixed::FixFormat = $fmt;
        $crate::slab_fix_presets!(__with_slab_fix_preset_arms!(f, $t, $body))
    }};
}

/// The dispatch arms of `with_slab_fix!` (callback of `slab_fix_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_slab_fix_preset_arms {
    ($f:ident, $t:ident, $body:block
        [$(($p:ident, [$($w:literal),*], $alias:ident, $deep:ident)),* $(,)?]) => {
        $crate::__fix_preset_arms!($f, $t, $body, "SlabFix",
            "slab_fix_presets! in rtl/src/slab/registry.rs" [$(($p, $crate::$alias)),*])
    };
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

/// The dispatch arms of `with_slab_fix_ladder!` (callback of `slab_fix_ladder!`).
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
                 (add a row to slab_fix_ladder! in rtl/src/slab/ladder.rs for another)",
                $f.name()
            )),
        }
    };
}

/// Runs `$body` with `$t` bound to the default `SlabFloat` type of a preset float format
/// ([`SLAB_FLOAT_FORMATS`]), or returns an error for a format without an instantiated block.
#[macro_export]
macro_rules! with_slab_float {
    ($f:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
        $crate::slab_float_presets!(__with_slab_float_preset_arms!(f, $t, $body))
    }};
}

/// The dispatch arms of `with_slab_float!` (callback of `slab_float_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_slab_float_preset_arms {
    ($f:ident, $t:ident, $body:block
        [$(($e:literal, $m:literal, $n:literal, $alias:ident, $deep:ident)),* $(,)?]) => {
        $crate::__float_arms!($f, $t, $body, "SlabFloat",
            "slab_float_presets! in rtl/src/slab/registry.rs" [$(($e, $m, $crate::$alias)),*])
    };
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

/// The dispatch arms of `with_slab_float_ladder!` (callback of `slab_float_ladder!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_slab_float_arms {
    ($f:ident, $t:ident, $body:block
        [$(($e:literal, $m:literal, $n:literal, $alias:ident)),* $(,)?]) => {
        $crate::__float_arms!($f, $t, $body, "RTL",
            "slab_float_ladder! in rtl/src/slab/ladder.rs" [$(($e, $m, $crate::$alias)),*])
    };
}
