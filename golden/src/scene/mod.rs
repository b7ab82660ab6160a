//! Scenes and traversal for the measurements on scenes: triangle scenes, OBJ input and the rays shot
//! into them ([`tri_scene`]), the exact ray-triangle test ([`tri`]), a binned-SAH BVH ([`bvh`]), the
//! closest-hit traversal with pluggable node testers ([`traverse`]) and the sweeps' one traversal model
//! over cull planes and bundles ([`sweep`]).

pub mod bvh;
pub mod sweep;
pub mod traverse;
pub mod tri;
pub mod tri_scene;
