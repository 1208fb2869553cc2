//! The R2 sequence (Roberts 2018) and the golden-ratio sequence in 64-bit fixed point.
//!
//! `frac(k · α)` is computed as the wrapping product of `k` with `α · 2^64` rounded: the rounding
//! error is below `k · 2^-65`, so for every `k < 2^31` the top 32 bits are exact to within one
//! unit (≤ 2^-32) — where an `f32` computation would have lost every bit of the fraction.

/// `2^64 / ρ`, where ρ ≈ 1.3247 is the plastic number (x³ = x + 1): R2's first axis.
pub const R2_A1: u64 = 0xc13f_a9a9_02a6_328f;
/// `2^64 / ρ²`: R2's second axis.
pub const R2_A2: u64 = 0x91e1_0da5_c79e_7b1c;
/// `2^64 · (φ − 1)`, φ the golden ratio.
pub const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// `frac(k · α)` as a 64-bit fixed-point fraction, for a fixed-point `alpha`.
#[must_use]
#[inline(always)]
pub const fn frac_mul(k: u64, alpha: u64) -> u64 {
    k.wrapping_mul(alpha)
}

/// The k-th point of R2 without its ½ seed, `(frac(k/ρ), frac(k/ρ²))`, as 32-bit fractions.
#[must_use]
#[inline(always)]
pub const fn r2_point(k: u32) -> (u32, u32) {
    (
        (frac_mul(k as u64, R2_A1) >> 32) as u32,
        (frac_mul(k as u64, R2_A2) >> 32) as u32,
    )
}

/// `frac(k · (φ − 1))` as a 32-bit fraction.
#[must_use]
#[inline(always)]
pub const fn golden(k: u32) -> u32 {
    (frac_mul(k as u64, GOLDEN) >> 32) as u32
}

/// A 32-bit fraction scaled to `0..n`: `floor(f · n / 2^32)`.
#[must_use]
#[inline(always)]
pub const fn scale(f: u32, n: u32) -> u32 {
    ((f as u64 * n as u64) >> 32) as u32
}

/// A 32-bit fraction as an `f32` in `[0, 1)` (the top 24 bits, exactly).
#[must_use]
#[inline(always)]
pub fn to_unit(f: u32) -> f32 {
    (f >> 8) as f32 * (1.0 / 16_777_216.0)
}
