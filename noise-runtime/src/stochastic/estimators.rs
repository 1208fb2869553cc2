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
/// `[0, 1)` for the next decision (Shirley et al. 1996, as in Algorithm 1). `t` is clamped to `[0, 1]`. With
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

/// The corner of a `D`-linear interpolation that Algorithm 1 selects with one ξ: for each axis
/// (first axis first), 1 if the upper side was chosen (probability `t[a]`), else 0. The same
/// selection as [`pick`] applied axis after axis, computed without a division, a branch or a
/// chain of dependent decisions, for the lattice estimators.
///
/// Remapping ξ after each decision (eq. 4) and keeping ξ fixed while narrowing the interval it
/// must fall in are the same selection: a decision with weight `t` splits the current interval
/// `[s, s + l)` at `s + l·t` into the upper side (first) and the lower one. All `2^D − 1` split
/// points depend only on the weights, and they are exactly the boundaries between the `2^D`
/// leaf intervals, which lie in corner order. So the corner's rank is the number of split
/// points at or below ξ: one compare each, all independent, summed — where the nested
/// decisions would be a chain of `D` dependent ones. A weight that rounds to 0 or 1 (the fade
/// of `t ≥ 0.9952` in f32) just gives a leaf of width 0, which ξ never falls in, and nothing is
/// ever divided. Rounding moves a corner's probability by a few ulps. `D` is at most 4.
#[inline(always)]
pub(crate) fn nested_corner<const D: usize>(xi: f32, t: [f32; D]) -> Corner {
    const { assert!(D >= 1 && D <= 4) };
    let xi = sanitize_xi(xi).to_bits() as i32;
    // The intervals of the current level, as (start, length); a level has 2^a of them.
    let mut start = [0.0f32; 8];
    let mut len = [1.0f32; 8];
    let mut rank = 0u32;
    for (a, &ta) in t.iter().enumerate() {
        let n = 1usize << a;
        for j in (0..n).rev() {
            let cut = len[j] * ta;
            let split = start[j] + cut;
            // Split points and ξ are non-negative floats below 2, so their bit patterns order
            // like their values: `split ≤ ξ` is the sign of the difference, as 0 or 1. An
            // integer, not a compare: LLVM lowers selects on a compare to branches on x86.
            rank += !(xi.wrapping_sub(split.to_bits() as i32) as u32) >> 31;
            if a + 1 < D {
                start[2 * j + 1] = split;
                len[2 * j + 1] = len[j] - cut;
                start[2 * j] = start[j];
                len[2 * j] = cut;
            }
        }
    }
    // Leaves are ranked upper side first, first axis most significant: the complement of the
    // rank has bit `D − 1 − a` set when axis `a` took its upper side. Shifted so that axis `a`
    // is bit `3 − a` whatever `D`.
    Corner((!rank & ((1 << D) - 1)) << (4 - D))
}

/// The corner [`nested_corner`] chose: bit `3 − a` is set when axis `a` took its upper side.
#[derive(Clone, Copy)]
pub(crate) struct Corner(u32);

/// `UNIT[k][a]` is bit `3 − a` of `k` as a float. Read by index, so that the side of a random
/// decision never becomes a float select, which LLVM lowers to a branch on x86 (mispredicted
/// on half of all random ξ).
static UNIT: [[f32; 4]; 16] = {
    let mut t = [[0.0f32; 4]; 16];
    let mut k = 0;
    while k < 16 {
        let mut a = 0;
        while a < 4 {
            t[k][a] = ((k >> (3 - a)) & 1) as f32;
            a += 1;
        }
        k += 1;
    }
    t
};

impl Corner {
    /// 1 if axis `a` took its upper side, else 0.
    #[inline(always)]
    pub(crate) fn int(self, a: usize) -> i32 {
        ((self.0 >> (3 - a)) & 1) as i32
    }

    /// The corner as a number in `0..16`: bit `3 − a` set when axis `a` took its upper side.
    #[inline(always)]
    pub(crate) fn index(self) -> usize {
        self.0 as usize & 15
    }

    /// 1.0 if axis `a` took its upper side, else 0.0, without a branch.
    #[inline(always)]
    pub(crate) fn float(self, a: usize) -> f32 {
        UNIT[self.0 as usize & 15][a]
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Corner `c` (bit `D − 1 − a` of `c` set = axis `a` upper) of a sweep of ξ over a fine grid.
    fn histogram<const D: usize>(t: [f32; D], steps: u32) -> [u32; 16] {
        let mut h = [0u32; 16];
        for k in 0..steps {
            let c = nested_corner((k as f32 + 0.5) / steps as f32, t);
            let mut idx = 0;
            for a in 0..D {
                idx = idx << 1 | c.int(a) as usize;
                assert_eq!(c.float(a), c.int(a) as f32);
            }
            h[idx] += 1;
        }
        h
    }

    #[test]
    fn nested_corner_picks_each_corner_with_its_interpolation_weight() {
        let steps = 1 << 16;
        for t in [[0.25f32, 0.5, 0.75], [0.1, 0.9, 0.6], [0.3, 0.0, 1.0]] {
            let h = histogram(t, steps);
            for (c, &count) in h.iter().enumerate().take(8) {
                let w: f32 = (0..3)
                    .map(|a| {
                        if c >> (2 - a) & 1 == 1 {
                            t[a]
                        } else {
                            1.0 - t[a]
                        }
                    })
                    .product();
                let freq = count as f32 / steps as f32;
                // A grid of 2^16 points resolves each leaf to within 2 steps.
                assert!(
                    (freq - w).abs() <= 2.0 / steps as f32,
                    "t {t:?} corner {c}: {freq} vs {w}"
                );
            }
        }
    }

    #[test]
    fn nested_corner_never_takes_a_side_of_weight_zero() {
        for xi in [0.0f32, 1e-30, 0.5, ONE_BELOW, 1.0, f32::NAN, -1.0, 2.0] {
            // Weights 0 and 1, as a fade weight rounded to exactly 0 or 1 in f32 gives them.
            for t in [[0.0f32, 1.0], [1.0, 0.0], [0.0, 0.0], [1.0, 1.0]] {
                let c = nested_corner(xi, t);
                for a in 0..2 {
                    assert_eq!(c.int(a), t[a] as i32, "ξ {xi}, t {t:?}, axis {a}");
                }
            }
        }
    }

    #[test]
    fn nested_corner_agrees_with_sequential_picks() {
        // Away from the split points (where rounding may differ by an ulp) the two forms are
        // the same selection.
        let t = [0.37f32, 0.61, 0.23, 0.83];
        for k in 0..997 {
            let xi = (k as f32 + 0.31) / 997.0;
            let c = nested_corner(xi, t);
            let mut x = xi;
            for (a, &ta) in t.iter().enumerate() {
                assert_eq!(pick(&mut x, ta) as i32, c.int(a), "ξ {xi}, axis {a}");
            }
        }
    }
}
