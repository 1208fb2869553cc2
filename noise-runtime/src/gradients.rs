//! The gradient sets of every lattice noise in the crate, beside the hashes that pick them
//! ([`hash`](crate::hash)): Perlin's and simplex noise in [`stochastic`](crate::stochastic),
//! the batch kernels, and the curl-noise fields of [`cnj`](crate::cnj) all read them here.
//! Each set is picked by the top bits of a finished corner hash.
//!
//! Rows are padded to four `f32` and 16-byte aligned, so that a gradient is one aligned load
//! into a lane register ([`crate::lanes`]).

use crate::hash::CORNER_MUL;

/// The 8 gradients of 2D Perlin noise: the axes and the diagonals (Perlin 2002's 2D choice).
const PERLIN2: [[f32; 2]; 8] = [
    [1.0, 1.0],
    [-1.0, 1.0],
    [1.0, -1.0],
    [-1.0, -1.0],
    [1.0, 0.0],
    [-1.0, 0.0],
    [0.0, 1.0],
    [0.0, -1.0],
];

/// Rows of four, 16-byte aligned.
#[repr(align(16))]
pub(crate) struct Rows<const N: usize>(pub(crate) [[f32; 4]; N]);

/// The 12 cube-edge gradients of improved noise (Perlin 2002) for 3D Perlin noise, padded
/// to 16 with four of them again, as rows.
pub(crate) static EDGES3: Rows<16> = Rows(EDGES3_ROWS);

const EDGES3_ROWS: [[f32; 4]; 16] = [
    [1.0, 1.0, 0.0, 0.0],
    [-1.0, 1.0, 0.0, 0.0],
    [1.0, -1.0, 0.0, 0.0],
    [-1.0, -1.0, 0.0, 0.0],
    [1.0, 0.0, 1.0, 0.0],
    [-1.0, 0.0, 1.0, 0.0],
    [1.0, 0.0, -1.0, 0.0],
    [-1.0, 0.0, -1.0, 0.0],
    [0.0, 1.0, 1.0, 0.0],
    [0.0, -1.0, 1.0, 0.0],
    [0.0, 1.0, -1.0, 0.0],
    [0.0, -1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0, 0.0],
    [1.0, -1.0, 0.0, 0.0],
    [-1.0, 1.0, 0.0, 0.0],
    [0.0, -1.0, -1.0, 0.0],
];

/// The same 12 edges for 3D simplex noise, padded as the `grad` function of Perlin's reference
/// code pads them: by the hash bits `h`, `u = x` for `h < 8` else `y`; `v = y` for `h < 4`,
/// `x` for `h` 12 and 14, else `z`; the gradient is `±u ± v` by bits 0 and 1. (Its padding
/// rows differ from [`EDGES3`]'s in one, row 13; both are pinned by the noises' values.)
pub(crate) static EDGES3_SIMPLEX: Rows<16> = Rows({
    let mut g = [[0.0f32; 4]; 16];
    let mut h = 0;
    while h < 16 {
        let u = if h < 8 { 0 } else { 1 };
        let v = if h < 4 {
            1
        } else if h == 12 || h == 14 {
            0
        } else {
            2
        };
        g[h][u] = if h & 1 == 0 { 1.0 } else { -1.0 };
        g[h][v] = if h & 2 == 0 { 1.0 } else { -1.0 };
        h += 1;
    }
    g
});

/// [`EDGES3`] by columns: `EDGES3_COLUMNS[a][j >> 3][j & 7]` is axis `a` of gradient `j`, for
/// the batch kernels, which read one axis of eight gradients at a time
/// ([`Lanes8::lookup16`](crate::lanes::Lanes8::lookup16)).
pub(crate) const EDGES3_COLUMNS: [[[f32; 8]; 2]; 3] = {
    let mut c = [[[0.0f32; 8]; 2]; 3];
    let mut j = 0;
    while j < 16 {
        let mut a = 0;
        while a < 3 {
            c[a][j >> 3][j & 7] = EDGES3_ROWS[j][a];
            a += 1;
        }
        j += 1;
    }
    c
};

/// The 32 edge gradients of the tesseract: one axis zero, the other three ±1 (4D Perlin and
/// 4D simplex noise).
pub(crate) static EDGES4: Rows<32> = Rows({
    let mut g = [[0.0f32; 4]; 32];
    let mut i = 0;
    while i < 32 {
        let zero = i >> 3;
        let mut axis = 0;
        let mut bit = 0;
        while axis < 4 {
            if axis != zero {
                g[i][axis] = if (i >> bit) & 1 == 0 { 1.0 } else { -1.0 };
                bit += 1;
            }
            axis += 1;
        }
        i += 1;
    }
    g
});

/// 16 unit vectors at the angles `(k + ½)·22.5°`, for 2D simplex noise: no direction of the
/// plane is favoured (the axes-and-diagonals set of 2D Perlin noise mixes lengths 1 and √2).
pub(crate) static UNIT2: [[f32; 2]; 16] = {
    const A: [f32; 4] = [0.980_785_3, 0.831_469_6, 0.555_570_24, 0.195_090_32];
    let mut g = [[0.0f32; 2]; 16];
    let mut k = 0;
    while k < 4 {
        let (c, s) = (A[k], A[3 - k]);
        g[k] = [c, s];
        g[k + 4] = [-s, c];
        g[k + 8] = [-c, -s];
        g[k + 12] = [s, -c];
        k += 1;
    }
    g
};

/// The 2D Perlin gradient of a finished corner hash (its top 3 bits).
#[inline(always)]
pub(crate) fn perlin2(h: u32) -> [f32; 2] {
    PERLIN2[(h >> 29) as usize]
}

/// The 3D Perlin gradient of a finished corner hash (its top 4 bits), as a padded row.
#[inline(always)]
pub(crate) fn edge3(h: u32) -> &'static [f32; 4] {
    &EDGES3.0[(h >> 28) as usize]
}

/// The 3D simplex gradient of a finished hash (its top 4 bits), as a padded row.
#[inline(always)]
pub(crate) fn edge3_simplex(h: u32) -> &'static [f32; 4] {
    &EDGES3_SIMPLEX.0[(h >> 28) as usize]
}

/// The 4D edge gradient of a finished corner hash (its top 5 bits), as a row.
#[inline(always)]
pub(crate) fn edge4(h: u32) -> &'static [f32; 4] {
    &EDGES4.0[(h >> 27) as usize]
}

/// A gradient uniform in `[−1, 1]²` from a corner hash before its finishing multiply, for the
/// 2D curl-noise field of CNJ (the Perlin-noise-with-derivatives formulation the paper adapts):
/// the finishing multiply, then one xorshift–multiply round so that the low half (the y
/// component) is as well mixed as the high half.
#[inline(always)]
pub(crate) fn uniform2(h: u32) -> [f32; 2] {
    let h = h.wrapping_mul(CORNER_MUL);
    let h = (h ^ (h >> 15)).wrapping_mul(0x2c1b_3c6d);
    const S: f32 = 1.0 / 32768.0;
    [
        (h >> 16) as i32 as f32 * S - 1.0,
        (h & 0xffff) as i32 as f32 * S - 1.0,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edge_sets_are_the_papers() {
        // 3D: the 12 distinct rows are the cube's edge midpoints (two ±1, one 0), each once
        // among the first 12, and the 4 padding rows repeat edges.
        for set in [&EDGES3, &EDGES3_SIMPLEX] {
            let mut seen = std::vec::Vec::new();
            for (h, r) in set.0.iter().enumerate() {
                assert_eq!(r[3], 0.0);
                assert_eq!(r[..3].iter().filter(|v| **v == 0.0).count(), 1, "row {h}");
                assert!(r[..3].iter().all(|v| [0.0, 1.0, -1.0].contains(v)));
                if h < 12 {
                    assert!(!seen.contains(r), "row {h} repeats");
                    seen.push(*r);
                } else {
                    assert!(seen.contains(r), "padding row {h} is not an edge");
                }
            }
        }
        assert_eq!(EDGES3.0[..12], EDGES3_SIMPLEX.0[..12]);
        let differ: std::vec::Vec<usize> = (12..16)
            .filter(|&h| EDGES3.0[h] != EDGES3_SIMPLEX.0[h])
            .collect();
        assert_eq!(differ, [13]);
        for (j, r) in EDGES3.0.iter().enumerate() {
            for a in 0..3 {
                assert_eq!(EDGES3_COLUMNS[a][j >> 3][j & 7], r[a]);
            }
        }
        // 4D: 32 distinct rows, one zero each.
        for (i, r) in EDGES4.0.iter().enumerate() {
            assert_eq!(r.iter().filter(|v| **v == 0.0).count(), 1);
            assert!(EDGES4.0[..i].iter().all(|o| o != r));
        }
        for g in UNIT2 {
            assert!(((g[0] * g[0] + g[1] * g[1]) - 1.0).abs() < 1e-6);
        }
    }
}
