//! # build-assets
//!
//! The generator side of noisebake: the spec, void and cluster in N-D, baselines, the cache,
//! exports and analysis, and the `noisebake` command-line tool. Everything here is a pure
//! function of the spec: same spec, same bytes, on any machine and thread count.

pub mod baselines;
pub mod fast;
pub mod generate;
pub mod points;
pub mod rng;
pub mod spec;
pub mod texture;
pub mod vac;

pub use generate::{ALGORITHM_VERSION, generate};
pub use spec::{SpecError, TextureSpec};
pub use texture::Texture;
pub mod analysis;
pub mod bake;
pub mod cache;
pub mod codegen;
pub mod export;
pub mod report;

pub use bake::{Bake, BakeError, bake};
