//! Four `f32` lanes in one SSE2 register, for the hot paths of gradient noise on x86_64.
//!
//! SSE2 is part of the x86_64 baseline, so this module is compiled whenever the target has it
//! (`cfg(target_feature = "sse2")`, set for every x86_64 target unless a build turns it off),
//! and elsewhere the scalar forms run. It is the only module of the crate with `unsafe`: Rust
//! requires it around a call of a `#[target_feature]` intrinsic even when the feature is
//! statically enabled. Each block is one such call on register values; no pointer is read or
//! written, so the only precondition is the feature itself, which the `cfg` guarantees.
//!
//! Each operation is, lane by lane, exactly the IEEE operation of its scalar counterpart in
//! [`math`](crate::math), in the same order, so a function written on lanes returns the same
//! bits as its scalar form; the tests of the callers compare the two.
//!
//! Why by hand: LLVM vectorises little of the scalar forms. In the 3D Perlin estimator it kept
//! the three fades and one lane of the split scalar (169 instructions a call, against 118 on
//! lanes), and the estimator is bound by how many of its calls fit in the out-of-order window,
//! so its instruction count is its speed.

use core::arch::x86_64::{
    __m128, __m128i, _mm_add_epi32, _mm_add_ps, _mm_add_ss, _mm_and_ps, _mm_and_si128,
    _mm_castps_si128, _mm_castsi128_ps, _mm_cmpgt_epi32, _mm_cmplt_ps, _mm_cvtepi32_ps,
    _mm_cvtsi32_si128, _mm_cvtsi128_si32, _mm_cvtss_f32, _mm_cvttps_epi32, _mm_cvttss_si32,
    _mm_max_ps, _mm_max_ss, _mm_min_ps, _mm_movehl_ps, _mm_movelh_ps, _mm_movemask_ps, _mm_mul_ps,
    _mm_set_epi32, _mm_set_ps, _mm_set_ss, _mm_set1_epi32, _mm_set1_ps, _mm_setzero_ps,
    _mm_setzero_si128, _mm_shuffle_epi32, _mm_shuffle_ps, _mm_slli_epi32, _mm_sqrt_ps, _mm_sqrt_ss,
    _mm_sra_epi32, _mm_sub_epi32, _mm_sub_ps, _mm_unpackhi_ps, _mm_unpacklo_ps, _mm_xor_si128,
};
use core::ops::{Add, Mul, Sub};

/// Methods `fn name(self) -> f32` returning the lane a shuffle immediate selects.
macro_rules! lane_getters {
    ($($(#[$doc:meta])* $name:ident = $imm:literal;)*) => {$(
        $(#[$doc])*
        #[inline(always)]
        pub(crate) fn $name(self) -> f32 {
            unsafe { _mm_cvtss_f32(_mm_shuffle_ps::<$imm>(self.0, self.0)) }
        }
    )*};
}

/// Methods `fn name(self) -> F4` rearranging the lanes by a shuffle immediate.
macro_rules! swizzles {
    ($($(#[$doc:meta])* $name:ident = $imm:literal;)*) => {$(
        $(#[$doc])*
        #[inline(always)]
        pub(crate) fn $name(self) -> F4 {
            F4(unsafe { _mm_shuffle_ps::<$imm>(self.0, self.0) })
        }
    )*};
}

/// Four `f32` lanes.
#[derive(Clone, Copy)]
pub(crate) struct F4(__m128);

/// Four 32-bit integer lanes.
#[derive(Clone, Copy)]
pub(crate) struct I4(__m128i);

impl F4 {
    /// The lanes of a row (one load when the row is in memory).
    #[inline(always)]
    pub(crate) fn new(r: &[f32; 4]) -> F4 {
        // SAFETY (here and in every block below): the call's only precondition is the
        // target feature, enabled at compile time (see the module doc).
        F4(unsafe { _mm_set_ps(r[3], r[2], r[1], r[0]) })
    }

    /// The lanes of a point.
    #[inline(always)]
    pub(crate) fn from4(p: [f32; 4]) -> F4 {
        F4(unsafe { _mm_set_ps(p[3], p[2], p[1], p[0]) })
    }

    /// `[x, y, z, 0]`.
    #[inline(always)]
    pub(crate) fn from3(p: [f32; 3]) -> F4 {
        F4(unsafe { _mm_set_ps(0.0, p[2], p[1], p[0]) })
    }

    /// `v` in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: f32) -> F4 {
        F4(unsafe { _mm_set1_ps(v) })
    }

    lane_getters! {
        /// Lane 0.
        x = 0x00;
        /// Lane 1.
        y = 0x55;
        /// Lane 2.
        z = 0xaa;
        /// Lane 3.
        w = 0xff;
    }

    swizzles! {
        /// Lane 0 in every lane.
        xxxx = 0x00;
        /// Lane 1 in every lane.
        yyyy = 0x55;
        /// Lane 2 in every lane.
        zzzz = 0xaa;
        /// Lanes 0 and 2 (twice).
        xzxz = 0b10_00_10_00;
        /// Lanes 1 and 3 (twice).
        ywyw = 0b11_01_11_01;
    }

    /// `if self < o { self } else { o }` per lane (`minps`; `o` where either is NaN).
    #[inline(always)]
    pub(crate) fn min(self, o: F4) -> F4 {
        F4(unsafe { _mm_min_ps(self.0, o.0) })
    }

    /// `max(self, o)` per lane (`o` where either is NaN, as `f32::max(self, o)` for a
    /// non-NaN `o`).
    #[inline(always)]
    pub(crate) fn max(self, o: F4) -> F4 {
        F4(unsafe { _mm_max_ps(self.0, o.0) })
    }

    /// All ones in each lane where `lane < v` (not where the lane is NaN), else 0.
    #[inline(always)]
    pub(crate) fn less(self, v: f32) -> I4 {
        I4(unsafe { _mm_castps_si128(_mm_cmplt_ps(self.0, _mm_set1_ps(v))) })
    }

    /// [`sum3`](Self::sum3) in lane 0 (the other lanes unspecified), to go on with lanes.
    #[inline(always)]
    pub(crate) fn sum3_x(self) -> F4 {
        let v = self.0;
        unsafe {
            let s = _mm_add_ss(v, _mm_shuffle_ps::<0x55>(v, v));
            F4(_mm_add_ss(s, _mm_movehl_ps(v, v)))
        }
    }

    /// `(x + y) + z`, the order of a scalar three-term dot product.
    #[inline(always)]
    pub(crate) fn sum3(self) -> f32 {
        let v = self.0;
        unsafe {
            let s = _mm_add_ps(v, _mm_shuffle_ps::<0x55>(v, v));
            _mm_cvtss_f32(_mm_add_ps(s, _mm_shuffle_ps::<0xaa>(v, v)))
        }
    }

    /// `(x + y) + (z + w)`, the order of the 4D dot product (`dot4`).
    #[inline(always)]
    pub(crate) fn sum4(self) -> f32 {
        let v = self.0;
        unsafe {
            // Lane 0: x + y; lane 1: z + w (of the pairs (x, z) and (y, w)).
            let s = _mm_add_ps(
                _mm_shuffle_ps::<0b10_00_10_00>(v, v),
                _mm_shuffle_ps::<0b11_01_11_01>(v, v),
            );
            _mm_cvtss_f32(_mm_add_ss(s, _mm_shuffle_ps::<0x55>(s, s)))
        }
    }

    /// `[r0.sum4(), r1.sum4(), r2.sum4(), r3.sum4()]`, by a transpose.
    #[inline(always)]
    pub(crate) fn sums4(r: [F4; 4]) -> F4 {
        let [x, y, z, w] = F4::transpose(r);
        (x + y) + (z + w)
    }

    /// `shufps`: lanes 0 and 1 from `a`, 2 and 3 from `b`, each picked by two bits of `IMM`
    /// (lane 0's from bits 0–1, up to lane 3's from bits 6–7).
    #[inline(always)]
    pub(crate) fn shuffle<const IMM: i32>(a: F4, b: F4) -> F4 {
        F4(unsafe { _mm_shuffle_ps::<IMM>(a.0, b.0) })
    }

    /// Lanes 0 and 2 of `a`, then lanes 0 and 2 of `b`.
    #[inline(always)]
    pub(crate) fn evens(a: F4, b: F4) -> F4 {
        F4(unsafe { _mm_shuffle_ps::<0b10_00_10_00>(a.0, b.0) })
    }

    /// Lanes 1 and 3 of `a`, then lanes 1 and 3 of `b`.
    #[inline(always)]
    pub(crate) fn odds(a: F4, b: F4) -> F4 {
        F4(unsafe { _mm_shuffle_ps::<0b11_01_11_01>(a.0, b.0) })
    }

    /// `[r0.sum3(), r1.sum3(), r2.sum3(), r3.sum3()]`, by a transpose: four dot products'
    /// sums in two adds.
    #[inline(always)]
    pub(crate) fn sums3(r: [F4; 4]) -> F4 {
        let [x, y, z, _] = F4::transpose(r);
        (x + y) + z
    }

    /// The columns of the rows `r`: lane `a` of every row, for `a` = 0…3.
    #[inline(always)]
    pub(crate) fn transpose(r: [F4; 4]) -> [F4; 4] {
        let [r0, r1, r2, r3] = r.map(|v| v.0);
        unsafe {
            let lo01 = _mm_unpacklo_ps(r0, r1);
            let lo23 = _mm_unpacklo_ps(r2, r3);
            let hi01 = _mm_unpackhi_ps(r0, r1);
            let hi23 = _mm_unpackhi_ps(r2, r3);
            [
                F4(_mm_movelh_ps(lo01, lo23)),
                F4(_mm_movehl_ps(lo23, lo01)),
                F4(_mm_movelh_ps(hi01, hi23)),
                F4(_mm_movehl_ps(hi23, hi01)),
            ]
        }
    }

    /// `a + t·(b − a)` on each lane, the scalar `lerp`.
    #[inline(always)]
    pub(crate) fn lerp(t: F4, a: F4, b: F4) -> F4 {
        a + t * (b - a)
    }
}

impl Add for F4 {
    type Output = F4;
    #[inline(always)]
    fn add(self, o: F4) -> F4 {
        F4(unsafe { _mm_add_ps(self.0, o.0) })
    }
}

impl Sub for F4 {
    type Output = F4;
    #[inline(always)]
    fn sub(self, o: F4) -> F4 {
        F4(unsafe { _mm_sub_ps(self.0, o.0) })
    }
}

impl Add for I4 {
    type Output = I4;
    #[inline(always)]
    fn add(self, o: I4) -> I4 {
        I4(unsafe { _mm_add_epi32(self.0, o.0) })
    }
}

impl Sub for I4 {
    type Output = I4;
    #[inline(always)]
    fn sub(self, o: I4) -> I4 {
        I4(unsafe { _mm_sub_epi32(self.0, o.0) })
    }
}

impl Mul for F4 {
    type Output = F4;
    #[inline(always)]
    fn mul(self, o: F4) -> F4 {
        F4(unsafe { _mm_mul_ps(self.0, o.0) })
    }
}

impl I4 {
    /// The lanes of four integers.
    #[inline(always)]
    pub(crate) fn new(v: [u32; 4]) -> I4 {
        I4(unsafe { _mm_set_epi32(v[3] as i32, v[2] as i32, v[1] as i32, v[0] as i32) })
    }

    /// All ones in each lane greater than `v` (as signed integers), else 0.
    #[inline(always)]
    pub(crate) fn greater(self, v: i32) -> I4 {
        I4(unsafe { _mm_cmpgt_epi32(self.0, _mm_set1_epi32(v)) })
    }

    /// `self & o` per lane.
    #[inline(always)]
    pub(crate) fn and(self, o: I4) -> I4 {
        I4(unsafe { _mm_and_si128(self.0, o.0) })
    }

    /// 1.0 in each lane of the mask `self` that is all ones, 0.0 where it is 0.
    #[inline(always)]
    pub(crate) fn ones(self) -> F4 {
        F4(unsafe { _mm_and_ps(_mm_castsi128_ps(self.0), _mm_set1_ps(1.0)) })
    }

    /// The xor of the four lanes.
    #[inline(always)]
    pub(crate) fn xor_lanes(self) -> u32 {
        unsafe {
            let v = _mm_xor_si128(self.0, _mm_shuffle_epi32::<0b01_00_11_10>(self.0));
            _mm_cvtsi128_si32(_mm_xor_si128(v, _mm_shuffle_epi32::<0b10_11_00_01>(v))) as u32
        }
    }

    /// All ones in lane `a < 3` where bit `a` of `bits < 8` is set, else 0 (lane 3 is 0): one
    /// read of a table.
    #[inline(always)]
    pub(crate) fn bit_masks(bits: u32) -> I4 {
        static MASKS: [[i32; 4]; 8] = {
            let mut t = [[0; 4]; 8];
            let mut b = 0;
            while b < 8 {
                t[b] = [
                    -((b & 1) as i32),
                    -((b >> 1 & 1) as i32),
                    -((b >> 2 & 1) as i32),
                    0,
                ];
                b += 1;
            }
            t
        };
        let r = &MASKS[bits as usize & 7];
        I4(unsafe { _mm_set_epi32(r[3], r[2], r[1], r[0]) })
    }

    /// Each lane shifted right by `s < 32`, arithmetically: `⌊c / 2^s⌋`.
    #[inline(always)]
    pub(crate) fn floor_div_pow2(self, s: u32) -> I4 {
        I4(unsafe { _mm_sra_epi32(self.0, _mm_cvtsi32_si128(s as i32)) })
    }

    /// Each lane's low `s < 32` bits: `c mod 2^s`, in `[0, 2^s)`.
    #[inline(always)]
    pub(crate) fn mod_pow2(self, s: u32) -> I4 {
        let mask = (1u32 << s).wrapping_sub(1) as i32;
        I4(unsafe { _mm_and_si128(self.0, _mm_set1_epi32(mask)) })
    }

    /// Each lane as `f32` (exact below 2^24).
    #[inline(always)]
    pub(crate) fn to_f32(self) -> F4 {
        F4(unsafe { _mm_cvtepi32_ps(self.0) })
    }

    /// The four lanes as `u32`.
    #[inline(always)]
    pub(crate) fn xyzw(self) -> [u32; 4] {
        let v = self.0;
        unsafe {
            [
                _mm_cvtsi128_si32(v) as u32,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<0x55>(v)) as u32,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<0xaa>(v)) as u32,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<0xff>(v)) as u32,
            ]
        }
    }

    /// Lanes 0, 1 and 2 as `u32`.
    #[inline(always)]
    pub(crate) fn xyz(self) -> [u32; 3] {
        let [x, y, z, _] = self.xyzw();
        [x, y, z]
    }
}

/// [`in_split_range`](crate::math::in_split_range) of all four lanes: the same add per lane,
/// and one sign mask instead of extracting the lanes.
#[inline(always)]
pub(crate) fn in_split_range(v: F4) -> bool {
    unsafe {
        let abs = _mm_and_si128(_mm_castps_si128(v.0), _mm_set1_epi32(0x7fff_ffff));
        let t = _mm_add_epi32(abs, _mm_set1_epi32((0x8000_0000u32 - 0x4a80_0000) as i32));
        _mm_movemask_ps(_mm_castsi128_ps(t)) == 0
    }
}

/// [`split_in_range`](crate::math::split_in_range) on each lane: the cells and the offsets.
/// Every lane must be in the split range (`|x| < 2^22`, finite).
#[inline(always)]
pub(crate) fn split_in_range(v: F4) -> (I4, F4) {
    unsafe {
        let magic = _mm_set1_ps(12_582_912.0);
        let y = _mm_add_ps(v.0, magic);
        let r = _mm_sub_epi32(_mm_castps_si128(y), _mm_castps_si128(magic));
        let f = _mm_sub_ps(v.0, _mm_sub_ps(y, magic));
        // All ones where f's bits exceed 0x8000_0000 as unsigned (strictly negative, not −0):
        // the sign-flipped bits compared as signed.
        let down = _mm_cmpgt_epi32(
            _mm_xor_si128(_mm_castps_si128(f), _mm_set1_epi32(i32::MIN)),
            _mm_setzero_si128(),
        );
        (
            I4(_mm_add_epi32(r, down)),
            F4(_mm_add_ps(
                f,
                _mm_and_ps(_mm_castsi128_ps(down), _mm_set1_ps(1.0)),
            )),
        )
    }
}

/// [`fade`](crate::math::fade) on each lane, in the same order of operations.
#[inline(always)]
pub(crate) fn fade(t: F4) -> F4 {
    let t3 = t * t * t;
    t3 * (t * (t * F4::splat(6.0) - F4::splat(15.0)) + F4::splat(10.0))
}

/// The bits of `1 + t` minus those of 1 on each lane: `t · 2^23` rounded, the fixed point of
/// the estimators' corner choice (`estimators::fixed`).
#[inline(always)]
pub(crate) fn fixed(t: F4) -> I4 {
    let one = t + F4::splat(1.0);
    I4(unsafe { _mm_sub_epi32(_mm_castps_si128(one.0), _mm_set1_epi32(0x3f80_0000)) })
}

/// [`sqrt`](crate::math::sqrt) on each lane, for lanes that are finite and neither negative
/// nor −0 (squared distances): `sqrtps`, correctly rounded like the scalar form, whose special
/// cases change nothing there.
#[inline(always)]
pub(crate) fn sqrt(x: F4) -> F4 {
    F4(unsafe { _mm_sqrt_ps(x.0) })
}

/// `t as i32` for a `t` known to be in range (`|t| < 2^31`): `cvttss2si` alone, without the
/// checks of the saturating `as` (NaN and out-of-range give `i32::MIN`).
#[inline(always)]
pub(crate) fn trunc1(t: f32) -> i32 {
    unsafe { _mm_cvttss_si32(_mm_set_ss(t)) }
}

/// [`sqrt`](crate::math::sqrt) of one value: `sqrtss` of `max(x, 0)`, where `maxss` gives its
/// second operand, +0, for NaN, −0 and negative `x`.
#[inline(always)]
pub(crate) fn sqrt1(x: f32) -> f32 {
    unsafe { _mm_cvtss_f32(_mm_sqrt_ss(_mm_max_ss(_mm_set_ss(x), _mm_setzero_ps()))) }
}

/// [`exp2_neg`](crate::math::exp2_neg) on each lane (each in `[−125, 0]`): the same
/// operations in the same order.
#[inline(always)]
pub(crate) fn exp2_neg(y: F4) -> F4 {
    const MAGIC: f32 = 12_582_912.0;
    let k = (y + F4::splat(MAGIC)) - F4::splat(MAGIC);
    let r = y - k;
    let c = crate::math::EXP2_POLY.map(F4::splat);
    let r2 = r * r;
    let p = (c[0] + c[1] * r) + r2 * ((c[2] + c[3] * r) + r2 * (c[4] + c[5] * r));
    let scale = unsafe {
        _mm_castsi128_ps(_mm_slli_epi32::<23>(_mm_add_epi32(
            _mm_cvttps_epi32(k.0),
            _mm_set1_epi32(127),
        )))
    };
    p * F4(scale)
}
