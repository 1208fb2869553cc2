//! Curl-noise jittering speed (single thread unless named), next to the quality it buys
//! (`noisebake report cnj`: ν_eff, ā, q): the direct 1000-point set (the paper's Python: 62 ms
//! per set in Table 2, 181 ms measured here), implicit closest-point queries in 2D and 3D in
//! random and coherent order, Worley F1 on CNJ points against `noise-functions`' Worley on a
//! plain jittered grid, and a 1920×1080 CNJ Worley image through the region cache on 2 threads.
//!
//! `cargo bench -p noisebake-cli --bench cnj`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use noise_runtime::cnj::{Cnj2, Cnj3};
use noisebake_cli::points::{Method, generate};
use rayon::prelude::*;
use std::hint::black_box;
use std::time::Duration;

fn queries(n: usize, scale: f32) -> Vec<[f32; 3]> {
    let mut rng = noisebake_test_support::Rng(0x51_7cc1_b727_220a);
    let mut next = move || rng.unit_f32() * scale;
    (0..n).map(|_| [next(), next(), next()]).collect()
}

fn cnj(c: &mut Criterion) {
    let mut g = c.benchmark_group("cnj");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    g.bench_function("direct 1000-point set", |b| {
        b.iter(|| generate(Method::Cnj, 1000, black_box(1)))
    });
    let c2 = Cnj2::default();
    let c3 = Cnj3::default();
    let random = queries(1024, 1000.0);
    let coherent: Vec<[f32; 3]> = (0..1024)
        .map(|i| [(i % 32) as f32 * 0.1, (i / 32) as f32 * 0.1, 0.3])
        .collect();
    g.throughput(Throughput::Elements(1024));
    g.bench_function("closest 2D random", |b| {
        b.iter(|| {
            random
                .iter()
                .map(|q| c2.closest([q[0], q[1]]).distance)
                .sum::<f32>()
        })
    });
    g.bench_function("closest 2D coherent", |b| {
        b.iter(|| {
            coherent
                .iter()
                .map(|q| c2.closest([q[0], q[1]]).distance)
                .sum::<f32>()
        })
    });
    let few = &random[..64];
    g.throughput(Throughput::Elements(64));
    g.bench_function("closest 3D random", |b| {
        b.iter(|| few.iter().map(|q| c3.closest(*q).distance).sum::<f32>())
    });
    g.bench_function("closest 3D coherent", |b| {
        b.iter(|| {
            coherent[..64]
                .iter()
                .map(|q| c3.closest(*q).distance)
                .sum::<f32>()
        })
    });
    {
        use noise_functions::{CellDistance, Noise};
        let cell = CellDistance::default();
        g.throughput(Throughput::Elements(1024));
        g.bench_function("worley F1 2D noise-functions (jittered grid)", |b| {
            b.iter(|| {
                random
                    .iter()
                    .map(|q| cell.sample2([q[0], q[1]]))
                    .sum::<f32>()
            })
        });
        g.bench_function("worley F1 3D noise-functions (jittered grid)", |b| {
            b.iter(|| random.iter().map(|q| cell.sample3(*q)).sum::<f32>())
        });
        g.bench_function("worley F1 2D cnj", |b| {
            b.iter(|| {
                random
                    .iter()
                    .map(|q| c2.closest([q[0], q[1]]).distance)
                    .sum::<f32>()
            })
        });
    }
    // A 1920×1080 frame: cache the sites once (rows in parallel), then F1 per pixel on 2 threads.
    let c = Cnj2::default().with_spacing(12.0).unwrap();
    let (origin, dims) = c.region_dims([0.0, 0.0], [1920.0, 1080.0]);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    g.throughput(Throughput::Elements(1920 * 1080));
    g.bench_function("1920x1080 worley image, region cache, 2 threads", |b| {
        b.iter(|| {
            pool.install(|| {
                let mut buf = vec![[0.0f32; 2]; dims[0] * dims[1]];
                buf.par_chunks_mut(dims[0] * 8)
                    .enumerate()
                    .for_each(|(k, rows)| {
                        c.fill_rows(origin, dims, k * 8, rows);
                    });
                let region = noise_runtime::cnj::Region2::from_parts(c, origin, dims, &buf);
                let mut img = vec![0.0f32; 1920 * 1080];
                img.par_chunks_mut(1920).enumerate().for_each(|(y, row)| {
                    region.f1_row(y as f32 + 0.5, 0.5, 1.0, row);
                });
                img
            })
        })
    });
    g.finish();
}

criterion_group!(benches, cnj);
criterion_main!(benches);
