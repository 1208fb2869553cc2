//! `noisebake report sampler`: several samples per pixel. Baked sampler tiles (kind `sampler`)
//! against Heitz et al. 2019's published tables and OpenQMC's blue-noise samplers (feature
//! `peers`: `blue-noise-sampler`, `openqmc-rs`), Ahmed & Wonka 2020's
//! hierarchical pixel ordering (ZSobol, [`crate::zsobol`]), the free samplers
//! (`sampler::r2_pairs`, `sampler::rd_ign_r2`, `sampler::sobol_owen`) and white noise, at 1, 2, 4, 8 and 16 spp.
//!
//! The measure: each pixel of a 256×256 image (twice the 128×128 tile in each direction, so the
//! tile's wrap is seen) estimates the integral over `[0, 1]²` of test integrands with the mean of
//! its `spp` samples of one pair of dimensions; the error image of each integrand goes through a
//! filter (none, Gaussian σ 1 and σ 2, box 5×5, toroidal) and the RMSE is taken over pixels and
//! integrands. Integrands: random half-planes (visibility edges, discontinuous) and smooth
//! products of quadratics, drawn from a seed of their own (never the training edges of the
//! generator). Dimensions 0–1 and 2–3 are measured apart.

use crate::export::plot::{Labels, PALETTE, Series, line_plot};
use build_assets::generate::sampler as gen_sampler;
use build_assets::spec::fast::Filter;
use build_assets::spec::sampler::SamplerParams;
use noise_runtime::sampler;
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// The tile's side.
pub const TILE: usize = 128;
/// The measured image's side (two tiles).
pub const IMAGE: usize = 256;
/// Dimensions of the baked tiles.
pub const SAMPLE_DIMS: u32 = 4;
/// The seed of the test integrands (never the generator's training edges).
pub const TEST_SEED: u64 = 0x7e57;
/// Samples per pixel measured.
pub const SPPS: [u32; 5] = [1, 2, 4, 8, 16];
/// Filters applied to the error images, by name.
pub const FILTERS: [(&str, Filter); 4] = [
    ("none", Filter::None),
    ("gauss σ1", Filter::Gauss { sigma: 1.0 }),
    ("gauss σ2", Filter::Gauss { sigma: 2.0 }),
    ("box 5x5", Filter::Box { size: 5 }),
];

/// A test integrand over `[0, 1]²` with its exact integral.
#[derive(Clone, Copy, Debug)]
pub enum Integrand {
    /// `a·u + b·v < c`.
    Edge { a: f64, b: f64, c: f64 },
    /// `(1 + p (u − q)²)(1 + r (v − s)²)`.
    Smooth { p: f64, q: f64, r: f64, s: f64 },
}

impl Integrand {
    /// The value at `(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> f64 {
        match *self {
            Integrand::Edge { a, b, c } => (a * u + b * v < c) as u8 as f64,
            Integrand::Smooth { p, q, r, s } => {
                (1.0 + p * (u - q) * (u - q)) * (1.0 + r * (v - s) * (v - s))
            }
        }
    }

    /// The exact integral over the unit square.
    pub fn integral(&self) -> f64 {
        match *self {
            Integrand::Edge { a, b, c } => gen_sampler::half_plane_area(a, b, c),
            Integrand::Smooth { p, q, r, s } => {
                // ∫₀¹ (x − q)² dx = 1/3 − q + q².
                let m = |w: f64| 1.0 / 3.0 - w + w * w;
                (1.0 + p * m(q)) * (1.0 + r * m(s))
            }
        }
    }
}

/// Test integrands: `edges` half-planes and `smooth` products, from `seed`.
pub fn integrands(edges: usize, smooth: usize, seed: u64) -> Vec<Integrand> {
    let mut rng = build_assets::generate::rng::SplitMix64::new(seed);
    let mut out = Vec::with_capacity(edges + smooth);
    for _ in 0..edges {
        let e = gen_sampler::random_edge(&mut rng);
        out.push(Integrand::Edge {
            a: e[0],
            b: e[1],
            c: e[2],
        });
    }
    for _ in 0..smooth {
        out.push(Integrand::Smooth {
            p: 4.0 * rng.unit_f64() - 1.0,
            q: rng.unit_f64(),
            r: 4.0 * rng.unit_f64() - 1.0,
            s: rng.unit_f64(),
        });
    }
    out
}

/// A sampler as measured: dimension `d` of sample `i` of pixel `(x, y)` in frame 0.
pub type Lookup<'a> = &'a (dyn Fn(i32, i32, u32, u32) -> f32 + Sync);

/// RMSE after each of [`FILTERS`] (and the per-pixel RMSE, unfiltered, is the first) of the
/// `spp`-sample estimates of `ints` with dimensions `pair` of `f`.
pub fn measure(f: Lookup<'_>, spp: u32, pair: [u32; 2], ints: &[Integrand]) -> [f64; 4] {
    let n = IMAGE;
    let taps: Vec<Vec<f64>> = FILTERS.iter().map(|(_, f)| f.taps()).collect();
    let points: Vec<Vec<(f64, f64)>> = (0..n * n)
        .into_par_iter()
        .map(|p| {
            let (x, y) = ((p % n) as i32, (p / n) as i32);
            (0..spp)
                .map(|i| (f(x, y, i, pair[0]) as f64, f(x, y, i, pair[1]) as f64))
                .collect()
        })
        .collect();
    let sums: Vec<[f64; 4]> = ints
        .par_iter()
        .map(|g| {
            let truth = g.integral();
            let err: Vec<f64> = points
                .iter()
                .map(|ps| ps.iter().map(|&(u, v)| g.eval(u, v)).sum::<f64>() / spp as f64 - truth)
                .collect();
            let mut s = [0.0; 4];
            for (k, t) in taps.iter().enumerate() {
                let e = crate::analysis::filtered::blur(&err, n, n, t);
                s[k] = e.iter().map(|v| v * v).sum::<f64>();
            }
            s
        })
        .collect();
    let count = (ints.len() * n * n) as f64;
    let mut out = [0.0; 4];
    for s in &sums {
        for k in 0..4 {
            out[k] += s[k];
        }
    }
    out.map(|v| (v / count).sqrt())
}

/// One sampler at one spp.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The sampler.
    pub sampler: String,
    /// What it is: `baked`, `published`, `free` or `white`.
    pub family: String,
    /// Samples per pixel.
    pub spp: u32,
    /// Bytes a game ships for it (0: computed in the shader).
    pub bytes: usize,
    /// Bake seconds (baked tiles), on this machine's threads.
    pub bake_seconds: Option<f64>,
    /// Dimensions 0–1: RMSE unfiltered (per pixel), Gaussian σ 1, σ 2, box 5×5.
    pub dims01: [f64; 4],
    /// Dimensions 2–3, the same.
    pub dims23: [f64; 4],
}

/// The report.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// What the numbers measure.
    pub measure: String,
    /// Every sampler at every spp.
    pub rows: Vec<Row>,
}

/// What the numbers measure.
pub const READING: &str = "\
RMSE of the per-pixel mean of spp samples of 256 half-planes (visibility edges) and 64 smooth
  integrands, 256x256 pixels over a 128x128 tile, after each filter (toroidal); dims 0-1 and 2-3
  apart. `tile (F)`: a sampler tile baked for that spp and filter F (kind `sampler`,
  sample_dims 4). bytes: what a game ships (0: computed in the shader).";

/// A baked tile's lookup through the runtime's view for `spp` (the view's `SPP` sets which
/// points a frame takes, so it must be the one the tile was baked for), in frame 0; the
/// tiles here are `square` in every pair, so every pair runs Sobol.
pub fn tile_lookup(keys: Vec<u16>, spp: u32) -> Box<dyn Fn(i32, i32, u32, u32) -> f32 + Sync> {
    use noise_runtime::{Mask3, SamplerTile};
    let bytes: &'static [u8] = Vec::leak(keys.iter().flat_map(|k| k.to_le_bytes()).collect());
    macro_rules! view {
        ($($spp:literal)*) => {
            match spp {
                $($spp => {
                    let t = SamplerTile::<128, 128, $spp, 4>::new(Mask3::new(bytes), 0b11);
                    Box::new(move |x, y, i, d| t.sample(x, y, 0, i, d))
                })*
                _ => panic!("no view for {spp} spp"),
            }
        };
    }
    view!(1 2 4 8 16)
}

/// Bakes the tile of `spp` for `spatial`; returns the keys and the seconds it took.
pub fn bake(spp: u32, spatial: Filter, seed: u64) -> (Vec<u16>, f64) {
    let p = SamplerParams {
        spp,
        sample_dims: SAMPLE_DIMS,
        sample_space: vec![build_assets::spec::sampler::PairSpace::Square; 2],
        spatial,
        temporal: build_assets::spec::fast::TemporalFilter::None,
        frames: 1,
    };
    let t = Instant::now();
    let (keys, _) = gen_sampler::generate(&p, TILE, TILE, seed, &mut |_, _| {});
    (keys, t.elapsed().as_secs_f64())
}

/// Heitz et al. 2019's sampler for the table made for `spp` (the `blue-noise-sampler` crate).
#[cfg(feature = "peers")]
fn heitz(spp: u32) -> Option<impl Fn(i32, i32, u32, u32) -> f32 + Sync> {
    use blue_noise_sampler as b;
    let (sobol, scrambling, ranking): (&[i32], &[i32], &[i32]) = match spp {
        1 => (
            b::spp1::SOBOL,
            b::spp1::SCRAMBLING_TILE,
            b::spp1::RANKING_TILE,
        ),
        2 => (
            b::spp2::SOBOL,
            b::spp2::SCRAMBLING_TILE,
            b::spp2::RANKING_TILE,
        ),
        4 => (
            b::spp4::SOBOL,
            b::spp4::SCRAMBLING_TILE,
            b::spp4::RANKING_TILE,
        ),
        8 => (
            b::spp8::SOBOL,
            b::spp8::SCRAMBLING_TILE,
            b::spp8::RANKING_TILE,
        ),
        16 => (
            b::spp16::SOBOL,
            b::spp16::SCRAMBLING_TILE,
            b::spp16::RANKING_TILE,
        ),
        _ => return None,
    };
    // The published sampling function (Heitz et al. 2019, supplemental code).
    Some(move |x: i32, y: i32, i: u32, d: u32| {
        let (x, y) = ((x & 127) as usize, (y & 127) as usize);
        let (i, d) = ((i & 255) as usize, (d & 255) as usize);
        let ranked = i ^ ranking[d + (x + y * 128) * 8] as usize;
        let v = sobol[d + ranked * 256] ^ scrambling[(d % 8) + (x + y * 128) * 8];
        (0.5 + v as f32) / 256.0
    })
}

/// Runs the report, writes `sampler.json` and `sampler.png` into `out`.
pub fn run(out: &Path, log: &mut dyn FnMut(&str)) -> Result<Report, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let ints = integrands(256, 64, TEST_SEED);
    let mut rows = Vec::new();
    log(&header());
    let mut push = |rows: &mut Vec<Row>,
                    name: &str,
                    family: &str,
                    spp: u32,
                    bytes: usize,
                    bake_seconds: Option<f64>,
                    f: Lookup<'_>| {
        let row = Row {
            sampler: name.to_string(),
            family: family.to_string(),
            spp,
            bytes,
            bake_seconds,
            dims01: measure(f, spp, [0, 1], &ints),
            dims23: measure(f, spp, [2, 3], &ints),
        };
        log(&line(&row));
        rows.push(row);
    };
    for spp in SPPS {
        for (label, spatial) in [
            ("tile (gauss σ1)", Filter::Gauss { sigma: 1.0 }),
            ("tile (box 5x5)", Filter::Box { size: 5 }),
        ] {
            let (keys, secs) = bake(spp, spatial, 1);
            let bytes = keys.len() * 2;
            let f = tile_lookup(keys, spp);
            push(&mut rows, label, "baked", spp, bytes, Some(secs), &*f);
        }
        #[cfg(feature = "peers")]
        if let Some(f) = heitz(spp) {
            push(
                &mut rows,
                "Heitz 2019 (table for this spp)",
                "published",
                spp,
                320 * 1024,
                None,
                &f,
            );
        }
        #[cfg(feature = "peers")]
        {
            // OpenQMC's blue-noise samplers (openqmc-rs): per-pixel key and rank tables of
            // 256 × 256 pixels (u32 each) over Owen-scrambled Sobol and a rank-1 lattice,
            // dimensions 0-3 of the root domain.
            use openqmc::{LatticeBnSampler, SobolBnSampler};
            let sobol = |x: i32, y: i32, i: u32, d: u32| {
                SobolBnSampler::new(x, y, 0, i as i32).draw_sample_f32::<4>()[d as usize]
            };
            push(
                &mut rows,
                "OpenQMC sobol bn",
                "published",
                spp,
                512 * 1024,
                None,
                &sobol,
            );
            let lattice = |x: i32, y: i32, i: u32, d: u32| {
                LatticeBnSampler::new(x, y, 0, i as i32).draw_sample_f32::<4>()[d as usize]
            };
            push(
                &mut rows,
                "OpenQMC lattice bn",
                "published",
                spp,
                512 * 1024,
                None,
                &lattice,
            );
        }
        let pairs = |x: i32, y: i32, i: u32, d: u32| sampler::r2_pairs::<4>(x, y, i)[d as usize];
        push(&mut rows, "r2_pairs (free)", "free", spp, 0, None, &pairs);
        let rd = |x: i32, y: i32, i: u32, d: u32| sampler::rd_ign_r2::<4>(x, y, i)[d as usize];
        push(&mut rows, "rd_ign_r2 (free)", "free", spp, 0, None, &rd);
        let so = |x: i32, y: i32, i: u32, d: u32| sampler::sobol_owen::<4>(x, y, i, 1)[d as usize];
        push(&mut rows, "sobol_owen (free)", "free", spp, 0, None, &so);
        let z = crate::zsobol::ZSobol::new(IMAGE, spp, 7);
        let zs = |x: i32, y: i32, i: u32, d: u32| z.sample(x, y, i, d);
        push(
            &mut rows,
            "ZSobol (Ahmed-Wonka 2020)",
            "free",
            spp,
            0,
            None,
            &zs,
        );
        let white = |x: i32, y: i32, i: u32, d: u32| {
            let h = noise_runtime::hash::hash3(x, y, (i * 4 + d) as i32, 99);
            noise_runtime::sequence::to_unit(h)
        };
        push(&mut rows, "white", "white", spp, 0, None, &white);
    }
    let r = Report {
        measure: READING.into(),
        rows,
    };
    let json = serde_json::to_string_pretty(&r).map_err(|e| e.to_string())?;
    std::fs::write(out.join("sampler.json"), json).map_err(|e| e.to_string())?;
    plot(&r, &out.join("sampler.png"))?;
    Ok(r)
}

/// The table's header line.
pub fn header() -> String {
    format!(
        "  {:<32} {:>4} {:>8} {:>7}  {:>31}  {:>31}",
        "sampler",
        "spp",
        "bytes",
        "bake s",
        "dims 0-1: none/σ1/σ2/box5",
        "dims 2-3: none/σ1/σ2/box5"
    )
}

/// One row as text.
pub fn line(r: &Row) -> String {
    let e = |v: &[f64; 4]| format!("{:.4} {:.4} {:.4} {:.4}", v[0], v[1], v[2], v[3]);
    format!(
        "  {:<32} {:>4} {:>8} {:>7}  {:>31}  {:>31}",
        r.sampler,
        r.spp,
        r.bytes,
        r.bake_seconds.map_or("-".into(), |s| format!("{s:.1}")),
        e(&r.dims01),
        e(&r.dims23)
    )
}

/// RMSE after Gaussian σ 1 against spp, one line per sampler (dims 0–1), log scale.
fn plot(r: &Report, path: &Path) -> Result<(), String> {
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
                .filter(|row| row.sampler == *name)
                .map(|row| (row.spp as f64, row.dims01[1]))
                .collect(),
        })
        .collect();
    let labels = Labels {
        title: "several samples per pixel: error after a Gaussian σ 1, dims 0-1".into(),
        x: "samples per pixel".into(),
        y: "RMSE (log scale)".into(),
    };
    line_plot(path, &series, &labels, true).map(|_| ())
}
