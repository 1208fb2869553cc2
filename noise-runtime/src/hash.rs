//! Integer hashes of lattice cells, shared by every lattice in the crate (stochastic noise, the
//! curl-noise fields and CNJ's lattices): a multiply-xor combination of the coordinates finished
//! by a 32-bit avalanche mix, so neighbouring cells get unrelated bits; the cheap corner hash of
//! the gradient noises; PCG for single words. Wrapping arithmetic only.

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

/// The PCG hash of one 32-bit word (PCG-RXS-M-XS; Jarzynski & Olano 2020, "Hash Functions for
/// GPU Rendering", §3): one LCG step, then a random xorshift, a multiply and a fixed xorshift.
/// The usual per-pixel seed hash in shaders; `nb_pcg` in the WGSL library is the same function.
#[inline(always)]
pub fn pcg(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// Per-axis multipliers of the lattice hashes: a corner's hash is the xor of its coordinates
/// times these, times one more odd constant — one multiply per corner once the axis products
/// are known, which is what keeps gradient noise fast.
pub(crate) const PRIME: [u32; 4] = [0x8da6_b343, 0xd816_3841, 0xcb1a_b31f, 0x165_667b1];

/// The cheap corner hash: `(seed ^ xp ^ yp ^ zp) · M`; use its **top** bits.
#[inline(always)]
pub(crate) fn corner(seed: u32, xp: u32, yp: u32, zp: u32) -> u32 {
    (seed ^ xp ^ yp ^ zp).wrapping_mul(CORNER_MUL)
}

/// The odd constant that finishes a [`corner`] hash.
pub(crate) const CORNER_MUL: u32 = 0x27d4_eb2d;

/// A point in the unit cell from a corner hash: one of [`POINTS`], chosen by the hash's top 10
/// bits. A table read instead of computing the point from the hash (a multiply–xorshift round
/// and three int-to-float conversions): a 27-cell search does it 27 times, and the table
/// nearly halved Worley F1's time (`noisebake report stochastic`).
#[inline(always)]
pub(crate) fn point3(h: u32) -> [f32; 3] {
    let p = POINTS[(h >> 22) as usize];
    [p[0], p[1], p[2]]
}

/// [`point3`] as its padded table row `[x, y, z, 0]`, for a 16-byte lane load.
#[inline(always)]
pub(crate) fn point3_row(h: u32) -> &'static [f32; 4] {
    &POINTS[(h >> 22) as usize]
}

/// 1024 feature points in the unit cell (16 KiB), each coordinate on the 1/1024 grid at a cell
/// centre `(k + ½)/1024`, from a multiply–xorshift hash of the index: as many distinct points
/// as the 10 hash bits can choose. Padded to four lanes so a point is one 16-byte read.
static POINTS: [[f32; 4]; 1024] = {
    let mut t = [[0.0f32; 4]; 1024];
    let mut k = 0;
    while k < 1024 {
        let mut a = (k as u32).wrapping_mul(0x9e37_79b9) ^ 0x5bd1_e995;
        a ^= a >> 15;
        a = a.wrapping_mul(0x2c1b_3c6d);
        a ^= a >> 12;
        const S: f32 = 1.0 / 1024.0;
        t[k] = [
            (a >> 22) as f32 * S + S * 0.5,
            ((a >> 12) & 1023) as f32 * S + S * 0.5,
            ((a >> 2) & 1023) as f32 * S + S * 0.5,
            0.0,
        ];
        k += 1;
    }
    t
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn feature_points_are_distinct_and_fill_the_cell_evenly() {
        let mut seen: [[f32; 3]; 1024] = [[0.0; 3]; 1024];
        for (k, p) in POINTS.iter().enumerate() {
            seen[k] = [p[0], p[1], p[2]];
            for &c in &p[..3] {
                assert!(c > 0.0 && c < 1.0);
            }
        }
        for k in 0..1024 {
            for j in 0..k {
                assert_ne!(seen[k], seen[j], "points {j} and {k}");
            }
        }
        // Each coordinate's octants hold 128 ± 4.5σ points (σ = √(1024·⅛·⅞) ≈ 10.6).
        for a in 0..3 {
            let mut bins = [0i32; 8];
            for p in &POINTS {
                bins[(p[a] * 8.0) as usize] += 1;
            }
            for b in bins {
                assert!((b - 128).abs() < 48, "axis {a}: {bins:?}");
            }
        }
    }
}
