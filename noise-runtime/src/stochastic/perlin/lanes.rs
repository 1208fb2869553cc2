//! The 3D and 4D Perlin pairs on the lane layer ([`crate::lanes`]): the one kernel of each,
//! on every target. The split and the fades of all axes run in one register, the
//! deterministic forms' dot products as transposed groups of four, and the estimator's chosen
//! corner as one row. A point in the split range (`|x| < 2^22`, the common case) is split on
//! lanes; any other point (huge, infinite or NaN coordinates) by the exact scalar
//! [`split`](crate::math::split), after which the same kernel runs. The tests compare each
//! kernel with the textbook scalar form (nested lerps over the corners, Perlin 2002;
//! Algorithm 1 of Fajardo & Pharr for the estimators) bit for bit.

use super::{Narrowing, PRIME, unit_corner};
use crate::gradients::{edge3, edge4};
use crate::hash::CORNER_MUL;
use crate::lanes::{self, F4, I4};
use crate::math::on_cells;

/// [`perlin3`](super::perlin3).
#[inline(always)]
pub(super) fn perlin3(p: [f32; 3], seed: u32) -> f32 {
    on_cells!(F4::from3(p), |cell, f| perlin3_cell(cell, f, seed))
}

/// [`perlin3_stochastic`](super::perlin3_stochastic).
#[inline(always)]
pub(super) fn perlin3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> f32 {
    on_cells!(F4::from3(p), |cell, f| {
        perlin3_stochastic_cell(cell, f, seed, Narrowing::new(xi))
    })
}

/// [`perlin4`](super::perlin4).
#[inline(always)]
pub(super) fn perlin4(p: [f32; 4], seed: u32) -> f32 {
    on_cells!(F4::from4(p), |cell, f| perlin4_cell(cell, f, seed))
}

/// [`perlin4_stochastic`](super::perlin4_stochastic).
#[inline(always)]
pub(super) fn perlin4_stochastic(p: [f32; 4], seed: u32, xi: f32) -> f32 {
    on_cells!(F4::from4(p), |cell, f| {
        perlin4_stochastic_cell(cell, f, seed, xi)
    })
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
    F4::new(edge3(h.wrapping_mul(CORNER_MUL)))
}

/// [`perlin3`](super::perlin3) of a point already in lanes: for the deterministic fBm, which
/// scales one register per octave. Lane 3 must be 0, or non-finite only where another lane
/// is (as `0 · freq` is).
#[inline(always)]
pub(crate) fn perlin3_lanes(v: F4, seed: u32) -> f32 {
    on_cells!(v, |cell, f| perlin3_cell(cell, f, seed))
}

/// The 3D kernel: [`perlin3`](super::perlin3) at offset `f` (lanes 0–2) in cell `cell`.
#[inline(always)]
fn perlin3_cell(cell: I4, f: F4, seed: u32) -> f32 {
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
    F4::new(edge4(h.wrapping_mul(CORNER_MUL)))
}

/// The 4D kernel: [`perlin4`](super::perlin4) at offset `f` in cell `cell`.
#[inline(always)]
fn perlin4_cell(cell: I4, f: F4, seed: u32) -> f32 {
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

/// The 4D estimator at offset `f` in cell `cell`.
#[inline(always)]
fn perlin4_stochastic_cell(cell: I4, f: F4, seed: u32, xi: f32) -> f32 {
    let t = lanes::fixed(lanes::fade(f)).xyzw();
    let (h, k) = pick_corner(cell.xyzw(), t, seed, Narrowing::new(xi));
    (grad4(h) * (f - F4::new(&unit_corner(k)))).sum4()
}

#[cfg(test)]
mod tests {
    //! The kernels against the textbook forms, written plainly in scalar code here: the nested
    //! lerps over the corners (Perlin 2002) and Algorithm 1 of Fajardo & Pharr, with the exact
    //! scalar splits. They share the kernels' gradient tables, hashes and corner choice, and sum
    //! in the same order, so the two agree bit for bit.
    use super::super::{g3, g4, lerp, perlin3, perlin3_stochastic, perlin4, perlin4_stochastic};
    use crate::hash::corner;
    use crate::hash::{CORNER_MUL, PRIME};
    use crate::math::{fade, in_split_range, split, split_in_range};
    use crate::stochastic::estimators::{Narrowing, ONE_BELOW, nested_corner, unit_corner};

    /// The split of every axis: the short one when all are in its range, else the general one
    /// (they differ in the offset of a subnormal negative coordinate, 1 or the float below).
    fn splits<const N: usize>(p: [f32; N]) -> [(i32, f32); N] {
        if in_split_range(p) {
            p.map(split_in_range)
        } else {
            p.map(split)
        }
    }

    fn perlin3_reference(p: [f32; 3], seed: u32) -> f32 {
        let [(ix, x), (iy, y), (iz, z)] = splits(p);
        let (u, v, w) = (fade(x), fade(y), fade(z));
        let c = |i: [i32; 3], d: [f32; 3]| {
            let h = |a: usize| (i[a] as u32).wrapping_mul(PRIME[a]);
            let g = g3(corner(seed, h(0), h(1), h(2)));
            g[0] * d[0] + g[1] * d[1] + g[2] * d[2]
        };
        let (x1, y1, z1) = (x - 1.0, y - 1.0, z - 1.0);
        let (jx, jy, jz) = (ix.wrapping_add(1), iy.wrapping_add(1), iz.wrapping_add(1));
        lerp(
            w,
            lerp(
                v,
                lerp(u, c([ix, iy, iz], [x, y, z]), c([jx, iy, iz], [x1, y, z])),
                lerp(u, c([ix, jy, iz], [x, y1, z]), c([jx, jy, iz], [x1, y1, z])),
            ),
            lerp(
                v,
                lerp(u, c([ix, iy, jz], [x, y, z1]), c([jx, iy, jz], [x1, y, z1])),
                lerp(
                    u,
                    c([ix, jy, jz], [x, y1, z1]),
                    c([jx, jy, jz], [x1, y1, z1]),
                ),
            ),
        )
    }

    fn perlin3_stochastic_reference(p: [f32; 3], seed: u32, xi: f32) -> f32 {
        let s = splits(p);
        let mut n = Narrowing::new(xi);
        let (mut h, mut k) = (seed, 0);
        for (a, &(c, f)) in s.iter().enumerate() {
            let up = n.upper(fade(f));
            h ^= (c as u32)
                .wrapping_mul(PRIME[a])
                .wrapping_add(up & PRIME[a]);
            k |= (up & 1) << a;
        }
        let g = g3(h.wrapping_mul(CORNER_MUL));
        let o = unit_corner(k);
        g[0] * (s[0].1 - o[0]) + g[1] * (s[1].1 - o[1]) + g[2] * (s[2].1 - o[2])
    }

    /// `g · (f − o)` summed in pairs, the 4D forms' order.
    fn dot4(g: [f32; 4], f: [f32; 4], o: [f32; 4]) -> f32 {
        (g[0] * (f[0] - o[0]) + g[1] * (f[1] - o[1]))
            + (g[2] * (f[2] - o[2]) + g[3] * (f[3] - o[3]))
    }

    fn grad4(cell: [i32; 4], up: [u32; 4], seed: u32) -> [f32; 4] {
        let mut h = seed;
        for a in 0..4 {
            h ^= (cell[a] as u32)
                .wrapping_mul(PRIME[a])
                .wrapping_add(up[a] & PRIME[a]);
        }
        g4(h.wrapping_mul(CORNER_MUL))
    }

    fn perlin4_reference(p: [f32; 4], seed: u32) -> f32 {
        let s = splits(p);
        let (cell, f) = (s.map(|v| v.0), s.map(|v| v.1));
        let u = f.map(fade);
        let corner = |c: usize| {
            let up: [u32; 4] = core::array::from_fn(|a| 0u32.wrapping_sub(((c >> a) & 1) as u32));
            dot4(grad4(cell, up, seed), f, unit_corner(c as u32))
        };
        let x = |c: usize| lerp(u[0], corner(c), corner(c + 1));
        let cube = |w: usize| {
            lerp(
                u[2],
                lerp(u[1], x(w), x(w + 2)),
                lerp(u[1], x(w + 4), x(w + 6)),
            )
        };
        lerp(u[3], cube(0), cube(8))
    }

    fn perlin4_stochastic_reference(p: [f32; 4], seed: u32, xi: f32) -> f32 {
        let s = splits(p);
        let (cell, f) = (s.map(|v| v.0), s.map(|v| v.1));
        let c = nested_corner(xi, f.map(fade));
        dot4(grad4(cell, c.masks(), seed), f, c.floats())
    }

    /// Calls `check` at points that are hard for the split (integers, their neighbouring
    /// floats, ±0, the smallest magnitudes, both sides of the edge of the split range, huge,
    /// infinite and NaN coordinates), every triple of them, and at random points.
    fn points(mut check: impl FnMut(usize, [f32; 3])) {
        let mut hard = [0.0f32; 40];
        hard[..12].copy_from_slice(&crate::stochastic::HARD_COORDINATES);
        for k in 0..7 {
            let v = k as f32 - 3.0;
            let up = f32::from_bits(v.abs().to_bits() + 1);
            hard[12 + 4 * k..16 + 4 * k].copy_from_slice(&[v, up, -up, v + 0.5]);
        }
        let n = hard.len();
        for i in 0..n * n * n {
            check(i, [hard[i % n], hard[i / n % n], hard[i / n / n]]);
        }
        let mut next = crate::stochastic::uniforms(0x9e37_79b9_7f4a_7c15);
        for i in 0..100_000 {
            let scale = [2e3, 1e7][i % 2];
            check(n * n * n + i, [0; 3].map(|_| (next() - 0.5) * scale));
        }
    }

    const ODD_XI: [f32; 8] = [0.0, -0.0, ONE_BELOW, 1.0, 2.0, -1.0, f32::NAN, 1e-30];

    fn same(got: f32, want: f32, what: impl Fn() -> std::string::String) {
        assert_eq!(got.to_bits(), want.to_bits(), "{}: {got} vs {want}", what());
    }

    #[test]
    fn the_3d_kernels_are_the_textbook_forms_bit_for_bit() {
        let mut next = crate::stochastic::uniforms(0x2545_f491_4f6c_dd1d);
        points(|i, p| {
            let seed = (i as u32).wrapping_mul(0x9e37_79b9);
            same(perlin3(p, seed), perlin3_reference(p, seed), || {
                std::format!("perlin3 at {p:?}")
            });
            let xi = if i % 4 == 0 {
                ODD_XI[i / 4 % ODD_XI.len()]
            } else {
                next()
            };
            same(
                perlin3_stochastic(p, seed, xi),
                perlin3_stochastic_reference(p, seed, xi),
                || std::format!("estimator at {p:?}, ξ {xi}"),
            );
        });
    }

    #[test]
    fn the_4d_kernels_are_the_textbook_forms_bit_for_bit() {
        let mut next = crate::stochastic::uniforms(0x853c_49e6_748f_ea9b);
        // The 3D points with w from a fourth coordinate that walks the same hard values.
        let mut w = 0.0f32;
        points(|i, p| {
            let p = [p[0], p[1], p[2], w];
            w = if i % 7 == 0 { -p[0] } else { p[1] + p[2] };
            let seed = (i as u32).wrapping_mul(0x9e37_79b9);
            same(perlin4(p, seed), perlin4_reference(p, seed), || {
                std::format!("perlin4 at {p:?}")
            });
            let xi = if i % 4 == 0 {
                ODD_XI[i / 4 % ODD_XI.len()]
            } else {
                next()
            };
            same(
                perlin4_stochastic(p, seed, xi),
                perlin4_stochastic_reference(p, seed, xi),
                || std::format!("estimator at {p:?}, ξ {xi}"),
            );
        });
    }
}
