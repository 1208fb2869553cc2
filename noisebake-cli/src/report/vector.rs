//! Which source of directions leaves the least error after the filter a game runs, measured
//! without trusting the optimiser (`noisebake report vector`): the vector counterpart of
//! [`super::compare`].
//!
//! **The measure.** Ambient-occlusion-like visibility integrands: a half-space occluder
//! `V(ω) = [a · ω < c]` for [`INTEGRANDS`] axes `a` spread over the sphere (a Fibonacci
//! spiral) and offsets `c` from −0.4 to 0.4. Every pixel estimates `∫ V` with one direction per
//! frame drawn from the row's source; each frame is filtered in space (toroidal), then an EMA
//! α 0.1 runs over the looping 32 frames to its steady state, and the RMSE against the true
//! integral (a 4096² midpoint rule through the same warp, within 1.2e-4) is taken over
//! integrands, pixels and the converged frames. Its standard error comes from the spread of 16
//! blocks of the image.
//!
//! **The rows.** Our FAST vector masks made for each filter (3D, and 2D read at an R2 offset
//! per frame), EA's published 2D vector textures (vendored in `testdata/ea-fast-bsd3/`) read the
//! same way, two values of our STBN, and the free constructions of
//! [`noise_runtime::sampler`] through the runtime's warp, PCG and white noise. Every row is
//! measured over the same 32 frames looped, the free constructions too (in a game they would
//! not loop, which can only help them after an EMA).

use super::kit::{bake, spec};
use crate::analysis::filtered::{Denoiser, filtered_rmse_integrands};
use build_assets::generate::fast::Filter;
use build_assets::spec::TextureSpec;
use noise_runtime::sequence::{r2_point, scale};
use noise_runtime::{hash, ldg, sampler, warp};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// Visibility integrands per measurement.
pub const INTEGRANDS: usize = 32;

/// The measured sizes: 128 × 128 × 32, the FAST paper's vector case.
pub const DIMS: [usize; 3] = [128, 128, 32];

/// A sample space of directions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Space {
    /// Cosine-weighted upper hemisphere (ambient occlusion, diffuse bounces).
    CosineHemisphere,
    /// The uniform unit sphere.
    Sphere,
}

impl Space {
    /// Its name in a spec's `sample_space`.
    pub fn name(self) -> &'static str {
        match self {
            Space::CosineHemisphere => "cosine_hemisphere",
            Space::Sphere => "sphere",
        }
    }

    /// The runtime's warp from two uniform values, as a game applies it.
    pub fn warp(self, u: f32, v: f32) -> [f32; 3] {
        match self {
            Space::CosineHemisphere => warp::cosine_hemisphere(u, v),
            Space::Sphere => warp::sphere_uniform(u, v),
        }
    }

    /// EA's published 2D texture for a filter (`testdata/ea-fast-bsd3/`).
    fn ea_file(self, filter: &str) -> String {
        let d = match self {
            Space::CosineHemisphere => "cosine",
            Space::Sphere => "uniform",
        };
        format!("sphere_{d}_{filter}.png")
    }
}

/// The spatial filters measured, each × plain EMA α 0.1: `(name, filter, EA's file suffix)`.
pub const FILTERS: [(&str, Filter, &str); 2] = [
    ("box 5x5", Filter::Box { size: 5 }, "box_5"),
    ("gauss σ 1", Filter::Gauss { sigma: 1.0 }, "gauss_1.0"),
];

/// The error of one row after one filter.
#[derive(Clone, Debug, Serialize)]
pub struct Error {
    /// The spatial filter (× EMA α 0.1).
    pub filter: String,
    /// RMSE over the visibility integrands, pixels and converged frames.
    pub rmse: f64,
    /// Its standard error (16 image blocks): differences within about twice the combined
    /// error are ties.
    pub se: f64,
}

/// One source's row.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The source.
    pub mask: String,
    /// `baked` (ours), `published` (EA's texture) or `free` (computed in the shader).
    pub kind: String,
    /// Bytes a game ships for it (0 for a free construction).
    pub bytes: usize,
    /// Seconds to bake it (or to compute all its directions); `None` for a published texture.
    pub seconds: Option<f64>,
    /// Whether the bake came from the cache (then `seconds` is the original bake's).
    pub cached: bool,
    /// The error after each filter of [`FILTERS`].
    pub errors: Vec<Error>,
}

/// The comparison of one sample space.
#[derive(Clone, Debug, Serialize)]
pub struct Table {
    /// The sample space.
    pub space: String,
    /// `[w, h, frames]`.
    pub dims: [usize; 3],
    /// One row per source.
    pub rows: Vec<Row>,
}

/// The visibility integrands: `(axis, offset)`.
fn integrands() -> Vec<([f64; 3], f64)> {
    let golden_angle = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..INTEGRANDS)
        .map(|j| {
            let z = 1.0 - (2 * j + 1) as f64 / INTEGRANDS as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = golden_angle * j as f64;
            let c = [-0.4, -0.2, 0.0, 0.2, 0.4][j % 5];
            ([r * phi.cos(), r * phi.sin(), z], c)
        })
        .collect()
}

/// The true value of every integrand under `space`'s distribution: a 4096² midpoint rule
/// through the warp (area-preserving, so the mean over the grid is the integral).
fn truths(space: Space, ints: &[([f64; 3], f64)]) -> Vec<f64> {
    use rayon::prelude::*;
    const N: usize = 4096;
    let counts: Vec<Vec<u32>> = (0..N)
        .into_par_iter()
        .map(|i| {
            let mut c = vec![0u32; ints.len()];
            for k in 0..N {
                let d = space.warp((i as f32 + 0.5) / N as f32, (k as f32 + 0.5) / N as f32);
                for (cj, (a, off)) in c.iter_mut().zip(ints) {
                    if dot(a, d) < *off {
                        *cj += 1;
                    }
                }
            }
            c
        })
        .collect();
    (0..ints.len())
        .map(|j| counts.iter().map(|c| c[j] as f64).sum::<f64>() / (N * N) as f64)
        .collect()
}

fn dot(a: &[f64; 3], d: [f32; 3]) -> f64 {
    a[0] * d[0] as f64 + a[1] * d[1] as f64 + a[2] * d[2] as f64
}

/// The errors of one source of directions (`w × h × t`, x fastest) after every filter.
pub fn measure(dirs: &[[f32; 3]], space: Space) -> Vec<Error> {
    let ints = integrands();
    let truth = truths(space, &ints);
    FILTERS
        .iter()
        .map(|(name, filter, _)| {
            let d = Denoiser {
                spatial: filter.taps(),
                ema_alpha: Some(0.1),
            };
            let (rmse, se) = filtered_rmse_integrands(DIMS, &d, ints.len(), &|j| {
                let (a, c) = ints[j];
                let v = dirs
                    .iter()
                    .map(|&w| if dot(&a, w) < c { 1.0 } else { 0.0 })
                    .collect();
                (v, truth[j])
            });
            Error {
                filter: (*name).into(),
                rmse,
                se,
            }
        })
        .collect()
}

/// Directions of a free construction: `f(x, y, frame)` for every texel.
fn free(f: impl Fn(i32, i32, u32) -> [f32; 3] + Sync) -> Vec<[f32; 3]> {
    let [w, h, t] = DIMS;
    (0..w * h * t)
        .map(|i| f((i % w) as i32, ((i / w) % h) as i32, (i / (w * h)) as u32))
        .collect()
}

/// Unit vectors stored as `0.5 + 0.5·v` in unorm bytes (our masks and EA's), decoded from
/// channel values at bin centres `(b + ½)/256` and renormalised.
fn unit_from_unorm(c: [f64; 3]) -> [f32; 3] {
    let v = c.map(|x| ((x * 256.0 - 0.5).round() / 255.0 * 2.0 - 1.0) as f32);
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-6);
    v.map(|x| x / len)
}

/// The index in a `w × h` slice of pixel `(x, y)` (non-negative) moved by the `k`-th R2 point
/// scaled to the slice, as the runtime's `get_k` reads a mask.
fn offset_index(x: i32, y: i32, k: u32, [w, h]: [usize; 2]) -> usize {
    let (ox, oy) = r2_point(k);
    let xi = (x as usize + scale(ox, w as u32) as usize) % w;
    let yi = (y as usize + scale(oy, h as u32) as usize) % h;
    yi * w + xi
}

/// A 2D `w × h` mask of directions read at the R2 offset of each frame, as the runtime's
/// `Mask2::get_k(x, y, frame)` reads it.
fn offset_per_frame(mask: &[[f32; 3]], wh: [usize; 2]) -> Vec<[f32; 3]> {
    free(|x, y, f| mask[offset_index(x, y, f, wh)])
}

/// Unit vectors from unorm channel values, three per texel.
pub fn unit_vectors(v: &[f64]) -> Vec<[f32; 3]> {
    v.chunks_exact(3)
        .map(|c| unit_from_unorm([c[0], c[1], c[2]]))
        .collect()
}

/// The spec of a FAST vector mask for `space` and `filter` × plain EMA at `dims`.
fn fast_spec(space: Space, filter: &str, dims: &[usize], extra: &str) -> TextureSpec {
    let temporal = if dims.len() == 3 {
        "temporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.0 }\n"
    } else {
        ""
    };
    let text = format!(
        "[[texture]]\nname = \"V\"\nkind = \"fast\"\ndims = {dims:?}\nseed = 1\nformat = \"u8x3\"\nsample_space = \"{}\"\nspatial_filter = {filter}\n{temporal}{extra}",
        space.name()
    );
    build_assets::spec::parse_toml(&text)
        .map_err(|e| e.render("vector", &text))
        .expect("the comparison's specs are valid")
        .textures
        .remove(0)
}

/// The spec text of a filter of [`FILTERS`].
fn filter_toml(f: &Filter) -> String {
    match f {
        Filter::Box { size } => format!("{{ kind = \"box\", size = {size} }}"),
        Filter::Gauss { sigma } => format!("{{ kind = \"gauss\", sigma = {sigma:?} }}"),
        _ => unreachable!("FILTERS holds boxes and Gaussians"),
    }
}

/// EA's 2D vector texture for `space` and a filter suffix, if the repository's `testdata/` is
/// here (or `NOISEBAKE_EA_DIR` names a directory holding it).
fn ea_texture(space: Space, suffix: &str) -> Option<Result<Vec<[f32; 3]>, String>> {
    let dir = std::env::var_os("NOISEBAKE_EA_DIR")
        .filter(|p| !p.is_empty())
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/ea-fast-bsd3"));
    let path = dir.join(space.ea_file(suffix));
    if !path.is_file() {
        return None;
    }
    Some((|| {
        let img = image::open(&path)
            .map_err(|e| format!("{}: {e}", path.display()))?
            .to_rgba8();
        if img.dimensions() != (128, 128) {
            return Err(format!("{}: expected 128×128", path.display()));
        }
        Ok(img
            .pixels()
            .map(|p| unit_from_unorm([0, 1, 2].map(|c| (p.0[c] as f64 + 0.5) / 256.0)))
            .collect())
    })())
}

/// The comparison for `space`.
pub fn table(space: Space, log: &mut dyn FnMut(&str)) -> Result<Table, String> {
    let [w, h, t] = DIMS;
    let mut rows = Vec::new();
    let push = |rows: &mut Vec<Row>,
                log: &mut dyn FnMut(&str),
                mask: String,
                kind: &str,
                bytes: usize,
                seconds: Option<f64>,
                cached: bool,
                dirs: &[[f32; 3]]| {
        log(&format!("  measuring {mask}"));
        let errors = measure(dirs, space);
        rows.push(Row {
            mask,
            kind: kind.into(),
            bytes,
            seconds,
            cached,
            errors,
        });
    };
    for (name, filter, suffix) in &FILTERS {
        let f = filter_toml(filter);
        for (label, extra) in [
            (", random start", "start = \"random\""),
            (", from sampler::ign_r2", "start = \"ign_r2\""),
            (", from sampler::rd_ign_r2", "start = \"rd_ign_r2\""),
        ] {
            let (v, secs, cached) = bake(&fast_spec(space, &f, &DIMS, extra), log)?;
            let dirs = unit_vectors(&v);
            push(
                &mut rows,
                log,
                format!("FAST 3D (ours, for {name}{label})"),
                "baked",
                w * h * t * 3,
                Some(secs),
                cached,
                &dirs,
            );
        }
        let (v, secs, cached) = bake(&fast_spec(space, &f, &[w, h], ""), log)?;
        let mask = unit_vectors(&v);
        push(
            &mut rows,
            log,
            format!("FAST 2D (ours, for {name}) + R2 offset per frame"),
            "baked",
            w * h * 3,
            Some(secs),
            cached,
            &offset_per_frame(&mask, [w, h]),
        );
        match ea_texture(space, suffix) {
            Some(m) => push(
                &mut rows,
                log,
                format!("FAST 2D (EA, published, {name}) + R2 offset per frame"),
                "published",
                w * h * 4,
                None,
                false,
                &offset_per_frame(&m?, [w, h]),
            ),
            None => log(&format!(
                "  EA's {} is not here (testdata/ea-fast-bsd3/ of a checkout, or NOISEBAKE_EA_DIR): its row is left out",
                space.ea_file(suffix)
            )),
        }
    }
    for (label, kind) in [
        ("STBN (ours) values 0 and 1", "stbn"),
        ("white noise (baked) values 0 and 1", "white"),
    ] {
        let (v, secs, cached) = bake(&spec("S", kind, &DIMS, ""), log)?;
        let at = |x: i32, y: i32, f: u32, k: u32| {
            v[f as usize * w * h + offset_index(x, y, k, [w, h])] as f32
        };
        let dirs = free(|x, y, f| space.warp(at(x, y, f, 0), at(x, y, f, 1)));
        push(
            &mut rows,
            log,
            label.into(),
            "baked",
            w * h * t,
            Some(secs),
            cached,
            &dirs,
        );
    }
    let (bv, bsecs, bcached) = bake(&spec("B", "blue2d", &[w, h], ""), log)?;
    let blue_at = |x: i32, y: i32, k: u32| bv[offset_index(x, y, k, [w, h])] as f32;
    push(
        &mut rows,
        log,
        "R2 sequence rotated by a 2D blue-noise mask (sampler::rd)".into(),
        "baked",
        w * h,
        Some(bsecs),
        bcached,
        &free(|x, y, f| {
            let [u, v] = sampler::rd::<2>(f, [blue_at(x, y, 0), blue_at(x, y, 1)]);
            space.warp(u, v)
        }),
    );
    type Free = (&'static str, fn(i32, i32, u32) -> [f32; 2]);
    let frees: [Free; 5] = [
        ("IGN x R2 (sampler::ign_r2)", |x, y, f| {
            sampler::ign_r2::<2>(x, y, f)
        }),
        (
            "IGN x R2, both golden-ratio animated (ldg::ign_frame, ldg::r2_frame)",
            |x, y, f| [ldg::ign_frame(x, y, f), ldg::r2_frame(x, y, f)],
        ),
        (
            "R2 sequence rotated by IGN x R2 (sampler::rd_ign_r2)",
            |x, y, f| sampler::rd_ign_r2::<2>(x, y, f),
        ),
        (
            "Sobol, Owen-scrambled per pixel (sampler::sobol_owen)",
            |x, y, f| sampler::sobol_owen::<2>(x, y, f, 1),
        ),
        ("PCG hash of pixel and frame", |x, y, f| {
            let s = hash::pcg((x as u32) ^ hash::pcg((y as u32) ^ hash::pcg(f)));
            let u = noise_runtime::sequence::to_unit(s);
            [u, noise_runtime::sequence::to_unit(hash::pcg(s))]
        }),
    ];
    for (label, f) in frees {
        let start = Instant::now();
        let dirs = free(|x, y, t| {
            let [u, v] = f(x, y, t);
            space.warp(u, v)
        });
        let secs = start.elapsed().as_secs_f64();
        push(
            &mut rows,
            log,
            label.into(),
            "free",
            0,
            Some(secs),
            false,
            &dirs,
        );
    }
    Ok(Table {
        space: space.name().into(),
        dims: DIMS,
        rows,
    })
}

/// The whole comparison: both sample spaces.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// What each column measures.
    pub measure: String,
    /// Cosine hemisphere, then sphere.
    pub tables: Vec<Table>,
}

/// What the numbers measure, printed above the tables and stored in the JSON.
pub const READING: &str = "\
RMSE of ambient-occlusion-like visibility (32 half-space occluders) estimated with one direction
  per pixel and frame, after the spatial filter and a plain EMA α 0.1 at its steady state over the
  looping 32 frames, 128x128; ± its standard error (16 image blocks): differences within about
  twice the combined error are ties. bytes: what a game ships (0: computed in the shader).";

/// Runs both tables, writes `vector.json` and `vector.png` into `out`.
pub fn run(out: &Path, log: &mut dyn FnMut(&str)) -> Result<Report, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut tables = Vec::new();
    for space in [Space::CosineHemisphere, Space::Sphere] {
        log(&format!(
            "{} {}x{}x{}: {}",
            space.name(),
            DIMS[0],
            DIMS[1],
            DIMS[2],
            FILTERS.map(|f| f.0).join(" | ")
        ));
        tables.push(table(space, log)?);
    }
    let r = Report {
        measure: READING.into(),
        tables,
    };
    let json = serde_json::to_string_pretty(&r).map_err(|e| e.to_string())?;
    std::fs::write(out.join("vector.json"), json).map_err(|e| e.to_string())?;
    plot(&r, &out.join("vector.png"))?;
    Ok(r)
}

/// The best free construction's error after filter `f` (index into [`FILTERS`]).
pub fn best_free(t: &Table, f: usize) -> Option<&Row> {
    t.rows
        .iter()
        .filter(|r| r.kind == "free")
        .min_by(|a, b| a.errors[f].rmse.total_cmp(&b.errors[f].rmse))
}

/// The tables as text, and for each filter a verdict: the best row, and our vector FAST made for
/// that filter against the best free construction (a tie within twice the combined error).
pub fn describe(r: &Report) -> Vec<String> {
    let mut out = READING
        .lines()
        .map(|l| format!("  {l}"))
        .collect::<Vec<_>>();
    for t in &r.tables {
        out.push(format!(
            "  {} {:<58} {:>20} {:>20} {:>9} {:>8}",
            t.space, "", FILTERS[0].0, FILTERS[1].0, "bytes", "seconds"
        ));
        for row in &t.rows {
            out.push(format!(
                "  {:<76} {:>20} {:>20} {:>9} {:>8}",
                row.mask,
                format!("{:.5} ± {:.5}", row.errors[0].rmse, row.errors[0].se),
                format!("{:.5} ± {:.5}", row.errors[1].rmse, row.errors[1].se),
                row.bytes,
                match (row.seconds, row.cached) {
                    (None, _) => "-".to_string(),
                    (Some(_), true) => "cached".to_string(),
                    (Some(s), false) => format!("{s:.1}"),
                }
            ));
        }
        for (f, (name, _, _)) in FILTERS.iter().enumerate() {
            let Some(free) = best_free(t, f) else {
                continue;
            };
            for fast in t.rows.iter().filter(|r| {
                r.kind == "baked" && r.mask.starts_with("FAST 3D") && r.mask.contains(name)
            }) {
                out.push(format!("  {name}: {}", verdict(fast, free, f)));
            }
        }
    }
    out
}

/// `a` against `b` after filter `f`: "leaves N % less/more error than" or "ties with".
pub fn verdict(a: &Row, b: &Row, f: usize) -> String {
    let (ea, eb) = (&a.errors[f], &b.errors[f]);
    let spread = 2.0 * (ea.se * ea.se + eb.se * eb.se).sqrt();
    let pct = 100.0 * (ea.rmse / eb.rmse - 1.0);
    if (ea.rmse - eb.rmse).abs() <= spread {
        format!(
            "{} ties with {} ({pct:+.1} %, within twice the combined error)",
            a.mask, b.mask
        )
    } else if pct < 0.0 {
        format!("{} leaves {:.1} % less error than {}", a.mask, -pct, b.mask)
    } else {
        format!("{} leaves {pct:.1} % more error than {}", a.mask, b.mask)
    }
}

/// A row's name for the plot's legend: the parenthesised details cut to their key words.
fn short(mask: &str) -> String {
    let mut s = mask.to_string();
    for (from, to) in [
        ("(ours, for ", "("),
        (", random start", ", random"),
        (", from sampler::", ", from "),
        ("(EA, published, ", "(EA "),
        (") + R2 offset per frame", ") + offset"),
        (" (sampler::rd)", ""),
        (
            "R2 sequence rotated by a 2D blue-noise mask",
            "R2 seq. + 2D blue rotation",
        ),
        (
            "R2 sequence rotated by IGN x R2",
            "R2 seq. + IGN x R2 rotation",
        ),
        (
            ", both golden-ratio animated (ldg::ign_frame, ldg::r2_frame)",
            ", both golden",
        ),
        (" (sampler::ign_r2)", ""),
        (" (sampler::rd_ign_r2)", ""),
        (", Owen-scrambled per pixel (sampler::sobol_owen)", "-Owen"),
        (" of pixel and frame", ""),
        (" values 0 and 1", ""),
        ("white noise (baked)", "white"),
        ("(ours)", ""),
        ("box 5x5", "box5"),
        ("gauss σ 1", "gauss1"),
    ] {
        s = s.replace(from, to);
    }
    s.trim().to_string()
}

/// One line per source over the four cases (space × filter): its RMSE over the best free
/// construction's in that case (log scale; below 1 beats every free construction).
pub fn plot(r: &Report, path: &Path) -> Result<(), String> {
    use crate::export::plot::{Labels, PALETTE, Series, line_plot};
    let Some(first) = r.tables.first() else {
        return Err("no tables".into());
    };
    let series: Vec<Series> = first
        .rows
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut points = Vec::new();
            for (ti, t) in r.tables.iter().enumerate() {
                let Some(same) = t.rows.iter().find(|o| o.mask == row.mask) else {
                    continue;
                };
                for f in 0..FILTERS.len() {
                    if let Some(best) = best_free(t, f) {
                        points.push((
                            (ti * FILTERS.len() + f + 1) as f64,
                            same.errors[f].rmse / best.errors[f].rmse,
                        ));
                    }
                }
            }
            Series {
                label: short(&row.mask),
                color: PALETTE[i % PALETTE.len()],
                points,
            }
        })
        .collect();
    let labels = Labels {
        title: "directions, 128x128x32: error over the best free construction's".into(),
        x: "1, 2: cosine hemisphere, box 5x5 / gauss σ 1 × EMA; 3, 4: sphere, the same".into(),
        y: "RMSE / best free RMSE (log scale)".into(),
    };
    line_plot(path, &series, &labels, true).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference integrals against closed forms: on the sphere a half-space through the
    /// centre holds half the directions and `[z < c]` holds `(1 + c)/2`; under the cosine
    /// weight `[z < c]` holds `c²` (z = √(1 − r²), r² uniform on Malley's disk).
    #[test]
    fn truths_match_closed_forms() {
        let ints: Vec<([f64; 3], f64)> = vec![
            ([0.0, 0.0, 1.0], 0.0),
            ([0.0, 0.0, 1.0], 0.4),
            ([0.0, 0.0, 1.0], -0.2),
            ([0.6, 0.0, 0.8], 0.0),
        ];
        let s = truths(Space::Sphere, &ints);
        for (t, want) in s.iter().zip([0.5, 0.7, 0.4, 0.5]) {
            assert!((t - want).abs() < 1.3e-4, "sphere {t} vs {want}");
        }
        let c = truths(Space::CosineHemisphere, &ints);
        for (t, want) in c.iter().zip([0.0, 0.16, 0.0]) {
            assert!((t - want).abs() < 1.3e-4, "cosine {t} vs {want}");
        }
        // Tilted (a = (0.6, 0, 0.8), c = 0): on Malley's disk the visible part is outside the
        // ellipse x² + (0.8y)² < 0.64 on the x < 0 side, (π/2 − 0.4π)/π = 0.1.
        assert!((c[3] - 0.1).abs() < 1.3e-4, "{}", c[3]);
    }

    /// The measure ranks: white noise leaves more error than the free pair, and both errors
    /// fall when the spatial filter widens; a source whose values all equal one constant
    /// direction has the integrand's full bias as its error.
    #[test]
    fn the_measure_ranks_white_noise_below_a_free_pair() {
        let space = Space::CosineHemisphere;
        let white = free(|x, y, f| {
            let h = hash::hash3(x, y, f as i32, 1);
            let u = noise_runtime::sequence::to_unit(h);
            space.warp(u, noise_runtime::sequence::to_unit(hash::pcg(h)))
        });
        let pair = free(|x, y, f| {
            let [u, v] = sampler::ign_r2::<2>(x, y, f);
            space.warp(u, v)
        });
        let (w, p) = (measure(&white, space), measure(&pair, space));
        for f in 0..FILTERS.len() {
            assert!(
                w[f].rmse > 1.5 * p[f].rmse,
                "{}: {} vs {}",
                w[f].filter,
                w[f].rmse,
                p[f].rmse
            );
            assert!(w[f].se > 0.0 && w[f].se < 0.1 * w[f].rmse);
        }
        let constant = vec![[0.0f32, 0.0, 1.0]; DIMS.iter().product()];
        let ints = integrands();
        let truth = truths(space, &ints);
        let bias = (ints
            .iter()
            .zip(&truth)
            .map(|((a, c), t)| {
                let v = if dot(a, [0.0, 0.0, 1.0]) < *c {
                    1.0
                } else {
                    0.0
                };
                (v - t) * (v - t)
            })
            .sum::<f64>()
            / ints.len() as f64)
            .sqrt();
        let e = measure(&constant, space);
        assert!((e[0].rmse - bias).abs() < 1e-9, "{} vs {bias}", e[0].rmse);
    }
}
