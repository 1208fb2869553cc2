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
