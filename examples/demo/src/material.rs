//! The second scene of the equal-time comparison: a procedural material under temporal
//! accumulation. A ground plane seen in perspective has an albedo of 10-octave Perlin fBm
//! (linear in the noise, so the estimators stay unbiased), lit by a small disk light that a
//! sphere shadows softly and by a sky. Each frame takes one sample per pixel — a jittered
//! position in the pixel, a point on the light and, for the stochastic variants, the noise's ξ —
//! and the frames are averaged, as a renderer's temporal accumulation does. The noise is
//! evaluated once per pixel and frame, so over the accumulation many times per pixel, and the
//! far plane packs many noise cells under a pixel: the case the estimators and band-limiting are
//! for.
//!
//! The per-pixel numbers come from the demo's baked STBN (`get_k_unit`, a fresh set of R2
//! offsets every 64 frames) or, for comparison, from white noise. STBN's values have 8 bits,
//! too coarse for the octave choice of a 10-octave estimator (octaves of probability below
//! 1/256 would never be chosen), so the estimator's ξ is the STBN value dithered within its bin
//! by a white number: still uniform on `[0, 1)`, blue in its top bits.

use crate::cloud::{Basis, Rng, Scene, Variant, fbm};
use crate::noises::STBN;
use noisebake::stochastic::Fractal;

/// Where the per-pixel numbers come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Xi {
    /// The demo's baked spatiotemporal blue noise.
    Stbn,
    /// Independent uniform numbers.
    White,
}

/// The material scene (see the module docs).
pub struct Material {
    /// Image side.
    pub size: usize,
    /// Source of the per-pixel numbers.
    pub xi: Xi,
}

const FBM: Fractal = Fractal::new(10, 2.0, 0.5);
/// Noise units per world unit on the plane.
const SCALE: f32 = 4.0;
const EYE: [f32; 3] = [0.0, 1.0, 0.0];
const PITCH: f32 = 0.45; // radians below the horizon
const FOV: f32 = 1.0; // tan of half the field of view
const LIGHT: [f32; 3] = [0.371_390_67, 0.928_476_7, 0.0]; // towards the light
const LIGHT_RADIUS: f32 = 0.12; // tan of the light's angular radius
const SPHERE: ([f32; 3], f32) = ([-0.6, 0.5, 3.0], 0.45);
const SKY: f32 = 0.75;

impl Material {
    /// The scene with STBN numbers.
    pub fn new(size: usize) -> Material {
        Material { size, xi: Xi::Stbn }
    }

    /// The variants compared in this scene: those of the clouds, band-limited ones included.
    pub fn variants() -> Vec<Variant> {
        crate::cloud::variants(true)
    }

    /// The `k`-th number of pixel `(x, y)` in frame `s`.
    fn number(&self, x: usize, y: usize, s: usize, k: u32, rng: &mut Rng) -> f32 {
        match self.xi {
            Xi::White => rng.unit_f32(),
            Xi::Stbn => STBN.get_k_unit(x as i32, y as i32, s as i32, k + 8 * (s / 64) as u32),
        }
    }

    /// Whether the ray from `p` along `d` hits the sphere.
    fn shadowed(p: [f32; 3], d: [f32; 3]) -> bool {
        let (c, r) = SPHERE;
        let oc = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
        let b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
        let cc = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - r * r;
        let disc = b * b - cc;
        disc > 0.0 && -b - disc.sqrt() > 0.0
    }
}

fn normalize(v: [f32; 3]) -> [f32; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

impl Scene for Material {
    fn name(&self) -> String {
        match self.xi {
            Xi::Stbn => "material".into(),
            Xi::White => "material-white".into(),
        }
    }
    fn size(&self) -> usize {
        self.size
    }
    fn sample(&self, x: usize, y: usize, s: usize, rng: &mut Rng, v: Variant) -> f32 {
        let n = self.size as f32;
        let jx = self.number(x, y, s, 0, rng);
        let jy = self.number(x, y, s, 1, rng);
        let sx = ((x as f32 + jx) / n * 2.0 - 1.0) * FOV;
        let sy = (1.0 - (y as f32 + jy) / n * 2.0) * FOV;
        // Camera pitched down: forward (0, −sin, cos), up (0, cos, sin).
        let (sp, cp) = PITCH.sin_cos();
        let d = normalize([sx, sy * cp - sp, sy * sp + cp]);
        if d[1] >= -1e-4 {
            return SKY;
        }
        let t = -EYE[1] / d[1];
        let p = [EYE[0] + t * d[0], 0.0, EYE[2] + t * d[2]];
        // The pixel's footprint on the plane along its narrower axis, in noise units.
        let footprint = t * 2.0 * FOV / n * SCALE;
        let xi = match self.xi {
            Xi::Stbn => {
                let b = self.number(x, y, s, 4, rng);
                ((b * 256.0).floor() + rng.unit_f32()) / 256.0
            }
            Xi::White => rng.unit_f32(),
        };
        let q = [p[0] * SCALE, 0.37, p[2] * SCALE];
        let noise = fbm(Basis::Perlin, v, q, FBM, footprint, 9, &mut || xi);
        let albedo = 0.5 + 0.4 * noise;
        // One point on the light's disk, then its visibility past the sphere.
        let (u1, u2) = (self.number(x, y, s, 2, rng), self.number(x, y, s, 3, rng));
        let a = 2.0 * std::f32::consts::PI * u1;
        let rr = LIGHT_RADIUS * u2.sqrt();
        // An orthonormal basis around the light direction (which has no z component).
        let e1 = [0.0, 0.0, 1.0];
        let e2 = [LIGHT[1], -LIGHT[0], 0.0];
        let l = normalize([
            LIGHT[0] + rr * (a.cos() * e1[0] + a.sin() * e2[0]),
            LIGHT[1] + rr * (a.cos() * e1[1] + a.sin() * e2[1]),
            LIGHT[2] + rr * (a.cos() * e1[2] + a.sin() * e2[2]),
        ]);
        let lit = if Self::shadowed(p, l) { 0.0 } else { l[1] };
        albedo * (0.25 + 0.9 * lit)
    }
}
