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

/// How a GPU holds a texel type: the texture format a mask is uploaded as (WebGPU's and
/// Vulkan's names) and whether its texels need padding first.
///
/// Unorm bytes load as `v / 255` on a GPU, where [`Texel::unit`] gives `v / 256`; the WGSL
/// library's `nb_unorm8_unit` converts. 16-bit masks use `R16_UINT` rather than `R16_UNORM`:
/// the unorm form is a native-only wgpu feature and absent on the web, and the integer load is
/// exact (`nb_u16_unit` divides by 65536 as the runtime does).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GpuFormat {
    /// One 8-bit unorm channel (`r8unorm`, `VK_FORMAT_R8_UNORM`).
    R8Unorm,
    /// Two 8-bit unorm channels (`rg8unorm`).
    Rg8Unorm,
    /// Four 8-bit unorm channels (`rgba8unorm`); 3-channel masks are padded with 255.
    Rgba8Unorm,
    /// One 16-bit unsigned integer channel (`r16uint`).
    R16Uint,
    /// Two 16-bit unsigned integer channels (`rg16uint`).
    Rg16Uint,
    /// Four 16-bit unsigned integer channels (`rgba16uint`); 3-channel masks are padded with 65535.
    Rgba16Uint,
    /// One 32-bit float channel (`r32float`).
    R32Float,
    /// Two 32-bit float channels (`rg32float`).
    Rg32Float,
    /// Four 32-bit float channels (`rgba32float`); 3-channel masks are padded with 1.0.
    Rgba32Float,
}

impl GpuFormat {
    /// The format for `channels` channels of a scalar type of `bytes` bytes (1, 2 or 4).
    pub const fn for_texel(bytes: usize, channels: usize) -> GpuFormat {
        match (bytes, channels) {
            (1, 1) => GpuFormat::R8Unorm,
            (1, 2) => GpuFormat::Rg8Unorm,
            (1, _) => GpuFormat::Rgba8Unorm,
            (2, 1) => GpuFormat::R16Uint,
            (2, 2) => GpuFormat::Rg16Uint,
            (2, _) => GpuFormat::Rgba16Uint,
            (_, 1) => GpuFormat::R32Float,
            (_, 2) => GpuFormat::Rg32Float,
            _ => GpuFormat::Rgba32Float,
        }
    }

    /// The WebGPU name (`GPUTextureFormat`), e.g. `"r8unorm"`.
    pub const fn name(self) -> &'static str {
        match self {
            GpuFormat::R8Unorm => "r8unorm",
            GpuFormat::Rg8Unorm => "rg8unorm",
            GpuFormat::Rgba8Unorm => "rgba8unorm",
            GpuFormat::R16Uint => "r16uint",
            GpuFormat::Rg16Uint => "rg16uint",
            GpuFormat::Rgba16Uint => "rgba16uint",
            GpuFormat::R32Float => "r32float",
            GpuFormat::Rg32Float => "rg32float",
            GpuFormat::Rgba32Float => "rgba32float",
        }
    }

    /// The `VkFormat` number (what a KTX2 header stores).
    pub const fn vk_format(self) -> u32 {
        match self {
            GpuFormat::R8Unorm => 9,
            GpuFormat::Rg8Unorm => 16,
            GpuFormat::Rgba8Unorm => 37,
            GpuFormat::R16Uint => 74,
            GpuFormat::Rg16Uint => 81,
            GpuFormat::Rgba16Uint => 95,
            GpuFormat::R32Float => 100,
            GpuFormat::Rg32Float => 103,
            GpuFormat::Rgba32Float => 109,
        }
    }

    /// Channels the GPU texel has (after padding).
    pub const fn channels(self) -> usize {
        match self {
            GpuFormat::R8Unorm | GpuFormat::R16Uint | GpuFormat::R32Float => 1,
            GpuFormat::Rg8Unorm | GpuFormat::Rg16Uint | GpuFormat::Rg32Float => 2,
            _ => 4,
        }
    }

    /// Bytes of one channel.
    pub const fn channel_bytes(self) -> usize {
        match self {
            GpuFormat::R8Unorm | GpuFormat::Rg8Unorm | GpuFormat::Rgba8Unorm => 1,
            GpuFormat::R16Uint | GpuFormat::Rg16Uint | GpuFormat::Rgba16Uint => 2,
            _ => 4,
        }
    }

    /// Bytes of one GPU texel.
    pub const fn texel_bytes(self) -> usize {
        self.channels() * self.channel_bytes()
    }

    /// The little-endian bytes of the padding channel: the channel's largest value (1.0 for
    /// unorm and float).
    pub const fn pad(self) -> &'static [u8] {
        match self.channel_bytes() {
            1 => &[0xff],
            2 => &[0xff, 0xff],
            _ => &[0x00, 0x00, 0x80, 0x3f],
        }
    }
}
