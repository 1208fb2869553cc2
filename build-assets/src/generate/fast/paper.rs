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
//! What `noisebake report fast --paper` measures (cosine hemisphere, box 5×5 × EMA, product):
//! once γ reaches 1, over half of all pairs swap together each iteration, their ΔL undo each
//! other and the loss climbs back above its start, where it stays. With γ capped
//! ([`Schedule::gamma_max`]) it converges, but its 10 000 iterations take over ten times as
//! long as [`super::optimize`] needs for the same loss.
//!
//! The early rejection of [`super::optimize`]'s ΔL only ever rejects swaps that cannot lower the
//! loss, so it decides exactly as a full evaluation would.

use super::filter::Footprint;
use super::optimize::{CurvePoint, Outcome, Run};
use crate::generate::rng::{SplitMix64, derive_seed, permutation};
use rayon::prelude::*;

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
/// `progress(iteration, iterations)` is called after each iteration. The start's loss is always
/// measured: the schedule's swaps can raise the loss, so its curve is of exact losses.
pub fn run_schedule<const C: usize, D>(
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
    let [w, h, n] = dims;
    let run = match Run::start(dims, fp, samples, dist, true) {
        Ok(run) => run,
        Err(done) => return done,
    };
    let (state, problem) = (&run.state, &run.problem);
    let initial_loss = run.initial_loss.expect("measured");
    let mut curve = Vec::new();
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
                        .gain(state, p, q, t, f64::INFINITY)
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
                seconds: run.seconds(),
                decrease: initial_loss - problem.loss(state),
                accepted: swapped_since,
            });
            swapped_since = 0;
        }
        progress(it as u64 + 1, iterations as u64);
    }
    run.finish(curve)
}

/// A uniform number in `[0, 1)` from the top 53 bits of a draw.
fn unit(rng: &mut SplitMix64) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}
