//! `rtu trace`: per-ray results of one configuration on one scene, as CSV, so that a user can compare
//! them with another renderer on the same OBJ. Each ray set (primary, bounce, shadow) runs through the
//! sweeps' traversal model ([`golden::scene::sweep`]) on the format's tester, in the set's mode; every
//! closest hit (or any-hit verdict) is checked against brute force before a row is written.

use crate::sweep_cmd::{
    bundles, load_scene, mode_name, parse_mode, tester, Format, Prepared, RunCfg,
};
use golden::bundle::traverse::BundlePath;
use golden::format::fixed::FixFormat;
use golden::format::float::FloatFormat;
use golden::scene::sweep::{traverse_rays, ExactTester, Machine, Mode, RaySet};
use golden::scene::traverse::NodeTester;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `rtu trace`.
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// The scene: a built-in name (room, grass, mesh, soup) or an OBJ file (`*.obj`).
    #[arg(long, default_value = "room")]
    pub scene: String,
    /// The tester: `exact`, a fixed format (b8, b12, b16, or G,I,FI,T,FT separated by `/`) or a float
    /// format (fp32, bf16, fp16, eXmY).
    #[arg(long, default_value = "b12")]
    pub format: String,
    /// Planes per node (0 = the slab tester alone, up to 8).
    #[arg(long, default_value_t = 0)]
    pub k: usize,
    /// Rays per bundle (1, 4, 16 or 64).
    #[arg(long, default_value_t = 1)]
    pub bundle: usize,
    /// Ray sets, comma-separated: primary, bounce, shadow.
    #[arg(long, default_value = "primary,bounce,shadow")]
    pub sets: String,
    /// Traversal mode: `default` (closest hit for primary and bounce rays, any hit for shadow rays),
    /// `closest`, `any` or `all`.
    #[arg(long, default_value = "default")]
    pub mode: String,
    /// Image width and height of the primary rays.
    #[arg(long, default_value_t = 32)]
    pub width: usize,
    #[arg(long, default_value_t = 24)]
    pub height: usize,
    /// Secondary-ray origin offset, as a fraction of the scene's diagonal (see `rtu sweep --help`).
    #[arg(long, default_value_t = 1e-5)]
    pub offset: f64,
    /// Seed of the scene and the secondary rays.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// The CSV written; default <out>/trace/<scene>_<format>_k<K>_b<B>.csv.
    #[arg(long)]
    pub csv: Option<PathBuf>,
}

/// The columns of the CSV, one row per ray.
pub const CSV_HEADER: &str = "set,ray,mode,ox,oy,oz,dx,dy,dz,t_min,t_max,hit,tri,obj_line,t,t_entry,ref_tri,ref_t,node_tests,pair_tests,tri_tests";

/// `exact` (`None`) or a format of the sweep.
fn parse_format(s: &str) -> Result<Option<Format>, String> {
    if s == "exact" {
        return Ok(None);
    }
    if let Ok(f) = FixFormat::parse(&s.replace('/', ",")) {
        return Ok(Some(Format::Fix(f)));
    }
    FloatFormat::parse(s)
        .map(|f| Some(Format::Float(f)))
        .map_err(|_| {
            format!("--format `{s}`: expected exact, a fixed format (b8, b12, b16, G/I/FI/T/FT) or a float format (fp32, bf16, fp16, eXmY)")
        })
}

/// `rtu trace`: writes the CSV and returns a summary.
pub fn run(a: &Args, out: &Path) -> Result<String, String> {
    let fmt = parse_format(&a.format)?;
    let mode = parse_mode(&a.mode)?;
    if a.k > golden::plane::fix::MAX_PLANES {
        return Err(format!(
            "--k {}: the testers take 0 to 8 planes per node",
            a.k
        ));
    }
    if !matches!(a.bundle, 1 | 4 | 16 | 64) {
        return Err(format!(
            "--bundle {}: bundle sizes are 1, 4, 16 or 64 (square tiles)",
            a.bundle
        ));
    }
    if a.width == 0 || a.height == 0 {
        return Err("--width and --height must be at least 1".into());
    }
    let sets = crate::opts::list(&a.sets, |s| Ok(s.to_string()))?;
    let sc = load_scene(&a.scene, a.seed)?;
    let p = Prepared::new(&sc, a.width, a.height, a.seed, &sets, a.offset)?;
    let planes = if a.k > 0 {
        golden::plane::generate::generate(&p.bvh, &sc.tris, a.k).map_err(|e| e.to_string())?
    } else {
        vec![]
    };
    let (mut t, pair): (Box<dyn NodeTester + '_>, Option<BundlePath>) = match &fmt {
        Some(f) => tester(&p, f, &planes, a.k)?,
        None => (
            Box::new(ExactTester::new(&p.bvh, &planes, a.k)),
            Some(BundlePath::Exact),
        ),
    };
    let fname = fmt.as_ref().map_or("exact".to_string(), |f| f.name());
    if a.bundle > 1 && pair.is_none() {
        return Err(format!("{fname}: no bundle pair for this format"));
    }
    let c = RunCfg {
        k: a.k,
        b: a.bundle,
        w: a.width,
        h: a.height,
        mode,
    };
    let mut csv = format!("{CSV_HEADER}\n");
    let mut summary = String::from(
        "| set | mode | rays | hits | node tests | pair tests | triangle tests |\n|---|---|---|---|---|---|---|\n",
    );
    for (name, rays) in &p.sets {
        let mut set = RaySet::new(&p.bvh, &sc.tris, rays);
        let built = bundles(name, rays, c.b, c.w, c.h, p.diag)?;
        let m_mode = c.mode.unwrap_or_else(|| Mode::default_for(name));
        let mut m = Machine {
            tester: t.as_mut(),
            planes: c.k,
            pair: if c.b > 1 { pair.as_ref() } else { None },
            rebound: true,
            mode: m_mode,
        };
        let (st, per) = traverse_rays(&p.bvh, &sc.tris, &mut set, &built, &mut m, || {})
            .map_err(|e| format!("{fname} K{} B{}: {name} rays: {e}", c.k, c.b))?;
        for (i, (r, res)) in rays.iter().zip(&per).enumerate() {
            let tri = |h: &Option<golden::scene::traverse::Hit>| {
                h.as_ref().map_or(String::new(), |h| h.0.to_string())
            };
            let t_of = |h: &Option<golden::scene::traverse::Hit>| {
                h.as_ref().map_or(String::new(), |h| {
                    golden::exact::round_down(&h.1).to_string()
                })
            };
            let line = res
                .hit
                .as_ref()
                .and_then(|h| sc.face_lines.get(h.0))
                .map_or(String::new(), |l| l.to_string());
            let _ = writeln!(
                csv,
                "{name},{i},{},{},{},{},{},{},{},{},{},{},{},{line},{},{},{},{},{},{},{}",
                m_mode.name(),
                r.origin.x,
                r.origin.y,
                r.origin.z,
                r.dir.x,
                r.dir.y,
                r.dir.z,
                r.t_min,
                r.t_max,
                res.hit.is_some(),
                tri(&res.hit),
                t_of(&res.hit),
                res.hit_entry.map_or(String::new(), |e| e.to_string()),
                tri(&set.closest[i]),
                t_of(&set.closest[i]),
                res.node_tests,
                res.pair_tests,
                res.tri_tests,
            );
        }
        let _ = writeln!(
            summary,
            "| {name} | {} | {} | {} | {} | {} | {} |",
            m_mode.name(),
            st.rays,
            st.hits,
            st.box_tests,
            st.pair_tests,
            st.tri_tests
        );
    }
    let path = a.csv.clone().unwrap_or_else(|| {
        out.join("trace").join(format!(
            "{}_{fname}_k{}_b{}.csv",
            crate::sweep_cmd::file_stem(&a.scene),
            a.k,
            a.bundle
        ))
    });
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    crate::out_file::write_file(&path, &csv)?;
    Ok(format!(
        "{} ({} triangles), {fname}, K {}, B {}, mode {}: every hit checked against brute force\n\n{summary}\nwrote {}\n",
        sc.name,
        sc.tris.len(),
        c.k,
        c.b,
        mode_name(mode),
        path.display()
    ))
}
