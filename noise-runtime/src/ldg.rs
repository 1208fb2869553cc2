//! Low-discrepancy grids: a value in `[0, 1)` per pixel, computed on the fly (no texture), with
//! neighbouring pixels well spread (blog post "plus-shaped and R2 low-discrepancy grids";
//! Jimenez 2014 for IGN). All are exact for any `i32` coordinate: products are taken in 64-bit
//! fixed point or integer arithmetic, never in `f32`, so there is no precision collapse at
//! `x = 10^7` or beyond.
//!
//! The `*_frame` variants animate a grid over time by adding `frame · (φ − 1)` (golden ratio) mod 1
//! (STBN §2), also in fixed point, so frame numbers up to `2^32` lose nothing.

use crate::sequence::{GOLDEN, R2_A1, R2_A2, to_unit};

#[inline(always)]
fn wide(v: i32) -> u64 {
    v as i64 as u64
}

/// R2 grid (Roberts): `frac(x/ρ + y/ρ²)`, ρ the plastic number, as a 32-bit fraction.
#[inline(always)]
fn r2_bits(x: i32, y: i32) -> u32 {
    (wide(x)
        .wrapping_mul(R2_A1)
        .wrapping_add(wide(y).wrapping_mul(R2_A2))
        >> 32) as u32
}

/// The R2 low-discrepancy grid: `frac(x/ρ + y/ρ²)` with ρ ≈ 1.3247 the plastic number.
#[must_use]
#[inline]
pub fn r2(x: i32, y: i32) -> f32 {
    to_unit(r2_bits(x, y))
}

/// Plus-shaped grid: `((x + 3y + 0.5) / 5) mod 1`: every plus-shaped neighbourhood (a pixel and
/// its four edge neighbours) holds each of ⅒, ³⁄₁₀, …, ⁹⁄₁₀ exactly once.
#[must_use]
#[inline]
pub fn plus(x: i32, y: i32) -> f32 {
    let k = (x as i64 + 3 * y as i64).rem_euclid(5);
    (k as f32 + 0.5) * 0.2
}

/// Interleaved gradient noise (Jimenez 2014): `frac(52.9829189 · frac(0.06711056·x + 0.00583715·y))`.
/// The inner fraction is exact in 64-bit fixed point; the outer product in `f64`.
#[must_use]
#[inline]
pub fn ign(x: i32, y: i32) -> f32 {
    const A: u64 = 0x112e_285c_6a8f_1506; // 0.06711056 · 2^64
    const B: u64 = 0x017e_8b20_5a12_9b0d; // 0.00583715 · 2^64
    let inner = wide(x)
        .wrapping_mul(A)
        .wrapping_add(wide(y).wrapping_mul(B));
    let f = (inner >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0);
    let v = crate::math::fract_f64(52.982_918_9 * f) as f32;
    if v >= 1.0 { 0.0 } else { v }
}

/// Bayer (ordered dither) matrix of size `N × N` (`N` a power of two from 2 to 65536), tiled:
/// `(index + 0.5) / N²`, always in `[0, 1)`. For `N ≥ 4096` an f32 cannot tell all `N²` ranks
/// apart, so neighbouring ranks may share a value.
#[must_use]
#[inline]
pub fn bayer<const N: u32>(x: i32, y: i32) -> f32 {
    const {
        assert!(
            N.is_power_of_two() && N >= 2 && N <= 65536,
            "Bayer size must be a power of two in 2..=65536"
        )
    };
    let levels = N.trailing_zeros();
    let (x, y) = (x as u32, y as u32);
    let mut index: u64 = 0;
    for k in 0..levels {
        let (xb, yb) = ((x >> k) & 1, (y >> k) & 1);
        index |= (((xb ^ yb) << 1 | yb) as u64) << (2 * (levels - 1 - k));
    }
    // In f32 the top ranks of N ≥ 4096 (N² ≥ 2^24) would round up to 1.0: stay below it.
    (((index as f64 + 0.5) / (N as f64 * N as f64)) as f32).min(ONE_BELOW)
}

/// The largest f32 below 1.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

/// Adds the golden-ratio offset of `frame` to a value in `[0, 1)`, mod 1.
#[inline]
fn animate(v: f32, frame: u32) -> f32 {
    let bits = (v as f64 * 4_294_967_296.0) as u64 as u32;
    let g = ((frame as u64).wrapping_mul(GOLDEN) >> 32) as u32;
    to_unit(bits.wrapping_add(g))
}

/// [`r2`] animated over frames by the golden ratio.
#[must_use]
#[inline]
pub fn r2_frame(x: i32, y: i32, frame: u32) -> f32 {
    let g = ((frame as u64).wrapping_mul(GOLDEN) >> 32) as u32;
    to_unit(r2_bits(x, y).wrapping_add(g))
}

/// [`plus`] animated over frames by the golden ratio.
#[must_use]
#[inline]
pub fn plus_frame(x: i32, y: i32, frame: u32) -> f32 {
    animate(plus(x, y), frame)
}

/// [`ign`] animated over frames by the golden ratio.
#[must_use]
#[inline]
pub fn ign_frame(x: i32, y: i32, frame: u32) -> f32 {
    animate(ign(x, y), frame)
}

/// [`bayer`] animated over frames by the golden ratio.
#[must_use]
#[inline]
pub fn bayer_frame<const N: u32>(x: i32, y: i32, frame: u32) -> f32 {
    animate(bayer::<N>(x, y), frame)
}
