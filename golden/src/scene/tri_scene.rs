//! Triangle scenes: seeded procedural scenes, OBJ input, and the rays shot into them.
//!
//! Every procedural scene is a function of its seed and size only (`rand_pcg::Pcg64`, IEEE f64, no
//! platform maths beyond `sin`/`cos`/`sqrt` of the standard library), so the same seed gives the same
//! scene on every machine this project runs on:
//!
//! | scene | what | default size |
//! | --- | --- | --- |
//! | [`room`] | a closed room (floor, ceiling, walls: 12 big triangles) with boxes, some rotated about the vertical | 150 boxes, 1,812 triangles |
//! | [`grass`] | a ground quad and a field of long, very thin blades leaning at random angles: the case cull planes target (a thin diagonal triangle leaves most of its box empty) | 3,000 blades, 3,002 triangles |
//! | [`mesh`] | a closed torus, tessellated `2n x n` and rotated at random | n = 28, 3,136 triangles |
//! | [`soup`] | random triangles of random size and orientation | 2,000 triangles |
//!
//! Rays: [`primary_rays`] from a pinhole camera, and [`secondary_rays`] from the primary hits: one bounce
//! ray (cosine-weighted about the surface normal, Malley's method: Pharr, Jakob and Humphreys,
//! *Physically Based Rendering*, 3rd ed., §13.6.3) and one shadow ray toward the scene's point light
//! (`t_max` = the distance to the light). Both start a small distance off the surface along the normal
//! on the side the primary ray came from, so they cannot hit the surface they leave.
//!
//! OBJ input ([`load_obj`], [`parse_obj`]): the Wavefront OBJ format (Wavefront Technologies, *Advanced
//! Visualizer* manual, Appendix B1, "Object Files"): `v x y z [w]` vertices and `f` faces whose vertex
//! references are `i`, `i/t`, `i//n` or `i/t/n`, 1-based or negative (relative to the vertices read so
//! far). Faces with more than three vertices are split into a fan. The format's other statements
//! ([`OBJ_SKIPPED`]: texture and normal vertices, groups, materials, lines, curves, ...) are skipped; a
//! statement the format does not have is an error (a typo such as `fx` would otherwise drop a face
//! silently). A vertex may carry `w` or an `r g b` colour after its coordinates (both ignored; every
//! number still checked). Numbers follow [`crate::text`]: one that underflows or overflows f64 is an
//! error. Errors name the file, the line and what is wrong.

use crate::error::Error;
use crate::geom::{Aabb, Ray};
use crate::scene::tri::{random_unit, Triangle};
use glam::DVec3;
use num_rational::BigRational;
use num_traits::ToPrimitive;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::f64::consts::PI;
use std::path::Path;

/// A pinhole camera: eye, the point looked at, the up direction and the vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: DVec3,
    pub look_at: DVec3,
    pub up: DVec3,
    pub fov_deg: f64,
}

/// A triangle scene with its camera and one point light.
#[derive(Clone, Debug, PartialEq)]
pub struct TriScene {
    pub name: String,
    pub tris: Vec<Triangle>,
    pub camera: Camera,
    pub light: DVec3,
    /// For a scene read from OBJ, the line of the `f` statement each triangle comes from (a polygon
    /// gives several, fanned from its first vertex); empty for the built-in scenes.
    pub face_lines: Vec<usize>,
}

impl TriScene {
    /// The exact bounds of every vertex (an empty box for no triangles).
    pub fn bounds(&self) -> Aabb {
        let mut b = Aabb {
            min: DVec3::splat(f64::INFINITY),
            max: DVec3::splat(f64::NEG_INFINITY),
        };
        for t in &self.tris {
            let (lo, hi) = t.min_max();
            b.min = b.min.min(lo);
            b.max = b.max.max(hi);
        }
        b
    }

    /// The world region a fixed-point grid over this scene covers: the scene's bounds grown by half their
    /// size on every side (plus 1e-3), and the camera, so that secondary rays' origins and every box fit.
    pub fn grid_bounds(&self) -> (DVec3, DVec3) {
        let b = self.bounds();
        let ext = (b.max - b.min) * 0.5 + DVec3::splat(1e-3);
        (
            (b.min - ext).min(self.camera.eye),
            (b.max + ext).max(self.camera.eye),
        )
    }
}

/// The scene names [`by_name`] knows.
pub const SCENES: [&str; 4] = ["room", "grass", "mesh", "soup"];

/// A procedural scene by name, with its size parameter (`None`: the default of the table above).
pub fn by_name(name: &str, seed: u64, size: Option<usize>) -> Result<TriScene, Error> {
    let check = |s: usize, max: usize| {
        if s == 0 || s > max {
            Err(Error::BadFormat {
                param: "scene size",
                value: s as i64,
                why: format!("scene `{name}` takes a size in 1..={max}"),
            })
        } else {
            Ok(s)
        }
    };
    match name {
        "room" => Ok(room(seed, check(size.unwrap_or(150), 100_000)?)),
        "grass" => Ok(grass(seed, check(size.unwrap_or(3000), 1_000_000)?)),
        "mesh" => Ok(mesh(seed, check(size.unwrap_or(28), 2000)?.max(3))),
        "soup" => Ok(soup(seed, check(size.unwrap_or(2000), 1_000_000)?)),
        _ => Err(Error::Io(format!(
            "unknown scene `{name}`: expected one of {}",
            SCENES.join(", ")
        ))),
    }
}

fn quad(out: &mut Vec<Triangle>, a: DVec3, b: DVec3, c: DVec3, d: DVec3) {
    out.push(Triangle::new(a, b, c));
    out.push(Triangle::new(a, c, d));
}

/// The 12 triangles of a box with centre `c`, half extents `h`, rotated by `yaw` radians about +y.
fn box_tris(out: &mut Vec<Triangle>, c: DVec3, h: DVec3, yaw: f64) {
    let (s, co) = yaw.sin_cos();
    let corner = |i: usize| {
        let l = DVec3::new(
            if i & 1 == 0 { -h.x } else { h.x },
            if i & 2 == 0 { -h.y } else { h.y },
            if i & 4 == 0 { -h.z } else { h.z },
        );
        c + DVec3::new(co * l.x + s * l.z, l.y, -s * l.x + co * l.z)
    };
    let p: Vec<DVec3> = (0..8).map(corner).collect();
    // Faces as corner-index quads.
    for f in [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ] {
        quad(out, p[f[0]], p[f[1]], p[f[2]], p[f[3]]);
    }
}

/// A closed room 24 x 8 x 24 with `boxes` boxes (crates and pillars, half of them rotated).
pub fn room(seed: u64, boxes: usize) -> TriScene {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut tris = Vec::with_capacity(12 + 12 * boxes);
    let (lo, hi) = (DVec3::new(-12.0, 0.0, -12.0), DVec3::new(12.0, 8.0, 12.0));
    box_tris(&mut tris, (lo + hi) * 0.5, (hi - lo) * 0.5, 0.0);
    for i in 0..boxes {
        let pillar = i % 10 == 0;
        let h = if pillar {
            DVec3::new(0.3, 4.0, 0.3)
        } else {
            DVec3::new(
                rng.gen_range(0.15..1.0),
                rng.gen_range(0.1..1.0),
                rng.gen_range(0.15..1.0),
            )
        };
        let c = DVec3::new(
            rng.gen_range(-10.5..10.5),
            h.y + if pillar || rng.gen_bool(0.7) {
                0.0
            } else {
                rng.gen_range(0.0..3.0)
            },
            rng.gen_range(-10.5..10.5),
        );
        let yaw = if rng.gen_bool(0.5) {
            rng.gen_range(0.0..PI / 2.0)
        } else {
            0.0
        };
        box_tris(&mut tris, c, h, yaw);
    }
    TriScene {
        name: "room".into(),
        tris,
        camera: Camera {
            eye: DVec3::new(0.0, 4.0, 11.0),
            look_at: DVec3::new(0.0, 1.0, 0.0),
            up: DVec3::Y,
            fov_deg: 70.0,
        },
        light: DVec3::new(2.0, 7.5, 3.0),
        face_lines: Vec::new(),
    }
}

/// A 24 x 24 ground quad and `blades` grass blades: each one triangle 2 to 4.5 units long and 0.01 to
/// 0.04 wide at the base, leaning 10 to 60 degrees from vertical in a random direction and twisted at
/// random about its own axis.
pub fn grass(seed: u64, blades: usize) -> TriScene {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut tris = Vec::with_capacity(2 + blades);
    quad(
        &mut tris,
        DVec3::new(-12.0, 0.0, -12.0),
        DVec3::new(-12.0, 0.0, 12.0),
        DVec3::new(12.0, 0.0, 12.0),
        DVec3::new(12.0, 0.0, -12.0),
    );
    for _ in 0..blades {
        let base = DVec3::new(rng.gen_range(-10.0..10.0), 0.0, rng.gen_range(-10.0..10.0));
        let len = rng.gen_range(2.0..4.5);
        let tilt = rng.gen_range(10.0f64..60.0).to_radians();
        let az = rng.gen_range(0.0..2.0 * PI);
        let axis = DVec3::new(tilt.sin() * az.cos(), tilt.cos(), tilt.sin() * az.sin());
        // A unit vector across the blade: perpendicular to the axis, twisted at random.
        let h = DVec3::new(-az.sin(), 0.0, az.cos());
        let k = axis.cross(h);
        let tw = rng.gen_range(0.0..PI);
        let across = h * tw.cos() + k * tw.sin();
        let w = rng.gen_range(0.01..0.04) * 0.5;
        tris.push(Triangle::new(
            base - across * w,
            base + across * w,
            base + axis * len,
        ));
    }
    TriScene {
        name: "grass".into(),
        tris,
        camera: Camera {
            eye: DVec3::new(0.0, 6.0, 16.0),
            look_at: DVec3::new(0.0, 1.0, 0.0),
            up: DVec3::Y,
            fov_deg: 60.0,
        },
        light: DVec3::new(-5.0, 20.0, 8.0),
        face_lines: Vec::new(),
    }
}

/// A closed torus (major radius 4, minor 1.5) of `2n x n` quads (`4 n^2` triangles), rotated at random.
/// Shared vertices are bit-identical, so the mesh has no cracks.
pub fn mesh(seed: u64, n: usize) -> TriScene {
    let mut rng = Pcg64::seed_from_u64(seed);
    let axis = random_unit(&mut rng);
    let angle = rng.gen_range(0.0..PI);
    let rot = glam::DQuat::from_axis_angle(axis, angle);
    let (nu, nv) = (2 * n, n);
    let (big, small) = (4.0, 1.5);
    let mut p = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let a = 2.0 * PI * i as f64 / nu as f64;
        for j in 0..nv {
            let b = 2.0 * PI * j as f64 / nv as f64;
            let r = big + small * b.cos();
            p.push(rot * DVec3::new(r * a.cos(), small * b.sin(), r * a.sin()));
        }
    }
    let at = |i: usize, j: usize| p[(i % nu) * nv + (j % nv)];
    let mut tris = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            quad(
                &mut tris,
                at(i, j),
                at(i + 1, j),
                at(i + 1, j + 1),
                at(i, j + 1),
            );
        }
    }
    TriScene {
        name: "mesh".into(),
        tris,
        camera: Camera {
            eye: DVec3::new(0.0, 3.0, 14.0),
            look_at: DVec3::ZERO,
            up: DVec3::Y,
            fov_deg: 50.0,
        },
        light: DVec3::new(6.0, 10.0, 10.0),
        face_lines: Vec::new(),
    }
}

/// `n` random triangles in the cube `[-10, 10]^3`, vertices up to 1.5 from their centre.
pub fn soup(seed: u64, n: usize) -> TriScene {
    let mut rng = Pcg64::seed_from_u64(seed);
    let tris = (0..n)
        .map(|_| {
            crate::scene::tri::random_triangle(
                &mut rng,
                DVec3::splat(-10.0),
                DVec3::splat(10.0),
                1.5,
            )
        })
        .collect();
    TriScene {
        name: "soup".into(),
        tris,
        camera: Camera {
            eye: DVec3::new(0.0, 0.0, 25.0),
            look_at: DVec3::ZERO,
            up: DVec3::Y,
            fov_deg: 55.0,
        },
        light: DVec3::new(15.0, 20.0, 20.0),
        face_lines: Vec::new(),
    }
}

/// One ray per pixel centre of a `w x h` image, row by row from the top left; unit directions,
/// `t` in `[0, inf)`.
pub fn primary_rays(scene: &TriScene, w: usize, h: usize) -> Vec<Ray> {
    let cam = &scene.camera;
    let fwd = (cam.look_at - cam.eye).normalize();
    let right = fwd.cross(cam.up).normalize();
    let up = right.cross(fwd);
    let th = (cam.fov_deg.to_radians() * 0.5).tan();
    let aspect = w as f64 / h.max(1) as f64;
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let sx = ((x as f64 + 0.5) / w as f64 * 2.0 - 1.0) * th * aspect;
            let sy = (1.0 - (y as f64 + 0.5) / h as f64 * 2.0) * th;
            let dir = (fwd + right * sx + up * sy).normalize();
            out.push(Ray {
                origin: cam.eye,
                dir,
                t_min: 0.0,
                t_max: f64::INFINITY,
            });
        }
    }
    out
}

/// Bounce and shadow rays from primary hits.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SecondaryRays {
    /// One per hit, cosine-weighted about the normal, `t` in `[0, inf)`.
    pub bounce: Vec<Ray>,
    /// One per hit whose surface faces the light: toward the light, `t_max` = distance to it.
    pub shadow: Vec<Ray>,
}

/// Secondary rays from the hits of `primaries` (`hits[i]`: the triangle and exact `t` of ray `i`, as
/// returned by [`crate::scene::traverse::closest_hit`]). The hit point is computed in f64 and moved off the
/// surface by `1e-7` of the scene's diagonal along the normal, on the primary ray's side.
pub fn secondary_rays(
    scene: &TriScene,
    primaries: &[Ray],
    hits: &[Option<(usize, BigRational)>],
    seed: u64,
) -> SecondaryRays {
    secondary_rays_offset(scene, primaries, hits, seed, 1e-7)
}

/// [`secondary_rays`] with the origins moved off the surface by `offset` of the scene's diagonal. A
/// tester that quantises the origin (a fixed grid, a short float) cannot tell an origin nearer the surface
/// than its resolution from the surface itself, so every box touching the surface near the origin is a
/// (conservative) hit for it: a renderer feeding such a unit offsets by at least its resolution.
pub fn secondary_rays_offset(
    scene: &TriScene,
    primaries: &[Ray],
    hits: &[Option<(usize, BigRational)>],
    seed: u64,
    offset: f64,
) -> SecondaryRays {
    let mut rng = Pcg64::seed_from_u64(seed);
    let b = scene.bounds();
    let eps = (b.max - b.min).length() * offset;
    let mut out = SecondaryRays::default();
    for (r, h) in primaries.iter().zip(hits) {
        let Some((ti, t)) = h else { continue };
        let Some(tri) = scene.tris.get(*ti) else {
            continue;
        };
        let n = tri.normal();
        if n == DVec3::ZERO || !n.is_finite() {
            continue;
        }
        let mut n = n.normalize();
        if n.dot(r.dir) > 0.0 {
            n = -n;
        }
        let t = t.to_f64().unwrap_or(0.0);
        let origin = r.origin + r.dir * t + n * eps;
        // Malley: a uniform point on the unit disc lifted to the hemisphere.
        let (s, k) = n.any_orthonormal_pair();
        let (rr, phi) = (rng.gen::<f64>().sqrt(), rng.gen_range(0.0..2.0 * PI));
        let (x, y) = (rr * phi.cos(), rr * phi.sin());
        let z = (1.0 - x * x - y * y).max(1e-12).sqrt();
        let dir = (s * x + k * y + n * z).normalize();
        out.bounce.push(Ray {
            origin,
            dir,
            t_min: 0.0,
            t_max: f64::INFINITY,
        });
        let to_light = scene.light - origin;
        let dist = to_light.length();
        if dist > 0.0 && to_light.dot(n) > 0.0 {
            out.shadow.push(Ray {
                origin,
                dir: to_light / dist,
                t_min: 0.0,
                t_max: dist,
            });
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------------
// OBJ input.

/// Reads an OBJ file (see the module doc). Errors name the file and, for content errors, the line.
pub fn load_obj(path: &Path) -> Result<TriScene, Error> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::Io(format!("{name}: cannot read the OBJ file: {e}")))?;
    parse_obj(&text, &name)
}

fn bad_line(src: &str, line: usize, field: impl Into<String>, why: impl Into<String>) -> Error {
    Error::BadLine {
        source_name: src.to_string(),
        line,
        field: field.into(),
        why: why.into(),
    }
}

/// The OBJ statements that [`parse_obj`] reads past: the Wavefront format's statements other than `v` and
/// `f` (vertex data, elements, free-form geometry, grouping, display and render attributes).
#[rustfmt::skip]
pub const OBJ_SKIPPED: [&str; 42] = [
    "vt", "vn", "vp", "cstype", "deg", "bmat", "step", "p", "l", "curv", "curv2", "surf", "parm", "trim",
    "hole", "scrv", "sp", "end", "con", "g", "s", "mg", "o", "bevel", "c_interp", "d_interp", "lod",
    "usemtl", "mtllib", "shadow_obj", "trace_obj", "ctech", "stech", "call", "csh", "maplib", "usemap",
    // Superseded by the statements above, still found in old files.
    "bsp", "bzp", "cdc", "cdp", "res",
];

/// Parses OBJ text; `source_name` names it in errors. The camera looks at the centre of the bounds
/// from the front (+z) and a little above; the light is above and to the right.
pub fn parse_obj(text: &str, source_name: &str) -> Result<TriScene, Error> {
    let mut verts: Vec<DVec3> = Vec::new();
    // (line, [resolved vertex indices]) per face, resolved once all vertices are read.
    let mut faces: Vec<(usize, Vec<(i64, usize)>)> = Vec::new();
    for (ln, raw) in crate::text::strip_bom(text).lines().enumerate() {
        let line_no = ln + 1;
        let line = raw.split('#').next().unwrap_or("").trim();
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let toks: Vec<&str> = it.collect();
                if ![3, 4, 6].contains(&toks.len()) {
                    return Err(bad_line(
                        source_name,
                        line_no,
                        "v",
                        format!(
                            "{} numbers: a vertex is `v x y z`, `v x y z w` or `v x y z r g b`",
                            toks.len()
                        ),
                    ));
                }
                let mut p = [0.0; 3];
                for (a, tok) in toks.iter().enumerate() {
                    let field = match (a, toks.len()) {
                        (0..=2, _) => format!("v {}", ["x", "y", "z"][a]),
                        (3, 4) => "v w".to_string(),
                        _ => format!("v {}", ["r", "g", "b"][a - 3]),
                    };
                    let x = crate::text::parse_f64(tok)
                        .map_err(|why| bad_line(source_name, line_no, &field, why))?;
                    if a < 3 {
                        p[a] = x;
                    }
                    if !x.is_finite() {
                        return Err(bad_line(
                            source_name,
                            line_no,
                            &field,
                            format!("`{tok}` is not finite; vertex numbers must be finite"),
                        ));
                    }
                }
                verts.push(DVec3::from_array(p));
            }
            Some("f") => {
                let mut refs = Vec::new();
                for tok in it {
                    let first = tok.split('/').next().unwrap_or("");
                    let i: i64 = first.parse().map_err(|_| {
                        bad_line(
                            source_name,
                            line_no,
                            "f",
                            format!("vertex reference `{tok}` is not an integer index"),
                        )
                    })?;
                    if i == 0 {
                        return Err(bad_line(
                            source_name,
                            line_no,
                            "f",
                            "vertex index 0: OBJ indices start at 1 (or are negative)",
                        ));
                    }
                    refs.push((i, verts.len()));
                }
                if refs.len() < 3 {
                    return Err(bad_line(
                        source_name,
                        line_no,
                        "f",
                        format!("a face needs at least 3 vertices, got {}", refs.len()),
                    ));
                }
                faces.push((line_no, refs));
            }
            Some(k) if OBJ_SKIPPED.contains(&k) => {}
            Some(k) => {
                return Err(bad_line(
                    source_name,
                    line_no,
                    k,
                    format!(
                        "not an OBJ statement (rtu reads `v` and `f` and skips {})",
                        OBJ_SKIPPED.join(", ")
                    ),
                ))
            }
            None => {}
        }
    }
    let mut tris = Vec::new();
    let mut face_lines = Vec::new();
    for (line_no, refs) in faces {
        let mut idx = Vec::with_capacity(refs.len());
        for (i, seen) in refs {
            let k = if i > 0 { i - 1 } else { seen as i64 + i };
            if k < 0 || k as usize >= verts.len() {
                return Err(bad_line(
                    source_name,
                    line_no,
                    "f",
                    format!(
                        "vertex index {i} is out of range ({} vertices{})",
                        if i > 0 { verts.len() } else { seen },
                        if i > 0 {
                            " in the file"
                        } else {
                            " before this line"
                        }
                    ),
                ));
            }
            idx.push(k as usize);
        }
        for j in 1..idx.len() - 1 {
            tris.push(Triangle::new(
                verts[idx[0]],
                verts[idx[j]],
                verts[idx[j + 1]],
            ));
            face_lines.push(line_no);
        }
    }
    if tris.is_empty() {
        return Err(Error::Io(format!(
            "{source_name}: no triangles (the file has {} vertices and no `f` faces)",
            verts.len()
        )));
    }
    let name = Path::new(source_name)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| source_name.to_string());
    let mut scene = TriScene {
        name,
        tris,
        camera: Camera {
            eye: DVec3::ZERO,
            look_at: DVec3::ZERO,
            up: DVec3::Y,
            fov_deg: 50.0,
        },
        light: DVec3::ZERO,
        face_lines,
    };
    let b = scene.bounds();
    let c = (b.min + b.max) * 0.5;
    let diag = (b.max - b.min).length().max(1e-9);
    scene.camera.look_at = c;
    scene.camera.eye = c + DVec3::new(0.0, 0.3, 1.0).normalize() * diag * 1.2;
    scene.light = c + DVec3::new(0.4, 1.0, 0.6) * diag;
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    fn temp_file(text: &str) -> std::path::PathBuf {
        static N: AtomicUsize = AtomicUsize::new(0);
        let p = std::env::temp_dir().join(format!(
            "golden_scene_test_{}_{}.obj",
            std::process::id(),
            N.fetch_add(1, Ordering::SeqCst)
        ));
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn procedural_scenes_are_seeded_and_sized() {
        for name in SCENES {
            let a = by_name(name, 5, None).unwrap();
            let b = by_name(name, 5, None).unwrap();
            let c = by_name(name, 6, None).unwrap();
            assert_eq!(a, b, "{name}");
            assert_ne!(a.tris, c.tris, "{name}");
            assert!(
                (1000..=5000).contains(&a.tris.len()),
                "{name}: {}",
                a.tris.len()
            );
            assert!(a.tris.iter().all(|t| t.is_finite()));
            assert!(!a.bounds().is_empty());
        }
        assert_eq!(room(1, 10).tris.len(), 12 + 120);
        assert_eq!(grass(1, 10).tris.len(), 12);
        assert_eq!(mesh(1, 5).tris.len(), 100);
        assert!(by_name("forest", 1, None).is_err());
        assert!(by_name("soup", 1, Some(0)).is_err());
    }

    #[test]
    fn grass_blades_are_long_thin_and_diagonal() {
        let s = grass(2, 500);
        for t in &s.tris[2..] {
            let (lo, hi) = t.min_max();
            let ext = hi - lo;
            let len = (t.v[2] - (t.v[0] + t.v[1]) * 0.5).length();
            assert!((2.0..4.5).contains(&len));
            assert!((t.v[1] - t.v[0]).length() < 0.04 + 1e-12);
            // Leaning: the box has real horizontal extent, so the thin blade leaves most of it empty.
            assert!(ext.x.max(ext.z) > 0.3, "{ext:?}");
        }
    }

    #[test]
    fn torus_is_closed() {
        // Every edge of a closed mesh is shared by exactly two triangles.
        let s = mesh(3, 8);
        let mut edges = std::collections::HashMap::new();
        for t in &s.tris {
            for k in 0..3 {
                let (a, b) = (t.v[k], t.v[(k + 1) % 3]);
                let key = |p: DVec3| (p.x.to_bits(), p.y.to_bits(), p.z.to_bits());
                let e = if key(a) < key(b) {
                    (key(a), key(b))
                } else {
                    (key(b), key(a))
                };
                *edges.entry(e).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&c| c == 2));
    }

    #[test]
    fn primary_rays_cover_the_image_and_look_forward() {
        let s = room(1, 20);
        let rays = primary_rays(&s, 8, 6);
        assert_eq!(rays.len(), 48);
        let fwd = (s.camera.look_at - s.camera.eye).normalize();
        for r in &rays {
            r.validate().unwrap();
            assert!((r.dir.length() - 1.0).abs() < 1e-12);
            assert!(r.dir.dot(fwd) > 0.5);
        }
        // Top-left looks up and left of bottom-right.
        assert!(rays[0].dir.y > rays[47].dir.y);
    }

    #[test]
    fn secondary_rays_leave_the_surface_on_the_incoming_side() {
        let s = TriScene {
            name: "floor".into(),
            tris: vec![Triangle::new(
                DVec3::new(-10.0, 0.0, -10.0),
                DVec3::new(10.0, 0.0, -10.0),
                DVec3::new(0.0, 0.0, 10.0),
            )],
            camera: room(1, 1).camera,
            light: DVec3::new(0.0, 5.0, 0.0),
            face_lines: Vec::new(),
        };
        let p =
            vec![Ray::new(DVec3::new(0.0, 2.0, 0.0), -DVec3::Y, 0.0, f64::INFINITY).unwrap(); 50];
        let hits = vec![Some((0, crate::exact::rat(2.0))); 50];
        let sec = secondary_rays(&s, &p, &hits, 9);
        assert_eq!(sec.bounce.len(), 50);
        assert_eq!(sec.shadow.len(), 50);
        for r in sec.bounce.iter().chain(&sec.shadow) {
            r.validate().unwrap();
            assert!(r.origin.y > 0.0 && r.dir.y > 0.0);
            assert!(crate::scene::tri::tri_exact(r, &s.tris[0]).is_none());
        }
        assert!((sec.shadow[0].t_max - (5.0 - sec.shadow[0].origin.y)).abs() < 1e-9);
        assert_eq!(sec, secondary_rays(&s, &p, &hits, 9));
    }

    #[test]
    fn obj_loads_triangles_quads_and_negative_indices() {
        let p = temp_file(
            "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n\
             f 1/1/1 2/2/1 3/3/1 4/4/1\nv 0 0 2\nf -1 1 2\no ignored\n",
        );
        let s = load_obj(&p).unwrap();
        std::fs::remove_file(&p).ok();
        assert_eq!(s.tris.len(), 3);
        assert_eq!(s.tris[2].v[0], DVec3::new(0.0, 0.0, 2.0));
        assert_eq!(s.bounds().max, DVec3::new(1.0, 1.0, 2.0));
        // The quad on line 7 gives two triangles, the triangle on line 9 one.
        assert_eq!(s.face_lines, vec![7, 7, 9]);
    }

    #[test]
    fn malformed_obj_files_get_clear_errors() {
        let missing = std::env::temp_dir().join("golden_scene_test_does_not_exist.obj");
        let e = load_obj(&missing).unwrap_err().to_string();
        assert!(
            e.contains("does_not_exist.obj") && e.contains("cannot read"),
            "{e}"
        );
        let cases: [(&str, &str); 11] = [
            ("v 0 0 0\nv 1 0 0\n", "no triangles"),
            ("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", ":2: field `v y`"),
            ("v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n", "not finite"),
            (
                "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
                ":2: field `v`: 2 numbers",
            ),
            (
                "v 0 0 0 1 2\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                ":1: field `v`: 5 numbers",
            ),
            (
                "v 0 0 0\nv 1 0 1e-400\nv 0 1 0\nf 1 2 3\n",
                ":2: field `v z`: `1e-400` underflows",
            ),
            (
                "v 0 0 0\nv 1 0 0 1e999\nv 0 1 0\nf 1 2 3\n",
                ":2: field `v w`: `1e999` overflows",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nfx 1 2 3\n",
                ":4: field `fx`: not an OBJ statement",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n",
                ":4: field `f`: vertex index 7 is out of range",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "not an integer"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "at least 3 vertices"),
        ];
        for (text, want) in cases {
            let p = temp_file(text);
            let e = load_obj(&p).unwrap_err().to_string();
            std::fs::remove_file(&p).ok();
            assert!(e.contains(want), "want `{want}` in `{e}`");
            assert!(e.contains(&p.display().to_string()), "{e}");
        }
        let e = parse_obj("v 0 0 0\nf -2 1 1\n", "neg.obj")
            .unwrap_err()
            .to_string();
        assert!(e.contains("neg.obj:2") && e.contains("index -2"), "{e}");
        let e = parse_obj("v 0 0 0\nf 0 1 1\n", "zero.obj")
            .unwrap_err()
            .to_string();
        assert!(e.contains("index 0"), "{e}");
    }

    /// A byte-order mark, the statements OBJ has besides `v` and `f`, and vertices with `w` or a colour
    /// read as the plain file does.
    #[test]
    fn obj_byte_order_mark_and_other_statements_are_read_past() {
        let plain = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let rich = "\u{feff}mtllib a.mtl\nmaplib m.map\nusemap off\nbsp 1\no tri\ng g1\ns off\nusemtl red\nv 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\n\
                    v 0 1 0\nvn 0 0 1\nvt 0 0\nl 1 2\nf 1//1 2//1 3//1\n";
        let (a, b) = (
            parse_obj(plain, "a").unwrap(),
            parse_obj(rich, "b").unwrap(),
        );
        assert_eq!(a.tris.len(), 1);
        assert_eq!(a.tris, b.tris);
    }
}
