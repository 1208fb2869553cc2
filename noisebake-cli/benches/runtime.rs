//! Runtime lookups against hand indexing (noise-runtime issue): `Mask3::get` / `get_k` on a
//! 128×128×64 u16 mask vs `u16::from_le_bytes` on the same bytes with `&` wrapping, and the
//! low-discrepancy grids, and one value of a 128×128 sampler tile (4 spp, 4 dimensions: a
//! lattice pair and a Sobol pair) beside the free samplers `rd_ign_r2`, `r2_pairs`,
//! `motion_pairs` and `sobol_owen`, ns per
//! lookup. Exactness is tested in noise-runtime's tests.
//!
//! `cargo bench -p noisebake-cli --bench runtime`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use noise_runtime::{Mask3, SamplerTile, ldg, sampler};
use std::hint::black_box;
use std::time::Duration;

fn lookups(c: &mut Criterion) {
    let bytes: &'static [u8] = Box::leak(
        (0..128 * 128 * 64 * 2)
            .map(|i| (i * 7 % 251) as u8)
            .collect::<Vec<u8>>()
            .into_boxed_slice(),
    );
    let mask: Mask3<u16, 128, 128, 64> = Mask3::new(bytes);
    let coords: Vec<(i32, i32, i32)> = (0..4096)
        .map(|i: i32| ((i * 37) % 300 - 100, (i * 91) % 260 - 70, (i * 13) % 200))
        .collect();
    let mut g = c.benchmark_group("runtime");
    g.measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    g.throughput(Throughput::Elements(coords.len() as u64));
    g.bench_function("hand indexing u16 128x128x64", |b| {
        b.iter(|| {
            coords
                .iter()
                .map(|&(x, y, t)| {
                    let i = (((t & 63) * 128 + (y & 127)) * 128 + (x & 127)) as usize * 2;
                    u16::from_le_bytes([bytes[i], bytes[i + 1]]) as u32
                })
                .sum::<u32>()
        })
    });
    g.bench_function("Mask3::get u16 128x128x64", |b| {
        b.iter(|| {
            coords
                .iter()
                .map(|&(x, y, t)| mask.get(x, y, t) as u32)
                .sum::<u32>()
        })
    });
    g.bench_function("Mask3::get_k (k = 5) u16 128x128x64", |b| {
        b.iter(|| {
            coords
                .iter()
                .map(|&(x, y, t)| mask.get_k(x, y, t, black_box(5)) as u32)
                .sum::<u32>()
        })
    });
    g.bench_function("ldg::r2", |b| {
        b.iter(|| coords.iter().map(|&(x, y, _)| ldg::r2(x, y)).sum::<f32>())
    });
    g.bench_function("ldg::plus", |b| {
        b.iter(|| coords.iter().map(|&(x, y, _)| ldg::plus(x, y)).sum::<f32>())
    });
    g.bench_function("ldg::ign", |b| {
        b.iter(|| coords.iter().map(|&(x, y, _)| ldg::ign(x, y)).sum::<f32>())
    });
    g.bench_function("ldg::bayer::<8>", |b| {
        b.iter(|| {
            coords
                .iter()
                .map(|&(x, y, _)| ldg::bayer::<8>(x, y))
                .sum::<f32>()
        })
    });
    g.bench_function("ldg::r2_frame", |b| {
        b.iter(|| {
            coords
                .iter()
                .map(|&(x, y, t)| ldg::r2_frame(x, y, t as u32))
                .sum::<f32>()
        })
    });
    // One value of a sampler tile: pixel, frame, sample and dimension vary per lookup.
    let tile: SamplerTile<128, 128, 4, 4> =
        SamplerTile::new(Mask3::new(&bytes[..128 * 128 * 4 * 2]), black_box(0b10));
    let reads: Vec<(i32, i32, u32, u32, u32)> = coords
        .iter()
        .enumerate()
        .map(|(k, &(x, y, t))| (x, y, t as u32, k as u32 % 4, (k as u32 / 4) % 4))
        .collect();
    g.bench_function("SamplerTile::sample 128x128 spp 4 D 4", |b| {
        b.iter(|| {
            reads
                .iter()
                .map(|&(x, y, f, i, d)| tile.sample(x, y, f, i, d))
                .sum::<f32>()
        })
    });
    g.bench_function("SamplerTile::sample, lattice pair (d 0)", |b| {
        b.iter(|| {
            reads
                .iter()
                .map(|&(x, y, f, i, _)| tile.sample(x, y, f, i, 0))
                .sum::<f32>()
        })
    });
    g.bench_function("SamplerTile::sample, Sobol pair (d 3)", |b| {
        b.iter(|| {
            reads
                .iter()
                .map(|&(x, y, f, i, _)| tile.sample(x, y, f, i, 3))
                .sum::<f32>()
        })
    });
    g.bench_function("sampler::rd_ign_r2::<2> (per value)", |b| {
        b.iter(|| {
            reads
                .iter()
                .map(|&(x, y, f, i, _)| sampler::rd_ign_r2::<2>(x, y, f * 4 + i)[0])
                .sum::<f32>()
        })
    });
    g.bench_function("sampler::r2_pairs::<2> (per value)", |b| {
        b.iter(|| {
            reads
                .iter()
                .map(|&(x, y, f, i, _)| sampler::r2_pairs::<2>(x, y, f * 4 + i)[0])
                .sum::<f32>()
        })
    });
    g.bench_function("sampler::motion_pairs::<2> spp 4 (per value)", |b| {
        b.iter(|| {
            reads
                .iter()
                .map(|&(x, y, f, i, _)| sampler::motion_pairs::<2>(x, y, f, i, black_box(4))[0])
                .sum::<f32>()
        })
    });
    g.bench_function("sampler::motion_pairs::<4> spp 4 (four values)", |b| {
        b.iter(|| {
            reads
                .iter()
                .map(|&(x, y, f, i, _)| {
                    sampler::motion_pairs::<4>(x, y, f, i, black_box(4))
                        .iter()
                        .sum::<f32>()
                })
                .sum::<f32>()
        })
    });
    g.bench_function("sampler::sobol_owen::<2> (per value)", |b| {
        b.iter(|| {
            reads
                .iter()
                .map(|&(x, y, f, i, _)| sampler::sobol_owen::<2>(x, y, f * 4 + i, 1)[0])
                .sum::<f32>()
        })
    });
    g.finish();
}

criterion_group!(benches, lookups);
criterion_main!(benches);
