//! Runtime lookups against hand indexing (noise-runtime issue): `Mask3::get` / `get_k` on a
//! 128×128×64 u16 mask vs `u16::from_le_bytes` on the same bytes with `&` wrapping, and the
//! low-discrepancy grids, ns per lookup. Exactness is tested in noise-runtime's tests.
//!
//! `cargo bench -p noisebake-cli --bench runtime`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use noise_runtime::{Mask3, ldg};
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
    g.finish();
}

criterion_group!(benches, lookups);
criterion_main!(benches);
