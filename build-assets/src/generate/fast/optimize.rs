//! The swap optimiser of FAST §4, made exact and deterministic on a CPU.
//!
//! The paper pairs every texel with a random partner on the GPU and swaps all pairs at once,
//! which can raise the loss and wastes most evaluations. Here swaps are evaluated and accepted
//! one at a time with the exact ΔL of eq. (8), so the loss never rises. Parallelism comes from
//! **conflict-free tiles**: the (x, y) plane is cut into tiles (all frames) coloured like a 2×2
//! checkerboard; tiles of one colour lie further apart than the footprint radius of `F`, so their
//! swaps neither read nor change anything another tile of that colour uses, and their ΔL add up
//! exactly. Each tile draws its pairs from its own seeded generator, so the result is the same on
//! any number of threads. The tile grid moves by a random offset every round so samples can
//! migrate anywhere. Proposals are screened ([`SCREENS`]): most losing swaps are skipped after a
//! few of their heaviest terms. Optimisation stops when a round under the last screen gains less
//! than [`CONVERGED`] of the total gain so far (or at the `iterations` cap, by default
//! [`super::MAX_ROUNDS`]).

use super::filter::Footprint;
use crate::generate::rng::{SplitMix64, derive_seed};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::time::Instant;

/// A round whose loss decrease is below this fraction of the decrease so far ends optimisation.
pub const CONVERGED: f64 = 2e-3;
/// Preferred tile side (texels); tiles are never narrower than the footprint radius + 1.
const TILE: usize = 16;
/// Half-width of the window near partners are drawn from.
const LOCAL: u64 = 2;

/// The screens κ of the ΔL evaluation that [`optimize`] runs through: it starts with the first
/// and moves to the next each time a round gains less than the convergence fraction, and stops
/// when a round under the last gains less.
///
/// Why screen: the exact early rejection bounds every unvisited term of eq. (8) by
/// `2 F d(s_i, s_j)` (triangle inequality), but the terms have mixed signs, so their sum is
/// typically of the order `d(s_i, s_j) √(Σ F²)`, far below that bound. On the paper's product
/// footprint (box 5×5 × EMA over 16 frames, 1296 entries) exact rejection visits ~1200 entries
/// per proposal on average; the screen at κ = 1 visits ~170, and the loss falls ~5× faster per
/// second. A screen only ever *skips* a swap that very likely does not gain: accepted swaps are
/// still evaluated in full, so the loss falls monotonically and its bookkeeping stays exact.
/// κ = 1 was the fastest single value of 0.3–3 on that case; κ = 4 then picks up most of the
/// subtle swaps it skips. The exact level (κ = ∞) is left out: on the long footprints of an EMA
/// over the whole loop (`beta = 0`, every frame coupled) one exact round costs several screened
/// ones for a gain the measured error does not show (`report fast`).
pub const SCREENS: [f64; 2] = [1.0, 4.0];

/// When to stop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Most rounds.
    pub max_rounds: u32,
    /// Wall-clock budget in seconds (reports only: it makes the result machine-dependent).
    pub budget: Option<f64>,
    /// A round gaining less than this fraction of the gain so far ends optimisation
    /// ([`CONVERGED`] when baking).
    pub converged: f64,
}

/// One point of the loss-against-time curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvePoint {
    /// Seconds since optimisation started.
    pub seconds: f64,
    /// Loss (eq. 7) after the round.
    pub loss: f64,
    /// Swaps accepted in the round.
    pub accepted: u64,
}

/// What the optimiser returns.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Samples, `channels` per texel, x fastest.
    pub samples: Vec<f64>,
    /// Loss of the stratified initialisation.
    pub initial_loss: f64,
    /// Loss after each round.
    pub curve: Vec<CurvePoint>,
}

impl Outcome {
    /// Final loss.
    pub fn loss(&self) -> f64 {
        self.curve.last().map_or(self.initial_loss, |p| p.loss)
    }
}

/// Texel samples shared between tile tasks: each `f64` lives in an atomic so disjoint tiles
/// can write concurrently without `unsafe` (relaxed loads compile to plain loads).
pub(super) struct State<const C: usize> {
    cells: Vec<[AtomicU64; C]>,
}

impl<const C: usize> State<C> {
    #[inline(always)]
    pub(super) fn load(&self, i: usize) -> [f64; C] {
        let c = &self.cells[i];
        std::array::from_fn(|k| f64::from_bits(c[k].load(Relaxed)))
    }

    #[inline(always)]
    pub(super) fn store(&self, i: usize, v: [f64; C]) {
        let c = &self.cells[i];
        for k in 0..C {
            c[k].store(v[k].to_bits(), Relaxed);
        }
    }

    /// The samples, `C` values per texel.
    pub(super) fn into_samples(self) -> Vec<f64> {
        self.cells
            .iter()
            .flat_map(|c| std::array::from_fn::<f64, C, _>(|k| f64::from_bits(c[k].load(Relaxed))))
            .collect()
    }
}

/// Index arithmetic of a wrapped `w × h × t` texture: offset tables that replace `mod`.
struct Torus {
    dims: [usize; 3],
    /// `xw[x + w + dx] = (x + dx) mod w`, for `|dx| ≤ w`.
    xw: Vec<u32>,
    /// Same for y, premultiplied by `w`.
    yw: Vec<u32>,
    /// Same for t, premultiplied by `w·h`.
    tw: Vec<u32>,
}

impl Torus {
    fn new(dims: [usize; 3]) -> Torus {
        let [w, h, t] = dims;
        let table = |n: usize, mul: usize| (0..3 * n).map(|m| ((m % n) * mul) as u32).collect();
        Torus {
            dims,
            xw: table(w, 1),
            yw: table(h, w),
            tw: table(t, w * h),
        }
    }
}

/// The problem: footprint, distance and torus.
pub(super) struct Problem<'a, const C: usize, D> {
    fp: &'a Footprint,
    torus: Torus,
    dist: D,
    /// The footprint's offsets `(dx, dy, dt, F)` sorted by decreasing `F`.
    sorted: Vec<(i32, i32, i32, f64)>,
    /// `tail[m] = Σ_{e ≥ m} F_e`: the weight not yet visited after `m` sorted entries.
    tail: Vec<f64>,
    /// `spread[m] = √(Σ_{e ≥ m} F_e²)`: the scale of the unvisited terms' sum (see [`SCREENS`]).
    spread: Vec<f64>,
}

/// Sorted entries are visited in blocks of this many between early-rejection checks.
const BLOCK: usize = 16;

impl<'a, const C: usize, D> Problem<'a, C, D> {
    pub(super) fn new(fp: &'a Footprint, dims: [usize; 3], dist: D) -> Self {
        let mut sorted: Vec<(i32, i32, i32, f64)> = fp
            .rows
            .iter()
            .flat_map(|r| r.entries.iter().map(move |&(dx, f)| (dx, r.dy, r.dt, f)))
            .collect();
        sorted.sort_by(|a, b| {
            b.3.total_cmp(&a.3)
                .then((a.0, a.1, a.2).cmp(&(b.0, b.1, b.2)))
        });
        let mut tail = vec![0.0; sorted.len() + 1];
        let mut spread = vec![0.0; sorted.len() + 1];
        for m in (0..sorted.len()).rev() {
            tail[m] = tail[m + 1] + sorted[m].3;
            spread[m] = spread[m + 1] + sorted[m].3 * sorted[m].3;
        }
        for v in &mut spread {
            *v = v.sqrt();
        }
        Problem {
            fp,
            torus: Torus::new(dims),
            dist,
            sorted,
            tail,
            spread,
        }
    }
}

impl<const C: usize, D: Fn(&[f64; C], &[f64; C]) -> f64 + Sync> Problem<'_, C, D> {
    /// Half the change of `Σ F_jk d(s_j, s_k)` when the samples at `p` and `q` of slice `t`
    /// swap (eq. 8): positive means the loss `−Σ F d` falls. Returns `None` as soon as the swap
    /// provably cannot help: by the triangle inequality each unvisited term is at most
    /// `F · d(s_i, s_j)` in size, so once the partial sum is below `−2 d(s_i, s_j) Σ F_unvisited`
    /// the sign is settled. Entries are visited heaviest first, so this usually happens early.
    ///
    /// With a finite `screen` κ it also gives up once the partial sum is below
    /// `−κ · d(s_i, s_j) · √(Σ F²_unvisited)` (see [`SCREENS`]); `f64::INFINITY` is exact.
    #[inline]
    pub(super) fn gain(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
        screen: f64,
    ) -> Option<f64> {
        let [w, h, n] = self.torus.dims;
        let tz = self.torus.tw[t] as usize;
        let i = tz + p[1] * w + p[0];
        let j = tz + q[1] * w + q[0];
        let (si, sj) = (s.load(i), s.load(j));
        let dij = (self.dist)(&si, &sj);
        if dij == 0.0 {
            return None;
        }
        // Both sides include k = j (resp. i) when in range; eq. 8's last term corrects for it.
        let fij = self.fp.same_slice[((q[1] + h - p[1]) % h) * w + (q[0] + w - p[0]) % w];
        let mut acc = 2.0 * fij * dij;
        let (tx, ty, tt) = (&self.torus.xw, &self.torus.yw, &self.torus.tw);
        for (b, block) in self.sorted.chunks(BLOCK).enumerate() {
            for &(dx, dy, dt, f) in block {
                let o = |x: usize, y: usize| {
                    tt[(t + n).wrapping_add_signed(dt as isize)] as usize
                        + ty[(y + h).wrapping_add_signed(dy as isize)] as usize
                        + tx[(x + w).wrapping_add_signed(dx as isize)] as usize
                };
                let a = s.load(o(p[0], p[1]));
                let c = s.load(o(q[0], q[1]));
                acc += f
                    * (((self.dist)(&sj, &a) - (self.dist)(&si, &a))
                        - ((self.dist)(&sj, &c) - (self.dist)(&si, &c)));
            }
            let m = ((b + 1) * BLOCK).min(self.sorted.len());
            // `screen · 0` is NaN for an infinite screen at the end: the test is then false.
            if acc + 2.0 * dij * self.tail[m] <= 0.0 || acc + screen * dij * self.spread[m] <= 0.0 {
                return None;
            }
        }
        Some(acc)
    }

    /// `Σ_j Σ_k F_jk d(s_j, s_k)` over slice `t` (as `j`).
    fn slice_energy(&self, s: &State<C>, t: usize) -> f64 {
        let [w, h, _] = self.torus.dims;
        let mut sum = 0.0;
        for y in 0..h {
            for x in 0..w {
                let sj = s.load(self.torus.tw[t] as usize + y * w + x);
                let [_, hh, n] = self.torus.dims;
                for row in &self.fp.rows {
                    let base = self.torus.tw[(t + n).wrapping_add_signed(row.dt as isize)] as usize
                        + self.torus.yw[(y + hh).wrapping_add_signed(row.dy as isize)] as usize;
                    for &(dx, f) in &row.entries {
                        let k =
                            base + self.torus.xw[(x + w).wrapping_add_signed(dx as isize)] as usize;
                        sum += f * (self.dist)(&sj, &s.load(k));
                    }
                }
            }
        }
        sum
    }

    /// The loss of eq. (7), `−Σ_jk F_jk d(s_j, s_k)`, summed per slice in a fixed order.
    pub(super) fn loss(&self, s: &State<C>) -> f64 {
        let per: Vec<f64> = (0..self.torus.dims[2])
            .into_par_iter()
            .map(|t| self.slice_energy(s, t))
            .collect();
        -per.iter().sum::<f64>()
    }
}

/// Tile boundaries along one axis of size `n` for a footprint radius `r`: an even number of
/// tiles (so a 2-colouring wraps), each wider than `r`, or a single tile.
fn tile_bounds(n: usize, r: usize) -> Vec<usize> {
    let side = TILE.max(r + 1);
    let mut count = n / side;
    if count % 2 == 1 {
        count -= 1;
    }
    let count = count.max(1);
    (0..=count).map(|k| k * n / count).collect()
}

/// Exact loss of eq. (7) of a sample array (`C` channels per texel).
pub fn loss<const C: usize, D>(dims: [usize; 3], fp: &Footprint, samples: &[f64], dist: D) -> f64
where
    D: Fn(&[f64; C], &[f64; C]) -> f64 + Sync,
{
    let state = to_state::<C>(samples);
    Problem::new(fp, dims, dist).loss(&state)
}

pub(super) fn to_state<const C: usize>(samples: &[f64]) -> State<C> {
    State {
        cells: samples
            .chunks_exact(C)
            .map(|c| std::array::from_fn(|k| AtomicU64::new(c[k].to_bits())))
            .collect(),
    }
}

/// Runs the optimiser. `samples` holds `C` values per texel, each slice already stratified;
/// swaps stay within a slice, so every slice keeps its values. `max_rounds` caps the rounds;
/// `budget` (seconds, for reports only — baking never sets it) stops after the round that
/// exceeds it; `progress(round, max_rounds)` is called after each.
pub fn optimize<const C: usize, D>(
    dims: [usize; 3],
    fp: &Footprint,
    samples: Vec<f64>,
    seed: u64,
    limits: Limits,
    progress: &mut dyn FnMut(u64, u64),
    dist: D,
) -> Outcome
where
    D: Fn(&[f64; C], &[f64; C]) -> f64 + Sync,
{
    let Limits {
        max_rounds,
        budget,
        converged,
    } = limits;
    let start = Instant::now();
    let [w, h, n] = dims;
    let state = to_state::<C>(&samples);
    let problem = Problem::new(fp, dims, dist);
    let initial_loss = problem.loss(&state);
    let mut curve = Vec::new();
    if fp.is_empty() || w * h < 2 {
        return Outcome {
            samples,
            initial_loss,
            curve,
        };
    }
    let bx = tile_bounds(w, fp.radius[0]);
    let by = tile_bounds(h, fp.radius[1]);
    let (tx, ty) = (bx.len() - 1, by.len() - 1);
    let mut loss = initial_loss;
    let mut total_gain = 0.0;
    let mut level = 0;
    for round in 0..max_rounds {
        let kappa = SCREENS[level];
        let mut rng = SplitMix64::new(derive_seed(seed, round as u64));
        let (ox, oy) = (rng.below(w as u64) as usize, rng.below(h as u64) as usize);
        let mut round_gain = 0.0;
        let mut accepted = 0;
        for colour in 0..4 {
            let tiles: Vec<(usize, usize)> = (0..ty)
                .flat_map(|j| (0..tx).map(move |i| (i, j)))
                .filter(|&(i, j)| (i % 2) + 2 * (j % 2) == colour)
                .collect();
            let results: Vec<(f64, u64)> = tiles
                .par_iter()
                .map(|&(i, j)| {
                    let tile_seed = derive_seed(
                        seed ^ 0x5eed_fa57,
                        ((round as u64) << 32) | ((j * tx + i) as u64),
                    );
                    let mut rng = SplitMix64::new(tile_seed);
                    let (x0, tw) = (bx[i], bx[i + 1] - bx[i]);
                    let (y0, th) = (by[j], by[j + 1] - by[j]);
                    let cells = (tw * th) as u64;
                    let (mut gain, mut acc) = (0.0, 0u64);
                    if cells < 2 {
                        return (gain, acc);
                    }
                    let at = |c: u64| {
                        let c = c as usize;
                        [(ox + x0 + c % tw) % w, (oy + y0 + c / tw) % h]
                    };
                    for _ in 0..cells * n as u64 {
                        let t = rng.below(n as u64) as usize;
                        let a = rng.below(cells);
                        let b = if rng.next_u64() & 1 == 0 {
                            // A near partner (within ±LOCAL in the tile): late in the
                            // optimisation these are the swaps that still get accepted.
                            let (ax, ay) = ((a as usize % tw) as i64, (a as usize / tw) as i64);
                            let span = 2 * LOCAL + 1;
                            let bx = (ax + rng.below(span) as i64 - LOCAL as i64)
                                .clamp(0, tw as i64 - 1);
                            let by = (ay + rng.below(span) as i64 - LOCAL as i64)
                                .clamp(0, th as i64 - 1);
                            (by as u64) * tw as u64 + bx as u64
                        } else {
                            rng.below(cells)
                        };
                        if a == b {
                            continue;
                        }
                        let (p, q) = (at(a), at(b));
                        if let Some(g) = problem.gain(&state, p, q, t, kappa).filter(|&g| g > 0.0) {
                            let i = problem.torus.tw[t] as usize + p[1] * w + p[0];
                            let j = problem.torus.tw[t] as usize + q[1] * w + q[0];
                            let (si, sj) = (state.load(i), state.load(j));
                            state.store(i, sj);
                            state.store(j, si);
                            gain += g;
                            acc += 1;
                        }
                    }
                    (gain, acc)
                })
                .collect();
            for (g, a) in results {
                round_gain += g;
                accepted += a;
            }
        }
        // ΔΣFd = 2·gain per swap (eq. 8), and L = −ΣFd.
        loss -= 2.0 * round_gain;
        total_gain += round_gain;
        curve.push(CurvePoint {
            seconds: start.elapsed().as_secs_f64(),
            loss,
            accepted,
        });
        progress(round as u64 + 1, max_rounds as u64);
        if round_gain <= converged * total_gain {
            if level + 1 == SCREENS.len() {
                break;
            }
            level += 1;
        }
        // A wall-clock budget (reports only: it makes the result depend on the machine).
        if budget.is_some_and(|b| start.elapsed().as_secs_f64() >= b) {
            break;
        }
    }
    Outcome {
        samples: state.into_samples(),
        initial_loss,
        curve,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::fast::{Combine, Filter, TemporalFilter};

    /// The screen only ever skips: whenever the screened ΔL accepts a swap, it is the exact
    /// ΔL, bit for bit (same terms, same order); it never accepts a swap the exact evaluation
    /// rejects; and it keeps most of the swaps that do gain.
    #[test]
    fn screened_gain_is_exact_when_it_accepts() {
        let dims = [16, 16, 8];
        let fp = Footprint::new(
            dims,
            Filter::Box { size: 5 },
            TemporalFilter::Ema {
                alpha: 0.1,
                beta: 0.1,
            },
            Combine::Product,
        );
        let mut rng = SplitMix64::new(7);
        let samples: Vec<f64> = (0..16 * 16 * 8 * 3).map(|_| rng.unit_f64()).collect();
        let state = to_state::<3>(&samples);
        let euclid = |a: &[f64; 3], b: &[f64; 3]| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        };
        let problem = Problem::new(&fp, dims, euclid);
        let (mut screened, mut exact_gains, mut both) = (0, 0, 0);
        for _ in 0..4000 {
            let p = [rng.below(16) as usize, rng.below(16) as usize];
            let q = [rng.below(16) as usize, rng.below(16) as usize];
            let t = rng.below(8) as usize;
            let exact = problem
                .gain(&state, p, q, t, f64::INFINITY)
                .filter(|&g| g > 0.0);
            let fast = problem
                .gain(&state, p, q, t, SCREENS[0])
                .filter(|&g| g > 0.0);
            exact_gains += exact.is_some() as u32;
            match (exact, fast) {
                (Some(e), Some(f)) => {
                    assert_eq!(e.to_bits(), f.to_bits());
                    both += 1;
                }
                (None, Some(f)) => panic!("screen accepted a swap the exact ΔL rejects: {f}"),
                (Some(_), None) => screened += 1,
                (None, None) => {}
            }
        }
        // Random samples: plenty of swaps help, and the screen keeps most of them.
        assert!(exact_gains > 1000, "{exact_gains}");
        assert!(both > exact_gains * 3 / 4, "{both} of {exact_gains} kept");
        eprintln!("exact gains {exact_gains}, kept {both}, screened out {screened}");
    }
}
