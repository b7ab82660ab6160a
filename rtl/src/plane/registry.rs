//! The cull-plane testers that exist: the fixed tester over each preset grid (table option and the
//! quotient option) and the float tester in binary16, bfloat16 and binary32 with K planes.

use super::fix::{PlaneFix, PLANE_FIX_DEEP};
use super::float::PlaneFloat;
use super::quot::PlaneQuot;
use golden::format::float::FloatFormat;

/// The chained slab + cull-plane tester over b12 with the default plane format (`N = 8`, `FD = 11`,
/// `R = 8`) and `K` planes.
pub type PlaneFixB12<const K: usize> = PlaneFix<12, 13, 16, 20, 8, 14, 24, 25, 23, K>;
/// The same over b8 (`FD = 8`).
pub type PlaneFixB8<const K: usize> = PlaneFix<8, 9, 12, 14, 8, 11, 20, 21, 20, K>;
/// The same over b16 (`FD = 14`).
pub type PlaneFixB16<const K: usize> = PlaneFix<16, 17, 20, 24, 8, 17, 28, 29, 26, K>;
/// [`PlaneFixB8`] in the deep configuration (11 clocks, [`PLANE_FIX_DEEP`]).
pub type PlaneFixB8P11<const K: usize> =
    PlaneFix<8, 9, 12, 14, 8, 11, 20, 21, 20, K, { PLANE_FIX_DEEP.0 }, { PLANE_FIX_DEEP.1 }>;
/// [`PlaneFixB12`] in the deep configuration (11 clocks, [`PLANE_FIX_DEEP`]).
pub type PlaneFixB12P11<const K: usize> =
    PlaneFix<12, 13, 16, 20, 8, 14, 24, 25, 23, K, { PLANE_FIX_DEEP.0 }, { PLANE_FIX_DEEP.1 }>;
/// [`PlaneFixB16`] in the deep configuration (11 clocks, [`PLANE_FIX_DEEP`]).
pub type PlaneFixB16P11<const K: usize> =
    PlaneFix<16, 17, 20, 24, 8, 17, 28, 29, 26, K, { PLANE_FIX_DEEP.0 }, { PLANE_FIX_DEEP.1 }>;

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

/// The fraction option of the chained tester ([`PlaneQuot`]) over b12 (`N = 8`, `FD = 11`)
/// with `K` planes.
pub type PlaneQuotB12<const K: usize> = PlaneQuot<12, 13, 16, 20, 8, 14, 24, 25, 23, 22, 47, K>;
/// The same over b8 (`FD = 8`).
pub type PlaneQuotB8<const K: usize> = PlaneQuot<8, 9, 12, 14, 8, 11, 20, 21, 20, 19, 40, K>;
/// The same over b16 (`FD = 14`).
pub type PlaneQuotB16<const K: usize> = PlaneQuot<16, 17, 20, 24, 8, 17, 28, 29, 26, 25, 54, K>;

/// The (float format, planes) pairs with an instantiated `PlaneFloat` (the aliases above).
pub const PLANE_FLOAT_CONFIGS: [(FloatFormat, usize); 9] = [
    (FloatFormat::FP16, 1),
    (FloatFormat::FP16, 2),
    (FloatFormat::FP16, 4),
    (FloatFormat::BF16, 1),
    (FloatFormat::BF16, 2),
    (FloatFormat::BF16, 4),
    (FloatFormat::FP32, 1),
    (FloatFormat::FP32, 2),
    (FloatFormat::FP32, 4),
];

/// Runs `$body` with `$t` bound to the `PlaneFloat` type of a float format and plane count, or returns an
/// error for a configuration without an instantiated block.
#[macro_export]
macro_rules! with_plane_float {
    ($f:expr, $k:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
        let k: usize = $k;
        match (f.e, f.m, k) {
            (5, 10, 1) => {
                type $t = $crate::PlaneFloatE5M10K1;
                Ok($body)
            }
            (5, 10, 2) => {
                type $t = $crate::PlaneFloatE5M10K2;
                Ok($body)
            }
            (5, 10, 4) => {
                type $t = $crate::PlaneFloatE5M10K4;
                Ok($body)
            }
            (8, 7, 1) => {
                type $t = $crate::PlaneFloatE8M7K1;
                Ok($body)
            }
            (8, 7, 2) => {
                type $t = $crate::PlaneFloatE8M7K2;
                Ok($body)
            }
            (8, 7, 4) => {
                type $t = $crate::PlaneFloatE8M7K4;
                Ok($body)
            }
            (8, 23, 1) => {
                type $t = $crate::PlaneFloatE8M23K1;
                Ok($body)
            }
            (8, 23, 2) => {
                type $t = $crate::PlaneFloatE8M23K2;
                Ok($body)
            }
            (8, 23, 4) => {
                type $t = $crate::PlaneFloatE8M23K4;
                Ok($body)
            }
            _ => Err(format!(
                "no PlaneFloat instance for {} with {k} planes: instantiated are e5m10, e8m7, e8m23 \
                 with 1, 2, 4 planes (add a type alias in rtl/src/plane/registry.rs for another)",
                f.name()
            )),
        }
    }};
}

/// Runs `$body` with `$t` bound to the `PlaneFix` type (table option, default depth) over a preset slab
/// format with `$k` planes (1 to 8), or returns an error for a configuration without an instantiated
/// block. `$body` is compiled once per format and plane count.
#[macro_export]
macro_rules! with_plane_fix {
    ($base:expr, $k:expr, $t:ident, $body:block) => {{
        let k: usize = $k;
        match k {
            1 => $crate::__with_plane_fix_k!($base, 1, $t, $body),
            2 => $crate::__with_plane_fix_k!($base, 2, $t, $body),
            3 => $crate::__with_plane_fix_k!($base, 3, $t, $body),
            4 => $crate::__with_plane_fix_k!($base, 4, $t, $body),
            5 => $crate::__with_plane_fix_k!($base, 5, $t, $body),
            6 => $crate::__with_plane_fix_k!($base, 6, $t, $body),
            7 => $crate::__with_plane_fix_k!($base, 7, $t, $body),
            8 => $crate::__with_plane_fix_k!($base, 8, $t, $body),
            k => Err(format!(
                "{k} planes: the cull-plane RTL takes 1 to 8 (the model takes 0 to 8)"
            )),
        }
    }};
}

/// The format arms of `with_plane_fix!` for one plane count.
#[doc(hidden)]
#[macro_export]
macro_rules! __with_plane_fix_k {
    ($base:expr, $k:literal, $t:ident, $body:block) => {{
        let f: &golden::format::fixed::FixFormat = $base;
        if *f == golden::format::fixed::FixFormat::b8() {
            type $t = $crate::PlaneFixB8<$k>;
            Ok($body)
        } else if *f == golden::format::fixed::FixFormat::b12() {
            type $t = $crate::PlaneFixB12<$k>;
            Ok($body)
        } else if *f == golden::format::fixed::FixFormat::b16() {
            type $t = $crate::PlaneFixB16<$k>;
            Ok($body)
        } else {
            Err(format!(
                "no PlaneFix instance for {}: the rtl and verilator engines take b8, b12, b16 \
                 (add a type alias in rtl/src/plane/registry.rs for another)",
                f.name()
            ))
        }
    }};
}
