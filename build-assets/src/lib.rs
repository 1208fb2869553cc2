//! # build-assets
//!
//! The part of noisebake that runs inside a game's build: a spec (from `noise.toml` or the
//! `noise_texture!` macro) is validated ([`spec`]), generated ([`generate()`]: void and cluster
//! in N dimensions, FAST, baselines), stored in a content-addressed [`cache`] and turned into
//! Rust items that embed the bytes ([`codegen`]). [`bake()`] does all of it for a build script.
//!
//! Everything here is a pure function of the spec: the same spec gives the same bytes on any
//! machine, thread count and build profile. The command-line tool, reports, analysis and plots
//! live in the `noisebake-cli` crate, so a game's build compiles none of them; see
//! `ARCHITECTURE.md` for the crates and what may depend on what.
#![cfg_attr(docsrs, feature(doc_cfg))]

pub mod atomic;
pub mod bake;
pub mod cache;
pub mod codegen;
mod detmath;
pub mod encoding;
pub mod error;
pub mod export;
pub mod generate;
pub mod spec;
pub mod texture;

pub use bake::{Bake, BakeError, bake, bake_or_exit};
pub use error::{Error, Warning};
pub use generate::{ALGORITHM_VERSION, bake_texture, generate};
pub use spec::{SpecError, TextureSpec};
pub use texture::{Baked, Texture};
