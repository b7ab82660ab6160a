//! The cull-plane testers that exist, one table per datapath: [`plane_fix_presets!`](crate::plane_fix_presets)
//! (the fixed tester over each preset grid: the table option at the default and the 11-clock depth, and
//! the quotient option) and [`plane_float_configs!`](crate::plane_float_configs) (the float tester's
//! format and plane count pairs). From each table come the type aliases and the configuration list
//! below, and the dispatch (`with_plane_fix!`, `with_plane_float!`), so a configuration is added by one
//! row. Which of them are exported (1 and 4 planes) is the export catalogue's choice
//! (`rtl/src/export.rs`).

/// Calls `$crate::$cb!(args... [(preset, [G, D, I, T, N, DB, WB, SB, EB], Alias, DeepAlias, [MB, FB],
/// QuotAlias), ...])` with the fixed cull-plane testers over the presets
/// (`golden::format::fixed::FixFormat::b8()`, ...; `golden::plane::fix::CullFixFormat::over` gives the
/// plane format, `N = 8` and `FD = FI`: 8, 11, 14): `Alias<K>` is the table option
/// `PlaneFix<G, .., EB, K>` at the default depth, `DeepAlias<K>` the same at the 11-clock depth
/// (`rtl::plane::fix::PLANE_FIX_DEEP`), and `QuotAlias<K>` the quotient option
/// `PlaneQuot<G, .., EB, MB, FB, K>`.
#[doc(hidden)]
#[macro_export]
macro_rules! plane_fix_presets {
    ($($call:tt)*) => {
        $crate::__call_with_rows! {
            $($call)* [
                (b8, [8, 9, 12, 14, 8, 11, 20, 21, 20], PlaneFixB8, PlaneFixB8P11, [19, 40], PlaneQuotB8),
                (b12, [12, 13, 16, 20, 8, 14, 24, 25, 23], PlaneFixB12, PlaneFixB12P11, [22, 47], PlaneQuotB12),
                (b16, [16, 17, 20, 24, 8, 17, 28, 29, 26], PlaneFixB16, PlaneFixB16P11, [25, 54], PlaneQuotB16),
            ]
        }
    };
}

/// Calls `$crate::$cb!(args... [(E, M, N, K, Alias), ...])` with the chained float node testers (slab +
/// `K` cull planes) that are instantiated: `Alias` is `PlaneFloat<E, M, N, K>`.
#[doc(hidden)]
#[macro_export]
macro_rules! plane_float_configs {
    ($($call:tt)*) => {
        $crate::__call_with_rows! {
            $($call)* [
                (5, 10, 16, 1, PlaneFloatE5M10K1),
                (5, 10, 16, 2, PlaneFloatE5M10K2),
                (5, 10, 16, 4, PlaneFloatE5M10K4),
                (5, 10, 16, 8, PlaneFloatE5M10K8),
                (8, 7, 16, 1, PlaneFloatE8M7K1),
                (8, 7, 16, 2, PlaneFloatE8M7K2),
                (8, 7, 16, 4, PlaneFloatE8M7K4),
                (8, 23, 32, 1, PlaneFloatE8M23K1),
                (8, 23, 32, 2, PlaneFloatE8M23K2),
                (8, 23, 32, 4, PlaneFloatE8M23K4),
            ]
        }
    };
}

/// Declares the fixed testers' aliases (callback of `plane_fix_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __plane_fix_preset_items {
    ([$(($p:ident, [$($w:literal),*], $alias:ident, $deep:ident, [$($q:literal),*], $quot:ident)),* $(,)?]) => {
        $(
            #[doc = concat!(
                "The chained slab + cull-plane tester (table option, default depth) over ",
                stringify!($p), " with the default plane format and `K` planes: `PlaneFix<",
                stringify!($($w),*), ", K>`."
            )]
            pub type $alias<const K: usize> = $crate::plane::fix::PlaneFix<$($w,)* K>;
            #[doc = concat!(
                "The same over ", stringify!($p),
                " in the deep configuration (11 clocks, `rtl::plane::fix::PLANE_FIX_DEEP`)."
            )]
            pub type $deep<const K: usize> = $crate::plane::fix::PlaneFix<
                $($w,)*
                K,
                { $crate::plane::fix::PLANE_FIX_DEEP.0 },
                { $crate::plane::fix::PLANE_FIX_DEEP.1 },
            >;
            #[doc = concat!(
                "The quotient option of the chained tester (`rtl::plane::quot::PlaneQuot`) over ",
                stringify!($p), " with `K` planes."
            )]
            pub type $quot<const K: usize> = $crate::plane::quot::PlaneQuot<$($w,)* $($q,)* K>;
        )*
    };
}

/// Declares the float testers' aliases and [`PLANE_FLOAT_CONFIGS`] (callback of `plane_float_configs!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __plane_float_config_items {
    ([$(($e:literal, $m:literal, $n:literal, $k:literal, $alias:ident)),* $(,)?]) => {
        $(
            #[doc = concat!(
                "The chained float node tester (slab + ", stringify!($k), " cull planes) in E",
                stringify!($e), "M", stringify!($m), "."
            )]
            pub type $alias = $crate::plane::float::PlaneFloat<$e, $m, $n, $k>;
        )*

        /// The (float format, planes) pairs with an instantiated `PlaneFloat` (the rows of
        /// `plane_float_configs!`).
        pub const PLANE_FLOAT_CONFIGS: [(golden::format::float::FloatFormat, usize); [$($k),*].len()] =
            [$((golden::format::float::FloatFormat { e: $e, m: $m }, $k)),*];
    };
}

crate::plane_fix_presets!(__plane_fix_preset_items!());
crate::plane_float_configs!(__plane_float_config_items!());

/// Runs `$body` with `$t` bound to the `PlaneFloat` type of a float format and plane count, or returns an
/// error for a configuration without an instantiated block. `$body` is compiled once per configuration.
#[macro_export]
macro_rules! with_plane_float {
    ($f:expr, $k:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
        let k: usize = $k;
        $crate::plane_float_configs!(__with_plane_float_arms!(f, k, $t, $body))
    }};
}

/// The dispatch arms of `with_plane_float!` (callback of `plane_float_configs!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_plane_float_arms {
    ($f:ident, $kk:ident, $t:ident, $body:block
        [$(($e:literal, $m:literal, $n:literal, $k:literal, $alias:ident)),* $(,)?]) => {
        match ($f.e, $f.m, $kk) {
            $(
                ($e, $m, $k) => {
                    type $t = $crate::$alias;
                    Ok($body)
                }
            )*
            _ => Err(format!(
                "no PlaneFloat instance for {} with {} planes: instantiated are {} \
                 (add a row to plane_float_configs! in rtl/src/plane/registry.rs for another)",
                $f.name(),
                $kk,
                [$(concat!("e", stringify!($e), "m", stringify!($m), " k", stringify!($k))),*].join(", ")
            )),
        }
    };
}

/// Runs `$body` with `$t` bound to the `PlaneFix` type (table option, default depth) over a preset slab
/// format with `$k` planes (1 to 8), or returns an error for a configuration without an instantiated
/// block. `$body` is compiled once per format and plane count.
#[macro_export]
macro_rules! with_plane_fix {
    ($base:expr, $k:expr, $t:ident, $body:block) => {{
        let f: &golden::format::fixed::FixFormat = $base;
        let k: usize = $k;
        match k {
            1 => $crate::plane_fix_presets!(__with_plane_fix_arms!(f, 1, $t, $body)),
            2 => $crate::plane_fix_presets!(__with_plane_fix_arms!(f, 2, $t, $body)),
            3 => $crate::plane_fix_presets!(__with_plane_fix_arms!(f, 3, $t, $body)),
            4 => $crate::plane_fix_presets!(__with_plane_fix_arms!(f, 4, $t, $body)),
            5 => $crate::plane_fix_presets!(__with_plane_fix_arms!(f, 5, $t, $body)),
            6 => $crate::plane_fix_presets!(__with_plane_fix_arms!(f, 6, $t, $body)),
            7 => $crate::plane_fix_presets!(__with_plane_fix_arms!(f, 7, $t, $body)),
            8 => $crate::plane_fix_presets!(__with_plane_fix_arms!(f, 8, $t, $body)),
            k => Err(format!(
                "{k} planes: the cull-plane RTL takes 1 to 8 (the model takes 0 to 8)"
            )),
        }
    }};
}

/// The format arms of `with_plane_fix!` for one plane count (callback of `plane_fix_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_plane_fix_arms {
    ($f:ident, $k:literal, $t:ident, $body:block
        [$(($p:ident, [$($w:literal),*], $alias:ident, $deep:ident, [$($q:literal),*], $quot:ident)),* $(,)?]) => {
        $crate::__fix_preset_arms!($f, $t, $body, "PlaneFix",
            "plane_fix_presets! in rtl/src/plane/registry.rs" [$(($p, $crate::$alias<$k>)),*])
    };
}
