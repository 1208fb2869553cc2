//! Texel types a mask can hold, read from little-endian bytes.
//!
//! Baked data is little-endian on disk and in the binary. Reads go through `from_le_bytes`, which
//! is a plain load on little-endian targets and a byte swap on big-endian ones, so a mask reads
//! the same values on every target.

/// A texel type: scalar `u8`, `u16`, `f32`, or 2–4 channel vectors of them.
pub trait Texel: Copy {
    /// Bytes per texel.
    const BYTES: usize;
    /// Channels per texel.
    const CHANNELS: usize;
    /// Reads texel `i` of a little-endian byte slice.
    fn read(bytes: &[u8], i: usize) -> Self;
    /// Channel `c` normalised to `[0, 1)`: unorm `v / 2^bits`, floats as stored.
    fn unit(self, c: usize) -> f32;
    /// Factor from [`unit`](Self::unit) to the `[0, 1]` encoding of unit vectors
    /// (`0.5 + 0.5·v`, stored as `round(·(2^bits − 1))` in unorm formats): `2^bits / (2^bits − 1)`.
    const SIGNED_SCALE: f32 = 1.0;
}

impl Texel for u8 {
    const SIGNED_SCALE: f32 = 256.0 / 255.0;
    const BYTES: usize = 1;
    const CHANNELS: usize = 1;
    #[inline(always)]
    fn read(bytes: &[u8], i: usize) -> Self {
        bytes[i]
    }
    #[inline(always)]
    fn unit(self, _: usize) -> f32 {
        self as f32 * (1.0 / 256.0)
    }
}

impl Texel for u16 {
    const SIGNED_SCALE: f32 = 65536.0 / 65535.0;
    const BYTES: usize = 2;
    const CHANNELS: usize = 1;
    #[inline(always)]
    fn read(bytes: &[u8], i: usize) -> Self {
        u16::from_le_bytes([bytes[2 * i], bytes[2 * i + 1]])
    }
    #[inline(always)]
    fn unit(self, _: usize) -> f32 {
        self as f32 * (1.0 / 65536.0)
    }
}

impl Texel for f32 {
    const BYTES: usize = 4;
    const CHANNELS: usize = 1;
    #[inline(always)]
    fn read(bytes: &[u8], i: usize) -> Self {
        let b = 4 * i;
        f32::from_le_bytes([bytes[b], bytes[b + 1], bytes[b + 2], bytes[b + 3]])
    }
    #[inline(always)]
    fn unit(self, _: usize) -> f32 {
        self
    }
}

impl<T: Texel, const N: usize> Texel for [T; N] {
    const SIGNED_SCALE: f32 = T::SIGNED_SCALE;
    const BYTES: usize = T::BYTES * N;
    const CHANNELS: usize = N;
    #[inline(always)]
    fn read(bytes: &[u8], i: usize) -> Self {
        core::array::from_fn(|c| T::read(bytes, i * N + c))
    }
    #[inline(always)]
    fn unit(self, c: usize) -> f32 {
        self[c % N].unit(0)
    }
}
