//! The built-in default scene: a room with walls, floor, pillars, crates and shelves, seen by a pinhole
//! camera. The boxes stand in for the BVH nodes a traversal would test.

use glam::DVec3;
use golden::{Aabb, Ray};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// Boxes and the rays that test them.
pub struct Scene {
    pub name: String,
    pub boxes: Vec<Aabb>,
    pub rays: Vec<Ray>,
    pub width: usize,
    pub height: usize,
}

impl Scene {
    /// Bounds of everything in the scene (boxes and ray origins): the grid the fixed formats cover.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for b in self.boxes.iter().filter(|b| !b.is_empty()) {
            lo = lo.min(b.min);
            hi = hi.max(b.max);
        }
        for r in &self.rays {
            lo = lo.min(r.origin);
            hi = hi.max(r.origin);
        }
        (lo, hi)
    }
}

fn aabb(min: [f64; 3], max: [f64; 3]) -> Aabb {
    Aabb::new(min.into(), max.into()).expect("finite")
}

/// The box room: 20 x 6 x 20 units, camera at eye height looking in; `width x height` primary rays. (Not
/// the triangle scene `room` of `golden::scene::tri_scene`, which the sweeps use.)
pub fn box_room(width: usize, height: usize) -> Scene {
    let mut boxes = vec![
        aabb([-10.0, -0.2, -10.0], [10.0, 0.0, 10.0]), // floor
        aabb([-10.0, 6.0, -10.0], [10.0, 6.2, 10.0]),  // ceiling
        aabb([-10.2, 0.0, -10.0], [-10.0, 6.0, 10.0]), // left wall
        aabb([10.0, 0.0, -10.0], [10.2, 6.0, 10.0]),   // right wall
        aabb([-10.0, 0.0, 10.0], [10.0, 6.0, 10.2]),   // back wall
    ];
    // Pillars.
    for i in 0..4 {
        for j in 0..2 {
            let (x, z) = (-6.0 + 4.0 * i as f64, 2.0 + 5.0 * j as f64);
            boxes.push(aabb([x - 0.3, 0.0, z - 0.3], [x + 0.3, 6.0, z + 0.3]));
        }
    }
    // Shelves: thin boards, one of them flat (zero thickness).
    for k in 0..3 {
        let y = 1.0 + k as f64;
        let t = if k == 1 { 0.0 } else { 0.05 };
        boxes.push(aabb([-9.5, y, 9.0], [-5.0, y + t, 9.9]));
    }
    // Crates, seeded.
    let mut rng = Pcg64::seed_from_u64(2025);
    for _ in 0..30 {
        let s = rng.gen_range(0.2..0.9);
        let (x, z) = (rng.gen_range(-9.0..9.0), rng.gen_range(-5.0..9.0));
        let y = if rng.gen_ratio(1, 4) {
            rng.gen_range(0.5..4.0)
        } else {
            0.0
        };
        boxes.push(aabb([x, y, z], [x + s, y + s, z + s]));
    }
    // A lamp that is a single point, and an empty box (as a BVH may hold for an empty node).
    boxes.push(aabb([0.0, 5.0, 4.0], [0.0, 5.0, 4.0]));
    boxes.push(aabb([1.0, 1.0, 1.0], [0.0, 0.0, 0.0]));

    let eye = DVec3::new(0.0, 1.6, -9.5);
    let (fwd, right, up) = (DVec3::Z, DVec3::X, DVec3::Y);
    let fov = 70f64.to_radians();
    let half = (fov / 2.0).tan();
    let mut rays = Vec::with_capacity(width * height);
    for py in 0..height {
        for px in 0..width {
            let u = ((px as f64 + 0.5) / width as f64 * 2.0 - 1.0) * half * width as f64
                / height as f64;
            let v = (1.0 - (py as f64 + 0.5) / height as f64 * 2.0) * half;
            let dir = (fwd + right * u + up * v).normalize();
            rays.push(Ray::new(eye, dir, 0.0, f64::INFINITY).expect("finite"));
        }
    }
    Scene {
        name: "box_room".into(),
        boxes,
        rays,
        width,
        height,
    }
}

/// A triangle scene (built-in or OBJ) as the main job takes it: the boxes of the first `max_boxes` nodes of
/// its BVH (binned SAH, leaves of up to 4 triangles) in breadth-first order, the boxes a traversal tests
/// first, and its camera's `width x height` primary rays.
pub fn from_tri(
    ts: &golden::scene::tri_scene::TriScene,
    width: usize,
    height: usize,
    max_boxes: usize,
) -> Result<Scene, String> {
    let bvh = golden::scene::bvh::Bvh::build(&ts.tris, 4).map_err(|e| e.to_string())?;
    let mut boxes = Vec::with_capacity(max_boxes);
    let mut queue = std::collections::VecDeque::from([0usize]);
    while let Some(n) = queue.pop_front() {
        if boxes.len() == max_boxes {
            break;
        }
        boxes.push(bvh.nodes[n].bounds);
        if let golden::scene::bvh::NodeKind::Inner { left, right } = bvh.nodes[n].kind {
            queue.extend([left, right]);
        }
    }
    Ok(Scene {
        name: ts.name.clone(),
        boxes,
        rays: golden::scene::tri_scene::primary_rays(ts, width, height),
        width,
        height,
    })
}
