//! Cellular noise on one hashed feature point per unit cell: Worley F1 (Worley 1996), smooth
//! Voronoi (Quilez; Fajardo & Pharr eq. 12) and the Russian-roulette estimator of smooth
//! Voronoi (eq. 5, Algorithm 3).
//!
//! All 27 cells are evaluated without branches: pruning by cell-box distance saves hashes but
//! its branches mispredict, which costs more on a CPU.

use super::estimators::{roulette_in_range, sanitize_xi};
use super::fractal::Octaves;
use super::fractal::octave_seed;
use super::noise::Noise;
use crate::hash::{PRIME, corner, point3};
use crate::lanes::{self, F4, I4};
#[cfg(test)]
use crate::math::{exp2_neg, in_split_range, split, split_in_range};
use crate::math::{ln, on_cells, sqrt};

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
/// −1, 0, +1 and the offset in the centre cell. The scalar statement of the 27 distances, the
/// tests' reference for the lane kernels.
#[cfg(test)]
struct Hood {
    p: [[u32; 3]; 3],
    f: [f32; 3],
}

#[cfg(test)]
impl Hood {
    fn new(p: [f32; 3]) -> Hood {
        // As in Perlin noise: one predictable branch buys the short split for ordinary points.
        if in_split_range(p) {
            Hood::with(p, split_in_range)
        } else {
            Hood::with(p, split)
        }
    }

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

    /// The squared distances to the feature points of the 27 cells, x fastest, then y, then z.
    fn distances(&self, seed: u32) -> [f32; 27] {
        let o: [[f32; 3]; 3] = core::array::from_fn(|a| {
            let v = self.f[a];
            [v + 1.0, v, v - 1.0]
        });
        let mut d = [0.0f32; 27];
        for (k, (&zp, &oz)) in self.p[2].iter().zip(&o[2]).enumerate() {
            for (j, (&yp, &oy)) in self.p[1].iter().zip(&o[1]).enumerate() {
                let syz = seed ^ yp ^ zp;
                for i in 0..3 {
                    let q = point3(corner(syz, self.p[0][i], 0, 0));
                    let (x, y, z) = (o[0][i] - q[0], oy - q[1], oz - q[2]);
                    d[9 * k + 3 * j + i] = x * x + y * y + z * z;
                }
            }
        }
        d
    }

    /// Squared distance to the feature point of neighbour `(i, j, k)` (indices 0..3 = −1..+1):
    /// the reference the estimator's [`picked_distance`] is tested against.
    fn d2(&self, i: usize, j: usize, k: usize, seed: u32) -> f32 {
        let q = point3(corner(seed, self.p[0][i], self.p[1][j], self.p[2][k]));
        let x = self.f[0] - (i as f32 - 1.0) - q[0];
        let y = self.f[1] - (j as f32 - 1.0) - q[1];
        let z = self.f[2] - (k as f32 - 1.0) - q[2];
        x * x + y * y + z * z
    }
}

/// The 27 cells in the order of `Hood::distances` (the tests' scalar neighbourhood) (z, then y, then x) in seven groups of four,
/// on lanes, for a point split by [`on_cells!`](crate::math::on_cells): lane `l` of group `g` is cell
/// `4g + l`, and the last group's lane 3, past the 27, has distance `f32::MAX` (a term of 0).
///
/// Four cells' feature points are four 16-byte table reads transposed into x, y and z lanes;
/// each distance is the scalar one's operations in the same order, so the same bits (the tests
/// compare the two). Four lanes for 27 cells, not the three cells of a row: seven square roots
/// and exponentials instead of nine.
#[inline(always)]
fn groups_lanes(cell: I4, f: F4, seed: u32) -> [F4; 7] {
    use crate::hash::point3_row;
    let prods = |c: u32, a: usize| {
        let b = c.wrapping_mul(PRIME[a]);
        [b.wrapping_sub(PRIME[a]), b, b.wrapping_add(PRIME[a])]
    };
    let [cx, cy, cz] = cell.xyz();
    let (px, py, pz) = (prods(cx, 0), prods(cy, 1), prods(cz, 2));
    let (fx, fy, fz) = (f.xxxx(), f.yyyy(), f.zzzz());
    let row = |c: usize| {
        let c = c.min(26);
        F4::new(point3_row(corner(
            seed ^ pz[c / 9] ^ py[c / 3 % 3],
            px[c % 3],
            0,
            0,
        )))
    };
    let group = |g: usize| {
        let c = 4 * g;
        let [qx, qy, qz, _] = F4::transpose([row(c), row(c + 1), row(c + 2), row(c + 3)]);
        // `f + 1`, `f + 0` (which differs from `f` only for −0, to the same differences) and
        // `f − 1` per axis.
        let dx = (fx + F4::new(&OFFSETS[g][0])) - qx;
        let dy = (fy + F4::new(&OFFSETS[g][1])) - qy;
        let dz = (fz + F4::new(&OFFSETS[g][2])) - qz;
        dx * dx + dy * dy + dz * dz
    };
    // Spelled out, so every index is a constant: as a loop or `array::from_fn`, LLVM kept the
    // loop (or the calls) and computed the indices at run time.
    let mut d = [
        group(0),
        group(1),
        group(2),
        group(3),
        group(4),
        group(5),
        group(6),
    ];
    d[6] = d[6].max(F4::new(&[0.0, 0.0, 0.0, f32::MAX]));
    d
}

/// Per group of [`groups_lanes`], per axis, the lanes' cell offsets negated: `1 − i` for the
/// cell at index `i` (offset `i − 1`) along the axis.
const OFFSETS: [[[f32; 4]; 3]; 7] = {
    let mut o = [[[0.0f32; 4]; 3]; 7];
    let mut c = 0;
    while c < 28 {
        let k = if c < 27 { c } else { 26 };
        o[c / 4][0][c % 4] = 1.0 - (k % 3) as f32;
        o[c / 4][1][c % 4] = 1.0 - (k / 3 % 3) as f32;
        o[c / 4][2][c % 4] = 1.0 - (k / 9) as f32;
        c += 1;
    }
    o
};

/// Worley F1: the distance to the nearest feature point.
#[inline]
pub fn worley3_f1(p: [f32; 3], seed: u32) -> f32 {
    // All 27 cells, branch-free: faster than pruning, whose branches are unpredictable.
    on_cells!(F4::from3(p), |cell, f| {
        sqrt(min_lanes(&groups_lanes(cell, f, seed)))
    })
}

/// [`worley3_f1`] on scalars, the tests' reference.
#[cfg(test)]
fn worley3_f1_scalar(p: [f32; 3], seed: u32) -> f32 {
    sqrt(Hood::new(p).distances(seed).into_iter().fold(f32::MAX, min))
}

/// `if a < b { a } else { b }`: the minimum, as `minss` computes it.
#[inline(always)]
fn min(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// The least lane of seven groups (no lane NaN).
#[inline(always)]
fn min_lanes(d: &[F4; 7]) -> f32 {
    // A tree, for a short chain.
    let m = (d[0].min(d[1]).min(d[2].min(d[3]))).min(d[4].min(d[5]).min(d[6]));
    min(min(m.x(), m.y()), min(m.z(), m.w()))
}

/// `e^(−32 t) = 2^(t · EXP_SCALE)`: −32 log₂ e, exactly 32 times the float `log₂ e`, so the
/// product rounds as `(−32 t) · log₂ e` would.
const EXP_SCALE: f32 = -32.0 * core::f32::consts::LOG2_E;

/// Smooth Voronoi (eq. 12): `−(1/32) ln Σ_c e^(−32 |p − p_c|)` over the 27 cells, as written:
/// the nearest point is within √3 (the point's own cell's), so the sum is at least
/// `e^(−32√3) ≈ 9e−25` and no relevant term underflows (terms below `2^−125` are clamped to it,
/// 13 orders below the sum). The terms are summed in four running sums, cell `c` into sum
/// `c mod 4`, then `(s₀ + s₁) + (s₂ + s₃)`: the order of the lanes, on every target.
///
/// Within 2e-7 of eq. 12 evaluated in f64 from the same f32 point (the tests check 3e-7).
/// Scaling the terms by the nearest distance first, `d₁ − (1/32) ln Σ e^(−32 (d − d₁))`, is
/// a little more accurate but waits for the nearest distance before the first exponential,
/// and measured slower (`noisebake report stochastic`'s per-call times).
#[inline]
pub fn smooth_voronoi3(p: [f32; 3], seed: u32) -> f32 {
    smooth_voronoi3_lanes(F4::from3(p), seed)
}

/// [`smooth_voronoi3`] of a point already in lanes.
#[inline(always)]
fn smooth_voronoi3_lanes(v: F4, seed: u32) -> f32 {
    on_cells!(v, |cell, f| {
        let mut sums = F4::splat(0.0);
        for g in groups_lanes(cell, f, seed) {
            let y = (g.sqrt() * F4::splat(EXP_SCALE)).max(F4::splat(-125.0));
            sums = sums + lanes::exp2_neg(y);
        }
        -ln(sums.sum4()) / 32.0
    })
}

/// [`smooth_voronoi3`] on scalars, the tests' reference.
#[cfg(test)]
fn smooth_voronoi3_scalar(p: [f32; 3], seed: u32) -> f32 {
    let mut sums = [0.0f32; 4];
    for (c, &d2) in Hood::new(p).distances(seed).iter().enumerate() {
        sums[c % 4] += exp2_neg((sqrt(d2) * EXP_SCALE).max(-125.0));
    }
    -ln((sums[0] + sums[1]) + (sums[2] + sums[3])) / 32.0
}

/// Russian-roulette estimator of [`smooth_voronoi3`] (Algorithm 3): ξ picks one of the 2×2×2
/// cells nearest `p`; its point's distance, clamped to 0.5 (about the function's mean), is the
/// cheap approximation kept with probability `q`; otherwise the full function corrects it
/// (eq. 5). `q` is clamped to `[0, 1)`.
#[inline(always)]
pub fn smooth_voronoi3_stochastic(p: [f32; 3], seed: u32, q: f32, xi: f32) -> f32 {
    // The point read once into lanes, in the pieces a caller that passes it in memory stored
    // it in (`F4::from3`): read back as scalars, or across the two stores, it stalled every
    // call that was not inlined (36 ns a sample against 16).
    let v = F4::from3(p);
    let t = sanitize_xi(xi) * 8.0;
    // t is in [0, 8): its integer part is the cell's 3 bits, and t minus it is exact, in [0, 1).
    let bits = lanes::trunc1(t) as u32 & 7;
    let rest = t - bits as f32;
    let approx = picked_distance(v, seed, bits).min(0.5);
    roulette_in_range(q, rest, approx, || smooth_voronoi3_of(v, seed))
}

/// [`smooth_voronoi3`] of the estimator's point in lanes, for its rare full evaluation, out of
/// line. The register goes over whole: rebuilt into an array, the point was stored in pieces
/// and read back across them, a stall on every full evaluation.
#[inline(never)]
fn smooth_voronoi3_of(v: F4, seed: u32) -> f32 {
    smooth_voronoi3_lanes(v, seed)
}

/// The distance from `p` to the feature point of the cell that `bits` picks among the 2×2×2
/// cells nearest `p`: bit `a` set, the farther of the two along axis `a`.
#[inline(always)]
fn picked_distance(p: F4, seed: u32, bits: u32) -> f32 {
    // For a point in the split range its split on lanes; the offset it gives may be exactly 1
    // where the general split steps to the next cell with offset 0, which picks the same cells
    // at the same offsets (the tests compare the two).
    on_cells!(p, |cell, f| picked_distance_lanes(cell, f, seed, bits))
}

/// [`picked_distance`] on lanes : per axis
/// `i − 1 = −1 + [f ≥ ½] + bit`, the cell's offset and the point's offset from it on lanes;
/// only the three hash products are scalar (SSE2 has no 32-bit lane multiply). With masks of
/// all ones for true, `−1 + [f ≥ ½]` is the mask of `f < ½` (0 or −1) and `+ bit` subtracts
/// the bit's mask.
#[inline(always)]
fn picked_distance_lanes(cell: I4, f: F4, seed: u32, bits: u32) -> f32 {
    let im1 = f.less(0.5) - I4::bit_masks(bits);
    let [cx, cy, cz] = (cell + im1).xyz();
    let h =
        seed ^ cx.wrapping_mul(PRIME[0]) ^ cy.wrapping_mul(PRIME[1]) ^ cz.wrapping_mul(PRIME[2]);
    let q = F4::new(crate::hash::point3_row(
        h.wrapping_mul(crate::hash::CORNER_MUL),
    ));
    let d = (f - im1.to_f32()) - q;
    // The square root on the lanes: a sum of squares needs no guard for negatives or NaN.
    (d * d).sum3_x().sqrt().x()
}

/// Smooth Voronoi noise (eq. 12): a soft minimum of the distances to the feature points of the
/// 27 cells around `p`; its estimator evaluates the nearest cells exactly and the rest by
/// Russian roulette (Algorithm 3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SmoothVoronoi {
    /// Seed of the feature points.
    pub seed: u32,
}

impl SmoothVoronoi {
    /// Smooth Voronoi noise with this seed.
    pub const fn new(seed: u32) -> SmoothVoronoi {
        SmoothVoronoi { seed }
    }

    /// The noise at `p`.
    #[must_use]
    #[inline]
    pub fn sample(self, p: [f32; 3]) -> f32 {
        smooth_voronoi3(p, self.seed)
    }

    /// An unbiased estimate with the paper's roulette probability
    /// ([`SMOOTH_VORONOI_Q`]).
    #[must_use]
    #[inline]
    pub fn estimate(self, p: [f32; 3], xi: f32) -> f32 {
        smooth_voronoi3_stochastic(p, self.seed, super::SMOOTH_VORONOI_Q, xi)
    }

    /// An unbiased estimate with roulette probability `q` (higher: more exact work, less
    /// variance).
    #[must_use]
    #[inline]
    pub fn estimate_with(self, p: [f32; 3], q: f32, xi: f32) -> f32 {
        smooth_voronoi3_stochastic(p, self.seed, q, xi)
    }
}

/// Worley (cellular) noise: one feature point per unit cell.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Worley {
    /// Seed of the feature points.
    pub seed: u32,
}

impl Worley {
    /// Worley noise with this seed.
    pub const fn new(seed: u32) -> Worley {
        Worley { seed }
    }

    /// F1: the distance from `p` to the nearest feature point.
    #[must_use]
    #[inline]
    pub fn f1(self, p: [f32; 3]) -> f32 {
        worley3_f1(p, self.seed)
    }

    /// The feature point of a cell.
    #[must_use]
    #[inline]
    pub fn feature_point(self, cell: [i32; 3]) -> [f32; 3] {
        feature_point3(cell, self.seed)
    }
}

impl Noise<[f32; 3]> for SmoothVoronoi {
    #[inline]
    fn sample(&self, p: [f32; 3]) -> f32 {
        SmoothVoronoi::sample(*self, p)
    }
    #[inline]
    fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        SmoothVoronoi::estimate(*self, p, xi)
    }
}

impl Octaves for SmoothVoronoi {
    #[inline]
    fn octave(&self, o: u32) -> SmoothVoronoi {
        SmoothVoronoi::new(octave_seed(self.seed, o))
    }
}

/// Worley F1 has no stochastic form: its exact value is its own unbiased estimate (no
/// variance, no saving), which lets it stand beside the other noises through [`Noise`].
impl Noise<[f32; 3]> for Worley {
    #[inline]
    fn sample(&self, p: [f32; 3]) -> f32 {
        self.f1(p)
    }
    #[inline]
    fn estimate(&self, p: [f32; 3], _xi: f32) -> f32 {
        self.f1(p)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::estimators::ONE_BELOW;
    use super::super::uniforms;
    use super::*;
    use std::{vec, vec::Vec};

    /// Coordinates that are hard for the splits: integers and their neighbouring floats of both
    /// signs (where the lane split's offset may be 1), halves (where the nearer pair of cells
    /// changes), ±0, the edge of the split range and far beyond it.
    fn hard() -> Vec<f32> {
        let mut v = crate::stochastic::HARD_COORDINATES.to_vec();
        for k in -3..=3 {
            let k = k as f32;
            let up = f32::from_bits(k.abs().to_bits() + 1);
            let down = f32::from_bits(k.abs().to_bits().saturating_sub(1));
            v.extend([k, up, -up, down, -down, k + 0.5, k - 0.5]);
        }
        v
    }

    /// Every triple of the hard coordinates, then random points.
    fn points(mut check: impl FnMut([f32; 3])) {
        let h = hard();
        for &x in &h {
            for &y in &h {
                for &z in &h {
                    check([x, y, z]);
                }
            }
        }
        let mut next = uniforms(0x6a09_e667_f3bc_c908);
        for _ in 0..20_000 {
            check([0; 3].map(|_| (next() - 0.5) * 2e3));
        }
    }

    #[test]
    fn picked_cell_is_the_neighbourhoods_bit_for_bit() {
        points(|p| {
            let h = Hood::with(p, split);
            for bits in 0..8 {
                // The cell as the estimator picked it before: the nearer pair along each axis
                // from the general split's offset, and the bit of the axis.
                let idx: [usize; 3] = core::array::from_fn(|a| {
                    let low = if h.f[a] < 0.5 { 0 } else { 1 };
                    low + ((bits >> a) & 1) as usize
                });
                let want = sqrt(h.d2(idx[0], idx[1], idx[2], 5));
                let got = picked_distance(F4::from3(p), 5, bits);
                assert_eq!(got.to_bits(), want.to_bits(), "p {p:?}, bits {bits}");
            }
        });
    }

    /// Algorithm 3 as the paper writes it, on the general split and the neighbourhood's `d2`.
    fn algorithm3(p: [f32; 3], seed: u32, q: f32, xi: f32) -> f32 {
        let h = Hood::with(p, split);
        let t = sanitize_xi(xi) * 8.0;
        let bits = (t as u32).min(7);
        let rest = (t - bits as f32).clamp(0.0, ONE_BELOW);
        let idx: [usize; 3] = core::array::from_fn(|a| {
            let low = if h.f[a] < 0.5 { 0 } else { 1 };
            low + ((bits >> a) & 1) as usize
        });
        let approx = sqrt(h.d2(idx[0], idx[1], idx[2], seed)).min(0.5);
        let q = if q >= 0.0 { q.min(ONE_BELOW) } else { 0.0 };
        if rest < q {
            approx
        } else {
            (smooth_voronoi3(p, seed) - q * approx) / (1.0 - q)
        }
    }

    #[test]
    fn estimator_is_algorithm_3_bit_for_bit() {
        // ξ at 0 and 1, past both ends, NaN, at and beside each eighth (where the cell and the
        // remapped ξ change), and beside q's eighth-scaled threshold.
        let mut xis = vec![0.0f32, 1.0, -0.5, 2.0, f32::NAN, ONE_BELOW, 1e-30];
        for k in 1..8 {
            let e = k as f32 / 8.0;
            xis.extend([
                e,
                f32::from_bits(e.to_bits() - 1),
                f32::from_bits(e.to_bits() + 1),
            ]);
            let t = (k as f32 + SMOOTH_VORONOI_Q) / 8.0;
            xis.extend([
                t,
                f32::from_bits(t.to_bits() - 1),
                f32::from_bits(t.to_bits() + 1),
            ]);
        }
        let mut next = uniforms(0x3c6e_f372_fe94_f82b);
        let mut n = 0usize;
        points(|p| {
            let xi = xis[n % xis.len()];
            let r = next();
            for (q, xi) in [
                (SMOOTH_VORONOI_Q, xi),
                (SMOOTH_VORONOI_Q, r),
                (0.0, r),
                (1.0, r),
            ] {
                let (got, want) = (
                    smooth_voronoi3_stochastic(p, 3, q, xi),
                    algorithm3(p, 3, q, xi),
                );
                assert_eq!(got.to_bits(), want.to_bits(), "p {p:?}, q {q}, ξ {xi:e}");
            }
            n += 1;
        });
    }

    #[test]
    fn lanes_are_the_scalar_forms_bit_for_bit() {
        let mut seen = 0;
        points(|p| {
            seen += 1;
            let groups = on_cells!(F4::from3(p), |cell, f| groups_lanes(cell, f, 9));
            let want = Hood::new(p).distances(9);
            for (c, want) in want.iter().enumerate() {
                let g = groups[c / 4];
                let got = [g.x(), g.y(), g.z(), g.w()][c % 4];
                assert_eq!(got.to_bits(), want.to_bits(), "p {p:?}, cell {c}");
            }
            assert_eq!(groups[6].w(), f32::MAX, "p {p:?}: lane 27");
            for (name, lane, scalar) in [
                (
                    "smooth",
                    smooth_voronoi3 as fn([f32; 3], u32) -> f32,
                    smooth_voronoi3_scalar as fn([f32; 3], u32) -> f32,
                ),
                ("Worley", worley3_f1, worley3_f1_scalar),
            ] {
                let (got, want) = (lane(p, 9), scalar(p, 9));
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "{name}, p {p:?}: {got} vs {want}"
                );
            }
        });
        assert!(seen > 20_000, "compared {seen} points");
    }

    #[test]
    fn lane_square_root_and_exponential_are_the_scalar_ones_bit_for_bit() {
        let mut next = uniforms(0xbb67_ae85_84ca_a73b);
        let mut sq = vec![0.0f32, 1e-45, 1e-38, 0.25, 1.0, 2.999_999_8, 12.0, 3e38];
        sq.extend((0..4000).map(|_| next() * 12.0));
        // exp2_neg's domain [−125, 0]: its ends, −0, the halves where the rounding to k ties
        // (to even), and their neighbours.
        let mut ex = vec![0.0f32, -0.0, -125.0, -1e-40, -1e-30];
        for k in 0..125 {
            let h = -(k as f32 + 0.5);
            ex.extend([
                h,
                f32::from_bits(h.to_bits() - 1),
                f32::from_bits(h.to_bits() + 1),
            ]);
        }
        ex.extend((0..4000).map(|_| -next() * 125.0));
        // Four inputs per call (the last group padded by repeating), each lane against the
        // scalar function of the same input.
        let check = |inputs: &[f32], lane: fn(F4) -> F4, scalar: fn(f32) -> f32, name: &str| {
            for c in inputs.chunks(4) {
                let r = [0, 1, 2, 3].map(|i| c[i % c.len()]);
                let v = lane(F4::new(&r));
                for (got, x) in [v.x(), v.y(), v.z(), v.w()].into_iter().zip(r) {
                    assert_eq!(got.to_bits(), scalar(x).to_bits(), "{name}({x:e})");
                }
            }
        };
        check(&sq, F4::sqrt, sqrt, "sqrt");
        check(&ex, lanes::exp2_neg, exp2_neg, "exp2_neg");
    }
}
