//! FAST: filter-adapted spatiotemporal sampling masks (Donnelly, Wolfe, Bütepage, Valdés 2024).
//!
//! A FAST mask holds one sample per texel — a scalar, an angle, a vector or a unit direction —
//! arranged so that the error left after the game's own denoising filter is as small as possible.
//! The loss (eq. 7) is `L = −Σ_jk F_jk d(s_j, s_k)`, where `F = f ⋆ f` is the overlap of the
//! filter (eq. 4) and `d` the distance of the sample space (eq. 6): minimising it pushes samples
//! that the filter averages together apart in sample space.
//!
//! **The loss is the expected error after the filter** — exactly, not by analogy. For a
//! step integrand `φ_c(s) = [s < c]` with `c` uniform, `E_c[(φ_c(a) − c)(φ_c(b) − c)] =
//! 1/3 − max(a, b) + (a² + b²)/2`, so the mean squared error of the filtered image, averaged
//! over pixels, is a constant of the value multiset minus `Σ F_jk |s_j − s_k| / (2N)` with
//! `F = W ⋆ W` of the filter `W` the game runs. Two consequences, both measured by
//! `noisebake report fast`:
//! - the temporal filter must be the one the game runs. A plain EMA over a texture that loops
//!   every `n` frames is `temporal_filter = { kind = "ema", alpha = α, beta = 0 }`: its taps
//!   `α (1 − α)^l` folded onto the ring of `n` slices. `beta > 0` is eq. 17's history
//!   rejection (EA's published texture uses β = 0.1); a mask made for it is made for an EMA
//!   that drops its history with probability β each frame, and ranks differently under a plain
//!   EMA;
//! - the optimiser's start matters: from a random order the swaps stall in a poor local
//!   minimum, from interleaved gradient noise's per-slice ranks ([`Start::Ign`], the default for
//!   scalars) they can only end below IGN's loss.
//!
//! - [`space`]: sample spaces, their stratified initialisation and distances;
//! - [`distance`]: the distances of the loss, in `f64` and (for the optimiser's screen) `f32`;
//! - [`filter`]: spatial and temporal filters (box, Gaussian, binomial, EMA with history
//!   rejection, eq. 14–17) and the footprint of `F`;
//! - [`optimize`]: exact sequential swaps on conflict-free tiles (eq. 8);
//! - `paper` (feature `research`): the paper's GPU schedule (random pairings, all at once), a baseline for reports.

pub mod distance;
pub mod filter;
pub mod optimize;
#[cfg(feature = "research")]
#[cfg_attr(docsrs, doc(cfg(feature = "research")))]
pub mod paper;
pub mod space;
pub mod windows;

pub use crate::spec::fast::{
    Combine, Distribution, FastParams, Filter, SampleSpace, Start, TemporalFilter,
};
pub use filter::Footprint;
pub use optimize::{CurvePoint, Outcome};
pub use windows::open_windows;

use crate::encoding::{Scalar, encode_ranks, encode_unit};
use crate::generate::rng::{SplitMix64, derive_seed};

/// Rounds run when no `iterations` cap is given and convergence is not reached earlier. From
/// IGN's ranks the loss keeps falling slowly for hundreds of rounds; by 40 the measured error is
/// within a few percent of where it ends, and a 128×128×64 mask bakes in minutes (the report's
/// comparison gives the times).
pub const MAX_ROUNDS: u32 = 40;

impl FastParams {
    /// The footprint of `F` on a texture of `dims` (x, y[, t]).
    pub fn footprint(&self, dims: &[usize]) -> Footprint {
        Footprint::new(dims3(dims), self.spatial, self.temporal, self.combine)
    }
}

fn dims3(dims: &[usize]) -> [usize; 3] {
    [dims[0], dims[1], dims.get(2).copied().unwrap_or(1)]
}

/// Distance of the loss for each sample space, monomorphised per channel count.
macro_rules! with_metric {
    ($space:expr, $($f:ident)::+ ( $($arg:expr),* )) => {
        match $space {
            SampleSpace::Scalar => $($f)::+::<1, _>($($arg,)* distance::Scalar),
            SampleSpace::Circle => $($f)::+::<1, _>($($arg,)* distance::Circle),
            SampleSpace::Vec2 => $($f)::+::<2, _>($($arg,)* distance::Euclid),
            SampleSpace::Vec3 => $($f)::+::<3, _>($($arg,)* distance::Euclid),
            SampleSpace::Vec4 => $($f)::+::<4, _>($($arg,)* distance::Euclid),
            SampleSpace::Sphere | SampleSpace::Hemisphere | SampleSpace::CosineHemisphere => {
                $($f)::+::<3, _>($($arg,)* distance::Sphere)
            }
        }
    };
}

/// The stratified initialisation: every (x, y) slice holds its own stratified set in a random
/// order (FAST §4), `channels` values per texel.
pub fn initial_samples(params: &FastParams, dims: &[usize], seed: u64) -> Vec<f64> {
    let [w, h, t] = dims3(dims);
    let mut out = Vec::with_capacity(w * h * t * params.sample_space.channels());
    if matches!(params.start, Start::IgnR2 | Start::RdIgnR2) {
        for slice in 0..t {
            for y in 0..h {
                for x in 0..w {
                    let pair = free_pair(params.start, x as i32, y as i32, slice as u32);
                    out.extend(warp_pair(params.sample_space, pair));
                }
            }
        }
        return out;
    }
    for slice in 0..t {
        let mut rng = SplitMix64::new(derive_seed(seed, slice as u64));
        let mut v =
            space::stratified_slice(params.sample_space, params.distribution, w * h, &mut rng);
        if params.start == Start::Ign && params.sample_space.channels() == 1 {
            v.sort_by(f64::total_cmp);
            let ign = ign_slice(w, h, slice);
            let mut order: Vec<usize> = (0..w * h).collect();
            order.sort_by(|&a, &b| ign[a].total_cmp(&ign[b]).then(a.cmp(&b)));
            let mut arranged = vec![0.0; w * h];
            for (rank, &texel) in order.iter().enumerate() {
                arranged[texel] = v[rank];
            }
            v = arranged;
        }
        out.extend(v);
    }
    out
}

/// The free pair of a start at pixel `(x, y)` in `frame` (`noise_runtime::sampler`).
fn free_pair(start: Start, x: i32, y: i32, frame: u32) -> [f32; 2] {
    use noise_runtime::sampler;
    match start {
        Start::RdIgnR2 => sampler::rd_ign_r2::<2>(x, y, frame),
        _ => sampler::ign_r2::<2>(x, y, frame),
    }
}

/// A pair through the runtime's warp for `space` (what a game applies to the free pair), in
/// `f64` and renormalised so the loss sees unit vectors; a `vec2` is the pair itself.
fn warp_pair(space: SampleSpace, [u, v]: [f32; 2]) -> Vec<f64> {
    use noise_runtime::warp;
    let d = match space {
        SampleSpace::Sphere => warp::sphere_uniform(u, v),
        SampleSpace::Hemisphere => warp::hemisphere_uniform(u, v),
        SampleSpace::CosineHemisphere => warp::cosine_hemisphere(u, v),
        _ => return vec![u as f64, v as f64],
    };
    let d = d.map(|c| c as f64);
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    d.iter().map(|c| c / len).collect()
}

/// Interleaved gradient noise over one `w × h` frame, x fastest: `fract(52.9829189 ·
/// fract(0.06711056·x + 0.00583715·y))` with x and y shifted by 5.588238 pixels per frame
/// (Jimenez 2014, as games animate it). Plain f64 arithmetic: the same bits everywhere.
pub fn ign_slice(w: usize, h: usize, frame: usize) -> Vec<f64> {
    let fract = |v: f64| v - v.floor();
    let o = 5.588238 * frame as f64;
    (0..h)
        .flat_map(|y| {
            (0..w).map(move |x| {
                let (xf, yf) = (x as f64 + o, y as f64 + o);
                fract(52.982_918_9 * fract(0.067_110_56 * xf + 0.005_837_15 * yf))
            })
        })
        .collect()
}

/// The loss of eq. (7) of `samples` for `params` on `dims`.
pub fn loss(params: &FastParams, dims: &[usize], samples: &[f64]) -> f64 {
    let fp = params.footprint(dims);
    let d = dims3(dims);
    with_metric!(params.sample_space, optimize::loss(d, &fp, samples))
}

/// Generates the optimised samples (`channels` per texel) and the curve of the loss's decrease,
/// as a bake does (the start's loss is not evaluated: [`optimize::Limits::measure_loss`]).
pub fn generate(
    params: &FastParams,
    dims: &[usize],
    seed: u64,
    progress: &mut dyn FnMut(u64, u64),
) -> Outcome {
    run(
        params,
        dims,
        seed,
        None,
        converged(params.sample_space),
        false,
        progress,
    )
}

/// The stopping threshold a bake of `space` uses: [`optimize::CONVERGED_DIRECTIONS`] for
/// directions, [`optimize::CONVERGED`] for everything else.
pub fn converged(space: SampleSpace) -> f64 {
    match space {
        SampleSpace::Sphere | SampleSpace::Hemisphere | SampleSpace::CosineHemisphere => {
            optimize::CONVERGED_DIRECTIONS
        }
        _ => optimize::CONVERGED,
    }
}

/// [`generate`] for reports: the same samples (without a budget), the start's loss measured, an
/// optional wall-clock budget in seconds and a convergence threshold ([`optimize::Limits`]; a
/// budget makes the result depend on the machine, so baking never sets one).
pub fn generate_within(
    params: &FastParams,
    dims: &[usize],
    seed: u64,
    budget: Option<f64>,
    converged: f64,
    progress: &mut dyn FnMut(u64, u64),
) -> Outcome {
    run(params, dims, seed, budget, converged, true, progress)
}

fn run(
    params: &FastParams,
    dims: &[usize],
    seed: u64,
    budget: Option<f64>,
    converged: f64,
    measure_loss: bool,
    progress: &mut dyn FnMut(u64, u64),
) -> Outcome {
    let samples = initial_samples(params, dims, seed);
    let fp = params.footprint(dims);
    let d = dims3(dims);
    let rounds = params.iterations.unwrap_or(MAX_ROUNDS);
    with_metric!(
        params.sample_space,
        optimize::optimize(
            d,
            &fp,
            samples,
            seed,
            optimize::Limits {
                max_rounds: rounds,
                budget,
                converged,
                measure_loss
            },
            progress
        )
    )
}

/// Runs the paper's own schedule ([`paper`]) from the same stratified start as
/// [`generate_within`] (a baseline for reports; baking never uses it).
#[cfg(feature = "research")]
#[cfg_attr(docsrs, doc(cfg(feature = "research")))]
pub fn paper_baseline(
    params: &FastParams,
    dims: &[usize],
    seed: u64,
    schedule: paper::Schedule,
    progress: &mut dyn FnMut(u64, u64),
) -> Outcome {
    let samples = initial_samples(params, dims, seed);
    let fp = params.footprint(dims);
    let d = dims3(dims);
    with_metric!(
        params.sample_space,
        paper::run_schedule(d, &fp, samples, seed, schedule, progress)
    )
}

/// Encodes samples for storage. Uniform scalars are the ranks of their slice (so unorm formats
/// are exactly flat: the rank encoding of [`crate::encoding::encode_ranks`]); other scalars and `[0, 1)` vectors are stored as
/// values; unit vectors as `0.5 + 0.5·v` (like the public STBN/FAST textures: unorm values
/// `round(·(2^bits − 1))`), Gaussian scalars raw (f32 only).
pub fn encode(params: &FastParams, dims: &[usize], samples: &[f64], scalar: Scalar) -> Vec<u8> {
    let [w, h, _] = dims3(dims);
    let slice = w * h;
    match (params.sample_space, params.distribution) {
        (SampleSpace::Scalar, Distribution::Uniform) => {
            let ranks: Vec<u32> = samples
                .iter()
                .map(|&v| (v * slice as f64 - 0.5).round() as u32)
                .collect();
            encode_ranks(&ranks, slice as u32, scalar)
        }
        (SampleSpace::Scalar, Distribution::Gauss) => samples
            .iter()
            .flat_map(|&v| (v as f32).to_le_bytes())
            .collect(),
        (s, _) if s.is_unit_vector() => {
            let half: Vec<f64> = samples.iter().map(|&v| 0.5 + 0.5 * v).collect();
            match scalar {
                Scalar::U8 => half.iter().map(|&v| (v * 255.0).round() as u8).collect(),
                Scalar::U16 => half
                    .iter()
                    .flat_map(|&v| ((v * 65535.0).round() as u16).to_le_bytes())
                    .collect(),
                Scalar::F32 => half
                    .iter()
                    .flat_map(|&v| (v as f32).to_le_bytes())
                    .collect(),
            }
        }
        _ => encode_unit(samples, scalar),
    }
}

/// Decodes stored bytes back to samples (inverse of [`encode`] up to quantisation).
pub fn decode(params: &FastParams, bytes: &[u8], scalar: Scalar) -> Vec<f64> {
    let unit = crate::encoding::decode_unit(bytes, scalar);
    if params.sample_space.is_unit_vector() {
        let top = match scalar {
            Scalar::U8 => Some(255.0),
            Scalar::U16 => Some(65535.0),
            Scalar::F32 => None,
        };
        let raw: Vec<f64> = match (scalar, top) {
            (Scalar::U8, Some(t)) => bytes.iter().map(|&b| b as f64 / t).collect(),
            (Scalar::U16, Some(t)) => bytes
                .chunks_exact(2)
                .map(|c| u16::from_le_bytes([c[0], c[1]]) as f64 / t)
                .collect(),
            _ => unit,
        };
        raw.iter().map(|&v| 2.0 * v - 1.0).collect()
    } else {
        unit
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The loss is the expected squared error after filtering (up to a constant of the value
    /// multiset): brute force over every pixel of a small torus, with the filter's weights spelt
    /// out — a separable Gaussian per frame and the steady-state EMA over the looping texture
    /// (β = 0) — and the error of estimating `∫ [s < c] = c` averaged over uniform thresholds
    /// `c`, whose kernel is `E_c[(φ_c(a) − c)(φ_c(b) − c)] = 1/3 − max(a, b) + (a² + b²)/2`.
    /// Two masks with the same values then differ in mean squared error by exactly
    /// `ΔL / (2 · texels)`.
    #[test]
    fn loss_differences_are_the_filtered_error_differences_by_brute_force() {
        let dims = [6usize, 5, 4];
        let [w, h, t] = dims;
        let (n, px) = (w * h * t, w * h);
        let alpha = 0.1f64;
        let taps = Filter::Gauss { sigma: 1.3435 }.taps();
        let r = (taps.len() / 2) as i64;
        let fold = 1.0 / (1.0 - (1.0 - alpha).powi(t as i32));
        // The weight of texel (x − dx, y − dy, f − age) in the filtered pixel (x, y, f).
        let mut wgt = vec![0.0; n];
        for age in 0..t {
            for (iy, gy) in taps.iter().enumerate() {
                for (ix, gx) in taps.iter().enumerate() {
                    let dx = (ix as i64 - r).rem_euclid(w as i64) as usize;
                    let dy = (iy as i64 - r).rem_euclid(h as i64) as usize;
                    wgt[age * px + dy * w + dx] +=
                        gx * gy * alpha * (1.0 - alpha).powi(age as i32) * fold;
                }
            }
        }
        let mse = |v: &[f64]| {
            let mut total = 0.0;
            for f in 0..t {
                for y in 0..h {
                    for x in 0..w {
                        let mut ws = vec![0.0; n];
                        for (o, &wo) in wgt.iter().enumerate() {
                            let (age, dy, dx) = (o / px, (o % px) / w, o % w);
                            let k = ((f + t - age) % t) * px
                                + ((y + h - dy) % h) * w
                                + (x + w - dx) % w;
                            ws[k] += wo;
                        }
                        for j in 0..n {
                            for k in 0..n {
                                let (a, b) = (v[j], v[k]);
                                total +=
                                    ws[j] * ws[k] * (1.0 / 3.0 - a.max(b) + (a * a + b * b) / 2.0);
                            }
                        }
                    }
                }
            }
            total / n as f64
        };
        let p = FastParams {
            sample_space: SampleSpace::Scalar,
            distribution: Distribution::Uniform,
            spatial: Filter::Gauss { sigma: 1.3435 },
            temporal: TemporalFilter::Ema { alpha, beta: 0.0 },
            combine: Combine::Product,
            iterations: None,
            start: Start::Random,
        };
        let masks: Vec<Vec<f64>> = (0..3)
            .map(|seed| initial_samples(&p, &dims, seed))
            .collect();
        let l: Vec<f64> = masks.iter().map(|m| loss(&p, &dims, m)).collect();
        let e: Vec<f64> = masks.iter().map(|m| mse(m)).collect();
        for k in 1..3 {
            let (de, dl) = (e[k] - e[0], (l[k] - l[0]) / (2.0 * n as f64));
            assert!(de.abs() > 1e-6, "the masks should differ");
            assert!(
                (de - dl).abs() < 1e-9 * de.abs().max(1e-6) + 1e-12,
                "ΔMSE {de} vs ΔL/2N {dl}"
            );
        }
    }

    fn params(space: SampleSpace, combine: Combine) -> FastParams {
        FastParams {
            sample_space: space,
            distribution: Distribution::Uniform,
            spatial: Filter::Gauss { sigma: 1.0 },
            temporal: TemporalFilter::Ema {
                alpha: 0.3,
                beta: 0.2,
            },
            combine,
            iterations: Some(6),
            start: Start::Random,
        }
    }

    #[test]
    fn tracked_loss_equals_recomputed_loss() {
        for (space, combine, dims) in [
            (SampleSpace::Scalar, Combine::Product, vec![16, 16, 4]),
            (SampleSpace::Scalar, Combine::Separate(0.5), vec![12, 10, 3]),
            (
                SampleSpace::CosineHemisphere,
                Combine::Product,
                vec![40, 36, 2],
            ),
            (SampleSpace::Circle, Combine::Product, vec![9, 7]),
        ] {
            let p = params(space, combine);
            let out = generate(&p, &dims, 5, &mut |_, _| {});
            let exact = loss(&p, &dims, &out.samples);
            let init = loss(&p, &dims, &initial_samples(&p, &dims, 5));
            // A bake tracks only the decrease; it is the exact one.
            assert_eq!(out.initial_loss, None);
            assert!(
                (init - exact - out.decrease()).abs() < 1e-9 * exact.abs(),
                "{space:?} {dims:?}: tracked decrease {} exact {}",
                out.decrease(),
                init - exact
            );
            assert!(exact < init, "{space:?}: {exact} !< {init}");
            // A report's run measures the start and gives the same samples.
            let measured = generate_within(&p, &dims, 5, None, converged(space), &mut |_, _| {});
            assert_eq!(measured.samples, out.samples);
            assert!((measured.initial_loss.unwrap() - init).abs() < 1e-9 * init.abs());
            assert!((measured.loss().unwrap() - exact).abs() < 1e-9 * exact.abs());
        }
    }

    /// A free-pair start is that free construction, texel for texel, and the swaps only lower
    /// its loss.
    #[test]
    fn free_pair_starts_are_the_free_construction_and_only_improve() {
        use noise_runtime::{sampler, warp};
        let dims = vec![24usize, 20, 4];
        for (start, space) in [
            (Start::IgnR2, SampleSpace::CosineHemisphere),
            (Start::RdIgnR2, SampleSpace::Sphere),
            (Start::IgnR2, SampleSpace::Vec2),
        ] {
            let mut p = params(space, Combine::Product);
            p.start = start;
            let init = initial_samples(&p, &dims, 9);
            let c = space.channels();
            for &(x, y, f) in &[(0usize, 0usize, 0usize), (5, 7, 1), (23, 19, 3)] {
                let i = ((f * 20 + y) * 24 + x) * c;
                let [u, v] = match start {
                    Start::IgnR2 => sampler::ign_r2::<2>(x as i32, y as i32, f as u32),
                    _ => sampler::rd_ign_r2::<2>(x as i32, y as i32, f as u32),
                };
                let want: Vec<f64> = match space {
                    SampleSpace::CosineHemisphere => {
                        warp::cosine_hemisphere(u, v).map(|a| a as f64).to_vec()
                    }
                    SampleSpace::Sphere => warp::sphere_uniform(u, v).map(|a| a as f64).to_vec(),
                    _ => vec![u as f64, v as f64],
                };
                for k in 0..c {
                    assert!(
                        (init[i + k] - want[k]).abs() < 1e-6,
                        "{start:?} {space:?} ({x}, {y}, {f})"
                    );
                }
            }
            let out = generate(&p, &dims, 9, &mut |_, _| {});
            let l0 = loss(&p, &dims, &init);
            let l = loss(&p, &dims, &out.samples);
            assert!((l0 - l - out.decrease()).abs() < 1e-9 * l0.abs());
            assert!(l < l0, "{start:?} {space:?}: {l} !< {l0}");
            // Swaps keep each slice's multiset: sorted values per slice are unchanged.
            let slice = 24 * 20 * c;
            for f in 0..4 {
                let mut a = init[f * slice..(f + 1) * slice].to_vec();
                let mut b = out.samples[f * slice..(f + 1) * slice].to_vec();
                a.sort_by(f64::total_cmp);
                b.sort_by(f64::total_cmp);
                assert_eq!(a, b);
            }
        }
    }

    /// Under TAA the bake closes the windows its start leaves open (IGN's, where its inner
    /// `fract` wraps), its tracked decrease stays exact although the swaps that close windows
    /// may raise the loss, and its loss still ends below the start's.
    #[test]
    fn a_taa_bake_closes_the_clamps_windows() {
        let dims = [32usize, 32, 16];
        let coverage = 0.2;
        let ema = FastParams {
            sample_space: SampleSpace::Scalar,
            distribution: Distribution::Uniform,
            spatial: Filter::Gauss { sigma: 1.3435 },
            temporal: TemporalFilter::Ema {
                alpha: 0.1,
                beta: 0.0,
            },
            combine: Combine::Product,
            iterations: None,
            start: Start::Ign,
        };
        let taa = FastParams {
            temporal: TemporalFilter::Taa {
                alpha: 0.1,
                coverage,
                motion: [0, 0],
                moving: 0.0,
            },
            ..ema.clone()
        };
        let init = initial_samples(&taa, &dims, 3);
        assert_eq!(init, initial_samples(&ema, &dims, 3));
        let open0 = open_windows(&init, dims, coverage);
        assert!(open0 > 100, "IGN leaves windows open: {open0}");
        let out = generate(&taa, &dims, 3, &mut |_, _| {});
        // A window counted closed holds values a margin inside the range, so the count holds
        // for the stored u8 values too.
        let u8s: Vec<f64> = out
            .samples
            .iter()
            .map(|&v| ((v * 256.0).floor().min(255.0) + 0.5) / 256.0)
            .collect();
        let open = open_windows(&u8s, dims, coverage);
        assert!(open * 50 < open0, "{open} windows still open of {open0}");
        let plain = generate(&ema, &dims, 3, &mut |_, _| {});
        assert!(open_windows(&plain.samples, dims, coverage) > 10 * open.max(1));
        let (l0, l) = (loss(&ema, &dims, &init), loss(&taa, &dims, &out.samples));
        assert!((l0 - l - out.decrease()).abs() < 1e-9 * l0.abs());
        // The swaps made for the loss win back what closing the windows cost, and more.
        assert!(l < l0, "{l} !< {l0}");
    }
}
