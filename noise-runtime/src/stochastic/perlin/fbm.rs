//! Perlin noise's own fBm kernels: the octave loop with the point kept in one lane register,
//! and the one-sample estimator whose lattice split is taken off the chain from ξ. The same
//! values, bit for bit, as the generic fractal sums of [`super::super::fractal`] over
//! [`perlin3`] (the tests hold them to it); `Octaves for Perlin` runs them.

use super::super::fractal::{Fractal, OctavePick, fractal_tail_estimate, octave_seed};
use super::lanes as perlin_lanes;
use super::{perlin3, perlin3_stochastic};

/// fBm of 3D Perlin noise (each octave with its own seed).
#[inline(always)]
pub fn fbm3(p: [f32; 3], f: Fractal, seed: u32) -> f32 {
    fbm3_lanes(p, f, seed)
}

/// [`fbm3`] with the point kept in one register: each octave scales it by its frequency
/// there, instead of scaling three scalars and loading them into lanes again for
/// [`perlin3`](super::perlin3)'s lane form. The same products and sums as [`fractal`], so the
/// same bits (lane 3 of the register is 0 times the frequency, which the lane form ignores).
/// (Fewer instructions a call; `cargo bench -p noisebake-cli` and `report stochastic`
/// measure it.)
#[inline(always)]
fn fbm3_lanes(p: [f32; 3], f: Fractal, seed: u32) -> f32 {
    use crate::lanes::F4;
    let (n, lac, gain) = f.sane();
    let v = F4::from3(p);
    let (mut amp, mut freq, mut sum) = (1.0f32, 1.0f32, 0.0f32);
    for o in 0..n {
        let q = v * F4::splat(freq);
        sum += amp * perlin_lanes::perlin3_lanes(q, octave_seed(seed, o));
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
        |q, o| perlin3(q, octave_seed(seed, o)),
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
    let perlin = |q: [f32; 3], o: u32| perlin3(q, octave_seed(seed, o));
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
    let n = super::super::estimators::Narrowing::new_unit(k.xi);
    let v = perlin_lanes::perlin3_stochastic_cell(cell, off, octave_seed(seed, k.octave), n);
    Some(k.scale(v))
}

#[cfg(test)]
mod tests {
    use super::super::super::estimators::ONE_BELOW;
    use super::super::super::fractal::{fractal, fractal_estimate};
    use super::*;

    /// The fBm estimator's shortcut (one split at the finest octave) returns what
    /// the generic estimator returns, bit for bit: every octave count, both signs of gain,
    /// points at and next to lattice planes of every octave, at the edge of the shortcut's
    /// range, and random ones, with hard and random ξ.
    #[test]
    fn fbm3_estimator_is_the_generic_one_bit_for_bit() {
        let mut next = super::super::super::uniforms(0x510e_527f_ade6_82d1);
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
        let mut next = super::super::super::uniforms(0x9b05_688c_1f83_d9ab);
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
}
