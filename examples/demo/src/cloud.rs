//! Stochastic noise where it is meant to pay (Fajardo & Pharr §7.2, Tables 2–3): inside Monte
//! Carlo renderers that already draw many random numbers per pixel, with the noise evaluated
//! deterministically or by one-sample estimators, compared at equal time
//! (the [`equal_time`](mod@crate::equal_time) module).
//!
//! Three scenes:
//! - **`cloud`** (the demo's panel): a 64×64 cloud of 8-octave Perlin fBm density, single
//!   scattering from a light above, ratio tracking with a fixed majorant.
//! - **`paper-cloud-*`**: the paper's Table 3 setting at a size a CPU renders in seconds:
//!   volumetric path tracing with delta tracking and null scattering (weighted, so any majorant
//!   is unbiased), multiple scattering, 10 octaves of Perlin or sparse-convolution fBm, with a
//!   strict majorant (a bound on the deterministic density) and optimised ones, chosen per
//!   variant as the paper did (the smallest that leaves the error unchanged; the
//!   null-scattering weights keep any majorant unbiased).
//! - **`material`** (the [`material`](mod@crate::material) module): a plane with a procedural fBm albedo seen in
//!   perspective, one sample per pixel and frame (ξ from the baked STBN), accumulated over frames.
//!
//! Density variants ([`Variant`]): the full deterministic fBm; the one-sample estimator of the
//! whole sum (Algorithm 2); the *tail* estimator (the largest octaves exact, one octave of the
//! rest sampled: `Fbm::estimate_tail`; or only the octave choice sampled: `Fbm::estimate_octave`); and band-limited forms of both, whose octave count
//! stops at the pixel footprint (a biased model of the scene, measured against the full sum).
//! Every estimator enters the renderers linearly (extinction, ratio-tracking factors,
//! null-scattering weights, albedo), so every unbiased variant converges to the same image.

use crate::equal_time::{self, Row};
use build_assets::export::png::write_slices;
use build_assets::spec::Format;
use build_assets::texture::Texture;
use noisebake::stochastic::{Fbm, Fractal, SparseConvolutionFbm};
use rayon::prelude::*;
use std::path::Path;

/// Per-pixel random numbers: the generator's SplitMix64 (`unit_f32` for a uniform in `[0, 1)`).
pub type Rng = build_assets::generate::rng::SplitMix64;

/// How a scene evaluates its noise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Variant {
    /// The full fBm, every octave.
    Deterministic,
    /// The fBm up to the pixel footprint's octave (biased: sub-pixel octaves dropped).
    BandLimited,
    /// The one-sample estimator of the whole sum (Algorithm 2).
    Stochastic,
    /// The first `k` octaves exact, one octave of the rest sampled (one Perlin gradient).
    Tail(u32),
    /// The first `k` octaves exact, one octave of the rest chosen by ξ and evaluated exactly:
    /// only the octave choice is random.
    TailOctave(u32),
    /// [`Variant::Tail`] up to the pixel footprint's octave.
    TailBandLimited(u32),
}

impl Variant {
    /// The name in tables and JSON.
    pub fn name(self) -> String {
        match self {
            Variant::Deterministic => "deterministic".into(),
            Variant::BandLimited => "deterministic band-limited".into(),
            Variant::Stochastic => "stochastic".into(),
            Variant::Tail(k) => format!("stochastic tail ({k} exact)"),
            Variant::TailOctave(k) => format!("stochastic octave ({k} exact)"),
            Variant::TailBandLimited(k) => format!("tail ({k} exact) band-limited"),
        }
    }

    fn band_limited(self) -> bool {
        matches!(self, Variant::BandLimited | Variant::TailBandLimited(_))
    }
}

/// The noise summed into fBm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Basis {
    /// Improved Perlin noise.
    Perlin,
    /// Sparse convolution noise with this many impulses per cell.
    Sparse(u32),
}

/// The octaves whose lattice cell is at least the pixel footprint `footprint` (in noise
/// units): the finer ones vary within a pixel, so the pixel filter averages them away and
/// evaluating them buys variance and time, not detail.
pub fn footprint_octaves(f: Fractal, footprint: f32) -> u32 {
    let visible = (1.0 / footprint.max(1e-9)).log2().floor() as i64 + 1;
    visible.clamp(1, f.octaves as i64) as u32
}

/// One evaluation of `basis` fBm at `q` as `variant` asks; `footprint` in noise units; `xi`
/// gives the estimator's number (called once, only by the sampling variants).
pub fn fbm(
    basis: Basis,
    variant: Variant,
    q: [f32; 3],
    f: Fractal,
    footprint: f32,
    seed: u32,
    xi: &mut dyn FnMut() -> f32,
) -> f32 {
    let f = if variant.band_limited() {
        Fractal::new(footprint_octaves(f, footprint), f.lacunarity, f.gain)
    } else {
        f
    };
    match (variant, basis) {
        (Variant::Deterministic | Variant::BandLimited, Basis::Perlin) => {
            Fbm::new(f, seed).sample(q)
        }
        (Variant::Deterministic | Variant::BandLimited, Basis::Sparse(n)) => {
            SparseConvolutionFbm::new(f, n, seed).sample(q)
        }
        (Variant::Stochastic, Basis::Perlin) => Fbm::new(f, seed).estimate(q, xi()),
        (Variant::Stochastic, Basis::Sparse(n)) => {
            SparseConvolutionFbm::new(f, n, seed).estimate(q, xi())
        }
        (Variant::Tail(k) | Variant::TailBandLimited(k), Basis::Perlin) => {
            Fbm::new(f, seed).estimate_tail(q, k, xi())
        }
        (Variant::Tail(k) | Variant::TailBandLimited(k), Basis::Sparse(n)) => {
            SparseConvolutionFbm::new(f, n, seed).estimate_tail(q, k, xi())
        }
        (Variant::TailOctave(k), Basis::Perlin) => Fbm::new(f, seed).estimate_octave(q, k, xi()),
        (Variant::TailOctave(k), Basis::Sparse(n)) => {
            SparseConvolutionFbm::new(f, n, seed).estimate_octave(q, k, xi())
        }
    }
}

/// A scene rendered one Monte Carlo sample at a time.
pub trait Scene: Sync {
    /// Name in tables and JSON.
    fn name(&self) -> String;
    /// Image side in pixels.
    fn size(&self) -> usize;
    /// One sample of pixel `(x, y)`; sample index `s` (for scenes that take ξ from a mask).
    fn sample(&self, x: usize, y: usize, s: usize, rng: &mut Rng, v: Variant) -> f32;
}

/// The image of `scene` at `spp` samples per pixel, on one thread.
pub fn render(scene: &dyn Scene, v: Variant, spp: usize, seed: u64) -> Vec<f32> {
    let n = scene.size();
    (0..n * n).map(|i| pixel(scene, v, spp, seed, i)).collect()
}

fn pixel(scene: &dyn Scene, v: Variant, spp: usize, seed: u64, i: usize) -> f32 {
    let n = scene.size();
    let mut rng = Rng::new(seed ^ (i as u64).wrapping_mul(0x2545_f491_4f6c_dd1d));
    (0..spp)
        .map(|s| scene.sample(i % n, i / n, s, &mut rng, v))
        .sum::<f32>()
        / spp as f32
}

/// The reference: the deterministic variant at `spp`, on every thread.
pub fn reference(scene: &dyn Scene, spp: usize) -> Vec<f32> {
    let n = scene.size();
    (0..n * n)
        .into_par_iter()
        .map(|i| pixel(scene, Variant::Deterministic, spp, 99, i))
        .collect()
}

/// Root-mean-square difference.
pub fn rmse(a: &[f32], b: &[f32]) -> f64 {
    (a.iter()
        .zip(b)
        .map(|(x, y)| ((x - y) as f64).powi(2))
        .sum::<f64>()
        / a.len().max(1) as f64)
        .sqrt()
}

/// Writes an image as an 8-bit PNG.
pub fn save(dir: &Path, name: &str, img: &[f32], size: usize) {
    let t = Texture {
        name: name.into(),
        dims: vec![size, size],
        format: Format::U8,
        data: img
            .iter()
            .map(|&v| (v.clamp(0.0, 1.0) * 255.0) as u8)
            .collect(),
    };
    write_slices(&t, dir, name).expect("write png");
}

/// The unit ball's density profile `max(0, 1 − 4r²)` about the cube's centre.
fn ball(p: [f32; 3]) -> f32 {
    let r2 = (p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2) + (p[2] - 0.5).powi(2);
    (1.0 - 4.0 * r2).max(0.0)
}

/// The part `[t0, t1]` of the ray `o + t·d` (`d` a unit vector), `t ∈ [0, len]`, inside the
/// ball of [`ball`]: the only part where the density is not zero, so the only part tracking
/// needs to visit — outside it every tentative collision is null with weight 1.
fn ball_segment(o: [f32; 3], d: [f32; 3], len: f32) -> Option<(f32, f32)> {
    let oc = [o[0] - 0.5, o[1] - 0.5, o[2] - 0.5];
    let b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    let c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - 0.25;
    let disc = b * b - c;
    if disc <= 0.0 {
        return None;
    }
    let h = disc.sqrt();
    let (t0, t1) = ((-b - h).max(0.0), (-b + h).min(len));
    (t0 < t1).then_some((t0, t1))
}

/// The clouds' density profile: the ball times `1 + fbm` at [`CLOUD_SCALE`] noise units per
/// unit, for an image of `size` pixels (the band-limited variants' footprint). Linear in the
/// noise (no clamp), so the estimators stay unbiased.
fn ball_fbm(
    p: [f32; 3],
    size: usize,
    basis: Basis,
    f: Fractal,
    seed: u32,
    rng: &mut Rng,
    v: Variant,
) -> f32 {
    let shape = ball(p);
    if shape == 0.0 {
        return 0.0;
    }
    let q = p.map(|c| c * CLOUD_SCALE);
    let foot = CLOUD_SCALE / size as f32;
    shape * (1.0 + fbm(basis, v, q, f, foot, seed, &mut || rng.unit_f32()))
}

/// The demo's cloud: single scattering, ratio tracking (see the module docs).
pub struct SingleScatter {
    /// Image side.
    pub size: usize,
}

const CLOUD_FBM: Fractal = Fractal::new(8, 2.0, 0.5);
/// Noise units per unit of the cube.
const CLOUD_SCALE: f32 = 3.0;
const CLOUD_MAJORANT: f32 = 12.0;

impl SingleScatter {
    fn density(&self, p: [f32; 3], rng: &mut Rng, v: Variant) -> f32 {
        6.0 * ball_fbm(p, self.size, Basis::Perlin, CLOUD_FBM, 3, rng, v)
    }

    /// Ratio-tracking transmittance from `o` along `d` over length `len`, over the part of it
    /// inside the cloud's ball.
    fn transmittance(&self, o: [f32; 3], d: [f32; 3], len: f32, rng: &mut Rng, v: Variant) -> f32 {
        let Some((mut t, end)) = ball_segment(o, d, len) else {
            return 1.0;
        };
        let mut tr = 1.0;
        loop {
            t -= (1.0 - rng.unit_f32()).ln() / CLOUD_MAJORANT;
            if t >= end {
                return tr;
            }
            let p = [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
            tr *= 1.0 - self.density(p, rng, v) / CLOUD_MAJORANT;
        }
    }
}

impl Scene for SingleScatter {
    fn name(&self) -> String {
        "cloud".into()
    }
    fn size(&self) -> usize {
        self.size
    }
    /// A uniform point along the ray, σ_s there, and the transmittance to the eye and the light.
    fn sample(&self, x: usize, y: usize, _: usize, rng: &mut Rng, v: Variant) -> f32 {
        let u = (x as f32 + rng.unit_f32()) / self.size as f32;
        let w = (y as f32 + rng.unit_f32()) / self.size as f32;
        let t = rng.unit_f32();
        let p = [u, w, t];
        let sigma = self.density(p, rng, v);
        if sigma == 0.0 {
            return 0.0;
        }
        let view = self.transmittance([u, w, 0.0], [0.0, 0.0, 1.0], t, rng, v);
        let light = self.transmittance(p, [0.0, -1.0, 0.0], w, rng, v);
        0.8 * sigma * view * light
    }
}

/// The paper's Table 3 setting (see the module docs): volumetric path tracing with weighted
/// delta tracking, multiple scattering, a sun and a sky.
pub struct PaperCloud {
    /// Image side.
    pub size: usize,
    /// The noise summed into the fBm.
    pub basis: Basis,
    /// Majorant as a multiple of the density scale, e.g. [`PaperCloud::STRICT`].
    pub majorant: f32,
    /// Per-variant majorants overriding `majorant` (the optimised setting, found by
    /// [`optimise_majorants`]); empty for one majorant for all.
    pub per_variant: Vec<(Variant, f32)>,
}

const PAPER_FBM: Fractal = Fractal::new(10, 2.0, 0.5);
const PAPER_DENSITY: f32 = 5.0;
const ALBEDO: f32 = 0.95;
const BOUNCES: usize = 6;
const SUN: [f32; 3] = [0.267_261_24, -0.801_783_7, 0.534_522_5]; // towards the sun
const SUN_RADIANCE: f32 = 3.0;
const SKY: f32 = 0.15;

impl PaperCloud {
    /// A bound on the deterministic density: `(1 + Σ 2^-o · max|noise|)` times the density
    /// scale, with `max|noise|` ≤ 1.04 for Perlin and ≤ 1 for the normalised sparse
    /// convolution (each ≤ 2.08 summed over ten octaves at gain ½).
    pub const STRICT: f32 = 3.1;
    /// Half the strict majorant: below the density's peaks, which the null-scattering weights
    /// tolerate (unbiased, at some variance), for half the tentative collisions.
    pub const HALF: f32 = 1.55;
    /// The multiples of [`PaperCloud::STRICT`] the optimisation tries, largest first.
    pub const SWEEP: [f32; 5] = [1.0, 0.8, 0.65, 0.5, 0.4];

    /// The paper cloud with one majorant for every variant.
    pub fn new(size: usize, basis: Basis, majorant: f32) -> PaperCloud {
        PaperCloud {
            size,
            basis,
            majorant,
            per_variant: Vec::new(),
        }
    }

    fn density(&self, p: [f32; 3], rng: &mut Rng, v: Variant) -> f32 {
        PAPER_DENSITY * ball_fbm(p, self.size, self.basis, PAPER_FBM, 5, rng, v)
    }

    fn sigma_bar(&self, v: Variant) -> f32 {
        let m = self
            .per_variant
            .iter()
            .find(|(w, _)| *w == v)
            .map_or(self.majorant, |&(_, m)| m);
        PAPER_DENSITY * m
    }

    /// Ratio-tracking transmittance towards the sun (unbiased for any density estimate),
    /// over the part of the ray inside the cloud's ball.
    fn shadow(&self, o: [f32; 3], rng: &mut Rng, v: Variant) -> f32 {
        let Some((mut t, end)) = ball_segment(o, SUN, f32::MAX) else {
            return 1.0;
        };
        let bar = self.sigma_bar(v);
        let mut tr = 1.0f32;
        loop {
            t -= (1.0 - rng.unit_f32()).ln() / bar;
            if t >= end || tr == 0.0 {
                return tr;
            }
            let p = [o[0] + t * SUN[0], o[1] + t * SUN[1], o[2] + t * SUN[2]];
            tr *= 1.0 - self.density(p, rng, v) / bar;
        }
    }
}

impl Scene for PaperCloud {
    fn name(&self) -> String {
        let basis = match self.basis {
            Basis::Perlin => "perlin",
            Basis::Sparse(_) => "sparse",
        };
        let m = if !self.per_variant.is_empty() {
            "optimised"
        } else if self.majorant >= Self::STRICT {
            "strict"
        } else {
            "half"
        };
        format!("paper-cloud-{basis}-{m}")
    }
    fn size(&self) -> usize {
        self.size
    }
    /// One path: delta tracking with null scattering weighted as in the null-scattering path
    /// integral (a real collision with probability |σ_t| / (|σ_t| + |σ_n|), the weight corrected
    /// by σ/(σ̄ p)), next-event estimation of the sun at every real collision, isotropic phase.
    fn sample(&self, x: usize, y: usize, _: usize, rng: &mut Rng, v: Variant) -> f32 {
        let mut o = [
            (x as f32 + rng.unit_f32()) / self.size as f32,
            (y as f32 + rng.unit_f32()) / self.size as f32,
            0.0,
        ];
        let mut d = [0.0f32, 0.0, 1.0];
        let bar = self.sigma_bar(v);
        let (mut weight, mut radiance) = (1.0f32, 0.0f32);
        let phase = 1.0 / (4.0 * std::f32::consts::PI);
        let mut bounces = 0;
        loop {
            let Some((mut t, end)) = ball_segment(o, d, f32::MAX) else {
                return radiance + weight * SKY;
            };
            let mut scattered = false;
            loop {
                t -= (1.0 - rng.unit_f32()).ln() / bar;
                if t >= end {
                    break;
                }
                let p = [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
                let sigma = self.density(p, rng, v);
                let null = bar - sigma;
                let p_real = sigma.abs() / (sigma.abs() + null.abs()).max(1e-30);
                if rng.unit_f32() < p_real {
                    // Sun by next-event estimation, then an isotropic scattering.
                    weight *= sigma / (bar * p_real) * ALBEDO;
                    radiance += weight * phase * SUN_RADIANCE * self.shadow(p, rng, v);
                    let z = 1.0 - 2.0 * rng.unit_f32();
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    let a = 2.0 * std::f32::consts::PI * rng.unit_f32();
                    d = [r * a.cos(), r * a.sin(), z];
                    o = p;
                    scattered = true;
                    break;
                }
                weight *= null / (bar * (1.0 - p_real));
            }
            if !scattered {
                return radiance + weight * SKY;
            }
            bounces += 1;
            if bounces >= BOUNCES || weight == 0.0 {
                return radiance;
            }
        }
    }
}

/// The paper's majorant optimisation (§7.2): for each variant, the smallest multiple of the
/// strict majorant in [`PaperCloud::SWEEP`] whose RMSE at `spp` against `reference` (over two
/// renders with different seeds, to steady the estimate) stays within 5 % of its RMSE under the
/// strict majorant ("the smallest majorant that left MRSE unchanged"). Returns the per-variant
/// majorants (absolute multiples of the density scale).
pub fn optimise_majorants(
    size: usize,
    basis: Basis,
    variants: &[Variant],
    spp: usize,
    reference: &[f32],
) -> Vec<(Variant, f32)> {
    variants
        .iter()
        .map(|&v| {
            let error = |m: f32| {
                let scene = PaperCloud::new(size, basis, PaperCloud::STRICT * m);
                let e = [77, 78].map(|seed| rmse(&render(&scene, v, spp, seed), reference));
                ((e[0] * e[0] + e[1] * e[1]) / 2.0).sqrt()
            };
            let strict = error(1.0);
            let mut best = 1.0;
            for &m in &PaperCloud::SWEEP[1..] {
                if error(m) <= 1.05 * strict {
                    best = m;
                } else {
                    break;
                }
            }
            (v, PaperCloud::STRICT * best)
        })
        .collect()
}

/// What the demo's panel shows: the images it wrote and the equal-time table.
pub struct Panel {
    /// `(image name, seconds, RMSE)` of the 16- and 64-spp renders shown.
    pub images: Vec<(String, f64, f64)>,
    /// The equal-time table (text).
    pub table: String,
}

/// The variants the cloud scenes compare (`bands`: with the band-limited ones).
pub fn variants(bands: bool) -> Vec<Variant> {
    let mut v = vec![
        Variant::Deterministic,
        Variant::Stochastic,
        Variant::Tail(1),
        Variant::Tail(2),
        Variant::Tail(3),
        Variant::TailOctave(1),
        Variant::TailOctave(2),
    ];
    if bands {
        v.extend([Variant::BandLimited, Variant::TailBandLimited(2)]);
    }
    v
}

/// Measures `scene` over `spps` against a `ref_spp` reference: rows, the table, and the
/// reference image.
pub fn equal_time(
    scene: &dyn Scene,
    variants: &[Variant],
    spps: &[usize],
    ref_spp: usize,
    repeats: usize,
) -> (Vec<Row>, String, Vec<f32>) {
    let reference = reference(scene, ref_spp);
    let names: Vec<String> = variants.iter().map(|v| v.name()).collect();
    let rows = equal_time::measure(
        &scene.name(),
        &names,
        spps,
        repeats,
        |v, spp, seed| render(scene, variants[v], spp, seed),
        |img| rmse(img, &reference),
    );
    let table = equal_time::table(&rows, &scene.name(), &names[0], &names);
    (rows, table, reference)
}

/// The demo's panel: the `cloud` scene's equal-time table (the main variants, fewer sample
/// counts than `cargo run --release --example cloud`), its rows in `dir/cloud.json`, and
/// images at 16 and 64 spp.
pub fn run(dir: &Path) -> Panel {
    let scene = SingleScatter { size: 64 };
    let vs = [
        Variant::Deterministic,
        Variant::Stochastic,
        Variant::Tail(2),
        Variant::TailOctave(1),
        Variant::BandLimited,
    ];
    let (rows, table, reference) = equal_time(&scene, &vs, &[4, 16, 64], 1024, 1);
    print!("{table}");
    let json = dir.join("cloud.json");
    if let Err(e) = std::fs::write(&json, equal_time::json(&rows)) {
        eprintln!("{}: {e}", json.display());
    }
    save(dir, "cloud_reference", &reference, scene.size);
    let mut images = Vec::new();
    for v in [
        Variant::Deterministic,
        Variant::Stochastic,
        Variant::Tail(2),
    ] {
        for spp in [16, 64] {
            let img = render(&scene, v, spp, 1000 + spp as u64);
            let name = format!("{}_{spp}spp", v.name().replace([' ', '(', ')'], ""));
            save(dir, &format!("cloud_{name}"), &img, scene.size);
            let secs = rows
                .iter()
                .find(|r| r.density == v.name() && r.spp == spp)
                .map_or(0.0, |r| r.seconds);
            images.push((name, secs, rmse(&img, &reference)));
        }
    }
    Panel { images, table }
}
