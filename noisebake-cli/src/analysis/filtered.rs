//! Error after filtering (FAST §6, Fig. 8): integrate step functions with one sample per pixel
//! and frame, denoise with a spatial filter per frame and an EMA over frames, and measure the
//! RMSE against the true integral. This is what a FAST mask is optimised for, so it is the
//! honest comparison between masks.

/// A denoiser: separable spatial taps per frame, then an optional EMA over frames.
#[derive(Clone, Debug)]
pub struct Denoiser {
    /// Normalised 1D taps applied in x and y, wrapping (`[1.0]` for none).
    pub spatial: Vec<f64>,
    /// EMA blend weight of the new frame; `None` measures each frame on its own.
    pub ema_alpha: Option<f64>,
}

/// Thresholds of the step integrands `φ_c(s) = [s < c]` (true integral `c`).
pub const STEPS: [f64; 7] = [0.1, 0.25, 0.4, 0.5, 0.6, 0.75, 0.9];

/// Separable wrapped convolution of one `w × h` frame.
fn blur(img: &[f64], w: usize, h: usize, taps: &[f64]) -> Vec<f64> {
    if taps.len() == 1 {
        return img.to_vec();
    }
    let along_x = blur_axis(img, w, h, taps, true);
    blur_axis(&along_x, w, h, taps, false)
}

/// One wrapped 1D pass of `taps` (centred) along x or along y.
fn blur_axis(img: &[f64], w: usize, h: usize, taps: &[f64], along_x: bool) -> Vec<f64> {
    let r = (taps.len() / 2) as isize;
    let mut out = vec![0.0; w * h];
    for y in 0..h {
        for x in 0..w {
            let mut s = 0.0;
            for (k, &f) in taps.iter().enumerate() {
                let o = k as isize - r;
                let at = if along_x {
                    y * w + (x as isize + o).rem_euclid(w as isize) as usize
                } else {
                    (y as isize + o).rem_euclid(h as isize) as usize * w + x
                };
                s += f * img[at];
            }
            out[y * w + x] = s;
        }
    }
    out
}

/// RMSE after denoising, over [`STEPS`], pixels and measured frames. `values` are scalar
/// samples in `[0, 1)`, x fastest, `w × h × t`. With an EMA the mask loops for `4t` frames
/// (at least 64) and the last `t` frames are measured (the converged filter); without, every
/// frame is measured.
pub fn filtered_rmse(values: &[f64], dims: [usize; 3], d: &Denoiser) -> f64 {
    filtered_rmse_at(values, dims, d, &STEPS)
}

/// Every frame of the step integrand `[s < c]`, one sample per pixel, filtered by `taps`.
fn step_frames(values: &[f64], [w, h, t]: [usize; 3], taps: &[f64], c: f64) -> Vec<Vec<f64>> {
    let n = w * h;
    (0..t)
        .map(|f| {
            let img: Vec<f64> = values[f * n..(f + 1) * n]
                .iter()
                .map(|&s| if s < c { 1.0 } else { 0.0 })
                .collect();
            blur(&img, w, h, taps)
        })
        .collect()
}

/// [`filtered_rmse`] over the thresholds `steps`.
pub fn filtered_rmse_at(values: &[f64], dims: [usize; 3], d: &Denoiser, steps: &[f64]) -> f64 {
    let t = dims[2];
    let (mut sum, mut count) = (0.0, 0usize);
    for &c in steps {
        let frames = step_frames(values, dims, &d.spatial, c);
        match d.ema_alpha {
            None => {
                for fr in &frames {
                    for &v in fr {
                        sum += (v - c) * (v - c);
                        count += 1;
                    }
                }
            }
            Some(alpha) => {
                let total = (4 * t).max(64).div_ceil(t) * t;
                let mut hist = frames[0].clone();
                for f in 1..total {
                    let cur = &frames[f % t];
                    for (hv, &v) in hist.iter_mut().zip(cur) {
                        *hv = alpha * v + (1.0 - alpha) * *hv;
                    }
                    if f >= total - t {
                        for &v in &hist {
                            sum += (v - c) * (v - c);
                            count += 1;
                        }
                    }
                }
            }
        }
    }
    (sum / count as f64).sqrt()
}

/// The RMSE after each of `frames` frames of spatial filtering + EMA, started from the first
/// frame (the history holds frame 0), over [`STEPS`] and pixels: how fast each mask converges.
pub fn filtered_rmse_curve(
    values: &[f64],
    dims: [usize; 3],
    d: &Denoiser,
    frames: usize,
) -> Vec<f64> {
    let [w, h, t] = dims;
    let n = w * h;
    let alpha = d.ema_alpha.unwrap_or(1.0);
    let mut sums = vec![0.0; frames];
    for &c in &STEPS {
        let filtered = step_frames(values, dims, &d.spatial, c);
        let mut hist = filtered[0].clone();
        for (f, sum) in sums.iter_mut().enumerate() {
            if f > 0 {
                for (hv, &v) in hist.iter_mut().zip(&filtered[f % t]) {
                    *hv = alpha * v + (1.0 - alpha) * *hv;
                }
            }
            *sum += hist.iter().map(|v| (v - c) * (v - c)).sum::<f64>();
        }
    }
    let count = (STEPS.len() * n) as f64;
    sums.iter().map(|s| (s / count).sqrt()).collect()
}
