//! The verbs every noise has, as traits: [`Noise`] (`sample`, the deterministic value, and
//! `estimate`, the unbiased one-sample estimator from one ξ; batch forms over slices of
//! points) and [`Gradient`] (the analytic gradient, where the noise has one); the points they
//! take ([`LatticePoint`], whose per-dimension dispatch is `lattice.rs`). The floor of the
//! folder: it imports no noise. A noise a fractal sum can be built from implements
//! [`Octaves`](super::Octaves) too, beside [`Fbm`](super::Fbm) in `fractal/`. Each noise type lives in its
//! own folder with its lane and batch kernels and implements these traits; its inherent
//! methods are the same functions, callable without importing a trait. A noise value is its
//! parameters (the seed among them, fixed at construction); the point comes first in every
//! call and ξ last.
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
    pub(crate) fn check(points: usize, xi: Option<usize>, out: usize) -> Result<(), Self> {
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
    /// Perlin noise at every point (lengths checked by the caller): a loop, or the 3D lane
    /// kernel.
    #[doc(hidden)]
    fn perlin_batch(points: &[Self], seed: u32, out: &mut [f32]) {
        for (o, &p) in out.iter_mut().zip(points) {
            *o = p.perlin(seed);
        }
    }
    /// The Perlin estimator at every point with its own ξ: a loop, or the 3D lane kernel.
    #[doc(hidden)]
    fn perlin_estimate_batch(points: &[Self], seed: u32, xi: &[f32], out: &mut [f32]) {
        for ((o, &p), &x) in out.iter_mut().zip(points).zip(xi) {
            *o = p.perlin_estimate(seed, x);
        }
    }
}

/// The verbs every noise has at points of type `P`: the deterministic value and an unbiased
/// one-sample estimate of it (Fajardo & Pharr: `E_ξ[estimate(p, ξ)] = sample(p)` for `ξ`
/// uniform in `[0, 1]`), and their batch forms. Object safe, so a renderer or a report can keep
/// noises of different types side by side (`Box<dyn Noise<[f32; 3]>>`).
pub trait Noise<P: Copy> {
    /// The noise at `p`.
    fn sample(&self, p: P) -> f32;

    /// An unbiased one-sample estimate of [`sample`](Self::sample) from one uniform `xi`.
    fn estimate(&self, p: P, xi: f32) -> f32;

    /// [`sample`](Self::sample) of every point into `out`, bit for bit the single-point
    /// values (eight per instruction where the noise has a lane kernel: 3D Perlin and fBm).
    /// Slices of different lengths are an error, and nothing is written.
    fn sample_batch(&self, points: &[P], out: &mut [f32]) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), None, out.len())?;
        for (o, &p) in out.iter_mut().zip(points) {
            *o = self.sample(p);
        }
        Ok(())
    }

    /// [`estimate`](Self::estimate) of every point with its own ξ, as
    /// [`sample_batch`](Self::sample_batch).
    fn estimate_batch(
        &self,
        points: &[P],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), Some(xi.len()), out.len())?;
        for ((o, &p), &x) in out.iter_mut().zip(points).zip(xi) {
            *o = self.estimate(p, x);
        }
        Ok(())
    }
}

/// A noise with an analytic gradient: the value and `∇` at `p`.
pub trait Gradient<P: Copy>: Noise<P> {
    /// The noise and its gradient at `p`.
    fn gradient(&self, p: P) -> (f32, P);
}
