//! Batch forms: 3D Perlin noise and its fBm, deterministic and as estimators, over a slice of
//! points at once, eight points sharing each instruction as the pixels of a GPU warp do: one
//! kernel per function over the lane layer's eight-lane operations, compiled for AVX2 on an
//! x86_64 CPU that has it (asked once at run time) and portably elsewhere. Either way each output is, **bit for bit**, what the single-point
//! function returns for that point (and ξ), so a renderer can switch freely between them.
//!
//! What the batch buys is the absolute time (`noisebake report stochastic` prints each batch
//! form's time and its ratio to the single-point form): on lanes the deterministic form's eight
//! corners cost little more than the estimator's one (both pay for the split, the fades and the
//! hashing, and a table read of eight gradients is three instructions), so the estimator's lead
//! over the deterministic form grows only a little.
//!
//! The noise types' batch verbs check that their slices agree in length
//! ([`BatchLengths`](super::BatchLengths)); the functions here evaluate the first `min` of the
//! lengths and return that count.
//!
//! ```
//! use noise_runtime::stochastic::{Fbm, Fractal};
//!
//! let points: Vec<[f32; 3]> = (0..100).map(|i| [i as f32 * 0.37, 1.5, -2.25]).collect();
//! let mut out = vec![0.0; points.len()];
//! let fbm = Fbm::new(Fractal::default(), 7);
//! fbm.sample_batch(&points, &mut out).unwrap();
//! assert_eq!(out[42].to_bits(), fbm.sample(points[42]).to_bits());
//! // One ξ per point, e.g. from a blue-noise mask's pixels.
//! let xi: Vec<f32> = (0..100).map(|i| (i as f32 + 0.5) / 100.0).collect();
//! fbm.estimate_batch(&points, &xi, &mut out).unwrap();
//! assert!(out.iter().all(|v| v.is_finite()));
//! // A ξ short is an error, not a silently shorter run.
//! assert!(fbm.estimate_batch(&points, &xi[..99], &mut out).is_err());
//! ```

use super::fractal::{Fractal, fbm3, fbm3_stochastic};
use super::perlin::{perlin3, perlin3_stochastic};

use crate::lanes::scalar::Portable8;

mod kernels;

/// Which backend of the lane layer runs the batch kernels.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Path {
    /// AVX2 lanes, with the token that proves the CPU has them.
    #[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
    Avx2(crate::lanes::avx2::Avx2),
    /// The same kernels with the portable eight-lane operations.
    Portable,
}

impl Path {
    /// The fastest path this CPU runs.
    #[inline]
    pub(crate) fn best() -> Path {
        #[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
        if let Some(cpu) = crate::lanes::avx2::Avx2::detect() {
            return Path::Avx2(cpu);
        }
        Path::Portable
    }
}

/// The kernels compiled for AVX2: each entry point instantiates its kernel with the token, so
/// that the whole kernel (every helper is `#[inline(always)]`) is compiled with the feature.
#[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
mod avx2 {
    use super::kernels;
    use crate::lanes::avx2::Avx2;
    use crate::stochastic::Fractal;

    #[target_feature(enable = "avx2")]
    pub(super) fn perlin3(cpu: Avx2, points: &[[f32; 3]], seed: u32, out: &mut [f32]) {
        kernels::perlin3(cpu, points, seed, out)
    }

    #[target_feature(enable = "avx2")]
    pub(super) fn perlin3_stochastic(
        cpu: Avx2,
        points: &[[f32; 3]],
        seed: u32,
        xi: &[f32],
        out: &mut [f32],
    ) {
        kernels::perlin3_stochastic(cpu, points, seed, xi, out)
    }

    #[target_feature(enable = "avx2")]
    pub(super) fn fbm3(cpu: Avx2, points: &[[f32; 3]], f: Fractal, seed: u32, out: &mut [f32]) {
        kernels::fbm3(cpu, points, f, seed, out)
    }

    #[target_feature(enable = "avx2")]
    pub(super) fn fbm3_stochastic(
        cpu: Avx2,
        points: &[[f32; 3]],
        f: Fractal,
        seed: u32,
        xi: &[f32],
        out: &mut [f32],
    ) {
        kernels::fbm3_stochastic(cpu, points, f, seed, xi, out)
    }
}

/// [`perlin3`] at every point: `out[i] = perlin3(points[i], seed)` for the
/// first `min(points.len(), out.len())` points, whose count it returns.
pub fn perlin3_batch(points: &[[f32; 3]], seed: u32, out: &mut [f32]) -> usize {
    perlin3_batch_on(Path::best(), points, seed, out)
}

/// [`perlin3_stochastic`] at every point with its own ξ:
/// `out[i] = perlin3_stochastic(points[i], seed, xi[i])` for the first `min` of the three
/// lengths, whose count it returns.
pub fn perlin3_stochastic_batch(
    points: &[[f32; 3]],
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) -> usize {
    perlin3_stochastic_batch_on(Path::best(), points, seed, xi, out)
}

/// [`fbm3`] at every point: `out[i] = fbm3(points[i], f, seed)` for the first
/// `min(points.len(), out.len())` points, whose count it returns.
pub fn fbm3_batch(points: &[[f32; 3]], f: Fractal, seed: u32, out: &mut [f32]) -> usize {
    fbm3_batch_on(Path::best(), points, f, seed, out)
}

/// [`fbm3_stochastic`] at every point with its own ξ:
/// `out[i] = fbm3_stochastic(points[i], f, seed, xi[i])` for the first `min` of the three
/// lengths, whose count it returns. The lanes serve lacunarity 2 and gain ±½ (the paper's
/// fBm); other parameters run one point at a time.
pub fn fbm3_stochastic_batch(
    points: &[[f32; 3]],
    f: Fractal,
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) -> usize {
    fbm3_stochastic_batch_on(Path::best(), points, f, seed, xi, out)
}

/// [`perlin3_batch`] on a chosen path (the tests run both).
#[allow(unsafe_code)]
pub(crate) fn perlin3_batch_on(
    path: Path,
    points: &[[f32; 3]],
    seed: u32,
    out: &mut [f32],
) -> usize {
    let n = points.len().min(out.len());
    let (points, out) = (&points[..n], &mut out[..n]);
    match path {
        #[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
        // SAFETY: the token exists only on a CPU with AVX2 (`Avx2::detect`).
        Path::Avx2(cpu) => unsafe { avx2::perlin3(cpu, points, seed, out) },
        Path::Portable => kernels::perlin3(Portable8, points, seed, out),
    }
    n
}

/// [`perlin3_stochastic_batch`] on a chosen path.
#[allow(unsafe_code)]
pub(crate) fn perlin3_stochastic_batch_on(
    path: Path,
    points: &[[f32; 3]],
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) -> usize {
    let n = points.len().min(xi.len()).min(out.len());
    let (points, xi, out) = (&points[..n], &xi[..n], &mut out[..n]);
    match path {
        #[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
        // SAFETY: as in `perlin3_batch_on`.
        Path::Avx2(cpu) => unsafe { avx2::perlin3_stochastic(cpu, points, seed, xi, out) },
        Path::Portable => kernels::perlin3_stochastic(Portable8, points, seed, xi, out),
    }
    n
}

/// [`fbm3_batch`] on a chosen path.
#[allow(unsafe_code)]
pub(crate) fn fbm3_batch_on(
    path: Path,
    points: &[[f32; 3]],
    f: Fractal,
    seed: u32,
    out: &mut [f32],
) -> usize {
    let n = points.len().min(out.len());
    let (points, out) = (&points[..n], &mut out[..n]);
    match path {
        #[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
        // SAFETY: as in `perlin3_batch_on`.
        Path::Avx2(cpu) => unsafe { avx2::fbm3(cpu, points, f, seed, out) },
        Path::Portable => kernels::fbm3(Portable8, points, f, seed, out),
    }
    n
}

/// [`fbm3_stochastic_batch`] on a chosen path.
#[allow(unsafe_code)]
pub(crate) fn fbm3_stochastic_batch_on(
    path: Path,
    points: &[[f32; 3]],
    f: Fractal,
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) -> usize {
    let n = points.len().min(xi.len()).min(out.len());
    let (points, xi, out) = (&points[..n], &xi[..n], &mut out[..n]);
    match path {
        #[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
        // SAFETY: as in `perlin3_batch_on`.
        Path::Avx2(cpu) if halving(f) => unsafe {
            avx2::fbm3_stochastic(cpu, points, f, seed, xi, out)
        },
        Path::Portable if halving(f) => {
            kernels::fbm3_stochastic(Portable8, points, f, seed, xi, out)
        }
        _ => {
            for ((o, &p), &x) in out.iter_mut().zip(points).zip(xi) {
                *o = fbm3_stochastic(p, f, seed, x);
            }
        }
    }
    n
}

/// Whether `f` has lacunarity 2 and gain ±½, the fBm whose estimator runs on lanes.
fn halving(f: Fractal) -> bool {
    let (_, lac, gain) = f.sane();
    lac == 2.0 && (gain == 0.5 || gain == -0.5)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::estimators::ONE_BELOW;
    use super::*;
    use std::{format, vec, vec::Vec};

    /// The portable path, and the AVX2 one when this build and CPU have it — said on stderr
    /// when they do not, so a green run without AVX2 is not mistaken for a tested AVX2 path.
    fn paths() -> impl Iterator<Item = Path> {
        let best = Path::best();
        let two = !matches!(best, Path::Portable);
        if !two {
            std::eprintln!(
                "SKIPPED: no AVX2 path on this build or CPU: only the portable batch path was tested"
            );
        }
        [Path::Portable, best].into_iter().take(1 + two as usize)
    }

    /// Points that are hard for the split and the range checks, mixed into batches with
    /// ordinary ones so that one odd lane sits among seven good ones: integers and their
    /// neighbouring floats, ±0, tiny magnitudes, the edge of the split range (2^22), huge
    /// coordinates, infinities and NaN; then random points at several scales.
    fn points() -> (Vec<[f32; 3]>, Vec<f32>) {
        let hard = [
            0.0f32,
            -0.0,
            1e-45,
            -1e-45,
            1.0,
            f32::from_bits(1.0f32.to_bits() + 1),
            -f32::from_bits(1.0f32.to_bits() + 1),
            -1.0,
            0.5,
            -2.5,
            4_194_303.5,
            -4_194_303.5,
            4_194_304.0,
            1e7,
            -1e7,
            3e38,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let odd_xi = [
            0.0f32,
            -0.0,
            1e-30,
            0.5,
            ONE_BELOW,
            1.0,
            2.0,
            -1.0,
            f32::NAN,
        ];
        let mut next = super::super::uniforms(0x6a09_e667_f3bc_c908);
        let mut pts = Vec::new();
        let mut xi = Vec::new();
        let n = hard.len();
        for i in 0..n * n * n {
            pts.push([hard[i % n], hard[i / n % n], hard[i / n / n]]);
            xi.push(if i % 3 == 0 {
                odd_xi[i / 3 % odd_xi.len()]
            } else {
                next()
            });
            // Seven ordinary points after every hard one.
            for _ in 0..7 {
                pts.push([0; 3].map(|_| (next() - 0.5) * 200.0));
                xi.push(next());
            }
        }
        for scale in [2.0f32, 1e3, 8e6] {
            for _ in 0..20_000 {
                pts.push([0; 3].map(|_| (next() - 0.5) * scale));
                xi.push(next());
            }
        }
        (pts, xi)
    }

    fn same_bits(what: &str, got: &[f32], want: impl Fn(usize) -> f32) {
        for (i, g) in got.iter().enumerate() {
            let w = want(i);
            assert_eq!(g.to_bits(), w.to_bits(), "{what} at {i}: {g} vs {w}");
        }
    }

    #[test]
    fn perlin3_batches_are_the_single_point_functions_bit_for_bit() {
        let (pts, xi) = points();
        let mut out = vec![0.0f32; pts.len()];
        for path in paths() {
            for seed in [0u32, 7, 0xdead_beef] {
                assert_eq!(perlin3_batch_on(path, &pts, seed, &mut out), pts.len());
                same_bits(&format!("{path:?} perlin3"), &out, |i| {
                    perlin3(pts[i], seed)
                });
                assert_eq!(
                    perlin3_stochastic_batch_on(path, &pts, seed, &xi, &mut out),
                    pts.len()
                );
                same_bits(&format!("{path:?} estimator"), &out, |i| {
                    perlin3_stochastic(pts[i], seed, xi[i])
                });
            }
        }
    }

    #[test]
    fn fbm3_batches_are_the_single_point_functions_bit_for_bit() {
        let (pts, xi) = points();
        let (pts, xi) = (&pts[..60_000], &xi[..60_000]);
        let mut out = vec![0.0f32; pts.len()];
        let fractals = [
            Fractal::default(),
            Fractal::new(10, 2.0, -0.5),
            Fractal::new(1, 2.0, 0.5),
            Fractal::new(24, 2.0, 0.5),
            Fractal::new(32, 2.0, 0.5),
            Fractal::new(5, 2.5, 0.6),
            Fractal::new(4, 1.0, 1.0),
            Fractal::new(3, f32::NAN, f32::NAN),
            // Frequencies that overflow to infinity within the octaves.
            Fractal::new(20, 1000.0, -3.0),
        ];
        for path in paths() {
            for f in fractals {
                let seed = 11;
                assert_eq!(fbm3_batch_on(path, pts, f, seed, &mut out), pts.len());
                same_bits(&format!("{path:?} fbm3 {f:?}"), &out, |i| {
                    fbm3(pts[i], f, seed)
                });
                fbm3_stochastic_batch_on(path, pts, f, seed, xi, &mut out);
                same_bits(&format!("{path:?} fbm3 estimator {f:?}"), &out, |i| {
                    fbm3_stochastic(pts[i], f, seed, xi[i])
                });
            }
        }
    }

    #[test]
    fn batches_take_the_shortest_slice_and_leave_the_rest() {
        let pts = [[0.3f32, 1.7, -2.2]; 21];
        let xi = [0.25f32; 13];
        let f = Fractal::default();
        for path in paths() {
            for len in [0usize, 1, 7, 8, 9, 16, 21] {
                let mut out = [f32::NAN; 24];
                let n = perlin3_batch_on(path, &pts[..len], 3, &mut out);
                check(&out, n, len, perlin3(pts[0], 3));
                let mut out = [f32::NAN; 24];
                let n = perlin3_stochastic_batch_on(path, &pts[..len], 3, &xi, &mut out[..10]);
                check(&out, n, len.min(10), perlin3_stochastic(pts[0], 3, 0.25));
                let mut out = [f32::NAN; 24];
                let n = fbm3_batch_on(path, &pts[..len], f, 3, &mut out[..20]);
                check(&out, n, len.min(20), fbm3(pts[0], f, 3));
                let mut out = [f32::NAN; 24];
                let n = fbm3_stochastic_batch_on(path, &pts[..len], f, 3, &xi, &mut out);
                check(&out, n, len.min(13), fbm3_stochastic(pts[0], f, 3, 0.25));
            }
        }
        /// `n` is the expected count, the first `n` outputs hold `v` and the rest are untouched.
        fn check(out: &[f32], n: usize, want: usize, v: f32) {
            assert_eq!(n, want);
            assert!(
                out[..n].iter().all(|o| o.to_bits() == v.to_bits()),
                "{out:?}"
            );
            assert!(
                out[n..].iter().all(|o| o.is_nan()),
                "wrote past {n}: {out:?}"
            );
        }
    }
}
