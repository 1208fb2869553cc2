//! The lane layer: the one place that knows about SIMD. Every kernel of the crate that runs on
//! lanes (3D and 4D Perlin and simplex noise and their estimators, the fBm octaves, Worley and
//! smooth Voronoi noise, the batch forms) is written once against the types here, and a
//! backend chosen at compile time supplies them, as in `glam`'s sibling backends:
//!
//! | backend | chosen when | types |
//! |---|---|---|
//! | [`sse2`] | x86_64 with SSE2 (its baseline), `portable` off | [`F4`], [`I4`] in one register |
//! | [`scalar`] | every other target, or feature `portable` | [`F4`], [`I4`] as arrays |
//! | [`avx2`] | x86_64, `portable` off, and the CPU has AVX2 (asked at run time) | [`Lanes8`] ops on `[f32; 8]` |
//! | [`scalar::Portable8`] | wherever AVX2 is not | [`Lanes8`] ops as loops |
//!
//! Each operation of a backend is, lane by lane, the IEEE operation of its siblings, with the
//! same answers at NaN, ±0 and out-of-range conversions, so every kernel returns the same bits
//! on every backend. That is tested three ways: the tests below compare the SSE2 and portable
//! backends operation by operation on x86_64; the AVX2 lane operations are compared with
//! their portable definitions (where the CPU has AVX2, and said plainly where it has not);
//! and the whole test suite, with its pinned values, runs once more with the `portable`
//! feature in CI (`tests/targets.rs` at the workspace root).
//!
//! The layer sits below [`math`](crate::math) and imports nothing of the crate: `math` takes
//! its square root from here ([`sqrt1`]), and [`EXP2_POLY`] lives here so that the lane and
//! scalar `exp2` share it without an import going up.
//!
//! This module and its backends hold all of the crate's `target_arch` conditions and all of
//! its `unsafe` but one kind: the batch forms' calls of their
//! `#[target_feature(enable = "avx2")]` entry points, each guarded by an [`avx2::Avx2`] token.

#[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
#[allow(unsafe_code)]
pub(crate) mod avx2;
pub(crate) mod scalar;
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "sse2",
    not(feature = "portable")
))]
#[allow(unsafe_code)]
pub(crate) mod sse2;

#[cfg(all(
    target_arch = "x86_64",
    target_feature = "sse2",
    not(feature = "portable")
))]
pub(crate) use sse2::{F4, I4, in_split_range, split_in_range, sqrt1, trunc1};

#[cfg(not(all(
    target_arch = "x86_64",
    target_feature = "sse2",
    not(feature = "portable")
)))]
pub(crate) use scalar::{F4, I4, in_split_range, split_in_range, sqrt1, trunc1};

/// Eight `f32` lanes, the batch forms' register.
pub(crate) type F8 = [f32; 8];
/// Eight `u32` lanes.
pub(crate) type U8 = [u32; 8];

/// The eight-lane operations that the batch kernels
/// ([`stochastic::batch`](crate::stochastic)) cannot leave to LLVM's vectoriser: everything
/// else in those kernels is plain loops over [`F8`] and [`U8`], which become one instruction a
/// step on AVX2 and NEON alike. Implemented by [`avx2::Avx2`] (a token proving the CPU has
/// AVX2) and by [`scalar::Portable8`] (loops, for every target); the same bits either way.
pub(crate) trait Lanes8: Copy {
    /// `table[j & 15]` per lane, reading a 16-entry table kept as two halves.
    fn lookup16(self, table: &[F8; 2], j: U8) -> F8;

    /// The sign bits of the lanes as an integer (bit `i` from lane `i`).
    fn sign_bits(self, v: U8) -> u32;

    /// One decision of the estimators' corner choice on every lane
    /// (`Narrowing::upper_fixed` with the cut given): all ones where `r < cut` (the upper
    /// side, of length `cut`), and there `l ← cut`; elsewhere `r ← r − cut` and
    /// `l ← l − cut`. `r` and `cut` must differ by less than 2^31 (they are below 2^24).
    fn narrow(self, r: &mut U8, l: &mut U8, cut: U8) -> U8;

    /// `((l · t) >> 23) as u32` per lane, the product taken in 64 bits: the fixed-point cut
    /// of the estimators' corner choice.
    fn mul_shr23(self, l: U8, t: U8) -> U8;
}

/// Coefficients of the degree-5 Chebyshev fit to `2^r` on `[−½, ½]` (relative error below
/// 1.1e-7), constant term first: the polynomial of [`exp2_neg`] and of
/// [`math::exp2_neg`](crate::math). (The linear one, 0.693 147 188, rounds to the float
/// `ln 2`.)
pub(crate) const EXP2_POLY: [f32; 6] = [
    1.000_000_1,
    core::f32::consts::LN_2,
    0.240_221_08,
    0.055_503_57,
    0.009_676_032,
    0.001_339_086_3,
];

/// Rearrangements and sums built from a backend's shuffle and transpose, so that each backend
/// has only the primitive.
impl F4 {
    /// Lane 0 in every lane.
    #[inline(always)]
    pub(crate) fn xxxx(self) -> F4 {
        F4::shuffle::<0x00>(self, self)
    }

    /// Lane 1 in every lane.
    #[inline(always)]
    pub(crate) fn yyyy(self) -> F4 {
        F4::shuffle::<0x55>(self, self)
    }

    /// Lane 2 in every lane.
    #[inline(always)]
    pub(crate) fn zzzz(self) -> F4 {
        F4::shuffle::<0xaa>(self, self)
    }

    /// Lanes 0 and 2 (twice).
    #[inline(always)]
    pub(crate) fn xzxz(self) -> F4 {
        F4::evens(self, self)
    }

    /// Lanes 1 and 3 (twice).
    #[inline(always)]
    pub(crate) fn ywyw(self) -> F4 {
        F4::odds(self, self)
    }

    /// Lanes 0 and 2 of `a`, then lanes 0 and 2 of `b`.
    #[inline(always)]
    pub(crate) fn evens(a: F4, b: F4) -> F4 {
        F4::shuffle::<0b10_00_10_00>(a, b)
    }

    /// Lanes 1 and 3 of `a`, then lanes 1 and 3 of `b`.
    #[inline(always)]
    pub(crate) fn odds(a: F4, b: F4) -> F4 {
        F4::shuffle::<0b11_01_11_01>(a, b)
    }

    /// `[r0.sum3(), r1.sum3(), r2.sum3(), r3.sum3()]`, by a transpose: four dot products'
    /// sums in two adds.
    #[inline(always)]
    pub(crate) fn sums3(r: [F4; 4]) -> F4 {
        let [x, y, z, _] = F4::transpose(r);
        (x + y) + z
    }

    /// `[r0.sum4(), r1.sum4(), r2.sum4(), r3.sum4()]`, by a transpose.
    #[inline(always)]
    pub(crate) fn sums4(r: [F4; 4]) -> F4 {
        let [x, y, z, w] = F4::transpose(r);
        (x + y) + (z + w)
    }

    /// `a + t·(b − a)` on each lane, the scalar `lerp`.
    #[inline(always)]
    pub(crate) fn lerp(t: F4, a: F4, b: F4) -> F4 {
        a + t * (b - a)
    }
}

impl I4 {
    /// 1.0 in each lane of the mask `self` that is all ones, 0.0 where it is 0.
    #[inline(always)]
    pub(crate) fn ones(self) -> F4 {
        self.and(I4::splat(0x3f80_0000)).bits_to_f32()
    }

    /// Lanes 0, 1 and 2 as `u32`.
    #[inline(always)]
    pub(crate) fn xyz(self) -> [u32; 3] {
        let [x, y, z, _] = self.xyzw();
        [x, y, z]
    }
}

/// Perlin's quintic fade `6t⁵ − 15t⁴ + 10t³` on each lane, in the order of the scalar
/// [`fade`](crate::math::fade).
#[inline(always)]
pub(crate) fn fade(t: F4) -> F4 {
    let t3 = t * t * t;
    t3 * (t * (t * F4::splat(6.0) - F4::splat(15.0)) + F4::splat(10.0))
}

/// The bits of `1 + t` minus those of 1 on each lane: `t · 2^23` rounded, the fixed point of
/// the estimators' corner choice (`estimators::fixed`).
#[inline(always)]
pub(crate) fn fixed(t: F4) -> I4 {
    (t + F4::splat(1.0)).to_bits() - I4::splat(0x3f80_0000)
}

/// `2^y` on each lane, each in `[−125, 0]`: `2^k · 2^r` for the nearest integer `k` and
/// `r ∈ [−½, ½]`, `2^r` by [`EXP2_POLY`] in Estrin's scheme; the operations and order of the
/// scalar `math::exp2_neg`.
#[inline(always)]
pub(crate) fn exp2_neg(y: F4) -> F4 {
    const MAGIC: f32 = 12_582_912.0;
    let k = (y + F4::splat(MAGIC)) - F4::splat(MAGIC);
    let r = y - k;
    let c = EXP2_POLY.map(F4::splat);
    let r2 = r * r;
    let p = (c[0] + c[1] * r) + r2 * ((c[2] + c[3] * r) + r2 * (c[4] + c[5] * r));
    p * (k.trunc() + I4::splat(127)).shl::<23>().bits_to_f32()
}

#[cfg(all(test, target_arch = "x86_64", not(feature = "portable")))]
mod tests {
    //! The SSE2 backend against the portable one, operation by operation, on inputs that
    //! include every special value (±0, subnormals, ±∞, NaN, the edge of the split range,
    //! integers near `i32` limits).
    use super::{scalar, sse2};
    use std::vec::Vec;

    fn inputs() -> Vec<[f32; 4]> {
        let special = [
            0.0f32,
            -0.0,
            1e-45,
            -1e-45,
            1.0,
            -1.0,
            0.5,
            -2.5,
            4_194_303.5,
            -4_194_304.0,
            2_147_483_520.0,
            -2_147_483_648.0,
            2_147_483_648.0,
            3e38,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let n = special.len();
        let mut v: Vec<[f32; 4]> = (0..n * n)
            .map(|i| {
                [
                    special[i % n],
                    special[i / n],
                    special[(i * 7) % n],
                    special[(i * 3 + 1) % n],
                ]
            })
            .collect();
        for _ in 0..20_000 {
            let r = next();
            let scale = [1.0f32, 100.0, 1e7][(r % 3) as usize];
            v.push([0; 4].map(|_| ((next() >> 40) as f32 / 16_777_216.0 - 0.5) * scale));
            v.push([0; 4].map(|_| f32::from_bits(next() as u32)));
        }
        v
    }

    /// The same bits, NaN for NaN (any NaN payload: the backends agree on NaN, not on which).
    fn same(what: &str, a: [f32; 4], got: [f32; 4], want: [f32; 4]) {
        for i in 0..4 {
            let (g, w) = (got[i], want[i]);
            assert!(
                g.to_bits() == w.to_bits() || (g.is_nan() && w.is_nan()),
                "{what} of {a:?}: lane {i} {g:e} vs {w:e}"
            );
        }
    }

    fn f(v: sse2::F4) -> [f32; 4] {
        [v.x(), v.y(), v.z(), v.w()]
    }

    #[test]
    fn sse2_and_portable_backends_agree_operation_by_operation() {
        let all = inputs();
        for (k, &a) in all.iter().enumerate() {
            let b = all[(k * 31 + 7) % all.len()];
            let (sa, sb) = (sse2::F4::from4(a), sse2::F4::from4(b));
            let (pa, pb) = (scalar::F4::from4(a), scalar::F4::from4(b));
            same("add", a, f(sa + sb), (pa + pb).0);
            same("sub", a, f(sa - sb), (pa - pb).0);
            same("mul", a, f(sa * sb), (pa * pb).0);
            same("min", a, f(sa.min(sb)), pa.min(pb).0);
            same("max", a, f(sa.max(sb)), pa.max(pb).0);
            same("sum3_x", a, f(sa.sum3_x()), pa.sum3_x().0);
            same(
                "shuffle",
                a,
                f(sse2::F4::shuffle::<0b01_11_10_00>(sa, sb)),
                scalar::F4::shuffle::<0b01_11_10_00>(pa, pb).0,
            );
            let st = sse2::F4::transpose([sa, sb, sb, sa]);
            let pt = scalar::F4::transpose([pa, pb, pb, pa]);
            for r in 0..4 {
                same("transpose", a, f(st[r]), pt[r].0);
            }
            same("sum3", a, [sa.sum3(); 4], [pa.sum3(); 4]);
            same("sum4", a, [sa.sum4(); 4], [pa.sum4(); 4]);
            assert_eq!(sa.less(b[1]).xyzw(), pa.less(b[1]).xyzw(), "less {a:?}");
            assert_eq!(sa.trunc().xyzw(), pa.trunc().xyzw(), "trunc {a:?}");
            assert_eq!(sa.to_bits().xyzw(), pa.to_bits().xyzw(), "to_bits {a:?}");
            let root = a.map(f32::abs);
            let finite = root.map(|v| if v.is_finite() && v != 0.0 { v } else { 1.0 });
            same(
                "sqrt",
                root,
                f(sse2::F4::from4(finite).sqrt()),
                scalar::F4::from4(finite).sqrt().0,
            );
            for &x in &a {
                let (s1, p1) = (sse2::sqrt1(x), scalar::sqrt1(x));
                assert_eq!(s1.to_bits(), p1.to_bits(), "sqrt1({x:e})");
                assert_eq!(sse2::trunc1(x), scalar::trunc1(x), "trunc1({x:e})");
            }
            assert_eq!(
                sse2::in_split_range(sa),
                scalar::in_split_range(pa),
                "in_split_range {a:?}"
            );
            if scalar::in_split_range(pa) {
                let (sc, sf) = sse2::split_in_range(sa);
                let (pc, pf) = scalar::split_in_range(pa);
                assert_eq!(sc.xyzw(), pc.xyzw(), "split cells {a:?}");
                same("split offsets", a, f(sf), pf.0);
            }
            // Integer lanes from the bits.
            let (si, pi) = (sa.to_bits(), pa.to_bits());
            let (sj, pj) = (sb.to_bits(), pb.to_bits());
            let s = (k % 32) as u32;
            assert_eq!((si + sj).xyzw(), (pi + pj).xyzw());
            assert_eq!((si - sj).xyzw(), (pi - pj).xyzw());
            assert_eq!(si.and(sj).xyzw(), pi.and(pj).xyzw());
            assert_eq!(si.xor_lanes(), pi.xor_lanes());
            assert_eq!(si.greater(b[0].to_bits() as i32).xyzw(), {
                pi.greater(b[0].to_bits() as i32).xyzw()
            });
            assert_eq!(si.floor_div_pow2(s).xyzw(), pi.floor_div_pow2(s).xyzw());
            assert_eq!(si.mod_pow2(s).xyzw(), pi.mod_pow2(s).xyzw());
            assert_eq!(si.shl::<23>().xyzw(), pi.shl::<23>().xyzw());
            same("to_f32", a, f(si.to_f32()), pi.to_f32().0);
            same("bits_to_f32", a, f(si.bits_to_f32()), pi.bits_to_f32().0);
            assert_eq!(
                sse2::I4::bit_masks(s).xyzw(),
                scalar::I4::bit_masks(s).xyzw()
            );
            assert_eq!(sse2::I4::splat(s).xyzw(), scalar::I4::splat(s).xyzw());
        }
    }
}
