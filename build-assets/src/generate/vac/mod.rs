//! Void and cluster in D dimensions with axis groups (Ulichney 1993; Wolfe et al. 2022, §4.1
//! and Appendix B).
//!
//! One engine serves every preset: 2D blue noise is one group `{x, y}`; spatiotemporal blue noise
//! (STBN) is `{x, y} × {t}`; 2D×1D×1D is `{x, y} × {z} × {w}`; 2D×2D is `{x, y} × {z, w}`;
//! isotropic 3D blue noise is one group `{x, y, z}`. See [`kernel`] for the energy (eq. 15) and
//! [`engine`] for the phases and why no step rescans the volume.

pub mod engine;
pub mod kernel;
mod queue;
mod tree;

pub use crate::spec::vac::{DEFAULT_CUTOFF, Group};
pub use engine::{ProgressFn, RunStats};
pub use kernel::{Axis, Footprint};

/// Everything void and cluster needs to rank a mask.
#[derive(Clone, Debug, PartialEq)]
pub struct VacConfig {
    /// The axes, x first (fastest in memory).
    pub axes: Vec<Axis>,
    /// A partition of the axes into groups, each with its σ.
    pub groups: Vec<Group>,
    /// Fraction of texels in the initial binary pattern, in `(0, 0.5]`.
    pub initial_density: f64,
    /// Seed of the initial pattern and of the tie-breaking permutation.
    pub seed: u64,
    /// Gaussian truncation ([`DEFAULT_CUTOFF`]); 0 disables it (small masks only).
    pub cutoff: f64,
}

impl VacConfig {
    /// Total texel count.
    pub fn texels(&self) -> usize {
        self.axes.iter().map(|a| a.size).product()
    }
}

/// Ranks every texel: `result[i]` in `0..n` is the order in which texel `i` turns on.
pub fn rank(cfg: &VacConfig, progress: ProgressFn) -> (Vec<u32>, RunStats) {
    let fp = Footprint::new(&cfg.axes, &cfg.groups, cfg.cutoff);
    engine::rank(&cfg.axes, &fp, cfg.initial_density, cfg.seed, progress)
}

/// Re-ranks a volume ranking within each 2D slice (axes 0 and 1), so every slice holds each
/// rank `0..W·H` exactly once: the `histogram = "slice"` option. The relative order of texels
/// in a slice is the volume's.
pub fn rank_per_slice(ranks: &[u32], width: usize, height: usize) -> Vec<u32> {
    let s = width * height;
    let mut out = vec![0u32; ranks.len()];
    let mut idx: Vec<usize> = Vec::with_capacity(s);
    for (slice, chunk) in ranks.chunks(s).enumerate() {
        idx.clear();
        idx.extend(0..chunk.len());
        idx.sort_unstable_by_key(|&i| chunk[i]);
        for (r, &i) in idx.iter().enumerate() {
            out[slice * s + i] = r as u32;
        }
    }
    out
}
