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

/// Per-axis multipliers of the lattice hashes: a corner's hash is the xor of its coordinates
/// times these, times one more odd constant — one multiply per corner once the axis products
/// are known, which is what keeps gradient noise fast.
pub(crate) const PRIME: [u32; 4] = [0x8da6_b343, 0xd816_3841, 0xcb1a_b31f, 0x165_667b1];

/// The cheap corner hash: `(seed ^ xp ^ yp ^ zp) · M`; use its **top** bits.
#[inline(always)]
pub(crate) fn corner(seed: u32, xp: u32, yp: u32, zp: u32) -> u32 {
    (seed ^ xp ^ yp ^ zp).wrapping_mul(0x27d4_eb2d)
}

/// A point in the unit cell from a corner hash: three 10-bit coordinates (1/1024 steps) after
/// one more multiply–xorshift round.
#[inline(always)]
pub(crate) fn point3(h: u32) -> [f32; 3] {
    let mut a = h ^ (h >> 15);
    a = a.wrapping_mul(0x2c1b_3c6d);
    a ^= a >> 12;
    const S: f32 = 1.0 / 1024.0;
    [
        (a >> 22) as i32 as f32 * S + S * 0.5,
        ((a >> 12) & 1023) as i32 as f32 * S + S * 0.5,
        ((a >> 2) & 1023) as i32 as f32 * S + S * 0.5,
    ]
}
