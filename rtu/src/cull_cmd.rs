//! `rtu cull-campaign` and `rtu cull-scenes`: the cull-plane tester's conservativeness campaign against
//! the exact clip and the exact triangle test, and the triangle tests it saves on scenes.

use crate::opts::{fix_formats, float_formats, list, parse_k};
use golden::format::fixed::{FixFormat, GridMap};
use golden::geom::Ray;
use golden::plane::fix::CullFixFormat;
use golden::plane::float::CullFloatFormat;
use golden::scene::bvh::Bvh;
use golden::scene::sweep::{FixTester, FloatTester};
use golden::scene::traverse::{trace, AabbOnly, NodeTester};
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;
use std::path::Path;
use tb::plane::fix::{cull_fix_campaign, cull_float_campaign, CullFixCtx, CullStats};

fn bar(n: u64, msg: String) -> ProgressBar {
    let pb = ProgressBar::new(n);
    pb.set_style(
        ProgressStyle::with_template("{msg:28} {bar:30} {pos}/{len} {per_sec} eta {eta}")
            .expect("template"),
    );
    pb.set_message(msg);
    pb
}

/// Runs `n` cases (half uniform, half adversarial, on two threads) per configuration and prints a table;
/// returns an error at the first violation.
pub fn campaign(
    n: u64,
    ks: &[usize],
    fixed: &[FixFormat],
    floats: &[golden::format::float::FloatFormat],
    seed: u64,
) -> Result<String, String> {
    let mut table = String::from("| datapath | format | K | vectors | exact culls | culled | culled by exact fractions | triangle hits | violations |\n|---|---|---|---|---|---|---|---|---|\n");
    for &k in ks {
        for fmt in fixed {
            let ctx = CullFixCtx {
                cf: CullFixFormat::over(*fmt),
                k,
            };
            let pb = bar(n, format!("fixed {} k{k}", fmt.name()));
            let st = two_halves(n, seed + k as u64, |s, m, adv| {
                cull_fix_campaign(ctx, s, m, adv, |_| pb.inc(65536))
            })?;
            pb.finish_and_clear();
            row(&mut table, "fixed", &ctx.cf.name(), k, &st);
        }
        for f in floats {
            let cf = CullFloatFormat::over(*f);
            let pb = bar(n, format!("float {} k{k}", f.name()));
            let st = two_halves(n, seed + 100 + k as u64, |s, m, adv| {
                cull_float_campaign(cf, k, s, m, adv, |_| pb.inc(65536))
            })?;
            pb.finish_and_clear();
            row(&mut table, "float", &cf.name(), k, &st);
        }
    }
    Ok(table)
}

/// Half the cases uniform and half adversarial, one half per thread.
fn two_halves(
    n: u64,
    seed: u64,
    run: impl Fn(u64, u64, f64) -> Result<CullStats, String> + Sync,
) -> Result<CullStats, String> {
    let (a, b) = std::thread::scope(|s| {
        let h = s.spawn(|| run(seed, n / 2, 0.0));
        let b = run(seed ^ 0xadd, n - n / 2, 1.0);
        (h.join().expect("campaign thread"), b)
    });
    let mut st = a?;
    st.add(&b?);
    Ok(st)
}

fn row(t: &mut String, dp: &str, name: &str, k: usize, st: &CullStats) {
    let _ = writeln!(
        t,
        "| {dp} | {name} | {k} | {} | {} | {} | {} | {} | {} |",
        st.vectors,
        st.exact_culled,
        st.culled,
        if dp == "fixed" {
            st.culled_fractions.to_string()
        } else {
            "-".into()
        },
        st.tri_hits,
        st.violations
    );
}

/// A node tester with a conservativeness check on scenes: every node that `inner` culls although the
/// exact slab test keeps it (a cull by the planes) is checked exactly — no triangle of its subtree is hit
/// by the ray within its current `[t_min, t_max]` ([`golden::scene::tri::tri_hit`]).
struct Checked<'a, T> {
    inner: T,
    bvh: &'a Bvh,
    tris: &'a [golden::scene::tri::Triangle],
    /// Plane culls checked.
    checked: u64,
    /// Plane culls of a node whose triangle the ray hits: correctness bugs.
    violations: u64,
}

impl<'a, T> Checked<'a, T> {
    fn new(inner: T, bvh: &'a Bvh, tris: &'a [golden::scene::tri::Triangle]) -> Self {
        Checked {
            inner,
            bvh,
            tris,
            checked: 0,
            violations: 0,
        }
    }
}

impl<T: NodeTester> NodeTester for Checked<'_, T> {
    fn test(&mut self, ray: &Ray, node: usize) -> Option<(f64, f64)> {
        let r = self.inner.test(ray, node);
        if r.is_none() && golden::exact::slab_exact(ray, &self.bvh.nodes[node].bounds).hit {
            self.checked += 1;
            let hit = self
                .bvh
                .subtree_tris(node)
                .iter()
                .any(|&t| golden::scene::tri::tri_hit(ray, &self.tris[t]).is_some());
            self.violations += u64::from(hit);
        }
        r
    }
}

/// Which planes a traversal uses: none (the format's own AABB-only tester), each node's own normals, or
/// normals shared by siblings (claim 8).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Normals {
    None,
    Own,
    Shared,
}

impl Normals {
    fn name(self) -> &'static str {
        match self {
            Normals::None => "-",
            Normals::Own => "own",
            Normals::Shared => "shared",
        }
    }
}

/// Triangle tests with `K` planes per node, per scene, format, K and normal layout (own, or shared by the
/// two children of a node), on primary rays (`w x h`) and one bounce ray per primary hit, against two
/// baselines: AABB-only traversal in exact arithmetic, and the same format's tester with no planes
/// (`K = 0`), which isolates what the planes save from what quantising the boxes costs. Every closest hit
/// is compared with the exact AABB-only traversal's. Also the bytes per node of each layout
/// ([`golden::plane::clip::NodeLayout`]; shared: binary tree, two siblings). Every cull by the planes is checked
/// against the exact ray-triangle test of the node's triangles ([`Checked`]); one that hides a hit is an
/// error. Writes `<out>/cull_scenes.csv` and returns a markdown table.
pub fn scenes(
    names: &[String],
    ks: &[usize],
    fixed: &[FixFormat],
    floats: &[golden::format::float::FloatFormat],
    w: usize,
    h: usize,
    out: &Path,
) -> Result<String, String> {
    let mut csv = String::from("scene,rays,datapath,format,k,normals,node_bytes,tri_tests,same_format_k0_tri_tests,exact_aabb_tri_tests,saved_vs_k0,saved_vs_exact_aabb,node_tests,closest_hit_mismatches\n");
    // Per traversal: (plane culls checked, plane culls of a hit node, which run).
    let mut check: Vec<(u64, u64, String)> = vec![];
    let mut table = String::from("| scene | rays | datapath | format | K | normals | bytes/node | triangle tests | saved vs same format K=0 | saved vs exact AABB | closest hits differing |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for name in names {
        let sc = crate::sweep_cmd::load_scene(name, 1)?;
        let bvh = Bvh::build(&sc.tris, 4).map_err(|e| e.to_string())?;
        let prim = golden::scene::tri_scene::primary_rays(&sc, w, h);
        let (hits0, _) = trace(&bvh, &sc.tris, &prim, &mut AabbOnly::new(&bvh));
        let sec = golden::scene::tri_scene::secondary_rays(&sc, &prim, &hits0, 2);
        let (lo, hi) = sc.grid_bounds();
        // Per K: (normals, planes of every node).
        let mut plane_sets = vec![];
        for &k in ks {
            for (nm, gen) in [
                (
                    Normals::Own,
                    golden::plane::generate::generate as fn(_, _, _) -> _,
                ),
                (Normals::Shared, golden::plane::generate::generate_shared),
            ] {
                plane_sets.push((k, nm, gen(&bvh, &sc.tris, k).map_err(|e| e.to_string())?));
            }
        }
        let none: Vec<Vec<golden::plane::clip::Plane>> = vec![vec![]; bvh.nodes.len()];
        let configs: Vec<(usize, Normals, &Vec<Vec<golden::plane::clip::Plane>>)> =
            std::iter::once((0, Normals::None, &none))
                .chain(plane_sets.iter().map(|(k, nm, p)| (*k, *nm, p)))
                .collect();
        for (set, rays) in [("primary", &prim), ("bounce", &sec.bounce)] {
            let (base_hits, base) = trace(&bvh, &sc.tris, rays, &mut AabbOnly::new(&bvh));
            let mut emit = |dp: &str,
                            fname: String,
                            k: usize,
                            nm: Normals,
                            bytes: f64,
                            k0: u64,
                            (hits, st): (
                Vec<Option<golden::scene::traverse::Hit>>,
                golden::scene::traverse::TraversalStats,
            )| {
                let diff = hits.iter().zip(&base_hits).filter(|(a, b)| a != b).count();
                let saved = |b: u64| 1.0 - st.tri_tests as f64 / b.max(1) as f64;
                let _ = writeln!(
                    csv,
                    "{name},{set},{dp},{fname},{k},{},{bytes},{},{k0},{},{:.4},{:.4},{},{diff}",
                    nm.name(),
                    st.tri_tests,
                    base.tri_tests,
                    saved(k0),
                    saved(base.tri_tests),
                    st.node_tests
                );
                let _ = writeln!(
                    table,
                    "| {name} | {set} | {dp} | {fname} | {k} | {} | {bytes} | {} | {:.1}% | {:.1}% | {diff} |",
                    nm.name(),
                    st.tri_tests,
                    100.0 * saved(k0),
                    100.0 * saved(base.tri_tests)
                );
            };
            let bytes = |l: golden::plane::clip::NodeLayout, k: usize, nm: Normals| match nm {
                Normals::Shared => l.shared_bytes(k as u32, 2),
                _ => f64::from(l.own_bytes(k as u32)),
            };
            for fmt in fixed {
                let cf = CullFixFormat::over(*fmt);
                let map = GridMap::for_bounds(*fmt, lo, hi).map_err(|e| e.to_string())?;
                let mut k0 = 0;
                for &(k, nm, planes) in &configs {
                    let tester = FixTester::new(cf, map.clone(), &bvh, &sc.tris, planes, k)
                        .map_err(|e| e.to_string())?;
                    let mut t = Checked::new(tester, &bvh, &sc.tris);
                    let run = trace(&bvh, &sc.tris, rays, &mut t);
                    check.push((
                        t.checked,
                        t.violations,
                        format!("{name} {set} {} k{k}", fmt.name()),
                    ));
                    if k == 0 {
                        k0 = run.1.tri_tests;
                    }
                    emit(
                        "fixed",
                        fmt.name(),
                        k,
                        nm,
                        bytes(cf.layout(), k, nm),
                        k0,
                        run,
                    );
                }
            }
            for f in floats {
                let cf = CullFloatFormat::over(*f);
                let mut k0 = 0;
                for &(k, nm, planes) in &configs {
                    let tester = FloatTester::new(cf, &bvh, &sc.tris, planes, k)
                        .map_err(|e| e.to_string())?;
                    let mut t = Checked::new(tester, &bvh, &sc.tris);
                    let run = trace(&bvh, &sc.tris, rays, &mut t);
                    check.push((
                        t.checked,
                        t.violations,
                        format!("{name} {set} {} k{k}", f.name()),
                    ));
                    if k == 0 {
                        k0 = run.1.tri_tests;
                    }
                    emit("float", f.name(), k, nm, bytes(cf.layout(), k, nm), k0, run);
                }
            }
        }
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join("cull_scenes.csv"), csv)?;
    let checked: u64 = check.iter().map(|c| c.0).sum();
    if let Some((_, v, which)) = check.iter().find(|c| c.1 > 0) {
        return Err(format!(
            "{which}: {v} plane culls of a node whose triangle the ray hits (a correctness bug)"
        ));
    }
    let _ = writeln!(
        table,
        "\n{checked} plane culls (nodes the planes culled although the exact slab test kept them) checked \
         against the exact ray-triangle test on every triangle below them: none hides a hit."
    );
    Ok(table)
}

/// Options of `rtu cull-campaign`.
#[derive(clap::Args, Clone, Debug)]
pub struct CampaignArgs {
    /// Cases per datapath, format and K (half uniform, half adversarial).
    #[arg(long, default_value_t = 1_000_000)]
    pub vectors: u64,
    /// Planes per node, comma separated.
    #[arg(long, default_value = "4")]
    pub k: String,
    /// Fixed formats (b8, b12, b16), comma separated; empty for none.
    #[arg(long, default_value = "b8,b12,b16")]
    pub fixed: String,
    /// Float formats (fp32, bf16, fp16, eXmY), comma separated; empty for none.
    #[arg(long, default_value = "fp32,bf16,fp16")]
    pub float: String,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// `rtu cull-campaign`: [`campaign`] over the options' planes and formats; prints the table and writes
/// it to `out/cull_campaign.md`.
pub fn campaign_cmd(a: &CampaignArgs, out: &Path) -> Result<(), String> {
    let ks = list(&a.k, parse_k)?;
    let (fx, fl) = (fix_formats(&a.fixed)?, float_formats(&a.float)?);
    let t = campaign(a.vectors, &ks, &fx, &fl, a.seed)?;
    print!("{t}");
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    crate::out_file::write_file(&out.join("cull_campaign.md"), t)
}

/// Options of `rtu cull-scenes`.
#[derive(clap::Args, Clone, Debug)]
pub struct ScenesArgs {
    /// Scenes, comma-separated: built-in names (grass, room, mesh, soup) or OBJ files (`*.obj`).
    #[arg(long, default_value = "grass,room,mesh")]
    pub scenes: String,
    #[arg(long, default_value = "1,2,4,8")]
    pub k: String,
    #[arg(long, default_value = "b12,b16")]
    pub fixed: String,
    #[arg(long, default_value = "bf16,fp16,fp32")]
    pub float: String,
    #[arg(long, default_value_t = 64)]
    pub width: usize,
    #[arg(long, default_value_t = 48)]
    pub height: usize,
}

/// `rtu cull-scenes`: [`scenes`] over the options; prints the table and writes it to
/// `out/cull_scenes.md`.
pub fn scenes_cmd(a: &ScenesArgs, out: &Path) -> Result<(), String> {
    let ks = list(&a.k, parse_k)?;
    let (fx, fl) = (fix_formats(&a.fixed)?, float_formats(&a.float)?);
    let names = list(&a.scenes, |s| Ok(s.to_string()))?;
    let t = scenes(&names, &ks, &fx, &fl, a.width, a.height, out)?;
    print!("{t}");
    crate::out_file::write_file(&out.join("cull_scenes.md"), t)
}
