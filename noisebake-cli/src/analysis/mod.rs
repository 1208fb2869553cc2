//! Quality metrics of masks (STBN §4.2, Fig. 5, 6 and 8): spectra, histograms, convergence.
//!
//! - Spatial low-frequency power of each 2D slice and temporal low-frequency power of each
//!   pixel's sequence: the mean DFT power at non-zero frequencies up to [`LOW_FREQUENCY`] cycles
//!   per texel, divided by the mean power over all non-zero frequencies. White noise scores about
//!   1; blue noise, whose spectrum is empty near the origin, far less.
//! - Histogram flatness of each slice: the largest deviation of a bin count from the flat count.
//! - Convergence: per-pixel RMSE of estimating ∫₀¹ f for a ramp, a step and a sine by plain
//!   averaging of the first k frames (Monte Carlo) and by an exponential moving average.

pub mod dft;
pub mod filtered;
pub mod points;
pub mod taa;

use build_assets::texture::Texture;
use serde::Serialize;

/// Non-zero frequencies at or below this (cycles per texel, Nyquist = 0.5) count as low.
pub const LOW_FREQUENCY: f64 = 0.125;
/// EMA blend factor of the convergence metric (STBN Fig. 8).
pub const EMA_ALPHA: f64 = 0.1;
/// Frames the EMA runs for (masks loop in time).
pub const EMA_FRAMES: usize = 64;

/// An integrand of the convergence metric: name, function, exact integral over [0, 1].
pub type Integrand = (&'static str, fn(f64) -> f64, f64);

/// The ramp, step and sine of STBN Fig. 6.
pub const INTEGRANDS: [Integrand; 3] = [
    ("ramp", |x| x, 0.5),
    ("step", |x| if x < 0.5 { 1.0 } else { 0.0 }, 0.5),
    (
        "sine",
        |x| (std::f64::consts::PI * x).sin(),
        std::f64::consts::FRAC_2_PI,
    ),
];

/// Metrics of one texture.
#[derive(Clone, Debug, Serialize)]
pub struct MaskReport {
    /// Sizes, x first.
    pub dims: Vec<usize>,
    /// Spatial low-frequency power ratio of each 2D slice.
    pub spatial_lf: Vec<f64>,
    /// Mean of `spatial_lf`.
    pub spatial_lf_mean: f64,
    /// Temporal low-frequency power ratio (pixel sequences along axis 2), if there is a third axis.
    pub temporal_lf: Option<f64>,
    /// Largest relative deviation of a histogram bin from flat, over all slices.
    pub histogram_max_deviation: f64,
    /// Convergence per integrand, if there is a third axis.
    pub convergence: Vec<Convergence>,
}

/// Convergence of one integrand over the frames of every pixel.
#[derive(Clone, Debug, Serialize)]
pub struct Convergence {
    /// `ramp`, `step` or `sine`.
    pub integrand: &'static str,
    /// RMSE over pixels of the plain average of frames `0..k`, for `k = 1..=T`.
    pub mc_rmse: Vec<f64>,
    /// Mean of `mc_rmse` (area under the curve).
    pub mc_mean: f64,
    /// RMSE over pixels of the EMA after frame `f`, for `f = 0..EMA_FRAMES` (frames loop).
    pub ema_rmse: Vec<f64>,
    /// Mean of `ema_rmse` over its second half (the steady state).
    pub ema_steady: f64,
}

/// Low-frequency ratio of a power spectrum `p` over bins whose frequency magnitude is `f(i)`.
fn lf_ratio(p: &[f64], f: impl Fn(usize) -> f64) -> (f64, f64) {
    let (mut low, mut nl, mut all, mut na) = (0.0, 0usize, 0.0, 0usize);
    for (i, &v) in p.iter().enumerate() {
        let r = f(i);
        if r == 0.0 {
            continue;
        }
        all += v;
        na += 1;
        if r <= LOW_FREQUENCY {
            low += v;
            nl += 1;
        }
    }
    (low / nl.max(1) as f64, all / na.max(1) as f64)
}

/// Spatial low-frequency ratio of one `w × h` slice.
pub fn spatial_lf(slice: &[f64], w: usize, h: usize) -> f64 {
    let p = dft::power2d(slice, w, h);
    let (low, all) = lf_ratio(&p, |i| {
        let (fx, fy) = (dft::freq(i % w, w), dft::freq(i / w, h));
        (fx * fx + fy * fy).sqrt()
    });
    low / all
}

/// Analyses channel 0 of a texture.
pub fn analyze(t: &Texture) -> MaskReport {
    let ch = t.format.channels as usize;
    let vals: Vec<f64> = t.values().iter().step_by(ch).copied().collect();
    let w = t.dims[0];
    let h = t.dims.get(1).copied().unwrap_or(1);
    let s = w * h;
    let slices: Vec<&[f64]> = vals.chunks(s).collect();
    let spatial: Vec<f64> = slices.iter().map(|sl| spatial_lf(sl, w, h)).collect();
    let bins = s.min(256);
    let mut dev: f64 = 0.0;
    for sl in &slices {
        let mut hist = vec![0usize; bins];
        for &v in *sl {
            hist[((v * bins as f64) as usize).min(bins - 1)] += 1;
        }
        let flat = s as f64 / bins as f64;
        dev = dev.max(
            hist.iter()
                .map(|&c| (c as f64 - flat).abs() / flat)
                .fold(0.0, f64::max),
        );
    }
    let (temporal_lf, convergence) = if t.dims.len() >= 3 {
        let frames = t.dims[2];
        // Pixel sequences along axis 2 (within the first block of further axes).
        let seqs: Vec<Vec<f64>> = (0..s)
            .map(|i| (0..frames).map(|f| vals[f * s + i]).collect())
            .collect();
        let (mut low, mut all) = (0.0, 0.0);
        for q in &seqs {
            let p = dft::power1d(q);
            let (l, a) = lf_ratio(&p, |k| dft::freq(k, frames).abs());
            low += l;
            all += a;
        }
        (
            Some(low / all),
            INTEGRANDS
                .iter()
                .map(|&(name, f, truth)| convergence(&seqs, name, f, truth))
                .collect(),
        )
    } else {
        (None, Vec::new())
    };
    MaskReport {
        dims: t.dims.clone(),
        spatial_lf_mean: spatial.iter().sum::<f64>() / spatial.len() as f64,
        spatial_lf: spatial,
        temporal_lf,
        histogram_max_deviation: dev,
        convergence,
    }
}

fn convergence(
    seqs: &[Vec<f64>],
    name: &'static str,
    f: fn(f64) -> f64,
    truth: f64,
) -> Convergence {
    let frames = seqs[0].len();
    let n = seqs.len() as f64;
    let mut mc = vec![0.0; frames];
    let mut ema = vec![0.0; EMA_FRAMES];
    for q in seqs {
        let mut sum = 0.0;
        for (k, &x) in q.iter().enumerate() {
            sum += f(x);
            let e = sum / (k + 1) as f64 - truth;
            mc[k] += e * e;
        }
        let mut hist = f(q[0]);
        for (fr, slot) in ema.iter_mut().enumerate() {
            if fr > 0 {
                hist += EMA_ALPHA * (f(q[fr % frames]) - hist);
            }
            *slot += (hist - truth) * (hist - truth);
        }
    }
    let mc: Vec<f64> = mc.iter().map(|s| (s / n).sqrt()).collect();
    let ema: Vec<f64> = ema.iter().map(|s| (s / n).sqrt()).collect();
    let half = &ema[EMA_FRAMES / 2..];
    Convergence {
        integrand: name,
        mc_mean: mc.iter().sum::<f64>() / mc.len() as f64,
        mc_rmse: mc,
        ema_steady: half.iter().sum::<f64>() / half.len() as f64,
        ema_rmse: ema,
    }
}

/// White noise of `t`'s dims and scalar type (seed 1; one channel, as only channel 0 is
/// analysed): the baseline [`explain`] reads a mask against, since every metric here is
/// relative and means something only beside it.
pub fn white_like(t: &Texture) -> Texture {
    let dims: Vec<String> = t.dims.iter().map(usize::to_string).collect();
    let text = format!(
        "[[texture]]\nname = \"WHITE\"\nkind = \"white\"\ndims = [{}]\nseed = 1\nformat = \"{}\"\n",
        dims.join(", "),
        build_assets::spec::Format {
            channels: 1,
            ..t.format
        }
    );
    let spec = build_assets::spec::parse_toml(&text)
        .ok()
        .and_then(|f| f.textures.into_iter().next())
        .expect("a white spec of a texture's own dims and format is valid");
    build_assets::generate(&spec, &mut |_, _| {})
}

/// The report as a person reads it: each metric of `mask` beside white noise of the same
/// size (`white`), what it measures, and which way is better.
pub fn explain(file: &str, t: &Texture, mask: &MaskReport, white: &MaskReport) -> String {
    use std::fmt::Write;
    let dims: Vec<String> = t.dims.iter().map(usize::to_string).collect();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{file}: {} texels, {}{}",
        dims.join("×"),
        t.format,
        if t.format.channels > 1 {
            " (channel 0 analysed)"
        } else {
            ""
        }
    );
    let _ = writeln!(
        s,
        "  {:<44} {:>10} {:>12}   better",
        "metric", "this mask", "white noise"
    );
    let mut row = |name: &str, a: f64, b: f64, pct: bool| {
        let f = |v: f64| {
            if pct {
                format!("{:.2} %", v * 100.0)
            } else {
                format!("{v:.4}")
            }
        };
        let _ = writeln!(s, "  {name:<44} {:>10} {:>12}   lower", f(a), f(b));
    };
    row(
        "spatial low-frequency power (slice mean)",
        mask.spatial_lf_mean,
        white.spatial_lf_mean,
        false,
    );
    if let (Some(a), Some(b)) = (mask.temporal_lf, white.temporal_lf) {
        row("temporal low-frequency power (per pixel)", a, b, false);
    }
    row(
        "histogram: largest bin off flat",
        mask.histogram_max_deviation,
        white.histogram_max_deviation,
        true,
    );
    for (m, w) in mask.convergence.iter().zip(&white.convergence) {
        row(
            &format!("{}: RMSE of the k-frame mean, mean over k", m.integrand),
            m.mc_mean,
            w.mc_mean,
            false,
        );
        row(
            &format!("{}: RMSE of the EMA (α {EMA_ALPHA}), steady", m.integrand),
            m.ema_steady,
            w.ema_steady,
            false,
        );
    }
    let _ = write!(
        s,
        "\
reading:
  low-frequency power: the mean DFT power at frequencies up to {LOW_FREQUENCY} cycles per texel
    over the mean at all non-zero frequencies; white noise is about 1, blue noise far below
    (its spectrum is empty near the origin, so errors it leaves blur away).
  histogram: the largest relative difference between a bin's count and the flat count, over
    every 2D slice ({} bins per slice); 0 % means every value occurs equally often.
  RMSE: the error, over pixels, of estimating ∫₀¹ f for a ramp, a step and a sine with the
    pixel's values over frames: the plain mean of the first k frames (mean over k = 1..T), and
    an exponential moving average at its steady state (frames loop).
  `--json` prints every number, per slice and per frame.
",
        (t.dims[0] * t.dims.get(1).copied().unwrap_or(1)).min(256)
    );
    s
}
