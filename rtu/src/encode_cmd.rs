//! `rtu encode` and `rtu decode`: world-space vectors (the files of `rtu run`) as the words on an
//! exported core's ports, and the words a simulation captured back as world-space results.
//!
//! `encode` writes three files beside a prefix: `<prefix>.in.hex` (one line per test: a hex word per
//! input port, the columns named by a `// ports:` line; `tb::ip::words`), `<prefix>.out.hex` (the
//! results the bit-accurate model predicts, as output words, in the same form) and `<prefix>.mem` (the
//! input words packed into one word per test for `$readmemh`). Test `n` carries the tag `n mod 2^16`.
//! `decode` reads captured output words (the `.out.hex` form) with the same vector file and writes the
//! results exactly as `rtu run` writes them, so `decode(simulate(encode(v)))` can be compared with
//! `rtu run` byte for byte (for a bundle pair, with `rtu run --bundles` on bundles given by their
//! bounds: for a bundle given by its rays, `rtu run` also runs the results processor). Decode must be
//! given the same `--bounds` as encode (or none to both): the grid is the vector file's, and the word
//! files only name it in a comment.

use crate::out_file::{write_file, Output};
use crate::run_vectors::{parse_bounds, slurp, vector_bounds, vectors_of};
use golden::format::fixed::GridMap;
use golden::slab::float::{quantize_box, quantize_ray};
use golden::slab::vectors::{write_header, write_result, VecFormat, Vector};
use rtl::export::{Exported, Family};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use tb::bundle::pair_float::PairFloatCtx;
use tb::ip::words;
use tb::plane::fix::{fix_vector, CullFixCtx};
use tb::plane::float::{float_vector, CullFloatCtx};
use tb::verilator::{parse_ports, Port};
use tb::xsim::{in_row, out_of_row, out_row, BlockCtx, TesterCtx};

/// Options of `rtu encode`.
#[derive(clap::Args)]
pub struct EncodeArgs {
    /// The exported module, e.g. slab_fix_g12_i16f11_t20f6 (`rtu export` lists them).
    #[arg(long)]
    pub module: String,
    /// Vectors in world space, as `rtu run` reads them (`.csv` is CSV, anything else JSON lines); for a
    /// bundle pair, bundle vectors as `rtu run --bundles` reads them.
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
    /// The bounds given to `rtu encode`, if any (the same grid is needed to read the t codes back).
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

/// Whether the encoder takes a module: the pipelined testers of the slab, cull-plane (table option)
/// and bundle pair families (the results processor takes jobs over several clocks; the fraction option
/// reports exact quotients, not t codes).
fn encodable(e: &Exported) -> Result<(), String> {
    let name = &e.module;
    if !e.pipelined() {
        return Err(format!(
            "module `{name}`: the results processor takes a job over several clocks (rays written to \
             its store, then `start`); encode drives pipelined testers one test a clock. Drive it \
             from its datasheet's job protocol, or use `rtu run --bundles`"
        ));
    }
    if matches!(e.family, Family::PlaneQuot { .. }) {
        return Err(format!(
            "module `{name}`: the fraction option reports its interval as exact quotients \
             (`num`, `den`, ...), not as t codes; encode and decode take the table option \
             (plane_fix_..._r8_k*) and the other slab and cull-plane testers"
        ));
    }
    Ok(())
}

/// The vectors of a file, each with its line, in order.
fn read_vectors(input: &Path) -> Result<(Vec<(usize, Vector)>, VecFormat), String> {
    let vfmt = VecFormat::from_path(input);
    let bytes = Arc::new(slurp(input)?);
    let vs = vectors_of(bytes, vfmt, input.display().to_string())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())?;
    if vs.is_empty() {
        return Err(format!("{}: no vectors", input.display()));
    }
    Ok((vs, vfmt))
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
    let (vs, vfmt) = read_vectors(input)?;
    let src = input.display().to_string();
    let grid = match bounds {
        Some(b) => parse_bounds(b)?,
        None => vector_bounds(vs.iter().map(|(_, v)| v)).expect("at least one vector"),
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
        Family::PlaneFix { cf, .. } | Family::PlaneQuot { cf, .. } => Some(cf.base),
        _ => None,
    };
    let map = match base {
        Some(fmt) => Some(GridMap::for_bounds(fmt, lo, hi).map_err(|e| e.to_string())?),
        None => None,
    };
    let k = match e.family {
        Family::PlaneFix { k, .. } | Family::PlaneQuot { k, .. } | Family::PlaneFloat { k, .. } => {
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
            Family::PlaneFix { cf, k, .. } | Family::PlaneQuot { cf, k } => {
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

/// Comment lines that say what a word file holds (`what`) and how the `n` vectors (`unit`: tests or
/// bundles) from `src` were mapped.
fn word_head(
    e: &Exported,
    map: Option<&GridMap>,
    n: usize,
    unit: &str,
    src: &str,
    what: &str,
) -> Vec<String> {
    let mut h = vec![format!(
        "rtu encode: {what} of module {}, latency {} clocks, {n} {unit} from {src}",
        e.module, e.latency
    )];
    if let Some(m) = map {
        h.push(format!(
            "grid: q = x / 2^{} - c, c = ({}, {}, {}) (the datasheet's grid map)",
            m.k, m.c[0], m.c[1], m.c[2]
        ));
    }
    h.push("test n carries tag_in = n mod 65536; results leave in order".into());
    h
}

fn head(s: &Setup, what: &str) -> Vec<String> {
    word_head(&s.e, s.map.as_ref(), s.vs.len(), "tests", &s.src, what)
}

/// `rtu encode`: writes the three word files and returns a summary line.
pub fn encode(a: &EncodeArgs, out: &Path) -> Result<String, String> {
    if is_bundle(&a.module)? {
        let b = bundle_setup(&a.module, &a.input, a.bounds.as_deref())?;
        let (ri, ro) = bundle_rows(&b)?;
        return write_words(
            &b.e,
            a.output.as_deref(),
            out,
            &b.head(),
            &b.ports,
            &ri,
            &ro,
        );
    }
    let s = setup(&a.module, &a.input, a.bounds.as_deref())?;
    let (rows_in, rows_out) = slab_rows(&s)?;
    let h = |what: &str| head(&s, what);
    write_words(
        &s.e,
        a.output.as_deref(),
        out,
        &h,
        &s.ports,
        &rows_in,
        &rows_out,
    )
}

/// The input words of every test and the output words the model gives for it.
fn slab_rows(s: &Setup) -> Result<(Vec<Vec<u64>>, Vec<Vec<u64>>), String> {
    let ins = words::columns(&s.ports, true);
    let outs = words::columns(&s.ports, false);
    Ok(with_ctx!(s, |ctx, q| {
        let tests = quantise(s, q)?;
        let mut ri = Vec::with_capacity(tests.len());
        let mut ro = Vec::with_capacity(tests.len());
        for (n, (r, b)) in tests.iter().enumerate() {
            let tag = tb::ip::seq_tag(n);
            ri.push(in_row(&ctx, &ins, tag, r, b)?);
            ro.push(out_row(&ctx, &outs, tag, &ctx.model(r, b))?);
        }
        (ri, ro)
    }))
}

/// Writes the results of output word rows (`(line of csrc, words)`, one per vector, in order) to `w` as
/// `rtu run` writes them, after checking each row's tag; `werr` names a write error.
fn slab_results(
    s: &Setup,
    rows: &[(usize, Vec<u64>)],
    csrc: &str,
    w: &mut impl std::io::Write,
    werr: impl Fn(std::io::Error) -> String,
) -> Result<(), String> {
    let outs = words::columns(&s.ports, false);
    with_ctx!(s, |ctx, q| {
        let tests = quantise(s, q)?;
        for (n, ((line, row), ((_, v), (r, _)))) in
            rows.iter().zip(s.vs.iter().zip(&tests)).enumerate()
        {
            let (tag, o) = out_of_row(&ctx, &outs, row)?;
            check_tag(csrc, *line, tag, n, v.tag)?;
            let (hit, en, ex) = ctx.world(r, &o);
            write_result(w, s.vfmt, v.tag, hit, en, ex).map_err(&werr)?;
        }
    });
    Ok(())
}

/// Writes `<prefix>.in.hex`, `.out.hex` and `.mem` (prefix: `output`, or `<out>/encode/<module>`), each
/// headed by `head(what the file holds)`.
fn write_words(
    e: &Exported,
    output: Option<&Path>,
    out: &Path,
    head: &dyn Fn(&str) -> Vec<String>,
    ports: &[Port],
    rows_in: &[Vec<u64>],
    rows_out: &[Vec<u64>],
) -> Result<String, String> {
    let ins = words::columns(ports, true);
    let outs = words::columns(ports, false);
    let prefix = output
        .map(Path::to_path_buf)
        .unwrap_or_else(|| out.join("encode").join(&e.module));
    if let Some(d) = prefix.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(d).map_err(|e| format!("{}: {e}", d.display()))?;
    }
    let file = |ext: &str| PathBuf::from(format!("{}.{ext}", prefix.display()));
    write_file(
        &file("in.hex"),
        words::write(&head("input words"), &ins, rows_in),
    )?;
    write_file(
        &file("out.hex"),
        words::write(&head("the model's output words"), &outs, rows_out),
    )?;
    write_file(
        &file("mem"),
        words::readmemh(&head("packed input words"), &ins, rows_in),
    )?;
    Ok(format!(
        "rtu encode: {} tests for {} -> {}.{{in.hex,out.hex,mem}}",
        rows_in.len(),
        e.module,
        prefix.display()
    ))
}

/// `rtu decode`: the captured words as world-space results, written as `rtu run` writes them.
pub fn decode(a: &DecodeArgs) -> Result<(), String> {
    if is_bundle(&a.module)? {
        return decode_bundles(a);
    }
    let s = setup(&a.module, &a.vectors, a.bounds.as_deref())?;
    let (csrc, rows) = captured(a, &s.ports, s.vs.len(), &s.src)?;
    let mut w = Output::open(a.output.as_deref())?;
    let mut header = vec![];
    write_header(&mut header, s.vfmt).map_err(|e| e.to_string())?;
    w.set_header(header);
    let name = w.name();
    slab_results(&s, &rows, &csrc, &mut w, |e| {
        format!("{name}: cannot write: {e}")
    })?;
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
    if matches!(
        e.family,
        Family::BundleFix { .. } | Family::BundleFloat { .. }
    ) {
        return bundle_example(e, ports).map(Some);
    }
    let mut v = example_vector();
    if matches!(
        e.family,
        Family::PlaneFix { .. } | Family::PlaneFloat { .. }
    ) {
        // One cull plane, relative to the box's centroid (0.625, 0.5, 1): keep x >= 0.625, so the
        // exact entry moves from t = 0.5 to t = 0.625.
        v.planes.push(golden::plane::clip::Plane {
            n: glam::DVec3::new(-1.0, 0.0, 0.0),
            w: 0.0,
        });
    }
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
    // Through the encoder and the model, and the model's words back through the decoder.
    let (ri, ro) = slab_rows(&s)?;
    let mut line = vec![];
    slab_results(&s, &[(1, ro[0].clone())], "the example", &mut line, |e| {
        e.to_string()
    })?;
    let mapping = match &s.map {
        Some(m) => format!(
            "(a line of `rtu run`'s JSON input) maps, with the grid of the vector's own bounds (what `rtu encode` does for a file \
             holding only this vector: `k = {}`, `c = ({}, {}, {})`, so one grid unit is 2^{} world \
             units), to these input words:",
            m.k, m.c[0], m.c[1], m.c[2], m.k
        ),
        None => "(a line of `rtu run`'s JSON input) maps to these input words:".into(),
    };
    Ok(Some(example_of(
        &s.ports, json, mapping, &ri[0], &ro[0], line,
    )))
}

/// The captured output words of a decode, checked against the number of vectors.
fn captured(
    a: &DecodeArgs,
    ports: &[Port],
    vectors: usize,
    src: &str,
) -> Result<(String, Vec<(usize, Vec<u64>)>), String> {
    let outs = words::columns(ports, false);
    let csrc = a.captured.display().to_string();
    let text = std::fs::read_to_string(&a.captured).map_err(|e| format!("{csrc}: {e}"))?;
    let rows = words::read(&text, &csrc, ports, &outs)?;
    if rows.len() != vectors {
        return Err(format!(
            "{csrc}: {} results, but {src} has {vectors} vectors",
            rows.len()
        ));
    }
    Ok((csrc, rows))
}

/// The tag of result `n` (on line `line` of `csrc`) must be test `n`'s.
fn check_tag(csrc: &str, line: usize, tag: u16, n: usize, user_tag: u64) -> Result<(), String> {
    if tag != tb::ip::seq_tag(n) {
        return Err(format!(
            "{csrc}:{line}: field `tag_out`: {tag:#x}, but result {n} (the vector with tag {user_tag}) \
             was sent with tag_in {:#x}: a result is missing, repeated or out of order",
            tb::ip::seq_tag(n)
        ));
    }
    Ok(())
}

/// Whether `module` is a bundle pair (its vectors are bundle vectors), after the module checks.
fn is_bundle(module: &str) -> Result<bool, String> {
    let e = rtl::export::find(module)?;
    encodable(&e)?;
    Ok(matches!(
        e.family,
        Family::BundleFix { .. } | Family::BundleFloat { .. }
    ))
}

/// A bundle pair and the bundle vectors for it.
struct BundleSetup {
    e: Exported,
    ports: Vec<Port>,
    vs: Vec<(usize, golden::bundle::vectors::BundleVector)>,
    map: Option<GridMap>,
    src: String,
}

impl BundleSetup {
    fn head(&self) -> impl Fn(&str) -> Vec<String> + '_ {
        move |what| {
            word_head(
                &self.e,
                self.map.as_ref(),
                self.vs.len(),
                "bundles",
                &self.src,
                what,
            )
        }
    }
}

fn bundle_setup(name: &str, input: &Path, bounds: Option<&str>) -> Result<BundleSetup, String> {
    let (e, ports) = module(name)?;
    let src = input.display().to_string();
    let bytes = slurp(input)?;
    let vs: Vec<_> = golden::bundle::vectors::read_numbered_bundles(
        std::io::BufReader::new(std::io::Cursor::new(bytes)),
        src.clone(),
    )
    .collect::<Result<_, _>>()
    .map_err(|e| e.to_string())?;
    if vs.is_empty() {
        return Err(format!("{src}: no bundles"));
    }
    bundle_setup_from(e, ports, vs, bounds, src)
}

fn bundle_setup_from(
    e: Exported,
    ports: Vec<Port>,
    vs: Vec<(usize, golden::bundle::vectors::BundleVector)>,
    bounds: Option<&str>,
    src: String,
) -> Result<BundleSetup, String> {
    let map = match e.family {
        Family::BundleFix { bf, .. } => {
            let (lo, hi) = match bounds {
                Some(b) => parse_bounds(b)?,
                None => crate::run_bundles::bounds(vs.iter().map(|(_, v)| v))
                    .ok_or_else(|| format!("{src}: no bundles"))?,
            };
            Some(GridMap::for_bounds(bf.base, lo, hi).map_err(|e| e.to_string())?)
        }
        _ => None,
    };
    Ok(BundleSetup {
        e,
        ports,
        vs,
        map,
        src,
    })
}

/// The input words and the model's output words (`tag_out`, `all_hit`, `all_miss`) of every bundle:
/// the pair tests the bundle (by its bounds, made from its rays when it is given by rays) against the
/// box's inner and outer quantisations.
fn bundle_rows(b: &BundleSetup) -> Result<(Vec<Vec<u64>>, Vec<Vec<u64>>), String> {
    let ins = words::columns(&b.ports, true);
    let outs = words::columns(&b.ports, false);
    let at = |line: usize, tag: u64, e: golden::Error| {
        format!("{}:{line}: bundle with tag {tag}: {e}", b.src)
    };
    let mut ri = vec![];
    let mut ro = vec![];
    for (n, (line, v)) in b.vs.iter().enumerate() {
        let tag = tb::ip::seq_tag(n);
        let (row_in, row_out) = match b.e.family {
            Family::BundleFix { bf, .. } => {
                let map = b.map.expect("a grid for a fixed format");
                let q = (|| {
                    Ok::<_, golden::Error>((
                        rtl::bundle::pair_fix::PairInput::Bundle(
                            golden::bundle::fix::quantize_bundle(&bf, &map, &v.bundle)?,
                        ),
                        golden::bundle::fix::quantize_box_pair(&map, &v.bx)?,
                    ))
                })()
                .map_err(|e| at(*line, v.tag, e))?;
                let out = bf.model(&q.0, &q.1);
                (
                    in_row(&bf, &ins, tag, &q.0, &q.1)?,
                    out_row(&bf, &outs, tag, &out)?,
                )
            }
            Family::BundleFloat { f, .. } => {
                let q = (|| {
                    Ok::<_, golden::Error>((
                        rtl::bundle::pair_float::FloatPairInput::Bundle(
                            golden::bundle::float::quantize_bundle(&f, &v.bundle)?,
                        ),
                        golden::bundle::float::quantize_box_pair(&f, &v.bx)?,
                    ))
                })()
                .map_err(|e| at(*line, v.tag, e))?;
                let ctx = PairFloatCtx(f);
                let out = ctx.model(&q.0, &q.1);
                (
                    in_row(&ctx, &ins, tag, &q.0, &q.1)?,
                    out_row(&ctx, &outs, tag, &out)?,
                )
            }
            _ => unreachable!("is_bundle"),
        };
        ri.push(row_in);
        ro.push(row_out);
    }
    Ok((ri, ro))
}

/// `rtu decode` of a bundle pair: one result line per bundle (`all_hit`, `all_miss`), as
/// `rtu run --bundles` writes a bundle given by its bounds.
fn decode_bundles(a: &DecodeArgs) -> Result<(), String> {
    let b = bundle_setup(&a.module, &a.vectors, a.bounds.as_deref())?;
    let (csrc, rows) = captured(a, &b.ports, b.vs.len(), &b.src)?;
    let mut w = Output::open(a.output.as_deref())?;
    let name = w.name();
    bundle_results(&b, &rows, &csrc, &mut w, |e| {
        format!("{name}: cannot write: {e}")
    })?;
    w.commit()
}

/// Writes the results of the pair's output word rows as `rtu run --bundles` writes a bundle given by its
/// bounds, after checking each row's tag; `werr` names a write error.
fn bundle_results(
    b: &BundleSetup,
    rows: &[(usize, Vec<u64>)],
    csrc: &str,
    w: &mut impl std::io::Write,
    werr: impl Fn(std::io::Error) -> String,
) -> Result<(), String> {
    let outs = words::columns(&b.ports, false);
    for (n, ((line, row), (_, v))) in rows.iter().zip(&b.vs).enumerate() {
        let (tag, (all_hit, all_miss)) = match b.e.family {
            Family::BundleFix { bf, .. } => out_of_row(&bf, &outs, row)?,
            Family::BundleFloat { f, .. } => out_of_row(&PairFloatCtx(f), &outs, row)?,
            _ => unreachable!("is_bundle"),
        };
        check_tag(csrc, *line, tag, n, v.tag)?;
        let r = golden::bundle::vectors::BundleResult {
            all_hit,
            all_miss,
            rays: None,
        };
        golden::bundle::vectors::write_bundle_result(w, v.tag, &r).map_err(&werr)?;
    }
    Ok(())
}

/// The bundle pairs' worked example: a bundle of rays from the square (-0.1..0.1, 0.4..0.6, -5) going
/// up the z axis within a small cone, unbounded (`t_lo = t_hi = inf`: every ray's `t_max` is infinite),
/// against the box (-1, -1, -1)-(1, 1, 1): every ray hits, and the AllHit tester can say so.
fn bundle_example(e: &Exported, ports: &[Port]) -> Result<tb::ip::datasheet::Example, String> {
    use glam::DVec3;
    let v = golden::bundle::vectors::BundleVector {
        tag: 0,
        bundle: golden::bundle::edge::Bundle::new(
            (DVec3::new(-0.1, 0.4, -5.0), DVec3::new(0.1, 0.6, -5.0)),
            (DVec3::new(-0.01, -0.01, 1.0), DVec3::new(0.01, 0.01, 1.0)),
            f64::INFINITY,
            f64::INFINITY,
        )
        .map_err(|e| e.to_string())?,
        rays: vec![],
        bx: golden::Aabb::new(DVec3::splat(-1.0), DVec3::splat(1.0)).map_err(|e| e.to_string())?,
    };
    let mut json = vec![];
    golden::bundle::vectors::write_bundle_vector(&mut json, &v).map_err(|e| e.to_string())?;
    let b = bundle_setup_from(
        e.clone(),
        ports.to_vec(),
        vec![(1, v.clone())],
        None,
        "the example".into(),
    )?;
    let (ri, ro) = bundle_rows(&b)?;
    let mut line = vec![];
    bundle_results(&b, &[(1, ro[0].clone())], "the example", &mut line, |e| {
        e.to_string()
    })?;
    let mapping = match &b.map {
        Some(m) => format!(
            "(a line of `rtu run --bundles`'s input) maps, with the grid of the vector's own bounds \
             (`k = {}`, `c = ({}, {}, {})`), to these input words:",
            m.k, m.c[0], m.c[1], m.c[2]
        ),
        None => "(a line of `rtu run --bundles`'s input) maps to these input words:".into(),
    };
    Ok(example_of(ports, json, mapping, &ri[0], &ro[0], line))
}

/// A datasheet example from the vector's JSON, the mapping sentence, its input and output word rows and
/// its result line.
fn example_of(
    ports: &[Port],
    json: Vec<u8>,
    mapping: String,
    ins: &[u64],
    outs: &[u64],
    result: Vec<u8>,
) -> tb::ip::datasheet::Example {
    let named = |cols: Vec<Port>, row: &[u64]| -> Vec<(String, u64)> {
        cols.into_iter()
            .map(|p| p.name)
            .zip(row.iter().copied())
            .collect()
    };
    tb::ip::datasheet::Example {
        vector: String::from_utf8_lossy(&json).trim().to_string(),
        mapping,
        ins: named(words::columns(ports, true), ins),
        outs: named(words::columns(ports, false), outs),
        result: String::from_utf8_lossy(&result).trim().to_string(),
    }
}
