//! `rtu encode` and `rtu decode`: world-space vectors (the files of `rtu run`) as the words on an
//! exported core's ports, and the words a simulation captured back as world-space results.
//!
//! `encode` writes three files beside a prefix: `<prefix>.in.hex` (one line per test: a hex word per
//! input port, the columns named by a `// ports:` line; `tb::ip::words`), `<prefix>.out.hex` (the
//! results the bit-accurate model predicts, as output words, in the same form) and `<prefix>.mem` (the
//! input words packed into one word per test for `$readmemh`). Test `n` carries the tag `n mod 2^16`.
//! `decode` reads captured output words (the `.out.hex` form) with the same vector file and writes the
//! results exactly as `rtu run` writes them, so `decode(simulate(encode(v)))` can be compared with
//! `rtu run` byte for byte.

use crate::out_file::{write_file, Output};
use crate::run_vectors::{file_bounds, parse_bounds, slurp, vectors_of};
use golden::format::fixed::GridMap;
use golden::slab::float::{quantize_box, quantize_ray};
use golden::slab::vectors::{write_header, write_result, VecFormat, Vector};
use rtl::export::{Exported, Family};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use tb::ip::words;
use tb::plane::fix::{fix_vector, CullFixCtx};
use tb::plane::float::{float_vector, CullFloatCtx};
use tb::slab::ports::SlabCtx;
use tb::verilator::{parse_ports, Port};

/// Options of `rtu encode`.
#[derive(clap::Args)]
pub struct EncodeArgs {
    /// The exported module, e.g. slab_fix_g12_i16f11_t20f6 (`rtu export` lists them).
    #[arg(long)]
    pub module: String,
    /// Vectors in world space, as `rtu run` reads them (`.csv` is CSV, anything else JSON lines).
    pub input: PathBuf,
    /// Prefix of the files written: <prefix>.in.hex, <prefix>.out.hex, <prefix>.mem (default
    /// <out>/encode/<module>).
    #[arg(long, short)]
    pub output: Option<PathBuf>,
    /// Fixed formats: scene bounds `x0,y0,z0,x1,y1,z1` for the grid; by default the bounds of the
    /// file's origins and boxes (as `rtu run`).
    #[arg(long)]
    pub bounds: Option<String>,
}

/// Options of `rtu decode`.
#[derive(clap::Args)]
pub struct DecodeArgs {
    /// The exported module the words were captured from.
    #[arg(long)]
    pub module: String,
    /// The vector file the words were encoded from (needed to turn t codes into world units).
    #[arg(long)]
    pub vectors: PathBuf,
    /// Captured output words: a `// ports:` line naming the columns, then one line per result in the
    /// order the results left (the form of <prefix>.out.hex).
    pub captured: PathBuf,
    /// Where to write the results (in the vector file's format, as `rtu run`); stdout when absent.
    #[arg(long, short)]
    pub output: Option<PathBuf>,
    /// The bounds given to `rtu encode`, if any.
    #[arg(long)]
    pub bounds: Option<String>,
}

/// A module's catalogue entry and ports, or an error naming the module.
fn module(name: &str) -> Result<(Exported, Vec<Port>), String> {
    let e = rtl::export::find(name)?;
    encodable(&e)?;
    let ports = parse_ports(&e.verilog(), name)?;
    Ok((e, ports))
}

/// Whether the encoder takes a module: the pipelined testers (the results processor takes jobs over
/// several clocks) of the slab and cull-plane families.
fn encodable(e: &Exported) -> Result<(), String> {
    let name = &e.module;
    if !e.pipelined() {
        return Err(format!(
            "module `{name}`: the results processor takes a job over several clocks (rays written to \
             its store, then `start`); encode drives pipelined testers one test a clock. Drive it \
             from its datasheet's job protocol, or use `rtu run --bundles`"
        ));
    }
    if matches!(e.family, Family::PlaneFrac { .. }) {
        return Err(format!(
            "module `{name}`: the fraction option reports its interval as exact quotients \
             (`num`, `den`, ...), not as t codes; encode and decode take the table option \
             (plane_fix_..._r8_k*) and the other slab and cull-plane testers"
        ));
    }
    if matches!(
        e.family,
        Family::BundleFix { .. } | Family::BundleFloat { .. }
    ) {
        return Err(format!(
            "module `{name}`: encode and decode take the slab and cull-plane testers; the bundle \
             pair's words are not encoded yet"
        ));
    }
    Ok(())
}

/// The vectors of a file, each with its line, in order.
fn read_vectors(input: &Path) -> Result<(Vec<(usize, Vector)>, Arc<Vec<u8>>, VecFormat), String> {
    let vfmt = VecFormat::from_path(input);
    let bytes = Arc::new(slurp(input)?);
    let vs = vectors_of(bytes.clone(), vfmt, input.display().to_string())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())?;
    if vs.is_empty() {
        return Err(format!("{}: no vectors", input.display()));
    }
    Ok((vs, bytes, vfmt))
}

/// What one module needs of its vectors: the grid (fixed formats) and the planes per node.
struct Setup {
    e: Exported,
    ports: Vec<Port>,
    vs: Vec<(usize, Vector)>,
    vfmt: VecFormat,
    map: Option<GridMap>,
    src: String,
}

fn setup(name: &str, input: &Path, bounds: Option<&str>) -> Result<Setup, String> {
    let (e, ports) = module(name)?;
    let (vs, bytes, vfmt) = read_vectors(input)?;
    let src = input.display().to_string();
    let grid = match bounds {
        Some(b) => parse_bounds(b)?,
        None => file_bounds(bytes, vfmt, &src)?,
    };
    setup_from(e, ports, vs, vfmt, grid, src)
}

/// A setup of vectors already read; `grid` the scene bounds for a fixed format's grid map.
fn setup_from(
    e: Exported,
    ports: Vec<Port>,
    vs: Vec<(usize, Vector)>,
    vfmt: VecFormat,
    (lo, hi): (glam::DVec3, glam::DVec3),
    src: String,
) -> Result<Setup, String> {
    let name = e.module.clone();
    let base = match e.family {
        Family::SlabFix { fmt, .. } => Some(fmt),
        Family::PlaneFix { cf, .. } | Family::PlaneFrac { cf, .. } => Some(cf.base),
        _ => None,
    };
    let map = match base {
        Some(fmt) => Some(GridMap::for_bounds(fmt, lo, hi).map_err(|e| e.to_string())?),
        None => None,
    };
    let k = match e.family {
        Family::PlaneFix { k, .. } | Family::PlaneFrac { k, .. } | Family::PlaneFloat { k, .. } => {
            k
        }
        _ => 0,
    };
    for (line, v) in &vs {
        if v.planes.len() > k {
            return Err(format!(
                "{src}:{line}: vector with tag {}: {} planes, but module `{name}` tests {k}",
                v.tag,
                v.planes.len()
            ));
        }
    }
    Ok(Setup {
        e,
        ports,
        vs,
        vfmt,
        map,
        src,
    })
}

/// Runs `f` with the module's testbench context and its quantiser of one vector.
macro_rules! with_ctx {
    ($s:expr, |$ctx:ident, $q:ident| $body:expr) => {{
        let s: &Setup = $s;
        match s.e.family {
            Family::SlabFix { fmt, .. } => {
                let map = s.map.expect("a grid for a fixed format");
                let $ctx = fmt;
                let $q = |v: &Vector| -> Result<_, golden::Error> {
                    Ok((map.quantize_ray(&v.ray)?, map.quantize_box(&v.bx)?))
                };
                $body
            }
            Family::SlabFloat { f, .. } => {
                let $ctx = f;
                let $q = |v: &Vector| -> Result<_, golden::Error> {
                    Ok((quantize_ray(&f, &v.ray)?, quantize_box(&f, &v.bx)?))
                };
                $body
            }
            Family::PlaneFix { cf, k, .. } | Family::PlaneFrac { cf, k } => {
                let map = s.map.expect("a grid for a fixed format");
                let $ctx = CullFixCtx { cf, k };
                let $q = |v: &Vector| fix_vector(&cf, &map, v);
                $body
            }
            Family::PlaneFloat { cf, k } => {
                let $ctx = CullFloatCtx::new(cf, k);
                let $q = |v: &Vector| float_vector(&cf, v);
                $body
            }
            _ => unreachable!("refused by module()"),
        }
    }};
}

/// The quantised tests of a setup, each error naming the file, line and tag.
fn quantise<R, B>(
    s: &Setup,
    q: impl Fn(&Vector) -> Result<(R, B), golden::Error>,
) -> Result<Vec<(R, B)>, String> {
    s.vs.iter()
        .map(|(line, v)| {
            q(v).map_err(|e| format!("{}:{line}: vector with tag {}: {e}", s.src, v.tag))
        })
        .collect()
}

/// Comment lines that say what a word file holds and how the vectors were mapped.
fn head(s: &Setup, what: &str) -> Vec<String> {
    let mut h = vec![format!(
        "rtu encode: {what} of module {}, latency {} clocks, {} tests from {}",
        s.e.module,
        s.e.latency,
        s.vs.len(),
        s.src
    )];
    if let Some(m) = &s.map {
        h.push(format!(
            "grid: q = x / 2^{} - c, c = ({}, {}, {}) (the datasheet's grid map)",
            m.k, m.c[0], m.c[1], m.c[2]
        ));
    }
    h.push("test n carries tag_in = n mod 65536; results leave in order".into());
    h
}

/// `rtu encode`: writes the three word files and returns a summary line.
pub fn encode(a: &EncodeArgs, out: &Path) -> Result<String, String> {
    let s = setup(&a.module, &a.input, a.bounds.as_deref())?;
    let ins = words::columns(&s.ports, true);
    let outs = words::columns(&s.ports, false);
    let (rows_in, rows_out) = with_ctx!(&s, |ctx, q| {
        let tests = quantise(&s, q)?;
        let mut ri = Vec::with_capacity(tests.len());
        let mut ro = Vec::with_capacity(tests.len());
        for (n, (r, b)) in tests.iter().enumerate() {
            let tag = tb::ip::seq_tag(n);
            ri.push(tb::ip::slab_in_row(&ctx, &ins, tag, r, b)?);
            ro.push(tb::ip::slab_out_row(&ctx, &outs, tag, &ctx.model(r, b))?);
        }
        (ri, ro)
    });
    let prefix = a
        .output
        .clone()
        .unwrap_or_else(|| out.join("encode").join(&s.e.module));
    if let Some(d) = prefix.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(d).map_err(|e| format!("{}: {e}", d.display()))?;
    }
    let file = |ext: &str| PathBuf::from(format!("{}.{ext}", prefix.display()));
    write_file(
        &file("in.hex"),
        words::write(&head(&s, "input words"), &ins, &rows_in),
    )?;
    write_file(
        &file("out.hex"),
        words::write(&head(&s, "the model's output words"), &outs, &rows_out),
    )?;
    write_file(
        &file("mem"),
        words::readmemh(&head(&s, "packed input words"), &ins, &rows_in),
    )?;
    Ok(format!(
        "rtu encode: {} tests for {} -> {}.{{in.hex,out.hex,mem}}",
        rows_in.len(),
        s.e.module,
        prefix.display()
    ))
}

/// `rtu decode`: the captured words as world-space results, written as `rtu run` writes them.
pub fn decode(a: &DecodeArgs) -> Result<(), String> {
    let s = setup(&a.module, &a.vectors, a.bounds.as_deref())?;
    let outs = words::columns(&s.ports, false);
    let csrc = a.captured.display().to_string();
    let text = std::fs::read_to_string(&a.captured).map_err(|e| format!("{csrc}: {e}"))?;
    let rows = words::read(&text, &csrc, &s.ports, &outs)?;
    if rows.len() != s.vs.len() {
        return Err(format!(
            "{csrc}: {} results, but {} has {} vectors",
            rows.len(),
            s.src,
            s.vs.len()
        ));
    }
    let mut w = Output::open(a.output.as_deref())?;
    let mut header = vec![];
    write_header(&mut header, s.vfmt).map_err(|e| e.to_string())?;
    w.set_header(header);
    with_ctx!(&s, |ctx, q| {
        let tests = quantise(&s, q)?;
        for (n, ((line, row), ((_, v), (r, _)))) in
            rows.iter().zip(s.vs.iter().zip(&tests)).enumerate()
        {
            let (tag, o) = tb::ip::slab_out_of_row(&ctx, &outs, row)?;
            if tag != tb::ip::seq_tag(n) {
                return Err(format!(
                    "{csrc}:{line}: field `tag_out`: {tag:#x}, but result {n} (the vector with tag {}) \
                     was sent with tag_in {:#x}: a result is missing, repeated or out of order",
                    v.tag,
                    tb::ip::seq_tag(n)
                ));
            }
            let (hit, en, ex) = ctx.world(r, &o);
            write_result(&mut w, s.vfmt, v.tag, hit, en, ex).map_err(|e| w.err(e))?;
        }
    });
    w.commit()
}

/// The datasheets' worked example: a ray that meets a box through a face it grazes at a shallow angle
/// (its z component is small but not zero), from the origin (0, 0.5, 2.01) along (1, 0, -0.02) against
/// the box (0.25, 0, 0)-(1, 1, 2); exact hit on t in [0.5, 1].
pub fn example_vector() -> Vector {
    use glam::DVec3;
    Vector {
        tag: 0,
        ray: golden::geom::Ray::new(
            DVec3::new(0.0, 0.5, 2.01),
            DVec3::new(1.0, 0.0, -0.02),
            0.0,
            f64::INFINITY,
        )
        .expect("a valid ray"),
        bx: golden::Aabb::new(DVec3::new(0.25, 0.0, 0.0), DVec3::new(1.0, 1.0, 2.0))
            .expect("a valid box"),
        planes: vec![],
    }
}

/// The worked example of `e`'s datasheet ([`example_vector`] through the encoder, the model and the
/// decoder), or `None` for a family the encoder does not take.
pub fn example(e: &Exported, ports: &[Port]) -> Result<Option<tb::ip::datasheet::Example>, String> {
    if encodable(e).is_err() {
        return Ok(None);
    }
    let v = example_vector();
    let mut json = vec![];
    golden::slab::vectors::write_vector(&mut json, VecFormat::JsonLines, &v)
        .map_err(|e| e.to_string())?;
    let grid = (v.ray.origin.min(v.bx.min), v.ray.origin.max(v.bx.max));
    let s = setup_from(
        e.clone(),
        ports.to_vec(),
        vec![(1, v.clone())],
        VecFormat::JsonLines,
        grid,
        "the example".into(),
    )?;
    let ins = words::columns(&s.ports, true);
    let outs = words::columns(&s.ports, false);
    let (ri, ro, res) = with_ctx!(&s, |ctx, q| {
        let tests = quantise(&s, q)?;
        let (r, b) = &tests[0];
        let o = ctx.model(r, b);
        let ri = tb::ip::slab_in_row(&ctx, &ins, 0, r, b)?;
        let ro = tb::ip::slab_out_row(&ctx, &outs, 0, &o)?;
        let (hit, en, ex) = ctx.world(r, &o);
        let mut line = vec![];
        write_result(&mut line, VecFormat::JsonLines, 0, hit, en, ex).map_err(|e| e.to_string())?;
        (ri, ro, String::from_utf8_lossy(&line).trim().to_string())
    });
    let mapping = match &s.map {
        Some(m) => format!(
            "maps, with the grid of the vector's own bounds (what `rtu encode` does for a file \
             holding only this vector: `k = {}`, `c = ({}, {}, {})`, so one grid unit is 2^{} world \
             units), to these input words:",
            m.k, m.c[0], m.c[1], m.c[2], m.k
        ),
        None => "maps to these input words:".into(),
    };
    Ok(Some(tb::ip::datasheet::Example {
        vector: String::from_utf8_lossy(&json).trim().to_string(),
        mapping,
        ins: ins.iter().map(|p| p.name.clone()).zip(ri).collect(),
        outs: outs.iter().map(|p| p.name.clone()).zip(ro).collect(),
        result: res,
    }))
}
