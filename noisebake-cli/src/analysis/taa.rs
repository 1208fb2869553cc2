//! Error after temporal anti-aliasing: the EMA of [`super::filtered`] with the history clamp
//! games run in front of it, and a camera that moves.
//!
//! **The model.** Every pixel estimates `∫₀¹ φ` with one value of the mask per frame (the mask
//! is fixed to the screen and loops over its frames). Each frame, the history is reprojected
//! (a camera moving `motion` whole pixels per frame: pixel `p` takes the history of pixel
//! `p − motion`, wrapped), **clamped** to the current frame's 3 × 3 neighbourhood of estimates
//! — its min/max box, or the variance box `μ ± γσ` of Salvi 2016 — and blended with the new
//! estimate, `h ← (1 − α) clamp(h) + α φ(s)` (Karis 2014's TAA without its colour-space
//! niceties: the integrand is one channel and the scene is static under the camera, so the
//! only thing the clamp can reject is noise). The image a player sees is then filtered in
//! space (the spatial filter the mask is made for), and the RMSE against `∫ φ` is taken over
//! pixels and the last loop of frames, after three loops (at least 64 frames) to reach the
//! steady state.
//!
//! Without the clamp and without motion this is exactly [`super::filtered`]'s measure (both
//! filters are linear, so their order does not matter). The clamp is what changes the picture
//! for binary integrands (a dither `[s < a]`): a 3 × 3 window whose nine values all fall on one
//! side of the threshold has a box of one value, and the history collapses onto it.

use super::filtered::blur;
use rayon::prelude::*;

/// The neighbourhood clamp applied to the reprojected history.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Clip {
    /// No clamp: a plain EMA.
    None,
    /// Clamp to the min/max of the current frame's 3 × 3 estimates.
    MinMax,
    /// Clamp to `μ ± γσ` of the current frame's 3 × 3 estimates (variance clipping).
    Variance(f64),
}

impl Clip {
    /// Its name in the report.
    pub fn name(self) -> String {
        match self {
            Clip::None => "none".into(),
            Clip::MinMax => "3x3 min/max".into(),
            Clip::Variance(g) => format!("3x3 variance γ {g}"),
        }
    }
}

/// The TAA a game runs: blend weight, clamp and camera motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Taa {
    /// Blend weight of the new frame.
    pub alpha: f64,
    /// The history clamp.
    pub clip: Clip,
    /// Whole pixels the camera moves per frame (`[0, 0]`: static).
    pub motion: [i32; 2],
}

/// The RMSE after `taa`, then the spatial `taps` (normalised, separable, wrapping), of
/// estimating `∫ φ = truth` with one of the mask's `values` per pixel and frame (`w × h × t`,
/// x fastest).
pub fn taa_rmse(
    values: &[f64],
    [w, h, t]: [usize; 3],
    phi: &(dyn Fn(f64) -> f64 + Sync),
    truth: f64,
    taa: Taa,
    taps: &[f64],
) -> f64 {
    let n = w * h;
    assert_eq!(values.len(), n * t, "values are w × h × t");
    let est: Vec<f64> = values.iter().map(|&s| phi(s)).collect();
    // Four loops of the mask, and for a slow blend (Bevy's 0.015 for a still pixel with `Hdr`) 6 / α
    // frames, so the first frame's weight in the history is below 0.3 % when the measured loop
    // starts.
    let total = (4 * t)
        .max(64)
        .max((6.0 / taa.alpha).ceil() as usize)
        .div_ceil(t)
        * t;
    let mut hist = est[..n].to_vec();
    let mut next = vec![0.0; n];
    let mut measured: Vec<Vec<f64>> = Vec::with_capacity(t);
    let [mx, my] = taa.motion;
    let wrap = |v: isize, m: usize| v.rem_euclid(m as isize) as usize;
    for f in 1..total {
        let cur = &est[(f % t) * n..][..n];
        next.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
            for (x, out) in row.iter_mut().enumerate() {
                let from =
                    wrap(y as isize - my as isize, h) * w + wrap(x as isize - mx as isize, w);
                let mut hv = hist[from];
                if taa.clip != Clip::None {
                    let (mut lo, mut hi, mut s, mut s2) = (f64::MAX, f64::MIN, 0.0, 0.0);
                    for dy in -1..=1isize {
                        let yy = wrap(y as isize + dy, h) * w;
                        for dx in -1..=1isize {
                            let v = cur[yy + wrap(x as isize + dx, w)];
                            lo = lo.min(v);
                            hi = hi.max(v);
                            s += v;
                            s2 += v * v;
                        }
                    }
                    if let Clip::Variance(g) = taa.clip {
                        let mu = s / 9.0;
                        let sd = (s2 / 9.0 - mu * mu).max(0.0).sqrt();
                        (lo, hi) = (mu - g * sd, mu + g * sd);
                    }
                    hv = hv.clamp(lo, hi);
                }
                *out = (1.0 - taa.alpha) * hv + taa.alpha * cur[y * w + x];
            }
        });
        std::mem::swap(&mut hist, &mut next);
        if f >= total - t {
            measured.push(hist.clone());
        }
    }
    let sum: f64 = measured
        .par_iter()
        .map(|fr| {
            blur(fr, w, h, taps)
                .iter()
                .map(|v| (v - truth) * (v - truth))
                .sum::<f64>()
        })
        .sum();
    (sum / (measured.len() * n) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::filtered::{Denoiser, filtered_rmse_at};

    fn white(dims: [usize; 3], seed: u64) -> Vec<f64> {
        let mut s = seed;
        (0..dims.iter().product::<usize>())
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((s >> 11) as f64 + 0.5) / (1u64 << 53) as f64
            })
            .collect()
    }

    #[test]
    fn without_clamp_or_motion_it_is_the_filtered_ema() {
        let dims = [16, 16, 8];
        let v = white(dims, 1);
        let taps = vec![0.25, 0.5, 0.25];
        let taa = Taa {
            alpha: 0.1,
            clip: Clip::None,
            motion: [0, 0],
        };
        let a = 0.25;
        let ours = taa_rmse(&v, dims, &|s| f64::from(u8::from(s < a)), a, taa, &taps);
        let d = Denoiser {
            spatial: taps.clone(),
            ema_alpha: Some(0.1),
        };
        let theirs = filtered_rmse_at(&v, dims, &d, &[a]);
        assert!((ours - theirs).abs() < 1e-12, "{ours} vs {theirs}");
    }

    #[test]
    fn the_clamp_collapses_windows_on_one_side_and_spares_windows_that_straddle() {
        // Every pixel runs through the same stratified values over time, offset per pixel.
        // `flat`: one offset everywhere, so every window lies on one side of the threshold and
        // the clamp pins the history to the current frame. `spread`: offset (x + 3y) mod 9
        // ninths, so every 3 × 3 window holds all nine offsets and straddles any threshold in
        // (1/9, 1): min/max clamping then never acts.
        let dims = [18, 18, 8];
        let make = |offset: &dyn Fn(usize, usize) -> f64| -> Vec<f64> {
            (0..8)
                .flat_map(|f| (0..18).flat_map(move |y| (0..18).map(move |x| (x, y, f))))
                .map(|(x, y, f)| (f as f64 / 8.0 + 1.0 / 16.0 + offset(x, y)).fract())
                .collect()
        };
        let flat = make(&|_, _| 0.0);
        let spread = make(&|x, y| ((x + 3 * y) % 9) as f64 / 9.0);
        let a = 0.3;
        let phi = |s: f64| f64::from(u8::from(s < a));
        let run = |v: &[f64], clip| {
            let taa = Taa {
                alpha: 0.1,
                clip,
                motion: [0, 0],
            };
            taa_rmse(v, dims, &phi, a, taa, &[1.0])
        };
        assert!(run(&flat, Clip::MinMax) > 2.0 * run(&flat, Clip::None));
        assert_eq!(run(&spread, Clip::MinMax), run(&spread, Clip::None));
    }

    #[test]
    fn a_moving_camera_mixes_pixels_histories() {
        // A mask constant in time: static, each pixel's error never averages out; moving, the
        // history runs over other pixels' values and the error falls.
        let dims = [16, 16, 1];
        let v = white(dims, 7);
        let phi = |s: f64| s;
        let run = |motion| {
            taa_rmse(
                &v,
                dims,
                &phi,
                0.5,
                Taa {
                    alpha: 0.1,
                    clip: Clip::None,
                    motion,
                },
                &[1.0],
            )
        };
        assert!(run([1, 0]) < 0.5 * run([0, 0]));
    }
}
