//! The filters games run on noisy per-pixel estimates, as linear maps fixed by the G-buffer
//! alone, so the error after each is exactly `filter(estimate) − filter(reference) =
//! filter(estimate − reference)`:
//!
//! - a Gaussian (σ in pixels, cut at 3σ) and a box, separable, renormalised where the image
//!   ends;
//! - an SVGF-style à-trous (Schied et al. 2017, "Spatiotemporal Variance-Guided Filtering",
//!   §4.4; Dammertz et al. 2010): passes of the 5 × 5 B3-spline kernel `h = (1, 4, 6, 4, 1)/16`
//!   with taps `2^k` pixels apart in pass `k`, each tap weighted by edge-stopping functions of
//!   the G-buffer — normals `max(0, n_p · n_q)^128` and depths `exp(−|z_p − z_q| / (σ_z ·
//!   ∇z · |offset|))` with `∇z` the mean of both pixels' depth gradients, so the raw weight of
//!   a pair is symmetric — and normalised per pixel. Unlike SVGF it has no luminance term: its
//!   weights depend on the geometry only, so its error is linear in the estimate's.
//!
//! Pixels that see the sky are filtered among themselves only (their estimates are exact).

use super::GBuffer;

/// One of the denoisers `report render` measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Denoiser {
    /// Nothing: the per-pixel error.
    None,
    /// A Gaussian of standard deviation `sigma` pixels.
    Gauss {
        /// σ in pixels.
        sigma: f32,
    },
    /// A `size × size` box.
    Box {
        /// Side in pixels (odd).
        size: usize,
    },
    /// The à-trous filter with `passes` passes (steps 1, 2, 4, …).
    Atrous {
        /// Passes.
        passes: usize,
    },
}

impl Denoiser {
    /// The report's name.
    pub fn name(self) -> String {
        match self {
            Denoiser::None => "none".into(),
            Denoiser::Gauss { sigma } => format!("gauss σ{sigma}"),
            Denoiser::Box { size } => format!("box {size}x{size}"),
            Denoiser::Atrous { passes } => format!("à-trous {passes}"),
        }
    }
}

/// The B3-spline taps.
pub const B3: [f32; 5] = [1.0 / 16.0, 4.0 / 16.0, 6.0 / 16.0, 4.0 / 16.0, 1.0 / 16.0];
/// Exponent of the normal weight (SVGF's σ_n).
const SIGMA_N: i32 = 128;
/// Scale of the depth weight (SVGF's σ_z).
const SIGMA_Z: f32 = 1.0;

/// A denoiser bound to a G-buffer, ready to apply to images of its size.
#[derive(Clone, Debug)]
pub struct Filter {
    kind: Denoiser,
    width: usize,
    height: usize,
    /// Separable taps (Gaussian, box).
    taps: Vec<f32>,
    /// À-trous: per pass, per pixel, the 25 normalised weights (row-major over the 5 × 5
    /// taps); and whether each pixel sees a surface.
    atrous: Vec<Vec<[f32; 25]>>,
    hit: Vec<bool>,
}

/// The raw (unnormalised) à-trous weight between pixels `p` and `q` of `g`, `offset` taps
/// apart at `step` pixels per tap, with kernel weight `h`: symmetric in `p` and `q`.
pub fn atrous_weight(g: &GBuffer, gradient: &[f32], p: usize, q: usize, dist: f32, h: f32) -> f32 {
    if g.hit[p] != g.hit[q] {
        return 0.0;
    }
    if !g.hit[p] {
        return h;
    }
    let wn = g.normal[p].dot(g.normal[q]).max(0.0).powi(SIGMA_N);
    let grad = 0.5 * (gradient[p] + gradient[q]);
    let wz = (-(g.depth[p] - g.depth[q]).abs() / (SIGMA_Z * grad * dist + 1e-6)).exp();
    h * wn * wz
}

/// Each pixel's depth gradient: the larger of its central differences in x and y (one-sided
/// at the image's edges and beside the sky).
pub fn depth_gradient(g: &GBuffer) -> Vec<f32> {
    let (w, h) = (g.width, g.height);
    (0..w * h)
        .map(|i| {
            if !g.hit[i] {
                return 0.0;
            }
            let (x, y) = (i % w, i / w);
            let d = |a: Option<usize>, b: Option<usize>| -> f32 {
                let z = |j: Option<usize>| j.filter(|&j| g.hit[j]).map(|j| g.depth[j]);
                match (z(a), z(b)) {
                    (Some(za), Some(zb)) => 0.5 * (za - zb).abs(),
                    (Some(za), None) => (za - g.depth[i]).abs(),
                    (None, Some(zb)) => (zb - g.depth[i]).abs(),
                    (None, None) => 0.0,
                }
            };
            let dx = d((x + 1 < w).then(|| i + 1), (x > 0).then(|| i - 1));
            let dy = d((y + 1 < h).then(|| i + w), (y > 0).then(|| i - w));
            dx.max(dy)
        })
        .collect()
}

impl Filter {
    /// `kind` bound to `g`.
    pub fn new(kind: Denoiser, g: &GBuffer) -> Filter {
        let (w, h) = (g.width, g.height);
        let mut f = Filter {
            kind,
            width: w,
            height: h,
            taps: Vec::new(),
            atrous: Vec::new(),
            hit: g.hit.clone(),
        };
        match kind {
            Denoiser::None => {}
            Denoiser::Gauss { sigma } => {
                let r = (3.0 * sigma).ceil() as i32;
                f.taps = (-r..=r)
                    .map(|d| (-(d * d) as f32 / (2.0 * sigma * sigma)).exp())
                    .collect();
            }
            Denoiser::Box { size } => f.taps = vec![1.0; size],
            Denoiser::Atrous { passes } => {
                let gradient = depth_gradient(g);
                for pass in 0..passes {
                    let step = 1i64 << pass;
                    let weights = (0..w * h)
                        .map(|p| {
                            let (x, y) = ((p % w) as i64, (p / w) as i64);
                            let mut row = [0.0f32; 25];
                            let mut sum = 0.0;
                            for (k, wk) in row.iter_mut().enumerate() {
                                let (i, j) = ((k % 5) as i64 - 2, (k / 5) as i64 - 2);
                                let (qx, qy) = (x + i * step, y + j * step);
                                if qx < 0 || qy < 0 || qx >= w as i64 || qy >= h as i64 {
                                    continue;
                                }
                                let q = (qy * w as i64 + qx) as usize;
                                let dist = (((i * i + j * j) as f32).sqrt()) * step as f32;
                                *wk =
                                    atrous_weight(g, &gradient, p, q, dist, B3[k % 5] * B3[k / 5]);
                                sum += *wk;
                            }
                            if sum > 0.0 {
                                row.iter_mut().for_each(|v| *v /= sum);
                            }
                            row
                        })
                        .collect();
                    f.atrous.push(weights);
                }
            }
        }
        f
    }

    /// What it filters with.
    pub fn kind(&self) -> Denoiser {
        self.kind
    }

    /// The filtered image.
    pub fn apply(&self, img: &[f32]) -> Vec<f32> {
        let (w, h) = (self.width, self.height);
        match self.kind {
            Denoiser::None => img.to_vec(),
            Denoiser::Gauss { .. } | Denoiser::Box { .. } => {
                let r = (self.taps.len() / 2) as i64;
                // Rows, then columns; sky pixels are averaged with sky pixels only.
                let pass = |src: &[f32], along_x: bool| -> Vec<f32> {
                    (0..w * h)
                        .map(|p| {
                            let (x, y) = ((p % w) as i64, (p / w) as i64);
                            let (mut s, mut ws) = (0.0f32, 0.0f32);
                            for (k, &t) in self.taps.iter().enumerate() {
                                let d = k as i64 - r;
                                let (qx, qy) = if along_x { (x + d, y) } else { (x, y + d) };
                                if qx < 0 || qy < 0 || qx >= w as i64 || qy >= h as i64 {
                                    continue;
                                }
                                let q = (qy * w as i64 + qx) as usize;
                                if self.hit[q] != self.hit[p] {
                                    continue;
                                }
                                s += t * src[q];
                                ws += t;
                            }
                            if ws > 0.0 { s / ws } else { src[p] }
                        })
                        .collect()
                };
                pass(&pass(img, true), false)
            }
            Denoiser::Atrous { .. } => {
                let mut cur = img.to_vec();
                for (pass, weights) in self.atrous.iter().enumerate() {
                    let step = 1i64 << pass;
                    cur = (0..w * h)
                        .map(|p| {
                            let (x, y) = ((p % w) as i64, (p / w) as i64);
                            let mut s = 0.0;
                            for (k, &wk) in weights[p].iter().enumerate() {
                                if wk == 0.0 {
                                    continue;
                                }
                                let (i, j) = ((k % 5) as i64 - 2, (k / 5) as i64 - 2);
                                let q = ((y + j * step) * w as i64 + x + i * step) as usize;
                                s += wk * cur[q];
                            }
                            s
                        })
                        .collect();
                }
                cur
            }
        }
    }

    /// The normalised à-trous weights of pixel `p` in `pass` (for tests).
    pub fn atrous_row(&self, pass: usize, p: usize) -> Option<[f32; 25]> {
        self.atrous.get(pass).map(|w| w[p])
    }
}
