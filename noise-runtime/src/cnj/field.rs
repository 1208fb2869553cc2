//! The curl-noise velocity fields that displace the lattice (CNJ eq. 4–5, §2.1).
//!
//! 2D: gradient noise `N` with quintic fade and analytic derivatives (gradients uniform in
//! `[−1, 1]²`, as in the Perlin-noise-with-derivatives formulation the paper adapts), and
//! `V(x) = (∂N(x/s)/∂y, −∂N(x/s)/∂x)` — the paper's sign (eq. 5). 3D: the curl of a vector
//! potential made of three 3D gradient noises with different seeds.
//!
//! Positions arrive as `f64` and are split into an integer noise cell and an `f32` offset in
//! `f64`, so the field is exact for any lattice site an `i32` can name; the arithmetic after the
//! split is `f32`.

use crate::gradients;
use crate::hash::PRIME;
use crate::math::{dfade, fade};
use crate::stochastic::Perlin;

/// Splits `x` into cell and offset in `[0, 1)`, in `f64` (total for finite input).
#[inline(always)]
pub(crate) fn split64(x: f64) -> (i32, f32) {
    let fl = if x.is_finite() {
        let t = x as i64 as f64;
        if t > x { t - 1.0 } else { t }
    } else {
        0.0
    };
    let f = (x - fl) as f32;
    (
        fl as i64 as i32,
        if (0.0..1.0).contains(&f) { f } else { 0.0 },
    )
}

/// The gradient of lattice point `(ix, iy)`: uniform in `[−1, 1]²`
/// ([`gradients::uniform2`]) from its corner hash.
#[inline(always)]
fn grad2(ix: i32, iy: i32, seed: u32) -> [f32; 2] {
    gradients::uniform2(
        seed ^ (ix as u32).wrapping_mul(PRIME[0]) ^ (iy as u32).wrapping_mul(PRIME[1]),
    )
}

/// 2D gradient noise and its gradient `(n, ∂n/∂x, ∂n/∂y)` at `p` (noise units).
#[must_use]
#[inline]
pub fn noise2(p: [f64; 2], seed: u32) -> (f32, f32, f32) {
    let (ix, x) = split64(p[0]);
    let (iy, y) = split64(p[1]);
    let ga = grad2(ix, iy, seed);
    let gb = grad2(ix.wrapping_add(1), iy, seed);
    let gc = grad2(ix, iy.wrapping_add(1), seed);
    let gd = grad2(ix.wrapping_add(1), iy.wrapping_add(1), seed);
    let va = ga[0] * x + ga[1] * y;
    let vb = gb[0] * (x - 1.0) + gb[1] * y;
    let vc = gc[0] * x + gc[1] * (y - 1.0);
    let vd = gd[0] * (x - 1.0) + gd[1] * (y - 1.0);
    let (ux, uy) = (fade(x), fade(y));
    let (dx, dy) = (dfade(x), dfade(y));
    let k = va - vb - vc + vd;
    let n = va + ux * (vb - va) + uy * (vc - va) + ux * uy * k;
    let nx = ga[0]
        + ux * (gb[0] - ga[0])
        + uy * (gc[0] - ga[0])
        + ux * uy * (ga[0] - gb[0] - gc[0] + gd[0])
        + dx * (uy * k + (vb - va));
    let ny = ga[1]
        + ux * (gb[1] - ga[1])
        + uy * (gc[1] - ga[1])
        + ux * uy * (ga[1] - gb[1] - gc[1] + gd[1])
        + dy * (ux * k + (vc - va));
    (n, nx, ny)
}

/// Amplitude of the 2D noise relative to [`noise2`]: calibrated so that the paper's `t` and `s`
/// give the reference implementation's displacements (largest 1.15 spacings; [`noise2`]'s
/// gradients in `[−1, 1]²` alone give 0.80).
pub const NOISE_GAIN: f64 = 1.4375;

/// The 2D curl-noise velocity at `p` (lattice units) for noise scale `s`:
/// `V = (∂N(p/s)/∂y, −∂N(p/s)/∂x)` (eq. 5), derivatives taken w.r.t. `p` (hence the `1/s`).
///
/// `s` below [`MIN_SCALE`] is taken as `MIN_SCALE`; a non-positive or NaN `s` gives no flow
/// (zero velocity). So finite `p` always gives a finite velocity.
#[must_use]
#[inline]
pub fn velocity2(p: [f64; 2], s: f64, seed: u32) -> [f32; 2] {
    let Some(s) = noise_scale(s) else {
        return [0.0; 2];
    };
    let inv_s = 1.0 / s;
    let (_, nx, ny) = noise2([p[0] * inv_s, p[1] * inv_s], seed);
    let inv = (NOISE_GAIN / s) as f32;
    [ny * inv, -nx * inv]
}

/// The 3D curl-noise velocity at `p`: `∇ × Φ(p/s)` with `Φ = (N₁, N₂, N₃)` three 3D gradient
/// noises (improved Perlin noise with different seeds). Divergence-free by construction.
///
/// `s` is treated as in [`velocity2`]: at least [`MIN_SCALE`], and no flow for a non-positive
/// or NaN `s`.
#[must_use]
#[inline]
pub fn velocity3(p: [f64; 3], s: f64, seed: u32) -> [f32; 3] {
    let Some(s) = noise_scale(s) else {
        return [0.0; 3];
    };
    let mut cell = [0i32; 3];
    let mut f = [0.0f32; 3];
    for a in 0..3 {
        (cell[a], f[a]) = split64(p[a] / s);
    }
    let q = |seed: u32| Perlin::new(seed).gradient_in_cell(cell, f).1;
    let g1 = q(seed);
    let g2 = q(seed ^ 0x6a09_e667);
    let g3 = q(seed ^ 0xbb67_ae85);
    let inv = (1.0 / s) as f32;
    // curl Φ = (∂Φz/∂y − ∂Φy/∂z, ∂Φx/∂z − ∂Φz/∂x, ∂Φy/∂x − ∂Φx/∂y)
    [
        (g3[1] - g2[2]) * inv,
        (g1[2] - g3[0]) * inv,
        (g2[0] - g1[1]) * inv,
    ]
}

/// The smallest noise scale the velocity fields use (in lattice units); the lattices clamp
/// their `s` to it too.
pub const MIN_SCALE: f64 = 1e-3;

/// `s` made safe for the fields: `None` (no flow) when non-positive or NaN, else at least
/// [`MIN_SCALE`] (an infinite `s` gives zero velocity through `1/s`).
#[inline]
fn noise_scale(s: f64) -> Option<f64> {
    (s > 0.0).then(|| s.max(MIN_SCALE))
}

/// Waves per component of the sum-of-sines potential.
pub const SOS_WAVES: usize = 32;

/// A sum-of-sines vector potential (CNJ §2.3, eq. 7–8, in 3D): per component,
/// `N(q) = (1/√W) Σ_w a_w sin 2π(d_w·q + φ_w)` with directions uniform on the sphere, frequency
/// `|d| = 1 + g` cycles per noise unit, `g` approximately normal (σ 1, Irwin–Hall of four
/// uniforms), amplitude `a = e^{−g²}`, phase uniform — the paper's construction with σ = 1.
#[derive(Clone, Debug)]
pub struct SumOfSines3 {
    amp: [f32; 3 * SOS_WAVES],
    dir: [[f32; 3]; 3 * SOS_WAVES],
    phase: [f32; 3 * SOS_WAVES],
}

impl SumOfSines3 {
    /// The waves of `seed`.
    #[must_use]
    pub fn new(seed: u32) -> SumOfSines3 {
        let mut w = SumOfSines3 {
            amp: [0.0; 3 * SOS_WAVES],
            dir: [[0.0; 3]; 3 * SOS_WAVES],
            phase: [0.0; 3 * SOS_WAVES],
        };
        let unit = |h: u32| (h >> 8) as f32 * (1.0 / 16_777_216.0);
        for i in 0..3 * SOS_WAVES {
            let h = |k: i32| crate::hash::hash3(i as i32, k, 0x5150_5150, seed);
            let z = 1.0 - 2.0 * unit(h(0));
            let r = crate::math::sqrt((1.0 - z * z).max(0.0));
            let az = unit(h(1));
            let g = (unit(h(2)) + unit(h(3)) + unit(h(4)) + unit(h(5)) - 2.0) * 1.732_050_8;
            let f = (1.0 + g).max(0.05);
            w.dir[i] = [
                f * r * crate::math::cos_turns(az),
                f * r * crate::math::cos_turns(az - 0.25),
                f * z,
            ];
            w.amp[i] = crate::math::exp_neg(-g * g);
            w.phase[i] = unit(h(6));
        }
        w
    }

    /// Gradients of the three components at `q` (noise units).
    fn gradients(&self, q: [f64; 3]) -> [[f32; 3]; 3] {
        let norm = core::f32::consts::TAU / crate::math::sqrt(SOS_WAVES as f32);
        let mut g = [[0.0f32; 3]; 3];
        for (c, gc) in g.iter_mut().enumerate() {
            for w in c * SOS_WAVES..(c + 1) * SOS_WAVES {
                let d = self.dir[w];
                let t = d[0] as f64 * q[0] + d[1] as f64 * q[1] + d[2] as f64 * q[2];
                let turns = crate::math::fract_f64(t) as f32 + self.phase[w];
                let k = self.amp[w] * norm * crate::math::cos_turns(turns);
                for a in 0..3 {
                    gc[a] += k * d[a];
                }
            }
        }
        g
    }

    /// The curl of the potential at `p` (lattice units) for noise scale `s`.
    #[must_use]
    pub fn velocity(&self, p: [f64; 3], s: f64) -> [f32; 3] {
        let inv = 1.0 / s;
        let [g1, g2, g3] = self.gradients([p[0] * inv, p[1] * inv, p[2] * inv]);
        let inv = inv as f32;
        [
            (g3[1] - g2[2]) * inv,
            (g1[2] - g3[0]) * inv,
            (g2[0] - g1[1]) * inv,
        ]
    }
}
