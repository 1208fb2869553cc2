//! Line plots as PNG (loss against time, RMSE against frames), drawn with `plotters` into an
//! RGB buffer: a title, numbered axes with labels, a light grid, a legend, and lines told apart
//! by colour and by marker shape. The font (DejaVu Sans, licence beside it in `assets/`) is
//! embedded, so plots need no system fonts.

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// One curve.
#[derive(Clone, Debug)]
pub struct Series {
    /// Name (the legend entry).
    pub label: String,
    /// Line colour.
    pub color: [u8; 3],
    /// `(x, y)` points in order.
    pub points: Vec<(f64, f64)>,
}

/// What the axes mean.
#[derive(Clone, Debug, Default)]
pub struct Labels {
    /// Above the plot.
    pub title: String,
    /// Under the x axis.
    pub x: String,
    /// Beside the y axis.
    pub y: String,
}

/// Distinct colours for up to ten series (the "tab10" palette).
pub const PALETTE: [[u8; 3]; 10] = [
    [214, 39, 40],
    [31, 119, 180],
    [44, 160, 44],
    [255, 127, 14],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
    [127, 127, 127],
    [188, 189, 34],
];

/// Width and height of every plot, in pixels (the legend takes [`LEGEND_WIDTH`] on the right).
pub const SIZE: (u32, u32) = (960, 500);

/// The legend's column beside the chart, so it never covers a curve.
pub const LEGEND_WIDTH: u32 = 230;

/// Tick values for a log axis over `[lo, hi]`: every 1-2-5 value of each decade in range, then
/// the other mantissas (3, 4, 6, 7, 8, 9) where they stand at least `min_gap` decades from every
/// tick already chosen, so a narrow range still gets several numbered ticks and no label sits
/// over another. A range too narrow for three such ticks also gets the half mantissas (1.5,
/// 2.5, …).
pub fn log_ticks(lo: f64, hi: f64, min_gap: f64) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let (d0, d1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let in_range = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
    let mut out: Vec<f64> = Vec::new();
    let halves = [1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5, 8.5, 9.5];
    for mantissas in [
        &[1.0, 2.0, 5.0][..],
        &[3.0, 4.0, 6.0, 7.0, 8.0, 9.0][..],
        &halves[..],
    ] {
        if mantissas[0] == 1.5 && out.len() >= 3 {
            break;
        }
        for d in d0..=d1 {
            for &m in mantissas {
                let v = m * 10f64.powi(d);
                if in_range(v) && out.iter().all(|&t| (v / t).log10().abs() >= min_gap) {
                    out.push(v);
                }
            }
        }
    }
    out.sort_by(f64::total_cmp);
    out
}

/// For each series, the earlier series it lies on (every shared x within 1 % in y), so the
/// legend can say which lines are hidden under which.
pub fn coinciding(series: &[Series]) -> Vec<Option<usize>> {
    (0..series.len())
        .map(|j| {
            (0..j).find(|&i| {
                let (a, b) = (&series[i].points, &series[j].points);
                a.len() == b.len()
                    && !a.is_empty()
                    && a.iter().zip(b).all(|(p, q)| {
                        p.0 == q.0 && (p.1 - q.1).abs() <= 0.01 * p.1.abs().max(q.1.abs())
                    })
            })
        })
        .collect()
}

const FONT: &str = "sans-serif";

fn register_font() -> Result<(), String> {
    static ONCE: Once = Once::new();
    let mut result = Ok(());
    ONCE.call_once(|| {
        result = plotters::style::register_font(
            FONT,
            FontStyle::Normal,
            include_bytes!("../../assets/DejaVuSans.ttf"),
        )
        .map_err(|_| "the embedded plot font does not parse".to_string());
    });
    result
}

/// The range of the finite points, widened when flat; `None` when there is none.
fn range(series: &[Series], log_y: bool) -> Option<[f64; 4]> {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in series.iter().flat_map(|s| s.points.iter()) {
        if x.is_finite() && y.is_finite() && (!log_y || y > 0.0) {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if x0 > x1 {
        return None;
    }
    if x1 == x0 {
        x1 = x0 + 1.0;
    }
    if y1 == y0 {
        y1 = if log_y { y0 * 10.0 } else { y0 + 1.0 };
    }
    Some([x0, x1, y0, y1])
}

/// Plots `series` into an 800×500 PNG at `path`, y on a log scale when `log_y`. Returns the
/// data ranges `[x_min, x_max, y_min, y_max]` for captions.
pub fn line_plot(
    path: &Path,
    series: &[Series],
    labels: &Labels,
    log_y: bool,
) -> Result<[f64; 4], String> {
    register_font()?;
    let r = range(series, log_y).ok_or("nothing to plot")?;
    let mut buf = vec![255u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, SIZE).into_drawing_area();
        draw(&root, series, labels, log_y, r).map_err(|e| format!("plot: {e}"))?;
        root.present().map_err(|e| format!("plot: {e}"))?;
    }
    let img = image::RgbImage::from_raw(SIZE.0, SIZE.1, buf).ok_or("plot buffer size")?;
    let mut bytes = Vec::new();
    img.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    )
    .map_err(|e| e.to_string())?;
    build_assets::export::write_atomic(path, &bytes)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(r)
}

/// A tick label with at most three significant digits (`0.3`, `12.5`, `4.2e-5`).
fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        return format!("{v:.1e}");
    }
    let digits = (2 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// The legend column: each series' colour, marker and name; a series lying on an earlier one
/// says so (`= IGN`), so a reader counting lines knows why fewer are visible.
fn legend(area: &Area<'_>, series: &[Series]) -> Result<(), Box<dyn std::error::Error>> {
    let under = coinciding(series);
    let top = 50;
    for (i, s) in series.iter().enumerate() {
        let y = top + 22 * i as i32;
        let c = RGBColor(s.color[0], s.color[1], s.color[2]);
        area.draw(&PathElement::new(vec![(8, y), (34, y)], c.stroke_width(2)))?;
        match i % 3 {
            0 => area.draw(&Circle::new((21, y), 3, c.filled()))?,
            1 => area.draw(&TriangleMarker::new((21, y), 4, c.filled()))?,
            _ => area.draw(&Cross::new((21, y), 4, c.stroke_width(2)))?,
        }
        let name = match under[i] {
            Some(j) => format!("{} (= {})", s.label, series[j].label),
            None => s.label.clone(),
        };
        area.draw(&Text::new(
            name,
            (42, y - 8),
            (FONT, 14).into_font().color(&BLACK),
        ))?;
    }
    Ok(())
}

fn draw(
    root: &Area<'_>,
    series: &[Series],
    labels: &Labels,
    log_y: bool,
    [x0, x1, y0, y1]: [f64; 4],
) -> Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let (plot_area, legend_area) = root.split_horizontally(SIZE.0 - LEGEND_WIDTH);
    legend(&legend_area, series)?;
    let mut builder = ChartBuilder::on(&plot_area);
    builder
        .caption(&labels.title, (FONT, 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70);
    let style = |s: &Series| RGBColor(s.color[0], s.color[1], s.color[2]);
    // Markers: every series gets its colour and one of three shapes, so lines stay apart in
    // grey print and for readers who do not tell the colours apart.
    macro_rules! body {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(&labels.x)
                .y_desc(&labels.y)
                .label_style((FONT, 14))
                .axis_desc_style((FONT, 16))
                .light_line_style(RGBColor(235, 235, 235))
                .max_light_lines(2)
                .x_label_formatter(&|v| number(*v))
                .y_label_formatter(&|v| number(*v))
                .draw()?;
            for (i, s) in series.iter().enumerate() {
                let c = style(s);
                let pts: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|&(x, y)| x.is_finite() && y.is_finite() && (!log_y || y > 0.0))
                    .collect();
                let every = (pts.len() / 12).max(1);
                let marks: Vec<(f64, f64)> = pts.iter().copied().step_by(every).collect();
                chart.draw_series(LineSeries::new(pts, c.stroke_width(2)))?;
                match i % 3 {
                    0 => {
                        chart.draw_series(marks.iter().map(|&p| Circle::new(p, 3, c.filled())))?;
                    }
                    1 => {
                        chart.draw_series(
                            marks.iter().map(|&p| TriangleMarker::new(p, 4, c.filled())),
                        )?;
                    }
                    _ => {
                        chart.draw_series(
                            marks.iter().map(|&p| Cross::new(p, 4, c.stroke_width(2))),
                        )?;
                    }
                }
            }
        }};
    }
    if log_y {
        // A little room above and below, and numbered ticks a reader can read values off.
        let (lo, hi) = (y0 / 1.12, y1 * 1.12);
        // Labels 14 px high need about 20 px between ticks on a plot area of about 400 px.
        let ticks = log_ticks(lo, hi, 20.0 / 400.0 * (hi / lo).log10());
        body!(builder.build_cartesian_2d(x0..x1, (lo..hi).log_scale().with_key_points(ticks))?);
    } else {
        let pad = (y1 - y0) * 0.05;
        body!(builder.build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))?);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_numbers_are_short() {
        assert_eq!(number(0.30000000001), "0.3");
        assert_eq!(number(12.5), "12.5");
        assert_eq!(number(45.0), "45");
        assert_eq!(number(0.00004), "4.0e-5");
        assert_eq!(number(-0.125), "-0.125");
    }

    #[test]
    fn a_plot_is_a_png_of_the_stated_size_with_text_and_every_colour() {
        let dir = std::env::temp_dir().join(format!("noisebake-plot-{}", std::process::id()));
        let path = dir.join("p.png");
        let series: Vec<Series> = (0..3)
            .map(|i| Series {
                label: format!("series {i}"),
                color: PALETTE[i],
                points: (1..50).map(|x| (x as f64, 1.0 / (x + i) as f64)).collect(),
            })
            .collect();
        let labels = Labels {
            title: "RMSE against frames".into(),
            x: "frames".into(),
            y: "RMSE".into(),
        };
        let r = line_plot(&path, &series, &labels, true).unwrap();
        assert_eq!(r[0], 1.0);
        assert_eq!(r[1], 49.0);
        let img = image::open(&path).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), SIZE);
        for s in &series {
            assert!(
                img.pixels().any(|p| p.0 == s.color),
                "no pixel of {:?}",
                s.color
            );
        }
        // Text (numbers, labels, the title) is drawn in black and grey antialiased glyphs:
        // many dark pixels outside the two axis lines.
        let dark = img
            .pixels()
            .filter(|p| p.0.iter().all(|&c| c < 100))
            .count();
        assert!(dark > 2000, "{dark} dark pixels: no text?");
        assert!(line_plot(&path, &[], &labels, false).is_err());
        if std::env::var_os("NOISEBAKE_KEEP_PLOT").is_none() {
            let _ = std::fs::remove_dir_all(dir);
        }
    }
}

#[cfg(test)]
mod tick_tests {
    use super::*;

    /// A narrow log range gets the 1-2-5 ticks and the mantissas between that fit; a wide one
    /// only 1-2-5; no two ticks closer than the gap asked for.
    #[test]
    fn log_ticks_cover_the_range_without_crowding() {
        let t = log_ticks(0.05, 0.4, 0.04);
        for v in [0.05, 0.1, 0.2, 0.06, 0.08, 0.3] {
            assert!(
                t.iter().any(|&x| (x - v).abs() < 1e-12),
                "{v} missing from {t:?}"
            );
        }
        let wide = log_ticks(1e-4, 1.0, 0.2);
        assert!(
            wide.contains(&1e-3)
                && wide.contains(&0.5)
                && !wide.iter().any(|&x| (x - 0.3).abs() < 1e-12)
        );
        for ticks in [t, wide, log_ticks(0.0031, 0.0049, 0.02)] {
            assert!(ticks.len() >= 2, "{ticks:?}");
            for w in ticks.windows(2) {
                assert!(w[1] > w[0]);
            }
        }
        assert!(log_ticks(0.0, 1.0, 0.1).is_empty());
    }

    /// A series on top of another is named with it; distinct ones are not.
    #[test]
    fn coinciding_series_are_found() {
        let s = |y: f64| Series {
            label: String::new(),
            color: [0; 3],
            points: (1..10).map(|x| (x as f64, y / x as f64)).collect(),
        };
        assert_eq!(
            coinciding(&[s(1.0), s(1.005), s(2.0)]),
            vec![None, Some(0), None]
        );
    }
}
