//! The format ladder's RTL instances: one fixed slab tester per grid width of
//! `golden::format::fixed::GRID_LADDER` (`SlabFixG6` .. `SlabFixG20`, formats `golden::format::fixed::FixFormat::grid`) and
//! one float slab tester per format of `golden::format::float::FloatFormat::LADDER` (`SlabFloatE5M3` ..
//! `SlabFloatE8M23`).
//!
//! Const generics need every width at compile time, so each format is one type alias. The lists live in
//! one place each, the hidden macros [`slab_fix_ladder!`](crate::slab_fix_ladder) and
//! [`slab_float_ladder!`](crate::slab_float_ladder), which hand them to a callback macro: here to declare
//! the aliases and the ladder constants, in `rtl/src/slab/registry.rs` to build the dispatch arms of
//! [`with_slab_fix_ladder!`](crate::with_slab_fix_ladder) and
//! [`with_slab_float_ladder!`](crate::with_slab_float_ladder) (the presets-only `with_slab_fix!` and
//! `with_slab_float!` serve the other commands, so the ladder is compiled only where it is used: export
//! of a fitted format). Adding a
//! format is one line in a list (and, for a fixed format off the ladder rule, nothing else: the dispatch
//! compares against `FixFormat::grid`).
//!
//! Cost: every use of a ladder dispatch macro compiles its body once per ladder format (15 fixed, 23
//! float); each use adds minutes to a release build, so there are few.

/// Calls `$crate::$cb!(args... [(G, D, I, T, Alias), ...])` with the fixed ladder, one entry per grid
/// width `G` of `golden::format::fixed::GRID_LADDER`; the widths are `FixFormat::grid(G)`'s (`D = G + 1`).
#[doc(hidden)]
#[macro_export]
macro_rules! slab_fix_ladder {
    ($($call:tt)*) => {
        $crate::__call_with_rows! {
            $($call)* [
                (6, 7, 10, 12, SlabFixG6),
                (7, 8, 11, 13, SlabFixG7),
                (8, 9, 12, 14, SlabFixG8),
                (9, 10, 13, 15, SlabFixG9),
                (10, 11, 14, 17, SlabFixG10),
                (11, 12, 15, 18, SlabFixG11),
                (12, 13, 16, 20, SlabFixG12),
                (13, 14, 17, 21, SlabFixG13),
                (14, 15, 18, 22, SlabFixG14),
                (15, 16, 19, 23, SlabFixG15),
                (16, 17, 20, 24, SlabFixG16),
                (17, 18, 21, 25, SlabFixG17),
                (18, 19, 22, 26, SlabFixG18),
                (19, 20, 23, 27, SlabFixG19),
                (20, 21, 24, 28, SlabFixG20),
            ]
        }
    };
}

/// Calls `$crate::$cb!(args... [(E, M, N, Alias), ...])` with the float ladder, in the order of
/// `golden::format::float::FloatFormat::LADDER` (`N = 1 + E + M`).
#[doc(hidden)]
#[macro_export]
macro_rules! slab_float_ladder {
    ($($call:tt)*) => {
        $crate::__call_with_rows! {
            $($call)* [
                (5, 3, 9, SlabFloatE5M3),
                (5, 4, 10, SlabFloatE5M4),
                (6, 3, 10, SlabFloatE6M3),
                (5, 5, 11, SlabFloatE5M5),
                (6, 4, 11, SlabFloatE6M4),
                (5, 6, 12, SlabFloatE5M6),
                (6, 5, 12, SlabFloatE6M5),
                (5, 7, 13, SlabFloatE5M7),
                (6, 6, 13, SlabFloatE6M6),
                (5, 8, 14, SlabFloatE5M8),
                (6, 7, 14, SlabFloatE6M7),
                (5, 9, 15, SlabFloatE5M9),
                (6, 8, 15, SlabFloatE6M8),
                (5, 10, 16, SlabFloatE5M10),
                (6, 9, 16, SlabFloatE6M9),
                (8, 7, 16, SlabFloatE8M7),
                (6, 10, 17, SlabFloatE6M10),
                (6, 12, 19, SlabFloatE6M12),
                (8, 10, 19, SlabFloatE8M10),
                (8, 12, 21, SlabFloatE8M12),
                (6, 15, 22, SlabFloatE6M15),
                (8, 15, 24, SlabFloatE8M15),
                (8, 23, 32, SlabFloatE8M23),
            ]
        }
    };
}

/// Declares the fixed ladder's aliases and [`SLAB_FIX_LADDER`] (callback of `slab_fix_ladder!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __slab_fix_ladder_items {
    ([$(($g:literal, $d:literal, $i:literal, $t:literal, $alias:ident)),* $(,)?]) => {
        $(
            #[doc = concat!(
                "The fixed slab tester of the ladder format `golden::format::fixed::FixFormat::grid(",
                stringify!($g), ")`: `SlabFix<", stringify!($g), ", ", stringify!($d), ", ",
                stringify!($i), ", ", stringify!($t), ">`."
            )]
            pub type $alias = $crate::SlabFix<$g, $d, $i, $t>;
        )*

        /// The grid widths with an instantiated fixed slab tester, smallest first: every width of
        /// `golden::format::fixed::GRID_LADDER` (`with_slab_fix!` dispatches `FixFormat::grid(g)` for each).
        pub const SLAB_FIX_LADDER: &[u32] = &[$($g),*];
    };
}

/// Declares the float ladder's aliases and [`SLAB_FLOAT_LADDER`] (callback of `slab_float_ladder!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __slab_float_ladder_items {
    ([$(($e:literal, $m:literal, $n:literal, $alias:ident)),* $(,)?]) => {
        $(
            #[doc = concat!(
                "The float slab tester in E", stringify!($e), "M", stringify!($m), " (",
                stringify!($n), " bits), a format of `golden::format::float::FloatFormat::LADDER`."
            )]
            pub type $alias = $crate::SlabFloat<$e, $m, $n>;
        )*

        /// The float formats with an instantiated float slab tester (`with_slab_float_ladder!`), in the order of
        /// `golden::format::float::FloatFormat::LADDER`, narrowest first. [`crate::SLAB_FLOAT_FORMATS`] is the
        /// five of them that the main job, `export_all` and the synthesis report use.
        pub const SLAB_FLOAT_LADDER: &[golden::format::float::FloatFormat] =
            &[$(golden::format::float::FloatFormat { e: $e, m: $m }),*];
    };
}

crate::slab_fix_ladder!(__slab_fix_ladder_items!());
crate::slab_float_ladder!(__slab_float_ladder_items!());
