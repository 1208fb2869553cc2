//! `noisebake report render`: every sampler judged in a ray-traced scene, after the denoisers
//! games run, on one frame and accumulated over frames (`crate::render`: the room or a
//! user's `.obj`, AO from dimensions 0–1, an area light's soft shadow from 2–3, a diffuse
//! bounce with next-event estimation from all four).
//!
//! - **Reference.** `REFERENCE_SPP` samples per pixel of Owen-scrambled Sobol points, as
//!   `REPLICATES` independent replicates (each pixel and replicate its own scrambles); its standard error after each denoiser (the spread of
//!   the replicates' means) is printed beside the errors it must be small against.
//! - **One frame.** The RMSE over the pixels that see a surface of `filter(estimate −
//!   reference)`, averaged (in squares) over several frames — every frame counts, not only
//!   the first, since a sampler whose frame 0 is its best is not what a game sees.
//! - **Accumulated.** An exponential moving average with α = 0.1 of the frames' estimates, a
//!   static camera, its error through the same filters over frames 32–63 of 64.
//!
//! Denoisers: none, Gaussian σ 1, box 5 × 5, the SVGF-style à-trous of 3 passes
//! ([`crate::render::denoise`]). The samplers: the crate's baked tiles (kind `sampler`, one per
//! filter they are baked for), its free samplers (`rd_ign_r2`, `ign_r2`, `sobol_owen`), Ahmed
//! and Wonka's ZSobol, white noise, and with `--features peers` Heitz et al. 2019's tables
//! (the one for that spp, and the 256-spp table read progressively, sample `f·spp + i`, as
//! NVIDIA's NRD sample reads it by frame) and OpenQMC's lattice blue-noise sampler.

use crate::render::denoise::{Denoiser, Filter};
use crate::render::scene::Scene;
use crate::render::trace::Tracer;
use crate::render::{GBuffer, INTEGRANDS, Sampler, render_frame};
use noise_runtime::sampler;
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// Image width and height: 160 × 120 over a 128 × 128 tile, so the tile's wrap is in view.
pub const SIZE: [usize; 2] = [160, 120];
/// Samples per pixel measured on one frame.
pub const SPPS: [u32; 5] = [1, 2, 4, 8, 16];
/// Samples per pixel per frame measured under the EMA (their one-frame figures come from the
/// same frames).
pub const EMA_SPPS: [u32; 2] = [4, 16];
/// Frames accumulated.
pub const FRAMES: u32 = 64;
/// The frames whose errors count: the EMA's history has settled by then (`(1 − α)^32 < 4 %`).
pub const MEASURED: std::ops::Range<u32> = 32..64;
/// Frames measured on their own at the spp values without an EMA run.
pub const ONE_FRAME_FRAMES: u32 = 8;
/// The EMA's blend weight.
pub const ALPHA: f32 = 0.1;
/// Samples per pixel per frame measured with the camera moving (for information).
pub const MOVING_SPPS: [u32; 1] = [4];
/// The moving camera pans right and back by this many pixels ...
pub const PAN: usize = 16;
/// ... this many pixels a frame (a triangle wave: [`pan`]).
pub const PAN_SPEED: usize = 2;

/// How far the moving camera has panned at `frame`: [`PAN_SPEED`] pixels a frame, right to
/// [`PAN`] and back.
pub fn pan(frame: u32) -> usize {
    let p = (PAN_SPEED * frame as usize) % (2 * PAN);
    if p > PAN { 2 * PAN - p } else { p }
}

/// The EMA of errors through a camera pan: pixel `x` of the new frame saw, a frame ago, what
/// pixel `x + delta` saw (the picture moved by `−delta`); the history is read from there and
/// blended with `err` by `alpha`, and where that pixel was out of view (disoccluded) the
/// history restarts from `err`, as a TAA resets history it cannot reproject.
pub fn reproject(history: &[f32], err: &[f32], width: usize, delta: isize, alpha: f32) -> Vec<f32> {
    err.iter()
        .enumerate()
        .map(|(i, &e)| {
            let x = (i % width) as isize + delta;
            if (0..width as isize).contains(&x) {
                let h = history[i - (i % width) + x as usize];
                h + alpha * (e - h)
            } else {
                e
            }
        })
        .collect()
}
/// The reference's samples per pixel, and its replicates.
pub const REFERENCE_SPP: u32 = 8192;
/// Independent replicates the reference is the mean of.
pub const REPLICATES: u32 = 4;
/// The denoisers, in the order of every row's errors.
pub const DENOISERS: [Denoiser; 4] = [
    Denoiser::None,
    Denoiser::Gauss { sigma: 1.0 },
    Denoiser::Box { size: 5 },
    Denoiser::Atrous { passes: 3 },
];

/// One sampler at one spp, one integrand, one mode.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The sampler.
    pub sampler: String,
    /// `baked`, `published`, `free` or `white`.
    pub family: String,
    /// Samples per pixel per frame.
    pub spp: u32,
    /// `frame` (one frame, averaged over frames), `ema` (accumulated) or `moving` (accumulated
    /// with the camera panning and the history reprojected).
    pub mode: String,
    /// `ao`, `shadow` or `bounce`.
    pub integrand: String,
    /// RMSE after each of [`DENOISERS`], in order.
    pub rmse: [f64; 4],
}

/// The reference and what it costs.
#[derive(Clone, Debug, Serialize)]
pub struct Reference {
    /// Samples per pixel.
    pub spp: u32,
    /// Replicates.
    pub replicates: u32,
    /// Per integrand, its standard error after each denoiser (RMS over surface pixels).
    pub standard_error: Vec<[f64; 4]>,
    /// Seconds it took (0 when read from disk).
    pub seconds: f64,
}

/// One cell of the tiles' goal: the tile baked for that cell against the best of the peers.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// Samples per pixel per frame.
    pub spp: u32,
    /// `ao` or `shadow`.
    pub integrand: String,
    /// `gauss σ1` or `à-trous 3`.
    pub denoiser: String,
    /// `frame` or `ema`.
    pub mode: String,
    /// The tile baked for this cell.
    pub tile: String,
    /// Its error.
    pub tile_rmse: f64,
    /// The best peer.
    pub best: String,
    /// Its error.
    pub best_rmse: f64,
    /// How much less error the tile leaves, in percent of the best peer's (negative: more).
    pub margin_percent: f64,
}

/// The peers a tile must beat: the free `rd_ign_r2`, Heitz et al. 2019's tables, ZSobol and
/// per-pixel Owen-scrambled Sobol.
pub const PEERS: [&str; 5] = [
    "rd_ign_r2 (free)",
    "Heitz 2019 (table for this spp)",
    "Heitz 2019 (256-spp table, progressive)",
    "ZSobol (Ahmed-Wonka 2020)",
    "sobol_owen (free)",
];

/// The goal's cells (4 and 16 spp; AO and the shadow; Gaussian σ 1 and the à-trous; one
/// frame and the EMA), each with the tile baked for it.
pub fn cells(rows: &[Row]) -> Vec<Cell> {
    let mut out = Vec::new();
    for spp in EMA_SPPS {
        for integrand in ["ao", "shadow"] {
            for (k, denoiser, tag) in [(1, "gauss σ1", "gauss σ1"), (3, "à-trous 3", "à-trous 3")]
            {
                for mode in ["frame", "ema"] {
                    let tile = if mode == "ema" {
                        format!("tile ({tag}, ema)")
                    } else {
                        format!("tile ({tag})")
                    };
                    let find = |name: &str| {
                        rows.iter().find(|r| {
                            r.sampler == name
                                && r.spp == spp
                                && r.integrand == integrand
                                && r.mode == mode
                        })
                    };
                    let Some(t) = find(&tile) else { continue };
                    let Some(best) = PEERS
                        .iter()
                        .filter_map(|p| find(p))
                        .min_by(|a, b| a.rmse[k].total_cmp(&b.rmse[k]))
                    else {
                        continue;
                    };
                    out.push(Cell {
                        spp,
                        integrand: integrand.into(),
                        denoiser: denoiser.into(),
                        mode: mode.into(),
                        tile,
                        tile_rmse: t.rmse[k],
                        best: best.sampler.clone(),
                        best_rmse: best.rmse[k],
                        margin_percent: 100.0 * (1.0 - t.rmse[k] / best.rmse[k]),
                    });
                }
            }
        }
    }
    out
}

/// The cells as text.
pub fn describe_cells(cells: &[Cell]) -> Vec<String> {
    let mut out = vec![format!(
        "  {:>4} {:<7} {:<10} {:<6} {:>9}  {:>9} {:<40} {:>7}",
        "spp", "", "denoiser", "mode", "tile", "best peer", "", "margin"
    )];
    for c in cells {
        out.push(format!(
            "  {:>4} {:<7} {:<10} {:<6} {:>9.5}  {:>9.5} {:<40} {:>+6.1}%",
            c.spp,
            c.integrand,
            c.denoiser,
            c.mode,
            c.tile_rmse,
            c.best_rmse,
            c.best,
            c.margin_percent
        ));
    }
    out
}

/// The report.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// The scene.
    pub scene: String,
    /// Its triangles.
    pub triangles: usize,
    /// Image size.
    pub size: [usize; 2],
    /// Pixels that see a surface (the errors are over these).
    pub surface_pixels: usize,
    /// The denoisers, in the order of every row's errors.
    pub denoisers: Vec<String>,
    /// The reference.
    pub reference: Reference,
    /// The tracer's incoherent rays per second on this machine's threads
    /// ([`crate::render::ray_rate`]).
    pub rays_per_second: f64,
    /// Threads.
    pub threads: usize,
    /// Seconds in all.
    pub seconds: f64,
    /// Every measurement.
    pub rows: Vec<Row>,
    /// The tiles' goal, cell by cell ([`cells`]; empty without the peers).
    pub cells: Vec<Cell>,
}

/// A sampler entry: how it reads, and what it costs a game.
pub struct Entry {
    /// Its name.
    pub name: String,
    /// `baked`, `published`, `free` or `white`.
    pub family: &'static str,
    /// The lookup.
    pub f: Box<dyn Fn(i32, i32, u32, u32) -> [f32; 4] + Sync>,
}

/// A 128 × 128 tile's lookup through the runtime's view for `spp` samples per frame, its
/// pairs flagged in `sobol_pairs` running Sobol.
pub fn tile_sampler(
    keys: Vec<u16>,
    spp: u32,
    sobol_pairs: u8,
) -> Box<dyn Fn(i32, i32, u32, u32) -> [f32; 4] + Sync> {
    use noise_runtime::{Mask3, SamplerTile};
    let bytes: &'static [u8] = Vec::leak(keys.iter().flat_map(|k| k.to_le_bytes()).collect());
    macro_rules! view {
        ($($spp:literal)*) => {
            match spp {
                $($spp => {
                    let t = SamplerTile::<128, 128, $spp, 4>::new(Mask3::new(bytes), sobol_pairs);
                    Box::new(move |x, y, f, i| {
                        let a = t.sample2(x, y, f, i, 0);
                        let b = t.sample2(x, y, f, i, 2);
                        [a[0], a[1], b[0], b[1]]
                    })
                })*
                _ => panic!("no view for {spp} spp"),
            }
        };
    }
    view!(1 2 4 8 16)
}

/// The tile for `spp` baked with the spec keys `keys` (through the workspace cache), named
/// `name`.
fn tile(spp: u32, name: &str, keys: &str, log: &mut dyn FnMut(&str)) -> Result<Entry, String> {
    let text = format!(
        "[[texture]]\nname = \"tile\"\nkind = \"sampler\"\ndims = [128, 128]\nseed = 1\nspp = {spp}\nsample_dims = 4\nsample_space = [\"cosine_hemisphere\", \"square\"]\n{keys}\n"
    );
    let s = build_assets::spec::parse_toml(&text)
        .map_err(|e| e.render("render", &text))?
        .textures
        .remove(0);
    let (t, secs, cached) = super::kit::bake_texture(&s, log)?;
    if !cached {
        log(&format!("  baked `{name}` at {spp} spp in {secs:.1} s"));
    }
    let keys = t
        .data
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    let sobol_pairs = match &s.kind {
        build_assets::spec::Kind::Sampler(p) => p.sobol_pairs(),
        _ => 0,
    };
    Ok(Entry {
        name: name.to_string(),
        family: "baked",
        f: tile_sampler(keys, spp, sobol_pairs),
    })
}

/// The tiles measured: a name, the spec keys it is baked with, and whether it is baked for
/// an EMA (baked at the spp values with an EMA run only). Dimensions 0–1 are
/// `cosine_hemisphere` (the AO and bounce directions), 2–3 `square` (the light).
pub const TILES: [(&str, &str, bool); 4] = [
    (
        "tile (gauss σ1)",
        "spatial_filter = { kind = \"gauss\", sigma = 1 }",
        false,
    ),
    (
        "tile (à-trous 3)",
        "spatial_filter = { kind = \"atrous\", passes = 3 }",
        false,
    ),
    (
        "tile (gauss σ1, ema)",
        "spatial_filter = { kind = \"gauss\", sigma = 1 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1 }",
        true,
    ),
    (
        "tile (à-trous 3, ema)",
        "spatial_filter = { kind = \"atrous\", passes = 3 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1 }",
        true,
    ),
];

/// Every sampler at `spp` samples per frame, for `frames` frames.
pub fn samplers(spp: u32, frames: u32, log: &mut dyn FnMut(&str)) -> Result<Vec<Entry>, String> {
    let mut out = Vec::new();
    let ema = frames > ONE_FRAME_FRAMES;
    for (name, keys, for_ema) in TILES {
        if !for_ema || ema {
            out.push(tile(spp, name, keys, log)?);
        }
    }
    #[cfg(feature = "peers")]
    out.extend(peers::heitz(spp));
    #[cfg(feature = "peers")]
    out.push(peers::openqmc());
    out.push(Entry {
        name: "rd_ign_r2 (free)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| sampler::rd_ign_r2::<4>(x, y, f * spp + i)),
    });
    out.push(Entry {
        name: "ign_r2 (free)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| sampler::ign_r2::<4>(x, y, f * spp + i)),
    });
    out.push(Entry {
        name: "sobol_owen (free)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| sampler::sobol_owen::<4>(x, y, f * spp + i, 1)),
    });
    let z = crate::zsobol::ZSobol::new(SIZE[0].max(SIZE[1]), spp * frames, 7);
    out.push(Entry {
        name: "ZSobol (Ahmed-Wonka 2020)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| {
            let k = f * spp + i;
            [
                z.sample(x, y, k, 0),
                z.sample(x, y, k, 1),
                z.sample(x, y, k, 2),
                z.sample(x, y, k, 3),
            ]
        }),
    });
    out.push(Entry {
        name: "white".into(),
        family: "white",
        f: Box::new(move |x, y, f, i| {
            let k = ((f * spp + i) * 4) as i32;
            core::array::from_fn(|d| {
                noise_runtime::sequence::to_unit(noise_runtime::hash::hash3(x, y, k + d as i32, 99))
            })
        }),
    });
    Ok(out)
}

#[cfg(feature = "peers")]
mod peers {
    use super::Entry;

    /// Heitz et al. 2019's published sampling function over one of their tables.
    fn table(
        sobol: &'static [i32],
        scrambling: &'static [i32],
        ranking: &'static [i32],
        spp: u32,
    ) -> Box<dyn Fn(i32, i32, u32, u32) -> [f32; 4] + Sync> {
        Box::new(move |x, y, f, i| {
            let (x, y) = ((x & 127) as usize, (y & 127) as usize);
            let index = ((f * spp + i) & 255) as usize;
            core::array::from_fn(|d| {
                let ranked = index ^ ranking[d + (x + y * 128) * 8] as usize;
                let v = sobol[d + ranked * 256] ^ scrambling[(d % 8) + (x + y * 128) * 8];
                (0.5 + v as f32) / 256.0
            })
        })
    }

    /// The table made for `spp` (read by frame: sample `f·spp + i`), and the 256-spp table
    /// read progressively.
    pub fn heitz(spp: u32) -> Vec<Entry> {
        use blue_noise_sampler as b;
        let matched: Option<(&[i32], &[i32], &[i32])> = match spp {
            1 => Some((
                b::spp1::SOBOL,
                b::spp1::SCRAMBLING_TILE,
                b::spp1::RANKING_TILE,
            )),
            2 => Some((
                b::spp2::SOBOL,
                b::spp2::SCRAMBLING_TILE,
                b::spp2::RANKING_TILE,
            )),
            4 => Some((
                b::spp4::SOBOL,
                b::spp4::SCRAMBLING_TILE,
                b::spp4::RANKING_TILE,
            )),
            8 => Some((
                b::spp8::SOBOL,
                b::spp8::SCRAMBLING_TILE,
                b::spp8::RANKING_TILE,
            )),
            16 => Some((
                b::spp16::SOBOL,
                b::spp16::SCRAMBLING_TILE,
                b::spp16::RANKING_TILE,
            )),
            _ => None,
        };
        let mut out = Vec::new();
        if let Some((s, sc, r)) = matched {
            out.push(Entry {
                name: "Heitz 2019 (table for this spp)".into(),
                family: "published",
                f: table(s, sc, r, spp),
            });
        }
        out.push(Entry {
            name: "Heitz 2019 (256-spp table, progressive)".into(),
            family: "published",
            f: table(
                b::spp256::SOBOL,
                b::spp256::SCRAMBLING_TILE,
                b::spp256::RANKING_TILE,
                spp,
            ),
        });
        out
    }

    /// OpenQMC's rank-1 lattice blue-noise sampler (openqmc-rs), frame and sample as its own
    /// arguments.
    pub fn openqmc() -> Entry {
        Entry {
            name: "OpenQMC lattice bn".into(),
            family: "published",
            f: Box::new(|x, y, f, i| {
                openqmc::LatticeBnSampler::new(x, y, f as i32, i as i32).draw_sample_f32::<4>()
            }),
        }
    }
}

/// The reference: the mean of `replicates` renders of `spp / replicates` samples of Sobol's
/// sequence, Owen-scrambled per pixel, replicate and dimension; and each replicate, for its
/// standard error.
pub fn reference(
    scene: &Scene,
    tracer: &Tracer,
    g: &GBuffer,
    spp: u32,
    replicates: u32,
    seed: u32,
) -> ([Vec<f32>; 3], Vec<[Vec<f32>; 3]>) {
    let per = spp / replicates;
    let points: Vec<[u32; 4]> = (0..per)
        .map(|i| core::array::from_fn(|d| sampler::sobol(i, d)))
        .collect();
    let reps: Vec<[Vec<f32>; 3]> = (0..replicates)
        .map(|r| {
            // Owen-scrambled Sobol points (Burley 2020), each pixel, replicate and dimension
            // scrambled by its own seed: each replicate is an unbiased estimate that
            // converges as a net does, the replicates are independent, and their spread is
            // the reference's error. The unscrambled points are tabulated once.
            let f = |x: i32, y: i32, _: u32, i: u32| {
                let pixel = noise_runtime::hash::hash3(x, y, r as i32, 0x5eed ^ seed);
                let p = &points[i as usize];
                core::array::from_fn(|d| {
                    noise_runtime::sequence::to_unit(sampler::owen(
                        p[d],
                        noise_runtime::hash::hash2(pixel as i32, d as i32, 0x0c3e),
                    ))
                })
            };
            render_frame(scene, tracer, g, per, 0, &f).0
        })
        .collect();
    let n = g.width * g.height;
    let mean: [Vec<f32>; 3] = core::array::from_fn(|c| {
        (0..n)
            .map(|p| reps.iter().map(|r| r[c][p]).sum::<f32>() / replicates as f32)
            .collect()
    });
    (mean, reps)
}

/// The reference's standard error after `filter`: per pixel, the spread of the filtered
/// replicates about the filtered mean over `√(R(R − 1))`; RMS over surface pixels.
pub fn standard_error(mean: &[f32], reps: &[&[f32]], filter: &Filter, hit: &[bool]) -> f64 {
    let fm = filter.apply(mean);
    let r = reps.len() as f64;
    let mut sum = 0.0;
    for rep in reps {
        let fr = filter.apply(rep);
        for p in 0..fm.len() {
            if hit[p] {
                sum += ((fr[p] - fm[p]) as f64).powi(2);
            }
        }
    }
    let pixels = hit.iter().filter(|&&h| h).count() as f64;
    (sum / (r * (r - 1.0)) / pixels).sqrt()
}

/// RMSE over surface pixels of `filter(err)`.
fn rmse2(err: &[f32], filter: &Filter, hit: &[bool], pixels: f64) -> f64 {
    filter
        .apply(err)
        .iter()
        .zip(hit)
        .filter(|(_, h)| **h)
        .map(|(e, _)| (*e as f64).powi(2))
        .sum::<f64>()
        / pixels
}

/// What one sampler run measured: per integrand and denoiser, the mean squared error of
/// single frames and of the EMA; and the rays traced.
pub struct Measured {
    /// One frame, `[integrand][denoiser]`.
    pub frame: [[f64; 4]; 3],
    /// Under the EMA (zero when not run).
    pub ema: [[f64; 4]; 3],
    /// Rays traced.
    pub rays: u64,
}

/// Runs `sampler` at `spp` for `frames` frames: one-frame errors over `one_frame` frames
/// (or [`MEASURED`] when `ema`), and under the EMA when `ema`.
#[allow(clippy::too_many_arguments)]
pub fn measure(
    scene: &Scene,
    tracer: &Tracer,
    g: &GBuffer,
    filters: &[Filter],
    reference: &[Vec<f32>; 3],
    sampler: Sampler<'_>,
    spp: u32,
    ema: bool,
) -> Measured {
    let pixels = g.surface_pixels() as f64;
    let (frames, counted) = if ema {
        (FRAMES, MEASURED)
    } else {
        (ONE_FRAME_FRAMES, 0..ONE_FRAME_FRAMES)
    };
    let n = g.width * g.height;
    let mut history: [Vec<f32>; 3] = core::array::from_fn(|_| vec![0.0; n]);
    let mut out = Measured {
        frame: [[0.0; 4]; 3],
        ema: [[0.0; 4]; 3],
        rays: 0,
    };
    let count = (counted.end - counted.start) as f64;
    for f in 0..frames {
        let (est, rays) = render_frame(scene, tracer, g, spp, f, sampler);
        out.rays += rays;
        let err: [Vec<f32>; 3] = core::array::from_fn(|c| {
            est[c]
                .iter()
                .zip(&reference[c])
                .map(|(e, r)| e - r)
                .collect()
        });
        for c in 0..3 {
            if f == 0 {
                history[c].clone_from(&err[c]);
            } else {
                for (h, e) in history[c].iter_mut().zip(&err[c]) {
                    *h += ALPHA * (e - *h);
                }
            }
        }
        if counted.contains(&f) {
            let sums: Vec<(usize, usize, f64, f64)> = (0..3)
                .flat_map(|c| (0..filters.len()).map(move |k| (c, k)))
                .collect::<Vec<_>>()
                .into_par_iter()
                .map(|(c, k)| {
                    let one = rmse2(&err[c], &filters[k], &g.hit, pixels);
                    let acc = if ema {
                        rmse2(&history[c], &filters[k], &g.hit, pixels)
                    } else {
                        0.0
                    };
                    (c, k, one, acc)
                })
                .collect();
            for (c, k, one, acc) in sums {
                out.frame[c][k] += one / count;
                out.ema[c][k] += acc / count;
            }
        }
    }
    out
}

/// What a moving camera sees: per pan, the view's G-buffer, its reference and its filters.
pub struct Panned {
    views: Vec<(GBuffer, [Vec<f32>; 3], Vec<Filter>)>,
}

impl Panned {
    /// The views of every pan `0 … PAN` cut from the widened G-buffer and reference.
    pub fn new(wide: &GBuffer, reference: &[Vec<f32>; 3], width: usize) -> Panned {
        Panned {
            views: (0..=PAN)
                .map(|x0| {
                    let g = wide.crop(x0, width);
                    let r = core::array::from_fn(|c| {
                        crate::render::crop(&reference[c], wide.width, x0, width)
                    });
                    let f = DENOISERS.iter().map(|&d| Filter::new(d, &g)).collect();
                    (g, r, f)
                })
                .collect(),
        }
    }
}

/// `sampler` at `spp` with the camera panning ([`pan`]) and the EMA's history reprojected
/// ([`reproject`]): the squared errors of the history over [`MEASURED`], and the rays traced.
/// The sampler is read in screen space, as a game reads it.
pub fn measure_moving(
    scene: &Scene,
    tracer: &Tracer,
    panned: &Panned,
    sampler: Sampler<'_>,
    spp: u32,
) -> ([[f64; 4]; 3], u64) {
    let mut history: Option<[Vec<f32>; 3]> = None;
    let mut out = [[0.0; 4]; 3];
    let mut rays = 0;
    let count = (MEASURED.end - MEASURED.start) as f64;
    for f in 0..FRAMES {
        let (g, refr, filters) = &panned.views[pan(f)];
        let (est, r) = render_frame(scene, tracer, g, spp, f, sampler);
        rays += r;
        let err: [Vec<f32>; 3] =
            core::array::from_fn(|c| est[c].iter().zip(&refr[c]).map(|(e, r)| e - r).collect());
        let next = match history.take() {
            None => err,
            Some(h) => {
                let delta = pan(f) as isize - pan(f - 1) as isize;
                core::array::from_fn(|c| reproject(&h[c], &err[c], g.width, delta, ALPHA))
            }
        };
        if MEASURED.contains(&f) {
            let pixels = g.surface_pixels() as f64;
            for (c, o) in out.iter_mut().enumerate() {
                for (k, v) in o.iter_mut().enumerate() {
                    *v += rmse2(&next[c], &filters[k], &g.hit, pixels) / count;
                }
            }
        }
        history = Some(next);
    }
    (out, rays)
}

/// What the numbers measure.
pub const READING: &str = "\
RMSE over the pixels that see a surface of filter(estimate - reference), for AO (dims 0-1,
  cosine-weighted r = sqrt(u), phi = 2 pi v), an area light's soft shadow (dims 2-3) and one
  diffuse bounce with next-event estimation (dims 0-3); after none / Gaussian sigma 1 / box 5x5 /
  a-trous of 3 passes weighted by the G-buffer. frame: one frame (mean over frames); ema: an EMA
  with alpha 0.1 over 64 frames, frames 32-63; moving (4 spp, for information): the same EMA
  with the camera panning 2 px a frame right and back over 16 px, the history reprojected and
  reset where disoccluded. `tile (F)`: a 128x128 sampler tile baked for F.";

/// Runs the report on `scene` and writes `render.json`, `render.png` and the images into `out`.
pub fn run(scene: &Scene, out: &Path, log: &mut dyn FnMut(&str)) -> Result<Report, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let start = Instant::now();
    let tracer = Tracer::new(&scene.triangles);
    let [w, h] = SIZE;
    // One G-buffer and reference for the view widened by the moving camera's pan; the static
    // camera's are their first columns.
    let wide = GBuffer::panned(scene, &tracer, SIZE, w + PAN);
    let g = wide.crop(0, w);
    let filters: Vec<Filter> = DENOISERS.iter().map(|&d| Filter::new(d, &g)).collect();
    log(&format!(
        "  scene `{}`: {} triangles, {w}x{h}, {} pixels see a surface",
        scene.name,
        scene.triangles.len(),
        g.surface_pixels()
    ));
    let (bench_rays, bench_seconds) = crate::render::ray_rate(scene, &tracer, &g, 32);
    let rays_per_second = bench_rays as f64 / bench_seconds.max(1e-9);
    log(&format!(
        "  tracer: {:.1} million incoherent rays per second on {} threads ({bench_rays} rays of 32 white-noise samples per pixel: AO/bounce, shadow and next-event rays)",
        rays_per_second / 1e6,
        rayon::current_num_threads()
    ));
    let t = Instant::now();
    let (wide_ref, wide_reps) = reference(scene, &tracer, &wide, REFERENCE_SPP, REPLICATES, 0);
    let ref_seconds = t.elapsed().as_secs_f64();
    let cut = |v: &[Vec<f32>; 3]| -> [Vec<f32>; 3] {
        core::array::from_fn(|c| crate::render::crop(&v[c], wide.width, 0, w))
    };
    let refr = cut(&wide_ref);
    let reps: Vec<[Vec<f32>; 3]> = wide_reps.iter().map(cut).collect();
    let panned = Panned::new(&wide, &wide_ref, w);
    let standard: Vec<[f64; 4]> = (0..3)
        .map(|c| {
            let r: Vec<&[f32]> = reps.iter().map(|r| r[c].as_slice()).collect();
            core::array::from_fn(|k| standard_error(&refr[c], &r, &filters[k], &g.hit))
        })
        .collect();
    log(&format!(
        "  reference: {REFERENCE_SPP} spp ({REPLICATES} replicates) in {ref_seconds:.1} s; standard error AO {}, shadow {}, bounce {} (none / gauss / box / a-trous)",
        fmt4(&standard[0]),
        fmt4(&standard[1]),
        fmt4(&standard[2])
    ));
    let mut rows = Vec::new();
    let (mut rays, mut trace_seconds) = (0u64, 0.0f64);
    log(&header());
    for spp in SPPS {
        let ema = EMA_SPPS.contains(&spp);
        for e in samplers(spp, if ema { FRAMES } else { ONE_FRAME_FRAMES }, log)? {
            let t = Instant::now();
            let m = measure(scene, &tracer, &g, &filters, &refr, &*e.f, spp, ema);
            rays += m.rays;
            let moving = if MOVING_SPPS.contains(&spp) {
                let (errs, r) = measure_moving(scene, &tracer, &panned, &*e.f, spp);
                rays += r;
                Some(errs)
            } else {
                None
            };
            trace_seconds += t.elapsed().as_secs_f64();
            let mut modes: Vec<(&str, &[[f64; 4]; 3])> = vec![("frame", &m.frame)];
            if ema {
                modes.push(("ema", &m.ema));
            }
            if let Some(errs) = &moving {
                modes.push(("moving", errs));
            }
            for (mode, errs) in modes {
                for c in 0..3 {
                    let row = Row {
                        sampler: e.name.clone(),
                        family: e.family.to_string(),
                        spp,
                        mode: mode.to_string(),
                        integrand: INTEGRANDS[c].to_string(),
                        rmse: errs[c].map(f64::sqrt),
                    };
                    rows.push(row);
                }
                log(&line(&rows[rows.len() - 3..]));
            }
        }
    }
    log(&format!(
        "  the samplers traced {:.2e} rays in {trace_seconds:.1} s, sampling and filtering included ({:.1} million per second)",
        rays as f64,
        rays as f64 / trace_seconds.max(1e-9) / 1e6
    ));
    // The reference's error adds to every error measured (in squares): say how large it is
    // beside the smallest.
    for (c, name) in INTEGRANDS.iter().enumerate() {
        let worst = (0..4)
            .filter_map(|k| {
                let least = rows
                    .iter()
                    .filter(|r| r.integrand == *name)
                    .map(|r| r.rmse[k])
                    .fold(f64::INFINITY, f64::min);
                (least > 0.0).then(|| standard[c][k] / least)
            })
            .fold(0.0, f64::max);
        log(&format!(
            "  {name}: the reference's standard error is at most {:.0} % of the smallest error measured after any denoiser",
            100.0 * worst
        ));
    }
    let report = Report {
        scene: scene.name.clone(),
        triangles: scene.triangles.len(),
        size: SIZE,
        surface_pixels: g.surface_pixels(),
        denoisers: DENOISERS.iter().map(|d| d.name()).collect(),
        reference: Reference {
            spp: REFERENCE_SPP,
            replicates: REPLICATES,
            standard_error: standard,
            seconds: ref_seconds,
        },
        rays_per_second,
        threads: rayon::current_num_threads(),
        seconds: start.elapsed().as_secs_f64(),
        cells: cells(&rows),
        rows,
    };
    if !report.cells.is_empty() {
        log(
            "  the tile baked for each cell against the best of rd_ign_r2, Heitz 2019 (both tables), ZSobol and sobol_owen:",
        );
        for l in describe_cells(&report.cells) {
            log(&l);
        }
    }
    let json = serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?;
    std::fs::write(out.join("render.json"), json).map_err(|e| e.to_string())?;
    images(scene, &tracer, &g, &refr, &filters, out)?;
    plot(&report, &out.join("render.png"))?;
    Ok(report)
}

fn fmt4(v: &[f64; 4]) -> String {
    format!("{:.5}/{:.5}/{:.5}/{:.5}", v[0], v[1], v[2], v[3])
}

/// The table's header line.
pub fn header() -> String {
    format!(
        "  {:<40} {:>4} {:>6}  {:>27}  {:>27}  {:>27}",
        "sampler",
        "spp",
        "mode",
        "AO: gauss / box / a-trous",
        "shadow: gauss/box/a-trous",
        "bounce: gauss/box/a-trous"
    )
}

/// One sampler, spp and mode as text (the three integrands' rows).
pub fn line(rows: &[Row]) -> String {
    let e = |r: &Row| format!("{:.5} {:.5} {:.5}", r.rmse[1], r.rmse[2], r.rmse[3]);
    format!(
        "  {:<40} {:>4} {:>6}  {:>27}  {:>27}  {:>27}",
        rows[0].sampler,
        rows[0].spp,
        rows[0].mode,
        e(&rows[0]),
        e(&rows[1]),
        e(&rows[2])
    )
}

/// The reference AO, one 4-spp estimate of white noise and of the first tile, and each one's
/// error after the à-trous, as grey PNGs (errors: mid-grey is 0, ±0.25 is black / white).
fn images(
    scene: &Scene,
    tracer: &Tracer,
    g: &GBuffer,
    refr: &[Vec<f32>; 3],
    filters: &[Filter],
    out: &Path,
) -> Result<(), String> {
    let save = |name: &str, v: &[f32], scale: f32, offset: f32| -> Result<(), String> {
        let px: Vec<u8> = v
            .iter()
            .map(|x| ((x * scale + offset).clamp(0.0, 1.0) * 255.0).round() as u8)
            .collect();
        image::GrayImage::from_raw(g.width as u32, g.height as u32, px)
            .ok_or("image size")?
            .save(out.join(name))
            .map_err(|e| format!("{name}: {e}"))
    };
    save("render-reference-ao.png", &refr[0], 1.0, 0.0)?;
    save("render-reference-shadow.png", &refr[1], 1.0, 0.0)?;
    let atrous = filters.last().expect("the à-trous");
    let mut quiet = |_: &str| {};
    let list = samplers(4, 1, &mut quiet)?;
    for (tag, e) in [
        ("white", list.iter().find(|e| e.family == "white")),
        ("tile", list.first()),
    ] {
        let Some(e) = e else { continue };
        let (est, _) = render_frame(scene, tracer, g, 4, 0, &*e.f);
        save(&format!("render-{tag}-ao-4spp.png"), &est[0], 1.0, 0.0)?;
        let err: Vec<f32> = est[0].iter().zip(&refr[0]).map(|(a, b)| a - b).collect();
        save(
            &format!("render-{tag}-ao-4spp-atrous-error.png"),
            &atrous.apply(&err),
            2.0,
            0.5,
        )?;
    }
    Ok(())
}

/// AO error after the à-trous on one frame against spp, one line per sampler, log scale.
fn plot(r: &Report, path: &Path) -> Result<(), String> {
    use crate::export::plot::{Labels, PALETTE, Series, line_plot};
    let mut names: Vec<&str> = Vec::new();
    for row in &r.rows {
        if !names.contains(&row.sampler.as_str()) {
            names.push(&row.sampler);
        }
    }
    let series: Vec<Series> = names
        .iter()
        .enumerate()
        .map(|(i, name)| Series {
            label: name.to_string(),
            color: PALETTE[i % PALETTE.len()],
            points: r
                .rows
                .iter()
                .filter(|row| row.sampler == *name && row.mode == "frame" && row.integrand == "ao")
                .map(|row| (row.spp as f64, row.rmse[3]))
                .collect(),
        })
        .collect();
    let labels = Labels {
        title: format!("{}: AO error after the à-trous, one frame", r.scene),
        x: "samples per pixel".into(),
        y: "RMSE (log scale)".into(),
    };
    line_plot(path, &series, &labels, true).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pan moves [`PAN_SPEED`] pixels a frame and stays within `0 … PAN`.
    #[test]
    fn the_pan_sweeps_and_returns() {
        for f in 0..200u32 {
            assert!(pan(f) <= PAN);
            if f > 0 {
                assert_eq!(pan(f).abs_diff(pan(f - 1)), PAN_SPEED, "frame {f}");
            }
        }
        assert_eq!((pan(0), pan(PAN as u32 / PAN_SPEED as u32)), (0, PAN));
    }

    /// Reprojection follows the picture: a history that is a crop of a fixed world image at
    /// one pan, blended with the crop at the next pan, is that crop wherever the pixel was in
    /// view, and restarts from the new frame where it was not.
    #[test]
    fn reprojection_follows_the_pan() {
        let (stride, width, height) = (40usize, 24usize, 3usize);
        let world: Vec<f32> = (0..stride * height).map(|i| (i * 7 % 13) as f32).collect();
        for (from, to) in [(4usize, 6usize), (10, 8)] {
            let h = crate::render::crop(&world, stride, from, width);
            let now = crate::render::crop(&world, stride, to, width);
            let noisy: Vec<f32> = now.iter().map(|v| v + 100.0).collect();
            let delta = to as isize - from as isize;
            let r = reproject(&h, &noisy, width, delta, 0.25);
            for (i, (&got, &want)) in r.iter().zip(&now).enumerate() {
                let x = (i % width) as isize + delta;
                if (0..width as isize).contains(&x) {
                    assert_eq!(got, want + 25.0, "pixel {i}: the same world point, blended");
                } else {
                    assert_eq!(got, want + 100.0, "pixel {i}: disoccluded, restarted");
                }
            }
        }
    }
}
