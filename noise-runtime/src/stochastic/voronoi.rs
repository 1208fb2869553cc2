//! Cellular noise on one hashed feature point per unit cell: Worley F1 (Worley 1996), smooth
//! Voronoi (Quilez; Fajardo & Pharr eq. 12) and the Russian-roulette estimator of smooth
//! Voronoi (eq. 5, Algorithm 3).
//!
//! Cells are visited centre first, then faces, edges and corners; a cell whose box is already
//! farther than the best distance (Worley), or whose term `e^(−32 d)` would be below 2⁻²⁴ of the
//! largest term (smooth Voronoi, relative error of the sum below 2e-6), is skipped without
//! hashing it.

use super::estimators::{ONE_BELOW, russian_roulette, sanitize_xi};
use super::hash::{hash3, mix, unit};
use crate::math::{exp_neg, ln, split, sqrt_fast};

/// The paper's roulette probability of keeping the cheap approximation.
pub const SMOOTH_VORONOI_Q: f32 = 0.875;

/// Neighbour offsets ordered by distance class (centre, 6 faces, 12 edges, 8 corners).
const ORDER: [[i8; 3]; 27] = {
    let mut out = [[0i8; 3]; 27];
    let mut n = 0;
    let mut class = 0;
    while class <= 3 {
        let mut i = 0;
        while i < 27 {
            let d = [
                (i % 3) as i8 - 1,
                ((i / 3) % 3) as i8 - 1,
                (i / 9) as i8 - 1,
            ];
            let nz = (d[0] != 0) as i32 + (d[1] != 0) as i32 + (d[2] != 0) as i32;
            if nz == class {
                out[n] = d;
                n += 1;
            }
            i += 1;
        }
        class += 1;
    }
    out
};

/// The feature point of lattice cell `cell`, in absolute coordinates relative to the cell's
/// corner (each component in `[0, 1)`).
pub fn feature_point3(cell: [i32; 3], seed: u32) -> [f32; 3] {
    feature(hash3(cell[0], cell[1], cell[2], seed))
}

#[inline(always)]
fn feature(h: u32) -> [f32; 3] {
    let b = mix(h);
    [unit(h), unit(b), unit(mix(b))]
}

/// Squared distance from `f` (in the centre cell) to the box of the cell at offset `d`.
#[inline(always)]
fn box_d2(f: [f32; 3], d: [i8; 3]) -> f32 {
    let mut s = 0.0;
    for a in 0..3 {
        let t = match d[a] {
            -1 => f[a],
            1 => 1.0 - f[a],
            _ => 0.0,
        };
        s += t * t;
    }
    s
}

#[inline(always)]
fn setup(p: [f32; 3]) -> ([i32; 3], [f32; 3]) {
    let (cx, fx) = split(p[0]);
    let (cy, fy) = split(p[1]);
    let (cz, fz) = split(p[2]);
    ([cx, cy, cz], [fx, fy, fz])
}

#[inline(always)]
fn d2_to(c: [i32; 3], f: [f32; 3], d: [i8; 3], seed: u32) -> f32 {
    let h = hash3(
        c[0].wrapping_add(d[0] as i32),
        c[1].wrapping_add(d[1] as i32),
        c[2].wrapping_add(d[2] as i32),
        seed,
    );
    let q = feature(h);
    let x = f[0] - d[0] as f32 - q[0];
    let y = f[1] - d[1] as f32 - q[1];
    let z = f[2] - d[2] as f32 - q[2];
    x * x + y * y + z * z
}

/// Worley F1: the distance to the nearest feature point.
#[inline]
pub fn worley3_f1(p: [f32; 3], seed: u32) -> f32 {
    let (c, f) = setup(p);
    let mut best = d2_to(c, f, ORDER[0], seed);
    for &d in &ORDER[1..] {
        if box_d2(f, d) < best {
            best = best.min(d2_to(c, f, d, seed));
        }
    }
    sqrt_fast(best)
}

/// Smooth Voronoi (eq. 12): `−(1/32) ln Σ_c e^(−32 |p − p_c|)` over the 27 cells.
#[inline]
pub fn smooth_voronoi3(p: [f32; 3], seed: u32) -> f32 {
    let (c, f) = setup(p);
    let d0 = sqrt_fast(d2_to(c, f, ORDER[0], seed));
    // Work relative to the centre cell's distance so the sum never underflows.
    let mut best = d0;
    let mut sum = 1.0f32;
    for &d in &ORDER[1..] {
        // Terms with 32(d − best) > 17 are below 2^-24 of the largest: skip.
        let lim = best + 17.0 / 32.0;
        if box_d2(f, d) >= lim * lim {
            continue;
        }
        let dist = sqrt_fast(d2_to(c, f, d, seed));
        if dist < best {
            sum = sum * exp_neg(-32.0 * (best - dist)) + 1.0;
            best = dist;
        } else {
            sum += exp_neg(-32.0 * (dist - best));
        }
    }
    best - ln(sum) / 32.0
}

/// Russian-roulette estimator of [`smooth_voronoi3`] (Algorithm 3): ξ picks one of the 2×2×2
/// cells nearest `p`; its point's distance, clamped to 0.5 (about the function's mean), is the
/// cheap approximation kept with probability `q`; otherwise the full function corrects it
/// (eq. 5). `q` is clamped to `[0, 1)`.
#[inline]
pub fn smooth_voronoi3_stochastic(p: [f32; 3], seed: u32, q: f32, xi: f32) -> f32 {
    let (c, f) = setup(p);
    let xi = sanitize_xi(xi) * 8.0;
    let bits = (xi as u32).min(7);
    let rest = (xi - bits as f32).clamp(0.0, ONE_BELOW);
    let mut d = [0i8; 3];
    for a in 0..3 {
        let low = if f[a] < 0.5 { -1 } else { 0 };
        d[a] = low + ((bits >> a) & 1) as i8;
    }
    let approx = sqrt_fast(d2_to(c, f, d, seed)).min(0.5);
    russian_roulette(q, rest, approx, || smooth_voronoi3(p, seed))
}
