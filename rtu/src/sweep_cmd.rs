//! `rtu sweep`: speed against accuracy on scenes. Every configuration — datapath and format,
//! planes per node `K`, bundle size `B` — runs the same traversal model ([`golden::scene::sweep`]) over the
//! scene's primary, bounce and shadow rays; accuracy is measured against the exact machine of the same
//! `K` and `B`, cost is joined from the synthesis table (area and logic depth from Yosys, latency) and the
//! traversal's tester cycles per ray. Writes `sweep.csv`, `sweep.md` and per scene two SVG charts (extra
//! tester cycles against area, cycles per ray against area) with the Pareto front drawn.

use crate::chart::{scatter_chart, Point};
use crate::opts::list;
use golden::bundle::build::{build, tiles, BuildParams, Built};
use golden::bundle::fix::BundleFixFormat;
use golden::bundle::traverse::BundlePath;
use golden::format::fixed::{FixFormat, GridMap};
use golden::format::float::FloatFormat;
use golden::geom::Ray;
use golden::plane::clip::Plane;
use golden::plane::fix::CullFixFormat;
use golden::plane::float::CullFloatFormat;
use golden::scene::bvh::Bvh;
use golden::scene::sweep::{
    traverse, ExactTester, FixTester, FloatTester, Intervals, Machine, Mode, RaySet, SceneStats,
};
use golden::scene::traverse::{trace, AabbOnly, NodeTester};
use golden::scene::tri_scene::TriScene;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `rtu sweep`.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// Scenes, comma-separated: built-in names (room, grass, mesh, soup) or OBJ files (`*.obj`).
    #[arg(long, default_value = "room,grass,mesh,soup")]
    pub scenes: String,
    /// Fixed formats (b8, b12, b16, or G,I,FI,T,FT separated by `/`), comma-separated; empty for none.
    #[arg(long, default_value = "b8,b12,b16")]
    pub fixed: String,
    /// Float formats (fp32, bf16, fp16, eXmY), comma-separated; empty for none.
    #[arg(long, default_value = "fp32,bf16,fp16")]
    pub float: String,
    /// Planes per node, comma-separated (0 = the slab tester alone). Each node's planes are generated
    /// once, for the largest K listed, and a K-plane tester takes the first K of them, so the figures
    /// of a smaller K depend on the largest K in the list (`golden::plane::generate` re-fits parents to the
    /// children's normals, which depend on how many planes are made).
    #[arg(long, default_value = "0,1,4")]
    pub k: String,
    /// Rays per bundle, comma-separated (1 = single rays; otherwise a square: 4, 16, 64).
    #[arg(long, default_value = "1,4,16")]
    pub bundle: String,
    /// Image width and height of the primary rays.
    #[arg(long, default_value_t = 32)]
    pub width: usize,
    #[arg(long, default_value_t = 24)]
    pub height: usize,
    /// Ray sets measured, comma-separated: primary, bounce, shadow.
    #[arg(long, default_value = "primary,bounce,shadow")]
    pub sets: String,
    /// Secondary-ray origins are moved off the surface by this fraction of the scene's diagonal (see
    /// `golden::scene::tri_scene::secondary_rays_offset`: a unit cannot tell an origin nearer than its resolution
    /// from the surface). The default is of the order of Waechter and Binder's self-intersection offset
    /// (Ray Tracing Gems, ch. 6, 2019: 256 binary32 ulps of the hit point, about 3e-5 of its magnitude).
    #[arg(long, default_value_t = 1e-5)]
    pub offset: f64,
    /// Seed of the scenes and the secondary rays.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Synthesis table (the CSV `scripts/synth` writes; rows of several runs may be concatenated);
    /// default: docs/sweep/area.csv of this source tree, when there is one.
    #[arg(long)]
    pub area: Option<PathBuf>,
    /// Post-route timing table (the CSV `scripts/timing` writes); default: docs/timing/timing.csv of this
    /// source tree, when there is one. Gives each configuration whose modules it names a clock (the
    /// slowest module's Fmax) and rays per second.
    #[arg(long)]
    pub timing: Option<PathBuf>,
    /// Traversal mode: `default` (closest hit for primary and bounce rays, any hit for shadow rays, as a
    /// renderer runs them), or `closest`, `any` or `all` (all hits: nothing shrinks or stops) for every set.
    #[arg(long, default_value = "default")]
    pub mode: String,
}

impl Args {
    /// The main job's small sweep: the room, 16x12 primary rays and their secondary rays, b8/b12/b16 and
    /// fp16/fp32, no planes or one, single rays or 2x2 bundles.
    pub fn small() -> Self {
        Args {
            scenes: "room".into(),
            fixed: "b8,b12,b16".into(),
            float: "fp32,fp16".into(),
            k: "0,1".into(),
            bundle: "1,4".into(),
            width: 16,
            height: 12,
            sets: "primary,bounce,shadow".into(),
            offset: 1e-5,
            seed: 1,
            area: None,
            timing: None,
            mode: "default".into(),
        }
    }

    /// The arguments as `rtu sweep` options.
    pub fn describe(&self) -> String {
        format!(
            "rtu sweep --scenes {} --fixed {} --float {} --k {} --bundle {} --width {} --height {} --mode {}",
            self.scenes, self.fixed, self.float, self.k, self.bundle, self.width, self.height, self.mode
        )
    }
}

/// A datapath and format of the sweep.
#[derive(Clone, Copy, Debug)]
pub enum Format {
    Fix(FixFormat),
    Float(FloatFormat),
}

impl Format {
    pub fn name(&self) -> String {
        match self {
            Format::Fix(f) => golden::bundle::traverse::short_name(f),
            Format::Float(f) => float_short(f),
        }
    }
    pub fn datapath(&self) -> &'static str {
        match self {
            Format::Fix(_) => "fixed",
            Format::Float(_) => "float",
        }
    }
    /// Bits of a stored coordinate: the grid width `G` (fixed), the whole word `1 + E + M` (float).
    pub fn bits(&self) -> u32 {
        match self {
            Format::Fix(f) => f.g,
            Format::Float(f) => 1 + f.e + f.m,
        }
    }
}

/// `fp32`, `bf16`, `fp16`, or the format's `eXmY` name.
pub fn float_short(f: &FloatFormat) -> String {
    match (f.e, f.m) {
        (8, 23) => "fp32".into(),
        (8, 7) => "bf16".into(),
        (5, 10) => "fp16".into(),
        _ => f.name(),
    }
}

/// One row of the synthesis table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Area {
    pub latency: usize,
    pub ice40_lut4: u64,
    pub ice40_depth: u64,
    pub xilinx_lut: u64,
    pub xilinx_dsp: u64,
}

impl Area {
    fn plus(&self, o: &Area) -> Area {
        Area {
            latency: self.latency.max(o.latency),
            ice40_lut4: self.ice40_lut4 + o.ice40_lut4,
            ice40_depth: self.ice40_depth.max(o.ice40_depth),
            xilinx_lut: self.xilinx_lut + o.xilinx_lut,
            xilinx_dsp: self.xilinx_dsp + o.xilinx_dsp,
        }
    }
}

/// The area table: the file given (which must exist), or by default `docs/sweep/area.csv` from here or
/// in the source tree this binary was built from (so `cargo run` from any folder finds it); an empty
/// table when neither exists.
pub fn load_area(given: Option<&Path>) -> Result<HashMap<String, Area>, String> {
    load_table(given, "--area", "docs/sweep/area.csv", read_area)
}

/// A per-module table: the file given to `option` (which must exist) read by `read`, or by default the
/// project's table at `rel` ([`default_table`]); an empty table when there is none.
fn load_table<T>(
    given: Option<&Path>,
    option: &str,
    rel: &str,
    read: fn(&Path) -> Result<HashMap<String, T>, String>,
) -> Result<HashMap<String, T>, String> {
    if let Some(p) = given {
        if !p.exists() {
            return Err(format!("{option} {}: no such file", p.display()));
        }
        return read(p);
    }
    default_table(rel).map_or_else(|| Ok(HashMap::new()), |p| read(&p))
}

/// A table of this project found by its path in the source tree: from the current folder, or from the
/// source tree this binary was built from (so `cargo run` from any folder finds it).
fn default_table(rel: &str) -> Option<PathBuf> {
    let here = PathBuf::from(rel);
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(rel);
    [here, src].into_iter().find(|p| p.exists())
}

/// One module's post-route figures on ECP5 (a row of `docs/timing/timing.csv`).
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    pub fmax_mhz: f64,
    pub lut4: u64,
    /// Flip-flops and MULT18X18D blocks, when the table has the columns `ff` and `mult18`.
    pub ff: Option<u64>,
    pub mult18: Option<u64>,
}

/// The timing table: the file given (which must exist), or by default `docs/timing/timing.csv` (found
/// as the area table is); an empty table when neither exists.
pub fn load_timing(given: Option<&Path>) -> Result<HashMap<String, Timing>, String> {
    load_table(given, "--timing", "docs/timing/timing.csv", read_timing)
}

/// Reads a timing CSV (`scripts/timing`'s `timing.csv`): a header line with at least the columns
/// `module`, `lut4` and `fmax_mhz` (others are carried by the file and ignored here), then one row per
/// module; a later row of a module replaces an earlier one. A missing column, a row with the wrong
/// number of cells, a LUT4 count that is not a count or an Fmax that is not a positive finite number is
/// an error naming the file, the line and the column.
pub fn read_timing(path: &Path) -> Result<HashMap<String, Timing>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read the timing table: {e}", path.display()))?;
    let mut lines = golden::text::strip_bom(&text)
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let Some((_, head)) = lines.next() else {
        return Err(format!(
            "{}: empty timing table (no header line)",
            path.display()
        ));
    };
    let cols: Vec<&str> = head.split(',').map(str::trim).collect();
    let col = |name: &str| {
        cols.iter().position(|c| *c == name).ok_or_else(|| {
            format!(
                "{}:1: column `{name}` missing from the header",
                path.display()
            )
        })
    };
    let (im, il, ifm) = (col("module")?, col("lut4")?, col("fmax_mhz")?);
    let (iff, imu) = (col("ff").ok(), col("mult18").ok());
    let mut t = HashMap::new();
    for (n, line) in lines {
        let bad = |what: String| format!("{}:{}: {what}", path.display(), n + 1);
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != cols.len() {
            return Err(bad(format!(
                "{} cells, but the header has {}",
                f.len(),
                cols.len()
            )));
        }
        let lut4 = f[il]
            .parse::<u64>()
            .map_err(|_| bad(format!("column `lut4`: `{}` is not a count", f[il])))?;
        let fmax_mhz = f[ifm]
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v > 0.0)
            .ok_or_else(|| {
                bad(format!(
                    "column `fmax_mhz`: `{}` is not a positive frequency in MHz",
                    f[ifm]
                ))
            })?;
        let count = |i: Option<usize>, name: &str| -> Result<Option<u64>, String> {
            i.map(|i| {
                f[i].parse::<u64>()
                    .map_err(|_| bad(format!("column `{name}`: `{}` is not a count", f[i])))
            })
            .transpose()
        };
        let (ff, mult18) = (count(iff, "ff")?, count(imu, "mult18")?);
        t.insert(
            f[im].to_string(),
            Timing {
                fmax_mhz,
                lut4,
                ff,
                mult18,
            },
        );
    }
    Ok(t)
}

/// The columns of a synthesis CSV (`scripts/synth` writes them all); the first six are required.
const AREA_COLUMNS: [&str; 11] = [
    "module",
    "latency",
    "ice40_lut4",
    "ice40_depth",
    "xilinx_lut",
    "xilinx_dsp",
    "generic_cells",
    "ice40_carry",
    "ice40_ff",
    "xilinx_ff",
    "ice40_stage_depth",
];

/// Reads a synthesis CSV: a header line naming its columns ([`AREA_COLUMNS`], any order, each once), then
/// one row per module. Rows of several runs may be concatenated: a later header line (one with a `module`
/// cell) names the columns of the rows after it, and a later row of a module replaces an earlier
/// one. A leading byte-order mark is skipped. An unknown or repeated column, a missing required one, a
/// row with the wrong number of cells or a cell that is not a count is an error naming the file, the line
/// and the column.
pub fn read_area(path: &Path) -> Result<HashMap<String, Area>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read the area table: {e}", path.display()))?;
    let mut t = HashMap::new();
    let mut cols: Option<Vec<String>> = None;
    for (n, line) in golden::text::strip_bom(&text).lines().enumerate() {
        let bad = |what: String| format!("{}:{}: {what}", path.display(), n + 1);
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if line.trim().is_empty() {
            continue;
        }
        if cols.is_none() || f.contains(&"module") {
            for (i, c) in f.iter().enumerate() {
                if f[..i].contains(c) {
                    return Err(bad(format!("column `{c}` named twice in the header")));
                }
                if !AREA_COLUMNS.contains(c) {
                    return Err(bad(format!(
                        "column `{c}`: {}",
                        golden::text::unknown_field(c, &AREA_COLUMNS)
                    )));
                }
            }
            if let Some(c) = AREA_COLUMNS[..6].iter().find(|c| !f.contains(c)) {
                return Err(bad(format!("column `{c}` missing from the header")));
            }
            cols = Some(f.iter().map(|c| c.to_string()).collect());
            continue;
        }
        let cols = cols.as_ref().expect("the first line is the header");
        if f.len() != cols.len() {
            return Err(bad(format!(
                "{} cells, but the header has {} (rows of another run need their own header line)",
                f.len(),
                cols.len()
            )));
        }
        let num = |name: &str| -> Result<u64, String> {
            let i = cols
                .iter()
                .position(|c| c == name)
                .expect("a required column");
            f[i].parse::<u64>()
                .map_err(|_| bad(format!("column `{name}`: `{}` is not a count", f[i])))
        };
        t.insert(
            f[cols
                .iter()
                .position(|c| c == "module")
                .expect("module column")]
            .to_string(),
            Area {
                latency: num("latency")? as usize,
                ice40_lut4: num("ice40_lut4")?,
                ice40_depth: num("ice40_depth")?,
                xilinx_lut: num("xilinx_lut")?,
                xilinx_dsp: num("xilinx_dsp")?,
            },
        );
    }
    Ok(t)
}

/// The RTL modules a configuration needs: the single-ray node tester, and the pair when `B > 1`.
pub fn modules(f: &Format, k: usize, b: usize) -> Result<Vec<String>, String> {
    let mut m = vec![match f {
        Format::Fix(x) if k == 0 => rtl::names::slab_fix_module(x),
        Format::Fix(x) => rtl::names::plane_fix_module(
            &CullFixFormat::try_over(*x).map_err(|e| format!("{}: {e}", x.name()))?,
            k,
        ),
        Format::Float(x) if k == 0 => rtl::names::slab_float_module(x),
        Format::Float(x) => rtl::names::plane_float_module(&CullFloatFormat::over(*x), k),
    }];
    if b > 1 {
        m.push(match f {
            Format::Fix(x) => rtl::names::bundle_fix_module(
                &BundleFixFormat::over(*x).map_err(|e| e.to_string())?,
            ),
            Format::Float(x) => rtl::names::bundle_float_module(x),
        });
    }
    Ok(m)
}

/// The bundles of a ray set for bundle size `b`: single rays, square tiles of the image (primary), or
/// the builder's bundles (secondary; direction spread 0.2, origin spread a tenth of the diagonal).
pub fn bundles(
    set: &str,
    rays: &[Ray],
    b: usize,
    w: usize,
    h: usize,
    diag: f64,
) -> Result<Vec<Built>, String> {
    if set == "primary" {
        let s = (b as f64).sqrt().round() as usize;
        if s * s != b {
            return Err(format!(
                "bundle size {b}: primary rays are bundled in square tiles (1, 4, 16, 64)"
            ));
        }
        return tiles(rays, w, h, s).map_err(|e| e.to_string());
    }
    if b == 1 {
        return tiles(rays, rays.len(), 1, 1).map_err(|e| e.to_string());
    }
    build(
        rays,
        &BuildParams {
            max_rays: b,
            origin_spread: 0.1 * diag,
            dir_spread: 0.2,
            t_spread: f64::INFINITY,
            open_slots: 16,
        },
    )
    .map_err(|e| format!("{set} rays: {e}"))
}

/// One measured configuration on one scene (all ray sets summed).
#[derive(Clone, Debug)]
pub struct Rec {
    pub scene: String,
    pub format: Format,
    pub k: usize,
    pub b: usize,
    pub st: SceneStats,
    /// The exact machine of the same `K` and `B`.
    pub exact: SceneStats,
    pub modules: Vec<String>,
    pub area: Option<Area>,
    /// The modules' post-route figures together: the slowest one's Fmax, their LUT4s summed; `None`
    /// unless the timing table has every module.
    pub timing: Option<Timing>,
    /// The traversal mode (`None`: each ray set's default).
    pub mode: Option<Mode>,
    /// Single rays (`B = 1`) only: what the format's interval costs, [`IntervalCost`].
    pub iv: Option<IntervalCost>,
}

/// What a format's `t` interval costs (the README's "what a loose interval costs"): the same machine
/// with the format's culls but the exact tester's intervals ([`Intervals`]), and for `K > 0` with the
/// planes' culls but the format's slab interval (no entry/exit update). In all-hits mode both equal the
/// format's own figures.
#[derive(Clone, Copy, Debug)]
pub struct IntervalCost {
    pub exact: SceneStats,
    pub slab_entry: Option<SceneStats>,
}

/// Runs the two machines of [`IntervalCost`] for tester `t` of format `f`.
pub fn interval_cost(
    p: &Prepared,
    sets: &mut [RaySet],
    t: &mut dyn NodeTester,
    f: &Format,
    planes: &[Vec<Plane>],
    c: RunCfg,
) -> Result<IntervalCost, String> {
    let mut ex = ExactTester::new(&p.bvh, planes, c.k);
    let exact = run_machine(
        p,
        sets,
        &mut Intervals {
            cull: t,
            interval: &mut ex,
        },
        None,
        c,
    )
    .map_err(|e| format!("{} with exact intervals: {e}", f.name()))?;
    let slab_entry = if c.k > 0 {
        let (mut slab, _) = tester(p, f, planes, 0)?;
        Some(
            run_machine(
                p,
                sets,
                &mut Intervals {
                    cull: t,
                    interval: slab.as_mut(),
                },
                None,
                c,
            )
            .map_err(|e| format!("{} with the slab's interval: {e}", f.name()))?,
        )
    } else {
        None
    };
    Ok(IntervalCost { exact, slab_entry })
}

impl Rec {
    /// Rays per second at the modules' clock (the slowest one's Fmax): Fmax over tester cycles per ray,
    /// each unit testing one node a clock and the pair's cycles counted beside the single-ray tester's, as
    /// if one unit ran at a time (`SceneStats::cycles_per_ray`).
    pub fn rays_per_s(&self) -> Option<f64> {
        let t = self.timing.as_ref()?;
        Some(t.fmax_mhz * 1e6 / self.st.cycles_per_ray())
    }

    /// Rays per second per 1,000 ECP5 LUT4s of the configuration's modules.
    pub fn rays_per_s_per_klut4(&self) -> Option<f64> {
        Some(self.rays_per_s()? / (self.timing.as_ref()?.lut4 as f64 / 1000.0))
    }

    /// Tester cycles beyond the exact machine's, as a fraction of its.
    pub fn extra_cycles(&self) -> f64 {
        let c = |s: &SceneStats| (s.box_tests + s.pair_tests) as f64;
        c(&self.st) / c(&self.exact).max(1.0) - 1.0
    }
    /// Triangle tests beyond the exact machine's, as a fraction of its.
    pub fn extra_tris(&self) -> f64 {
        self.st.tri_tests as f64 / self.exact.tri_tests.max(1) as f64 - 1.0
    }
    pub fn label(&self) -> String {
        format!("{} K{} B{}", self.format.name(), self.k, self.b)
    }
}

/// A scene by name or OBJ path.
pub fn load_scene(name: &str, seed: u64) -> Result<TriScene, String> {
    if name.ends_with(".obj") {
        golden::scene::tri_scene::load_obj(Path::new(name)).map_err(|e| e.to_string())
    } else {
        golden::scene::tri_scene::by_name(name, seed, None).map_err(|e| e.to_string())
    }
}

/// A scene prepared for measuring: BVH, planes per K, ray sets with their exact facts.
pub struct Prepared<'a> {
    pub sc: &'a TriScene,
    pub bvh: Bvh,
    pub sets: Vec<(&'static str, Vec<Ray>)>,
    pub lo_hi: (glam::DVec3, glam::DVec3),
    pub diag: f64,
}

impl<'a> Prepared<'a> {
    /// Builds the BVH (binned SAH, leaves of up to 4) and the primary (`w x h`), bounce and shadow rays;
    /// keeps the sets named in `sets`.
    pub fn new(
        sc: &'a TriScene,
        w: usize,
        h: usize,
        seed: u64,
        sets: &[String],
        offset: f64,
    ) -> Result<Self, String> {
        if !(offset.is_finite() && (0.0..=0.1).contains(&offset)) {
            return Err(format!(
                "--offset {offset}: the secondary-ray offset must be in [0, 0.1] of the diagonal"
            ));
        }
        if let Some(bad) = sets
            .iter()
            .find(|s| !["primary", "bounce", "shadow"].contains(&s.as_str()))
        {
            return Err(format!(
                "ray set `{bad}`: expected primary, bounce or shadow"
            ));
        }
        let bvh = Bvh::build(&sc.tris, 4).map_err(|e| e.to_string())?;
        let prim = golden::scene::tri_scene::primary_rays(sc, w, h);
        let (hits, _) = trace(&bvh, &sc.tris, &prim, &mut AabbOnly::new(&bvh));
        let sec =
            golden::scene::tri_scene::secondary_rays_offset(sc, &prim, &hits, seed + 1, offset);
        let b = sc.bounds();
        Ok(Prepared {
            sc,
            bvh,
            sets: [
                ("primary", prim),
                ("bounce", sec.bounce),
                ("shadow", sec.shadow),
            ]
            .into_iter()
            .filter(|(n, _)| sets.iter().any(|s| s == n))
            .collect(),
            lo_hi: sc.grid_bounds(),
            diag: (b.max - b.min).length(),
        })
    }
}

/// A single-ray node tester of a format over a prepared scene.
pub fn tester(
    p: &Prepared,
    f: &Format,
    planes: &[Vec<Plane>],
    k: usize,
) -> Result<(Box<dyn NodeTester>, Option<BundlePath>), String> {
    let e = |e: golden::Error| format!("{}: {e}", f.name());
    Ok(match f {
        Format::Fix(x) => {
            let map = GridMap::for_bounds(*x, p.lo_hi.0, p.lo_hi.1).map_err(e)?;
            let cf = if k == 0 {
                CullFixFormat::slab_only(*x)
            } else {
                CullFixFormat::try_over(*x)
            }
            .map_err(e)?;
            let t = FixTester::new(cf, map, &p.bvh, &p.sc.tris, planes, k).map_err(e)?;
            for (name, rays) in &p.sets {
                t.check_rays(rays)
                    .map_err(|x| format!("{}: {name} {x}", f.name()))?;
            }
            let pair = BundleFixFormat::over(*x)
                .ok()
                .map(|bf| BundlePath::Fix(bf, map));
            (Box::new(t), pair)
        }
        Format::Float(x) => {
            let t = FloatTester::new(CullFloatFormat::over(*x), &p.bvh, &p.sc.tris, planes, k)
                .map_err(e)?;
            for (name, rays) in &p.sets {
                t.check_rays(rays)
                    .map_err(|x| format!("{}: {name} {x}", f.name()))?;
            }
            (Box::new(t), Some(BundlePath::Float(*x)))
        }
    })
}

/// What a machine run needs besides the tester: planes per node, bundle size, image size, and the
/// traversal mode (`None`: each ray set's default, [`Mode::default_for`]).
#[derive(Clone, Copy, Debug)]
pub struct RunCfg {
    pub k: usize,
    pub b: usize,
    pub w: usize,
    pub h: usize,
    pub mode: Option<Mode>,
}

/// Parses a `--mode` option: `default` (each ray set's own mode) or a [`Mode`] for every set.
pub fn parse_mode(s: &str) -> Result<Option<Mode>, String> {
    if s == "default" {
        return Ok(None);
    }
    Mode::parse(s)
        .map(Some)
        .map_err(|_| format!("--mode `{s}`: expected default, closest, any or all"))
}

/// The name of a `--mode` value, as the tables print it.
pub fn mode_name(m: Option<Mode>) -> &'static str {
    m.map_or("default", |m| m.name())
}

/// Runs one machine over one ray set (`name`: primary, bounce or shadow) of a prepared scene.
pub fn run_set(
    p: &Prepared,
    name: &str,
    set: &mut RaySet,
    t: &mut dyn NodeTester,
    pair: Option<&BundlePath>,
    c: RunCfg,
) -> Result<SceneStats, String> {
    let built = bundles(name, set.rays, c.b, c.w, c.h, p.diag)?;
    let mut m = Machine {
        tester: t,
        planes: c.k,
        pair: if c.b > 1 { pair } else { None },
        rebound: true,
        mode: c.mode.unwrap_or_else(|| Mode::default_for(name)),
    };
    traverse(&p.bvh, &p.sc.tris, set, &built, &mut m, || {})
        .map_err(|e| format!("{name} rays: {e}"))
}

/// Runs one machine over every ray set of a prepared scene, summing the counts.
pub fn run_machine(
    p: &Prepared,
    sets: &mut [RaySet],
    t: &mut dyn NodeTester,
    pair: Option<&BundlePath>,
    c: RunCfg,
) -> Result<SceneStats, String> {
    let mut total = SceneStats::default();
    for (i, set) in sets.iter_mut().enumerate() {
        total.add(&run_set(p, p.sets[i].0, set, t, pair, c)?);
    }
    Ok(total)
}

/// Parses the format lists of the arguments.
pub fn formats(fixed: &str, float: &str) -> Result<Vec<Format>, String> {
    let mut v = list(fixed, |s| {
        FixFormat::parse(&s.replace('/', ","))
            .map(Format::Fix)
            .map_err(|e| format!("--fixed `{s}`: {e}"))
    })?;
    v.extend(list(float, |s| {
        FloatFormat::parse(s)
            .map(Format::Float)
            .map_err(|e| format!("--float `{s}`: {e}"))
    })?);
    Ok(v)
}

/// Measures every configuration on every scene; returns the records and each scene's diagonal (progress
/// lines on stderr).
pub fn measure(a: &Args) -> Result<(Vec<Rec>, HashMap<String, f64>), String> {
    let fmts = formats(&a.fixed, &a.float)?;
    let ks = list(&a.k, |s| {
        let k: usize = s
            .parse()
            .map_err(|_| format!("--k `{s}` is not a number"))?;
        if k > 8 {
            return Err(format!("--k {k}: the testers take 0 to 8 planes per node"));
        }
        Ok(k)
    })?;
    let bs = list(&a.bundle, |s| {
        let b: usize = s
            .parse()
            .map_err(|_| format!("--bundle `{s}` is not a number"))?;
        if !matches!(b, 1 | 4 | 16 | 64) {
            return Err(format!(
                "--bundle {b}: bundle sizes are 1, 4, 16 or 64 (square tiles)"
            ));
        }
        Ok(b)
    })?;
    if a.width == 0 || a.height == 0 {
        return Err("--width and --height must be at least 1".into());
    }
    let area = load_area(a.area.as_deref())?;
    let timing = load_timing(a.timing.as_deref())?;
    let mut scenes: Vec<String> = vec![];
    for s in list(&a.scenes, |s| Ok(s.to_string()))? {
        if scenes.contains(&s) {
            return Err(format!("--scenes: `{s}` is listed twice"));
        }
        scenes.push(s);
    }
    let set_names = list(&a.sets, |s| Ok(s.to_string()))?;
    let mode = parse_mode(&a.mode)?;
    let total = scenes.len() * ks.len() * bs.len() * (fmts.len() + 1);
    let mut done = 0;
    let mut recs = vec![];
    let mut diag = HashMap::new();
    for name in &scenes {
        let sc = load_scene(name, a.seed)?;
        let p = Prepared::new(&sc, a.width, a.height, a.seed, &set_names, a.offset)?;
        diag.insert(name.clone(), p.diag);
        let mut sets: Vec<RaySet> = p
            .sets
            .iter()
            .map(|(_, r)| RaySet::new(&p.bvh, &sc.tris, r))
            .collect();
        let kmax = ks.iter().copied().max().unwrap_or(0);
        let planes = if kmax > 0 {
            golden::plane::generate::generate(&p.bvh, &sc.tris, kmax).map_err(|e| e.to_string())?
        } else {
            vec![]
        };
        for &k in &ks {
            for &b in &bs {
                let t0 = Instant::now();
                let cfg = RunCfg {
                    k,
                    b,
                    w: a.width,
                    h: a.height,
                    mode,
                };
                let mut ex = ExactTester::new(&p.bvh, &planes, k);
                let exact = run_machine(&p, &mut sets, &mut ex, Some(&BundlePath::Exact), cfg)
                    .map_err(|e| format!("{name} exact K{k} B{b}: {e}"))?;
                done += 1;
                eprintln!(
                    "[{done}/{total}] {name} exact K{k} B{b}: {:.1} s",
                    t0.elapsed().as_secs_f64()
                );
                for f in &fmts {
                    let t0 = Instant::now();
                    let (mut t, pair) = tester(&p, f, &planes, k)?;
                    if b > 1 && pair.is_none() {
                        return Err(format!("{}: no bundle pair for this format", f.name()));
                    }
                    let st = run_machine(&p, &mut sets, t.as_mut(), pair.as_ref(), cfg)
                        .map_err(|e| format!("{name} {} K{k} B{b}: {e}", f.name()))?;
                    let iv = if b == 1 {
                        Some(
                            interval_cost(&p, &mut sets, t.as_mut(), f, &planes, cfg)
                                .map_err(|e| format!("{name} K{k} B{b}: {e}"))?,
                        )
                    } else {
                        None
                    };
                    let mods = modules(f, k, b)?;
                    let area = mods
                        .iter()
                        .map(|m| area.get(m).cloned())
                        .collect::<Option<Vec<_>>>()
                        .map(|v| v.iter().fold(Area::default(), |acc, x| acc.plus(x)));
                    let tm = mods
                        .iter()
                        .map(|m| timing.get(m))
                        .collect::<Option<Vec<_>>>()
                        .map(|v| Timing {
                            fmax_mhz: v.iter().map(|t| t.fmax_mhz).fold(f64::INFINITY, f64::min),
                            lut4: v.iter().map(|t| t.lut4).sum(),
                            ff: None,
                            mult18: None,
                        });
                    done += 1;
                    eprintln!(
                        "[{done}/{total}] {name} {} K{k} B{b}: {:.1} s",
                        f.name(),
                        t0.elapsed().as_secs_f64()
                    );
                    recs.push(Rec {
                        scene: name.clone(),
                        format: *f,
                        k,
                        b,
                        st,
                        exact,
                        modules: mods,
                        area,
                        timing: tm,
                        mode,
                        iv,
                    });
                }
            }
        }
    }
    Ok((recs, diag))
}

/// Indices of the records on the Pareto front of (cost, badness): no other record is at most as costly
/// and at most as bad, and strictly better in one. Records without a cost are left out.
pub fn pareto(pts: &[(f64, f64)]) -> Vec<usize> {
    let mut front: Vec<usize> = (0..pts.len())
        .filter(|&i| {
            !pts.iter().enumerate().any(|(j, q)| {
                j != i && q.0 <= pts[i].0 && q.1 <= pts[i].1 && (q.0 < pts[i].0 || q.1 < pts[i].1)
            })
        })
        .collect();
    front.sort_by(|&a, &b| pts[a].0.total_cmp(&pts[b].0));
    front
}

/// CSV header of `sweep.csv`. `plane_tests`: plane evaluations (each single-ray test of a node runs its
/// `K` plane units; the pair tests boxes only).
pub const CSV_HEADER: &str = "scene,datapath,format,coord_bits,k,bundle,rays,box_tests,plane_tests,pair_tests,pair_ideal,pair_decided,cycles_per_ray,exact_cycles_per_ray,extra_cycles,tri_tests,exact_tri_tests,extra_tri_tests,false_box_hits,true_box_misses,false_hit_rate,plane_culls,mean_looseness,looseness_of_diagonal,hits,modules,latency,ice40_lut4,ice40_depth,xilinx_lut,xilinx_dsp,pareto_accuracy,pareto_speed,ecp5_fmax_mhz,ecp5_lut4,rays_per_s,rays_per_s_per_klut4,pareto_rays_per_area,mode,entry_skips,exact_interval_box_tests,exact_interval_tri_tests,slab_entry_box_tests,slab_entry_tri_tests";

/// Writes `sweep.csv`, `sweep.md` and the charts under `out`; returns the markdown.
pub fn report(recs: &[Rec], out: &Path, diag: &HashMap<String, f64>) -> Result<String, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut csv = format!("{CSV_HEADER}\n");
    let mode = recs.first().map_or("default", |r| mode_name(r.mode));
    let mut md = format!(
        "Traversal mode: {mode}{}.\n\n",
        if mode == "default" {
            " (closest hit for primary and bounce rays, any hit for shadow rays)"
        } else {
            ""
        }
    );
    md.push_str("| scene | format | K | B | cycles/ray | extra cycles vs exact | extra triangle tests | false-hit rate | looseness (of diagonal) | iCE40 LUT4 | 7-series LUT + DSP | latency | ECP5 MHz | Mrays/s | Mrays/s per 1k ECP5 LUT4 | front |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    let scenes: Vec<&String> = {
        let mut v: Vec<&String> = recs.iter().map(|r| &r.scene).collect();
        v.dedup();
        v
    };
    for scene in scenes {
        let rs: Vec<&Rec> = recs.iter().filter(|r| &r.scene == scene).collect();
        let with_area: Vec<usize> = (0..rs.len()).filter(|&i| rs[i].area.is_some()).collect();
        let cost = |i: usize| rs[i].area.as_ref().map_or(0.0, |a| a.ice40_lut4 as f64);
        let acc: Vec<(f64, f64)> = with_area
            .iter()
            .map(|&i| (cost(i), rs[i].extra_cycles()))
            .collect();
        let spd: Vec<(f64, f64)> = with_area
            .iter()
            .map(|&i| (cost(i), rs[i].st.cycles_per_ray()))
            .collect();
        let fa: Vec<usize> = pareto(&acc).into_iter().map(|j| with_area[j]).collect();
        let fs: Vec<usize> = pareto(&spd).into_iter().map(|j| with_area[j]).collect();
        // Accuracy against rays per second per area: more rays per LUT4 is better, so the front is of
        // (its reciprocal, extra cycles).
        let with_time: Vec<usize> = (0..rs.len())
            .filter(|&i| rs[i].rays_per_s_per_klut4().is_some())
            .collect();
        let per_area = |i: usize| rs[i].rays_per_s_per_klut4().unwrap_or(0.0);
        let tp: Vec<(f64, f64)> = with_time
            .iter()
            .map(|&i| (1.0 / per_area(i), rs[i].extra_cycles()))
            .collect();
        let ft: Vec<usize> = pareto(&tp).into_iter().map(|j| with_time[j]).collect();
        let d = diag.get(scene).copied().unwrap_or(1.0);
        for (i, r) in rs.iter().enumerate() {
            let a = r.area.clone();
            let cell = |f: &dyn Fn(&Area) -> String| a.as_ref().map_or(String::new(), f);
            let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or(String::new(), f);
            let tm = r.timing.as_ref();
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{},{},{},{},{:.4},{:.4},{:.6},{},{},{:.6},{},{},{:.6},{},{:.6e},{:.6e},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                r.scene,
                r.format.datapath(),
                r.format.name(),
                r.format.bits(),
                r.k,
                r.b,
                r.st.rays,
                r.st.box_tests,
                r.st.box_tests * r.k as u64,
                r.st.pair_tests,
                r.st.pair_ideal,
                r.st.pair_decided,
                r.st.cycles_per_ray(),
                r.exact.cycles_per_ray(),
                r.extra_cycles(),
                r.st.tri_tests,
                r.exact.tri_tests,
                r.extra_tris(),
                r.st.false_box_hits,
                r.st.true_box_misses,
                r.st.false_hit_rate(),
                r.st.plane_culls,
                r.st.mean_looseness(),
                r.st.mean_looseness() / d,
                r.st.hits,
                r.modules.join("+"),
                cell(&|a| a.latency.to_string()),
                cell(&|a| a.ice40_lut4.to_string()),
                cell(&|a| a.ice40_depth.to_string()),
                cell(&|a| a.xilinx_lut.to_string()),
                cell(&|a| a.xilinx_dsp.to_string()),
                fa.contains(&i),
                fs.contains(&i),
                opt(tm.map(|t| t.fmax_mhz), &|v| format!("{v:.1}")),
                tm.map_or(String::new(), |t| t.lut4.to_string()),
                opt(r.rays_per_s(), &|v| format!("{v:.4e}")),
                opt(r.rays_per_s_per_klut4(), &|v| format!("{v:.4e}")),
                ft.contains(&i),
                mode_name(r.mode),
                r.st.entry_skips,
                ivs(r, &|c| Some(c.exact.box_tests)),
                ivs(r, &|c| Some(c.exact.tri_tests)),
                ivs(r, &|c| c.slab_entry.map(|s| s.box_tests)),
                ivs(r, &|c| c.slab_entry.map(|s| s.tri_tests)),
            );
            let front = [
                (fa.contains(&i), "accuracy"),
                (fs.contains(&i), "speed"),
                (ft.contains(&i), "rays/s per area"),
            ]
            .iter()
            .filter(|(on, _)| *on)
            .map(|(_, n)| *n)
            .collect::<Vec<_>>()
            .join(", ");
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {:.2} | {:+.2}% | {:+.2}% | {:.3}% | {:.2e} | {} | {} | {} | {} | {} | {} | {front} |",
                r.scene,
                r.format.name(),
                r.k,
                r.b,
                r.st.cycles_per_ray(),
                100.0 * r.extra_cycles(),
                100.0 * r.extra_tris(),
                100.0 * r.st.false_hit_rate(),
                r.st.mean_looseness() / d,
                cell(&|a| a.ice40_lut4.to_string()),
                cell(&|a| format!("{} + {}", a.xilinx_lut, a.xilinx_dsp)),
                cell(&|a| a.latency.to_string()),
                opt(tm.map(|t| t.fmax_mhz), &|v| format!("{v:.1}")),
                opt(r.rays_per_s(), &|v| format!("{:.2}", v / 1e6)),
                opt(r.rays_per_s_per_klut4(), &|v| format!("{:.2}", v / 1e6)),
            );
        }
        let pts = |f: &dyn Fn(&Rec) -> f64, front: &[usize]| -> Vec<Point> {
            with_area
                .iter()
                .map(|&i| Point {
                    x: cost(i),
                    y: f(rs[i]),
                    label: rs[i].label(),
                    group: format!("{} K{}", rs[i].format.datapath(), rs[i].k),
                    front: front.contains(&i),
                })
                .collect()
        };
        if !with_area.is_empty() {
            scatter_chart(
                &out.join(format!("sweep_{}_accuracy.svg", file_stem(scene))),
                &format!("{scene}: extra tester cycles against area (Pareto front joined)"),
                "area (iCE40 LUT4, log)",
                "extra tester cycles vs exact (%)",
                &pts(&|r| 100.0 * r.extra_cycles(), &fa),
            )?;
            scatter_chart(
                &out.join(format!("sweep_{}_speed.svg", file_stem(scene))),
                &format!("{scene}: tester cycles per ray against area (Pareto front joined)"),
                "area (iCE40 LUT4, log)",
                "tester cycles per ray",
                &pts(&|r| r.st.cycles_per_ray(), &fs),
            )?;
        }
        if !with_time.is_empty() {
            let tpts: Vec<Point> = with_time
                .iter()
                .map(|&i| Point {
                    x: per_area(i),
                    y: 100.0 * rs[i].extra_cycles(),
                    label: rs[i].label(),
                    group: format!("{} K{}", rs[i].format.datapath(), rs[i].k),
                    front: ft.contains(&i),
                })
                .collect();
            scatter_chart(
                &out.join(format!("sweep_{}_rays_per_area.svg", file_stem(scene))),
                &format!("{scene}: extra tester cycles against rays/s per 1,000 ECP5 LUT4 (Pareto front joined)"),
                "rays per second per 1,000 ECP5 LUT4 (one tester at its post-route Fmax, log)",
                "extra tester cycles vs exact (%)",
                &tpts,
            )?;
        }
    }
    crate::out_file::write_file(&out.join("sweep.csv"), &csv)?;
    md.push_str(&interval_table(recs));
    let missing = modules_without(recs, |r| r.area.is_none());
    if !missing.is_empty() {
        let _ = writeln!(
            md,
            "\nNo synthesis figures for (left out of the charts and fronts): {}. Synthesise them with \
             `scripts/synth <module>` and add the rows to the area table.",
            missing.join(", ")
        );
    }
    let untimed = modules_without(recs, |r| r.timing.is_none());
    if !untimed.is_empty() {
        let _ = writeln!(
            md,
            "\nNo post-route timing for (no rays per second): {}. Place and route them with \
             `scripts/timing <module>` and add the rows to the timing table.",
            untimed.join(", ")
        );
    }
    crate::out_file::write_file(&out.join("sweep.md"), &md)?;
    Ok(md)
}

/// A field of a record's [`IntervalCost`], empty when it has none.
fn ivs(r: &Rec, f: &dyn Fn(&IntervalCost) -> Option<u64>) -> String {
    r.iv.as_ref()
        .and_then(f)
        .map_or(String::new(), |v| v.to_string())
}

/// The markdown table of what each single-ray configuration's interval costs (records with an
/// [`IntervalCost`]): node and triangle tests beyond the same culls with exact intervals, and for planes
/// the tests their entry/exit update saves against the slab's own interval.
fn interval_table(recs: &[Rec]) -> String {
    let with: Vec<&Rec> = recs.iter().filter(|r| r.iv.is_some()).collect();
    if with.is_empty() {
        return String::new();
    }
    let pct = |a: u64, b: u64| format!("{:+.2}%", 100.0 * (a as f64 / b.max(1) as f64 - 1.0));
    let mut md = format!(
        "\n**What a loose interval costs** (single rays, mode {}): the format's node tests and triangle \
         tests beyond those of the same culls with the exact tester's intervals (the looseness of `t` \
         alone), and with planes the tests their entry/exit update saves against the format's slab \
         interval (the culls unchanged). Entry skips: a ray's visits of a node skipped because its entry \
         lies beyond the closest hit so far.\n\n\
         | scene | format | K | node tests | entry skips | extra node tests from looseness | extra triangle tests from looseness | node tests the planes' entry saves | triangle tests the planes' entry saves |\n\
         |---|---|---|---|---|---|---|---|---|\n",
        mode_name(with[0].mode)
    );
    for r in with {
        let c = r.iv.as_ref().expect("filtered");
        let saved = |f: fn(&SceneStats) -> u64| {
            c.slab_entry.map_or("—".to_string(), |s| {
                format!(
                    "{:.2}%",
                    100.0 * (1.0 - f(&r.st) as f64 / f(&s).max(1) as f64)
                )
            })
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.scene,
            r.format.name(),
            r.k,
            r.st.box_tests,
            r.st.entry_skips,
            pct(r.st.box_tests, c.exact.box_tests),
            pct(r.st.tri_tests, c.exact.tri_tests),
            saved(|s| s.box_tests),
            saved(|s| s.tri_tests),
        );
    }
    md
}

/// The module sets (`a+b`) of the records `lacks` picks, sorted, each once.
fn modules_without(recs: &[Rec], lacks: impl Fn(&Rec) -> bool) -> Vec<String> {
    let mut m: Vec<String> = recs
        .iter()
        .filter(|r| lacks(r))
        .map(|r| r.modules.join("+"))
        .collect();
    m.sort();
    m.dedup();
    m
}

/// A file-name-safe form of a scene name (an OBJ path's stem).
pub fn file_stem(scene: &str) -> String {
    Path::new(scene)
        .file_stem()
        .map_or_else(|| scene.to_string(), |s| s.to_string_lossy().into_owned())
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

/// `rtu sweep`.
pub fn run(a: &Args, out: &Path) -> Result<String, String> {
    let (recs, diag) = measure(a)?;
    report(&recs, out, &diag)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pareto_keeps_exactly_the_undominated_points() {
        let pts = [
            (1.0, 5.0),
            (2.0, 3.0),
            (3.0, 4.0),
            (4.0, 1.0),
            (2.0, 3.0),
            (5.0, 1.0),
        ];
        // (3,4) is dominated by (2,3); (5,1) by (4,1); the two equal (2,3) do not dominate each other.
        assert_eq!(pareto(&pts), vec![0, 1, 4, 3]);
    }

    #[test]
    fn area_table_rejects_bad_rows_and_later_rows_win() {
        let dir = std::env::temp_dir().join(format!("rtu-area-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("a.csv");
        let h = "module,latency,generic_cells,ice40_lut4,ice40_carry,ice40_ff,ice40_depth,xilinx_lut,xilinx_dsp";
        // Two runs concatenated, the second with its columns in another order and a byte-order mark.
        std::fs::write(
            &p,
            format!("\u{feff}{h}\nm,4,1,100,0,0,9,50,2\n\nmodule,ice40_lut4,latency,ice40_depth,xilinx_lut,xilinx_dsp\nm,120,5,9,60,2\n"),
        )
        .unwrap();
        let t = read_area(&p).unwrap();
        assert_eq!((t["m"].ice40_lut4, t["m"].latency), (120, 5));
        std::fs::write(
            &p,
            "latency,module,ice40_lut4,ice40_depth,xilinx_lut,xilinx_dsp\n3,q,1,2,3,4\n",
        )
        .unwrap();
        assert_eq!(read_area(&p).unwrap()["q"].latency, 3);
        for (text, want) in [
            (
                format!("{h}\nm,4,1,x,0,0,9,50,2\n"),
                "a.csv:2: column `ice40_lut4`: `x` is not a count",
            ),
            (
                "m,4,1,1,0,0,9,50,2\n".to_string(),
                "a.csv:1: column `m`: unknown field",
            ),
            (
                format!("{h},lut\nm,4,1,1,0,0,9,50,2,3\n"),
                "a.csv:1: column `lut`: unknown field",
            ),
            (
                format!("{h},latency\n"),
                "a.csv:1: column `latency` named twice",
            ),
            (
                "module,latency,ice40_lut4\n".to_string(),
                "a.csv:1: column `ice40_depth` missing",
            ),
            (
                format!("{h}\nm,4,1,1,0,0,9,50\n"),
                "a.csv:2: 8 cells, but the header has 9",
            ),
        ] {
            std::fs::write(&p, &text).unwrap();
            let e = read_area(&p).unwrap_err();
            assert!(e.contains(want), "{text}: {e}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn timing_table_rejects_bad_rows_and_later_rows_win() {
        let dir = std::env::temp_dir().join(format!("rtu-timing-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("t.csv");
        let h = "module,latency,device,lut4,ff,mult18,fmax_mhz,crit_from,crit_to,seed";
        std::fs::write(
            &p,
            format!("\u{feff}{h}\nm,4,D,453,422,6,97.8,a,b,1\n\nm,6,D,493,766,6,145.6,a,b,1\nq,9,D,10,1,0,5,a,b,1\n"),
        )
        .unwrap();
        let t = read_timing(&p).unwrap();
        assert_eq!(
            t["m"],
            Timing {
                fmax_mhz: 145.6,
                lut4: 493,
                ff: Some(766),
                mult18: Some(6),
            }
        );
        assert_eq!(t["q"].fmax_mhz, 5.0);
        for (text, want) in [
            (String::new(), "t.csv: empty timing table"),
            (
                "module,lut4\n".to_string(),
                "t.csv:1: column `fmax_mhz` missing",
            ),
            (
                format!("{h}\nm,4,D,x,422,6,97.8,a,b,1\n"),
                "t.csv:2: column `lut4`: `x` is not a count",
            ),
            (
                format!("{h}\nm,4,D,1,422,6,NaN,a,b,1\n"),
                "t.csv:2: column `fmax_mhz`: `NaN` is not a positive frequency",
            ),
            (
                format!("{h}\nm,4,D,1,422,6,0,a,b,1\n"),
                "t.csv:2: column `fmax_mhz`: `0` is not a positive frequency",
            ),
            (
                format!("{h}\n\nm,4,D,1,422,6,9,a,b\n"),
                "t.csv:3: 9 cells, but the header has 10",
            ),
        ] {
            std::fs::write(&p, &text).unwrap();
            let e = read_timing(&p).unwrap_err();
            assert!(e.contains(want), "{text}: {e}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
