//! Storage formats of baked textures and the rank → value encoding (ARCHITECTURE.md: rank `r` of `N`
//! becomes `(r + 0.5) / N` in f32 and `floor(r · 2^bits / N)` in unorm formats, so every format
//! has a flat histogram over the ranked set).

use std::fmt;

/// The scalar type of one channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scalar {
    /// 8-bit unorm.
    U8,
    /// 16-bit unorm.
    U16,
    /// 32-bit float in `[0, 1)` (or `[-1, 1]` for unit vectors).
    F32,
}

impl Scalar {
    /// Bytes per channel.
    pub fn bytes(self) -> usize {
        match self {
            Scalar::U8 => 1,
            Scalar::U16 => 2,
            Scalar::F32 => 4,
        }
    }

    /// The NumPy dtype string.
    pub fn npy_descr(self) -> &'static str {
        match self {
            Scalar::U8 => "|u1",
            Scalar::U16 => "<u2",
            Scalar::F32 => "<f4",
        }
    }
}

/// A texel format: scalar type and channel count (1–4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Format {
    /// Channel type.
    pub scalar: Scalar,
    /// Channels per texel.
    pub channels: u8,
}

impl Format {
    /// One u8 channel.
    pub const U8: Format = Format {
        scalar: Scalar::U8,
        channels: 1,
    };
    /// One u16 channel.
    pub const U16: Format = Format {
        scalar: Scalar::U16,
        channels: 1,
    };
    /// One f32 channel.
    pub const F32: Format = Format {
        scalar: Scalar::F32,
        channels: 1,
    };

    /// Parses `u8`, `u16`, `f32`, or a vector form such as `u8x3` / `f32x4`.
    pub fn parse(s: &str) -> Option<Format> {
        let (base, ch) = match s.split_once('x') {
            Some((b, c)) => (b, c.parse::<u8>().ok().filter(|c| (2..=4).contains(c))?),
            None => (s, 1),
        };
        let scalar = match base {
            "u8" => Scalar::U8,
            "u16" => Scalar::U16,
            "f32" => Scalar::F32,
            _ => return None,
        };
        Some(Format {
            scalar,
            channels: ch,
        })
    }

    /// Bytes per texel.
    pub fn texel_bytes(self) -> usize {
        self.scalar.bytes() * self.channels as usize
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = match self.scalar {
            Scalar::U8 => "u8",
            Scalar::U16 => "u16",
            Scalar::F32 => "f32",
        };
        if self.channels == 1 {
            write!(f, "{b}")
        } else {
            write!(f, "{b}x{}", self.channels)
        }
    }
}

/// Encodes ranks (`ranks[i]` in `0..count`) as little-endian texels of a scalar format.
pub fn encode_ranks(ranks: &[u32], count: u32, scalar: Scalar) -> Vec<u8> {
    let n = count as u64;
    match scalar {
        Scalar::U8 => ranks
            .iter()
            .map(|&r| ((r as u64 * 256) / n) as u8)
            .collect(),
        Scalar::U16 => ranks
            .iter()
            .flat_map(|&r| (((r as u64 * 65536) / n) as u16).to_le_bytes())
            .collect(),
        Scalar::F32 => ranks
            .iter()
            .flat_map(|&r| (((r as f64 + 0.5) / n as f64) as f32).to_le_bytes())
            .collect(),
    }
}

/// Encodes values in `[0, 1)` as little-endian texels (unorm: `floor(v · 2^bits)`).
pub fn encode_unit(values: &[f64], scalar: Scalar) -> Vec<u8> {
    let clamp = |v: f64, top: f64| (v * top).floor().clamp(0.0, top - 1.0);
    match scalar {
        Scalar::U8 => values.iter().map(|&v| clamp(v, 256.0) as u8).collect(),
        Scalar::U16 => values
            .iter()
            .flat_map(|&v| (clamp(v, 65536.0) as u16).to_le_bytes())
            .collect(),
        Scalar::F32 => values
            .iter()
            .flat_map(|&v| {
                // The largest f32 below 1 keeps [0, 1) closed under rounding.
                let x = (v as f32).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
                x.to_le_bytes()
            })
            .collect(),
    }
}

/// Decodes little-endian texels to `f64` values in `[0, 1)` (unorm: bin centres `(v + 0.5)/2^bits`).
pub fn decode_unit(bytes: &[u8], scalar: Scalar) -> Vec<f64> {
    match scalar {
        Scalar::U8 => bytes.iter().map(|&v| (v as f64 + 0.5) / 256.0).collect(),
        Scalar::U16 => bytes
            .chunks_exact(2)
            .map(|c| (u16::from_le_bytes([c[0], c[1]]) as f64 + 0.5) / 65536.0)
            .collect(),
        Scalar::F32 => bytes
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64)
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_prints_formats() {
        for s in ["u8", "u16", "f32", "u8x3", "f32x4", "u16x2"] {
            assert_eq!(Format::parse(s).unwrap().to_string(), s);
        }
        for s in ["u32", "u8x1", "u8x5", "f16", ""] {
            assert!(Format::parse(s).is_none(), "{s}");
        }
    }

    #[test]
    fn unorm_encoding_of_a_full_ranking_is_flat() {
        let ranks: Vec<u32> = (0..1000).collect();
        let bytes = encode_ranks(&ranks, 1000, Scalar::U8);
        let mut hist = [0u32; 256];
        for b in bytes {
            hist[b as usize] += 1;
        }
        assert!(hist.iter().all(|&c| c == 3 || c == 4), "{hist:?}");
    }
}
