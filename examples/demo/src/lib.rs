//! # The noisebake demo
//!
//! A small scene that declares the noise it needs — six textures in `noise.toml`, baked by
//! `build.rs` through the cache, and one inline with `noise_texture!` — and renders, on the CPU,
//! the applications the papers evaluate with every noise type side by side: stochastic
//! transparency, RGB dithering, a single-scattering volume and ambient occlusion. Each is shown
//! after 1 frame, after a Monte Carlo average of 16 frames and after a 64-frame EMA (α = 0.1),
//! with RMSE against a converged reference, convergence plots and an `index.html`.
//!
//! Run it with `cargo run --release --example demo` from the workspace root.

pub mod apps;
pub mod cloud;
pub mod cnj_panel;
pub mod equal_time;
pub mod material;
pub mod noises;
mod output;
pub mod spp_panel;
pub mod taa_panel;

pub use output::png as save_png;

/// The transparency and dithering scenes in WGSL (`src/scenes.wgsl`), for the GPU example.
pub const GPU_SCENES: &str = include_str!("scenes.wgsl");

use apps::{App, Dither, Occlusion, Transparency, Volume};
use noises::Noise;
use rayon::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

/// EMA blend factor of the temporal filter.
pub const EMA_ALPHA: f64 = 0.1;

/// What to render.
#[derive(Clone, Debug)]
pub struct Config {
    /// Image size in pixels.
    pub size: [usize; 2],
    /// Frames rendered (MC average and EMA).
    pub frames: usize,
    /// Frames of the Monte Carlo average shown as an image.
    pub mc_frames: usize,
    /// Where to write images, plots and `index.html` (`None`: metrics only).
    pub out: Option<PathBuf>,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            size: [128, 128],
            frames: 64,
            mc_frames: 16,
            out: Some(PathBuf::from("target/noisebake-demo")),
        }
    }
}

/// Errors of one application and noise type.
#[derive(Clone, Debug)]
pub struct Metrics {
    /// Application.
    pub app: &'static str,
    /// Noise type.
    pub noise: Noise,
    /// RMSE of frame 0 after a Gaussian blur (σ = 1 px) of both it and the reference — what a
    /// spatial denoiser sees.
    pub filtered_1: f64,
    /// RMSE of the mean of the first k frames, k = 1..=frames.
    pub mc: Vec<f64>,
    /// RMSE of the EMA after frame k, k = 1..=frames.
    pub ema: Vec<f64>,
    /// RMSE of the final EMA after the same Gaussian blur: spatial + temporal denoising, what
    /// FAST's product masks are optimised for.
    pub denoised: f64,
    /// Standard error of `denoised` from the spread of the per-pixel squared errors, with the
    /// blur's footprint (4πσ² ≈ 12.6 pixels) as one independent sample: differences within
    /// about twice the combined error are ties, not wins.
    pub denoised_se: f64,
    /// `(frame, RMSE)` of the EMA after the blur at frames 1, 2, 3, 4, 6, 8, 12, 16, …: the
    /// verdict's metric as it converges.
    pub ema_blur: Vec<(usize, f64)>,
    /// Seconds to render all frames.
    pub seconds: f64,
}

/// The frames at which the EMA + blur curve is sampled: 1, 2, 3, 4, 6, 8, 12, 16, 24, … (and
/// the last), so the plot has a point per half octave for a blur per point.
pub fn curve_frames(frames: usize) -> Vec<usize> {
    let mut out = Vec::new();
    let mut k = 1;
    while k < frames {
        out.push(k);
        k = if k < 2 || k.is_power_of_two() {
            k + k.div_ceil(2)
        } else {
            k.next_power_of_two()
        };
    }
    out.push(frames);
    out.dedup();
    out
}

/// RMSE and its standard error over pixels, with `footprint` pixels as one independent sample.
fn rmse_se(a: &[f32], b: &[f32], footprint: f64) -> (f64, f64) {
    let n = a.len().max(1) as f64;
    let sq: Vec<f64> = a
        .iter()
        .zip(b)
        .map(|(x, y)| ((x - y) as f64).powi(2))
        .collect();
    let mse = sq.iter().sum::<f64>() / n;
    let var = sq.iter().map(|s| (s - mse).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    let se_mse = (var * footprint / n).sqrt();
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

fn rmse(a: &[f32], b: &[f32]) -> f64 {
    let s: f64 = a.iter().zip(b).map(|(x, y)| ((x - y) as f64).powi(2)).sum();
    (s / a.len().max(1) as f64).sqrt()
}

/// Gaussian blur (σ = 1 px, clamped edges) of an image with `c` channels: the spatial filter
/// the demo's errors are measured after.
pub fn blur(img: &[f32], [w, h]: [usize; 2], c: usize) -> Vec<f32> {
    let taps: Vec<f32> = (-3i32..=3).map(|d| (-(d * d) as f32 / 2.0).exp()).collect();
    let norm: f32 = taps.iter().sum();
    let pass = |src: &[f32], dx: usize, dy: usize| -> Vec<f32> {
        let mut out = vec![0.0; src.len()];
        for y in 0..h {
            for x in 0..w {
                for ch in 0..c {
                    let mut s = 0.0;
                    for (k, t) in taps.iter().enumerate() {
                        let o = k as i64 - 3;
                        let xx = (x as i64 + o * dx as i64).clamp(0, w as i64 - 1) as usize;
                        let yy = (y as i64 + o * dy as i64).clamp(0, h as i64 - 1) as usize;
                        s += t * src[(yy * w + xx) * c + ch];
                    }
                    out[(y * w + x) * c + ch] = s / norm;
                }
            }
        }
        out
    };
    pass(&pass(img, 1, 0), 0, 1)
}

/// One application's images and metrics for every noise type.
pub struct AppResult {
    /// Application.
    pub name: &'static str,
    /// Caption.
    pub caption: &'static str,
    /// Channels.
    pub channels: usize,
    /// Reference image.
    pub reference: Vec<f32>,
    /// Per noise: metrics, first frame, MC average, EMA.
    pub runs: Vec<(Metrics, [Vec<f32>; 3])>,
    /// Seconds for the reference.
    pub reference_seconds: f64,
}

/// The demo's metrics of one application and noise type from its frames: `render(f, frame)`
/// fills frame `f` (`cfg.size` pixels × the app's channels). Returns the metrics (with
/// `seconds` 0) and the first frame, the Monte Carlo mean after `cfg.mc_frames` frames and the
/// final EMA. `ref_blur` is the reference after [`blur`]. The CPU demo and the GPU example
/// both measure through this, so their errors are the same numbers of the same images.
pub fn evaluate(
    app: &dyn App,
    cfg: &Config,
    noise: Noise,
    reference: &[f32],
    ref_blur: &[f32],
    render: &mut dyn FnMut(u32, &mut [f32]),
) -> (Metrics, [Vec<f32>; 3]) {
    let [w, h] = cfg.size;
    let c = app.channels();
    let mut sum = vec![0.0f64; w * h * c];
    let mut ema = vec![0.0f32; w * h * c];
    let (mut mc, mut em) = (Vec::new(), Vec::new());
    let (mut first, mut mc_img) = (Vec::new(), Vec::new());
    let mut frame = vec![0.0f32; w * h * c];
    let sampled = curve_frames(cfg.frames);
    let mut ema_blur = Vec::new();
    for f in 0..cfg.frames {
        render(f as u32, &mut frame);
        for (s, v) in sum.iter_mut().zip(&frame) {
            *s += *v as f64;
        }
        if f == 0 {
            ema.copy_from_slice(&frame);
            first = frame.clone();
        } else {
            for (e, v) in ema.iter_mut().zip(&frame) {
                *e += EMA_ALPHA as f32 * (v - *e);
            }
        }
        let mean: Vec<f32> = sum.iter().map(|s| (s / (f + 1) as f64) as f32).collect();
        mc.push(rmse(&mean, reference));
        em.push(rmse(&ema, reference));
        if sampled.contains(&(f + 1)) && f + 1 < cfg.frames {
            ema_blur.push((f + 1, rmse(&blur(&ema, cfg.size, c), ref_blur)));
        }
        if f + 1 == cfg.mc_frames.min(cfg.frames) {
            mc_img = mean;
        }
    }
    let filtered_1 = rmse(&blur(&first, cfg.size, c), ref_blur);
    let footprint = 4.0 * std::f64::consts::PI;
    let (denoised, denoised_se) = rmse_se(&blur(&ema, cfg.size, c), ref_blur, footprint);
    ema_blur.push((cfg.frames, denoised));
    (
        Metrics {
            app: app.name(),
            noise,
            filtered_1,
            mc,
            ema: em,
            denoised,
            denoised_se,
            ema_blur,
            seconds: 0.0,
        },
        [first, mc_img, ema],
    )
}

fn render_app(app: &dyn App, cfg: &Config) -> AppResult {
    let [w, _] = cfg.size;
    let c = app.channels();
    let t0 = Instant::now();
    let reference = app.reference();
    let reference_seconds = t0.elapsed().as_secs_f64();
    let ref_blur = blur(&reference, cfg.size, c);
    let runs = Noise::ALL
        .iter()
        .map(|&noise| {
            let start = Instant::now();
            let mut frames = |f: u32, frame: &mut [f32]| {
                frame
                    .par_chunks_mut(w * c)
                    .enumerate()
                    .for_each(|(y, row)| {
                        for x in 0..w {
                            app.pixel(noise, x, y, f, &mut row[x * c..(x + 1) * c]);
                        }
                    });
            };
            let (mut m, images) = evaluate(app, cfg, noise, &reference, &ref_blur, &mut frames);
            m.seconds = start.elapsed().as_secs_f64();
            (m, images)
        })
        .collect();
    AppResult {
        name: app.name(),
        caption: app.caption(),
        channels: c,
        reference,
        runs,
        reference_seconds,
    }
}

/// Renders every application with every noise type; writes the outputs if `cfg.out` is set.
pub fn run(cfg: &Config) -> Result<Vec<AppResult>, String> {
    let size = cfg.size;
    let apps: Vec<Box<dyn App>> = vec![
        Box::new(Transparency { size }),
        Box::new(Dither { size }),
        Box::new(Volume::new(size)),
        Box::new(Occlusion::new(size)),
    ];
    let results: Vec<AppResult> = apps.iter().map(|a| render_app(a.as_ref(), cfg)).collect();
    if let Some(dir) = &cfg.out {
        output::write(dir, cfg, &results)?;
    }
    Ok(results)
}

/// What the build script's bake did, one line per texture: name, bytes, source, seconds.
pub const BAKE_SUMMARY: &str = include_str!(concat!(env!("OUT_DIR"), "/bake_summary.tsv"));

/// The demo's entry point.
pub fn main() {
    let start = Instant::now();
    let cfg = Config::default();
    println!("noisebake demo: the scene's noise, baked at build time");
    println!(
        "  {:<10} {:>9}  {:<10} {:>8}",
        "texture", "bytes", "last bake", "seconds"
    );
    for line in BAKE_SUMMARY.lines() {
        let f: Vec<&str> = line.split('\t').collect();
        if let [name, bytes, source, secs] = f[..] {
            println!(
                "  {name:<10} {bytes:>9}  {:<10} {secs:>8}",
                source.to_lowercase()
            );
        }
    }
    let inline = noises::BLUE2D.bytes().len();
    println!(
        "  {:<10} {:>9}  {:<10} {:>8}",
        "BLUE2D", inline, "inline", "-"
    );
    println!(
        "  (\"generated\" at a first build; \"hit\" when the build script reran against a warm cache)"
    );
    match run(&cfg) {
        Ok(results) => {
            output::summary(&results, &cfg);
            let spp = spp_panel::run(&cfg);
            spp_panel::print(&spp, &cfg);
            let taa = taa_panel::run(&cfg);
            taa_panel::print(&taa, &cfg);
            let dir = cfg.out.clone().unwrap_or_default();
            println!("\ncurl-noise jittering (implicit blue-noise points):");
            let cnj = cnj_panel::run(&dir, 256).unwrap_or_else(|e| {
                eprintln!("error: {e}");
                std::process::exit(1)
            });
            for r in &cnj {
                match r.quality {
                    Some((nu, a, q)) => println!(
                        "  {:<58} {:>8.2} ms  ν_eff {nu:.3}  ā {a:.1}  q {q:.5}",
                        r.what,
                        r.seconds * 1e3
                    ),
                    None => println!("  {:<58} {:>8.2} ms", r.what, r.seconds * 1e3),
                }
            }
            for line in noisebake_cli::analysis::points::READING.lines() {
                println!("  {line}");
            }
            println!(
                "\nstochastic noise: fBm cloud, deterministic vs one-sample fBm density at equal time (1 thread):"
            );
            let cloud = cloud::run(&dir);
            output::extra_panels(&dir, &cnj, &cloud).unwrap_or_else(|e| {
                eprintln!("error: {e}");
                std::process::exit(1)
            });
            println!(
                "\nrender time {:.1} s; images, plots and index.html in {}",
                start.elapsed().as_secs_f64(),
                cfg.out
                    .as_ref()
                    .map(|p| p.display().to_string())
                    .unwrap_or_default()
            );
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
