//! Fractal sums of octaves (fBm, Perlin 1985; eq. 9) and the one-octave estimator (eq. 10–11,
//! Algorithm 2): the octave is importance-sampled by its weight, and the chosen octave's noise
//! may itself be stochastic (it receives the remapped ξ). Algorithm 2 finds the octave by a
//! linear search of the CDF; here it is the count of octave starts at or below the target (a
//! fixed number of compares), or for lacunarity 2 and gain ±½ read off the exponent of
//! `2 − target` — the same octave either way, without the search's ξ-dependent exit, which a
//! branch predictor misses about once per sample.
//!
//! Algorithm 2 in the paper normalises by `(1 − w^(n+1))/(1 − w)`; the sum of the `n` weights
//! `w^0 … w^(n−1)` is `(1 − w^n)/(1 − w)`, which is what we use (summed directly, so gain → 1
//! and gain = 0 need no special case).

use super::estimators::{ONE_BELOW, sanitize_xi};
use super::perlin::{perlin3, perlin3_stochastic};

/// Octaves, lacunarity (frequency factor per octave) and gain (amplitude factor per octave).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fractal {
    /// Number of octaves, clamped to `1..=32`.
    pub octaves: u32,
    /// Frequency factor per octave, clamped to `[-1024, 1024]`.
    pub lacunarity: f32,
    /// Amplitude factor per octave, clamped to `[-16, 16]` (negative gains alternate sign).
    pub gain: f32,
}

impl Default for Fractal {
    /// 10 octaves, lacunarity 2, gain ½ (the paper's settings).
    fn default() -> Self {
        Fractal::new(10, 2.0, 0.5)
    }
}

impl Fractal {
    /// A fractal sum.
    pub const fn new(octaves: u32, lacunarity: f32, gain: f32) -> Self {
        Fractal {
            octaves,
            lacunarity,
            gain,
        }
    }

    #[inline(always)]
    fn sane(self) -> (u32, f32, f32) {
        let c = |x: f32, m: f32| if x >= -m { x.min(m) } else { -m };
        let gain = if self.gain.is_nan() {
            0.0
        } else {
            c(self.gain, 16.0)
        };
        let lac = if self.lacunarity.is_nan() {
            1.0
        } else {
            c(self.lacunarity, 1024.0)
        };
        (self.octaves.clamp(1, 32), lac, gain)
    }
}

/// `Σ_o gain^o · noise(p · lacunarity^o, o)` over the octaves (eq. 9).
#[inline]
pub fn fractal(p: [f32; 3], f: Fractal, mut noise: impl FnMut([f32; 3], u32) -> f32) -> f32 {
    let (n, lac, gain) = f.sane();
    let (mut amp, mut freq, mut sum) = (1.0f32, 1.0f32, 0.0f32);
    for o in 0..n {
        sum += amp * noise([p[0] * freq, p[1] * freq, p[2] * freq], o);
        amp *= gain;
        freq *= lac;
    }
    sum
}

/// One-sample estimator of [`fractal`] (Algorithm 2): octave `o` is chosen with probability
/// `|gain^o| / Σ|gain^i|`, and `noise(p · lacunarity^o, o, ξ')` is scaled by the sum; `ξ'` is ξ
/// remapped within the chosen octave's interval, so the noise can be stochastic too.
#[inline(always)]
pub fn fractal_stochastic(
    p: [f32; 3],
    f: Fractal,
    xi: f32,
    noise: impl FnOnce([f32; 3], u32, f32) -> f32,
) -> f32 {
    let k = OctavePick::new(f, xi);
    k.scale(noise(k.point(p), k.octave, k.xi))
}

/// The octave Algorithm 2 picks for one ξ, with what the estimator needs of it.
#[derive(Clone, Copy)]
pub(crate) struct OctavePick {
    /// The chosen octave.
    pub(crate) octave: u32,
    /// Its frequency `lacunarity^octave`, as [`fractal`] computes it.
    freq: f32,
    /// ξ remapped within the octave's interval, in `[0, 1)`, for a stochastic octave noise.
    pub(crate) xi: f32,
    /// `Σ|gain^i|`, the estimator's weight.
    total: f32,
    /// The sign bit of `gain^octave` (negative gains alternate).
    flip: u32,
}

impl OctavePick {
    #[inline(always)]
    pub(crate) fn new(f: Fractal, xi: f32) -> Self {
        let (n, lac, gain) = f.sane();
        if lac == 2.0 && (gain == 0.5 || gain == -0.5) {
            Self::halving(n, gain, xi)
        } else {
            Self::table(n, lac, gain, xi)
        }
    }

    /// [`OctavePick::new`] for any parameters, by a table of the CDF.
    #[inline(always)]
    fn table(n: u32, lac: f32, gain: f32, xi: f32) -> Self {
        let g = gain.abs();
        // Each octave's interval `[start, start + amp)` of the CDF and its frequency,
        // accumulated in the order the deterministic sum multiplies them, so the chosen
        // octave's frequency is bit for bit the one `fractal` uses. Independent of ξ: with a
        // constant `Fractal` the compiler folds the table.
        let mut start = [0.0f32; 32];
        let mut amp = [0.0f32; 32];
        let mut freq = [0.0f32; 32];
        let (mut s, mut a, mut fr) = (0.0f32, 1.0f32, 1.0f32);
        for o in 0..n as usize {
            (start[o], amp[o], freq[o]) = (s, a, fr);
            s += a;
            a *= g;
            fr *= lac;
        }
        let target = Self::target(xi, s);
        // The octave is the number of later starts at or below the target: a fixed number of
        // compares, summed. The linear search of Algorithm 2 stops after a number of steps set
        // by ξ, which the branch predictor cannot know: about one misprediction per call,
        // which cost more than the rest of the estimator.
        let mut o = 0usize;
        for &st in &start[1..n as usize] {
            o += (target >= st) as usize;
        }
        let xi = if amp[o] > 0.0 {
            ((target - start[o]) / amp[o]).clamp(0.0, ONE_BELOW)
        } else {
            0.0
        };
        OctavePick {
            octave: o as u32,
            freq: freq[o],
            xi,
            total: s,
            // An integer, not a select on the octave's parity (which would be a branch).
            flip: ((gain < 0.0) as u32 & o as u32) << 31,
        }
    }

    /// [`OctavePick::new`] for lacunarity 2 and gain ±½ (the paper's settings and the most
    /// common fBm): the same octave, frequency and remapped ξ, bit for bit, from exponent bits
    /// instead of a table of the CDF. The octave starts are `S_o = 2 − 2^(1−o)`, exact in f32
    /// up to `o = 24` (after that the sum rounds to 2 and later octaves are never chosen, in
    /// either form), so `S_o ≤ target < S_(o+1)` is `2^(−o) < w ≤ 2^(1−o)` for
    /// `w = 2 − target`, and `o` is minus the exponent of the double just below `w`. The
    /// frequency `2^o` and `(target − S_o)·2^o ∈ [0, 1)` are exact.
    #[inline(always)]
    fn halving(n: u32, gain: f32, xi: f32) -> Self {
        // Σ_(o<n) 2^−o = 2 − 2^(1−n), computed in f32 as the running sum rounds it: exact up to
        // n = 24, and 2 from n = 25 (2 − 2^−24 is a tie that rounds to even, 2), where the sum
        // also stops growing. A closed form, not the loop: with a `Fractal` that is not a
        // compile-time constant the loop's ten dependent adds would delay every sample.
        let total = 2.0 - f32::from_bits((128 - n) << 23);
        let target = Self::target(xi, total);
        // In f64, where `2 − target` is exact for every f32 target (in f32 it rounds for
        // targets just below 1, to an octave too far).
        let w = 2.0 - target as f64;
        let o = (1023 - ((w.to_bits() - 1) >> 52)) as u32;
        let pow2 = |e: u32| f32::from_bits((127 + e) << 23);
        let start = 2.0 - 2.0 * f32::from_bits((127 - o) << 23);
        OctavePick {
            octave: o,
            freq: pow2(o),
            xi: (target - start) * pow2(o),
            total,
            flip: ((gain < 0.0) as u32 & o) << 31,
        }
    }

    /// `ξ · total`, kept below `total` (the product rounds up to it for ξ just below 1), so
    /// that it lies in some octave's interval `[start, start + weight)`.
    #[inline(always)]
    fn target(xi: f32, total: f32) -> f32 {
        (sanitize_xi(xi) * total).min(f32::from_bits(total.to_bits() - 1))
    }

    /// The point scaled to the chosen octave's frequency.
    #[inline(always)]
    pub(crate) fn point(self, p: [f32; 3]) -> [f32; 3] {
        p.map(|c| c * self.freq)
    }

    /// The estimate from the chosen octave's noise value `v`: `±total · v`.
    #[inline(always)]
    pub(crate) fn scale(self, v: f32) -> f32 {
        f32::from_bits((self.total * v).to_bits() ^ self.flip)
    }
}

/// The seed of octave `o`: each octave of a fractal noise is an independent noise.
#[inline(always)]
pub(crate) fn octave_seed(seed: u32, o: u32) -> u32 {
    seed.wrapping_add(o.wrapping_mul(0x9e37_79b9))
}

/// fBm of 3D Perlin noise (each octave with its own seed).
#[inline(always)]
pub fn fbm3(p: [f32; 3], f: Fractal, seed: u32) -> f32 {
    fractal(p, f, |q, o| perlin3(q, octave_seed(seed, o)))
}

/// One-sample estimator of [`fbm3`]: one octave, and in it one Perlin gradient — one hash and
/// one dot product whatever the octave count.
#[inline(always)]
pub fn fbm3_stochastic(p: [f32; 3], f: Fractal, seed: u32, xi: f32) -> f32 {
    let k = OctavePick::new(f, xi);
    k.scale(perlin3_stochastic(
        k.point(p),
        octave_seed(seed, k.octave),
        k.xi,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exponent-bit form for lacunarity 2 and gain ±½ picks what the table form picks:
    /// the same octave, frequency, remapped ξ, weight and sign, bit for bit, for every octave
    /// count, on a fine ξ grid, at each octave boundary and an ulp either side, and at the
    /// hard values of ξ.
    #[test]
    fn halving_form_is_the_table_form_bit_for_bit() {
        let fields = |k: OctavePick| {
            (
                k.octave,
                k.freq.to_bits(),
                k.xi.to_bits(),
                k.total.to_bits(),
                k.flip,
            )
        };
        for n in 1..=32u32 {
            for gain in [0.5f32, -0.5] {
                let hard = [0.0f32, 1e-30, ONE_BELOW, 1.0, 2.0, -1.0, f32::NAN];
                let grid = (0..1u32 << 16).map(|i| (i as f32 + 0.5) / 65_536.0);
                // ξ at which the target crosses each octave start, and its neighbours.
                let (mut total, mut w) = (0.0f32, 1.0f32);
                for _ in 0..n {
                    total += w;
                    w *= 0.5;
                }
                let edges = (1..n).flat_map(|o| {
                    let x = (2.0 - 2.0 * f32::from_bits((127 - o) << 23)) / total;
                    (-3i32..=3).map(move |d| f32::from_bits(x.to_bits().wrapping_add_signed(d)))
                });
                for xi in hard.into_iter().chain(grid).chain(edges) {
                    let fast = OctavePick::halving(n, gain, xi);
                    let table = OctavePick::table(n, 2.0, gain, xi);
                    assert_eq!(fields(fast), fields(table), "n {n}, gain {gain}, ξ {xi:e}");
                    assert!(fast.octave < n && (0.0..1.0).contains(&fast.xi));
                }
            }
        }
    }

    /// Over a fine ξ grid, the estimator picks each octave in proportion to `|gain|^o`, hands
    /// the noise a remapped ξ in `[0, 1)` whose mean is ½ per octave, and signs it like `gain^o`.
    #[test]
    fn octave_choice_follows_the_weights() {
        for (n, gain) in [
            (10, 0.5),
            (1, 0.5),
            (32, 0.9),
            (7, -0.7),
            (8, 1.0),
            (5, 0.0),
            (32, 1e-30),
            (32, 16.0),
            (6, 3.0),
        ] {
            let f = Fractal::new(n, 2.0, gain);
            // The estimator's scale, summed as it sums it.
            let (mut total_f32, mut a) = (0.0f32, 1.0f32);
            for _ in 0..n {
                total_f32 += a;
                a *= gain.abs();
            }
            let steps = 1u32 << 18;
            let mut count = [0u32; 32];
            let mut xi_sum = [0.0f64; 32];
            for i in 0..steps {
                let xi = (i as f32 + 0.5) / steps as f32;
                let v = fractal_stochastic([1.0; 3], f, xi, |q, o, x| {
                    assert!((0.0..1.0).contains(&x), "ξ' = {x}");
                    assert_eq!(q[0], 2.0f32.powi(o as i32), "frequency of octave {o}");
                    count[o as usize] += 1;
                    xi_sum[o as usize] += x as f64;
                    1.0
                });
                assert!(v.is_finite() && v.abs() == total_f32, "weight {v}");
            }
            let g = (gain as f64).abs();
            let total: f64 = (0..n).map(|o| g.powi(o as i32)).sum();
            for o in 0..32 {
                let want = if (o as u32) < n {
                    g.powi(o as i32) / total
                } else {
                    0.0
                };
                let got = count[o] as f64 / steps as f64;
                // Each interval's ends are exact to an f32 rounding; the grid adds 1/steps.
                assert!(
                    (got - want).abs() <= 2.0 / steps as f64 + 1e-6,
                    "n {n} gain {gain} octave {o}: {got} vs {want}"
                );
                if count[o] > 64 {
                    let mean = xi_sum[o] / count[o] as f64;
                    assert!((mean - 0.5).abs() < 0.01, "octave {o}: mean ξ' {mean}");
                }
            }
        }
        // Negative gains alternate the sign: octave 1 of gain −0.7 is negative.
        let f = Fractal::new(3, 2.0, -0.7);
        let total = 1.0 + 0.7 + 0.49f32;
        let xi = 1.2 / total; // inside octave 1's interval [1, 1.7) / total
        assert!(fractal_stochastic([0.0; 3], f, xi, |_, o, _| o as f32) < 0.0);
        assert!(fractal_stochastic([0.0; 3], f, 0.1, |_, _, _| 1.0) > 0.0);
    }
}
