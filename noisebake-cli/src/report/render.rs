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
//! filter they are baked for), its free samplers (`r2_pairs`, the per-pair R2 lattice that is the bar; `rd_ign_r2`, `ign_r2`, `sobol_owen`), Ahmed
//! and Wonka's ZSobol, white noise, and with `--features peers` Heitz et al. 2019's tables
//! (the one for that spp, and the 256-spp table read progressively, sample `f·spp + i`, as
//! NVIDIA's NRD sample reads it by frame) and OpenQMC's lattice blue-noise sampler.

use crate::render::denoise::{Denoiser, Filter};
use crate::render::motion::{Motion, Reprojection};
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
/// Samples per pixel measured on one frame (with `--full`, [`FULL_SPPS`]).
pub const SPPS: [u32; 3] = [1, 4, 16];
/// Samples per pixel a `--full` run measures on one frame.
pub const FULL_SPPS: [u32; 5] = [1, 2, 4, 8, 16];
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
/// Samples per pixel per frame measured with the camera moving.
pub const MOVING_SPPS: [u32; 3] = [1, 4, 16];
/// Samplers only a `--full` run measures (superseded by `r2_pairs`, or not a goal's peer).
pub const FULL_ONLY: [&str; 2] = ["ign_r2 (free)", "OpenQMC lattice bn"];

/// What a run measures. The default fits the report's time on 2 cores; `full` adds 2 and 8
/// spp, the samplers of [`FULL_ONLY`], every sampler of [`MOVING`] under the moving cameras,
/// and the per-pixel anchor experiment ([`crate::render::anchor`]) on them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// Everything.
    pub full: bool,
    /// Only the samplers whose names contain one of these (all when empty), for a quick look
    /// at a few; the goal tables need the peers and the tiles.
    pub only: Vec<String>,
}

impl Options {
    /// Samples per pixel measured on one frame.
    pub fn spps(&self) -> &'static [u32] {
        if self.full { &FULL_SPPS } else { &SPPS }
    }

    /// Whether the run measures the sampler `name`.
    pub fn measures(&self, name: &str) -> bool {
        (self.full || !FULL_ONLY.contains(&name))
            && (self.only.is_empty() || self.only.iter().any(|o| name.contains(o.as_str())))
    }

    /// Whether the run measures the sampler `name` with the camera moving, and through an
    /// anchor.
    pub fn moves(&self, name: &str) -> Option<bool> {
        MOVING
            .iter()
            .find(|m| m.name == name && (self.full || m.default))
            .map(|m| m.anchor && self.full)
    }
}
/// The moving cameras: a sub-pixel pan in a diagonal direction, and a truck with a dolly
/// (parallax, magnification, disocclusion); then three motions held out from the search
/// behind `motion_pairs` (which saw pans of up to 4 pixels a frame in a model): a fast pan, a
/// yaw and a dolly.
pub const MOTIONS: [Motion; 5] = [
    Motion::Pan {
        velocity: [1.6, 0.7],
        sweep: 20,
    },
    Motion::Parallax {
        truck: 0.03,
        dolly: 0.04,
        sweep: 16,
    },
    Motion::Pan {
        velocity: [-4.3, 2.1],
        sweep: 8,
    },
    Motion::Yaw {
        turn: 0.012,
        sweep: 16,
    },
    Motion::Dolly {
        speed: 0.05,
        sweep: 20,
    },
];
/// A moving camera's reference: samples per pixel of each frame's, in two replicates whose
/// difference measures its own error ([`Moving`]).
pub const MOVING_REFERENCE_SPP: u32 = 64;
/// A sampler measured with the camera moving.
pub struct MovingSampler {
    /// Its name.
    pub name: &'static str,
    /// Measured by a default run (else by `--full` only).
    pub default: bool,
    /// With `--full`, also read through a per-pixel [`crate::render::anchor::Anchor`]
    /// (`… + anchor`).
    pub anchor: bool,
}

const fn moving(name: &'static str, default: bool, anchor: bool) -> MovingSampler {
    MovingSampler {
        name,
        default,
        anchor,
    }
}

/// The samplers measured with the camera moving, at every spp of [`MOVING_SPPS`]: by default
/// the free samplers `motion_pairs` and `r2_pairs`, the Gaussian tiles (the one optimised for
/// one frame, which is all a table keeps under motion, and the one optimised for the EMA),
/// Heitz's tables and white noise; with `--full` the others too.
pub const MOVING: [MovingSampler; 12] = [
    moving("motion_pairs (free)", true, false),
    moving("tile (gauss σ1)", true, false),
    moving("tile (à-trous 3)", false, false),
    moving("tile (gauss σ1, ema)", true, true),
    moving("tile (à-trous 3, ema)", false, true),
    moving("r2_pairs (free)", true, true),
    moving("rd_ign_r2 (free)", false, false),
    moving("Heitz 2019 (table for this spp)", true, false),
    moving("Heitz 2019 (256-spp table, progressive)", true, true),
    moving("ZSobol (Ahmed-Wonka 2020)", false, false),
    moving("sobol_owen (free)", false, false),
    moving("white", true, false),
];

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
    /// `frame` (one frame, averaged over frames), `ema` (accumulated), or a motion's name
    /// (`pan`, `parallax`: accumulated with the camera moving and the history reprojected).
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

/// The peers a tile must beat: the free sampler built for motion (`motion_pairs`), the free
/// per-pair R2 lattice (`r2_pairs`) and `rd_ign_r2`,
/// Heitz et al. 2019's tables, ZSobol and per-pixel Owen-scrambled Sobol.
pub const PEERS: [&str; 7] = [
    "motion_pairs (free)",
    "r2_pairs (free)",
    "rd_ign_r2 (free)",
    "Heitz 2019 (table for this spp)",
    "Heitz 2019 (256-spp table, progressive)",
    "ZSobol (Ahmed-Wonka 2020)",
    "sobol_owen (free)",
];

/// The row of `sampler` at `spp`, `integrand` and `mode`.
fn find<'a>(
    rows: &'a [Row],
    sampler: &str,
    spp: u32,
    integrand: &str,
    mode: &str,
) -> Option<&'a Row> {
    rows.iter().find(|r| {
        r.sampler == sampler && r.spp == spp && r.integrand == integrand && r.mode == mode
    })
}

/// The row of the [`PEERS`] with the least error after denoiser `k`.
fn best_peer<'a>(
    rows: &'a [Row],
    spp: u32,
    integrand: &str,
    mode: &str,
    k: usize,
) -> Option<&'a Row> {
    PEERS
        .iter()
        .filter_map(|p| find(rows, p, spp, integrand, mode))
        .min_by(|a, b| a.rmse[k].total_cmp(&b.rmse[k]))
}

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
                    let Some(t) = find(rows, &tile, spp, integrand, mode) else {
                        continue;
                    };
                    let Some(best) = best_peer(rows, spp, integrand, mode, k) else {
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

/// One cell of the moving-camera goal: the EMA tile baked for the cell, with the camera
/// moving, against its own still-camera EMA error and the best peer under the same motion.
#[derive(Clone, Debug, Serialize)]
pub struct MovingCell {
    /// Samples per pixel per frame.
    pub spp: u32,
    /// `ao` or `shadow`.
    pub integrand: String,
    /// `gauss σ1` or `à-trous 3`.
    pub denoiser: String,
    /// `pan` or `parallax`.
    pub motion: String,
    /// The tile baked for this cell (its EMA tile).
    pub tile: String,
    /// Its error with the camera moving.
    pub tile_rmse: f64,
    /// Its error with the camera still (the `ema` row).
    pub still_rmse: f64,
    /// How much more error the motion leaves, in percent of the still error.
    pub rise_percent: f64,
    /// The best peer under the motion.
    pub best: String,
    /// Its error.
    pub best_rmse: f64,
    /// How much less error the tile leaves than the best peer, in percent (negative: more).
    pub margin_percent: f64,
}

/// The moving-camera goal's cells, at every spp measured both still under the EMA and moving.
pub fn moving_cells(rows: &[Row]) -> Vec<MovingCell> {
    let mut out = Vec::new();
    for spp in EMA_SPPS {
        for motion in MOTIONS.map(|m| m.name()) {
            for integrand in ["ao", "shadow"] {
                for (k, denoiser) in [(1, "gauss σ1"), (3, "à-trous 3")] {
                    let tile = format!("tile ({denoiser}, ema)");
                    let (Some(t), Some(still)) = (
                        find(rows, &tile, spp, integrand, motion),
                        find(rows, &tile, spp, integrand, "ema"),
                    ) else {
                        continue;
                    };
                    let Some(best) = best_peer(rows, spp, integrand, motion, k) else {
                        continue;
                    };
                    out.push(MovingCell {
                        spp,
                        integrand: integrand.into(),
                        denoiser: denoiser.into(),
                        motion: motion.into(),
                        tile,
                        tile_rmse: t.rmse[k],
                        still_rmse: still.rmse[k],
                        rise_percent: 100.0 * (t.rmse[k] / still.rmse[k] - 1.0),
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

/// One cell of the goal of the sampler built for motion: `motion_pairs` against `r2_pairs` and
/// against the best table (the tiles and Heitz et al. 2019's two tables) under one
/// camera (`ema`: still), at one spp, for one integrand and denoiser.
#[derive(Clone, Debug, Serialize)]
pub struct MotionCell {
    /// Samples per pixel per frame.
    pub spp: u32,
    /// `ao` or `shadow`.
    pub integrand: String,
    /// `gauss σ1` or `à-trous 3`.
    pub denoiser: String,
    /// `ema` (the still camera) or a motion's name.
    pub camera: String,
    /// `motion_pairs`'s error.
    pub motion_pairs: f64,
    /// `r2_pairs`'s error.
    pub r2_pairs: f64,
    /// How much less error `motion_pairs` leaves than `r2_pairs`, percent (negative: more).
    pub vs_r2_pairs: f64,
    /// The best table under the same camera.
    pub table: String,
    /// Its error.
    pub table_rmse: f64,
    /// How much less error `motion_pairs` leaves than that table, percent (negative: more).
    pub vs_table: f64,
}

/// The tables `motion_pairs` is held against (each where measured).
pub const TABLES: [&str; 6] = [
    "tile (gauss σ1)",
    "tile (à-trous 3)",
    "tile (gauss σ1, ema)",
    "tile (à-trous 3, ema)",
    "Heitz 2019 (table for this spp)",
    "Heitz 2019 (256-spp table, progressive)",
];

/// `motion_pairs`'s cells: every spp measured under the EMA, the still camera and each motion.
pub fn motion_cells(rows: &[Row]) -> Vec<MotionCell> {
    let mut out = Vec::new();
    let cameras: Vec<&str> = std::iter::once("ema")
        .chain(MOTIONS.iter().map(|m| m.name()))
        .collect();
    for spp in MOVING_SPPS {
        for &camera in &cameras {
            for integrand in ["ao", "shadow"] {
                for (k, denoiser) in [(1, "gauss σ1"), (3, "à-trous 3")] {
                    let (Some(m), Some(r)) = (
                        find(rows, "motion_pairs (free)", spp, integrand, camera),
                        find(rows, "r2_pairs (free)", spp, integrand, camera),
                    ) else {
                        continue;
                    };
                    let Some(t) = TABLES
                        .iter()
                        .filter_map(|t| find(rows, t, spp, integrand, camera))
                        .min_by(|a, b| a.rmse[k].total_cmp(&b.rmse[k]))
                    else {
                        continue;
                    };
                    out.push(MotionCell {
                        spp,
                        integrand: integrand.into(),
                        denoiser: denoiser.into(),
                        camera: camera.into(),
                        motion_pairs: m.rmse[k],
                        r2_pairs: r.rmse[k],
                        vs_r2_pairs: 100.0 * (1.0 - m.rmse[k] / r.rmse[k]),
                        table: t.sampler.clone(),
                        table_rmse: t.rmse[k],
                        vs_table: 100.0 * (1.0 - m.rmse[k] / t.rmse[k]),
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
    /// The moving cameras: per motion, its name, mean motion of the pixels that keep their
    /// history (pixels a frame) and the share of surface pixels reset a frame.
    pub motions: Vec<MotionSummary>,
    /// The moving-camera goal, cell by cell ([`moving_cells`]).
    pub moving_cells: Vec<MovingCell>,
    /// `motion_pairs` against `r2_pairs` and the best table, cell by cell ([`motion_cells`]).
    pub motion_cells: Vec<MotionCell>,
    /// Every tile's bake, measured beside its estimate.
    pub bakes: Vec<BakeTime>,
    /// Whether this was a `--full` run.
    pub full: bool,
}

/// A moving camera as measured.
#[derive(Clone, Debug, Serialize)]
pub struct MotionSummary {
    /// `pan` or `parallax`.
    pub motion: String,
    /// The mean motion of the pixels that keep their history, pixels a frame.
    pub mean_motion: f64,
    /// The share of surface pixels whose history resets, per frame.
    pub reset_share: f64,
}

/// A sampler entry: how it reads, and what it costs a game.
pub struct Entry {
    /// Its name.
    pub name: String,
    /// `baked`, `published`, `free` or `white`.
    pub family: &'static str,
    /// The lookup.
    pub f: Box<dyn Fn(i32, i32, u32, u32) -> [f32; 4] + Sync>,
    /// For a baked tile, what its bake took and what was announced for it.
    pub bake: Option<BakeTime>,
}

/// A tile's bake: measured and estimated seconds on this machine's threads.
#[derive(Clone, Debug, Serialize)]
pub struct BakeTime {
    /// The tile.
    pub tile: String,
    /// Its samples per pixel.
    pub spp: u32,
    /// Seconds it took (0 when read from the cache).
    pub seconds: f64,
    /// Whether it was read from the cache.
    pub cached: bool,
    /// What `build_assets::generate::estimate` announces for it, seconds.
    pub estimate: f64,
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
    let estimate = build_assets::generate::estimate::estimate(&s).seconds;
    if !cached {
        log(&format!(
            "  baked `{name}` at {spp} spp in {secs:.1} s (estimated {estimate:.1} s)"
        ));
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
        bake: Some(BakeTime {
            tile: name.to_string(),
            spp,
            seconds: if cached { 0.0 } else { secs },
            cached,
            estimate,
        }),
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

/// Every sampler at `spp` samples per frame, for `frames` frames; of the tiles, only those
/// `bake` accepts are baked.
pub fn samplers(
    spp: u32,
    frames: u32,
    bake: &dyn Fn(&str) -> bool,
    log: &mut dyn FnMut(&str),
) -> Result<Vec<Entry>, String> {
    let mut out = Vec::new();
    let ema = frames > ONE_FRAME_FRAMES;
    for (name, keys, for_ema) in TILES {
        if (!for_ema || ema) && bake(name) {
            out.push(tile(spp, name, keys, log)?);
        }
    }
    #[cfg(feature = "peers")]
    out.extend(peers::heitz(spp));
    #[cfg(feature = "peers")]
    out.push(peers::openqmc());
    out.push(Entry {
        name: "motion_pairs (free)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| sampler::motion_pairs::<4>(x, y, f, i, spp)),
        bake: None,
    });
    out.push(Entry {
        name: "r2_pairs (free)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| sampler::r2_pairs::<4>(x, y, f * spp + i)),
        bake: None,
    });
    out.push(Entry {
        name: "rd_ign_r2 (free)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| sampler::rd_ign_r2::<4>(x, y, f * spp + i)),
        bake: None,
    });
    out.push(Entry {
        name: "ign_r2 (free)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| sampler::ign_r2::<4>(x, y, f * spp + i)),
        bake: None,
    });
    out.push(Entry {
        name: "sobol_owen (free)".into(),
        family: "free",
        f: Box::new(move |x, y, f, i| sampler::sobol_owen::<4>(x, y, f * spp + i, 1)),
        bake: None,
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
        bake: None,
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
        bake: None,
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
                bake: None,
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
            bake: None,
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
            bake: None,
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

/// A moving camera, traced: every frame's G-buffer, reprojection and filters, its reference,
/// and the floor its reference's own error adds.
pub struct Moving {
    /// The motion.
    pub motion: Motion,
    frames: Vec<(GBuffer, Option<Reprojection>, Vec<Filter>)>,
    reference: Vec<[Vec<f32>; 3]>,
    /// Per integrand and denoiser, the mean square of the reference's own error through the
    /// same EMA over [`MEASURED`] (subtracted from every sampler's).
    pub floor: [[f64; 4]; 3],
    /// The share of surface pixels whose history resets, per frame on average.
    pub reset_share: f64,
    /// The mean motion of the pixels that keep their history, pixels a frame.
    pub mean_motion: f64,
}

impl Moving {
    /// Traces `motion` over [`FRAMES`] at [`SIZE`], with each frame's reference of
    /// [`MOVING_REFERENCE_SPP`] samples in two replicates. The error of the EMA against the
    /// mean of the replicates is the sampler's plus the reference's, independent of each other;
    /// half the replicates' difference has the reference's error's spread, so its EMA's mean
    /// square (the floor) is subtracted.
    pub fn new(scene: &Scene, tracer: &Tracer, motion: Motion) -> Moving {
        let path = crate::render::motion::path(scene, tracer, motion, SIZE, FRAMES);
        let mut frames = Vec::new();
        let mut references = Vec::new();
        let mut floor = [[0.0; 4]; 3];
        let mut history: Option<[Vec<f32>; 3]> = None;
        let (mut resets, mut moved) = (0.0, 0.0);
        let count = (MEASURED.end - MEASURED.start) as f64;
        for (f, (_, g, rep)) in path.into_iter().enumerate() {
            let (mean, reps) = reference(scene, tracer, &g, MOVING_REFERENCE_SPP, 2, f as u32 + 1);
            let half: [Vec<f32>; 3] = core::array::from_fn(|c| {
                reps[0][c]
                    .iter()
                    .zip(&reps[1][c])
                    .map(|(a, b)| 0.5 * (a - b))
                    .collect()
            });
            let next = match (history.take(), &rep) {
                (Some(h), Some(r)) => core::array::from_fn(|c| r.blend(&h[c], &half[c], ALPHA)),
                _ => half,
            };
            let filters: Vec<Filter> = DENOISERS.iter().map(|&d| Filter::new(d, &g)).collect();
            if MEASURED.contains(&(f as u32)) {
                let pixels = g.surface_pixels() as f64;
                for (c, o) in floor.iter_mut().enumerate() {
                    for (k, v) in o.iter_mut().enumerate() {
                        *v += rmse2(&next[c], &filters[k], &g.hit, pixels) / count;
                    }
                }
            }
            if let Some(r) = &rep {
                resets += r.reset_share(&g.hit);
                moved += r.mean_motion(&g.hit, g.width);
            }
            history = Some(next);
            references.push(mean);
            frames.push((g, rep, filters));
        }
        let n = (FRAMES - 1) as f64;
        Moving {
            motion,
            frames,
            reference: references,
            floor,
            reset_share: resets / n,
            mean_motion: moved / n,
        }
    }
}

/// `sampler` at `spp` with the camera moving and the EMA's history reprojected: the mean
/// squared errors of the history over [`MEASURED`] less the reference's floor, and the rays
/// traced. `anchored`: the sampler is read at each pixel's [`crate::render::anchor::Anchor`],
/// followed along the motion vectors; else at the screen pixel, as a
/// game reads a table today.
pub fn measure_moving(
    scene: &Scene,
    tracer: &Tracer,
    moving: &Moving,
    sampler: Sampler<'_>,
    spp: u32,
    anchored: bool,
) -> ([[f64; 4]; 3], u64) {
    use crate::render::anchor::{Anchor, follow_frame};
    let [w, h] = SIZE;
    let mut history: Option<[Vec<f32>; 3]> = None;
    let mut anchors = vec![Anchor::START; w * h];
    let mut next_anchors = anchors.clone();
    let mut out = [[0.0; 4]; 3];
    let mut rays = 0;
    let count = (MEASURED.end - MEASURED.start) as f64;
    for (f, (g, rep, filters)) in moving.frames.iter().enumerate() {
        let f = f as u32;
        if let (true, Some(r)) = (anchored, rep) {
            follow_frame(&anchors, &r.prev, w as u32, h as u32, &mut next_anchors);
            std::mem::swap(&mut anchors, &mut next_anchors);
        }
        let (est, r) = if anchored {
            let a = &anchors;
            let read = |x: i32, y: i32, f: u32, i: u32| {
                let [ax, ay] = a[y as usize * w + x as usize].pixel(x, y);
                sampler(ax, ay, f, i)
            };
            render_frame(scene, tracer, g, spp, f, &read)
        } else {
            render_frame(scene, tracer, g, spp, f, sampler)
        };
        rays += r;
        let refr = &moving.reference[f as usize];
        let err: [Vec<f32>; 3] =
            core::array::from_fn(|c| est[c].iter().zip(&refr[c]).map(|(e, r)| e - r).collect());
        let next = match (history.take(), rep) {
            (Some(h), Some(r)) => core::array::from_fn(|c| r.blend(&h[c], &err[c], ALPHA)),
            _ => err,
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
    for (o, fl) in out.iter_mut().zip(&moving.floor) {
        for (v, f) in o.iter_mut().zip(fl) {
            *v = (*v - f).max(0.0);
        }
    }
    (out, rays)
}

/// What the numbers measure.
pub const READING: &str = "\
RMSE over the pixels that see a surface of filter(estimate - reference), for AO (dims 0-1,
  cosine-weighted r = sqrt(u), phi = 2 pi v), an area light's soft shadow (dims 2-3) and one
  diffuse bounce with next-event estimation (dims 0-3); after none / Gaussian sigma 1 / box 5x5 /
  a-trous of 3 passes weighted by the G-buffer. frame: one frame (mean over frames); ema: an EMA
  with alpha 0.1 over 64 frames, frames 32-63; pan / parallax / fast pan / yaw / dolly: the
  same EMA with the camera moving, every frame traced anew, the history reprojected bilinearly
  along the motion vectors and reset where a depth / normal test rejects it (pan: the image
  moves (1.6, 0.7) px a frame out and back; parallax: the eye trucks and dollies, near surfaces
  move more, surfaces disocclude; fast pan (-4.3, 2.1) px a frame, yaw and dolly: motions the
  search behind motion_pairs never saw), against 64-spp references of each frame whose own
  error is subtracted. `tile (F)`: a 128x128 sampler tile baked for F.";

/// Runs the report on `scene` and writes `render.json`, `render.png` and the images into `out`.
pub fn run(
    scene: &Scene,
    out: &Path,
    options: Options,
    log: &mut dyn FnMut(&str),
) -> Result<Report, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let start = Instant::now();
    let tracer = Tracer::new(&scene.triangles);
    let [w, h] = SIZE;
    let g = GBuffer::new(scene, &tracer, w, h, [0, 0]);
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
    let (refr, reps) = reference(scene, &tracer, &g, REFERENCE_SPP, REPLICATES, 0);
    let ref_seconds = t.elapsed().as_secs_f64();
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
    let t = Instant::now();
    let moving: Vec<Moving> = MOTIONS
        .iter()
        .map(|&m| Moving::new(scene, &tracer, m))
        .collect();
    for m in &moving {
        log(&format!(
            "  moving camera `{}`: {:.2} px a frame on average, {:.2} % of surface pixels reset a frame; reference {MOVING_REFERENCE_SPP} spp a frame, floor AO {}, shadow {}",
            m.motion.name(),
            m.mean_motion,
            100.0 * m.reset_share,
            fmt4(&m.floor[0].map(f64::sqrt)),
            fmt4(&m.floor[1].map(f64::sqrt)),
        ));
    }
    log(&format!(
        "  the moving cameras traced and referenced in {:.1} s",
        t.elapsed().as_secs_f64()
    ));
    let mut rows = Vec::new();
    let mut bakes = Vec::new();
    let (mut rays, mut trace_seconds) = (0u64, 0.0f64);
    log(&header());
    for &spp in options.spps() {
        let ema = EMA_SPPS.contains(&spp);
        let list = samplers(
            spp,
            if ema { FRAMES } else { ONE_FRAME_FRAMES },
            &|name| options.measures(name),
            log,
        )?;
        for e in list {
            if !options.measures(&e.name) {
                continue;
            }
            bakes.extend(e.bake.clone());
            let t = Instant::now();
            let m = measure(scene, &tracer, &g, &filters, &refr, &*e.f, spp, ema);
            rays += m.rays;
            let mut modes: Vec<(String, String, [[f64; 4]; 3])> =
                vec![(e.name.clone(), "frame".into(), m.frame)];
            if ema {
                modes.push((e.name.clone(), "ema".into(), m.ema));
            }
            if let (true, Some(anchor)) = (MOVING_SPPS.contains(&spp), options.moves(&e.name)) {
                for mv in &moving {
                    for anchored in [false, true] {
                        if anchored && !anchor {
                            continue;
                        }
                        let (errs, r) = measure_moving(scene, &tracer, mv, &*e.f, spp, anchored);
                        rays += r;
                        let name = if anchored {
                            format!("{} + anchor", e.name)
                        } else {
                            e.name.clone()
                        };
                        modes.push((name, mv.motion.name().into(), errs));
                    }
                }
            }
            trace_seconds += t.elapsed().as_secs_f64();
            for (name, mode, errs) in modes {
                for c in 0..3 {
                    rows.push(Row {
                        sampler: name.clone(),
                        family: e.family.to_string(),
                        spp,
                        mode: mode.clone(),
                        integrand: INTEGRANDS[c].to_string(),
                        rmse: errs[c].map(f64::sqrt),
                    });
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
        moving_cells: moving_cells(&rows),
        motion_cells: motion_cells(&rows),
        motions: moving
            .iter()
            .map(|m| MotionSummary {
                motion: m.motion.name().into(),
                mean_motion: m.mean_motion,
                reset_share: m.reset_share,
            })
            .collect(),
        bakes,
        full: options.full,
        rows,
    };
    if !report.cells.is_empty() {
        log(
            "  the tile baked for each cell against the best of r2_pairs, rd_ign_r2, Heitz 2019 (both tables), ZSobol and sobol_owen:",
        );
        for l in describe_cells(&report.cells) {
            log(&l);
        }
    }
    if !report.moving_cells.is_empty() {
        log(
            "  with the camera moving: each EMA tile against its own still error and the best peer under the same motion:",
        );
        for c in &report.moving_cells {
            log(&format!(
                "  {:>4} {:<7} {:<10} {:<9} {:>9.5} (still {:.5}, {:>+6.1}%)  {:>9.5} {:<40} {:>+6.1}%",
                c.spp,
                c.integrand,
                c.denoiser,
                c.motion,
                c.tile_rmse,
                c.still_rmse,
                c.rise_percent,
                c.best_rmse,
                c.best,
                c.margin_percent
            ));
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
    let list = samplers(4, 1, &|_| true, &mut quiet)?;
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

/// The report as the Markdown document `docs/measured/render.md` is: the stamp, the goal's
/// cells still and moving, every row, and the bakes beside their estimates.
pub fn markdown(r: &Report, stamp: &super::stamp::Stamp) -> String {
    use std::fmt::Write;
    let mut s = stamp.header("Samplers in a ray-traced scene (`noisebake report render`)");
    let _ = writeln!(
        s,
        "\nScene `{}` ({} triangles), {}×{} pixels ({} see a surface); reference {} spp in {} replicates; the tracer ran {:.1} million rays per second; the report took {:.0} s{}. RMSE over the pixels that see a surface, after the denoiser named. Margins: how much less error the tile leaves than the best peer (r2_pairs, rd_ign_r2, Heitz 2019 both tables, ZSobol, sobol_owen), in percent of the peer's; negative means more.\n",
        r.scene,
        r.triangles,
        r.size[0],
        r.size[1],
        r.surface_pixels,
        r.reference.spp,
        r.reference.replicates,
        r.rays_per_second / 1e6,
        r.seconds,
        if r.full { " (`--full`)" } else { "" }
    );
    if !r.cells.is_empty() {
        s.push_str("## Camera still: the tile baked for each cell against the best peer\n\n");
        s.push_str("| spp | integrand | denoiser | mode | tile | best peer | its error | margin |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n");
        for c in &r.cells {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {:.5} | {} | {:.5} | {:+.1} % |",
                c.spp,
                c.integrand,
                c.denoiser,
                c.mode,
                c.tile_rmse,
                c.best,
                c.best_rmse,
                c.margin_percent
            );
        }
    }
    if !r.motions.is_empty() {
        s.push_str("\n## Camera moving: the EMA tile against its still error and the best peer under the motion\n\n");
        for m in &r.motions {
            let _ = writeln!(
                s,
                "- `{}`: the pixels that keep their history move {:.2} px a frame on average; {:.2} % of surface pixels reset a frame.",
                m.motion,
                m.mean_motion,
                100.0 * m.reset_share
            );
        }
        s.push_str("\n| spp | integrand | denoiser | motion | tile moving | tile still | rise | best peer | its error | margin |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
        for c in &r.moving_cells {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {:.5} | {:.5} | {:+.1} % | {} | {:.5} | {:+.1} % |",
                c.spp,
                c.integrand,
                c.denoiser,
                c.motion,
                c.tile_rmse,
                c.still_rmse,
                c.rise_percent,
                c.best,
                c.best_rmse,
                c.margin_percent
            );
        }
    }
    if !r.motion_cells.is_empty() {
        s.push_str("\n## The sampler built for motion: `motion_pairs` against `r2_pairs` and the best table\n\nEach cell under the EMA, the camera still (`ema`) or moving; the best table is the least error of the tiles (optimised for one frame or for the EMA) and Heitz et al. 2019's two tables under the same camera. Margins: how much less error `motion_pairs` leaves, in percent of the other's; negative means more.\n\n| spp | integrand | denoiser | camera | motion_pairs | r2_pairs | margin | best table | its error | margin |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
        for c in &r.motion_cells {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {:.5} | {:.5} | {:+.1} % | {} | {:.5} | {:+.1} % |",
                c.spp,
                c.integrand,
                c.denoiser,
                c.camera,
                c.motion_pairs,
                c.r2_pairs,
                c.vs_r2_pairs,
                c.table,
                c.table_rmse,
                c.vs_table
            );
        }
    }
    s.push_str("\n## Every sampler\n\nErrors after Gaussian σ 1 / box 5×5 / à-trous (3 passes).\n\n| sampler | spp | mode | AO | shadow | bounce |\n| --- | --- | --- | --- | --- | --- |\n");
    for rows in r.rows.chunks(3) {
        let e = |x: &Row| format!("{:.5} / {:.5} / {:.5}", x.rmse[1], x.rmse[2], x.rmse[3]);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} |",
            rows[0].sampler,
            rows[0].spp,
            rows[0].mode,
            e(&rows[0]),
            e(&rows[1]),
            e(&rows[2])
        );
    }
    let baked: Vec<&BakeTime> = r.bakes.iter().filter(|b| !b.cached).collect();
    if !baked.is_empty() {
        s.push_str("\n## Bakes\n\nEach tile's bake on this machine beside the estimate `gen` and build scripts announce.\n\n| tile | spp | measured | estimated | measured / estimated |\n| --- | --- | --- | --- | --- |\n");
        for b in baked {
            let _ = writeln!(
                s,
                "| {} | {} | {:.1} s | {:.1} s | {:.2} |",
                b.tile,
                b.spp,
                b.seconds,
                b.estimate,
                b.seconds / b.estimate.max(1e-9)
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(sampler: &str, spp: u32, mode: &str, integrand: &str, e: f64) -> Row {
        Row {
            sampler: sampler.into(),
            family: "x".into(),
            spp,
            mode: mode.into(),
            integrand: integrand.into(),
            rmse: [0.0, e, 0.0, e],
        }
    }

    /// A moving cell compares the EMA tile under the motion with its own still EMA row and
    /// with the best of the peers under the same motion, never a peer's still row.
    #[test]
    fn moving_cells_compare_like_with_like() {
        let rows = vec![
            row("tile (gauss σ1, ema)", 4, "ema", "ao", 1.0),
            row("tile (gauss σ1, ema)", 4, "pan", "ao", 1.5),
            row("r2_pairs (free)", 4, "pan", "ao", 2.0),
            row("Heitz 2019 (table for this spp)", 4, "pan", "ao", 1.2),
            row("Heitz 2019 (table for this spp)", 4, "ema", "ao", 0.1),
            row("white", 4, "pan", "ao", 0.5),
        ];
        let moving = moving_cells(&rows);
        assert_eq!(moving.len(), 1, "{moving:?}");
        let c = &moving[0];
        assert_eq!(
            (c.motion.as_str(), c.denoiser.as_str()),
            ("pan", "gauss σ1")
        );
        assert_eq!(c.best, "Heitz 2019 (table for this spp)");
        assert!((c.rise_percent - 50.0).abs() < 1e-9);
        assert!((c.margin_percent - 100.0 * (1.0 - 1.5 / 1.2)).abs() < 1e-9);
        // The still cells see only the still rows.
        let still = cells(&rows);
        assert_eq!(still.len(), 1, "{still:?}");
        assert_eq!((still[0].mode.as_str(), still[0].best_rmse), ("ema", 0.1));
    }
}
