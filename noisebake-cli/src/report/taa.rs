//! Which mask survives temporal anti-aliasing (`noisebake report taa`): the error after the
//! history clamp games run, for binary dithers at three coverages and for continuous
//! integrands, with a static and a moving camera ([`crate::analysis::taa`] is the model).
//!
//! **The rows.** Our FAST masks made for the plain EMA and for TAA (`temporal_filter =
//! {kind = "taa"}`), EA's published FAST texture, golden-ratio animated blue noise, and the
//! free constructions games use under TAA: interleaved gradient noise moved 5.588238 pixels
//! per frame and the R2 grid animated by the golden ratio; white noise for scale. All
//! 128 × 128 × 64, made for (or measured after) a Gaussian σ 1.3435 with α 0.1.

use super::kit::{EA_MISSING, bake, ea_path, ea_values, ign, r2, spec};
use crate::analysis::taa::{Clip, Taa, taa_rmse};
use build_assets::generate::fast::{Filter, open_windows};
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;

/// The measured size: EA's published texture's.
pub const DIMS: [usize; 3] = [128, 128, 64];
/// The spatial filter the error is measured after (and the FAST masks are made for).
pub const SIGMA: f64 = 1.3435;
/// The history blend weight.
pub const ALPHA: f64 = 0.1;
/// Whole pixels per frame of the moving camera.
pub const MOTION: [i32; 2] = [3, 1];
/// Bevy's blend weight for a still pixel in low dynamic range, its default. Its TAA blends the
/// new frame at `clamp(1 / confidence, 0.015, 0.1)` and adds 10 to the confidence each frame a
/// pixel is still, but keeps the confidence in the history's alpha channel, and in low dynamic
/// range the history has the view target's 8-bit format: the stored confidence saturates at 1,
/// so every still frame blends at 1 / (1 + 10).
pub const BEVY_LDR_ALPHA: f64 = 1.0 / 11.0;
/// Bevy's blend weight for a pixel still for a few frames with `Hdr` (a float history, whose
/// confidence grows until the blend reaches this floor).
pub const BEVY_HDR_STILL_ALPHA: f64 = 0.015;
/// Other motions the 25 % dither is measured at, with and without the clamp: a mask baked for
/// [`MOTION`] met off the motion it was made for.
pub const OTHER_MOTIONS: [[i32; 2]; 5] = [[-3, 1], [1, 2], [1, 0], [0, -3], [6, 2]];

/// An integrand: name, its estimate from one value, its integral.
pub struct Integrand {
    /// Its name in the table.
    pub name: &'static str,
    /// The one-sample estimate.
    pub phi: fn(f64) -> f64,
    /// `∫₀¹ φ`.
    pub truth: f64,
}

/// Binary dithers `[s < a]` at coverages 0.1, 0.25, 0.5, a soft-edged one (a ramp 0.2 wide
/// around 0.25) and the plain ramp.
pub const INTEGRANDS: [Integrand; 5] = [
    Integrand {
        name: "dither 0.10",
        phi: |s| f64::from(u8::from(s < 0.1)),
        truth: 0.1,
    },
    Integrand {
        name: "dither 0.25",
        phi: |s| f64::from(u8::from(s < 0.25)),
        truth: 0.25,
    },
    Integrand {
        name: "dither 0.50",
        phi: |s| f64::from(u8::from(s < 0.5)),
        truth: 0.5,
    },
    Integrand {
        name: "soft 0.25",
        phi: |s| ((0.35 - s) / 0.2).clamp(0.0, 1.0),
        truth: 0.25,
    },
    Integrand {
        name: "ramp",
        phi: |s| s,
        truth: 0.5,
    },
];

/// The clamps measured: none, 3 × 3 min/max, 3 × 3 variance γ 1.
pub const CLIPS: [Clip; 3] = [Clip::None, Clip::MinMax, Clip::Variance(1.0)];

/// One measurement.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// Integrand name.
    pub integrand: &'static str,
    /// Clamp name.
    pub clip: String,
    /// The history's blend weight.
    pub alpha: f64,
    /// Camera motion in pixels per frame.
    pub motion: [i32; 2],
    /// RMSE after TAA and the spatial filter.
    pub rmse: f64,
}

/// One mask's row.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The mask.
    pub mask: String,
    /// Every integrand × clamp × camera.
    pub cells: Vec<Cell>,
    /// `(coverage, RMSE)` of the dither under the 3 × 3 min/max clamp, static camera, at
    /// [`SWEEP`]'s coverages (the plot).
    pub sweep: Vec<(f64, f64)>,
    /// 3 × 3 windows (of all slices) with no value below 0.2 or none at or above 0.8: where
    /// the clamp acts on the dither of some coverage in [0.2, 0.8]
    /// (`build_assets::generate::fast::open_windows`).
    pub open_windows_0_2: u64,
    /// The same for [0.25, 0.75].
    pub open_windows_0_25: u64,
}

/// The coverages of the plot's sweep.
pub const SWEEP: [f64; 10] = [0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5];

impl Row {
    /// The cell of `integrand` under `clip` with `motion`, blended at [`ALPHA`].
    pub fn rmse(&self, integrand: &str, clip: Clip, motion: [i32; 2]) -> Option<f64> {
        self.rmse_at(integrand, clip, motion, ALPHA)
    }

    /// The cell of `integrand` under `clip` with `motion`, blended at `alpha`.
    pub fn rmse_at(
        &self,
        integrand: &str,
        clip: Clip,
        motion: [i32; 2],
        alpha: f64,
    ) -> Option<f64> {
        self.cells
            .iter()
            .find(|c| {
                c.integrand == integrand
                    && c.clip == clip.name()
                    && c.motion == motion
                    && c.alpha == alpha
            })
            .map(|c| c.rmse)
    }
}

/// Every cell of one mask.
pub fn measure(mask: &str, values: &[f64]) -> Row {
    let taps = Filter::Gauss { sigma: SIGMA }.taps();
    let mut jobs = Vec::new();
    for ig in &INTEGRANDS {
        for clip in CLIPS {
            for motion in [[0, 0], MOTION] {
                jobs.push((ig, clip, motion, ALPHA));
            }
        }
    }
    for motion in OTHER_MOTIONS {
        for clip in [Clip::None, Clip::MinMax] {
            jobs.push((&INTEGRANDS[1], clip, motion, ALPHA));
        }
    }
    // Bevy's TAA with a still camera: variance clipping, and its blend in low dynamic range
    // and, for the 25 % dither, with `Hdr`.
    for ig in &INTEGRANDS[..3] {
        jobs.push((ig, Clip::Variance(1.0), [0, 0], BEVY_LDR_ALPHA));
    }
    jobs.push((
        &INTEGRANDS[1],
        Clip::Variance(1.0),
        [0, 0],
        BEVY_HDR_STILL_ALPHA,
    ));
    let cells = jobs
        .into_par_iter()
        .map(|(ig, clip, motion, alpha)| Cell {
            integrand: ig.name,
            clip: clip.name(),
            alpha,
            motion,
            rmse: taa_rmse(
                values,
                DIMS,
                &ig.phi,
                ig.truth,
                Taa {
                    alpha,
                    clip,
                    motion,
                },
                &taps,
            ),
        })
        .collect();
    let clamp = Taa {
        alpha: ALPHA,
        clip: Clip::MinMax,
        motion: [0, 0],
    };
    let sweep = SWEEP
        .par_iter()
        .map(|&a| {
            let phi = move |s: f64| f64::from(u8::from(s < a));
            (a, taa_rmse(values, DIMS, &phi, a, clamp, &taps))
        })
        .collect();
    Row {
        mask: mask.into(),
        cells,
        sweep,
        open_windows_0_2: open_windows(values, DIMS, 0.2),
        open_windows_0_25: open_windows(values, DIMS, 0.25),
    }
}

/// The report.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// `[w, h, frames]`.
    pub dims: [usize; 3],
    /// One row per mask.
    pub rows: Vec<Row>,
}

/// The FAST spec `extra` keys for a temporal filter, Gaussian σ 1.3435 in space.
fn fast_keys(temporal: &str) -> String {
    format!(
        "spatial_filter = {{ kind = \"gauss\", sigma = {SIGMA} }}\ntemporal_filter = {temporal}"
    )
}

/// Measures every row; writes `taa.json` and `taa.png` under `out`.
pub fn run(out: &Path, log: &mut dyn FnMut(&str)) -> Result<Report, String> {
    let mut rows = Vec::new();
    let baked = |name: &str, kind: &str, extra: &str, log: &mut dyn FnMut(&str)| {
        let (v, secs, cached) = bake(&spec(name, kind, &DIMS, extra), log)?;
        log(&format!(
            "  {name}: {}",
            if cached {
                "cached".to_string()
            } else {
                format!("baked in {secs:.1} s")
            }
        ));
        Ok::<_, String>(v)
    };
    for (name, label, temporal) in [
        (
            "FAST_TAA",
            "FAST (ours, for TAA, coverage 0.2)",
            "{ kind = \"taa\", alpha = 0.1 }",
        ),
        (
            "FAST_TAA25",
            "FAST (ours, for TAA, coverage 0.25)",
            "{ kind = \"taa\", alpha = 0.1, coverage = 0.25 }",
        ),
        (
            "FAST_TAA_MOVING",
            "FAST (ours, for TAA, moving (3, 1))",
            "{ kind = \"taa\", alpha = 0.1, motion = [3, 1] }",
        ),
        (
            "FAST_TAA25_MOVING",
            "FAST (ours, TAA, cov. .25, moving)",
            "{ kind = \"taa\", alpha = 0.1, coverage = 0.25, motion = [3, 1] }",
        ),
        (
            "FAST",
            "FAST (ours, for the plain EMA)",
            "{ kind = \"ema\", alpha = 0.1 }",
        ),
        (
            "FAST_TAA_BEVY",
            "FAST (ours, for TAA at α 0.015)",
            "{ kind = \"taa\", alpha = 0.015 }",
        ),
    ] {
        let v = baked(name, "fast", &fast_keys(temporal), log)?;
        rows.push(measure(label, &v));
    }
    match ea_path() {
        Some(p) => rows.push(measure("FAST (EA, published)", &ea_values(&p)?)),
        None => log(&format!("  {}", EA_MISSING)),
    }
    let gold = baked("GOLD", "golden", "", log)?;
    rows.push(measure("golden-ratio animated blue noise", &gold));
    rows.push(measure("IGN (5.588238 px per frame)", &ign(DIMS)));
    rows.push(measure("R2 (golden-ratio animated)", &r2(DIMS)));
    let white = baked("WHITE", "white", "", log)?;
    rows.push(measure("white noise", &white));
    let report = Report { dims: DIMS, rows };
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let json = out.join("taa.json");
    std::fs::write(
        &json,
        serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?,
    )
    .map_err(|e| format!("{}: {e}", json.display()))?;
    plot(&report, &out.join("taa.png"))?;
    Ok(report)
}

/// Plots each row's error under the clamp against the dither's coverage.
pub fn plot(r: &Report, path: &Path) -> Result<(), String> {
    use crate::export::plot::{Labels, PALETTE, Series, line_plot};
    let series: Vec<Series> = r
        .rows
        .iter()
        .enumerate()
        .map(|(i, row)| Series {
            label: row.mask.clone(),
            color: PALETTE[i % PALETTE.len()],
            points: row.sweep.clone(),
        })
        .collect();
    let labels = Labels {
        title: "dither under TAA (3x3 min/max clamp, α 0.1) + Gaussian σ 1.3435".into(),
        x: "coverage a of the dither [s < a]".into(),
        y: "RMSE (log scale)".into(),
    };
    line_plot(path, &series, &labels, true).map(|_| ())
}

/// A column printed: heading, integrand, clamp, motion, blend weight.
pub type Column = (String, &'static str, Clip, [i32; 2], f64);

/// The columns printed.
pub fn columns() -> Vec<Column> {
    let mut c = Vec::new();
    for ig in [
        "dither 0.25",
        "dither 0.10",
        "dither 0.50",
        "soft 0.25",
        "ramp",
    ] {
        for clip in [Clip::None, Clip::MinMax] {
            let short = if clip == Clip::None { "" } else { " clamp" };
            c.push((format!("{ig}{short}"), ig, clip, [0, 0], ALPHA));
        }
    }
    let var = Clip::Variance(1.0);
    c.push(("d0.25 var".into(), "dither 0.25", var, [0, 0], ALPHA));
    c.push((
        "d0.25 moving".into(),
        "dither 0.25",
        Clip::None,
        MOTION,
        ALPHA,
    ));
    c.push((
        "d0.25 mv clamp".into(),
        "dither 0.25",
        Clip::MinMax,
        MOTION,
        ALPHA,
    ));
    for ig in ["dither 0.25", "dither 0.10", "dither 0.50"] {
        let head = format!("{} bevy", ig.replace("dither ", "d"));
        c.push((head, ig, var, [0, 0], BEVY_LDR_ALPHA));
    }
    c.push((
        "d0.25 bevy hdr".into(),
        "dither 0.25",
        var,
        [0, 0],
        BEVY_HDR_STILL_ALPHA,
    ));
    c
}

/// The table as text.
pub fn describe(r: &Report) -> Vec<String> {
    let cols = columns();
    let mut head = format!("  {:<36}", "mask");
    for (h, ..) in &cols {
        head += &format!(" {:>9}", h.replace("dither ", "d"));
    }
    head += &format!(" {:>9} {:>9}", "open 0.2", "open .25");
    let mut out = vec![head];
    for row in &r.rows {
        let mut line = format!("  {:<36}", row.mask);
        for (_, ig, clip, m, alpha) in &cols {
            line += &format!(
                " {:>9.5}",
                row.rmse_at(ig, *clip, *m, *alpha).unwrap_or(f64::NAN)
            );
        }
        line += &format!(" {:>9} {:>9}", row.open_windows_0_2, row.open_windows_0_25);
        out.push(line);
    }
    out.push(
        "  the 25 % dither at other motions (pixels per frame), without / with the clamp:".into(),
    );
    let mut head = format!("  {:<36}", "mask");
    for m in OTHER_MOTIONS {
        head += &format!(" {:>17}", format!("{m:?}"));
    }
    out.push(head);
    for row in &r.rows {
        let mut line = format!("  {:<36}", row.mask);
        for m in OTHER_MOTIONS {
            let cell = |clip| row.rmse("dither 0.25", clip, m).unwrap_or(f64::NAN);
            line += &format!(
                " {:>17}",
                format!("{:.5}/{:.5}", cell(Clip::None), cell(Clip::MinMax))
            );
        }
        out.push(line);
    }
    out
}

/// What the table's columns mean, printed above it.
pub const READING: &str = "\
RMSE after TAA (α 0.1, the history reprojected, clamped, blended) and a Gaussian σ 1.3435, at
  the steady state over the looping 128x128x64 mask; lower is better. Columns: the integrand
  (d0.25: a binary dither [s < 0.25] at 25 % coverage; soft 0.25: a ramp 0.2 wide around 0.25;
  ramp: s itself), without and with the 3x3 min/max clamp; `var`: variance clipping μ ± σ;
  `moving`: the camera moves (3, 1) pixels per frame and the history is reprojected (and, in the
  second table, at five other motions); `bevy`: Bevy's TAA with a still camera, variance
  clipping μ ± σ and its blend in low dynamic range, 1/11 (its confidence saturates in the
  8-bit history), `bevy hdr` with `Hdr`, 0.015, both on a float history (the `taa3d` example
  measures Bevy itself, whose 8-bit history also rounds). open 0.2 /
  open .25: 3x3 windows (of 1 048 576) lacking a value below 0.2 (0.25) or one at or above 0.8
  (0.75), where the clamp acts on some dither in that range.";

#[cfg(test)]
mod tests {
    use super::*;

    /// The two free constructions games use under TAA, told apart by the clamp: every 3 × 3
    /// window of the R2 grid spreads over the whole range (its nine offsets leave no gap wider
    /// than 0.19), so at coverage 0.25 the clamp never acts on it; interleaved gradient noise
    /// has windows where its inner `fract` wraps, and there the clamp adds error.
    #[test]
    fn the_clamp_spares_the_r2_grid_and_not_ign() {
        let dims = [64, 64, 16];
        let taps = Filter::Gauss { sigma: SIGMA }.taps();
        let phi = |s: f64| f64::from(u8::from(s < 0.25));
        let run = |v: &[f64], clip| {
            let taa = Taa {
                alpha: ALPHA,
                clip,
                motion: [0, 0],
            };
            taa_rmse(v, dims, &phi, 0.25, taa, &taps)
        };
        let (r2, ign) = (r2(dims), ign(dims));
        assert_eq!(open_windows(&r2, dims, 0.25), 0);
        assert_eq!(run(&r2, Clip::MinMax), run(&r2, Clip::None));
        assert!(open_windows(&ign, dims, 0.25) > 0);
        assert!(run(&ign, Clip::MinMax) > 1.2 * run(&ign, Clip::None));
    }

    /// The loss with a `motion` is the error of the EMA followed along it: a mask baked with
    /// it leaves less error under that motion than the mask baked for a still camera, which
    /// leaves less when the camera is still.
    #[test]
    fn a_mask_baked_for_a_motion_does_better_under_it() {
        let dims = [32, 32, 16];
        let taps = Filter::Gauss { sigma: SIGMA }.taps();
        let phi = |s: f64| f64::from(u8::from(s < 0.25));
        let mask = |temporal: &str| {
            let s = spec("M", "fast", &dims, &fast_keys(temporal));
            build_assets::generate(&s, &mut |_, _| {}).values()
        };
        let still = mask("{ kind = \"taa\", alpha = 0.1 }");
        let moving = mask("{ kind = \"taa\", alpha = 0.1, motion = [2, 1], moving = 0.5 }");
        let run = |v: &[f64], motion| {
            let taa = Taa {
                alpha: ALPHA,
                clip: Clip::None,
                motion,
            };
            taa_rmse(v, dims, &phi, 0.25, taa, &taps)
        };
        let (a, b) = (run(&still, [2, 1]), run(&moving, [2, 1]));
        assert!(b < 0.95 * a, "moving: still mask {a}, moving mask {b}");
        let (a, b) = (run(&still, [0, 0]), run(&moving, [0, 0]));
        assert!(a < b, "still: still mask {a}, moving mask {b}");
    }
}
