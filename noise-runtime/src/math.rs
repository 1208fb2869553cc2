//! The little floating-point math the runtime needs, without `std` or `libm`: square root,
//! sine/cosine of an angle given in turns, and `fract` — all total on finite inputs.

use crate::lanes::{F4, I4};

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

/// Splits `x` into its lattice cell and the offset in it: `(⌊x⌋, x − ⌊x⌋)` with the offset in
/// `[0, 1)`. Total: beyond `±2^31` the cell saturates, and a NaN or infinite input gives
/// `(cell, 0)`, so noise built on it never sees a NaN.
#[inline(always)]
pub fn split(x: f32) -> (i32, f32) {
    let t = x as i32; // saturating, NaN → 0
    let ft = t as f32;
    // Branch-free floor: truncation rounds negatives up, so step down by one when it did
    // (the sign bit of x − ⌊x⌋_trunc). Integer bit tests rather than float compares: LLVM turns
    // float selects into branches on x86, which mispredict on random input.
    // Strictly negative and not NaN: the bit patterns 0x8000_0001 ..= 0xff80_0000 (−0 and every
    // NaN, whatever its sign bit, excluded). A NaN's sign is not specified by Rust, so the test
    // must not depend on it.
    let d = (x - ft).to_bits();
    let down = (d.wrapping_sub(0x8000_0001) < 0x7f80_0000) as i32;
    let cell = t.saturating_sub(down);
    // The offset from the integer cell, not from `ft − down`: a float select there would become
    // a branch, mispredicted on half of all random coordinates. Exact below 2^24 (the cell is a
    // float); above, x is an integer and equals its cell; a saturated cell gives an offset
    // outside [0, 1), caught below.
    let f = x - cell as f32;
    // A negative x within 2^-25 of an integer has an offset that rounds up to exactly 1: the
    // point is on the next lattice plane, so step the cell up (its offset becomes 0 below).
    let cell = cell.wrapping_add((f.to_bits() == 0x3f80_0000) as i32);
    // Keep f only when it is a valid offset in [0, 1) (NaN or infinite inputs give 0): for
    // non-negative floats the bit patterns order like the values.
    let keep = (f.to_bits() < 0x3f80_0000) as u32;
    (cell, f32::from_bits(f.to_bits() & keep.wrapping_neg()))
}

/// `e^x` for `x ≤ 0` in f32 (relative error below 2e-7); `x > 0` is clamped to 0 (gives 1),
/// very negative or NaN `x` gives 0.
#[inline(always)]
pub fn exp_neg(x: f32) -> f32 {
    if x.is_nan() || x <= -87.0 {
        return 0.0;
    }
    let x = if x > 0.0 { 0.0 } else { x };
    // e^x = 2^(x·log2 e) = 2^k · 2^r, r ∈ [-½, ½]; 2^r by its Taylor series in r·ln 2.
    let y = x * core::f32::consts::LOG2_E;
    let k = y.round_ties_even_noneg();
    let r = (y - k) * core::f32::consts::LN_2;
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0))))));
    let bits = ((k as i32 + 127) as u32) << 23;
    p * f32::from_bits(bits)
}

/// `2^y` for `y ∈ [−125, 0]` (the caller clamps), in f32 with relative error below 3e-7:
/// `2^k · 2^r` for the nearest integer `k` and `r ∈ [−½, ½]`, `2^r` by the lane layer's
/// `EXP2_POLY` in Estrin's scheme, whose chain of dependent operations is 6 long instead of
/// Horner's 10. For `k ≥ −125` the result is a normal float (no slow subnormal arithmetic).
/// The scalar statement of the lane kernels' `lanes::exp2_neg`, which the tests compare with
/// it.
#[cfg(test)]
pub(crate) fn exp2_neg(y: f32) -> f32 {
    debug_assert!((-125.0..=0.0).contains(&y), "y = {y}");
    let k = y.round_ties_even_noneg();
    let r = y - k;
    let c = crate::lanes::EXP2_POLY;
    let r2 = r * r;
    let p = (c[0] + c[1] * r) + r2 * ((c[2] + c[3] * r) + r2 * (c[4] + c[5] * r));
    p * f32::from_bits(((k as i32 + 127) as u32) << 23)
}

/// Rounding used by [`exp_neg`] without `std` (`y ≤ 0`, |y| < 2^22).
trait RoundNoStd {
    fn round_ties_even_noneg(self) -> f32;
}

impl RoundNoStd for f32 {
    #[inline(always)]
    fn round_ties_even_noneg(self) -> f32 {
        // Adding and subtracting 1.5·2^23 rounds to an integer in the current mode (nearest).
        const MAGIC: f32 = 12_582_912.0;
        (self + MAGIC) - MAGIC
    }
}

/// `ln x` for `x > 0` in f32, within 2e-7 of the exact value plus half an ulp of the result;
/// `x ≤ 0` or NaN gives `-87.0` (≈ ln of the smallest normal), infinity gives `88.7`.
///
/// `x = m · 2^e` with `m ∈ [√½, √2)` by integer steps on the bits, then `ln m = u · P(u)` for
/// `u = m − 1`, `P` a degree-7 Chebyshev fit to `ln(1 + u)/u` evaluated in Estrin's scheme:
/// no division and no select, so a chain of 8 dependent operations after the bits (smooth
/// Voronoi ends in one, and the atanh series with its division was a large share of its time).
#[inline(always)]
pub fn ln(x: f32) -> f32 {
    if x.is_nan() || x < f32::MIN_POSITIVE {
        return -87.0;
    }
    if x == f32::INFINITY {
        return 88.7;
    }
    // Subtracting the bits of √½ moves the exponent's steps to the powers of two times √½.
    const SQRT_HALF: u32 = 0x3f35_04f3;
    let t = x.to_bits().wrapping_sub(SQRT_HALF);
    let e = (t as i32) >> 23;
    let m = f32::from_bits((t & 0x007f_ffff) + SQRT_HALF);
    let u = m - 1.0; // exact (Sterbenz)
    let c = LN_POLY;
    let (u2, p01, p23) = (u * u, c[0] + c[1] * u, c[2] + c[3] * u);
    let (p45, p67) = (c[4] + c[5] * u, c[6] + c[7] * u);
    let p = (p01 + u2 * p23) + (u2 * u2) * (p45 + u2 * p67);
    // ln 2 in two parts, the first with 17 significant bits so that e times it is exact: the
    // sum rounds once.
    const LN2_HI: f32 = f32::from_bits(0x3f31_7180);
    const LN2_LO: f32 = f32::from_bits(0x3717_f7d1);
    let e = e as f32;
    (u * p + e * LN2_LO) + e * LN2_HI
}

/// [`ln`]'s polynomial: the degree-7 Chebyshev fit to `ln(1 + u)/u` on `[√½ − 1, √2 − 1]`
/// (error below 7e-8), constant term first.
const LN_POLY: [f32; 8] = [
    0.999_999_97,
    -0.500_003_75,
    0.333_346_06,
    -0.249_689_07,
    0.199_133_48,
    -0.172_782_06,
    0.161_262_48,
    -0.098_953_51,
];

/// `cos 2πu` for an angle in turns, f32, any finite `u` (error below 1e-6).
#[inline(always)]
pub fn cos_turns(u: f32) -> f32 {
    let (_, f) = split(u + 0.5);
    // f − ½ ∈ [−½, ½) turns, and cos 2πr = sin 2π(¼ − |r|) with ¼ − |r| ∈ [−¼, ¼]: an odd
    // polynomial over the whole range, so no fold into a quadrant and no sign select (which
    // LLVM would branch on, mispredicting half the time on random angles).
    let x = (0.25 - (f - 0.5).abs()) * core::f32::consts::TAU;
    let x2 = x * x;
    // Taylor series of sin to x^13 (the next term is below 6e-8 for |x| ≤ π/2).
    x * (1.0
        + x2 * (-1.0 / 6.0
            + x2 * (1.0 / 120.0
                + x2 * (-1.0 / 5040.0
                    + x2 * (1.0 / 362_880.0 + x2 * (-1.0 / 39_916_800.0 + x2 / 6_227_020_800.0))))))
}

/// `√x` in f32, correctly rounded (the IEEE square root), for the hot paths (Worley distances,
/// kernels); `x ≤ 0` or NaN gives 0, `+∞` gives `+∞`. The lane layer's root: on x86_64 the
/// processor's `sqrtss`, one instruction where a Newton-refined guess is a chain of thirteen
/// (smooth Voronoi, which takes a root per cell, measured markedly faster with it); elsewhere the portable backend's Newton-refined root
/// (`lanes::scalar::sqrt1`, compared bit for bit in the tests below). Both round correctly, so
/// every target gets the same bits.
#[inline(always)]
pub fn sqrt(x: f32) -> f32 {
    crate::lanes::sqrt1(x)
}

/// [`sqrt`] without a square-root instruction, as targets whose `core` offers none compute it
/// (`f32::sqrt` needs `std`): the portable lane backend's root, for the tests' comparisons.
#[cfg(test)]
fn sqrt_soft(x: f32) -> f32 {
    crate::lanes::scalar::sqrt1(x)
}

/// `⌊v⌋` for finite `v` (NaN passes through; |v| ≥ 2^52 is already integral).
#[inline]
pub fn floor_f64(v: f64) -> f64 {
    if v.is_nan() || v.abs() >= 4_503_599_627_370_496.0 {
        return v;
    }
    let t = v as i64 as f64;
    if t > v { t - 1.0 } else { t }
}

/// `⌈v⌉` for finite `v`.
#[inline]
pub fn ceil_f64(v: f64) -> f64 {
    -floor_f64(-v)
}

/// `√x` in f64 (Newton from a bit-level guess; correctly rounded to within an ulp); `x ≤ 0` or
/// NaN gives 0.
#[inline]
pub fn sqrt_f64(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    if x == f64::INFINITY {
        return x;
    }
    let mut y = f64::from_bits((x.to_bits() >> 1) + (1023u64 << 51));
    for _ in 0..6 {
        y = 0.5 * (y + x / y);
    }
    y
}

/// [`split`] for callers that have checked `|x| < 2^22` with [`in_split_range`], by a shorter
/// chain of dependent instructions. The same cell and offset, except that the offset may be
/// exactly 1 (for a negative `x` within 2^-25 of an integer, where `split` steps to the next
/// cell with offset 0): the same point, which interpolating callers treat alike.
///
/// Adding and subtracting 1.5·2^23 rounds `x` to the nearest integer `r` (exact below 2^22);
/// `x − r ∈ [−½, ½]` is exact, and when it is negative the cell is `r − 1` and the offset
/// `(x − r) + 1`, which rounds the same real number as `x − (r − 1)`. About 19 cycles from `x`
/// to the offset where truncating, converting back and subtracting took about 28; the
/// estimators, which wait on this chain, gain the most.
///
/// The integer `r` is read from the bits of `x + 1.5·2^23`, which lies in `(2^23, 2^24)` where
/// the ulp is 1: its bit pattern minus that of 1.5·2^23 is `r` exactly. One integer subtraction
/// instead of a float-to-integer conversion, whose saturating semantics add two compares and
/// two conditional moves per axis.
#[inline(always)]
pub(crate) fn split_in_range(x: f32) -> (i32, f32) {
    // Written once, in the portable lane backend, whose lanes run it.
    let (c, f) = crate::lanes::scalar::split1(x);
    (c as i32, f)
}

/// `on_cells!(v, |cell, f| body)`: `body` with the cells and offsets of the four lanes of
/// `v`, split as [`split_in_range`] splits them when every lane is in its range (the common
/// case, on lanes) and as [`split`] does otherwise (huge, infinite or NaN coordinates; one
/// predictable branch). How every lane kernel meets its point.
///
/// A macro that writes `body` into both branches, rather than a function returning the split
/// or taking the kernel as a closure: a returned split merges the two paths into one value,
/// which LLVM passed through the stack (Worley F1 measured much slower), and a closure that
/// the cold path also calls keeps its captures (seed, ξ) in memory on the hot path too (the
/// 3D Perlin estimator measured slower).
macro_rules! on_cells {
    ($v:expr, |$cell:ident, $f:ident| $body:expr) => {{
        let v: $crate::lanes::F4 = $v;
        if $crate::lanes::in_split_range(v) {
            let ($cell, $f) = $crate::lanes::split_in_range(v);
            $body
        } else {
            let ($cell, $f) = $crate::math::split_lanes_cold(v);
            $body
        }
    }};
}
pub(crate) use on_cells;

/// [`split_lanes`] kept out of line, for the cold branch of [`on_cells!`].
#[cold]
#[inline(never)]
pub(crate) fn split_lanes_cold(v: F4) -> (I4, F4) {
    split_lanes(v)
}

/// [`split`] per lane.
#[inline(always)]
pub(crate) fn split_lanes(v: F4) -> (I4, F4) {
    let s = [v.x(), v.y(), v.z(), v.w()].map(split);
    (
        I4::new(s.map(|(c, _)| c as u32)),
        F4::from4(s.map(|(_, f)| f)),
    )
}

/// Whether every coordinate is finite and below 2^22 in magnitude (then [`split_in_range`]
/// applies; larger coordinates take [`split`]).
#[inline(always)]
pub(crate) fn in_split_range<const N: usize>(p: [f32; N]) -> bool {
    // `|v| < 2^22` is `abs_bits < 0x4a80_0000` (NaN and infinity are above), which is the sign
    // bit of `abs_bits + (2^31 − 0x4a80_0000)` being clear: one add per coordinate, their OR,
    // and a single test, where compares chained by `&&` were a branch each.
    let mut any = 0u32;
    for v in p {
        any |= (v.to_bits() & 0x7fff_ffff) + (0x8000_0000 - 0x4a80_0000);
    }
    any >> 31 == 0
}

/// Perlin's quintic fade `6t⁵ − 15t⁴ + 10t³` (Perlin 2002): C² interpolation weights.
#[inline(always)]
pub fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// The derivative of [`fade`], `30 t² (t − 1)²`.
#[inline(always)]
pub fn dfade(t: f32) -> f32 {
    let s = t * (t - 1.0);
    30.0 * s * s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// NaN handling does not read the NaN's sign bit (Rust leaves it unspecified, and Miri
    /// picks it at random): every NaN splits the same way, as does every infinity of a sign.
    #[test]
    fn split_of_nan_ignores_its_sign() {
        let nans = [
            0x7fc0_0000u32,
            0xffc0_0000,
            0x7f80_0001,
            0xff80_0001,
            0x7fff_ffff,
            0xffff_ffff,
        ];
        for bits in nans {
            assert_eq!(split(f32::from_bits(bits)), (0, 0.0), "{bits:#x}");
        }
        assert_eq!(split(-0.0), (0, 0.0));
        assert_eq!(split(-0.25), (-1, 0.75));
        assert_eq!(split(f32::NEG_INFINITY).1, 0.0);
        // Within 2^-25 below an integer the offset rounds to 1: the point is on the plane.
        assert_eq!(split(-1e-45), (0, 0.0));
    }

    #[test]
    fn cos_turns_is_within_1e6_of_cos() {
        // A sweep over two turns, through the quadrant boundaries where a fold would switch
        // sides. (Farther out, rounding `u + ½` to f32 adds up to 2π·ulp(u) of angle.)
        for k in -40_000..=40_000 {
            let u = k as f32 / 40_000.0;
            let exact = (u as f64 * core::f64::consts::TAU).cos();
            // In f64, the reduction of u is exact, so compare with cos of the same f32 angle.
            let got = cos_turns(u) as f64;
            assert!((got - exact).abs() < 1e-6, "u {u}: {got} vs {exact}");
        }
        for u in [0.25f32, 0.5, 0.75, 1e6 + 0.25, -1e6 - 0.5] {
            let exact = (u as f64 * core::f64::consts::TAU).cos();
            assert!((cos_turns(u) as f64 - exact).abs() < 1e-6, "u {u}");
        }
        // Beyond 2^31 the reduction saturates: any value, but a finite one in [−1, 1].
        for u in [1e30f32, -3e38, f32::MAX] {
            assert!(cos_turns(u).abs() <= 1.0, "u {u}");
        }
    }

    /// The reference the fast split must agree with: truncate, step down when that rounded up,
    /// subtract the cell.
    fn split_by_truncation(x: f32) -> (i32, f32) {
        let t = x as i32;
        let cell = t - (x < t as f32) as i32;
        (cell, x - cell as f32)
    }

    #[test]
    fn split_in_range_agrees_with_split() {
        let check = |x: f32| {
            assert!(in_split_range([x]), "{x}");
            let (c, f) = split_in_range(x);
            // Equal values (the truncating form keeps the sign of −0, `split` clears it).
            let (rc, rf) = split_by_truncation(x);
            assert!(
                c == rc && f == rf,
                "x {x:e}: ({c}, {f:e}) vs ({rc}, {rf:e})"
            );
            let (gc, gf) = split(x);
            if f == 1.0 {
                assert_eq!((c + 1, 0), (gc, gf.to_bits()), "split, x {x:e}");
            } else {
                assert_eq!((c, f.to_bits()), (gc, gf.to_bits()), "split, x {x:e}");
            }
        };
        // Every float around the integers and half-integers up to 2^22 (ties of the rounding
        // step, both signs), zero of both signs, the smallest magnitudes, and the range's edge.
        for x in [
            0.0f32,
            -0.0,
            1e-45,
            -1e-45,
            1e-10,
            -1e-10,
            4_194_303.5,
            -4_194_303.5,
        ] {
            check(x);
        }
        for k in 0..=22 {
            for base in [
                (1u32 << k) as f32,
                (1u32 << k) as f32 + 0.5,
                (1u32 << k) as f32 - 0.5,
            ] {
                for v in [base, -base] {
                    let (mut a, mut b) = (v, v);
                    for _ in 0..4 {
                        for x in [a, b] {
                            if x.abs() < 4_194_304.0 {
                                check(x);
                            }
                        }
                        a = f32::from_bits(a.to_bits() + 1);
                        b = f32::from_bits(b.to_bits().wrapping_sub(1));
                    }
                }
            }
        }
        // And a million random coordinates at every scale below 2^22.
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..1_000_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let mag = f32::from_bits(0x3000_0000 + ((s >> 8) as u32 % 0x1600_0000));
            check(if s & 1 == 0 { mag } else { -mag });
        }
        // A coordinate just below an integer is on that integer's lattice plane, not a whole
        // cell away.
        for (x, cell) in [
            (-1e-30f32, 0),
            (-1e-45, 0),
            (-1e-8, 0),
            (1.0 - 1e-8, 1),
            (-3.0 - 1e-7, -3),
        ] {
            assert_eq!(split(x), (cell, 0.0), "x {x:e}");
        }
        // Outside the range the callers take `split`: the bound itself, anything larger,
        // non-finite values of either sign, in any position of the point.
        for out in [
            4_194_304.0f32,
            -4_194_304.0,
            4_194_304.5,
            1e30,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
        ] {
            assert!(!in_split_range([out]), "{out}");
            assert!(!in_split_range([0.5, out, -2.0]), "{out}");
            assert!(!in_split_range([1e-30, 3.0, out]), "{out}");
        }
        // Inside: up to the largest float below 2^22, both signs, zeros and subnormals.
        let below = f32::from_bits(4_194_304.0f32.to_bits() - 1);
        assert!(in_split_range([below, -below, 0.0]));
        assert!(in_split_range([-0.0f32, 1e-45, -1e-45]));
    }

    /// Floats to test a square root on: every 61st positive finite float (every exponent, the
    /// subnormals included, with mantissas spread over it) and the 64 floats either side of
    /// every power of two, where the ulp of the root halves.
    fn roots_to_check(mut check: impl FnMut(f32)) {
        for bits in (1..0x7f80_0000u32).step_by(61) {
            check(f32::from_bits(bits));
        }
        for e in 1..255u32 {
            let pow = e << 23;
            for bits in pow - 64..pow + 64 {
                check(f32::from_bits(bits));
            }
        }
    }

    #[test]
    fn square_root_is_the_correctly_rounded_one_on_every_target() {
        extern crate std;
        let mut n = 0u32;
        roots_to_check(|x| {
            let want = std::primitive::f32::sqrt(x).to_bits();
            assert_eq!(sqrt(x).to_bits(), want, "sqrt({x:e})");
            assert_eq!(sqrt_soft(x).to_bits(), want, "sqrt_soft({x:e})");
            n += 1;
        });
        assert!(n > 35_000_000, "{n} inputs");
        for (x, want) in [
            (0.0, 0.0),
            (-0.0, 0.0),
            (-1.0, 0.0),
            (-1e-45, 0.0),
            (f32::NEG_INFINITY, 0.0),
            (f32::NAN, 0.0),
            (f32::INFINITY, f32::INFINITY),
        ] {
            assert_eq!(sqrt(x).to_bits(), f32::to_bits(want), "sqrt({x})");
            assert_eq!(sqrt_soft(x).to_bits(), f32::to_bits(want), "sqrt_soft({x})");
        }
    }

    #[test]
    fn ln_is_within_2e7_and_half_an_ulp() {
        extern crate std;
        let mut worst = 0.0f64;
        // Every 61st positive normal float and the floats around √½ · 2^e, where m wraps.
        let around = (1..254u32).flat_map(|e| {
            let b = (e << 23) | 0x35_04f3;
            b - 64..b + 64
        });
        for bits in (0x0080_0000..0x7f80_0000u32).step_by(61).chain(around) {
            let x = f32::from_bits(bits);
            let (got, want) = (ln(x) as f64, (x as f64).ln());
            let half_ulp = (want as f32).abs() as f64 * f32::EPSILON as f64 / 2.0;
            let err = (got - want).abs() - half_ulp;
            assert!(err < 2e-7, "ln({x:e}) = {got}, want {want}");
            worst = worst.max(err);
        }
        assert_eq!(ln(0.0), -87.0);
        assert_eq!(ln(-1.0), -87.0);
        assert_eq!(ln(f32::NAN), -87.0);
        assert_eq!(ln(1e-40), -87.0);
        assert_eq!(ln(f32::INFINITY), 88.7);
        assert_eq!(ln(1.0), 0.0);
        assert!(worst > 5e-8, "the bound is {worst:e} from tight");
    }

    #[test]
    fn exp2_neg_is_within_3e7_relative() {
        extern crate std;
        let mut worst = 0.0f64;
        // A fine grid over the domain, and each half-integer (where k's rounding ties) with its
        // neighbours.
        let grid = (0..=2_000_000).map(|i| -125.0 * i as f32 / 2_000_000.0);
        let ties = (0..125).flat_map(|k| {
            let h = -(k as f32 + 0.5);
            [
                h,
                f32::from_bits(h.to_bits() - 1),
                f32::from_bits(h.to_bits() + 1),
            ]
        });
        for y in grid.chain(ties).chain([0.0, -0.0, -125.0]) {
            let (got, want) = (exp2_neg(y) as f64, (y as f64).exp2());
            let err = (got / want - 1.0).abs();
            assert!(err < 3e-7, "exp2_neg({y}) = {got:e}, want {want:e}");
            worst = worst.max(err);
        }
        assert!(worst > 1e-7, "the bound is {worst:e} from tight");
    }
}
