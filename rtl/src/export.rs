//! Verilog export: one `.v` per block and configuration, the configuration in the module name.
//!
//! rust-hdl names the top module `top` and each child `top$path`; the export renames the whole family
//! after the block and its format (for example `slab_fix_g16_i20f14_t24f6`), so several configurations
//! can be synthesised together.
//!
//! [`export_all`] writes the slab testers (the fixed one at 4 and at 6 clocks) and the cull-plane testers that the synthesis report compares
//! (`scripts/synth plane_`): the table option `PlaneFix` over b8, b12 and b16 and the fraction option
//! `PlaneQuot` over b12 and b16 with 1 and 4 planes, and the float `PlaneFloat` with 1 plane.

use crate::bundle::pair_fix::{BundleFixIo, BUNDLE_FIX_LATENCY};
use crate::bundle::pair_float::BundleFloatIo;
use crate::bundle::stream::BundleStreamIo;
use crate::names;
use crate::verilog::verilog_named;
use golden::bundle::fix::BundleFixFormat;
use golden::bundle::stream::decided_latency;
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use golden::plane::fix::CullFixFormat;
use golden::plane::float::CullFloatFormat;
use rust_hdl::prelude::*;
use std::path::{Path, PathBuf};

/// Verilog of the fixed slab tester `S` for `fmt`, named after the format and the block's cut points.
pub fn slab_fix_verilog_of<S: crate::slab::fix::SlabFixIo + Block>(fmt: &FixFormat) -> String {
    let mut uut = S::for_format(fmt);
    verilog_named(&mut uut, &names::slab_fix_module_cuts(fmt, S::CUTS))
}

/// Verilog of the default fixed slab tester for a preset format.
pub fn slab_fix_verilog(fmt: &FixFormat) -> Result<String, String> {
    crate::with_slab_fix!(fmt, S, { slab_fix_verilog_of::<S>(fmt) })
}

/// `(module, Verilog, latency)` of the 6-clock fixed slab testers over the presets b8, b12, b16.
pub fn slab_fix_deep_verilog() -> Vec<(String, String, usize)> {
    fn one<S: crate::slab::fix::SlabFixIo + Block>(fmt: FixFormat) -> (String, String, usize) {
        (
            names::slab_fix_module_cuts(&fmt, S::CUTS),
            slab_fix_verilog_of::<S>(&fmt),
            S::LATENCY,
        )
    }
    vec![
        one::<crate::SlabFixB8P6>(FixFormat::b8()),
        one::<crate::SlabFixB12P6>(FixFormat::b12()),
        one::<crate::SlabFixB16P6>(FixFormat::b16()),
    ]
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

/// `(module, Verilog, latency)` of the 13-clock float slab testers over [`crate::SLAB_FLOAT_FORMATS`].
pub fn slab_float_deep_verilog() -> Vec<(String, String, usize)> {
    fn one<S: crate::slab::float::SlabFloatIo + Block>() -> (String, String, usize) {
        (
            names::slab_float_module_cuts(&S::format(), S::CUTS),
            slab_float_verilog_of::<S>(),
            S::LATENCY,
        )
    }
    vec![
        one::<crate::SlabFloatE8M23P13>(),
        one::<crate::SlabFloatE8M15P13>(),
        one::<crate::SlabFloatE8M7P13>(),
        one::<crate::SlabFloatE5M10P13>(),
        one::<crate::SlabFloatE6M5P13>(),
    ]
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

/// Writes `<dir>/<module>.v` for every preset fixed format and every instantiated float format, and
/// `<dir>/latency.csv` (module, latency in clocks) for the synthesis report; returns the Verilog paths.
pub fn export_all(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut out = vec![];
    let mut latency = String::from("module,latency\n");
    let mut write = |module: String, v: String, lat: usize| -> std::io::Result<()> {
        let p = dir.join(format!("{module}.v"));
        std::fs::write(&p, v)?;
        latency += &format!("{module},{lat}\n");
        out.push(p);
        Ok(())
    };
    for fmt in FixFormat::presets() {
        write(
            names::slab_fix_module(&fmt),
            slab_fix_verilog(&fmt).expect("presets are instantiated"),
            crate::SLAB_FIX_LATENCY,
        )?;
    }
    for (module, v, lat) in slab_fix_deep_verilog() {
        write(module, v, lat)?;
    }
    for f in crate::SLAB_FLOAT_FORMATS {
        write(
            names::slab_float_module(&f),
            slab_float_verilog(&f).expect("instantiated"),
            crate::SLAB_FLOAT_LATENCY,
        )?;
    }
    for (module, v, lat) in slab_float_deep_verilog() {
        write(module, v, lat)?;
    }
    for (module, v, lat) in plane_verilog() {
        write(module, v, lat)?;
    }
    // The fixed bundle pair over the presets.
    for (module, v, lat) in bundle_fix_verilog() {
        write(module, v, lat)?;
    }
    // The bundle results processor over b12 and b16 (latency: clocks of a decided job).
    for (module, v, lat) in bundle_split_verilog() {
        write(module, v, lat)?;
    }
    // The streaming results processor over b12 and b16 (latency: clocks of a decided job).
    for (module, v, lat) in bundle_stream_verilog() {
        write(module, v, lat)?;
    }
    for f in crate::BUNDLE_FLOAT_FORMATS {
        write(
            names::bundle_float_module(&f),
            bundle_float_verilog(&f).expect("instantiated"),
            crate::bundle::pair_float::BUNDLE_FLOAT_LATENCY,
        )?;
    }
    for (module, v, lat) in bundle_float_deep_verilog() {
        write(module, v, lat)?;
    }
    // The streaming results processor around the float pair (latency: clocks of a decided job).
    for (module, v, lat) in bundle_stream_float_verilog() {
        write(module, v, lat)?;
    }
    std::fs::write(dir.join("latency.csv"), latency)?;
    Ok(out)
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
/// the clocks of a decided job) and its family. The Verilog is made on demand ([`Exported::verilog`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Exported {
    pub module: String,
    pub latency: usize,
    pub family: Family,
}

impl Exported {
    /// One test a clock (every module but the results processor).
    pub fn pipelined(&self) -> bool {
        !matches!(
            self.family,
            Family::BundleSplit { .. }
                | Family::BundleStream { .. }
                | Family::BundleStreamFloat { .. }
        )
    }

    /// The module's Verilog, exactly as [`export_all`] writes it.
    pub fn verilog(&self) -> String {
        let pick = |v: Vec<(String, String, usize)>| {
            v.into_iter()
                .find(|(m, _, _)| *m == self.module)
                .map(|(_, v, _)| v)
                .unwrap_or_else(|| panic!("{} is in the catalogue but not exported", self.module))
        };
        match self.family {
            Family::SlabFix { fmt, cuts } if cuts == crate::slab::fix::SLAB_FIX_CUTS => {
                slab_fix_verilog(&fmt).expect("presets are instantiated")
            }
            Family::SlabFix { .. } => pick(slab_fix_deep_verilog()),
            Family::SlabFloat { f, cuts: 0 } => slab_float_verilog(&f).expect("instantiated"),
            Family::SlabFloat { .. } => pick(slab_float_deep_verilog()),
            Family::PlaneFix { .. } | Family::PlaneQuot { .. } | Family::PlaneFloat { .. } => {
                pick(plane_verilog())
            }
            Family::BundleFix { .. } => pick(bundle_fix_verilog()),
            Family::BundleFloat { f, cuts: 0 } => bundle_float_verilog(&f).expect("instantiated"),
            Family::BundleFloat { .. } => pick(bundle_float_deep_verilog()),
            Family::BundleSplit { .. } => pick(bundle_split_verilog()),
            Family::BundleStream { .. } => pick(bundle_stream_verilog()),
            Family::BundleStreamFloat { .. } => pick(bundle_stream_float_verilog()),
        }
    }
}

/// Every module [`export_all`] writes, in the same order, with its family: the one list the encoder,
/// the datasheets and the packaging read (a test checks it against the export).
pub fn catalog() -> Vec<Exported> {
    use crate::slab::fix::{SLAB_FIX_CUTS, SLAB_FIX_CUTS_DEEP};
    use crate::slab::float::SLAB_FLOAT_CUTS_DEEP;
    let mut v = vec![];
    let mut add = |module: String, latency: usize, family: Family| {
        v.push(Exported {
            module,
            latency,
            family,
        })
    };
    for fmt in FixFormat::presets() {
        add(
            names::slab_fix_module(&fmt),
            crate::SLAB_FIX_LATENCY,
            Family::SlabFix {
                fmt,
                cuts: SLAB_FIX_CUTS,
            },
        );
    }
    for fmt in FixFormat::presets() {
        add(
            names::slab_fix_module_cuts(&fmt, SLAB_FIX_CUTS_DEEP),
            crate::slab::fix::slab_fix_latency(SLAB_FIX_CUTS_DEEP),
            Family::SlabFix {
                fmt,
                cuts: SLAB_FIX_CUTS_DEEP,
            },
        );
    }
    for f in crate::SLAB_FLOAT_FORMATS {
        add(
            names::slab_float_module(&f),
            crate::SLAB_FLOAT_LATENCY,
            Family::SlabFloat { f, cuts: 0 },
        );
    }
    for f in crate::SLAB_FLOAT_FORMATS {
        add(
            names::slab_float_module_cuts(&f, SLAB_FLOAT_CUTS_DEEP),
            crate::slab::float::slab_float_latency(SLAB_FLOAT_CUTS_DEEP),
            Family::SlabFloat {
                f,
                cuts: SLAB_FLOAT_CUTS_DEEP,
            },
        );
    }
    let presets = FixFormat::presets().map(CullFixFormat::over);
    for deep in [false, true] {
        for cf in presets {
            for k in [1, 4] {
                let (s, p, _) = crate::plane::fix::PLANE_FIX_DEPTHS[deep as usize];
                add(
                    names::plane_fix_module_cuts(&cf, k, s, p),
                    crate::plane::fix::plane_fix_latency(s, p),
                    Family::PlaneFix { cf, k, deep },
                );
            }
        }
    }
    for cf in &presets[1..] {
        for k in [1, 4] {
            add(
                names::plane_quot_module(cf, k),
                crate::plane::quot::PLANE_QUOT_LATENCY,
                Family::PlaneQuot { cf: *cf, k },
            );
        }
    }
    for (f, k) in crate::PLANE_FLOAT_CONFIGS {
        if k == 1 {
            let cf = CullFloatFormat::over(f);
            add(
                names::plane_float_module(&cf, k),
                crate::PLANE_FLOAT_LATENCY,
                Family::PlaneFloat { cf, k },
            );
        }
    }
    for (cuts, _) in crate::bundle::pair_fix::BUNDLE_FIX_DEPTHS {
        for bf in golden::bundle::fix::BundleFixFormat::presets() {
            add(
                names::bundle_fix_module_cuts(&bf, cuts),
                crate::bundle::pair_fix::bundle_fix_latency(cuts),
                Family::BundleFix { bf, cuts },
            );
        }
    }
    for bf in &golden::bundle::fix::BundleFixFormat::presets()[1..] {
        add(
            names::bundle_split_module(bf),
            crate::bundle::pair_fix::BUNDLE_FIX_LATENCY + 1,
            Family::BundleSplit { bf: *bf },
        );
    }
    for (bf, cuts) in crate::bundle::stream::bundle_stream_configs() {
        add(
            names::bundle_stream_module_cuts(&bf, cuts),
            golden::bundle::stream::decided_latency(crate::bundle::pair_fix::bundle_fix_latency(
                cuts,
            )),
            Family::BundleStream { bf, cuts },
        );
    }
    for (cuts, _) in crate::bundle::pair_float::BUNDLE_FLOAT_DEPTHS {
        for f in crate::BUNDLE_FLOAT_FORMATS {
            add(
                names::bundle_float_module_cuts(&f, cuts),
                crate::bundle::pair_float::bundle_float_latency(cuts),
                Family::BundleFloat { f, cuts },
            );
        }
    }
    for (f, cuts) in crate::bundle::stream_float::bundle_stream_float_configs() {
        add(
            names::bundle_stream_float_module(&f, cuts),
            golden::bundle::stream::decided_latency(
                crate::bundle::pair_float::bundle_float_latency(cuts),
            ),
            Family::BundleStreamFloat { f, cuts },
        );
    }
    v
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

/// `(module, Verilog, latency)` of the cull-plane testers in the synthesis report: the table option over
/// b8, b12 and b16 at the default depth and the 11-clock depth and the fraction option over b12 and b16,
/// each with 1 and 4 planes; the float tester with 1 plane.
pub fn plane_verilog() -> Vec<(String, String, usize)> {
    fn named<S: crate::TesterIo>(module: String, mut uut: S) -> (String, String, usize) {
        let v = verilog_named(&mut uut, &module);
        (module, v, S::LATENCY)
    }
    fn fix<S: crate::plane::fix::PlaneFixIo>(cf: &CullFixFormat) -> (String, String, usize) {
        named(names::plane_fix_module_of::<S>(cf), S::for_format(cf))
    }
    let b8 = CullFixFormat::over(FixFormat::b8());
    let b12 = CullFixFormat::over(FixFormat::b12());
    let b16 = CullFixFormat::over(FixFormat::b16());
    let mut v = vec![
        fix::<crate::PlaneFixB8<1>>(&b8),
        fix::<crate::PlaneFixB8<4>>(&b8),
        fix::<crate::PlaneFixB12<1>>(&b12),
        fix::<crate::PlaneFixB12<4>>(&b12),
        fix::<crate::PlaneFixB16<1>>(&b16),
        fix::<crate::PlaneFixB16<4>>(&b16),
        fix::<crate::PlaneFixB8P11<1>>(&b8),
        fix::<crate::PlaneFixB8P11<4>>(&b8),
        fix::<crate::PlaneFixB12P11<1>>(&b12),
        fix::<crate::PlaneFixB12P11<4>>(&b12),
        fix::<crate::PlaneFixB16P11<1>>(&b16),
        fix::<crate::PlaneFixB16P11<4>>(&b16),
        named(
            names::plane_quot_module(&b12, 1),
            crate::PlaneQuotB12::<1>::new(&b12),
        ),
        named(
            names::plane_quot_module(&b12, 4),
            crate::PlaneQuotB12::<4>::new(&b12),
        ),
        named(
            names::plane_quot_module(&b16, 1),
            crate::PlaneQuotB16::<1>::new(&b16),
        ),
        named(
            names::plane_quot_module(&b16, 4),
            crate::PlaneQuotB16::<4>::new(&b16),
        ),
    ];
    for (f, k) in crate::PLANE_FLOAT_CONFIGS {
        if k == 1 {
            let m = names::plane_float_module(&CullFloatFormat::over(f), k);
            let text = plane_float_verilog(&f, k).expect("instantiated");
            v.push((m, text, crate::PLANE_FLOAT_LATENCY));
        }
    }
    v
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
    match (fmt.g, fmt.i, fmt.t) {
        (8, 12, 14) => Ok(verilog_named(
            &mut crate::slab::mul_round::MulRound::<9, 12, 14>::new(ceil, shift, false),
            &name,
        )),
        (12, 16, 20) => Ok(verilog_named(
            &mut crate::slab::mul_round::MulRound::<13, 16, 20>::new(ceil, shift, false),
            &name,
        )),
        (16, 20, 24) => Ok(verilog_named(
            &mut crate::slab::mul_round::MulRound::<17, 20, 24>::new(ceil, shift, false),
            &name,
        )),
        _ => Err(format!(
            "no multiply-round instance for {}: the presets are b8, b12, b16",
            fmt.name()
        )),
    }
}

/// Verilog of the fixed cull-plane tester's directed reciprocal table `BoundTable` with `2^r` entries,
/// module `plane_recip_table_r<r>`.
pub fn plane_recip_table_verilog(r: u32) -> String {
    let mut uut = crate::plane::bound_table::BoundTable::new(r);
    verilog_named(&mut uut, &format!("plane_recip_table_r{r}"))
}

/// `(module, Verilog, latency)` of the fixed pair `S` for `bf`.
fn bundle_fix_verilog_of<S: BundleFixIo>(bf: &BundleFixFormat) -> (String, String, usize) {
    let module = names::bundle_fix_of::<S>(bf);
    let v = verilog_named(&mut S::for_format(bf), &module);
    (module, v, S::LATENCY)
}

/// `(module, Verilog, latency)` of the fixed bundle pair over the presets b8, b12, b16, at every depth
/// of [`crate::bundle::pair_fix::BUNDLE_FIX_DEPTHS`] (the 3-clock pairs first; for [`export_all`]).
pub fn bundle_fix_verilog() -> Vec<(String, String, usize)> {
    let [b8, b12, b16] = BundleFixFormat::presets();
    vec![
        bundle_fix_verilog_of::<crate::BundleFixB8>(&b8),
        bundle_fix_verilog_of::<crate::BundleFixB12>(&b12),
        bundle_fix_verilog_of::<crate::BundleFixB16>(&b16),
        bundle_fix_verilog_of::<crate::BundleFixB8P5>(&b8),
        bundle_fix_verilog_of::<crate::BundleFixB12P5>(&b12),
        bundle_fix_verilog_of::<crate::BundleFixB16P5>(&b16),
    ]
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

/// `(module, Verilog, latency)` of the 13-clock float bundle pairs over [`crate::BUNDLE_FLOAT_FORMATS`].
pub fn bundle_float_deep_verilog() -> Vec<(String, String, usize)> {
    fn one<S: BundleFloatIo + Block>() -> (String, String, usize) {
        (
            names::bundle_float_of::<S>(),
            bundle_float_verilog_of::<S>(),
            S::LATENCY,
        )
    }
    vec![
        one::<crate::BundleFloatFp32P13>(),
        one::<crate::BundleFloatBf16P13>(),
        one::<crate::BundleFloatFp16P13>(),
    ]
}

/// `(module, Verilog, clocks of a decided job)` of the results processor over the presets b12 and b16
/// (for [`export_all`]).
pub fn bundle_split_verilog() -> Vec<(String, String, usize)> {
    let [_, b12, b16] = BundleFixFormat::presets();
    let decided = BUNDLE_FIX_LATENCY + 1;
    vec![
        (
            names::bundle_split_module(&b12),
            verilog_named(
                &mut crate::BundleSplitB12::new(&b12),
                &names::bundle_split_module(&b12),
            ),
            decided,
        ),
        (
            names::bundle_split_module(&b16),
            verilog_named(
                &mut crate::BundleSplitB16::new(&b16),
                &names::bundle_split_module(&b16),
            ),
            decided,
        ),
    ]
}

/// `(module, Verilog, clocks of a decided job)` of a streaming processor `S` over `dp`.
pub fn bundle_stream_verilog_of<S: BundleStreamIo>(dp: &S::Dp) -> (String, String, usize) {
    let module = names::bundle_stream_of::<S>(dp);
    let v = verilog_named(&mut S::for_format(dp), &module);
    (module, v, decided_latency(S::PAIR_LATENCY))
}

/// `(module, Verilog, clocks of a decided job)` of every configuration in [`crate::bundle::stream::bundle_stream_configs`]
/// (for [`export_all`]).
pub fn bundle_stream_verilog() -> Vec<(String, String, usize)> {
    let [_, b12, b16] = BundleFixFormat::presets();
    vec![
        bundle_stream_verilog_of::<crate::BundleStreamB12>(&b12),
        bundle_stream_verilog_of::<crate::BundleStreamB16>(&b16),
        bundle_stream_verilog_of::<crate::BundleStreamB12P5>(&b12),
    ]
}

/// `(module, Verilog, clocks of a decided job)` of every configuration in
/// [`crate::bundle::stream_float::bundle_stream_float_configs`] (for [`export_all`]).
pub fn bundle_stream_float_verilog() -> Vec<(String, String, usize)> {
    vec![
        bundle_stream_verilog_of::<crate::BundleStreamFp32>(&FloatFormat::FP32),
        bundle_stream_verilog_of::<crate::BundleStreamBf16>(&FloatFormat::BF16),
        bundle_stream_verilog_of::<crate::BundleStreamFp16>(&FloatFormat::FP16),
        bundle_stream_verilog_of::<crate::BundleStreamFp16P13>(&FloatFormat::FP16),
    ]
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

    #[test]
    fn the_catalogue_lists_what_the_export_writes_with_the_same_latencies() {
        // rust-hdl's Verilog generation of the cull-plane testers recurses deeper than a test thread's
        // stack.
        std::thread::Builder::new()
            .stack_size(256 << 20)
            .spawn(catalogue_matches_export)
            .unwrap()
            .join()
            .unwrap();
    }

    fn catalogue_matches_export() {
        let dir = std::env::temp_dir().join(format!("rtu_catalog_{}", std::process::id()));
        export_all(&dir).unwrap();
        let written = std::fs::read_to_string(dir.join("latency.csv")).unwrap();
        let listed: String = std::iter::once("module,latency\n".to_string())
            .chain(
                catalog()
                    .iter()
                    .map(|e| format!("{},{}\n", e.module, e.latency)),
            )
            .collect();
        assert_eq!(written, listed);
        // Each entry's Verilog is the file the export wrote (spot check across families).
        for e in catalog().iter().step_by(7) {
            let v = std::fs::read_to_string(dir.join(format!("{}.v", e.module))).unwrap();
            assert!(v == e.verilog(), "{}", e.module);
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
