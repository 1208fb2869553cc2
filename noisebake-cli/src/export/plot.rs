//! Line plots as PNG (loss against time, RMSE against frames): axes with tick marks and one
//! coloured polyline per series. Labels live next to the image (report text, HTML captions).

use image::{Rgb, RgbImage};
use std::path::Path;

/// One curve.
#[derive(Clone, Debug)]
pub struct Series {
    /// Name (for the caption).
    pub label: String,
    /// Line colour.
    pub color: [u8; 3],
    /// `(x, y)` points in order.
    pub points: Vec<(f64, f64)>,
}

/// Distinct colours for up to eight series.
pub const PALETTE: [[u8; 3]; 8] = [
    [214, 39, 40],
    [31, 119, 180],
    [44, 160, 44],
    [255, 127, 14],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
];

const W: u32 = 640;
const H: u32 = 400;
const M: i64 = 40;

fn line(img: &mut RgbImage, a: (i64, i64), b: (i64, i64), c: [u8; 3]) {
    let (dx, dy) = ((b.0 - a.0).abs(), -(b.1 - a.1).abs());
    let (sx, sy) = (
        if a.0 < b.0 { 1 } else { -1 },
        if a.1 < b.1 { 1 } else { -1 },
    );
    let (mut x, mut y, mut err) = (a.0, a.1, dx + dy);
    loop {
        for (ox, oy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let (px, py) = (x + ox, y + oy);
            if (0..W as i64).contains(&px) && (0..H as i64).contains(&py) {
                img.put_pixel(px as u32, py as u32, Rgb(c));
            }
        }
        if (x, y) == b {
            break;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x += sx;
        }
        if e2 <= dx {
            err += dx;
            y += sy;
        }
    }
}

/// Plots `series` into a 640×400 PNG at `path`; `log_y` plots log10 of y. Returns the axis
/// ranges `(x_min, x_max, y_min, y_max)` (in plotted units) for the caption.
pub fn line_plot(path: &Path, series: &[Series], log_y: bool) -> Result<[f64; 4], String> {
    let ty = |y: f64| if log_y { y.max(1e-12).log10() } else { y };
    let pts = series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in pts {
        let y = ty(y);
        if x.is_finite() && y.is_finite() {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if x0 > x1 {
        return Err("nothing to plot".into());
    }
    if x1 == x0 {
        x1 = x0 + 1.0;
    }
    if y1 == y0 {
        y1 = y0 + 1.0;
    }
    let mut img = RgbImage::from_pixel(W, H, Rgb([255, 255, 255]));
    let (pw, ph) = ((W as i64 - 2 * M) as f64, (H as i64 - 2 * M) as f64);
    let map = |x: f64, y: f64| {
        (
            M + ((x - x0) / (x1 - x0) * pw).round() as i64,
            H as i64 - M - ((ty(y) - y0) / (y1 - y0) * ph).round() as i64,
        )
    };
    let grey = [160, 160, 160];
    let (l, r, b, t) = (M, W as i64 - M, H as i64 - M, M);
    line(&mut img, (l, b), (r, b), [0, 0, 0]);
    line(&mut img, (l, b), (l, t), [0, 0, 0]);
    for k in 1..=4 {
        let gx = l + (r - l) * k / 4;
        let gy = b - (b - t) * k / 4;
        line(&mut img, (gx, b), (gx, b + 5), [0, 0, 0]);
        line(&mut img, (l - 5, gy), (l, gy), [0, 0, 0]);
        for x in (l..r).step_by(6) {
            img.put_pixel(x as u32, gy as u32, Rgb(grey));
        }
    }
    for s in series {
        for w in s.points.windows(2) {
            line(&mut img, map(w[0].0, w[0].1), map(w[1].0, w[1].1), s.color);
        }
    }
    build_assets::export::write_atomic(path, &{
        let mut bytes = Vec::new();
        img.write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .map_err(|e| e.to_string())?;
        bytes
    })
    .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok([x0, x1, y0, y1])
}
