//! Sparse convolution noise (Lewis 1989; Fajardo & Pharr §4): impulses at hashed positions in
//! unit cells, convolved with a kernel of radius 1, so only the 27 cells around the point
//! matter (eq. 7). Impulse `i` of `n` in a cell has the stratified weight `±(i + ½)/n`, which
//! lets the estimator importance-sample one impulse per cell directly with `i = ⌊n √ξ⌋`
//! (probability `(2i + 1)/n²`), giving eq. (8): `½ Σ_c ±k(|p − p_(i,c)|)`.

use super::estimators::sanitize_xi;
use super::fractal::{Fractal, fractal, fractal_stochastic};
use super::hash::{hash3, mix, unit};
use crate::math::{split, sqrt_fast};

/// Kernel `k(r) = 1 − fade(r)` for `r < 1` (a C² quintic falloff), 0 beyond.
#[inline(always)]
fn kernel(r2: f32) -> f32 {
    if r2 >= 1.0 {
        return 0.0;
    }
    let r = sqrt_fast(r2);
    1.0 - r * r * r * (r * (r * 6.0 - 15.0) + 10.0)
}

/// Position in the cell and sign of impulse `i` of a cell with hash `h`.
#[inline(always)]
fn impulse(h: u32, i: u32) -> ([f32; 3], f32) {
    let a = mix(h ^ i.wrapping_mul(0x9e37_79b9));
    let b = mix(a);
    let c = mix(b);
    (
        [unit(a), unit(b), unit(c)],
        if c & 1 == 0 { 1.0 } else { -1.0 },
    )
}

#[inline(always)]
fn r2(f: [f32; 3], d: [i32; 3], q: [f32; 3]) -> f32 {
    let x = f[0] - d[0] as f32 - q[0];
    let y = f[1] - d[1] as f32 - q[1];
    let z = f[2] - d[2] as f32 - q[2];
    x * x + y * y + z * z
}

#[inline(always)]
fn cells(p: [f32; 3], mut each: impl FnMut(u32, [f32; 3], [i32; 3])) {
    let (cx, fx) = split(p[0]);
    let (cy, fy) = split(p[1]);
    let (cz, fz) = split(p[2]);
    let f = [fx, fy, fz];
    for dz in -1..=1 {
        for dy in -1..=1 {
            for dx in -1..=1 {
                let h = hash3(
                    cx.wrapping_add(dx),
                    cy.wrapping_add(dy),
                    cz.wrapping_add(dz),
                    0,
                );
                each(h, f, [dx, dy, dz]);
            }
        }
    }
}

/// Sparse convolution noise with `n` impulses per cell (`n` clamped to `1..=64`; the paper uses
/// 10): `(1/n) Σ_c Σ_i w_i k(|p − p_(i,c)|)` (eq. 7).
#[inline]
pub fn sparse_conv3(p: [f32; 3], n: u32, seed: u32) -> f32 {
    let n = n.clamp(1, 64);
    let inv = 1.0 / n as f32;
    let mut sum = 0.0;
    cells(p, |h, f, d| {
        let h = h ^ seed;
        for i in 0..n {
            let (q, s) = impulse(h, i);
            let k = kernel(r2(f, d, q));
            if k > 0.0 {
                sum += s * (i as f32 + 0.5) * inv * k;
            }
        }
    });
    sum * inv
}

/// One-sample estimator of [`sparse_conv3`] (eq. 8): one importance-sampled impulse per cell.
/// Each cell uses ξ rotated by a hash of the cell (Cranley–Patterson), so cells are decorrelated
/// while each still sees a uniform ξ.
#[inline]
pub fn sparse_conv3_stochastic(p: [f32; 3], n: u32, seed: u32, xi: f32) -> f32 {
    let n = n.clamp(1, 64);
    let xi = sanitize_xi(xi);
    let mut sum = 0.0;
    cells(p, |h, f, d| {
        let h = h ^ seed;
        let mut x = xi + unit(mix(h ^ 0x51ed_270b));
        if x >= 1.0 {
            x -= 1.0;
        }
        let i = ((n as f32 * sqrt_fast(x)) as u32).min(n - 1);
        let (q, s) = impulse(h, i);
        sum += s * kernel(r2(f, d, q));
    });
    0.5 * sum
}

#[inline(always)]
fn octave_seed(seed: u32, o: u32) -> u32 {
    seed.wrapping_add(o.wrapping_mul(0x9e37_79b9))
}

/// Fractal sum of [`sparse_conv3`] with `n` impulses per cell.
#[inline]
pub fn fbm_sparse_conv3(p: [f32; 3], f: Fractal, n: u32, seed: u32) -> f32 {
    fractal(p, f, |q, o| sparse_conv3(q, n, octave_seed(seed, o)))
}

/// One-sample estimator of [`fbm_sparse_conv3`]: one octave (Algorithm 2), and in it one
/// impulse per cell (eq. 8).
#[inline]
pub fn fbm_sparse_conv3_stochastic(p: [f32; 3], f: Fractal, n: u32, seed: u32, xi: f32) -> f32 {
    fractal_stochastic(p, f, xi, |q, o, x| {
        sparse_conv3_stochastic(q, n, octave_seed(seed, o), x)
    })
}
