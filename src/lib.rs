//! # noisebake
//!
//! High-quality noise baked into the binary at build time. This facade re-exports the `no_std`
//! runtime ([`noise_runtime`]) and the `noise_texture!` macro.
//!
//! Two ways in, one spec and one cache:
//! - a `noise.toml` baked by `build_assets::bake("noise.toml")` in `build.rs`, then
//!   `noisebake::include_textures!();` in the crate;
//! - inline: `noisebake::noise_texture!(pub STBN = stbn { dims: [64, 64, 16], seed: 7, format: u16 });`
#![no_std]

#[cfg(feature = "macros")]
pub use noise_macros::noise_texture;
pub use noise_runtime::*;

/// Includes the textures `build_assets::bake()` generated in this crate's build script: one
/// `pub static` per texture, named as in the spec.
#[macro_export]
macro_rules! include_textures {
    () => {
        include!(concat!(env!("OUT_DIR"), "/noisebake_textures.rs"));
    };
}
