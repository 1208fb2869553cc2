//! Integer hashes of lattice cells: a multiply-xor combination of the coordinates finished by
//! a 32-bit avalanche mix, so neighbouring cells get unrelated bits. Wrapping arithmetic only.

/// Avalanche mix of 32 bits.
#[inline(always)]
pub(crate) fn mix(mut h: u32) -> u32 {
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    h
}

/// Hash of a 2D cell.
#[inline(always)]
pub fn hash2(x: i32, y: i32, seed: u32) -> u32 {
    mix(seed ^ (x as u32).wrapping_mul(0x8da6_b343) ^ (y as u32).wrapping_mul(0xd816_3841))
}

/// Hash of a 3D cell.
#[inline(always)]
pub fn hash3(x: i32, y: i32, z: i32, seed: u32) -> u32 {
    mix(seed
        ^ (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ (z as u32).wrapping_mul(0xcb1a_b31f))
}

/// Hash of a 4D cell.
#[inline(always)]
pub fn hash4(x: i32, y: i32, z: i32, w: i32, seed: u32) -> u32 {
    mix(seed
        ^ (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ (z as u32).wrapping_mul(0xcb1a_b31f)
        ^ (w as u32).wrapping_mul(0x165_667b1))
}

/// A uniform number in `[0, 1)` from the top 24 bits of `h`.
#[inline(always)]
pub(crate) fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}
