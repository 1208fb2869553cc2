//! Images, convergence plots, `index.html` and the terminal summary.

use crate::{AppResult, Config};
use build_assets::export::write_atomic;
use noisebake_cli::export::plot::{Labels, PALETTE, Series, line_plot};
use std::fmt::Write as _;
use std::path::Path;

/// Writes an image (values in [0, 1], `c` = 1 or 3 channels) as an 8-bit PNG.
pub fn png(path: &Path, img: &[f32], [w, h]: [usize; 2], c: usize) -> Result<(), String> {
    let to8 = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    let mut bytes = Vec::new();
    let enc = if c == 3 {
        let buf: Vec<u8> = img.iter().map(|&v| to8(v)).collect();
        image::RgbImage::from_raw(w as u32, h as u32, buf)
            .ok_or("image size")?
            .write_to(
                &mut std::io::Cursor::new(&mut bytes),
                image::ImageFormat::Png,
            )
    } else {
        let buf: Vec<u8> = img.iter().map(|&v| to8(v)).collect();
        image::GrayImage::from_raw(w as u32, h as u32, buf)
            .ok_or("image size")?
            .write_to(
                &mut std::io::Cursor::new(&mut bytes),
                image::ImageFormat::Png,
            )
    };
    enc.map_err(|e| e.to_string())?;
    write_atomic(path, &bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Writes every image, the plots and `index.html` under `dir`.
pub fn write(dir: &Path, cfg: &Config, results: &[AppResult]) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut html = String::from(
        "<!doctype html><meta charset=utf-8><title>noisebake demo</title>\n<style>body{font-family:sans-serif;max-width:1400px;margin:auto}img{image-rendering:pixelated;width:192px}td,th{padding:2px 6px;text-align:center;font-size:13px}figure{display:inline-block;margin:4px}</style>\n<h1>noisebake demo</h1>\n<p>Every image is rendered on the CPU with one random number (or direction) per pixel and frame from the named noise; RMSE is against the converged reference. EMA: α = 0.1. Plots: RMSE (log axis) against frames, one line per noise; curves that lie on top of each other are named together in the legend. The ± after EMA + blur is the standard error from the per-pixel spread: noises within twice the combined error of the best are tied.</p>\n",
    );
    let mc = cfg.mc_frames.min(cfg.frames);
    for r in results {
        let app = r.name;
        png(
            &dir.join(format!("{app}_reference.png")),
            &r.reference,
            cfg.size,
            r.channels,
        )?;
        let _ = write!(
            html,
            "<h2>{app}</h2><p>{}</p><figure><img src=\"{app}_reference.png\" alt=\"{app}: reference image\"><figcaption>reference</figcaption></figure>\n<table><tr><th>noise</th><th>1 frame</th><th>{mc}-frame average</th><th>{}-frame EMA</th><th>RMSE: 1 frame</th><th>blurred</th><th>{mc}-frame mean</th><th>EMA {}</th><th>EMA {} + blur</th><th>render s</th></tr>\n",
            r.caption, cfg.frames, cfg.frames, cfg.frames
        );
        for (m, imgs) in &r.runs {
            let n = m.noise.name();
            for (img, tag) in imgs.iter().zip(["1", "mc", "ema"]) {
                png(
                    &dir.join(format!("{app}_{n}_{tag}.png")),
                    img,
                    cfg.size,
                    r.channels,
                )?;
            }
            let ema_frames = cfg.frames;
            let _ = writeln!(
                html,
                "<tr><td>{n}</td><td><img src=\"{app}_{n}_1.png\" alt=\"{app} with {n}: one frame\"></td><td><img src=\"{app}_{n}_mc.png\" alt=\"{app} with {n}: {mc}-frame average\"></td><td><img src=\"{app}_{n}_ema.png\" alt=\"{app} with {n}: EMA after {ema_frames} frames\"></td><td>{:.4}</td><td>{:.4}</td><td>{:.4}</td><td>{:.4}</td><td>{:.4} ± {:.4}</td><td>{:.2}</td></tr>",
                m.mc[0],
                m.filtered_1,
                m.mc[mc - 1],
                m.ema[cfg.frames - 1],
                m.denoised,
                m.denoised_se,
                m.seconds
            );
        }
        html += "</table>\n";
        let _ = writeln!(html, "<p><b>{}</b></p>", verdict(r));
        for (kind, title) in [
            ("mc", "mean of the first k frames"),
            ("ema", "exponential moving average"),
            ("ema_blur", "EMA + blur (the verdict's metric)"),
        ] {
            let series: Vec<Series> = r
                .runs
                .iter()
                .enumerate()
                .map(|(i, (m, _))| Series {
                    label: m.noise.name().into(),
                    color: PALETTE[i % PALETTE.len()],
                    points: match kind {
                        "mc" => frames_curve(&m.mc),
                        "ema" => frames_curve(&m.ema),
                        _ => m.ema_blur.iter().map(|&(f, e)| (f as f64, e)).collect(),
                    },
                })
                .collect();
            let file = format!("{app}_{kind}_convergence.png");
            let labels = Labels {
                title: format!("{app}: {title}"),
                x: "frames".into(),
                y: "RMSE (log axis)".into(),
            };
            let range = line_plot(&dir.join(&file), &series, &labels, true)?;
            let _ = writeln!(
                html,
                "<figure><img style=\"width:560px\" src=\"{file}\" alt=\"{app}: RMSE of the {title} against frames, one line per noise\"><figcaption>{title}: RMSE {} to {} over frames {:.0}–{:.0}</figcaption></figure>",
                fmt_rmse(range[2]),
                fmt_rmse(range[3]),
                range[0],
                range[1],
            );
        }
    }
    write_atomic(&dir.join("index.html"), html.as_bytes()).map_err(|e| format!("index.html: {e}"))
}

fn frames_curve(v: &[f64]) -> Vec<(f64, f64)> {
    v.iter()
        .enumerate()
        .map(|(f, &e)| ((f + 1) as f64, e))
        .collect()
}

fn fmt_rmse(v: f64) -> String {
    format!("{v:.4}")
}

/// Prints the per-application, per-noise table.
pub fn summary(results: &[AppResult], cfg: &Config) {
    let mc = cfg.mc_frames.min(cfg.frames);
    let frames = cfg.frames;
    println!("\nRMSE against the converged reference, lower is better (the page's columns):");
    println!(
        "  1 frame: one frame as rendered; blurred: that frame after a Gaussian blur of σ 1 px"
    );
    println!(
        "  (both it and the reference, as a spatial denoiser sees it); {mc}-frame mean: the average of the"
    );
    println!(
        "  first {mc} frames; EMA {frames}: an exponential moving average (α {}) after {frames} frames;",
        crate::EMA_ALPHA
    );
    println!(
        "  EMA {frames} + blur: that EMA after the same blur, the verdict's metric (± its standard error)."
    );
    println!(
        "\n{:<13} {:<14} {:>9} {:>9} {:>9} {:>9} {:>18} {:>9}",
        "application",
        "noise",
        "1 frame",
        "blurred",
        format!("{mc}-mean"),
        format!("EMA {frames}"),
        format!("EMA {frames} + blur"),
        "render s"
    );
    for r in results {
        for (m, _) in &r.runs {
            println!(
                "{:<13} {:<14} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>10.4} ± {:.4} {:>9.2}",
                r.name,
                m.noise.name(),
                m.mc[0],
                m.filtered_1,
                m.mc[mc - 1],
                m.ema[cfg.frames - 1],
                m.denoised,
                m.denoised_se,
                m.seconds
            );
        }
        println!(
            "{:<13} {:<14} reference rendered in {:.2} s",
            r.name, "", r.reference_seconds
        );
        println!("{:<13} {}", "", verdict(r));
    }
}

/// One contender of a verdict: its name, its error and that error's standard error, and
/// whether it is free (computed in the shader: no texture or table to ship).
pub struct Contender<'a> {
    /// Name.
    pub name: &'a str,
    /// Error.
    pub err: f64,
    /// Its standard error.
    pub se: f64,
    /// Needs no texture.
    pub free: bool,
}

/// The verdict of a panel, from its own numbers: which contender leaves the least error
/// (`measure` names what was measured), which are tied with it (within twice the standard
/// error of the difference), and whether the best free one (white noise aside) is as good —
/// tied, within 5 %, or how much more it leaves. Every panel of the demo says it this way.
pub fn judge(measure: &str, rows: &[Contender<'_>]) -> String {
    let Some(best) = rows.iter().min_by(|a, b| a.err.total_cmp(&b.err)) else {
        return String::new();
    };
    let tied = |r: &Contender<'_>| (r.err - best.err).abs() <= 2.0 * r.se.hypot(best.se);
    let mut s = format!(
        "least error {measure}: {} ({:.4} ± {:.4})",
        best.name, best.err, best.se
    );
    let ties: Vec<&str> = rows
        .iter()
        .filter(|r| r.name != best.name && tied(r))
        .map(|r| r.name)
        .collect();
    if !ties.is_empty() {
        s += &format!(
            ", tied within twice the standard error with {}",
            ties.join(", ")
        );
    }
    let free = rows
        .iter()
        .filter(|r| r.free && r.name != "white")
        .min_by(|a, b| a.err.total_cmp(&b.err));
    if let Some(f) = free {
        if f.name == best.name {
            s += "; a free construction wins here: no texture needed";
        } else if tied(f) {
            s += &format!("; {} ties it and needs no texture", f.name);
        } else if f.err <= 1.05 * best.err {
            s += &format!(
                "; {} ({:.4}) is within 5 % and needs no texture",
                f.name, f.err
            );
        } else {
            s += &format!(
                "; the best free construction, {}, leaves {:.0} % more",
                f.name,
                100.0 * (f.err / best.err - 1.0)
            );
        }
    }
    s
}

/// Which noise leaves the least error in an application after EMA + blur ([`judge`]).
pub fn verdict(r: &AppResult) -> String {
    let rows: Vec<Contender<'_>> = r
        .runs
        .iter()
        .map(|(m, _)| Contender {
            name: m.noise.name(),
            err: m.denoised,
            se: m.denoised_se,
            free: m.noise.is_free_hash(),
        })
        .collect();
    judge("after EMA + blur", &rows)
}

/// Appends the CNJ and stochastic-noise panels to `index.html`.
pub fn extra_panels(
    dir: &Path,
    cnj: &[crate::cnj_panel::Row],
    cloud: &crate::cloud::Panel,
) -> Result<(), String> {
    let path = dir.join("index.html");
    let mut html = std::fs::read_to_string(&path).map_err(|e| format!("index.html: {e}"))?;
    html += "<h2>curl-noise jittering</h2><p>Implicit blue-noise points (Bærentzen et al. 2023): every lattice site is displaced along a curl-noise field; cells are shaded from a region cache of jittered sites. Left to right: Worley F1, cell borders F2 − F1, the foam SDF of eq. (12), cell colours; then 1000-point sets with their point-set quality.</p>\n";
    for f in ["cnj_f1", "cnj_f2_minus_f1", "cnj_foam", "cnj_cells"] {
        let _ = write!(
            html,
            "<figure><img src=\"{f}.png\" style=\"width:256px\" alt=\"{f}\"><figcaption>{f}</figcaption></figure>"
        );
    }
    html += "<br>";
    for r in cnj {
        if let Some((nu, a, q)) = r.quality {
            let _ = write!(
                html,
                "<figure><img src=\"{}.png\" style=\"width:256px\" alt=\"{} point set\"><figcaption>{}: ν_eff {nu:.3}, ā {a:.1}, q {q:.5}, {:.2} ms</figcaption></figure>",
                r.what,
                r.what,
                r.what,
                r.seconds * 1e3
            );
        } else {
            let _ = write!(html, "<p>{}: {:.1} ms</p>", r.what, r.seconds * 1e3);
        }
    }
    let _ = write!(
        html,
        "<pre>{}</pre>",
        noisebake_cli::analysis::points::READING
    );
    html += "<h2>stochastic noise</h2><p>A procedural fBm cloud (single scattering, ratio tracking) with the density evaluated deterministically, by the one-sample fBm estimator (Fajardo &amp; Pharr), or with its largest octaves exact and one octave of the rest sampled; all unbiased, RMSE against 1024 spp. The table compares them at equal time (`cargo run --release --example cloud` adds the paper's Table 3 scene and a procedural material).</p>\n";
    let _ = writeln!(html, "<pre>{}</pre>", cloud.table);
    html += "<figure><img src=\"cloud_reference.png\" style=\"width:256px\" alt=\"fBm cloud, 1024-spp reference\"><figcaption>reference</figcaption></figure>";
    for (name, secs, e) in &cloud.images {
        let _ = write!(
            html,
            "<figure><img src=\"cloud_{name}.png\" style=\"width:256px\" alt=\"fBm cloud rendered with {name}\"><figcaption>{name}: {secs:.2} s, RMSE {e:.4}</figcaption></figure>"
        );
    }
    write_atomic(&path, html.as_bytes()).map_err(|e| format!("index.html: {e}"))
}
