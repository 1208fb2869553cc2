//! # build-assets
//!
//! The generator side of noisebake: the spec, void and cluster in N-D, baselines, the cache,
//! exports and analysis, and the `noisebake` command-line tool. Everything here is a pure
//! function of the spec: same spec, same bytes, on any machine and thread count.

pub mod rng;
pub mod vac;
pub mod spec;
pub mod baselines;
pub mod generate;
pub mod texture;

pub use generate::{ALGORITHM_VERSION, generate};
pub use spec::{SpecError, TextureSpec};
pub use texture::Texture;
pub mod export;
pub mod analysis;
