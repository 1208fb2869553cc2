//! Baselines the STBN paper compares against (§4.2): white noise, independent 2D blue noise per
//! slice, and one 2D blue-noise mask animated by the golden ratio.

use crate::generate::rng::{SplitMix64, derive_seed};
use rayon::prelude::*;

/// The golden ratio conjugate φ − 1 = (√5 − 1)/2, the additive recurrence of golden animation.
pub const GOLDEN: f64 = 0.618_033_988_749_894_9;

/// Independent uniform values in `[0, 1)`.
pub fn white(texels: usize, seed: u64) -> Vec<f64> {
    let mut rng = SplitMix64::new(seed);
    (0..texels).map(|_| rng.unit_f64()).collect()
}

/// Ranks of an independent 2D mask per slice; `blue2d(slice_seed)` ranks one slice.
pub fn independent2d(
    slices: usize,
    seed: u64,
    blue2d: impl Fn(u64) -> Vec<u32> + Sync,
) -> Vec<u32> {
    let per: Vec<Vec<u32>> = (0..slices)
        .into_par_iter()
        .map(|s| blue2d(derive_seed(seed, s as u64)))
        .collect();
    per.concat()
}

/// Golden-ratio animation: frame `t` holds `frac((r + 0.5)/N + t·φ)` for the 2D mask's rank `r`.
pub fn golden(ranks: &[u32], frames: usize) -> Vec<f64> {
    let n = ranks.len() as f64;
    let mut out = Vec::with_capacity(ranks.len() * frames);
    for t in 0..frames {
        // t·φ mod 1 computed in f64 from an exact integer product would lose nothing for any
        // frame count a texture can have (frames < 2^26).
        let shift = (t as f64 * GOLDEN).fract();
        out.extend(
            ranks
                .iter()
                .map(|&r| ((r as f64 + 0.5) / n + shift).fract()),
        );
    }
    out
}
