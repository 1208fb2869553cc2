//! Batch forms: 3D Perlin noise and its fBm, deterministic and as estimators, over a slice of
//! points at once, eight points sharing each instruction as the pixels of a GPU warp do. This
//! module is what every batch kernel shares: the lane backend a call runs on ([`Path`]: AVX2 on
//! an x86_64 CPU that has it, asked once at run time, portably elsewhere), the one AVX2
//! dispatch ([`on_lanes!`]), and the chunk loop with its exact per-lane fallback. The kernels
//! live with their noise: `perlin/batch.rs`, `fractal/batch.rs`. Either way each output is,
//! **bit for bit**, what the single-point function returns for that point (and ξ), so a
//! renderer can switch freely between them.
//!
//! What the batch buys is the absolute time (`noisebake report stochastic` prints each batch
//! form's time and its ratio to the single-point form): on lanes the deterministic form's eight
//! corners cost little more than the estimator's one (both pay for the split, the fades and the
//! hashing, and a table read of eight gradients is three instructions), so the estimator's lead
//! over the deterministic form grows only a little.
//!
//! The noise types' batch verbs check that their slices agree in length
//! ([`BatchLengths`](super::BatchLengths)); the kernels' entry points evaluate the first `min`
//! of the lengths and return that count.
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
//!
//! The kernels are `#[inline(always)]` and generic over the [`Lanes8`] implementation, so each
//! is compiled inside each entry point: inside a `#[target_feature(enable = "avx2")]` one with
//! the [`Avx2`](crate::lanes::avx2::Avx2) token, and inside the portable one with
//! [`Portable8`]. A lane whose coordinates leave the split range (`|x| ≥ 2^22`, NaN, infinite)
//! is computed again by the single-point function, which handles it exactly.

use crate::lanes::{F8, Lanes8, U8};
use crate::math::split_in_range;

pub(crate) use crate::lanes::scalar::Portable8;

/// Lanes per register.
pub(crate) const W: usize = 8;
/// The fixed-point 1 of the corner choice (`estimators::Narrowing`).
pub(crate) const ONE: u32 = 1 << 23;

/// Eight points as three coordinate registers.
#[inline(always)]
pub(crate) fn columns(p: &[[f32; 3]; W]) -> [F8; 3] {
    let mut c = [[0.0f32; W]; 3];
    for i in 0..W {
        for a in 0..3 {
            c[a][i] = p[i][a];
        }
    }
    c
}

/// Bit `i` set when lane `i` of `p` is outside the split range (the test of
/// [`in_split_range`](crate::math::in_split_range), lane by lane).
#[inline(always)]
pub(crate) fn outside<L: Lanes8>(cpu: L, p: &[F8; 3]) -> u32 {
    let mut any = [0u32; W];
    for c in p {
        for i in 0..W {
            any[i] |= (c[i].to_bits() & 0x7fff_ffff).wrapping_add(0x8000_0000 - 0x4a80_0000);
        }
    }
    cpu.sign_bits(any)
}

/// Cells (as `u32`) and offsets of every lane by [`split_in_range`].
#[inline(always)]
pub(crate) fn split(p: &[F8; 3]) -> ([U8; 3], [F8; 3]) {
    let mut cell = [[0u32; W]; 3];
    let mut f = [[0.0f32; W]; 3];
    for a in 0..3 {
        for i in 0..W {
            let (c, fa) = split_in_range(p[a][i]);
            cell[a][i] = c as u32;
            f[a][i] = fa;
        }
    }
    (cell, f)
}

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

/// Runs the batch kernel `$kernel(cpu, args…)` on `$path`: the one place the AVX2 entry point
/// is written. It instantiates the generic kernel inside a `#[target_feature(enable =
/// "avx2")]` function (so that the whole kernel, every helper being `#[inline(always)]`, is
/// compiled with the feature) and calls it with the token that proves the CPU has AVX2; the
/// portable path runs the same kernel with [`Portable8`]. The `unsafe` of that call is the only
/// one of the runtime outside the lane layer.
macro_rules! on_lanes {
    ($path:expr, $kernel:ident($($arg:ident: $ty:ty),*)) => {{
        match $path {
            #[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
            $crate::stochastic::batch::Path::Avx2(cpu) => {
                #[target_feature(enable = "avx2")]
                fn entry(cpu: $crate::lanes::avx2::Avx2, $($arg: $ty),*) {
                    $kernel(cpu, $($arg),*)
                }
                #[allow(unsafe_code)]
                // SAFETY: the token exists only on a CPU with AVX2 (`Avx2::detect`).
                unsafe {
                    entry(cpu, $($arg),*)
                }
            }
            $crate::stochastic::batch::Path::Portable => {
                $kernel($crate::stochastic::batch::Portable8, $($arg),*)
            }
        }
    }};
}
pub(crate) use on_lanes;

/// The loop of every entry point: `$lanes` (an expression of the chunk's columns `$p`, and
/// of its ξ `$x` when the entry point has them, giving the eight values and a mask of lanes
/// outside the split range) over the points eight at a time; `$one` (an expression of the
/// point's index `$i`) for each masked lane and for the points after the last whole chunk.
macro_rules! chunks {
    ($points:expr, $out:expr, |$p:ident| $lanes:expr, |$i:ident| $one:expr) => {{
        let (points, out): (&[[f32; 3]], &mut [f32]) = ($points, $out);
        let (chunks, _) = points.as_chunks::<W>();
        let (outs, _) = out.as_chunks_mut::<W>();
        for (k, (c, o)) in chunks.iter().zip(outs.iter_mut()).enumerate() {
            let $p = columns(c);
            let (v, bad): (F8, u32) = $lanes;
            *o = v;
            $crate::stochastic::batch::fix_lanes!(o, bad, k, |$i| $one);
        }
        for (n, o) in out.iter_mut().enumerate().skip(chunks.len() * W) {
            let $i = n;
            *o = $one;
        }
    }};
    (
        $points:expr, $xi:expr, $out:expr,
        |$p:ident, $x:ident| $lanes:expr, |$i:ident| $one:expr
    ) => {{
        let (points, xi, out): (&[[f32; 3]], &[f32], &mut [f32]) = ($points, $xi, $out);
        let (chunks, _) = points.as_chunks::<W>();
        let (xis, _) = xi.as_chunks::<W>();
        let (outs, _) = out.as_chunks_mut::<W>();
        for (k, ((c, $x), o)) in chunks.iter().zip(xis).zip(outs.iter_mut()).enumerate() {
            let $p = columns(c);
            let (v, bad): (F8, u32) = $lanes;
            *o = v;
            $crate::stochastic::batch::fix_lanes!(o, bad, k, |$i| $one);
        }
        for (n, o) in out.iter_mut().enumerate().skip(chunks.len() * W) {
            let $i = n;
            *o = $one;
        }
    }};
}

/// `$one` for each lane of chunk `$k` whose bit is set in `$bad`, written to `$o`.
macro_rules! fix_lanes {
    ($o:ident, $bad:ident, $k:ident, |$i:ident| $one:expr) => {
        if $bad != 0 {
            for (lane, o) in $o.iter_mut().enumerate() {
                if $bad >> lane & 1 == 1 {
                    let $i = $k * W + lane;
                    *o = $one;
                }
            }
        }
    };
}

pub(crate) use chunks;
pub(crate) use fix_lanes;

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::estimators::ONE_BELOW;
    use super::super::fractal::Fractal;
    use super::super::perlin::batch::{perlin3_batch_on, perlin3_stochastic_batch_on};
    use super::super::perlin::fbm::{fbm3, fbm3_stochastic};
    use super::super::perlin::fbm_batch::{fbm3_batch_on, fbm3_stochastic_batch_on};
    use super::super::perlin::{perlin3, perlin3_stochastic};
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
