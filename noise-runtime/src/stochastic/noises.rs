//! The noises as types, each with the same verbs: [`sample`](Perlin::sample) (deterministic),
//! [`estimate`](Perlin::estimate) (the unbiased one-sample estimator, one ξ), and batch forms
//! where they pay. A noise value is its parameters (seed first among them fixed at
//! construction); the point comes first in every call and ξ last.
//!
//! ```
//! use noise_runtime::stochastic::{Fbm, Fractal, Perlin};
//!
//! let perlin = Perlin::new(7);
//! let v = perlin.sample([0.3, 1.2, -4.0]); // 3D; [f32; 2] and [f32; 4] work too
//! let (_, grad) = perlin.gradient([0.3, 1.2]);
//! assert!(v.abs() <= 1.1 && grad.iter().all(|g| g.is_finite()));
//!
//! let fbm = Fbm::new(Fractal::default(), 7);
//! let p = [0.7, 3.1, -5.2];
//! let mean = (0..256).map(|i| fbm.estimate(p, (i as f32 + 0.5) / 256.0)).sum::<f32>() / 256.0;
//! assert!((mean - fbm.sample(p)).abs() < 0.1);
//! ```

use super::fractal::{self, Fractal};
use super::{gabor, perlin, simplex, sparse, voronoi};

mod sealed {
    pub trait Sealed {}
    impl Sealed for [f32; 2] {}
    impl Sealed for [f32; 3] {}
    impl Sealed for [f32; 4] {}
}

/// The error of a batch call whose slices differ in length: one output per point (and one ξ
/// per point for an estimator) is the contract, and a silent shortest-slice run would hide a
/// caller's off-by-one. Nothing is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BatchLengths {
    /// `points.len()`.
    pub points: usize,
    /// `xi.len()`, for estimators.
    pub xi: Option<usize>,
    /// `out.len()`.
    pub out: usize,
}

impl BatchLengths {
    fn check(points: usize, xi: Option<usize>, out: usize) -> Result<(), Self> {
        if out == points && xi.is_none_or(|x| x == points) {
            Ok(())
        } else {
            Err(Self { points, xi, out })
        }
    }
}

impl core::fmt::Display for BatchLengths {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "batch slices differ in length: {} points", self.points)?;
        if let Some(xi) = self.xi {
            write!(f, ", {xi} ξ")?;
        }
        write!(f, ", {} outputs; give one of each per point", self.out)
    }
}

impl core::error::Error for BatchLengths {}

/// A point lattice noises are defined at: `[f32; 2]`, `[f32; 3]` or `[f32; 4]`. Sealed: the
/// dispatch to each dimension's kernel is an implementation detail.
pub trait LatticePoint: sealed::Sealed + Copy {
    #[doc(hidden)]
    fn perlin(self, seed: u32) -> f32;
    #[doc(hidden)]
    fn perlin_estimate(self, seed: u32, xi: f32) -> f32;
    #[doc(hidden)]
    fn perlin_gradient(self, seed: u32) -> (f32, Self);
    #[doc(hidden)]
    fn simplex(self, seed: u32) -> f32;
    #[doc(hidden)]
    fn simplex_estimate(self, seed: u32, xi: f32) -> f32;
    #[doc(hidden)]
    fn simplex_gradient(self, seed: u32) -> (f32, Self);
}

macro_rules! lattice_point {
    ($n:literal, $perlin:ident, $pe:ident, $pg:ident, $simplex:ident, $se:ident, $sg:ident) => {
        impl LatticePoint for [f32; $n] {
            #[inline(always)]
            fn perlin(self, seed: u32) -> f32 {
                perlin::$perlin(self, seed)
            }
            #[inline(always)]
            fn perlin_estimate(self, seed: u32, xi: f32) -> f32 {
                perlin::$pe(self, seed, xi)
            }
            #[inline(always)]
            fn perlin_gradient(self, seed: u32) -> (f32, Self) {
                perlin::$pg(self, seed)
            }
            #[inline(always)]
            fn simplex(self, seed: u32) -> f32 {
                simplex::$simplex(self, seed)
            }
            #[inline(always)]
            fn simplex_estimate(self, seed: u32, xi: f32) -> f32 {
                simplex::$se(self, seed, xi)
            }
            #[inline(always)]
            fn simplex_gradient(self, seed: u32) -> (f32, Self) {
                simplex::$sg(self, seed)
            }
        }
    };
}
lattice_point!(
    2,
    perlin2,
    perlin2_stochastic,
    perlin2_grad,
    simplex2,
    simplex2_stochastic,
    simplex2_grad
);
lattice_point!(
    3,
    perlin3,
    perlin3_stochastic,
    perlin3_grad,
    simplex3,
    simplex3_stochastic,
    simplex3_grad
);
lattice_point!(
    4,
    perlin4,
    perlin4_stochastic,
    perlin4_grad,
    simplex4,
    simplex4_stochastic,
    simplex4_grad
);

/// Improved Perlin noise (Perlin 2002) in 2D, 3D or 4D, about `[-1, 1]`; its estimator evaluates
/// one lattice gradient of the `2^d` (Fajardo & Pharr, Algorithm 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Perlin {
    /// Seed of the lattice hash.
    pub seed: u32,
}

impl Perlin {
    /// Perlin noise with this seed.
    pub const fn new(seed: u32) -> Perlin {
        Perlin { seed }
    }

    /// The noise at `p`.
    #[must_use]
    #[inline(always)]
    pub fn sample<P: LatticePoint>(self, p: P) -> f32 {
        p.perlin(self.seed)
    }

    /// An unbiased one-sample estimate of [`sample`](Self::sample) from one uniform `xi`.
    #[must_use]
    #[inline(always)]
    pub fn estimate<P: LatticePoint>(self, p: P, xi: f32) -> f32 {
        p.perlin_estimate(self.seed, xi)
    }

    /// The noise and its analytic gradient at `p`.
    #[must_use]
    #[inline]
    pub fn gradient<P: LatticePoint>(self, p: P) -> (f32, P) {
        p.perlin_gradient(self.seed)
    }

    /// The 3D noise and its gradient at offset `f ∈ [0, 1)³` in the integer lattice cell
    /// `cell`: exact for any `i32` cell, however far from the origin an `f32` point could not
    /// reach (the curl-noise fields use it).
    #[must_use]
    #[inline]
    pub fn gradient_in_cell(self, cell: [i32; 3], f: [f32; 3]) -> (f32, [f32; 3]) {
        perlin::perlin3_grad_cell(cell, f, self.seed)
    }

    /// [`sample`](Self::sample) of many 3D points into `out` (eight per AVX2 instruction where
    /// the CPU has it), bit for bit the single-point values. Slices of different lengths are
    /// an error, and nothing is written.
    #[inline]
    pub fn sample_batch(self, points: &[[f32; 3]], out: &mut [f32]) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), None, out.len())?;
        perlin::batch::perlin3_batch(points, self.seed, out);
        Ok(())
    }

    /// [`estimate`](Self::estimate) of many 3D points, one ξ each, into `out`. Slices of
    /// different lengths are an error, and nothing is written.
    #[inline]
    pub fn estimate_batch(
        self,
        points: &[[f32; 3]],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), Some(xi.len()), out.len())?;
        perlin::batch::perlin3_stochastic_batch(points, self.seed, xi, out);
        Ok(())
    }
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

/// Fractal Brownian motion of 3D Perlin noise: `Σ gain^o · perlin(p · lacunarity^o)` with an
/// independent seed per octave (eq. 9). Its estimators choose octaves by their weight
/// (Algorithm 2).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fbm {
    /// Octaves, lacunarity and gain.
    pub fractal: Fractal,
    /// Seed of octave 0 (see [`octave_seed`](super::octave_seed)).
    pub seed: u32,
}

impl Fbm {
    /// fBm with these octaves and this seed.
    pub const fn new(fractal: Fractal, seed: u32) -> Fbm {
        Fbm { fractal, seed }
    }

    /// The sum of every octave at `p`.
    #[must_use]
    #[inline(always)]
    pub fn sample(self, p: [f32; 3]) -> f32 {
        fractal::fbm3(p, self.fractal, self.seed)
    }

    /// One octave chosen by ξ and, in it, one lattice gradient: unbiased, at the cost of one
    /// gradient whatever the octave count.
    #[must_use]
    #[inline(always)]
    pub fn estimate(self, p: [f32; 3], xi: f32) -> f32 {
        fractal::fbm3_stochastic(p, self.fractal, self.seed, xi)
    }

    /// The first `exact` octaves summed exactly and one gradient of one octave of the rest:
    /// the tail's variance shrinks by `gain^(2·exact)` ([`fractal_tail_estimate`](super::fractal_tail_estimate)).
    #[must_use]
    #[inline]
    pub fn estimate_tail(self, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        fractal::fbm3_tail_stochastic(p, self.fractal, exact, self.seed, xi)
    }

    /// The first `exact` octaves summed exactly and one octave of the rest chosen by ξ and
    /// evaluated exactly: only the octave choice is random.
    #[must_use]
    #[inline]
    pub fn estimate_octave(self, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        fractal::fbm3_octave_stochastic(p, self.fractal, exact, self.seed, xi)
    }

    /// [`sample`](Self::sample) of many points into `out`, as [`Perlin::sample_batch`].
    #[inline]
    pub fn sample_batch(self, points: &[[f32; 3]], out: &mut [f32]) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), None, out.len())?;
        fractal::batch::fbm3_batch(points, self.fractal, self.seed, out);
        Ok(())
    }

    /// [`estimate`](Self::estimate) of many points, one ξ each, as [`Perlin::estimate_batch`].
    #[inline]
    pub fn estimate_batch(
        self,
        points: &[[f32; 3]],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), Some(xi.len()), out.len())?;
        fractal::batch::fbm3_stochastic_batch(points, self.fractal, self.seed, xi, out);
        Ok(())
    }
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
        sparse::sparse_conv3(p, self.impulses, self.seed)
    }

    /// One impulse per cell (eq. 8), unbiased.
    #[must_use]
    #[inline]
    pub fn estimate(self, p: [f32; 3], xi: f32) -> f32 {
        sparse::sparse_conv3_stochastic(p, self.impulses, self.seed, xi)
    }

    /// One impulse of one cell: one kernel evaluation, much more variance.
    #[must_use]
    #[inline]
    pub fn estimate_one_term(self, p: [f32; 3], xi: f32) -> f32 {
        sparse::sparse_conv3_stochastic1(p, self.impulses, self.seed, xi)
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
        sparse::fbm_sparse_conv3(p, self.fractal, self.impulses, self.seed)
    }

    /// One octave (Algorithm 2) and in it one impulse per cell.
    #[must_use]
    #[inline]
    pub fn estimate(self, p: [f32; 3], xi: f32) -> f32 {
        sparse::fbm_sparse_conv3_stochastic(p, self.fractal, self.impulses, self.seed, xi)
    }

    /// One octave and in it one impulse of one cell.
    #[must_use]
    #[inline]
    pub fn estimate_one_term(self, p: [f32; 3], xi: f32) -> f32 {
        sparse::fbm_sparse_conv3_stochastic1(p, self.fractal, self.impulses, self.seed, xi)
    }

    /// The first `exact` octaves exact, one octave of the rest sampled, one impulse per cell.
    #[must_use]
    #[inline]
    pub fn estimate_tail(self, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        sparse::fbm_sparse_conv3_tail_stochastic(
            p,
            self.fractal,
            exact,
            self.impulses,
            self.seed,
            xi,
        )
    }

    /// The first `exact` octaves exact, one octave of the rest chosen by ξ and evaluated
    /// exactly (as [`Fbm::estimate_octave`]).
    #[must_use]
    #[inline]
    pub fn estimate_octave(self, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        let octave = |q: [f32; 3], o: u32| {
            sparse::sparse_conv3(q, self.impulses, fractal::octave_seed(self.seed, o))
        };
        fractal::fractal_tail_estimate(p, self.fractal, exact, xi, octave, |q, o, _| octave(q, o))
    }
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
        voronoi::smooth_voronoi3(p, self.seed)
    }

    /// An unbiased estimate with the paper's roulette probability
    /// ([`SMOOTH_VORONOI_Q`](super::SMOOTH_VORONOI_Q)).
    #[must_use]
    #[inline]
    pub fn estimate(self, p: [f32; 3], xi: f32) -> f32 {
        voronoi::smooth_voronoi3_stochastic(p, self.seed, super::SMOOTH_VORONOI_Q, xi)
    }

    /// An unbiased estimate with roulette probability `q` (higher: more exact work, less
    /// variance).
    #[must_use]
    #[inline]
    pub fn estimate_with(self, p: [f32; 3], q: f32, xi: f32) -> f32 {
        voronoi::smooth_voronoi3_stochastic(p, self.seed, q, xi)
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
        voronoi::worley3_f1(p, self.seed)
    }

    /// The feature point of a cell.
    #[must_use]
    #[inline]
    pub fn feature_point(self, cell: [i32; 3]) -> [f32; 3] {
        voronoi::feature_point3(cell, self.seed)
    }
}

/// 3D Gabor noise (Lagae et al. 2009) with its parameters and seed. Building it prepares the
/// impulse-count tables (about 10 µs): build it once and sample it many times. Its estimator
/// evaluates one impulse per cell.
///
/// ```
/// use noise_runtime::stochastic::{Gabor, GaborNoise};
/// let noise = GaborNoise::new(Gabor::default(), 7);
/// let p = [1.25, -3.5, 0.75];
/// // One sample of the estimator; its mean over ξ is `noise.sample(p)`.
/// assert!(noise.estimate(p, 0.3).is_finite() && noise.sample(p).is_finite());
/// ```
#[derive(Clone, Debug)]
pub struct GaborNoise {
    noise: gabor::GaborTables,
    seed: u32,
}

impl GaborNoise {
    /// Gabor noise with parameters `g` and this seed.
    pub fn new(g: gabor::Gabor, seed: u32) -> GaborNoise {
        GaborNoise {
            noise: gabor::GaborTables::new(g),
            seed,
        }
    }

    /// The noise at `p`.
    #[must_use]
    #[inline]
    pub fn sample(&self, p: [f32; 3]) -> f32 {
        self.noise.sample(p, self.seed)
    }

    /// An unbiased one-sample estimate.
    #[must_use]
    #[inline]
    pub fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        self.noise.sample_stochastic(p, self.seed, xi)
    }
}
