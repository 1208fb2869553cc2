//! Baked sampler tiles: `spp` samples of `D` dimensions per pixel per frame, from per-pixel keys
//! chosen at build time (kind `sampler`).
//!
//! Dimensions go in pairs (0–1, 2–3, …; an odd last one alone), and every pair draws its points
//! from one Owen-scrambled Sobol sequence of its own (Burley 2020, "Practical Hash-based Owen
//! Scrambling", JCGT 9(4), §3; the pair's seed is fixed). The sequence is cut into blocks of
//! `B = spp` rounded up to a power of two consecutive points, and each pixel holds, per pair,
//! the index of the block it takes in frame 0: its *key*. In frame `f` the pixel takes block
//! `key ^ f`. So:
//!
//! - **Each pixel's samples are a net.** An aligned block of `2^m` Sobol points is a
//!   (0, m, 2)-net after Owen scrambling, so a pixel's `spp` samples are stratified whatever its
//!   key (for a power-of-two `spp`), and the frames `0 … 2^j − 1` together take an aligned group
//!   of `2^j` blocks: a pixel's samples over frames continue one progressive net.
//! - **Neighbours can be stratified together.** Blocks `b` and `b ^ 1` make an aligned block of
//!   `2B` points, blocks `b ^ 0 … b ^ 3` one of `4B`, and so on: pixels whose keys differ in
//!   their low bits hold samples that are stratified *jointly*, which is what cancels their
//!   errors under a denoiser's blur. Ahmed and Wonka (2020) get this from the Morton order of the
//!   pixels; the generator chooses the keys for the scene's filter instead, from a pool several
//!   times the tile's size, so that the pixels' errors are blue (the goal of Heitz, Belcour,
//!   Ostromoukhov, Coeurjolly and Iehl 2019, "A Low-Discrepancy Sampler that Distributes Monte
//!   Carlo Errors as a Blue Noise in Screen Space"). XOR-ing every key with the frame keeps
//!   siblings siblings, so that structure holds in every frame.
//!
//! The keys are stored as a mask of 16-bit texels, `D` layers of `W × H` (layer = dimension; a
//! pair's key is its first layer's texel plus `2^16` times its second's), so a lookup reads one
//! texel per key and the tile uploads, caches and exports as any other mask.
//! `nb_sampler_tile` in the WGSL library is the same integer arithmetic.

use super::{combine, owen, sobol};
use crate::mask::Mask3;
use crate::sequence::to_unit;

/// The word the pairs' scramble seeds are derived from.
const TILE_SEED: u32 = 0x5348_5546;

/// The Sobol index of sample `i` (below `spp`) of a pixel keyed `key`, in `frame`: point `i`
/// of block `key ^ frame`, blocks being `spp` rounded up to a power of two points long (a block
/// index past `2^32 / B` wraps).
#[must_use]
#[inline]
pub const fn tile_index(key: u32, frame: u32, i: u32, spp: u32) -> u32 {
    let shift = block_shift(spp);
    match (key ^ frame).checked_shl(shift) {
        Some(base) => base | i,
        None => i,
    }
}

/// `log2` of the block length for `spp` samples: `spp` rounded up to a power of two.
#[inline]
const fn block_shift(spp: u32) -> u32 {
    32 - spp.saturating_sub(1).leading_zeros()
}

/// Dimension `axis` (0 or 1) of the point at Sobol `index` of pair `pair` (dimensions
/// `2·pair` and `2·pair + 1`), as a 32-bit fraction: Sobol's dimension `axis`, Owen-scrambled
/// by the pair's own seed. What [`SamplerTile::sample`] returns, and what the generator
/// evaluates when it chooses keys.
#[must_use]
#[inline]
pub fn tile_value(index: u32, pair: u32, axis: usize) -> u32 {
    let axis = axis & 1;
    owen(
        sobol(index, axis),
        combine(combine(TILE_SEED, pair), axis as u32),
    )
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

    /// The key of the pair holding dimension `d` at pixel (x, y).
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

    /// Dimension `d` of sample `i` of pixel (x, y) in `frame`, as a 32-bit fraction: point `i`
    /// of block `key ^ frame` of the pair holding `d` ([`tile_index`], [`tile_value`]). `i` and
    /// `d` are taken modulo `SPP` and `D`.
    #[must_use]
    #[inline]
    pub fn sample_bits(&self, x: i32, y: i32, frame: u32, i: u32, d: u32) -> u32 {
        let (i, d) = (i % SPP, d % D);
        let index = tile_index(self.pair_key(x, y, d), frame, i, SPP);
        tile_value(index, d / 2, (d & 1) as usize)
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
        let index = tile_index(self.pair_key(x, y, d), frame, i, SPP);
        [
            to_unit(tile_value(index, d / 2, 0)),
            if d + 1 < D {
                to_unit(tile_value(index, d / 2, 1))
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

    /// Whether `pts` hold one point in each of the `len` elementary intervals of every shape:
    /// a (0, m, 2)-net.
    fn is_net(pts: &[[u32; 2]]) -> bool {
        let m = pts.len().trailing_zeros();
        assert_eq!(pts.len(), 1 << m);
        (0..=m).all(|lx| {
            let ly = m - lx;
            let mut seen = std::vec![false; pts.len()];
            pts.iter().all(|p| {
                let cx = if lx == 0 { 0 } else { p[0] >> (32 - lx) };
                let cy = if ly == 0 { 0 } else { p[1] >> (32 - ly) };
                let cell = (cx << ly | cy) as usize;
                !std::mem::replace(&mut seen[cell], true)
            })
        })
    }

    fn points(key: u32, frames: core::ops::Range<u32>, spp: u32, pair: u32) -> Vec<[u32; 2]> {
        frames
            .flat_map(|f| {
                (0..spp).map(move |i| {
                    let index = tile_index(key, f, i, spp);
                    [tile_value(index, pair, 0), tile_value(index, pair, 1)]
                })
            })
            .collect()
    }

    /// Whatever the key, a pixel's samples of one frame are a (0, m, 2)-net, its frames
    /// `0 … 2^j − 1` together one of `2^j` times as many points, and two pixels whose keys differ
    /// in the lowest bit hold a net together (so do four whose keys differ in the lowest two).
    #[test]
    fn every_key_gives_nets_over_samples_frames_and_siblings() {
        for key in [0u32, 1, 0xdead_beef, u32::MAX, 0x8000_0000, 0x1234] {
            for spp in [1u32, 2, 4, 16] {
                for pair in 0..3 {
                    assert!(is_net(&points(key, 0..1, spp, pair)), "{key:#x} spp {spp}");
                    assert!(is_net(&points(key, 3..4, spp, pair)), "{key:#x} spp {spp}");
                    assert!(is_net(&points(key, 0..4, spp, pair)), "{key:#x} spp {spp}");
                    assert!(is_net(&points(key, 8..16, spp, pair)), "{key:#x} spp {spp}");
                    let mut two = points(key, 5..6, spp, pair);
                    two.extend(points(key ^ 1, 5..6, spp, pair));
                    assert!(is_net(&two), "{key:#x} spp {spp}: siblings");
                    let four: Vec<[u32; 2]> = (0..4)
                        .flat_map(|s| points(key ^ s, 2..3, spp, pair))
                        .collect();
                    assert!(is_net(&four), "{key:#x} spp {spp}: four siblings");
                }
            }
        }
        // Keys that differ in a high bit only do not stratify together: the property is the
        // low bits', which is what the generator arranges.
        let mut far = points(0, 0..1, 4, 0);
        far.extend(points(1 << 12, 0..1, 4, 0));
        assert!(!is_net(&far));
        // A non-power-of-two spp takes the first spp points of a block of the next power of two.
        assert_eq!(tile_index(5, 0, 2, 3), 5 * 4 + 2);
        assert_eq!(tile_index(5, 2, 0, 3), 7 * 4);
    }

    /// The view reads the right layers: a pair's key is its first layer plus 2^16 times its
    /// second, a lone last dimension's its one layer; coordinates wrap; `sample2` is two
    /// `sample`s; pairs are scrambled apart.
    #[test]
    fn the_view_reads_keys_by_pair() {
        let mut bytes: Vec<u8> = (0..4 * 2 * 3 * 2).map(|i| (i * 91 + 3) as u8).collect();
        bytes[0] = 7;
        let key = |b: &[u8], layer: usize| {
            u16::from_le_bytes([b[2 * (7 + 8 * layer)], b[2 * (7 + 8 * layer) + 1]]) as u32
        };
        let pair = key(&bytes, 0) | key(&bytes, 1) << 16;
        let lone = key(&bytes, 2);
        let t = tile(Vec::leak(bytes));
        // Pixel (3, 1), frame 2, sample 5: point 5 of block pair ^ 2, 8 points long.
        assert_eq!(
            t.sample_bits(3, 1, 2, 5, 1),
            tile_value(((pair ^ 2) << 3) | 5, 0, 1)
        );
        assert_eq!(
            t.sample_bits(3, 1, 2, 13, 2),
            tile_value(((lone ^ 2) << 3) | 5, 1, 0)
        );
        assert_eq!(t.sample_bits(-1, -1, 1, 0, 2), t.sample_bits(3, 1, 1, 0, 2));
        assert_eq!(
            t.sample2(2, 0, 3, 1, 0),
            [t.sample(2, 0, 3, 1, 0), t.sample(2, 0, 3, 1, 1)]
        );
        assert_eq!(t.sample2(2, 0, 3, 1, 2), [t.sample(2, 0, 3, 1, 2), 0.0]);
        assert_ne!(tile_value(77, 0, 0), tile_value(77, 1, 0));
    }
}
