//! Void-and-cluster generation time at the sizes the engine issue names (single thread), with
//! the kernel's truncation and rounding bounds printed beside each: the speed and the error it was bought with.
//!
//! `cargo bench -p noisebake-cli --bench vac`

use build_assets::generate::vac::{self, Axis, DEFAULT_CUTOFF, Footprint, Group, VacConfig};
use criterion::{Criterion, criterion_group, criterion_main};
use std::time::Duration;

fn config(sizes: &[usize], groups: &[&[usize]]) -> VacConfig {
    VacConfig {
        axes: sizes
            .iter()
            .map(|&size| Axis {
                size,
                toroidal: true,
            })
            .collect(),
        groups: groups
            .iter()
            .map(|a| Group {
                axes: a.to_vec(),
                sigma: 1.9,
            })
            .collect(),
        initial_density: 0.1,
        seed: 7,
        cutoff: DEFAULT_CUTOFF,
    }
}

fn bench(c: &mut Criterion) {
    let cases: [(&str, VacConfig, usize); 4] = [
        ("blue2d_64x64", config(&[64, 64], &[&[0, 1]]), 50),
        ("stbn_64x64x16", config(&[64, 64, 16], &[&[0, 1], &[2]]), 20),
        (
            "stbn_128x128x64",
            config(&[128, 128, 64], &[&[0, 1], &[2]]),
            10,
        ),
        (
            "vac_2x1x1_64x64x16x16",
            config(&[64, 64, 16, 16], &[&[0, 1], &[2], &[3]]),
            10,
        ),
    ];
    let mut g = c.benchmark_group("void_and_cluster");
    for (name, cfg, samples) in cases {
        let fp = Footprint::new(&cfg.axes, &cfg.groups, cfg.cutoff);
        let full: f64 = Footprint::new(&cfg.axes, &cfg.groups, 0.0)
            .groups
            .iter()
            .flat_map(|g| &g.weights)
            .map(|&w| w as f64 / fp.scale)
            .sum();
        eprintln!(
            "{name}: footprint {} entries; truncation error ≤ {:.2e} and rounding error ≤ {:.2e} of a full neighbourhood's energy (exact reference: identical ranks where nothing is dropped)",
            fp.len(),
            fp.dropped_weight() / full,
            fp.rounding_error() / full
        );
        g.sample_size(samples)
            .measurement_time(Duration::from_secs(if samples == 10 { 60 } else { 5 }));
        g.bench_function(name, |b| b.iter(|| vac::rank(&cfg, &mut |_, _| {})));
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
