//! Sampler tiles (kind `sampler`): per-pixel keys of the runtime's Owen-scrambled Sobol samples
//! (`noise_runtime::sampler::tile_value`), chosen so that the pixels' Monte Carlo errors are
//! blue under the declared spatial filter.
//!
//! The construction is Heitz, Belcour, Ostromoukhov, Coeurjolly and Iehl (2019, "A
//! Low-Discrepancy Sampler that Distributes Monte Carlo Errors as a Blue Noise in Screen
//! Space"): every pixel integrates with an Owen-scrambled Sobol sequence, so its own error is
//! that of a scrambled (0, 2)-sequence whatever its key, and an optimiser chooses the keys so
//! that neighbouring pixels' errors cancel under the filter. The optimiser here is ours:
//!
//! - **Loss.** For training integrands `f_t` (random half-planes, the visibility edges of
//!   occlusion and shadows) the per-pixel error `e_t(x)` of the pixel's `spp`-sample estimate
//!   in each optimised frame, and the loss `L = Σ_t ‖g ∗ e_t‖²`, the energy of the errors after
//!   the filter `g` (FAST's loss, eq. 7–8 of Donnelly et al. 2024, with an integrand's error in
//!   place of a sample value). With `A = g ⋆ g` the filter's autocorrelation,
//!   `L = Σ_t Σ_x e_t(x) (A ∗ e_t)(x)`, and changing pixel `p`'s errors from `a` to `b` (vectors
//!   over `t`) changes it by exactly `2 (b − a)·q + A(0) (‖b‖² − ‖a‖²)`, `q = (A ∗ e)(p) − A(0) a`
//!   the other pixels' part — one dot product per candidate key, given `A ∗ e`, which an
//!   accepted change updates over `A`'s support.
//! - **Candidates.** A pool of keys drawn from the seed, each with its error vector computed
//!   once (the same keys serve every pixel). Each sweep visits the pixels in a seeded order,
//!   scores a seeded subset of the pool at each and takes the best if it lowers the loss, so
//!   the loss never rises. Sweeps stop once one gains under [`Schedule::stop_gain`] of the loss.
//! - **Pairs.** Each pair of dimensions has its own keys and is optimised alone, with its own
//!   integrands, so dimensions 2–3, 4–5, … are as blue as 0–1 (Heitz et al. optimise by pairs
//!   too); pairs run in parallel. A lone last dimension is optimised with 1D steps.
//!
//! Deterministic: every draw comes from the seed, each pair is one thread's fixed sequence of
//! `f32` operations (dot products in eight explicit partial sums, so the compiler can vectorise
//! without reordering), and pairs are joined in order.

use crate::generate::rng::{SplitMix64, derive_seed, permutation};
use crate::spec::sampler::SamplerParams;
use crate::texture::Texture;
use noise_runtime::sampler::tile_value;
use noise_runtime::sequence::to_unit;
use rayon::prelude::*;

/// The optimiser's settings. [`Schedule::DEFAULT`] is what a bake uses; reports vary it to
/// measure the trade of time against error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schedule {
    /// Keys in the candidate pool of each pair.
    pub pool: usize,
    /// Candidates scored per pixel and sweep.
    pub tries: usize,
    /// Training integrand values per candidate (integrands × frames, at least
    /// [`MIN_INTEGRANDS`] integrands per frame).
    pub training: usize,
    /// A sweep that lowers the loss by less than this fraction of it ends the optimisation.
    pub stop_gain: f64,
    /// Most sweeps.
    pub max_sweeps: usize,
}

impl Schedule {
    /// The bake's schedule.
    pub const DEFAULT: Schedule = Schedule {
        pool: 4096,
        tries: 48,
        training: 1024,
        stop_gain: 2e-3,
        max_sweeps: 60,
    };
}

/// Fewest integrands per optimised frame.
pub const MIN_INTEGRANDS: usize = 32;

/// What a bake did, for reports: the loss of each pair at the start and after each sweep.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// Per pair: the loss before the first sweep, then after each sweep.
    pub loss: Vec<Vec<f64>>,
}

/// The keys of a `w × h` tile: `sample_dims` layers of 16-bit keys, x fastest, then y, then the
/// dimension (a pair's 32-bit key is layer `2p` low and layer `2p + 1` high).
pub fn generate(
    p: &SamplerParams,
    w: usize,
    h: usize,
    seed: u64,
    progress: &mut dyn FnMut(u64, u64),
) -> (Vec<u16>, Trace) {
    generate_with(p, w, h, seed, &Schedule::DEFAULT, progress)
}

/// [`generate`] with another schedule.
pub fn generate_with(
    p: &SamplerParams,
    w: usize,
    h: usize,
    seed: u64,
    s: &Schedule,
    progress: &mut dyn FnMut(u64, u64),
) -> (Vec<u16>, Trace) {
    let pairs = (p.sample_dims as usize).div_ceil(2);
    let lone = p.sample_dims % 2 == 1;
    let total = (pairs * s.max_sweeps) as u64;
    progress(0, total);
    let results: Vec<(Vec<u32>, Vec<f64>)> = (0..pairs)
        .into_par_iter()
        .map(|pair| {
            let axes = if lone && pair == pairs - 1 { 1 } else { 2 };
            optimise_pair(p, w, h, derive_seed(seed, pair as u64), axes, s)
        })
        .collect();
    progress(total, total);
    let n = w * h;
    let mut keys = vec![0u16; n * p.sample_dims as usize];
    let mut trace = Trace::default();
    for (pair, (k, loss)) in results.into_iter().enumerate() {
        for (i, &key) in k.iter().enumerate() {
            keys[2 * pair * n + i] = key as u16;
            if 2 * pair + 1 < p.sample_dims as usize {
                keys[(2 * pair + 1) * n + i] = (key >> 16) as u16;
            }
        }
        trace.loss.push(loss);
    }
    (keys, trace)
}

/// The samples a baked tile gives, as the runtime returns them (`SamplerTile::sample`): `f32`
/// with dims `[sample_dims, spp, W, H]` (so a `.npy` has shape `(H, W, spp, D)`), and a last
/// axis of `frames` when the tile was optimised for more than one frame (`(frames, H, W, spp,
/// D)`). `keys` is the generated key texture (`[W, H, sample_dims]`, u16).
pub fn samples(keys: &Texture, p: &SamplerParams) -> Texture {
    let (w, h) = (keys.dims[0], keys.dims[1]);
    let (spp, dims, frames) = (p.spp as usize, p.sample_dims as usize, p.frames as usize);
    let n = w * h;
    let key = |layer: usize, px: usize| {
        let o = 2 * (layer * n + px);
        u16::from_le_bytes([keys.data[o], keys.data[o + 1]]) as u32
    };
    let mut data = Vec::with_capacity(frames * n * spp * dims * 4);
    for f in 0..frames {
        for px in 0..n {
            for i in 0..spp {
                for d in 0..dims {
                    let first = d & !1;
                    let hi = if first + 1 < dims {
                        key(first + 1, px)
                    } else {
                        0
                    };
                    let pair = key(first, px) | hi << 16;
                    let bits = tile_value(pair, (f * spp + i) as u32, d & 1);
                    data.extend_from_slice(&to_unit(bits).to_le_bytes());
                }
            }
        }
    }
    let mut out_dims = vec![dims, spp, w, h];
    if frames > 1 {
        out_dims.push(frames);
    }
    Texture {
        name: keys.name.clone(),
        dims: out_dims,
        format: crate::encoding::Format::F32,
        data,
    }
}

/// One training integrand: the indicator of `a·u + b·v < c` over the unit square (or of
/// `u < c` for a lone dimension), and its exact integral.
#[derive(Clone, Copy, Debug)]
struct Edge {
    a: f64,
    b: f64,
    c: f64,
    integral: f64,
}

impl Edge {
    fn random(rng: &mut SplitMix64, axes: usize) -> Edge {
        if axes == 1 {
            let c = rng.unit_f64();
            return Edge {
                a: 1.0,
                b: 0.0,
                c,
                integral: c,
            };
        }
        let [a, b, c] = random_edge(rng);
        Edge {
            a,
            b,
            c,
            integral: half_plane_area(a, b, c),
        }
    }

    #[inline]
    fn inside(&self, u: f64, v: f64) -> bool {
        self.a * u + self.b * v < self.c
    }
}

/// A random half-plane `[a, b, c]` (`a·u + b·v < c`, `(a, b)` a unit normal) through a
/// uniform point of the unit square, with a uniform direction drawn by rejection, so no
/// transcendental function decides a bit.
pub fn random_edge(rng: &mut SplitMix64) -> [f64; 3] {
    let (a, b) = loop {
        let (a, b) = (2.0 * rng.unit_f64() - 1.0, 2.0 * rng.unit_f64() - 1.0);
        let r2 = a * a + b * b;
        if r2 > 1e-4 && r2 <= 1.0 {
            let r = r2.sqrt();
            break (a / r, b / r);
        }
    };
    let (qx, qy) = (rng.unit_f64(), rng.unit_f64());
    [a, b, a * qx + b * qy]
}

/// The area of `{(u, v) ∈ [0, 1]²: a·u + b·v < c}`: the unit square clipped by the half-plane
/// (one Sutherland–Hodgman pass), by the shoelace formula.
pub fn half_plane_area(a: f64, b: f64, c: f64) -> f64 {
    let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let side = |p: (f64, f64)| c - (a * p.0 + b * p.1);
    let mut poly: Vec<(f64, f64)> = Vec::with_capacity(5);
    for i in 0..4 {
        let (p, q) = (square[i], square[(i + 1) % 4]);
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            poly.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            let t = sp / (sp - sq);
            poly.push((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)));
        }
    }
    let n = poly.len();
    let twice: f64 = (0..n)
        .map(|i| {
            let (p, q) = (poly[i], poly[(i + 1) % n]);
            p.0 * q.1 - q.0 * p.1
        })
        .sum();
    (twice / 2.0).abs()
}

/// The 1D autocorrelation of `taps` folded onto a ring of `n` (so a filter wider than the tile
/// wraps as the tile does): entry `d` is `Σ_i g[i] g[i + d']` over every `d' ≡ d (mod n)`.
fn ring_autocorrelation(taps: &[f64], n: usize) -> Vec<f64> {
    let l = taps.len() as i64;
    let mut out = vec![0.0; n];
    for d in -(l - 1)..l {
        let s: f64 = (0..l)
            .filter(|&i| (0..l).contains(&(i + d)))
            .map(|i| taps[i as usize] * taps[(i + d) as usize])
            .sum();
        out[d.rem_euclid(n as i64) as usize] += s;
    }
    out
}

/// `Σ a[i]·b[i]` in [`DOT_LANES`] partial sums added in a fixed order: the same bits on every
/// machine and build, and vectorised. (Element `i` goes to sum `i mod 32`; a tail shorter than
/// 32 is added lane by lane into the first sums.) The scoring of candidates is this dot
/// product, and with eight sums it waited on the latency of its additions: 32 independent sums
/// keep the vector units busy (`perf` on a tile's bake; `noisebake report sampler` times it).
#[inline]
fn dot(a: &[f32], b: &[f32]) -> f32 {
    let mut acc = [0.0f32; DOT_LANES];
    let whole = a.len().min(b.len()) / DOT_LANES * DOT_LANES;
    for (x, y) in a[..whole]
        .chunks_exact(DOT_LANES)
        .zip(b[..whole].chunks_exact(DOT_LANES))
    {
        for k in 0..DOT_LANES {
            acc[k] += x[k] * y[k];
        }
    }
    for (k, (x, y)) in a[whole..].iter().zip(&b[whole..]).enumerate() {
        acc[k] += x * y;
    }
    // A pairwise tree over the sums, in a fixed order.
    let mut width = DOT_LANES;
    while width > 1 {
        width /= 2;
        for k in 0..width {
            acc[k] += acc[k + width];
        }
    }
    acc[0]
}

/// Offsets of the filter's autocorrelation (per axis) weighing less than this fraction of its
/// centre are left out of the field `A ∗ e`. For a Gaussian of σ 1 that keeps offsets up to 4
/// of the 8 it reaches (weights from e^−4 on), so each accepted change updates 81 pixels' fields
/// instead of 289, at the same measured error (`noisebake report sampler`); a box filter's
/// autocorrelation (a tent) keeps every offset.
const SUPPORT_CUTOFF: f32 = 1e-2;

/// Offsets per axis the field keeps for `spatial` on a ring of `n` ([`SUPPORT_CUTOFF`]): what
/// an accepted key costs, for the estimate.
pub(crate) fn support_width(spatial: crate::spec::fast::Filter, n: usize) -> usize {
    let a = ring_autocorrelation(&spatial.taps(), n);
    let cut = SUPPORT_CUTOFF as f64 * a[0].abs();
    a.iter().filter(|&&v| v != 0.0 && v.abs() >= cut).count()
}

/// Partial sums of [`dot`].
const DOT_LANES: usize = 32;

/// `dst += s · src`, element by element.
#[inline]
fn axpy(dst: &mut [f32], s: f32, src: &[f32]) {
    for (d, &x) in dst.iter_mut().zip(src) {
        *d += s * x;
    }
}

/// Chooses the keys of one pair (`axes` 2) or lone dimension (`axes` 1) for every pixel; returns
/// them with the loss before and after each sweep.
fn optimise_pair(
    p: &SamplerParams,
    w: usize,
    h: usize,
    seed: u64,
    axes: usize,
    s: &Schedule,
) -> (Vec<u32>, Vec<f64>) {
    let (pool_len, tries) = (s.pool, s.tries);
    let mut rng = SplitMix64::new(seed);
    let frames = p.frames as usize;
    let spp = p.spp as usize;
    // Integrands per frame, a multiple of 8.
    let per_frame = (s.training / frames).max(MIN_INTEGRANDS) / 8 * 8;
    let m = per_frame * frames;
    let edges: Vec<Edge> = (0..m).map(|_| Edge::random(&mut rng, axes)).collect();
    let pool: Vec<u32> = (0..pool_len).map(|_| rng.next_u64() as u32).collect();

    // Each candidate's error per (frame, integrand), and its squared norm.
    let errors: Vec<f32> = pool
        .iter()
        .flat_map(|&key| {
            let edges = &edges;
            (0..frames).flat_map(move |f| {
                let pts: Vec<(f64, f64)> = (0..spp)
                    .map(|i| {
                        let n = (f * spp + i) as u32;
                        let u = to_unit(tile_value(key, n, 0)) as f64;
                        let v = if axes == 2 {
                            to_unit(tile_value(key, n, 1)) as f64
                        } else {
                            0.0
                        };
                        (u, v)
                    })
                    .collect();
                edges[f * per_frame..(f + 1) * per_frame]
                    .iter()
                    .map(move |e| {
                        let hits = pts.iter().filter(|&&(u, v)| e.inside(u, v)).count();
                        (hits as f64 / spp as f64 - e.integral) as f32
                    })
            })
        })
        .collect();
    let row = |k: usize| &errors[k * m..(k + 1) * m];
    let norms: Vec<f32> = (0..pool_len).map(|k| dot(row(k), row(k))).collect();

    // The filter's autocorrelation on the tile's rings.
    let taps = p.spatial.taps();
    let ax: Vec<f32> = ring_autocorrelation(&taps, w)
        .iter()
        .map(|&v| v as f32)
        .collect();
    let ay: Vec<f32> = ring_autocorrelation(&taps, h)
        .iter()
        .map(|&v| v as f32)
        .collect();
    let a0 = ax[0] * ay[0];
    // Offsets whose weight is below SUPPORT_CUTOFF of the centre's are left out: every
    // accepted change is added to the field at each kept offset (the bake's hot loop).
    let support = |a: &[f32]| -> Vec<(usize, f32)> {
        let cut = SUPPORT_CUTOFF * a[0].abs();
        a.iter()
            .enumerate()
            .filter(|&(_, &v)| v != 0.0 && v.abs() >= cut)
            .map(|(d, &v)| (d, v))
            .collect()
    };
    let (sx, sy) = (support(&ax), support(&ay));

    // Start: a seeded candidate per pixel; then A ∗ e, separably (x, then y).
    let n = w * h;
    let mut chosen: Vec<u32> = (0..n).map(|_| rng.below(pool_len as u64) as u32).collect();
    let mut tmp = vec![0.0f32; n * m];
    for y in 0..h {
        for x in 0..w {
            let out = &mut tmp[(y * w + x) * m..(y * w + x + 1) * m];
            for &(d, a) in &sx {
                let src = chosen[y * w + (x + d) % w] as usize;
                axpy(out, a, row(src));
            }
        }
    }
    let mut field = vec![0.0f32; n * m];
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            for &(d, a) in &sy {
                let j = ((y + d) % h) * w + x;
                let (src, dst) = (&tmp[j * m..(j + 1) * m], i);
                for (o, &v) in field[dst * m..(dst + 1) * m].iter_mut().zip(src) {
                    *o += a * v;
                }
            }
        }
    }
    drop(tmp);
    let loss = |chosen: &[u32], field: &[f32]| -> f64 {
        (0..n)
            .map(|i| dot(row(chosen[i] as usize), &field[i * m..(i + 1) * m]) as f64)
            .sum()
    };

    let mut trace = vec![loss(&chosen, &field)];
    let mut q = vec![0.0f32; m];
    let mut delta = vec![0.0f32; m];
    for sweep in 0..s.max_sweeps {
        let mut srng = SplitMix64::new(derive_seed(seed, 1 + sweep as u64));
        let order = permutation(n, &mut srng);
        let mut gain = 0.0f64;
        for &i in &order {
            let i = i as usize;
            let cur = chosen[i] as usize;
            let here = &field[i * m..(i + 1) * m];
            for ((qv, &f), &e) in q.iter_mut().zip(here).zip(row(cur)) {
                *qv = f - a0 * e;
            }
            let score = |k: usize| 2.0 * dot(row(k), &q) + a0 * norms[k];
            let here_score = score(cur);
            let mut best = (here_score, cur);
            for _ in 0..tries {
                let k = srng.below(pool_len as u64) as usize;
                let s = score(k);
                if s < best.0 {
                    best = (s, k);
                }
            }
            if best.1 == cur {
                continue;
            }
            gain += (here_score - best.0) as f64;
            for ((d, &b), &a) in delta.iter_mut().zip(row(best.1)).zip(row(cur)) {
                *d = b - a;
            }
            chosen[i] = best.1 as u32;
            let (x, y) = (i % w, i / w);
            for &(dy, ay) in &sy {
                let yy = (y + h - dy % h) % h;
                for &(dx, axv) in &sx {
                    let xx = (x + w - dx % w) % w;
                    let j = yy * w + xx;
                    axpy(&mut field[j * m..(j + 1) * m], axv * ay, &delta);
                }
            }
        }
        let l = trace.last().copied().unwrap_or(0.0) - gain;
        trace.push(l);
        if gain < s.stop_gain * l.abs() {
            break;
        }
    }
    (chosen.iter().map(|&k| pool[k as usize]).collect(), trace)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_plane_areas_are_exact() {
        assert!((half_plane_area(1.0, 0.0, 0.25) - 0.25).abs() < 1e-15);
        assert!((half_plane_area(0.0, -1.0, -0.75) - 0.25).abs() < 1e-15);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        // x + y < 1: half of the square; x + y < 0.5: a triangle of area 1/8.
        assert!((half_plane_area(s, s, s) - 0.5).abs() < 1e-12);
        assert!((half_plane_area(s, s, 0.5 * s) - 0.125).abs() < 1e-12);
        assert_eq!(half_plane_area(1.0, 0.0, -1.0), 0.0);
        assert!((half_plane_area(1.0, 0.0, 2.0) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn the_autocorrelation_folds_onto_small_rings() {
        let taps = [0.25, 0.5, 0.25];
        let wide = ring_autocorrelation(&taps, 16);
        assert_eq!(wide[0], 0.375);
        assert_eq!(wide[1], 0.25);
        assert_eq!(wide[15], 0.25);
        assert_eq!(wide[2], 0.0625);
        let total: f64 = wide.iter().sum();
        assert!((total - 1.0).abs() < 1e-12);
        let folded = ring_autocorrelation(&taps, 2);
        assert!((folded.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }

    fn params(spp: u32, dims: u32) -> SamplerParams {
        SamplerParams {
            spp,
            sample_dims: dims,
            spatial: crate::spec::fast::Filter::Gauss { sigma: 1.0 },
            frames: 1,
        }
    }

    /// The loss never rises, and the optimiser lowers it well below the random start's.
    #[test]
    fn the_loss_falls_monotonically() {
        let (_, trace) = generate(&params(4, 3), 16, 16, 5, &mut |_, _| {});
        assert_eq!(trace.loss.len(), 2);
        for l in &trace.loss {
            assert!(
                l.windows(2).all(|w| w[1] <= w[0] + 1e-9 * w[0].abs()),
                "{l:?}"
            );
            assert!(l.last().unwrap() < &(0.7 * l[0]), "{l:?}");
        }
    }

    /// Same seed, same keys; another seed, other keys; one layer per dimension.
    #[test]
    fn keys_are_deterministic_and_laid_out_by_dimension() {
        let p = params(2, 3);
        let (a, _) = generate(&p, 8, 8, 9, &mut |_, _| {});
        let (b, _) = generate(&p, 8, 8, 9, &mut |_, _| {});
        assert_eq!(a, b);
        assert_eq!(a.len(), 8 * 8 * 3);
        let (c, _) = generate(&p, 8, 8, 10, &mut |_, _| {});
        assert_ne!(a, c);
    }
}
