//! KTX2 files from `Bake::ktx2_dir`, loaded by Bevy's asset server and its `ktx2` loader.
//!
//! Two of the loader's defaults do not fit a mask, and [`NoiseMasks::load`] sets them:
//!
//! - `is_srgb` is on by default, and Bevy refuses an `R8_UNORM` or `R8G8_UNORM` file under it
//!   (it would need transcoding). A mask holds ranks, not colours: it loads linear.
//! - A file with one layer (a 2D mask) loads with a `D2` view, since Bevy's loader treats a
//!   KTX2 `layerCount` of 1 like 0 (not an array). The WGSL library reads masks as
//!   `texture_2d_array`, so the plugin gives every image loaded through [`NoiseMasks`] a
//!   `D2Array` view in `PostUpdate` of the frame it arrives, before the render world extracts it.
//!
//! The sampler is nearest, as for [`mask_image`](crate::mask_image).

use bevy::asset::{AssetId, AssetPath, AssetServer, Assets, Handle};
use bevy::ecs::prelude::*;
use bevy::ecs::system::SystemParam;
use bevy::image::{Image, ImageLoaderSettings, ImageSampler};

/// Images loaded through [`NoiseMasks`] that have not arrived yet.
#[derive(Resource, Default)]
pub(crate) struct PendingMasks(Vec<AssetId<Image>>);

/// Loads baked masks from KTX2 files: `masks.load("noise/stbn.ktx2")`.
#[derive(SystemParam)]
pub struct NoiseMasks<'w> {
    server: Res<'w, AssetServer>,
    pending: ResMut<'w, PendingMasks>,
}

impl NoiseMasks<'_> {
    /// Starts loading the mask at `path` (relative to the asset folder, as any asset), linear,
    /// sampled nearest, with a `D2Array` view once loaded.
    pub fn load<'a>(&mut self, path: impl Into<AssetPath<'a>>) -> Handle<Image> {
        let handle = self
            .server
            .load_builder()
            .with_settings(|s: &mut ImageLoaderSettings| {
                s.is_srgb = false;
                s.sampler = ImageSampler::nearest();
            })
            .load(path.into());
        self.pending.0.push(handle.id());
        handle
    }
}

/// Gives each mask that has arrived its `D2Array` view.
pub(crate) fn give_array_views(
    mut pending: ResMut<PendingMasks>,
    mut images: ResMut<Assets<Image>>,
    server: Res<AssetServer>,
) {
    pending.0.retain(|&id| {
        if let Some(mut image) = images.get_mut(id) {
            crate::image::set_array_view(&mut image);
            return false;
        }
        // A failed load is the asset server's to report; stop waiting for it.
        !server.load_state(id).is_failed()
    });
}
