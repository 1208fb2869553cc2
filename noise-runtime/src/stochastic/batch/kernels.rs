//! The batch kernels on eight lanes, one per algorithm for every target: each step of the
//! single-point function as a plain loop over `[f32; 8]`, which LLVM compiles to one vector
//! instruction (AVX2, or two SSE2 or NEON ones), plus the [`Lanes8`] operations it does not
//! make well itself (the gradient table read, the fixed-point cut and decision of the corner
//! choice, the range mask). Everything is `#[inline(always)]` and generic over the
//! [`Lanes8`] implementation, so that it is compiled inside each entry point: inside the
//! `#[target_feature(enable = "avx2")]` ones of `batch::avx2` with the [`Avx2`] token, and
//! inside the portable ones with [`Portable8`]. A lane whose coordinates leave the split range
//! (`|x| ≥ 2^22`, NaN, infinite) is computed again by the single-point function, which
//! handles it exactly.
//!
//! [`Avx2`]: crate::lanes::avx2::Avx2
//! [`Portable8`]: crate::lanes::scalar::Portable8

use super::super::estimators::{fixed, sanitize_xi};
use super::super::fractal::{Fractal, octave_seed};
use crate::gradients::EDGES3_COLUMNS;
use crate::hash::{CORNER_MUL, PRIME};
use crate::lanes::{F8, Lanes8, U8};
use crate::math::{fade, split_in_range};

/// Lanes per register.
const W: usize = 8;
/// The fixed-point 1 of the corner choice (`estimators::Narrowing`).
const ONE: u32 = 1 << 23;

/// Eight points as three coordinate registers.
#[inline(always)]
fn columns(p: &[[f32; 3]; W]) -> [F8; 3] {
    let mut c = [[0.0f32; W]; 3];
    for i in 0..W {
        for a in 0..3 {
            c[a][i] = p[i][a];
        }
    }
    c
}

/// Bit `i` set when lane `i` of `p` is outside the split range (the test of
/// [`in_split_range`](crate::math::in_split_range), lane by lane).
#[inline(always)]
fn outside<L: Lanes8>(cpu: L, p: &[F8; 3]) -> u32 {
    let mut any = [0u32; W];
    for c in p {
        for i in 0..W {
            any[i] |= (c[i].to_bits() & 0x7fff_ffff).wrapping_add(0x8000_0000 - 0x4a80_0000);
        }
    }
    cpu.sign_bits(any)
}

/// Cells (as `u32`) and offsets of every lane by [`split_in_range`].
#[inline(always)]
fn split(p: &[F8; 3]) -> ([U8; 3], [F8; 3]) {
    let mut cell = [[0u32; W]; 3];
    let mut f = [[0.0f32; W]; 3];
    for a in 0..3 {
        for i in 0..W {
            let (c, fa) = split_in_range(p[a][i]);
            cell[a][i] = c as u32;
            f[a][i] = fa;
        }
    }
    (cell, f)
}

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
fn perlin3_lanes<L: Lanes8>(cpu: L, p: &[F8; 3], seed: u32) -> F8 {
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
fn perlin3_stochastic_lanes<L: Lanes8, const UNIT: bool>(
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

/// The loop of every entry point: `$lanes` (an expression of the chunk's columns `$p`, and
/// of its ξ `$x` when the entry point has them, giving the eight values and a mask of lanes
/// outside the split range) over the points eight at a time; `$one` (an expression of the
/// point's index `$i`) for each masked lane and for the points after the last whole chunk.
macro_rules! chunks {
    ($points:expr, $out:expr, |$p:ident| $lanes:expr, |$i:ident| $one:expr) => {{
        let (points, out): (&[[f32; 3]], &mut [f32]) = ($points, $out);
        let (chunks, _) = points.as_chunks::<W>();
        let (outs, _) = out.as_chunks_mut::<W>();
        for (k, (c, o)) in chunks.iter().zip(outs.iter_mut()).enumerate() {
            let $p = columns(c);
            let (v, bad): (F8, u32) = $lanes;
            *o = v;
            fix_lanes!(o, bad, k, |$i| $one);
        }
        for (n, o) in out.iter_mut().enumerate().skip(chunks.len() * W) {
            let $i = n;
            *o = $one;
        }
    }};
    (
        $points:expr, $xi:expr, $out:expr,
        |$p:ident, $x:ident| $lanes:expr, |$i:ident| $one:expr
    ) => {{
        let (points, xi, out): (&[[f32; 3]], &[f32], &mut [f32]) = ($points, $xi, $out);
        let (chunks, _) = points.as_chunks::<W>();
        let (xis, _) = xi.as_chunks::<W>();
        let (outs, _) = out.as_chunks_mut::<W>();
        for (k, ((c, $x), o)) in chunks.iter().zip(xis).zip(outs.iter_mut()).enumerate() {
            let $p = columns(c);
            let (v, bad): (F8, u32) = $lanes;
            *o = v;
            fix_lanes!(o, bad, k, |$i| $one);
        }
        for (n, o) in out.iter_mut().enumerate().skip(chunks.len() * W) {
            let $i = n;
            *o = $one;
        }
    }};
}

/// `$one` for each lane of chunk `$k` whose bit is set in `$bad`, written to `$o`.
macro_rules! fix_lanes {
    ($o:ident, $bad:ident, $k:ident, |$i:ident| $one:expr) => {
        if $bad != 0 {
            for (lane, o) in $o.iter_mut().enumerate() {
                if $bad >> lane & 1 == 1 {
                    let $i = $k * W + lane;
                    *o = $one;
                }
            }
        }
    };
}

/// [`perlin3_batch`](super::perlin3_batch) on eight lanes (`points` and `out` of one length).
#[inline(always)]
pub(super) fn perlin3<L: Lanes8>(cpu: L, points: &[[f32; 3]], seed: u32, out: &mut [f32]) {
    chunks!(
        points,
        out,
        |p| (perlin3_lanes(cpu, &p, seed), outside(cpu, &p)),
        |i| super::perlin3(points[i], seed)
    );
}

/// [`perlin3_stochastic_batch`](super::perlin3_stochastic_batch) on eight lanes (slices of one
/// length).
#[inline(always)]
pub(super) fn perlin3_stochastic<L: Lanes8>(
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

/// [`fbm3_batch`](super::fbm3_batch) on eight lanes: `fbm3`'s octaves in its order, each
/// octave's points on lanes (a lane outside the split range at some octave takes the
/// single-point Perlin noise for that octave).
#[inline(always)]
pub(super) fn fbm3<L: Lanes8>(cpu: L, points: &[[f32; 3]], f: Fractal, seed: u32, out: &mut [f32]) {
    let (n, lac, gain) = f.sane();
    chunks!(
        points,
        out,
        |p| {
            let (mut amp, mut freq, mut sum) = (1.0f32, 1.0f32, [0.0f32; W]);
            for o in 0..n {
                let mut q = p;
                for c in q.iter_mut() {
                    for v in c.iter_mut() {
                        *v *= freq;
                    }
                }
                let s = octave_seed(seed, o);
                let mut v = perlin3_lanes(cpu, &q, s);
                let bad = outside(cpu, &q);
                if bad != 0 {
                    for (i, v) in v.iter_mut().enumerate() {
                        if bad >> i & 1 == 1 {
                            *v = super::perlin3([q[0][i], q[1][i], q[2][i]], s);
                        }
                    }
                }
                for i in 0..W {
                    sum[i] += amp * v[i];
                }
                amp *= gain;
                freq *= lac;
            }
            (sum, 0)
        },
        |i| super::fbm3(points[i], f, seed)
    );
}

/// [`fbm3_stochastic_batch`](super::fbm3_stochastic_batch) on eight lanes, for lacunarity 2
/// and gain ±½ (the caller checks). Each lane's octave is the one `fractal::OctavePick`
/// picks, here read off the exponent of `2 − target` (exact, by Sterbenz's lemma): a target
/// in `[2 − 2^−k, 2 − 2^−(k+1))` lies in octave `k + 1`, and then `2 − target` lies in
/// `(2^−(k+1), 2^−k]`, whose exponent `e` gives `k = −e`, or `−e − 1` when `2 − target` is
/// not a power of two. Then the octave's estimator on lanes, each lane with its own
/// octave's frequency, seed and remapped ξ.
#[inline(always)]
pub(super) fn fbm3_stochastic<L: Lanes8>(
    cpu: L,
    points: &[[f32; 3]],
    f: Fractal,
    seed: u32,
    xi: &[f32],
    out: &mut [f32],
) {
    let (n, _, gain) = f.sane();
    let total = 2.0 - f32::from_bits((128 - n) << 23);
    let below = f32::from_bits(total.to_bits() - 1);
    let negative = (gain < 0.0) as u32;
    chunks!(
        points,
        xi,
        out,
        |p, x| {
            let mut octave = [0u32; W];
            let mut seeds = [0u32; W];
            let mut remapped = [0.0f32; W];
            let mut q = [[0.0f32; W]; 3];
            for i in 0..W {
                // Non-negative, so the bits order as the values: an integer minimum, without
                // `f32::min`'s NaN case (no NaN comes out of `sanitize_xi`).
                let target =
                    f32::from_bits((sanitize_xi(x[i]) * total).to_bits().min(below.to_bits()));
                let d = (2.0 - target).to_bits();
                // k + 1 = 128 − (biased exponent of d), less one unless d is a power of two;
                // octave 0 below 1.
                let o = 128u32
                    .wrapping_sub(d >> 23)
                    .wrapping_sub((d & 0x7f_ffff != 0) as u32)
                    & 0u32.wrapping_sub((target.to_bits() >= 0x3f80_0000) as u32);
                let freq = f32::from_bits((127 + o) << 23);
                octave[i] = o;
                seeds[i] = octave_seed(seed, o);
                remapped[i] = target * freq - (((2u32 << o) - 2) as i32) as f32;
                for a in 0..3 {
                    q[a][i] = p[a][i] * freq;
                }
            }
            let v = perlin3_stochastic_lanes::<L, true>(cpu, &q, &seeds, &remapped);
            let mut s = [0.0f32; W];
            for i in 0..W {
                s[i] = f32::from_bits((total * v[i]).to_bits() ^ ((negative & octave[i]) << 31));
            }
            (s, outside(cpu, &q))
        },
        |i| super::fbm3_stochastic(points[i], f, seed, xi[i])
    );
}
