//! Improved Perlin noise (Perlin 2002: quintic fade, hashed gradients) in 2D, 3D and 4D, and its
//! one-sample estimator (Fajardo & Pharr, Algorithm 1): the interpolation over the `2^d` lattice
//! corners is a nested `lerp`, so one ξ, remapped after each axis (eq. 4), selects a single
//! corner with probability equal to its interpolation weight, and only that corner's gradient
//! is evaluated.

pub(crate) mod batch;
pub(crate) mod fbm;
pub(crate) mod fbm_batch;
use super::estimators::{Narrowing, fresh_corner2, unit_corner};
use super::fractal::{Fractal, Octaves, octave_seed};
use super::noise::{BatchLengths, Gradient, LatticePoint, Noise};
use crate::gradients;
use crate::hash::{CORNER_MUL, PRIME, corner};
use crate::math::{dfade, fade, split};
use fbm::{fbm3, fbm3_octave_stochastic, fbm3_stochastic, fbm3_tail_stochastic};

pub(super) mod lanes;

#[inline(always)]
fn lerp(t: f32, a: f32, b: f32) -> f32 {
    a + t * (b - a)
}

#[inline(always)]
fn g2(h: u32) -> [f32; 2] {
    gradients::perlin2(h)
}
#[inline(always)]
fn g3(h: u32) -> [f32; 4] {
    *gradients::edge3(h)
}
#[inline(always)]
fn g4(h: u32) -> [f32; 4] {
    *gradients::edge4(h)
}

/// 2D Perlin noise, about `[-1, 1]`.
#[inline(always)]
pub fn perlin2(p: [f32; 2], seed: u32) -> f32 {
    if crate::math::in_split_range(p) {
        perlin2_with(p, seed, crate::math::split_in_range)
    } else {
        perlin2_with(p, seed, split)
    }
}

#[inline(always)]
fn perlin2_with(p: [f32; 2], seed: u32, sp: impl Fn(f32) -> (i32, f32)) -> f32 {
    let (ix, x) = sp(p[0]);
    let (iy, y) = sp(p[1]);
    let xp0 = (ix as u32).wrapping_mul(PRIME[0]);
    let yp0 = (iy as u32).wrapping_mul(PRIME[1]);
    let (xp1, yp1) = (xp0.wrapping_add(PRIME[0]), yp0.wrapping_add(PRIME[1]));
    let c = |xp: u32, yp: u32, dx: f32, dy: f32| {
        let g = g2(corner(seed, xp, yp, 0));
        g[0] * dx + g[1] * dy
    };
    let (u, v) = (fade(x), fade(y));
    lerp(
        v,
        lerp(u, c(xp0, yp0, x, y), c(xp1, yp0, x - 1.0, y)),
        lerp(u, c(xp0, yp1, x, y - 1.0), c(xp1, yp1, x - 1.0, y - 1.0)),
    )
}

/// 2D Perlin noise and its analytic gradient `(∂n/∂x, ∂n/∂y)`.
#[inline]
pub fn perlin2_grad(p: [f32; 2], seed: u32) -> (f32, [f32; 2]) {
    let (ix, x) = split(p[0]);
    let (iy, y) = split(p[1]);
    let (u, v) = (fade(x), fade(y));
    let (du, dv) = (dfade(x), dfade(y));
    let mut n = 0.0;
    let mut d = [0.0f32; 2];
    for c in 0..4u32 {
        let (cx, cy) = (c & 1, c >> 1);
        let g = g2(corner(
            seed,
            (ix.wrapping_add(cx as i32) as u32).wrapping_mul(PRIME[0]),
            (iy.wrapping_add(cy as i32) as u32).wrapping_mul(PRIME[1]),
            0,
        ));
        let (ox, oy) = (x - cx as f32, y - cy as f32);
        let dot = g[0] * ox + g[1] * oy;
        let wx = if cx == 1 { u } else { 1.0 - u };
        let wy = if cy == 1 { v } else { 1.0 - v };
        let sx = if cx == 1 { du } else { -du };
        let sy = if cy == 1 { dv } else { -dv };
        n += wx * wy * dot;
        d[0] += sx * wy * dot + wx * wy * g[0];
        d[1] += wx * sy * dot + wx * wy * g[1];
    }
    (n, d)
}

/// One-sample estimator of [`perlin2`] (Algorithm 1): one gradient, one ξ.
///
/// On a CPU this saves nothing in 2D: [`perlin2`]'s four corners are independent and overlap,
/// while the estimator's choice of one corner is a chain of dependent steps, and the two take
/// about the same time (`noisebake report`: about 1.0×). It is here for completeness and for
/// targets where gradient reads are expensive; in 3D and 4D (8 and 16 corners) it pays.
#[inline(always)]
pub fn perlin2_stochastic(p: [f32; 2], seed: u32, xi: f32) -> f32 {
    if crate::math::in_split_range(p) {
        // LLVM keeps the masked split free of branches here. (It once lowered its select to a
        // branch inside the 3D estimator, 40 ns a call instead of 21, and the estimators took
        // a form with the step made by bit operations; in their present shape the masked
        // split is 1–5 % faster in each, and that form is gone.)
        perlin2_stochastic_with(p, seed, xi, crate::math::split_in_range)
    } else {
        perlin2_stochastic_with(p, seed, xi, split)
    }
}

#[inline(always)]
fn perlin2_stochastic_with(p: [f32; 2], seed: u32, xi: f32, sp: impl Fn(f32) -> (i32, f32)) -> f32 {
    let (ix, x) = sp(p[0]);
    let (iy, y) = sp(p[1]);
    let cell = [ix, iy];
    let t = [fade(x), fade(y)];
    // As in 3D, only the chosen corner is hashed; its two decisions come from `fresh_corner2`.
    // (This loop and the 3D one, shared as one generic helper, measured 15 % slower here: LLVM
    // then packed the two cell products into emulated 32-bit SIMD multiplies.)
    let up = fresh_corner2(xi, t);
    let mut h = seed;
    let mut k = 0;
    for (a, &up) in up.iter().enumerate() {
        h ^= (cell[a] as u32)
            .wrapping_mul(PRIME[a])
            .wrapping_add(up & PRIME[a]);
        k |= (up & 1) << a;
    }
    let g = g2(h.wrapping_mul(CORNER_MUL));
    let o = unit_corner(k);
    g[0] * (x - o[0]) + g[1] * (y - o[1])
}

/// 3D Perlin noise (improved noise), about `[-1, 1]`.
#[inline(always)]
pub fn perlin3(p: [f32; 3], seed: u32) -> f32 {
    lanes::perlin3(p, seed)
}

/// 3D Perlin noise and its analytic gradient.
pub fn perlin3_grad(p: [f32; 3], seed: u32) -> (f32, [f32; 3]) {
    let mut cell = [0i32; 3];
    let mut f = [0.0f32; 3];
    for a in 0..3 {
        (cell[a], f[a]) = split(p[a]);
    }
    perlin3_grad_cell(cell, f, seed)
}

/// [`perlin3_grad`] at offset `f ∈ [0, 1)³` in the integer lattice cell `cell`: exact for any
/// `i32` cell, however far from the origin.
pub fn perlin3_grad_cell(cell: [i32; 3], f: [f32; 3], seed: u32) -> (f32, [f32; 3]) {
    let u = f.map(fade);
    let du = f.map(dfade);
    let mut n = 0.0;
    let mut d = [0.0f32; 3];
    for c in 0..8u32 {
        let b = [c & 1, (c >> 1) & 1, c >> 2];
        let g = g3(corner(
            seed,
            (cell[0].wrapping_add(b[0] as i32) as u32).wrapping_mul(PRIME[0]),
            (cell[1].wrapping_add(b[1] as i32) as u32).wrapping_mul(PRIME[1]),
            (cell[2].wrapping_add(b[2] as i32) as u32).wrapping_mul(PRIME[2]),
        ));
        let o = [f[0] - b[0] as f32, f[1] - b[1] as f32, f[2] - b[2] as f32];
        let dot = g[0] * o[0] + g[1] * o[1] + g[2] * o[2];
        let w: [f32; 3] = core::array::from_fn(|a| if b[a] == 1 { u[a] } else { 1.0 - u[a] });
        let s: [f32; 3] = core::array::from_fn(|a| if b[a] == 1 { du[a] } else { -du[a] });
        let weight = w[0] * w[1] * w[2];
        n += weight * dot;
        d[0] += s[0] * w[1] * w[2] * dot + weight * g[0];
        d[1] += w[0] * s[1] * w[2] * dot + weight * g[1];
        d[2] += w[0] * w[1] * s[2] * dot + weight * g[2];
    }
    (n, d)
}

/// One-sample estimator of [`perlin3`] (Algorithm 1 in 3D): one gradient instead of eight.
#[inline(always)]
pub fn perlin3_stochastic(p: [f32; 3], seed: u32, xi: f32) -> f32 {
    lanes::perlin3_stochastic(p, seed, xi)
}

/// A 4D point's offset in its cell and the hash products of the cell's lower corner per axis,
/// `cell[a]·PRIME[a]` (the upper corner's are `+ PRIME[a]`), for [`perlin4_grad`].
#[inline(always)]
fn split4(p: [f32; 4], sp: impl Fn(f32) -> (i32, f32)) -> ([u32; 4], [f32; 4]) {
    let mut lo = [0u32; 4];
    let mut f = [0.0f32; 4];
    for a in 0..4 {
        let (c, fa) = sp(p[a]);
        lo[a] = (c as u32).wrapping_mul(PRIME[a]);
        f[a] = fa;
    }
    (lo, f)
}

/// The gradient at the corner of a 4D cell given by `up` (per axis all ones for the upper
/// side, 0 for the lower), from the cell's lower products `lo`: as in 3D, the xor of the
/// corner's products and one multiply ([`corner`]).
#[inline(always)]
fn grad4(lo: [u32; 4], up: [u32; 4], seed: u32) -> [f32; 4] {
    let mut h = seed;
    for a in 0..4 {
        h ^= lo[a].wrapping_add(up[a] & PRIME[a]);
    }
    g4(h.wrapping_mul(CORNER_MUL))
}

/// `g · (f − o)`, the gradient term of a 4D corner at offset `o` (0 or 1 per axis), summed in
/// pairs: the same order in [`perlin4`] and its estimator.
#[inline(always)]
fn dot4(g: [f32; 4], f: [f32; 4], o: [f32; 4]) -> f32 {
    (g[0] * (f[0] - o[0]) + g[1] * (f[1] - o[1])) + (g[2] * (f[2] - o[2]) + g[3] * (f[3] - o[3]))
}

/// Corner `c` of a 4D cell (bit `a` set: upper side on axis `a`) as per-axis masks.
#[inline(always)]
fn corner_masks(c: usize) -> [u32; 4] {
    core::array::from_fn(|a| 0u32.wrapping_sub(((c >> a) & 1) as u32))
}

/// 4D Perlin noise (e.g. 3D noise animated over time).
#[inline(always)]
pub fn perlin4(p: [f32; 4], seed: u32) -> f32 {
    lanes::perlin4(p, seed)
}

/// 4D Perlin noise and its analytic gradient `(∂n/∂x, ∂n/∂y, ∂n/∂z, ∂n/∂w)`: the value is
/// `Σ_c (Π_a w_a(c)) · g_c·(f − c)` over the 16 corners, with `w_a` the fade weight of axis `a`
/// (`fade(f_a)` on the upper side, `1 − fade(f_a)` on the lower), so by the product rule
/// `∂n/∂a = Σ_c ±dfade(f_a) · Π_(b≠a) w_b · g_c·(f − c) + Π_b w_b · g_c[a]`.
pub fn perlin4_grad(p: [f32; 4], seed: u32) -> (f32, [f32; 4]) {
    let (lo, f) = split4(p, split);
    let u = f.map(fade);
    let du = f.map(dfade);
    let mut n = 0.0;
    let mut d = [0.0f32; 4];
    for c in 0..16usize {
        let b: [i32; 4] = core::array::from_fn(|a| ((c >> a) & 1) as i32);
        let g = grad4(lo, corner_masks(c), seed);
        let dot = dot4(g, f, b.map(|v| v as f32));
        let w: [f32; 4] = core::array::from_fn(|a| if b[a] == 1 { u[a] } else { 1.0 - u[a] });
        let s: [f32; 4] = core::array::from_fn(|a| if b[a] == 1 { du[a] } else { -du[a] });
        let weight = w[0] * w[1] * w[2] * w[3];
        n += weight * dot;
        for a in 0..4 {
            let others: f32 = (0..4).filter(|&o| o != a).map(|o| w[o]).product();
            d[a] += s[a] * others * dot + weight * g[a];
        }
    }
    (n, d)
}

/// One-sample estimator of [`perlin4`]: one gradient instead of sixteen.
#[inline(always)]
pub fn perlin4_stochastic(p: [f32; 4], seed: u32, xi: f32) -> f32 {
    lanes::perlin4_stochastic(p, seed, xi)
}

/// Improved Perlin noise (Perlin 2002) in 2D, 3D or 4D, about `[-1, 1]`; its estimator evaluates
/// one lattice gradient of the `2^d` (Fajardo & Pharr, Algorithm 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Perlin {
    /// Seed of the lattice hash.
    pub seed: u32,
}

impl Perlin {
    /// Perlin noise with this seed.
    pub const fn new(seed: u32) -> Perlin {
        Perlin { seed }
    }

    /// The noise at `p`.
    #[must_use]
    #[inline(always)]
    pub fn sample<P: LatticePoint>(self, p: P) -> f32 {
        p.perlin(self.seed)
    }

    /// An unbiased one-sample estimate of [`sample`](Self::sample) from one uniform `xi`.
    #[must_use]
    #[inline(always)]
    pub fn estimate<P: LatticePoint>(self, p: P, xi: f32) -> f32 {
        p.perlin_estimate(self.seed, xi)
    }

    /// The noise and its analytic gradient at `p`.
    #[must_use]
    #[inline]
    pub fn gradient<P: LatticePoint>(self, p: P) -> (f32, P) {
        p.perlin_gradient(self.seed)
    }

    /// The 3D noise and its gradient at offset `f ∈ [0, 1)³` in the integer lattice cell
    /// `cell`: exact for any `i32` cell, however far from the origin an `f32` point could not
    /// reach (the curl-noise fields use it).
    #[must_use]
    #[inline]
    pub fn gradient_in_cell(self, cell: [i32; 3], f: [f32; 3]) -> (f32, [f32; 3]) {
        perlin3_grad_cell(cell, f, self.seed)
    }

    /// [`sample`](Self::sample) of many points into `out`, bit for bit the single-point
    /// values (3D points eight per AVX2 instruction where the CPU has it). Slices of different
    /// lengths are an error, and nothing is written.
    #[inline]
    pub fn sample_batch<P: LatticePoint>(
        self,
        points: &[P],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), None, out.len())?;
        P::perlin_batch(points, self.seed, out);
        Ok(())
    }

    /// [`estimate`](Self::estimate) of many points, one ξ each, into `out`. Slices of
    /// different lengths are an error, and nothing is written.
    #[inline]
    pub fn estimate_batch<P: LatticePoint>(
        self,
        points: &[P],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), Some(xi.len()), out.len())?;
        P::perlin_estimate_batch(points, self.seed, xi, out);
        Ok(())
    }
}

impl<P: LatticePoint> Noise<P> for Perlin {
    #[inline(always)]
    fn sample(&self, p: P) -> f32 {
        p.perlin(self.seed)
    }
    #[inline(always)]
    fn estimate(&self, p: P, xi: f32) -> f32 {
        p.perlin_estimate(self.seed, xi)
    }
    #[inline]
    fn sample_batch(&self, points: &[P], out: &mut [f32]) -> Result<(), BatchLengths> {
        Perlin::sample_batch(*self, points, out)
    }
    #[inline]
    fn estimate_batch(
        &self,
        points: &[P],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        Perlin::estimate_batch(*self, points, xi, out)
    }
}

impl<P: LatticePoint> Gradient<P> for Perlin {
    #[inline]
    fn gradient(&self, p: P) -> (f32, P) {
        p.perlin_gradient(self.seed)
    }
}

/// Perlin fBm runs its own kernels: the octave loop on lanes, the halving estimator's split
/// taken off the chain from ξ, the batch kernels; the same values as the generic forms.
impl Octaves for Perlin {
    #[inline]
    fn octave(&self, o: u32) -> Perlin {
        Perlin::new(octave_seed(self.seed, o))
    }
    #[inline(always)]
    fn fbm_sample(&self, f: Fractal, p: [f32; 3]) -> f32 {
        fbm3(p, f, self.seed)
    }
    #[inline(always)]
    fn fbm_estimate(&self, f: Fractal, p: [f32; 3], xi: f32) -> f32 {
        fbm3_stochastic(p, f, self.seed, xi)
    }
    #[inline]
    fn fbm_estimate_tail(&self, f: Fractal, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        fbm3_tail_stochastic(p, f, exact, self.seed, xi)
    }
    #[inline]
    fn fbm_estimate_octave(&self, f: Fractal, p: [f32; 3], exact: u32, xi: f32) -> f32 {
        fbm3_octave_stochastic(p, f, exact, self.seed, xi)
    }
    #[inline]
    fn fbm_sample_batch(
        &self,
        f: Fractal,
        points: &[[f32; 3]],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), None, out.len())?;
        fbm_batch::fbm3_batch(points, f, self.seed, out);
        Ok(())
    }
    #[inline]
    fn fbm_estimate_batch(
        &self,
        f: Fractal,
        points: &[[f32; 3]],
        xi: &[f32],
        out: &mut [f32],
    ) -> Result<(), BatchLengths> {
        BatchLengths::check(points.len(), Some(xi.len()), out.len())?;
        fbm_batch::fbm3_stochastic_batch(points, f, self.seed, xi, out);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Which of the 32 gradients the lower corner of the 4D cell `c` gets, through the same
    /// split and corner hash as [`perlin4`].
    fn index4(c: [i32; 4], seed: u32) -> usize {
        let (lo, _) = split4(c.map(|v| v as f32 + 0.5), split);
        let g = grad4(lo, [0; 4], seed);
        gradients::EDGES4.0.iter().position(|&r| r == g).unwrap()
    }

    /// The gradient row the lower corner of the 3D cell `c` gets in [`perlin3`] (the top four
    /// bits of its corner hash).
    fn index3(c: [i32; 3], seed: u32) -> usize {
        let [x, y, z] = [0, 1, 2].map(|a| (c[a] as u32).wrapping_mul(PRIME[a]));
        (corner(seed, x, y, z) >> 28) as usize
    }

    /// Asserts that the gradient indices `(i, j)` of 65 536 pairs of neighbouring cells, out of
    /// `B` gradients, look independent and uniform: the χ² of the `B × B` contingency table
    /// (`B² − 1` degrees of freedom) and of the first index alone (`B − 1`) each below its mean
    /// plus 6σ (σ = √(2·dof)). A hash that misses an axis's product or mixes too little puts
    /// whole rows into few bins and fails by orders of magnitude.
    fn assert_independent<const B: usize>(
        pairs: impl Iterator<Item = (usize, usize)>,
        what: impl core::fmt::Debug,
    ) {
        let mut joint = [[0u32; B]; B];
        let mut single = [0u32; B];
        let mut n = 0;
        for (i, j) in pairs {
            joint[i][j] += 1;
            single[i] += 1;
            n += 1;
        }
        let chi2 = |obs: &mut dyn Iterator<Item = u32>, bins: usize| {
            let expect = n as f64 / bins as f64;
            obs.map(|o| (o as f64 - expect).powi(2) / expect)
                .sum::<f64>()
        };
        let limit = |dof: usize| dof as f64 + 6.0 * (2.0 * dof as f64).sqrt();
        let c1 = chi2(&mut single.iter().copied(), B);
        let c2 = chi2(&mut joint.iter().flatten().copied(), B * B);
        assert!(c1 < limit(B - 1), "{what:?}: χ² {c1} of the indices");
        assert!(c2 < limit(B * B - 1), "{what:?}: χ² {c2} of the pairs");
    }

    #[test]
    fn neighbouring_3d_cells_get_independent_gradients() {
        // The cells of a 64 × 32 × 32 block near the origin and far out, each against its
        // neighbour along every axis and two diagonals.
        let steps = [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [1, 1, 1]];
        for origin in [[0i32; 3], [-8_000_000, 123, 4_000_000]] {
            for step in steps {
                let pairs = (0..65_536i32).map(|k| {
                    let c = [k & 63, k >> 6 & 31, k >> 11];
                    let c: [i32; 3] = core::array::from_fn(|a| origin[a] + c[a]);
                    let d: [i32; 3] = core::array::from_fn(|a| c[a] + step[a]);
                    (index3(c, 3), index3(d, 3))
                });
                assert_independent::<16>(pairs, (origin, step));
            }
        }
    }

    #[test]
    fn neighbouring_4d_cells_get_independent_gradients() {
        // The cells of a 16⁴ block near the origin and far out, each against its neighbour
        // along every axis and two diagonals (the report samples w = x + z).
        let steps = [
            [1, 0, 0, 0],
            [0, 1, 0, 0],
            [0, 0, 1, 0],
            [0, 0, 0, 1],
            [1, 0, 0, 1],
            [1, 1, 1, 1],
        ];
        for origin in [[0i32; 4], [-8_000_000, 123, 4_000_000, -77]] {
            for step in steps {
                let pairs = (0..65_536i32).map(|k| {
                    let c: [i32; 4] = core::array::from_fn(|a| origin[a] + (k >> (4 * a) & 15));
                    let d: [i32; 4] = core::array::from_fn(|a| c[a] + step[a]);
                    (index4(c, 3), index4(d, 3))
                });
                assert_independent::<32>(pairs, (origin, step));
            }
        }
    }
}
