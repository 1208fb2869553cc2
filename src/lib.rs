//! # noisebake
//!
//! High-quality noise baked into the binary at build time. This facade re-exports the `no_std`
//! runtime ([`noise_runtime`]) and the `noise_texture!` macro.
#![no_std]

pub use noise_runtime::*;
