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
/// (first axis first), the upper side with probability `t[a]`. The same selection as [`pick`]
/// applied axis after axis, computed without a division or a branch, for the lattice
/// estimators.
///
/// Remapping ξ after each decision (eq. 4) and keeping ξ fixed while narrowing the interval it
/// must fall in are the same selection: a decision with weight `t` splits the current interval
/// `[s, s + l)` at `s + l·t` into the upper side (first) and the lower one. The interval is
/// kept as ξ's residue `r = ξ − s` and its length `l`, in fixed point with 23 fractional bits:
/// the upper side is taken when `r < c = ⌊l·t⌋`, then `l ← c`; otherwise `r ← r − c` and
/// `l ← l − c`. Each axis is an integer multiply, a shift, a compare and a few masked moves,
/// where the remap of eq. 4 divides by `t` or `1 − t`.
///
/// In integers the invariant `0 ≤ r < l` holds exactly, so a side of weight 0 — a fade weight
/// that rounds to exactly 0 or 1 in f32, as it does for `t ≥ 0.9952` — has length 0 and is
/// never taken, and there is no `0/0` to guard. Each weight is rounded to a multiple of 2^-23
/// and each cut floors, so a corner's probability is off by at most `D · 2^-23` (f32 rounding
/// in the remap is of the same order). `D` is at most 4.
#[cfg(test)]
pub(crate) fn nested_corner<const D: usize>(xi: f32, t: [f32; D]) -> Corner<D> {
    const { assert!(D >= 1 && D <= 4) };
    let mut n = Narrowing::new(xi);
    Corner(t.map(|ta| n.upper(ta)))
}

/// The interval `nested_corner` narrows, one decision at a time: ξ's residue `r` in it and
/// its length `l`, in fixed point. For estimators that interleave their own work with the
/// decisions (the 3D Perlin estimator hashes as it decides).
#[derive(Clone, Copy)]
pub(crate) struct Narrowing {
    r: u64,
    l: u64,
}

impl Narrowing {
    /// The whole unit interval, with ξ sanitised ([`sanitize_xi`]) and below the fixed-point 1.
    #[inline(always)]
    pub(crate) fn new(xi: f32) -> Self {
        const ONE: u64 = 1 << FIXED_BITS;
        Narrowing {
            r: fixed(sanitize_xi(xi)).min(ONE - 1),
            l: ONE,
        }
    }

    /// [`Narrowing::new`] for a ξ known to lie in `[0, 1)` (a remapped one), the same state
    /// without the sanitising steps, which would change nothing.
    #[inline(always)]
    pub(crate) fn new_unit(xi: f32) -> Self {
        const ONE: u64 = 1 << FIXED_BITS;
        debug_assert!((0.0..1.0).contains(&xi) && xi.to_bits() >> 31 == 0);
        Narrowing {
            r: fixed(xi).min(ONE - 1),
            l: ONE,
        }
    }

    /// One decision with weight `t ∈ [0, 1]`: all ones when the upper side was taken. (The
    /// kernels make the weights' fixed points four at a time and call
    /// [`upper_fixed`](Self::upper_fixed); this is the tests' reference form.)
    #[cfg(test)]
    pub(crate) fn upper(&mut self, t: f32) -> u32 {
        self.upper_fixed(fixed(t))
    }

    /// `Narrowing::upper` with the weight already in fixed point (`fixed(t)`, as
    /// [`lanes::fixed`](crate::lanes::fixed) makes it for four weights at once).
    #[inline(always)]
    pub(crate) fn upper_fixed(&mut self, t: u64) -> u32 {
        // Wrapping: for weights in [0, 1] nothing comes near 2^64; for others it must not panic.
        let cut = self.l.wrapping_mul(t) >> FIXED_BITS;
        // All ones when `r < cut` (both below 2^24, so the difference's sign says it). The sign
        // of a subtraction rather than a compare: LLVM turns selects on a compare into branches
        // on x86, mispredicted on half of all random ξ.
        let up = (self.r.wrapping_sub(cut) as i64 >> 63) as u64;
        self.r -= cut & !up;
        let rest = self.l.wrapping_sub(cut);
        self.l = rest ^ ((cut ^ rest) & up);
        up as u32
    }
}

/// The two decisions of a fresh [`Narrowing`] (the corner of a 2D cell), exactly as two
/// `Narrowing::upper` calls make them, but with the second decision's two candidate cuts
/// computed before the first decision is known: the interval of the second decision is one of
/// two, both products of the weights alone. That takes a multiply and a handful of dependent
/// moves off the chain from the weights to the corner, where the 2D estimator spends its time
/// waiting (the 2D estimator measured faster with it). In 3D the same for the third decision,
/// whose interval is one of four, measured slower than the sequential form: more work than the
/// chain saves, on an Intel and an AMD Zen 5 core alike. The chain still costs the 3D estimator
/// most of its lead over the deterministic form: an experiment that replaced the three decisions
/// by independent compares (wrong, but with the same hashing and dot product) ran far faster,
/// so no form of the decisions reaches the paper's speed-up there (`noisebake report
/// stochastic` measures both forms). Returns the masks of the two decisions (all ones: upper
/// side).
#[inline(always)]
pub(crate) fn fresh_corner2(xi: f32, t: [f32; 2]) -> [u32; 2] {
    const ONE: u64 = 1 << FIXED_BITS;
    let r = Narrowing::new(xi).r;
    let sign = |a: u64, b: u64| (a.wrapping_sub(b) as i64 >> 63) as u64;
    let sel = |m: u64, a: u64, b: u64| b ^ ((a ^ b) & m);
    let cut = |l: u64, t: u64| l.wrapping_mul(t) >> FIXED_BITS;
    // First decision: the interval is [0, 1), its cut the first weight itself.
    let (w0, w1) = (fixed(t[0]), fixed(t[1]));
    let up0 = sign(r, w0);
    // Second: on the upper side [0, w0), on the lower [w0, 1) with residue r − w0.
    let c_up = cut(w0, w1);
    let c_dn = cut(ONE.wrapping_sub(w0), w1);
    let up1 = sign(sel(up0, r, r.wrapping_sub(w0)), sel(up0, c_up, c_dn));
    [up0 as u32, up1 as u32]
}

/// Fractional bits of `nested_corner`'s fixed point.
const FIXED_BITS: u32 = 23;

/// `t · 2^23` rounded to nearest, for `t ∈ [0, 1]`: the mantissa of `1 + t`, read from its
/// bits, where the ulp is 2^-23 — one add, no saturating conversion. Not clamped (an integer
/// clamp here became branches on x86): the lattice weights are fades of offsets in `[0, 1]`,
/// which lie in `[0, 1]` up to an ulp. A weight a little above 1 gives a cut a little above
/// `l`, so the upper side is always taken, as for 1; nothing wraps into a panic.
#[inline(always)]
pub(crate) fn fixed(t: f32) -> u64 {
    (t + 1.0).to_bits().wrapping_sub(0x3f80_0000) as u64
}

/// The corner [`nested_corner`] chose: per axis, all ones when it took its upper side, else 0.
#[cfg(test)]
#[derive(Clone, Copy)]
pub(crate) struct Corner<const D: usize>([u32; D]);

/// `UNIT[k][a]` is bit `a` of `k` as a float. Read by index, so that the side of a random
/// decision never becomes a float select, which LLVM lowers to a branch on x86 (mispredicted
/// on half of all random ξ).
static UNIT: [[f32; 4]; 16] = {
    let mut t = [[0.0f32; 4]; 16];
    let mut k = 0;
    while k < 16 {
        let mut a = 0;
        while a < 4 {
            t[k][a] = ((k >> a) & 1) as f32;
            a += 1;
        }
        k += 1;
    }
    t
};

#[cfg(test)]
impl<const D: usize> Corner<D> {
    /// 1 if axis `a` took its upper side, else 0.
    #[cfg(test)]
    pub(crate) fn int(self, a: usize) -> i32 {
        (self.0[a] & 1) as i32
    }

    /// Per axis all ones if it took its upper side, else 0.
    #[inline(always)]
    pub(crate) fn masks(self) -> [u32; D] {
        self.0
    }

    /// The corner's offsets per axis as floats: `[1.0 or 0.0; 4]` (lanes past `D` are 0).
    #[inline(always)]
    pub(crate) fn floats(self) -> [f32; 4] {
        let mut k = 0;
        for (a, m) in self.0.iter().enumerate() {
            k |= (m & 1) << a;
        }
        unit_corner(k)
    }
}

/// Corner `k` (bit `a` set when axis `a` took its upper side) as per-axis offsets
/// `[1.0 or 0.0; 4]`; `k < 16`.
#[inline(always)]
pub(crate) fn unit_corner(k: u32) -> [f32; 4] {
    UNIT[k as usize & 15]
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
    roulette_in_range(p, sanitize_xi(xi), approx, f)
}

/// [`russian_roulette`] for a ξ already in `[0, 1)` (an estimator's remapped ξ): the same
/// result without clamping ξ again.
#[inline(always)]
pub(crate) fn roulette_in_range(p: f32, xi: f32, approx: f32, f: impl FnOnce() -> f32) -> f32 {
    debug_assert!((0.0..1.0).contains(&xi), "ξ = {xi}");
    let p = if p >= 0.0 { p.min(ONE_BELOW) } else { 0.0 };
    if xi < p {
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
                assert_eq!(c.floats()[a], c.int(a) as f32);
                assert_eq!(
                    c.0[a],
                    c.int(a).wrapping_neg() as u32,
                    "a mask, all ones or 0"
                );
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
    fn narrowing_decides_weights_at_and_past_the_ends_alike_at_every_depth() {
        // Four decisions deep, after any mix of sides: a weight of 0 (or −0) never takes the
        // upper side and a weight of 1 — or an ulp or a few past it, as a fade's rounding could
        // give — always does, for ξ at both ends of [0, 1] and beyond. Mixed with ordinary
        // weights, so that the interval has been narrowed unevenly before the extreme one.
        let above = [
            1.0f32,
            f32::from_bits(0x3f80_0001),
            f32::from_bits(0x3f80_0004),
        ];
        let xis = [
            0.0f32,
            1e-30,
            1e-7,
            0.3,
            0.5,
            0.999_999,
            ONE_BELOW,
            1.0,
            2.0,
            f32::NAN,
        ];
        for &xi in &xis {
            for mix in 0..81u32 {
                // Each of the four weights: 0, 0.5, or something ≥ 1 (cycling the three kinds).
                let t: [f32; 4] = core::array::from_fn(|a| match (mix / 3u32.pow(a as u32)) % 3 {
                    0 => [0.0, -0.0][a % 2],
                    1 => 0.5,
                    _ => above[a % 3],
                });
                let mut n = Narrowing::new(xi);
                for (a, &ta) in t.iter().enumerate() {
                    let up = n.upper(ta);
                    assert!(up == 0 || up == u32::MAX, "a mask: {up:#x}");
                    if ta <= 0.0 {
                        assert_eq!(up, 0, "ξ {xi}, t {t:?}, axis {a}");
                    } else if ta >= 1.0 {
                        assert_eq!(up, u32::MAX, "ξ {xi}, t {t:?}, axis {a}");
                    }
                    assert!(n.r < n.l, "ξ {xi}, t {t:?}, axis {a}: r {} l {}", n.r, n.l);
                }
            }
        }
    }

    #[test]
    fn fresh_corner2_is_the_sequential_narrowing() {
        // Random weights and ξ, and every mix of the weights that are hard for the cuts (0, a
        // few ulps, ½, just below 1, 1, a few ulps past 1) with ξ at and near the ends.
        let mut next = super::super::uniforms(0x2545_f491_4f6c_dd1du64);
        let hard = [
            0.0f32,
            1e-7,
            0.5,
            f32::from_bits(0x3f7f_ffff),
            1.0,
            f32::from_bits(0x3f80_0002),
        ];
        let xis = [
            0.0f32,
            1e-7,
            0.25,
            0.5,
            0.75,
            f32::from_bits(0x3f7f_fffe),
            ONE_BELOW,
            1.0,
        ];
        let check = |xi: f32, t: [f32; 2]| {
            let mut n = Narrowing::new(xi);
            let seq = t.map(|ta| n.upper(ta));
            assert_eq!(fresh_corner2(xi, t), seq, "ξ {xi:e}, t {t:?}");
        };
        for _ in 0..200_000 {
            check(next(), [next(), next()]);
        }
        for &xi in &xis {
            for &a in &hard {
                for &b in &hard {
                    check(xi, [a, b]);
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
