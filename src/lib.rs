//! # noisebake
//!
//! High-quality noise baked into the game binary at build time: blue-noise masks by void and
//! cluster (2D, spatiotemporal, any axis grouping), FAST filter-adapted masks, low-discrepancy
//! grids, curl-noise jittered points and stochastic procedural noise, sampled through a small
//! `no_std`, dependency-free runtime. Baked masks are `static` tables: no file to ship, no
//! start-up cost.
//!
//! This facade re-exports the runtime ([`noise_runtime`]), [`include_textures!`] and, with the
//! default feature `macros`, the `noise_texture!` macro.
//!
//! # Set-up
//!
//! ```toml
//! # Cargo.toml of the game
//! [dependencies]
//! noisebake = "0.1"
//!
//! [build-dependencies]   # only for the build.rs way in
//! build-assets = "0.1"
//!
//! # Build scripts and proc macros compile at opt-level 0 unless told otherwise, and void and
//! # cluster runs 8-10x slower there. These sections go in the *workspace's* Cargo.toml.
//! [profile.dev.package.build-assets]
//! opt-level = 3
//! [profile.release.package.build-assets]
//! opt-level = 3
//! ```
//!
//! Features of this crate:
//! - `macros` (default): `noise_texture!`. It generates at compile time, so it compiles the
//!   generator and `syn` into the build. A game that bakes only through `build.rs`, or only
//!   calls the runtime's functions, sets `default-features = false` and compiles neither.
//!
//! ## Two ways in, one spec and one cache
//!
//! A `noise.toml` baked by the build script, included as one `pub static` per texture:
//!
//! ```toml
//! # noise.toml, beside the game's Cargo.toml
//! [[texture]]
//! name   = "STBN"
//! kind   = "stbn"
//! dims   = [64, 64, 16]
//! seed   = 7
//! format = "u16"
//! ```
//!
//! ```ignore
//! // build.rs
//! fn main() {
//!     build_assets::bake_or_exit("noise.toml"); // an error: Cargo `error:` lines, no panic
//! }
//!
//! // src/main.rs
//! noisebake::include_textures!();
//! let v: u16 = STBN.get(x, y, frame);
//! ```
//!
//! Or inline, with the same keys as `key: value`:
//!
//! ```ignore
//! noisebake::noise_texture!(pub DITHER = blue2d { dims: [64, 64], seed: 1, sigma: 1.9 });
//! ```
//!
//! The expansion names its types through `::noisebake`; a crate that renames the dependency or
//! reaches noisebake through a re-export (a plugin wrapping it) says where with a leading
//! `crate = PATH;`, as serde's derives take `crate = "…"`:
//! `noise_texture!(crate = ::my_plugin::noisebake; DITHER = blue2d { … })`.
//!
//! Both give a typed view over bytes embedded with `include_bytes!` in a 16-byte aligned static
//! (`Mask2<u8, 64, 64>`, `Mask3<u16, 64, 64, 16>`, `Mask4<f32, …>`, vector formats as
//! `[u8; 3]` …). Bytes are little-endian, so every target reads the same values.
//!
//! ## The cache and offline builds
//!
//! Generated textures are stored in a content-addressed cache keyed by the canonical spec (every
//! default filled in) and the generator version: a second build, or another crate declaring the
//! same spec, reads the entry instead of generating. One resolver serves `build.rs`, the macro
//! and the CLI; the first that applies:
//! 1. the `NOISEBAKE_CACHE_DIR` environment variable;
//! 2. a directory given in code (`build_assets::Bake::cache_dir`, the CLI's `--cache-dir`);
//! 3. `cache_dir = "…"` at the top of the spec file, relative to it. The macro reads it from the
//!    `noise.toml` beside the crate's `Cargo.toml` (a file holding only `cache_dir` is fine), so
//!    both ways in find a committed cache. It must be relative and stay inside the workspace;
//!    an absolute path is taken only from the two explicit places above;
//! 4. `noisebake-cache/` in the workspace's target directory.
//!
//! `NOISEBAKE_OFFLINE=1` turns a missing entry into an error instead of a generation: commit the
//! cache directory (step 3) and set it in CI. Entries are verified on read; a corrupt one is
//! regenerated with a warning. A cache directory that cannot be written costs nothing when
//! every entry is present, and otherwise sends new entries to `OUT_DIR` (or the system
//! temporary directory, for the macro) with a warning. Generations longer than a second are
//! announced by the build script (`cargo:warning`); the macro announces every generation and
//! every replaced entry on stderr. Cargo replays what a build step printed until that step runs
//! again, so after announcing, the build script has the next build run it once more, quietly
//! (every texture is then a cache hit; the crate recompiles once): from then on a no-op build
//! prints nothing. The macro forces no second compile: Cargo shows its message again on fresh
//! builds until the crate next compiles.
//!
//! ## On the GPU
//!
//! A baked mask describes itself as a GPU texture ([`Mask3::gpu_texture`]: a 2D array, one
//! layer per time slice) and gives the bytes to upload ([`Mask3::gpu_bytes`],
//! [`Mask3::write_gpu_bytes`]); `build_assets::Bake::ktx2_dir` and the CLI's `--ktx2` write the
//! same texture as KTX2 files for an asset folder. [`shaders::WGSL`] is the runtime's mask
//! lookup, grids, hashes, CNJ and Perlin/fBm functions in WGSL, matching the CPU (see
//! [`shaders`] for how exactly).
//!
//! Which `format` to bake for which platform:
//!
//! | format | GPU format | native wgpu / Bevy | WebGPU | WebGL2 | three.js (r187 `KTX2Loader`) |
//! | --- | --- | --- | --- | --- | --- |
//! | `u8`, `u8x2`, `u8x3`, `u8x4` | `r8unorm`, `rg8unorm`, `rgba8unorm` (3 channels padded to 4) | yes | yes | yes | yes |
//! | `u16` | `r16uint` (`r16unorm` is native-only) | yes | yes | yes | no: it refuses `R16_UINT`; use `u8` or `f32` |
//! | `f32`, `f32xN` | `r32float`, `rg32float`, `rgba32float` | yes | yes | yes | yes |
//!
//! Every mask is a 2D array texture; WebGL2 guarantees only 256 layers, and three.js reads an
//! uncompressed KTX2 array as one 2D texture of all layers, so build a `DataArrayTexture`
//! from the level data there. A mask costs `W × H × layers × bytes per texel` in the binary and
//! on the GPU: a 64×64×16 `u8` STBN is 64 KiB, a 128×128×64 one 1 MiB (2 MiB as `u16`).
//!
//! ## Debug builds
//!
//! Lookups and noise functions are `#[inline]` and generic, so they compile into the calling
//! crate at *its* opt-level; a package override for `noise-runtime` does not reach them. For
//! debug builds that run at speed, set `[profile.dev] opt-level = 2` (or at least 1) in the
//! game; the bake itself wants `[profile.dev.package.build-assets] opt-level = 3` (above).
//!
//! # Spec keys
//!
//! Every texture takes `name` (a Rust identifier; in the macro, the item name), `kind`, `dims`
//! (x, y, then further axes), `seed` (default 0) and `format` (`"u8"` default, `"u16"`,
//! `"f32"`; vector sample spaces of `fast` add channels: `"u8x2"`, `"u8x3"`, `"f32x4"` …).
//! Unorm formats store rank `r` of `N` as `floor(r · 2^bits / N)`, `f32` as `(r + 0.5) / N`.
//!
//! | kind | what | dims | keys (defaults) |
//! | --- | --- | --- | --- |
//! | `blue2d` | 2D void and cluster (Ulichney) | 2 | `sigma` (1.5), `initial_density` (0.1) |
//! | `stbn` | spatiotemporal blue noise, 2D × 1D (Wolfe et al. 2022) | 3 | `sigma_xy` (1.9), `sigma_t` (1.9), `initial_density` (0.1), `histogram` (`"volume"` \| `"slice"`) |
//! | `vac` | void and cluster over any grouping of 1–4 axes (STBN App. B) | 1–4 | `groups` (`[{ axes = all, sigma = 1.9 }]`), `toroidal` (true, or one bool per axis), `initial_density` (0.1), `histogram` (`"volume"` \| `"slice"`) |
//! | `white` | independent uniform values | 1–4 | — |
//! | `independent2d` | an independent 2D mask per slice | 2–4 | `sigma` (1.9), `initial_density` |
//! | `golden` | one 2D mask animated by `t·φ` per frame | 3 | `sigma` (1.9), `initial_density` |
//! | `fast` | FAST filter-adapted mask, 2D or 2D × time (Donnelly et al. 2024) | 2–3 | `sample_space` (`"scalar"`, `"circle"`, `"vec2"`…`"vec4"`, `"sphere"`, `"hemisphere"`, `"cosine_hemisphere"`), `distribution` (`"uniform"`, `"tent"`, `"gauss"`; scalar only), `spatial_filter` (`{ kind = "gauss", sigma = 1.3435 }`, `{ kind = "box", size = 5 }`, `{ kind = "binomial", order = 2 }`, `{ kind = "atrous", passes = 3 }` (the B3-spline à-trous of an SVGF-style denoiser without its edge stops, 1–5 passes), `{ kind = "none" }`), `temporal_filter` (the filter the game runs; default for 3 dims `{ kind = "ema", alpha = 0.1, beta = 0 }`, a plain EMA at its steady state over the looping texture — `beta > 0` adds eq. 17's history rejection, as EA's published texture (`beta = 0.1`) — or `{ kind = "taa", alpha = 0.1, coverage = 0.2 }`, a game's TAA: the EMA with the history clamped to the 3×3 neighbourhood, every window of a scalar mask kept spread so that the clamp spares dithers from `coverage` to `1 − coverage`, and with `motion = [vx, vy]` (pixels per frame) the EMA followed along a moving camera weighed in by the share `moving`, 0.25 by default — or `gauss`, `box`, `none`), `combine` (`"product"` or `{ separate = w }`), `start` (`"ign"`, the default for scalars: IGN's per-slice ranks; `"ign_r2"`, the default for the two-value spaces under a box filter, and `"rd_ign_r2"` under any other: the free pairs `sampler::ign_r2` / `sampler::rd_ign_r2` warped to the space; `"random"`, the default for `"vec3"` and `"vec4"`), `iterations` (until converged) |
//! | `sampler` | a sampler tile: per pixel, one low-discrepancy sequence per pair of dimensions, frame `f` taking samples `f·spp …`, shifted by per-pixel keys arranged so the errors are blue under a filter (Heitz et al. 2019's goal): a rank-1 lattice in radical-inverse order for warped pairs (Belcour and Heitz 2021's structure), the Sobol (0, 2)-sequence Owen-scrambled for `square` ones; a `SamplerTile<W, H, SPP, D>`, at most 256×256 | 2 | `spp` (1; 1–64 samples per pixel per frame), `sample_dims` (2; 1–8), `sample_space` (`"square"`; `"cosine_hemisphere"` (r = √u, φ = 2πv, z = √(1 − u)), `"disk"` (r = √u, φ = 2πv): one string for every pair or a list, one per pair), `spatial_filter` (`{ kind = "gauss", sigma = 1 }`; `"box"`, `"binomial"`, `"atrous"`, `"none"` as `fast`'s), `temporal_filter` (`{ kind = "none" }`: every frame alone; `{ kind = "ema", alpha = 0.1 }`: the history an EMA accumulates), `frames` (the EMA's history optimised: 32 under `ema`, 1 otherwise), `format` (`"u16"`, the only one) |
//!
//! One example per kind, in spec-file form (the macro takes the same as `key: value`):
//!
//! ```toml
//! [[texture]]                 # dithering, stochastic transparency
//! name = "DITHER"
//! kind = "blue2d"
//! dims = [64, 64]
//!
//! [[texture]]                 # temporal accumulation: STBN, each frame's histogram flat
//! name = "STBN"
//! kind = "stbn"
//! dims = [64, 64, 32]
//! format = "u16"
//! histogram = "slice"
//!
//! [[texture]]                 # 4D: blue in (x, y), in time, and in a fourth axis apart
//! name = "VAC4"
//! kind = "vac"
//! dims = [32, 32, 8, 4]
//! groups = [{ axes = [0, 1], sigma = 1.9 }, { axes = [2], sigma = 1.9 }, { axes = [3], sigma = 1.9 }]
//!
//! [[texture]]                 # the baselines, for comparisons
//! name = "WHITE"
//! kind = "white"
//! dims = [64, 64, 16]
//!
//! [[texture]]
//! name = "IND2D"
//! kind = "independent2d"
//! dims = [64, 64, 16]
//!
//! [[texture]]
//! name = "GOLDEN"
//! kind = "golden"
//! dims = [64, 64, 16]
//!
//! [[texture]]                 # FAST for the filter a game runs: a Gaussian blur and a plain EMA
//! name = "FAST"
//! kind = "fast"
//! dims = [64, 64, 16]
//! spatial_filter = { kind = "gauss", sigma = 1.3435 }
//! temporal_filter = { kind = "ema", alpha = 0.1, beta = 0 }
//!
//! [[texture]]                 # FAST cosine-weighted hemisphere directions (ambient occlusion)
//! name = "AO_DIRS"
//! kind = "fast"
//! dims = [32, 32, 16]
//! format = "u8x3"
//! sample_space = "cosine_hemisphere"
//! spatial_filter = { kind = "box", size = 5 }
//!
//! [[texture]]                 # 4 rays per pixel for occlusion, 4 dimensions, a Gaussian denoiser
//! name = "AO_RAYS"
//! kind = "sampler"
//! dims = [128, 128]
//! spp = 4
//! sample_dims = 4
//! spatial_filter = { kind = "gauss", sigma = 1.0 }
//! ```
//!
//! A sampler tile is read as `AO_RAYS.sample(x, y, frame, i, d)` (dimension `d` of ray `i`, in
//! `[0, 1)`), or `sample2` for a pair; on the GPU `nb_sampler_tile(keys, pixel, frame, i, d,
//! spp, sobol_pairs)` over `AO_RAYS.keys()` uploaded as any `u16` mask (an `r16uint` array bound
//! as `texture_2d_array<u32>`), with `sobol_pairs` the value of `AO_RAYS.sobol_pairs()` (which
//! pairs run Owen-scrambled Sobol: those whose `sample_space` is `"square"`) passed in a
//! uniform or written into the shader.
//!
//! Unknown keys, wrong types and impossible values are errors that name the key and point at
//! its line (spec file) or token (macro).
#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(feature = "macros")]
#[cfg_attr(docsrs, doc(cfg(feature = "macros")))]
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
