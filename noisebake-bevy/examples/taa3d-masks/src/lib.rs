//! The masks of `noisebake-bevy`'s `taa3d` example, baked from `noise.toml` by `build.rs`
//! through the cache, as a game bakes its own: `STBN`, `FAST_EMA` and `FAST_TAA`, each a
//! `Mask3<u8, 64, 64, 64>`.
#![no_std]

noisebake::include_textures!();
