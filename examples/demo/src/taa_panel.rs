//! The transparency scene under TAA: the same frames as the demo's table, accumulated the way
//! games do — the history clamped to the current frame's 3 × 3 min/max before each blend
//! (Karis 2014) — beside the plain EMA, after the demo's blur. The clamp is where blue noise
//! breaks in engines: a window whose nine pixels all fall on one side of the opacity has a box
//! of one colour, and the history collapses onto the current frame.

use crate::apps::{App, Transparency};
use crate::noises::Noise;
use crate::output::{Contender, judge};
use crate::{Config, EMA_ALPHA, blur, rmse_se};
use rayon::prelude::*;

/// The noises compared: the free constructions games use under TAA, the baked masks, and
/// FAST made for the plain EMA and for TAA.
pub const NOISES: [Noise; 8] = [
    Noise::White,
    Noise::Ign,
    Noise::R2,
    Noise::Rd,
    Noise::Golden,
    Noise::Stbn,
    Noise::Fast,
    Noise::FastTaa,
];

/// One noise's errors after the blur, with their standard errors, on the right half (opacity
/// 0.3) and the left (0.9).
#[derive(Clone, Debug)]
pub struct Row {
    /// The noise.
    pub noise: Noise,
    /// Plain EMA, opacity 0.3.
    pub ema: (f64, f64),
    /// EMA with the 3 × 3 min/max history clamp, opacity 0.3.
    pub taa: (f64, f64),
    /// Plain EMA and TAA at opacity 0.9, where a window needs a value above 0.9 to keep a
    /// background pixel: no mask keeps every window so.
    pub opaque: [(f64, f64); 2],
}

/// The pixels of the left (`left`) or right half, four pixels (the blur's reach) away from the
/// edge between them and from the image's border, where the clamp's window is cut short.
fn half(img: &[f32], [w, h]: [usize; 2], left: bool) -> Vec<f32> {
    const M: usize = 4;
    let (x0, x1) = if left {
        (M, w / 2 - M)
    } else {
        (w / 2 + M, w - M)
    };
    (M..h - M)
        .flat_map(|y| (x0..x1).map(move |x| img[y * w + x]))
        .collect()
}

/// Renders the transparency scene with every noise of [`NOISES`] under the EMA and under TAA.
pub fn run(cfg: &Config) -> Vec<Row> {
    let app = Transparency { size: cfg.size };
    let [w, h] = cfg.size;
    let reference = blur(&app.reference(), cfg.size, 1);
    let footprint = 4.0 * std::f64::consts::PI;
    let alpha = EMA_ALPHA as f32;
    NOISES
        .iter()
        .map(|&noise| {
            let mut frame = vec![0.0f32; w * h];
            let (mut ema, mut taa) = (Vec::new(), Vec::new());
            for f in 0..cfg.frames as u32 {
                frame.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
                    for (x, out) in row.iter_mut().enumerate() {
                        app.pixel(noise, x, y, f, std::slice::from_mut(out));
                    }
                });
                if f == 0 {
                    ema = frame.clone();
                    taa = frame.clone();
                    continue;
                }
                for (e, v) in ema.iter_mut().zip(&frame) {
                    *e += alpha * (v - *e);
                }
                // The clamp reads the frame's neighbourhood, clamped at the image's edges.
                let at = |x: i64, y: i64| {
                    frame[y.clamp(0, h as i64 - 1) as usize * w + x.clamp(0, w as i64 - 1) as usize]
                };
                taa.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
                    for (x, hv) in row.iter_mut().enumerate() {
                        let (mut lo, mut hi) = (f32::MAX, f32::MIN);
                        for dy in -1..=1 {
                            for dx in -1..=1 {
                                let v = at(x as i64 + dx, y as i64 + dy);
                                lo = lo.min(v);
                                hi = hi.max(v);
                            }
                        }
                        let clamped = hv.clamp(lo, hi);
                        *hv = clamped + alpha * (frame[y * w + x] - clamped);
                    }
                });
            }
            let err = |img: &[f32], left: bool| {
                let b = blur(img, cfg.size, 1);
                rmse_se(
                    &half(&b, cfg.size, left),
                    &half(&reference, cfg.size, left),
                    footprint,
                )
            };
            Row {
                noise,
                ema: err(&ema, false),
                taa: err(&taa, false),
                opaque: [err(&ema, true), err(&taa, true)],
            }
        })
        .collect()
}

/// Which noise leaves the least error under TAA, which tie with it, and what the best free
/// construction leaves: the demo's one verdict (`output::judge`) on this panel's numbers.
pub fn verdict(rows: &[Row]) -> String {
    let rows: Vec<Contender<'_>> = rows
        .iter()
        .map(|r| Contender {
            name: r.noise.name(),
            err: r.taa.0,
            se: r.taa.1,
            free: r.noise.is_free_hash(),
        })
        .collect();
    judge("under TAA", &rows)
}

/// Prints the panel.
pub fn print(rows: &[Row], cfg: &Config) {
    println!(
        "\ntransparency under TAA: the history clamped to the frame's 3x3 min/max, then blended (α {}),",
        EMA_ALPHA
    );
    println!(
        "  {} frames, after the blur (σ 1 px), beside the plain EMA; each half of the image:",
        cfg.frames
    );
    println!(
        "  {:<14} {:>18} {:>18} {:>8} {:>10} {:>10}",
        "noise", "α 0.3: EMA + blur", "TAA + blur", "TAA/EMA", "α 0.9: EMA", "TAA"
    );
    for r in rows {
        println!(
            "  {:<14} {:>9.4} ± {:.4} {:>9.4} ± {:.4} {:>8.2} {:>10.4} {:>10.4}",
            r.noise.name(),
            r.ema.0,
            r.ema.1,
            r.taa.0,
            r.taa.1,
            r.taa.0 / r.ema.0,
            r.opaque[0].0,
            r.opaque[1].0
        );
    }
    println!("  at α 0.3: {}", verdict(rows));
    println!(
        "  at α 0.9 a 3x3 window keeps a background pixel only if one of its nine values is above 0.9: every"
    );
    println!(
        "  noise collapses onto the surface there (fast-taa keeps its windows for opacities 0.2 to 0.8)"
    );
}
