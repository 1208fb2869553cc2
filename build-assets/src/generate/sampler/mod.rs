//! Sampler tiles (kind `sampler`): for every pixel and pair of dimensions, the block of the
//! pair's Owen-scrambled Sobol sequence it takes (`noise_runtime::sampler::{tile_index,
//! tile_value}`), chosen so that the pixels' Monte Carlo errors are blue under the declared
//! spatial filter.
//!
//! Every pixel integrates with an aligned block of Sobol points, so its own error is that of a
//! (0, m, 2)-net whatever block it holds; what the generator chooses is the arrangement: blocks
//! whose errors, integrand by integrand, cancel under the filter — Heitz, Belcour,
//! Ostromoukhov, Coeurjolly and Iehl's goal (2019, "A Low-Discrepancy Sampler that Distributes
//! Monte Carlo Errors as a Blue Noise in Screen Space"), over the block structure of Ahmed and
//! Wonka (2020, "Screen-space blue-noise diffusion of Monte Carlo sampling error via
//! hierarchical ordering of pixels"), where neighbours holding sibling blocks are stratified
//! together. `training.rs` holds the integrands and the pool's table, `optimise.rs` the loss and
//! the moves.
//!
//! - **Pairs.** Each pair of dimensions has its own sequence and keys and is optimised alone,
//!   with its own integrands, so dimensions 2–3, 4–5, … are as blue as 0–1 (Heitz et al.
//!   optimise by pairs too); pairs run in parallel. A lone last dimension is optimised with 1D
//!   steps.
//! - **Frames.** A tile baked for `frames > 1` scores frame `f` (block `key ^ f`) on its own
//!   integrands, each frame's error filtered alone.
//!
//! Deterministic: every draw comes from the seed, each pair is one thread's fixed sequence of
//! `f32` operations, and pairs are joined in order.

mod optimise;
mod training;

pub use optimise::MIN_INTEGRANDS;
pub(crate) use optimise::{pool_blocks, support_width, training_len};
pub use training::{half_plane_area, random_edge};

use crate::generate::rng::derive_seed;
use crate::spec::sampler::SamplerParams;
use crate::texture::Texture;
use noise_runtime::sampler::{tile_index, tile_value};
use noise_runtime::sequence::to_unit;
use rayon::prelude::*;

/// The optimiser's settings. [`Schedule::DEFAULT`] is what a bake uses; reports vary it to
/// measure the trade of time against error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schedule {
    /// Blocks in a pair's pool per pixel (rounded up to a power of two; fewer where the pool's
    /// table would be too much work, see `optimise::pool_blocks`).
    pub pool_factor: usize,
    /// Candidate blocks scored per pixel and sweep.
    pub candidates: usize,
    /// Training integrand values per pixel (integrands × frames, at least
    /// [`MIN_INTEGRANDS`] integrands per frame).
    pub training: usize,
    /// A sweep that lowers the loss by less than this fraction of it ends the optimisation.
    pub stop_gain: f64,
    /// Most sweeps.
    pub max_sweeps: usize,
}

impl Schedule {
    /// The bake's schedule.
    pub const DEFAULT: Schedule = Schedule {
        pool_factor: 4,
        candidates: 36,
        training: 1024,
        stop_gain: 5e-3,
        max_sweeps: 40,
    };
}

/// What a bake did, for reports: the loss of each pair at the start and after each sweep.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// Per pair: the loss before the first sweep, then after each sweep.
    pub loss: Vec<Vec<f64>>,
    /// Per pair: the seconds since the pair began (its table built, then each sweep), beside
    /// `loss`. Wall time, so not deterministic; nothing generated depends on it.
    pub seconds: Vec<Vec<f64>>,
}

/// The stopping rule: a sweep that lowered the loss by `gain`, leaving `loss`, ends the
/// optimisation when `gain < stop_gain · loss` ([`Schedule::stop_gain`]). The loss does not
/// fall towards zero (each pixel's own error stays), so the rule is relative to what is left;
/// `noisebake report bench` runs a tile on to the sweep cap and shows where it stops.
pub fn spent(gain: f64, loss: f64, stop_gain: f64) -> bool {
    gain < stop_gain * loss.abs()
}

/// The keys of a `w × h` tile: `sample_dims` layers of 16-bit keys, x fastest, then y, then the
/// dimension (a pair's key is layer `2p` low and layer `2p + 1` high).
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
    let pairs = (p.sample_dims as usize).div_ceil(2);
    let lone = p.sample_dims % 2 == 1;
    let total = (pairs * s.max_sweeps) as u64;
    progress(0, total);
    let results: Vec<(Vec<u32>, Vec<f64>, Vec<f64>)> = (0..pairs)
        .into_par_iter()
        .map(|pair| {
            let axes = if lone && pair == pairs - 1 { 1 } else { 2 };
            optimise::optimise_pair(
                p,
                w,
                h,
                derive_seed(seed, pair as u64),
                pair as u32,
                axes,
                s,
            )
        })
        .collect();
    progress(total, total);
    let n = w * h;
    let mut keys = vec![0u16; n * p.sample_dims as usize];
    let mut trace = Trace::default();
    for (pair, (k, loss, seconds)) in results.into_iter().enumerate() {
        for (i, &key) in k.iter().enumerate() {
            keys[2 * pair * n + i] = key as u16;
            if 2 * pair + 1 < p.sample_dims as usize {
                keys[(2 * pair + 1) * n + i] = (key >> 16) as u16;
            }
        }
        trace.loss.push(loss);
        trace.seconds.push(seconds);
    }
    (keys, trace)
}

/// The samples a baked tile gives, as the runtime returns them (`SamplerTile::sample`): `f32`
/// with dims `[sample_dims, spp, W, H]` (so a `.npy` has shape `(H, W, spp, D)`), and a last
/// axis of `frames` when the tile was optimised for more than one frame (`(frames, H, W, spp,
/// D)`). `keys` is the generated key texture (`[W, H, sample_dims]`, u16).
pub fn samples(keys: &Texture, p: &SamplerParams) -> Texture {
    let (w, h) = (keys.dims[0], keys.dims[1]);
    let (spp, dims, frames) = (p.spp as usize, p.sample_dims as usize, p.frames as usize);
    let n = w * h;
    let key = |layer: usize, px: usize| {
        let o = 2 * (layer * n + px);
        u16::from_le_bytes([keys.data[o], keys.data[o + 1]]) as u32
    };
    let mut data = Vec::with_capacity(frames * n * spp * dims * 4);
    for f in 0..frames {
        for px in 0..n {
            for i in 0..spp {
                for d in 0..dims {
                    let first = d & !1;
                    let hi = if first + 1 < dims {
                        key(first + 1, px)
                    } else {
                        0
                    };
                    let index = tile_index(key(first, px) | hi << 16, f as u32, i as u32, p.spp);
                    let bits = tile_value(index, (d / 2) as u32, d & 1);
                    data.extend_from_slice(&to_unit(bits).to_le_bytes());
                }
            }
        }
    }
    let mut out_dims = vec![dims, spp, w, h];
    if frames > 1 {
        out_dims.push(frames);
    }
    Texture {
        name: keys.name.clone(),
        dims: out_dims,
        format: crate::encoding::Format::F32,
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::fast::Filter;

    fn params(spp: u32, dims: u32) -> SamplerParams {
        SamplerParams {
            spp,
            sample_dims: dims,
            spatial: Filter::Gauss { sigma: 1.0 },
            frames: 1,
        }
    }

    /// Same seed, same keys; another seed, other keys; one layer per dimension, a pair's key
    /// split low / high over its two layers, a lone last dimension's in its one.
    #[test]
    fn keys_are_deterministic_and_laid_out_by_dimension() {
        let p = params(2, 3);
        let (a, trace) = generate(&p, 8, 8, 9, &mut |_, _| {});
        let (b, _) = generate(&p, 8, 8, 9, &mut |_, _| {});
        assert_eq!(a, b);
        assert_eq!(a.len(), 8 * 8 * 3);
        assert_eq!(trace.loss.len(), 2);
        let (c, _) = generate(&p, 8, 8, 10, &mut |_, _| {});
        assert_ne!(a, c);
        // 64 pixels, a pool of 256 blocks: the high layer of pair 0 is zero, the keys distinct.
        assert!(a[64..128].iter().all(|&k| k == 0));
        let mut pair0 = a[..64].to_vec();
        pair0.sort();
        pair0.dedup();
        assert_eq!(pair0.len(), 64);
        assert!(a[..64].iter().chain(&a[128..]).all(|&k| k < 256));
    }
}
