//! The 3D Perlin batch kernels on eight lanes (see [`super::super::batch`] for the
//! backends and the dispatch): each step of the single-point function as a plain loop over
//! `[f32; 8]`, which LLVM compiles to one vector instruction (AVX2, or two SSE2 or NEON ones),
//! plus the [`Lanes8`] operations it does not make well itself (the gradient table read, the
//! fixed-point cut and decision of the corner choice).

use super::super::batch::{ONE, Path, W, chunks, columns, on_lanes, outside, split};
use super::super::estimators::{fixed, sanitize_xi};
use crate::gradients::EDGES3_COLUMNS;
use crate::hash::{CORNER_MUL, PRIME};
use crate::lanes::{F8, Lanes8, U8};
use crate::math::fade;

/// `g · d` for the gradients of corner hashes `h` (before their finishing multiply), in the
/// single-point form's order `(gx·dx + gy·dy) + gz·dz`.
#[inline(always)]
fn gradient_dot<L: Lanes8>(cpu: L, h: &U8, dx: &F8, dy: &F8, dz: &F8) -> F8 {
    let mut j = [0u32; W];
    for i in 0..W {
        j[i] = h[i].wrapping_mul(CORNER_MUL) >> 28;
    }
    let gx = cpu.lookup16(&EDGES3_COLUMNS[0], j);
    let gy = cpu.lookup16(&EDGES3_COLUMNS[1], j);
    let gz = cpu.lookup16(&EDGES3_COLUMNS[2], j);
    let mut v = [0.0f32; W];
    for i in 0..W {
        v[i] = (gx[i] * dx[i] + gy[i] * dy[i]) + gz[i] * dz[i];
    }
    v
}

/// [`perlin3`](super::super::perlin::perlin3) of eight points in the split range: the lane form's
/// (`perlin::lanes::perlin3_cell`) products and sums, lane by lane.
#[inline(always)]
pub(crate) fn perlin3_lanes<L: Lanes8>(cpu: L, p: &[F8; 3], seed: u32) -> F8 {
    let (cell, f) = split(p);
    let mut t = [[0.0f32; W]; 3];
    let mut f1 = [[0.0f32; W]; 3];
    // The axis products of each side: `cell · PRIME` below, that plus `PRIME` above.
    let mut side = [[[0u32; W]; 2]; 3];
    for a in 0..3 {
        for i in 0..W {
            t[a][i] = fade(f[a][i]);
            f1[a][i] = f[a][i] - 1.0;
            side[a][0][i] = cell[a][i].wrapping_mul(PRIME[a]);
            side[a][1][i] = side[a][0][i].wrapping_add(PRIME[a]);
        }
    }
    // Corners (y, z) at x = 0 and x = 1, lerped along x; one call per (y, z), so that
    // every array index is a constant (a loop over them kept the offsets behind pointers
    // and read them lane by lane).
    let d = [f, f1];
    let a = [
        edge(cpu, seed, &side, &d, &t[0], 0, 0),
        edge(cpu, seed, &side, &d, &t[0], 1, 0),
        edge(cpu, seed, &side, &d, &t[0], 0, 1),
        edge(cpu, seed, &side, &d, &t[0], 1, 1),
    ];
    let mut v = [0.0f32; W];
    for i in 0..W {
        let b0 = a[0][i] + t[1][i] * (a[1][i] - a[0][i]);
        let b1 = a[2][i] + t[1][i] * (a[3][i] - a[2][i]);
        v[i] = b0 + t[2][i] * (b1 - b0);
    }
    v
}

/// The corners `(0, y, z)` and `(1, y, z)` of [`perlin3_lanes`] lerped along x by `tx`:
/// `side[a][s]` is axis `a`'s hash product on side `s`, `d[s][a]` the offset from side `s`.
#[inline(always)]
fn edge<L: Lanes8>(
    cpu: L,
    seed: u32,
    side: &[[U8; 2]; 3],
    d: &[[F8; 3]; 2],
    tx: &F8,
    y: usize,
    z: usize,
) -> F8 {
    let (mut h0, mut h1) = ([0u32; W], [0u32; W]);
    for i in 0..W {
        let yz = seed ^ side[1][y][i] ^ side[2][z][i];
        h0[i] = yz ^ side[0][0][i];
        h1[i] = yz ^ side[0][1][i];
    }
    let lo = gradient_dot(cpu, &h0, &d[0][0], &d[y][1], &d[z][2]);
    let hi = gradient_dot(cpu, &h1, &d[1][0], &d[y][1], &d[z][2]);
    let mut a = [0.0f32; W];
    for i in 0..W {
        a[i] = lo[i] + tx[i] * (hi[i] - lo[i]);
    }
    a
}

/// [`perlin3_stochastic`](super::super::perlin::perlin3_stochastic) of eight points in the split
/// range, each with its own seed and ξ: the fixed-point corner choice of
/// `estimators::Narrowing`, lane by lane (`perlin::lanes::perlin3_stochastic_cell`). `UNIT`:
/// every ξ is known to lie in `[0, 1)` (a remapped one), where sanitising changes nothing
/// and is left out (`Narrowing::new_unit`).
#[inline(always)]
pub(crate) fn perlin3_stochastic_lanes<L: Lanes8, const UNIT: bool>(
    cpu: L,
    p: &[F8; 3],
    seed: &U8,
    xi: &F8,
) -> F8 {
    let (cell, f) = split(p);
    // Weights and ξ in the corner choice's fixed point (`estimators::fixed`).
    let mut t = [[0u32; W]; 3];
    let mut r = [0u32; W];
    for i in 0..W {
        for a in 0..3 {
            t[a][i] = fixed(fade(f[a][i])) as u32;
        }
        let x = if UNIT { xi[i] } else { sanitize_xi(xi[i]) };
        r[i] = (fixed(x) as u32).min(ONE - 1);
    }
    let mut l = [ONE; W];
    let mut h = *seed;
    let mut d = [[0.0f32; W]; 3];
    for a in 0..3 {
        // The whole interval's cut is the weight itself.
        let cut = if a == 0 { t[0] } else { cpu.mul_shr23(l, t[a]) };
        let up = cpu.narrow(&mut r, &mut l, cut);
        for i in 0..W {
            let up = up[i];
            h[i] ^= cell[a][i]
                .wrapping_mul(PRIME[a])
                .wrapping_add(up & PRIME[a]);
            d[a][i] = f[a][i] - f32::from_bits(up & 0x3f80_0000);
        }
    }
    gradient_dot(cpu, &h, &d[0], &d[1], &d[2])
}

/// [`perlin3_batch`] on eight lanes (`points` and `out` of one length).
#[inline(always)]
pub(crate) fn perlin3<L: Lanes8>(cpu: L, points: &[[f32; 3]], seed: u32, out: &mut [f32]) {
    chunks!(
        points,
        out,
        |p| (perlin3_lanes(cpu, &p, seed), outside(cpu, &p)),
        |i| super::perlin3(points[i], seed)
    );
}

/// [`perlin3_stochastic_batch`] on eight lanes (slices of one
/// length).
#[inline(always)]
pub(crate) fn perlin3_stochastic<L: Lanes8>(
    cpu: L,
    points: &[[f32; 3]],
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) {
    chunks!(
        points,
        xi,
        out,
        |p, x| (
            perlin3_stochastic_lanes::<L, false>(cpu, &p, &[seed; W], x),
            outside(cpu, &p)
        ),
        |i| super::perlin3_stochastic(points[i], seed, xi[i])
    );
}

/// [`perlin3`](super::perlin3) at every point: `out[i] = perlin3(points[i], seed)` for the
/// first `min(points.len(), out.len())` points, whose count it returns.
pub fn perlin3_batch(points: &[[f32; 3]], seed: u32, out: &mut [f32]) -> usize {
    perlin3_batch_on(Path::best(), points, seed, out)
}

/// [`perlin3_stochastic`](super::perlin3_stochastic) at every point with its own ξ:
/// `out[i] = perlin3_stochastic(points[i], seed, xi[i])` for the first `min` of the three
/// lengths, whose count it returns.
pub fn perlin3_stochastic_batch(
    points: &[[f32; 3]],
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) -> usize {
    perlin3_stochastic_batch_on(Path::best(), points, seed, xi, out)
}

/// [`perlin3_batch`] on a chosen path (the tests run both).
pub(crate) fn perlin3_batch_on(
    path: Path,
    points: &[[f32; 3]],
    seed: u32,
    out: &mut [f32],
) -> usize {
    let n = points.len().min(out.len());
    let (points, out) = (&points[..n], &mut out[..n]);
    on_lanes!(path, perlin3(points: &[[f32; 3]], seed: u32, out: &mut [f32]));
    n
}

/// [`perlin3_stochastic_batch`] on a chosen path.
pub(crate) fn perlin3_stochastic_batch_on(
    path: Path,
    points: &[[f32; 3]],
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) -> usize {
    let n = points.len().min(xi.len()).min(out.len());
    let (points, xi, out) = (&points[..n], &xi[..n], &mut out[..n]);
    on_lanes!(path, perlin3_stochastic(points: &[[f32; 3]], seed: u32, xi: &[f32], out: &mut [f32]));
    n
}
