//! The portable backend: four lanes as arrays, each operation a loop of the scalar IEEE
//! operation that its SSE2 sibling ([`sse2`](super::sse2)) performs lane by lane, with the same
//! answers in the corners where instructions and Rust's operators differ (`minps`'s NaN rule,
//! `cvttps2dq`'s out-of-range value, `sqrtss` of a negative number). It runs on every target
//! without SSE2 and, with the `portable` feature, on x86_64 too; the tests below compare it
//! with the SSE2 backend operation by operation, where both exist.
//!
//! Always compiled, because the scalar square root [`sqrt1`] here is the root for targets whose
//! `core` has none.

// On x86_64 with SSE2 only the square root and the eight-lane operations are used outside the
// tests; the four-lane types stand by as the tests' reference.
#![cfg_attr(
    all(
        target_arch = "x86_64",
        target_feature = "sse2",
        not(feature = "portable")
    ),
    allow(dead_code)
)]

use super::{F8, Lanes8, U8};
use core::ops::{Add, Mul, Sub};

/// Four `f32` lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct F4(pub(super) [f32; 4]);

/// Four 32-bit integer lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct I4(pub(super) [u32; 4]);

/// `f(a[i], b[i])` per lane.
#[inline(always)]
fn zip<T: Copy, U>(a: [T; 4], b: [T; 4], f: impl Fn(T, T) -> U) -> [U; 4] {
    [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])]
}

/// `t as i32` with `cvttss2si`'s answer for NaN and out-of-range `t`: `i32::MIN`.
#[inline(always)]
fn cvtt(t: f32) -> i32 {
    if (-2_147_483_648.0..2_147_483_648.0).contains(&t) {
        t as i32
    } else {
        i32::MIN
    }
}

/// The lane a two-bit field of a shuffle immediate selects.
#[inline(always)]
fn pick(v: [f32; 4], imm: i32, field: u32) -> f32 {
    v[(imm >> (2 * field) & 3) as usize]
}

impl F4 {
    /// The lanes of a row.
    #[inline(always)]
    pub(crate) fn new(r: &[f32; 4]) -> F4 {
        F4(*r)
    }

    /// The lanes of a point.
    #[inline(always)]
    pub(crate) fn from4(p: [f32; 4]) -> F4 {
        F4(p)
    }

    /// `[x, y, z, 0]`, read as an 8-byte and a 4-byte load, as the SSE2 sibling reads it: the
    /// pieces a caller stores a point in when it passes it in memory (see there).
    #[inline(always)]
    #[allow(unsafe_code)]
    pub(crate) fn from3(p: [f32; 3]) -> F4 {
        // SAFETY: bytes 0..8 of the 12-byte array, read without an alignment requirement.
        let [x, y] = unsafe { core::ptr::read_unaligned(p.as_ptr().cast::<[f32; 2]>()) };
        F4([x, y, p[2], 0.0])
    }

    /// `v` in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: f32) -> F4 {
        F4([v; 4])
    }

    /// Lane 0.
    #[inline(always)]
    pub(crate) fn x(self) -> f32 {
        self.0[0]
    }

    /// Lane 1.
    #[inline(always)]
    pub(crate) fn y(self) -> f32 {
        self.0[1]
    }

    /// Lane 2.
    #[inline(always)]
    pub(crate) fn z(self) -> f32 {
        self.0[2]
    }

    /// Lane 3.
    #[inline(always)]
    pub(crate) fn w(self) -> f32 {
        self.0[3]
    }

    /// `shufps`: lanes 0 and 1 from `a`, 2 and 3 from `b`, each picked by two bits of `IMM`.
    #[inline(always)]
    pub(crate) fn shuffle<const IMM: i32>(a: F4, b: F4) -> F4 {
        F4([
            pick(a.0, IMM, 0),
            pick(a.0, IMM, 1),
            pick(b.0, IMM, 2),
            pick(b.0, IMM, 3),
        ])
    }

    /// `if self < o { self } else { o }` per lane (`minps`; `o` where either is NaN).
    #[inline(always)]
    pub(crate) fn min(self, o: F4) -> F4 {
        F4(zip(self.0, o.0, |a, b| if a < b { a } else { b }))
    }

    /// `if self > o { self } else { o }` per lane (`maxps`; `o` where either is NaN).
    #[inline(always)]
    pub(crate) fn max(self, o: F4) -> F4 {
        F4(zip(self.0, o.0, |a, b| if a > b { a } else { b }))
    }

    /// All ones in each lane where `lane < v` (not where the lane is NaN), else 0.
    #[inline(always)]
    pub(crate) fn less(self, v: f32) -> I4 {
        I4(self.0.map(|a| 0u32.wrapping_sub((a < v) as u32)))
    }

    /// `(x + y) + z` in lane 0; lanes 1–3 keep `y`, `z`, `w` (as `addss` leaves them).
    #[inline(always)]
    pub(crate) fn sum3_x(self) -> F4 {
        let [x, y, z, w] = self.0;
        F4([(x + y) + z, y, z, w])
    }

    /// `(x + y) + z`, the order of a scalar three-term dot product.
    #[inline(always)]
    pub(crate) fn sum3(self) -> f32 {
        let [x, y, z, _] = self.0;
        (x + y) + z
    }

    /// `(x + y) + (z + w)`, the order of the 4D dot product.
    #[inline(always)]
    pub(crate) fn sum4(self) -> f32 {
        let [x, y, z, w] = self.0;
        (x + y) + (z + w)
    }

    /// The columns of the rows `r`: lane `a` of every row, for `a` = 0…3.
    #[inline(always)]
    pub(crate) fn transpose(r: [F4; 4]) -> [F4; 4] {
        core::array::from_fn(|a| F4([r[0].0[a], r[1].0[a], r[2].0[a], r[3].0[a]]))
    }

    /// The bits of each lane.
    #[inline(always)]
    pub(crate) fn to_bits(self) -> I4 {
        I4(self.0.map(f32::to_bits))
    }

    /// Each lane truncated to an integer (`cvttps2dq`: `i32::MIN` for NaN and out of range).
    #[inline(always)]
    pub(crate) fn trunc(self) -> I4 {
        I4(self.0.map(|t| cvtt(t) as u32))
    }

    /// The square root of each lane, for lanes that are finite and neither negative nor −0.
    #[inline(always)]
    pub(crate) fn sqrt(self) -> F4 {
        F4(self.0.map(sqrt1))
    }
}

impl Add for F4 {
    type Output = F4;
    #[inline(always)]
    fn add(self, o: F4) -> F4 {
        F4(zip(self.0, o.0, |a, b| a + b))
    }
}

impl Sub for F4 {
    type Output = F4;
    #[inline(always)]
    fn sub(self, o: F4) -> F4 {
        F4(zip(self.0, o.0, |a, b| a - b))
    }
}

impl Mul for F4 {
    type Output = F4;
    #[inline(always)]
    fn mul(self, o: F4) -> F4 {
        F4(zip(self.0, o.0, |a, b| a * b))
    }
}

impl Add for I4 {
    type Output = I4;
    #[inline(always)]
    fn add(self, o: I4) -> I4 {
        I4(zip(self.0, o.0, u32::wrapping_add))
    }
}

impl Sub for I4 {
    type Output = I4;
    #[inline(always)]
    fn sub(self, o: I4) -> I4 {
        I4(zip(self.0, o.0, u32::wrapping_sub))
    }
}

impl I4 {
    /// The lanes of four integers.
    #[inline(always)]
    pub(crate) fn new(v: [u32; 4]) -> I4 {
        I4(v)
    }

    /// `v` in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: u32) -> I4 {
        I4([v; 4])
    }

    /// All ones in each lane greater than `v` (as signed integers), else 0.
    #[inline(always)]
    pub(crate) fn greater(self, v: i32) -> I4 {
        I4(self.0.map(|a| 0u32.wrapping_sub((a as i32 > v) as u32)))
    }

    /// `self & o` per lane.
    #[inline(always)]
    pub(crate) fn and(self, o: I4) -> I4 {
        I4(zip(self.0, o.0, |a, b| a & b))
    }

    /// Each lane shifted left by `S`.
    #[inline(always)]
    pub(crate) fn shl<const S: i32>(self) -> I4 {
        I4(self.0.map(|a| a << S))
    }

    /// The lanes' bits as `f32` lanes.
    #[inline(always)]
    pub(crate) fn bits_to_f32(self) -> F4 {
        F4(self.0.map(f32::from_bits))
    }

    /// The xor of the four lanes.
    #[inline(always)]
    pub(crate) fn xor_lanes(self) -> u32 {
        let [x, y, z, w] = self.0;
        (x ^ z) ^ (y ^ w)
    }

    /// All ones in lane `a < 3` where bit `a` of `bits` is set, else 0 (lane 3 is 0).
    #[inline(always)]
    pub(crate) fn bit_masks(bits: u32) -> I4 {
        let m = |a: u32| 0u32.wrapping_sub(bits >> a & 1);
        I4([m(0), m(1), m(2), 0])
    }

    /// Each lane shifted right by `s < 32`, arithmetically: `⌊c / 2^s⌋`.
    #[inline(always)]
    pub(crate) fn floor_div_pow2(self, s: u32) -> I4 {
        I4(self.0.map(|a| ((a as i32) >> s) as u32))
    }

    /// Each lane's low `s < 32` bits: `c mod 2^s`, in `[0, 2^s)`.
    #[inline(always)]
    pub(crate) fn mod_pow2(self, s: u32) -> I4 {
        let mask = (1u32 << s).wrapping_sub(1);
        I4(self.0.map(|a| a & mask))
    }

    /// Each lane as `f32` (exact below 2^24; rounded to nearest above).
    #[inline(always)]
    pub(crate) fn to_f32(self) -> F4 {
        F4(self.0.map(|a| a as i32 as f32))
    }

    /// The four lanes as `u32`.
    #[inline(always)]
    pub(crate) fn xyzw(self) -> [u32; 4] {
        self.0
    }
}

/// Whether every lane is finite and below 2^22 in magnitude.
#[inline(always)]
pub(crate) fn in_split_range(v: F4) -> bool {
    let mut any = 0u32;
    for a in v.0 {
        any |= (a.to_bits() & 0x7fff_ffff).wrapping_add(0x8000_0000 - 0x4a80_0000);
    }
    any >> 31 == 0
}

/// The lane split of [`lanes::split_in_range`](super::split_in_range), lane by lane
/// ([`split1`]).
#[inline(always)]
pub(crate) fn split_in_range(v: F4) -> (I4, F4) {
    let s = v.0.map(split1);
    (I4(s.map(|(c, _)| c)), F4(s.map(|(_, f)| f)))
}

/// The split of one value with `|x| < 2^22` (the scalar
/// [`math::split_in_range`](crate::math::split_in_range), which is this): the nearest integer
/// from the bits of `x + 1.5·2^23`, then one step down where the remainder is strictly
/// negative (not −0). The cell as `u32` bits of the `i32`.
#[inline(always)]
pub(crate) fn split1(x: f32) -> (u32, f32) {
    const MAGIC: f32 = 12_582_912.0;
    let y = x + MAGIC;
    let r = y.to_bits().wrapping_sub(MAGIC.to_bits());
    let f = x - (y - MAGIC);
    let down = 0u32.wrapping_sub((f.to_bits() > 0x8000_0000) as u32);
    (r.wrapping_add(down), f + f32::from_bits(down & 0x3f80_0000))
}

/// `t as i32` for `|t| < 2^31` (`i32::MIN` for NaN and out of range, as `cvttss2si`).
#[inline(always)]
pub(crate) fn trunc1(t: f32) -> i32 {
    cvtt(t)
}

/// The correctly rounded `√x` of one value without a square-root instruction; `x ≤ 0` or NaN
/// gives 0, `+∞` gives `+∞` (as `sqrtss` of `max(x, 0)`).
///
/// The classic bit-level guess of `1/√x` refined by three Newton steps gives a root `r` within
/// a few ulps; then `r` steps to its neighbour while `x` lies outside the squares of the
/// midpoints between `r` and its neighbours. Those midpoints have 25 significant bits, so
/// their squares are exact in f64, and never equal to an f32 `x` (the square of an odd 25-bit
/// integer has 49 or 50 bits): the test decides the correctly rounded root.
#[inline]
pub(crate) fn sqrt1(x: f32) -> f32 {
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    if x == f32::INFINITY {
        return x;
    }
    // A subnormal times 2^24 is normal, and its root times 2^-12 is the root: both exact.
    let (x, scale) = if x < f32::MIN_POSITIVE {
        (x * 16_777_216.0, 1.0 / 4096.0)
    } else {
        (x, 1.0)
    };
    let mut y = f32::from_bits(0x5f37_5a86u32.wrapping_sub(x.to_bits() >> 1));
    let h = 0.5 * x;
    y *= 1.5 - h * y * y;
    y *= 1.5 - h * y * y;
    y *= 1.5 - h * y * y;
    let mut r = x * y;
    let xd = x as f64;
    // The guess is within 3 ulps (the tests check every input class); 8 steps bound the loop.
    for _ in 0..8 {
        let (down, up) = (
            f32::from_bits(r.to_bits() - 1),
            f32::from_bits(r.to_bits() + 1),
        );
        let (lo, hi) = ((r as f64 + down as f64) * 0.5, (r as f64 + up as f64) * 0.5);
        if xd < lo * lo {
            r = down;
        } else if xd > hi * hi {
            r = up;
        } else {
            break;
        }
    }
    r * scale
}

/// The eight-lane operations of the batch kernels as loops: the definitions the AVX2 forms
/// are tested against, and the code on every CPU without AVX2 (where LLVM vectorises them as
/// it can, e.g. to NEON).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Portable8;

impl Lanes8 for Portable8 {
    #[inline(always)]
    fn lookup16(self, table: &[F8; 2], j: U8) -> F8 {
        j.map(|j| table[(j >> 3 & 1) as usize][(j & 7) as usize])
    }

    #[inline(always)]
    fn sign_bits(self, v: U8) -> u32 {
        let mut b = 0;
        for (i, v) in v.iter().enumerate() {
            b |= (v >> 31) << i;
        }
        b
    }

    #[inline(always)]
    fn narrow(self, r: &mut U8, l: &mut U8, cut: U8) -> U8 {
        let mut up = [0u32; 8];
        for i in 0..8 {
            up[i] = ((r[i].wrapping_sub(cut[i]) as i32) >> 31) as u32;
            r[i] = r[i].wrapping_sub(!up[i] & cut[i]);
            l[i] = if up[i] != 0 {
                cut[i]
            } else {
                l[i].wrapping_sub(cut[i])
            };
        }
        up
    }

    #[inline(always)]
    fn mul_shr23(self, l: U8, t: U8) -> U8 {
        core::array::from_fn(|i| ((l[i] as u64 * t[i] as u64) >> 23) as u32)
    }
}
