//! Simplex noise (Perlin 2001) in 2D, 3D and 4D, its analytic gradient and its one-sample
//! estimator. Simplex noise is a weighted sum over the `N + 1` corners of the simplex holding
//! the point, with weights `(½ − r²)⁴ ≥ 0`; the estimator picks one corner with probability
//! proportional to its weight (eq. 1 with importance sampling) and evaluates only that
//! corner's gradient.
//!
//! Every form is free of branches on the point: which simplex holds it comes from the ranks
//! of its offsets, a weight's support from a `max`, the gradient from a table, and the
//! estimator's corner from a count of compares. On random points the first 3D form's branches
//! (the simplex's six cases, a corner's support, the gradient's cases) mispredicted several
//! times a call. The 2D forms and the gradients of every dimension are written once, for any
//! dimension, in [`lattice`]; the 3D and 4D pairs run on the lane layer (`lanes`), on every
//! target, and the tests compare them with the general lattice bit for bit.

#[cfg(test)]
use super::estimators::sanitize_xi;
use super::fractal::Octaves;
use super::fractal::octave_seed;
use super::noise::{Gradient, LatticePoint, Noise};
use crate::gradients;
use crate::hash::{CORNER_MUL, PRIME, hash3};
#[cfg(test)]
use crate::math::split;
use lattice::{Corners, Skew};

mod lanes;
mod lattice;

const G3: f32 = 1.0 / 6.0;
/// Scale of 3D simplex noise, so that it lies in `[-1, 1]`. The largest value any point can
/// take is below `B = max Σ_k t_k⁴ |d_k| |g|` over the simplex (each gradient turned towards
/// its offset); searched numerically, `1/B` is 99.20 in 2D (unit gradients), 76.12 in 3D
/// (`|g| = √2`) and 62.68 in 4D (`|g| = √3`), and the scales are these rounded down. (The
/// earlier 3D scale, 32, is Gustavson's for a radius² of 0.6; with ½ it left the noise in
/// ±0.42.)
const SCALE: f32 = 76.0;

/// The simplex corners of `p`: lattice cell and offsets of each corner, as the 3D form once
/// found them; now the tests' reference for the general lattice ([`lattice`]).
#[cfg(test)]
fn corners(p: [f32; 3]) -> ([[i32; 3]; 4], [[f32; 3]; 4]) {
    corners_by(p, rank_order)
}

/// The simplex holding the unskewed offset `d0` from its cell's origin, as the steps to its
/// second and third corners. The simplex is the one whose path from the cell's origin steps
/// first along the largest offset, then the second: axis `a` is in the second corner when its
/// rank (the number of other offsets it is at least, ties going to the earlier axis) is 2, in
/// the third when it is at least 1.
#[inline(always)]
fn rank_order(d0: [f32; 3]) -> ([i32; 3], [i32; 3]) {
    let ge = |a: usize, b: usize| (d0[a] >= d0[b]) as i32;
    let (xy, yz, xz) = (ge(0, 1), ge(1, 2), ge(0, 2));
    let rank = [xy + xz, 1 - xy + yz, 2 - xz - yz];
    (rank.map(|r| (r >= 2) as i32), rank.map(|r| (r >= 1) as i32))
}

/// [`corners`] with the simplex chosen by `order` (see [`rank_order`]).
#[cfg(test)]
fn corners_by(
    p: [f32; 3],
    order: impl Fn([f32; 3]) -> ([i32; 3], [i32; 3]),
) -> ([[i32; 3]; 4], [[f32; 3]; 4]) {
    let s = (p[0] + p[1] + p[2]) * (1.0 / 3.0);
    let q = [p[0] + s, p[1] + s, p[2] + s];
    // One predictable branch buys the short split for every ordinary coordinate.
    if crate::math::in_split_range(q) {
        corners_of(q, crate::math::split_in_range, order)
    } else {
        corners_of(q, split, order)
    }
}

/// [`corners_by`] for the skewed point `q`, split by `sp`.
#[cfg(test)]
fn corners_of(
    q: [f32; 3],
    sp: impl Fn(f32) -> (i32, f32),
    order: impl Fn([f32; 3]) -> ([i32; 3], [i32; 3]),
) -> ([[i32; 3]; 4], [[f32; 3]; 4]) {
    let (i, fx) = sp(q[0]);
    let (j, fy) = sp(q[1]);
    let (k, fz) = sp(q[2]);
    // Unskewed offset from the cell origin: f − (Σf)·G3 (exact, independent of the magnitude of p).
    let t = (fx + fy + fz) * G3;
    let d0 = [fx - t, fy - t, fz - t];
    let (o1, o2) = order(d0);
    let cell = |o: [i32; 3]| {
        [
            i.wrapping_add(o[0]),
            j.wrapping_add(o[1]),
            k.wrapping_add(o[2]),
        ]
    };
    let off = |o: [i32; 3], n: f32| {
        [
            d0[0] - o[0] as f32 + n * G3,
            d0[1] - o[1] as f32 + n * G3,
            d0[2] - o[2] as f32 + n * G3,
        ]
    };
    (
        [cell([0, 0, 0]), cell(o1), cell(o2), cell([1, 1, 1])],
        [d0, off(o1, 1.0), off(o2, 2.0), off([1, 1, 1], 3.0)],
    )
}

/// 3D simplex noise, in `[-1, 1]`.
#[inline(always)]
pub fn simplex3(p: [f32; 3], seed: u32) -> f32 {
    lanes::simplex3(p, seed)
}

/// [`simplex3`] on the general lattice ([`lattice`]): the tests' reference for the lane kernel.
#[cfg(test)]
fn simplex3_scalar(p: [f32; 3], seed: u32) -> f32 {
    Corners::<3, 4>::new(p, SKEW3).value(SCALE, |c| grad3(c, seed))
}

/// One-sample estimator of [`simplex3`]: one gradient, chosen with probability ∝ its weight.
///
/// On a CPU this saves little: choosing a corner needs all four weights, which is most of
/// [`simplex3`]'s work, and the three gradients it skips are a hash and a dot product each
/// (`noisebake report`: about 1.1×). It is here for completeness, and for fractal sums, where
/// one octave instead of all of them is the saving.
#[inline(always)]
pub fn simplex3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> f32 {
    lanes::simplex3_stochastic(p, seed, xi)
}

/// [`simplex3_stochastic`] in scalar code (see [`simplex3_scalar`]).
#[cfg(test)]
fn simplex3_stochastic_scalar(p: [f32; 3], seed: u32, xi: f32) -> f32 {
    Corners::<3, 4>::new(p, SKEW3).stochastic(SCALE, xi, |c| grad3(c, seed))
}

/// The skews of the 2D, 3D and 4D lattices (see [`Skew`]).
const SKEW2: Skew = Skew {
    skew: 0.366_025_42,
    unskew: 0.211_324_87,
};
const SKEW3: Skew = Skew {
    skew: 1.0 / 3.0,
    unskew: G3,
};
const SKEW4: Skew = Skew {
    skew: 0.309_017,
    unskew: 0.138_196_6,
};

/// Scale of 2D simplex noise, `[-1, 1]`: see [`SCALE`].
const SCALE2: f32 = 99.0;
/// Scale of 4D simplex noise, `[-1, 1]`: see [`SCALE`].
const SCALE4: f32 = 62.0;

/// The hash of lattice point `c` for the 2D and 4D gradients: the xor of the coordinates'
/// axis products with the seed, times one odd constant ([`corner`](crate::hash::corner)'s
/// form; use its top bits). One multiply per axis, all side by side, and one after, where
/// [`hash2`](crate::hash::hash2)'s finishing rounds would add two more multiplies to the
/// chain from the point to its value.
#[inline(always)]
fn lattice_hash<const N: usize>(c: [i32; N], seed: u32) -> u32 {
    let mut h = seed;
    for a in 0..N {
        h ^= (c[a] as u32).wrapping_mul(PRIME[a]);
    }
    h.wrapping_mul(CORNER_MUL)
}

#[inline(always)]
fn grad2(c: [i32; 2], seed: u32) -> [f32; 2] {
    gradients::UNIT2[(lattice_hash(c, seed) >> 28) as usize]
}

#[inline(always)]
fn grad3(c: [i32; 3], seed: u32) -> [f32; 3] {
    let g = gradients::edge3_simplex(hash3(c[0], c[1], c[2], seed));
    [g[0], g[1], g[2]]
}

#[inline(always)]
fn grad4(c: [i32; 4], seed: u32) -> [f32; 4] {
    *gradients::edge4(lattice_hash(c, seed))
}

/// 2D simplex noise, in `[-1, 1]`: three corners instead of [`perlin2`](super::perlin::perlin2)'s
/// four, and no axis-aligned grid in its look. On a CPU it takes about twice as long as
/// `perlin2` all the same (`noisebake report`): the skew, the unskew and the corners' weights
/// are a longer chain of dependent steps than Perlin's fade, and the chain is the time. (A
/// lane form, one corner per lane, cut its instructions by a sixth and its time by 2 %.)
#[inline(always)]
pub fn simplex2(p: [f32; 2], seed: u32) -> f32 {
    Corners::<2, 3>::new(p, SKEW2).value(SCALE2, |c| grad2(c, seed))
}

/// 2D simplex noise and its analytic gradient `(∂n/∂x, ∂n/∂y)`.
#[inline]
pub fn simplex2_grad(p: [f32; 2], seed: u32) -> (f32, [f32; 2]) {
    Corners::<2, 3>::new(p, SKEW2).value_grad(SCALE2, |c| grad2(c, seed))
}

/// One-sample estimator of [`simplex2`]: one corner of three, chosen with probability ∝ its
/// weight. On a CPU it is slower than [`simplex2`] (`noisebake report`: about 0.7×): choosing
/// needs all three weights, which is most of the work, and then adds a running sum, a
/// multiply and compares to the chain that the time is. It is here for completeness, for
/// targets where a gradient read is dear, and for fractal sums, where one octave instead of
/// all of them is the saving.
#[inline(always)]
pub fn simplex2_stochastic(p: [f32; 2], seed: u32, xi: f32) -> f32 {
    Corners::<2, 3>::new(p, SKEW2).stochastic(SCALE2, xi, |c| grad2(c, seed))
}

/// 3D simplex noise and its analytic gradient. The value is [`simplex3`]'s (the same
/// operations in the same order).
#[inline]
pub fn simplex3_grad(p: [f32; 3], seed: u32) -> (f32, [f32; 3]) {
    Corners::<3, 4>::new(p, SKEW3).value_grad(SCALE, |c| grad3(c, seed))
}

/// 4D simplex noise, in `[-1, 1]`: five corners instead of [`perlin4`](super::perlin::perlin4)'s 16.
#[inline(always)]
pub fn simplex4(p: [f32; 4], seed: u32) -> f32 {
    lanes::simplex4(p, seed)
}

/// [`simplex4`] on the general lattice ([`lattice`]): the tests' reference for the lane kernel.
#[cfg(test)]
fn simplex4_scalar(p: [f32; 4], seed: u32) -> f32 {
    Corners::<4, 5>::new(p, SKEW4).value(SCALE4, |c| grad4(c, seed))
}

/// 4D simplex noise and its analytic gradient.
#[inline]
pub fn simplex4_grad(p: [f32; 4], seed: u32) -> (f32, [f32; 4]) {
    Corners::<4, 5>::new(p, SKEW4).value_grad(SCALE4, |c| grad4(c, seed))
}

/// One-sample estimator of [`simplex4`]: one gradient of five, chosen with probability ∝ its
/// weight. On a CPU it takes about as long as [`simplex4`] (`noisebake report`: 1.0×): the
/// four gradients it skips are cheap next to the weights it must compute. For fractal sums,
/// choose the octave stochastically ([`fractal_estimate`](super::fractal_estimate)).
#[inline(always)]
pub fn simplex4_stochastic(p: [f32; 4], seed: u32, xi: f32) -> f32 {
    lanes::simplex4_stochastic(p, seed, xi)
}

/// [`simplex4_stochastic`] in scalar code (see [`simplex4_scalar`]).
#[cfg(test)]
fn simplex4_stochastic_scalar(p: [f32; 4], seed: u32, xi: f32) -> f32 {
    Corners::<4, 5>::new(p, SKEW4).stochastic(SCALE4, xi, |c| grad4(c, seed))
}

/// Simplex noise (Perlin 2001; Gustavson's formulation) in 2D, 3D or 4D; its estimator picks
/// one simplex corner by its kernel weight.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Simplex {
    /// Seed of the lattice hash.
    pub seed: u32,
}

impl Simplex {
    /// Simplex noise with this seed.
    pub const fn new(seed: u32) -> Simplex {
        Simplex { seed }
    }

    /// The noise at `p`.
    #[must_use]
    #[inline(always)]
    pub fn sample<P: LatticePoint>(self, p: P) -> f32 {
        p.simplex(self.seed)
    }

    /// An unbiased one-sample estimate of [`sample`](Self::sample).
    #[must_use]
    #[inline(always)]
    pub fn estimate<P: LatticePoint>(self, p: P, xi: f32) -> f32 {
        p.simplex_estimate(self.seed, xi)
    }

    /// The noise and its analytic gradient at `p`.
    #[must_use]
    #[inline]
    pub fn gradient<P: LatticePoint>(self, p: P) -> (f32, P) {
        p.simplex_gradient(self.seed)
    }
}

impl<P: LatticePoint> Noise<P> for Simplex {
    #[inline(always)]
    fn sample(&self, p: P) -> f32 {
        p.simplex(self.seed)
    }
    #[inline(always)]
    fn estimate(&self, p: P, xi: f32) -> f32 {
        p.simplex_estimate(self.seed, xi)
    }
}

impl<P: LatticePoint> Gradient<P> for Simplex {
    #[inline]
    fn gradient(&self, p: P) -> (f32, P) {
        p.simplex_gradient(self.seed)
    }
}

impl Octaves for Simplex {
    #[inline]
    fn octave(&self, o: u32) -> Simplex {
        Simplex::new(octave_seed(self.seed, o))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stochastic::ONE_BELOW;

    /// The plain form: the simplex by its six cases, a corner's support by a test, the
    /// gradient by Perlin's reference cases, the corner by a linear search (which asserts
    /// that it never lands on a corner of weight 0).
    mod plain {
        use super::super::{SCALE, corners_by, hash3, sanitize_xi};

        fn corners(p: [f32; 3]) -> ([[i32; 3]; 4], [[f32; 3]; 4]) {
            corners_by(p, |d0| {
                if d0[0] >= d0[1] {
                    if d0[1] >= d0[2] {
                        ([1, 0, 0], [1, 1, 0])
                    } else if d0[0] >= d0[2] {
                        ([1, 0, 0], [1, 0, 1])
                    } else {
                        ([0, 0, 1], [1, 0, 1])
                    }
                } else if d0[1] < d0[2] {
                    ([0, 0, 1], [0, 1, 1])
                } else if d0[0] < d0[2] {
                    ([0, 1, 0], [0, 1, 1])
                } else {
                    ([0, 1, 0], [1, 1, 0])
                }
            })
        }

        fn weight(d: [f32; 3]) -> f32 {
            let t = 0.5 - (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if t > 0.0 { (t * t) * (t * t) } else { 0.0 }
        }

        fn grad_dot(c: [i32; 3], d: [f32; 3], seed: u32) -> f32 {
            let h = hash3(c[0], c[1], c[2], seed) >> 28;
            let u = if h < 8 { d[0] } else { d[1] };
            let v = match h {
                0..4 => d[1],
                12 | 14 => d[0],
                _ => d[2],
            };
            (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
        }

        pub(super) fn simplex3(p: [f32; 3], seed: u32) -> f32 {
            let (c, d) = corners(p);
            let mut n = 0.0;
            for k in 0..4 {
                let w = weight(d[k]);
                if w > 0.0 {
                    n += w * grad_dot(c[k], d[k], seed);
                }
            }
            SCALE * n
        }

        pub(super) fn simplex3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> f32 {
            let (c, d) = corners(p);
            let w = d.map(weight);
            let total = w[0] + w[1] + w[2] + w[3];
            if total <= 0.0 {
                return 0.0;
            }
            let target = (sanitize_xi(xi) * total).min(f32::from_bits(total.to_bits() - 1));
            let mut end = 0.0;
            let mut k = 3;
            for (i, &wi) in w.iter().enumerate().take(3) {
                end += wi;
                if target < end {
                    k = i;
                    break;
                }
            }
            assert!(w[k] > 0.0, "a corner of weight 0 at {p:?}, ξ {xi}");
            SCALE * total * grad_dot(c[k], d[k], seed)
        }
    }

    #[test]
    fn branch_free_forms_are_the_plain_ones() {
        // Equal as numbers (a gradient's unused axis adds a zero, which can turn a −0 into +0),
        // at random points and at points where offsets tie (the diagonal, the cell's faces),
        // where the rank order must pick the simplex the six cases pick.
        let mut next = super::super::uniforms(0x9e37_79b9_7f4a_7c15u64);
        let xis = [0.0, 1e-7, 0.25, 0.5, 0.999_999, 1.0];
        for i in 0..30_000 {
            let p = if i < 20_000 {
                [
                    next() * 64.0 - 32.0,
                    next() * 64.0 - 32.0,
                    next() * 64.0 - 32.0,
                ]
            } else {
                let (t, u) = ((i / 5) as f32 / 97.0 - 30.0, next() * 8.0);
                [[t, t, t], [t, t, u], [t, u, t], [u, t, t], [t, -t, 0.5 * t]][i % 5]
            };
            assert_eq!(simplex3(p, 7), plain::simplex3(p, 7), "{p:?}");
            let xi = if i % 7 == 0 { xis[i % 6] } else { next() };
            assert_eq!(
                simplex3_stochastic(p, 7, xi),
                plain::simplex3_stochastic(p, 7, xi),
                "{p:?}, ξ {xi}"
            );
        }
    }

    /// The general lattice finds the 3D simplex the specialised one finds: the same lattice
    /// points and the same offsets, and so [`simplex3_grad`]'s value is [`simplex3`]'s.
    #[test]
    fn general_lattice_is_the_3d_one() {
        let mut next = super::super::uniforms(0x6a09_e667_f3bc_c908);
        for i in 0..50_000 {
            let p = if i < 40_000 {
                [0; 3].map(|_| next() * 64.0 - 32.0)
            } else {
                // Ties between offsets: the diagonal and the cell's faces.
                let (t, u) = ((i / 5) as f32 / 97.0 - 30.0, next() * 8.0);
                [[t, t, t], [t, t, u], [t, u, t], [u, t, t], [t, -t, 0.5 * t]][i % 5]
            };
            let (c, d) = corners(p);
            let g = Corners::<3, 4>::new(p, SKEW3);
            assert_eq!(c, g.cell, "{p:?}");
            assert_eq!(d, g.d, "{p:?}");
            assert_eq!(simplex3_grad(p, 9).0, simplex3(p, 9), "{p:?}");
        }
    }

    /// Random short steps, many across a face of the simplices: the change of the value is
    /// its gradient times the step to second order. A kernel reaching past the neighbouring
    /// faces (radius² 0.6, Gustavson's in 3D and 4D) breaks this by jumps of about 10⁻³ at
    /// the faces, ten times the bound (checked by making the change); so does a gradient
    /// formula that is wrong anywhere.
    #[test]
    fn noise_is_smooth_across_simplex_faces_and_the_gradient_is_its_derivative() {
        fn check<const N: usize, const M: usize>(
            name: &str,
            k: Skew,
            f: impl Fn([f32; N]) -> (f32, [f32; N]),
        ) {
            let mut next = super::super::uniforms(0xbb67_ae85_84ca_a73b ^ N as u64);
            let (h, mut crossed) = (2e-3f32, 0);
            for _ in 0..400_000 {
                let p: [f32; N] = core::array::from_fn(|_| next() * 16.0 - 8.0);
                let v: [f32; N] = core::array::from_fn(|_| next() - 0.5);
                let q: [f32; N] = core::array::from_fn(|a| p[a] + h * v[a]);
                let ((a, g), (b, _)) = (f(p), f(q));
                let linear: f32 = (0..N).map(|i| g[i] * (q[i] - p[i])).sum();
                // The second-order remainder: at most about 15h² measured in each dimension;
                // the bound allows 30h² and the f32 rounding of two values near 1.
                assert!(
                    (b - a - linear).abs() <= 30.0 * h * h + 1e-5,
                    "{name} from {p:?} to {q:?}: {a} → {b}, gradient step {linear}"
                );
                crossed +=
                    (Corners::<N, M>::new(p, k).cell != Corners::<N, M>::new(q, k).cell) as u32;
            }
            assert!(crossed > 500, "{name}: only {crossed} steps crossed a face");
        }
        check::<2, 3>("2D", SKEW2, |p| simplex2_grad(p, 4));
        check::<3, 4>("3D", SKEW3, |p| simplex3_grad(p, 4));
        check::<4, 5>("4D", SKEW4, |p| simplex4_grad(p, 4));
    }

    /// The scales put every dimension in `[-1, 1]` and use most of it.
    #[test]
    fn values_lie_in_the_unit_interval_and_fill_most_of_it() {
        let mut next = super::super::uniforms(0x3c6e_f372_fe94_f82b);
        let mut max = [0.0f32; 3];
        for i in 0..300_000u32 {
            let p: [f32; 4] = core::array::from_fn(|_| next() * 200.0 - 100.0);
            let seed = i % 5;
            let v = [
                simplex2([p[0], p[1]], seed),
                simplex3([p[0], p[1], p[2]], seed),
                simplex4(p, seed),
            ];
            for (m, v) in max.iter_mut().zip(v) {
                assert!(v.abs() <= 1.0, "{v} at {p:?}");
                *m = m.max(v.abs());
            }
        }
        assert!(max.iter().all(|&m| m > 0.75), "largest values {max:?}");
    }

    /// The estimators never pick a corner of weight 0, at any ξ, also where only one corner
    /// has weight (at a lattice point) and where all do.
    #[test]
    fn estimators_pick_only_corners_with_weight() {
        let xis = [0.0, 1e-30, 0.5, ONE_BELOW, 1.0, 2.0, -1.0, f32::NAN];
        for p in [
            [0.0f32; 4],
            [3.0, -2.0, 7.0, 1.0],
            [0.1, 0.2, 0.3, 0.4],
            [1e7; 4],
        ] {
            for &xi in &xis {
                let c = Corners::<4, 5>::new(p, SKEW4);
                let v = simplex4_stochastic(p, 2, xi);
                // A zero-weight corner would give a finite but wrong value; here every value
                // is one of the weighted corners' terms.
                let total: f32 =
                    c.d.iter()
                        .map(|d| {
                            (0.5 - d.iter().map(|x| x * x).sum::<f32>())
                                .max(0.0)
                                .powi(4)
                        })
                        .sum();
                let terms: [Option<f32>; 5] = core::array::from_fn(|k| {
                    let r2: f32 = c.d[k].iter().map(|x| x * x).sum();
                    (r2 < 0.5).then(|| SCALE4 * total * lattice_dot(grad4(c.cell[k], 2), c.d[k]))
                });
                assert!(
                    terms
                        .iter()
                        .flatten()
                        .any(|t| (t - v).abs() <= 1e-6 * (1.0 + t.abs()))
                        || total == 0.0,
                    "{p:?} ξ {xi}: {v} not among {terms:?}"
                );
                assert!(simplex2_stochastic([p[0], p[1]], 2, xi).is_finite());
            }
        }
    }

    fn lattice_dot<const N: usize>(g: [f32; N], d: [f32; N]) -> f32 {
        (0..N).map(|a| g[a] * d[a]).sum()
    }
}
