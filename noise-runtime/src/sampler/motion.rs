//! A free sampler built for a moving camera: every frame a rank-1 lattice per pair of
//! dimensions, moved by a shift that is linear in the pixel and in the frame.
//!
//! Sample `i` of `frame` at pixel `(x, y)`, pair `p` (dimensions `2p`, `2p + 1`), with `N` the
//! samples per frame:
//!
//! ```text
//! c   = frac(x·a + y·b + frame·g)                        two fractions: the shift
//! u_x = (i + c₀) / N                                     the lattice {i·(1, z) / N}
//! u_y = frac(z·u_x + c₁)                                 moved by c₀·(1, z)/N + c₁·(0, 1)
//! ```
//!
//! **Why linear.** A surface that moves `v` pixels a frame is seen by pixel `p₀ + f·v` in
//! frame `f`, so its shift is `frac(p₀·(a, b) + f·(v·(a, b) + g))`: the motion only changes
//! the step of the surface's Kronecker sequence, and each surface point still walks a
//! low-discrepancy sequence of lattice translates. A table or a hash keyed by the screen
//! (Heitz et al. 2019's tables, the baked tiles, Owen-scrambled Sobol) gives a moving
//! surface an unrelated sequence every frame, and its accumulated error falls to that of
//! independent frames.
//!
//! **Why a lattice per frame.** The `N` samples of a frame are a whole rank-1 lattice, so
//! only its dual frequencies `k` (with `k·(1, z) ≡ 0 mod N`) carry error; the shift maps each
//! of those to a spatial frequency `(m·a, m·b)` and a temporal one `m·g` of the screen, with
//! `m = ((k_x + z·k_y)/N, k_y)`. The denoiser removes high spatial frequencies and the
//! accumulation (following the motion) high temporal ones along the motion's direction.
//!
//! **Two pairs.** Dimensions 2–3 run the same construction with constants of their own. In
//! one frame both pairs are lattices moved by a shift, so sample `i` of the second would be
//! sample `i` of the first plus a constant, and an integrand of all four dimensions (a
//! bounce: a direction, then a point on a light) would accumulate that correlation as a bias.
//! The second pair's sample `i` is therefore its lattice point `i + h` (mod `N`), `h` a hash
//! of the pixel and frame: a lattice point moves the lattice onto itself, so the second
//! pair's set, and its error, are unchanged.
//!
//! **How the constants were chosen.** `noisebake search-sampler` minimises, for every `N`
//! from 1 to 16 and every lattice generator `z`, the worst ratio of the expected error (in
//! closed form: integrand power spectra of half-planes of the square and half-spaces of
//! cosine-weighted directions, times the response of a Gaussian σ 1 or an à-trous of three
//! passes, times an EMA of α 0.1 whose history is resampled bilinearly along the motion) to
//! that of [`super::r2_pairs`], over a still camera and pans of 0.3 to 3.4 pixels a frame in
//! twelve directions, at once. The result is [`MOTION_PAIRS`]; `noisebake report render`
//! measures it in a ray-traced scene under motions the search never saw.
//!
//! Integer arithmetic on 32-bit fractions throughout, so `nb_motion_pairs` in the WGSL library
//! gives the same bits.

use crate::hash::hash3;
use crate::sequence::to_unit;

/// The seed of the hash that pairs the second pair's samples with the first's.
const PAIRING_SEED: u32 = 0x6d6f_7469;

/// One pair's lattice and its linear shift, as `noisebake search-sampler` chose them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PairDrift {
    /// The lattice generator: sample `i` of a frame sits at `(i/N, i·z/N)` before the shift.
    pub z: u32,
    /// The shift's step per pixel in x, as two 32-bit fractions (lattice coordinates).
    pub x: [u32; 2],
    /// The shift's step per pixel in y.
    pub y: [u32; 2],
    /// The shift's step per frame.
    pub frame: [u32; 2],
}

/// The largest number of samples per frame with their own constants; more are split into
/// blocks of this many (see [`motion_pairs`]).
pub const MOTION_MAX_SPP: u32 = 16;

/// Per samples-per-frame `N` (index `N − 1`), the two pairs' constants.
pub const MOTION_PAIRS: [[PairDrift; 2]; MOTION_MAX_SPP as usize] = super::motion_table::TABLE;

/// The shift of one pair at pixel `(x, y)` in `frame`: `frac(x·a + y·b + frame·g)` in 32-bit
/// fixed point, exact for any coordinates (negative ones wrap as two's complement, which is
/// the same fraction).
#[inline(always)]
fn shift(p: &PairDrift, x: i32, y: i32, frame: u32) -> [u32; 2] {
    core::array::from_fn(|k| {
        (x as u32)
            .wrapping_mul(p.x[k])
            .wrapping_add((y as u32).wrapping_mul(p.y[k]))
            .wrapping_add(frame.wrapping_mul(p.frame[k]))
    })
}

/// `⌊2^32 / n⌋` for `n` in 2..=16: `(i + c/2^32) / n` is `i·R + ⌊c·R / 2^32⌋`, exact for powers
/// of two and within `2^-31` of the lattice otherwise. Tabulated: a division per read would
/// cost more than the rest of the read.
#[inline(always)]
fn reciprocal(n: u32) -> u32 {
    const TABLE: [u32; MOTION_MAX_SPP as usize + 1] = {
        let mut t = [0u32; MOTION_MAX_SPP as usize + 1];
        let mut n = 2;
        while n <= MOTION_MAX_SPP as usize {
            t[n] = (0x1_0000_0000u64 / n as u64) as u32;
            n += 1;
        }
        t
    };
    TABLE[n as usize]
}

/// Point `i` of the `n`-point lattice of `p` moved by the shift `c`, as two 32-bit fractions.
#[inline(always)]
fn point(p: &PairDrift, c: [u32; 2], i: u32, n: u32) -> [u32; 2] {
    let ux = if n == 1 {
        c[0]
    } else {
        let r = reciprocal(n);
        i.wrapping_mul(r)
            .wrapping_add(((c[0] as u64 * r as u64) >> 32) as u32)
    };
    [ux, p.z.wrapping_mul(ux).wrapping_add(c[1])]
}

/// `(frame, i, n)` for sample `i` of `frame` at `spp` samples per frame: a sample index past
/// the frame continues into the next frames; more than [`MOTION_MAX_SPP`] samples a frame
/// run as several blocks of 16, each a frame of the 16-sample design.
#[inline(always)]
fn schedule(frame: u32, i: u32, spp: u32) -> (u32, u32, u32) {
    let spp = spp.max(1);
    let frame = frame.wrapping_add(i / spp);
    let i = i % spp;
    if spp <= MOTION_MAX_SPP {
        (frame, i, spp)
    } else {
        let blocks = spp.div_ceil(MOTION_MAX_SPP);
        (
            frame.wrapping_mul(blocks).wrapping_add(i / MOTION_MAX_SPP),
            i % MOTION_MAX_SPP,
            MOTION_MAX_SPP,
        )
    }
}

/// The sample's pairs as 32-bit fractions: `D` of dimensions 0–3.
#[inline(always)]
pub(crate) fn motion_bits<const D: usize>(
    x: i32,
    y: i32,
    frame: u32,
    i: u32,
    spp: u32,
) -> [u32; D] {
    let (frame, i, n) = schedule(frame, i, spp);
    let table = &MOTION_PAIRS[n as usize - 1];
    let mut out = [0u32; D];
    for (pair, p) in table.iter().enumerate().take(D.div_ceil(2)) {
        // The second pair's sample `i` is its lattice point `i + h`, `h` a hash of the pixel
        // and frame: the same set, but no longer the first pair's point plus a constant.
        let j = if pair == 0 {
            i
        } else {
            (i + hash3(x, y, frame as i32, PAIRING_SEED) % n) % n
        };
        let v = point(p, shift(p, x, y, frame), j, n);
        for (k, &bits) in v.iter().enumerate() {
            if 2 * pair + k < D {
                out[2 * pair + k] = bits;
            }
        }
    }
    out
}

/// `D` values (1 to 4) of sample `i` of `frame` at pixel `(x, y)`, for a renderer that takes
/// `spp` samples per pixel per frame: a free sampler built for a moving camera (module docs).
/// Dimensions 0–1 and 2–3 are two pairs with constants of their own, each a rank-1 lattice per
/// frame whose shift is linear in the pixel and the frame. The first values of `D = 4` are
/// those of smaller `D`.
///
/// `spp` is the renderer's samples per frame (0 reads as 1); `i` is below it (an `i` past it
/// continues into later frames). Above 16 samples a frame, the samples run as blocks of 16,
/// block `j` of frame `f` being frame `f·⌈spp/16⌉ + j` of the 16-sample design.
#[must_use]
#[inline]
pub fn motion_pairs<const D: usize>(x: i32, y: i32, frame: u32, i: u32, spp: u32) -> [f32; D] {
    const { assert!(D >= 1 && D <= super::MAX_DIMS, "1 to 4 values per pixel") };
    motion_bits::<D>(x, y, frame, i, spp).map(to_unit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec::Vec;

    /// Distance on the circle of 32-bit fractions.
    fn apart(a: u32, b: u32) -> u32 {
        a.wrapping_sub(b).min(b.wrapping_sub(a))
    }

    /// Every frame of every pair is the whole lattice `{i·(1, z)/N}` moved by one shift: the
    /// samples minus sample 0 are the lattice's points, each once (to the 2^-28 the
    /// fixed-point division leaves for an `N` that does not divide 2^32).
    #[test]
    fn every_frame_is_a_shifted_lattice() {
        for n in 1..=MOTION_MAX_SPP {
            for &(x, y, f) in &[
                (0, 0, 0u32),
                (17, -5, 3),
                (-40_000, 123, 999),
                (i32::MAX, 7, u32::MAX),
            ] {
                for pair in 0..2 {
                    let z = MOTION_PAIRS[n as usize - 1][pair].z;
                    let pts: Vec<[u32; 2]> = (0..n)
                        .map(|i| {
                            let v = motion_bits::<4>(x, y, f, i, n);
                            [v[2 * pair], v[2 * pair + 1]]
                        })
                        .collect();
                    let mut seen = std::vec![false; n as usize];
                    for p in &pts {
                        let d = [p[0].wrapping_sub(pts[0][0]), p[1].wrapping_sub(pts[0][1])];
                        let k = (0..n)
                            .find(|&k| {
                                let want = ((k as u64) << 32) / n as u64;
                                apart(d[0], want as u32) < 16
                                    && apart(d[1], (want as u32).wrapping_mul(z)) < 16 * n
                            })
                            .unwrap_or_else(|| panic!("n {n} pair {pair} ({x}, {y}, {f}): {d:x?}"));
                        assert!(
                            !seen[k as usize],
                            "n {n} pair {pair}: lattice point {k} twice"
                        );
                        seen[k as usize] = true;
                    }
                }
            }
        }
    }

    /// A surface moving a whole number of pixels a frame sees its shift advance by the same
    /// step every frame: `c(p₀ + f·v, f) = c(p₀, 0) + f·(v·(a, b) + g)`, the Kronecker sequence
    /// the module's design rests on.
    #[test]
    fn a_uniform_motion_keeps_a_kronecker_sequence() {
        for n in [1u32, 4, 7, 16] {
            let p = &MOTION_PAIRS[n as usize - 1][0];
            for v in [[0, 0], [2, -1], [-3, 5]] {
                let (x0, y0) = (11, -4);
                let at = |f: u32| shift(p, x0 + f as i32 * v[0], y0 + f as i32 * v[1], f);
                let step = [
                    at(1)[0].wrapping_sub(at(0)[0]),
                    at(1)[1].wrapping_sub(at(0)[1]),
                ];
                for f in 1..64 {
                    assert_eq!(at(f)[0].wrapping_sub(at(f - 1)[0]), step[0]);
                    assert_eq!(at(f)[1].wrapping_sub(at(f - 1)[1]), step[1]);
                }
                // And sample 0's first coordinate is that shift's, divided by N.
                let u = |f: u32| {
                    motion_bits::<1>(x0 + f as i32 * v[0], y0 + f as i32 * v[1], f, 0, n)[0]
                };
                let want = |f: u32| {
                    if n == 1 {
                        at(f)[0]
                    } else {
                        ((at(f)[0] as u64 * reciprocal(n) as u64) >> 32) as u32
                    }
                };
                for f in 0..64 {
                    assert_eq!(u(f), want(f), "n {n} v {v:?} f {f}");
                }
            }
        }
    }

    /// Samples past the frame continue into the next frames, more than 16 a frame run as blocks
    /// of the 16-sample design, and 0 samples a frame read as 1.
    #[test]
    fn the_schedule_is_as_documented() {
        for (x, y, f) in [(3, 4, 5u32), (-9, 0, 1000)] {
            for spp in [1u32, 3, 16] {
                for i in 0..spp {
                    assert_eq!(
                        motion_pairs::<4>(x, y, f, i + spp, spp),
                        motion_pairs::<4>(x, y, f + 1, i, spp)
                    );
                }
            }
            for i in 0..40 {
                assert_eq!(
                    motion_pairs::<4>(x, y, f, i, 40),
                    motion_pairs::<4>(x, y, 3 * f + i / 16, i % 16, 16),
                    "40 spp, sample {i}"
                );
            }
            assert_eq!(
                motion_pairs::<2>(x, y, f, 0, 0),
                motion_pairs::<2>(x, y, f, 0, 1)
            );
            // The first values of D = 4 are those of smaller D.
            let four = motion_pairs::<4>(x, y, f, 2, 5);
            assert_eq!(
                motion_pairs::<3>(x, y, f, 2, 5),
                [four[0], four[1], four[2]]
            );
        }
    }

    /// The WGSL library carries the same constants (written by `noisebake search-sampler
    /// --all --wgsl`): a table edited on one side only fails here, without a GPU.
    #[test]
    fn the_wgsl_table_is_the_runtime_table() {
        let wgsl = crate::shaders::WGSL;
        for (i, pairs) in MOTION_PAIRS.iter().enumerate() {
            for (k, p) in pairs.iter().enumerate() {
                let line = std::format!(
                    "vec4<u32>({}u, 0x{:08x}u, 0x{:08x}u, 0x{:08x}u), vec4<u32>(0x{:08x}u, 0x{:08x}u, 0x{:08x}u, 0u), // spp {}, pair {k}",
                    p.z,
                    p.x[0],
                    p.x[1],
                    p.y[0],
                    p.y[1],
                    p.frame[0],
                    p.frame[1],
                    i + 1
                );
                assert!(wgsl.contains(&line), "the WGSL table lacks `{line}`");
            }
        }
        assert!(wgsl.contains("const NB_MOTION_PAIRING_SEED = 0x6d6f7469u;"));
        assert_eq!(PAIRING_SEED, 0x6d6f_7469);
    }
}
