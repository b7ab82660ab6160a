//! The machinery shared by the configuration tables (`rtl/src/{slab,plane,bundle}/registry.rs`,
//! `rtl/src/slab/ladder.rs`): how a table hands its rows to a callback, and the two shapes of per-format
//! dispatch built from rows (over the fixed presets, over float formats). Const generics need every
//! width at compile time, so run-time dispatch is a `match` with one arm per row, each compiling the
//! caller's body with its own type.

/// Expands to `$crate::$cb! { args... $rows }`: a table macro (`slab_fix_presets!`, ...) is
/// `$crate::__call_with_rows!(<its caller's callback> [rows])`.
#[doc(hidden)]
#[macro_export]
macro_rules! __call_with_rows {
    ($cb:ident ! ( $($args:tt)* ) $rows:tt) => {
        $crate::$cb! { $($args)* $rows }
    };
}

/// The arms of a dispatch over preset grids: runs `$body` with `$t` bound to the type of the row whose
/// preset (`golden::format::fixed::FixFormat::$p()`) equals `*$f`, or returns an error naming the format,
/// the block and the table to extend.
#[doc(hidden)]
#[macro_export]
macro_rules! __fix_preset_arms {
    ($f:ident, $t:ident, $body:block, $what:literal, $table:literal [$(($p:ident, $ty:ty)),* $(,)?]) => {
        match () {
            $(
                _ if *$f == golden::format::fixed::FixFormat::$p() => {
                    type $t = $ty;
                    Ok($body)
                }
            )*
            _ => Err(format!(
                "no {} instance for format {}: instantiated over the presets {} (add a row to {} for \
                 another)",
                $what,
                $f.name(),
                [$(stringify!($p)),*].join(", "),
                $table
            )),
        }
    };
}

/// The arms of a dispatch over float formats: runs `$body` with `$t` bound to the type of the row whose
/// `(E, M)` equals `$f`'s, or returns an error naming the format, the block and the table to extend.
#[doc(hidden)]
#[macro_export]
macro_rules! __float_arms {
    ($f:ident, $t:ident, $body:block, $what:literal, $table:literal [$(($e:literal, $m:literal, $ty:ty)),* $(,)?]) => {
        match ($f.e, $f.m) {
            $(
                ($e, $m) => {
                    type $t = $ty;
                    Ok($body)
                }
            )*
            _ => Err(format!(
                "no {} instance for float format {}: instantiated are {} (add a row to {} for another)",
                $what,
                $f.name(),
                [$(concat!("e", stringify!($e), "m", stringify!($m))),*].join(", "),
                $table
            )),
        }
    };
}
