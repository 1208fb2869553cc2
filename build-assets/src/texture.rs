//! A generated texture: dims, format and little-endian bytes (x fastest).

use crate::encoding::{Format, decode_unit};

/// A generated texture.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// The Rust item name.
    pub name: String,
    /// Sizes, x first.
    pub dims: Vec<usize>,
    /// Storage format.
    pub format: Format,
    /// Texels, little-endian, x fastest, channels interleaved.
    pub data: Vec<u8>,
}

impl Texture {
    /// Total texel count.
    pub fn texels(&self) -> usize {
        self.dims.iter().product()
    }

    /// Channel values as `f64` (unorm values at their bin centres), channels interleaved.
    pub fn values(&self) -> Vec<f64> {
        decode_unit(&self.data, self.format.scalar)
    }
}

/// What a generation hands the cache: the texture and what the generator knows of it that the
/// cache records in the entry's header, so that reading an entry never runs a generator.
#[derive(Clone, Debug, PartialEq)]
pub struct Baked {
    /// The texture.
    pub texture: Texture,
    /// How many 3 × 3 windows of a `taa` mask's slices lack a low or a high value
    /// (`generate::open_windows_of`); 0 for every other texture.
    pub open_windows: u64,
}

impl From<Texture> for Baked {
    /// A texture with nothing more to record (every kind but a `taa` mask).
    fn from(texture: Texture) -> Baked {
        Baked {
            texture,
            open_windows: 0,
        }
    }
}
