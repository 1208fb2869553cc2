//! Deterministic floating-point functions: built from IEEE basic operations only (correctly
//! rounded everywhere), so the spec's filter taps and the generators' values are the same bits
//! on every platform; no libm call is used.

/// `e^x` from basic operations only: `2^k · e^r` with `|r| ≤ ln 2 / 2` and a Taylor series, so
/// the result is bit-identical everywhere (relative error below 1e-15).
pub fn exp(x: f64) -> f64 {
    if x < -745.0 {
        return 0.0;
    }
    if x > 709.0 {
        return f64::INFINITY;
    }
    const LN2: f64 = core::f64::consts::LN_2;
    let k = (x / LN2).round();
    let r = x - k * LN2;
    let mut term = 1.0;
    let mut sum = 1.0;
    for i in 1..=18 {
        term *= r / i as f64;
        sum += term;
    }
    let mut scale = 1.0;
    let (base, mut n) = if k >= 0.0 {
        (2.0, k as i32)
    } else {
        (0.5, -k as i32)
    };
    let mut b = base;
    while n > 0 {
        if n & 1 == 1 {
            scale *= b;
        }
        b *= b;
        n >>= 1;
    }
    sum * scale
}
