//! Speed against error the way a renderer decides: each variant's RMSE-against-time curve over a
//! range of sample counts, and from it the error each variant reaches in the time the
//! deterministic render takes, and the time it needs to reach the deterministic render's error.
//!
//! Variants are timed interleaved (every sample count renders each variant in turn, and the
//! fastest of the repeats is kept), so a machine whose speed drifts moves all of them alike.

use std::fmt::Write as _;
use std::time::Instant;

/// One render: a scene, a density (or material) variant, a sample count, its time and error.
#[derive(Clone, Debug)]
pub struct Row {
    /// Scene name.
    pub scene: String,
    /// Variant name.
    pub density: String,
    /// Samples per pixel (frames, for accumulated scenes).
    pub spp: usize,
    /// Seconds (single thread; the fastest of the repeats).
    pub seconds: f64,
    /// RMSE against the scene's reference.
    pub rmse: f64,
}

/// Renders every variant at every sample count, interleaved, `repeats` times each (keeping
/// the fastest time; the error of the first), and returns the rows. `render(variant, spp,
/// seed)` returns the image; `rmse` measures it. Then every variant faster than the first
/// (the baseline) renders at doubled sample counts until it has spent the baseline's time at
/// 64 spp (or its largest count): its error in that time is then measured, not extrapolated.
pub fn measure(
    scene: &str,
    variants: &[String],
    spps: &[usize],
    repeats: usize,
    mut render: impl FnMut(usize, usize, u64) -> Vec<f32>,
    rmse: impl Fn(&[f32]) -> f64,
) -> Vec<Row> {
    let mut rows = Vec::new();
    for &spp in spps {
        let mut best = vec![(f64::MAX, 0.0f64); variants.len()];
        for rep in 0..repeats.max(1) {
            for (v, b) in best.iter_mut().enumerate() {
                let start = Instant::now();
                let img = render(v, spp, 1000 + spp as u64);
                let secs = start.elapsed().as_secs_f64();
                if rep == 0 {
                    b.1 = rmse(&img);
                }
                b.0 = b.0.min(secs);
            }
        }
        for (v, (secs, e)) in best.into_iter().enumerate() {
            rows.push(Row {
                scene: scene.into(),
                density: variants[v].clone(),
                spp,
                seconds: secs,
                rmse: e,
            });
        }
    }
    let budget = rows
        .iter()
        .filter(|r| r.density == variants[0])
        .filter(|r| r.spp <= 64)
        .map(|r| r.seconds)
        .fold(0.0f64, f64::max);
    for (v, name) in variants.iter().enumerate().skip(1) {
        while let Some(last) = rows
            .iter()
            .filter(|r| &r.density == name)
            .max_by_key(|r| r.spp)
            .cloned()
        {
            if last.seconds >= budget || last.spp >= 1 << 16 {
                break;
            }
            let spp = last.spp * 2;
            let mut row = Row {
                spp,
                seconds: f64::MAX,
                ..last
            };
            for rep in 0..repeats.max(1) {
                let start = Instant::now();
                let img = render(v, spp, 1000 + spp as u64);
                row.seconds = row.seconds.min(start.elapsed().as_secs_f64());
                if rep == 0 {
                    row.rmse = rmse(&img);
                }
            }
            rows.push(row);
        }
    }
    rows
}

/// The curve of one variant: `(seconds, rmse)` by increasing time.
fn curve(rows: &[Row], scene: &str, variant: &str) -> Vec<(f64, f64)> {
    let mut c: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.scene == scene && r.density == variant)
        .map(|r| (r.seconds, r.rmse))
        .collect();
    c.sort_by(|a, b| a.0.total_cmp(&b.0));
    c
}

/// Log-log interpolation of `y` at `x` over points sorted by `x`; beyond the ends, the Monte
/// Carlo slope `y ∝ x^slope` from the nearest point.
fn loglog(points: &[(f64, f64)], x: f64, slope: f64) -> f64 {
    let (first, last) = (points[0], points[points.len() - 1]);
    if x <= first.0 {
        return first.1 * (x / first.0).powf(slope);
    }
    if x >= last.0 {
        return last.1 * (x / last.0).powf(slope);
    }
    for w in points.windows(2) {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        if x >= x0 && x <= x1 {
            let t = (x / x0).ln() / (x1 / x0).ln();
            return (y0.ln() + t * (y1 / y0).ln()).exp();
        }
    }
    last.1
}

/// The RMSE `variant` reaches in `seconds`, on its own curve.
pub fn rmse_at(rows: &[Row], scene: &str, variant: &str, seconds: f64) -> f64 {
    loglog(&curve(rows, scene, variant), seconds, -0.5)
}

/// The seconds `variant` needs to reach `rmse`, on its own curve. `None` when the curve stays
/// above it (a biased variant whose error floors there).
pub fn time_to(rows: &[Row], scene: &str, variant: &str, rmse: f64) -> Option<f64> {
    let c = curve(rows, scene, variant);
    let min = c.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    // Past the measured range only a variant still falling like Monte Carlo is extrapolated.
    let (last_t, last_e) = *c.last()?;
    if rmse < min {
        let falling = c.len() >= 2 && {
            let (t0, e0) = c[c.len() - 2];
            (last_e / e0).ln() / (last_t / t0).ln() < -0.35
        };
        return falling.then(|| last_t * (last_e / rmse).powi(2));
    }
    let mut by_error: Vec<(f64, f64)> = c.iter().map(|&(t, e)| (e, t)).collect();
    by_error.sort_by(|a, b| a.0.total_cmp(&b.0));
    Some(loglog(&by_error, rmse, -2.0))
}

/// The deterministic render's time and RMSE at `spp`.
fn baseline(rows: &[Row], scene: &str, base: &str, spp: usize) -> Option<(f64, f64)> {
    rows.iter()
        .find(|r| r.scene == scene && r.density == base && r.spp == spp)
        .map(|r| (r.seconds, r.rmse))
}

/// The equal-time table of a scene against the variant `base`: per variant, the RMSE in the
/// time `base` takes at 16 and at 64 spp (and its ratio to `base`'s), and the time to reach
/// `base`'s 64-spp RMSE (and its ratio to `base`'s time).
pub fn table(rows: &[Row], scene: &str, base: &str, variants: &[String]) -> String {
    let mut out = String::new();
    let (Some((t16, e16)), Some((t64, e64))) = (
        baseline(rows, scene, base, 16),
        baseline(rows, scene, base, 64),
    ) else {
        return format!("{scene}: no {base} rows at 16 and 64 spp\n");
    };
    let _ = writeln!(
        out,
        "{scene}: equal time against `{base}` (16 spp: {t16:.3} s, RMSE {e16:.5}; 64 spp: {t64:.3} s, RMSE {e64:.5})"
    );
    let _ = writeln!(
        out,
        "  {:<28} {:>12} {:>7} {:>12} {:>7} {:>14} {:>7}",
        "variant", "RMSE @ t16", "ratio", "RMSE @ t64", "ratio", "s to RMSE64", "ratio"
    );
    for v in variants {
        let a = rmse_at(rows, scene, v, t16);
        let b = rmse_at(rows, scene, v, t64);
        let reach = time_to(rows, scene, v, e64);
        let (reach_s, reach_r) = match reach {
            Some(s) => (format!("{s:.3}"), format!("{:.2}", s / t64)),
            None => ("never".into(), "-".into()),
        };
        let _ = writeln!(
            out,
            "  {v:<28} {a:>12.5} {:>7.2} {b:>12.5} {:>7.2} {reach_s:>14} {reach_r:>7}",
            a / e16,
            b / e64
        );
    }
    for v in variants.iter().filter(|v| v.contains("band-limited")) {
        match bias(rows, scene, base, v) {
            Some((spp, b)) if b > 0.0 => {
                let _ = writeln!(
                    out,
                    "  bias of `{v}` against the full sum, from {spp} spp: {b:.5} (an RMSE it cannot go below)"
                );
            }
            Some((spp, _)) => {
                let _ = writeln!(
                    out,
                    "  bias of `{v}` against the full sum: below the noise at {spp} spp"
                );
            }
            None => {}
        }
    }
    out
}

/// Bias of the `variant`'s image against the reference, estimated from the largest sample
/// count both it and `base` rendered: `√max(0, RMSE_variant² − RMSE_base²)` (the base is
/// unbiased, so its RMSE there is the noise both share). For band-limited variants.
pub fn bias(rows: &[Row], scene: &str, base: &str, variant: &str) -> Option<(usize, f64)> {
    let at = |name: &str, spp: usize| {
        rows.iter()
            .find(|r| r.scene == scene && r.density == name && r.spp == spp)
            .map(|r| r.rmse)
    };
    let spp = rows
        .iter()
        .filter(|r| r.scene == scene && r.density == variant)
        .map(|r| r.spp)
        .filter(|&s| at(base, s).is_some())
        .max()?;
    let (v, b) = (at(variant, spp)?, at(base, spp)?);
    Some((spp, (v * v - b * b).max(0.0).sqrt()))
}

/// The rows as a JSON array of `{scene, density, spp, seconds, rmse}`.
pub fn json(rows: &[Row]) -> String {
    let items: Vec<String> = rows
        .iter()
        .map(|r| {
            format!(
                "  {{\"scene\": \"{}\", \"density\": \"{}\", \"spp\": {}, \"seconds\": {:.6}, \"rmse\": {:.6e}}}",
                r.scene, r.density, r.spp, r.seconds, r.rmse
            )
        })
        .collect();
    format!("[\n{}\n]\n", items.join(",\n"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(variant: &str, k: f64) -> Vec<Row> {
        // RMSE = k / sqrt(seconds): a pure Monte Carlo curve.
        [4, 16, 64, 256]
            .iter()
            .map(|&spp| {
                let seconds = spp as f64 * 0.01;
                Row {
                    scene: "s".into(),
                    density: variant.into(),
                    spp,
                    seconds,
                    rmse: k / seconds.sqrt(),
                }
            })
            .collect()
    }

    #[test]
    fn equal_time_of_monte_carlo_curves_is_their_efficiency_ratio() {
        let mut r = rows("det", 1.0);
        r.extend(rows("sto", 0.5));
        let (t64, e64) = baseline(&r, "s", "det", 64).unwrap();
        // Half the error at equal time; a quarter of the time to equal error.
        assert!((rmse_at(&r, "s", "sto", t64) / e64 - 0.5).abs() < 1e-9);
        assert!((time_to(&r, "s", "sto", e64).unwrap() / t64 - 0.25).abs() < 1e-9);
        assert!((rmse_at(&r, "s", "det", t64) / e64 - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_variant_whose_error_floors_never_reaches_a_lower_error() {
        let mut r = rows("det", 0.2);
        for row in rows("biased", 0.1) {
            r.push(Row {
                rmse: row.rmse.max(0.5),
                ..row
            });
        }
        let (_, e64) = baseline(&r, "s", "det", 64).unwrap();
        assert!(e64 < 0.5);
        assert_eq!(time_to(&r, "s", "biased", e64), None);
    }
}
