//! Ahmed & Wonka 2020, "Screen-space blue-noise diffusion of Monte Carlo sampling error via
//! hierarchical ordering of pixels" (SIGGRAPH Asia 2020), as pbrt-v4's `ZSobolSampler` and
//! Blender Cycles build on it: no table. Pixels are visited in Morton (Z) order, and the base-4
//! digits of that order are shuffled level by level — each digit by one of the 24 permutations
//! of four, chosen by a hash of the digits above it — so that every aligned 2^k × 2^k block of
//! pixels takes consecutive points of one Owen-scrambled Sobol sequence. Consecutive Sobol
//! points are stratified, so each block's samples together are too: the error is blue across
//! the screen at every scale, and each pixel's own `spp` points are a stratified run.
//!
//! The algorithm is the paper's and pbrt-v4's, over the runtime's Sobol matrices and Burley's
//! Owen scramble (`noise_runtime::sampler::{sobol, owen}`, as pbrt's `FastOwenScrambler`); the
//! seed hash is ours (any good 64-bit mix: pbrt hashes with MurmurHash), so the values are not
//! pbrt's bit for bit.

use noise_runtime::sampler::{owen, sobol};

/// The 24 permutations of `0..4`, in lexicographic order.
const PERMUTATIONS: [[u8; 4]; 24] = {
    let mut out = [[0u8; 4]; 24];
    let mut n = 0;
    let mut a = 0;
    while a < 4 {
        let mut b = 0;
        while b < 4 {
            let mut c = 0;
            while c < 4 {
                let d = 6 - a - b - c;
                if a != b && a != c && b != c && d < 4 && d != a && d != b && d != c {
                    out[n] = [a as u8, b as u8, c as u8, d as u8];
                    n += 1;
                }
                c += 1;
            }
            b += 1;
        }
        a += 1;
    }
    out
};

/// A 64-bit finaliser (pbrt's `MixBits`, after Stafford's Mix13).
fn mix(mut v: u64) -> u64 {
    v ^= v >> 31;
    v = v.wrapping_mul(0x7fb5_d329_728e_a185);
    v ^= v >> 27;
    v = v.wrapping_mul(0x81da_def4_bc2d_d44d);
    v ^= v >> 33;
    v
}

/// A ZSobol sampler for an image of `resolution` pixels on its longer side and `spp` (a power
/// of two) samples per pixel.
#[derive(Clone, Copy, Debug)]
pub struct ZSobol {
    log2_spp: u32,
    base4_digits: u32,
    seed: u64,
}

impl ZSobol {
    /// The sampler; `spp` is rounded up to a power of two.
    pub fn new(resolution: usize, spp: u32, seed: u64) -> ZSobol {
        let log2_spp = spp.max(1).next_power_of_two().trailing_zeros();
        let log2_res = resolution.max(1).next_power_of_two().trailing_zeros();
        ZSobol {
            log2_spp,
            base4_digits: log2_res + log2_spp.div_ceil(2),
            seed,
        }
    }

    /// The Sobol index of sample `i` of pixel `(x, y)` for the pair of dimensions starting at
    /// `dimension`: the pixel's Morton code with the sample index below it, each base-4 digit
    /// permuted by a hash of the digits above it (and, for an odd `log2 spp`, the last bit
    /// flipped by one).
    fn index(&self, x: u32, y: u32, i: u32, dimension: u64) -> u32 {
        let morton = (morton2(x, y) << self.log2_spp) | u64::from(i);
        let odd = self.log2_spp & 1;
        let mut index = 0u64;
        for level in (odd..self.base4_digits).rev() {
            let shift = 2 * level - odd;
            let digit = (morton >> shift) & 3;
            let higher = morton >> (shift + 2);
            let p = (mix(higher ^ 0x5555_5555u64.wrapping_mul(dimension)) >> 24) % 24;
            index |= u64::from(PERMUTATIONS[p as usize][digit as usize]) << shift;
        }
        if odd == 1 {
            let bit = morton & 1;
            index |= bit ^ (mix((morton >> 1) ^ 0x5555_5555u64.wrapping_mul(dimension)) & 1);
        }
        index as u32
    }

    /// Dimension `d` of sample `i` of pixel `(x, y)`, in `[0, 1)`: dimensions come in pairs,
    /// each pair its own ordering and scramble of Sobol dimensions 0 and 1 (pbrt's `Get2D`).
    pub fn sample(&self, x: i32, y: i32, i: u32, d: u32) -> f32 {
        let pair = u64::from(d / 2) * 2;
        let index = self.index(x as u32, y as u32, i, pair);
        let bits = mix(self.seed ^ mix(pair + 2));
        let seed = if d.is_multiple_of(2) {
            bits as u32
        } else {
            (bits >> 32) as u32
        };
        let v = owen(sobol(index, (d % 2) as usize), seed);
        (v >> 8) as f32 / (1u32 << 24) as f32
    }
}

/// The Morton code of `(x, y)`: their bits interleaved, x in the even bits.
fn morton2(x: u32, y: u32) -> u64 {
    let spread = |v: u32| {
        let mut v = u64::from(v);
        v = (v | (v << 16)) & 0x0000_ffff_0000_ffff;
        v = (v | (v << 8)) & 0x00ff_00ff_00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333_3333_3333;
        (v | (v << 1)) & 0x5555_5555_5555_5555
    };
    spread(x) | (spread(y) << 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_permutations_are_the_24_distinct_ones() {
        let mut seen = std::collections::BTreeSet::new();
        for p in PERMUTATIONS {
            let mut s = p;
            s.sort();
            assert_eq!(s, [0, 1, 2, 3]);
            seen.insert(p);
        }
        assert_eq!(seen.len(), 24);
    }

    /// The hierarchical property: an aligned 2^k × 2^k block of pixels at `spp` samples takes
    /// 4^k · spp consecutive Sobol indices, so in each dimension its samples fall one to each
    /// of 4^k · spp equal intervals (Owen scrambling keeps that stratification); and a pixel's
    /// own samples are a stratified run too.
    #[test]
    fn blocks_and_pixels_are_stratified() {
        for spp in [1u32, 2, 4, 8] {
            let z = ZSobol::new(64, spp, 11);
            for d in 0..4 {
                for (x0, y0, side) in [(0, 0, 2), (8, 4, 4), (32, 48, 8)] {
                    let n = (side * side) as u32 * spp;
                    let mut strata = vec![false; n as usize];
                    for y in y0..y0 + side {
                        for x in x0..x0 + side {
                            for i in 0..spp {
                                let v = z.sample(x, y, i, d);
                                let s = (v * n as f32) as usize;
                                assert!(!strata[s], "spp {spp} d {d} block ({x0}, {y0})");
                                strata[s] = true;
                            }
                        }
                    }
                }
                let mut strata = vec![false; spp as usize];
                for i in 0..spp {
                    let s = (z.sample(5, 9, i, d) * spp as f32) as usize;
                    assert!(!strata[s]);
                    strata[s] = true;
                }
            }
        }
    }
}
