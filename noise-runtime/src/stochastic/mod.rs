//! Procedural noise, each function both deterministic and as an unbiased one-sample Monte Carlo
//! estimator (Fajardo & Pharr, "Stochastic procedural noise"): Perlin and simplex noise, fractal
//! sums, sparse convolution, Gabor and smooth Voronoi, plus Worley F1.
//!
//! A stochastic function takes one uniform number `ξ ∈ [0, 1]` (from a blue-noise mask's
//! [`get_k`](crate::Mask3::get_k), a low-discrepancy grid, or white noise) and returns a value
//! whose **expectation over ξ is the deterministic value**, at a fraction of the cost: it
//! evaluates one lattice gradient instead of `2^d` (Algorithm 1), one octave instead of `n`
//! (Algorithm 2), one impulse per cell instead of `n` (eq. 8), or a cheap approximation most of
//! the time (Russian roulette, Algorithm 3). Inside a Monte Carlo renderer, where every pixel
//! already averages many samples, the extra variance is small against the time saved.
//!
//! ```
//! use noise_runtime::stochastic::{Fbm, Fractal};
//!
//! let fbm = Fbm::new(Fractal::new(10, 2.0, 0.5), 1); // ten octaves, lacunarity 2, gain ½
//! let p = [0.7, 3.1, -5.2];
//! let exact = fbm.sample(p);
//! // One octave per sample, chosen by ξ: 64 stratified ξ average close to the exact sum.
//! let mean = (0..64).map(|i| fbm.estimate(p, (i as f32 + 0.5) / 64.0)).sum::<f32>() / 64.0;
//! assert!((mean - exact).abs() < 0.1, "{mean} vs {exact}");
//! // ξ of exactly 0 and 1 are valid.
//! assert!(fbm.estimate(p, 0.0).is_finite() && fbm.estimate(p, 1.0).is_finite());
//! ```
//!
//! Every noise is a type with the same verbs — [`sample`](Perlin::sample) (deterministic),
//! [`estimate`](Perlin::estimate) (one ξ, unbiased), batch forms where they pay — the point
//! first and ξ last: [`Perlin`], [`Simplex`] (2D, 3D, 4D through [`LatticePoint`]), [`Fbm`],
//! [`SparseConvolution`], [`SparseConvolutionFbm`], [`GaborNoise`], [`SmoothVoronoi`],
//! [`Worley`]. The free functions of earlier releases (`perlin3`, `fbm3_stochastic`, …) remain
//! for one release, deprecated, each naming its replacement.
//!
//! # When not to use them (Jensen's inequality)
//!
//! `E[g(X)] ≠ g(E[X])` for a non-linear `g`. A stochastic value is only unbiased where it enters
//! the rendered integral **linearly**: an albedo, a density or scattering coefficient in delta
//! or ratio tracking, an emission. Fed through a non-linear function it is biased: bump or
//! displacement mapping (normals from a noisy height), roughness, a `pow`/`smoothstep` colour
//! ramp, or squaring a density. Use the deterministic function there, or write the non-linear
//! function as a product of independent estimates (a square is the product of two evaluations
//! with independent ξ, paper §7.2).
//!
//! # When they pay on a CPU
//!
//! The saving grows with the work the estimator skips: the estimators of fBm, sparse
//! convolution (and its fractal sum), Gabor and smooth Voronoi skip most of it and pay well.
//! One octave of lattice noise does not: the deterministic Perlin and simplex forms evaluate
//! their corners on SIMD lanes side by side, while the estimator's corner choice is a chain of
//! dependent decisions, so single-octave Perlin and simplex run about level with their
//! deterministic forms. Use the deterministic function for those (it has no variance); the
//! paper's 1.9× for Perlin is a GPU figure.
//!
//! Where many points are shaded at once, the batch forms ([`Perlin::sample_batch`],
//! [`Fbm::sample_batch`] and their estimators) run eight points per AVX2 instruction, as a GPU warp runs its
//! pixels, and cut the time of every variant severalfold; the estimator's lead over the
//! deterministic form stays below the paper's GPU ratios, since on lanes the deterministic
//! form's eight corners cost little more than the estimator's one.
//!
//! The measured times and ratios, each next to its error (RMSE at 1, 4, 16, 64 samples and the
//! bias), come from `noisebake report stochastic [--json FILE]`, run on the machine at hand.
//!
//! # Hard cases
//!
//! Every function is total: ξ of exactly 0 and exactly 1 (1 is treated as the largest f32
//! below 1), NaN ξ (treated as 0), fade weights that round to exactly 0 or 1 (then the other
//! corner is never chosen, so no `0/0`), octave counts clamped to `1..=32`, any gain and
//! lacunarity (clamped to `[-16, 16]` and `[-1024, 1024]` so the geometric weights stay finite),
//! and coordinates anywhere, including ±10^7 and beyond, where f32 has no fractional bits left
//! and the noise degenerates to its lattice values without NaN or infinity.

mod batch;
mod estimators;
mod fractal;
mod gabor;

mod perlin;
mod simplex;
mod sparse;
mod voronoi;

/// Uniform numbers in `[0, 1)` from a xorshift generator, for the tests' random points and ξ.
#[cfg(test)]
pub(crate) fn uniforms(mut s: u64) -> impl FnMut() -> f32 {
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / 16_777_216.0
    }
}

/// Coordinates that are hard for the lattice splits, for the tests: ±0, the smallest
/// subnormals, both sides of the edge of the fast split's range (2^22), far beyond it, the
/// infinities and NaN. Each test adds the integers and halves near the origin it needs.
#[cfg(test)]
pub(crate) const HARD_COORDINATES: [f32; 12] = [
    0.0,
    -0.0,
    1e-45,
    -1e-45,
    4_194_303.5,
    -4_194_303.5,
    4_194_304.0,
    -1e7,
    3e38,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
];

mod noises;

pub use crate::hash::{hash2, hash3, hash4, pcg};
pub use estimators::{
    ONE_BELOW, bilerp_estimate, lerp_estimate, pick, russian_roulette, sanitize_xi,
};
pub use fractal::{Fractal, fractal, fractal_stochastic, fractal_tail_stochastic, octave_seed};
pub use gabor::Gabor;
pub use noises::{
    Fbm, GaborNoise, LatticePoint, Perlin, Simplex, SmoothVoronoi, SparseConvolution,
    SparseConvolutionFbm, Worley,
};
pub use voronoi::SMOOTH_VORONOI_Q;

/// The free functions of earlier releases, kept for one release. Each is the method of a noise
/// type named in its deprecation note (the same code, bit for bit: `tests/api.rs`).
mod aliases {
    use super::*;

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin2(p: [f32; 2], seed: u32) -> f32 {
        perlin::perlin2(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin3(p: [f32; 3], seed: u32) -> f32 {
        perlin::perlin3(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin4(p: [f32; 4], seed: u32) -> f32 {
        perlin::perlin4(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).estimate(p, xi)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin2_stochastic(p: [f32; 2], seed: u32, xi: f32) -> f32 {
        perlin::perlin2_stochastic(p, seed, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).estimate(p, xi)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> f32 {
        perlin::perlin3_stochastic(p, seed, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).estimate(p, xi)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin4_stochastic(p: [f32; 4], seed: u32, xi: f32) -> f32 {
        perlin::perlin4_stochastic(p, seed, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).gradient(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin2_grad(p: [f32; 2], seed: u32) -> (f32, [f32; 2]) {
        perlin::perlin2_grad(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).gradient(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin3_grad(p: [f32; 3], seed: u32) -> (f32, [f32; 3]) {
        perlin::perlin3_grad(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Perlin::new(seed).gradient(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin4_grad(p: [f32; 4], seed: u32) -> (f32, [f32; 4]) {
        perlin::perlin4_grad(p, seed)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `Perlin::new(seed).gradient_in_cell(cell, f)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin3_grad_cell(cell: [i32; 3], f: [f32; 3], seed: u32) -> (f32, [f32; 3]) {
        perlin::perlin3_grad_cell(cell, f, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex2(p: [f32; 2], seed: u32) -> f32 {
        simplex::simplex2(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex3(p: [f32; 3], seed: u32) -> f32 {
        simplex::simplex3(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex4(p: [f32; 4], seed: u32) -> f32 {
        simplex::simplex4(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).estimate(p, xi)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex2_stochastic(p: [f32; 2], seed: u32, xi: f32) -> f32 {
        simplex::simplex2_stochastic(p, seed, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).estimate(p, xi)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> f32 {
        simplex::simplex3_stochastic(p, seed, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).estimate(p, xi)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex4_stochastic(p: [f32; 4], seed: u32, xi: f32) -> f32 {
        simplex::simplex4_stochastic(p, seed, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).gradient(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex2_grad(p: [f32; 2], seed: u32) -> (f32, [f32; 2]) {
        simplex::simplex2_grad(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).gradient(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex3_grad(p: [f32; 3], seed: u32) -> (f32, [f32; 3]) {
        simplex::simplex3_grad(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Simplex::new(seed).gradient(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn simplex4_grad(p: [f32; 4], seed: u32) -> (f32, [f32; 4]) {
        simplex::simplex4_grad(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Fbm::new(f, seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn fbm3(p: [f32; 3], f: Fractal, seed: u32) -> f32 {
        fractal::fbm3(p, f, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Fbm::new(f, seed).estimate(p, xi)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn fbm3_stochastic(p: [f32; 3], f: Fractal, seed: u32, xi: f32) -> f32 {
        fractal::fbm3_stochastic(p, f, seed, xi)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `Perlin::new(seed).sample_batch(points, out)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin3_batch(points: &[[f32; 3]], seed: u32, out: &mut [f32]) -> usize {
        batch::perlin3_batch(points, seed, out)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `Perlin::new(seed).estimate_batch(points, xi, out)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn perlin3_stochastic_batch(
        points: &[[f32; 3]],
        seed: u32,
        xi: &[f32],
        out: &mut [f32],
    ) -> usize {
        batch::perlin3_stochastic_batch(points, seed, xi, out)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `Fbm::new(f, seed).sample_batch(points, out)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn fbm3_batch(points: &[[f32; 3]], f: Fractal, seed: u32, out: &mut [f32]) -> usize {
        batch::fbm3_batch(points, f, seed, out)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `Fbm::new(f, seed).estimate_batch(points, xi, out)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn fbm3_stochastic_batch(
        points: &[[f32; 3]],
        f: Fractal,
        seed: u32,
        xi: &[f32],
        out: &mut [f32],
    ) -> usize {
        batch::fbm3_stochastic_batch(points, f, seed, xi, out)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `SparseConvolution::new(n, seed).sample(p)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn sparse_conv3(p: [f32; 3], n: u32, seed: u32) -> f32 {
        sparse::sparse_conv3(p, n, seed)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `SparseConvolution::new(n, seed).estimate(p, xi)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn sparse_conv3_stochastic(p: [f32; 3], n: u32, seed: u32, xi: f32) -> f32 {
        sparse::sparse_conv3_stochastic(p, n, seed, xi)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `SparseConvolution::new(n, seed).estimate_one_term(p, xi)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn sparse_conv3_stochastic1(p: [f32; 3], n: u32, seed: u32, xi: f32) -> f32 {
        sparse::sparse_conv3_stochastic1(p, n, seed, xi)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `SparseConvolutionFbm::new(f, n, seed).sample(p)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn fbm_sparse_conv3(p: [f32; 3], f: Fractal, n: u32, seed: u32) -> f32 {
        sparse::fbm_sparse_conv3(p, f, n, seed)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `SparseConvolutionFbm::new(f, n, seed).estimate(p, xi)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn fbm_sparse_conv3_stochastic(p: [f32; 3], f: Fractal, n: u32, seed: u32, xi: f32) -> f32 {
        sparse::fbm_sparse_conv3_stochastic(p, f, n, seed, xi)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `SparseConvolutionFbm::new(f, n, seed).estimate_one_term(p, xi)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn fbm_sparse_conv3_stochastic1(
        p: [f32; 3],
        f: Fractal,
        n: u32,
        seed: u32,
        xi: f32,
    ) -> f32 {
        sparse::fbm_sparse_conv3_stochastic1(p, f, n, seed, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `GaborNoise::new(g, seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn gabor3(p: [f32; 3], g: Gabor, seed: u32) -> f32 {
        gabor::gabor3(p, g, seed)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `GaborNoise::new(g, seed).estimate(p, xi)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn gabor3_stochastic(p: [f32; 3], g: Gabor, seed: u32, xi: f32) -> f32 {
        gabor::gabor3_stochastic(p, g, seed, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `SmoothVoronoi::new(seed).sample(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn smooth_voronoi3(p: [f32; 3], seed: u32) -> f32 {
        voronoi::smooth_voronoi3(p, seed)
    }

    #[deprecated(
        since = "0.2.0",
        note = "use `SmoothVoronoi::new(seed).estimate_with(p, q, xi)`"
    )]
    #[doc(hidden)]
    #[inline(always)]
    pub fn smooth_voronoi3_stochastic(p: [f32; 3], seed: u32, q: f32, xi: f32) -> f32 {
        voronoi::smooth_voronoi3_stochastic(p, seed, q, xi)
    }

    #[deprecated(since = "0.2.0", note = "use `Worley::new(seed).f1(p)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn worley3_f1(p: [f32; 3], seed: u32) -> f32 {
        voronoi::worley3_f1(p, seed)
    }

    #[deprecated(since = "0.2.0", note = "use `Worley::new(seed).feature_point(cell)`")]
    #[doc(hidden)]
    #[inline(always)]
    pub fn feature_point3(cell: [i32; 3], seed: u32) -> [f32; 3] {
        voronoi::feature_point3(cell, seed)
    }
}
#[allow(deprecated)]
pub use aliases::*;
