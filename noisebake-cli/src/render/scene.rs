//! Scenes for `noisebake report render`: triangles, a pinhole camera, a rectangular area light
//! and an open sky. [`Scene::room`] is built in code with what makes occlusion hard (creases
//! where walls meet the floor, contacts under spheres and boxes, a thin table top on thin legs,
//! steps, columns, curved surfaces, open sky above); [`Scene::from_obj`] loads a user's `.obj`
//! (through `tobj`) and places the camera and light around its bounds, so anyone can judge the
//! samplers on their own geometry.

use glam::{Mat3, Vec3};
use std::path::Path;

/// A triangle's corners.
pub type Tri = [Vec3; 3];

/// A pinhole camera: `width × height` pixels, rays through pixel centres.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    /// The eye.
    pub eye: Vec3,
    /// Where it looks.
    pub target: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
}

impl Camera {
    /// The unit direction of the ray through the centre of pixel `(x, y)` of a `w × h` image
    /// (x right, y down), with the image plane shifted by `shift` pixels (a pan that moves the
    /// picture without moving the eye: every pixel's ray is the ray of pixel `(x, y) + shift`
    /// of the unshifted camera).
    pub fn ray(&self, x: f32, y: f32, w: usize, h: usize) -> Vec3 {
        let forward = (self.target - self.eye).normalize();
        let right = forward.cross(Vec3::Y).normalize();
        let up = right.cross(forward);
        let half = (self.fov_y * 0.5).tan();
        let aspect = w as f32 / h as f32;
        let u = ((x + 0.5) / w as f32 * 2.0 - 1.0) * half * aspect;
        let v = (1.0 - (y + 0.5) / h as f32 * 2.0) * half;
        (forward + right * u + up * v).normalize()
    }
}

/// A one-sided rectangular emitter: `corner + s·edges[0] + t·edges[1]` for `s, t ∈ [0, 1]`,
/// emitting `radiance` on the side of `edges[0] × edges[1]`.
#[derive(Clone, Copy, Debug)]
pub struct AreaLight {
    /// One corner.
    pub corner: Vec3,
    /// The two edges from it.
    pub edges: [Vec3; 2],
    /// Emitted radiance.
    pub radiance: f32,
}

impl AreaLight {
    /// The point at `(s, t)` of the unit square.
    pub fn point(&self, s: f32, t: f32) -> Vec3 {
        self.corner + self.edges[0] * s + self.edges[1] * t
    }

    /// The emitting side's unit normal.
    pub fn normal(&self) -> Vec3 {
        self.edges[0].cross(self.edges[1]).normalize()
    }

    /// Area.
    pub fn area(&self) -> f32 {
        self.edges[0].cross(self.edges[1]).length()
    }
}

/// A scene: what `noisebake report render` traces.
#[derive(Clone, Debug)]
pub struct Scene {
    /// What it is, for the report.
    pub name: String,
    /// Every triangle (double-sided).
    pub triangles: Vec<Tri>,
    /// The camera.
    pub camera: Camera,
    /// The light whose soft shadow is measured.
    pub light: AreaLight,
    /// Ambient occlusion's radius: occluders farther than this along a ray do not count.
    pub ao_radius: f32,
    /// Diffuse albedo of every surface (the bounce).
    pub albedo: f32,
    /// Radiance of the open sky a bounce ray escapes to.
    pub sky: f32,
}

/// Two triangles of the quad `a b c d` (counter-clockwise).
fn quad(out: &mut Vec<Tri>, a: Vec3, b: Vec3, c: Vec3, d: Vec3) {
    out.push([a, b, c]);
    out.push([a, c, d]);
}

/// A box of half-sizes `half`, turned by `yaw` radians about the vertical, centred at `centre`.
fn cuboid(out: &mut Vec<Tri>, centre: Vec3, half: Vec3, yaw: f32) {
    let r = Mat3::from_rotation_y(yaw);
    let p = |sx: f32, sy: f32, sz: f32| centre + r * (half * Vec3::new(sx, sy, sz));
    let c = [
        p(-1.0, -1.0, -1.0),
        p(1.0, -1.0, -1.0),
        p(1.0, 1.0, -1.0),
        p(-1.0, 1.0, -1.0),
        p(-1.0, -1.0, 1.0),
        p(1.0, -1.0, 1.0),
        p(1.0, 1.0, 1.0),
        p(-1.0, 1.0, 1.0),
    ];
    for [a, b, cc, d] in [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [3, 7, 6, 2],
        [0, 4, 7, 3],
        [1, 2, 6, 5],
    ] {
        quad(out, c[a], c[b], c[cc], c[d]);
    }
}

/// A UV sphere of `rings × 2·rings` quads.
fn sphere(out: &mut Vec<Tri>, centre: Vec3, radius: f32, rings: usize) {
    use std::f32::consts::PI;
    let at = |i: usize, j: usize| {
        let theta = PI * i as f32 / rings as f32;
        let phi = 2.0 * PI * j as f32 / (2 * rings) as f32;
        centre
            + radius
                * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                )
    };
    for i in 0..rings {
        for j in 0..2 * rings {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if i > 0 {
                out.push([a, b, d]);
            }
            if i + 1 < rings {
                out.push([b, c, d]);
            }
        }
    }
}

/// A vertical cylinder (its side and its top) of `sides` facets, standing on `base`.
fn column(out: &mut Vec<Tri>, base: Vec3, radius: f32, height: f32, sides: usize) {
    use std::f32::consts::PI;
    let ring = |k: usize, y: f32| {
        let a = 2.0 * PI * k as f32 / sides as f32;
        base + Vec3::new(radius * a.cos(), y, radius * a.sin())
    };
    let top = base + Vec3::Y * height;
    for k in 0..sides {
        let (a, b) = (ring(k, 0.0), ring(k + 1, 0.0));
        let (c, d) = (ring(k + 1, height), ring(k, height));
        quad(out, a, b, c, d);
        out.push([top, d, c]);
    }
}

impl Scene {
    /// The room: a 4 × 4 floor with walls 2 high on three sides and no ceiling (open sky);
    /// a box turned 30° and a stack of two boxes (contacts and creases), steps against the
    /// left wall, two columns, a table whose 4 cm top stands on thin legs (a thin feature and
    /// narrow gaps), a tessellated sphere resting on the floor and a smaller one on the stack
    /// (curved surfaces and point contacts); a 1.2 × 0.9 light above, a camera looking down
    /// into the room. About 6 000 triangles.
    pub fn room() -> Scene {
        let mut t = Vec::new();
        let (lo, hi, wall) = (-2.0f32, 2.0f32, 2.0f32);
        let v = Vec3::new;
        // Floor and three walls (back, left, right), each split into a grid so the BVH has
        // more than a few huge triangles.
        let grid = |out: &mut Vec<Tri>, o: Vec3, a: Vec3, b: Vec3, n: usize| {
            for i in 0..n {
                for j in 0..n {
                    let p = |s: usize, r: usize| {
                        o + a * (s as f32 / n as f32) + b * (r as f32 / n as f32)
                    };
                    quad(out, p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
                }
            }
        };
        grid(
            &mut t,
            v(lo, 0.0, lo),
            v(0.0, 0.0, hi - lo),
            v(hi - lo, 0.0, 0.0),
            8,
        );
        grid(
            &mut t,
            v(lo, 0.0, lo),
            v(hi - lo, 0.0, 0.0),
            v(0.0, wall, 0.0),
            8,
        );
        grid(
            &mut t,
            v(lo, 0.0, lo),
            v(0.0, wall, 0.0),
            v(0.0, 0.0, hi - lo),
            8,
        );
        grid(
            &mut t,
            v(hi, 0.0, lo),
            v(0.0, 0.0, hi - lo),
            v(0.0, wall, 0.0),
            8,
        );
        // A box turned 30°, and a stack of two.
        cuboid(&mut t, v(0.7, 0.35, 0.2), v(0.35, 0.35, 0.35), 0.52);
        cuboid(&mut t, v(-0.6, 0.3, -1.3), v(0.45, 0.3, 0.45), -0.2);
        cuboid(&mut t, v(-0.55, 0.8, -1.3), v(0.25, 0.2, 0.25), 0.4);
        // Steps against the left wall.
        for k in 0..4 {
            let hgt = 0.15 * (k + 1) as f32;
            cuboid(
                &mut t,
                v(lo + 0.25, hgt * 0.5, 0.4 + 0.3 * k as f32),
                v(0.25, hgt * 0.5, 0.15),
                0.0,
            );
        }
        // Columns.
        column(&mut t, v(1.5, 0.0, -1.5), 0.18, 1.6, 24);
        column(&mut t, v(-1.5, 0.0, -1.5), 0.12, 1.2, 16);
        // A table: a thin top on four thin legs.
        cuboid(&mut t, v(0.9, 0.62, -0.9), v(0.45, 0.02, 0.3), 0.1);
        for (dx, dz) in [(-0.38, -0.23), (0.38, -0.23), (-0.38, 0.23), (0.38, 0.23)] {
            let r = Mat3::from_rotation_y(0.1) * v(dx, 0.0, dz);
            cuboid(&mut t, v(0.9, 0.3, -0.9) + r, v(0.025, 0.3, 0.025), 0.1);
        }
        // Spheres: one on the floor, one on the stack.
        sphere(&mut t, v(-0.4, 0.4, 0.9), 0.4, 24);
        sphere(&mut t, v(-0.55, 1.15, -1.3), 0.15, 12);
        Scene {
            name: "room".to_string(),
            triangles: t,
            camera: Camera {
                eye: v(0.3, 2.9, 4.0),
                target: v(0.0, 0.3, -0.4),
                fov_y: 55f32.to_radians(),
            },
            light: AreaLight {
                corner: v(-0.2, 3.2, -0.8),
                edges: [v(1.2, 0.0, 0.0), v(0.0, 0.0, 0.9)],
                radiance: 12.0,
            },
            ao_radius: 1.0,
            albedo: 0.7,
            sky: 0.4,
        }
    }

    /// A scene from a Wavefront `.obj` file (every object, triangulated): the camera looks at
    /// the centre of its bounds from above and in front, the light sits above them, the AO
    /// radius is a quarter of their largest side.
    pub fn from_obj(path: &Path) -> Result<Scene, String> {
        let (models, _) = tobj::load_obj(
            path,
            &tobj::LoadOptions {
                triangulate: true,
                single_index: true,
                ..Default::default()
            },
        )
        .map_err(|e| format!("{}: {e}", path.display()))?;
        let mut t = Vec::new();
        for m in &models {
            let p = &m.mesh.positions;
            let vertex = |i: u32| -> Option<Vec3> {
                let i = i as usize * 3;
                Some(Vec3::new(*p.get(i)?, *p.get(i + 1)?, *p.get(i + 2)?))
            };
            for f in m.mesh.indices.chunks_exact(3) {
                let tri = [vertex(f[0]), vertex(f[1]), vertex(f[2])];
                let [Some(a), Some(b), Some(c)] = tri else {
                    return Err(format!(
                        "{}: a face indexes past the vertices",
                        path.display()
                    ));
                };
                if [a, b, c].iter().all(|v| v.is_finite()) && (b - a).cross(c - a).length() > 0.0 {
                    t.push([a, b, c]);
                }
            }
        }
        if t.is_empty() {
            return Err(format!("{}: no triangles", path.display()));
        }
        let (mut min, mut max) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
        for v in t.iter().flatten() {
            min = min.min(*v);
            max = max.max(*v);
        }
        let size = (max - min).max_element();
        let centre = (min + max) * 0.5;
        let name = path
            .file_name()
            .map_or("obj".to_string(), |n| n.to_string_lossy().into_owned());
        Ok(Scene {
            name,
            triangles: t,
            camera: Camera {
                eye: centre + Vec3::new(0.1, 0.75, 1.0) * size,
                target: centre,
                fov_y: 50f32.to_radians(),
            },
            light: AreaLight {
                corner: centre + Vec3::new(-0.15, 0.8, -0.1) * size,
                edges: [
                    Vec3::new(0.3, 0.0, 0.0) * size,
                    Vec3::new(0.0, 0.0, 0.22) * size,
                ],
                radiance: 12.0,
            },
            ao_radius: 0.25 * size,
            albedo: 0.7,
            sky: 0.4,
        })
    }
}
