//! Randomised conservativeness of the two cull-plane models against the exact clip, on fitted planes.

use glam::DVec3;
use golden::format::fixed::{FixFormat, GridMap};
use golden::format::float::FloatFormat;
use golden::geom::{Aabb, Ray};
use golden::plane::clip::clip_exact;
use golden::plane::fix::{self as plane_fix, CullFixFormat, FixNode, NodeFixRay};
use golden::plane::float::{self as plane_float, CullFloatFormat, FloatNode, NodeFloatRay};
use golden::slab::check::{judge, Verdict};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

struct Case {
    ray: Ray,
    bounds: Aabb,
    normals: Vec<DVec3>,
    verts: Vec<DVec3>,
}

fn case(rng: &mut Pcg64) -> Case {
    let c = DVec3::new(
        rng.gen_range(-5.0..5.0),
        rng.gen_range(-5.0..5.0),
        rng.gen_range(-5.0..5.0),
    );
    let h = DVec3::new(
        rng.gen_range(0.01..2.0),
        rng.gen_range(0.01..2.0),
        rng.gen_range(0.01..2.0),
    );
    let verts: Vec<DVec3> = (0..3)
        .map(|_| {
            c + h * DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            )
        })
        .collect();
    let mut lo = verts[0];
    let mut hi = verts[0];
    for v in &verts {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    let normals = (0..4)
        .map(|_| {
            let n = DVec3::new(
                rng.gen_range(-2i32..=2) as f64,
                rng.gen_range(-2i32..=2) as f64,
                rng.gen_range(-2i32..=2) as f64,
            );
            if n == DVec3::ZERO {
                DVec3::X
            } else {
                n
            }
        })
        .collect();
    // Aim at a random point of the triangle or of the box; sometimes parallel to an axis.
    let w: [f64; 3] = std::array::from_fn(|_| rng.gen_range(0.0..1.0));
    let s = w[0] + w[1] + w[2];
    let target = if rng.gen_bool(0.5) {
        (verts[0] * w[0] + verts[1] * w[1] + verts[2] * w[2]) / s
    } else {
        lo + (hi - lo) * DVec3::from(w)
    };
    let origin = DVec3::new(
        rng.gen_range(-7.0..7.0),
        rng.gen_range(-7.0..7.0),
        rng.gen_range(-7.0..7.0),
    );
    let mut dir = target - origin;
    if rng.gen_bool(0.1) {
        dir[rng.gen_range(0..3)] = 0.0;
    }
    if dir == DVec3::ZERO {
        dir = DVec3::X;
    }
    let t_max = if rng.gen_bool(0.3) {
        rng.gen_range(0.0..1.5)
    } else {
        f64::INFINITY
    };
    Case {
        ray: Ray::new(origin, dir, 0.0, t_max).unwrap(),
        bounds: Aabb::new(lo, hi).unwrap(),
        normals,
        verts,
    }
}

#[test]
fn fixed_model_encloses_the_exact_clip() {
    let mut rng = Pcg64::seed_from_u64(7);
    let mut culled = 0;
    for fmt in FixFormat::presets() {
        let cf = CullFixFormat::over(fmt);
        let map = GridMap::for_bounds(fmt, DVec3::splat(-8.0), DVec3::splat(8.0)).unwrap();
        for i in 0..20_000 {
            let c = case(&mut rng);
            let r = NodeFixRay {
                ray: map.quantize_ray(&c.ray).unwrap(),
                dir: plane_fix::quantize_dir(&cf, &c.ray).unwrap(),
            };
            let mut node = FixNode {
                b: map.quantize_box(&c.bounds).unwrap(),
                ..Default::default()
            };
            for (k, n) in c.normals.iter().enumerate() {
                node.planes[k] = plane_fix::fit_plane(&cf, &map, &node.b, *n, &c.verts).unwrap();
            }
            let k = c.normals.len();
            let exact: Vec<_> = node.planes[..k]
                .iter()
                .map(|p| p.to_exact(&map, &node.b))
                .collect();
            let ex = clip_exact(&c.ray, &c.bounds, &exact);
            let out = plane_fix::node_fix(&cf, k, &r, &node);
            culled += usize::from(!out.hit);
            let v = judge(&ex, out.hit, || {
                Some((
                    r.ray.t_world(&fmt, out.t_entry),
                    r.ray.t_world(&fmt, out.t_exit),
                ))
            });
            assert!(
                !matches!(v, Verdict::Violation(_)),
                "{} case {i}: {v:?} {:?} {node:?} {out:?}",
                fmt.name(),
                c.ray
            );
        }
    }
    assert!(culled > 1000, "the planes cull something: {culled}");
}

#[test]
fn float_model_encloses_the_exact_clip() {
    let mut rng = Pcg64::seed_from_u64(8);
    let mut culled = 0;
    for f in [
        FloatFormat::FP32,
        FloatFormat::BF16,
        FloatFormat::FP16,
        FloatFormat::new(6, 5).unwrap(),
    ] {
        let cf = CullFloatFormat::over(f);
        for i in 0..20_000 {
            let c = case(&mut rng);
            let r = NodeFloatRay {
                ray: golden::slab::float::quantize_ray(&f, &c.ray).unwrap(),
                dir: plane_float::quantize_dir(&cf, &c.ray).unwrap(),
            };
            let mut node = FloatNode {
                b: golden::slab::float::quantize_box(&f, &c.bounds).unwrap(),
                ..Default::default()
            };
            for (k, n) in c.normals.iter().enumerate() {
                node.planes[k] = plane_float::fit_plane(&cf, &node.b, *n, &c.verts).unwrap();
            }
            let k = c.normals.len();
            let exact: Vec<_> = node.planes[..k]
                .iter()
                .map(|p| p.to_exact(&f, &node.b))
                .collect();
            let ex = clip_exact(&c.ray, &c.bounds, &exact);
            let out = plane_float::node_float(&cf, k, &r, &node);
            culled += usize::from(!out.hit);
            let v = judge(&ex, out.hit, || plane_float::out_interval(&f, &out));
            assert!(
                !matches!(v, Verdict::Violation(_)),
                "{} case {i}: {v:?} {:?} {node:?} {out:?}",
                f.name(),
                c.ray
            );
        }
    }
    assert!(culled > 1000, "the planes cull something: {culled}");
}
