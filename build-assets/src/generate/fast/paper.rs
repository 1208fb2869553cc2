//! The paper's own optimisation schedule (FAST §4.1), kept as a baseline for reports: what loss
//! its GPU run reaches, so the CPU optimiser ([`super::optimize`]) can be measured against it.
//!
//! Every iteration pairs all texels of each slice at random (the paper builds the pairing as an
//! involution `ρ = σ ∘ τ ∘ σ⁻¹` from a Feistel permutation; any uniformly random perfect
//! matching is the same distribution of pairs, and a shuffle gives one for any size), evaluates
//! every pair's ΔL (eq. 8) against the same state, as the GPU threads do, and performs a
//! fraction γ of the swaps that would lower the loss: γ starts at 1/8 and doubles, up to 1,
//! whenever the fraction of considered pairs that swapped drops below γ/4. Swaps made together
//! can raise the loss (their ΔL were computed apart); the curve records the exact loss every
//! `loss_every` iterations.
//!
//! Measured here (cosine hemisphere, box 5×5 × EMA, product; `noisebake report fast --paper`):
//! once γ reaches 1, over half of all pairs swap together each iteration, their ΔL undo each
//! other and the loss climbs back above its start, where it stays (32×32×8: −4768.8 at the
//! start, about −4715 from then on). With γ capped ([`Schedule::gamma_max`]) it converges: on
//! 64×64×16 and 2 threads, 10 000 iterations reach −55681.9 in 267–301 s at γ ≤ 1/8 (our
//! optimiser: the same loss after 13 s) and −55693.2 in 528–576 s at γ ≤ 1/4 (below where our
//! optimiser stops when baking, −55682.0 after 19 s; run on, it reaches −55693.2 after 28 s).
//!
//! The early rejection of [`super::optimize`]'s ΔL only ever rejects swaps that cannot lower the
//! loss, so it decides exactly as a full evaluation would.

use super::filter::Footprint;
use super::optimize::{CurvePoint, Outcome, Problem, to_state};
use crate::generate::rng::{SplitMix64, derive_seed, permutation};
use rayon::prelude::*;
use std::time::Instant;

/// How long to run the paper's schedule, and how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schedule {
    /// Iterations (the paper runs 10 000).
    pub iterations: u32,
    /// The exact loss is computed every this many iterations (and after the last).
    pub loss_every: u32,
    /// Largest γ: 1 is the paper's schedule; lower caps keep fewer swaps in flight at once.
    pub gamma_max: f64,
}

/// Runs the paper's schedule from `samples` (each slice already stratified).
/// `progress(iteration, iterations)` is called after each iteration.
pub fn optimize<const C: usize, D>(
    dims: [usize; 3],
    fp: &Footprint,
    samples: Vec<f64>,
    seed: u64,
    schedule: Schedule,
    progress: &mut dyn FnMut(u64, u64),
    dist: D,
) -> Outcome
where
    D: super::distance::Distance<C>,
{
    let Schedule {
        iterations,
        loss_every,
        gamma_max,
    } = schedule;
    let start = Instant::now();
    let [w, h, n] = dims;
    let state = to_state::<C>(&samples, dims);
    let problem = Problem::new(fp, dims, dist);
    let initial_loss = problem.loss(&state);
    let mut curve = Vec::new();
    let pairs = (w * h / 2 * n) as u64;
    if fp.is_empty() || pairs == 0 {
        return Outcome {
            samples,
            initial_loss,
            curve,
        };
    }
    let mut gamma = 0.125f64.min(gamma_max);
    let mut swapped_since = 0;
    for it in 0..iterations {
        // Per slice: a random matching, every pair's gain against the current state, and a
        // γ-thinned choice of the improving ones.
        let chosen: Vec<(u64, Vec<(usize, usize)>)> = (0..n)
            .into_par_iter()
            .map(|t| {
                let mut rng = SplitMix64::new(derive_seed(seed, ((it as u64) << 20) | t as u64));
                let order = permutation(w * h, &mut rng);
                let (mut candidates, mut out) = (0, Vec::new());
                for pair in order.chunks_exact(2) {
                    let (a, b) = (pair[0] as usize, pair[1] as usize);
                    if unit(&mut rng) >= gamma {
                        continue;
                    }
                    candidates += 1;
                    let (p, q) = ([a % w, a / w], [b % w, b / w]);
                    if problem
                        .gain(&state, p, q, t, f64::INFINITY)
                        .is_some_and(|g| g > 0.0)
                    {
                        out.push((problem.cell(p, t), problem.cell(q, t)));
                    }
                }
                (candidates, out)
            })
            .collect();
        let candidates: u64 = chosen.iter().map(|c| c.0).sum();
        let mut swapped = 0u64;
        for (i, j) in chosen.into_iter().flat_map(|c| c.1) {
            let (si, sj) = (state.load(i), state.load(j));
            state.store(i, sj);
            state.store(j, si);
            swapped += 1;
        }
        swapped_since += swapped;
        // "Double γ whenever the fraction of swaps drops below γ/4": swaps among the pairs
        // considered this iteration.
        if gamma < gamma_max && (swapped as f64) < gamma / 4.0 * candidates as f64 {
            gamma = (gamma * 2.0).min(gamma_max);
        }
        if (it + 1) % loss_every.max(1) == 0 || it + 1 == iterations {
            curve.push(CurvePoint {
                seconds: start.elapsed().as_secs_f64(),
                loss: problem.loss(&state),
                accepted: swapped_since,
            });
            swapped_since = 0;
        }
        progress(it as u64 + 1, iterations as u64);
    }
    Outcome {
        samples: state.into_samples(),
        initial_loss,
        curve,
    }
}

/// A uniform number in `[0, 1)` from the top 53 bits of a draw.
fn unit(rng: &mut SplitMix64) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}
