//! 3D simplex noise (Perlin 2001) and its one-sample estimator. Simplex noise is a weighted sum
//! over the 4 corners of the simplex holding the point, with weights `(½ − r²)⁴ ≥ 0`; the
//! estimator picks one corner with probability proportional to its weight (eq. 1 with
//! importance sampling) and evaluates only that corner's gradient.

use super::estimators::sanitize_xi;
use super::hash::hash3;
use crate::math::split;

const G3: f32 = 1.0 / 6.0;
const SCALE: f32 = 32.0;

/// The simplex corners of `p`: lattice cell and offsets of each corner.
#[inline(always)]
fn corners(p: [f32; 3]) -> ([[i32; 3]; 4], [[f32; 3]; 4]) {
    let s = (p[0] + p[1] + p[2]) * (1.0 / 3.0);
    let (i, fx) = split(p[0] + s);
    let (j, fy) = split(p[1] + s);
    let (k, fz) = split(p[2] + s);
    // Unskewed offset from the cell origin: f − (Σf)·G3 (exact, independent of the magnitude of p).
    let t = (fx + fy + fz) * G3;
    let d0 = [fx - t, fy - t, fz - t];
    let (o1, o2) = if d0[0] >= d0[1] {
        if d0[1] >= d0[2] {
            ([1, 0, 0], [1, 1, 0])
        } else if d0[0] >= d0[2] {
            ([1, 0, 0], [1, 0, 1])
        } else {
            ([0, 0, 1], [1, 0, 1])
        }
    } else if d0[1] < d0[2] {
        ([0, 0, 1], [0, 1, 1])
    } else if d0[0] < d0[2] {
        ([0, 1, 0], [0, 1, 1])
    } else {
        ([0, 1, 0], [1, 1, 0])
    };
    let cell = |o: [i32; 3]| {
        [
            i.wrapping_add(o[0]),
            j.wrapping_add(o[1]),
            k.wrapping_add(o[2]),
        ]
    };
    let off = |o: [i32; 3], n: f32| {
        [
            d0[0] - o[0] as f32 + n * G3,
            d0[1] - o[1] as f32 + n * G3,
            d0[2] - o[2] as f32 + n * G3,
        ]
    };
    (
        [cell([0, 0, 0]), cell(o1), cell(o2), cell([1, 1, 1])],
        [d0, off(o1, 1.0), off(o2, 2.0), off([1, 1, 1], 3.0)],
    )
}

#[inline(always)]
fn weight(d: [f32; 3]) -> f32 {
    let t = 0.5 - (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if t > 0.0 { (t * t) * (t * t) } else { 0.0 }
}

#[inline(always)]
fn grad_dot(c: [i32; 3], d: [f32; 3], seed: u32) -> f32 {
    // The 12 edge gradients picked from the hash's top bits (as in improved noise).
    let h = hash3(c[0], c[1], c[2], seed) >> 28;
    let (u, v) = match h {
        0..=3 => (d[0], d[1]),
        4..=7 => (d[0], d[2]),
        8..=11 => (d[1], d[2]),
        12 | 14 => (d[1], d[0]),
        _ => (d[1], d[2]),
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

/// 3D simplex noise, about `[-1, 1]`.
#[inline]
pub fn simplex3(p: [f32; 3], seed: u32) -> f32 {
    let (c, d) = corners(p);
    let mut n = 0.0;
    for k in 0..4 {
        let w = weight(d[k]);
        if w > 0.0 {
            n += w * grad_dot(c[k], d[k], seed);
        }
    }
    SCALE * n
}

/// One-sample estimator of [`simplex3`]: one gradient, chosen with probability ∝ its weight.
#[inline]
pub fn simplex3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> f32 {
    let (c, d) = corners(p);
    let w = [weight(d[0]), weight(d[1]), weight(d[2]), weight(d[3])];
    let total = w[0] + w[1] + w[2] + w[3];
    if total <= 0.0 {
        return 0.0;
    }
    let mut target = sanitize_xi(xi) * total;
    let mut k = 3;
    for (i, &wi) in w.iter().enumerate() {
        if target < wi {
            k = i;
            break;
        }
        target -= wi;
    }
    // Guard against rounding landing on a zero-weight corner.
    while w[k] <= 0.0 {
        k -= 1;
    }
    SCALE * total * grad_dot(c[k], d[k], seed)
}
