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
//! [`Worley`].
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
mod lattice;

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

mod noise;

pub use estimators::{
    ONE_BELOW, bilerp_estimate, lerp_estimate, pick, russian_roulette, sanitize_xi,
};
pub use fractal::{Fbm, Octaves};
pub use fractal::{Fractal, fractal, fractal_estimate, fractal_tail_estimate, octave_seed};
pub use gabor::Gabor;
pub use gabor::GaborNoise;
pub use noise::{BatchLengths, Gradient, LatticePoint, Noise};
pub use perlin::Perlin;
pub use simplex::Simplex;
pub use sparse::{SparseConvolution, SparseConvolutionFbm};
pub use voronoi::SMOOTH_VORONOI_Q;
pub use voronoi::{SmoothVoronoi, Worley};
