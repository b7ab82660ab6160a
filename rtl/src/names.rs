//! Exported module names: every configuration's name is made here, and only here.
//!
//! A name is the join key between the exported Verilog, the datasheets, the export catalogue
//! ([`crate::export::catalog`]), the synthesis and timing tables (`docs/sweep/area.csv`,
//! `docs/timing/timing.csv`) and the testbenches' harness builds. It carries the block family, the
//! format, the configuration (planes, rays) and the pipeline depth: the suffix a block's list of built
//! depths gives its cut points (`_p6`, `_p11`, `_p13`, `_p5`), or `_c` and the cut mask in hex for a
//! depth the list does not name ([`depth_suffix`]).
//!
//! Blocks never import this module; it reads their configuration constants (cut masks, depth lists,
//! ray counts) and the traits through which a testbench holds a block of any width (`*_of` functions).
//! [`crate::export`] writes the Verilog under these names.

use crate::bundle::edge_fix::BUNDLE_TEST_CUTS;
use crate::bundle::pair_fix::{BundleFixIo, BUNDLE_FIX_DEPTHS};
use crate::bundle::pair_float::{BundleFloatIo, BUNDLE_FLOAT_DEPTHS};
use crate::bundle::split::SPLIT_RAYS;
use crate::bundle::stream::BundleStreamIo;
use crate::plane::fix::{PlaneFixIo, PLANE_FIX_DEPTHS};
use crate::slab::fix::{SLAB_FIX_CUTS, SLAB_FIX_DEPTHS};
use crate::slab::float::SLAB_FLOAT_DEPTHS;
use golden::bundle::fix::BundleFixFormat;
use golden::bundle::stream::{STREAM_RAYS, STREAM_SETS};
use golden::format::fixed::FixFormat;
use golden::format::float::{FloatFormat, Rounding};
use golden::plane::fix::CullFixFormat;
use golden::plane::float::CullFloatFormat;

/// The module-name suffix of a block's configuration with cut points `cuts`: its entry in the block's
/// list of built configurations `depths` (`(cuts, suffix)`, e.g. `("_p13")`, none for the default), or
/// `_c` and the cut mask in two hex digits for a configuration the list does not name.
pub fn depth_suffix(depths: &[(usize, &str)], cuts: usize) -> String {
    match depths.iter().find(|(c, _)| *c == cuts) {
        Some((_, s)) => s.to_string(),
        None => format!("_c{cuts:02x}"),
    }
}

/// Module name of the default (4-clock) fixed slab tester for a format.
pub fn slab_fix_module(fmt: &FixFormat) -> String {
    slab_fix_module_cuts(fmt, SLAB_FIX_CUTS)
}

/// Module name of the fixed slab tester for a format and cut points: the format's name, then the
/// suffix of the configuration in [`crate::slab::fix::SLAB_FIX_DEPTHS`] (`_p6` for the 6-clock
/// tester), or `_c` and the cut mask in hex for another.
pub fn slab_fix_module_cuts(fmt: &FixFormat, cuts: usize) -> String {
    let suffix = depth_suffix(&SLAB_FIX_DEPTHS, cuts);
    format!("slab_fix_{}{suffix}", fmt.name())
}

/// Module name of the default (9-clock) float slab tester for a format, e.g. `slab_float_e8m23`.
pub fn slab_float_module(f: &FloatFormat) -> String {
    slab_float_module_cuts(f, 0)
}

/// Module name of the float slab tester for a format and cut points: the format's name, then the
/// suffix of the configuration in [`crate::slab::float::SLAB_FLOAT_DEPTHS`] (`_p13` for the 13-clock
/// tester), or `_c` and the cut mask in hex for another.
pub fn slab_float_module_cuts(f: &FloatFormat, cuts: usize) -> String {
    let suffix = depth_suffix(&SLAB_FLOAT_DEPTHS, cuts);
    format!("slab_float_{}{suffix}", f.name())
}

/// Module name of the table option of the fixed cull-plane tester at its default depth, e.g.
/// `plane_fix_g12_i16f11_t20f6_n8_fd11_r8_k4` (the testbenches' name).
pub fn plane_fix_module(cf: &CullFixFormat, k: usize) -> String {
    format!("plane_fix_{}_k{k}", cf.name())
}

/// Module name of the table option with slab cuts `scuts` and plane cuts `pcuts`: the default name
/// with the depth's suffix from [`crate::plane::fix::PLANE_FIX_DEPTHS`] (`_p11`), or `_c<slab>_<plane>`
/// in hex for a depth not in that list.
pub fn plane_fix_module_cuts(cf: &CullFixFormat, k: usize, scuts: usize, pcuts: usize) -> String {
    let suffix = match PLANE_FIX_DEPTHS
        .iter()
        .find(|(s, p, _)| (*s, *p) == (scuts, pcuts))
    {
        Some((_, _, s)) => s.to_string(),
        None => format!("_c{scuts:02x}_{pcuts:02x}"),
    };
    format!("{}{suffix}", plane_fix_module(cf, k))
}

/// Module name of the fixed cull-plane tester `S` for `cf`, from its planes and cut points.
pub fn plane_fix_module_of<S: PlaneFixIo>(cf: &CullFixFormat) -> String {
    plane_fix_module_cuts(cf, S::PLANES, S::SLAB_CUTS, S::CUTS)
}

/// Module name of the quotient option (`crate::plane::quot::PlaneQuot`), e.g. `plane_fix_frac_g12_i16f11_t20f6_n8_fd11_k4` (no table bits).
pub fn plane_quot_module(cf: &CullFixFormat, k: usize) -> String {
    format!(
        "plane_fix_frac_{}_n{}_fd{}_k{k}",
        cf.base.name(),
        cf.n,
        cf.fd
    )
}

/// Module name of the chained float node tester, e.g. `plane_float_e5m10_r8_k2`.
pub fn plane_float_module(cf: &CullFloatFormat, k: usize) -> String {
    format!("plane_float_{}_k{k}", cf.name())
}

/// Module name of a float unit (`add`, `mul`): format and rounding mode, e.g. `fp_add_e8m23_rd`.
pub fn fp_unit_module(unit: &str, f: &FloatFormat, mode: Rounding) -> String {
    format!("fp_{unit}_{}_{}", f.name(), mode_suffix(mode))
}

/// `rne`, `rd` or `ru`.
pub fn mode_suffix(mode: Rounding) -> &'static str {
    match mode {
        Rounding::NearestEven => "rne",
        Rounding::Down => "rd",
        Rounding::Up => "ru",
    }
}

/// The module name of the default (3-clock) fixed bundle pair for `bf` in exported Verilog.
pub fn bundle_fix_module(bf: &BundleFixFormat) -> String {
    bundle_fix_module_cuts(bf, BUNDLE_TEST_CUTS)
}

/// The module name of the fixed bundle pair for `bf` with cut points `cuts`: the format's name with the
/// suffix of the configuration in [`BUNDLE_FIX_DEPTHS`](crate::bundle::pair_fix::BUNDLE_FIX_DEPTHS) (`_p5` for the 5-clock pair; an unlisted
/// configuration gets `_c<cuts in two hex digits>`, [`depth_suffix`]).
pub fn bundle_fix_module_cuts(bf: &BundleFixFormat, cuts: usize) -> String {
    let suffix = depth_suffix(&BUNDLE_FIX_DEPTHS, cuts);
    format!("bundle_fix_{}{suffix}", bf.name())
}

/// Module name of the default (9-clock) float bundle pair for a format, e.g. `bundle_float_e8m23`.
pub fn bundle_float_module(f: &FloatFormat) -> String {
    bundle_float_module_cuts(f, 0)
}

/// Module name of the float bundle pair for a format and cut points: the format's name with the suffix
/// of the configuration in [`BUNDLE_FLOAT_DEPTHS`](crate::bundle::pair_float::BUNDLE_FLOAT_DEPTHS) (`_p13` for the 13-clock pair; an unlisted
/// configuration gets `_c<cuts in two hex digits>`, [`depth_suffix`]).
pub fn bundle_float_module_cuts(f: &FloatFormat, cuts: usize) -> String {
    let suffix = depth_suffix(&BUNDLE_FLOAT_DEPTHS, cuts);
    format!("bundle_float_{}{suffix}", f.name())
}

/// Module name of the results processor for a format, e.g. `bundle_split_g12_i16f11_t20f6_d10_n16`.
pub fn bundle_split_module(bf: &BundleFixFormat) -> String {
    format!("bundle_split_{}_n{SPLIT_RAYS}", bf.name())
}

/// A streaming processor's name: its format's name, the depth of the pair inside (from the pair's list
/// of built depths `depths`), and the ray store's shape.
fn bundle_stream_name(format: &str, depths: &[(usize, &str)], cuts: usize) -> String {
    let depth = depth_suffix(depths, cuts);
    format!("bundle_stream_{format}{depth}_n{STREAM_RAYS}x{STREAM_SETS}")
}

/// Module name of the fixed bundle pair `S` for `bf`, from its cut points.
pub fn bundle_fix_of<S: BundleFixIo>(bf: &BundleFixFormat) -> String {
    bundle_fix_module_cuts(bf, S::CUTS)
}

/// Module name of the float bundle pair `S`, from its format and cut points.
pub fn bundle_float_of<S: BundleFloatIo>() -> String {
    bundle_float_module_cuts(&S::format(), S::CUTS)
}

/// Module name of the streaming processor `S` over `dp` (fixed or float), from the pair's cut points, e.g.
/// `bundle_stream_g12_i16f11_t20f6_d10_n16x4` (around the default fixed pair),
/// `bundle_stream_g12_i16f11_t20f6_d10_p5_n16x4` (around the 5-clock one) or
/// `bundle_stream_e5m10_p13_n16x4` (around the 13-clock float pair).
pub fn bundle_stream_of<S: BundleStreamIo>(dp: &S::Dp) -> String {
    bundle_stream_name(&S::format_name(dp), S::PAIR_DEPTHS, S::CUTS)
}
