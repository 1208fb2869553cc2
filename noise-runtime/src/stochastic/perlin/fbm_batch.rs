//! The fBm batch kernels on eight lanes: the octaves of [`fbm3`](super::fbm::fbm3) in its order, each
//! octave's points on the Perlin lane kernels (`perlin/batch.rs`).

use super::super::batch::{Path, W, chunks, columns, on_lanes, outside};
use super::super::estimators::sanitize_xi;
use super::super::fractal::{Fractal, octave_seed};
use super::batch::{perlin3_lanes, perlin3_stochastic_lanes};
use super::fbm as single;
use crate::lanes::{F8, Lanes8};

/// [`fbm3_batch`] on eight lanes: `fbm3`'s octaves in its order, each
/// octave's points on lanes (a lane outside the split range at some octave takes the
/// single-point Perlin noise for that octave).
#[inline(always)]
pub(crate) fn fbm3<L: Lanes8>(cpu: L, points: &[[f32; 3]], f: Fractal, seed: u32, out: &mut [f32]) {
    let (n, lac, gain) = f.sane();
    chunks!(
        points,
        out,
        |p| {
            let (mut amp, mut freq, mut sum) = (1.0f32, 1.0f32, [0.0f32; W]);
            for o in 0..n {
                let mut q = p;
                for c in q.iter_mut() {
                    for v in c.iter_mut() {
                        *v *= freq;
                    }
                }
                let s = octave_seed(seed, o);
                let mut v = perlin3_lanes(cpu, &q, s);
                let bad = outside(cpu, &q);
                if bad != 0 {
                    for (i, v) in v.iter_mut().enumerate() {
                        if bad >> i & 1 == 1 {
                            *v = super::perlin3([q[0][i], q[1][i], q[2][i]], s);
                        }
                    }
                }
                for i in 0..W {
                    sum[i] += amp * v[i];
                }
                amp *= gain;
                freq *= lac;
            }
            (sum, 0)
        },
        |i| single::fbm3(points[i], f, seed)
    );
}

/// [`fbm3_stochastic_batch`] on eight lanes, for lacunarity 2
/// and gain ±½ (the caller checks). Each lane's octave is the one `fractal::OctavePick`
/// picks, here read off the exponent of `2 − target` (exact, by Sterbenz's lemma): a target
/// in `[2 − 2^−k, 2 − 2^−(k+1))` lies in octave `k + 1`, and then `2 − target` lies in
/// `(2^−(k+1), 2^−k]`, whose exponent `e` gives `k = −e`, or `−e − 1` when `2 − target` is
/// not a power of two. Then the octave's estimator on lanes, each lane with its own
/// octave's frequency, seed and remapped ξ.
#[inline(always)]
pub(crate) fn fbm3_stochastic<L: Lanes8>(
    cpu: L,
    points: &[[f32; 3]],
    f: Fractal,
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) {
    let (n, _, gain) = f.sane();
    let total = 2.0 - f32::from_bits((128 - n) << 23);
    let below = f32::from_bits(total.to_bits() - 1);
    let negative = (gain < 0.0) as u32;
    chunks!(
        points,
        xi,
        out,
        |p, x| {
            let mut octave = [0u32; W];
            let mut seeds = [0u32; W];
            let mut remapped = [0.0f32; W];
            let mut q = [[0.0f32; W]; 3];
            for i in 0..W {
                // Non-negative, so the bits order as the values: an integer minimum, without
                // `f32::min`'s NaN case (no NaN comes out of `sanitize_xi`).
                let target =
                    f32::from_bits((sanitize_xi(x[i]) * total).to_bits().min(below.to_bits()));
                let d = (2.0 - target).to_bits();
                // k + 1 = 128 − (biased exponent of d), less one unless d is a power of two;
                // octave 0 below 1.
                let o = 128u32
                    .wrapping_sub(d >> 23)
                    .wrapping_sub((d & 0x7f_ffff != 0) as u32)
                    & 0u32.wrapping_sub((target.to_bits() >= 0x3f80_0000) as u32);
                let freq = f32::from_bits((127 + o) << 23);
                octave[i] = o;
                seeds[i] = octave_seed(seed, o);
                remapped[i] = target * freq - (((2u32 << o) - 2) as i32) as f32;
                for a in 0..3 {
                    q[a][i] = p[a][i] * freq;
                }
            }
            let v = perlin3_stochastic_lanes::<L, true>(cpu, &q, &seeds, &remapped);
            let mut s = [0.0f32; W];
            for i in 0..W {
                s[i] = f32::from_bits((total * v[i]).to_bits() ^ ((negative & octave[i]) << 31));
            }
            (s, outside(cpu, &q))
        },
        |i| single::fbm3_stochastic(points[i], f, seed, xi[i])
    );
}

/// [`fbm3`](super::fbm::fbm3) at every point: `out[i] = fbm3(points[i], f, seed)` for the first
/// `min(points.len(), out.len())` points, whose count it returns.
pub fn fbm3_batch(points: &[[f32; 3]], f: Fractal, seed: u32, out: &mut [f32]) -> usize {
    fbm3_batch_on(Path::best(), points, f, seed, out)
}

/// [`fbm3_stochastic`](super::fbm::fbm3_stochastic) at every point with its own ξ:
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

/// [`fbm3_batch`] on a chosen path.
pub(crate) fn fbm3_batch_on(
    path: Path,
    points: &[[f32; 3]],
    f: Fractal,
    seed: u32,
    out: &mut [f32],
) -> usize {
    let n = points.len().min(out.len());
    let (points, out) = (&points[..n], &mut out[..n]);
    on_lanes!(path, fbm3(points: &[[f32; 3]], f: Fractal, seed: u32, out: &mut [f32]));
    n
}

/// [`fbm3_stochastic_batch`] on a chosen path.
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
    if halving(f) {
        on_lanes!(path, fbm3_stochastic(points: &[[f32; 3]], f: Fractal, seed: u32, xi: &[f32], out: &mut [f32]));
    } else {
        for ((o, &p), &x) in out.iter_mut().zip(points).zip(xi) {
            *o = single::fbm3_stochastic(p, f, seed, x);
        }
    }
    n
}

/// Whether `f` has lacunarity 2 and gain ±½, the fBm whose estimator runs on lanes.
fn halving(f: Fractal) -> bool {
    let (_, lac, gain) = f.sane();
    lac == 2.0 && (gain == 0.5 || gain == -0.5)
}
