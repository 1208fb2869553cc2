//! Render-level check of stochastic noise (Fajardo & Pharr §7.2, Tables 2–3): a procedural cloud
//! of fBm density, single scattering from a light above, rendered with ratio tracking — once
//! with deterministic fBm and once with the one-sample fBm estimator — at 16 and 64 samples per
//! pixel. Both are unbiased: the density enters every estimate linearly (the scattering
//! coefficient, and each factor `1 − σ̂/σ̄` of ratio tracking uses its own independent ξ), which
//! is exactly where the paper says stochastic noise is safe. Reports time and RMSE against a
//! 1024-spp reference for each (single thread).

use build_assets::export::png::write_slices;
use build_assets::spec::Format;
use build_assets::texture::Texture;
use noisebake::stochastic::{Fractal, fbm3, fbm3_stochastic};
use std::time::Instant;

const SIZE: usize = 64;
const OCTAVES: Fractal = Fractal::new(8, 2.0, 0.5);
/// Majorant of ratio tracking (density units per unit length).
const MAJORANT: f32 = 12.0;

/// Per-pixel random numbers (SplitMix64).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / 16_777_216.0
    }
}

/// Density at `p` in the unit cube: a ball modulated by fBm. `xi` selects the estimator.
fn density(p: [f32; 3], xi: Option<f32>) -> f32 {
    let r2 = (p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2) + (p[2] - 0.5).powi(2);
    let shape = (1.0 - 4.0 * r2).max(0.0);
    if shape == 0.0 {
        return 0.0;
    }
    let q = [p[0] * 3.0, p[1] * 3.0, p[2] * 3.0];
    let n = match xi {
        None => fbm3(q, OCTAVES, 3),
        Some(x) => fbm3_stochastic(q, OCTAVES, 3, x),
    };
    // Linear in the noise (no clamp), so the stochastic form stays unbiased.
    6.0 * shape * (1.0 + n)
}

/// Ratio-tracking transmittance from `o` along `d` over length `len`.
fn transmittance(o: [f32; 3], d: [f32; 3], len: f32, rng: &mut Rng, stochastic: bool) -> f32 {
    let mut t = 0.0;
    let mut tr = 1.0;
    loop {
        t -= (1.0 - rng.next()).ln() / MAJORANT;
        if t >= len {
            return tr;
        }
        let p = [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
        let xi = stochastic.then(|| rng.next());
        tr *= 1.0 - density(p, xi) / MAJORANT;
    }
}

/// One single-scattering sample of the ray through pixel `(x, y)` (looking along +z, light
/// from −y): a uniform point along the ray, σ̂_s there, transmittance to the eye and the light.
fn sample(x: usize, y: usize, rng: &mut Rng, stochastic: bool) -> f32 {
    let u = (x as f32 + rng.next()) / SIZE as f32;
    let v = (y as f32 + rng.next()) / SIZE as f32;
    let t = rng.next();
    let p = [u, v, t];
    let xi = stochastic.then(|| rng.next());
    let sigma = density(p, xi);
    if sigma == 0.0 {
        return 0.0;
    }
    let view = transmittance([u, v, 0.0], [0.0, 0.0, 1.0], t, rng, stochastic);
    let light = transmittance(p, [0.0, -1.0, 0.0], v, rng, stochastic);
    0.8 * sigma * view * light
}

fn render(spp: usize, stochastic: bool, seed: u64) -> (Vec<f32>, f64) {
    let start = Instant::now();
    let img = (0..SIZE * SIZE)
        .map(|i| {
            let mut rng = Rng(seed ^ (i as u64).wrapping_mul(0x2545_f491_4f6c_dd1d));
            (0..spp)
                .map(|_| sample(i % SIZE, i / SIZE, &mut rng, stochastic))
                .sum::<f32>()
                / spp as f32
        })
        .collect();
    (img, start.elapsed().as_secs_f64())
}

fn rmse(a: &[f32], b: &[f32]) -> f64 {
    (a.iter()
        .zip(b)
        .map(|(x, y)| ((x - y) as f64).powi(2))
        .sum::<f64>()
        / a.len() as f64)
        .sqrt()
}

fn save(dir: &std::path::Path, name: &str, img: &[f32]) {
    let t = Texture {
        name: name.into(),
        dims: vec![SIZE, SIZE],
        format: Format::U8,
        data: img
            .iter()
            .map(|&v| (v.clamp(0.0, 1.0) * 255.0) as u8)
            .collect(),
    };
    write_slices(&t, dir, name).expect("write png");
}

/// Renders the reference and the four variants into `dir`; returns `(label, seconds, RMSE)`
/// rows and prints them.
pub fn run(dir: &std::path::Path) -> Vec<(String, f64, f64)> {
    let mut rows = Vec::new();
    println!(
        "cloud: {SIZE}x{SIZE}, 8-octave fBm density, single scattering, ratio tracking (1 thread)"
    );
    let (reference, secs) = render(1024, false, 99);
    println!("reference: 1024 spp deterministic in {secs:.1} s");
    save(dir, "cloud_reference", &reference);
    println!("{:>5} {:<14} {:>9} {:>9}", "spp", "noise", "time s", "RMSE");
    for spp in [16, 64] {
        for stochastic in [false, true] {
            let (img, secs) = render(spp, stochastic, 7 + spp as u64);
            let name = if stochastic {
                "stochastic"
            } else {
                "deterministic"
            };
            let e = rmse(&img, &reference);
            println!("{spp:>5} {name:<14} {secs:>9.2} {e:>9.5}");
            save(dir, &format!("cloud_{name}_{spp}spp"), &img);
            rows.push((format!("{name}_{spp}spp"), secs, e));
        }
    }
    rows
}
