//! The sampler optimiser: which pixel holds which shift of one pair of dimensions.
//!
//! **Loss.** For training integrands `k` (`training.rs`) each pixel's error `e_k(x)` — of one
//! frame's `spp` samples, or of the EMA's history — and `L = Σ_k ‖g ∗ e_k‖²`, the energy of
//! the errors after the declared filter `g` (FAST's loss, eq. 7–8 of Donnelly et al. 2024, with
//! an integrand's error in place of a sample value). With `A = g ⋆ g` the filter's
//! autocorrelation, `L = Σ_x e(x)·B(x)` with the field `B = A ∗ e`.
//!
//! **The à-trous at every scale.** A denoiser's edge-stopping weights cut its à-trous short
//! near edges and creases (Schied et al. 2017, §4.4), where occlusion's error lives, so its
//! effective filter there is its first passes, and only on open surfaces all of them. For
//! `atrous` with `N` passes the loss is therefore `Σ_{k=1..N} ‖g_k ∗ e‖² / ‖g_k‖⁴`, `g_k` the
//! first `k` passes and `‖g_k‖⁴ = (Σ g_k²)²` its gain on white noise, so each scale weighs
//! alike: `A = Σ_k A_k / ‖g_k‖⁴`. Trained on the full filter alone, a tile traded away the
//! fine scales and lost to the free lattice behind the edge-stopped denoiser.
//!
//! **Moves.** Swaps of two pixels' shifts, so the tile keeps the start's set of shifts (a
//! stratified set: every shift is as good as any other on its own) and only their arrangement
//! changes. Swapping `p` and `q` moves `e(p)` by `δ = e(q) − e(p)` and `e(q)` by `−δ`, which
//! changes `L` by exactly `2 δ·(B(p) − B(q)) + 2 ‖δ‖² (A(0) − A(p − q))`: one pass over the
//! pixel's training values. Per pixel and sweep, [`Schedule::candidates`](super::Schedule)
//! partners (most within the filter's reach, some anywhere) are scored, and the best swap that
//! lowers `L` is made, so the loss never rises: started from the free construction's
//! arrangement (`rd_ign_r2`'s shifts), the tile ends at or below it on the training loss.
//! Sweeps stop once one gains under [`Schedule::stop_gain`](super::Schedule) of the loss.
//!
//! Deterministic: every draw comes from the seed, and every dot product is a fixed sequence of
//! `f32` operations in [`DOT_LANES`] partial sums.

use super::Schedule;
use super::training::Errors;
use crate::generate::rng::{SplitMix64, permutation};
use crate::spec::fast::Filter;

/// Offsets of the filter's autocorrelation (per axis) weighing less than this fraction of its
/// centre are left out of the field `A ∗ e`. For a Gaussian of σ 1 that keeps offsets up to 4
/// of the 8 it reaches (weights from e^−4 on), so each swap updates 81 pixels' fields instead
/// of 289; a box filter's autocorrelation (a tent) keeps every offset.
const SUPPORT_CUTOFF: f32 = 1e-2;

/// Partial sums of the dot products.
const DOT_LANES: usize = 16;

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

/// The loss's autocorrelation on the `w × h` torus, row by row: the sum of the separable
/// terms of [`scales`], each with its axes cut at [`SUPPORT_CUTOFF`], in `f32`.
fn kept_table(spatial: Filter, w: usize, h: usize) -> Vec<f32> {
    let mut table = vec![0.0f32; w * h];
    for (weight, filter) in scales(spatial) {
        let (ax, ay) = (
            kept_autocorrelation(filter, w),
            kept_autocorrelation(filter, h),
        );
        for (dy, &vy) in ay.iter().enumerate() {
            for (dx, &vx) in ax.iter().enumerate() {
                if vx != 0.0 && vy != 0.0 {
                    table[dy * w + dx] += weight * (vx * vy);
                }
            }
        }
    }
    table
}

/// The filters whose error energies the loss sums, with their weights: `spatial` alone, or
/// for the à-trous each pass count `1..=N` over its white-noise gain (see the module's doc).
fn scales(spatial: Filter) -> Vec<(f32, Filter)> {
    match spatial {
        Filter::Atrous { passes } if passes > 1 => (1..=passes)
            .map(|k| {
                let f = Filter::Atrous { passes: k };
                let gain: f64 = f.taps().iter().map(|t| t * t).sum();
                ((1.0 / (gain * gain)) as f32, f)
            })
            .collect(),
        _ => vec![(1.0, spatial)],
    }
}

/// Offsets per axis the field keeps for `spatial` on a ring of `n` ([`SUPPORT_CUTOFF`]): what
/// a swap costs, for the estimate.
pub(crate) fn support_width(spatial: Filter, n: usize) -> usize {
    kept_autocorrelation(spatial, n)
        .iter()
        .filter(|&&v| v != 0.0)
        .count()
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

/// `Σ δ·(bp − bq)` and `Σ δ²` for `δ = eq − ep`, in [`DOT_LANES`] partial sums (the rows'
/// lengths are a multiple of it).
#[inline]
fn swap_terms(ep: &[f32], eq: &[f32], bp: &[f32], bq: &[f32]) -> (f32, f32) {
    let (mut cross, mut norm) = ([0.0f32; DOT_LANES], [0.0f32; DOT_LANES]);
    for (((a, b), c), d) in ep
        .chunks_exact(DOT_LANES)
        .zip(eq.chunks_exact(DOT_LANES))
        .zip(bp.chunks_exact(DOT_LANES))
        .zip(bq.chunks_exact(DOT_LANES))
    {
        for k in 0..DOT_LANES {
            let delta = b[k] - a[k];
            cross[k] += delta * (c[k] - d[k]);
            norm[k] += delta * delta;
        }
    }
    (reduce(cross), reduce(norm))
}

/// `Σ a·b` in [`DOT_LANES`] partial sums.
#[inline]
fn dot(a: &[f32], b: &[f32]) -> f32 {
    let mut acc = [0.0f32; DOT_LANES];
    for (x, y) in a.chunks_exact(DOT_LANES).zip(b.chunks_exact(DOT_LANES)) {
        for k in 0..DOT_LANES {
            acc[k] += x[k] * y[k];
        }
    }
    reduce(acc)
}

/// The field `A ∗ e` on the tile's torus, and the swaps that change it.
struct Field {
    w: usize,
    h: usize,
    len: usize,
    values: Vec<f32>,
    /// `A` on the torus, row by row.
    table: Vec<f32>,
    support: Vec<(usize, usize, f32)>,
}

impl Field {
    fn new(spatial: Filter, w: usize, h: usize, e: &Errors) -> Field {
        let table = kept_table(spatial, w, h);
        let mut support = Vec::new();
        for dy in 0..h {
            for dx in 0..w {
                let a = table[dy * w + dx];
                if a != 0.0 {
                    support.push((dx, dy, a));
                }
            }
        }
        let len = e.len;
        let mut f = Field {
            w,
            h,
            len,
            values: vec![0.0; w * h * len],
            table,
            support,
        };
        for p in 0..w * h {
            f.add(p, e.row(p));
        }
        f
    }

    /// `A(p − q)`.
    fn between(&self, p: usize, q: usize) -> f32 {
        let (w, h) = (self.w, self.h);
        let dx = (p % w + w - q % w) % w;
        let dy = (p / w + h - q / w) % h;
        self.table[dy * w + dx]
    }

    /// The offsets per axis (`0..=n/2`) that `A` reaches: whether column (`x`) or row (`y`)
    /// `d` holds a kept entry.
    fn reach(&self) -> (usize, usize) {
        let (w, h) = (self.w, self.h);
        let farthest = |n: usize, kept: &dyn Fn(usize) -> bool| -> usize {
            (0..=n / 2).filter(|&d| kept(d)).max().unwrap_or(0).max(2)
        };
        let rx = farthest(w, &|d| (0..h).any(|dy| self.table[dy * w + d] != 0.0));
        let ry = farthest(h, &|d| (0..w).any(|dx| self.table[d * w + dx] != 0.0));
        (rx, ry)
    }

    fn at(&self, p: usize) -> &[f32] {
        &self.values[p * self.len..(p + 1) * self.len]
    }

    /// Adds `A(q − p) · delta` to every `q` in `p`'s support.
    fn add(&mut self, p: usize, delta: &[f32]) {
        let (w, h, len) = (self.w, self.h, self.len);
        let (x, y) = (p % w, p / w);
        for &(dx, dy, a) in &self.support {
            let q = (y + dy) % h * w + (x + dx) % w;
            for (d, &v) in self.values[q * len..(q + 1) * len].iter_mut().zip(delta) {
                *d += a * v;
            }
        }
    }

    /// The loss `Σ e·B`.
    fn loss(&self, e: &Errors) -> f64 {
        (0..self.w * self.h)
            .map(|p| dot(e.row(p), self.at(p)) as f64)
            .sum()
    }
}

/// Rearranges `shifts` (one per pixel of a `w × h` tile) to lower the loss of `errors` (their
/// rows, swapped with them) under `spatial`. Returns the loss before the first sweep and after
/// each, and the seconds since the start at each (for reports).
pub(super) fn optimise(
    shifts: &mut [[u16; 2]],
    errors: &mut Errors,
    spatial: Filter,
    [w, h]: [usize; 2],
    seed: u64,
    s: &Schedule,
    progress: &mut dyn FnMut(),
) -> (Vec<f64>, Vec<f64>) {
    let start = std::time::Instant::now();
    let n = w * h;
    let mut field = Field::new(spatial, w, h, errors);
    let mut loss = field.loss(errors);
    let mut curve = vec![loss];
    let mut seconds = vec![start.elapsed().as_secs_f64()];
    // Partners within the filter's reach: the autocorrelation's kept half-width, at least 2.
    let (rx, ry) = field.reach();
    let mut rng = SplitMix64::new(seed);
    let a0 = field.between(0, 0);
    let mut delta = vec![0.0f32; errors.len];
    for _ in 0..s.max_sweeps {
        let before = loss;
        for p in permutation(n, &mut rng) {
            let p = p as usize;
            let (px, py) = (p % w, p / w);
            let mut best: Option<(f32, usize)> = None;
            for c in 0..s.candidates {
                let q = if c % 4 == 3 {
                    rng.below(n as u64) as usize
                } else {
                    let dx = rng.below(2 * rx as u64 + 1) as usize;
                    let dy = rng.below(2 * ry as u64 + 1) as usize;
                    (py + h + dy - ry % h) % h * w + (px + w + dx - rx % w) % w
                };
                if q == p {
                    continue;
                }
                let (cross, norm) =
                    swap_terms(errors.row(p), errors.row(q), field.at(p), field.at(q));
                let change = 2.0 * cross + 2.0 * norm * (a0 - field.between(p, q));
                if change < 0.0 && best.is_none_or(|(b, _)| change < b) {
                    best = Some((change, q));
                }
            }
            if let Some((change, q)) = best {
                for ((d, &a), &b) in delta.iter_mut().zip(errors.row(p)).zip(errors.row(q)) {
                    *d = b - a;
                }
                field.add(p, &delta);
                delta.iter_mut().for_each(|d| *d = -*d);
                field.add(q, &delta);
                errors.swap(p, q);
                shifts.swap(p, q);
                loss += change as f64;
            }
        }
        progress();
        curve.push(loss);
        seconds.push(start.elapsed().as_secs_f64());
        if super::spent(before - loss, loss, s.stop_gain) {
            break;
        }
    }
    (curve, seconds)
}

#[cfg(test)]
mod tests {
    use super::super::training::{Integrands, sample_weights};
    use super::*;
    use crate::spec::sampler::PairSpace;

    fn start(w: usize, h: usize) -> Vec<[u16; 2]> {
        (0..w * h)
            .map(|p| {
                let v = noise_runtime::sampler::rd_ign_r2::<2>((p % w) as i32, (p / w) as i32, 0);
                [(v[0] * 65536.0) as u16, (v[1] * 65536.0) as u16]
            })
            .collect()
    }

    /// The loss tracked through the swaps' ΔL is the loss recomputed from scratch, it never
    /// rises, and the shifts stay a permutation of the start's.
    #[test]
    fn tracked_loss_is_the_recomputed_loss() {
        let (w, h) = (16, 12);
        let mut rng = SplitMix64::new(3);
        let ints = Integrands::new(PairSpace::CosineHemisphere, 2, 32, &mut rng);
        let mut shifts = start(w, h);
        let weights = sample_weights(2, None);
        let mut e = Errors::new(&ints, &shifts, [0, 1], 2, 0, &weights);
        let spatial = Filter::Gauss { sigma: 1.0 };
        let s = Schedule {
            max_sweeps: 3,
            stop_gain: 0.0,
            ..Schedule::DEFAULT
        };
        let original = shifts.clone();
        let (curve, _) = optimise(&mut shifts, &mut e, spatial, [w, h], 7, &s, &mut || {});
        assert!(
            curve.windows(2).all(|c| c[1] <= c[0] + 1e-6 * c[0].abs()),
            "{curve:?}"
        );
        assert!(curve.last().unwrap() < &(0.95 * curve[0]), "{curve:?}");
        let fresh = Errors::new(&ints, &shifts, [0, 1], 2, 0, &weights);
        assert_eq!(fresh.values, e.values);
        let field = Field::new(spatial, w, h, &fresh);
        let exact = field.loss(&fresh);
        let tracked = *curve.last().unwrap();
        assert!(
            (exact - tracked).abs() < 1e-3 * exact,
            "{exact} vs {tracked}"
        );
        let (mut a, mut b) = (original, shifts);
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b);
    }
}
