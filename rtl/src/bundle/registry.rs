//! The bundle blocks that exist, one table per datapath: [`bundle_fix_presets!`](crate::bundle_fix_presets)
//! (over each preset grid: the fixed pair at 3 and 5 clocks, the results processor, and the streaming
//! processor around either pair) and [`bundle_float_presets!`](crate::bundle_float_presets) (in binary32,
//! bfloat16 and binary16: the float pair at 9 and 13 clocks and the streaming processor around either).
//! From each table come the type aliases, the format list and the dispatch below (`with_bundle_float!`,
//! `with_bundle_stream_float!`, `with_bundle_split!`, `with_bundle_stream!`), so a format is added by one
//! row. Which of them are exported is the export catalogue's choice (`rtl/src/export.rs`).

/// Calls `$crate::$cb!(args... [(preset, [G, V, D, T], Pair, PairP5, Split, Stream, StreamP5), ...])` with
/// the fixed bundle blocks over the presets (`golden::bundle::fix::BundleFixFormat::presets()`, named by
/// their grid, `golden::format::fixed::FixFormat::b8()`, ...): `Pair` is `BundleFix<G, V, D, T>` (3 clocks),
/// `PairP5` the 5-clock pair (products and compares registered, `rtl::bundle::edge_fix::BUNDLE_TEST_CUTS_DEEP`),
/// `Split` the results processor (16 rays), `Stream` and `StreamP5` the streaming processor (jobs in
/// flight, 4 sets of 16 rays) around the 3-clock and the 5-clock pair.
#[doc(hidden)]
#[macro_export]
macro_rules! bundle_fix_presets {
    ($($call:tt)*) => {
        $crate::__call_with_rows! {
            $($call)* [
                (b8, [8, 9, 9, 14], BundleFixB8, BundleFixB8P5, BundleSplitB8, BundleStreamB8, BundleStreamB8P5),
                (b12, [12, 13, 13, 20], BundleFixB12, BundleFixB12P5, BundleSplitB12, BundleStreamB12, BundleStreamB12P5),
                (b16, [16, 17, 17, 24], BundleFixB16, BundleFixB16P5, BundleSplitB16, BundleStreamB16, BundleStreamB16P5),
            ]
        }
    };
}

/// Calls `$crate::$cb!(args... [(name, E, M, N, Pair, PairP13, Stream, StreamP13), ...])` with the float
/// bundle blocks: `Pair` is `BundleFloat<E, M, N>` (9 clocks), `PairP13` the 13-clock pair (every optional
/// cut of its adders and multipliers, `rtl::fp::cuts::ALL`), `Stream` and `StreamP13` the streaming
/// processor around either.
#[doc(hidden)]
#[macro_export]
macro_rules! bundle_float_presets {
    ($($call:tt)*) => {
        $crate::__call_with_rows! {
            $($call)* [
                (fp32, 8, 23, 32, BundleFloatFp32, BundleFloatFp32P13, BundleStreamFp32, BundleStreamFp32P13),
                (bf16, 8, 7, 16, BundleFloatBf16, BundleFloatBf16P13, BundleStreamBf16, BundleStreamBf16P13),
                (fp16, 5, 10, 16, BundleFloatFp16, BundleFloatFp16P13, BundleStreamFp16, BundleStreamFp16P13),
            ]
        }
    };
}

/// Declares the fixed bundle blocks' aliases (callback of `bundle_fix_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __bundle_fix_preset_items {
    ([$(($p:ident, [$($w:literal),*], $pair:ident, $pair5:ident, $split:ident, $stream:ident, $stream5:ident)),* $(,)?]) => {
        $(
            #[doc = concat!(
                "The fixed-point AllHit + AnyHit bundle pair over ", stringify!($p),
                " (3 clocks): `BundleFix<", stringify!($($w),*), ">`."
            )]
            pub type $pair = $crate::bundle::pair_fix::BundleFix<$($w),*>;
            #[doc = concat!(
                "The 5-clock fixed pair over ", stringify!($p),
                " (products and compares registered, `rtl::bundle::edge_fix::cut`)."
            )]
            pub type $pair5 = $crate::bundle::pair_fix::BundleFix<
                $($w,)*
                { $crate::bundle::edge_fix::BUNDLE_TEST_CUTS_DEEP },
            >;
            #[doc = concat!(
                "The bundle results processor (`rtl::bundle::split::BundleSplit`, 16 rays) over ",
                stringify!($p), "."
            )]
            pub type $split = $crate::bundle::split::BundleSplit<$($w),*>;
            #[doc = concat!(
                "The streaming results processor (`rtl::bundle::stream::BundleStream`, jobs in flight, ",
                "4 sets of 16 rays) over ", stringify!($p), " around the 3-clock pair."
            )]
            pub type $stream = $crate::bundle::stream::BundleStream<$($w),*>;
            #[doc = concat!(
                "The streaming results processor over ", stringify!($p), " around the 5-clock pair."
            )]
            pub type $stream5 = $crate::bundle::stream::BundleStream<
                $($w,)*
                { $crate::bundle::edge_fix::BUNDLE_TEST_CUTS_DEEP },
            >;
        )*
    };
}

/// Declares the float bundle blocks' aliases and [`BUNDLE_FLOAT_FORMATS`] (callback of
/// `bundle_float_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __bundle_float_preset_items {
    ([$(($name:ident, $e:literal, $m:literal, $n:literal, $pair:ident, $pair13:ident, $stream:ident, $stream13:ident)),* $(,)?]) => {
        $(
            #[doc = concat!(
                "The float AllHit + AnyHit bundle pair in ", stringify!($name), " (9 clocks)."
            )]
            pub type $pair = $crate::bundle::pair_float::BundleFloat<$e, $m, $n>;
            #[doc = concat!(
                "The 13-clock float pair in ", stringify!($name),
                " (every optional cut of its adders and multipliers, `rtl::fp::cuts::ALL`)."
            )]
            pub type $pair13 =
                $crate::bundle::pair_float::BundleFloat<$e, $m, $n, { $crate::fp::cuts::ALL }>;
            #[doc = concat!(
                "The streaming results processor around the float pair ",
                "(`rtl::bundle::stream_float::BundleStreamFloat`) in ", stringify!($name), "."
            )]
            pub type $stream = $crate::bundle::stream_float::BundleStreamFloat<$e, $m, $n>;
            #[doc = concat!(
                "The same in ", stringify!($name), " around the 13-clock float pair."
            )]
            pub type $stream13 = $crate::bundle::stream_float::BundleStreamFloat<
                $e,
                $m,
                $n,
                { $crate::fp::cuts::ALL },
            >;
        )*

        /// The float formats with an instantiated float bundle pair (the rows of
        /// `bundle_float_presets!`, `with_bundle_float!`).
        pub const BUNDLE_FLOAT_FORMATS: [golden::format::float::FloatFormat; [$($e),*].len()] =
            [$(golden::format::float::FloatFormat { e: $e, m: $m }),*];
    };
}

crate::bundle_fix_presets!(__bundle_fix_preset_items!());
crate::bundle_float_presets!(__bundle_float_preset_items!());

/// Runs `$body` with `$t` bound to the default (9-clock) `BundleFloat` type of a float format, or returns
/// an error for a format without an instantiated block.
#[macro_export]
macro_rules! with_bundle_float {
    ($f:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
        $crate::bundle_float_presets!(__with_bundle_float_arms!(f, pair, $t, $body))
    }};
}

/// Runs `$body` with `$t` bound to the streaming processor around the default (9-clock) float pair
/// (`BundleStreamFloat`) of a float format, or returns an error for a format without an instantiated
/// block.
#[macro_export]
macro_rules! with_bundle_stream_float {
    ($f:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
        $crate::bundle_float_presets!(__with_bundle_float_arms!(f, stream, $t, $body))
    }};
}

/// The dispatch arms of `with_bundle_float!` and `with_bundle_stream_float!` (callback of
/// `bundle_float_presets!`; `pair` or `stream` picks the column).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_bundle_float_arms {
    ($f:ident, pair, $t:ident, $body:block
        [$(($name:ident, $e:literal, $m:literal, $n:literal, $pair:ident, $pair13:ident, $stream:ident, $stream13:ident)),* $(,)?]) => {
        $crate::__float_arms!($f, $t, $body, "BundleFloat",
            "bundle_float_presets! in rtl/src/bundle/registry.rs" [$(($e, $m, $crate::$pair)),*])
    };
    ($f:ident, stream, $t:ident, $body:block
        [$(($name:ident, $e:literal, $m:literal, $n:literal, $pair:ident, $pair13:ident, $stream:ident, $stream13:ident)),* $(,)?]) => {
        $crate::__float_arms!($f, $t, $body, "BundleStreamFloat (streaming processor)",
            "bundle_float_presets! in rtl/src/bundle/registry.rs" [$(($e, $m, $crate::$stream)),*])
    };
}

/// Runs `$body` with `$t` bound to the results processor (`BundleSplit`) over a preset grid (the
/// bundle format's base, `golden::bundle::fix::BundleFixFormat::base`), or returns an error for another.
#[macro_export]
macro_rules! with_bundle_split {
    ($base:expr, $t:ident, $body:block) => {{
        let f: &golden::format::fixed::FixFormat = $base;
        $crate::bundle_fix_presets!(__with_bundle_fix_arms!(f, split, $t, $body))
    }};
}

/// Runs `$body` with `$t` bound to the streaming processor (`BundleStream`, around the 3-clock pair) over
/// a preset grid, or returns an error for another.
#[macro_export]
macro_rules! with_bundle_stream {
    ($base:expr, $t:ident, $body:block) => {{
        let f: &golden::format::fixed::FixFormat = $base;
        $crate::bundle_fix_presets!(__with_bundle_fix_arms!(f, stream, $t, $body))
    }};
}

/// The dispatch arms of `with_bundle_split!` and `with_bundle_stream!` (callback of
/// `bundle_fix_presets!`; `split` or `stream` picks the column).
#[doc(hidden)]
#[macro_export]
macro_rules! __with_bundle_fix_arms {
    ($f:ident, split, $t:ident, $body:block
        [$(($p:ident, [$($w:literal),*], $pair:ident, $pair5:ident, $split:ident, $stream:ident, $stream5:ident)),* $(,)?]) => {
        $crate::__fix_preset_arms!($f, $t, $body, "BundleSplit (results processor)",
            "bundle_fix_presets! in rtl/src/bundle/registry.rs" [$(($p, $crate::$split)),*])
    };
    ($f:ident, stream, $t:ident, $body:block
        [$(($p:ident, [$($w:literal),*], $pair:ident, $pair5:ident, $split:ident, $stream:ident, $stream5:ident)),* $(,)?]) => {
        $crate::__fix_preset_arms!($f, $t, $body, "BundleStream (streaming processor)",
            "bundle_fix_presets! in rtl/src/bundle/registry.rs" [$(($p, $crate::$stream)),*])
    };
}
