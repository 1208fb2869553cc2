//! The little floating-point math the runtime needs, without `std` or `libm`: square root,
//! sine/cosine of an angle given in turns, and `fract` — all total on finite inputs.

/// `√x` for `x ≥ 0` (negative or NaN inputs give 0), to within an ulp of `f32`.
#[inline]
pub fn sqrt(x: f32) -> f32 {
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    if x == f32::INFINITY {
        return x;
    }
    let xd = x as f64;
    // Halve the exponent for a first guess within a few percent, then three Newton steps in f64
    // (each doubles the correct digits).
    let mut y = f64::from_bits((xd.to_bits() >> 1) + (1023u64 << 51));
    for _ in 0..4 {
        y = 0.5 * (y + xd / y);
    }
    y as f32
}

/// `(sin 2πu, cos 2πu)` for an angle in turns; any finite `u` (reduced exactly to `[-½, ½]`).
#[inline]
pub fn sincos_turns(u: f32) -> (f32, f32) {
    let u = u as f64;
    let r = u - round_f64(u);
    let x = r * core::f64::consts::TAU;
    let x2 = x * x;
    // Taylor series to x^17 / x^16: error below 1e-9 on [-π, π].
    let s = x
        * (1.0
            + x2 * (-1.0 / 6.0
                + x2 * (1.0 / 120.0
                    + x2 * (-1.0 / 5040.0
                        + x2 * (1.0 / 362_880.0
                            + x2 * (-1.0 / 39_916_800.0
                                + x2 * (1.0 / 6_227_020_800.0
                                    + x2 * (-1.0 / 1_307_674_368_000.0
                                        + x2 * (1.0 / 355_687_428_096_000.0)))))))));
    let c = 1.0
        + x2 * (-0.5
            + x2 * (1.0 / 24.0
                + x2 * (-1.0 / 720.0
                    + x2 * (1.0 / 40_320.0
                        + x2 * (-1.0 / 3_628_800.0
                            + x2 * (1.0 / 479_001_600.0
                                + x2 * (-1.0 / 87_178_291_200.0
                                    + x2 * (1.0 / 20_922_789_888_000.0))))))));
    (s.clamp(-1.0, 1.0) as f32, c.clamp(-1.0, 1.0) as f32)
}

/// Nearest integer to `v` (ties away from zero) for any finite `v`.
#[inline]
pub fn round_f64(v: f64) -> f64 {
    // At 2^52 and beyond every f64 is an integer; NaN and infinities pass through unchanged.
    if v.is_nan() || v.abs() >= 4_503_599_627_370_496.0 {
        return v;
    }
    let t = v as i64 as f64;
    let d = v - t;
    if d >= 0.5 {
        t + 1.0
    } else if d <= -0.5 {
        t - 1.0
    } else {
        t
    }
}

/// `v − ⌊v⌋` in `[0, 1)` for any finite `v`.
#[inline]
pub fn fract_f64(v: f64) -> f64 {
    if v.is_nan() || v.abs() >= 4_503_599_627_370_496.0 {
        return 0.0;
    }
    let t = v as i64 as f64;
    let f = v - t;
    let f = if f < 0.0 { f + 1.0 } else { f };
    if f >= 1.0 { 0.0 } else { f }
}
