//! Ray queries on a scene's triangles through `obvhs`'s compressed wide BVH (Ylitie, Karras
//! and Laine 2017's CWBVH: eight children per node, traversed four at a time with SIMD),
//! built by PLOC with reinsertion. Chosen over the `bvh` crate (a binary BVH, one node per
//! step) because incoherent secondary rays — the ones AO and soft shadows shoot — are what a
//! wide BVH is for; `report render` prints the rays per second it measures.

use super::scene::Tri;
use glam::{Vec3, Vec3A};
use obvhs::{
    BvhBuildParams,
    cwbvh::{CwBvh, builder::build_cwbvh_from_tris},
    ray::{Ray, RayHit},
    rt_triangle::RtTriangle,
    triangle::Triangle,
};
use std::time::Duration;

/// A closest hit: distance along the ray and the triangle's index in the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray direction.
    pub t: f32,
    /// The triangle, as indexed in the scene's list.
    pub triangle: usize,
}

/// The scene's triangles in a BVH.
pub struct Tracer {
    bvh: CwBvh,
    /// Triangles in the BVH's primitive order, with their edges precomputed.
    ordered: Vec<RtTriangle>,
    /// For each BVH primitive, its index in the scene's list.
    original: Vec<u32>,
    /// Each scene triangle's unit geometric normal.
    normals: Vec<Vec3>,
}

impl Tracer {
    /// Builds the BVH (deterministic: PLOC on one thread).
    pub fn new(triangles: &[Tri]) -> Tracer {
        let tris: Vec<Triangle> = triangles
            .iter()
            .map(|t| Triangle {
                v0: t[0].into(),
                v1: t[1].into(),
                v2: t[2].into(),
            })
            .collect();
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::slow_build(),
            &mut Duration::default(),
        );
        let ordered = bvh
            .primitive_indices
            .iter()
            .map(|&i| {
                let t = tris[i as usize];
                RtTriangle::new(t.v0, t.v1, t.v2)
            })
            .collect();
        let normals = triangles
            .iter()
            .map(|t| (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero())
            .collect();
        Tracer {
            original: bvh.primitive_indices.clone(),
            bvh,
            ordered,
            normals,
        }
    }

    /// The unit geometric normal of scene triangle `i` (its winding's side).
    pub fn normal(&self, i: usize) -> Vec3 {
        self.normals[i]
    }

    /// The closest hit along `origin + t·dir` for `t` in `(0, tmax)`.
    #[inline]
    pub fn closest(&self, origin: Vec3, dir: Vec3, tmax: f32) -> Option<Hit> {
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(dir), 0.0, tmax);
        let mut hit = RayHit::none();
        if self
            .bvh
            .ray_traverse(ray, &mut hit, |r, id| self.ordered[id].intersect(r))
        {
            Some(Hit {
                t: hit.t,
                triangle: self.original[hit.primitive_id as usize] as usize,
            })
        } else {
            None
        }
    }

    /// Whether anything lies along `origin + t·dir` for `t` in `(0, tmax)` (any hit ends the
    /// traversal).
    #[inline]
    pub fn occluded(&self, origin: Vec3, dir: Vec3, tmax: f32) -> bool {
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(dir), 0.0, tmax);
        !self
            .bvh
            .ray_traverse_miss(ray, |r, id| self.ordered[id].intersect(r))
    }
}
