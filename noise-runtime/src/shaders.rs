//! The runtime's functions in WGSL, for games that sample noise on the GPU.
//!
//! [`WGSL`] is `noise-runtime/wgsl/noisebake.wgsl`: plain WGSL (no preprocessor, no bindings of its own),
//! so it can be prepended to a wgpu shader module or loaded as a Bevy shader library. Every
//! function is prefixed `nb_` and computes what the runtime function of the same name does:
//!
//! | WGSL | runtime | agreement |
//! |---|---|---|
//! | `nb_mask_coord_k`, `nb_wrap` | [`Mask3::get_k`](crate::Mask3::get_k)'s texel address | bit for bit (integer) |
//! | `nb_unorm8_unit`, `nb_u16_unit` | [`Texel::unit`](crate::Texel::unit) of a loaded texel | bit for bit |
//! | `nb_r2`, `nb_r2_frame`, `nb_plus`, `nb_plus_frame`, `nb_bayer`, `nb_bayer_frame` | [`ldg`](crate::ldg) | bit for bit (64-bit fixed point emulated in `u32` pairs) |
//! | `nb_ign`, `nb_ign_frame` | [`ldg::ign`](crate::ldg::ign) | within 2⁻²³ (the CPU rounds an `f64`) |
//! | `nb_hash2`, `nb_hash3`, `nb_pcg` | [`hash::hash2`](crate::hash::hash2), [`hash::pcg`](crate::hash::pcg) | bit for bit |
//! | `nb_ign_r2`, `nb_rd2_ign_r2` … `nb_rd4_ign_r2`, `nb_rd2`, `nb_rd3`, `nb_sobol_owen` | [`sampler`](crate::sampler) | bit for bit (32-bit fractions) |
//! | `nb_sampler_tile`, `nb_sampler_tile_bits`, `nb_tile_point`, `nb_tile_generator`, `nb_sobol2` | [`SamplerTile::sample`](crate::SamplerTile::sample), [`sampler::tile_point`](crate::sampler::tile_point), [`sampler::sobol2`](crate::sampler::sobol2) | bit for bit (the keys are integers) |
//! | `nb_disk_polar`, `nb_cosine_hemisphere_polar`, `nb_sampler_tile_cosine_hemisphere` | [`warp::disk_polar`](crate::warp::disk_polar), [`warp::cosine_hemisphere_polar`](crate::warp::cosine_hemisphere_polar), [`SamplerTile::cosine_hemisphere`](crate::SamplerTile::cosine_hemisphere) | within `2^-10` per component (below) |
//! | `nb_perlin3`, `nb_fbm3`, `nb_perlin3_estimate`, `nb_fbm3_estimate` | [`Perlin`](crate::stochastic::Perlin), [`Fbm`](crate::stochastic::Fbm) | within tolerances (below) |
//! | `nb_cnj2_closest` | [`Cnj2::closest`](crate::cnj::Cnj2::closest) | same site; point within tolerance |
//!
//! The floating-point functions cannot promise the same bits: WGSL lets an implementation fuse
//! `a * b + c` into one rounding (GPUs do), and has no `f64`, which the CPU's CNJ queries use.
//! The `noisebake-gpu` tests hold them, on a Vulkan device, to these tolerances:
//!
//! - `nb_perlin3` within `2^-16` of [`Perlin::sample`](crate::stochastic::Perlin::sample) (values of
//!   magnitude ≤ 2 through seven lerps and the fades, each of which may round once more or
//!   once less when fused: a few ulps of 2, far below the bound); `nb_fbm3` within
//!   `Σ|gain^o| · 2^-16`.
//! - The estimators bit for bit, except where a decision flips because a fade weight or the
//!   remapped ξ landed within one rounding of its cut: the GPU then evaluated another, equally
//!   valid corner or octave. At most one input in 10⁴ may do so.
//! - The polar warps within `2^-10` of the CPU's in every component: the same `u` and `v` in,
//!   then a square root (correctly rounded on both sides) and `sin`/`cos` of `2πv`, which Vulkan
//!   only holds to `2^-11` absolute.
//! - `nb_cnj2_closest` within `2^-12` spacings of [`Cnj2::closest`](crate::cnj::Cnj2::closest)'s
//!   point for queries within 256 spacings of the origin (f32 positions through the flow), and
//!   the same site unless the two nearest points are within twice that of a tie. Far from the
//!   origin the f32 positions lose precision in proportion to |x|: offset coordinates there.
//!
//! The tests run on every Vulkan driver of the machine; CI runs them on two software drivers,
//! Mesa's lavapipe (which does not fuse, and matched every one of them bit for bit) and
//! Google's SwiftShader (which fuses and approximates as GPUs do).
//! Gradient noise coordinates must lie within `|p| < 2^22` (the runtime's fast split range;
//! beyond it the GPU's `floor` and `i32` conversion no longer match the CPU's exact split).
//!
//! # What a game can rely on
//!
//! - **Every value a mask, grid, hash or sampler gives is the CPU's, bit for bit**: the integer
//!   paths above, and the `f32` they end in (a 24-bit fraction, converted exactly). A threshold
//!   against one of them (`ξ < α` for stochastic transparency, `c > ξ` for dithering) decides
//!   the same way on both sides *when the other operand is the same number*.
//! - **The other operand is the game's own arithmetic**, and that is where CPU and GPU part:
//!   a colour computed as `0.1 + 0.8 * u` may be fused into one rounding on the GPU, a
//!   division may be off by 2.5 ulp, and `sin`/`cos` only promise `2^-11` absolute (Vulkan's
//!   precision rules). Where that operand lies within its error of ξ, the pixel may come out the
//!   other way. With 8-bit masks this is not rare: their values are multiples of 1/256, and
//!   so are many colours (the demo's dither has a red channel equal to 192/256 at one column,
//!   and there a fused multiply-add decides). A game that needs the CPU's image exactly
//!   computes the thresholded operand in fixed point, or uploads it; otherwise it can count on
//!   a flip only within that distance of the threshold, never farther — which is what
//!   `noisebake-gpu`'s scene test asserts, pixel by pixel.
//!
//! # Using it
//!
//! ```
//! let source = format!("{}\n{}", noise_runtime::shaders::WGSL, "
//! @group(0) @binding(0) var<storage, read_write> out: array<f32>;
//! @compute @workgroup_size(64)
//! fn main(@builtin(global_invocation_id) id: vec3<u32>) {
//!     out[id.x] = nb_r2_frame(vec2<i32>(i32(id.x), 0), 7u);
//! }");
//! assert!(source.contains("fn nb_perlin3"));
//! ```

/// The WGSL library (`noise-runtime/wgsl/noisebake.wgsl`).
pub const WGSL: &str = include_str!("../wgsl/noisebake.wgsl");
