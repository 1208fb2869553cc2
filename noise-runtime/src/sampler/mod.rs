//! Several values per pixel per frame with no texture: the free constructions a graphics
//! programmer reaches for when a pixel needs a direction (two values) or an RGB dither (three),
//! and the fair baselines every baked vector mask is measured against.
//!
//! The k-th value of a pixel must not be a function of its first. Shifting the coordinates of
//! one grid (`r2(x + 17k, y + 29k)`) fails that: R2 is linear in `(x, y)`, so the shifted value
//! is the first plus a constant, and a direction warped from the pair lies on one curve. Every
//! construction here gives each dimension its own per-pixel value instead:
//!
//! - [`ign_r2`]: interleaved gradient noise for the first value, the R2 grid for the second
//!   (then R2 mirrored and IGN with x and y swapped), each animated over frames — the pair a
//!   shader writes in two lines;
//! - [`rd`] and [`rd_ign_r2`]: the frame-th point of the R_d sequence (Roberts 2018, the
//!   generalised golden ratio), Cranley–Patterson rotated per pixel — by the free grids of
//!   [`ign_r2`], or by any per-pixel offsets (a 2D blue-noise mask's `get_k`);
//! - [`sobol_owen`]: the per-pixel shuffled, Owen-scrambled Sobol sequence of Burley (2020,
//!   "Practical Hash-based Owen Scrambling", JCGT 9(4)): white noise across pixels, and in time
//!   each pixel's first 2^m frames form a (0, m, 2)-net in every pair of its first two
//!   dimensions.
//!
//! - [`motion_pairs`]: built for a moving camera — every frame a rank-1 lattice per pair of
//!   dimensions, moved by a shift linear in the pixel and the frame, so a surface the camera
//!   moves across still walks a low-discrepancy sequence (constants from `noisebake
//!   search-sampler`);
//!
//! - [`SamplerTile`]: the baked form (kind `sampler`): `rd_ign_r2`'s structure — every pixel
//!   runs one sequence per pair (a rank-1 lattice, or Owen-scrambled Sobol for `square`
//!   pairs), moved by keys of its own — with the keys arranged at build
//!   time so that the pixels' errors are blue under the scene's denoiser, in the space the
//!   ray uses, on one frame or accumulated (Heitz et al. 2019's goal; Belcour and Heitz 2021's
//!   lattice with optimised shifts).
//!
//! Everything is integer arithmetic on 32-bit fractions, so `nb_ign_r2`, `nb_rd2_ign_r2`,
//! `nb_rd3_ign_r2` and `nb_sobol_owen` in the WGSL library give the same bits.

mod motion;
mod motion_table;
mod tile;
pub use motion::{MOTION_MAX_SPP, MOTION_PAIRS, PairDrift, motion_pairs};
pub use tile::{MAX_TILE_DIMS, SamplerTile, TILE_GENERATOR, sobol2, tile_point};

use crate::hash::hash2;
use crate::sequence::{GOLDEN, R2_A1, R2_A2, frac_mul, to_unit};

/// The largest `D` of the fixed-size constructions.
pub const MAX_DIMS: usize = 4;

#[inline(always)]
fn wide(v: i32) -> u64 {
    v as i64 as u64
}

/// `frac(x·a + y·b)` as a 32-bit fraction, exact for any `i32` coordinates.
#[inline(always)]
fn linear_bits(x: i32, y: i32, a: u64, b: u64) -> u32 {
    (wide(x)
        .wrapping_mul(a)
        .wrapping_add(wide(y).wrapping_mul(b))
        >> 32) as u32
}

/// IGN's inner fraction `frac(0.06711056x + 0.00583715y)` in 64-bit fixed point, plus
/// `frame · shift` (a 64-bit fraction): moving IGN by `o` pixels per frame adds
/// `o · (0.06711056, 0.00583715) · (1, 1)` per frame to the fraction, exactly.
#[inline(always)]
fn ign_inner(x: i32, y: i32, frame: u32, shift: u64) -> u64 {
    wide(x)
        .wrapping_mul(IGN_A)
        .wrapping_add(wide(y).wrapping_mul(IGN_B))
        .wrapping_add((frame as u64).wrapping_mul(shift))
}

/// 0.06711056 · 2^64 and 0.00583715 · 2^64: IGN's inner weights.
const IGN_A: u64 = 0x112e_285c_6a8f_1506;
const IGN_B: u64 = 0x017e_8b20_5a12_9b0d;
/// 5.588238 · (IGN_A + IGN_B) mod 2^64: IGN moved by 5.588238 pixels in x and in y per frame.
const IGN_SHIFT_XY: u64 = 0x685b_b218_1123_5c12;
/// 5.588238 · IGN_A mod 2^64: IGN moved by 5.588238 pixels in x only per frame.
const IGN_SHIFT_X: u64 = 0x6001_f3a6_f81a_e4eb;

/// Interleaved gradient noise of an inner fraction, as a 32-bit fraction, computed as the WGSL
/// library computes it: `52·f` (exact) plus `0.9829189·f` (to 2^-32). `ldg::ign` rounds an
/// `f64` product instead; the two agree to within 2^-23 modulo 1.
#[inline(always)]
fn ign_bits(inner: u64) -> u32 {
    const FRACTION: u64 = 0xfba0_92b2; // 0.9829189 · 2^32
    let (lo, hi) = (inner as u32, (inner >> 32) as u32);
    let whole = 52u32
        .wrapping_mul(hi)
        .wrapping_add(((52 * lo as u64) >> 32) as u32);
    whole.wrapping_add(((FRACTION * hi as u64) >> 32) as u32)
}

/// The four free per-pixel values in `frame`, as 32-bit fractions: IGN, the R2 grid, R2
/// mirrored (`frac(x/ρ − y/ρ²)`), IGN with x and y swapped. Each is a different function of
/// `(x, y)`, and each moves differently over frames (IGN by 5.588238 pixels in x and y, R2 by
/// φ − 1, mirrored R2 by 1/ρ, IGNᵀ by 5.588238 pixels along its first axis), so no value is a
/// function of another in one frame or in one pixel's time series.
///
/// Mirrored, not transposed: R2 and R2 with x and y swapped map neighbouring pixels to the
/// columns (1/ρ, 1/ρ²) and (1/ρ², 1/ρ) of a matrix of determinant 0.245, nearly parallel, and
/// that pair measured no better than white noise for directions (`report vector`'s measure:
/// 0.0190 against white's 0.0185 after box 5×5 × EMA); mirrored, the columns (1/ρ, 1/ρ) and
/// (1/ρ², −1/ρ²) are orthogonal (determinant −0.860) and the pair measured 0.0113.
#[inline(always)]
fn grids(x: i32, y: i32, frame: u32) -> [u32; MAX_DIMS] {
    let step = |alpha: u64| (frac_mul(frame as u64, alpha) >> 32) as u32;
    [
        ign_bits(ign_inner(x, y, frame, IGN_SHIFT_XY)),
        linear_bits(x, y, R2_A1, R2_A2).wrapping_add(step(GOLDEN)),
        linear_bits(x, y, R2_A1, R2_A2_NEG).wrapping_add(step(R2_A1)),
        ign_bits(ign_inner(y, x, frame, IGN_SHIFT_X)),
    ]
}

/// `2^64 − R2_A2`: `−1/ρ²` as a 64-bit fraction, the mirrored R2 grid's second weight.
const R2_A2_NEG: u64 = 0x6e1e_f25a_3861_84e4;

/// `D` values of pixel `(x, y)` in `frame` from interleaved gradient noise and the R2 grid:
/// value 0 is IGN moved by 5.588238 pixels per frame (Jimenez 2014, as games animate it),
/// value 1 the R2 grid advanced by `frame · (φ − 1)` mod 1 (exactly `ldg::r2_frame`); value 2
/// the mirrored R2 grid `frac(x/ρ − y/ρ²)` advanced by `1/ρ` per frame, value 3 IGN with x and
/// y swapped, moved 5.588238 pixels along one axis per frame. `D` is 1 to 4.
///
/// Measured by `noisebake report vector`, the IGN shift leaves less error after a box filter
/// × EMA than IGN advanced by the golden ratio (`ldg::ign_frame`), whose pairs would walk a
/// diagonal of the unit square over time; [`rd_ign_r2`] walks the R_d sequence instead.
#[must_use]
#[inline]
pub fn ign_r2<const D: usize>(x: i32, y: i32, frame: u32) -> [f32; D] {
    const { assert!(D >= 1 && D <= MAX_DIMS, "1 to 4 values per pixel") };
    let g = grids(x, y, frame);
    core::array::from_fn(|k| to_unit(g[k]))
}

/// `2^64 / φ_d^(k+1)` for the generalised golden ratio φ_d, the positive root of
/// `x^(d+1) = x + 1` (Roberts 2018): the step of axis `k` of the R_d sequence. R1 is the golden
/// ratio and R2 the plastic number's, the same constants as [`crate::sequence`].
const RD_ALPHA: [[u64; MAX_DIMS]; MAX_DIMS] = [
    [GOLDEN, 0, 0, 0],
    [R2_A1, R2_A2, 0, 0],
    [
        0xd1b5_4a32_d192_ed04,
        0xabc9_8388_fb8f_ac03,
        0x8cb9_2ba7_2f3d_8dd7,
        0,
    ],
    [
        0xdb4f_0b91_75ae_2165,
        0xbbe0_5633_03a4_615f,
        0xa0f2_ec75_a1fe_1576,
        0x89e1_8285_7d9e_d689,
    ],
];

/// The `frame`-th point of the `D`-dimensional R_d sequence, `frac(frame · α)` with
/// `α_k = φ_D^-(k+1)`, Cranley–Patterson rotated by `rotation` (each in `[0, 1)`, clamped to `[0, 1]`; added mod 1).
/// Over frames the points of one pixel are a low-discrepancy sequence in `[0, 1)^D`; the
/// rotation makes pixels differ. `D` is 1 to 4.
#[must_use]
#[inline]
pub fn rd<const D: usize>(frame: u32, rotation: [f32; D]) -> [f32; D] {
    const { assert!(D >= 1 && D <= MAX_DIMS, "1 to 4 values per pixel") };
    core::array::from_fn(|k| to_unit(rd_bits::<D>(frame, k).wrapping_add(fraction(rotation[k]))))
}

#[inline(always)]
fn rd_bits<const D: usize>(frame: u32, k: usize) -> u32 {
    (frac_mul(frame as u64, RD_ALPHA[D - 1][k]) >> 32) as u32
}

/// A value as a 32-bit fraction, clamped to `[0, 1]` first (1 becomes `2^32 − 1`; NaN 0).
#[inline(always)]
fn fraction(v: f32) -> u32 {
    (v.clamp(0.0, 1.0) as f64 * 4_294_967_296.0) as u32
}

/// [`rd`] rotated per pixel by the free grids of [`ign_r2`] at frame 0 (IGN, R2, mirrored R2,
/// IGNᵀ): no texture, and each pixel's values over frames are the R_d sequence.
#[must_use]
#[inline]
pub fn rd_ign_r2<const D: usize>(x: i32, y: i32, frame: u32) -> [f32; D] {
    const { assert!(D >= 1 && D <= MAX_DIMS, "1 to 4 values per pixel") };
    let g = grids(x, y, 0);
    core::array::from_fn(|k| to_unit(rd_bits::<D>(frame, k).wrapping_add(g[k])))
}

/// The free baseline for sampling: a rank-1 R2 lattice per pair of dimensions. Dimensions
/// `2j` and `2j + 1` walk the 2D R2 sequence, `frac(shift + index · (1/ρ, 1/ρ²))` (Roberts
/// 2018; ρ the plastic number), each pair from its own per-pixel shift: the free grids of
/// [`rd_ign_r2`] in frame 0 (IGN, R2, mirrored R2, IGNᵀ), one per dimension. `index` is the
/// sample's number in the pixel's sequence, `frame · spp + i` for sample `i` of `frame`.
///
/// Against [`rd_ign_r2`], which walks the 4D R_4 sequence with the same shifts, every pair
/// is a 2D rank-1 lattice: R_4's 2D projections pack points unevenly, R2 packs them close to
/// hexagonally, so the pair a ray warps (an AO direction, a point on an area light) is
/// better stratified in each pixel's time series and across a frame's `spp` samples. It is
/// what a graphics programmer writes in five lines, so it is the bar `noisebake report
/// render` holds every baked table against. The price: the pairs walk the same steps, so in
/// one pixel's time series dimension `2j + 2` is dimension `2j` plus a constant; an integrand
/// that couples the pairs (a bounce lit by an area light) sees them correlated. `D` is 1 to 4.
#[must_use]
#[inline]
pub fn r2_pairs<const D: usize>(x: i32, y: i32, index: u32) -> [f32; D] {
    const { assert!(D >= 1 && D <= MAX_DIMS, "1 to 4 values per pixel") };
    let g = grids(x, y, 0);
    core::array::from_fn(|k| to_unit(rd_bits::<2>(index, k & 1).wrapping_add(g[k])))
}

/// Sobol's direction numbers of the first four dimensions, 32 bits (Joe & Kuo 2008): dimension
/// 0 is van der Corput's radical inverse; 1–3 come from the primitive polynomials `x + 1`,
/// `x² + x + 1` and `x³ + x + 1` with initial numbers `m = (1)`, `(1, 3)`, `(1, 3, 1)`.
const SOBOL: [[u32; 32]; MAX_DIMS] = {
    // (degree s, coefficients a, initial m_1..m_s)
    const POLY: [(usize, u32, [u32; 3]); MAX_DIMS - 1] =
        [(1, 0, [1, 0, 0]), (2, 1, [1, 3, 0]), (3, 1, [1, 3, 1])];
    let mut v = [[0u32; 32]; MAX_DIMS];
    let mut i = 0;
    while i < 32 {
        v[0][i] = 1 << (31 - i);
        i += 1;
    }
    let mut d = 1;
    while d < MAX_DIMS {
        let (s, a, m) = POLY[d - 1];
        let mut i = 0;
        while i < 32 {
            v[d][i] = if i < s {
                m[i] << (31 - i)
            } else {
                let mut x = v[d][i - s] ^ (v[d][i - s] >> s);
                let mut k = 1;
                while k < s {
                    if (a >> (s - 1 - k)) & 1 == 1 {
                        x ^= v[d][i - k];
                    }
                    k += 1;
                }
                x
            };
            i += 1;
        }
        d += 1;
    }
    v
};

/// Dimension `d` (below [`MAX_DIMS`]) of the `index`-th Sobol point, as a 32-bit fraction: a
/// building block for other orderings of the sequence (the CLI's ZSobol comparison orders it by
/// pixel blocks).
///
/// # Panics
///
/// If `d` is [`MAX_DIMS`] or more.
#[must_use]
#[inline(always)]
pub fn sobol(index: u32, d: usize) -> u32 {
    let mut out = 0;
    let mut n = index;
    let mut i = 0;
    while n != 0 {
        if n & 1 == 1 {
            out ^= SOBOL[d][i];
        }
        n >>= 1;
        i += 1;
    }
    out
}

/// Burley's hash-based nested uniform (Owen) scramble of a 32-bit fraction: the Laine–Karras
/// permutation with Burley's constants, applied to the reversed bits, so each bit is flipped
/// by a hash of the bits above it.
#[must_use]
#[inline(always)]
pub fn owen(x: u32, seed: u32) -> u32 {
    owen_reversed(x.reverse_bits(), seed)
}

/// [`owen`] of the fraction whose bits, reversed, are `v`: a caller that has the reversed
/// bits at hand (the Sobol tables of a baked tile) skips one reversal.
#[must_use]
#[inline(always)]
pub(crate) fn owen_reversed(mut v: u32, seed: u32) -> u32 {
    v ^= v.wrapping_mul(0x3d20_adea);
    v = v.wrapping_add(seed);
    v = v.wrapping_mul((seed >> 16) | 1);
    v ^= v.wrapping_mul(0x0552_6c56);
    v ^= v.wrapping_mul(0x53a2_2864);
    v.reverse_bits()
}

/// Burley's seed combination (a Boost-style `hash_combine` finished by the runtime's mix).
#[inline(always)]
fn combine(seed: u32, v: u32) -> u32 {
    crate::hash::mix(
        seed ^ v
            .wrapping_add(0x9e37_79b9)
            .wrapping_add(seed << 6)
            .wrapping_add(seed >> 2),
    )
}

/// `D` values of pixel `(x, y)` in `frame` from the shuffled, Owen-scrambled Sobol sequence
/// (Burley 2020, §4): the pixel's seed is `hash2(x, y, seed)`; the frame index is scrambled by
/// it (a shuffle that keeps every power-of-two prefix stratified) and each dimension by its own
/// derived seed. Values of different pixels are independent; a pixel's first 2^m frames hold
/// one point in each of the 2^m elementary intervals of any shape in its first two
/// dimensions. The first values of `D = 4` are those of smaller `D`. `D` is 1 to 4.
#[must_use]
#[inline]
pub fn sobol_owen<const D: usize>(x: i32, y: i32, frame: u32, seed: u32) -> [f32; D] {
    const { assert!(D >= 1 && D <= MAX_DIMS, "1 to 4 values per pixel") };
    let pixel = hash2(x, y, seed);
    let index = owen(frame, pixel);
    core::array::from_fn(|d| to_unit(owen(sobol(index, d), combine(pixel, d as u32))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ldg;
    use std::vec::Vec;

    /// How much of a second value's spread is left once the first is known: the mean variance
    /// of `b` within 32 bins of `a`, over `b`'s variance. 1 for independent values; 0 when `b`
    /// is a function of `a`. Circular in `b` (values live on the torus).
    fn left_after(pairs: &[(f32, f32)]) -> f64 {
        let bins = 32;
        let mut groups: Vec<Vec<f64>> = (0..bins).map(|_| Vec::new()).collect();
        for &(a, b) in pairs {
            groups[((a * bins as f32) as usize).min(bins - 1)].push(b as f64);
        }
        // Circular: the least variance of `b − c mod 1` over 64 cuts `c` of the circle.
        let var = |v: &[f64]| {
            (0..64)
                .map(|c| {
                    let d: Vec<f64> = v
                        .iter()
                        .map(|&b| (b - c as f64 / 64.0).rem_euclid(1.0))
                        .collect();
                    let m = d.iter().sum::<f64>() / d.len() as f64;
                    d.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / d.len() as f64
                })
                .fold(f64::INFINITY, f64::min)
        };
        let within: f64 = groups
            .iter()
            .filter(|g| g.len() > 1)
            .map(|g| var(g))
            .sum::<f64>()
            / bins as f64;
        within / (1.0 / 12.0)
    }

    /// Every pair of dimensions `(i, j)` of a construction over a 64×64 frame and over 64
    /// frames of one pixel.
    fn pairs_of<const D: usize>(
        f: impl Fn(i32, i32, u32) -> [f32; D],
    ) -> [Vec<(usize, usize, f64)>; 2] {
        let mut out = [Vec::new(), Vec::new()];
        for i in 0..D {
            for j in 0..D {
                if i == j {
                    continue;
                }
                let space: Vec<(f32, f32)> = (0..64 * 64)
                    .map(|p| f(p % 64, p / 64, 3))
                    .map(|v| (v[i], v[j]))
                    .collect();
                let time: Vec<(f32, f32)> = (0..4096u32)
                    .map(|t| f(5, 9, t))
                    .map(|v| (v[i], v[j]))
                    .collect();
                out[0].push((i, j, left_after(&space)));
                out[1].push((i, j, left_after(&time)));
            }
        }
        out
    }

    /// The test can fail: shifted coordinates of one grid make the second value a function of
    /// the first, and the measure sees it.
    #[test]
    fn shifted_coordinates_are_caught() {
        let shifted =
            |x: i32, y: i32, f: u32| [ldg::r2_frame(x, y, f), ldg::r2_frame(x + 17, y + 29, f)];
        let [space, _] = pairs_of(shifted);
        for (i, j, left) in space {
            assert!(left < 0.01, "({i}, {j}): {left}");
        }
        let ign_shifted =
            |x: i32, y: i32, f: u32| [ldg::ign_frame(x, y, f), ldg::ign_frame(x + 17, y + 29, f)];
        let [space, _] = pairs_of(ign_shifted);
        for (i, j, left) in space {
            assert!(left < 0.2, "ign ({i}, {j}): {left}");
        }
    }

    #[test]
    fn no_value_is_a_function_of_another_in_space_or_time() {
        let check = |name: &str, r: [Vec<(usize, usize, f64)>; 2], time_too: bool| {
            for (i, j, left) in &r[0] {
                assert!(*left > 0.5, "{name} space ({i}, {j}): {left}");
            }
            if time_too {
                for (i, j, left) in &r[1] {
                    assert!(*left > 0.5, "{name} time ({i}, {j}): {left}");
                }
            }
        };
        // Independent values keep ~1 of their spread, a function of the first keeps ~0 (the
        // shifted grids above: < 0.01 for R2). Two grids keep less than 1 where their linear
        // structures meet (0.6 for mirrored R2 given IGN in one frame), and R_d's higher
        // projections in time (0.75 for dims 2 and 0 of R4): related, never functions.
        check("ign_r2", pairs_of(ign_r2::<4>), true);
        check("rd_ign_r2<2>", pairs_of(rd_ign_r2::<2>), true);
        check("rd_ign_r2<3>", pairs_of(rd_ign_r2::<3>), true);
        check("rd_ign_r2<4>", pairs_of(rd_ign_r2::<4>), true);
        // Sample `i` of a frame has its first value in the lattice's column `i` (a stratified
        // frame, not a dependence): read a sample chosen by a hash so every value is uniform.
        check(
            "motion_pairs",
            pairs_of(|x, y, f| {
                motion_pairs::<4>(x, y, f, crate::hash::hash3(x, y, f as i32, 1) % 4, 4)
            }),
            true,
        );
        check(
            "sobol_owen",
            pairs_of(|x, y, f| sobol_owen::<4>(x, y, f, 7)),
            true,
        );
        // Both values advanced by the golden ratio (as `ldg::ign_frame` and `ldg::r2_frame`
        // would) make the second the first plus a constant in one pixel's time series.
        let [_, time] = pairs_of(|x, y, f| [ldg::ign_frame(x, y, f), ldg::r2_frame(x, y, f)]);
        assert!(time[0].2 < 0.05, "golden-ratio pair in time: {}", time[0].2);
    }

    #[test]
    fn ign_r2_matches_the_grids_it_names() {
        // IGN at (x + 5.588238 f, y + 5.588238 f) in f64, as games compute it.
        let shifted = |x: i32, y: i32, f: u32| {
            let o = 5.588_238 * f as f64;
            let fract = |v: f64| v - v.floor();
            let inner = fract(0.067_110_56 * (x as f64 + o) + 0.005_837_15 * (y as f64 + o));
            fract(52.982_918_9 * inner) as f32
        };
        let close = |v: f32, want: f32, tol: f32| {
            let e = (v - want).abs();
            e.min(1.0 - e) <= tol
        };
        for (x, y, f) in [(0, 0, 0), (3, -7, 5), (1000, 20, 77), (-40, 9, 1000)] {
            let [a, b, c, d] = ign_r2::<4>(x, y, f);
            assert_eq!(b, ldg::r2_frame(x, y, f));
            // frac(x/ρ − y/ρ² + f/ρ) in f64, good to ~1e-12 for these coordinates.
            let r2m = (x as f64 * 0.754_877_666_246_692_7 - y as f64 * 0.569_840_290_998_053_3
                + f as f64 * 0.754_877_666_246_692_7)
                .rem_euclid(1.0) as f32;
            assert!(close(c, r2m, 1e-6), "({x}, {y}, {f}): {c} vs {r2m}");
            assert!(close(a, shifted(x, y, f), 1e-5), "({x}, {y}, {f}): {a}");
            let o = 5.588_238 * f as f64;
            let fract = |v: f64| v - v.floor();
            let ignt = fract(
                52.982_918_9 * fract(0.067_110_56 * (y as f64 + o) + 0.005_837_15 * x as f64),
            ) as f32;
            assert!(close(d, ignt, 1e-5), "({y}, {x}, {f}): {d} vs {ignt}");
        }
        // In frame 0 it is IGN itself, to within 2^-23, for any coordinates.
        for (x, y) in [(0, 0), (3, -7), (i32::MAX, i32::MIN), (1000, 20)] {
            let [a, _, _, d] = ign_r2::<4>(x, y, 0);
            assert!(close(a, ldg::ign(x, y), f32::EPSILON), "({x}, {y})");
            assert!(close(d, ldg::ign(y, x), f32::EPSILON), "({y}, {x})");
        }
    }

    /// Each pixel's values over frames are low-discrepancy: 256 frames in the 16×16 cells of the
    /// first two dimensions leave under a quarter of them empty and none holds more than 4
    /// (independent random points would leave about 37 % empty and pile 5 or more in some).
    #[test]
    fn rd_is_stratified_in_time() {
        for (x, y) in [(0, 0), (17, 3), (-5, 100)] {
            let mut cells = [0u8; 256];
            for f in 0..256 {
                let [a, b] = rd_ign_r2::<2>(x, y, f);
                cells[(a * 16.0) as usize * 16 + (b * 16.0) as usize] += 1;
            }
            let empty = cells.iter().filter(|&&c| c == 0).count();
            assert!(empty < 64, "({x}, {y}): {empty} empty cells");
            assert!(cells.iter().all(|&c| c <= 4), "({x}, {y}): {cells:?}");
        }
        // The rotation is added mod 1.
        let r = rd::<3>(10, [0.25, 0.5, 0.999]);
        let z = rd::<3>(10, [0.0; 3]);
        for k in 0..3 {
            let d = (r[k] - z[k]).rem_euclid(1.0);
            assert!((d - [0.25, 0.5, 0.999][k]).abs() < 1e-6, "{k}: {d}");
        }
    }

    /// Each pair of `r2_pairs` is the R2 sequence rotated by the pixel's grids: its first two
    /// dimensions are `rd_ign_r2::<2>`, its last two the same walk from the mirrored R2 and
    /// IGNᵀ shifts, so every pair of a pixel's 16 samples is a rank-1 lattice (no two
    /// points closer than 0.15, where 16 random points come within about 0.05).
    #[test]
    fn r2_pairs_walk_r2_in_each_pair() {
        for (x, y) in [(0, 0), (17, 3), (-5, 100), (i32::MAX, i32::MIN)] {
            let g = ign_r2::<4>(x, y, 0);
            for k in 0..64 {
                let p = r2_pairs::<4>(x, y, k);
                assert_eq!([p[0], p[1]], rd_ign_r2::<2>(x, y, k), "({x}, {y}, {k})");
                let r = rd::<2>(k, [0.0, 0.0]);
                for (d, (v, base)) in [(2, r[0]), (3, r[1])]
                    .into_iter()
                    .map(|(d, b)| (d, (p[d], b)))
                {
                    let off = (v - base - g[d]).rem_euclid(1.0);
                    assert!(off.min(1.0 - off) < 1e-6, "({x}, {y}, {k}) dim {d}: {off}");
                }
            }
            for pair in [0, 2] {
                let pts: Vec<[f32; 2]> = (0..16)
                    .map(|k| {
                        let p = r2_pairs::<4>(x, y, k);
                        [p[pair], p[pair + 1]]
                    })
                    .collect();
                let torus = |a: f32, b: f32| {
                    let d = (a - b).abs();
                    d.min(1.0 - d)
                };
                for i in 0..16 {
                    for j in 0..i {
                        let d = torus(pts[i][0], pts[j][0]).hypot(torus(pts[i][1], pts[j][1]));
                        assert!(d > 0.15, "({x}, {y}) pair {pair}: points {i}, {j} at {d}");
                    }
                }
            }
        }
        // The first values of D = 4 are those of smaller D.
        assert_eq!(r2_pairs::<2>(9, 4, 7), {
            let v = r2_pairs::<4>(9, 4, 7);
            [v[0], v[1]]
        });
    }

    /// The R_d steps are the generalised golden ratio's: `α_k = φ^-(k+1)` with φ^(d+1) = φ + 1.
    #[test]
    fn rd_steps_are_powers_of_the_generalised_golden_ratio() {
        for d in 1..=MAX_DIMS {
            let a0 = RD_ALPHA[d - 1][0] as f64 / 18_446_744_073_709_551_616.0;
            let phi = 1.0 / a0;
            let mut p = 1.0;
            for _ in 0..=d {
                p *= phi;
            }
            assert!(
                (p - phi - 1.0).abs() < 1e-12,
                "d = {d}: φ^(d+1) − φ − 1 = {}",
                p - phi - 1.0
            );
            for (k, &alpha) in RD_ALPHA[d - 1].iter().enumerate().take(d).skip(1) {
                let ak = alpha as f64 / 18_446_744_073_709_551_616.0;
                let mut want = a0;
                for _ in 0..k {
                    want *= a0;
                }
                assert!((ak - want).abs() < 1e-15, "d = {d}, k = {k}");
            }
        }
    }

    /// A pixel's first 2^m frames are a (0, m, 2)-net in its first two dimensions: every
    /// elementary interval of area 2^-m holds exactly one point. Scrambling and the shuffle
    /// keep Sobol's property; a broken direction table or scramble does not.
    #[test]
    fn sobol_owen_pixels_are_nets_in_time() {
        for (x, y, seed) in [(0, 0, 0), (12, -3, 99), (i32::MAX, 7, 1)] {
            for m in [4u32, 6, 8] {
                let pts: Vec<[f32; 4]> = (0..1u32 << m)
                    .map(|f| sobol_owen::<4>(x, y, f, seed))
                    .collect();
                {
                    let (i, j) = (0, 1);
                    for xbits in 0..=m {
                        let ybits = m - xbits;
                        let mut seen = std::vec![false; 1 << m];
                        for p in &pts {
                            let cx = (p[i] * (1u32 << xbits) as f32) as usize;
                            let cy = (p[j] * (1u32 << ybits) as f32) as usize;
                            let c = (cx << ybits) | cy;
                            assert!(!seen[c], "({x}, {y}) m {m} dims ({i}, {j}) {xbits}x{ybits}");
                            seen[c] = true;
                        }
                    }
                }
            }
        }
        // Different pixels are differently scrambled, and the prefix property holds across D.
        assert_ne!(sobol_owen::<2>(0, 0, 5, 1), sobol_owen::<2>(1, 0, 5, 1));
        assert_eq!(sobol_owen::<2>(4, 4, 9, 3), {
            let v = sobol_owen::<4>(4, 4, 9, 3);
            [v[0], v[1]]
        });
    }

    /// The direction numbers against Sobol's first points in index order (not Gray-code order),
    /// worked by hand from the recurrence: dimension 1 has `v = ½, ¾, ⅝`, dimension 2 `½, ¾, ⅜`.
    #[test]
    fn sobol_first_points() {
        let unit = |v: u32| v as f64 / 4_294_967_296.0;
        let d0: Vec<f64> = (0..8).map(|n| unit(sobol(n, 0))).collect();
        assert_eq!(d0, [0.0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875]);
        let d1: Vec<f64> = (0..8).map(|n| unit(sobol(n, 1))).collect();
        assert_eq!(d1, [0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875]);
        let d2: Vec<f64> = (0..5).map(|n| unit(sobol(n, 2))).collect();
        assert_eq!(d2, [0.0, 0.5, 0.75, 0.25, 0.375]);
    }
}
