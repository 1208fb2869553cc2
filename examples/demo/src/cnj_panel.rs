//! The curl-noise-jittering panel: cellular images shaded through the region cache (Worley F1,
//! cell borders F2 − F1, the foam SDF of CNJ eq. 12, cell colours), and CNJ points next to random
//! jitter with their point-set quality (ν_eff, ā, q; CNJ §2.4).

use noisebake::cnj::{Cnj2, Region2};
use noisebake_cli::analysis::points::table2;
use noisebake_cli::points::{Method, generate};
use rayon::prelude::*;
use std::path::Path;
use std::time::Instant;

/// One row of the panel's table.
pub struct Row {
    /// What was rendered or measured.
    pub what: String,
    /// Seconds.
    pub seconds: f64,
    /// Quality (ν_eff, ā, q) for point sets.
    pub quality: Option<(f64, f64, f64)>,
}

fn gray(path: &Path, img: &[f32], size: usize) -> Result<(), String> {
    let buf: Vec<u8> = img
        .iter()
        .map(|&v| (v.clamp(0.0, 1.0) * 255.0) as u8)
        .collect();
    let mut bytes = Vec::new();
    image::GrayImage::from_raw(size as u32, size as u32, buf)
        .ok_or("size")?
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .map_err(|e| e.to_string())?;
    build_assets::export::write_atomic(path, &bytes).map_err(|e| e.to_string())
}

/// Renders the panel into `dir` (`size`² images); returns the table rows.
pub fn run(dir: &Path, size: usize) -> Result<Vec<Row>, String> {
    let mut rows = Vec::new();
    let c = Cnj2::default()
        .with_spacing(size as f32 / 24.0)
        .map_err(|e| e.to_string())?;
    let max = [size as f32, size as f32];
    let start = Instant::now();
    let (origin, dims) = c.region_dims([0.0, 0.0], max);
    let mut buf = vec![[0.0f32; 2]; dims[0] * dims[1]];
    buf.par_chunks_mut(dims[0] * 4)
        .enumerate()
        .for_each(|(k, rows)| {
            c.fill_rows(origin, dims, k * 4, rows);
        });
    let region = Region2::from_parts(c, origin, dims, &buf);
    let cells: Vec<_> = (0..size * size)
        .into_par_iter()
        .map(|i| region.cells([(i % size) as f32 + 0.5, (i / size) as f32 + 0.5]))
        .collect();
    rows.push(Row {
        what: format!("{size}x{size} cells (F1..F4) through the region cache, 2 threads"),
        seconds: start.elapsed().as_secs_f64(),
        quality: None,
    });
    let sp = c.spacing();
    let f1: Vec<f32> = cells.iter().map(|k| k.f1() / sp).collect();
    let border: Vec<f32> = cells
        .iter()
        .map(|k| (k.f2_minus_f1() / sp * 4.0).min(1.0))
        .collect();
    let foam: Vec<f32> = cells
        .iter()
        .map(|k| if k.foam12(0.06 * sp) < 0.0 { 0.15 } else { 0.9 })
        .collect();
    let id: Vec<f32> = cells.iter().map(|k| k.cell_id()).collect();
    gray(&dir.join("cnj_f1.png"), &f1, size)?;
    gray(&dir.join("cnj_f2_minus_f1.png"), &border, size)?;
    gray(&dir.join("cnj_foam.png"), &foam, size)?;
    gray(&dir.join("cnj_cells.png"), &id, size)?;
    for (name, m) in [
        ("cnj", Method::Cnj),
        ("jitter", Method::Jitter),
        ("poisson-disk", Method::PoissonDisk),
    ] {
        // The quality is CNJ Table 2's mean over 20 sets, as `noisebake report cnj` prints it
        // (one set's ν_eff is too noisy to compare methods by); the image shows one of them.
        let q = table2(m, 1000, 20);
        let pts = generate(m, 1000, 1);
        let mut img = vec![1.0f32; size * size];
        for p in &pts {
            let (x, y) = ((p[0] * size as f64) as usize, (p[1] * size as f64) as usize);
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                if x + dx < size && y + dy < size {
                    img[(y + dy) * size + x + dx] = 0.0;
                }
            }
        }
        gray(&dir.join(format!("points_{name}.png")), &img, size)?;
        rows.push(Row {
            what: format!("points_{name}"),
            seconds: q.ms_per_set / 1e3,
            quality: Some((q.nu_eff, q.anisotropy, q.q)),
        });
    }
    Ok(rows)
}
