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

pub(crate) mod batch;
use super::estimators::{ONE_BELOW, sanitize_xi};
use super::perlin::perlin3_stochastic;

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
    fn halving(n: u32, gain: f32, xi: f32) -> Self {
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

/// fBm of 3D Perlin noise (each octave with its own seed).
#[inline(always)]
pub fn fbm3(p: [f32; 3], f: Fractal, seed: u32) -> f32 {
    fbm3_lanes(p, f, seed)
}

/// [`fbm3`] with the point kept in one register: each octave scales it by its frequency
/// there, instead of scaling three scalars and loading them into lanes again for
/// [`perlin3`](super::perlin::perlin3)'s lane form. The same products and sums as [`fractal`], so the
/// same bits (lane 3 of the register is 0 times the frequency, which the lane form ignores).
/// (Ten octaves: 1618 instead of 1745 instructions a call, 4.5 % faster.)
#[inline(always)]
fn fbm3_lanes(p: [f32; 3], f: Fractal, seed: u32) -> f32 {
    use crate::lanes::F4;
    let (n, lac, gain) = f.sane();
    let v = F4::from3(p);
    let (mut amp, mut freq, mut sum) = (1.0f32, 1.0f32, 0.0f32);
    for o in 0..n {
        let q = v * F4::splat(freq);
        sum += amp * super::perlin::lanes::perlin3_lanes(q, octave_seed(seed, o));
        amp *= gain;
        freq *= lac;
    }
    sum
}

/// One-sample estimator of [`fbm3`]: one octave, and in it one Perlin gradient — one hash and
/// one dot product whatever the octave count.
#[inline(always)]
pub fn fbm3_stochastic(p: [f32; 3], f: Fractal, seed: u32, xi: f32) -> f32 {
    if let Some(v) = fbm3_stochastic_halving(p, f, seed, xi) {
        return v;
    }
    let k = OctavePick::new(f, xi);
    k.scale(perlin3_stochastic(
        k.point(p),
        octave_seed(seed, k.octave),
        k.xi,
    ))
}

/// [`fbm3`] with its first `exact` octaves exact and one octave of the rest sampled
/// ([`fractal_tail_estimate`]): `exact` Perlin evaluations and one gradient.
#[inline]
pub fn fbm3_tail_stochastic(p: [f32; 3], f: Fractal, exact: u32, seed: u32, xi: f32) -> f32 {
    fractal_tail_estimate(
        p,
        f,
        exact,
        xi,
        |q, o| super::perlin::perlin3(q, octave_seed(seed, o)),
        |q, o, x| perlin3_stochastic(q, octave_seed(seed, o), x),
    )
}

/// [`fbm3`] with its first `exact` octaves exact and one octave of the rest chosen by ξ
/// (Algorithm 2's choice, weight `|gain^o|`) and evaluated exactly: only the octave choice is
/// random, not the corner. For Perlin noise on a CPU the one-gradient estimator saves little
/// over a full `perlin3` (8 corners in SIMD lanes) but adds the corner choice's variance, so
/// inside a renderer this is usually the better trade (`cargo run --release --example cloud`).
#[inline]
pub fn fbm3_octave_stochastic(p: [f32; 3], f: Fractal, exact: u32, seed: u32, xi: f32) -> f32 {
    let perlin = |q: [f32; 3], o: u32| super::perlin::perlin3(q, octave_seed(seed, o));
    fractal_tail_estimate(p, f, exact, xi, perlin, |q, o, _| perlin(q, o))
}

/// [`fbm3_stochastic`] for lacunarity 2, gain ±½ and a point whose finest octave
/// `q = p · 2^(n−1)` is in the split range; `None` otherwise. The same bits, with the point's
/// split taken off the chain from ξ: `q` is split before the octave `o` is known, and octave
/// `o`'s cell and offset follow from it exactly, with `s = n − 1 − o`, as `⌊cell_q / 2^s⌋`
/// and `((cell_q mod 2^s) + f_q) / 2^s`. (The sum is `q mod 2^s`, a truncation of `q`'s
/// mantissa, so it is exact, and so is the power-of-two scaling.) The split of `p · 2^o`
/// would otherwise wait for the octave, and the estimator's time is that chain (the gain is
/// in `noisebake report stochastic`'s fBm rows).
#[inline(always)]
fn fbm3_stochastic_halving(p: [f32; 3], f: Fractal, seed: u32, xi: f32) -> Option<f32> {
    use crate::lanes::{self, F4};
    let (n, lac, gain) = f.sane();
    if !(lac == 2.0 && (gain == 0.5 || gain == -0.5)) {
        return None;
    }
    let pow2 = |e: i32| f32::from_bits(((127 + e) as u32) << 23);
    let q = F4::from3(p) * F4::splat(pow2(n as i32 - 1));
    if !lanes::in_split_range(q) {
        return None;
    }
    let (cell_q, f_q) = lanes::split_in_range(q);
    let k = OctavePick::halving(n, gain, xi);
    let s = n - 1 - k.octave;
    let cell = cell_q.floor_div_pow2(s);
    let off = (cell_q.mod_pow2(s).to_f32() + f_q) * F4::splat(pow2(-(s as i32)));
    // The remapped ξ is in [0, 1) by construction, so it needs no sanitising.
    let n = super::estimators::Narrowing::new_unit(k.xi);
    let v =
        super::perlin::lanes::perlin3_stochastic_cell(cell, off, octave_seed(seed, k.octave), n);
    Some(k.scale(v))
}

// The type and its verbs.
use super::Perlin;
use super::noise::{BatchLengths, Noise, Octaves};

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
    use super::super::perlin::perlin3;
    use super::*;

    /// The fBm estimator's shortcut (one split at the finest octave) returns what
    /// the generic estimator returns, bit for bit: every octave count, both signs of gain,
    /// points at and next to lattice planes of every octave, at the edge of the shortcut's
    /// range, and random ones, with hard and random ξ.
    #[test]
    fn fbm3_estimator_is_the_generic_one_bit_for_bit() {
        let mut next = super::super::uniforms(0x510e_527f_ade6_82d1);
        let xis = [0.0f32, -0.0, 1e-30, 0.5, ONE_BELOW, 1.0, 2.0, f32::NAN];
        for n in 1..=32u32 {
            for gain in [0.5f32, -0.5] {
                let f = Fractal::new(n, 2.0, gain);
                let edge = 4_194_303.5 / f32::from_bits((126 + n) << 23);
                let mut hard = [0.0f32, -0.0, 1e-45, edge, -edge, 1.0, -1.0, 0.375, -0.625];
                for h in hard.iter_mut().skip(5) {
                    *h = f32::from_bits(h.to_bits() + 1);
                }
                let check = |p: [f32; 3], xi: f32| {
                    let seed = p[0].to_bits() ^ n;
                    let got = fbm3_stochastic(p, f, seed, xi);
                    let want = fractal_estimate(p, f, xi, |q, o, x| {
                        perlin3_stochastic(q, octave_seed(seed, o), x)
                    });
                    assert_eq!(
                        got.to_bits(),
                        want.to_bits(),
                        "n {n}, gain {gain}, p {p:?}, ξ {xi:e}"
                    );
                };
                for i in 0..hard.len().pow(3) {
                    let p = [hard[i % 9], hard[i / 9 % 9], hard[i / 81]];
                    check(p, xis[i % xis.len()]);
                    check(p, next());
                }
                for _ in 0..3000 {
                    let p = [0; 3].map(|_| (next() - 0.5) * 200.0);
                    check(p, next());
                }
            }
        }
    }

    /// The lane form of the deterministic fBm returns what [`fractal`] over
    /// [`perlin3`](super::super::perlin3) returns, bit for bit: octave counts 1–32,
    /// ordinary, negative, huge and NaN parameters (frequencies that overflow, points that
    /// leave the split range at some octave), hard and random points.
    #[test]
    fn fbm3_is_the_generic_fractal_sum_bit_for_bit() {
        let mut next = super::super::uniforms(0x9b05_688c_1f83_d9ab);
        let params = [
            (2.0f32, 0.5f32),
            (2.0, -0.5),
            (1.93, 0.6),
            (-2.5, 0.7),
            (0.5, 1.0),
            (1024.0, 16.0),
            (f32::NAN, f32::NAN),
            (1.0, 0.0),
        ];
        for n in 1..=32u32 {
            for (k, &(lac, gain)) in params.iter().enumerate() {
                let f = Fractal::new(n, lac, gain);
                for i in 0..200 {
                    let p = match i % 4 {
                        0 => [0.0, -0.0, 1e-45],
                        1 => [4_194_303.5, -1.0, 0.5].map(|c| c / (1 + i) as f32),
                        _ => [0; 3].map(|_| (next() - 0.5) * 200.0),
                    };
                    let seed = (n * 31 + k as u32) ^ i;
                    let want = fractal(p, f, |q, o| perlin3(q, octave_seed(seed, o)));
                    let got = fbm3(p, f, seed);
                    assert_eq!(
                        got.to_bits(),
                        want.to_bits(),
                        "n {n}, lacunarity {lac}, gain {gain}, p {p:?}: {got} vs {want}"
                    );
                }
            }
        }
    }

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
