//! noisebake in Bevy: the WGSL library as a shader import, baked masks as array textures.
//!
//! A Bevy game writes three lines: the plugin, the mask as an image, and the import in its
//! material's shader. The crate's README, below, has them as code its doc tests compile (and
//! `noisebake-gpu`'s tests validate its WGSL against the library); the sections after it say
//! what the plugin does.
//!
#![doc = include_str!("../README.md")]
//!
//! # What the plugin does
//!
//! - **The shader library.** [`NoisebakePlugin`] registers the runtime's WGSL
//!   (`noise_runtime::shaders::WGSL`) under the import path `noisebake`, so `#import
//!   noisebake::{nb_mask_unit, nb_ign_frame, nb_r2_frame}` works in any material or compute
//!   shader. Each function computes what the runtime function of the same name computes on the
//!   CPU; the tests run them in Bevy's renderer and compare (bit for bit on the integer paths,
//!   IGN within 2⁻²³; see `noise_runtime::shaders` for the table).
//! - **The frame index.** Masks are indexed by frame. The plugin uses Bevy's own counter,
//!   [`FrameCount`](bevy::diagnostic::FrameCount), which Bevy's renderer writes into the
//!   `globals` uniform (`globals.frame_count`) that every material's view bindings carry; the
//!   plugin adds `FrameCountPlugin` when the app lacks it. A mask wraps the frame onto its
//!   depth, so any count works. To pause or replay the noise, set `FrameCount`.
//! - **Masks as images.** [`mask_image`] turns a baked static into an [`Image`](bevy::image::Image)
//!   with no file: a `D2Array` texture in the mask's format (`r8unorm`, `r16uint`, `r32float`,
//!   2 and 4 channels; 3 padded to 4), one layer per frame, sampled nearest. A sampler tile
//!   (`SamplerTile`) becomes its key mask, `r16uint` with a layer per sample dimension, which
//!   WGSL's `nb_sampler_tile(keys, pixel, frame, i, d, spp, sobol_pairs)` reads, `sobol_pairs`
//!   being the tile's (`SamplerTile::sobol_pairs`, from the spec's `sample_space`).
//! - **Masks as KTX2 files.** `Bake::ktx2_dir` writes the same textures as KTX2.
//!   [`NoiseMasks`] (a system parameter: `masks.load(path)`) loads one through Bevy's asset
//!   server and `ktx2` loader, with the
//!   settings a mask needs (linear, nearest) and a `D2Array` view also for one layer (see
//!   [`load`](crate::NoiseMasks) for why Bevy's defaults do not fit).
//!
//! # Bind it
//!
//! In WGSL a unorm or float mask is `texture_2d_array<f32>`, a 16-bit one
//! `texture_2d_array<u32>`; both are read with `textureLoad`, never sampled: `nb_mask_unit_u8`,
//! `nb_mask_unit_u16` and `nb_mask_unit_f32` give each kind's values as the CPU's `get_k`
//! does (`nb_mask_unit` is the first of a `u8` mask). In an `AsBindGroup` material that is
//! `#[texture(N, dimension = "2d_array", sample_type = "float", filterable = false)]` (and
//! `sample_type = "u_int"` for 16-bit masks).
//!
//! # Versions
//!
//! Built on Bevy 0.19, the newest release this workspace's toolchain (Rust 1.95) builds; the
//! crate's `rust-version` is Bevy's.

mod image;
mod load;
mod shader;

pub use image::{BakedMask, mask_image, texture_format};
pub use load::NoiseMasks;
pub use shader::{IMPORT_PATH, NOISEBAKE_SHADER, library, source};

use bevy::app::{App, Plugin, PostUpdate};
use bevy::asset::Assets;
use bevy::diagnostic::FrameCountPlugin;
use bevy::shader::Shader;

/// Registers the WGSL library as `#import noisebake::…`, makes sure the frame counter runs,
/// and gives masks loaded through [`NoiseMasks`] their array view.
///
/// Add it after `DefaultPlugins` (it needs the asset plugin; the shader library needs the
/// renderer, and is skipped without one).
pub struct NoisebakePlugin;

impl Plugin for NoisebakePlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<FrameCountPlugin>() {
            app.add_plugins(FrameCountPlugin);
        }
        app.init_resource::<load::PendingMasks>()
            .add_systems(PostUpdate, load::give_array_views);
    }

    fn finish(&self, app: &mut App) {
        // `Assets<Shader>` is created by the render plugin, which may be added after this one.
        if let Some(mut shaders) = app.world_mut().get_resource_mut::<Assets<Shader>>() {
            shaders
                .insert(&NOISEBAKE_SHADER, library())
                .expect("a uuid handle is always valid");
        }
    }
}
