//! Typed views of baked masks: dims are const generics, so every wrap is resolved at compile time
//! (a bit mask for power-of-two sizes) and a lookup is one multiply-add and one load.
//!
//! Layout: x fastest, then y, then further axes; texels little-endian (see [`Texel`]).

use crate::coord::Coord;
use crate::sequence::{r2_point, scale};
use crate::texel::{GpuFormat, Texel};
use core::marker::PhantomData;

/// Why bytes cannot back a view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SizeMismatch {
    /// Bytes the dims and texel type need.
    pub expected: usize,
    /// Bytes given.
    pub actual: usize,
}

macro_rules! mask {
    (
        $(#[$doc:meta])*
        $name:ident, $n:literal, [$($d:ident),+], [$($c:ident),+], layers = $layers:expr
    ) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug)]
        pub struct $name<T: Texel, $(const $d: u32),+> {
            bytes: &'static [u8],
            _texel: PhantomData<T>,
        }

        impl<T: Texel, $(const $d: u32),+> $name<T, $($d),+> {
            /// Texels in the mask.
            pub const TEXELS: usize = 1 $(* $d as usize)+;
            /// Sizes, x first.
            pub const DIMS: [u32; $n] = [$($d),+];

            /// A view over `bytes`; fails to compile (in a `const`/`static`) or panics (at run
            /// time) when the length does not match the dims and texel type.
            pub const fn new(bytes: &'static [u8]) -> Self {
                assert!(bytes.len() == Self::TEXELS * T::BYTES, "mask bytes do not match its dims and texel type");
                $(assert!($d > 0, "mask dims must be positive");)+
                Self { bytes, _texel: PhantomData }
            }

            /// A view over `bytes`, or the size mismatch.
            pub const fn try_new(bytes: &'static [u8]) -> Result<Self, SizeMismatch> {
                if bytes.len() != Self::TEXELS * T::BYTES $(|| $d == 0)+ {
                    return Err(SizeMismatch { expected: Self::TEXELS * T::BYTES, actual: bytes.len() });
                }
                Ok(Self { bytes, _texel: PhantomData })
            }

            /// The raw little-endian bytes.
            pub const fn bytes(&self) -> &'static [u8] {
                self.bytes
            }

            /// The mask as a GPU texture: a 2D array of `W × H` layers (see [`GpuTexture`]).
            pub const fn gpu_texture(&self) -> GpuTexture {
                let [w, h, ..] = Self::DIMS;
                GpuTexture {
                    width: w,
                    height: h,
                    layers: $layers,
                    format: GpuFormat::for_texel(T::BYTES / T::CHANNELS, T::CHANNELS),
                }
            }

            /// The bytes to upload as [`gpu_texture`](Self::gpu_texture), when they need no
            /// padding (every format but 3-channel vectors): the baked bytes themselves.
            pub fn gpu_bytes(&self) -> Option<&'static [u8]> {
                (T::CHANNELS != 3).then_some(self.bytes)
            }

            /// Writes the bytes to upload as [`gpu_texture`](Self::gpu_texture) into `out`,
            /// padding 3-channel texels to 4 (see [`GpuFormat::pad`]). `out` must be exactly
            /// [`GpuTexture::byte_len`] long.
            pub fn write_gpu_bytes(&self, out: &mut [u8]) -> Result<(), SizeMismatch> {
                write_gpu_bytes(self.bytes, self.gpu_texture(), T::CHANNELS, out)
            }

            #[inline(always)]
            fn index(&self, $($c: u32),+) -> usize {
                let mut i = 0usize;
                let mut stride = 1usize;
                $(
                    i += $c as usize * stride;
                    stride *= $d as usize;
                )+
                let _ = stride;
                i
            }

            /// The texel at the given coordinates, each wrapped toroidally onto its axis.
            #[must_use]
            #[inline(always)]
            pub fn get(&self, $($c: impl Coord),+) -> T {
                T::read(self.bytes, self.index($($c.wrap($d)),+))
            }

            /// Channel 0 of [`get`](Self::get) normalised to `[0, 1)`.
            #[must_use]
            #[inline(always)]
            pub fn get_unit(&self, $($c: impl Coord),+) -> f32 {
                self.get($($c),+).unit(0)
            }

            /// Channel `c` of a unit-vector texture (stored as `0.5 + 0.5·v`) decoded to `[-1, 1]`.
            #[must_use]
            #[inline(always)]
            pub fn get_signed(&self, $($c: impl Coord),+, channel: usize) -> f32 {
                let t = self.get($($c),+);
                (t.unit(channel) * T::SIGNED_SCALE * 2.0 - 1.0).clamp(-1.0, 1.0)
            }

            /// Whether the texel is "on" at coverage `p`: its value is below `p`. For a mask with
            /// a flat histogram the on fraction of every slice is `p` to within one texel.
            #[must_use]
            #[inline(always)]
            pub fn threshold(&self, $($c: impl Coord),+, p: f32) -> bool {
                self.get_unit($($c),+) < p
            }
        }
    };
}

mask!(
    /// A 2D mask: `get(x, y)`.
    Mask2, 2, [W, H], [x, y], layers = 1
);
mask!(
    /// A 3D mask over (x, y, t): spatiotemporal masks, one 2D slice per frame.
    Mask3, 3, [W, H, D], [x, y, t], layers = D
);
mask!(
    /// A 4D mask over (x, y, z, w), e.g. 2D×1D×1D or 2D×2D blue noise.
    Mask4, 4, [W, H, D, E], [x, y, z, w], layers = D * E
);

impl<T: Texel, const W: u32, const H: u32> Mask2<T, W, H> {
    /// The k-th independent value of pixel (x, y): the texel offset by the k-th R2 point scaled
    /// to the mask (STBN §5.2; FAST §6). `get_k(x, y, 0) == get(x, y)`.
    #[must_use]
    #[inline(always)]
    pub fn get_k(&self, x: impl Coord, y: impl Coord, k: u32) -> T {
        let (ox, oy) = r2_point(k);
        let xi = (x.wrap(W) + scale(ox, W)).wrap(W);
        let yi = (y.wrap(H) + scale(oy, H)).wrap(H);
        T::read(self.bytes, self.index(xi, yi))
    }

    /// Channel 0 of [`get_k`](Self::get_k) normalised to `[0, 1)`.
    #[must_use]
    #[inline(always)]
    pub fn get_k_unit(&self, x: impl Coord, y: impl Coord, k: u32) -> f32 {
        self.get_k(x, y, k).unit(0)
    }

    /// The k-th independent pair of values of a pixel: R2-offset reads `2k` and `2k + 1`
    /// (as [`Mask3::get_pair_unit`]).
    #[must_use]
    #[inline(always)]
    pub fn get_pair_unit(&self, x: impl Coord, y: impl Coord, k: u32) -> [f32; 2] {
        let k2 = k.wrapping_mul(2);
        [
            self.get_k_unit(x, y, k2),
            self.get_k_unit(x, y, k2.wrapping_add(1)),
        ]
    }
}

impl<T: Texel, const W: u32, const H: u32, const D: u32> Mask3<T, W, H, D> {
    /// The k-th independent value of pixel (x, y) in frame t: the texel offset spatially by the
    /// k-th R2 point scaled to the mask (STBN §5.2; FAST §6). `get_k(x, y, t, 0) == get(x, y, t)`.
    /// Exact for every `k < 2^32` (see [`sequence`](crate::sequence)).
    #[must_use]
    #[inline(always)]
    pub fn get_k(&self, x: impl Coord, y: impl Coord, t: impl Coord, k: u32) -> T {
        let (ox, oy) = r2_point(k);
        let xi = (x.wrap(W) + scale(ox, W)).wrap(W);
        let yi = (y.wrap(H) + scale(oy, H)).wrap(H);
        T::read(self.bytes, self.index(xi, yi, t.wrap(D)))
    }

    /// Channel 0 of [`get_k`](Self::get_k) normalised to `[0, 1)`.
    #[must_use]
    #[inline(always)]
    pub fn get_k_unit(&self, x: impl Coord, y: impl Coord, t: impl Coord, k: u32) -> f32 {
        self.get_k(x, y, t, k).unit(0)
    }

    /// The k-th independent *pair* of values of a pixel from a scalar mask: R2-offset reads
    /// `2k` and `2k + 1` (STBN §5.4: scalar masks feeding 2D warps such as
    /// [`warp::cosine_hemisphere`](crate::warp::cosine_hemisphere)).
    #[must_use]
    #[inline(always)]
    pub fn get_pair_unit(&self, x: impl Coord, y: impl Coord, t: impl Coord, k: u32) -> [f32; 2] {
        let k2 = k.wrapping_mul(2);
        [
            self.get_k_unit(x, y, t, k2),
            self.get_k_unit(x, y, t, k2.wrapping_add(1)),
        ]
    }
}

impl<T: Texel, const W: u32, const H: u32, const D: u32, const E: u32> Mask4<T, W, H, D, E> {
    /// The k-th independent value of a pixel, as [`Mask3::get_k`].
    #[must_use]
    #[inline(always)]
    pub fn get_k(&self, x: impl Coord, y: impl Coord, z: impl Coord, w: impl Coord, k: u32) -> T {
        let (ox, oy) = r2_point(k);
        let xi = (x.wrap(W) + scale(ox, W)).wrap(W);
        let yi = (y.wrap(H) + scale(oy, H)).wrap(H);
        T::read(self.bytes, self.index(xi, yi, z.wrap(D), w.wrap(E)))
    }

    /// Channel 0 of [`get_k`](Self::get_k) normalised to `[0, 1)`.
    #[must_use]
    #[inline(always)]
    pub fn get_k_unit(
        &self,
        x: impl Coord,
        y: impl Coord,
        z: impl Coord,
        w: impl Coord,
        k: u32,
    ) -> f32 {
        self.get_k(x, y, z, w, k).unit(0)
    }

    /// The k-th independent pair of values of a pixel: R2-offset reads `2k` and `2k + 1`
    /// (as [`Mask3::get_pair_unit`]).
    #[must_use]
    #[inline(always)]
    pub fn get_pair_unit(
        &self,
        x: impl Coord,
        y: impl Coord,
        z: impl Coord,
        w: impl Coord,
        k: u32,
    ) -> [f32; 2] {
        let k2 = k.wrapping_mul(2);
        [
            self.get_k_unit(x, y, z, w, k2),
            self.get_k_unit(x, y, z, w, k2.wrapping_add(1)),
        ]
    }
}

/// A mask as a GPU sees it: a 2D array texture of `layers` slices of `width × height` texels,
/// one mip level. A 2D mask is one layer; a 3D mask one layer per time slice; a 4D mask
/// `(x, y, z, w)` is flattened layer-major, layer `z + D·w` (the bytes' own order). In WGSL
/// bind it as `texture_2d_array<f32>` (unorm and float formats) or `texture_2d_array<u32>`
/// (`r16uint`…) and read it with `textureLoad`, as `noise-runtime/wgsl/noisebake.wgsl` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GpuTexture {
    /// Texels per row.
    pub width: u32,
    /// Rows per layer.
    pub height: u32,
    /// Array layers.
    pub layers: u32,
    /// The texture format (3-channel masks are padded to 4 channels).
    pub format: GpuFormat,
}

impl GpuTexture {
    /// Bytes of one row of the uploaded data (no row padding: wgpu's `Queue::write_texture`
    /// takes any row pitch).
    pub const fn bytes_per_row(&self) -> u32 {
        self.width * self.format.texel_bytes() as u32
    }

    /// Bytes of the whole uploaded texture.
    pub const fn byte_len(&self) -> usize {
        self.bytes_per_row() as usize * self.height as usize * self.layers as usize
    }
}

fn write_gpu_bytes(
    bytes: &[u8],
    tex: GpuTexture,
    channels: usize,
    out: &mut [u8],
) -> Result<(), SizeMismatch> {
    if out.len() != tex.byte_len() {
        return Err(SizeMismatch {
            expected: tex.byte_len(),
            actual: out.len(),
        });
    }
    let cb = tex.format.channel_bytes();
    let (src_texel, dst_texel) = (cb * channels, tex.format.texel_bytes());
    for (src, dst) in bytes
        .chunks_exact(src_texel)
        .zip(out.chunks_exact_mut(dst_texel))
    {
        dst[..src_texel].copy_from_slice(src);
        for pad in dst[src_texel..].chunks_exact_mut(cb) {
            pad.copy_from_slice(tex.format.pad());
        }
    }
    Ok(())
}

#[doc(hidden)]
/// `bytes[offset..offset + len]` in a `const` context: the texel data of an included file that
/// carries a header (cache entries). Panics at compile time when out of range.
pub const fn payload(bytes: &'static [u8], offset: usize, len: usize) -> &'static [u8] {
    bytes.split_at(offset).1.split_at(len).0
}

/// `include_bytes!` into a 16-byte-aligned static, as a `&'static [u8]` (what
/// `include_bytes_aligned` does; kept here so the runtime stays dependency-free). Used by
/// generated code; alignment lets vector loads of `u16`/`f32` texels take the fast path.
#[doc(hidden)]
#[macro_export]
macro_rules! include_aligned {
    ($path:expr) => {{
        #[repr(C, align(16))]
        struct Aligned<B: ?Sized>(B);
        static ALIGNED: &Aligned<[u8]> = &Aligned(*include_bytes!($path));
        &ALIGNED.0
    }};
}
