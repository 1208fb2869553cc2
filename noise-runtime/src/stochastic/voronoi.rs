//! Cellular noise on one hashed feature point per unit cell: Worley F1 (Worley 1996), smooth
//! Voronoi (Quilez; Fajardo & Pharr eq. 12) and the Russian-roulette estimator of smooth
//! Voronoi (eq. 5, Algorithm 3).
//!
//! All 27 cells are evaluated without branches: pruning by cell-box distance saves hashes but
//! its branches mispredict, which costs more on a CPU.

use super::estimators::{ONE_BELOW, russian_roulette, sanitize_xi};
use super::hash::{PRIME, corner, point3};
use crate::math::{exp_neg, in_split_range, ln, split, split_in_range, sqrt_fast};

/// The paper's roulette probability of keeping the cheap approximation.
pub const SMOOTH_VORONOI_Q: f32 = 0.875;

/// The feature point of lattice cell `cell`, relative to the cell's corner (each component in
/// `(0, 1)`, on a 1/1024 grid): one of 1024 points, chosen by a hash of the cell.
pub fn feature_point3(cell: [i32; 3], seed: u32) -> [f32; 3] {
    point3(corner(
        seed,
        (cell[0] as u32).wrapping_mul(PRIME[0]),
        (cell[1] as u32).wrapping_mul(PRIME[1]),
        (cell[2] as u32).wrapping_mul(PRIME[2]),
    ))
}

/// The 3×3×3 neighbourhood of a point: per axis the hash products of the cells at offsets
/// −1, 0, +1 and the offset in the centre cell.
struct Hood {
    p: [[u32; 3]; 3],
    f: [f32; 3],
}

impl Hood {
    #[inline(always)]
    fn new(p: [f32; 3]) -> Hood {
        // As in Perlin noise: one predictable branch buys the short split for ordinary points.
        if in_split_range(p) {
            Hood::with(p, split_in_range)
        } else {
            Hood::with(p, split)
        }
    }

    #[inline(always)]
    fn with(p: [f32; 3], sp: impl Fn(f32) -> (i32, f32)) -> Hood {
        let mut h = Hood {
            p: [[0; 3]; 3],
            f: [0.0; 3],
        };
        for a in 0..3 {
            let (c, f) = sp(p[a]);
            let base = (c as u32).wrapping_mul(PRIME[a]);
            h.p[a] = [
                base.wrapping_sub(PRIME[a]),
                base,
                base.wrapping_add(PRIME[a]),
            ];
            h.f[a] = f;
        }
        h
    }

    /// Calls `f` with the squared distances to the feature points of each row of 3 cells along
    /// x (9 calls, y then z).
    #[inline(always)]
    fn each(&self, seed: u32, mut f: impl FnMut([f32; 3])) {
        let o: [[f32; 3]; 3] = core::array::from_fn(|a| {
            let v = self.f[a];
            [v + 1.0, v, v - 1.0]
        });
        for (&zp, &oz) in self.p[2].iter().zip(&o[2]) {
            for (&yp, &oy) in self.p[1].iter().zip(&o[1]) {
                let syz = seed ^ yp ^ zp;
                f(core::array::from_fn(|i| {
                    let q = point3(corner(syz, self.p[0][i], 0, 0));
                    let (x, y, z) = (o[0][i] - q[0], oy - q[1], oz - q[2]);
                    x * x + y * y + z * z
                }));
            }
        }
    }

    /// Squared distance to the feature point of neighbour `(i, j, k)` (indices 0..3 = −1..+1).
    #[inline(always)]
    fn d2(&self, i: usize, j: usize, k: usize, seed: u32) -> f32 {
        let q = point3(corner(seed, self.p[0][i], self.p[1][j], self.p[2][k]));
        let x = self.f[0] - (i as f32 - 1.0) - q[0];
        let y = self.f[1] - (j as f32 - 1.0) - q[1];
        let z = self.f[2] - (k as f32 - 1.0) - q[2];
        x * x + y * y + z * z
    }
}

/// Worley F1: the distance to the nearest feature point.
#[inline]
pub fn worley3_f1(p: [f32; 3], seed: u32) -> f32 {
    // All 27 cells, branch-free: faster than pruning, whose branches are unpredictable.
    let h = Hood::new(p);
    // Three running minima (one per x column) keep the dependency chains short.
    let mut best = [f32::MAX; 3];
    h.each(seed, |d| {
        for i in 0..3 {
            best[i] = if d[i] < best[i] { d[i] } else { best[i] };
        }
    });
    let b = if best[0] < best[1] { best[0] } else { best[1] };
    sqrt_fast(if b < best[2] { b } else { best[2] })
}

/// Smooth Voronoi (eq. 12): `−(1/32) ln Σ_c e^(−32 |p − p_c|)` over the 27 cells.
#[inline]
pub fn smooth_voronoi3(p: [f32; 3], seed: u32) -> f32 {
    let h = Hood::new(p);
    let mut d = [[0.0f32; 3]; 9];
    let mut n = 0;
    let mut b = [f32::MAX; 3];
    h.each(seed, |v| {
        d[n] = v;
        n += 1;
        for i in 0..3 {
            b[i] = if v[i] < b[i] { v[i] } else { b[i] };
        }
    });
    let b01 = if b[0] < b[1] { b[0] } else { b[1] };
    let best2 = if b01 < b[2] { b01 } else { b[2] };
    // Relative to the nearest point, so the sum is in [1, 27] and never underflows.
    let best = sqrt_fast(best2);
    let mut sums = [0.0f32; 3];
    for row in &d {
        for i in 0..3 {
            sums[i] += exp_neg(-32.0 * (sqrt_fast(row[i]) - best));
        }
    }
    let sum = sums[0] + sums[1] + sums[2];
    best - ln(sum) / 32.0
}

/// Russian-roulette estimator of [`smooth_voronoi3`] (Algorithm 3): ξ picks one of the 2×2×2
/// cells nearest `p`; its point's distance, clamped to 0.5 (about the function's mean), is the
/// cheap approximation kept with probability `q`; otherwise the full function corrects it
/// (eq. 5). `q` is clamped to `[0, 1)`.
#[inline]
pub fn smooth_voronoi3_stochastic(p: [f32; 3], seed: u32, q: f32, xi: f32) -> f32 {
    // The general split, not the dispatch of `Hood::new`: with the dispatch here, the
    // benchmark measured 77 ns against 58.
    let h = Hood::with(p, split);
    let xi = sanitize_xi(xi) * 8.0;
    let bits = (xi as u32).min(7);
    let rest = (xi - bits as f32).clamp(0.0, ONE_BELOW);
    let idx: [usize; 3] = core::array::from_fn(|a| {
        let low = if h.f[a] < 0.5 { 0 } else { 1 };
        low + ((bits >> a) & 1) as usize
    });
    let approx = sqrt_fast(h.d2(idx[0], idx[1], idx[2], seed)).min(0.5);
    russian_roulette(q, rest, approx, || smooth_voronoi3(p, seed))
}
