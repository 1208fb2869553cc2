//! The power spectra of the integrands a pair of dimensions meets, on the torus of its unit
//! square: `P(k) = E_h |ĥ(k)|²` over random integrands `h`, the weight of frequency `k` in the
//! error of any sampler whose points are a set moved by a shift (see [`super::model`]).
//!
//! - `square`: half-planes of the unit square (an occluder's edge across an area light);
//! - `cosine`: half-spaces `[a · ω < c]` of the cosine-weighted direction `ω(u, v) = (√u cos
//!   2πv, √u sin 2πv, √(1 − u))` (an occluder's plane cutting the hemisphere of ambient
//!   occlusion).
//!
//! The families are those `build-assets` trains sampler tiles on. Each integrand is sampled
//! on a `GRID²` grid and its power spectrum taken by FFT; the spectra are averaged.

use crate::analysis::dft::power2d;
use build_assets::generate::rng::SplitMix64;
use rayon::prelude::*;

/// Cells per side of the grid each integrand is sampled on: frequencies up to `GRID / 2` per
/// axis are resolved (the model reads them up to 64).
pub const GRID: usize = 256;

/// An integrand family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// Half-planes of the square.
    Square,
    /// Half-spaces of cosine-weighted directions.
    Cosine,
}

impl Family {
    /// Both, in the order of every table.
    pub const ALL: [Family; 2] = [Family::Square, Family::Cosine];

    /// Its name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Family::Square => "square",
            Family::Cosine => "cosine",
        }
    }
}

/// A power spectrum on the `GRID × GRID` frequencies, `k` read modulo `GRID`.
#[derive(Clone, Debug)]
pub struct Spectrum {
    power: Vec<f64>,
}

impl Spectrum {
    /// The mean power spectrum of `count` random integrands of `family` (deterministic in
    /// `seed`, whatever the thread count: each integrand has its own sub-stream and the sum is
    /// taken in integrand order).
    pub fn of(family: Family, count: usize, seed: u64) -> Spectrum {
        let spectra: Vec<Vec<f64>> = (0..count)
            .into_par_iter()
            .map(|i| {
                let mut rng =
                    SplitMix64::new(build_assets::generate::rng::derive_seed(seed, i as u64));
                let img = integrand(family, &mut rng);
                power2d(&img, GRID, GRID)
            })
            .collect();
        let scale = 1.0 / (count as f64 * (GRID * GRID) as f64 * (GRID * GRID) as f64);
        let mut power = vec![0.0; GRID * GRID];
        for s in &spectra {
            for (p, v) in power.iter_mut().zip(s) {
                *p += v * scale;
            }
        }
        Spectrum { power }
    }

    /// `P(k)` at integer frequency `(kx, ky)`, `kx` along the pair's first dimension.
    pub fn at(&self, kx: i64, ky: i64) -> f64 {
        let g = GRID as i64;
        self.power[(ky.rem_euclid(g) * g + kx.rem_euclid(g)) as usize]
    }
}

/// One random integrand of `family` sampled at the cell centres, `x` (the pair's first
/// dimension) fastest.
fn integrand(family: Family, rng: &mut SplitMix64) -> Vec<f64> {
    let mid = |i: usize| (i as f64 + 0.5) / GRID as f64;
    match family {
        Family::Square => {
            let angle = std::f64::consts::TAU * rng.unit_f64();
            let (a, b) = (angle.cos(), angle.sin());
            let (px, py) = (rng.unit_f64(), rng.unit_f64());
            (0..GRID * GRID)
                .map(|i| {
                    let (u, v) = (mid(i % GRID), mid(i / GRID));
                    f64::from(a * (u - px) + b * (v - py) < 0.0)
                })
                .collect()
        }
        Family::Cosine => {
            let a = loop {
                let v = [0, 1, 2].map(|_| 2.0 * rng.unit_f64() - 1.0);
                let r2 = v.iter().map(|x| x * x).sum::<f64>();
                if r2 > 1e-4 && r2 <= 1.0 {
                    break v.map(|x| x / r2.sqrt());
                }
            };
            let c = rng.unit_f64() - 0.5;
            (0..GRID * GRID)
                .map(|i| {
                    let (u, v) = (mid(i % GRID), mid(i / GRID));
                    let r = u.sqrt();
                    let (s, co) = (std::f64::consts::TAU * v).sin_cos();
                    let w = [r * co, r * s, (1.0 - u).sqrt()];
                    f64::from(a[0] * w[0] + a[1] * w[1] + a[2] * w[2] < c)
                })
                .collect()
        }
    }
}
