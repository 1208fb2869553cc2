//! # noise-runtime
//!
//! The part of noisebake a game links: `#![no_std]`, no dependencies, no `unsafe`.
//!
//! - [`Mask2`], [`Mask3`], [`Mask4`]: typed, `const`-constructible views over baked bytes, read
//!   toroidally with any integer coordinates; [`Mask3::get_k`] gives the k-th independent value
//!   of a pixel through R2 offsets (STBN §5.2, FAST §6).
//! - [`ldg`]: low-discrepancy grids computed on the fly (R2, plus-shaped, IGN, Bayer), exact for
//!   huge coordinates, optionally animated per frame.
//! - [`sequence`]: the R2 and golden-ratio sequences in 64-bit fixed point.
//! - [`warp`]: from uniform numbers to disks, spheres and hemispheres; safe at 0 and 1.
//!
//! Nothing here panics or returns NaN for any finite input.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod cnj;
pub mod coord;
pub mod ldg;
pub mod mask;
pub mod math;
pub mod sequence;
pub mod stochastic;
pub mod texel;
pub mod warp;

pub use coord::Coord;
pub use mask::{Mask2, Mask3, Mask4};
pub use texel::Texel;
