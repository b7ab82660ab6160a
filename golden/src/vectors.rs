//! Reading users' slab vectors (JSON lines or CSV) and writing results in the same format.
//!
//! JSON lines, one object a line (blank lines and lines starting with `#` are skipped):
//! ```text
//! {"tag": 1, "origin": [0, 0, -5], "dir": [0, 0, 1], "t_min": 0, "t_max": "inf",
//!  "box_min": [-1, -1, -1], "box_max": [1, 1, 1]}
//! ```
//! CSV with this header (any column order):
//! `tag,ox,oy,oz,dx,dy,dz,t_min,t_max,min_x,min_y,min_z,max_x,max_y,max_z`.
//!
//! Numbers may be written `inf`, `-inf` (JSON: as strings) where the field allows it (`t_min`, `t_max`).
//! `tag` is optional and defaults to the vector's index. Every error names the line and the field.
//!
//! Results: JSON lines `{"tag", "hit", "t_entry", "t_exit"}` or CSV `tag,hit,t_entry,t_exit`, with t in
//! world units (exactly the datapath's t codes converted back; `inf`/`-inf` for the end codes).

use crate::error::Error;
use crate::geom::{Aabb, Ray};
use glam::DVec3;
use serde_json::Value;
use std::io::{BufRead, Write};

/// One input vector: a tagged ray and box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vector {
    pub tag: u64,
    pub ray: Ray,
    pub bx: Aabb,
}

/// File format of vectors and results.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VecFormat {
    JsonLines,
    Csv,
}

impl VecFormat {
    /// From a file name: `.csv` is CSV, anything else JSON lines.
    pub fn from_path(p: &std::path::Path) -> Self {
        match p.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("csv") => VecFormat::Csv,
            _ => VecFormat::JsonLines,
        }
    }
}

const CSV_FIELDS: [&str; 15] = [
    "tag", "ox", "oy", "oz", "dx", "dy", "dz", "t_min", "t_max", "min_x", "min_y", "min_z",
    "max_x", "max_y", "max_z",
];

fn line_err(src: &str, line: usize, field: &str, why: impl Into<String>) -> Error {
    Error::BadLine {
        source_name: src.into(),
        line,
        field: field.into(),
        why: why.into(),
    }
}

fn parse_num(s: &str) -> Option<f64> {
    match s.trim() {
        "inf" | "+inf" | "Infinity" => Some(f64::INFINITY),
        "-inf" | "-Infinity" => Some(f64::NEG_INFINITY),
        t => t.parse::<f64>().ok(),
    }
}

fn json_num(v: &Value) -> Option<f64> {
    match v {
        Value::Number(n) => n.as_f64(),
        Value::String(s) => parse_num(s),
        _ => None,
    }
}

/// Builds and validates the vector; a validation error is re-labelled with the line and field.
fn build(src: &str, line: usize, tag: u64, f: &[f64; 14]) -> Result<Vector, Error> {
    let ray = Ray {
        origin: DVec3::new(f[0], f[1], f[2]),
        dir: DVec3::new(f[3], f[4], f[5]),
        t_min: f[6],
        t_max: f[7],
    };
    let bx = Aabb {
        min: DVec3::new(f[8], f[9], f[10]),
        max: DVec3::new(f[11], f[12], f[13]),
    };
    let relabel = |e: Error| match e {
        Error::BadValue { what, value, why } => {
            line_err(src, line, &what, format!("{value} is not allowed: {why}"))
        }
        other => other,
    };
    ray.validate().map_err(relabel)?;
    bx.validate().map_err(relabel)?;
    Ok(Vector { tag, ray, bx })
}

fn parse_json_line(src: &str, line: usize, text: &str, index: u64) -> Result<Vector, Error> {
    let v: Value = serde_json::from_str(text)
        .map_err(|e| line_err(src, line, "(line)", format!("not JSON: {e}")))?;
    let obj = v
        .as_object()
        .ok_or_else(|| line_err(src, line, "(line)", "expected a JSON object"))?;
    let tag = match obj.get("tag") {
        None => index,
        Some(t) => t.as_u64().ok_or_else(|| {
            line_err(
                src,
                line,
                "tag",
                format!("`{t}` is not a non-negative integer"),
            )
        })?,
    };
    let mut f = [0.0; 14];
    for (name, base) in [("origin", 0), ("dir", 3), ("box_min", 8), ("box_max", 11)].iter() {
        let arr = obj
            .get(*name)
            .ok_or_else(|| line_err(src, line, name, "missing"))?
            .as_array()
            .ok_or_else(|| line_err(src, line, name, "expected an array of three numbers"))?;
        if arr.len() != 3 {
            return Err(line_err(
                src,
                line,
                name,
                format!("expected three numbers, found {}", arr.len()),
            ));
        }
        for (a, x) in arr.iter().enumerate() {
            f[base + a] = json_num(x).ok_or_else(|| {
                line_err(
                    src,
                    line,
                    &format!("{name}[{a}]"),
                    format!("`{x}` is not a number"),
                )
            })?;
        }
    }
    for (name, idx, default) in [("t_min", 6, 0.0), ("t_max", 7, f64::INFINITY)] {
        f[idx] = match obj.get(name) {
            None => default,
            Some(x) => json_num(x)
                .ok_or_else(|| line_err(src, line, name, format!("`{x}` is not a number")))?,
        };
    }
    build(src, line, tag, &f)
}

/// Streams vectors from a reader. Each item is a vector or an error naming the line and field.
pub fn read_vectors<'a, R: BufRead + Send + 'a>(
    reader: R,
    fmt: VecFormat,
    src: impl Into<String>,
) -> Box<dyn Iterator<Item = Result<Vector, Error>> + Send + 'a> {
    let src: String = src.into();
    match fmt {
        VecFormat::JsonLines => {
            let mut index = 0u64;
            Box::new(reader.lines().enumerate().filter_map(move |(n, l)| {
                let line = n + 1;
                let src = src.as_str();
                let text = match l {
                    Ok(t) => t,
                    Err(e) => return Some(Err(Error::Io(format!("{src}:{line}: {e}")))),
                };
                let t = text.trim();
                if t.is_empty() || t.starts_with('#') {
                    return None;
                }
                let r = parse_json_line(src, line, t, index);
                index += 1;
                Some(r)
            }))
        }
        VecFormat::Csv => {
            let mut rdr = csv::ReaderBuilder::new()
                .comment(Some(b'#'))
                .trim(csv::Trim::All)
                .from_reader(reader);
            let header: Result<Vec<String>, Error> = rdr
                .headers()
                .map(|h| h.iter().map(|s| s.to_string()).collect())
                .map_err(|e| Error::Io(format!("{src}: cannot read the CSV header: {e}")));
            let src_h = src.clone();
            let cols = header.and_then(|h| {
                let mut cols = [usize::MAX; 15];
                for (k, name) in CSV_FIELDS.iter().enumerate() {
                    match h.iter().position(|c| c == name) {
                        Some(i) => cols[k] = i,
                        None if *name == "tag" => {}
                        None => {
                            return Err(line_err(&src_h, 1, name, "column missing from the header"))
                        }
                    }
                }
                Ok(cols)
            });
            let cols = match cols {
                Ok(c) => c,
                Err(e) => return Box::new(std::iter::once(Err(e))),
            };
            let mut index = 0u64;
            Box::new(rdr.into_records().map(move |rec| {
                let src = src.as_str();
                let rec = rec.map_err(|e| Error::Io(format!("{src}: {e}")))?;
                let line = rec.position().map(|p| p.line() as usize).unwrap_or(0);
                let get = |k: usize| {
                    rec.get(cols[k])
                        .ok_or_else(|| line_err(src, line, CSV_FIELDS[k], "missing"))
                };
                let tag = if cols[0] == usize::MAX {
                    index
                } else {
                    let t = get(0)?;
                    t.parse::<u64>().map_err(|_| {
                        line_err(
                            src,
                            line,
                            "tag",
                            format!("`{t}` is not a non-negative integer"),
                        )
                    })?
                };
                index += 1;
                let mut f = [0.0; 14];
                for k in 1..15 {
                    let s = get(k)?;
                    f[k - 1] = parse_num(s).ok_or_else(|| {
                        line_err(src, line, CSV_FIELDS[k], format!("`{s}` is not a number"))
                    })?;
                }
                build(src, line, tag, &f)
            }))
        }
    }
}

fn num_text(x: f64, json: bool) -> String {
    if x.is_infinite() {
        let s = if x > 0.0 { "inf" } else { "-inf" };
        if json {
            format!("\"{s}\"")
        } else {
            s.into()
        }
    } else {
        format!("{x:?}")
    }
}

/// Writes the header line of a results file (CSV only).
pub fn write_header<W: Write>(w: &mut W, fmt: VecFormat) -> std::io::Result<()> {
    if fmt == VecFormat::Csv {
        writeln!(w, "tag,hit,t_entry,t_exit")?;
    }
    Ok(())
}

/// Writes one result line.
pub fn write_result<W: Write>(
    w: &mut W,
    fmt: VecFormat,
    tag: u64,
    hit: bool,
    t_entry: f64,
    t_exit: f64,
) -> std::io::Result<()> {
    match fmt {
        VecFormat::JsonLines => writeln!(
            w,
            "{{\"tag\":{tag},\"hit\":{hit},\"t_entry\":{},\"t_exit\":{}}}",
            num_text(t_entry, true),
            num_text(t_exit, true)
        ),
        VecFormat::Csv => writeln!(
            w,
            "{tag},{},{},{}",
            u8::from(hit),
            num_text(t_entry, false),
            num_text(t_exit, false)
        ),
    }
}

/// Writes one input vector (used to export generated vectors and the default scene).
pub fn write_vector<W: Write>(w: &mut W, fmt: VecFormat, v: &Vector) -> std::io::Result<()> {
    let (r, b) = (&v.ray, &v.bx);
    match fmt {
        VecFormat::JsonLines => {
            let a = |p: DVec3| format!("[{:?},{:?},{:?}]", p.x, p.y, p.z);
            writeln!(
                w,
                "{{\"tag\":{},\"origin\":{},\"dir\":{},\"t_min\":{},\"t_max\":{},\"box_min\":{},\"box_max\":{}}}",
                v.tag,
                a(r.origin),
                a(r.dir),
                num_text(r.t_min, true),
                num_text(r.t_max, true),
                a(b.min),
                a(b.max)
            )
        }
        VecFormat::Csv => {
            let a = |p: DVec3| format!("{:?},{:?},{:?}", p.x, p.y, p.z);
            writeln!(
                w,
                "{},{},{},{},{},{},{}",
                v.tag,
                a(r.origin),
                a(r.dir),
                num_text(r.t_min, false),
                num_text(r.t_max, false),
                a(b.min),
                a(b.max)
            )
        }
    }
}

/// The CSV header of vector files.
pub fn csv_vector_header() -> String {
    CSV_FIELDS.join(",")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(fmt: VecFormat, text: &str) -> Vec<Result<Vector, Error>> {
        read_vectors(std::io::Cursor::new(text.to_string()), fmt, "test").collect()
    }

    #[test]
    fn json_round_trip() {
        let v = Vector {
            tag: 9,
            ray: Ray::new(DVec3::new(0.1, -2.0, 3.0), DVec3::Z, 0.0, f64::INFINITY).unwrap(),
            bx: Aabb::new(DVec3::splat(-1.0), DVec3::ONE).unwrap(),
        };
        for fmt in [VecFormat::JsonLines, VecFormat::Csv] {
            let mut buf = Vec::new();
            if fmt == VecFormat::Csv {
                writeln!(buf, "{}", csv_vector_header()).unwrap();
            }
            write_vector(&mut buf, fmt, &v).unwrap();
            let got = read(fmt, std::str::from_utf8(&buf).unwrap());
            assert_eq!(got, vec![Ok(v)], "{fmt:?}");
        }
    }

    #[test]
    fn malformed_json_names_line_and_field() {
        let text = "# comment\n{\"origin\":[0,0,0],\"dir\":[0,0,1],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}\n\
                    {\"origin\":[0,\"x\",0],\"dir\":[0,0,1],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}\n";
        let got = read(VecFormat::JsonLines, text);
        assert!(got[0].is_ok());
        let e = got[1].clone().unwrap_err().to_string();
        assert!(e.contains("test:3") && e.contains("origin[1]"), "{e}");
    }

    #[test]
    fn nan_in_csv_names_line_and_field() {
        let text = format!(
            "{}\n1,0,0,0,0,0,1,0,inf,0,0,0,1,nan,1\n",
            csv_vector_header()
        );
        let e = read(VecFormat::Csv, &text)[0]
            .clone()
            .unwrap_err()
            .to_string();
        assert!(e.contains("test:2") && e.contains("box max.y"), "{e}");
    }

    #[test]
    fn missing_csv_column_is_named() {
        let e = read(VecFormat::Csv, "tag,ox,oy\n1,2,3\n")[0]
            .clone()
            .unwrap_err()
            .to_string();
        assert!(e.contains("oz") && e.contains("missing"), "{e}");
    }
}
