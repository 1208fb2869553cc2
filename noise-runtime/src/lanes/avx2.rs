//! Eight lanes in one AVX2 register, for the batch forms of gradient noise
//! ([`stochastic::batch`](crate::stochastic)) on x86_64: whether the CPU has AVX2 (asked once
//! at run time, since the x86_64 baseline is SSE2), and the few lane operations that LLVM
//! does not make well by itself from the batch kernels' plain loops over `[f32; 8]`: a
//! 16-entry table read, a 64-bit product's middle bits, one step of the estimators' corner
//! choice, and a lane mask's sign bits.
//!
//! The kernels themselves are ordinary Rust over eight-element arrays, compiled with
//! `#[target_feature(enable = "avx2")]`: LLVM turns each loop over the lanes into one AVX2
//! instruction per step. Each lane runs, operation for operation, the IEEE arithmetic of the
//! single-point form, so the batch forms return the same bits (the tests compare them).
//!
//! `unsafe` here: reading the OS's register-state mask (`xgetbv`, whose intrinsic requires
//! the `xsave` feature), and calling AVX2 intrinsics from the lane operations, which take an
//! [`Avx2`] token that only exists once the CPU said yes.

use core::arch::x86_64::{
    __cpuid, __cpuid_count, __m256, __m256i, _mm256_andnot_si256, _mm256_blend_epi32,
    _mm256_blendv_epi8, _mm256_blendv_ps, _mm256_castsi256_ps, _mm256_movemask_ps,
    _mm256_mul_epu32, _mm256_permutevar8x32_ps, _mm256_slli_epi32, _mm256_slli_epi64,
    _mm256_srai_epi32, _mm256_srli_epi64, _mm256_sub_epi32, _xgetbv,
};
use core::mem::transmute;
use core::sync::atomic::{AtomicU8, Ordering};

use super::{F8, Lanes8, U8};

/// 0: not asked yet; 1: no AVX2; 2: AVX2.
static AVX2: AtomicU8 = AtomicU8::new(0);

/// Whether this CPU runs AVX2 instructions and the OS saves their registers: CPUID leaf 7
/// (AVX2), leaf 1 (AVX, OSXSAVE) and `XCR0` (SSE and AVX state enabled). Asked once; later
/// calls read the cached answer (a relaxed atomic: every thread computes the same answer).
#[inline]
pub(crate) fn avx2() -> bool {
    match AVX2.load(Ordering::Relaxed) {
        0 => {
            let yes = detect();
            AVX2.store(1 + yes as u8, Ordering::Relaxed);
            yes
        }
        v => v == 2,
    }
}

#[cold]
#[allow(unused_unsafe)] // `__cpuid` is safe on newer toolchains, unsafe on older ones.
fn detect() -> bool {
    // SAFETY: CPUID exists on every x86_64 processor.
    let (max, leaf1) = unsafe { (__cpuid(0).eax, __cpuid(1)) };
    let (avx, osxsave) = (leaf1.ecx >> 28 & 1 == 1, leaf1.ecx >> 27 & 1 == 1);
    if max < 7 || !avx || !osxsave {
        return false;
    }
    // SAFETY: OSXSAVE set means the OS enabled XGETBV.
    let xcr0 = unsafe { xcr0() };
    // SAFETY: leaf 7 exists (max ≥ 7).
    let leaf7 = unsafe { __cpuid_count(7, 0) };
    xcr0 & 0b110 == 0b110 && leaf7.ebx >> 5 & 1 == 1
}

#[target_feature(enable = "xsave")]
fn xcr0() -> u64 {
    // SAFETY: the caller checked OSXSAVE; the intrinsic only reads XCR0.
    unsafe { _xgetbv(0) }
}

/// Proof that this CPU runs AVX2: made only by [`Avx2::detect`], and required by the lane
/// operations below, which are plain functions (so they inline into the batch kernels'
/// loops) whose intrinsics would be undefined behaviour on a CPU without AVX2.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx2(());

impl Avx2 {
    /// `Some` when [`avx2`] says this CPU runs AVX2.
    #[inline]
    pub(crate) fn detect() -> Option<Avx2> {
        avx2().then_some(Avx2(()))
    }
}

/// The AVX2 forms: each a few instructions where LLVM, left to the plain loops, read or
/// assembled the lanes one by one.
impl Lanes8 for Avx2 {
    /// `table[j]` per lane for `j < 16` (higher bits of `j` are ignored): two `vpermps` over
    /// the table's halves and a blend on bit 3. A gradient table read for eight corners in
    /// three instructions, where LLVM would read it lane by lane.
    #[inline(always)]
    fn lookup16(self, table: &[F8; 2], j: U8) -> F8 {
        // SAFETY: `self` exists only on a CPU with AVX2 (`Avx2::detect`); the transmutes are
        // 32 bytes to 32 bytes, every bit pattern valid in both types.
        unsafe {
            let j = transmute::<U8, __m256i>(j);
            let lo = _mm256_permutevar8x32_ps(transmute::<F8, __m256>(table[0]), j);
            let hi = _mm256_permutevar8x32_ps(transmute::<F8, __m256>(table[1]), j);
            // The blend takes `hi` where the sign bit of its mask is set: bit 3 of `j`.
            let bit3 = _mm256_castsi256_ps(_mm256_slli_epi32::<28>(j));
            transmute::<__m256, F8>(_mm256_blendv_ps(lo, hi, bit3))
        }
    }

    /// The sign bits of the lanes as an integer (bit `i` from lane `i`): one `vmovmskps`,
    /// where LLVM assembled the mask lane by lane.
    #[inline(always)]
    fn sign_bits(self, v: U8) -> u32 {
        // SAFETY: as in `lookup16`.
        unsafe { _mm256_movemask_ps(_mm256_castsi256_ps(transmute::<U8, __m256i>(v))) as u32 }
    }

    /// One decision of the estimators' corner choice on every lane (`Narrowing::upper_fixed`
    /// with the cut given): all ones where `r < cut` (the upper side, of length `cut`), and
    /// there `l ← cut`; elsewhere `r ← r − cut` and `l ← l − cut`. Written out because LLVM
    /// split these few steps into half-register pieces. `r` and `cut` must differ by less than
    /// 2^31 (they are below 2^24).
    #[inline(always)]
    fn narrow(self, r: &mut U8, l: &mut U8, cut: U8) -> U8 {
        // SAFETY: as in `lookup16`.
        unsafe {
            let (rv, lv) = (transmute::<U8, __m256i>(*r), transmute::<U8, __m256i>(*l));
            let c = transmute::<U8, __m256i>(cut);
            let up = _mm256_srai_epi32::<31>(_mm256_sub_epi32(rv, c));
            *r = transmute::<__m256i, U8>(_mm256_sub_epi32(rv, _mm256_andnot_si256(up, c)));
            let rest = _mm256_sub_epi32(lv, c);
            *l = transmute::<__m256i, U8>(_mm256_blendv_epi8(rest, c, up));
            transmute::<__m256i, U8>(up)
        }
    }

    /// `((l · t) >> 23) as u32` per lane, the product taken in 64 bits: the fixed-point cut
    /// of the estimators' corner choice (`Narrowing::upper_fixed`). Two `vpmuludq` (even
    /// lanes, then odd lanes moved down) and a blend, where LLVM widened each half to four
    /// 64-bit lanes first.
    #[inline(always)]
    fn mul_shr23(self, l: U8, t: U8) -> U8 {
        // SAFETY: as in `lookup16`.
        unsafe {
            let (l, t) = (transmute::<U8, __m256i>(l), transmute::<U8, __m256i>(t));
            let even = _mm256_srli_epi64::<23>(_mm256_mul_epu32(l, t));
            // The odd lanes' products shifted left by 32 − 23: bits 23..55 land in the high
            // half of each 64-bit lane, where the blend takes them.
            let odd = _mm256_slli_epi64::<9>(_mm256_mul_epu32(
                _mm256_srli_epi64::<32>(l),
                _mm256_srli_epi64::<32>(t),
            ));
            transmute::<__m256i, U8>(_mm256_blend_epi32::<0b1010_1010>(even, odd))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::scalar::Portable8;
    use super::*;

    /// Each AVX2 operation against the portable loops, which state the definitions.
    #[test]
    fn avx2_lane_operations_match_the_portable_ones() {
        let Some(cpu) = Avx2::detect() else {
            std::eprintln!(
                "SKIPPED: this CPU has no AVX2; the AVX2 lane operations were not tested \
                 (the portable ones, which every other CPU runs, were)"
            );
            return;
        };
        let table: [F8; 2] = [
            core::array::from_fn(|k| k as f32 * 1.5),
            core::array::from_fn(|k| -(k as f32) - 100.0),
        ];
        let mut s = 0x1357_9bdf_2468_ace0u64;
        let mut bits = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 32) as u32
        };
        let p = Portable8;
        for _ in 0..10_000 {
            let j: U8 = core::array::from_fn(|_| bits());
            let l: U8 = core::array::from_fn(|_| bits());
            let t: U8 = core::array::from_fn(|_| bits());
            assert_eq!(cpu.lookup16(&table, j), p.lookup16(&table, j), "j {j:?}");
            assert_eq!(cpu.mul_shr23(l, t), p.mul_shr23(l, t));
            assert_eq!(cpu.sign_bits(j), p.sign_bits(j));
            // One decision: r and the cut below 2^24, l above the cut or not.
            let r: U8 = core::array::from_fn(|i| l[i] >> 8);
            let len: U8 = core::array::from_fn(|i| t[i] >> 8);
            let cut: U8 = core::array::from_fn(|i| j[i] >> 8);
            let (mut r1, mut l1, mut r2, mut l2) = (r, len, r, len);
            assert_eq!(
                cpu.narrow(&mut r1, &mut l1, cut),
                p.narrow(&mut r2, &mut l2, cut)
            );
            assert_eq!((r1, l1), (r2, l2));
        }
    }
}
