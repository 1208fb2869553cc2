//! The sampler optimiser: which block of its pair's Sobol sequence each pixel takes.
//!
//! **Loss.** For training integrands `f_t` the per-pixel error `e_t(x)` of the pixel's
//! `spp`-sample estimate in each optimised frame, and `L = Σ_t ‖g ∗ e_t‖²`, the energy of the
//! errors after the declared filter `g` (FAST's loss, eq. 7–8 of Donnelly et al. 2024, with an
//! integrand's error in place of a sample value). With `A = g ⋆ g` the filter's autocorrelation,
//! `L = Σ_x e(x)·F(x)` with the field `F = A ∗ e`, and adding `δ` to pixel `p`'s error vector
//! changes `L` by exactly `2 δ·F(p) + A(0) ‖δ‖²`; moving two pixels' vectors at once adds the
//! cross term `2 A(p − q) δ_p·δ_q`.
//!
//! **Moves.** The pool holds a few times as many blocks as the tile has pixels, and each pixel
//! holds a distinct one. Per pixel and sweep the optimiser scores candidate blocks: half of them
//! a *sibling* of a nearby pixel's block (its index with one of the low bits flipped: the two
//! together make an aligned, finer net, the stratification that cancels errors across pixels,
//! which Ahmed and Wonka 2020 get from the Morton order), half drawn from the whole pool. A
//! free candidate is scored as a replacement (one dot product); one another pixel holds, as a
//! swap with that pixel (four). The best move that lowers the loss is made, so the loss never
//! rises; sweeps stop once one gains under [`Schedule::stop_gain`](super::Schedule) of it.
//!
//! Deterministic: every draw comes from the seed, and every dot product is a fixed sequence of
//! `f32` operations in [`DOT_LANES`] partial sums.

use super::Schedule;
use super::training::{Edge, Table};
use crate::generate::rng::{SplitMix64, derive_seed, permutation};
use crate::spec::fast::Filter;
use crate::spec::sampler::SamplerParams;

/// Fewest integrands per optimised frame (a multiple of the dot products' 32 lanes).
pub const MIN_INTEGRANDS: usize = 32;

/// Most blocks in a pair's pool: a lone last dimension's key is one 16-bit layer.
pub const MAX_BLOCKS: usize = 1 << 16;

/// Most (block, sample, integrand) inside tests the pool's table may take: the pool shrinks
/// towards one block per pixel at high spp rather than take longer to set up than to optimise.
const MAX_TABLE_WORK: usize = 1 << 30;

/// Pixels around a pixel (a square of this radius) whose blocks' siblings are candidates.
const SIBLING_RADIUS: usize = 2;

/// Low bits a sibling candidate may differ in: block groups up to 2^8 blocks.
const SIBLING_BITS: u32 = 8;

/// Offsets of the filter's autocorrelation (per axis) weighing less than this fraction of its
/// centre are left out of the field `A ∗ e`. For a Gaussian of σ 1 that keeps offsets up to 4
/// of the 8 it reaches (weights from e^−4 on), so each move updates 81 pixels' fields instead of
/// 289, at the same measured error (`noisebake report sampler`); a box filter's autocorrelation
/// (a tent) keeps every offset.
const SUPPORT_CUTOFF: f32 = 1e-2;

/// Partial sums of [`dot`].
const DOT_LANES: usize = 32;

/// The blocks in the pool of a `pixels`-pixel tile: `pool_factor` times the pixels rounded up
/// to a power of two, fewer when the table would be too much work, at least one per pixel and
/// at least `frames`, at most [`MAX_BLOCKS`].
pub(crate) fn pool_blocks(
    pixels: usize,
    spp: u32,
    frames: u32,
    training: usize,
    s: &Schedule,
) -> usize {
    let least = pixels.next_power_of_two().max(frames as usize).max(2);
    let mut blocks = least * s.pool_factor.next_power_of_two();
    while blocks > least
        && (blocks > MAX_BLOCKS || blocks * spp as usize * training > MAX_TABLE_WORK)
    {
        blocks /= 2;
    }
    blocks.min(MAX_BLOCKS.max(least))
}

/// The training values per pixel for `frames` frames: [`Schedule::training`] split over the
/// frames, at least [`MIN_INTEGRANDS`] per frame, a multiple of [`DOT_LANES`] per frame.
pub(crate) fn training_len(training: usize, frames: u32) -> usize {
    let per_frame = (training / frames as usize).max(MIN_INTEGRANDS) / DOT_LANES * DOT_LANES;
    per_frame * frames as usize
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

/// The autocorrelation of `spatial` on a ring of `n`, as `f32`, with the offsets under
/// [`SUPPORT_CUTOFF`] of the centre set to zero.
fn kept_autocorrelation(spatial: Filter, n: usize) -> Vec<f32> {
    let a = ring_autocorrelation(&spatial.taps(), n);
    let cut = SUPPORT_CUTOFF as f64 * a[0].abs();
    a.iter()
        .map(|&v| if v.abs() >= cut { v as f32 } else { 0.0 })
        .collect()
}

/// Offsets per axis the field keeps for `spatial` on a ring of `n` ([`SUPPORT_CUTOFF`]): what
/// a move costs, for the estimate.
pub(crate) fn support_width(spatial: Filter, n: usize) -> usize {
    kept_autocorrelation(spatial, n)
        .iter()
        .filter(|&&v| v != 0.0)
        .count()
}

/// `Σ a[i]·b[i]` in [`DOT_LANES`] partial sums added in a fixed order: the same bits on every
/// machine and build, and vectorised. (Element `i` goes to sum `i mod 32`; a tail shorter than
/// 32 is added lane by lane into the first sums.) 32 independent sums keep the vector units
/// busy where eight waited on the latency of their additions (`perf` on a tile's bake).
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
    reduce(acc)
}

/// [`dot`] of `f32` values with hit counts (exact as `f32`).
#[inline]
fn dot_hits(a: &[f32], h: &[u8]) -> f32 {
    let mut acc = [0.0f32; DOT_LANES];
    for (x, y) in a.chunks_exact(DOT_LANES).zip(h.chunks_exact(DOT_LANES)) {
        for k in 0..DOT_LANES {
            acc[k] += x[k] * y[k] as f32;
        }
    }
    reduce(acc)
}

/// A pairwise tree over the partial sums, in a fixed order.
#[inline]
fn reduce(mut acc: [f32; DOT_LANES]) -> f32 {
    let mut width = DOT_LANES;
    while width > 1 {
        width /= 2;
        for k in 0..width {
            acc[k] += acc[k + width];
        }
    }
    acc[0]
}

/// `dst += s · src`, element by element.
#[inline]
fn axpy(dst: &mut [f32], s: f32, src: &[f32]) {
    for (d, &x) in dst.iter_mut().zip(src) {
        *d += s * x;
    }
}

/// `Σ_t x[t]·hits[t]` over a pixel holding block `b`: each frame's slice from block `b ^ f`.
#[inline]
fn dot_block(t: &Table, b: usize, x: &[f32]) -> f32 {
    let mut s = 0.0;
    for f in 0..t.frames {
        let range = f * t.per_frame..(f + 1) * t.per_frame;
        s += dot_hits(&x[range], t.slice(b ^ f, f));
    }
    s
}

/// The field `A ∗ e` on the tile's torus, and the moves that change it.
struct Field {
    w: usize,
    h: usize,
    len: usize,
    values: Vec<f32>,
    ax: Vec<f32>,
    ay: Vec<f32>,
    sx: Vec<(usize, f32)>,
    sy: Vec<(usize, f32)>,
}

impl Field {
    fn new(spatial: Filter, w: usize, h: usize, len: usize) -> Field {
        let (ax, ay) = (
            kept_autocorrelation(spatial, w),
            kept_autocorrelation(spatial, h),
        );
        let kept = |a: &[f32]| -> Vec<(usize, f32)> {
            a.iter()
                .enumerate()
                .filter(|&(_, &v)| v != 0.0)
                .map(|(d, &v)| (d, v))
                .collect()
        };
        let (sx, sy) = (kept(&ax), kept(&ay));
        Field {
            w,
            h,
            len,
            values: vec![0.0; w * h * len],
            ax,
            ay,
            sx,
            sy,
        }
    }

    /// `A(0)`.
    fn centre(&self) -> f32 {
        self.ax[0] * self.ay[0]
    }

    /// `A(p − q)`.
    fn between(&self, p: usize, q: usize) -> f32 {
        let (w, h) = (self.w, self.h);
        let dx = (p % w + w - q % w) % w;
        let dy = (p / w + h - q / w) % h;
        self.ax[dx] * self.ay[dy]
    }

    fn at(&self, p: usize) -> &[f32] {
        &self.values[p * self.len..(p + 1) * self.len]
    }

    /// Sets the field of pixels holding `chosen` (it was zero); returns their loss `Σ e·F`.
    fn fill(&mut self, table: &Table, chosen: &[u32]) -> f64 {
        let mut e = vec![0.0f32; self.len];
        for (i, &b) in chosen.iter().enumerate() {
            table.errors(b as usize, &mut e);
            self.add(i, 1.0, &e);
        }
        chosen
            .iter()
            .enumerate()
            .map(|(i, &b)| {
                table.errors(b as usize, &mut e);
                dot(&e, self.at(i)) as f64
            })
            .sum()
    }

    /// Adds `s · delta` at pixel `p`: `s · A(q − p) · delta` to every `q` in its support.
    fn add(&mut self, p: usize, s: f32, delta: &[f32]) {
        let (w, h, len) = (self.w, self.h, self.len);
        let (x, y) = (p % w, p / w);
        for &(dy, ay) in &self.sy {
            let yy = (y + dy) % h;
            for &(dx, ax) in &self.sx {
                let q = yy * w + (x + dx) % w;
                axpy(&mut self.values[q * len..(q + 1) * len], s * ax * ay, delta);
            }
        }
    }
}

/// A move the optimiser found for one pixel.
#[derive(Clone, Copy)]
enum Move {
    /// Take this free block.
    Replace(usize),
    /// Take this block from that pixel, which takes ours.
    Swap(usize, usize),
}

/// Each pixel's rank in the Morton (Z) order of a `w × h` tile: its block in the start.
fn morton_ranks(w: usize, h: usize) -> Vec<u32> {
    let spread = |v: usize| (0..16).fold(0u64, |r, b| r | (((v >> b) & 1) as u64) << (2 * b));
    let mut order: Vec<usize> = (0..w * h).collect();
    order.sort_by_key(|&i| spread(i % w) | spread(i / w) << 1);
    let mut rank = vec![0u32; w * h];
    for (r, &i) in order.iter().enumerate() {
        rank[i] = r as u32;
    }
    rank
}

/// No pixel holds the block.
const FREE: u32 = u32::MAX;

/// The training table of a pair (its integrands drawn from `seed`) and every block's squared
/// error norm.
fn training_table(
    p: &SamplerParams,
    pixels: usize,
    seed: u64,
    pair: u32,
    axes: usize,
    s: &Schedule,
) -> (Table, Vec<f32>) {
    let mut rng = SplitMix64::new(seed);
    let len = training_len(s.training, p.frames);
    let edges: Vec<Edge> = (0..len).map(|_| Edge::random(&mut rng, axes)).collect();
    let blocks = pool_blocks(pixels, p.spp, p.frames, len, s);
    let table = Table::build(&edges, blocks, p.frames as usize, p.spp, pair, axes);
    let mut va = vec![0.0f32; len];
    let norms = (0..blocks)
        .map(|b| {
            table.errors(b, &mut va);
            dot(&va, &va)
        })
        .collect();
    (table, norms)
}

/// Chooses the blocks of pair `pair` (`axes` 2, or 1 for a lone last dimension) for every pixel;
/// returns them with the loss before and after each sweep, and the seconds to each.
pub(super) fn optimise_pair(
    p: &SamplerParams,
    w: usize,
    h: usize,
    seed: u64,
    pair: u32,
    axes: usize,
    s: &Schedule,
) -> (Vec<u32>, Vec<f64>, Vec<f64>) {
    let started = std::time::Instant::now();
    let n = w * h;
    let (table, norms) = training_table(p, n, seed, pair, axes, s);
    let (blocks, len) = (norms.len(), table.len);
    let mut va = vec![0.0f32; len];

    // Start: the first `n` blocks in the Morton order of the pixels (Ahmed and Wonka's
    // arrangement, the best free one: every aligned square of pixels holds an aligned group of
    // blocks), so the optimiser starts from ZSobol's stratification and only improves on it.
    let mut chosen = morton_ranks(w, h);
    let mut holder = vec![FREE; blocks];
    for (i, &b) in chosen.iter().enumerate() {
        holder[b as usize] = i as u32;
    }
    let mut field = Field::new(p.spatial, w, h, len);
    let a0 = field.centre();
    let loss = field.fill(&table, &chosen);

    let mut trace = vec![loss];
    let mut seconds = vec![started.elapsed().as_secs_f64()];

    let bits = blocks.trailing_zeros().clamp(1, SIBLING_BITS) as u64;
    let side = 2 * SIBLING_RADIUS as u64 + 1;
    let mut q = vec![0.0f32; len];
    let mut wv = vec![0.0f32; len];
    let mut vc = vec![0.0f32; len];
    let mut cands = Vec::with_capacity(s.candidates);
    for sweep in 0..s.max_sweeps {
        let mut srng = SplitMix64::new(derive_seed(seed, 1 + sweep as u64));
        let order = permutation(n, &mut srng);
        let mut gain = 0.0f64;
        for &i in &order {
            let i = i as usize;
            let a = chosen[i] as usize;
            table.errors(a, &mut va);
            let fi = field.at(i);
            for ((qv, &f), &e) in q.iter_mut().zip(fi).zip(&va) {
                *qv = f - a0 * e;
            }
            for ((wv, &e), &t) in wv.iter_mut().zip(&va).zip(&table.integral) {
                *wv = e + t;
            }
            let aq = dot(&va, &q);
            let iq = dot(&table.integral, &q);
            let iva = dot(&table.integral, &va);
            let (x, y) = (i % w, i / w);
            let mut best: Option<(f32, Move)> = None;
            cands.clear();
            for _ in 0..s.candidates {
                let c = if srng.below(2) == 0 {
                    let nx =
                        (x + w * side as usize + srng.below(side) as usize - SIBLING_RADIUS) % w;
                    let ny =
                        (y + h * side as usize + srng.below(side) as usize - SIBLING_RADIUS) % h;
                    chosen[ny * w + nx] as usize ^ (1 << srng.below(bits))
                } else {
                    srng.below(blocks as u64) as usize
                };
                table.prefetch(c);
                cands.push(c);
            }
            for &c in &cands {
                if c == a {
                    continue;
                }
                // v_c·q, from the table.
                let cq = table.scale * dot_block(&table, c, &q) - iq;
                let j = holder[c];
                let take = 2.0 * (cq - aq) + a0 * (norms[c] - norms[a]);
                let (delta, mv) = if j == FREE {
                    (take, Move::Replace(c))
                } else if take >= best.map_or(0.0, |(d, _)| d) {
                    // A held block is scored as a swap only when taking it would beat the best
                    // move so far by itself: the holder's loss rarely makes up for a pixel's
                    // gain, and a swap costs four dot products to a replacement's one (this
                    // skips nine in ten of them and keeps the error: `report sampler`).
                    continue;
                } else {
                    let j = j as usize;
                    let fj = field.at(j);
                    let ac = table.scale * dot_block(&table, c, &va) - iva;
                    // (v_c − v_a)·F_i and (v_c − v_a)·F_j.
                    let di = (cq + a0 * ac) - (aq + a0 * norms[a]);
                    let dj = table.scale * dot_block(&table, c, fj) - dot(&wv, fj);
                    let dd = norms[c] + norms[a] - 2.0 * ac;
                    let cross = a0 - field.between(i, j);
                    (2.0 * (di - dj) + 2.0 * cross * dd, Move::Swap(c, j))
                };
                if delta < 0.0 && best.is_none_or(|(d, _)| delta < d) {
                    best = Some((delta, mv));
                }
            }
            let Some((delta, mv)) = best else { continue };
            gain -= delta as f64;
            let c = match mv {
                Move::Replace(c) | Move::Swap(c, _) => c,
            };
            table.errors(c, &mut vc);
            for (d, &e) in vc.iter_mut().zip(&va) {
                *d -= e;
            }
            field.add(i, 1.0, &vc);
            chosen[i] = c as u32;
            holder[c] = i as u32;
            match mv {
                Move::Replace(_) => holder[a] = FREE,
                Move::Swap(_, j) => {
                    field.add(j, -1.0, &vc);
                    chosen[j] = a as u32;
                    holder[a] = j as u32;
                }
            }
        }
        let l = trace.last().copied().unwrap_or(0.0) - gain;
        trace.push(l);
        seconds.push(started.elapsed().as_secs_f64());
        if super::spent(gain, l, s.stop_gain) {
            break;
        }
    }
    (chosen, trace, seconds)
}

#[cfg(test)]
mod tests {
    use super::*;

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

    fn params(spp: u32, frames: u32, spatial: Filter) -> SamplerParams {
        SamplerParams {
            spp,
            sample_dims: 2,
            spatial,
            frames,
        }
    }

    /// The loss the optimiser tracks from its moves' exact changes is the loss of the blocks it
    /// returns, computed afresh: the replacement and swap formulas, the field's updates and the
    /// frames' gathering agree. The loss never rises, and falls well below the start's.
    #[test]
    fn the_tracked_loss_is_the_loss_of_the_result() {
        let s = Schedule {
            training: 256,
            max_sweeps: 6,
            ..Schedule::DEFAULT
        };
        for (p, axes) in [
            (params(4, 1, Filter::Gauss { sigma: 1.0 }), 2),
            (params(2, 3, Filter::Box { size: 3 }), 2),
            (params(1, 1, Filter::Gauss { sigma: 1.5 }), 1),
        ] {
            let (w, h) = (16, 8);
            let (chosen, trace, _) = optimise_pair(&p, w, h, 11, 0, axes, &s);
            assert!(trace.windows(2).all(|t| t[1] <= t[0]), "{trace:?}");
            assert!(trace.last().unwrap() < &(0.9 * trace[0]), "{trace:?}");
            let (table, _) = training_table(&p, w * h, 11, 0, axes, &s);
            let mut field = Field::new(p.spatial, w, h, table.len);
            let fresh = field.fill(&table, &chosen);
            let tracked = *trace.last().unwrap();
            assert!(
                (fresh - tracked).abs() < 1e-4 * fresh,
                "{p:?}: fresh {fresh}, tracked {tracked}"
            );
            // Every pixel holds its own block.
            let mut seen = chosen.clone();
            seen.sort();
            seen.dedup();
            assert_eq!(seen.len(), chosen.len());
        }
    }

    /// The start is the Morton order, ranked, on any tile.
    #[test]
    fn the_start_is_the_morton_order() {
        assert_eq!(morton_ranks(2, 2), [0, 1, 2, 3]);
        assert_eq!(morton_ranks(4, 2), [0, 1, 4, 5, 2, 3, 6, 7]);
        // 3 × 2: codes 0, 1, 4 / 2, 3, 6, ranked.
        assert_eq!(morton_ranks(3, 2), [0, 1, 4, 2, 3, 5]);
    }

    /// The pool is a power of two, several blocks per pixel for a small spp, one per pixel
    /// rounded up when the table would be too much work, and covers the frames.
    #[test]
    fn pools_are_sized_for_the_tile_and_the_work() {
        let s = Schedule::DEFAULT;
        assert_eq!(pool_blocks(128 * 128, 4, 1, 1024, &s), 1 << 16);
        assert_eq!(pool_blocks(128 * 128, 64, 1, 1024, &s), 1 << 14);
        assert_eq!(pool_blocks(256 * 256, 1, 1, 1024, &s), 1 << 16);
        assert_eq!(pool_blocks(100, 1, 1, 1024, &s), 512);
        assert_eq!(pool_blocks(2, 1, 64, 2048, &s), 256);
        assert_eq!(training_len(1024, 64), 2048);
        assert_eq!(training_len(1024, 3), 3 * 320);
    }
}
