//! Users' bundle vectors for the AllHit / AnyHit pair (`rtu run --bundles`): JSON lines in, JSON lines out.
//!
//! One object a line (blank lines and lines starting with `#` are skipped). A bundle is given by its rays,
//! by its bounds, or both (then every ray must lie in the bounds):
//! ```text
//! {"tag": 1, "rays": [{"origin": [0, 0, -5], "dir": [0.1, 0, 1], "t_max": "inf"}, ...],
//!  "box_min": [-1, -1, -1], "box_max": [1, 1, 1]}
//! {"tag": 2, "o_lo": [0, 0, -5], "o_hi": [0.5, 0, -5], "d_lo": [0, 0, 1], "d_hi": [0.1, 0.1, 1],
//!  "t_lo": 10, "t_hi": "inf", "box_min": [-1, -1, -1], "box_max": [1, 1, 1]}
//! ```
//! Rays start at their origin (`t_min = 0`); `t_max` defaults to `inf`, as does `t_hi` (`t_lo` to `t_hi`).
//! At most [`MAX_BUNDLE_RAYS`] rays. Every error names the line and the field.
//!
//! Results, one line per bundle in input order: `{"tag", "all_hit", "all_miss"}`, and for a bundle given
//! with rays the results processor's answer too: `"split"` (the pair decided nothing and the rays were
//! tested two per clock), `"hits"` (per ray: may hit the box; never false for a ray that hits) and
//! `"pair_cycles"`.

use crate::bundle::build::MAX_BUNDLE_RAYS;
use crate::bundle::edge::Bundle;
use crate::error::Error;
use crate::geom::{Aabb, Ray};
use crate::slab::vectors::{json_num, json_object, line_err, num_text, read_line};
use glam::DVec3;
use serde_json::{Map, Value};
use std::io::{BufRead, Write};

/// One input bundle: its tag, the bundle, its rays when given, and the box.
#[derive(Clone, Debug, PartialEq)]
pub struct BundleVector {
    pub tag: u64,
    pub bundle: Bundle,
    pub rays: Vec<Ray>,
    pub bx: Aabb,
}

fn vec3(
    src: &str,
    line: usize,
    obj: &Map<String, Value>,
    name: &str,
) -> Result<Option<DVec3>, Error> {
    let Some(v) = obj.get(name) else {
        return Ok(None);
    };
    let arr = v
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| line_err(src, line, name, "expected an array of three numbers"))?;
    let mut out = [0.0; 3];
    for (a, x) in arr.iter().enumerate() {
        out[a] = json_num(x).map_err(|why| line_err(src, line, &format!("{name}[{a}]"), why))?;
    }
    Ok(Some(DVec3::from(out)))
}

fn num(src: &str, line: usize, obj: &Map<String, Value>, name: &str) -> Result<Option<f64>, Error> {
    obj.get(name)
        .map(|x| json_num(x).map_err(|why| line_err(src, line, name, why)))
        .transpose()
}

fn relabel<'a>(src: &'a str, line: usize, field: &str) -> impl Fn(Error) -> Error + 'a {
    let field = field.to_string();
    move |e| match e {
        Error::BadValue { what, value, why } => line_err(
            src,
            line,
            &format!("{field}{what}"),
            format!("{value} is not allowed: {why}"),
        ),
        Error::Io(why) => line_err(src, line, &field, why),
        other => other,
    }
}

fn parse_line(src: &str, line: usize, text: &str, index: u64) -> Result<BundleVector, Error> {
    let (obj, tag) = json_object(src, line, text, index)?;
    let obj = &obj;
    const KEYS: [&str; 10] = [
        "tag", "rays", "box_min", "box_max", "o_lo", "o_hi", "d_lo", "d_hi", "t_lo", "t_hi",
    ];
    if let Some(k) = obj.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(line_err(src, line, k, crate::text::unknown_field(k, &KEYS)));
    }
    if !obj.contains_key("o_lo") {
        if let Some(k) = KEYS[5..].iter().find(|k| obj.contains_key(**k)) {
            return Err(line_err(
                src,
                line,
                k,
                "a bound without `o_lo`: give all of a bundle's bounds",
            ));
        }
    }
    let need = |name: &str| -> Result<DVec3, Error> {
        vec3(src, line, obj, name)?.ok_or_else(|| line_err(src, line, name, "missing"))
    };
    let bx = Aabb {
        min: need("box_min")?,
        max: need("box_max")?,
    };
    bx.validate().map_err(relabel(src, line, ""))?;
    let mut rays = vec![];
    if let Some(rs) = obj.get("rays") {
        let rs = rs
            .as_array()
            .ok_or_else(|| line_err(src, line, "rays", "expected an array of ray objects"))?;
        if rs.is_empty() || rs.len() > MAX_BUNDLE_RAYS {
            return Err(line_err(
                src,
                line,
                "rays",
                format!("{} rays: 1..={MAX_BUNDLE_RAYS} expected", rs.len()),
            ));
        }
        for (k, r) in rs.iter().enumerate() {
            let field = format!("rays[{k}]");
            let ro = r.as_object().ok_or_else(|| {
                line_err(
                    src,
                    line,
                    &field,
                    "expected {\"origin\", \"dir\", \"t_max\"}",
                )
            })?;
            if let Some(k) = ro
                .keys()
                .find(|k| !["origin", "dir", "t_max"].contains(&k.as_str()))
            {
                return Err(line_err(
                    src,
                    line,
                    &format!("{field}.{k}"),
                    crate::text::unknown_field(k, &["origin", "dir", "t_max"]),
                ));
            }
            let get = |name: &str| -> Result<DVec3, Error> {
                vec3(src, line, ro, name)
                    .map_err(|e| match e {
                        Error::BadLine { field: f, why, .. } => {
                            line_err(src, line, &format!("{field}.{f}"), why)
                        }
                        o => o,
                    })?
                    .ok_or_else(|| line_err(src, line, &format!("{field}.{name}"), "missing"))
            };
            let ray = Ray {
                origin: get("origin")?,
                dir: get("dir")?,
                t_min: 0.0,
                t_max: num(src, line, ro, "t_max")?.unwrap_or(f64::INFINITY),
            };
            ray.validate()
                .map_err(relabel(src, line, &format!("{field} ")))?;
            rays.push(ray);
        }
    }
    let bounds = match (vec3(src, line, obj, "o_lo")?, rays.is_empty()) {
        (None, true) => {
            return Err(line_err(
                src,
                line,
                "rays",
                "a bundle needs its rays or its bounds (o_lo, o_hi, d_lo, d_hi)",
            ))
        }
        (None, false) => None,
        (Some(o_lo), _) => {
            let t_hi = num(src, line, obj, "t_hi")?.unwrap_or(f64::INFINITY);
            let bound = |name: &str| -> Result<DVec3, Error> {
                vec3(src, line, obj, name)?.ok_or_else(|| {
                    line_err(
                        src,
                        line,
                        name,
                        "missing: a bundle's bounds are o_lo, o_hi, d_lo and d_hi, all four \
                         (t_lo and t_hi are optional); or give only its rays",
                    )
                })
            };
            Some(Bundle {
                o_lo: o_lo.into(),
                o_hi: bound("o_hi")?.into(),
                d_lo: bound("d_lo")?.into(),
                d_hi: bound("d_hi")?.into(),
                t_lo: num(src, line, obj, "t_lo")?.unwrap_or(t_hi),
                t_hi,
            })
        }
    };
    let bundle = match bounds {
        Some(b) => {
            b.validate().map_err(relabel(src, line, ""))?;
            if let Some(k) = rays.iter().position(|r| !b.contains(r)) {
                return Err(line_err(
                    src,
                    line,
                    &format!("rays[{k}]"),
                    "the ray is not inside the bundle's bounds",
                ));
            }
            b
        }
        None => Bundle::around(&rays).map_err(relabel(src, line, "rays "))?,
    };
    Ok(BundleVector {
        tag,
        bundle,
        rays,
        bx,
    })
}

/// Streams bundle vectors from a reader; each item is a vector or an error naming the line and field.
pub fn read_bundles<'a, R: BufRead + Send + 'a>(
    reader: R,
    src: impl Into<String>,
) -> Box<dyn Iterator<Item = Result<BundleVector, Error>> + Send + 'a> {
    Box::new(read_numbered_bundles(reader, src).map(|r| r.map(|(_, v)| v)))
}

/// [`read_bundles`] with each bundle's line number (1-based), for errors found after reading.
pub fn read_numbered_bundles<'a, R: BufRead + Send + 'a>(
    reader: R,
    src: impl Into<String>,
) -> Box<dyn Iterator<Item = Result<(usize, BundleVector), Error>> + Send + 'a> {
    let src: String = src.into();
    let mut index = 0u64;
    Box::new(reader.lines().enumerate().filter_map(move |(n, l)| {
        let line = n + 1;
        let text = match read_line(&src, line, l) {
            Ok(t) => t,
            Err(e) => return Some(Err(e)),
        };
        let t = text.trim();
        if t.is_empty() || t.starts_with('#') {
            return None;
        }
        let r = parse_line(&src, line, t, index).map(|v| (line, v));
        index += 1;
        Some(r)
    }))
}

/// What the pair (and, for a bundle with rays, the results processor) said of one bundle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BundleResult {
    pub all_hit: bool,
    pub all_miss: bool,
    /// For a bundle given with rays: `(split, per-ray may-hit, pair cycles)`.
    pub rays: Option<(bool, Vec<bool>, u32)>,
}

/// Writes one result line.
pub fn write_bundle_result<W: Write>(w: &mut W, tag: u64, r: &BundleResult) -> std::io::Result<()> {
    write!(
        w,
        "{{\"tag\":{tag},\"all_hit\":{},\"all_miss\":{}",
        r.all_hit, r.all_miss
    )?;
    if let Some((split, hits, cycles)) = &r.rays {
        let h: Vec<&str> = hits
            .iter()
            .map(|&b| if b { "true" } else { "false" })
            .collect();
        write!(
            w,
            ",\"split\":{split},\"hits\":[{}],\"pair_cycles\":{cycles}",
            h.join(",")
        )?;
    }
    writeln!(w, "}}")
}

/// Writes one bundle vector in the input format (with its rays when it has them, else its bounds).
pub fn write_bundle_vector<W: Write>(w: &mut W, v: &BundleVector) -> std::io::Result<()> {
    let v3 = |p: DVec3| format!("[{:?},{:?},{:?}]", p.x, p.y, p.z);
    let a3 = |p: [f64; 3]| v3(DVec3::from(p));
    write!(w, "{{\"tag\":{}", v.tag)?;
    if v.rays.is_empty() {
        let b = &v.bundle;
        write!(
            w,
            ",\"o_lo\":{},\"o_hi\":{},\"d_lo\":{},\"d_hi\":{},\"t_lo\":{},\"t_hi\":{}",
            a3(b.o_lo),
            a3(b.o_hi),
            a3(b.d_lo),
            a3(b.d_hi),
            num_text(b.t_lo, true),
            num_text(b.t_hi, true)
        )?;
    } else {
        let rs: Vec<String> = v
            .rays
            .iter()
            .map(|r| {
                format!(
                    "{{\"origin\":{},\"dir\":{},\"t_max\":{}}}",
                    v3(r.origin),
                    v3(r.dir),
                    num_text(r.t_max, true)
                )
            })
            .collect();
        write!(w, ",\"rays\":[{}]", rs.join(","))?;
    }
    writeln!(
        w,
        ",\"box_min\":{},\"box_max\":{}}}",
        v3(v.bx.min),
        v3(v.bx.max)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bundle::gen::BundleGen;

    fn read(text: &str) -> Vec<Result<BundleVector, Error>> {
        read_bundles(std::io::Cursor::new(text.to_string()), "in.jsonl").collect()
    }

    #[test]
    fn generated_bundles_round_trip() {
        let mut g = BundleGen::new(3, DVec3::splat(-10.0), DVec3::splat(10.0), 0.5);
        let mut buf = vec![];
        let mut want = vec![];
        for tag in 0..500u64 {
            let c = g.next_case();
            let v = BundleVector {
                tag,
                bundle: if tag % 2 == 0 {
                    Bundle::around(&c.rays).unwrap()
                } else {
                    c.bundle
                },
                rays: if tag % 2 == 0 { c.rays.clone() } else { vec![] },
                bx: c.bounds,
            };
            write_bundle_vector(&mut buf, &v).unwrap();
            want.push(v);
        }
        let got: Vec<BundleVector> = read(&String::from_utf8(buf).unwrap())
            .into_iter()
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(got.len(), want.len());
        for (g, w) in got.iter().zip(&want) {
            assert_eq!(g, w);
        }
    }

    #[test]
    fn bad_lines_name_line_and_field() {
        let cases = [
            ("{\"box_min\":[0,0,0],\"box_max\":[1,1,1]}", "rays"),
            ("{\"rays\":[],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}", "rays"),
            ("{\"rays\":[{\"origin\":[0,0,0]}],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}", "rays[0].dir"),
            (
                "{\"rays\":[{\"origin\":[0,\"nan\",0],\"dir\":[1,0,0]}],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}",
                "rays[0] ray origin",
            ),
            ("{\"rays\":[{\"origin\":[0,0,0],\"dir\":[1,0,0]}],\"box_min\":[0,0],\"box_max\":[1,1,1]}", "box_min"),
            (
                "{\"o_lo\":[0,0,0],\"o_hi\":[1,1,1],\"d_lo\":[1,0,0],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}",
                "d_hi",
            ),
            (
                "{\"o_lo\":[0,0,0],\"o_hi\":[0,0,0],\"d_lo\":[1,0,0],\"d_hi\":[1,0,0],\"rays\":[{\"origin\":[2,0,0],\"dir\":[1,0,0]}],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}",
                "rays[0]",
            ),
            ("not json", "(line)"),
            ("{\"rays\":[{\"origin\":[0,0,0],\"dir\":[1,0,0]}],\"t_mx\":1,\"box_min\":[0,0,0],\"box_max\":[1,1,1]}", "t_mx"),
            ("{\"rays\":[{\"origin\":[0,0,0],\"dir\":[1,0,0],\"tmax\":1}],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}", "rays[0].tmax"),
            ("{\"rays\":[{\"origin\":[0,0,0],\"dir\":[1,0,0]}],\"t_hi\":1,\"box_min\":[0,0,0],\"box_max\":[1,1,1]}", "t_hi"),
            ("{\"rays\":[{\"origin\":[0,0,0],\"dir\":[1,1e-400,0]}],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}", "dir`: `1e-400` underflows"),
            ("{\"rays\":[{\"origin\":[0,0,0],\"dir\":[1,0,0]}],\"o_lo\":[0,0,0],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}", "o_hi`: missing: a bundle's bounds are o_lo, o_hi, d_lo and d_hi"),
        ];
        for (text, field) in cases {
            let r = read(&format!("# comment\n\n{text}\n"));
            let e = r[0].as_ref().unwrap_err().to_string();
            assert!(e.starts_with("in.jsonl:3:"), "{e}");
            assert!(e.contains(&format!("field `{field}")), "{text}: {e}");
        }
    }

    #[test]
    fn a_byte_order_mark_is_read_past() {
        let line = "{\"rays\":[{\"origin\":[0,0,-5],\"dir\":[0,0,1]}],\"box_min\":[0,0,0],\"box_max\":[1,1,1]}\n";
        let plain = read(line);
        assert!(plain[0].is_ok());
        assert_eq!(read(&format!("\u{feff}{line}")), plain);
    }

    #[test]
    fn results_are_json_with_per_ray_hits() {
        let mut buf = vec![];
        write_bundle_result(
            &mut buf,
            7,
            &BundleResult {
                all_hit: false,
                all_miss: false,
                rays: Some((true, vec![true, false], 2)),
            },
        )
        .unwrap();
        let v: Value = serde_json::from_slice(&buf).unwrap();
        assert_eq!(v["tag"], 7);
        assert_eq!(v["hits"], serde_json::json!([true, false]));
        assert_eq!(v["pair_cycles"], 2);
        assert_eq!(v["split"], true);
    }
}
