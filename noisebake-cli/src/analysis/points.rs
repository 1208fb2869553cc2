//! Point-set quality (CNJ §2.4): the periodogram of a point set in the unit torus, its radially
//! averaged power spectrum, per-ring variance (anisotropy), effective Nyquist frequency and
//! `q = ν_eff / ā`.
//!
//! Conventions (those of the point-set analysis framework the paper uses): the periodogram is
//! `P(f) = |Σ_j e^{−2πi f·x_j}|² / N` at integer frequency vectors `f` with `|f_x|, |f_y| < F`,
//! `F = 5√N`; rings are 2 frequency units wide; frequencies are reported in units of `√N`
//! (so a regular grid's first peak sits near 1). Anisotropy `ā` is the sum over rings `r > 0`
//! of the variance of `P` in the ring, in linear units; `ν_eff` is the largest `|f|/√N` such
//! that the mean of `P` over all `0 < |f'| ≤ |f|` stays below 0.1.

use rayon::prelude::*;
use serde::Serialize;

/// The most points [`analyze`] is given by the CLI: the periodogram costs about `100·N²`
/// complex multiply-adds and `32·N·10√N` bytes of tables (8192 points: a few seconds, 0.2 GB).
pub const MAX_POINTS: usize = 8192;

/// Quality of one point set.
#[derive(Clone, Debug, Serialize)]
pub struct PointStats {
    /// Points analysed.
    pub n: usize,
    /// Effective Nyquist frequency (units of √N).
    pub nu_eff: f64,
    /// Σ of per-ring periodogram variances.
    pub anisotropy: f64,
    /// `ν_eff / ā`.
    pub q: f64,
    /// Radially averaged power per ring (ring r covers `2r ≤ |f| < 2r + 2`).
    pub radial: Vec<f64>,
}

/// The periodogram on `(2F)²` integer frequencies `−F..F` in x and y (row-major, y outer).
pub fn periodogram(points: &[[f64; 2]], f: i64) -> Vec<f64> {
    let n = points.len();
    let side = (2 * f) as usize;
    // e^{−2πi k x} for k = −F..F−1 per point, by recurrence from e^{−2πi x}.
    let table = |axis: usize| -> Vec<(f64, f64)> {
        let mut t = vec![(0.0, 0.0); n * side];
        for (j, p) in points.iter().enumerate() {
            let a = -std::f64::consts::TAU * p[axis];
            let (s1, c1) = a.sin_cos();
            let (sf, cf) = (a * -(f as f64)).sin_cos();
            let (mut c, mut s) = (cf, sf);
            for k in 0..side {
                t[k * n + j] = (c, s);
                // Renormalise occasionally to keep |e| = 1 over long recurrences.
                let (nc, ns) = (c * c1 - s * s1, c * s1 + s * c1);
                let m = if k % 64 == 63 {
                    1.0 / (nc * nc + ns * ns).sqrt()
                } else {
                    1.0
                };
                c = nc * m;
                s = ns * m;
            }
        }
        t
    };
    let tx = table(0);
    let ty = table(1);
    (0..side)
        .into_par_iter()
        .flat_map_iter(|ky| {
            let ry = &ty[ky * n..(ky + 1) * n];
            let tx = &tx;
            (0..side).map(move |kx| {
                let rx = &tx[kx * n..(kx + 1) * n];
                let (mut re, mut im) = (0.0, 0.0);
                for (a, b) in rx.iter().zip(ry) {
                    re += a.0 * b.0 - a.1 * b.1;
                    im += a.0 * b.1 + a.1 * b.0;
                }
                (re * re + im * im) / n as f64
            })
        })
        .collect()
}

/// Analyses one point set.
pub fn analyze(points: &[[f64; 2]]) -> PointStats {
    let n = points.len().max(1);
    let f = (5.0 * (n as f64).sqrt()).floor() as i64;
    let p = periodogram(points, f);
    let side = (2 * f) as usize;
    let rings = (f / 2) as usize;
    let (mut sum, mut sum2, mut count) = (vec![0.0; rings], vec![0.0; rings], vec![0usize; rings]);
    let mut by_radius = Vec::with_capacity(side * side);
    for ky in 0..side {
        for kx in 0..side {
            let (fx, fy) = (kx as i64 - f, ky as i64 - f);
            let r = ((fx * fx + fy * fy) as f64).sqrt();
            let v = p[ky * side + kx];
            let ring = (r / 2.0) as usize;
            if ring < rings {
                sum[ring] += v;
                sum2[ring] += v * v;
                count[ring] += 1;
            }
            if fx != 0 || fy != 0 {
                by_radius.push((r, v));
            }
        }
    }
    let radial: Vec<f64> = (0..rings)
        .map(|r| {
            if count[r] > 0 {
                sum[r] / count[r] as f64
            } else {
                0.0
            }
        })
        .collect();
    let anisotropy: f64 = (1..rings)
        .filter(|&r| count[r] > 1)
        .map(|r| {
            let c = count[r] as f64;
            ((sum2[r] - sum[r] * sum[r] / c) / (c - 1.0)).max(0.0)
        })
        .sum();
    by_radius.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut acc, mut nu) = (0.0, 0.0);
    for (i, &(r, v)) in by_radius.iter().enumerate() {
        acc += v;
        if acc / (i + 1) as f64 >= 0.1 {
            break;
        }
        nu = r;
    }
    let nu_eff = nu / (n as f64).sqrt();
    PointStats {
        n,
        nu_eff,
        anisotropy,
        q: if anisotropy > 0.0 {
            nu_eff / anisotropy
        } else {
            0.0
        },
        radial,
    }
}

/// Mean of the statistics of several sets (the paper averages its runs).
pub fn mean(stats: &[PointStats]) -> (f64, f64, f64) {
    let k = stats.len().max(1) as f64;
    (
        stats.iter().map(|s| s.nu_eff).sum::<f64>() / k,
        stats.iter().map(|s| s.anisotropy).sum::<f64>() / k,
        stats.iter().map(|s| s.q).sum::<f64>() / k,
    )
}

/// What the three numbers mean and which way is better, for every place that prints them.
pub const READING: &str = "\
ν_eff: the effective Nyquist frequency, in units of √N (a regular grid's first peak is near 1):
  the highest frequency below which the point set has almost no power (mean periodogram < 0.1).
  Higher is better: more of the low frequencies are empty, as in blue noise; white noise is 0.
ā: the anisotropy, the sum over frequency rings of the periodogram's variance within the ring
  (linear units). Lower is better: a lattice's peaks make it huge, an isotropic set small.
q = ν_eff / ā: both at once. Higher is better.
Each is a mean over 20 sets of 1000 points (one set's ν_eff varies by ±0.3 from seed to seed).";

/// One method's row of CNJ Table 2 as the report and the demo print it.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct MethodQuality {
    /// Mean ν_eff.
    pub nu_eff: f64,
    /// Mean ā.
    pub anisotropy: f64,
    /// Mean q.
    pub q: f64,
    /// Milliseconds to generate one set.
    pub ms_per_set: f64,
}

/// CNJ Table 2's protocol: `sets` point sets of `n` points (seeds `0..sets`) by `method`, the
/// mean of their statistics and the generation time per set. One set is not enough: ν_eff is
/// a threshold crossing, and a single Poisson-disk set's can be twice the mean.
pub fn table2(method: crate::points::Method, n: usize, sets: u64) -> MethodQuality {
    let start = std::time::Instant::now();
    let all: Vec<_> = (0..sets)
        .map(|s| crate::points::generate(method, n, s))
        .collect();
    let ms_per_set = start.elapsed().as_secs_f64() * 1e3 / sets.max(1) as f64;
    let stats: Vec<_> = all.iter().map(|p| analyze(p)).collect();
    let (nu_eff, anisotropy, q) = mean(&stats);
    MethodQuality {
        nu_eff,
        anisotropy,
        q,
        ms_per_set,
    }
}
