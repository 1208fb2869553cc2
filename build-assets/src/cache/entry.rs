//! The entry file format `<key>.nbk`: a 64-byte header (magic `NBAKE\0` and a two-byte format
//! version, then little-endian u64 data length, FNV-1a 64 of the data followed by the open
//! windows' eight bytes, canonical-spec length, FNV-1a 64 of the canonical spec, the open TAA
//! windows, zero padding), the texel bytes, then the canonical spec. The open windows (bytes
//! 40–47, format 3) are how many 3 × 3 windows of a `taa` mask lack a low or a high value, 0
//! for every other texture — a promise a bake could not keep, recorded beside the texture.
//! The bake counts them ([`crate::texture::Baked`]); format 4 puts them under the data's hash,
//! so a read verifies them with the checksums and never decodes or re-counts a texture: the
//! cache knows entries, not generators. Reads check every header field with checked
//! arithmetic before using any.

use super::key::fnv64;
use crate::spec::TextureSpec;
use crate::texture::{Baked, Texture};
use std::time::Duration;

/// Magic and entry-format version (the last two bytes).
pub(crate) const MAGIC: &[u8; 8] = b"NBAKE\x00\x04\x00";
/// Bytes before the texture data in an entry file.
pub const HEADER: usize = 64;
/// The modification time of every entry: 2001-09-09, long before any build that reads it.
pub(crate) const ENTRY_MTIME: Duration = Duration::from_secs(1_000_000_000);

/// Why an entry file failed verification.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Corrupt {
    /// Shorter than a header, or not starting with the magic.
    NotAnEntry,
    /// An entry of another format version.
    Version(u16),
    /// The header's lengths do not add up to the file's.
    Length {
        /// The file's length.
        file: u64,
        /// What the header implies (saturated).
        header: u64,
    },
    /// Padding bytes 48–63 are not zero.
    Padding,
    /// The data (with the open windows) or spec hash does not match.
    Hash,
    /// The entry holds another spec.
    OtherSpec,
    /// The data length is not the spec's.
    DataLength {
        /// Held.
        held: u64,
        /// Needed.
        needed: u64,
    },
}

impl std::fmt::Display for Corrupt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Corrupt::NotAnEntry => f.write_str("not a noisebake cache entry"),
            Corrupt::Version(v) => write!(f, "entry format {v}, this build reads {}", MAGIC[6]),
            Corrupt::Length { file, header } => {
                write!(f, "truncated or padded: {file} bytes, header says {header}")
            }
            Corrupt::Padding => f.write_str("header padding is not zero"),
            Corrupt::Hash => f.write_str("content hash mismatch"),
            Corrupt::OtherSpec => f.write_str("entry belongs to a different spec"),
            Corrupt::DataLength { held, needed } => {
                write!(f, "holds {held} bytes, the spec needs {needed}")
            }
        }
    }
}

/// FNV-1a 64 of the texel bytes followed by the open windows (little-endian): the header's
/// data hash.
fn data_hash(data: &[u8], open_windows: u64) -> u64 {
    open_windows
        .to_le_bytes()
        .iter()
        .fold(fnv64(data), |h, &b| {
            (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
        })
}

/// The bytes of an entry file holding `baked`.
pub fn encode(baked: &Baked, spec: &TextureSpec) -> Vec<u8> {
    let (t, open) = (&baked.texture, baked.open_windows);
    let canon = spec.canonical();
    let mut out = Vec::with_capacity(HEADER + t.data.len() + canon.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&(t.data.len() as u64).to_le_bytes());
    out.extend_from_slice(&data_hash(&t.data, open).to_le_bytes());
    out.extend_from_slice(&(canon.len() as u64).to_le_bytes());
    out.extend_from_slice(&fnv64(canon.as_bytes()).to_le_bytes());
    out.extend_from_slice(&open.to_le_bytes());
    out.resize(HEADER, 0);
    out.extend_from_slice(&t.data);
    out.extend_from_slice(canon.as_bytes());
    out
}

/// Verifies an entry's bytes against `spec` and returns its texture and open windows. Every
/// header field is checked, lengths with checked arithmetic, before any is used to slice.
pub fn decode(bytes: &[u8], spec: &TextureSpec) -> Result<Baked, Corrupt> {
    let (data, canon) = split(bytes)?;
    if canon != spec.canonical().as_bytes() {
        return Err(Corrupt::OtherSpec);
    }
    if data.len() != spec.byte_len() {
        return Err(Corrupt::DataLength {
            held: data.len() as u64,
            needed: spec.byte_len() as u64,
        });
    }
    let t = Texture {
        name: spec.name.clone(),
        dims: spec.dims.clone(),
        format: spec.format,
        data: data.to_vec(),
    };
    Ok(Baked {
        texture: t,
        open_windows: open_windows(bytes).unwrap_or(0),
    })
}

/// The open TAA windows an entry's header records (bytes 40–47), `None` for bytes too short to
/// hold a header.
pub fn open_windows(bytes: &[u8]) -> Option<u64> {
    let b: [u8; 8] = bytes.get(40..48)?.try_into().ok()?;
    Some(u64::from_le_bytes(b))
}

/// An entry's texel bytes and canonical spec, after checking its magic, format version,
/// padding, lengths (with checked arithmetic) and both hashes (the data's covers the open
/// windows); nothing is sliced before the
/// lengths it depends on are checked.
pub(crate) fn split(bytes: &[u8]) -> Result<(&[u8], &[u8]), Corrupt> {
    if bytes.len() < HEADER || bytes[..6] != MAGIC[..6] {
        return Err(Corrupt::NotAnEntry);
    }
    if bytes[6..8] != MAGIC[6..8] {
        return Err(Corrupt::Version(u16::from_le_bytes([bytes[6], bytes[7]])));
    }
    let u = |i: usize| {
        let mut b = [0u8; 8];
        b.copy_from_slice(&bytes[i..i + 8]);
        u64::from_le_bytes(b)
    };
    let (len, hash, clen, chash, open) = (u(8), u(16), u(24), u(32), u(40));
    if bytes[48..HEADER].iter().any(|&b| b != 0) {
        return Err(Corrupt::Padding);
    }
    let total = (HEADER as u64)
        .checked_add(len)
        .and_then(|t| t.checked_add(clen));
    if total != Some(bytes.len() as u64) {
        return Err(Corrupt::Length {
            file: bytes.len() as u64,
            header: total.unwrap_or(u64::MAX),
        });
    }
    // Both fit in the file, so both fit in usize.
    let data_end = HEADER + len as usize;
    let data = &bytes[HEADER..data_end];
    let canon = &bytes[data_end..];
    if data_hash(data, open) != hash || fnv64(canon) != chash {
        return Err(Corrupt::Hash);
    }
    Ok((data, canon))
}
