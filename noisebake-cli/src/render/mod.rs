//! A small CPU ray tracer to judge samplers where games use them (`noisebake report render`):
//! one primary ray per pixel centre makes a G-buffer, and each sample of a pixel estimates
//! three integrals at the surface it sees:
//!
//! - **ambient occlusion** from the sample's dimensions 0–1, warped to a cosine-weighted
//!   direction (`r = √u`, `φ = 2πv`, `noise_runtime::warp::cosine_hemisphere_polar`): 1 where nothing
//!   lies within the scene's AO radius along it;
//! - **a soft shadow** from dimensions 2–3, a point on the rectangular area light: its
//!   unoccluded contribution `L cos θ cos θ' A / (π d²)`, the direct light a white diffuse
//!   surface reflects;
//! - **one diffuse bounce with next-event estimation** from all four: the AO direction traced
//!   to the first surface it meets (or the open sky), lit there by the light point of
//!   dimensions 2–3 — a 4D integrand, so a sampler's pairs are judged together.
//!
//! The estimate of a pixel is the mean over its samples; [`denoise`] holds the filters games
//! run on such estimates, [`scene`] the scenes and [`trace`] the BVH. Everything is
//! deterministic: rows are shaded in parallel, each pixel by one thread in a fixed order.

pub mod anchor;
pub mod denoise;
pub mod motion;
pub mod scene;
pub mod trace;

use glam::Vec3;
use rayon::prelude::*;
use scene::{Camera, Scene};
use trace::Tracer;

/// A camera and its image plane's shift in pixels (a lens shift: the picture moves without
/// the eye moving).
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// The camera.
    pub camera: Camera,
    /// The shift, `(x, y)` pixels: pixel `p` sees what pixel `p + shift` of the unshifted
    /// camera sees.
    pub shift: [f32; 2],
}

impl View {
    /// The unit direction of the ray through the centre of pixel `(x, y)` of a `w × h` image.
    pub fn ray(&self, x: f32, y: f32, w: usize, h: usize) -> Vec3 {
        self.camera.ray(x + self.shift[0], y + self.shift[1], w, h)
    }

    /// Where the point `p` appears in a `w × h` image: its continuous pixel position (pixel
    /// centres at integers), or `None` behind the eye. The inverse of [`View::ray`].
    pub fn project(&self, p: Vec3, w: usize, h: usize) -> Option<[f32; 2]> {
        let c = &self.camera;
        let forward = (c.target - c.eye).normalize();
        let right = forward.cross(Vec3::Y).normalize();
        let up = right.cross(forward);
        let d = p - c.eye;
        let z = d.dot(forward);
        if z <= 1e-6 {
            return None;
        }
        let half = (c.fov_y * 0.5).tan();
        let aspect = w as f32 / h as f32;
        let u = d.dot(right) / z / (half * aspect);
        let v = d.dot(up) / z / half;
        Some([
            (u + 1.0) * 0.5 * w as f32 - 0.5 - self.shift[0],
            (1.0 - v) * 0.5 * h as f32 - 0.5 - self.shift[1],
        ])
    }
}

/// What a pixel's primary ray found.
#[derive(Clone, Debug)]
pub struct GBuffer {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Whether the pixel's ray hit a surface (else it sees the sky, and every integrand is 0
    /// there, exactly).
    pub hit: Vec<bool>,
    /// The surface point, nudged off the surface along its normal.
    pub position: Vec<Vec3>,
    /// The unit normal, turned to face the camera.
    pub normal: Vec<Vec3>,
    /// Distance from the eye.
    pub depth: Vec<f32>,
}

/// How far secondary rays start off the surface, relative to the scene's AO radius.
const OFFSET: f32 = 1e-4;

impl GBuffer {
    /// The G-buffer of `scene` at `width × height`, its image plane shifted by `shift` pixels
    /// (a camera pan: the picture moves by whole pixels, the eye stays).
    pub fn new(
        scene: &Scene,
        tracer: &Tracer,
        width: usize,
        height: usize,
        shift: [i32; 2],
    ) -> GBuffer {
        let view = View {
            camera: scene.camera,
            shift: [shift[0] as f32, shift[1] as f32],
        };
        Self::window(scene, tracer, &view, [width, height])
    }

    /// The G-buffer of `view` at `size`.
    pub fn of_view(scene: &Scene, tracer: &Tracer, view: &View, size: [usize; 2]) -> GBuffer {
        Self::window(scene, tracer, view, size)
    }

    fn window(scene: &Scene, tracer: &Tracer, view: &View, size: [usize; 2]) -> GBuffer {
        let [width, height] = size;
        let eps = OFFSET * scene.ao_radius;
        let eye = view.camera.eye;
        let rows: Vec<Vec<(bool, Vec3, Vec3, f32)>> = (0..height)
            .into_par_iter()
            .map(|y| {
                (0..width)
                    .map(|x| {
                        let dir = view.ray(x as f32, y as f32, width, height);
                        match tracer.closest(eye, dir, f32::MAX) {
                            Some(h) => {
                                let mut n = tracer.normal(h.triangle);
                                if n.dot(dir) > 0.0 {
                                    n = -n;
                                }
                                let p = eye + dir * h.t + n * eps;
                                (true, p, n, h.t)
                            }
                            None => (false, Vec3::ZERO, Vec3::ZERO, f32::INFINITY),
                        }
                    })
                    .collect()
            })
            .collect();
        let flat: Vec<(bool, Vec3, Vec3, f32)> = rows.into_iter().flatten().collect();
        GBuffer {
            width,
            height,
            hit: flat.iter().map(|p| p.0).collect(),
            position: flat.iter().map(|p| p.1).collect(),
            normal: flat.iter().map(|p| p.2).collect(),
            depth: flat.iter().map(|p| p.3).collect(),
        }
    }

    /// Pixels that see a surface.
    pub fn surface_pixels(&self) -> usize {
        self.hit.iter().filter(|&&h| h).count()
    }
}

/// The integrands, in the order estimates are returned.
pub const INTEGRANDS: [&str; 3] = ["ao", "shadow", "bounce"];

/// An orthonormal basis `(t, b)` completing the unit normal `n` (Duff et al. 2017, "Building
/// an Orthonormal Basis, Revisited", JCGT 6(1)).
fn basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// The light a white diffuse surface at `p` (normal `n`) reflects from the light point of
/// `(s, t)`, or 0 where the light is occluded or behind either surface: one sample of
/// `L cos θ cos θ' A / (π d²)`. Returns the value and whether a shadow ray was traced.
#[inline]
fn direct(scene: &Scene, tracer: &Tracer, p: Vec3, n: Vec3, s: f32, t: f32) -> (f32, bool) {
    let l = &scene.light;
    let y = l.point(s, t);
    let d = y - p;
    let dist2 = d.length_squared();
    let dist = dist2.sqrt();
    let w = d / dist;
    let (cos_p, cos_l) = (n.dot(w), -l.normal().dot(w));
    if cos_p <= 0.0 || cos_l <= 0.0 {
        return (0.0, false);
    }
    if tracer.occluded(p, w, dist * (1.0 - 1e-4)) {
        return (0.0, true);
    }
    (
        l.radiance * cos_p * cos_l * l.area() / (std::f32::consts::PI * dist2),
        true,
    )
}

/// A direction `local` about +z (e.g. a cosine-weighted one) turned into the frame of the unit
/// normal `n`.
#[inline]
pub fn to_world(n: Vec3, local: [f32; 3]) -> Vec3 {
    let (t, b) = basis(n);
    (t * local[0] + b * local[1] + n * local[2]).normalize()
}

/// One ray of ambient occlusion from the surface point `p` with normal `n` along `local` (a
/// direction about +z): 1 where nothing lies within the scene's AO radius, else 0.
#[inline]
pub fn ao_ray(scene: &Scene, tracer: &Tracer, p: Vec3, n: Vec3, local: [f32; 3]) -> f32 {
    let dir = to_world(n, local);
    if tracer.occluded(p, dir, scene.ao_radius) {
        0.0
    } else {
        1.0
    }
}

/// One sample `s` (four values in `[0, 1)`) at the surface point `p` with normal `n`: the AO,
/// shadow and bounce estimates, and the rays it traced.
#[inline]
pub fn shade(scene: &Scene, tracer: &Tracer, p: Vec3, n: Vec3, s: [f32; 4]) -> ([f32; 3], u32) {
    let [u, v] = [s[0], s[1]];
    let dir = to_world(n, noise_runtime::warp::cosine_hemisphere_polar(u, v));
    let mut rays = 1;
    let hit = tracer.closest(p, dir, f32::MAX);
    let ao = match hit {
        Some(h) if h.t < scene.ao_radius => 0.0,
        _ => 1.0,
    };
    let (shadow, traced) = direct(scene, tracer, p, n, s[2], s[3]);
    rays += u32::from(traced);
    let bounce = match hit {
        None => scene.sky,
        Some(h) => {
            let mut nq = tracer.normal(h.triangle);
            if nq.dot(dir) > 0.0 {
                nq = -nq;
            }
            let q = p + dir * h.t + nq * (OFFSET * scene.ao_radius);
            let (light, traced) = direct(scene, tracer, q, nq, s[2], s[3]);
            rays += u32::from(traced);
            scene.albedo * light
        }
    };
    ([ao, shadow, scene.albedo * bounce], rays)
}

/// The tracer's throughput: one frame of `spp` samples per pixel from a hash (white noise,
/// the cheapest sampler, so the time is the rays'), as `(rays, seconds)`.
pub fn ray_rate(scene: &Scene, tracer: &Tracer, g: &GBuffer, spp: u32) -> (u64, f64) {
    let white = |x: i32, y: i32, f: u32, i: u32| -> [f32; 4] {
        core::array::from_fn(|d| {
            noise_runtime::sequence::to_unit(noise_runtime::hash::hash3(
                x,
                y,
                (4 * (f * spp + i) + d as u32) as i32,
                0xbe9c,
            ))
        })
    };
    let t = std::time::Instant::now();
    let (_, rays) = render_frame(scene, tracer, g, spp, 0, &white);
    (rays, t.elapsed().as_secs_f64())
}

/// A sampler as the renderer reads it: the four values of sample `i` of pixel `(x, y)` in
/// `frame`.
pub type Sampler<'a> = &'a (dyn Fn(i32, i32, u32, u32) -> [f32; 4] + Sync);

/// One frame of `spp` samples per pixel from `sampler`: the three estimate images (pixels
/// that see the sky hold 0) and the rays traced.
pub fn render_frame(
    scene: &Scene,
    tracer: &Tracer,
    g: &GBuffer,
    spp: u32,
    frame: u32,
    sampler: Sampler<'_>,
) -> ([Vec<f32>; 3], u64) {
    let w = g.width;
    let rows: Vec<(Vec<[f32; 3]>, u64)> = (0..g.height)
        .into_par_iter()
        .map(|y| {
            let mut rays = 0u64;
            let row = (0..w)
                .map(|x| {
                    let i = y * w + x;
                    if !g.hit[i] {
                        return [0.0; 3];
                    }
                    let mut sum = [0.0f32; 3];
                    for k in 0..spp {
                        let s = sampler(x as i32, y as i32, frame, k);
                        let (v, r) = shade(scene, tracer, g.position[i], g.normal[i], s);
                        rays += r as u64;
                        for c in 0..3 {
                            sum[c] += v[c];
                        }
                    }
                    sum.map(|v| v / spp as f32)
                })
                .collect();
            (row, rays)
        })
        .collect();
    let mut out = [
        vec![0.0; w * g.height],
        vec![0.0; w * g.height],
        vec![0.0; w * g.height],
    ];
    let mut rays = 0;
    for (y, (row, r)) in rows.into_iter().enumerate() {
        rays += r;
        for (x, v) in row.into_iter().enumerate() {
            for c in 0..3 {
                out[c][y * w + x] = v[c];
            }
        }
    }
    (out, rays)
}

#[cfg(test)]
mod tests;
