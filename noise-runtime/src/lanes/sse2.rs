//! The SSE2 backend: four `f32` lanes in one register.
//!
//! SSE2 is part of the x86_64 baseline, so this backend is chosen whenever the target has it
//! (`cfg(target_feature = "sse2")`, set for every x86_64 target unless a build turns it off)
//! and the `portable` feature is off. Rust requires `unsafe` around a call of a
//! `#[target_feature]` intrinsic even when the feature is statically enabled; each block here
//! is one such call on register values (or, in `F4::from3`, a read of an array it is handed),
//! so the only precondition is the feature itself, which the `cfg` guarantees.
//!
//! Each operation is, lane by lane, exactly the IEEE operation of its sibling in the portable
//! backend ([`scalar`](super::scalar)); the tests in [`lanes`](super) compare the two.
//!
//! Why by hand: LLVM vectorises little of the scalar forms. In the 3D Perlin estimator it kept
//! the three fades and one lane of the split scalar (about half again the instructions of the
//! lane form), and the estimator is bound by how many of its calls fit in the out-of-order window,
//! so its instruction count is its speed.

use core::arch::x86_64::{
    __m128, __m128i, _mm_add_epi32, _mm_add_ps, _mm_add_ss, _mm_and_ps, _mm_and_si128,
    _mm_castpd_ps, _mm_castps_si128, _mm_castsi128_ps, _mm_cmpgt_epi32, _mm_cmplt_ps,
    _mm_cvtepi32_ps, _mm_cvtsi32_si128, _mm_cvtsi128_si32, _mm_cvtss_f32, _mm_cvttps_epi32,
    _mm_cvttss_si32, _mm_load_sd, _mm_load_ss, _mm_max_ps, _mm_max_ss, _mm_min_ps, _mm_movehl_ps,
    _mm_movelh_ps, _mm_movemask_ps, _mm_mul_ps, _mm_set_epi32, _mm_set_ps, _mm_set_ss,
    _mm_set1_epi32, _mm_set1_ps, _mm_setzero_ps, _mm_setzero_si128, _mm_shuffle_epi32,
    _mm_shuffle_ps, _mm_slli_epi32, _mm_sqrt_ps, _mm_sqrt_ss, _mm_sra_epi32, _mm_sub_epi32,
    _mm_sub_ps, _mm_unpackhi_ps, _mm_unpacklo_ps, _mm_xor_si128,
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

    /// `[x, y, z, 0]`, read as an 8-byte and a 4-byte load. A point that a caller passes in
    /// memory (a `[f32; 3]` argument of a function that is not inlined) was stored in those
    /// two pieces; left to itself, LLVM read it as 4 + 8 bytes, and a load that spans two
    /// stores cannot be forwarded from them: a stall of every call (3D Perlin noise through a
    /// function pointer measured about three times slower).
    #[inline(always)]
    pub(crate) fn from3(p: [f32; 3]) -> F4 {
        let p = &p;
        // SAFETY: bytes 0..8 and 8..12 of the 12-byte array; `movsd` and `movss` need no
        // alignment.
        F4(unsafe {
            let xy = _mm_castpd_ps(_mm_load_sd(p.as_ptr().cast::<f64>()));
            _mm_movelh_ps(xy, _mm_load_ss(&p[2]))
        })
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

    /// `shufps`: lanes 0 and 1 from `a`, 2 and 3 from `b`, each picked by two bits of `IMM`
    /// (lane 0's from bits 0–1, up to lane 3's from bits 6–7).
    #[inline(always)]
    pub(crate) fn shuffle<const IMM: i32>(a: F4, b: F4) -> F4 {
        F4(unsafe { _mm_shuffle_ps::<IMM>(a.0, b.0) })
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

    /// The bits of each lane.
    #[inline(always)]
    pub(crate) fn to_bits(self) -> I4 {
        I4(unsafe { _mm_castps_si128(self.0) })
    }

    /// Each lane truncated to an integer (`cvttps2dq`: `i32::MIN` for NaN and out of range).
    #[inline(always)]
    pub(crate) fn trunc(self) -> I4 {
        I4(unsafe { _mm_cvttps_epi32(self.0) })
    }

    /// The square root of each lane, for lanes that are finite and neither negative nor −0
    /// (squared distances): `sqrtps`, correctly rounded like the portable root, whose special
    /// cases change nothing there.
    #[inline(always)]
    pub(crate) fn sqrt(self) -> F4 {
        F4(unsafe { _mm_sqrt_ps(self.0) })
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

    /// `v` in every lane.
    #[inline(always)]
    pub(crate) fn splat(v: u32) -> I4 {
        I4(unsafe { _mm_set1_epi32(v as i32) })
    }

    /// Each lane shifted left by `S`.
    #[inline(always)]
    pub(crate) fn shl<const S: i32>(self) -> I4 {
        I4(unsafe { _mm_slli_epi32::<S>(self.0) })
    }

    /// The lanes' bits as `f32` lanes.
    #[inline(always)]
    pub(crate) fn bits_to_f32(self) -> F4 {
        F4(unsafe { _mm_castsi128_ps(self.0) })
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

/// `t as i32` for a `t` known to be in range (`|t| < 2^31`): `cvttss2si` alone, without the
/// checks of the saturating `as` (NaN and out-of-range give `i32::MIN`).
#[inline(always)]
pub(crate) fn trunc1(t: f32) -> i32 {
    unsafe { _mm_cvttss_si32(_mm_set_ss(t)) }
}

/// The square root of one value: `sqrtss` of `max(x, 0)`, where `maxss` gives its
/// second operand, +0, for NaN, −0 and negative `x`.
#[inline(always)]
pub(crate) fn sqrt1(x: f32) -> f32 {
    unsafe { _mm_cvtss_f32(_mm_sqrt_ss(_mm_max_ss(_mm_set_ss(x), _mm_setzero_ps()))) }
}
