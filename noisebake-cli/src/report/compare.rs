//! Which scalar mask leaves the least error after the filter FAST is made for (Gaussian
//! σ 1.3435 in space × EMA α 0.1, β 0.1 in time, product), measured two ways that do not trust
//! the optimiser:
//!
//! - the FAST loss of eq. (7) of every mask, by the same code for every row;
//! - the error after filtering, measured directly ([`filtered_rmse`]): Heaviside integrands at
//!   thresholds across (0, 1), one sample per pixel and frame, each frame filtered in space
//!   (toroidal), then an EMA over the looping texture run to its steady state, RMSE against the
//!   true integral; for the Gaussian and for the 3×3 and 5×5 boxes games run.
//!
//! Rows: our FAST, EA's published texture (128×128×64 only; vendored in `testdata/`), our STBN
//! (per-slice histograms), independent 2D blue noise, golden-ratio animated blue noise,
//! interleaved gradient noise animated by the usual 5.588238 pixels per frame, R2 animated by the
//! golden ratio, and white noise. The baked masks are u8, as EA ships its texture.

use super::kit::{EA_MISSING, bake, ea_path, ea_values, ign, r2, spec};
use crate::analysis::filtered::{Denoiser, filtered_rmse, filtered_rmse_curve};
use build_assets::generate::fast::{self, Filter};
use build_assets::spec::TextureSpec;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// One mask's row.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The mask.
    pub mask: String,
    /// The FAST loss (eq. 7) of the filter the measurement runs: Gaussian σ 1.3435 × EMA α 0.1
    /// at its steady state over the looping texture (β = 0). Its differences are the measured
    /// error's expectation (lower is better).
    pub loss: f64,
    /// The loss relative to white noise's (1 = white).
    pub loss_vs_white: f64,
    /// The loss in the units of the measured columns: the RMSE it predicts after the same
    /// filter for step integrands with a uniform threshold ([`loss_as_rmse`]). It should sit
    /// beside `rmse_gauss`; the raw loss is dominated by a constant its differences ride on.
    pub loss_rmse: f64,
    /// The loss with history rejection β = 0.1 (FAST eq. 17), the filter EA's texture was
    /// made for; it models an EMA whose history is dropped with probability β each frame,
    /// which the measurement does not run.
    pub loss_beta_0_1: f64,
    /// RMSE after Gaussian σ 1.3435 per frame + steady-state EMA α 0.1.
    pub rmse_gauss: f64,
    /// RMSE after a 3×3 box per frame + EMA.
    pub rmse_box3: f64,
    /// RMSE after a 5×5 box per frame + EMA.
    pub rmse_box5: f64,
    /// Seconds to make it (bake, or computing a hash; `null` for the published texture).
    pub seconds: Option<f64>,
    /// Whether the bake came from the cache (its time is then the original bake's unknown).
    pub cached: bool,
    /// RMSE after Gaussian + EMA after each of the first 64 frames (from frame 0).
    pub curve: Vec<f64>,
}

/// The comparison at one size.
#[derive(Clone, Debug, Serialize)]
pub struct Table {
    /// `[w, h, frames]`.
    pub dims: [usize; 3],
    /// One row per mask, in the order above.
    pub rows: Vec<Row>,
}

/// The FAST parameters the comparison is about.
pub fn params() -> fast::FastParams {
    super::kit::scalar_params(fast::Combine::Product)
}

/// The FAST spec of the comparison at `dims` with history rejection `beta`.
pub fn fast_spec(dims: [usize; 3], beta: f64) -> TextureSpec {
    spec(
        "FAST",
        "fast",
        &dims,
        &format!(
            "spatial_filter = {{ kind = \"gauss\", sigma = 1.3435 }}\ntemporal_filter = {{ kind = \"ema\", alpha = 0.1, beta = {beta:?} }}"
        ),
    )
}

/// The FAST parameters of the two losses: β = 0 (the measured filter) and β = 0.1 (EA's).
pub fn loss_params(beta: f64) -> fast::FastParams {
    let mut p = params();
    p.temporal = fast::TemporalFilter::Ema { alpha: 0.1, beta };
    p
}

/// The RMSE a FAST loss predicts (the `fast` module's derivation): for step integrands
/// `[s < c]` with `c` uniform, the filtered image's mean squared error is
/// `R · mean_j(1/3 − s_j + s_j²) + L / (2N)`, where `L` is the loss of eq. 7 (negative) over
/// `N` texels and `R` the footprint's row sum ([`fast::Footprint::total`]; the pairs the
/// cutoff drops are nearly independent, and the kernel's mean over independent uniform pairs
/// is 0). The constant depends only on the values, so masks with flat histograms share it and
/// differ by `ΔL / 2N` exactly.
pub fn loss_as_rmse(loss: f64, values: &[f64], fp: &fast::Footprint) -> f64 {
    let n = values.len().max(1) as f64;
    let c = values.iter().map(|s| 1.0 / 3.0 - s + s * s).sum::<f64>() / n;
    (fp.total * c + loss / (2.0 * n)).max(0.0).sqrt()
}

/// Loss and measured errors of one mask; `fps` are the footprints of β = 0 and β = 0.1.
pub fn measure(name: &str, values: &[f64], dims: [usize; 3], fps: &[fast::Footprint; 2]) -> Row {
    let l = |fp: &fast::Footprint| {
        fast::optimize::loss::<1, _>(dims, fp, values, fast::distance::Scalar)
    };
    let d = |spatial: Filter| Denoiser {
        spatial: spatial.taps(),
        ema_alpha: Some(0.1),
    };
    let gauss = d(Filter::Gauss { sigma: 1.3435 });
    let loss = l(&fps[0]);
    Row {
        mask: name.into(),
        loss,
        loss_vs_white: f64::NAN,
        loss_rmse: loss_as_rmse(loss, values, &fps[0]),
        loss_beta_0_1: l(&fps[1]),
        rmse_gauss: filtered_rmse(values, dims, &gauss),
        rmse_box3: filtered_rmse(values, dims, &d(Filter::Box { size: 3 })),
        rmse_box5: filtered_rmse(values, dims, &d(Filter::Box { size: 5 })),
        seconds: None,
        cached: false,
        curve: filtered_rmse_curve(values, dims, &gauss, 64),
    }
}

/// The table at `dims` (EA's row only at 128×128×64).
pub fn table(dims: [usize; 3], log: &mut dyn FnMut(&str)) -> Result<Table, String> {
    let fp = [
        loss_params(0.0).footprint(&dims),
        loss_params(0.1).footprint(&dims),
    ];
    let mut rows = Vec::new();
    let baked = |name: &str, s: TextureSpec, log: &mut dyn FnMut(&str)| -> Result<Row, String> {
        let (v, secs, cached) = bake(&s, log)?;
        let mut r = measure(name, &v, dims, &fp);
        r.seconds = Some(secs);
        r.cached = cached;
        Ok(r)
    };
    rows.push(baked(
        "FAST (ours, for the measured EMA, beta 0)",
        fast_spec(dims, 0.0),
        log,
    )?);
    rows.push(baked(
        "FAST (ours, EA's parameters, beta 0.1)",
        fast_spec(dims, 0.1),
        log,
    )?);
    if dims == [128, 128, 64] {
        match ea_path() {
            Some(p) => rows.push(measure("FAST (EA, published)", &ea_values(&p)?, dims, &fp)),
            None => log(&format!("  {EA_MISSING}")),
        }
    }
    rows.push(baked(
        "STBN (ours, slice histograms)",
        spec("STBN", "stbn", &dims, "histogram = \"slice\""),
        log,
    )?);
    rows.push(baked(
        "independent 2D blue noise",
        spec("IND", "independent2d", &dims, ""),
        log,
    )?);
    rows.push(baked(
        "golden-ratio animated blue noise",
        spec("GOLD", "golden", &dims, ""),
        log,
    )?);
    for (name, make) in [
        (
            "IGN (5.588238 px per frame)",
            ign as fn([usize; 3]) -> Vec<f64>,
        ),
        ("R2 (golden-ratio animated)", r2),
    ] {
        let start = Instant::now();
        let v = make(dims);
        let secs = start.elapsed().as_secs_f64();
        let mut r = measure(name, &v, dims, &fp);
        r.seconds = Some(secs);
        rows.push(r);
    }
    rows.push(baked(
        "white noise",
        spec("WHITE", "white", &dims, ""),
        log,
    )?);
    let white = rows.last().map_or(1.0, |r| r.loss);
    for r in &mut rows {
        r.loss_vs_white = r.loss / white;
    }
    Ok(Table { dims, rows })
}

/// What the table's columns mean, printed under it.
pub const READING: &str = "\
loss: FAST's eq. (7) for Gaussian σ 1.3435 × plain EMA α 0.1 (β 0), lower is better; /white: over
  white noise's. The loss is a large constant plus the part that differs between masks, so its
  ratios look close to 1 where errors differ severalfold. loss b=0.1: the same with EA's
  history rejection (eq. 17). loss->rmse: the RMSE that loss predicts after the filter for step
  integrands with a uniform threshold (mean(1/3 − s + s²) + loss / 2N), in the units of:
rmse gauss / box3 / box5: the RMSE measured directly after a Gaussian σ 1.3435, a 3×3 or a 5×5
  box per frame, then the EMA α 0.1 at its steady state over the looping texture; lower is better.
seconds: time to bake (or compute the hash); `cached` when the bake came from the cache.";

/// The table as text, one line per row.
pub fn describe(t: &Table) -> Vec<String> {
    let mut out = vec![format!(
        "  {}x{}x{}: {:<36} {:>14} {:>8} {:>14} {:>10} {:>10} {:>10} {:>10} {:>8}",
        t.dims[0],
        t.dims[1],
        t.dims[2],
        "mask",
        "loss",
        "/white",
        "loss b=0.1",
        "loss->rmse",
        "rmse gauss",
        "rmse box3",
        "rmse box5",
        "seconds"
    )];
    for r in &t.rows {
        out.push(format!(
            "  {:<48} {:>14.2} {:>8.5} {:>14.2} {:>10.5} {:>10.5} {:>10.5} {:>10.5} {:>8}",
            r.mask,
            r.loss,
            r.loss_vs_white,
            r.loss_beta_0_1,
            r.loss_rmse,
            r.rmse_gauss,
            r.rmse_box3,
            r.rmse_box5,
            match (r.seconds, r.cached) {
                (None, _) => "-".to_string(),
                (Some(_), true) => "cached".to_string(),
                (Some(s), false) => format!("{s:.1}"),
            }
        ));
    }
    out
}

/// Plots each row's RMSE after Gaussian + EMA against frames (log scale).
pub fn plot(t: &Table, path: &Path) -> Result<(), String> {
    use crate::export::plot::{Labels, PALETTE, Series, line_plot};
    let series: Vec<Series> = t
        .rows
        .iter()
        .enumerate()
        .map(|(i, r)| Series {
            label: r.mask.clone(),
            color: PALETTE[i % PALETTE.len()],
            points: r
                .curve
                .iter()
                .enumerate()
                .map(|(f, &e)| ((f + 1) as f64, e))
                .collect(),
        })
        .collect();
    let labels = Labels {
        title: format!(
            "{}x{}x{}: error after Gaussian σ 1.3435 + EMA α 0.1",
            t.dims[0], t.dims[1], t.dims[2]
        ),
        x: "frames".into(),
        y: "RMSE over thresholds (log scale)".into(),
    };
    line_plot(path, &series, &labels, true).map(|_| ())
}

impl Table {
    /// The row named `prefix…`.
    pub fn row(&self, prefix: &str) -> Option<&Row> {
        self.rows.iter().find(|r| r.mask.starts_with(prefix))
    }
}
