//! The bundle blocks that exist: the fixed pair (at 3 and 5 clocks) and the results processors over each preset grid, and the
//! float pair (at 9 and 13 clocks) and its streaming processor in binary32, bfloat16 and binary16.

use super::pair_fix::BundleFix;
use super::pair_float::BundleFloat;
use super::split::BundleSplit;
use super::stream::BundleStream;
use super::stream_float::BundleStreamFloat;

/// The fixed-point AllHit + AnyHit bundle pair over b8 (`FD = 6`).
pub type BundleFixB8 = BundleFix<8, 9, 9, 14>;
/// The same over b12 (`FD = 10`).
pub type BundleFixB12 = BundleFix<12, 13, 13, 20>;
/// The same over b16 (`FD = 14`).
pub type BundleFixB16 = BundleFix<16, 17, 17, 24>;
/// The 5-clock fixed pair over b8 (products and compares registered, `rtl::bundle::edge_fix::cut`).
pub type BundleFixB8P5 = BundleFix<8, 9, 9, 14, { super::edge_fix::BUNDLE_TEST_CUTS_DEEP }>;
/// The same over b12.
pub type BundleFixB12P5 = BundleFix<12, 13, 13, 20, { super::edge_fix::BUNDLE_TEST_CUTS_DEEP }>;
/// The same over b16.
pub type BundleFixB16P5 = BundleFix<16, 17, 17, 24, { super::edge_fix::BUNDLE_TEST_CUTS_DEEP }>;

/// The float AllHit + AnyHit bundle pair in binary32.
pub type BundleFloatFp32 = BundleFloat<8, 23, 32>;
/// The same in bfloat16.
pub type BundleFloatBf16 = BundleFloat<8, 7, 16>;
/// The same in binary16.
pub type BundleFloatFp16 = BundleFloat<5, 10, 16>;
/// The 13-clock float pair in binary32 (every optional cut of its adders and multipliers,
/// [`crate::fp::cuts::ALL`]).
pub type BundleFloatFp32P13 = BundleFloat<8, 23, 32, { crate::fp::cuts::ALL }>;
/// The same in bfloat16.
pub type BundleFloatBf16P13 = BundleFloat<8, 7, 16, { crate::fp::cuts::ALL }>;
/// The same in binary16.
pub type BundleFloatFp16P13 = BundleFloat<5, 10, 16, { crate::fp::cuts::ALL }>;

/// The float formats with an instantiated float bundle pair (`with_bundle_float!`).
pub const BUNDLE_FLOAT_FORMATS: [golden::format::float::FloatFormat; 3] = [
    golden::format::float::FloatFormat::FP32,
    golden::format::float::FloatFormat::BF16,
    golden::format::float::FloatFormat::FP16,
];

/// The bundle results processor ([`BundleSplit`], 16 rays) over b8 (`FD = 6`).
pub type BundleSplitB8 = BundleSplit<8, 9, 9, 14>;
/// The same over b12 (`FD = 10`).
pub type BundleSplitB12 = BundleSplit<12, 13, 13, 20>;
/// The same over b16 (`FD = 14`).
pub type BundleSplitB16 = BundleSplit<16, 17, 17, 24>;

/// The streaming results processor ([`BundleStream`], jobs in flight, 4 sets of 16 rays) over b8.
pub type BundleStreamB8 = BundleStream<8, 9, 9, 14>;
/// The same over b12.
pub type BundleStreamB12 = BundleStream<12, 13, 13, 20>;
/// The same over b16.
pub type BundleStreamB16 = BundleStream<16, 17, 17, 24>;
/// The streaming processor over the 5-clock fixed pair, b12.
pub type BundleStreamB12P5 =
    BundleStream<12, 13, 13, 20, { super::edge_fix::BUNDLE_TEST_CUTS_DEEP }>;

/// The streaming results processor around the float pair ([`BundleStreamFloat`]) in binary32.
pub type BundleStreamFp32 = BundleStreamFloat<8, 23, 32>;
/// The same in bfloat16.
pub type BundleStreamBf16 = BundleStreamFloat<8, 7, 16>;
/// The same in binary16.
pub type BundleStreamFp16 = BundleStreamFloat<5, 10, 16>;
/// The same in binary16 around the 13-clock float pair.
pub type BundleStreamFp16P13 = BundleStreamFloat<5, 10, 16, { crate::fp::cuts::ALL }>;

/// Runs `$body` with `$t` bound to the `BundleFloat` type of a float format, or returns an error for a
/// format without an instantiated block.
#[macro_export]
macro_rules! with_bundle_float {
    ($f:expr, $t:ident, $body:block) => {{
        let f: &golden::format::float::FloatFormat = $f;
        match (f.e, f.m) {
            (8, 23) => {
                type $t = $crate::BundleFloatFp32;
                Ok($body)
            }
            (8, 7) => {
                type $t = $crate::BundleFloatBf16;
                Ok($body)
            }
            (5, 10) => {
                type $t = $crate::BundleFloatFp16;
                Ok($body)
            }
            _ => Err(format!(
                "no BundleFloat instance for float format {}: instantiated are e8m23, e8m7, e5m10 \
                 (add a type alias in rtl/src/bundle/registry.rs for another)",
                f.name()
            )),
        }
    }};
}
