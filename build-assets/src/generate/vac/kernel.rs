//! The energy kernel of generalised void and cluster (STBN, Appendix B, eq. 15), in fixed point.
//!
//! Energy between texels `p` and `q` is a sum over axis groups `g`:
//! `E(p, q) = Σ_g [p_h = q_h] · exp(−‖p_g − q_g‖² / 2σ_g²)`, where `h` are the axes outside `g`
//! and distances wrap on toroidal axes. Each pairwise weight is quantised to an integer multiple
//! of `2^-shift` ([`quantize`], [`energy_scale`]), so energy fields are exact sums: independent of
//! summation order, free of drift over millions of updates, and identical between the fast engine
//! and the brute-force reference in the tests.
//!
//! Energies are [`Energy`] (`i32`): half the bytes of `i64`, which is what the large masks are
//! bound by (memory traffic; the large STBN bench case measured faster). The scale is chosen per mask so
//! that a texel's largest possible energy stays below `2^28`: `shift = 23` for STBN at σ 1.9.
//!
//! The fast engine truncates each group's Gaussian where it falls below a cutoff (offsets whose
//! weight is below `cutoff` are dropped). [`Footprint::dropped_weight`] is the exact bound on the
//! truncation error of any texel's energy, per unit of point density, and
//! [`Footprint::rounding_error`] the bound on its quantisation error.

use crate::spec::vac::Group;

/// A fixed-point energy (see [`energy_scale`]).
pub type Energy = i32;

/// Bound on the kernel summed over every texel (before rounding), leaving room below `2^30`
/// for the engine's poison offset.
const MAX_ENERGY: f64 = (1u64 << 28) as f64;

/// A Gaussian weight in fixed point: `round(w · scale)`.
pub fn quantize(w: f64, scale: f64) -> Energy {
    (w * scale).round() as Energy
}

/// The fixed-point scale of a mask's energies: the largest power of two with which the energy
/// of a texel whose every neighbour is on, `Σ_g Π_{a ∈ g} Σ_d exp(−d²/2σ_g²)` (untruncated, each
/// texel counted once), stays below `2^28`. A power of two, so `w · scale` is exact before
/// rounding; it depends on the axes and groups only, not on the truncation, so truncated and
/// untruncated footprints quantise alike.
pub fn energy_scale(axes: &[Axis], groups: &[Group]) -> f64 {
    let full: f64 = groups
        .iter()
        .map(|g| {
            g.axes
                .iter()
                .map(|&a| {
                    let (lo, hi) = offset_range(axes[a], i64::MAX / 4);
                    // Beyond 40σ the terms vanish in f64; the sum stays a bound.
                    let r = (40.0 * g.sigma).ceil() as i64;
                    (lo.max(-r)..=hi.min(r))
                        .map(|d| gaussian((d * d) as f64, g.sigma))
                        .sum::<f64>()
                })
                .product::<f64>()
        })
        .sum();
    // Rounding adds at most ½ per weight; the budget (at most 2^26 texels) keeps that below
    // another 2^25, so energies stay below 2^29.
    let shift = (MAX_ENERGY / full.max(1.0)).log2().floor().clamp(0.0, 30.0);
    shift.exp2()
}

/// `exp(−d² / 2σ²)` for a squared distance `d2`.
pub fn gaussian(d2: f64, sigma: f64) -> f64 {
    (-d2 / (2.0 * sigma * sigma)).exp()
}

/// One axis of a mask: its size and whether distances wrap around it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Axis {
    /// Number of texels along the axis.
    pub size: usize,
    /// Whether the axis wraps (distances are taken on the circle).
    pub toroidal: bool,
}

/// The range of signed offsets along an axis that reach every other texel exactly once (toroidal:
/// `-⌊(n−1)/2⌋ ..= ⌊n/2⌋`, so the offset's magnitude is the wrapped distance) or every texel of the
/// line (open axis: `-(n−1) ..= n−1`), clipped to `radius`.
pub fn offset_range(axis: Axis, radius: i64) -> (i64, i64) {
    let n = axis.size as i64;
    let (lo, hi) = if axis.toroidal {
        (-((n - 1) / 2), n / 2)
    } else {
        (-(n - 1), n - 1)
    };
    (lo.max(-radius), hi.min(radius))
}

/// The truncated kernel of one group: integer offsets along the group's axes and their weights.
#[derive(Clone, Debug)]
pub struct GroupFootprint {
    /// The group's axes.
    pub axes: Vec<usize>,
    /// Offsets, `axes.len()` values per entry, flattened.
    pub offsets: Vec<i32>,
    /// Fixed-point weight of each entry (all positive).
    pub weights: Vec<Energy>,
    /// Sum of the weights (f64, unquantised) of the offsets the truncation dropped.
    pub dropped: f64,
}

/// The truncated kernels of all groups of a mask.
#[derive(Clone, Debug)]
pub struct Footprint {
    /// One footprint per group.
    pub groups: Vec<GroupFootprint>,
    /// Fixed-point units per unit of Gaussian weight ([`energy_scale`]).
    pub scale: f64,
}

impl Footprint {
    /// Builds the footprints. `cutoff = 0` keeps every offset that reaches a distinct texel.
    pub fn new(axes: &[Axis], groups: &[Group], cutoff: f64) -> Self {
        let scale = energy_scale(axes, groups);
        let groups = groups
            .iter()
            .map(|g| GroupFootprint::new(axes, g, cutoff, scale))
            .collect();
        Self { groups, scale }
    }

    /// Number of (group, offset) entries touched by one splat.
    pub fn len(&self) -> usize {
        self.groups.iter().map(|g| g.weights.len()).sum()
    }

    /// Whether the footprint is empty (never, for a valid mask).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Upper bound on the truncation error of one texel's energy when every texel is on, in
    /// units of one Gaussian peak: the total weight of the dropped offsets.
    pub fn dropped_weight(&self) -> f64 {
        self.groups.iter().map(|g| g.dropped).sum()
    }

    /// Upper bound on the quantisation error of one texel's energy, in the same units: half a
    /// fixed-point step per footprint entry.
    pub fn rounding_error(&self) -> f64 {
        0.5 * self.len() as f64 / self.scale
    }
}

impl GroupFootprint {
    fn new(axes: &[Axis], group: &Group, cutoff: f64, scale: f64) -> Self {
        let radius = if cutoff > 0.0 {
            (-2.0 * group.sigma * group.sigma * cutoff.ln())
                .sqrt()
                .floor() as i64
        } else {
            i64::MAX / 4
        };
        let ranges: Vec<(i64, i64)> = group
            .axes
            .iter()
            .map(|&a| offset_range(axes[a], radius))
            .collect();
        let mut offsets = Vec::new();
        let mut weights = Vec::new();
        let mut dropped = 0.0;
        let mut d: Vec<i64> = ranges.iter().map(|r| r.0).collect();
        'outer: loop {
            let d2: f64 = d.iter().map(|&v| (v * v) as f64).sum();
            let w = gaussian(d2, group.sigma);
            if (cutoff <= 0.0 || w >= cutoff) && quantize(w, scale) > 0 {
                offsets.extend(d.iter().map(|&v| v as i32));
                weights.push(quantize(w, scale));
            } else {
                dropped += w;
            }
            // Odometer over the offset box (the whole torus when the cutoff is disabled, which
            // the engine allows for small masks only).
            for k in 0..d.len() {
                if d[k] < ranges[k].1 {
                    d[k] += 1;
                    continue 'outer;
                }
                d[k] = ranges[k].0;
            }
            break;
        }
        if cutoff > 0.0 {
            // Offsets outside the clipped box: their weight is below the cutoff; bound the sum
            // by the Gaussian's tail mass outside the radius along each axis.
            dropped += tail_bound(group.sigma, radius, group.axes.len());
        }
        Self {
            axes: group.axes.clone(),
            offsets,
            weights,
            dropped,
        }
    }
}

/// A bound on `Σ exp(−|d|²/2σ²)` over integer offsets with some `|d_i| > radius` in `dims`
/// dimensions: `dims · 2 · Σ_{k>radius} g(k) · (Σ_k g(k))^(dims−1)`.
fn tail_bound(sigma: f64, radius: i64, dims: usize) -> f64 {
    let line: f64 = (-200..=200)
        .map(|k: i64| gaussian((k * k) as f64, sigma))
        .sum();
    let tail: f64 = (radius + 1..radius + 200)
        .map(|k| gaussian((k * k) as f64, sigma))
        .sum();
    dims as f64 * 2.0 * tail * line.powi(dims as i32 - 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::vac::DEFAULT_CUTOFF;

    #[test]
    fn toroidal_offsets_reach_each_texel_once() {
        for n in 1..9 {
            let (lo, hi) = offset_range(
                Axis {
                    size: n,
                    toroidal: true,
                },
                100,
            );
            assert_eq!((hi - lo + 1) as usize, n);
        }
    }

    #[test]
    fn untruncated_footprint_covers_the_torus() {
        let axes = [
            Axis {
                size: 5,
                toroidal: true,
            },
            Axis {
                size: 4,
                toroidal: true,
            },
        ];
        let f = Footprint::new(
            &axes,
            &[Group {
                axes: vec![0, 1],
                sigma: 1.9,
            }],
            0.0,
        );
        assert_eq!(f.len(), 20);
        assert_eq!(f.dropped_weight(), 0.0);
    }

    #[test]
    fn truncation_drops_only_small_weights() {
        let axes = [
            Axis {
                size: 64,
                toroidal: true,
            },
            Axis {
                size: 64,
                toroidal: true,
            },
        ];
        let g = [Group {
            axes: vec![0, 1],
            sigma: 1.9,
        }];
        let f = Footprint::new(&axes, &g, DEFAULT_CUTOFF);
        let min = *f.groups[0].weights.iter().min().unwrap();
        assert!(min as f64 / f.scale >= DEFAULT_CUTOFF);
        let full = Footprint::new(&axes, &g, 0.0);
        let kept: f64 = f.groups[0]
            .weights
            .iter()
            .map(|&w| w as f64 / f.scale)
            .sum();
        let all: f64 = full.groups[0]
            .weights
            .iter()
            .map(|&w| w as f64 / f.scale)
            .sum();
        assert!(f.dropped_weight() >= all - kept - full.rounding_error());
        assert!(f.dropped_weight() < 0.05, "{}", f.dropped_weight());
    }

    #[test]
    fn scale_keeps_a_full_neighbourhood_below_the_poison() {
        let axis = |size| Axis {
            size,
            toroidal: true,
        };
        let g = |axes: &[usize], sigma| Group {
            axes: axes.to_vec(),
            sigma,
        };
        // STBN at σ 1.9: 2πσ² + √(2π)σ ≈ 27.4, so 2^23 units per unit weight.
        let stbn = [axis(64), axis(64), axis(16)];
        let stbn_groups = [g(&[0, 1], 1.9), g(&[2], 1.9)];
        assert_eq!(energy_scale(&stbn, &stbn_groups), (1u64 << 23) as f64);
        for (axes, groups) in [
            (&stbn[..], &stbn_groups[..]),
            (&[axis(3), axis(2)][..], &[g(&[0, 1], 0.1)][..]),
            (
                &[axis(40), axis(40), axis(40)][..],
                &[g(&[0, 1, 2], 100.0)][..],
            ),
        ] {
            let full = Footprint::new(axes, groups, 0.0);
            let sum: i64 = full
                .groups
                .iter()
                .flat_map(|g| &g.weights)
                .map(|&w| w as i64)
                .sum();
            assert!(sum <= 1 << 28, "{sum}");
            assert!(sum > 1 << 26, "the scale wastes precision: {sum}");
        }
    }
}
