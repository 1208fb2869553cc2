//! Sparse convolution noise (Lewis 1989; Fajardo & Pharr §4): impulses at hashed positions in
//! unit cells, convolved with the kernel `(1 − r²)³` of radius 1, so only the 27 cells around the point
//! matter (eq. 7). Impulse `i` of `n` in a cell has the stratified weight `±(i + ½)/n`, which
//! lets the estimator importance-sample one impulse per cell directly with `i = ⌊n √ξ⌋`
//! (probability `(2i + 1)/n²`), giving eq. (8): `½ Σ_c ±k(|p − p_(i,c)|)`.

use super::estimators::sanitize_xi;
use super::fractal::{Fractal, fractal, fractal_stochastic};
use super::hash::{PRIME, corner};
use crate::math::{in_split_range, split, split_in_range};

/// Kernel `k(r) = (1 − r²)³` for `r < 1`, 0 beyond: smooth (C¹ at the support edge, zero
/// slope) and polynomial in `r²`, so no square root.
#[inline(always)]
fn kernel(r2: f32) -> f32 {
    let t = (1.0 - r2).max(0.0);
    t * t * t
}

/// Position in the cell (21-bit coordinates) and sign of impulse `i` of the cell with hash `h`:
/// one 64-bit multiply–xorshift–multiply of `(h, i)`, so any impulse is reached directly. The
/// sign is a sign-bit mask for [`flip`]: a random ±1 as a float select would become a branch,
/// mispredicted on half of all impulses.
#[inline(always)]
pub(crate) fn impulse(h: u32, i: u32) -> ([f32; 3], u32) {
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
        (z as u32) << 31,
    )
}

/// `v` with its sign bit flipped by `sign` (0 or `0x8000_0000`, from [`impulse`]).
#[inline(always)]
pub(crate) fn flip(v: f32, sign: u32) -> f32 {
    f32::from_bits(v.to_bits() ^ sign)
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
    if in_split_range(p) {
        block_with(p, split_in_range)
    } else {
        block_with(p, split)
    }
}

#[inline(always)]
fn block_with(
    p: [f32; 3],
    sp: impl Fn(f32) -> (i32, f32),
) -> ([[u32; 3]; 3], [f32; 3], [[f32; 3]; 3]) {
    let mut hp = [[0u32; 3]; 3];
    let mut f = [0.0f32; 3];
    let mut slab = [[0.0f32; 3]; 3];
    for a in 0..3 {
        let (c, fa) = sp(p[a]);
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

/// The cells of the 3×3×3 block around `p` that the kernel's unit ball reaches (about 21 of 27
/// on average), compacted: their hashes and the offsets of `p` from their corners.
pub(crate) struct Reach {
    /// Hashes of the reachable cells (the first `count`; the rest are scratch).
    pub(crate) hash: [u32; 27],
    offset: [[f32; 3]; 27],
    count: usize,
}

impl Reach {
    /// Every cell is written and the count advanced only for reachable ones, so no branch
    /// depends on where `p` lies in its cell (such branches mispredict on random points); the
    /// loops over the compacted cells then exit on one count.
    #[inline(always)]
    pub(crate) fn new(p: [f32; 3], seed: u32) -> Self {
        let (hp, f, slab) = block(p);
        let mut r = Reach {
            hash: [0; 27],
            offset: [[0.0; 3]; 27],
            count: 0,
        };
        for k in 0..3 {
            for j in 0..3 {
                for i in 0..3 {
                    let c = r.count;
                    r.hash[c] = corner(seed, hp[0][i], hp[1][j], hp[2][k]);
                    r.offset[c] = [
                        f[0] + 1.0 - i as f32,
                        f[1] + 1.0 - j as f32,
                        f[2] + 1.0 - k as f32,
                    ];
                    r.count += (slab[0][i] + slab[1][j] + slab[2][k] < 1.0) as usize;
                }
            }
        }
        r
    }

    /// The reachable cells as `(hash, offset of p from the cell's corner)`.
    #[inline(always)]
    pub(crate) fn iter(&self) -> impl Iterator<Item = (u32, [f32; 3])> + '_ {
        self.hash[..self.count]
            .iter()
            .copied()
            .zip(self.offset[..self.count].iter().copied())
    }
}

/// Calls `each(cell hash, offset of p from that cell's corner)` for the cells of the 3×3×3
/// block that the kernel's unit ball around `p` reaches.
#[inline(always)]
pub(crate) fn cells(p: [f32; 3], seed: u32, mut each: impl FnMut(u32, [f32; 3])) {
    for (h, d) in Reach::new(p, seed).iter() {
        each(h, d);
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
            sum += flip((i as f32 + 0.5) * kernel(r2(d, q)), s);
        }
    });
    sum * inv * inv
}

/// One-sample estimator of [`sparse_conv3`] (eq. 8): one importance-sampled impulse per cell.
/// Each cell uses ξ rotated by a hash of the cell (Cranley–Patterson), so cells are decorrelated
/// while each still sees a uniform ξ.
#[inline]
pub fn sparse_conv3_stochastic(p: [f32; 3], n: u32, seed: u32, xi: f32) -> f32 {
    let n = n.clamp(1, 64);
    let xi = sanitize_xi(xi);
    let r = Reach::new(p, seed);
    // The impulse of every cell first, in one fixed-length pass without branches (which LLVM
    // vectorises), so the impulse evaluations below do not each wait on a square root.
    let idx: [u32; 27] = core::array::from_fn(|c| importance_index(rotate(xi, r.hash[c]), n));
    let mut sum = 0.0;
    for ((h, d), &i) in r.iter().zip(&idx) {
        let (q, s) = impulse(h, i);
        sum += flip(kernel(r2(d, q)), s);
    }
    0.5 * sum
}

/// The impulse `i = ⌊n √u⌋` (probability `(2i + 1)/n²` for uniform `u ∈ [0, 1)`, eq. 8),
/// branch-free: `√u` as `u · 1/√u` from the bit-level first guess and three Newton steps
/// (relative error below 3e-7), with `u` kept away from 0.
#[inline(always)]
pub(crate) fn importance_index(u: f32, n: u32) -> u32 {
    let v = u.max(1e-30);
    let mut y = f32::from_bits(0x5f37_5a86u32.wrapping_sub(v.to_bits() >> 1));
    let h = 0.5 * v;
    y *= 1.5 - h * y * y;
    y *= 1.5 - h * y * y;
    y *= 1.5 - h * y * y;
    // `as i32`: the product is in [0, n], and the signed conversion is one instruction where
    // the unsigned one branches.
    ((n as f32 * (u * y)) as i32 as u32).min(n - 1)
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
    let (q, s) = impulse(h, importance_index(rest, n));
    flip(0.5 * count as f32 * kernel(r2(d, q)), s)
}

/// One-term estimator of [`fbm_sparse_conv3`]: one octave, one cell, one impulse.
#[inline]
pub fn fbm_sparse_conv3_stochastic1(p: [f32; 3], f: Fractal, n: u32, seed: u32, xi: f32) -> f32 {
    fractal_stochastic(p, f, xi, |q, o, x| {
        sparse_conv3_stochastic1(q, n, octave_seed(seed, o), x)
    })
}
