//! The cache key: FNV-1a 128 of `v{ALGORITHM_VERSION};` and the canonical spec text
//! ([`TextureSpec::canonical`]), as 32 lowercase hex digits. Any change of the generator
//! version or of the canonical text is a new key; nothing else is.

use crate::generate::ALGORITHM_VERSION;
use crate::spec::TextureSpec;

/// FNV-1a, 64-bit: content hashes in entry headers (fast, dependency-free, stable forever).
pub fn fnv64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
    })
}

/// FNV-1a, 128-bit (offset basis and prime of the FNV specification): cache keys.
pub fn fnv128(bytes: &[u8]) -> u128 {
    const PRIME: u128 = (1 << 88) + (1 << 8) + 0x3b;
    bytes
        .iter()
        .fold(0x6c62_272e_07bb_0142_62b8_2175_6295_c58d, |h, &b| {
            (h ^ b as u128).wrapping_mul(PRIME)
        })
}

/// The cache key of a spec: 32 hex digits, all 128 bits of one hash.
pub fn key(spec: &TextureSpec) -> String {
    key_of(ALGORITHM_VERSION, &spec.canonical())
}

/// The key formula, the one place it is written: FNV-1a 128 of `v{version};{canonical}` as 32
/// lowercase hex digits. [`key`] applies it to this generator's version; the tidy pass applies
/// it to older versions to tell a stale entry from a corrupt one.
pub fn key_of(version: u32, canonical: &str) -> String {
    format!(
        "{:032x}",
        fnv128(format!("v{version};{canonical}").as_bytes())
    )
}
