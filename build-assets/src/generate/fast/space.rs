//! Sample spaces of FAST masks: their stratified initialisation, the distance of the loss
//! (FAST eq. 6–7) and how values are stored.
//!
//! All arithmetic here is IEEE basic operations and `sqrt` (correctly rounded everywhere), so the
//! samples, and hence the baked bytes, are the same on every platform; no libm call is used.

use crate::detmath::exp;
use crate::generate::rng::{SplitMix64, permutation};
use crate::spec::fast::{Distribution, SampleSpace};

/// The standard normal CDF Φ(x) by the series `erf(z) = 2/√π e^{−z²} Σ 2^n z^{2n+1} / (2n+1)!!`
/// (all terms positive: no cancellation), good to ~1e-15 for |x| ≤ 12.
pub fn normal_cdf(x: f64) -> f64 {
    let z = x.abs() / core::f64::consts::SQRT_2;
    let mut term = z;
    let mut sum = z;
    let mut n = 0.0;
    while term > sum * 1e-17 {
        n += 1.0;
        term *= 2.0 * z * z / (2.0 * n + 1.0);
        sum += term;
    }
    let erf = (2.0 / core::f64::consts::PI.sqrt() * exp(-z * z) * sum).min(1.0);
    if x >= 0.0 {
        0.5 + 0.5 * erf
    } else {
        0.5 - 0.5 * erf
    }
}

/// Φ⁻¹(p) for `p ∈ (0, 1)` by bisection on [`normal_cdf`] (deterministic, 1e-14).
pub fn normal_icdf(p: f64) -> f64 {
    let (mut lo, mut hi) = (-12.0f64, 12.0f64);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if normal_cdf(mid) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// `acos(x)` for `x ∈ [−1, 1]` (Abramowitz & Stegun 4.4.45, |error| ≤ 7e-5 rad): the geodesic
/// distance of the loss, about 10× cheaper than an exact `acos`.
#[inline(always)]
pub fn acos_fast(x: f64) -> f64 {
    let a = x.abs().min(1.0);
    let r =
        (1.0 - a).sqrt() * (1.570_728_8 + a * (-0.212_114_4 + a * (0.074_261 - a * 0.018_729_3)));
    if x >= 0.0 {
        r
    } else {
        core::f64::consts::PI - r
    }
}

/// `(cos 2πu, sin 2πu)` from basic operations (Taylor series after reduction to |θ| ≤ π/4).
pub fn cos_sin_turns(u: f64) -> (f64, f64) {
    let u = u - u.floor();
    // Octant reduction: θ = 2π(q/8 + r), |r| ≤ 1/16 turn.
    let q = (u * 8.0).round();
    let r = (u - q / 8.0) * 2.0 * core::f64::consts::PI;
    let r2 = r * r;
    let (mut c, mut s) = (1.0, r);
    let (mut tc, mut ts) = (1.0, r);
    for i in 1..12 {
        let i = i as f64;
        tc *= -r2 / ((2.0 * i - 1.0) * (2.0 * i));
        ts *= -r2 / ((2.0 * i) * (2.0 * i + 1.0));
        c += tc;
        s += ts;
    }
    let h = core::f64::consts::FRAC_1_SQRT_2;
    let (c0, s0) = match (q as i64).rem_euclid(8) {
        0 => (1.0, 0.0),
        1 => (h, h),
        2 => (0.0, 1.0),
        3 => (-h, h),
        4 => (-1.0, 0.0),
        5 => (-h, -h),
        6 => (0.0, -1.0),
        _ => (h, -h),
    };
    (c0 * c - s0 * s, s0 * c + c0 * s)
}

/// The largest divisor of `n` not above `√n` (rows of a stratification grid).
fn grid_rows(n: usize) -> usize {
    let mut r = (n as f64).sqrt() as usize;
    while r > 1 && !n.is_multiple_of(r) {
        r -= 1;
    }
    r.max(1)
}

/// `n` stratified points in `[0, 1)^2`: one per cell of a `rows × n/rows` grid, jittered.
fn jittered_2d(n: usize, rng: &mut SplitMix64) -> Vec<[f64; 2]> {
    let rows = grid_rows(n);
    let cols = n / rows;
    (0..n)
        .map(|i| {
            let (cx, cy) = (i % cols, i / cols);
            [
                (cx as f64 + rng.unit_f64()) / cols as f64,
                (cy as f64 + rng.unit_f64()) / rows as f64,
            ]
        })
        .collect()
}

/// `n` values per channel, each channel stratified (one value per `1/n` stratum, Latin
/// hypercube), for `channels` channels.
fn latin(n: usize, channels: usize, rng: &mut SplitMix64) -> Vec<f64> {
    let perms: Vec<Vec<u32>> = (0..channels).map(|_| permutation(n, rng)).collect();
    let mut out = vec![0.0; n * channels];
    for i in 0..n {
        for c in 0..channels {
            out[i * channels + c] = (perms[c][i] as f64 + rng.unit_f64()) / n as f64;
        }
    }
    out
}

/// The stratified samples of one slice of `n` texels, in a random order: `n · channels` values.
///
/// Scalars take the bin centres `(r + ½)/n` through the inverse CDF (so uniform scalars are
/// exactly the ranks of a flat histogram); 2D spaces are jittered on a grid; sphere, hemisphere
/// and cosine hemisphere map a jittered grid through an area-preserving warp; vec3/vec4 are Latin
/// hypercubes.
pub fn stratified_slice(
    space: SampleSpace,
    dist: Distribution,
    n: usize,
    rng: &mut SplitMix64,
) -> Vec<f64> {
    let order = permutation(n, rng);
    let warp = |f: &dyn Fn([f64; 2]) -> [f64; 3], rng: &mut SplitMix64| -> Vec<f64> {
        let pts = jittered_2d(n, rng);
        order.iter().flat_map(|&i| f(pts[i as usize])).collect()
    };
    match space {
        SampleSpace::Scalar | SampleSpace::Circle => order
            .iter()
            .map(|&r| {
                let u = (r as f64 + 0.5) / n as f64;
                match (space, dist) {
                    (SampleSpace::Circle, _) | (_, Distribution::Uniform) => u,
                    (_, Distribution::Tent) => {
                        if u < 0.5 {
                            (0.5 * u).sqrt()
                        } else {
                            1.0 - (0.5 * (1.0 - u)).sqrt()
                        }
                    }
                    (_, Distribution::Gauss) => normal_icdf(u),
                }
            })
            .collect(),
        SampleSpace::Vec2 => {
            let pts = jittered_2d(n, rng);
            order.iter().flat_map(|&i| pts[i as usize]).collect()
        }
        SampleSpace::Vec3 | SampleSpace::Vec4 => latin(n, space.channels(), rng),
        SampleSpace::Sphere => warp(
            &|[u, v]| {
                let z = 1.0 - 2.0 * u;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (c, s) = cos_sin_turns(v);
                [r * c, r * s, z]
            },
            rng,
        ),
        SampleSpace::Hemisphere => warp(
            &|[u, v]| {
                let z = 1.0 - u;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (c, s) = cos_sin_turns(v);
                [r * c, r * s, z]
            },
            rng,
        ),
        SampleSpace::CosineHemisphere => warp(
            &|[u, v]| {
                let r = u.sqrt();
                let (c, s) = cos_sin_turns(v);
                [r * c, r * s, (1.0 - u).max(0.0).sqrt()]
            },
            rng,
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deterministic_math_matches_std() {
        for i in -200..200 {
            let x = i as f64 * 0.173;
            let (a, b) = (exp(x), x.exp());
            assert!(((a - b) / b).abs() < 1e-14, "exp({x})");
        }
        for i in 0..=100 {
            let x = -1.0 + i as f64 * 0.02;
            assert!((acos_fast(x) - x.acos()).abs() < 7e-5, "acos({x})");
            let (c, s) = cos_sin_turns(i as f64 * 0.0173 - 0.4);
            let t = (i as f64 * 0.0173 - 0.4) * std::f64::consts::TAU;
            assert!((c - t.cos()).abs() < 1e-14 && (s - t.sin()).abs() < 1e-14);
        }
        assert!((normal_icdf(0.975) - 1.959_963_984_540_054).abs() < 1e-12);
        assert!((normal_icdf(0.5)).abs() < 1e-14);
    }

    #[test]
    fn slices_are_stratified() {
        let mut rng = SplitMix64::new(3);
        let v = stratified_slice(SampleSpace::Scalar, Distribution::Uniform, 64, &mut rng);
        let mut bins: Vec<usize> = v.iter().map(|x| (x * 64.0) as usize).collect();
        bins.sort_unstable();
        assert_eq!(bins, (0..64).collect::<Vec<_>>());
        let v = stratified_slice(
            SampleSpace::CosineHemisphere,
            Distribution::Uniform,
            256,
            &mut rng,
        );
        for p in v.chunks(3) {
            let len = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            assert!((len - 1.0).abs() < 1e-12 && p[2] >= 0.0);
        }
        // Cosine weighting: E[z] = 2/3.
        let mean_z: f64 = v.chunks(3).map(|p| p[2]).sum::<f64>() / 256.0;
        assert!((mean_z - 2.0 / 3.0).abs() < 0.01, "{mean_z}");
    }
}
