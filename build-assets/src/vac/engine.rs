//! The fast void-and-cluster engine: local splats on a fixed-point energy field and lazy
//! priority queues, so no step rescans the volume.
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
//! Ties between equal energies are broken by a seeded random permutation (lowest rank wins),
//! never by memory order, so no raster pattern can appear.
//!
//! Speed: a splat touches only the truncated footprint of each group, and candidates wait in a
//! [`CandidateQueue`] with *lazy* keys. In phases I–III energies move one way only (they fall
//! while clusters are removed, rise while voids are filled), so a queued key is a bound on the
//! true key and is refreshed in place when it reaches the top. During relaxation energies move
//! both ways; every change that improves a candidate queues a fresh key. Energy, tie rank and
//! state of a texel share one 16-byte record, so validating a key costs one cache line.

use super::kernel::{Axis, Footprint};
use super::queue::{CandidateQueue, key_index};
use crate::rng::{SplitMix64, permutation};

const INVALID: u32 = u32::MAX;

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
    texels: Vec<Texel>,
    /// `K(p)` when axes are open (it varies near borders); `None` when it is constant.
    k_field: Option<Vec<i64>>,
}

/// One texel's state: fixed-point energy, tie-break rank, on/off.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(16))]
struct Texel {
    energy: i64,
    tie: u32,
    on: bool,
}

fn bias(key: i64) -> u64 {
    (key as u64) ^ (1 << 63)
}

fn pack(key: i64, tie: u32, idx: usize) -> u128 {
    (bias(key) as u128) << 64 | (tie as u128) << 32 | idx as u128
}

impl<'f> Engine<'f> {
    pub(crate) fn new(axes: &[Axis], fp: &'f Footprint, tie: Vec<u32>) -> Self {
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
            texels: tie
                .iter()
                .map(|&t| Texel {
                    energy: 0,
                    tie: t,
                    on: false,
                })
                .collect(),
            k_field: None,
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

    /// Visits `(q, weight)` for every footprint entry of `p` that lands inside the mask.
    #[inline(always)]
    fn for_each(&self, p: usize, mut f: impl FnMut(usize, i64)) {
        let mut coord = [0usize; 8];
        for (c, (&stride, &size)) in coord.iter_mut().zip(self.strides.iter().zip(&self.sizes)) {
            *c = (p / stride) % size;
        }
        for g in &self.fp.groups {
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
                                [(coord[a] as isize + o[j] as isize) as usize + self.pad[a]];
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
    }

    /// Turns `p` on or off and updates the energy field; `visit(q, on)` sees every touched texel.
    #[inline(always)]
    fn toggle(&mut self, p: usize, turn_on: bool, mut visit: impl FnMut(usize, bool)) {
        self.texels[p].on = turn_on;
        let sign = if turn_on { 1 } else { -1 };
        // Split borrows: the footprint walk reads tables, the closure writes texels.
        let mut texels = std::mem::take(&mut self.texels);
        self.for_each(p, |q, w| {
            let t = &mut texels[q];
            t.energy += sign * w;
            visit(q, t.on);
        });
        self.texels = texels;
    }

    /// Key of an off texel: lowest energy first (phase III: lowest `F(p) − K(p)`), ties by rank.
    #[inline(always)]
    fn void_key(&self, p: usize, phase3: bool) -> u128 {
        let t = &self.texels[p];
        let e = match (&self.k_field, phase3) {
            (Some(k), true) => t.energy - k[p],
            _ => t.energy,
        };
        pack(e, t.tie, p)
    }

    /// Key of an on texel: highest energy first, ties by rank.
    #[inline(always)]
    fn cluster_key(&self, p: usize) -> u128 {
        let t = &self.texels[p];
        pack(-t.energy, t.tie, p)
    }

    fn key(&self, p: usize, voids: bool, phase3: bool) -> u128 {
        if voids {
            self.void_key(p, phase3)
        } else {
            self.cluster_key(p)
        }
    }

    /// A queue of every off texel (`voids`) or every on texel, with fresh keys.
    fn queue(&self, voids: bool, phase3: bool) -> CandidateQueue {
        let n = self.texels.len();
        let keys = (0..n)
            .filter(|&p| self.texels[p].on != voids)
            .map(|p| self.key(p, voids, phase3));
        CandidateQueue::new(n, keys)
    }

    /// Takes the best candidate out of a lazy queue: an off texel when `voids`, else an on one.
    /// A stale key that underestimates the texel is refreshed in place; one that overestimates it
    /// is dropped (a fresher key is queued already).
    fn take(&self, q: &mut CandidateQueue, voids: bool, phase3: bool) -> usize {
        while let Some(k) = q.peek() {
            let p = key_index(k);
            if self.texels[p].on == voids {
                q.pop();
                continue;
            }
            let cur = self.key(p, voids, phase3);
            if cur == k {
                q.pop();
                return p;
            }
            if cur > k {
                q.refresh_top(cur);
            } else {
                q.pop();
            }
        }
        unreachable!("the queue holds every candidate texel")
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
    let tie = permutation(n, &mut rng);
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

    // Initial binary pattern: the first m texels of a random permutation (no duplicates).
    let order = permutation(n, &mut rng);
    for &p in &order[..m] {
        e.toggle(p as usize, true, |_, _| {});
    }
    drop(order);

    // Relaxation: tightest cluster -> largest void until the two coincide. Removing a point
    // lowers energies (better voids: queue them); adding one raises them (tighter clusters).
    let mut clusters = e.queue(false, false);
    let mut voids = e.queue(true, false);
    let cap = 64 * m + 4096;
    let mut fresh = Vec::new();
    loop {
        let p = e.take(&mut clusters, false, false);
        e.toggle(p, false, |q, on| {
            if !on {
                fresh.push(q);
            }
        });
        for q in fresh.drain(..) {
            voids.push(e.void_key(q, false));
        }
        let q = e.take(&mut voids, true, false);
        e.toggle(q, true, |r, on| {
            if on {
                fresh.push(r);
            }
        });
        for r in fresh.drain(..) {
            clusters.push(e.cluster_key(r));
        }
        if q == p {
            break;
        }
        stats.relaxation_swaps += 1;
        if stats.relaxation_swaps >= cap {
            stats.relaxation_capped = true;
            break;
        }
        if voids.len() > 3 * n + 4096 {
            voids = e.queue(true, false);
        }
        if clusters.len() > 3 * n + 4096 {
            clusters = e.queue(false, false);
        }
    }
    drop(voids);

    let total = n as u64;
    let mut rank = vec![u32::MAX; n];
    let tick = 1u64 << 14;
    // Phase I: remove clusters from a copy of the relaxed pattern (energies only fall).
    let saved = e.texels.clone();
    for r in (0..m).rev() {
        let p = e.take(&mut clusters, false, false);
        rank[p] = r as u32;
        e.toggle(p, false, |_, _| {});
    }
    drop(clusters);
    e.texels = saved;
    progress(m as u64, total);

    // Phases II and III: fill voids, then the tightest clusters of the off texels, whose keys
    // are shifted by K(p) (a constant, so the same order, when every axis wraps).
    let half = n / 2;
    let mut voids = e.queue(true, false);
    for r in m..n {
        let phase3 = r >= half && e.k_field.is_some();
        if r == half && phase3 {
            voids = e.queue(true, true);
        }
        let p = e.take(&mut voids, true, phase3);
        rank[p] = r as u32;
        e.toggle(p, true, |_, _| {});
        if (r as u64 + 1).is_multiple_of(tick) {
            progress(r as u64 + 1, total);
        }
    }
    progress(total, total);
    (rank, stats)
}
