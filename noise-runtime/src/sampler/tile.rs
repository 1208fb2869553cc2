//! Baked sampler tiles: `spp` samples of `D` dimensions per pixel per frame, from per-pixel keys
//! chosen at build time (kind `sampler`).
//!
//! Each pixel holds one 16-bit key per dimension. Dimensions go in pairs (0–1, 2–3, …; an odd
//! last one alone); a pair's two keys make one 32-bit key `k`, and sample `n` of the pair is the
//! `n`-th point of the shuffled, Owen-scrambled Sobol sequence (Burley 2020, §4) seeded by `k`:
//! the index scrambled by `combine(k, SHUFFLE)`, dimension `a ∈ {0, 1}` of Sobol's first two
//! scrambled by `combine(k, a)`. Every pair is therefore a (0, m, 2)-net in each power-of-two
//! prefix of a pixel's samples whatever the key, so the per-pixel error is that of Owen-scrambled
//! Sobol, and the pairs are decorrelated by their own shuffles (Burley's padding). What the
//! generator chooses is *which* scramble each pixel gets: keys whose per-pixel errors,
//! integrand by integrand, cancel under the declared filter — the construction of Heitz,
//! Belcour, Ostromoukhov, Coeurjolly and Iehl (2019, "A Low-Discrepancy Sampler that Distributes
//! Monte Carlo Errors as a Blue Noise in Screen Space"), with full 32-bit Owen scrambling where
//! their tables store 8-bit XOR keys.
//!
//! Frame `f`, sample `i` of a tile baked for `spp` samples is the pair's sample
//! `n = f·spp + i`: a pixel's samples over frames continue one progressive sequence.
//!
//! The keys are stored as a mask of 16-bit texels, `D` layers of `W × H` (layer = dimension),
//! so a lookup reads one texel per key (two for a pair) and the tile uploads, caches and exports
//! as any other mask. `nb_sampler_tile` in the WGSL library is the same integer arithmetic.

use super::{combine, owen, sobol};
use crate::mask::Mask3;
use crate::sequence::to_unit;

/// The word the index shuffle's seed is combined with (the dimension seeds use 0 and 1).
const SHUFFLE: u32 = 0x5348_5546;

/// Dimension `axis` (0 or 1) of sample `n` of a pair keyed by `key`, as a 32-bit fraction: the
/// shuffled, Owen-scrambled Sobol point. What [`SamplerTile::sample`] returns, and what the
/// generator evaluates when it chooses keys.
#[must_use]
#[inline]
pub fn tile_value(key: u32, n: u32, axis: usize) -> u32 {
    let index = owen(n, combine(key, SHUFFLE));
    owen(sobol(index, axis & 1), combine(key, axis as u32 & 1))
}

/// A baked sampler tile: `W × H` pixels, `SPP` samples per pixel per frame, `D` dimensions per
/// sample, over the 16-bit key mask the build baked (`D` layers). Coordinates wrap toroidally.
#[derive(Clone, Copy, Debug)]
pub struct SamplerTile<const W: u32, const H: u32, const SPP: u32, const D: u32> {
    keys: Mask3<u16, W, H, D>,
}

impl<const W: u32, const H: u32, const SPP: u32, const D: u32> SamplerTile<W, H, SPP, D> {
    /// Samples per pixel per frame the tile was baked for.
    pub const SPP: u32 = SPP;
    /// Dimensions per sample.
    pub const DIMS: u32 = D;

    /// A tile over its key mask; fails to compile (in a `const`/`static`) when `SPP` or `D` is
    /// zero.
    pub const fn new(keys: Mask3<u16, W, H, D>) -> Self {
        assert!(
            SPP > 0 && D > 0,
            "a sampler tile needs samples and dimensions"
        );
        Self { keys }
    }

    /// The key mask (one 16-bit key per pixel and dimension), e.g. to upload it to a GPU for
    /// `nb_sampler_tile`.
    pub const fn keys(&self) -> &Mask3<u16, W, H, D> {
        &self.keys
    }

    /// The 32-bit key of the pair holding dimension `d` at pixel (x, y).
    #[inline]
    fn pair_key(&self, x: i32, y: i32, d: u32) -> u32 {
        let first = d & !1;
        let lo = self.keys.get(x, y, first as i32) as u32;
        let hi = if first + 1 < D {
            self.keys.get(x, y, first as i32 + 1) as u32
        } else {
            0
        };
        lo | hi << 16
    }

    /// Dimension `d` of sample `i` of pixel (x, y) in `frame`, as a 32-bit fraction: sample
    /// `frame·SPP + i` of the pair holding `d`. `i` and `d` are taken modulo `SPP` and `D`.
    #[must_use]
    #[inline]
    pub fn sample_bits(&self, x: i32, y: i32, frame: u32, i: u32, d: u32) -> u32 {
        let (i, d) = (i % SPP, d % D);
        let n = frame.wrapping_mul(SPP).wrapping_add(i);
        tile_value(self.pair_key(x, y, d), n, (d & 1) as usize)
    }

    /// Dimension `d` of sample `i` of pixel (x, y) in `frame`, in `[0, 1)`: the top 24 bits of
    /// [`sample_bits`](Self::sample_bits), exactly.
    #[must_use]
    #[inline]
    pub fn sample(&self, x: i32, y: i32, frame: u32, i: u32, d: u32) -> f32 {
        to_unit(self.sample_bits(x, y, frame, i, d))
    }

    /// Dimensions `d` and `d + 1` of sample `i` (`d` even): a 2D point, from one pair's key.
    #[must_use]
    #[inline]
    pub fn sample2(&self, x: i32, y: i32, frame: u32, i: u32, d: u32) -> [f32; 2] {
        let (i, d) = (i % SPP, (d % D) & !1);
        let n = frame.wrapping_mul(SPP).wrapping_add(i);
        let key = self.pair_key(x, y, d);
        [
            to_unit(tile_value(key, n, 0)),
            if d + 1 < D {
                to_unit(tile_value(key, n, 1))
            } else {
                0.0
            },
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    fn tile(keys: &'static [u8]) -> SamplerTile<4, 2, 8, 3> {
        SamplerTile::new(Mask3::new(keys))
    }

    /// The lookup reads the keys of the dimension's pair: changing a key of pair 0 changes
    /// dimensions 0 and 1 of that pixel and nothing else.
    #[test]
    fn a_key_moves_its_pair_and_pixel_only() {
        let mut bytes: Vec<u8> = (0..4 * 2 * 3 * 2).map(|i| (i * 37 + 11) as u8).collect();
        let a = tile(Vec::leak(bytes.clone()));
        bytes[2 * (1 + 4)] ^= 0x5a; // pixel (1, 1), dimension 0
        let b = tile(Vec::leak(bytes));
        for y in 0..2 {
            for x in 0..4 {
                for d in 0..3 {
                    for i in 0..8 {
                        let same = a.sample_bits(x, y, 2, i, d) == b.sample_bits(x, y, 2, i, d);
                        assert_eq!(same, !((x, y) == (1, 1) && d < 2), "({x}, {y}) d {d} i {i}");
                    }
                }
            }
        }
    }

    /// Whatever the key, each pixel's first 2^m samples of a pair hold one point in each of the
    /// 2^m elementary intervals of every shape (a (0, m, 2)-net), and frames continue the
    /// sequence.
    #[test]
    fn every_key_gives_nets_over_samples_and_frames() {
        for key in [0u32, 1, 0xdead_beef, u32::MAX, 0x8000_0000] {
            let pts: Vec<[u32; 2]> = (0..64)
                .map(|n| [tile_value(key, n, 0), tile_value(key, n, 1)])
                .collect();
            for m in 1..=6u32 {
                for lx in 0..=m {
                    let ly = m - lx;
                    let mut seen = std::vec![false; 1 << m];
                    for p in &pts[..1 << m] {
                        let cx = if lx == 0 { 0 } else { p[0] >> (32 - lx) };
                        let cy = if ly == 0 { 0 } else { p[1] >> (32 - ly) };
                        let cell = (cx << ly | cy) as usize;
                        assert!(!seen[cell], "key {key:#x}: 2^{m} samples, {lx}×{ly}");
                        seen[cell] = true;
                    }
                }
            }
        }
        let mut bytes: Vec<u8> = (0..4 * 2 * 3 * 2).map(|i| (i * 91 + 3) as u8).collect();
        bytes[0] = 7;
        let key = |b: &[u8], layer: usize| {
            u16::from_le_bytes([b[2 * (7 + 8 * layer)], b[2 * (7 + 8 * layer) + 1]]) as u32
        };
        let pair = key(&bytes, 0) | key(&bytes, 1) << 16;
        let t = tile(Vec::leak(bytes));
        // Pixel (3, 1), frame 2, sample 5 is the pair's sample 2·8 + 5.
        assert_eq!(t.sample_bits(3, 1, 2, 5, 1), tile_value(pair, 21, 1));
        assert_eq!(t.sample_bits(-1, -1, 1, 0, 2), t.sample_bits(3, 1, 1, 0, 2));
        assert_eq!(
            t.sample2(2, 0, 3, 1, 0),
            [t.sample(2, 0, 3, 1, 0), t.sample(2, 0, 3, 1, 1)]
        );
        assert_eq!(t.sample2(2, 0, 3, 1, 2), [t.sample(2, 0, 3, 1, 2), 0.0]);
    }
}
