//! The 3D and 4D Perlin pairs on SSE2 lanes (the [`crate::lanes`] module), for coordinates
//! in the split range: the split and the fades of all axes run in one register, and the
//! deterministic forms' dot products as transposed groups of four. Bit for bit the scalar
//! forms (`perlin3_with`, `perlin3_stochastic_with`, `perlin4_with`,
//! `perlin4_stochastic_with`), which remain the code on other targets; the tests compare the
//! two.

use super::{GRAD3, GRAD4, Narrowing, PRIME, unit_corner};
use crate::hash::CORNER_MUL;
use crate::lanes::{self, F4, I4};

/// [`perlin3`](super::perlin3) on lanes, `None` outside the split range (where the scalar
/// form runs). The four entry points below have the shape the scalar ones dispatch on.
#[inline(always)]
pub(super) fn perlin3(p: [f32; 3], seed: u32) -> Option<f32> {
    let v = F4::from3(p);
    lanes::in_split_range(v).then(|| perlin3_in_range(v, seed))
}

/// [`perlin3_stochastic`](super::perlin3_stochastic) on lanes, `None` outside the split range.
#[inline(always)]
pub(super) fn perlin3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> Option<f32> {
    let v = F4::from3(p);
    lanes::in_split_range(v).then(|| perlin3_stochastic_in_range(v, seed, xi))
}

/// [`perlin4`](super::perlin4) on lanes, `None` outside the split range.
#[inline(always)]
pub(super) fn perlin4(p: [f32; 4], seed: u32) -> Option<f32> {
    let v = F4::from4(p);
    lanes::in_split_range(v).then(|| perlin4_in_range(v, seed))
}

/// [`perlin4_stochastic`](super::perlin4_stochastic) on lanes, `None` outside the split range.
#[inline(always)]
pub(super) fn perlin4_stochastic(p: [f32; 4], seed: u32, xi: f32) -> Option<f32> {
    let v = F4::from4(p);
    lanes::in_split_range(v).then(|| perlin4_stochastic_in_range(v, seed, xi))
}

/// The corner of a `D`-dimensional cell that the narrowing `n` picks for the fixed-point
/// weights `t`, hashed axis by axis as it is picked: each axis adds its lower side's product
/// and, on the upper side, the axis prime under the decision's mask (an add, no multiply and
/// no select after the decision). Returns the corner's hash (before its finishing multiply)
/// and its number `k` (bit `a` set on the upper side of axis `a`).
#[inline(always)]
fn pick_corner<const D: usize>(
    cell: [u32; D],
    t: [u32; D],
    seed: u32,
    mut n: Narrowing,
) -> (u32, u32) {
    let mut h = seed;
    let mut k = 0;
    for a in 0..D {
        let up = n.upper_fixed(t[a] as u64);
        h ^= cell[a].wrapping_mul(PRIME[a]).wrapping_add(up & PRIME[a]);
        k |= (up & 1) << a;
    }
    (h, k)
}

/// The gradient row of corner hash `h` (before its finishing multiply).
#[inline(always)]
fn grad(h: u32) -> F4 {
    F4::new(&GRAD3.0[(h.wrapping_mul(CORNER_MUL) >> 28) as usize])
}

/// [`perlin3`](super::perlin3) of a point already in lanes (lane 3 is ignored): for the
/// deterministic fBm, which scales one register per octave.
#[inline(always)]
pub(crate) fn perlin3_lanes(v: F4, seed: u32) -> f32 {
    if lanes::in_split_range(v) {
        perlin3_in_range(v, seed)
    } else {
        super::perlin3_with([v.x(), v.y(), v.z()], seed, crate::math::split)
    }
}

/// [`perlin3`](super::perlin3) for a point in the split range.
#[inline(always)]
fn perlin3_in_range(v: F4, seed: u32) -> f32 {
    let (cell, f) = lanes::split_in_range(v);
    let t = lanes::fade(f);
    let [cx, cy, cz] = cell.xyz();
    let xp0 = cx.wrapping_mul(PRIME[0]);
    let yp0 = cy.wrapping_mul(PRIME[1]);
    let zp0 = cz.wrapping_mul(PRIME[2]);
    let (xp1, yp1, zp1) = (
        xp0.wrapping_add(PRIME[0]),
        yp0.wrapping_add(PRIME[1]),
        zp0.wrapping_add(PRIME[2]),
    );
    // The corners by (y, z): 00, 10, 01, 11; then once with x = 0 and once with x = 1.
    let yz = [
        seed ^ yp0 ^ zp0,
        seed ^ yp1 ^ zp0,
        seed ^ yp0 ^ zp1,
        seed ^ yp1 ^ zp1,
    ];
    // The four corners of a group by lanes, as columns: the gradient rows transposed, times
    // the offsets from the corners along each axis. The offsets along y and z are the same
    // in both groups, (y, z) = 00, 10, 01, 11 by lane; along x, `x` for the lower corners
    // and `x − 1` for the upper. The same products and sums as the scalar form's dot
    // products, in the same order.
    let f1 = f - F4::splat(1.0);
    let yy = F4::shuffle::<0b01_01_01_01>(f, f1);
    let dy = F4::shuffle::<0b10_00_10_00>(yy, yy);
    let dz = F4::shuffle::<0b10_10_10_10>(f, f1);
    let dots = |h: [u32; 4], dx: F4| {
        let [gx, gy, gz, _] = F4::transpose([grad(h[0]), grad(h[1]), grad(h[2]), grad(h[3])]);
        (gx * dx + gy * dy) + gz * dz
    };
    let lo = dots(yz.map(|h| h ^ xp0), f.xxxx());
    let hi = dots(yz.map(|h| h ^ xp1), f1.xxxx());
    // The scalar form's nested lerps, x first: lanes (y, z) = 00, 10, 01, 11; then y: lanes
    // z = 0, 1; then z.
    let a = F4::lerp(t.xxxx(), lo, hi);
    let b = F4::lerp(t.yyyy(), a.xzxz(), a.ywyw());
    let (b0, b1, w) = (b.x(), b.y(), t.z());
    b0 + w * (b1 - b0)
}

/// [`perlin3_stochastic`](super::perlin3_stochastic) for a point in the split range.
#[inline(always)]
fn perlin3_stochastic_in_range(v: F4, seed: u32, xi: f32) -> f32 {
    let (cell, f) = lanes::split_in_range(v);
    perlin3_stochastic_cell(cell, f, seed, Narrowing::new(xi))
}

/// The estimator at offset `f` in cell `cell` (lanes 0–2), with ξ already in its
/// [`Narrowing`]: for callers that find the cell another way (the fBm estimator splits once at
/// its finest octave).
#[inline(always)]
pub(crate) fn perlin3_stochastic_cell(cell: I4, f: F4, seed: u32, n: Narrowing) -> f32 {
    let t = lanes::fixed(lanes::fade(f)).xyz();
    let (h, k) = pick_corner(cell.xyz(), t, seed, n);
    (grad(h) * (f - F4::new(&unit_corner(k)))).sum3()
}

/// The gradient row of 4D corner hash `h` (before its finishing multiply).
#[inline(always)]
fn grad4(h: u32) -> F4 {
    F4::new(&GRAD4.0[(h.wrapping_mul(CORNER_MUL) >> 27) as usize])
}

/// [`perlin4`](super::perlin4) for a point in the split range.
#[inline(always)]
fn perlin4_in_range(v: F4, seed: u32) -> f32 {
    let (cell, f) = lanes::split_in_range(v);
    let t = lanes::fade(f);
    let c = cell.xyzw();
    let lo: [u32; 4] = core::array::from_fn(|a| c[a].wrapping_mul(PRIME[a]));
    let side = |a: usize, up: usize| lo[a].wrapping_add(PRIME[a] & 0u32.wrapping_sub(up as u32));
    // Corner `c` has bit `a` set on the upper side of axis `a`; its hash is the xor of its
    // sides' products, built from the (z, w) pairs out.
    let zw: [u32; 4] = core::array::from_fn(|i| seed ^ side(2, i & 1) ^ side(3, i >> 1));
    let dot = |c: usize| {
        let h = zw[c >> 2] ^ side(1, (c >> 1) & 1) ^ side(0, c & 1);
        grad4(h) * (f - F4::new(&unit_corner(c as u32)))
    };
    // The scalar form's nested lerps, x first: corners with x = 0 and x = 1 for (y, z) = 00,
    // 10, 01, 11, at w = 0 and at w = 1.
    let x0 = F4::lerp(
        t.xxxx(),
        F4::sums4([dot(0), dot(2), dot(4), dot(6)]),
        F4::sums4([dot(1), dot(3), dot(5), dot(7)]),
    );
    let x1 = F4::lerp(
        t.xxxx(),
        F4::sums4([dot(8), dot(10), dot(12), dot(14)]),
        F4::sums4([dot(9), dot(11), dot(13), dot(15)]),
    );
    // Then y (lanes (z, w) = 00, 10, 01, 11), then z (lanes w = 0, 1), then w.
    let y = F4::lerp(t.yyyy(), F4::evens(x0, x1), F4::odds(x0, x1));
    let z = F4::lerp(t.zzzz(), F4::evens(y, y), F4::odds(y, y));
    let (z0, z1) = (z.x(), z.y());
    z0 + t.w() * (z1 - z0)
}

/// [`perlin4_stochastic`](super::perlin4_stochastic) for a point in the split range.
#[inline(always)]
fn perlin4_stochastic_in_range(v: F4, seed: u32, xi: f32) -> f32 {
    let (cell, f) = lanes::split_in_range(v);
    let t = lanes::fixed(lanes::fade(f)).xyzw();
    let (h, k) = pick_corner(cell.xyzw(), t, seed, Narrowing::new(xi));
    (grad4(h) * (f - F4::new(&unit_corner(k)))).sum4()
}

#[cfg(test)]
mod tests {
    use super::super::perlin3_with;
    use super::*;
    use crate::math::split_in_range;
    use crate::stochastic::estimators::ONE_BELOW;

    /// Calls `check` at points that are hard for the split (integers, their neighbouring
    /// floats, ±0, the smallest magnitudes, the edge of the split range), every triple of
    /// them, and at random points.
    fn points(mut check: impl FnMut(usize, [f32; 3])) {
        let mut hard = [0.0f32; 34];
        hard[..6].copy_from_slice(&[0.0, -0.0, 1e-45, -1e-45, 4_194_303.5, -4_194_303.5]);
        for k in 0..7 {
            let v = k as f32 - 3.0;
            let up = f32::from_bits(v.abs().to_bits() + 1);
            hard[6 + 4 * k..10 + 4 * k].copy_from_slice(&[v, up, -up, v + 0.5]);
        }
        let n = hard.len();
        for i in 0..n * n * n {
            check(i, [hard[i % n], hard[i / n % n], hard[i / n / n]]);
        }
        let mut next = crate::stochastic::uniforms(0x9e37_79b9_7f4a_7c15);
        for i in 0..100_000 {
            check(n * n * n + i, [0; 3].map(|_| (next() - 0.5) * 2e3));
        }
    }

    #[test]
    fn lane_forms_4d_are_the_scalar_forms_bit_for_bit() {
        let mut next = crate::stochastic::uniforms(0x853c_49e6_748f_ea9b);
        let odd_xi = [0.0, -0.0, ONE_BELOW, 1.0, 2.0, -1.0, f32::NAN, 1e-30];
        // The 3D points with w from a fourth coordinate that walks the same hard values.
        let mut w = 0.0f32;
        points(|i, p| {
            let p = [p[0], p[1], p[2], w];
            w = if i % 7 == 0 { -p[0] } else { p[1] + p[2] };
            let seed = (i as u32).wrapping_mul(0x9e37_79b9);
            let d = perlin4_in_range(F4::from4(p), seed);
            let want = super::super::perlin4_with(p, seed, split_in_range);
            assert_eq!(
                d.to_bits(),
                want.to_bits(),
                "perlin4 at {p:?}: {d} vs {want}"
            );
            let xi = if i % 4 == 0 {
                odd_xi[i / 4 % odd_xi.len()]
            } else {
                next()
            };
            let s = perlin4_stochastic_in_range(F4::from4(p), seed, xi);
            let want = super::super::perlin4_stochastic_with(p, seed, xi, split_in_range);
            assert_eq!(
                s.to_bits(),
                want.to_bits(),
                "estimator at {p:?}, ξ {xi}: {s} vs {want}"
            );
        });
    }

    #[test]
    fn lane_forms_are_the_scalar_forms_bit_for_bit() {
        let mut next = crate::stochastic::uniforms(0x2545_f491_4f6c_dd1d);
        let odd_xi = [0.0, -0.0, ONE_BELOW, 1.0, 2.0, -1.0, f32::NAN, 1e-30];
        points(|i, p| {
            let seed = (i as u32).wrapping_mul(0x9e37_79b9);
            let d = perlin3_in_range(F4::from3(p), seed);
            let want = perlin3_with(p, seed, split_in_range);
            assert_eq!(
                d.to_bits(),
                want.to_bits(),
                "perlin3 at {p:?}: {d} vs {want}"
            );
            let xi = if i % 4 == 0 {
                odd_xi[i / 4 % odd_xi.len()]
            } else {
                next()
            };
            let s = super::perlin3_stochastic_in_range(F4::from3(p), seed, xi);
            let want = super::super::perlin3_stochastic_in_range(p, seed, xi);
            assert_eq!(
                s.to_bits(),
                want.to_bits(),
                "estimator at {p:?}, ξ {xi}: {s} vs {want}"
            );
        });
    }
}
