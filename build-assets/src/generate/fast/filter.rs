//! The filters FAST optimises for and the overlap `F = f ⋆ f` its loss weighs pairs with
//! (FAST eq. 4: `F_jk = Σ_i f_ij f_ik`).
//!
//! Every filter is applied separably per axis and wraps on the texture's torus, so its overlap is
//! the circular autocorrelation of the taps laid onto a ring of the axis size. The filter types
//! themselves are the spec's ([`crate::spec::fast`]).

use crate::spec::fast::{Combine, Filter, TemporalFilter};

/// The circular autocorrelation `F[d] = Σ_x f[x] f[x + d]` of `taps` wrapped onto a ring of `n`.
///
/// Only the ring's non-zero entries are visited, pair by pair, in the order of `x` for every
/// `d` (so each sum adds the same terms in the same order as the dense `O(n²)` form, skipping
/// zeros): `O(s²)` for `s` non-zero entries, which keeps a long texture's temporal overlap
/// (65 536 frames under an EMA whose taps underflow to zero after a few thousand) from costing
/// `n²`.
pub fn ring_autocorrelation(taps: &[f64], n: usize) -> Vec<f64> {
    let mut ring = vec![0.0; n];
    for (i, &t) in taps.iter().enumerate() {
        ring[i % n] += t;
    }
    let support: Vec<(usize, f64)> = ring
        .iter()
        .enumerate()
        .filter(|(_, v)| **v != 0.0)
        .map(|(i, &v)| (i, v))
        .collect();
    let mut out = vec![0.0; n];
    for &(x, a) in &support {
        for &(y, b) in &support {
            out[(y + n - x) % n] += a * b;
        }
    }
    out
}

impl TemporalFilter {
    /// The temporal overlap `F_t[d]` on a ring of `n` frames.
    ///
    /// For the EMA this is eq. (17) truncated to the stored frames: a weighted average, over the
    /// history length `m = 1..=n` with weight `β (1 − β)^(m−1)`, of the autocorrelation of the
    /// truncated filter `f^(m)` of eq. (16) (taps `α (1 − α)^l` for `l < m − 1`, and the remaining
    /// `(1 − α)^(m−1)` on the oldest frame). The overall scale does not change the optimum.
    pub fn overlap(self, n: usize) -> Vec<f64> {
        match self {
            TemporalFilter::None => ring_autocorrelation(&[1.0], n),
            TemporalFilter::Box { size } => ring_autocorrelation(&Filter::Box { size }.taps(), n),
            TemporalFilter::Gauss { sigma } => {
                ring_autocorrelation(&Filter::Gauss { sigma }.taps(), n)
            }
            TemporalFilter::Taa { .. } => self.weights().overlap(n),
            TemporalFilter::Ema { alpha, beta: 0.0 } => ema_folded(alpha, n),
            TemporalFilter::Ema { alpha, beta } => ema_rejected(alpha, beta, n),
        }
    }
}

/// The plain EMA's overlap on a ring of `n` frames, in closed form (`O(n)`).
///
/// No history rejection: the EMA's steady state over a texture that loops every `n` frames.
/// Its taps `α r^l` (`r = 1 − α`) for every age `l` fold onto the ring (frame `t − l` reads
/// slice `(t − l) mod n`): slice `l` holds `α r^l / (1 − r^n)`. The ring's autocorrelation at
/// `d` is the taps' linear autocorrelation at lags `d` and `n − d`, `L(k) = c r^k (1 −
/// r^(2(n − k)))` with `c = α² / ((1 − r^n)² (1 − r²))`, a geometric sum.
fn ema_folded(alpha: f64, n: usize) -> Vec<f64> {
    let r = 1.0 - alpha;
    let fold = 1.0 / (1.0 - r.powi(n as i32));
    let c = alpha * alpha * fold * fold / (1.0 - r * r);
    let lin = |k: usize| c * r.powi(k as i32) * (1.0 - r.powi(2 * (n - k) as i32));
    (0..n)
        .map(|d| if d == 0 { lin(0) } else { lin(d) + lin(n - d) })
        .collect()
}

/// The EMA's overlap with history rejection (FAST eq. 17) on a ring of `n` frames, in closed
/// form (`O(n)`).
///
/// Eq. (17) averages, over the history length `m = 1 … n` with weight `w_m = β q^(m−1)` (`q =
/// 1 − β`), the autocorrelation of the truncated filter `f^(m)` of eq. (16): taps `α r^l` for
/// `l < m − 1` and `r^(m−1)` on the oldest frame (`r = 1 − α`). Swapping the sums, the pair of
/// ages `x ≤ y` carries `G(x, y) = r^(x+y) (α² W(y + 2) + c w_(y+1))` with `c = α` for `x < y`
/// and 1 for `x = y`, where `W(k) = Σ_(m ≥ k) w_m = q^(k−1) − q^n` is the weight of the histories
/// longer than `y + 1`. The sum of `G` over pairs `d` apart, `S(d)`, is three geometric sums in
/// `x`; the ring's autocorrelation is `S(d) + S(n − d)` (no history is longer than the ring,
/// so nothing folds). The scale does not change the optimum.
fn ema_rejected(alpha: f64, beta: f64, n: usize) -> Vec<f64> {
    let (r, q) = (1.0 - alpha, 1.0 - beta);
    let pow = |b: f64, e: usize| b.powi(e as i32);
    let geometric = |b: f64, len: usize| {
        // Σ_{x < len} b^x, for b in [0, 1).
        (1.0 - pow(b, len)) / (1.0 - b)
    };
    let qn = pow(q, n);
    // S(k) over the pairs (x, x + k), x = 0 … n − 1 − k.
    let lag = |k: usize| -> f64 {
        let m = n - k; // pairs
        // Σ_{x ≤ n−2−k} r^(2x+k) α² (q^(x+k+1) − q^n): histories longer than y + 1 = x + k + 1.
        let longer = alpha
            * alpha
            * pow(r, k)
            * (pow(q, k + 1) * geometric(r * r * q, m - 1) - qn * geometric(r * r, m - 1));
        // Σ_{x ≤ n−1−k} r^(2x+k) c β q^(x+k): the history that ends at y.
        let c = if k == 0 { 1.0 } else { alpha };
        let ending = c * beta * pow(r, k) * pow(q, k) * geometric(r * r * q, m);
        longer + ending
    };
    (0..n)
        .map(|d| if d == 0 { lag(0) } else { lag(d) + lag(n - d) })
        .collect()
}

/// Lags of a moving camera's EMA whose weight falls below this fraction of the newest frame's
/// are left out of its overlap (the static EMA folds them all onto its ring).
const MOTION_LAG_CUTOFF: f64 = 1e-9;

/// Pair weights below this fraction of the largest are dropped from the footprint.
pub const FOOTPRINT_CUTOFF: f64 = 1e-4;

/// One row of the footprint: fixed `(dy, dt)`, consecutive `dx` with their weights.
#[derive(Clone, Debug)]
pub struct Row {
    /// Offset along y.
    pub dy: i32,
    /// Offset along t.
    pub dt: i32,
    /// `(dx, weight)` pairs.
    pub entries: Vec<(i32, f64)>,
}

/// The non-zero pair weights `F(dx, dy, dt)` around a texel, `(0, 0, 0)` excluded.
#[derive(Clone, Debug)]
pub struct Footprint {
    /// Rows of offsets and weights.
    pub rows: Vec<Row>,
    /// Weight of same-slice offsets, `F(dx, dy, 0)`, indexed `[dy mod h][dx mod w]` (dense).
    pub same_slice: Vec<f64>,
    /// Largest |dx| and |dy| with a weight (the tile halo).
    pub radius: [usize; 2],
    /// Weight dropped by the cutoff, relative to the kept total.
    pub dropped: f64,
    /// Every weight kept, `F(0, 0, 0)` included: the row sum of `F` as the loss sees it (1
    /// less the cutoff for a filter whose weights sum to 1). With it the loss converts to the
    /// mean squared error it predicts (`noisebake report fast`'s `loss->rmse`).
    pub total: f64,
    /// Under TAA ([`TemporalFilter::Taa`]), the coverage every 3 × 3 window of a slice keeps:
    /// a value below it and one at or above one less it. A constraint on the arrangement the
    /// optimiser keeps (`optimize`), not a weight.
    pub clamp: Option<f64>,
}

/// Distinct offsets on a ring of `n`: `-(n-1)/2 ..= n/2`.
fn ring_offsets(n: usize) -> std::ops::RangeInclusive<i32> {
    -(((n - 1) / 2) as i32)..=(n / 2) as i32
}

impl Footprint {
    /// Builds the footprint of `F` for a `w × h × t` texture.
    pub fn new(
        dims: [usize; 3],
        spatial: Filter,
        temporal: TemporalFilter,
        combine: Combine,
    ) -> Footprint {
        let [w, h, t] = dims;
        let taps = spatial.taps();
        let fx = ring_autocorrelation(&taps, w);
        let fy = ring_autocorrelation(&taps, h);
        let ft = temporal.overlap(t);
        let at = |f: &[f64], d: i32| f[d.rem_euclid(f.len() as i32) as usize];
        // A moving camera (`taa` with `motion`, product only): the EMA followed along `v`. Its
        // taps `a_l = α(1 − α)^l` sit at frame `−l` and pixel `−l·v`, so its overlap at
        // `(d, τ)` is `Σ_{m ≡ τ (mod t)} A(m) · G(d − m·v)`, with `A(m) = α²(1 − α)^|m| /
        // (1 − (1 − α)²)` the taps' autocorrelation on the line and `G` the spatial one on the
        // torus; each lag `m` keeps its own shift (a loop of `t` frames moves the picture `t·v`).
        // (For `v = 0` the sum is the static EMA's folded overlap, `overlap`.) It is mixed in by
        // its share.
        let moving = temporal.motion().map(|(v, share)| {
            let alpha = match temporal.weights() {
                TemporalFilter::Ema { alpha, .. } => alpha,
                _ => unreachable!("only a `taa` filter has a motion"),
            };
            let reach = (MOTION_LAG_CUTOFF.ln() / (1.0 - alpha).ln()).ceil() as i32;
            // The lags of each residue mod t.
            let mut lags: Vec<Vec<(i32, f64)>> = vec![Vec::new(); t];
            for m in -reach..=reach {
                let a = alpha * alpha * (1.0 - alpha).powi(m.abs())
                    / (1.0 - (1.0 - alpha) * (1.0 - alpha));
                lags[m.rem_euclid(t as i32) as usize].push((m, a));
            }
            (v, share, lags)
        });
        let weight = |dx: i32, dy: i32, dt: i32| -> f64 {
            let sxy = at(&fx, dx) * at(&fy, dy);
            if let (Some(([vx, vy], share, lags)), Combine::Product) = (&moving, combine) {
                let along: f64 = lags[dt.rem_euclid(t as i32) as usize]
                    .iter()
                    .map(|&(m, a)| a * at(&fx, dx - m * vx) * at(&fy, dy - m * vy))
                    .sum();
                return (1.0 - share) * sxy * at(&ft, dt) + share * along;
            }
            match combine {
                Combine::Product => sxy * at(&ft, dt),
                Combine::Separate(wt) => {
                    let mut f = 0.0;
                    if dt == 0 {
                        f += wt * sxy;
                    }
                    if dx == 0 && dy == 0 {
                        f += (1.0 - wt) * at(&ft, dt);
                    }
                    f
                }
            }
        };
        let mut max: f64 = 0.0;
        for dt in ring_offsets(t) {
            for dy in ring_offsets(h) {
                for dx in ring_offsets(w) {
                    max = max.max(weight(dx, dy, dt));
                }
            }
        }
        let cut = FOOTPRINT_CUTOFF * max;
        let mut rows = Vec::new();
        let mut same_slice = vec![0.0; w * h];
        let mut radius = [0usize; 2];
        let (mut kept, mut dropped) = (0.0, 0.0);
        for dt in ring_offsets(t) {
            for dy in ring_offsets(h) {
                let mut entries = Vec::new();
                for dx in ring_offsets(w) {
                    let f = weight(dx, dy, dt);
                    if (dx, dy, dt) == (0, 0, 0) || f <= 0.0 {
                        continue;
                    }
                    if f < cut {
                        dropped += f;
                        continue;
                    }
                    kept += f;
                    entries.push((dx, f));
                    radius[0] = radius[0].max(dx.unsigned_abs() as usize);
                    radius[1] = radius[1].max(dy.unsigned_abs() as usize);
                    if dt == 0 {
                        same_slice[dy.rem_euclid(h as i32) as usize * w
                            + dx.rem_euclid(w as i32) as usize] = f;
                    }
                }
                if !entries.is_empty() {
                    rows.push(Row { dy, dt, entries });
                }
            }
        }
        Footprint {
            rows,
            same_slice,
            radius,
            dropped: if kept > 0.0 { dropped / kept } else { 0.0 },
            total: kept + weight(0, 0, 0).max(0.0),
            clamp: temporal.clamp_coverage(),
        }
    }

    /// Number of offsets.
    pub fn len(&self) -> usize {
        self.rows.iter().map(|r| r.entries.len()).sum()
    }

    /// Whether no pair interacts (no filter at all).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taps_are_normalised_and_binomial_is_pascal() {
        for f in [
            Filter::Box { size: 5 },
            Filter::Gauss { sigma: 1.3435 },
            Filter::Binomial { order: 4 },
        ] {
            let s: f64 = f.taps().iter().sum();
            assert!((s - 1.0).abs() < 1e-12, "{f:?}");
        }
        let b = Filter::Binomial { order: 4 }.taps();
        let want = [1.0, 4.0, 6.0, 4.0, 1.0].map(|x| x / 16.0);
        assert_eq!(b, want);
    }

    /// A moving camera's footprint: when a loop of the texture moves the picture by whole
    /// tiles (`t·v ≡ 0`), every lag `m ≡ τ` carries the same shift and the overlap is the static
    /// one sheared by `τ·v`; otherwise each wrapped lag keeps its own shift, which moves weight
    /// but never adds or loses any. Mixed in by its share.
    #[test]
    fn a_moving_footprint_is_the_static_one_sheared() {
        let dims = [16, 16, 8];
        let spatial = Filter::Gauss { sigma: 1.0 };
        let taa = |motion, moving| TemporalFilter::Taa {
            alpha: 0.2,
            coverage: 0.2,
            motion,
            moving,
        };
        let footprint = |t| Footprint::new(dims, spatial, t, Combine::Product);
        let weights = |t: TemporalFilter| -> std::collections::HashMap<(i32, i32, i32), f64> {
            footprint(t)
                .rows
                .iter()
                .flat_map(|r| r.entries.iter().map(move |&(dx, w)| ((dx, r.dy, r.dt), w)))
                .collect()
        };
        let wrap = |d: i32, n: i32| (d + n / 2 - 1).rem_euclid(n) - (n / 2 - 1);
        let still = weights(taa([0, 0], 0.0));
        // 8 frames × (2, −2) px = one tile: a plain shear.
        let moving = weights(taa([2, -2], 1.0));
        let mut sheared = 0;
        for (&(dx, dy, dt), &w) in &moving {
            let at = (wrap(dx - 2 * dt, 16), wrap(dy + 2 * dt, 16), dt);
            let s = still.get(&at).copied().unwrap_or(0.0);
            assert!(
                (w - s).abs() < 1e-7 * w.abs().max(1e-3),
                "{dx} {dy} {dt}: {w} {s}"
            );
            sheared += (dt != 0 && (dx, dy) != (at.0, at.1)) as usize;
        }
        assert!(sheared > 100, "{sheared}");
        // 8 × (3, −1) is no whole tile: not a plain shear, but the same total weight.
        let odd = weights(taa([3, -1], 1.0));
        let differs = odd.iter().any(|(&(dx, dy, dt), &w)| {
            let at = (wrap(dx - 3 * dt, 16), wrap(dy + dt, 16), dt);
            (w - still.get(&at).copied().unwrap_or(0.0)).abs() > 1e-6
        });
        assert!(differs);
        let (a, b) = (
            footprint(taa([0, 0], 0.0)).total,
            footprint(taa([3, -1], 1.0)).total,
        );
        assert!((a - b).abs() < 1e-3 * a, "{a} {b}");
        // Half and half: the average of the two.
        let mixed = weights(taa([2, -2], 0.5));
        let mut both = 0;
        for (k, &w) in &mixed {
            if let (Some(a), Some(b)) = (still.get(k), moving.get(k)) {
                let want = 0.5 * a + 0.5 * b;
                assert!((w - want).abs() < 1e-12 * want, "{k:?}: {w} {want}");
                both += 1;
            }
        }
        assert!(both > 100, "{both}");
    }

    #[test]
    fn box_overlap_is_a_triangle() {
        let f = ring_autocorrelation(&Filter::Box { size: 5 }.taps(), 32);
        for d in 0..5 {
            assert!((f[d] - (5 - d) as f64 / 25.0).abs() < 1e-12);
            assert!((f[32 - d.max(1)] - f[d.max(1)]).abs() < 1e-15);
        }
        assert_eq!(f[5], 0.0);
    }

    /// The closed forms of the EMA's overlap against the dense sums they replace (the dense
    /// ring autocorrelation of the folded taps for β = 0, eq. 17's sum over history lengths
    /// for β > 0), at several ring sizes and weights.
    #[test]
    fn ema_closed_forms_match_the_dense_sums() {
        let dense = |taps: &[f64], n: usize| -> Vec<f64> {
            (0..n)
                .map(|d| (0..n).map(|x| taps[x] * taps[(x + d) % n]).sum())
                .collect()
        };
        for (alpha, n) in [
            (0.1f64, 1usize),
            (0.1, 2),
            (0.1, 64),
            (0.5, 7),
            (1.0, 5),
            (0.001, 300),
        ] {
            let fold = 1.0 / (1.0 - (1.0 - alpha).powi(n as i32));
            let taps: Vec<f64> = (0..n)
                .map(|l| alpha * (1.0f64 - alpha).powi(l as i32) * fold)
                .collect();
            let want = dense(&taps, n);
            let got = TemporalFilter::Ema { alpha, beta: 0.0 }.overlap(n);
            for d in 0..n {
                assert!(
                    (got[d] - want[d]).abs() <= 1e-12 * want[0],
                    "α {alpha} n {n} d {d}: {} vs {}",
                    got[d],
                    want[d]
                );
            }
            for beta in [0.05, 0.5, 1.0] {
                let mut want = vec![0.0; n];
                for m in 1..=n {
                    let taps: Vec<f64> = (0..n)
                        .map(|l| match l + 1 {
                            k if k < m => alpha * (1.0f64 - alpha).powi(l as i32),
                            k if k == m => (1.0f64 - alpha).powi(l as i32),
                            _ => 0.0,
                        })
                        .collect();
                    let w = beta * (1.0f64 - beta).powi(m as i32 - 1);
                    for (t, a) in want.iter_mut().zip(dense(&taps, n)) {
                        *t += w * a;
                    }
                }
                let got = TemporalFilter::Ema { alpha, beta }.overlap(n);
                for d in 0..n {
                    assert!(
                        (got[d] - want[d]).abs() <= 1e-12 * want[0],
                        "α {alpha} β {beta} n {n} d {d}: {} vs {}",
                        got[d],
                        want[d]
                    );
                }
            }
        }
        // The sparse ring autocorrelation is the dense one, bit for bit.
        let taps = Filter::Gauss { sigma: 1.3 }.taps();
        let mut ring = vec![0.0; 40];
        for (i, t) in taps.iter().enumerate() {
            ring[i % 40] += t;
        }
        assert_eq!(ring_autocorrelation(&taps, 40), dense(&ring, 40));
    }

    #[test]
    fn ema_overlap_is_eq17_wrapped() {
        // Brute force: lag pairs of each truncated filter f^(m) (eq. 16) on the infinite line,
        // weighted by β(1 − β)^(m − 1) (eq. 17) and folded onto the ring of n frames.
        let (alpha, beta, n) = (0.3, 0.2, 8usize);
        let f = TemporalFilter::Ema { alpha, beta }.overlap(n);
        for (d, &got) in f.iter().enumerate().take(n) {
            let mut want = 0.0;
            for m in 1..=n {
                let tap = |l: usize| {
                    if l + 1 < m {
                        alpha * (1.0f64 - alpha).powi(l as i32)
                    } else if l + 1 == m {
                        (1.0f64 - alpha).powi(l as i32)
                    } else {
                        0.0
                    }
                };
                let w = beta * (1.0f64 - beta).powi(m as i32 - 1);
                for l in 0..m {
                    for l2 in 0..m {
                        if (l2 + n - l) % n == d {
                            want += w * tap(l) * tap(l2);
                        }
                    }
                }
            }
            assert!((got - want).abs() < 1e-12, "d {d}: {got} vs {want}");
        }
        // Symmetric and, without rejection, the eq. (15) decay (1 − α)^|d| near d = 0.
        assert!((f[1] - f[n - 1]).abs() < 1e-15);
        let g = TemporalFilter::Ema {
            alpha: 0.5,
            beta: 1e-3,
        }
        .overlap(64);
        assert!((g[2] / g[1] - 0.5).abs() < 0.03, "{}", g[2] / g[1]);
        // β = 1 rejects history every frame: no temporal coupling.
        let f = TemporalFilter::Ema { alpha, beta: 1.0 }.overlap(16);
        assert_eq!(f[0], 1.0);
        assert!(f[1..].iter().all(|&x| x == 0.0));
    }
}
