//! [`simplex3`](super::simplex3), [`simplex4`](super::simplex4) and their estimators on the
//! lane layer ([`crate::lanes`]), the one kernel of each on every target: the split as one
//! register, the corners' squared distances, weights and gradient dot products as registers
//! (by transposes). Bit for bit the general lattice's forms ([`lattice`](super::lattice)),
//! which the tests compare them with.

use super::{G3, SCALE, SCALE4, SKEW4, rank_order};
use crate::gradients::{edge3_simplex as edge3, edge4};
use crate::hash::{CORNER_MUL, PRIME, hash3};
use crate::lanes::{F4, I4};
use crate::math::on_cells;
use crate::stochastic::estimators::{sanitize_xi, unit_corner};

/// `kernel` of the simplex corners of `p` (lattice points and offsets, as `corners` gives
/// them).
#[inline(always)]
fn on_corners<R>(p: [f32; 3], kernel: impl FnOnce([[i32; 3]; 4], [F4; 4]) -> R) -> R {
    // The point read once into lanes (see `F4::from3`), and the skew from them: `(x + y) + z`
    // as the lattice form sums it. Lane 3 becomes `s`; it is never used, and cannot change the
    // range test: when `|s| ≥ 2^22`, the skewed coordinates sum to `6s`, so one of them is
    // out of range too.
    let v = F4::from3(p);
    let s = v.sum3() * (1.0 / 3.0);
    let q = v + F4::splat(s);
    on_cells!(q, |cell, f| {
        let (c, d) = corners_of(cell, f);
        kernel(c, d)
    })
}

/// The corners of a skewed point split into `cell` and `f`.
#[inline(always)]
fn corners_of(cell: I4, f: F4) -> ([[i32; 3]; 4], [F4; 4]) {
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
    (
        [at([0, 0, 0]), at(o1), at(o2), at([1, 1, 1])],
        [d0, off(o1, 1.0), off(o2, 2.0), off([1, 1, 1], 3.0)],
    )
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
    F4::new(edge3(hash3(c[0], c[1], c[2], seed)))
}

/// [`simplex3`](super::simplex3).
#[inline(always)]
pub(super) fn simplex3(p: [f32; 3], seed: u32) -> f32 {
    on_corners(p, |c, d| simplex3_of(c, d, seed))
}

/// [`simplex3`] from its corners.
#[inline(always)]
fn simplex3_of(c: [[i32; 3]; 4], d: [F4; 4], seed: u32) -> f32 {
    let dots = F4::sums3([0, 1, 2, 3].map(|k| grad(c[k], seed) * d[k]));
    let v = weights(d) * dots;
    // The scalar form's running sum, from 0.0.
    SCALE * ((((0.0 + v.x()) + v.y()) + v.z()) + v.w())
}

/// [`simplex3_stochastic`](super::simplex3_stochastic).
#[inline(always)]
pub(super) fn simplex3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> f32 {
    on_corners(p, |c, d| simplex3_stochastic_of(c, d, seed, xi))
}

/// [`simplex3_stochastic`] from its corners.
#[inline(always)]
fn simplex3_stochastic_of(c: [[i32; 3]; 4], d: [F4; 4], seed: u32, xi: f32) -> f32 {
    let w = weights(d);
    let ends = [w.x(), w.x() + w.y(), (w.x() + w.y()) + w.z()];
    let total = ends[2] + w.w();
    if total <= 0.0 {
        return 0.0;
    }
    let target = (sanitize_xi(xi) * total).min(f32::from_bits(total.to_bits() - 1));
    let k = ends.iter().map(|&e| (target >= e) as usize).sum::<usize>() & 3;
    // Corner `k`'s lattice point from the ranks of the offsets (`rank_order`: corner `k` has
    // stepped along the axes whose rank is at least `3 − k`), in registers, rather than read
    // from the array by `k`, which put a store and a load on the chain from ξ to the hash.
    let ck: [i32; 3] = core::array::from_fn(|a| {
        let rank = c[1][a].wrapping_sub(c[0][a]) + c[2][a].wrapping_sub(c[0][a]);
        c[0][a].wrapping_add((rank + k as i32 >= 3) as i32)
    });
    SCALE * total * (grad(ck, seed) * d[k]).sum3()
}

/// The five corners of the 4D simplex holding a point: per corner, the hash of its lattice
/// point before the finishing multiply and the point's offset from it.
struct Corners4 {
    h: [u32; 5],
    d: [F4; 5],
}

impl Corners4 {
    /// `kernel` of the corners of `p`, as `lattice::Corners::<4, 5>` finds them.
    #[inline(always)]
    fn on<R>(p: [f32; 4], seed: u32, kernel: impl FnOnce(&Self) -> R) -> R {
        let v = F4::from4(p);
        let q = v + F4::splat(v.sum4() * SKEW4.skew);
        on_cells!(q, |cell, f| kernel(&Corners4::of(cell, f, seed)))
    }

    /// The corners of a skewed point split into `cell` and `f`.
    #[inline(always)]
    fn of(cell: I4, f: F4, seed: u32) -> Self {
        let g = SKEW4.unskew;
        let d0 = f - F4::splat(f.sum4() * g);
        let e = [d0.x(), d0.y(), d0.z(), d0.w()];
        let mut rank = [0u32; 4];
        for a in 0..4 {
            for b in a + 1..4 {
                let ge = (e[a] >= e[b]) as u32;
                rank[a] += ge;
                rank[b] += 1 - ge;
            }
        }
        // A lattice point's hash is the xor of its axis products: the lower side's `base·P`,
        // or on the upper side `base·P + P`, so corner `k` adds `P` on the axes it has
        // stepped along, those with `rank + k ≥ 4`: one compare of the four ranks at once.
        let base = cell.xyzw();
        let lo = I4::new(core::array::from_fn(|a| base[a].wrapping_mul(PRIME[a])));
        let (rank, primes) = (I4::new(rank), I4::new(PRIME));
        let corner = |k: i32| {
            let up = rank.greater(3 - k);
            let h = seed ^ (lo + primes.and(up)).xor_lanes();
            (h, (d0 - up.ones()) + F4::splat(k as f32 * g))
        };
        // Spelled out: as `[0, 1, 2, 3, 4].map(corner)` LLVM called the closure per corner.
        let [c1, c2, c3, c4] = [corner(1), corner(2), corner(3), corner(4)];
        Corners4 {
            h: [seed ^ lo.xor_lanes(), c1.0, c2.0, c3.0, c4.0],
            d: [d0, c1.1, c2.1, c3.1, c4.1],
        }
    }

    /// Corners 0–3's weights `t⁴`, `t = max(½ − r², 0)`, and corner 4's.
    #[inline(always)]
    fn weights(&self) -> (F4, f32) {
        let d = &self.d;
        let r2 = F4::sums4([d[0] * d[0], d[1] * d[1], d[2] * d[2], d[3] * d[3]]);
        let t = (F4::splat(0.5) - r2).max(F4::splat(0.0));
        let t4 = (0.5 - (d[4] * d[4]).sum4()).max(0.0);
        ((t * t) * (t * t), (t4 * t4) * (t4 * t4))
    }

    /// The gradient row of corner `k`.
    #[inline(always)]
    fn grad(&self, k: usize) -> F4 {
        F4::new(edge4(self.h[k].wrapping_mul(CORNER_MUL)))
    }
}

/// [`simplex4`](super::simplex4).
#[inline(always)]
pub(super) fn simplex4(p: [f32; 4], seed: u32) -> f32 {
    Corners4::on(p, seed, simplex4_of)
}

/// [`simplex4`] from its corners.
#[inline(always)]
fn simplex4_of(c: &Corners4) -> f32 {
    let (w, w4) = c.weights();
    let dot = |k: usize| c.grad(k) * c.d[k];
    let v = w * F4::sums4([dot(0), dot(1), dot(2), dot(3)]);
    let last = w4 * (c.grad(4) * c.d[4]).sum4();
    // The scalar form's running sum, from 0.0.
    SCALE4 * (((((0.0 + v.x()) + v.y()) + v.z()) + v.w()) + last)
}

/// [`simplex4_stochastic`](super::simplex4_stochastic).
#[inline(always)]
pub(super) fn simplex4_stochastic(p: [f32; 4], seed: u32, xi: f32) -> f32 {
    Corners4::on(p, seed, |c| simplex4_stochastic_of(c, xi))
}

/// [`simplex4_stochastic`] from its corners.
#[inline(always)]
fn simplex4_stochastic_of(c: &Corners4, xi: f32) -> f32 {
    let (w, w4) = c.weights();
    let e0 = 0.0 + w.x();
    let e1 = e0 + w.y();
    let e2 = e1 + w.z();
    let e3 = e2 + w.w();
    let total = e3 + w4;
    if total <= 0.0 {
        return 0.0;
    }
    let target = (sanitize_xi(xi) * total).min(f32::from_bits(total.to_bits() - 1));
    let k = [e0, e1, e2, e3].map(|e| (target >= e) as usize);
    let k = (k[0] + k[1] + k[2] + k[3]).min(4);
    SCALE4 * total * (c.grad(k) * c.d[k]).sum4()
}

#[cfg(test)]
mod tests {
    use super::super::{
        simplex3_scalar, simplex3_stochastic_scalar, simplex4_scalar, simplex4_stochastic_scalar,
    };
    use crate::stochastic::estimators::ONE_BELOW;

    /// The lane kernels `lane` and `lane_sto` against the general lattice's forms bit for bit
    /// at 200 000 points from `point(i, next)` (some far outside the split range), seeds and
    /// ξ (hard ones every third point).
    #[allow(clippy::type_complexity)]
    fn compare<const N: usize>(
        stream: u64,
        point: impl Fn(usize, &mut dyn FnMut() -> f32) -> [f32; N],
        forms: (
            fn([f32; N], u32) -> f32,
            fn([f32; N], u32) -> f32,
            fn([f32; N], u32, f32) -> f32,
            fn([f32; N], u32, f32) -> f32,
        ),
    ) {
        let (lane, scalar, lane_sto, scalar_sto) = forms;
        let mut next = crate::stochastic::uniforms(stream);
        let xis = [0.0f32, -0.0, 1e-30, 0.5, ONE_BELOW, 1.0, 2.0, f32::NAN];
        for i in 0..200_000usize {
            let p = point(i, &mut next);
            let seed = i as u32;
            let xi = if i % 3 == 0 {
                xis[i / 3 % xis.len()]
            } else {
                next()
            };
            let (a, b) = (lane(p, seed), scalar(p, seed));
            assert_eq!(a.to_bits(), b.to_bits(), "{p:?}: {a} vs {b}");
            let (a, b) = (lane_sto(p, seed, xi), scalar_sto(p, seed, xi));
            assert_eq!(a.to_bits(), b.to_bits(), "{p:?}, ξ {xi}: {a} vs {b}");
        }
    }

    /// Lattice points and their neighbouring floats up to and beyond the edge of the split
    /// range, infinities and NaN: coordinate `k` of one of eight, and `n` one to three floats
    /// above its magnitude.
    fn near_lattice(i: usize) -> (f32, f32) {
        let k = [
            0.0f32,
            1.0,
            -1.0,
            2_097_151.0,
            -2_097_151.0,
            -3e9,
            f32::INFINITY,
            f32::NAN,
        ][i / 4 % 8];
        (k, f32::from_bits(k.abs().to_bits() + (i as u32 / 20 % 3)))
    }

    #[test]
    fn lane_kernels_are_the_lattice_forms_bit_for_bit() {
        // Random points, points where offsets tie (the diagonal, the cells' faces: the rank
        // order's hard cases), lattice points and their neighbouring floats, and the edge of
        // the split range for the skewed point.
        let point = |i: usize, next: &mut dyn FnMut() -> f32| match i % 4 {
            0 | 1 => [0; 3].map(|_| (next() - 0.5) * 200.0),
            2 => {
                let (t, u) = ((i / 4) as f32 / 97.0 - 30.0, next() * 8.0);
                [[t, t, t], [t, t, u], [t, u, t], [u, t, t], [t, -t, 0.5 * t]][i / 4 % 5]
            }
            _ => {
                let (k, n) = near_lattice(i);
                [n.copysign(k), k, -n]
            }
        };
        let forms = (
            super::simplex3 as fn(_, _) -> _,
            simplex3_scalar as fn(_, _) -> _,
            super::simplex3_stochastic as fn(_, _, _) -> _,
            simplex3_stochastic_scalar as fn(_, _, _) -> _,
        );
        compare(0x1f83_d9ab_fb41_bd6b, point, forms);
    }

    #[test]
    fn lane_kernels_4d_are_the_lattice_forms_bit_for_bit() {
        // As in 3D, with the ties of four offsets.
        let point = |i: usize, next: &mut dyn FnMut() -> f32| match i % 4 {
            0 | 1 => [0; 4].map(|_| (next() - 0.5) * 200.0),
            2 => {
                let (t, u) = ((i / 4) as f32 / 97.0 - 30.0, next() * 8.0);
                [
                    [t, t, t, t],
                    [t, t, u, t],
                    [t, u, t, u],
                    [u, t, t, t],
                    [t, -t, 0.5 * t, u],
                    [u, u, t, t],
                ][i / 4 % 6]
            }
            _ => {
                let (k, n) = near_lattice(i);
                [n.copysign(k), k, -n, k]
            }
        };
        let forms = (
            super::simplex4 as fn(_, _) -> _,
            simplex4_scalar as fn(_, _) -> _,
            super::simplex4_stochastic as fn(_, _, _) -> _,
            simplex4_stochastic_scalar as fn(_, _, _) -> _,
        );
        compare(0x5be0_cd19_137e_2179, point, forms);
    }
}
