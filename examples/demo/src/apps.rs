//! The applications the papers evaluate, rendered on the CPU with one random number (or
//! direction) per pixel and frame from a [`Noise`] source.

use crate::noises::Noise;
use noisebake::stochastic::{Fbm, Fractal};
use noisebake_cli::render::{self, GBuffer, scene::Scene, trace::Tracer};
use rayon::prelude::*;

/// One application: a reference image and a noisy per-frame estimate of it.
pub trait App: Sync {
    /// File-name stem.
    fn name(&self) -> &'static str;
    /// Caption.
    fn caption(&self) -> &'static str;
    /// Channels per pixel (1 or 3).
    fn channels(&self) -> usize;
    /// The converged image.
    fn reference(&self) -> Vec<f32>;
    /// One pixel of frame `f` with random numbers from `noise`.
    fn pixel(&self, noise: Noise, x: usize, y: usize, f: u32, out: &mut [f32]);
}

/// Stochastic transparency (STBN §5.1): a surface of opacity α over a background, drawn
/// opaque where ξ < α. The left half has α = 0.9, the right half α = 0.3.
pub struct Transparency {
    /// Image size.
    pub size: [usize; 2],
}

impl Transparency {
    fn alpha(&self, x: usize) -> f32 {
        if x < self.size[0] / 2 { 0.9 } else { 0.3 }
    }
    fn background(&self, x: usize, y: usize) -> f32 {
        let (u, v) = (
            x as f32 / self.size[0] as f32,
            y as f32 / self.size[1] as f32,
        );
        0.15 + 0.5 * (0.5 + 0.5 * (9.0 * u + 4.0 * v).sin()) * v
    }
}

const FOREGROUND: f32 = 0.95;

impl App for Transparency {
    fn name(&self) -> &'static str {
        "transparency"
    }
    fn caption(&self) -> &'static str {
        "Stochastic transparency (STBN §5.1): a bright surface with α = 0.9 (left) and α = 0.3 (right) over a background; a pixel shows the surface when ξ < α."
    }
    fn channels(&self) -> usize {
        1
    }
    fn reference(&self) -> Vec<f32> {
        let [w, h] = self.size;
        (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                let a = self.alpha(x);
                a * FOREGROUND + (1.0 - a) * self.background(x, y)
            })
            .collect()
    }
    fn pixel(&self, noise: Noise, x: usize, y: usize, f: u32, out: &mut [f32]) {
        let xi = noise.xi(x as i32, y as i32, f, 0);
        out[0] = if xi < self.alpha(x) {
            FOREGROUND
        } else {
            self.background(x, y)
        };
    }
}

/// Dithering an RGB image to one bit per channel with three independent values per pixel
/// (STBN §5.2): channel c is on where its value exceeds ξ_c, ξ_c the c-th R2-offset read.
pub struct Dither {
    /// Image size.
    pub size: [usize; 2],
}

impl Dither {
    /// The RGB colour of pixel (x, y) before dithering, each channel in [0, 1].
    pub fn colour(&self, x: usize, y: usize) -> [f32; 3] {
        let (u, v) = (
            x as f32 / self.size[0] as f32,
            y as f32 / self.size[1] as f32,
        );
        let r = ((u - 0.35).powi(2) + (v - 0.4).powi(2)).sqrt();
        [
            (0.1 + 0.8 * u).clamp(0.0, 1.0),
            (0.5 + 0.45 * (6.0 * r).cos()).clamp(0.0, 1.0),
            (0.2 + 0.7 * v * (1.0 - u * 0.5)).clamp(0.0, 1.0),
        ]
    }
}

impl App for Dither {
    fn name(&self) -> &'static str {
        "dither"
    }
    fn caption(&self) -> &'static str {
        "Dithering an RGB image to 1 bit per channel (STBN §5.2): three independent values per pixel, from masks through R2 offsets (get_k with k = 0, 1, 2), from the free constructions each its own function of the pixel (sampler)."
    }
    fn channels(&self) -> usize {
        3
    }
    fn reference(&self) -> Vec<f32> {
        let [w, h] = self.size;
        (0..w * h).flat_map(|i| self.colour(i % w, i / w)).collect()
    }
    fn pixel(&self, noise: Noise, x: usize, y: usize, f: u32, out: &mut [f32]) {
        let c = self.colour(x, y);
        for k in 0..3 {
            out[k] = if c[k] > noise.xi(x as i32, y as i32, f, k as u32) {
                1.0
            } else {
                0.0
            };
        }
    }
}

/// A single-scattering heterogeneous volume by ray marching with a random offset per pixel
/// (STBN §5.3): density from fBm (noisebake's Perlin fBm), light from above; 8 steps per ray
/// against a 256-step reference.
pub struct Volume {
    /// Image size.
    pub size: [usize; 2],
    grid: Vec<f32>,
    light: Vec<f32>,
}

const G: usize = 48;
const STEPS: usize = 8;

impl Volume {
    /// Precomputes the density and the transmittance towards the light on a 48³ grid.
    pub fn new(size: [usize; 2]) -> Volume {
        let f = Fractal::new(5, 2.0, 0.5);
        let mut grid = vec![0.0f32; G * G * G];
        for (i, d) in grid.iter_mut().enumerate() {
            let (x, y, z) = (i % G, (i / G) % G, i / (G * G));
            let p = [
                x as f32 / G as f32,
                y as f32 / G as f32,
                z as f32 / G as f32,
            ];
            let r2 = (p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2) + (p[2] - 0.5).powi(2);
            let n = Fbm::new(f, 11).sample([p[0] * 4.0, p[1] * 4.0, p[2] * 4.0]);
            *d = (12.0 * (n + 0.35 - 2.2 * r2)).max(0.0);
        }
        // Transmittance to a light at −y (top of the image), marched once per column.
        let mut light = vec![1.0f32; G * G * G];
        for z in 0..G {
            for x in 0..G {
                let mut tau = 0.0f32;
                for y in 0..G {
                    let i = x + y * G + z * G * G;
                    light[i] = (-tau).exp();
                    tau += grid[i] / G as f32;
                }
            }
        }
        Volume { size, grid, light }
    }

    fn sample(&self, g: &[f32], p: [f32; 3]) -> f32 {
        let c = p.map(|v| (v * G as f32 - 0.5).clamp(0.0, (G - 1) as f32 - 1e-3));
        let i = c.map(|v| v as usize);
        let t = [c[0] - i[0] as f32, c[1] - i[1] as f32, c[2] - i[2] as f32];
        let at = |dx: usize, dy: usize, dz: usize| {
            g[(i[0] + dx) + (i[1] + dy) * G + (i[2] + dz) * G * G]
        };
        let lerp = |a: f32, b: f32, t: f32| a + t * (b - a);
        lerp(
            lerp(
                lerp(at(0, 0, 0), at(1, 0, 0), t[0]),
                lerp(at(0, 1, 0), at(1, 1, 0), t[0]),
                t[1],
            ),
            lerp(
                lerp(at(0, 0, 1), at(1, 0, 1), t[0]),
                lerp(at(0, 1, 1), at(1, 1, 1), t[0]),
                t[1],
            ),
            t[2],
        )
    }

    /// Radiance along the ray through pixel `(x, y)` with `n` steps offset by `xi`.
    fn march(&self, x: usize, y: usize, n: usize, xi: f32) -> f32 {
        let (u, v) = (
            (x as f32 + 0.5) / self.size[0] as f32,
            (y as f32 + 0.5) / self.size[1] as f32,
        );
        let dt = 1.0 / n as f32;
        let (mut l, mut tr) = (0.0f32, 1.0f32);
        for i in 0..n {
            let p = [u, v, (i as f32 + xi) * dt];
            let s = self.sample(&self.grid, p);
            let seg = (-s * dt).exp();
            // Single scattering: in-scattered light × the fraction absorbed over the step.
            l += tr * (1.0 - seg) * 0.9 * self.sample(&self.light, p);
            tr *= seg;
        }
        l + tr * 0.08
    }
}

impl App for Volume {
    fn name(&self) -> &'static str {
        "volume"
    }
    fn caption(&self) -> &'static str {
        "Single-scattering heterogeneous volume (STBN §5.3): fBm density lit from above, 8 ray-march steps offset by ξ per pixel; reference 256 steps."
    }
    fn channels(&self) -> usize {
        1
    }
    fn reference(&self) -> Vec<f32> {
        let [w, h] = self.size;
        (0..w * h)
            .map(|i| self.march(i % w, i / w, 256, 0.5))
            .collect()
    }
    fn pixel(&self, noise: Noise, x: usize, y: usize, f: u32, out: &mut [f32]) {
        out[0] = self.march(x, y, STEPS, noise.xi(x as i32, y as i32, f, 0));
    }
}

/// Ray-traced ambient occlusion of the room `noisebake report render` judges samplers in
/// (`noisebake_cli::render::scene::Scene::room`: creases, contacts, thin columns, steps,
/// spheres, open sky), one primary ray per pixel centre, traced through its BVH; one
/// cosine-weighted ray per pixel and frame within the scene's AO radius. Pixels that see the
/// sky hold 0 in every estimate and in the reference. Reference: 1024 stratified rays.
pub struct Occlusion {
    /// Image size.
    pub size: [usize; 2],
    scene: Scene,
    tracer: Tracer,
    g: GBuffer,
}

impl Occlusion {
    /// The room at `size`, its BVH and G-buffer built.
    pub fn new(size: [usize; 2]) -> Occlusion {
        let scene = Scene::room();
        let tracer = Tracer::new(&scene.triangles);
        let g = GBuffer::new(&scene, &tracer, size[0], size[1], [0, 0]);
        Occlusion {
            size,
            scene,
            tracer,
            g,
        }
    }

    /// The visibility seen from pixel `(x, y)` along `local`, a direction about +z (turned into
    /// the frame of the pixel's normal): one ray of the estimate.
    pub fn ray(&self, x: usize, y: usize, local: [f32; 3]) -> f32 {
        let i = y * self.size[0] + x;
        if !self.g.hit[i] {
            return 0.0;
        }
        render::ao_ray(
            &self.scene,
            &self.tracer,
            self.g.position[i],
            self.g.normal[i],
            local,
        )
    }
}

impl App for Occlusion {
    fn name(&self) -> &'static str {
        "occlusion"
    }
    fn caption(&self) -> &'static str {
        "Ray-traced ambient occlusion in the room `noisebake report render` traces (creases, contacts, columns, steps, spheres, open sky), one cosine-weighted ray per pixel and frame (FAST: its baked cosine-hemisphere vector mask); reference 1024 stratified rays."
    }
    fn channels(&self) -> usize {
        1
    }
    fn reference(&self) -> Vec<f32> {
        let [w, h] = self.size;
        (0..w * h)
            .into_par_iter()
            .map(|i| {
                let mut v = 0.0;
                for s in 0..1024u32 {
                    let (a, b) = ((s % 32) as f32, (s / 32) as f32);
                    let j = noisebake::hash::hash2(i as i32, s as i32, 5);
                    let u = (a + (j >> 16) as f32 / 65536.0) / 32.0;
                    let vv = (b + (j & 0xffff) as f32 / 65536.0) / 32.0;
                    v += self.ray(i % w, i / w, noisebake::warp::cosine_hemisphere(u, vv));
                }
                v / 1024.0
            })
            .collect()
    }
    fn pixel(&self, noise: Noise, x: usize, y: usize, f: u32, out: &mut [f32]) {
        out[0] = self.ray(x, y, noise.cosine_dir(x as i32, y as i32, f));
    }
}
