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

/// Separable wrapped convolution of one `w × h` frame (a single tap copies it).
pub(crate) fn blur(img: &[f64], w: usize, h: usize, taps: &[f64]) -> Vec<f64> {
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
    let (mut sum, mut count) = (0.0, 0usize);
    for &c in steps {
        let (s, n) = squared_errors(&step_frames(values, dims, &d.spatial, c), c, d.ema_alpha);
        sum += s;
        count += n;
    }
    (sum / count as f64).sqrt()
}

/// The squared errors against `truth` of filtered `frames` and their count: every frame
/// without an EMA; with one, the last `t` frames of `4t` (at least 64) over the looping frames.
fn squared_errors(frames: &[Vec<f64>], truth: f64, ema_alpha: Option<f64>) -> (f64, usize) {
    let t = frames.len();
    let (mut sum, mut count) = (0.0, 0usize);
    match ema_alpha {
        None => {
            for fr in frames {
                for &v in fr {
                    sum += (v - truth) * (v - truth);
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
                        sum += (v - truth) * (v - truth);
                        count += 1;
                    }
                }
            }
        }
    }
    (sum, count)
}

/// [`filtered_rmse`] for any integrands: `integrand(j)` gives integrand `j`'s one-sample
/// estimate at every texel (x fastest, `w × h × t`) and its true value. Returns the RMSE over
/// the `count` integrands, pixels and measured frames (the same filter and steady-state EMA),
/// and its standard error from the spread of the mean squared error over 4 × 4 blocks of the
/// image (each block one sample).
pub fn filtered_rmse_integrands(
    dims: [usize; 3],
    d: &Denoiser,
    count: usize,
    integrand: &(dyn Fn(usize) -> (Vec<f64>, f64) + Sync),
) -> (f64, f64) {
    use rayon::prelude::*;
    let [w, h, t] = dims;
    let n = w * h;
    let per_pixel: Vec<Vec<f64>> = (0..count)
        .into_par_iter()
        .map(|j| {
            let (values, truth) = integrand(j);
            let frames: Vec<Vec<f64>> = (0..t)
                .map(|f| blur(&values[f * n..(f + 1) * n], w, h, &d.spatial))
                .collect();
            pixel_squared_errors(&frames, truth, d.ema_alpha)
        })
        .collect();
    let mut sum = vec![0.0; n];
    for p in &per_pixel {
        for (s, v) in sum.iter_mut().zip(p) {
            *s += v;
        }
    }
    const B: usize = 4;
    let mut blocks = [0.0f64; B * B];
    for (i, s) in sum.iter().enumerate() {
        let (x, y) = (i % w, i / w);
        blocks[(y * B / h) * B + x * B / w] += s;
    }
    let per = (n / (B * B)) as f64;
    let mse_of = |v: f64, pixels: f64| v / (pixels * count.max(1) as f64);
    let mse = mse_of(sum.iter().sum(), n as f64);
    let bm: Vec<f64> = blocks.iter().map(|&b| mse_of(b, per)).collect();
    let var = bm.iter().map(|m| (m - mse) * (m - mse)).sum::<f64>() / (B * B - 1) as f64;
    let se_mse = (var / (B * B) as f64).sqrt();
    let rmse = mse.sqrt();
    (
        rmse,
        if rmse > 0.0 {
            se_mse / (2.0 * rmse)
        } else {
            0.0
        },
    )
}

/// Per pixel, the mean over measured frames of the squared error of filtered `frames` against
/// `truth` (the frames [`squared_errors`] measures).
fn pixel_squared_errors(frames: &[Vec<f64>], truth: f64, ema_alpha: Option<f64>) -> Vec<f64> {
    let t = frames.len();
    let mut out = vec![0.0; frames[0].len()];
    let add = |fr: &[f64], out: &mut [f64], k: f64| {
        for (o, &v) in out.iter_mut().zip(fr) {
            *o += (v - truth) * (v - truth) * k;
        }
    };
    match ema_alpha {
        None => {
            for fr in frames {
                add(fr, &mut out, 1.0 / t as f64);
            }
        }
        Some(alpha) => {
            let total = (4 * t).max(64).div_ceil(t) * t;
            let mut hist = frames[0].clone();
            for f in 1..total {
                for (hv, &v) in hist.iter_mut().zip(&frames[f % t]) {
                    *hv = alpha * v + (1.0 - alpha) * *hv;
                }
                if f >= total - t {
                    add(&hist, &mut out, 1.0 / t as f64);
                }
            }
        }
    }
    out
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
