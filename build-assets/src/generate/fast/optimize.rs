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
//! migrate anywhere. Proposals are screened ([`SCREEN`]): most losing swaps are skipped after a
//! few of their heaviest terms. Optimisation stops when a round gains less than [`CONVERGED`] of
//! the total gain so far (or at the `iterations` cap, by default [`super::MAX_ROUNDS`]).
//!
//! **Where the time goes, and the layout that follows.** Profiled with `perf` on the scalar
//! mask EA publishes (128×128×64, Gaussian σ 1.3435 × plain EMA, over ten thousand coupled
//! texels per texel): from IGN's start well under 1 % of proposals gain, so almost all the time
//! is the ΔL of rejected swaps, thousands of terms each before the screen gives up. The terms
//! used to be visited heaviest first, one at a time, each through three wrap tables and a
//! scattered load. Now:
//! - the state is stored **time fastest** (`State`), and the footprint walked one spatial
//!   offset at a time (`Column`), so a neighbour's frames are one contiguous run and the sum
//!   over them vectorises (the footprint of a separable filter, `F = F_xy ⊗ F_t`, is exactly
//!   such columns);
//! - the screen runs in **`f32`** over an `f32` copy of the samples (`Problem::survives`):
//!   half the bytes and twice the lanes. Only the swaps it passes are evaluated exactly in
//!   `f64` (`Problem::gain`) and accepted if they gain, so the loss still falls monotonically
//!   and its bookkeeping stays exact;
//! - both loops have an AVX2 copy chosen at run time, the same operations in the same order,
//!   so the same bits (`avx2_kernels_give_the_portable_bits`).
//!
//! Together these made the optimiser several times faster at the same filtered error. A bake
//! also skips evaluating the start's loss (eq. 7 visits every term, the cost of many rounds:
//! [`Limits::measure_loss`]) and stops when a round's gain is spent ([`CONVERGED`]).
//! `noisebake report bench` measures the current times, errors and loss curves.

use super::distance::Distance;
use super::filter::Footprint;
use crate::generate::rng::{SplitMix64, derive_seed};
use rayon::prelude::*;
use std::cell::UnsafeCell;
use std::time::Instant;

/// A round whose loss decrease is below this fraction of the decrease so far ends optimisation:
/// the gain is spent.
///
/// Why this fraction: the gain of a round falls off slowly (roughly as a power of the round
/// count), and so does the filtered error, so any threshold is a trade of bake time for error.
/// At 1 % the two bench cases FAST is measured on (scalar Gaussian × EMA, cosine hemisphere
/// box 5 × EMA, 128² × 64 and × 32) end within about 1 % of the error that 40 rounds reach, in
/// under half their time; `noisebake report bench` prints each case's curve of loss decrease and
/// error against time, where the trade can be read off. The optimiser's own gain is the yardstick, not
/// the start's head start over a random order: that head start is hundreds of times the whole
/// optimisation's gain from a free start (IGN, the free pair) and would end it after a round or
/// two, well before the error stops falling.
pub const CONVERGED: f64 = 1e-2;
/// [`CONVERGED`] for directions (sphere, hemisphere, cosine hemisphere): their error flattens
/// sooner against the gain. On the bench's AO mask (cosine hemisphere, box 5 × EMA) a round's
/// gain falls to 2 % of the decrease so far near round 10, where its error is within 1 % of what
/// the 40-round cap reaches — the trade the scalar mask makes at 1 % — in about half the time;
/// `noisebake report bench` prints the curve (`super::converged` picks the threshold).
pub const CONVERGED_DIRECTIONS: f64 = 2e-2;
/// Preferred tile side (texels); tiles are never narrower than the footprint radius + 1.
const TILE: usize = 16;
/// Half-width of the window near partners are drawn from.
const LOCAL: u64 = 2;

/// The screen κ of the ΔL evaluation: a proposal is given up once its partial sum falls below
/// `−κ · d(s_i, s_j) · √(Σ F²)` of the terms not yet visited.
///
/// Why screen: the exact early rejection bounds every unvisited term of eq. (8) by
/// `2 F d(s_i, s_j)` (triangle inequality), but the terms have mixed signs, so their sum is
/// typically of the order `d(s_i, s_j) √(Σ F²)`, far below that bound. On the paper's product
/// footprint (box 5×5 × EMA over 16 frames) exact rejection visits nearly every entry per
/// proposal; the screen at κ = 1 visits a small fraction of them, and the loss falls several
/// times faster per second. A screen only ever *skips* a swap that very likely does not gain: accepted swaps are
/// still evaluated in full, so the loss falls monotonically and its bookkeeping stays exact.
/// κ = 1 was the fastest of 0.3–3 on that case. A second, wider screen (κ = 4) used to follow
/// once κ = 1 converged; under the stopping rule of [`CONVERGED`] a bake now ends before that
/// point, where the measured error no longer pays for more rounds (`noisebake report bench`'s
/// curves).
pub const SCREEN: f64 = 1.0;

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
    /// Whether to evaluate the start's loss (eq. 7) for [`Outcome::initial_loss`]: reports
    /// want it, a bake does not (it costs about a round).
    pub measure_loss: bool,
}

/// One point of the loss-against-time curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvePoint {
    /// Seconds since optimisation started.
    pub seconds: f64,
    /// How far the loss (eq. 7) has fallen since the start, after this round: exact, from the
    /// ΔL of every accepted swap (eq. 8), so it needs no evaluation of the loss itself.
    pub decrease: f64,
    /// Swaps accepted in the round.
    pub accepted: u64,
}

/// What the optimiser returns.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Samples, `channels` per texel, x fastest.
    pub samples: Vec<f64>,
    /// Loss of the start, when [`Limits::measure_loss`] asked for it. One evaluation of eq. (7)
    /// costs about as much as a round, so a bake (which only needs the samples) skips it.
    pub initial_loss: Option<f64>,
    /// One point per round.
    pub curve: Vec<CurvePoint>,
}

impl Outcome {
    /// How far the loss fell in all.
    pub fn decrease(&self) -> f64 {
        self.curve.last().map_or(0.0, |p| p.decrease)
    }

    /// Final loss, when the start's was measured.
    pub fn loss(&self) -> Option<f64> {
        self.initial_loss.map(|l| l - self.decrease())
    }

    /// `(seconds, loss)` from the start (at 0 s) through every round, when the start's loss
    /// was measured.
    pub fn loss_curve(&self) -> Option<Vec<(f64, f64)>> {
        let l0 = self.initial_loss?;
        Some(
            std::iter::once((0.0, l0))
                .chain(self.curve.iter().map(|p| (p.seconds, l0 - p.decrease)))
                .collect(),
        )
    }
}

/// What a run shares with the paper's schedule ([`super::paper`]): the clock, the state in the
/// optimiser's layout, the ΔL evaluator and, when asked for, the start's loss.
pub(super) struct Run<'a, const C: usize, D> {
    pub(super) clock: Instant,
    pub(super) state: State<C>,
    pub(super) problem: Problem<'a, C, D>,
    pub(super) initial_loss: Option<f64>,
}

impl<'a, const C: usize, D: Distance<C>> Run<'a, C, D> {
    /// Sets a run up, or returns the finished outcome when there is nothing to optimise (an
    /// empty footprint, or a slice of one texel: no pair to swap).
    pub(super) fn start(
        dims: [usize; 3],
        fp: &'a Footprint,
        samples: Vec<f64>,
        dist: D,
        measure_loss: bool,
    ) -> Result<Self, Outcome> {
        let mut state = to_state::<C>(&samples, dims);
        let problem = Problem::new(fp, dims, dist);
        problem.count_windows(&mut state);
        let initial_loss = measure_loss.then(|| problem.loss(&state));
        // The curve's clock starts after the measurement: its times are the optimisation's.
        let clock = Instant::now();
        if fp.is_empty() || dims[0] * dims[1] < 2 {
            return Err(Outcome {
                samples,
                initial_loss,
                curve: Vec::new(),
            });
        }
        Ok(Run {
            clock,
            state,
            problem,
            initial_loss,
        })
    }

    /// Seconds since the run started.
    pub(super) fn seconds(&self) -> f64 {
        self.clock.elapsed().as_secs_f64()
    }

    /// The outcome: the samples in the texture's order and the curve.
    pub(super) fn finish(self, curve: Vec<CurvePoint>) -> Outcome {
        Outcome {
            samples: self.state.into_samples(),
            initial_loss: self.initial_loss,
            curve,
        }
    }
}

/// Texel samples shared between tile tasks.
///
/// **Layout: time fastest.** Cell `(y·w + x)·n + t` holds texel `(x, y)` of slice `t`, so the
/// `n` frames of one pixel are contiguous: ΔL walks the footprint one spatial offset at a time
/// and reads each neighbour's frames as one or two runs ([`Column`]) that the compiler
/// vectorises. Samples come in and go out in the texture's order (x fastest, t slowest).
///
/// **Sharing.** Tiles of one colour run in parallel and swap samples in place. The colouring is
/// what makes that sound: two tiles of a colour lie further apart than the footprint's radius,
/// so no tile reads or writes a cell another tile of its colour writes (the same argument that
/// makes their gains add up exactly). Cells are `UnsafeCell`s, read and written only through
/// [`State::run`], [`State::load`] and [`State::store`], whose callers keep to that rule.
pub(super) struct State<const C: usize> {
    cells: Box<[UnsafeCell<[f64; C]>]>,
    /// The same samples rounded to `f32`, for the screen ([`Problem::survives`]).
    screen: Box<[UnsafeCell<[f32; C]>]>,
    /// Under TAA ([`Footprint::clamp`]), per cell (the 3 × 3 window centred on that texel of
    /// that slice, the same layout): how many of its values are low (below the coverage) and
    /// how many high (at or above one less it). Empty otherwise.
    windows: Box<[UnsafeCell<[u8; 2]>]>,
    /// `w·h` and `n`, for the conversions.
    pixels: usize,
    frames: usize,
}

// SAFETY: see the type's docs: concurrent tasks touch disjoint cells.
unsafe impl<const C: usize> Sync for State<C> {}

impl<const C: usize> State<C> {
    /// Cells `start..start + len` (frames of one pixel).
    #[inline(always)]
    pub(super) fn run(&self, start: usize, len: usize) -> &[[f64; C]] {
        assert!(start + len <= self.cells.len());
        // SAFETY: in bounds; `UnsafeCell<T>` has `T`'s layout; no task writes these cells
        // while another reads them (the type's docs), and the slice dies before its own task
        // writes again.
        unsafe { std::slice::from_raw_parts(self.cells.as_ptr().add(start).cast(), len) }
    }

    /// [`run`](Self::run) of the `f32` copy.
    #[inline(always)]
    pub(super) fn run32(&self, start: usize, len: usize) -> &[[f32; C]] {
        assert!(start + len <= self.screen.len());
        // SAFETY: as for `run`.
        unsafe { std::slice::from_raw_parts(self.screen.as_ptr().add(start).cast(), len) }
    }

    #[inline(always)]
    pub(super) fn load32(&self, i: usize) -> [f32; C] {
        // SAFETY: as for `run`.
        unsafe { *self.screen[i].get() }
    }

    #[inline(always)]
    pub(super) fn load(&self, i: usize) -> [f64; C] {
        // SAFETY: as for `run`.
        unsafe { *self.cells[i].get() }
    }

    #[inline(always)]
    pub(super) fn store(&self, i: usize, v: [f64; C]) {
        // SAFETY: only the task whose tile holds cell `i` writes it, and no other task reads
        // it meanwhile (the type's docs).
        unsafe {
            *self.cells[i].get() = v;
            *self.screen[i].get() = v.map(|x| x as f32);
        }
    }

    #[inline(always)]
    fn window(&self, i: usize) -> [u8; 2] {
        // SAFETY: as for `run`: a window's counts are read and written only by the task whose
        // tile holds a texel within one of its centre (the tiles' halo covers that).
        unsafe { *self.windows[i].get() }
    }

    #[inline(always)]
    fn set_window(&self, i: usize, v: [u8; 2]) {
        // SAFETY: as for `window`.
        unsafe { *self.windows[i].get() = v }
    }

    /// The samples, `C` values per texel, in the texture's order.
    pub(super) fn into_samples(self) -> Vec<f64> {
        let (px, n) = (self.pixels, self.frames);
        let mut out = vec![0.0; px * n * C];
        for (i, c) in self.cells.into_vec().into_iter().enumerate() {
            let (pixel, t) = (i / n, i % n);
            out[(t * px + pixel) * C..][..C].copy_from_slice(&c.into_inner());
        }
        out
    }
}

/// Index arithmetic of a wrapped `w × h × n` texture: offset tables that replace `mod`.
struct Torus {
    dims: [usize; 3],
    /// `xw[x + w + dx] = (x + dx) mod w`, for `|dx| ≤ w`.
    xw: Vec<u32>,
    /// Same for y, premultiplied by `w` (a pixel index).
    yw: Vec<u32>,
}

impl Torus {
    fn new(dims: [usize; 3]) -> Torus {
        let [w, h, _] = dims;
        let table = |n: usize, mul: usize| (0..3 * n).map(|m| ((m % n) * mul) as u32).collect();
        Torus {
            dims,
            xw: table(w, 1),
            yw: table(h, w),
        }
    }

    /// The pixel `(x + dx, y + dy)`, wrapped.
    #[inline(always)]
    fn pixel(&self, x: usize, y: usize, dx: i32, dy: i32) -> usize {
        let [w, h, _] = self.dims;
        self.yw[(y + h).wrapping_add_signed(dy as isize)] as usize
            + self.xw[(x + w).wrapping_add_signed(dx as isize)] as usize
    }
}

/// The footprint's entries at one spatial offset `(dx, dy)`: its weights over a ring interval
/// of frame offsets, `taps[k]` at `dt = lo + k`. Walking the footprint a column at a time reads
/// each neighbour's frames as one or two contiguous runs of the time-fastest [`State`].
#[derive(Clone, Debug)]
pub(super) struct Column {
    dx: i32,
    dy: i32,
    lo: i32,
    taps: Vec<f64>,
    /// For a column over the whole ring (`taps.len() == n`): the taps twice over, so that the
    /// neighbour's frames `0..n` are read as one run against `ring[n − u0..2n − u0]`.
    ring: Vec<f64>,
    /// `taps` and `ring` in `f32`, for the screen.
    taps32: Vec<f32>,
    ring32: Vec<f32>,
}

/// The (at most two) contiguous runs of a column at slice `t` of `n`: `(taps, first frame)`
/// pairs, the frames of each run consecutive in the time-fastest state. A column over the
/// whole ring is one run over frames `0..n` against its doubled taps (`ring`).
#[inline(always)]
fn runs<'c, F>(taps: &'c [F], ring: &'c [F], lo: i32, t: usize, n: usize) -> [(&'c [F], usize); 2] {
    // |lo| < n, so one conditional step wraps `t + lo` (no division).
    let u = t as isize + lo as isize;
    let u0 = if u < 0 {
        (u + n as isize) as usize
    } else if u >= n as isize {
        u as usize - n
    } else {
        u as usize
    };
    if ring.is_empty() {
        let first = taps.len().min(n - u0);
        [(&taps[..first], u0), (&taps[first..], 0)]
    } else {
        [(&ring[n - u0..2 * n - u0], 0), (&ring[..0], 0)]
    }
}

/// The columns of a footprint, heaviest (largest total weight) first. A column spans the ring
/// interval from its lowest to its highest kept `dt`; offsets in between that the footprint
/// dropped carry weight 0.
fn columns(fp: &Footprint, n: usize) -> Vec<Column> {
    let mut by_offset: std::collections::BTreeMap<(i32, i32), Vec<(i32, f64)>> =
        std::collections::BTreeMap::new();
    for r in &fp.rows {
        for &(dx, f) in &r.entries {
            by_offset.entry((dx, r.dy)).or_default().push((r.dt, f));
        }
    }
    let mut cols: Vec<(f64, Column)> = by_offset
        .into_iter()
        .map(|((dx, dy), entries)| {
            let lo = entries.iter().map(|e| e.0).min().unwrap_or(0);
            let hi = entries.iter().map(|e| e.0).max().unwrap_or(0);
            debug_assert!(((hi - lo) as usize) < n);
            let mut taps = vec![0.0; (hi - lo + 1) as usize];
            for (dt, f) in entries {
                taps[(dt - lo) as usize] = f;
            }
            let total: f64 = taps.iter().sum();
            let ring = if taps.len() == n {
                taps.iter().chain(&taps).copied().collect()
            } else {
                Vec::new()
            };
            let taps32 = taps.iter().map(|&f| f as f32).collect();
            let ring32 = ring.iter().map(|&f| f as f32).collect();
            (
                total,
                Column {
                    dx,
                    dy,
                    lo,
                    taps,
                    ring,
                    taps32,
                    ring32,
                },
            )
        })
        .collect();
    cols.sort_by(|a, b| {
        b.0.total_cmp(&a.0)
            .then((a.1.dx, a.1.dy).cmp(&(b.1.dx, b.1.dy)))
    });
    cols.into_iter().map(|c| c.1).collect()
}

/// The problem: footprint, distance and torus.
pub(super) struct Problem<'a, const C: usize, D> {
    fp: &'a Footprint,
    torus: Torus,
    dist: std::marker::PhantomData<D>,
    /// `fp.same_slice` in `f32`, for the screen.
    same_slice32: Vec<f32>,
    /// `tail` and `spread` in `f32`, for the screen.
    tail32: Vec<f32>,
    spread32: Vec<f32>,
    /// The footprint by spatial offset, heaviest first.
    columns: Vec<Column>,
    /// `tail[m] = Σ F` over the columns from `m` on: the weight not yet visited.
    tail: Vec<f64>,
    /// `spread[m] = √(Σ F²)` over the columns from `m` on: the scale of the unvisited terms'
    /// sum (see [`SCREEN`]).
    spread: Vec<f64>,
    /// Whether the CPU has AVX2 ([`Problem::gain`] then runs its AVX2 copy: the same bits).
    avx2: bool,
}

/// Partial sums of a column: frame `k` of each of its (at most two) runs goes to sum
/// `k mod LANES`, and the sums are added in order at the column's end. Eight independent sums
/// keep two AVX2 registers of additions in flight.
const LANES: usize = 8;
/// The same for the `f32` screen: sixteen sums, two AVX2 registers.
const LANES32: usize = 16;

impl<'a, const C: usize, D> Problem<'a, C, D> {
    pub(super) fn new(fp: &'a Footprint, dims: [usize; 3], _: D) -> Self {
        let columns = columns(fp, dims[2]);
        let mut tail = vec![0.0; columns.len() + 1];
        let mut spread = vec![0.0; columns.len() + 1];
        for m in (0..columns.len()).rev() {
            let taps = &columns[m].taps;
            tail[m] = tail[m + 1] + taps.iter().sum::<f64>();
            spread[m] = spread[m + 1] + taps.iter().map(|f| f * f).sum::<f64>();
        }
        for v in &mut spread {
            *v = v.sqrt();
        }
        Problem {
            fp,
            torus: Torus::new(dims),
            dist: std::marker::PhantomData,
            same_slice32: fp.same_slice.iter().map(|&f| f as f32).collect(),
            tail32: tail.iter().map(|&f| f as f32).collect(),
            spread32: spread.iter().map(|&f| f as f32).collect(),
            columns,
            tail,
            spread,
            #[cfg(target_arch = "x86_64")]
            avx2: std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(not(target_arch = "x86_64"))]
            avx2: false,
        }
    }

    /// The cell of texel `p` in slice `t` ([`State`]'s layout).
    #[inline(always)]
    pub(super) fn cell(&self, p: [usize; 2], t: usize) -> usize {
        let [w, _, n] = self.torus.dims;
        (p[1] * w + p[0]) * n + t
    }
}

impl<const C: usize, D: Distance<C>> Problem<'_, C, D> {
    /// Half the change of `Σ F_jk d(s_j, s_k)` when the samples at `p` and `q` of slice `t`
    /// swap (eq. 8): positive means the loss `−Σ F d` falls. Returns `None` as soon as the swap
    /// provably cannot help: by the triangle inequality each unvisited term is at most
    /// `F · d(s_i, s_j)` in size, so once the partial sum is below `−2 d(s_i, s_j) Σ F_unvisited`
    /// the sign is settled. Columns are visited heaviest first, so this usually happens early.
    ///
    /// With a finite `screen` κ it also gives up once the partial sum is below
    /// `−κ · d(s_i, s_j) · √(Σ F²_unvisited)` (see [`SCREEN`]); `f64::INFINITY` is exact.
    ///
    /// The sum over a column runs in [`LANES`] interleaved partial sums, added in a fixed order
    /// at the column's end: the same bits whether or not the compiler vectorises it. The `f32`
    /// screen ([`survives`](Self::survives)) repeats this walk in its own precision rather than
    /// through a shared generic helper: that helper measured slower here.
    #[inline]
    pub(super) fn gain(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
        screen: f64,
    ) -> Option<f64> {
        self.gain_dispatch::<true>(s, p, q, t, screen)
    }

    /// The exact half change of `Σ F d` of [`gain`](Self::gain) (positive: the loss falls),
    /// without giving up early: for swaps accepted whatever their ΔL (a window repaired under
    /// TAA), whose change the loss's bookkeeping still needs.
    pub(super) fn delta(&self, s: &State<C>, p: [usize; 2], q: [usize; 2], t: usize) -> f64 {
        self.gain_dispatch::<false>(s, p, q, t, f64::INFINITY)
            .unwrap_or(0.0)
    }

    /// `BOUNDED`: whether to give up early (a compile-time choice, so the hot path of
    /// [`gain`](Self::gain) carries no test of it).
    #[inline(always)]
    fn gain_dispatch<const BOUNDED: bool>(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
        screen: f64,
    ) -> Option<f64> {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU has AVX2 (`Problem::new`).
            return unsafe { self.gain_avx2::<BOUNDED>(s, p, q, t, screen) };
        }
        self.gain_body::<BOUNDED>(s, p, q, t, screen)
    }

    /// [`gain`](Self::gain) compiled for AVX2: the same operations in the same order, so the
    /// same bits, four `f64` to a register.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn gain_avx2<const BOUNDED: bool>(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
        screen: f64,
    ) -> Option<f64> {
        self.gain_body::<BOUNDED>(s, p, q, t, screen)
    }

    #[inline(always)]
    fn gain_body<const BOUNDED: bool>(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
        screen: f64,
    ) -> Option<f64> {
        let [w, h, n] = self.torus.dims;
        let (i, j) = (self.cell(p, t), self.cell(q, t));
        let (si, sj) = (s.load(i), s.load(j));
        let dij = D::d(&si, &sj);
        if dij == 0.0 {
            return None;
        }
        // Both sides include k = j (resp. i) when in range; eq. 8's last term corrects for it.
        let fij = self.fp.same_slice[((q[1] + h - p[1]) % h) * w + (q[0] + w - p[0]) % w];
        let mut acc = 2.0 * fij * dij;
        for (m, col) in self.columns.iter().enumerate() {
            let a = self.torus.pixel(p[0], p[1], col.dx, col.dy) * n;
            let c = self.torus.pixel(q[0], q[1], col.dx, col.dy) * n;
            // Frames t + lo, t + lo + 1, … on the ring: at most two contiguous runs.
            let mut lanes = [0.0f64; LANES];
            for (taps, u) in runs(&col.taps, &col.ring, col.lo, t, n) {
                let (ra, rc) = (s.run(a + u, taps.len()), s.run(c + u, taps.len()));
                let whole = taps.len() / LANES * LANES;
                for ((f, ra), rc) in taps[..whole]
                    .chunks_exact(LANES)
                    .zip(ra.chunks_exact(LANES))
                    .zip(rc.chunks_exact(LANES))
                {
                    for l in 0..LANES {
                        lanes[l] += f[l] * self.term(&si, &sj, &ra[l], &rc[l]);
                    }
                }
                for k in whole..taps.len() {
                    lanes[k - whole] += taps[k] * self.term(&si, &sj, &ra[k], &rc[k]);
                }
            }
            acc += lanes.iter().sum::<f64>();
            // `screen · 0` is NaN for an infinite screen at the end: the test is then false.
            let rest = m + 1;
            if BOUNDED
                && (acc + 2.0 * dij * self.tail[rest] <= 0.0
                    || acc + screen * dij * self.spread[rest] <= 0.0)
            {
                return None;
            }
        }
        Some(acc)
    }

    /// The screen: whether the swap of `p` and `q` in slice `t` is worth an exact evaluation.
    /// It runs [`gain`](Self::gain)'s walk over the columns in `f32` (half the memory, twice
    /// the lanes) and gives up where `gain` would with screen κ = `screen` (the partial sum
    /// falls below `−κ · d(s_i, s_j) · √(Σ F²_unvisited)`, or below the triangle bound). Every
    /// swap it passes is then evaluated exactly in `f64` and accepted only if it gains, so the
    /// loss still falls monotonically and its bookkeeping stays exact; rounding in `f32` only
    /// ever changes which borderline swaps get a second look.
    #[inline]
    pub(super) fn survives(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
        screen: f32,
    ) -> bool {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU has AVX2 (`Problem::new`).
            return unsafe { self.survives_avx2(s, p, q, t, screen) };
        }
        self.survives_body(s, p, q, t, screen)
    }

    /// [`survives`](Self::survives) compiled for AVX2: the same operations in the same order.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn survives_avx2(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
        screen: f32,
    ) -> bool {
        self.survives_body(s, p, q, t, screen)
    }

    #[inline(always)]
    fn survives_body(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
        screen: f32,
    ) -> bool {
        let [w, h, n] = self.torus.dims;
        let (i, j) = (self.cell(p, t), self.cell(q, t));
        let (si, sj) = (s.load32(i), s.load32(j));
        let dij = D::d32(&si, &sj);
        if dij == 0.0 {
            return false;
        }
        let fij = self.same_slice32[((q[1] + h - p[1]) % h) * w + (q[0] + w - p[0]) % w];
        let mut acc = 2.0 * fij * dij;
        let term = |a: &[f32; C], c: &[f32; C]| {
            (D::d32(&sj, a) - D::d32(&si, a)) - (D::d32(&sj, c) - D::d32(&si, c))
        };
        for (m, col) in self.columns.iter().enumerate() {
            let a = self.torus.pixel(p[0], p[1], col.dx, col.dy) * n;
            let c = self.torus.pixel(q[0], q[1], col.dx, col.dy) * n;
            let mut lanes = [0.0f32; LANES32];
            for (taps, u) in runs(&col.taps32, &col.ring32, col.lo, t, n) {
                let (ra, rc) = (s.run32(a + u, taps.len()), s.run32(c + u, taps.len()));
                let whole = taps.len() / LANES32 * LANES32;
                for ((f, ra), rc) in taps[..whole]
                    .chunks_exact(LANES32)
                    .zip(ra.chunks_exact(LANES32))
                    .zip(rc.chunks_exact(LANES32))
                {
                    for l in 0..LANES32 {
                        lanes[l] += f[l] * term(&ra[l], &rc[l]);
                    }
                }
                for k in whole..taps.len() {
                    lanes[k - whole] += taps[k] * term(&ra[k], &rc[k]);
                }
            }
            acc += lanes.iter().sum::<f32>();
            let rest = m + 1;
            if acc + 2.0 * dij * self.tail32[rest] <= 0.0
                || acc + screen * dij * self.spread32[rest] <= 0.0
            {
                return false;
            }
        }
        true
    }

    /// One term of eq. 8 before its weight: `(d(s_j, a) − d(s_i, a)) − (d(s_j, c) − d(s_i, c))`
    /// for the neighbours `a` of `p` and `c` of `q` at the same offset.
    #[inline(always)]
    fn term(&self, si: &[f64; C], sj: &[f64; C], a: &[f64; C], c: &[f64; C]) -> f64 {
        (D::d(sj, a) - D::d(si, a)) - (D::d(sj, c) - D::d(si, c))
    }

    /// `Σ_j Σ_k F_jk d(s_j, s_k)` over slice `t` (as `j`).
    fn slice_energy(&self, s: &State<C>, t: usize) -> f64 {
        let [w, h, n] = self.torus.dims;
        let mut sum = 0.0;
        for y in 0..h {
            for x in 0..w {
                let sj = s.load(self.cell([x, y], t));
                for row in &self.fp.rows {
                    let u = (t + n).wrapping_add_signed(row.dt as isize) % n;
                    for &(dx, f) in &row.entries {
                        let k = self.torus.pixel(x, y, dx, row.dy) * n + u;
                        sum += f * D::d(&sj, &s.load(k));
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

/// Under TAA, the margin of a window's classes: one 8-bit step, so that a value counted low
/// (high) still reads below `coverage` (at or above `1 − coverage`) however its texel is read —
/// `q / 256` by the runtime, `q / 255` as a GPU unorm, `(q + 0.5) / 256` at the centre — in
/// 8 or 16 bits.
pub const CLAMP_MARGIN: f64 = 1.0 / 256.0;

/// Under TAA: a value's membership of a window's counts, `[low, high]`: below the coverage,
/// at or above one less it, with [`CLAMP_MARGIN`].
#[inline(always)]
fn class(v: f64, coverage: f64) -> [i8; 2] {
    [
        i8::from(v < coverage - CLAMP_MARGIN),
        i8::from(v >= 1.0 - coverage + CLAMP_MARGIN),
    ]
}

/// Whether a window with these counts is open: it lacks a low or a high value, so the clamp
/// acts on the dither of some coverage the filter keeps.
#[inline(always)]
fn open(c: [u8; 2]) -> i32 {
    i32::from(c[0] == 0 || c[1] == 0)
}

/// The windows a swap changes (at most the 18 centred within one texel of either partner) and
/// their new counts.
pub(super) struct WindowChange {
    cells: [usize; 18],
    counts: [[u8; 2]; 18],
    len: usize,
    /// The change in the number of open windows.
    pub(super) opened: i32,
}

impl<const C: usize, D> Problem<'_, C, D> {
    /// Counts every window of `s` ([`State`]'s `windows`) when the footprint has a clamp.
    pub(super) fn count_windows(&self, s: &mut State<C>) {
        let Some(coverage) = self.fp.clamp else {
            return;
        };
        let [w, h, n] = self.torus.dims;
        let counts: Vec<UnsafeCell<[u8; 2]>> = (0..w * h * n)
            .map(|i| {
                let (pixel, t) = (i / n, i % n);
                let (x, y) = (pixel % w, pixel / w);
                let mut c = [0u8; 2];
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let k = class(s.load(self.torus.pixel(x, y, dx, dy) * n + t)[0], coverage);
                        c[0] += k[0] as u8;
                        c[1] += k[1] as u8;
                    }
                }
                UnsafeCell::new(c)
            })
            .collect();
        s.windows = counts.into_boxed_slice();
    }

    /// Under TAA, how swapping the samples at `p` and `q` of slice `t` changes the windows;
    /// `None` when it changes none (no clamp, or both values of the same class).
    #[inline]
    pub(super) fn window_change(
        &self,
        s: &State<C>,
        p: [usize; 2],
        q: [usize; 2],
        t: usize,
    ) -> Option<WindowChange> {
        let coverage = self.fp.clamp?;
        let n = self.torus.dims[2];
        let ci = class(s.load(self.cell(p, t))[0], coverage);
        let cj = class(s.load(self.cell(q, t))[0], coverage);
        if ci == cj {
            return None;
        }
        // Windows around p trade s_i for s_j; those around q the reverse; a window around both
        // keeps its counts.
        let d = [cj[0] - ci[0], cj[1] - ci[1]];
        let mut cells = [0usize; 18];
        let mut delta = [[0i8; 2]; 18];
        let mut len = 0;
        for (at, sign) in [(p, 1i8), (q, -1i8)] {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let cell = self.torus.pixel(at[0], at[1], dx, dy) * n + t;
                    let k = cells[..len]
                        .iter()
                        .position(|&c| c == cell)
                        .unwrap_or_else(|| {
                            cells[len] = cell;
                            len += 1;
                            len - 1
                        });
                    delta[k][0] += sign * d[0];
                    delta[k][1] += sign * d[1];
                }
            }
        }
        let mut counts = [[0u8; 2]; 18];
        let mut opened = 0;
        for k in 0..len {
            let old = s.window(cells[k]);
            let new = [
                (old[0] as i8 + delta[k][0]) as u8,
                (old[1] as i8 + delta[k][1]) as u8,
            ];
            opened += open(new) - open(old);
            counts[k] = new;
        }
        Some(WindowChange {
            cells,
            counts,
            len,
            opened,
        })
    }

    /// Writes a change's counts (after its swap).
    #[inline]
    pub(super) fn apply(&self, s: &State<C>, change: &WindowChange) {
        for k in 0..change.len {
            s.set_window(change.cells[k], change.counts[k]);
        }
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
pub fn loss<const C: usize, D: Distance<C>>(
    dims: [usize; 3],
    fp: &Footprint,
    samples: &[f64],
    dist: D,
) -> f64 {
    let state = to_state::<C>(samples, dims);
    Problem::new(fp, dims, dist).loss(&state)
}

pub(super) fn to_state<const C: usize>(samples: &[f64], dims: [usize; 3]) -> State<C> {
    let [w, h, n] = dims;
    let px = w * h;
    let at = |i: usize| -> [f64; C] {
        let (pixel, t) = (i / n, i % n);
        let c = &samples[(t * px + pixel) * C..][..C];
        std::array::from_fn(|k| c[k])
    };
    State {
        cells: (0..px * n).map(|i| UnsafeCell::new(at(i))).collect(),
        screen: (0..px * n)
            .map(|i| UnsafeCell::new(at(i).map(|x| x as f32)))
            .collect(),
        windows: Box::new([]),
        pixels: px,
        frames: n,
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
    D: Distance<C>,
{
    let Limits {
        max_rounds,
        budget,
        converged,
        measure_loss,
    } = limits;
    let [w, h, n] = dims;
    let run = match Run::start(dims, fp, samples, dist, measure_loss) {
        Ok(run) => run,
        Err(done) => return done,
    };
    let (state, problem) = (&run.state, &run.problem);
    let mut curve = Vec::new();
    // Under TAA a tile also writes the window counts of texels one beyond it and reads those
    // within one of its partners: a halo of at least 2.
    let halo = |r: usize| if fp.clamp.is_some() { r.max(2) } else { r };
    let bx = tile_bounds(w, halo(fp.radius[0]));
    let by = tile_bounds(h, halo(fp.radius[1]));
    let (tx, ty) = (bx.len() - 1, by.len() - 1);
    let mut total_gain = 0.0;
    let mut total_repaired = 0.0;
    for round in 0..max_rounds {
        let mut rng = SplitMix64::new(derive_seed(seed, round as u64));
        let (ox, oy) = (rng.below(w as u64) as usize, rng.below(h as u64) as usize);
        let mut round_gain = 0.0;
        let mut accepted = 0;
        let mut round_repaired = 0.0;
        for colour in 0..4 {
            let tiles: Vec<(usize, usize)> = (0..ty)
                .flat_map(|j| (0..tx).map(move |i| (i, j)))
                .filter(|&(i, j)| (i % 2) + 2 * (j % 2) == colour)
                .collect();
            let results: Vec<(f64, u64, f64)> = tiles
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
                    let (mut gain, mut acc, mut repaired) = (0.0, 0u64, 0.0);
                    if cells < 2 {
                        return (gain, acc, repaired);
                    }
                    // Tile cell `c` at (c mod tw, c / tw), shifted by the round's offset; both
                    // sums stay below twice the axis, so one conditional subtraction wraps.
                    let wrap = |v: usize, n: usize| if v >= n { v - n } else { v };
                    let at = |c: u64| {
                        let c = c as u32;
                        let (cy, cx) = (c / tw as u32, c % tw as u32);
                        [
                            wrap(ox + x0 + cx as usize, w),
                            wrap(oy + y0 + cy as usize, h),
                        ]
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
                        let swap = |g: f64| {
                            let (i, j) = (problem.cell(p, t), problem.cell(q, t));
                            let (si, sj) = (state.load(i), state.load(j));
                            state.store(i, sj);
                            state.store(j, si);
                            g
                        };
                        // Under TAA the windows come first: a swap that opens one is never
                        // made, and one that closes more than it opens is made whatever its
                        // ΔL (the order is lexicographic: open windows, then the loss).
                        let change = problem.window_change(state, p, q, t);
                        match change.as_ref().map(|c| c.opened) {
                            Some(o) if o > 0 => continue,
                            Some(o) if o < 0 => {
                                repaired += swap(problem.delta(state, p, q, t));
                                problem.apply(state, change.as_ref().expect("some"));
                                acc += 1;
                                continue;
                            }
                            _ => {}
                        }
                        if !problem.survives(state, p, q, t, SCREEN as f32) {
                            continue;
                        }
                        if let Some(g) = problem
                            .gain(state, p, q, t, f64::INFINITY)
                            .filter(|&g| g > 0.0)
                        {
                            gain += swap(g);
                            if let Some(c) = &change {
                                problem.apply(state, c);
                            }
                            acc += 1;
                        }
                    }
                    (gain, acc, repaired)
                })
                .collect();
            for (g, a, r) in results {
                round_gain += g;
                accepted += a;
                round_repaired += r;
            }
        }
        total_gain += round_gain;
        total_repaired += round_repaired;
        curve.push(CurvePoint {
            seconds: run.seconds(),
            // ΔΣFd = 2·gain per swap (eq. 8), and L = −ΣFd.
            decrease: 2.0 * (total_gain + total_repaired),
            accepted,
        });
        progress(round as u64 + 1, max_rounds as u64);
        // The yardstick is the gain of the swaps made for the loss; under TAA, the swaps that
        // close windows (made whatever their ΔL) are left out of it.
        if round_gain <= converged * total_gain {
            break;
        }
        // A wall-clock budget (reports only: it makes the result depend on the machine).
        if budget.is_some_and(|b| run.seconds() >= b) {
            break;
        }
    }
    run.finish(curve)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::fast::{Combine, Filter, TemporalFilter};

    /// The AVX2 copies of the ΔL and screen loops give the bits of the portable ones (the
    /// same operations in the same order), so masks do not depend on the CPU; checked on
    /// scalars and on the sphere, over a full ring of frames and a partial one.
    #[test]
    fn avx2_kernels_give_the_portable_bits() {
        fn check<const C: usize, D: Distance<C>>(dims: [usize; 3], temporal: TemporalFilter) {
            let fp = Footprint::new(
                dims,
                Filter::Gauss { sigma: 1.3435 },
                temporal,
                Combine::Product,
            );
            let mut rng = SplitMix64::new(11);
            let samples: Vec<f64> = (0..dims.iter().product::<usize>() * C)
                .map(|_| rng.unit_f64() * 2.0 - 1.0)
                .collect();
            let state = to_state::<C>(&samples, dims);
            let mut problem = Problem::new(&fp, dims, D::default_value());
            let mut portable = Vec::new();
            let mut fast = Vec::new();
            let cases: Vec<_> = (0..3000)
                .map(|_| {
                    let p = [
                        rng.below(dims[0] as u64) as usize,
                        rng.below(dims[1] as u64) as usize,
                    ];
                    let q = [
                        rng.below(dims[0] as u64) as usize,
                        rng.below(dims[1] as u64) as usize,
                    ];
                    (p, q, rng.below(dims[2] as u64) as usize)
                })
                .collect();
            for avx2 in [false, problem.avx2] {
                problem.avx2 = avx2;
                let out = if avx2 { &mut fast } else { &mut portable };
                for &(p, q, t) in &cases {
                    out.push((
                        problem
                            .gain(&state, p, q, t, f64::INFINITY)
                            .map(f64::to_bits),
                        problem.gain(&state, p, q, t, 1.0).map(f64::to_bits),
                        problem.survives(&state, p, q, t, 1.0),
                    ));
                }
            }
            if problem.avx2 {
                assert_eq!(portable, fast);
            }
            assert!(
                portable.iter().any(|c| c.2),
                "some swaps survive the screen"
            );
        }
        let ema = TemporalFilter::Ema {
            alpha: 0.1,
            beta: 0.0,
        };
        check::<1, super::super::distance::Scalar>([16, 16, 16], ema);
        check::<3, super::super::distance::Sphere>([16, 16, 8], TemporalFilter::Box { size: 3 });
    }

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
        let state = to_state::<3>(&samples, dims);
        let problem = Problem::new(&fp, dims, super::super::distance::Euclid);
        let (mut screened, mut exact_gains, mut both) = (0, 0, 0);
        for _ in 0..4000 {
            let p = [rng.below(16) as usize, rng.below(16) as usize];
            let q = [rng.below(16) as usize, rng.below(16) as usize];
            let t = rng.below(8) as usize;
            let exact = problem
                .gain(&state, p, q, t, f64::INFINITY)
                .filter(|&g| g > 0.0);
            let fast = problem.gain(&state, p, q, t, SCREEN).filter(|&g| g > 0.0);
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
