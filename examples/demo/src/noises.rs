//! The random-number sources compared side by side: one uniform `ξ` (or a direction) per pixel,
//! frame and index `k`.

use noisebake::{Texel, ldg, warp};

noisebake::include_textures!();
// Declared inline rather than in noise.toml: a static 2D mask, to show what animation buys.
noisebake::noise_texture!(pub BLUE2D = blue2d { dims: [64, 64], seed: 8, format: u8 });

/// A way to draw the per-pixel random numbers of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Noise {
    /// Independent uniform numbers (baked white noise).
    White,
    /// Interleaved gradient noise, golden-ratio animated.
    Ign,
    /// The R2 low-discrepancy grid, golden-ratio animated.
    R2,
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
}

impl Noise {
    /// Every source, in display order.
    pub const ALL: [Noise; 8] = [
        Noise::White,
        Noise::Ign,
        Noise::R2,
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
            Noise::Blue2dStatic => "blue2d-static",
            Noise::Independent2d => "independent2d",
            Noise::Golden => "golden",
            Noise::Stbn => "stbn",
            Noise::Fast => "fast",
        }
    }

    /// A hash computed in the shader: no texture to bake, ship or sample.
    pub fn is_free_hash(self) -> bool {
        matches!(self, Noise::Ign | Noise::R2)
    }

    /// The `k`-th uniform number of pixel `(x, y)` in frame `f`, in `[0, 1)`. Masks give
    /// independent values through R2 offsets (`get_k`); the grids through shifted coordinates.
    #[inline]
    pub fn xi(self, x: i32, y: i32, f: u32, k: u32) -> f32 {
        let t = f as i32;
        match self {
            Noise::White => WHITE.get_k_unit(x, y, t, k),
            Noise::Ign => ldg::ign_frame(x + 17 * k as i32, y + 29 * k as i32, f),
            Noise::R2 => ldg::r2_frame(x + 17 * k as i32, y + 29 * k as i32, f),
            Noise::Blue2dStatic => BLUE2D.get_k(x, y, k).unit(0),
            Noise::Independent2d => IND2D.get_k_unit(x, y, t, k),
            Noise::Golden => GOLDEN.get_k_unit(x, y, t, k),
            Noise::Stbn => STBN.get_k_unit(x, y, t, k),
            Noise::Fast => FAST.get_k_unit(x, y, t, k),
        }
    }

    /// A cosine-weighted direction about +z: FAST reads its baked unit-vector mask, the others
    /// warp two of their numbers.
    #[inline]
    pub fn cosine_dir(self, x: i32, y: i32, f: u32) -> [f32; 3] {
        match self {
            Noise::Fast => {
                let t = f as i32;
                let v = [0, 1, 2].map(|c| FAST_COS.get_signed(x, y, t, c));
                let len = noisebake::math::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).max(1e-6);
                [v[0] / len, v[1] / len, (v[2] / len).max(0.0)]
            }
            _ => warp::cosine_hemisphere(self.xi(x, y, f, 0), self.xi(x, y, f, 1)),
        }
    }
}
