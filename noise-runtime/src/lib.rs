//! # noise-runtime
//!
//! The part of noisebake a game links: `#![no_std]`, no dependencies. Its SIMD lives in one
//! private lane layer with sibling backends, glam-style: SSE2 on x86_64 (its baseline), AVX2
//! for the batch forms when the CPU has it (asked at run time), and a portable scalar backend
//! everywhere else. Every kernel is written once on that layer, and every backend gives the
//! same bits; the feature `portable` forces the scalar backend on x86_64 too, and CI runs the
//! whole test suite that way as well.
//!
//! - [`Mask2`], [`Mask3`], [`Mask4`]: typed, `const`-constructible views over baked bytes, read
//!   toroidally with any integer coordinates; [`Mask3::get_k`] gives the k-th independent value
//!   of a pixel through R2 offsets (STBN §5.2, FAST §6).
//! - [`ldg`]: low-discrepancy grids computed on the fly (R2, plus-shaped, IGN, Bayer), exact for
//!   huge coordinates, optionally animated per frame.
//! - [`sampler`]: several decorrelated values per pixel per frame with no texture (IGN × R2,
//!   the rotated R_d sequence, Owen-scrambled Sobol): the free baselines of vector masks.
//! - [`sequence`]: the R2 and golden-ratio sequences in 64-bit fixed point.
//! - [`hash`]: the integer hashes every lattice here uses (cells, corners, PCG).
//! - [`warp`]: from uniform numbers to disks, spheres and hemispheres; safe at 0 and 1.
//! - [`cnj`]: curl-noise jittering (Bærentzen et al. 2023): closest-point and k-nearest queries
//!   on a jittered triangular (2D) or BCC (3D) lattice, and Worley noise built on them, with no
//!   point set stored.
//! - [`shaders`]: the same functions in WGSL, for wgpu and Bevy, and how a mask is uploaded
//!   ([`Mask3::gpu_texture`]).
//! - [`stochastic`]: Perlin, simplex, fractal, sparse convolution, Gabor and smooth Voronoi
//!   noise, each deterministic and as an unbiased one-sample estimator (Fajardo & Pharr).
//!
//! Nothing here panics or returns NaN for any finite input.
//!
//! # Example
//!
//! A game gets a mask's bytes from `noise_texture!` or from `build.rs` (a `static` over
//! `include_bytes_aligned!`); here a 4×4 ordered-dither pattern stands in for them.
//!
//! ```
//! use noise_runtime::{Mask2, ldg, stochastic};
//!
//! static BYTES: [u8; 16] = [0, 128, 32, 160, 192, 64, 224, 96, 48, 176, 16, 144, 240, 112, 208, 80];
//! // The dims are part of the type; a length mismatch fails to compile in a `static`.
//! static MASK: Mask2<u8, 4, 4> = Mask2::new(&BYTES);
//!
//! // Reads wrap toroidally, for any integer coordinates.
//! assert_eq!(MASK.get(-1, 5), MASK.get(3, 1));
//! // Thresholding at coverage p turns on a fraction p of the pixels.
//! let on = (0..4).flat_map(|y| (0..4).map(move |x| (x, y)));
//! assert_eq!(on.filter(|&(x, y)| MASK.threshold(x, y, 0.25)).count(), 4);
//!
//! // A stochastic noise value averages to the deterministic one: here over the ξ of a
//! // 64×64 block of the R2 low-discrepancy grid.
//! let p = [1.3, -2.7, 0.4];
//! let mut mean = 0.0;
//! for y in 0..64 {
//!     for x in 0..64 {
//!         mean += stochastic::Perlin::new(7).estimate(p, ldg::r2(x, y)) / 4096.0;
//!     }
//! }
//! assert!((mean - stochastic::Perlin::new(7).sample(p)).abs() < 0.002);
//! ```
#![no_std]
#![deny(unsafe_code)]
#![warn(missing_docs)]

#[cfg(test)]
extern crate std;

pub mod cnj;
pub mod coord;
mod gradients;
pub mod hash;
mod lanes;
pub mod ldg;
pub mod mask;
pub mod math;
pub mod sampler;
pub mod sequence;
pub mod shaders;
pub mod stochastic;
pub mod texel;
pub mod warp;

pub use coord::Coord;
pub use mask::{GpuTexture, Mask2, Mask3, Mask4};
pub use sampler::SamplerTile;
pub use texel::{GpuFormat, Texel};
