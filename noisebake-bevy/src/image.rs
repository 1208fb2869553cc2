//! A baked mask as a Bevy [`Image`]: a 2D array texture in the mask's own GPU format.
//!
//! The layout is the runtime's [`GpuTexture`]: `width × height` per layer, one layer for a 2D
//! mask, one per time slice for a 3D mask, layer `z + D·w` for a 4D one; 3-channel masks are
//! padded to 4 ([`GpuFormat::pad`](noise_runtime::GpuFormat)). The view is always
//! `D2Array`, also for one layer, because the WGSL library's loads take `texture_2d_array`.

use bevy::asset::RenderAssetUsages;
use bevy::image::{Image, ImageSampler};
use bevy::render::render_resource::{
    Extent3d, TextureDimension, TextureFormat, TextureViewDescriptor, TextureViewDimension,
};
use noise_runtime::{GpuFormat, GpuTexture, Mask2, Mask3, Mask4, SamplerTile, Texel};

/// A mask baked into the binary (`Mask2`, `Mask3`, `Mask4` statics from `build.rs` or
/// `noise_texture!`, and `SamplerTile`s through their key mask), as the GPU sees it.
pub trait BakedMask {
    /// The texture's size, layers and format.
    fn gpu_texture(&self) -> GpuTexture;
    /// The bytes to upload: the baked bytes, 3-channel texels padded to 4.
    fn gpu_data(&self) -> Vec<u8>;
}

macro_rules! baked_mask {
    ($name:ident, $($d:ident),+) => {
        impl<T: Texel, $(const $d: u32),+> BakedMask for $name<T, $($d),+> {
            fn gpu_texture(&self) -> GpuTexture {
                $name::gpu_texture(self)
            }
            fn gpu_data(&self) -> Vec<u8> {
                match self.gpu_bytes() {
                    Some(bytes) => bytes.to_vec(),
                    None => {
                        let mut out = vec![0; self.gpu_texture().byte_len()];
                        self.write_gpu_bytes(&mut out)
                            .expect("the buffer has the texture's byte length");
                        out
                    }
                }
            }
        }
    };
}
baked_mask!(Mask2, W, H);
baked_mask!(Mask3, W, H, D);
baked_mask!(Mask4, W, H, D, E);

/// A sampler tile is its key mask on the GPU (`R16Uint`, one layer per sample dimension), as
/// WGSL's `nb_sampler_tile(keys, pixel, frame, i, d, spp, sobol_pairs)` reads it.
impl<const W: u32, const H: u32, const SPP: u32, const D: u32> BakedMask
    for SamplerTile<W, H, SPP, D>
{
    fn gpu_texture(&self) -> GpuTexture {
        self.keys().gpu_texture()
    }
    fn gpu_data(&self) -> Vec<u8> {
        BakedMask::gpu_data(self.keys())
    }
}

/// The Bevy (wgpu) texture format of a runtime [`GpuFormat`].
pub fn texture_format(format: GpuFormat) -> TextureFormat {
    match format {
        GpuFormat::R8Unorm => TextureFormat::R8Unorm,
        GpuFormat::Rg8Unorm => TextureFormat::Rg8Unorm,
        GpuFormat::Rgba8Unorm => TextureFormat::Rgba8Unorm,
        GpuFormat::R16Uint => TextureFormat::R16Uint,
        GpuFormat::Rg16Uint => TextureFormat::Rg16Uint,
        GpuFormat::Rgba16Uint => TextureFormat::Rgba16Uint,
        GpuFormat::R32Float => TextureFormat::R32Float,
        GpuFormat::Rg32Float => TextureFormat::Rg32Float,
        GpuFormat::Rgba32Float => TextureFormat::Rgba32Float,
    }
}

/// The mask as an [`Image`]: a `D2Array` texture of the mask's format and layers, sampled
/// nearest (a mask is read texel by texel with `textureLoad`; filtering would mix ranks), and
/// kept only in the render world once uploaded.
///
/// ```no_run
/// # use bevy::prelude::*;
/// # static STBN: noise_runtime::Mask3<u8, 64, 64, 32> = noise_runtime::Mask3::new(&[0; 64 * 64 * 32]);
/// fn setup(mut images: ResMut<Assets<Image>>) {
///     let stbn: Handle<Image> = images.add(noisebake_bevy::mask_image(&STBN));
/// }
/// ```
pub fn mask_image(mask: &(impl BakedMask + ?Sized)) -> Image {
    let tex = mask.gpu_texture();
    let mut image = Image::new(
        Extent3d {
            width: tex.width,
            height: tex.height,
            depth_or_array_layers: tex.layers,
        },
        TextureDimension::D2,
        mask.gpu_data(),
        texture_format(tex.format),
        RenderAssetUsages::RENDER_WORLD,
    );
    image.sampler = ImageSampler::nearest();
    set_array_view(&mut image);
    image
}

/// Gives `image` a `D2Array` view, whatever its layer count.
pub(crate) fn set_array_view(image: &mut Image) {
    image.texture_view_descriptor = Some(TextureViewDescriptor {
        dimension: Some(TextureViewDimension::D2Array),
        ..Default::default()
    });
}
