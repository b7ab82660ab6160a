//! Verilog export: one `.v` per block and configuration, the configuration in the module name.
//!
//! rust-hdl names the top module `top` and each child `top$path`; the export renames the whole family
//! after the block and its format (for example `slab_fix_g16_i20f14_t24f6`), so several configurations
//! can be synthesised together.
//!
//! [`catalog`] is the list of exported modules (one [`Exported`] row each, made from the block's type:
//! name, latency, family and Verilog); [`export_all`] writes it. The per-format functions below serve
//! the commands that export one block of a format chosen at run time (`rtu fit`, the engines, the
//! formal proofs).

use crate::bundle::pair_fix::{BundleFixIo, BUNDLE_FIX_LATENCY};
use crate::bundle::pair_float::BundleFloatIo;
use crate::bundle::stream::BundleStreamIo;
use crate::names;
use crate::plane::fix::{PlaneFixIo, PLANE_FIX_CUTS};
use crate::plane::float::PlaneFloatIo;
use crate::plane::quot::PlaneQuotIo;
use crate::slab::fix::{SlabFixIo, SLAB_FIX_CUTS};
use crate::slab::float::SlabFloatIo;
use crate::verilog::verilog_named;
use golden::bundle::fix::BundleFixFormat;
use golden::bundle::stream::decided_latency;
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use golden::plane::fix::CullFixFormat;
use golden::plane::float::CullFloatFormat;
use rust_hdl::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Verilog of the fixed slab tester `S` for `fmt`, named after the format and the block's cut points.
pub fn slab_fix_verilog_of<S: crate::slab::fix::SlabFixIo + Block>(fmt: &FixFormat) -> String {
    let mut uut = S::for_format(fmt);
    verilog_named(&mut uut, &names::slab_fix_module_cuts(fmt, S::CUTS))
}

/// Verilog of the default fixed slab tester for a preset format.
pub fn slab_fix_verilog(fmt: &FixFormat) -> Result<String, String> {
    crate::with_slab_fix!(fmt, S, { slab_fix_verilog_of::<S>(fmt) })
}

/// Verilog of the float slab tester `S`, named after its format and cut points.
pub fn slab_float_verilog_of<S: crate::slab::float::SlabFloatIo + Block>() -> String {
    let mut uut = S::make();
    verilog_named(
        &mut uut,
        &names::slab_float_module_cuts(&S::format(), S::CUTS),
    )
}

/// Verilog of the default float slab tester for an instantiated format.
pub fn slab_float_verilog(f: &golden::format::float::FloatFormat) -> Result<String, String> {
    crate::with_slab_float!(f, S, { slab_float_verilog_of::<S>() })
}

/// Verilog of the fixed slab tester for any format of the grid ladder (`FixFormat::grid`), for the fit.
pub fn slab_fix_verilog_ladder(fmt: &FixFormat) -> Result<String, String> {
    crate::with_slab_fix_ladder!(fmt, S, { slab_fix_verilog_of::<S>(fmt) })
}

/// `(module, Verilog, latency)` of the default fixed slab tester for any format of the grid ladder (the
/// formal conservativeness proofs take the smallest, `g6`, which `export_all` does not write).
pub fn slab_fix_ladder_default(fmt: &FixFormat) -> Result<(String, String, usize), String> {
    crate::with_slab_fix_ladder!(fmt, S, {
        (
            names::slab_fix_module_cuts(fmt, <S as crate::slab::fix::SlabFixIo>::CUTS),
            slab_fix_verilog_of::<S>(fmt),
            <S as crate::io::TesterIo>::LATENCY,
        )
    })
}

/// `(module, Verilog, latency)` of the default float slab tester for any format of the float ladder
/// (the formal conservativeness proof takes the smallest, `e5m3`).
pub fn slab_float_ladder_default(
    f: &golden::format::float::FloatFormat,
) -> Result<(String, String, usize), String> {
    crate::with_slab_float_ladder!(f, S, {
        (
            names::slab_float_module_cuts(f, <S as crate::slab::float::SlabFloatIo>::CUTS),
            slab_float_verilog_of::<S>(),
            <S as crate::io::TesterIo>::LATENCY,
        )
    })
}

/// Verilog of the float slab tester for any format of the float ladder, for the fit.
pub fn slab_float_verilog_ladder(f: &golden::format::float::FloatFormat) -> Result<String, String> {
    crate::with_slab_float_ladder!(f, S, { slab_float_verilog_of::<S>() })
}

/// The block family and configuration of an exported module: what a testbench, an encoder or a datasheet
/// needs to know of it beyond its ports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Family {
    /// The fixed slab tester of a format, with its cut points.
    SlabFix { fmt: FixFormat, cuts: usize },
    /// The float slab tester of a format, with its cut points.
    SlabFloat {
        f: golden::format::float::FloatFormat,
        cuts: usize,
    },
    /// The fixed chained slab + cull-plane tester, table option, `k` planes; `deep` is the 11-clock depth.
    PlaneFix {
        cf: CullFixFormat,
        k: usize,
        deep: bool,
    },
    /// The fixed chained slab + cull-plane tester, fraction option, `k` planes.
    PlaneQuot { cf: CullFixFormat, k: usize },
    /// The float chained slab + cull-plane tester, `k` planes.
    PlaneFloat { cf: CullFloatFormat, k: usize },
    /// The fixed AllHit / AnyHit bundle pair, with its cut points
    /// (`crate::bundle::edge_fix::cut`).
    BundleFix {
        bf: golden::bundle::fix::BundleFixFormat,
        cuts: usize,
    },
    /// The float AllHit / AnyHit bundle pair, with its cut points (`crate::fp::cuts`).
    BundleFloat {
        f: golden::format::float::FloatFormat,
        cuts: usize,
    },
    /// The bundle results processor (jobs over several clocks, not one test a clock).
    BundleSplit {
        bf: golden::bundle::fix::BundleFixFormat,
    },
    /// The streaming results processor (jobs in flight, tagged reports, out of order) around the fixed
    /// pair with its cut points `cuts`.
    BundleStream {
        bf: golden::bundle::fix::BundleFixFormat,
        cuts: usize,
    },
    /// The streaming results processor around the float pair with its cut points `cuts`.
    BundleStreamFloat {
        f: golden::format::float::FloatFormat,
        cuts: usize,
    },
}

/// One exported module of the catalogue: its name, its latency in clocks (for the results processor,
/// the clocks of a decided job), its family, and how to make its Verilog ([`Exported::verilog`], on
/// demand). Everything but the family's format is read from the block's type, so a row cannot name one
/// configuration and build another.
#[derive(Clone)]
pub struct Exported {
    pub module: String,
    pub latency: usize,
    pub family: Family,
    make: Arc<dyn Fn(&str) -> String + Send + Sync>,
}

impl PartialEq for Exported {
    fn eq(&self, other: &Self) -> bool {
        (&self.module, self.latency, &self.family) == (&other.module, other.latency, &other.family)
    }
}

impl std::fmt::Debug for Exported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Exported")
            .field("module", &self.module)
            .field("latency", &self.latency)
            .field("family", &self.family)
            .finish_non_exhaustive()
    }
}

impl Exported {
    fn new(
        module: String,
        latency: usize,
        family: Family,
        make: impl Fn(&str) -> String + Send + Sync + 'static,
    ) -> Self {
        Exported {
            module,
            latency,
            family,
            make: Arc::new(make),
        }
    }

    /// One test a clock (every module but the results processor).
    pub fn pipelined(&self) -> bool {
        !matches!(
            self.family,
            Family::BundleSplit { .. }
                | Family::BundleStream { .. }
                | Family::BundleStreamFloat { .. }
        )
    }

    /// The module's Verilog, exactly as [`export_all`] writes it. rust-hdl's Verilog generation of the
    /// larger blocks recurses deeper than a test thread's default stack: call it on a thread with a
    /// large stack (256 MiB serves every block).
    pub fn verilog(&self) -> String {
        (self.make)(&self.module)
    }
}

/// The catalogue row of the fixed slab tester `S` over `fmt`.
pub fn slab_fix<S: SlabFixIo + 'static>(fmt: FixFormat) -> Exported {
    Exported::new(
        names::slab_fix_module_cuts(&fmt, S::CUTS),
        S::LATENCY,
        Family::SlabFix { fmt, cuts: S::CUTS },
        move |_| slab_fix_verilog_of::<S>(&fmt),
    )
}

/// The catalogue row of the float slab tester `S`.
pub fn slab_float<S: SlabFloatIo + 'static>() -> Exported {
    let f = S::format();
    Exported::new(
        names::slab_float_module_cuts(&f, S::CUTS),
        S::LATENCY,
        Family::SlabFloat { f, cuts: S::CUTS },
        |_| slab_float_verilog_of::<S>(),
    )
}

/// The catalogue row of the fixed cull-plane tester `S` (table option) over `cf`.
pub fn plane_fix<S: PlaneFixIo + 'static>(cf: CullFixFormat) -> Exported {
    let deep = (S::SLAB_CUTS, S::CUTS) != (SLAB_FIX_CUTS, PLANE_FIX_CUTS);
    Exported::new(
        names::plane_fix_module_of::<S>(&cf),
        S::LATENCY,
        Family::PlaneFix {
            cf,
            k: S::PLANES,
            deep,
        },
        move |m| verilog_named(&mut S::for_format(&cf), m),
    )
}

/// The catalogue row of the fixed cull-plane tester `S` (quotient option) over `cf`.
pub fn plane_quot<S: PlaneQuotIo + 'static>(cf: CullFixFormat) -> Exported {
    Exported::new(
        names::plane_quot_module(&cf, S::PLANES),
        S::LATENCY,
        Family::PlaneQuot { cf, k: S::PLANES },
        move |m| verilog_named(&mut S::for_format(&cf), m),
    )
}

/// The catalogue row of the float cull-plane tester `S` (default table).
pub fn plane_float<S: PlaneFloatIo + 'static>() -> Exported {
    let (cf, k) = (CullFloatFormat::over(S::format()), S::planes());
    Exported::new(
        names::plane_float_module(&cf, k),
        S::LATENCY,
        Family::PlaneFloat { cf, k },
        |m| verilog_named(&mut S::make(), m),
    )
}

/// The catalogue row of the fixed bundle pair `S` over `bf`.
pub fn bundle_fix<S: BundleFixIo + 'static>(bf: BundleFixFormat) -> Exported {
    Exported::new(
        names::bundle_fix_of::<S>(&bf),
        S::LATENCY,
        Family::BundleFix { bf, cuts: S::CUTS },
        move |m| verilog_named(&mut S::for_format(&bf), m),
    )
}

/// The catalogue row of the float bundle pair `S`.
pub fn bundle_float<S: BundleFloatIo + 'static>() -> Exported {
    let f = S::format();
    Exported::new(
        names::bundle_float_of::<S>(),
        S::LATENCY,
        Family::BundleFloat { f, cuts: S::CUTS },
        |_| bundle_float_verilog_of::<S>(),
    )
}

/// The catalogue row of the results processor over `bf` (`new` builds it; latency: the clocks of a
/// decided job, the pair's and one).
pub fn bundle_split<S: Block + 'static>(
    bf: BundleFixFormat,
    new: fn(&BundleFixFormat) -> S,
) -> Exported {
    Exported::new(
        names::bundle_split_module(&bf),
        BUNDLE_FIX_LATENCY + 1,
        Family::BundleSplit { bf },
        move |m| verilog_named(&mut new(&bf), m),
    )
}

/// The catalogue row of the streaming processor `S` around a fixed pair (latency: the clocks of a
/// decided job).
pub fn bundle_stream<S: BundleStreamIo<Dp = BundleFixFormat> + 'static>(
    bf: BundleFixFormat,
) -> Exported {
    Exported::new(
        names::bundle_stream_of::<S>(&bf),
        decided_latency(S::PAIR_LATENCY),
        Family::BundleStream { bf, cuts: S::CUTS },
        move |m| verilog_named(&mut S::for_format(&bf), m),
    )
}

/// The catalogue row of the streaming processor `S` around a float pair (latency: the clocks of a
/// decided job).
pub fn bundle_stream_float<S: BundleStreamIo<Dp = FloatFormat> + 'static>(
    f: FloatFormat,
) -> Exported {
    Exported::new(
        names::bundle_stream_of::<S>(&f),
        decided_latency(S::PAIR_LATENCY),
        Family::BundleStreamFloat { f, cuts: S::CUTS },
        move |m| verilog_named(&mut S::for_format(&f), m),
    )
}

/// The rows of the slab presets' tables, both depths, default first (callback of
/// `slab_fix_presets!` and `slab_float_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __slab_catalogue {
    (fix [$(($p:ident, [$($w:literal),*], $alias:ident, $deep:ident)),* $(,)?]) => {
        vec![
            $($crate::export::slab_fix::<$crate::$alias>(golden::format::fixed::FixFormat::$p()),)*
            $($crate::export::slab_fix::<$crate::$deep>(golden::format::fixed::FixFormat::$p()),)*
        ]
    };
    (float [$(($e:literal, $m:literal, $n:literal, $alias:ident, $deep:ident)),* $(,)?]) => {
        vec![
            $($crate::export::slab_float::<$crate::$alias>(),)*
            $($crate::export::slab_float::<$crate::$deep>(),)*
        ]
    };
}

/// The pair rows of the bundle presets' tables, both depths, the shallow pairs first (callback of
/// `bundle_fix_presets!` and `bundle_float_presets!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __bundle_pair_catalogue {
    (fix [$(($p:ident, [$($w:literal),*], $pair:ident, $pair5:ident, $split:ident, $stream:ident, $stream5:ident)),* $(,)?]) => {
        vec![
            $($crate::export::bundle_fix::<$crate::$pair>(
                golden::bundle::fix::BundleFixFormat::over(golden::format::fixed::FixFormat::$p())
                    .expect("a preset"),
            ),)*
            $($crate::export::bundle_fix::<$crate::$pair5>(
                golden::bundle::fix::BundleFixFormat::over(golden::format::fixed::FixFormat::$p())
                    .expect("a preset"),
            ),)*
        ]
    };
    (float [$(($name:ident, $e:literal, $m:literal, $n:literal, $pair:ident, $pair13:ident, $stream:ident, $stream13:ident)),* $(,)?]) => {
        vec![
            $($crate::export::bundle_float::<$crate::$pair>(),)*
            $($crate::export::bundle_float::<$crate::$pair13>(),)*
        ]
    };
}

/// Every exported module, in export order, with its family: the one list that [`export_all`] writes
/// and the encoder, the datasheets, the packaging, `rtu synth` and `rtu timing` read.
///
/// The slab testers and the bundle pairs are every row of their family's table
/// (`rtl/src/slab/registry.rs`, `rtl/src/bundle/registry.rs`) at both depths; the cull-plane testers
/// and the results processors are the configurations the synthesis report compares, one line each
/// (their tables instantiate more: every plane count for run and campaign).
pub fn catalog() -> Vec<Exported> {
    let [b8, b12, b16] = FixFormat::presets().map(CullFixFormat::over);
    let [_, bb12, bb16] = BundleFixFormat::presets();
    let mut v: Vec<Exported> = crate::slab_fix_presets!(__slab_catalogue!(fix));
    v.extend(crate::slab_float_presets!(__slab_catalogue!(float)));
    v.extend([
        plane_fix::<crate::PlaneFixB8<1>>(b8),
        plane_fix::<crate::PlaneFixB8<4>>(b8),
        plane_fix::<crate::PlaneFixB12<1>>(b12),
        plane_fix::<crate::PlaneFixB12<4>>(b12),
        plane_fix::<crate::PlaneFixB16<1>>(b16),
        plane_fix::<crate::PlaneFixB16<4>>(b16),
        plane_fix::<crate::PlaneFixB8P11<1>>(b8),
        plane_fix::<crate::PlaneFixB8P11<4>>(b8),
        plane_fix::<crate::PlaneFixB12P11<1>>(b12),
        plane_fix::<crate::PlaneFixB12P11<4>>(b12),
        plane_fix::<crate::PlaneFixB16P11<1>>(b16),
        plane_fix::<crate::PlaneFixB16P11<4>>(b16),
        plane_quot::<crate::PlaneQuotB12<1>>(b12),
        plane_quot::<crate::PlaneQuotB12<4>>(b12),
        plane_quot::<crate::PlaneQuotB16<1>>(b16),
        plane_quot::<crate::PlaneQuotB16<4>>(b16),
        plane_float::<crate::PlaneFloatE5M10K1>(),
        plane_float::<crate::PlaneFloatE8M7K1>(),
        plane_float::<crate::PlaneFloatE8M23K1>(),
    ]);
    v.extend(crate::bundle_fix_presets!(__bundle_pair_catalogue!(fix)));
    v.extend([
        bundle_split(bb12, crate::BundleSplitB12::new),
        bundle_split(bb16, crate::BundleSplitB16::new),
        bundle_stream::<crate::BundleStreamB12>(bb12),
        bundle_stream::<crate::BundleStreamB16>(bb16),
        bundle_stream::<crate::BundleStreamB12P5>(bb12),
    ]);
    v.extend(crate::bundle_float_presets!(__bundle_pair_catalogue!(
        float
    )));
    v.extend([
        bundle_stream_float::<crate::BundleStreamFp32>(FloatFormat::FP32),
        bundle_stream_float::<crate::BundleStreamBf16>(FloatFormat::BF16),
        bundle_stream_float::<crate::BundleStreamFp16>(FloatFormat::FP16),
        bundle_stream_float::<crate::BundleStreamFp16P13>(FloatFormat::FP16),
    ]);
    v
}

/// Writes `<dir>/<module>.v` for every module of the [`catalog`], and `<dir>/latency.csv` (module,
/// latency in clocks) for the synthesis report; returns the Verilog paths. Call it on a thread with a
/// large stack (see [`Exported::verilog`]).
pub fn export_all(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut out = vec![];
    let mut latency = String::from("module,latency\n");
    for e in catalog() {
        let p = dir.join(format!("{}.v", e.module));
        std::fs::write(&p, e.verilog())?;
        latency += &format!("{},{}\n", e.module, e.latency);
        out.push(p);
    }
    std::fs::write(dir.join("latency.csv"), latency)?;
    Ok(out)
}

/// The catalogue entry of `module`, or an error naming it and the closest exported names.
pub fn find(module: &str) -> Result<Exported, String> {
    let all = catalog();
    if let Some(e) = all.iter().find(|e| e.module == module) {
        return Ok(e.clone());
    }
    let stem = module.split('_').take(2).collect::<Vec<_>>().join("_");
    let near: Vec<&str> = all
        .iter()
        .map(|e| e.module.as_str())
        .filter(|m| m.starts_with(&stem))
        .collect();
    let list = if near.is_empty() {
        all.iter().map(|e| e.module.as_str()).collect::<Vec<_>>()
    } else {
        near
    };
    Err(format!(
        "module `{module}` is not an exported module; exported are: {}",
        list.join(", ")
    ))
}

/// Verilog of the float adder `FpAdd<E, M, N>` in `mode`.
pub fn fp_add_verilog<const E: usize, const M: usize, const N: usize>(
    mode: golden::format::float::Rounding,
) -> String {
    let f = golden::format::float::FloatFormat::new(E as u32, M as u32).expect("valid format");
    let mut uut = crate::fp::add::FpAdd::<E, M, N>::new(mode);
    verilog_named(&mut uut, &names::fp_unit_module("add", &f, mode))
}

/// Verilog of the float multiplier `FpMul<E, M, N>` in `mode`.
pub fn fp_mul_verilog<const E: usize, const M: usize, const N: usize>(
    mode: golden::format::float::Rounding,
) -> String {
    let f = golden::format::float::FloatFormat::new(E as u32, M as u32).expect("valid format");
    let mut uut = crate::fp::mul::FpMul::<E, M, N>::new(mode);
    verilog_named(&mut uut, &names::fp_unit_module("mul", &f, mode))
}

/// Verilog of the float comparator `FpCmp<N>` of format `f` (combinational `lt`, `le`), module
/// `fp_cmp_<format>`.
pub fn fp_cmp_verilog<const N: usize>(f: &golden::format::float::FloatFormat) -> String {
    assert_eq!(f.width() as usize, N, "FpCmp<{N}> for {}", f.name());
    let mut uut = crate::fp::cmp::FpCmp::<N>::new(f.inf(false) as u64);
    verilog_named(&mut uut, &format!("fp_cmp_{}", f.name()))
}

/// Verilog of the registered float minimum and maximum `FpMinMax<N>` of format `f`, module
/// `fp_min_max_<format>`.
pub fn fp_min_max_verilog<const N: usize>(f: &golden::format::float::FloatFormat) -> String {
    let mut uut = crate::fp::min_max::FpMinMax::<N>::new(f);
    verilog_named(&mut uut, &format!("fp_min_max_{}", f.name()))
}

/// Verilog of one multiply-round unit `MulRound<D, I, T>` as the fixed slab tester of a preset uses it
/// (floor for a lower bound, `ceil` for an upper; the tester's shift; product not registered), module
/// `mul_round_<format>_floor` or `_ceil`; an error for a format that is not a preset.
pub fn mul_round_verilog(fmt: &FixFormat, ceil: bool) -> Result<String, String> {
    let name = format!(
        "mul_round_{}_{}",
        fmt.name(),
        if ceil { "ceil" } else { "floor" }
    );
    let shift = fmt.shift() as usize;
    crate::slab_fix_presets!(__mul_round_arms!(fmt, U, {
        verilog_named(&mut U::new(ceil, shift, false), &name)
    }))
}

/// The per-preset arms of [`mul_round_verilog`] (callback of `slab_fix_presets!`: the unit's widths
/// are the preset tester's `D`, `I`, `T`).
#[doc(hidden)]
#[macro_export]
macro_rules! __mul_round_arms {
    ($f:ident, $u:ident, $body:block
        [$(($p:ident, [$g:literal, $d:literal, $i:literal, $t:literal], $alias:ident, $deep:ident)),* $(,)?]) => {
        $crate::__fix_preset_arms!($f, $u, $body, "MulRound",
            "slab_fix_presets! in rtl/src/slab/registry.rs"
            [$(($p, $crate::slab::mul_round::MulRound<$d, $i, $t>)),*])
    };
}

/// Verilog of the fixed cull-plane tester's directed reciprocal table `BoundTable` with `2^r` entries,
/// module `plane_recip_table_r<r>`.
pub fn plane_recip_table_verilog(r: u32) -> String {
    let mut uut = crate::plane::bound_table::BoundTable::new(r);
    verilog_named(&mut uut, &format!("plane_recip_table_r{r}"))
}

/// Verilog of the float pair `S`, named after its format and cut points.
pub fn bundle_float_verilog_of<S: BundleFloatIo + Block>() -> String {
    let mut uut = Box::new(S::for_format(&S::format()));
    verilog_named(uut.as_mut(), &names::bundle_float_of::<S>())
}

/// Verilog of the default float bundle pair for an instantiated format.
pub fn bundle_float_verilog(f: &FloatFormat) -> Result<String, String> {
    crate::with_bundle_float!(f, P, { bundle_float_verilog_of::<P>() })
}

/// Verilog of the chained float node tester for an instantiated format and plane count, with the
/// default table (`R = min(M, 8)`).
pub fn plane_float_verilog(f: &FloatFormat, k: usize) -> Result<String, String> {
    crate::with_plane_float!(f, k, P, {
        let mut uut = P::new();
        verilog_named(
            &mut uut,
            &names::plane_float_module(&CullFloatFormat::over(*f), k),
        )
    })
}

#[cfg(test)]
mod catalog_tests {
    use super::*;

    /// The latency each row reads from its block's type is the documented function of the row's
    /// configuration (`slab_fix_latency`, `plane_fix_latency`, `decided_latency`, ...), and module names
    /// are unique (they are the join key of the area and timing tables).
    #[test]
    fn every_row_has_its_configurations_documented_latency_and_a_unique_name() {
        use crate::bundle::pair_fix::bundle_fix_latency;
        use crate::bundle::pair_float::bundle_float_latency;
        let all = catalog();
        for e in &all {
            let documented = match e.family {
                Family::SlabFix { cuts, .. } => crate::slab::fix::slab_fix_latency(cuts),
                Family::SlabFloat { cuts, .. } => crate::slab::float::slab_float_latency(cuts),
                Family::PlaneFix { deep, .. } => {
                    let (s, p, _) = crate::plane::fix::PLANE_FIX_DEPTHS[deep as usize];
                    crate::plane::fix::plane_fix_latency(s, p)
                }
                Family::PlaneQuot { .. } => crate::plane::quot::PLANE_QUOT_LATENCY,
                Family::PlaneFloat { .. } => crate::PLANE_FLOAT_LATENCY,
                Family::BundleFix { cuts, .. } => bundle_fix_latency(cuts),
                Family::BundleFloat { cuts, .. } => bundle_float_latency(cuts),
                Family::BundleSplit { .. } => BUNDLE_FIX_LATENCY + 1,
                Family::BundleStream { cuts, .. } => decided_latency(bundle_fix_latency(cuts)),
                Family::BundleStreamFloat { cuts, .. } => {
                    decided_latency(bundle_float_latency(cuts))
                }
            };
            assert_eq!(e.latency, documented, "{}", e.module);
        }
        let mut names: Vec<&str> = all.iter().map(|e| e.module.as_str()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), all.len(), "a module name is exported twice");
    }

    #[test]
    fn the_export_writes_each_row_under_its_name_with_its_latency() {
        // rust-hdl's Verilog generation of the cull-plane testers recurses deeper than a test thread's
        // stack.
        std::thread::Builder::new()
            .stack_size(256 << 20)
            .spawn(export_writes_the_catalogue)
            .unwrap()
            .join()
            .unwrap();
    }

    fn export_writes_the_catalogue() {
        let dir = std::env::temp_dir().join(format!("rtu_catalog_{}", std::process::id()));
        let paths = export_all(&dir).unwrap();
        let written = std::fs::read_to_string(dir.join("latency.csv")).unwrap();
        let listed: String = std::iter::once("module,latency\n".to_string())
            .chain(
                catalog()
                    .iter()
                    .map(|e| format!("{},{}\n", e.module, e.latency)),
            )
            .collect();
        assert_eq!(written, listed);
        assert_eq!(paths.len(), catalog().len());
        // Each file declares the module it is named after (spot check across families).
        for e in catalog().iter().step_by(7) {
            let v = std::fs::read_to_string(dir.join(format!("{}.v", e.module))).unwrap();
            assert!(
                v.contains(&format!("\nmodule {}(", e.module)),
                "{}",
                e.module
            );
        }
        std::fs::remove_dir_all(&dir).ok();
    }
    #[test]
    fn an_unknown_module_is_an_error_naming_the_near_ones() {
        let e = find("slab_fix_g13_i16f11_t20f6").unwrap_err();
        assert!(e.contains("`slab_fix_g13_i16f11_t20f6`"), "{e}");
        assert!(
            e.contains("slab_fix_g12_i16f11_t20f6") && !e.contains("bundle_"),
            "{e}"
        );
        assert_eq!(
            find("slab_fix_g12_i16f11_t20f6_p6").unwrap().latency,
            crate::slab::fix::slab_fix_latency(crate::slab::fix::SLAB_FIX_CUTS_DEEP)
        );
    }
}
