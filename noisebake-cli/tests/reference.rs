//! The fast engine against an exact, obviously-correct reference: every pairwise energy of
//! eq. 15 computed from its formula (full toroidal or open distances, no truncation, no
//! locality), full linear scans for every arg-min / arg-max, the phases written out plainly.
//! Energies are the same fixed-point quantisation the engine uses (`kernel::quantize` at
//! `kernel::energy_scale`), so sums
//! are exact and the comparison can demand identical rankings.

use build_assets::generate::rng::{SplitMix64, TieRank, sample_distinct};
use build_assets::generate::vac::kernel::{energy_scale, gaussian, quantize};
use build_assets::generate::vac::{self, Axis, DEFAULT_CUTOFF, Footprint, Group, VacConfig};

struct Reference<'a> {
    /// Fixed-point units per unit weight.
    scale: f64,
    axes: &'a [Axis],
    groups: &'a [Group],
    coords: Vec<Vec<usize>>,
}

impl Reference<'_> {
    /// E(p, q) of STBN eq. 15: the sum over groups of a Gaussian in the group's axes, counted
    /// only when every other axis matches.
    fn energy(&self, p: usize, q: usize) -> i64 {
        let (cp, cq) = (&self.coords[p], &self.coords[q]);
        let mut e = 0;
        for g in self.groups {
            let others_equal = (0..self.axes.len())
                .filter(|a| !g.axes.contains(a))
                .all(|a| cp[a] == cq[a]);
            if !others_equal {
                continue;
            }
            let d2: f64 = g
                .axes
                .iter()
                .map(|&a| {
                    let d = cp[a].abs_diff(cq[a]);
                    let d = if self.axes[a].toroidal {
                        d.min(self.axes[a].size - d)
                    } else {
                        d
                    };
                    (d * d) as f64
                })
                .sum();
            e += quantize(gaussian(d2, g.sigma), self.scale) as i64;
        }
        e
    }
}

fn reference_rank(cfg: &VacConfig) -> Vec<u32> {
    let n = cfg.texels();
    let mut coords = Vec::with_capacity(n);
    for i in 0..n {
        let mut rest = i;
        coords.push(
            cfg.axes
                .iter()
                .map(|a| {
                    let c = rest % a.size;
                    rest /= a.size;
                    c
                })
                .collect(),
        );
    }
    let r = Reference {
        scale: energy_scale(&cfg.axes, &cfg.groups),
        axes: &cfg.axes,
        groups: &cfg.groups,
        coords,
    };
    let mut rng = SplitMix64::new(cfg.seed);
    let tie_rank = TieRank::new(&mut rng);
    let tie: Vec<u32> = (0..n as u32).map(|i| tie_rank.of(i)).collect();
    let m = ((cfg.initial_density * n as f64).round() as usize).clamp(1, (n / 2).max(1));
    let order = sample_distinct(n, m, &mut rng);
    let mut on = vec![false; n];
    let mut field = vec![0i64; n];
    let toggle = |on: &mut Vec<bool>, field: &mut Vec<i64>, p: usize, state: bool| {
        on[p] = state;
        for (q, f) in field.iter_mut().enumerate() {
            let e = r.energy(p, q);
            *f += if state { e } else { -e };
        }
    };
    // The energy every texel would give p (for phase III: the field of the off texels is
    // K(p) − F(p)).
    let k: Vec<i64> = (0..n)
        .map(|p| (0..n).map(|q| r.energy(p, q)).sum())
        .collect();
    // Tightest cluster: largest F among on texels; largest void: smallest key among off texels.
    // Ties: lowest tie rank.
    let cluster = |on: &[bool], field: &[i64]| {
        (0..n)
            .filter(|&p| on[p])
            .max_by(|&a, &b| field[a].cmp(&field[b]).then(tie[b].cmp(&tie[a])))
            .unwrap()
    };
    let void = |on: &[bool], key: &dyn Fn(usize) -> i64| {
        (0..n)
            .filter(|&p| !on[p])
            .min_by(|&a, &b| key(a).cmp(&key(b)).then(tie[a].cmp(&tie[b])))
            .unwrap()
    };
    for &p in &order {
        toggle(&mut on, &mut field, p as usize, true);
    }
    let cap = 64 * m + 4096;
    for _ in 0..cap {
        let p = cluster(&on, &field);
        toggle(&mut on, &mut field, p, false);
        let f = field.clone();
        let q = void(&on, &|i| f[i]);
        toggle(&mut on, &mut field, q, true);
        if q == p {
            break;
        }
    }
    let mut rank = vec![u32::MAX; n];
    let (saved_on, saved_field) = (on.clone(), field.clone());
    for rnk in (0..m).rev() {
        let p = cluster(&on, &field);
        rank[p] = rnk as u32;
        toggle(&mut on, &mut field, p, false);
    }
    (on, field) = (saved_on, saved_field);
    for rnk in m..n {
        let f = field.clone();
        let p = if rnk < n / 2 {
            void(&on, &|i| f[i])
        } else {
            void(&on, &|i| f[i] - k[i])
        };
        rank[p] = rnk as u32;
        toggle(&mut on, &mut field, p, true);
    }
    rank
}

fn config(
    sizes: &[usize],
    toroidal: bool,
    groups: Vec<Group>,
    cutoff: f64,
    seed: u64,
) -> VacConfig {
    VacConfig {
        axes: sizes.iter().map(|&size| Axis { size, toroidal }).collect(),
        groups,
        initial_density: 0.1,
        seed,
        cutoff,
    }
}

fn g(axes: &[usize]) -> Group {
    Group {
        axes: axes.to_vec(),
        sigma: 1.9,
    }
}

fn assert_same(cfg: &VacConfig) {
    let fast = vac::rank(cfg, &mut |_, _| {}).0;
    let slow = reference_rank(cfg);
    let differ = fast.iter().zip(&slow).filter(|(a, b)| a != b).count();
    assert_eq!(
        differ,
        0,
        "{differ} of {} ranks differ for {cfg:?}",
        fast.len()
    );
    let mut sorted = fast.clone();
    sorted.sort_unstable();
    assert!(
        sorted.iter().enumerate().all(|(i, &r)| r == i as u32),
        "ranks are a permutation"
    );
}

#[test]
fn stbn_16x16x8_matches_the_reference_exactly() {
    for seed in 0..3 {
        assert_same(&config(
            &[16, 16, 8],
            true,
            vec![g(&[0, 1]), g(&[2])],
            0.0,
            seed,
        ));
    }
}

#[test]
fn two_d_by_one_d_by_one_d_8x8x4x4_matches_the_reference_exactly() {
    assert_same(&config(
        &[8, 8, 4, 4],
        true,
        vec![g(&[0, 1]), g(&[2]), g(&[3])],
        0.0,
        5,
    ));
}

#[test]
fn two_d_by_two_d_and_isotropic_3d_match_the_reference_exactly() {
    assert_same(&config(
        &[8, 8, 4, 4],
        true,
        vec![g(&[0, 1]), g(&[2, 3])],
        0.0,
        6,
    ));
    assert_same(&config(&[8, 8, 8], true, vec![g(&[0, 1, 2])], 0.0, 7));
}

#[test]
fn open_axes_and_odd_sizes_match_the_reference_exactly() {
    // Non-toroidal axes make K(p) vary, which exercises the phase III key.
    assert_same(&config(
        &[13, 11, 5],
        false,
        vec![g(&[0, 1]), g(&[2])],
        0.0,
        8,
    ));
    assert_same(&config(&[9, 7], true, vec![g(&[0, 1])], 0.0, 9));
}

#[test]
fn the_truncated_kernel_matches_the_reference_where_it_covers_the_torus() {
    // At σ 1.9 the default cutoff keeps offsets up to radius 7: on a 12×12×6 torus every offset
    // reaches, so truncation drops nothing that exists.
    let cfg = config(
        &[12, 12, 6],
        true,
        vec![g(&[0, 1]), g(&[2])],
        DEFAULT_CUTOFF,
        4,
    );
    let fp = Footprint::new(&cfg.axes, &cfg.groups, DEFAULT_CUTOFF);
    let full = Footprint::new(&cfg.axes, &cfg.groups, 0.0);
    if fp.len() == full.len() {
        assert_same(&cfg);
    } else {
        // Some far corner offsets fall below the cutoff: the bound must say how much.
        assert!(
            fp.dropped_weight() > 0.0 && fp.dropped_weight() < 0.01,
            "{}",
            fp.dropped_weight()
        );
    }
}

/// Where truncation does drop offsets (large masks), its error per texel is bounded by the
/// dropped weight (plus the fixed-point rounding), and quality (spatial and temporal low-frequency power) is unchanged.
#[test]
fn truncation_error_is_bounded_and_quality_is_unchanged() {
    use build_assets::encoding::{Format, encode_ranks};
    use noisebake_cli::analysis::analyze;
    let sizes = [48, 48, 8];
    let groups = vec![g(&[0, 1]), g(&[2])];
    let axes: Vec<Axis> = sizes
        .iter()
        .map(|&size| Axis {
            size,
            toroidal: true,
        })
        .collect();
    let fp = Footprint::new(&axes, &groups, DEFAULT_CUTOFF);
    // Relative to the energy of a texel whose whole neighbourhood is on (≈ 2πσ² + √(2π)σ ≈ 27).
    let full_energy: f64 = Footprint::new(&axes, &groups, 0.0)
        .groups
        .iter()
        .flat_map(|g| &g.weights)
        .map(|&w| w as f64 / fp.scale)
        .sum();
    let bound = (fp.dropped_weight() + fp.rounding_error()) / full_energy;
    assert!(
        bound < 2e-3,
        "truncation and rounding may move an energy by {bound} of its full-neighbourhood value"
    );
    let report = |cutoff: f64| {
        let (mut s, mut t) = (0.0, 0.0);
        for seed in 0..3 {
            let cfg = config(&sizes, true, groups.clone(), cutoff, seed);
            let r = vac::rank(&cfg, &mut |_, _| {}).0;
            let tex = build_assets::Texture {
                name: "t".into(),
                dims: sizes.to_vec(),
                format: Format::U16,
                data: encode_ranks(&r, r.len() as u32, Format::U16.scalar),
            };
            let a = analyze(&tex);
            s += a.spatial_lf_mean;
            t += a.temporal_lf.unwrap();
        }
        (s / 3.0, t / 3.0)
    };
    let (s_fast, t_fast) = report(DEFAULT_CUTOFF);
    let (s_full, t_full) = report(0.0);
    eprintln!(
        "truncated: spatial {s_fast:.5} temporal {t_fast:.5}; full: spatial {s_full:.5} temporal {t_full:.5}; bound {bound:.2e}"
    );
    assert!(
        s_fast < 1.5 * s_full && t_fast < 1.25 * t_full,
        "truncation changed quality"
    );
}
