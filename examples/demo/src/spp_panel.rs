//! Several rays per pixel: the occlusion scene (the room of `noisebake report render`) with 4
//! cosine-weighted rays per pixel and frame, each ray's direction from a sampler — the baked
//! sampler tile (`AO_RAYS`, trained on cosine-weighted directions for the demo's blur, read
//! through its own warp `SamplerTile::cosine_hemisphere`), Ahmed & Wonka 2020's hierarchical ordering (ZSobol, Blender Cycles' default,
//! no table), the free `r2_pairs` (the per-pair R2 lattice; for one pair the same points as `rd_ign_r2`) and `sobol_owen`, and white noise. Measured after the blur on
//! the first frame (what a real-time renderer's denoiser sees) and after the EMA.

use crate::apps::{App, Occlusion};
use crate::noises::AO_RAYS;
use crate::output::{Contender, judge};
use crate::{Config, EMA_ALPHA, blur, rmse_se};
use noisebake::{sampler, warp};
use noisebake_cli::zsobol::ZSobol;
use rayon::prelude::*;

/// Rays per pixel per frame.
pub const SPP: u32 = 4;

/// A source of each ray's direction about +z: `(x, y, frame, ray) → ω`.
type Source<'a> = &'a (dyn Fn(i32, i32, u32, u32) -> [f32; 3] + Sync);

/// One sampler's errors after the blur, with their standard errors.
#[derive(Clone, Debug)]
pub struct Row {
    /// The sampler.
    pub name: &'static str,
    /// Whether it needs no table.
    pub free: bool,
    /// Bytes it ships.
    pub bytes: usize,
    /// Frame 0 after the blur.
    pub first: (f64, f64),
    /// The EMA after every frame, then the blur.
    pub ema: (f64, f64),
}

/// Renders the occlusion scene at [`SPP`] rays per pixel with every sampler.
pub fn run(cfg: &Config) -> Vec<Row> {
    let app = Occlusion::new(cfg.size);
    let [w, h] = cfg.size;
    let reference = blur(&app.reference(), cfg.size, 1);
    let footprint = 4.0 * std::f64::consts::PI;
    let sources: [(&str, bool, usize, Source<'_>); 5] = [
        (
            "sampler tile",
            false,
            AO_RAYS.keys().bytes().len(),
            &|x, y, f, i| AO_RAYS.cosine_hemisphere(x, y, f, i, 0),
        ),
        ("zsobol", true, 0, &|x, y, f, i| {
            // Ordered for SPP samples a frame, scrambled afresh each frame (seeded by it), as
            // a real-time renderer would run it.
            let z = ZSobol::new(w.max(h), SPP, 7 + u64::from(f));
            warp::cosine_hemisphere(z.sample(x, y, i, 0), z.sample(x, y, i, 1))
        }),
        ("r2_pairs", true, 0, &|x, y, f, i| {
            let [u, v] = sampler::r2_pairs::<2>(x, y, f * SPP + i);
            warp::cosine_hemisphere(u, v)
        }),
        ("sobol_owen", true, 0, &|x, y, f, i| {
            let [u, v] = sampler::sobol_owen::<2>(x, y, f * SPP + i, 1);
            warp::cosine_hemisphere(u, v)
        }),
        ("white", true, 0, &|x, y, f, i| {
            let n = ((f * SPP + i) * 2) as i32;
            let u = |k: i32| (noisebake::hash::hash3(x, y, n + k, 99) >> 8) as f32 / 16_777_216.0;
            warp::cosine_hemisphere(u(0), u(1))
        }),
    ];
    sources
        .iter()
        .map(|&(name, free, bytes, source)| {
            let mut frame = vec![0.0f32; w * h];
            let mut ema = Vec::new();
            let mut first = (0.0, 0.0);
            for f in 0..cfg.frames as u32 {
                frame.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
                    for (x, out) in row.iter_mut().enumerate() {
                        let mut sum = 0.0;
                        for i in 0..SPP {
                            sum += app.ray(x, y, source(x as i32, y as i32, f, i));
                        }
                        *out = sum / SPP as f32;
                    }
                });
                if f == 0 {
                    first = rmse_se(&blur(&frame, cfg.size, 1), &reference, footprint);
                    ema = frame.clone();
                } else {
                    for (e, v) in ema.iter_mut().zip(&frame) {
                        *e += EMA_ALPHA as f32 * (v - *e);
                    }
                }
            }
            Row {
                name,
                free,
                bytes,
                first,
                ema: rmse_se(&blur(&ema, cfg.size, 1), &reference, footprint),
            }
        })
        .collect()
}

/// The least error on the first frame, what ties with it, and what the best free sampler
/// leaves: the demo's one verdict (`output::judge`) on this panel's numbers.
pub fn verdict(rows: &[Row]) -> String {
    let rows: Vec<Contender<'_>> = rows
        .iter()
        .map(|r| Contender {
            name: r.name,
            err: r.first.0,
            se: r.first.1,
            free: r.free,
        })
        .collect();
    judge("on one frame", &rows)
}

/// Prints the panel.
pub fn print(rows: &[Row], cfg: &Config) {
    println!(
        "\nocclusion in the room with {SPP} rays per pixel per frame (each ray's direction from a sampler), after the blur:"
    );
    println!(
        "  {:<14} {:>8} {:>18} {:>22}",
        "sampler",
        "bytes",
        "1 frame",
        format!("EMA {} frames", cfg.frames)
    );
    for r in rows {
        println!(
            "  {:<14} {:>8} {:>9.4} ± {:.4} {:>13.4} ± {:.4}",
            r.name, r.bytes, r.first.0, r.first.1, r.ema.0, r.ema.1
        );
    }
    println!("  {}", verdict(rows));
}
