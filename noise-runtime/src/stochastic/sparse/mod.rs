//! Sparse convolution noise (Lewis 1989; Fajardo & Pharr §4): impulses at hashed positions in
//! unit cells, convolved with the kernel `(1 − r²)³` of radius 1, so only the 27 cells around the point
//! matter (eq. 7). Impulse `i` of `n` in a cell has the stratified weight `±(i + ½)/n`, which
//! lets the estimator importance-sample one impulse per cell directly with `i = ⌊n √ξ⌋`
//! (probability `(2i + 1)/n²`), giving eq. (8): `½ Σ_c ±k(|p − p_(i,c)|)`.

use super::estimators::sanitize_xi;
use super::fractal::Octaves;
use super::fractal::{Fractal, fractal, fractal_estimate, fractal_tail_estimate, octave_seed};
use super::noise::Noise;
use crate::hash::{PRIME, corner};
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

/// A uniform `u ∈ [0, 1)` as its 24 bits `U` on the 2^-24 grid (`u = U / 2^24`).
#[inline(always)]
pub(crate) fn unit_bits(u: f32) -> u32 {
    ((u * 16_777_216.0) as u32).min(0x00ff_ffff)
}

/// ξ (as [`unit_bits`]) rotated by the cell hash `h` (Cranley–Patterson), modulo 1: an integer
/// addition modulo 2^24 instead of a float compare-and-subtract, whose branch would mispredict
/// on half the cells.
#[inline(always)]
pub(crate) fn rotate(xi_bits: u32, h: u32) -> u32 {
    xi_bits.wrapping_add(h >> 8) & 0x00ff_ffff
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
/// on average), compacted: their hashes and block numbers.
pub(crate) struct Reach {
    /// Hashes of the reachable cells (the first `count`; the rest are scratch).
    pub(crate) hash: [u32; 27],
    /// Block numbers `i + 3j + 9k` of the reachable cells (the cell at offset
    /// `(i − 1, j − 1, k − 1)` from `p`'s), likewise.
    block: [u8; 27],
    /// `p`'s offset in its own cell plus 1 per axis: the offset from block cell `(i, j, k)`'s
    /// corner is this minus `(i, j, k)`.
    f1: [f32; 4],
    count: usize,
}

/// `BLOCK_CELL[i + 3j + 9k] = (i, j, k, 0)`, padded to 32 rows so an index modulo 32 needs no
/// bounds check.
static BLOCK_CELL: [[f32; 4]; 32] = {
    let mut t = [[0.0f32; 4]; 32];
    let mut c = 0;
    while c < 27 {
        t[c] = [(c % 3) as f32, (c / 3 % 3) as f32, (c / 9) as f32, 0.0];
        c += 1;
    }
    t
};

impl Reach {
    /// Every cell is written and the count advanced only for reachable ones, so no branch
    /// depends on where `p` lies in its cell (such branches mispredict on random points); the
    /// loops over the compacted cells then exit on one count. A cell's offset is not stored
    /// but made from its block number when read: a byte per cell instead of three floats,
    /// and a third of the memory to clear (135 bytes instead of 432).
    #[inline(always)]
    pub(crate) fn new(p: [f32; 3], seed: u32) -> Self {
        let (hp, f, slab) = block(p);
        let mut r = Reach {
            hash: [0; 27],
            block: [0; 27],
            f1: [f[0] + 1.0, f[1] + 1.0, f[2] + 1.0, 0.0],
            count: 0,
        };
        for k in 0..3 {
            for j in 0..3 {
                for i in 0..3 {
                    let c = r.count;
                    r.hash[c] = corner(seed, hp[0][i], hp[1][j], hp[2][k]);
                    r.block[c] = (i + 3 * j + 9 * k) as u8;
                    r.count += (slab[0][i] + slab[1][j] + slab[2][k] < 1.0) as usize;
                }
            }
        }
        r
    }

    /// The offset of `p` from the corner of reachable cell `c` (`c < count`), as [`Reach::iter`]
    /// gives it.
    #[inline(always)]
    pub(crate) fn offset(&self, c: usize) -> [f32; 3] {
        let b = BLOCK_CELL[self.block[c % 27] as usize & 31];
        [self.f1[0] - b[0], self.f1[1] - b[1], self.f1[2] - b[2]]
    }

    /// The reachable cells as `(hash, offset of p from the cell's corner)`.
    #[inline(always)]
    pub(crate) fn iter(&self) -> impl Iterator<Item = (u32, [f32; 3])> + '_ {
        self.hash[..self.count]
            .iter()
            .copied()
            .zip(self.block[..self.count].iter().map(|&c| {
                let b = BLOCK_CELL[c as usize & 31];
                // The same rounding as `(f + 1) − i` per axis.
                [self.f1[0] - b[0], self.f1[1] - b[1], self.f1[2] - b[2]]
            }))
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
/// while each still sees a uniform ξ. (Eq. 8 as printed takes one index `i` for every cell;
/// measured by `noisebake report stochastic`, that shared index saves the per-cell rotation,
/// 6.2× → 7.1× over the sum, but doubles the variance, RMSE 0.37 against 0.25 at one sample:
/// half the efficiency, so the rotation stays.)
///
/// Against [`sparse_conv3`] its speedup cannot reach `n` (the paper's GPU figure, 10.9× at
/// `n = 10`, is above it): both find the same cells, and per cell the estimator evaluates one
/// impulse, and picks it, where the sum evaluates `n`, so the times are `R + N·(c + s)` and
/// `R + N·n·c` for a shared cost `R`, `N` cells, `c` per impulse and `s` for the pick.
#[inline]
pub fn sparse_conv3_stochastic(p: [f32; 3], n: u32, seed: u32, xi: f32) -> f32 {
    let n = n.clamp(1, 64);
    let xi = unit_bits(sanitize_xi(xi));
    let mut sum = 0.0;
    for (h, d) in Reach::new(p, seed).iter() {
        let (q, s) = impulse(h, importance_index(rotate(xi, h), n));
        sum += flip(kernel(r2(d, q)), s);
    }
    0.5 * sum
}

/// The impulse `i = ⌊n √u⌋` of `n ≤ 64` (probability `(2i + 1)/n²` for uniform `u ∈ [0, 1)`,
/// eq. 8), with `u` given as its 24 bits `U`, exactly and without a square root: `⌊√x⌋ =
/// ⌊√⌊x⌋⌋`, so `i = ⌊√⌊n² u⌋⌋`, where `⌊n² u⌋ = n²U >> 24` is below `n² ≤ 4096` and its
/// integer square root one read of [`ISQRT`]. (A float square root by Newton steps measured
/// several times slower in a stochastic Gabor call, and its rounding could move `i` by one
/// near the boundaries.)
#[inline(always)]
pub(crate) fn importance_index(u_bits: u32, n: u32) -> u32 {
    debug_assert!((1..=64).contains(&n) && u_bits < 1 << 24);
    let w = ((n * n) as u64 * u_bits as u64) >> 24;
    // The mask changes nothing (w < n² ≤ 4096) but spares the bounds check.
    ISQRT[w as usize & 4095] as u32
}

/// `ISQRT[w] = ⌊√w⌋`.
static ISQRT: [u8; 4096] = {
    let mut t = [0u8; 4096];
    let mut r = 0usize;
    let mut w = 0;
    while w < 4096 {
        if (r + 1) * (r + 1) <= w {
            r += 1;
        }
        t[w] = r as u8;
        w += 1;
    }
    t
};

/// Fractal sum of [`sparse_conv3`] with `n` impulses per cell.
#[inline]
pub fn fbm_sparse_conv3(p: [f32; 3], f: Fractal, n: u32, seed: u32) -> f32 {
    fractal(p, f, |q, o| sparse_conv3(q, n, octave_seed(seed, o)))
}

/// One-sample estimator of [`fbm_sparse_conv3`]: one octave (Algorithm 2), and in it one
/// impulse per cell (eq. 8).
#[inline]
pub fn fbm_sparse_conv3_stochastic(p: [f32; 3], f: Fractal, n: u32, seed: u32, xi: f32) -> f32 {
    fractal_estimate(p, f, xi, |q, o, x| {
        sparse_conv3_stochastic(q, n, octave_seed(seed, o), x)
    })
}

/// [`fbm_sparse_conv3`] with its first `exact` octaves exact and one octave of the rest sampled,
/// one impulse per cell ([`fractal_tail_estimate`]).
#[inline]
pub fn fbm_sparse_conv3_tail_stochastic(
    p: [f32; 3],
    f: Fractal,
    exact: u32,
    n: u32,
    seed: u32,
    xi: f32,
) -> f32 {
    fractal_tail_estimate(
        p,
        f,
        exact,
        xi,
        |q, o| sparse_conv3(q, n, octave_seed(seed, o)),
        |q, o, x| sparse_conv3_stochastic(q, n, octave_seed(seed, o), x),
    )
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
    let (q, s) = impulse(h, importance_index(unit_bits(rest), n));
    flip(0.5 * count as f32 * kernel(r2(d, q)), s)
}

/// One-term estimator of [`fbm_sparse_conv3`]: one octave, one cell, one impulse.
#[inline]
pub fn fbm_sparse_conv3_stochastic1(p: [f32; 3], f: Fractal, n: u32, seed: u32, xi: f32) -> f32 {
    fractal_estimate(p, f, xi, |q, o, x| {
        sparse_conv3_stochastic1(q, n, octave_seed(seed, o), x)
    })
}

/// Sparse convolution noise (Lewis 1989): `impulses` random impulses per cell convolved with a
/// quintic kernel (eq. 7). The estimator evaluates one impulse per cell (eq. 8); the one-term
/// estimator samples the 27-cell sum too.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SparseConvolution {
    /// Impulses per cell, clamped to `1..=64` (the paper uses 10).
    pub impulses: u32,
    /// Seed of the impulse hash.
    pub seed: u32,
}

impl SparseConvolution {
    /// Sparse convolution noise with `impulses` per cell.
    pub const fn new(impulses: u32, seed: u32) -> SparseConvolution {
        SparseConvolution { impulses, seed }
    }

    /// The noise at `p`.
    #[must_use]
    #[inline]
    pub fn sample(self, p: [f32; 3]) -> f32 {
        sparse_conv3(p, self.impulses, self.seed)
    }

    /// One impulse per cell (eq. 8), unbiased.
    #[must_use]
    #[inline]
    pub fn estimate(self, p: [f32; 3], xi: f32) -> f32 {
        sparse_conv3_stochastic(p, self.impulses, self.seed, xi)
    }

    /// One impulse of one cell: one kernel evaluation, much more variance.
    #[must_use]
    #[inline]
    pub fn estimate_one_term(self, p: [f32; 3], xi: f32) -> f32 {
        sparse_conv3_stochastic1(p, self.impulses, self.seed, xi)
    }
}

/// The fractal sum of [`SparseConvolution`] octaves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SparseConvolutionFbm {
    /// Octaves, lacunarity and gain.
    pub fractal: Fractal,
    /// Impulses per cell.
    pub impulses: u32,
    /// Seed of octave 0.
    pub seed: u32,
}

impl SparseConvolutionFbm {
    /// The fractal sum with these octaves, `impulses` per cell, and this seed.
    pub const fn new(fractal: Fractal, impulses: u32, seed: u32) -> SparseConvolutionFbm {
        SparseConvolutionFbm {
            fractal,
            impulses,
            seed,
        }
    }

    /// The sum of every octave at `p`.
    #[must_use]
    #[inline]
    pub fn sample(self, p: [f32; 3]) -> f32 {
        fbm_sparse_conv3(p, self.fractal, self.impulses, self.seed)
    }

    /// One octave (Algorithm 2) and in it one impulse per cell.
    #[must_use]
    #[inline]
    pub fn estimate(self, p: [f32; 3], xi: f32) -> f32 {
        fbm_sparse_conv3_stochastic(p, self.fractal, self.impulses, self.seed, xi)
    }

    /// One octave and in it one impulse of one cell.
    #[must_use]
    #[inline]
    pub fn estimate_one_term(self, p: [f32; 3], xi: f32) -> f32 {
        fbm_sparse_conv3_stochastic1(p, self.fractal, self.impulses, self.seed, xi)
    }

    /// The first `exact` octaves exact, one octave of the rest sampled, one impulse per cell.
    #[must_use]
    #[inline]
    pub fn estimate_tail(self, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        fbm_sparse_conv3_tail_stochastic(p, self.fractal, exact, self.impulses, self.seed, xi)
    }

    /// The first `exact` octaves exact, one octave of the rest chosen by ξ and evaluated
    /// exactly (as [`Fbm::estimate_octave`](super::Fbm::estimate_octave)).
    #[must_use]
    #[inline]
    pub fn estimate_octave(self, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        let octave =
            |q: [f32; 3], o: u32| sparse_conv3(q, self.impulses, octave_seed(self.seed, o));
        fractal_tail_estimate(p, self.fractal, exact, xi, octave, |q, o, _| octave(q, o))
    }
}

impl Noise<[f32; 3]> for SparseConvolution {
    #[inline]
    fn sample(&self, p: [f32; 3]) -> f32 {
        SparseConvolution::sample(*self, p)
    }
    #[inline]
    fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        SparseConvolution::estimate(*self, p, xi)
    }
}

impl Octaves for SparseConvolution {
    #[inline]
    fn octave(&self, o: u32) -> SparseConvolution {
        SparseConvolution::new(self.impulses, octave_seed(self.seed, o))
    }
}

impl Noise<[f32; 3]> for SparseConvolutionFbm {
    #[inline]
    fn sample(&self, p: [f32; 3]) -> f32 {
        SparseConvolutionFbm::sample(*self, p)
    }
    #[inline]
    fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        SparseConvolutionFbm::estimate(*self, p, xi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn importance_index_is_exactly_floor_n_sqrt_u() {
        const ONE: u64 = 1 << 24;
        for n in 1..=64u32 {
            let n2 = (n * n) as u64;
            // The first U of impulse k is ⌈k²·2^24 / n²⌉: there the index steps from k − 1 to k.
            for k in 1..n as u64 {
                let first = (k * k * ONE).div_ceil(n2) as u32;
                assert_eq!(importance_index(first, n), k as u32, "n {n}, k {k}");
                assert_eq!(importance_index(first - 1, n), k as u32 - 1, "n {n}, k {k}");
            }
            assert_eq!(importance_index(0, n), 0);
            assert_eq!(importance_index((ONE - 1) as u32, n), n - 1);
        }
        // And so impulse i is drawn by (2i + 1)/n² of all 2^24 values, to one value per step.
        let n = 10u32;
        let mut hist = [0u32; 10];
        for u in 0..1u32 << 24 {
            hist[importance_index(u, n) as usize] += 1;
        }
        for (i, &c) in hist.iter().enumerate() {
            let want = (2 * i + 1) as f64 / 100.0 * ONE as f64;
            assert!((c as f64 - want).abs() <= 1.0, "i {i}: {c} vs {want}");
        }
    }

    #[test]
    fn unit_bits_keeps_the_top_of_the_interval_inside() {
        assert_eq!(unit_bits(0.0), 0);
        assert_eq!(unit_bits(0.5), 1 << 23);
        assert_eq!(
            unit_bits(super::super::estimators::ONE_BELOW),
            (1 << 24) - 1
        );
        assert_eq!(unit_bits(1.0), (1 << 24) - 1);
    }
}
