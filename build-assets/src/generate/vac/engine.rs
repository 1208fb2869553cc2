//! The fast void-and-cluster engine: local splats on a fixed-point energy field and lazy
//! block minima, so no step rescans the volume.
//!
//! Phases (Ulichney 1993; STBN §3 and §4.1):
//! 1. an initial binary pattern of `round(density · n)` distinct texels (drawn without
//!    duplicates: a repeated draw would splat twice and leave a permanent "ghost" cluster);
//! 2. relaxation: move the tightest cluster to the largest void until they coincide;
//! 3. phase I: remove clusters from the relaxed pattern, ranking down from `m − 1`;
//! 4. phase II: from the relaxed pattern, add voids until half the texels are on;
//! 5. phase III: add the tightest cluster of the off texels (`K(p) − F(p)` maximal, where
//!    `K(p)` is the energy a texel receives when every texel is on) until all are on.
//!
//! Ties between equal energies are broken by a seeded bijection of the texel index
//! ([`TieRank`], lowest wins), never by memory order, so no raster pattern can appear.
//!
//! Speed: a splat touches only the truncated footprint of each group, walked as runs along x
//! where a group contains x (contiguous adds). Candidates wait in a `queue::BlockQueue` of per-block
//! minimum keys (blocks of `BLOCK` (32) texels along x). Those keys are *lazy lower bounds*: a
//! splat that makes candidates worse leaves them alone, and the top block is recomputed until
//! its key is exact, so a step pays for the three or four blocks that reach the top, not for
//! the ≈ 40 it touched. In phases I–III energies move one way only, so every change makes
//! candidates worse. During relaxation energies move both ways; a change that improves a
//! candidate lowers its block's key at once (`BlockQueue::lower`), one offer per block a run of
//! changed texels crosses.
//!
//! Memory: the splat writes only the energy array, `i32` in fixed point
//! ([`super::kernel::energy_scale`]). In phases I–III the texels that are not candidates carry a
//! `POISON` offset instead of an on/off test, and tie ranks are hashed, not stored, so a block's
//! minimum reads just its energies (one pass for the lowest score, a second for the lowest tie
//! rank among the texels that reach it). A queue key is the score and the tie rank in one `u64`;
//! the rank names the texel ([`TieRank::index`]), so the tree is half the size of one that also
//! carries the index.
//!
//! Measured by `cargo bench -p build-assets --bench vac` (single thread) and `noisebake report
//! bench`: the large sizes are bound by cache misses: their energies (4 MB) do not fit in L2,
//! and each splat reaches 15 slices along t. (`i64` energies and `u128` keys measured slower
//! at every size; so did padding runs to whole SSE2 vectors, or blocks of 16 or 64 texels.)
//!
//! Profile (`perf record -e cpu-clock`, one thread, blue2d 2048² and STBN 128×128×64; everything
//! is inlined into [`rank`], so build with line tables and sort by `srcline`): at 2048² the time
//! splits into three parts of similar size, the splat's adds (about 30 %), the block minima's
//! energy reads (about 20 %) and the tree walk of `BlockQueue::set` (about 20 %); STBN splits
//! about the same way, plus about 8 % on its temporal adds (one line per slice). A `take` refreshes
//! about four blocks per step (4.05 for blue2d, 4.5 for STBN), and the refreshed top block's
//! key rises, so each refresh walks the tree to its root. The splat's run adds compile to
//! scalar read-modify-writes whose cost is the cache miss at a random place of the field.
//! Refreshing every block a splat touched while it is still in cache (so a `take` finds its top
//! exact) gave the same bytes but measured slower: 16 to 35 block minima per step cost more than
//! four lazy refreshes. So a faster engine needs a field layout whose splat touches fewer cache
//! lines (tiles, or STBN's t nearer the fastest axis); more arithmetic per step does not pay.

use super::kernel::{Axis, Energy, Footprint, GroupFootprint};
use super::queue::{BLOCK, BLOCK_BITS, BlockQueue};
use super::tree::ABSENT;
use crate::generate::rng::{SplitMix64, TieRank, sample_distinct};

const INVALID: u32 = u32::MAX;

/// Energy offset that takes a texel out of the running in phases I–III: added to texels that are
/// on while voids are sought, subtracted from texels that are off while clusters are. Any real
/// energy is below `2^29` ([`super::kernel::energy_scale`]), so poisoned and real keys never mix
/// and no sum leaves `i32`.
const POISON: Energy = 1 << 30;

/// Receives `(done, total)` texel counts as ranking advances.
pub type ProgressFn<'a> = &'a mut dyn FnMut(u64, u64);

/// Statistics of one run, for reports.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RunStats {
    /// Texels in the initial pattern.
    pub initial_points: usize,
    /// Cluster-to-void moves made by the relaxation.
    pub relaxation_swaps: usize,
    /// Whether relaxation stopped at its iteration cap instead of converging.
    pub relaxation_capped: bool,
    /// Entries touched by one splat.
    pub footprint: usize,
}

/// Energy field and state of a run.
pub(crate) struct Engine<'f> {
    fp: &'f Footprint,
    /// Per axis: stride-scaled wrapped coordinate for `coordinate + pad`, or `INVALID`.
    wrap: Vec<Vec<u32>>,
    pad: Vec<usize>,
    sizes: Vec<usize>,
    strides: Vec<usize>,
    /// Fixed-point energy of each texel (plus or minus [`POISON`] in phases I–III).
    energy: Vec<Energy>,
    /// Tie-break rank of each texel, a bijection of its index.
    tie: TieRank,
    /// Whether each texel is on (kept during the initial pattern and relaxation).
    on: Vec<bool>,
    /// `K(p)` when axes are open (it varies near borders); `None` when it is constant.
    k_field: Option<Vec<Energy>>,
    /// Per group: its footprint as runs along x when the group contains axis 0, else empty.
    spans: Vec<Vec<Span>>,
}

/// A run of footprint entries along x: offsets `dx..dx + len` at fixed offsets `rest` along the
/// group's other axes, with weights `weights[start..start + len]`.
#[derive(Clone, Debug)]
struct Span {
    dx: i32,
    rest: [i32; 3],
    start: u32,
    len: u32,
}

/// Splits a group's footprint into runs along x (its first axis must be axis 0; entries are in
/// odometer order, x fastest).
fn spans_of(g: &GroupFootprint) -> Vec<Span> {
    let k = g.axes.len();
    if g.axes[0] != 0 || k > 4 {
        return Vec::new();
    }
    let mut spans: Vec<Span> = Vec::new();
    for (i, o) in g.offsets.chunks_exact(k).enumerate() {
        let mut rest = [0i32; 3];
        rest[..k - 1].copy_from_slice(&o[1..]);
        match spans.last_mut() {
            Some(s)
                if s.rest == rest && s.dx + s.len as i32 == o[0] && s.start + s.len == i as u32 =>
            {
                s.len += 1
            }
            _ => spans.push(Span {
                dx: o[0],
                rest,
                start: i as u32,
                len: 1,
            }),
        }
    }
    spans
}

/// A score as an unsigned number of the same order.
fn bias(score: Energy) -> u32 {
    (score as u32) ^ (1 << 31)
}

/// A queue key: the score, then the tie rank (which names the texel: [`TieRank::index`]).
#[inline(always)]
fn pack(score: Energy, tie: u32) -> u64 {
    (bias(score) as u64) << 32 | tie as u64
}

impl<'f> Engine<'f> {
    pub(crate) fn new(axes: &[Axis], fp: &'f Footprint, tie: TieRank) -> Self {
        let sizes: Vec<usize> = axes.iter().map(|a| a.size).collect();
        let n: usize = sizes.iter().product();
        let mut strides = vec![1usize; axes.len()];
        for a in 1..axes.len() {
            strides[a] = strides[a - 1] * sizes[a - 1];
        }
        let mut pad = vec![0usize; axes.len()];
        for g in &fp.groups {
            let k = g.axes.len();
            for (j, &a) in g.axes.iter().enumerate() {
                let m = g
                    .offsets
                    .chunks(k)
                    .map(|o| o[j].unsigned_abs() as usize)
                    .max();
                pad[a] = pad[a].max(m.unwrap_or(0));
            }
        }
        let wrap = axes
            .iter()
            .enumerate()
            .map(|(a, ax)| {
                (0..ax.size + 2 * pad[a])
                    .map(|i| {
                        let c = i as i64 - pad[a] as i64;
                        let s = ax.size as i64;
                        if ax.toroidal {
                            (c.rem_euclid(s) as usize * strides[a]) as u32
                        } else if (0..s).contains(&c) {
                            (c as usize * strides[a]) as u32
                        } else {
                            INVALID
                        }
                    })
                    .collect()
            })
            .collect();
        let mut e = Self {
            fp,
            wrap,
            pad,
            sizes,
            strides,
            energy: vec![0; n],
            tie,
            on: vec![false; n],
            k_field: None,
            spans: fp.groups.iter().map(spans_of).collect(),
        };
        if axes.iter().any(|a| !a.toroidal) {
            // K(p): the energy every texel would give p. Computed by splatting each texel's
            // footprint into itself, so open borders are counted exactly as in the engine.
            let k = (0..n)
                .map(|p| {
                    let mut s = 0;
                    e.for_each(p, |_, w| s += w);
                    s
                })
                .collect();
            e.k_field = Some(k);
        }
        e
    }

    /// Coordinates of texel `p`, by successive division in u32 (masks stay below 2^32 texels).
    #[inline(always)]
    fn coords(&self, p: usize) -> [usize; 8] {
        let mut coord = [0usize; 8];
        let mut rest = p as u32;
        for (c, &size) in coord.iter_mut().zip(&self.sizes) {
            *c = (rest % size as u32) as usize;
            rest /= size as u32;
        }
        coord
    }

    /// Visits `(q, weight)` for every footprint entry of `p` that lands inside the mask.
    fn for_each(&self, p: usize, mut f: impl FnMut(usize, Energy)) {
        let coord = self.coords(p);
        for g in &self.fp.groups {
            self.for_group(p, &coord, g, &mut f);
        }
    }

    /// Visits `(q, weight)` for every entry of group `g`'s footprint around `p`.
    #[inline(always)]
    fn for_group(
        &self,
        p: usize,
        coord: &[usize; 8],
        g: &GroupFootprint,
        mut f: impl FnMut(usize, Energy),
    ) {
        let mut base = p;
        for &a in &g.axes {
            base -= coord[a] * self.strides[a];
        }
        match g.axes.len() {
            1 => {
                let a = g.axes[0];
                let t = &self.wrap[a][coord[a]..];
                let pa = self.pad[a] as isize;
                for (o, &w) in g.offsets.iter().zip(&g.weights) {
                    let v = t[(*o as isize + pa) as usize];
                    if v != INVALID {
                        f(base + v as usize, w);
                    }
                }
            }
            2 => {
                let (a0, a1) = (g.axes[0], g.axes[1]);
                let t0 = &self.wrap[a0][coord[a0]..];
                let t1 = &self.wrap[a1][coord[a1]..];
                let (p0, p1) = (self.pad[a0] as isize, self.pad[a1] as isize);
                for (o, &w) in g.offsets.chunks_exact(2).zip(&g.weights) {
                    let v0 = t0[(o[0] as isize + p0) as usize];
                    let v1 = t1[(o[1] as isize + p1) as usize];
                    if v0 != INVALID && v1 != INVALID {
                        f(base + v0 as usize + v1 as usize, w);
                    }
                }
            }
            k => {
                'entry: for (o, &w) in g.offsets.chunks_exact(k).zip(&g.weights) {
                    let mut q = base;
                    for (j, &a) in g.axes.iter().enumerate() {
                        let v = self.wrap[a]
                            [((coord[a] + self.pad[a]) as isize + o[j] as isize) as usize];
                        if v == INVALID {
                            continue 'entry;
                        }
                        q += v as usize;
                    }
                    f(q, w);
                }
            }
        }
    }

    /// Adds `sign ·` the footprint of `p` to the energy field; `touched(lo, hi)` sees each run of
    /// texels `lo..hi` it changed.
    ///
    /// Groups that contain the x axis are walked as runs along x ([`Span`]): away from the x
    /// border a run is one contiguous slice of energies (no wrap lookups, vectorised adds).
    #[inline(always)]
    fn splat(&mut self, p: usize, sign: Energy, mut touched: impl FnMut(usize, usize)) {
        let coord = self.coords(p);
        // Split borrows: the footprint walk reads tables, the closure writes energies.
        let mut energy = std::mem::take(&mut self.energy);
        for (g, spans) in self.fp.groups.iter().zip(&self.spans) {
            if spans.is_empty() {
                self.for_group(p, &coord, g, |q, w| {
                    energy[q] += sign * w;
                    touched(q, q + 1);
                });
                continue;
            }
            // Offsets of the other axes of the group: the row of each run.
            let x = coord[0];
            let width = self.sizes[0];
            let mut base = p - x;
            for &a in &g.axes[1..] {
                base -= coord[a] * self.strides[a];
            }
            // x_wrap[dx] is the wrapped x of `x + dx - pad`: index it with `dx + pad`.
            let x_wrap = &self.wrap[0][x..];
            for s in spans {
                let mut row = base;
                let mut outside = false;
                for (j, &a) in g.axes[1..].iter().enumerate() {
                    let v = self.wrap[a]
                        [((coord[a] + self.pad[a]) as isize + s.rest[j] as isize) as usize];
                    outside |= v == INVALID;
                    row = row.wrapping_add(v as usize);
                }
                if outside {
                    continue;
                }
                let w = &g.weights[s.start as usize..(s.start + s.len) as usize];
                let x0 = x as isize + s.dx as isize;
                if x0 >= 0 && x0 as usize + w.len() <= width {
                    let at = row + x0 as usize;
                    let e = &mut energy[at..at + w.len()];
                    if sign > 0 {
                        e.iter_mut().zip(w).for_each(|(e, &w)| *e += w);
                    } else {
                        e.iter_mut().zip(w).for_each(|(e, &w)| *e -= w);
                    }
                    touched(at, at + w.len());
                } else {
                    for (i, &w) in w.iter().enumerate() {
                        let v =
                            x_wrap[(s.dx as isize + i as isize + self.pad[0] as isize) as usize];
                        if v != INVALID {
                            let q = row + v as usize;
                            energy[q] += sign * w;
                            touched(q, q + 1);
                        }
                    }
                }
            }
        }
        self.energy = energy;
    }

    /// Score of texel `p` as a void (lowest energy first; in phase III with open axes lowest
    /// `F(p) − K(p)`) or as a cluster (highest energy first). Lower is better.
    #[inline(always)]
    fn score<const VOIDS: bool, const PHASE3: bool>(&self, p: usize) -> Energy {
        let e = self.energy[p];
        if !VOIDS {
            -e
        } else if PHASE3 {
            e - self.k_field.as_ref().map_or(0, |k| k[p])
        } else {
            e
        }
    }

    /// Lowest score among texels `lo..hi` (`Energy::MAX` if none is a candidate): poisoned
    /// texels lose by their offset (phases I–III), or, with `CHECK_ON`, texels of the wrong state
    /// are skipped (relaxation).
    #[inline(always)]
    fn range_score<const VOIDS: bool, const PHASE3: bool, const CHECK_ON: bool>(
        &self,
        lo: usize,
        hi: usize,
    ) -> Energy {
        let mut best = Energy::MAX;
        for p in lo..hi {
            best = best.min(self.candidate_score::<VOIDS, PHASE3, CHECK_ON>(p));
        }
        best
    }

    /// Score of texel `p`, or `Energy::MAX` when `CHECK_ON` finds it in the wrong state.
    #[inline(always)]
    fn candidate_score<const VOIDS: bool, const PHASE3: bool, const CHECK_ON: bool>(
        &self,
        p: usize,
    ) -> Energy {
        if CHECK_ON && self.on[p] == VOIDS {
            Energy::MAX
        } else {
            self.score::<VOIDS, PHASE3>(p)
        }
    }

    /// Smallest key among texels `lo..hi` whose lowest score is `best`: the lowest tie rank
    /// among the texels that reach it (almost always one).
    #[inline(always)]
    fn range_key<const VOIDS: bool, const PHASE3: bool, const CHECK_ON: bool>(
        &self,
        lo: usize,
        hi: usize,
        best: Energy,
    ) -> u64 {
        if best == Energy::MAX {
            return ABSENT;
        }
        let mut key = ABSENT;
        for p in lo..hi {
            if self.candidate_score::<VOIDS, PHASE3, CHECK_ON>(p) == best {
                key = key.min(pack(best, self.tie.of(p as u32)));
            }
        }
        key
    }

    /// Smallest key in block `b`: two passes, a plain minimum of the scores, then the tie.
    #[inline(always)]
    fn block_min<const VOIDS: bool, const PHASE3: bool, const CHECK_ON: bool>(
        &self,
        b: usize,
    ) -> u64 {
        let lo = b << BLOCK_BITS;
        let hi = (lo + BLOCK).min(self.energy.len());
        let best = self.range_score::<VOIDS, PHASE3, CHECK_ON>(lo, hi);
        self.range_key::<VOIDS, PHASE3, CHECK_ON>(lo, hi, best)
    }

    /// Offers the candidates among texels `lo..hi` to their blocks (relaxation, after a change
    /// that improved them): per block the run crosses, the lowest score settles most offers
    /// against the block's key; the tie is looked up only when it could win.
    #[inline(always)]
    fn offer<const VOIDS: bool>(&self, q: &mut BlockQueue, mut lo: usize, hi: usize) {
        while lo < hi {
            let end = hi.min((lo | (BLOCK - 1)) + 1);
            let b = lo >> BLOCK_BITS;
            let best = self.range_score::<VOIDS, false, true>(lo, end);
            if best != Energy::MAX && bias(best) <= (q.leaf(b) >> 32) as u32 {
                q.lower(b, self.range_key::<VOIDS, false, true>(lo, end, best));
            }
            lo = end;
        }
    }

    /// A queue over every block.
    fn queue<const VOIDS: bool, const PHASE3: bool, const CHECK_ON: bool>(&self) -> BlockQueue {
        BlockQueue::new(self.energy.len(), |b| {
            self.block_min::<VOIDS, PHASE3, CHECK_ON>(b)
        })
    }

    /// Takes the best candidate from a queue whose block keys are lower bounds: the top block is
    /// recomputed until its key is exact.
    #[inline(always)]
    fn take<const VOIDS: bool, const PHASE3: bool, const CHECK_ON: bool>(
        &self,
        q: &mut BlockQueue,
    ) -> usize {
        loop {
            let k = q.top().expect("the queue holds a candidate");
            let p = self.tie.index(k as u32) as usize;
            let b = p >> BLOCK_BITS;
            let m = self.block_min::<VOIDS, PHASE3, CHECK_ON>(b);
            if m == k {
                return p;
            }
            debug_assert!(m > k, "a lazy key overestimated its block");
            q.set(b, m);
        }
    }
}

/// Ranks every texel of the mask: `result[i]` is the order in which texel `i` turns on.
pub fn rank(
    axes: &[Axis],
    fp: &Footprint,
    initial_density: f64,
    seed: u64,
    progress: ProgressFn,
) -> (Vec<u32>, RunStats) {
    let n: usize = axes.iter().map(|a| a.size).product();
    let mut rng = SplitMix64::new(seed);
    let tie = TieRank::new(&mut rng);
    let mut stats = RunStats {
        footprint: fp.len(),
        ..RunStats::default()
    };
    if n <= 1 {
        return (vec![0; n], stats);
    }
    let mut e = Engine::new(axes, fp, tie);
    let m = ((initial_density * n as f64).round() as usize).clamp(1, (n / 2).max(1));
    stats.initial_points = m;

    // Initial binary pattern: m distinct random texels (no duplicates).
    let order = sample_distinct(n, m, &mut rng);
    for &p in &order {
        e.on[p as usize] = true;
        e.splat(p as usize, 1, |_, _| {});
    }
    drop(order);

    // Relaxation: tightest cluster -> largest void until the two coincide.
    let mut clusters = e.queue::<false, false, true>();
    let mut voids = e.queue::<true, false, true>();
    let cap = 64 * m + 4096;
    let mut touched = Vec::with_capacity(fp.len());
    loop {
        // Removing p lowers energies: void keys fall (offer them), cluster keys rise (lazy).
        let p = e.take::<false, false, true>(&mut clusters);
        e.on[p] = false;
        e.splat(p, -1, |lo, hi| touched.push((lo, hi)));
        for (lo, hi) in touched.drain(..) {
            e.offer::<true>(&mut voids, lo, hi);
        }
        // Adding q raises energies: cluster keys fall (offer them), void keys rise (lazy).
        let q = e.take::<true, false, true>(&mut voids);
        e.on[q] = true;
        e.splat(q, 1, |lo, hi| touched.push((lo, hi)));
        for (lo, hi) in touched.drain(..) {
            e.offer::<false>(&mut clusters, lo, hi);
        }
        if q == p {
            break;
        }
        stats.relaxation_swaps += 1;
        if stats.relaxation_swaps >= cap {
            stats.relaxation_capped = true;
            break;
        }
    }
    drop(voids);

    let total = n as u64;
    let mut rank = vec![u32::MAX; n];
    let tick = 1u64 << 14;
    // Phase I: remove clusters from a copy of the relaxed pattern. Off texels are poisoned low
    // (their cluster key −E is then huge); the relaxation's lower bounds stay lower bounds.
    let relaxed = e.energy.clone();
    for (en, &on) in e.energy.iter_mut().zip(&e.on) {
        if !on {
            *en -= POISON;
        }
    }
    for r in (0..m).rev() {
        let p = e.take::<false, false, false>(&mut clusters);
        rank[p] = r as u32;
        e.splat(p, -1, |_, _| {});
        e.energy[p] -= POISON;
    }
    drop(clusters);
    e.energy = relaxed;
    progress(m as u64, total);

    // Phases II and III: fill voids, then the tightest clusters of the off texels, whose keys
    // are shifted by K(p) (a constant, so the same order, when every axis wraps). On texels are
    // poisoned high.
    for (en, &on) in e.energy.iter_mut().zip(&e.on) {
        if on {
            *en += POISON;
        }
    }
    let half = n / 2;
    let open = e.k_field.is_some();
    let mut voids = e.queue::<true, false, false>();
    for r in m..n {
        if r == half && open {
            voids = e.queue::<true, true, false>();
        }
        let p = if r >= half && open {
            e.take::<true, true, false>(&mut voids)
        } else {
            e.take::<true, false, false>(&mut voids)
        };
        rank[p] = r as u32;
        e.splat(p, 1, |_, _| {});
        e.energy[p] += POISON;
        if (r as u64 + 1).is_multiple_of(tick) {
            progress(r as u64 + 1, total);
        }
    }
    progress(total, total);
    (rank, stats)
}
