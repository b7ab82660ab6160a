//! `rtu run` and `rtu gen`: users' vector files through any engine, and generated vectors out to a file.

use crate::out_file::Output;
use glam::DVec3;
use golden::format::fixed::{FixFormat, GridMap};
use golden::format::float::FloatFormat;
use golden::plane::fix::CullFixFormat;
use golden::plane::float::CullFloatFormat;
use golden::slab::float::{quantize_box, quantize_ray};
use golden::slab::gen::{GenKind, SlabGen};
use golden::slab::vectors::{
    csv_vector_header, read_numbered_vectors, write_header, write_result, write_vector, VecFormat,
    Vector, MAX_VECTOR_PLANES,
};
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use tb::engine::{run_cull_fix, run_cull_float, run_fix, run_float, Engine};
use tb::plane::fix::{fix_vector, CullFixCtx};
use tb::plane::float::{float_vector, CullFloatCtx};
use tb::xsim::TesterCtx;

pub(crate) fn parse_bounds(s: &str) -> Result<(DVec3, DVec3), String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| {
            x.trim()
                .parse::<f64>()
                .map_err(|_| format!("--bounds: `{x}` is not a number"))
        })
        .collect::<Result<_, _>>()?;
    if v.len() != 6 {
        return Err(format!(
            "--bounds: expected six numbers x0,y0,z0,x1,y1,z1, got {}",
            v.len()
        ));
    }
    Ok((DVec3::new(v[0], v[1], v[2]), DVec3::new(v[3], v[4], v[5])))
}

/// The whole input as bytes (so stdin can be read twice).
pub(crate) fn slurp(input: &Path) -> Result<Vec<u8>, String> {
    let mut buf = vec![];
    if input == Path::new("-") {
        std::io::stdin()
            .read_to_end(&mut buf)
            .map_err(|e| format!("stdin: {e}"))?;
    } else {
        std::fs::File::open(input)
            .and_then(|mut f| f.read_to_end(&mut buf))
            .map_err(|e| format!("{}: {e}", input.display()))?;
    }
    Ok(buf)
}

pub(crate) fn vectors_of(
    bytes: Arc<Vec<u8>>,
    fmt: VecFormat,
    src: String,
) -> impl Iterator<Item = Result<(usize, Vector), golden::Error>> {
    struct Shared(Arc<Vec<u8>>);
    impl AsRef<[u8]> for Shared {
        fn as_ref(&self) -> &[u8] {
            &self.0
        }
    }
    let reader: Box<dyn BufRead + Send> =
        Box::new(BufReader::new(std::io::Cursor::new(Shared(bytes))));
    read_numbered_vectors(reader, fmt, src)
}

/// Runs a vector file through `engine` on the fixed (`b8`, `b12`, `b16`, `G,I,FI,T,FT`) or float (`fp32`,
/// `fp16`, `bf16`, `eXmY`) tester of `format` — the slab tester, or with `planes = Some(K)` the chained
/// slab + cull-plane tester with `K` planes, each vector's planes fitted outward into the format — and
/// writes results in the input's format.
#[allow(clippy::too_many_arguments)]
pub fn run(
    input: &Path,
    output: Option<&Path>,
    engine: Engine,
    format: &str,
    planes: Option<usize>,
    bounds: Option<&str>,
    vcd: Option<&Path>,
    out: &Path,
) -> Result<(), String> {
    let vfmt = if input == Path::new("-") {
        VecFormat::JsonLines
    } else {
        VecFormat::from_path(input)
    };
    let src = input.display().to_string();
    let bytes = Arc::new(slurp(input)?);
    let mut w = Output::open(output)?;
    let mut header = vec![];
    write_header(&mut header, vfmt).map_err(|e| e.to_string())?;
    w.set_header(header);
    let failure: Arc<Mutex<Option<String>>> = Arc::new(Mutex::new(None));
    let vdir = out.join("verilator");
    let lower = format.to_ascii_lowercase();
    let looks_float = lower.starts_with('e') || lower.starts_with("fp") || lower.starts_with("bf");
    let k = planes.unwrap_or(0);
    if k > MAX_VECTOR_PLANES {
        return Err(format!("--k {k}: at most {MAX_VECTOR_PLANES} planes"));
    }
    let too_many = move |v: &Vector| -> Result<(), golden::Error> {
        if v.planes.len() > k {
            return Err(golden::Error::Io(format!(
                "{} planes, but the tester has {k} (--k)",
                v.planes.len()
            )));
        }
        Ok(())
    };
    let (n, what) = if looks_float && planes.is_some() {
        let f = FloatFormat::parse(format).map_err(|e| e.to_string())?;
        let ctx = CullFloatCtx::new(CullFloatFormat::over(f), k);
        let tests = quantized(bytes, vfmt, src, failure.clone(), move |v| {
            too_many(v)?;
            float_vector(&ctx.cf, v)
        });
        let n = run_cull_float(engine, ctx, tests, &vdir, vcd, |tag, r, o| {
            emit(&mut w, vfmt, tag, ctx.world(r, &o))
        })?;
        (n, format!("float format {}, {k} planes", f.name()))
    } else if looks_float {
        let f = FloatFormat::parse(format).map_err(|e| e.to_string())?;
        let tests = quantized(bytes, vfmt, src, failure.clone(), move |v| {
            too_many(v)?;
            Ok((quantize_ray(&f, &v.ray)?, quantize_box(&f, &v.bx)?))
        });
        let n = run_float(engine, f, tests, &vdir, vcd, |tag, r, o| {
            emit(&mut w, vfmt, tag, f.world(r, &o))
        })?;
        (n, format!("float format {}", f.name()))
    } else {
        let fmt = FixFormat::parse(format)
            .map_err(|e| format!("{e} (or a float format: fp32, fp16, bf16, eXmY)"))?;
        let (lo, hi) = match bounds {
            Some(b) => parse_bounds(b)?,
            None => file_bounds(bytes.clone(), vfmt, &src)?,
        };
        let map = GridMap::for_bounds(fmt, lo, hi).map_err(|e| e.to_string())?;
        let n = if planes.is_some() {
            let ctx = CullFixCtx {
                cf: CullFixFormat::over(fmt),
                k,
            };
            let tests = quantized(bytes, vfmt, src, failure.clone(), move |v| {
                too_many(v)?;
                fix_vector(&ctx.cf, &map, v)
            });
            run_cull_fix(engine, ctx, tests, &vdir, vcd, |tag, r, o| {
                emit(&mut w, vfmt, tag, ctx.world(r, &o))
            })?
        } else {
            let tests = quantized(bytes, vfmt, src, failure.clone(), move |v| {
                too_many(v)?;
                Ok((map.quantize_ray(&v.ray)?, map.quantize_box(&v.bx)?))
            });
            run_fix(engine, fmt, tests, &vdir, vcd, |tag, r, o| {
                emit(&mut w, vfmt, tag, fmt.world(r, &o))
            })?
        };
        (
            n,
            format!(
                "format {}, grid cell {}, {k} planes",
                fmt.name(),
                golden::format::fixed::ldexp(1.0, map.k)
            ),
        )
    };
    if let Some(e) = failure.lock().unwrap().take() {
        return Err(e);
    }
    w.commit()?;
    eprintln!("rtu run: {n} vectors through the {engine:?} engine, {what}");
    Ok(())
}

fn emit(
    w: &mut Output,
    vfmt: VecFormat,
    tag: u64,
    (hit, en, ex): (bool, f64, f64),
) -> Result<(), String> {
    write_result(w, vfmt, tag, hit, en, ex).map_err(|e| w.err(e))
}

/// Bounds of the origins and non-empty boxes of a vector file (validating every line on the way; the
/// file is streamed, not held).
pub(crate) fn file_bounds(
    bytes: Arc<Vec<u8>>,
    vfmt: VecFormat,
    src: &str,
) -> Result<(DVec3, DVec3), String> {
    let mut failure = None;
    let vs = vectors_of(bytes, vfmt, src.to_string()).map_while(|v| match v {
        Ok((_, v)) => Some(v),
        Err(e) => {
            failure = Some(e.to_string());
            None
        }
    });
    let b = vector_bounds(vs);
    if let Some(e) = failure {
        return Err(e);
    }
    b.ok_or_else(|| format!("{src}: no vectors"))
}

/// Bounds of the origins and non-empty boxes of some vectors, the grid's default (`None` for none).
pub(crate) fn vector_bounds<V: std::borrow::Borrow<Vector>>(
    vs: impl IntoIterator<Item = V>,
) -> Option<(DVec3, DVec3)> {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for v in vs {
        let v = v.borrow();
        lo = lo.min(v.ray.origin);
        hi = hi.max(v.ray.origin);
        if !v.bx.is_empty() {
            lo = lo.min(v.bx.min);
            hi = hi.max(v.bx.max);
        }
    }
    lo.is_finite().then_some((lo, hi))
}

/// The file's vectors quantised by `q`, streamed; the first error stops the stream and is kept in `failure`.
fn quantized<R, B>(
    bytes: Arc<Vec<u8>>,
    vfmt: VecFormat,
    src: String,
    failure: Arc<Mutex<Option<String>>>,
    q: impl Fn(&Vector) -> Result<(R, B), golden::Error> + Send + 'static,
) -> impl Iterator<Item = (u64, R, B)> + Send + 'static {
    vectors_of(bytes, vfmt, src.clone()).map_while(move |v| {
        let r = v.map_err(|e| e.to_string()).and_then(|(line, v)| {
            q(&v)
                .map(|(r, b)| (v.tag, r, b))
                .map_err(|e| format!("{src}:{line}: vector with tag {}: {e}", v.tag))
        });
        match r {
            Ok(t) => Some(t),
            Err(e) => {
                *failure.lock().unwrap() = Some(e);
                None
            }
        }
    })
}

/// Writes `n` generated vectors over the campaign bounds.
pub fn gen(kind: GenKind, n: u64, seed: u64, output: Option<&Path>) -> Result<(), String> {
    let (lo, hi) = tb::campaign::campaign_bounds();
    let vfmt = output
        .map(VecFormat::from_path)
        .unwrap_or(VecFormat::JsonLines);
    let mut w = Output::open(output)?;
    if vfmt == VecFormat::Csv {
        w.set_header(format!("{}\n", csv_vector_header()));
    }
    for (tag, (ray, bx)) in SlabGen::new(kind, lo, hi, 1.0 / 64.0, seed)
        .take(n as usize)
        .enumerate()
    {
        write_vector(
            &mut w,
            vfmt,
            &Vector {
                tag: tag as u64,
                ray,
                bx,
                planes: vec![],
            },
        )
        .map_err(|e| w.err(e))?;
    }
    w.commit()
}

/// Options of `rtu run`.
#[derive(clap::Args, Clone, Debug)]
pub struct RunArgs {
    /// Input vectors (`.csv` is CSV, anything else JSON lines; `-` reads JSON lines from stdin).
    pub input: PathBuf,
    /// Where to write results (same format as the input); stdout when absent.
    #[arg(long, short)]
    pub output: Option<PathBuf>,
    /// model, rtl or verilator.
    #[arg(long, default_value = "model")]
    pub engine: tb::engine::Engine,
    /// Format: fixed b8, b12, b16 or G,I,FI,T,FT; float fp32, fp16, bf16 or eXmY. The rtl and verilator
    /// engines take the instantiated ones (fixed presets; e8m23, e8m15, e8m7, e5m10, e6m5).
    #[arg(long, default_value = "b16")]
    pub format: String,
    /// Run the chained slab + cull-plane tester with this many planes per node (0 to 8; the rtl and
    /// verilator engines take 1 to 8 with b8, b12, b16, 1, 2, 4, 8 with fp16 and 1, 2, 4 with bf16,
    /// fp32); each vector's planes (`planes` in JSON, `p0_nx..p7_w` in CSV) are fitted outward into the format
    /// (also `--planes`).
    #[arg(long, alias = "planes")]
    pub k: Option<usize>,
    /// Fixed formats: scene bounds `x0,y0,z0,x1,y1,z1` for the grid; by default the bounds of the file's
    /// origins and boxes.
    #[arg(long)]
    pub bounds: Option<String>,
    /// Write a waveform of the run here (rtl engine).
    #[arg(long)]
    pub vcd: Option<PathBuf>,
    /// The input is bundle vectors (JSON lines: a bundle by its rays or its bounds, and a box) for the
    /// AllHit / AnyHit pair and the results processor (model engine; rtl engine on b8, b12, b16).
    #[arg(long)]
    pub bundles: bool,
}

/// `rtu run`: a file of slab or cull-plane vectors ([`run`]), or of bundle vectors with `--bundles`
/// ([`crate::run_bundles::run`]).
pub fn run_cmd(a: &RunArgs, out: &Path) -> Result<(), String> {
    if a.bundles {
        if a.k.is_some() {
            return Err("--bundles does not take --k (planes per node)".to_string());
        }
        let grid = a.bounds.as_deref().map(parse_bounds).transpose()?;
        return crate::run_bundles::run(
            &a.input,
            a.output.as_deref(),
            a.engine,
            &a.format,
            grid,
            a.vcd.as_deref(),
        );
    }
    run(
        &a.input,
        a.output.as_deref(),
        a.engine,
        &a.format,
        a.k,
        a.bounds.as_deref(),
        a.vcd.as_deref(),
        out,
    )
}

/// Options of `rtu gen`.
#[derive(clap::Args, Clone, Debug)]
pub struct GenArgs {
    #[arg(long, default_value = "mixed")]
    pub kind: golden::slab::gen::GenKind,
    /// Vectors to write (also `--n`).
    #[arg(long, short = 'n', alias = "n", default_value_t = 1000)]
    pub vectors: u64,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output file (`.csv` for CSV); stdout when absent.
    #[arg(long, short)]
    pub output: Option<PathBuf>,
}

/// `rtu gen`: [`gen`] with its options.
pub fn gen_cmd(a: &GenArgs) -> Result<(), String> {
    gen(a.kind, a.vectors, a.seed, a.output.as_deref())
}
