//! The random-number sources compared side by side: one uniform `ξ` (or a direction) per pixel,
//! frame and index `k`.

use noisebake::{Texel, sampler, warp};

noisebake::include_textures!();
// Declared inline rather than in noise.toml: a static 2D mask, to show what animation buys.
noisebake::noise_texture!(pub BLUE2D = blue2d { dims: [64, 64], seed: 8, format: u8 });

/// A way to draw the per-pixel random numbers of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Noise {
    /// Independent uniform numbers (baked white noise).
    White,
    /// Interleaved gradient noise moved 5.588238 px per frame for the first value, then the
    /// R2 grid and mirrored R2 (`sampler::ign_r2`): a fair free construction, each value its
    /// own function of the pixel.
    Ign,
    /// The R2 grid, golden-ratio animated, for the first value, then the other grids of
    /// `sampler::ign_r2` (mirrored R2, then IGN).
    R2,
    /// The R_d sequence over frames, rotated per pixel by IGN and R2 (`sampler::rd_ign_r2`).
    Rd,
    /// Owen-scrambled Sobol per pixel (`sampler::sobol_owen`, Burley 2020).
    Sobol,
    /// One 2D blue-noise mask, the same every frame.
    Blue2dStatic,
    /// An independent 2D blue-noise mask per frame.
    Independent2d,
    /// One 2D mask plus the golden ratio per frame.
    Golden,
    /// Spatiotemporal blue noise.
    Stbn,
    /// FAST, optimised for the demo's own filter: a Gaussian blur (σ 1 px) and an EMA.
    Fast,
    /// FAST for the same blur under TAA (the EMA with a 3 × 3 history clamp); measured in the
    /// TAA panel only ([`crate::taa_panel`]).
    FastTaa,
}

impl Noise {
    /// Every source, in display order.
    pub const ALL: [Noise; 10] = [
        Noise::White,
        Noise::Ign,
        Noise::R2,
        Noise::Rd,
        Noise::Sobol,
        Noise::Blue2dStatic,
        Noise::Independent2d,
        Noise::Golden,
        Noise::Stbn,
        Noise::Fast,
    ];

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            Noise::White => "white",
            Noise::Ign => "ign",
            Noise::R2 => "r2",
            Noise::Rd => "rd",
            Noise::Sobol => "sobol",
            Noise::Blue2dStatic => "blue2d-static",
            Noise::Independent2d => "independent2d",
            Noise::Golden => "golden",
            Noise::Stbn => "stbn",
            Noise::Fast => "fast",
            Noise::FastTaa => "fast-taa",
        }
    }

    /// A hash computed in the shader: no texture to bake, ship or sample.
    pub fn is_free_hash(self) -> bool {
        matches!(self, Noise::Ign | Noise::R2 | Noise::Rd | Noise::Sobol)
    }

    /// The `k`-th uniform number of pixel `(x, y)` in frame `f`, in `[0, 1)`, `k < 3` (the
    /// demo's most: an RGB dither). Masks give independent values through R2 offsets
    /// (`get_k`); the free constructions through `sampler`, each value its own function of the
    /// pixel (never a shifted copy of the first).
    #[inline]
    pub fn xi(self, x: i32, y: i32, f: u32, k: u32) -> f32 {
        let t = f as i32;
        let k3 = (k as usize).min(2);
        match self {
            Noise::White => WHITE.get_k_unit(x, y, t, k),
            Noise::Ign => sampler::ign_r2::<3>(x, y, f)[k3],
            Noise::R2 => {
                let g = sampler::ign_r2::<3>(x, y, f);
                [g[1], g[2], g[0]][k3]
            }
            Noise::Rd => sampler::rd_ign_r2::<3>(x, y, f)[k3],
            Noise::Sobol => sampler::sobol_owen::<3>(x, y, f, 1)[k3],
            Noise::Blue2dStatic => BLUE2D.get_k(x, y, k).unit(0),
            Noise::Independent2d => IND2D.get_k_unit(x, y, t, k),
            Noise::Golden => GOLDEN.get_k_unit(x, y, t, k),
            Noise::Stbn => STBN.get_k_unit(x, y, t, k),
            Noise::Fast => FAST.get_k_unit(x, y, t, k),
            Noise::FastTaa => FAST_TAA.get_k_unit(x, y, t, k),
        }
    }

    /// A cosine-weighted direction about +z: FAST reads its baked unit-vector mask, the others
    /// warp two of their numbers (R_d its two-dimensional sequence, R2).
    #[inline]
    pub fn cosine_dir(self, x: i32, y: i32, f: u32) -> [f32; 3] {
        match self {
            Noise::Fast => {
                let t = f as i32;
                let v = [0, 1, 2].map(|c| FAST_COS.get_signed(x, y, t, c));
                let len = noisebake::math::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).max(1e-6);
                [v[0] / len, v[1] / len, (v[2] / len).max(0.0)]
            }
            Noise::Rd => {
                let [u, v] = sampler::rd_ign_r2::<2>(x, y, f);
                warp::cosine_hemisphere(u, v)
            }
            _ => warp::cosine_hemisphere(self.xi(x, y, f, 0), self.xi(x, y, f, 1)),
        }
    }
}
