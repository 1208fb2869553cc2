//! Sparse convolution noise (Lewis 1989; Fajardo & Pharr §4): impulses at hashed positions in
//! unit cells, convolved with the kernel `(1 − r²)³` of radius 1, so only the 27 cells around the point
//! matter (eq. 7). Impulse `i` of `n` in a cell has the stratified weight `±(i + ½)/n`, which
//! lets the estimator importance-sample one impulse per cell directly with `i = ⌊n √ξ⌋`
//! (probability `(2i + 1)/n²`), giving eq. (8): `½ Σ_c ±k(|p − p_(i,c)|)`.

use super::estimators::sanitize_xi;
use super::fractal::{Fractal, fractal, fractal_stochastic};
use super::hash::{PRIME, corner};
use crate::math::{split, sqrt_fast};

/// Kernel `k(r) = (1 − r²)³` for `r < 1`, 0 beyond: smooth (C¹ at the support edge, zero
/// slope) and polynomial in `r²`, so no square root.
#[inline(always)]
fn kernel(r2: f32) -> f32 {
    let t = 1.0 - r2;
    if t > 0.0 { t * t * t } else { 0.0 }
}

/// Position in the cell (21-bit coordinates) and sign of impulse `i` of the cell with hash `h`:
/// one 64-bit multiply–xorshift–multiply of `(h, i)`, so any impulse is reached directly.
#[inline(always)]
pub(crate) fn impulse(h: u32, i: u32) -> ([f32; 3], f32) {
    let mut z = ((h as u64) << 32 | i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z ^= z >> 29;
    z = z.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    const S: f32 = 1.0 / 2_097_152.0;
    (
        [
            (z >> 43) as i32 as f32 * S,
            ((z >> 22) & 0x1f_ffff) as i32 as f32 * S,
            ((z >> 1) & 0x1f_ffff) as i32 as f32 * S,
        ],
        if z & 1 == 0 { 1.0 } else { -1.0 },
    )
}

/// ξ rotated by the cell hash `h` (Cranley–Patterson) on the 2^-24 grid, in `[0, 1)`: integer
/// addition modulo 2^24 instead of a float compare-and-subtract, whose branch would mispredict
/// on half the cells.
#[inline(always)]
pub(crate) fn rotate(xi: f32, h: u32) -> f32 {
    let u = ((xi * 16_777_216.0) as u32).wrapping_add(h >> 8) & 0x00ff_ffff;
    u as f32 * (1.0 / 16_777_216.0)
}

#[inline(always)]
fn r2(f: [f32; 3], q: [f32; 3]) -> f32 {
    let x = f[0] - q[0];
    let y = f[1] - q[1];
    let z = f[2] - q[2];
    x * x + y * y + z * z
}

/// The 3×3×3 cell block around `p`: per axis, the hash products of the cells at offsets
/// −1, 0, +1, the offset of `p` in its cell, and the squared distance from `p` to each of the
/// three slabs (0 for its own).
#[inline(always)]
fn block(p: [f32; 3]) -> ([[u32; 3]; 3], [f32; 3], [[f32; 3]; 3]) {
    let mut hp = [[0u32; 3]; 3];
    let mut f = [0.0f32; 3];
    let mut slab = [[0.0f32; 3]; 3];
    for a in 0..3 {
        let (c, fa) = split(p[a]);
        let base = (c as u32).wrapping_mul(PRIME[a]);
        hp[a] = [
            base.wrapping_sub(PRIME[a]),
            base,
            base.wrapping_add(PRIME[a]),
        ];
        f[a] = fa;
        slab[a] = [fa * fa, 0.0, (1.0 - fa) * (1.0 - fa)];
    }
    (hp, f, slab)
}

/// Calls `each(cell hash, offset of p from that cell's corner)` for the cells of the 3×3×3
/// block that the kernel's unit ball around `p` reaches (about 21 of 27 on average).
#[inline(always)]
pub(crate) fn cells(p: [f32; 3], seed: u32, mut each: impl FnMut(u32, [f32; 3])) {
    let (hp, f, slab) = block(p);
    for k in 0..3 {
        for j in 0..3 {
            let s_jk = slab[1][j] + slab[2][k];
            if s_jk >= 1.0 {
                continue;
            }
            for i in 0..3 {
                if slab[0][i] + s_jk >= 1.0 {
                    continue;
                }
                let h = corner(seed, hp[0][i], hp[1][j], hp[2][k]);
                each(
                    h,
                    [
                        f[0] + 1.0 - i as f32,
                        f[1] + 1.0 - j as f32,
                        f[2] + 1.0 - k as f32,
                    ],
                );
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
    cells(p, seed, |h, d| {
        for i in 0..n {
            let (q, s) = impulse(h, i);
            let k = kernel(r2(d, q));
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
    let nf = n as f32;
    let mut sum = 0.0;
    cells(p, seed, |h, d| {
        let i = ((nf * sqrt_fast(rotate(xi, h))) as u32).min(n - 1);
        let (q, s) = impulse(h, i);
        sum += s * kernel(r2(d, q));
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

/// One-term estimator of [`sparse_conv3`]: the 27-cell sum is sampled too (Fajardo & Pharr §4:
/// "sample a single term from both sums, giving a savings of 27n×"). ξ first picks one of the
/// cells the kernel can reach (weight = their count; the others contribute nothing), then,
/// remapped, one impulse in it by `i = ⌊n √ξ⌋` (eq. 8). One kernel evaluation per call; far
/// more variance than [`sparse_conv3_stochastic`] — the report shows both.
#[inline]
pub fn sparse_conv3_stochastic1(p: [f32; 3], n: u32, seed: u32, xi: f32) -> f32 {
    let n = n.clamp(1, 64);
    let (hp, f, slab) = block(p);
    // The reachable cells, in a fixed order.
    let mut reach = [(0u8, 0u8, 0u8); 27];
    let mut count = 0usize;
    for k in 0..3u8 {
        for j in 0..3u8 {
            for i in 0..3u8 {
                let d = slab[0][i as usize] + slab[1][j as usize] + slab[2][k as usize];
                reach[count] = (i, j, k);
                count += (d < 1.0) as usize;
            }
        }
    }
    if count == 0 {
        return 0.0;
    }
    let x = sanitize_xi(xi) * count as f32;
    let pick = (x as usize).min(count - 1);
    let rest = (x - pick as f32).clamp(0.0, super::estimators::ONE_BELOW);
    let (i, j, k) = reach[pick];
    let h = corner(
        seed,
        hp[0][i as usize],
        hp[1][j as usize],
        hp[2][k as usize],
    );
    let d = [
        f[0] + 1.0 - i as f32,
        f[1] + 1.0 - j as f32,
        f[2] + 1.0 - k as f32,
    ];
    let imp = ((n as f32 * sqrt_fast(rest)) as u32).min(n - 1);
    let (q, s) = impulse(h, imp);
    0.5 * count as f32 * s * kernel(r2(d, q))
}

/// One-term estimator of [`fbm_sparse_conv3`]: one octave, one cell, one impulse.
#[inline]
pub fn fbm_sparse_conv3_stochastic1(p: [f32; 3], f: Fractal, n: u32, seed: u32, xi: f32) -> f32 {
    fractal_stochastic(p, f, xi, |q, o, x| {
        sparse_conv3_stochastic1(q, n, octave_seed(seed, o), x)
    })
}
