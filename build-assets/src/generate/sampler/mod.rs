//! Sampler tiles (kind `sampler`): for every pixel and dimension, the key of the tile's
//! sequence there (`noise_runtime::sampler::{SamplerTile, tile_point}`), arranged so that the
//! pixels' Monte Carlo errors are blue under the declared spatial filter, in the space each
//! pair of dimensions is warped into, on every frame or accumulated by an EMA.
//!
//! Every pixel runs the same low-discrepancy sequence per pair, moved by its key: a
//! rank-1 lattice in radical-inverse order rotated by it for warped pairs (Belcour and Heitz's structure, 2021, "Lessons
//! Learned and Improvements when Building Screen-Space Samplers with Blue-Noise Error
//! Distribution": progressive in time for free), the Sobol (0, 2)-sequence Owen-scrambled with
//! it as seed for `square` pairs (the structure of Heitz et al.'s tables). What the generator
//! chooses is the arrangement of the keys: keys whose errors, integrand by integrand, cancel
//! under the filter — Heitz, Belcour, Ostromoukhov, Coeurjolly and Iehl's goal (2019, "A
//! Low-Discrepancy Sampler that Distributes Monte Carlo Errors as a Blue Noise in Screen
//! Space"). `training.rs` holds the integrands and the pixels' errors, `optimise.rs` the loss
//! and the swaps.
//!
//! - **Start.** The free construction `rd_ign_r2`'s shifts (interleaved gradient noise and the
//!   R2 grid; for a lattice pair, `rd_ign_r2`'s rotations of the tile's lattice). The optimiser only makes swaps
//!   that lower the loss, so a tile never ends above its start on what it is trained for.
//! - **Pairs.** Each pair of dimensions is optimised alone, with integrands of its own space
//!   (`sample_space`); pairs run in parallel. A lone last dimension is optimised with
//!   thresholds.
//! - **Frames.** A lattice pair's frame `f` is frame 0 with every shift moved by the same
//!   amount (`reverse_bits(f · spp) · g`, exactly for a power-of-two `spp`),
//!   so integrands at random offsets train every frame alike; a Sobol pair's frames are other
//!   nets under the same scrambles, met by integrands at random XOR offsets. Under
//!   `temporal_filter = { kind = "ema", … }` a pixel's error is its EMA history's over
//!   `frames` frames.
//!
//! Deterministic: every draw comes from the seed, each pixel's errors are a fixed sequence of
//! `f32` operations, each pair's swaps are one thread's, and pairs are joined in order.

mod optimise;
mod training;

pub(crate) use optimise::support_width;
pub use training::{half_plane_area, random_edge};

use crate::generate::rng::{SplitMix64, derive_seed};
use crate::spec::fast::TemporalFilter;
use crate::spec::sampler::SamplerParams;
use crate::texture::Texture;
use noise_runtime::sampler::tile_point;
use noise_runtime::sequence::to_unit;
use rayon::prelude::*;
use training::{Errors, Integrands, sample_weights};

/// The optimiser's settings. [`Schedule::DEFAULT`] is what a bake uses; reports vary it to
/// measure the trade of time against error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schedule {
    /// Partners scored per pixel and sweep (three in four within the filter's reach).
    pub candidates: usize,
    /// Training integrands per pair for one frame's error (a multiple of 16).
    pub training: usize,
    /// Training integrands per pair for an EMA's error (a multiple of 16; each costs
    /// `frames` times as many samples).
    pub training_ema: usize,
    /// A sweep that lowers the loss by less than this fraction of it ends the optimisation.
    pub stop_gain: f64,
    /// Most sweeps.
    pub max_sweeps: usize,
}

impl Schedule {
    /// The bake's schedule.
    pub const DEFAULT: Schedule = Schedule {
        candidates: 24,
        training: 256,
        training_ema: 128,
        stop_gain: 5e-3,
        max_sweeps: 40,
    };

    /// Training integrands per pair for `p`.
    pub fn integrands(&self, p: &SamplerParams) -> usize {
        match p.temporal {
            TemporalFilter::Ema { .. } => self.training_ema,
            _ => self.training,
        }
    }
}

/// What a bake did, for reports: the loss of each pair at the start and after each sweep.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// Per pair: the loss before the first sweep, then after each sweep.
    pub loss: Vec<Vec<f64>>,
    /// Per pair: the seconds since its errors were tabulated, beside `loss`. Wall time, so not
    /// deterministic; nothing generated depends on it.
    pub seconds: Vec<Vec<f64>>,
}

/// One pair's keys (two per pixel), its loss after each sweep and the seconds each took.
type PairResult = (Vec<[u16; 2]>, Vec<f64>, Vec<f64>);

/// The stopping rule: a sweep that lowered the loss by `gain`, leaving `loss`, ends the
/// optimisation when `gain < stop_gain · loss` ([`Schedule::stop_gain`]). The loss does not
/// fall towards zero (each pixel's own error stays), so the rule is relative to what is left.
pub fn spent(gain: f64, loss: f64, stop_gain: f64) -> bool {
    gain < stop_gain * loss.abs()
}

/// The free construction's shift of dimension `d` at pixel `(x, y)`, in 16 bits:
/// `sampler::rd_ign_r2`'s rotation (IGN, R2, mirrored R2, IGN transposed), for dimensions past
/// 4 the same grids at coordinates moved by `(61, 37)` per group of four.
pub fn free_shift(x: i32, y: i32, d: u32) -> u16 {
    let group = (d / 4) as i32;
    let v = noise_runtime::sampler::rd_ign_r2::<4>(x + 61 * group, y + 37 * group, 0);
    (v[(d % 4) as usize] * 65536.0) as u16
}

/// The shifts of a `w × h` tile: `sample_dims` layers of 16-bit shifts, x fastest, then y,
/// then the dimension.
pub fn generate(
    p: &SamplerParams,
    w: usize,
    h: usize,
    seed: u64,
    progress: &mut dyn FnMut(u64, u64),
) -> (Vec<u16>, Trace) {
    generate_with(p, w, h, seed, &Schedule::DEFAULT, progress)
}

/// [`generate`] with another schedule.
pub fn generate_with(
    p: &SamplerParams,
    w: usize,
    h: usize,
    seed: u64,
    s: &Schedule,
    progress: &mut dyn FnMut(u64, u64),
) -> (Vec<u16>, Trace) {
    let pairs = p.pairs();
    let dims = p.sample_dims;
    let total = (pairs * s.max_sweeps) as u64;
    progress(0, total);
    let ema = match p.temporal {
        TemporalFilter::Ema { alpha, .. } => Some((alpha, p.frames)),
        _ => None,
    };
    let weights = sample_weights(p.spp, ema);
    let sobol_pairs = p.sobol_pairs();
    let n = w * h;
    let results: Vec<PairResult> = (0..pairs)
        .into_par_iter()
        .map(|pair| {
            let first = 2 * pair as u32;
            let axes = if first + 1 < dims { 2 } else { 1 };
            let pseed = derive_seed(seed, pair as u64);
            let mut rng = SplitMix64::new(pseed);
            let ints = Integrands::new(p.sample_space[pair], axes, s.integrands(p), &mut rng);
            let mut shifts: Vec<[u16; 2]> = (0..n)
                .map(|i| {
                    let (x, y) = ((i % w) as i32, (i / w) as i32);
                    [free_shift(x, y, first), free_shift(x, y, first + 1)]
                })
                .collect();
            let second = if axes == 2 { first + 1 } else { first };
            let mut errors =
                Errors::new(&ints, &shifts, [first, second], dims, sobol_pairs, &weights);
            let (loss, seconds) = optimise::optimise(
                &mut shifts,
                &mut errors,
                p.spatial,
                [w, h],
                rng.next_u64(),
                s,
                &mut || {},
            );
            (shifts, loss, seconds)
        })
        .collect();
    progress(total, total);
    let mut keys = vec![0u16; n * dims as usize];
    let mut trace = Trace::default();
    for (pair, (shifts, loss, seconds)) in results.into_iter().enumerate() {
        for (i, s) in shifts.iter().enumerate() {
            keys[2 * pair * n + i] = s[0];
            if 2 * pair + 1 < dims as usize {
                keys[(2 * pair + 1) * n + i] = s[1];
            }
        }
        trace.loss.push(loss);
        trace.seconds.push(seconds);
    }
    (keys, trace)
}

/// The samples a baked tile gives, as the runtime returns them (`SamplerTile::sample`): `f32`
/// with dims `[sample_dims, spp, W, H, frames]` (so a `.npy` has shape `(frames, H, W, spp,
/// D)`): frames `0 … frames − 1`, whatever the tile was baked for. `keys` is the generated
/// shift texture (`[W, H, sample_dims]`, u16).
pub fn samples(keys: &Texture, p: &SamplerParams, frames: u32) -> Texture {
    let (w, h) = (keys.dims[0], keys.dims[1]);
    let (spp, dims) = (p.spp, p.sample_dims);
    let sobol_pairs = p.sobol_pairs();
    let n = w * h;
    let key = |d: usize, px: usize| {
        let o = 2 * (d * n + px);
        u16::from_le_bytes([keys.data[o], keys.data[o + 1]])
    };
    let mut data = Vec::with_capacity(frames as usize * n * spp as usize * dims as usize * 4);
    for f in 0..frames {
        for px in 0..n {
            for i in 0..spp {
                let index = f.wrapping_mul(spp).wrapping_add(i);
                for d in 0..dims {
                    let bits = tile_point(index, d, dims, key(d as usize, px), sobol_pairs);
                    data.extend_from_slice(&to_unit(bits).to_le_bytes());
                }
            }
        }
    }
    Texture {
        name: keys.name.clone(),
        dims: vec![dims as usize, spp as usize, w, h, frames as usize],
        format: crate::encoding::Format::F32,
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::fast::Filter;
    use crate::spec::sampler::PairSpace;

    fn params(spp: u32, dims: u32) -> SamplerParams {
        SamplerParams {
            spp,
            sample_dims: dims,
            sample_space: vec![PairSpace::Square; dims.div_ceil(2) as usize],
            spatial: Filter::Gauss { sigma: 1.0 },
            temporal: TemporalFilter::None,
            frames: 1,
        }
    }

    /// Same seed, same shifts, on any thread count; another seed, others; one layer per
    /// dimension; each layer a permutation of the free construction's shifts (swaps only).
    #[test]
    fn shifts_are_deterministic_and_a_rearrangement_of_the_free_ones() {
        let p = params(2, 3);
        let (a, trace) = generate(&p, 8, 8, 9, &mut |_, _| {});
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let (b, _) = one.install(|| generate(&p, 8, 8, 9, &mut |_, _| {}));
        assert_eq!(a, b);
        assert_eq!(a.len(), 8 * 8 * 3);
        assert_eq!(trace.loss.len(), 2);
        let (c, _) = generate(&p, 8, 8, 10, &mut |_, _| {});
        assert_ne!(a, c);
        for d in 0..3u32 {
            let mut got = a[d as usize * 64..(d as usize + 1) * 64].to_vec();
            let mut free: Vec<u16> = (0..64).map(|i| free_shift(i % 8, i / 8, d)).collect();
            got.sort_unstable();
            free.sort_unstable();
            // Pairs move their two shifts together, so each layer keeps its multiset.
            assert_eq!(got, free, "dimension {d}");
        }
    }
}
