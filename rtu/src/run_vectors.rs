//! `rtu run` and `rtu gen`: users' vector files through any engine, and generated vectors out to a file.

use glam::DVec3;
use golden::fixed::{FixFormat, GridMap};
use golden::gen::{GenKind, SlabGen};
use golden::vectors::{
    csv_vector_header, read_vectors, write_header, write_result, write_vector, VecFormat, Vector,
};
use std::io::{BufRead, BufReader, BufWriter, Read, Write};
use std::path::Path;
use std::sync::{Arc, Mutex};
use tb::engine::{run_engine, Engine};

fn parse_bounds(s: &str) -> Result<(DVec3, DVec3), String> {
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
fn slurp(input: &Path) -> Result<Vec<u8>, String> {
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

fn vectors_of(
    bytes: Arc<Vec<u8>>,
    fmt: VecFormat,
    src: String,
) -> impl Iterator<Item = Result<Vector, golden::Error>> {
    struct Shared(Arc<Vec<u8>>);
    impl AsRef<[u8]> for Shared {
        fn as_ref(&self) -> &[u8] {
            &self.0
        }
    }
    let reader: Box<dyn BufRead + Send> =
        Box::new(BufReader::new(std::io::Cursor::new(Shared(bytes))));
    read_vectors(reader, fmt, src)
}

/// Runs a vector file through `engine` and writes results in the input's format.
#[allow(clippy::too_many_arguments)]
pub fn run(
    input: &Path,
    output: Option<&Path>,
    engine: Engine,
    format: &str,
    bounds: Option<&str>,
    vcd: Option<&Path>,
    out: &Path,
) -> Result<(), String> {
    let fmt = FixFormat::parse(format).map_err(|e| e.to_string())?;
    let vfmt = if input == Path::new("-") {
        VecFormat::JsonLines
    } else {
        VecFormat::from_path(input)
    };
    let src = input.display().to_string();
    let bytes = Arc::new(slurp(input)?);
    // First pass: validate every line and find the bounds.
    let (lo, hi) = match bounds {
        Some(b) => parse_bounds(b)?,
        None => {
            let mut lo = DVec3::splat(f64::INFINITY);
            let mut hi = DVec3::splat(f64::NEG_INFINITY);
            for v in vectors_of(bytes.clone(), vfmt, src.clone()) {
                let v = v.map_err(|e| e.to_string())?;
                lo = lo.min(v.ray.origin);
                hi = hi.max(v.ray.origin);
                if !v.bx.is_empty() {
                    lo = lo.min(v.bx.min);
                    hi = hi.max(v.bx.max);
                }
            }
            if !lo.is_finite() {
                return Err(format!("{src}: no vectors"));
            }
            (lo, hi)
        }
    };
    let map = GridMap::for_bounds(fmt, lo, hi).map_err(|e| e.to_string())?;
    // Second pass, streamed: quantise and run. The first error stops the stream and is reported.
    let failure: Arc<Mutex<Option<String>>> = Arc::new(Mutex::new(None));
    let fail = failure.clone();
    let tests = vectors_of(bytes, vfmt, src).map_while(move |v| {
        let r = v.map_err(|e| e.to_string()).and_then(|v| {
            let q = |e: golden::Error| format!("vector with tag {}: {e}", v.tag);
            Ok((
                v.tag,
                map.quantize_ray(&v.ray).map_err(q)?,
                map.quantize_box(&v.bx).map_err(q)?,
            ))
        });
        match r {
            Ok(t) => Some(t),
            Err(e) => {
                *fail.lock().unwrap() = Some(e);
                None
            }
        }
    });
    let mut w: Box<dyn Write> = match output {
        Some(p) => Box::new(BufWriter::new(
            std::fs::File::create(p).map_err(|e| format!("{}: {e}", p.display()))?,
        )),
        None => Box::new(BufWriter::new(std::io::stdout())),
    };
    write_header(&mut w, vfmt).map_err(|e| e.to_string())?;
    let n = run_engine(
        engine,
        fmt,
        tests,
        &out.join("verilator"),
        vcd,
        |tag, r, o| {
            write_result(
                &mut w,
                vfmt,
                tag,
                o.hit,
                r.t_world_f64(&fmt, o.t_entry),
                r.t_world_f64(&fmt, o.t_exit),
            )
            .map_err(|e| e.to_string())
        },
    )?;
    w.flush().map_err(|e| e.to_string())?;
    if let Some(e) = failure.lock().unwrap().take() {
        return Err(e);
    }
    eprintln!(
        "rtu run: {n} vectors through the {engine:?} engine, format {}, grid cell {}",
        fmt.name(),
        golden::fixed::ldexp(1.0, map.k)
    );
    Ok(())
}

/// Writes `n` generated vectors over the campaign bounds.
pub fn gen(kind: GenKind, n: u64, seed: u64, output: Option<&Path>) -> Result<(), String> {
    let (lo, hi) = tb::campaign::campaign_bounds();
    let vfmt = output
        .map(VecFormat::from_path)
        .unwrap_or(VecFormat::JsonLines);
    let mut w: Box<dyn Write> = match output {
        Some(p) => Box::new(BufWriter::new(
            std::fs::File::create(p).map_err(|e| format!("{}: {e}", p.display()))?,
        )),
        None => Box::new(BufWriter::new(std::io::stdout())),
    };
    if vfmt == VecFormat::Csv {
        writeln!(w, "{}", csv_vector_header()).map_err(|e| e.to_string())?;
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
            },
        )
        .map_err(|e| e.to_string())?;
    }
    w.flush().map_err(|e| e.to_string())
}
