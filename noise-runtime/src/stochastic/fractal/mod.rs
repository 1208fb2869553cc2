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
    pub(crate) fn sane(self) -> (u32, f32, f32) {
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
pub fn fractal_estimate(
    p: [f32; 3],
    f: Fractal,
    xi: f32,
    noise: impl FnOnce([f32; 3], u32, f32) -> f32,
) -> f32 {
    let k = OctavePick::new(f, xi);
    k.scale(noise(k.point(p), k.octave, k.xi))
}

/// [`fractal`] with its first `exact` octaves (the largest, which carry most of the weight)
/// summed exactly by `noise` and one octave of the rest sampled by [`fractal_estimate`] with
/// `noise_estimate`. Unbiased like the full estimator, but the sampled part has weight
/// `Σ_(o ≥ exact) |gain^o|`, so its variance shrinks by `gain^(2·exact)` (1/16 for two exact
/// octaves at gain ½) while the cost is `exact` noise evaluations plus one estimate — the
/// variance reduction that makes one-sample fBm pay inside a Monte Carlo renderer
/// (`cargo run --release --example cloud`). `exact = 0` is [`fractal_estimate`];
/// `exact ≥ octaves` is [`fractal`].
#[inline(always)]
pub fn fractal_tail_estimate(
    p: [f32; 3],
    f: Fractal,
    exact: u32,
    xi: f32,
    mut noise: impl FnMut([f32; 3], u32) -> f32,
    noise_estimate: impl FnOnce([f32; 3], u32, f32) -> f32,
) -> f32 {
    let (n, lac, gain) = f.sane();
    let exact = exact.min(n);
    let (mut amp, mut freq, mut sum) = (1.0f32, 1.0f32, 0.0f32);
    for o in 0..exact {
        sum += amp * noise([p[0] * freq, p[1] * freq, p[2] * freq], o);
        amp *= gain;
        freq *= lac;
    }
    if exact == n {
        return sum;
    }
    let q = [p[0] * freq, p[1] * freq, p[2] * freq];
    let tail = Fractal::new(n - exact, lac, gain);
    sum + amp * fractal_estimate(q, tail, xi, |q, o, x| noise_estimate(q, o + exact, x))
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
    /// common fBm): the same octave, frequency and remapped ξ, bit for bit, from the target's
    /// bits instead of a table of the CDF. The octave starts are `S_o = 2 − 2^(1−o)`, exact in
    /// f32 up to `o = 24` (after that the sum rounds to 2 and later octaves are never chosen,
    /// in either form). In binary `S_o` is `1.1…1` with `o − 1` ones after the point, so a
    /// target in `[1, 2)` lies in octave 1 + the number of leading ones of its mantissa, and
    /// a target below 1 in octave 0. The remapped ξ `(target − S_o)·2^o` is computed as
    /// `target·2^o − (2^(o+1) − 2)`: both terms and the result are exact, and the two
    /// products run side by side, where the difference first waited on `S_o`. This is the
    /// chain from ξ to the octave's noise, which the fBm estimator's time is.
    #[inline(always)]
    pub(crate) fn halving(n: u32, gain: f32, xi: f32) -> Self {
        // Σ_(o<n) 2^−o = 2 − 2^(1−n), computed in f32 as the running sum rounds it: exact up to
        // n = 24, and 2 from n = 25 (2 − 2^−24 is a tie that rounds to even, 2), where the sum
        // also stops growing. A closed form, not the loop: with a `Fractal` that is not a
        // compile-time constant the loop's ten dependent adds would delay every sample.
        let total = 2.0 - f32::from_bits((128 - n) << 23);
        let target = Self::target(xi, total);
        let b = target.to_bits();
        // The shifted mantissa's low nine bits are ones after the `!`, so it is never 0.
        let ones = (!(b << 9)).leading_zeros();
        let o = (1 + ones) & 0u32.wrapping_sub((b >= 0x3f80_0000) as u32);
        let pow2 = |e: u32| f32::from_bits((127 + e) << 23);
        OctavePick {
            octave: o,
            freq: pow2(o),
            xi: target * pow2(o) - ((2u32 << o) - 2) as f32,
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

/// The seed of octave `o` in [`Fbm`] and the other fractal sums: each octave is an independent
/// noise. For building a sum with [`fractal`] or [`fractal_tail_estimate`] that matches them.
#[inline(always)]
pub fn octave_seed(seed: u32, o: u32) -> u32 {
    seed.wrapping_add(o.wrapping_mul(0x9e37_79b9))
}

// The traits and the type.
use super::Perlin;
use super::noise::{BatchLengths, Noise};

/// A 3D noise a fractal sum can be built from: `Σ_o gain^o · octave(o)(p · lacunarity^o)`
/// (eq. 9), each octave the same noise with its own seed ([`octave_seed`]). The sums and their
/// estimators have generic forms here (Algorithm 2 and the tail and octave estimators of
/// [`fractal`](fn@fractal), [`fractal_tail_estimate`]); a
/// noise with faster kernels for them (3D Perlin: lanes, batch kernels) overrides them with
/// the same values.
pub trait Octaves: Noise<[f32; 3]> + Sized {
    /// Octave `o`: this noise with the seed `octave_seed(seed, o)`.
    fn octave(&self, o: u32) -> Self;

    /// The fractal sum at `p`.
    fn fbm_sample(&self, f: Fractal, p: [f32; 3]) -> f32 {
        fractal(p, f, |q, o| self.octave(o).sample(q))
    }

    /// One octave chosen by ξ (weight `|gain^o|`), estimated with the remapped ξ.
    fn fbm_estimate(&self, f: Fractal, p: [f32; 3], xi: f32) -> f32 {
        fractal_estimate(p, f, xi, |q, o, x| self.octave(o).estimate(q, x))
    }

    /// The first `exact` octaves exact and one octave of the rest estimated.
    fn fbm_estimate_tail(&self, f: Fractal, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        fractal_tail_estimate(
            p,
            f,
            exact,
            xi,
            |q, o| self.octave(o).sample(q),
            |q, o, x| self.octave(o).estimate(q, x),
        )
    }

    /// The first `exact` octaves exact and one octave of the rest chosen by ξ and evaluated
    /// exactly.
    fn fbm_estimate_octave(&self, f: Fractal, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        let exact_octave = |q: [f32; 3], o: u32| self.octave(o).sample(q);
        fractal_tail_estimate(p, f, exact, xi, exact_octave, |q, o, _| exact_octave(q, o))
    }

    /// [`fbm_sample`](Self::fbm_sample) of every point (lengths as [`Noise::sample_batch`]).
    fn fbm_sample_batch(
        &self,
        f: Fractal,
        points: &[[f32; 3]],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), None, out.len())?;
        for (o, &p) in out.iter_mut().zip(points) {
            *o = self.fbm_sample(f, p);
        }
        Ok(())
    }

    /// [`fbm_estimate`](Self::fbm_estimate) of every point with its own ξ.
    fn fbm_estimate_batch(
        &self,
        f: Fractal,
        points: &[[f32; 3]],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), Some(xi.len()), out.len())?;
        for ((o, &p), &x) in out.iter_mut().zip(points).zip(xi) {
            *o = self.fbm_estimate(f, p, x);
        }
        Ok(())
    }
}

/// A fractal sum (fBm) of a noise: `Σ_o gain^o · octave(o)(p · lacunarity^o)` with an
/// independent seed per octave (eq. 9); its estimators choose octaves by their weight
/// (Algorithm 2). Of 3D Perlin noise by default ([`Fbm::new`], which runs Perlin's own lane and
/// batch kernels), of any [`Octaves`] noise through [`Fbm::of`].
///
/// ```
/// use noise_runtime::stochastic::{Fbm, Fractal, Simplex};
///
/// let perlin = Fbm::new(Fractal::default(), 7);
/// let simplex = Fbm::of(Fractal::new(6, 2.0, 0.5), Simplex::new(7));
/// let p = [0.7, 3.1, -5.2];
/// let mean = (0..256).map(|i| simplex.estimate(p, (i as f32 + 0.5) / 256.0)).sum::<f32>() / 256.0;
/// assert!((mean - simplex.sample(p)).abs() < 0.1 && perlin.sample(p).is_finite());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fbm<N = Perlin> {
    /// Octaves, lacunarity and gain.
    pub fractal: Fractal,
    /// The noise of octave 0; octave `o` is it with seed [`octave_seed`]`(seed, o)`.
    pub noise: N,
}

impl Fbm<Perlin> {
    /// fBm of 3D Perlin noise with these octaves and this seed.
    pub const fn new(fractal: Fractal, seed: u32) -> Fbm {
        Fbm {
            fractal,
            noise: Perlin::new(seed),
        }
    }
}

impl<N: Octaves> Fbm<N> {
    /// The fractal sum of `noise` with these octaves.
    pub const fn of(fractal: Fractal, noise: N) -> Fbm<N> {
        Fbm { fractal, noise }
    }

    /// The sum of every octave at `p`.
    #[must_use]
    #[inline(always)]
    pub fn sample(&self, p: [f32; 3]) -> f32 {
        self.noise.fbm_sample(self.fractal, p)
    }

    /// One octave chosen by ξ and, in it, the noise's own estimator: unbiased, at the cost of
    /// one estimate whatever the octave count.
    #[must_use]
    #[inline(always)]
    pub fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        self.noise.fbm_estimate(self.fractal, p, xi)
    }

    /// The first `exact` octaves summed exactly and one estimate of one octave of the rest:
    /// the tail's variance shrinks by `gain^(2·exact)` ([`fractal_tail_estimate`]).
    #[must_use]
    #[inline]
    pub fn estimate_tail(&self, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        self.noise.fbm_estimate_tail(self.fractal, p, exact, xi)
    }

    /// The first `exact` octaves summed exactly and one octave of the rest chosen by ξ and
    /// evaluated exactly: only the octave choice is random.
    #[must_use]
    #[inline]
    pub fn estimate_octave(&self, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        self.noise.fbm_estimate_octave(self.fractal, p, exact, xi)
    }

    /// [`sample`](Self::sample) of many points into `out` (eight per AVX2 instruction for
    /// Perlin fBm); slices of different lengths are an error, and nothing is written.
    #[inline]
    pub fn sample_batch(&self, points: &[[f32; 3]], out: &mut [f32]) -> Result<(), BatchLengths> {
        self.noise.fbm_sample_batch(self.fractal, points, out)
    }

    /// [`estimate`](Self::estimate) of many points, one ξ each, as
    /// [`sample_batch`](Self::sample_batch).
    #[inline]
    pub fn estimate_batch(
        &self,
        points: &[[f32; 3]],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        self.noise.fbm_estimate_batch(self.fractal, points, xi, out)
    }
}

impl<N: Octaves> Noise<[f32; 3]> for Fbm<N> {
    #[inline(always)]
    fn sample(&self, p: [f32; 3]) -> f32 {
        Fbm::sample(self, p)
    }
    #[inline(always)]
    fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        Fbm::estimate(self, p, xi)
    }
    #[inline]
    fn sample_batch(&self, points: &[[f32; 3]], out: &mut [f32]) -> Result<(), BatchLengths> {
        Fbm::sample_batch(self, points, out)
    }
    #[inline]
    fn estimate_batch(
        &self,
        points: &[[f32; 3]],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        Fbm::estimate_batch(self, points, xi, out)
    }
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
                let v = fractal_estimate([1.0; 3], f, xi, |q, o, x| {
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
        assert!(fractal_estimate([0.0; 3], f, xi, |_, o, _| o as f32) < 0.0);
        assert!(fractal_estimate([0.0; 3], f, 0.1, |_, _, _| 1.0) > 0.0);
    }
}
