//! The building blocks of Fajardo & Pharr §2.1: one-sample estimators of a linear
//! interpolation (eq. 2), a bilinear one with a single remapped ξ (eq. 4), and Russian
//! roulette (eq. 5).

/// The largest `f32` below 1: ξ = 1 is treated as this.
pub const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

/// Clamps ξ into `[0, 1)`: 1 (and above) become [`ONE_BELOW`], negatives and NaN become 0.
#[inline(always)]
pub fn sanitize_xi(xi: f32) -> f32 {
    // Branch-free: zero the bits of negative or NaN ξ (an integer test of the bit pattern:
    // non-negative floats up to +∞ are exactly the patterns ≤ 0x7f80_0000), then clamp.
    let keep = (xi.to_bits() <= 0x7f80_0000) as u32;
    f32::from_bits(xi.to_bits() & keep.wrapping_neg()).min(ONE_BELOW)
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

/// Branch-free [`pick`] for the hot paths: `(upper, remapped ξ)`, where `upper` says which
/// side was chosen as a value `0` or `1` whose bits LLVM cannot see (see [`Side`]). One
/// division, no branch on the random decision.
#[inline(always)]
pub(crate) fn choose(xi: f32, t: f32) -> (Side, f32) {
    // ξ and t are non-negative floats below 2, so their bit patterns order like their values
    // and differ by less than 2^31: the sign of the difference is the decision, as a mask
    // built by an arithmetic shift. No compare, so LLVM cannot turn the selects below into a
    // branch (which would mispredict half the time on random ξ).
    let m = ((xi.to_bits() as i32).wrapping_sub(t.to_bits() as i32) >> 31) as u32;
    let keep = |mask: u32, v: f32| f32::from_bits(v.to_bits() & mask);
    let num = xi - keep(!m, t);
    // Reciprocals of both sides do not depend on ξ, so their divisions run in parallel, off the
    // dependency chain; the remap itself is one multiply. A side of width 0 has reciprocal ∞
    // but is never chosen (its mask is zero).
    let (inv_up, inv_low) = (1.0 / t, 1.0 / (1.0 - t));
    let inv = f32::from_bits(keep(m, inv_up).to_bits() | keep(!m, inv_low).to_bits());
    (Side(m), (num * inv).min(ONE_BELOW))
}

/// Which side [`choose`] took, as an all-ones (upper) or all-zeros (lower) mask.
#[derive(Clone, Copy)]
pub(crate) struct Side(u32);

impl Side {
    /// 1 for the upper side, 0 for the lower.
    #[inline(always)]
    pub(crate) fn int(self) -> i32 {
        (self.0 & 1) as i32
    }

    /// 1.0 for the upper side, 0.0 for the lower, without a branch.
    #[inline(always)]
    pub(crate) fn float(self) -> f32 {
        (self.0 & 1) as f32
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
