//! The scaling benchmark (`noisebake report bench`): each generator at three sizes, on one
//! and two threads, beside the estimate a user is shown up front
//! ([`build_assets::generate::estimate`]) and, for FAST, the error after the filter the mask
//! is made for. It fits the exponent of time against texels per kind (1 is linear) and writes
//! the table as JSON and a log-log plot to the report folder; the README's bake times come
//! from it.
//!
//! For each FAST case and the sampler tile at its largest size it also runs the optimiser on
//! past its stopping rule to the round cap ([`Curve`]): the loss's decrease against time, the
//! round (sweep, for the tile) where the bake stopped, and the error there and at the cap, which
//! is the trade the stopping rule ([`build_assets::generate::fast::converged`] of the case's
//! sample space; [`build_assets::generate::sampler::spent`]) makes.

use crate::export::plot::{Labels, PALETTE, Series, line_plot};
use crate::report::compare::{loss_params, measure};
use crate::report::sampler;
use crate::report::vector::{self, Space};
use build_assets::generate::estimate::estimate_with_threads;
use build_assets::generate::fast::{self, MAX_ROUNDS};
use build_assets::generate::sampler::{self as gen_sampler, Schedule};
use build_assets::spec::sampler::SamplerParams;
use build_assets::spec::{Kind, TextureSpec};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// One bake.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The kind and its parameters, as the table names it.
    pub case: String,
    /// Texture dimensions.
    pub dims: Vec<usize>,
    /// Texels.
    pub texels: usize,
    /// Worker threads.
    pub threads: usize,
    /// Measured wall time, seconds.
    pub seconds: f64,
    /// The up-front estimate for this many threads, seconds.
    pub estimate: f64,
    /// For FAST masks, the error after the filter the mask is made for: scalar masks, RMSE of
    /// step integrands after Gaussian σ 1.3435 × plain EMA (α 0.1, `report fast`'s measure);
    /// the cosine-hemisphere mask, RMSE of visibility integrands after box 5×5 × plain EMA
    /// (`report vector`'s measure); the 128² sampler tile, RMSE of its 4-sample estimates after
    /// Gaussian σ 1, dimensions 0–1 (`report sampler`'s measure).
    pub rmse: Option<f64>,
}

/// A FAST case or the sampler tile at its largest size, on 2 threads, run on past the bake's
/// stopping rule to the round cap.
#[derive(Clone, Debug, Serialize)]
pub struct Curve {
    /// The case.
    pub case: String,
    /// Texture dimensions.
    pub dims: Vec<usize>,
    /// `(seconds, decrease of the loss since the start)` after each round (the tile: each
    /// sweep of its first pair of dimensions).
    pub points: Vec<(f64, f64)>,
    /// The round after which the bake stops (1-based): FAST's first whose gain is at most the
    /// sample space's threshold (`fast::converged`) of the decrease so far; the tile's first
    /// sweep whose gain is under `Schedule::stop_gain` of the loss left (`sampler::spent`).
    pub stop_round: usize,
    /// The error at the round cap (the bake's error is its row's `rmse`).
    pub rmse_at_cap: f64,
}

/// A kind's fit: `seconds ∝ texels^exponent` over its three sizes, per thread count.
#[derive(Clone, Debug, Serialize)]
pub struct Fit {
    /// The case.
    pub case: String,
    /// Worker threads.
    pub threads: usize,
    /// The fitted exponent (least squares on the logs).
    pub exponent: f64,
}

/// The whole benchmark.
#[derive(Clone, Debug, Serialize)]
pub struct Bench {
    /// Every bake.
    pub rows: Vec<Row>,
    /// Exponents per case and thread count.
    pub fits: Vec<Fit>,
    /// Each FAST case and the sampler tile run on to the round cap.
    pub curves: Vec<Curve>,
}

/// The cases: `(name, TOML body without dims, sizes)`.
fn cases(full: bool) -> Vec<(&'static str, &'static str, Vec<Vec<usize>>)> {
    let mut v2 = vec![vec![256, 256], vec![512, 512], vec![1024, 1024]];
    if full {
        v2.push(vec![2048, 2048]);
    }
    vec![
        ("blue2d", "kind = \"blue2d\"", v2),
        (
            "stbn",
            "kind = \"stbn\"",
            vec![vec![64, 64, 64], vec![128, 128, 64], vec![256, 256, 64]],
        ),
        (
            "fast scalar, gauss x plain EMA",
            "kind = \"fast\"",
            vec![vec![32, 32, 64], vec![64, 64, 64], vec![128, 128, 64]],
        ),
        (
            "fast scalar, box 3 x plain EMA",
            "kind = \"fast\"\nspatial_filter = { kind = \"box\", size = 3 }",
            vec![vec![32, 32, 64], vec![64, 64, 64], vec![128, 128, 64]],
        ),
        (
            "fast cosine hemisphere u8x3, box 5 x plain EMA",
            "kind = \"fast\"\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 5 }",
            vec![vec![32, 32, 32], vec![64, 64, 32], vec![128, 128, 32]],
        ),
        (
            "sampler 4 spp x 4 dims, gauss 1",
            "kind = \"sampler\"\nspp = 4\nsample_dims = 4",
            vec![vec![32, 32], vec![64, 64], vec![128, 128]],
        ),
    ]
}

fn spec(body: &str, dims: &[usize]) -> Result<TextureSpec, String> {
    let text = format!("[[texture]]\nname = \"BENCH\"\n{body}\ndims = {dims:?}\nseed = 1\n");
    let file = build_assets::spec::parse_toml(&text).map_err(|e| e.render("bench", &text))?;
    Ok(file.textures.into_iter().next().expect("one texture"))
}

/// Least-squares slope of `ln y` against `ln x`.
pub fn exponent(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// The fitted exponents of time against texels, as text (the rows are printed as they run).
pub fn describe_fits(b: &Bench) -> Vec<String> {
    std::iter::once("  fitted exponent of time against texels (1 = linear):".to_string())
        .chain(
            b.fits
                .iter()
                .map(|f| format!("  {:<48} {} thr  {:.2}", f.case, f.threads, f.exponent)),
        )
        .collect()
}

/// Runs the benchmark (with `full`, also void and cluster at 2048²), logging each bake, and
/// writes `bench.json` and `bench.png` into `out`.
pub fn run(out: &Path, full: bool, log: &mut dyn FnMut(&str)) -> Result<Bench, String> {
    let mut rows = Vec::new();
    for (name, body, sizes) in cases(full) {
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| e.to_string())?;
            for dims in &sizes {
                let s = spec(body, dims)?;
                let est = estimate_with_threads(&s, threads).seconds;
                let start = Instant::now();
                let tex = pool.install(|| build_assets::generate(&s, &mut |_, _| {}));
                let seconds = start.elapsed().as_secs_f64();
                let rmse = if let Kind::Sampler(p) = &s.kind {
                    sampler_error(p, dims, &tex.data)
                } else {
                    fast_error(name, dims, &tex.values())
                };
                let row = Row {
                    case: name.to_string(),
                    dims: dims.clone(),
                    texels: s.texels(),
                    threads,
                    seconds,
                    estimate: est,
                    rmse,
                };
                log(&describe(&row));
                rows.push(row);
            }
        }
    }
    let mut curves = Vec::new();
    for (name, body, sizes) in cases(full) {
        let dims = sizes.last().expect("sizes");
        if let Some(c) = run_on(name, &spec(body, dims)?, log)? {
            curves.push(c);
        }
    }
    let mut fits = Vec::new();
    let mut series = Vec::new();
    for (k, (name, _, _)) in cases(full).iter().enumerate() {
        for threads in [1, 2] {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.case == *name && r.threads == threads)
                .map(|r| (r.texels as f64, r.seconds))
                .collect();
            fits.push(Fit {
                case: name.to_string(),
                threads,
                exponent: exponent(&pts),
            });
            series.push(Series {
                label: format!(
                    "{name} ({threads} thread{})",
                    if threads > 1 { "s" } else { "" }
                ),
                color: PALETTE[(2 * k + threads - 1) % PALETTE.len()],
                points: pts.iter().map(|&(x, y)| (x.log10(), y)).collect(),
            });
        }
    }
    std::fs::create_dir_all(out).map_err(|e| e.to_string())?;
    let bench = Bench { rows, fits, curves };
    let json = serde_json::to_string_pretty(&bench).map_err(|e| e.to_string())?;
    std::fs::write(out.join("bench.json"), json).map_err(|e| e.to_string())?;
    line_plot(
        &out.join("bench.png"),
        &series,
        &Labels {
            title: "bake time against size".into(),
            x: "log10 texels".into(),
            y: "seconds (log)".into(),
        },
        true,
    )?;
    plot_curves(&bench.curves, &out.join("bench_fast_curves.png"))?;
    Ok(bench)
}

/// The error of a FAST bench case after the filter it is made for ([`Row::rmse`]); `None` for
/// other kinds.
fn fast_error(case: &str, dims: &[usize], values: &[f64]) -> Option<f64> {
    if case.starts_with("fast scalar") {
        let d = [dims[0], dims[1], dims[2]];
        let fps = [
            loss_params(0.0).footprint(dims),
            loss_params(0.1).footprint(dims),
        ];
        Some(measure("", values, d, &fps).rmse_gauss)
    } else if case.starts_with("fast cosine hemisphere") && dims == vector::DIMS {
        let box5 = vector::measure(&vector::unit_vectors(values), Space::CosineHemisphere);
        Some(box5[0].rmse)
    } else {
        None
    }
}

/// The error of a 128² sampler tile (its stored keys) after the filter it is made for
/// ([`Row::rmse`]); `None` at other sizes.
fn sampler_error(p: &SamplerParams, dims: &[usize], bytes: &[u8]) -> Option<f64> {
    if dims != [sampler::TILE, sampler::TILE] || p.sample_dims != sampler::SAMPLE_DIMS {
        return None;
    }
    let keys: Vec<u16> = bytes
        .chunks_exact(2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .collect();
    let f = sampler::tile_lookup(keys, p.spp);
    let ints = sampler::integrands(256, 64, sampler::TEST_SEED);
    Some(sampler::measure(&*f, p.spp, [0, 1], &ints)[1])
}

/// Runs the sampler tile on 2 threads to the sweep cap ([`Curve`]).
fn run_sampler_on(
    case: &str,
    s: &TextureSpec,
    p: &SamplerParams,
    log: &mut dyn FnMut(&str),
) -> Result<Curve, String> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .map_err(|e| e.to_string())?;
    let bake = Schedule::DEFAULT;
    // A stop gain of 0 never stops: the same sweeps as the bake, then on to the cap.
    let on = Schedule {
        stop_gain: 0.0,
        ..bake
    };
    let (w, h) = (s.dims[0], s.dims[1]);
    let (keys, trace) =
        pool.install(|| gen_sampler::generate_with(p, w, h, s.seed, &on, &mut |_, _| {}));
    let (loss, seconds) = (&trace.loss[0], &trace.seconds[0]);
    let points: Vec<(f64, f64)> = seconds
        .iter()
        .zip(loss)
        .skip(1)
        .map(|(&t, &l)| (t, loss[0] - l))
        .collect();
    let stop_round = sweeps_to_stop(loss, bake.stop_gain);
    let bytes: Vec<u8> = keys.iter().flat_map(|k| k.to_le_bytes()).collect();
    let rmse_at_cap = sampler_error(p, &s.dims, &bytes).unwrap_or(f64::NAN);
    log(&format!(
        "  {case} {:?}: the bake stops after sweep {stop_round} of {}; run on to the cap: {:.2} s, rmse {rmse_at_cap:.5}",
        s.dims,
        points.len(),
        points.last().map_or(0.0, |p| p.0)
    ));
    Ok(Curve {
        case: case.to_string(),
        dims: s.dims.clone(),
        points,
        stop_round,
        rmse_at_cap,
    })
}

/// Runs a FAST case (or the sampler tile) on 2 threads to the round cap ([`Curve`]); `None`
/// for other kinds.
fn run_on(case: &str, s: &TextureSpec, log: &mut dyn FnMut(&str)) -> Result<Option<Curve>, String> {
    if let Kind::Sampler(p) = &s.kind {
        return run_sampler_on(case, s, p, log).map(Some);
    }
    let Kind::Fast(params) = &s.kind else {
        return Ok(None);
    };
    let mut capped = params.clone();
    capped.iterations = Some(MAX_ROUNDS);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .map_err(|e| e.to_string())?;
    // A threshold of 0 never stops: the same rounds as the bake, then on to the cap.
    let out =
        pool.install(|| fast::generate_within(&capped, &s.dims, s.seed, None, 0.0, &mut |_, _| {}));
    let points: Vec<(f64, f64)> = out.curve.iter().map(|p| (p.seconds, p.decrease)).collect();
    let stop_round = stop_round(&points, fast::converged(params.sample_space));
    let scalar = s.format.scalar;
    let bytes = fast::encode(&capped, &s.dims, &out.samples, scalar);
    let values = build_assets::Texture {
        name: s.name.clone(),
        dims: s.storage_dims(),
        format: s.format,
        data: bytes,
    }
    .values();
    let rmse_at_cap = fast_error(case, &s.dims, &values).unwrap_or(f64::NAN);
    log(&format!(
        "  {case} {:?}: the bake stops after round {stop_round} of {}; run on to the cap: {:.2} s, rmse {rmse_at_cap:.5}",
        s.dims,
        points.len(),
        points.last().map_or(0.0, |p| p.0)
    ));
    Ok(Some(Curve {
        case: case.to_string(),
        dims: s.dims.clone(),
        points,
        stop_round,
        rmse_at_cap,
    }))
}

/// The round (1-based) after which the stopping rule ends a run with these `(seconds,
/// decrease)` points: the first whose gain is at most `converged` ([`fast::converged`] of the
/// sample space) of the decrease so far (the optimiser's test, in the same terms), or the last.
pub fn stop_round(points: &[(f64, f64)], converged: f64) -> usize {
    let mut prev = 0.0;
    for (r, &(_, d)) in points.iter().enumerate() {
        if d - prev <= converged * d {
            return r + 1;
        }
        prev = d;
    }
    points.len()
}

/// The sweep (1-based) after which the sampler's stopping rule ends a run whose loss went
/// `loss` (the start, then after each sweep): the first whose gain is spent
/// ([`gen_sampler::spent`], the optimiser's test), or the last.
pub fn sweeps_to_stop(loss: &[f64], stop_gain: f64) -> usize {
    (1..loss.len())
        .find(|&k| gen_sampler::spent(loss[k - 1] - loss[k], loss[k], stop_gain))
        .unwrap_or(loss.len() - 1)
}

/// Loss decrease (as a share of the decrease at the cap) against seconds, one line per case.
fn plot_curves(curves: &[Curve], path: &Path) -> Result<(), String> {
    let series: Vec<Series> = curves
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let end = c.points.last().map_or(1.0, |p| p.1).max(f64::MIN_POSITIVE);
            Series {
                label: format!(
                    "{} {:?} (bake stops after round {})",
                    c.case, c.dims, c.stop_round
                ),
                color: PALETTE[k % PALETTE.len()],
                points: c.points.iter().map(|&(t, d)| (t, d / end)).collect(),
            }
        })
        .collect();
    if series.is_empty() {
        return Ok(());
    }
    line_plot(
        path,
        &series,
        &Labels {
            title: "FAST and the sampler tile: loss decrease against time, run on to the cap"
                .into(),
            x: "seconds (2 threads)".into(),
            y: "share of the decrease at the cap".into(),
        },
        false,
    )
    .map(|_| ())
}

/// One line of the table.
pub fn describe(r: &Row) -> String {
    let dims = r
        .dims
        .iter()
        .map(|d| d.to_string())
        .collect::<Vec<_>>()
        .join("×");
    let rmse = r.rmse.map_or(String::new(), |e| format!("  rmse {e:.5}"));
    format!(
        "  {:<48} {:>12} {} thr {:>8.2} s  estimate {:>7.2} s ({:.2}×){rmse}",
        r.case,
        dims,
        r.threads,
        r.seconds,
        r.estimate,
        r.estimate / r.seconds
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fit_recovers_a_power_law() {
        let pts: Vec<(f64, f64)> = [1e4, 4e4, 1.6e5]
            .iter()
            .map(|&x: &f64| (x, 3e-6 * x.powf(1.3)))
            .collect();
        assert!((exponent(&pts) - 1.3).abs() < 1e-9);
        let linear: Vec<(f64, f64)> = [1.0, 2.0, 8.0].iter().map(|&x| (x, 5.0 * x)).collect();
        assert!((exponent(&linear) - 1.0).abs() < 1e-9);
    }

    /// The bench reads the stop from a run-on curve: it must stop where the optimiser does.
    #[test]
    fn the_stop_read_off_a_curve_is_the_bakes() {
        let s = spec("kind = \"fast\"", &[16, 16, 8]).unwrap();
        let Kind::Fast(p) = &s.kind else { panic!() };
        let baked = fast::generate(p, &s.dims, s.seed, &mut |_, _| {});
        let mut capped = p.clone();
        capped.iterations = Some(MAX_ROUNDS);
        let on = fast::generate_within(&capped, &s.dims, s.seed, None, 0.0, &mut |_, _| {});
        let pts: Vec<(f64, f64)> = on.curve.iter().map(|p| (p.seconds, p.decrease)).collect();
        assert!(
            baked.curve.len() < on.curve.len(),
            "the rule stops before the cap here"
        );
        assert_eq!(
            stop_round(&pts, fast::converged(p.sample_space)),
            baked.curve.len()
        );
        for (a, b) in baked.curve.iter().zip(&on.curve) {
            assert_eq!(a.decrease, b.decrease);
        }
    }

    /// The same for the sampler tile: the bake stops at the sweep read off the run-on trace.
    #[test]
    fn the_sampler_stop_read_off_a_trace_is_the_bakes() {
        let s = spec("kind = \"sampler\"\nspp = 4\nsample_dims = 2", &[16, 16]).unwrap();
        let Kind::Sampler(p) = &s.kind else { panic!() };
        let bake = Schedule {
            training: 256,
            stop_gain: 2e-2,
            ..Schedule::DEFAULT
        };
        let on = Schedule {
            stop_gain: 0.0,
            ..bake
        };
        let (_, baked) = gen_sampler::generate_with(p, 16, 16, 1, &bake, &mut |_, _| {});
        let (_, ran) = gen_sampler::generate_with(p, 16, 16, 1, &on, &mut |_, _| {});
        let (baked, ran) = (&baked.loss[0], &ran.loss[0]);
        assert!(
            baked.len() < ran.len(),
            "the rule stops before the cap here"
        );
        assert_eq!(sweeps_to_stop(ran, bake.stop_gain), baked.len() - 1);
        assert_eq!(baked[..], ran[..baked.len()]);
    }

    #[test]
    fn every_case_parses_at_every_size() {
        for (name, body, sizes) in cases(true) {
            for dims in sizes {
                let s = spec(body, &dims).unwrap_or_else(|e| panic!("{name} {dims:?}: {e}"));
                let layers = match &s.kind {
                    Kind::Sampler(p) => p.sample_dims as usize,
                    _ => 1,
                };
                assert_eq!(s.texels(), layers * dims.iter().product::<usize>());
            }
        }
    }
}
