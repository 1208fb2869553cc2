//! The simplex lattice in any dimension `N` (Perlin 2001; the skew constants as in Gustavson
//! 2005): the simplex holding a point, each corner's weight `max(½ − r², 0)⁴`, and from these
//! the noise value, its analytic gradient and the one-sample estimator. [`simplex2`] and its
//! estimator and the gradients of every dimension are built on it; the 3D and 4D values and
//! estimators run as lane kernels (`simplex::lanes`), which the tests compare with this
//! lattice's forms bit for bit.
//!
//! **Why the radius is ½.** The skewed cubic lattice splits into simplices whose altitudes are
//! all `√½` in 2D, 3D and 4D alike (the squared distance from any corner to the plane of its
//! opposite face is ½). A corner's kernel then vanishes before it leaves the simplices that
//! share the corner, so summing the `N + 1` corners of the point's own simplex is summing every
//! lattice point's kernel: the noise is as smooth as the kernel (C³), across every face. The
//! radius² of 0.6 that Gustavson uses in 3D and 4D leaves jumps of about 10⁻³ at the faces.
//!
//! [`simplex2`]: super::simplex2
//! [`simplex3`]: super::simplex3
//! [`simplex3_grad`]: super::simplex3_grad
//! [`simplex4`]: super::simplex4

use crate::math::{in_split_range, split, split_in_range};
use crate::stochastic::estimators::sanitize_xi;

/// The skew of an `N`-dimensional simplex lattice: `skew = (√(N+1) − 1)/N` maps a point to the
/// cubic lattice, `unskew = (1 − 1/√(N+1))/N` maps back.
#[derive(Clone, Copy)]
pub(super) struct Skew {
    pub(super) skew: f32,
    pub(super) unskew: f32,
}

/// The `M = N + 1` corners of the simplex holding a point: lattice points and the point's
/// offsets from them (in the unskewed space, where the kernel is round).
pub(super) struct Corners<const N: usize, const M: usize> {
    pub(super) cell: [[i32; N]; M],
    pub(super) d: [[f32; N]; M],
}

impl<const N: usize, const M: usize> Corners<N, M> {
    /// The simplex holding `p`. The skewed point is split into its cell and the offset in it,
    /// and the unskewed offset from the cell's origin is `f − (Σf)·unskew`: computed from the
    /// fraction alone, so its precision does not depend on the magnitude of `p`.
    #[inline(always)]
    pub(super) fn new(p: [f32; N], k: Skew) -> Self {
        const { assert!(M == N + 1) };
        let s = sum(p) * k.skew;
        let q = p.map(|c| c + s);
        // One predictable branch buys the short split for every ordinary coordinate.
        if in_split_range(q) {
            Self::of(q, split_in_range, k.unskew)
        } else {
            Self::of(q, split, k.unskew)
        }
    }

    #[inline(always)]
    fn of(q: [f32; N], sp: impl Fn(f32) -> (i32, f32), g: f32) -> Self {
        let mut base = [0i32; N];
        let mut f = [0.0f32; N];
        for a in 0..N {
            (base[a], f[a]) = sp(q[a]);
        }
        let t = sum(f) * g;
        let d0 = f.map(|v| v - t);
        // The path from the cell's origin through the simplex steps along the axes from the
        // largest offset down. Axis `a`'s rank is the number of other offsets it is at least
        // (ties going to the earlier axis), so the ranks are a permutation of `0..N`, and
        // corner `k` has stepped along axis `a` when `rank[a] ≥ N − k`.
        let mut rank = [0usize; N];
        for a in 0..N {
            for b in a + 1..N {
                let ge = (d0[a] >= d0[b]) as usize;
                rank[a] += ge;
                rank[b] += 1 - ge;
            }
        }
        let mut cell = [[0i32; N]; M];
        let mut d = [d0; M];
        for k in 1..M {
            for a in 0..N {
                let step = (rank[a] + k >= N) as i32;
                cell[k][a] = base[a].wrapping_add(step);
                d[k][a] = d0[a] - step as f32 + k as f32 * g;
            }
        }
        cell[0] = base;
        Corners { cell, d }
    }

    /// Each corner's `t = max(½ − r², 0)`; its weight is `t⁴`.
    #[inline(always)]
    fn support(&self) -> [f32; M] {
        self.d.map(|d| (0.5 - sum(d.map(|v| v * v))).max(0.0))
    }

    /// `scale · Σ_k t_k⁴ (g_k · d_k)`, with `grad` giving a lattice point's gradient.
    #[inline(always)]
    pub(super) fn value(&self, scale: f32, grad: impl Fn([i32; N]) -> [f32; N]) -> f32 {
        let t = self.support();
        let mut n = 0.0;
        for ((&t, &c), &d) in t.iter().zip(&self.cell).zip(&self.d) {
            n += ((t * t) * (t * t)) * dot(grad(c), d);
        }
        scale * n
    }

    /// [`Corners::value`] and its gradient. The offsets move with the point (`∂d_k/∂p = I`
    /// inside a simplex), so `∇(t⁴ g·d) = −8t³ (g·d) d + t⁴ g`, and the sum is smooth across
    /// faces (see the module notes), so this is the gradient everywhere.
    #[inline(always)]
    pub(super) fn value_grad(
        &self,
        scale: f32,
        grad: impl Fn([i32; N]) -> [f32; N],
    ) -> (f32, [f32; N]) {
        let t = self.support();
        let mut n = 0.0;
        let mut dn = [0.0f32; N];
        for ((&t, &c), &d) in t.iter().zip(&self.cell).zip(&self.d) {
            let g = grad(c);
            let t2 = t * t;
            let (w, gd) = (t2 * t2, dot(g, d));
            n += w * gd;
            let c = -8.0 * t2 * t * gd;
            for a in 0..N {
                dn[a] += c * d[a] + w * g[a];
            }
        }
        (scale * n, dn.map(|v| scale * v))
    }

    /// One-sample estimator of [`Corners::value`]: corner `k` with probability `t_k⁴ / Σ t⁴`,
    /// whose term divided by that probability is `scale · Σt⁴ · (g_k · d_k)`. The corner is the
    /// number of the weights' running ends at or below `ξ·Σt⁴` (a count of compares, not a
    /// search); the target is kept below the total, so a corner of weight 0 is never counted to.
    #[inline(always)]
    pub(super) fn stochastic(
        &self,
        scale: f32,
        xi: f32,
        grad: impl Fn([i32; N]) -> [f32; N],
    ) -> f32 {
        let t = self.support();
        let mut ends = [0.0f32; M];
        let mut total = 0.0;
        for k in 0..M {
            total += (t[k] * t[k]) * (t[k] * t[k]);
            ends[k] = total;
        }
        if total <= 0.0 {
            return 0.0;
        }
        let target = (sanitize_xi(xi) * total).min(f32::from_bits(total.to_bits() - 1));
        let mut k = 0;
        for &e in &ends[..M - 1] {
            k += (target >= e) as usize;
        }
        // Every corner's term is made before the choice and one is read after it: the terms
        // do not depend on ξ, so they run beside the weights and the compares instead of
        // after them (in 2D the estimator took 1.5× the deterministic form's time otherwise).
        let terms: [f32; M] = core::array::from_fn(|k| dot(grad(self.cell[k]), self.d[k]));
        scale * total * terms[k.min(M - 1)]
    }
}

/// `g · d`.
#[inline(always)]
fn dot<const N: usize>(g: [f32; N], d: [f32; N]) -> f32 {
    sum::<N>(core::array::from_fn(|a| g[a] * d[a]))
}

/// `Σ v`: from the first term on in 2D and 3D (the order of the 3D forms), in pairs in 4D,
/// `(v₀ + v₁) + (v₂ + v₃)`, the order of a four-lane sum ([`F4::sum4`]), so that the 4D lane
/// forms are bit for bit these.
///
/// [`F4::sum4`]: crate::lanes
#[inline(always)]
pub(super) fn sum<const N: usize>(v: [f32; N]) -> f32 {
    if N == 4 {
        (v[0] + v[1]) + (v[2] + v[3])
    } else {
        let mut s = v[0];
        for &x in &v[1..] {
            s += x;
        }
        s
    }
}
