//! [`simplex3`](super::simplex3) and its estimator on SSE2 lanes
//! (the [`crate::lanes`] module), for skewed points in the split range: the split as one
//! register, the four corners' squared distances, weights and gradient dot products each as
//! one register (by transposes). Bit for bit the scalar forms, which remain the code on other
//! targets; the tests compare the two.

use super::{G3, GRAD, SCALE, rank_order};
use crate::lanes::{self, F4};
use crate::stochastic::estimators::{sanitize_xi, unit_corner};
use crate::stochastic::hash::hash3;

/// [`GRAD`] padded to four lanes, so that a row is one load.
static GRAD_ROWS: [[f32; 4]; 16] = {
    let mut r = [[0.0f32; 4]; 16];
    let mut h = 0;
    while h < 16 {
        r[h] = [GRAD[h][0], GRAD[h][1], GRAD[h][2], 0.0];
        h += 1;
    }
    r
};

/// The simplex corners of `p` (lattice points and offsets, as `corners` gives them), or
/// `None` when the skewed point leaves the split range.
#[inline(always)]
fn corners(p: [f32; 3]) -> Option<([[i32; 3]; 4], [F4; 4])> {
    let s = (p[0] + p[1] + p[2]) * (1.0 / 3.0);
    let q = F4::from3([p[0] + s, p[1] + s, p[2] + s]);
    if !lanes::in_split_range(q) {
        return None;
    }
    let (cell, f) = lanes::split_in_range(q);
    let d0 = f - F4::splat(f.sum3() * G3);
    let (o1, o2) = rank_order([d0.x(), d0.y(), d0.z()]);
    let bits = |o: [i32; 3]| (o[0] | o[1] << 1 | o[2] << 2) as u32;
    let off = |o: [i32; 3], n: f32| (d0 - F4::new(&unit_corner(bits(o)))) + F4::splat(n * G3);
    let [i, j, k] = cell.xyz().map(|c| c as i32);
    let at = |o: [i32; 3]| {
        [
            i.wrapping_add(o[0]),
            j.wrapping_add(o[1]),
            k.wrapping_add(o[2]),
        ]
    };
    Some((
        [at([0, 0, 0]), at(o1), at(o2), at([1, 1, 1])],
        [d0, off(o1, 1.0), off(o2, 2.0), off([1, 1, 1], 3.0)],
    ))
}

/// The four corners' weights `max(½ − r², 0)⁴`.
#[inline(always)]
fn weights(d: [F4; 4]) -> F4 {
    let t = (F4::splat(0.5) - F4::sums3(d.map(|v| v * v))).max(F4::splat(0.0));
    (t * t) * (t * t)
}

/// The gradient of lattice point `c` (as `grad_dot` picks it).
#[inline(always)]
fn grad(c: [i32; 3], seed: u32) -> F4 {
    F4::new(&GRAD_ROWS[(hash3(c[0], c[1], c[2], seed) >> 28) as usize])
}

/// [`simplex3`](super::simplex3), or `None` when the skewed point leaves the split range.
#[inline(always)]
pub(super) fn simplex3(p: [f32; 3], seed: u32) -> Option<f32> {
    let (c, d) = corners(p)?;
    let dots = F4::sums3([0, 1, 2, 3].map(|k| grad(c[k], seed) * d[k]));
    let v = weights(d) * dots;
    // The scalar form's running sum, from 0.0.
    Some(SCALE * ((((0.0 + v.x()) + v.y()) + v.z()) + v.w()))
}

/// [`simplex3_stochastic`](super::simplex3_stochastic), or `None` when the skewed point
/// leaves the split range.
#[inline(always)]
pub(super) fn simplex3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> Option<f32> {
    let (c, d) = corners(p)?;
    let w = weights(d);
    let ends = [w.x(), w.x() + w.y(), (w.x() + w.y()) + w.z()];
    let total = ends[2] + w.w();
    if total <= 0.0 {
        return Some(0.0);
    }
    let target = (sanitize_xi(xi) * total).min(f32::from_bits(total.to_bits() - 1));
    let k = ends.iter().map(|&e| (target >= e) as usize).sum::<usize>() & 3;
    Some(SCALE * total * (grad(c[k], seed) * d[k]).sum3())
}

#[cfg(test)]
mod tests {
    use super::super::{simplex3_scalar, simplex3_stochastic_scalar};
    use crate::stochastic::estimators::ONE_BELOW;

    #[test]
    fn lane_forms_are_the_scalar_forms_bit_for_bit() {
        // Random points, points where offsets tie (the diagonal, the cells' faces: the rank
        // order's hard cases), lattice points and their neighbouring floats, and the edge of
        // the split range for the skewed point.
        let mut next = crate::stochastic::uniforms(0x1f83_d9ab_fb41_bd6b);
        let xis = [0.0f32, -0.0, 1e-30, 0.5, ONE_BELOW, 1.0, 2.0, f32::NAN];
        let mut compared = 0;
        for i in 0..200_000usize {
            let p = match i % 4 {
                0 | 1 => [0; 3].map(|_| (next() - 0.5) * 200.0),
                2 => {
                    let (t, u) = ((i / 4) as f32 / 97.0 - 30.0, next() * 8.0);
                    [[t, t, t], [t, t, u], [t, u, t], [u, t, t], [t, -t, 0.5 * t]][i / 4 % 5]
                }
                _ => {
                    let k = [0.0f32, 1.0, -1.0, 2_097_151.0, -2_097_151.0][i / 4 % 5];
                    let n = f32::from_bits(k.abs().to_bits() + (i as u32 / 20 % 3));
                    [n.copysign(k), k, -n]
                }
            };
            let seed = i as u32;
            let xi = if i % 3 == 0 {
                xis[i / 3 % xis.len()]
            } else {
                next()
            };
            // Points whose skewed form leaves the split range take the scalar form anyway.
            if let Some(a) = super::simplex3(p, seed) {
                let b = simplex3_scalar(p, seed);
                assert_eq!(a.to_bits(), b.to_bits(), "{p:?}: {a} vs {b}");
                let a = super::simplex3_stochastic(p, seed, xi).unwrap();
                let b = simplex3_stochastic_scalar(p, seed, xi);
                assert_eq!(a.to_bits(), b.to_bits(), "{p:?}, ξ {xi}: {a} vs {b}");
                compared += 1;
            }
        }
        assert!(compared > 190_000, "{compared}");
    }
}
