//! The building blocks of Fajardo & Pharr §2.1: one-sample estimators of a linear
//! interpolation (eq. 2), a bilinear one with a single remapped ξ (eq. 4), and Russian
//! roulette (eq. 5).

/// The largest `f32` below 1: ξ = 1 is treated as this.
pub const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

/// Clamps ξ into `[0, 1)`: 1 (and above) become [`ONE_BELOW`], negatives and NaN become 0.
#[inline(always)]
pub fn sanitize_xi(xi: f32) -> f32 {
    if xi >= 0.0 { xi.min(ONE_BELOW) } else { 0.0 }
}

/// Chooses the "upper" branch with probability `t` and remaps ξ to a fresh uniform number in
/// `[0, 1)` for the next decision ([SWZ96], as in Algorithm 1). `t` is clamped to `[0, 1]`. With
/// `t = 0` the upper branch is never taken and with `t = 1` always (ξ < 1), so neither remap
/// divides by zero.
#[inline(always)]
pub fn pick(xi: &mut f32, t: f32) -> bool {
    let t = if t >= 0.0 { t.min(1.0) } else { 0.0 };
    if *xi < t {
        *xi = (*xi / t).min(ONE_BELOW);
        true
    } else {
        *xi = ((*xi - t) / (1.0 - t)).min(ONE_BELOW);
        false
    }
}

/// One-sample estimator of `lerp(f0, f1, t)` (eq. 2): evaluates only the chosen endpoint.
#[inline(always)]
pub fn lerp_estimate<T>(t: f32, xi: f32, f0: impl FnOnce() -> T, f1: impl FnOnce() -> T) -> T {
    let mut xi = sanitize_xi(xi);
    if pick(&mut xi, t) { f1() } else { f0() }
}

/// One-sample estimator of the bilinear interpolation of `f(i, j)`, `i, j ∈ {0, 1}`, with a
/// single ξ remapped between the two decisions (eq. 4).
#[inline(always)]
pub fn bilerp_estimate<T>(tx: f32, ty: f32, xi: f32, f: impl FnOnce(u32, u32) -> T) -> T {
    let mut xi = sanitize_xi(xi);
    let i = pick(&mut xi, tx) as u32;
    let j = pick(&mut xi, ty) as u32;
    f(i, j)
}

/// Russian roulette (eq. 5): with probability `p` returns the approximation `approx`, otherwise
/// `(f() − p·approx) / (1 − p)`, whose expectation is `f()`. `p` is clamped to `[0, 1)`.
#[inline(always)]
pub fn russian_roulette(p: f32, xi: f32, approx: f32, f: impl FnOnce() -> f32) -> f32 {
    let p = if p >= 0.0 { p.min(ONE_BELOW) } else { 0.0 };
    if sanitize_xi(xi) < p {
        approx
    } else {
        (f() - p * approx) / (1.0 - p)
    }
}
