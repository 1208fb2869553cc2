//! Stochastic noise against its deterministic twin and the best peer crates, single thread,
//! random-order points (Fajardo & Pharr Table 1 on this CPU). The RMSE each stochastic variant
//! pays is in `noisebake report stochastic` (same functions, same settings).
//!
//! Criterion times one function after another, each for a couple of seconds; on a machine whose
//! clock or neighbours' load drifts over seconds (a shared VM), the ratio of two of these times
//! moves with the drift. The report times each deterministic/stochastic pair (and each peer
//! against ours) in interleaved chunks of the same points, and its speedups are the steady ones.
//!
//! `cargo bench -p noisebake-cli --bench stochastic`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use noise_runtime::stochastic::*;
use std::hint::black_box;
use std::time::Duration;

/// As many points as `noisebake report` times: a short sequence, replayed on every iteration,
/// lets the branch predictor learn the outcomes of data-dependent branches (with 4096 points,
/// stochastic fBm's octave search measured 25.5 ns here against 42.3 ns in the report).
const N: usize = 1 << 16;

fn points() -> (Vec<[f32; 3]>, Vec<f32>) {
    let mut rng = noisebake_test_support::Rng(0x1234_5678_9abc_def0);
    let mut next = move || rng.unit_f32();
    let pts = (0..N)
        .map(|_| {
            [
                next() * 100.0 - 50.0,
                next() * 100.0 - 50.0,
                next() * 100.0 - 50.0,
            ]
        })
        .collect();
    let xis = (0..N).map(|_| next()).collect();
    (pts, xis)
}

/// The slices, not each point, go through `black_box`: a `black_box`ed `[f32; 3]` is written to
/// the stack and read back in pieces of other widths, which stalls store-to-load forwarding and
/// adds a delay to every call that no renderer pays (it moved the stochastic Perlin figure by 2×).
macro_rules! bench {
    ($g:expr, $name:expr, $pts:expr, $xis:expr, |$p:ident, $x:ident| $body:expr) => {
        $g.bench_function($name, |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for (&$p, &$x) in black_box(&$pts).iter().zip(black_box(&$xis).iter()) {
                    acc += $body;
                }
                acc
            })
        });
    };
}

fn noise(c: &mut Criterion) {
    let (pts, xis) = points();
    let f10 = Fractal::new(10, 2.0, 0.5);
    let mut g = c.benchmark_group("noise3d");
    g.throughput(Throughput::Elements(N as u64));
    g.sample_size(10)
        .measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    bench!(g, "perlin3/deterministic", pts, xis, |p, _x| Perlin::new(1)
        .sample(p));
    bench!(g, "perlin3/stochastic", pts, xis, |p, x| Perlin::new(1)
        .estimate(p, x));
    bench!(g, "simplex2/deterministic", pts, xis, |p, _x| Simplex::new(
        1
    )
    .sample([p[0], p[1]]));
    bench!(g, "simplex2/stochastic", pts, xis, |p, x| {
        Simplex::new(1).estimate([p[0], p[1]], x)
    });
    bench!(g, "simplex3/deterministic", pts, xis, |p, _x| Simplex::new(
        1
    )
    .sample(p));
    bench!(g, "simplex3/stochastic", pts, xis, |p, x| {
        Simplex::new(1).estimate(p, x)
    });
    bench!(g, "simplex4/deterministic", pts, xis, |p, _x| Simplex::new(
        1
    )
    .sample([p[0], p[1], p[2], p[0] + p[2]]));
    bench!(g, "simplex4/stochastic", pts, xis, |p, x| {
        Simplex::new(1).estimate([p[0], p[1], p[2], p[0] + p[2]], x)
    });
    bench!(g, "fbm3/deterministic", pts, xis, |p, _x| Fbm::new(f10, 1)
        .sample(p));
    bench!(g, "fbm3/stochastic", pts, xis, |p, x| Fbm::new(f10, 1)
        .estimate(p, x));
    bench!(g, "sparse_conv3/deterministic", pts, xis, |p, _x| {
        SparseConvolution::new(10, 1).sample(p)
    });
    bench!(g, "sparse_conv3/stochastic", pts, xis, |p, x| {
        SparseConvolution::new(10, 1).estimate(p, x)
    });
    bench!(g, "sparse_conv3/stochastic-1term", pts, xis, |p, x| {
        SparseConvolution::new(10, 1).estimate_one_term(p, x)
    });
    bench!(g, "fbm_sparse_conv3/deterministic", pts, xis, |p, _x| {
        SparseConvolutionFbm::new(f10, 10, 1).sample(p)
    });
    bench!(g, "fbm_sparse_conv3/stochastic", pts, xis, |p, x| {
        SparseConvolutionFbm::new(f10, 10, 1).estimate(p, x)
    });
    bench!(g, "fbm_sparse_conv3/stochastic-1term", pts, xis, |p, x| {
        SparseConvolutionFbm::new(f10, 10, 1).estimate_one_term(p, x)
    });
    // Gabor noise as a renderer keeps it: parameters prepared once (`GaborNoise`).
    let gabor = GaborNoise::new(Gabor::default(), 1);
    bench!(g, "gabor3/deterministic", pts, xis, |p, _x| gabor.sample(p));
    bench!(g, "gabor3/stochastic", pts, xis, |p, x| gabor
        .estimate(p, x));
    bench!(g, "voronoi3/deterministic", pts, xis, |p, _x| {
        SmoothVoronoi::new(1).sample(p)
    });
    bench!(g, "voronoi3/stochastic", pts, xis, |p, x| {
        SmoothVoronoi::new(1).estimate_with(p, SMOOTH_VORONOI_Q, x)
    });
    bench!(g, "worley3/deterministic", pts, xis, |p, _x| Worley::new(1)
        .f1(p));
    // The batch forms over all N points in one call (eight per instruction on AVX2).
    let mut out = vec![0.0f32; N];
    macro_rules! batch {
        ($name:expr, |$p:ident, $x:ident, $o:ident| $call:expr) => {
            g.bench_function($name, |b| {
                b.iter(|| {
                    let ($p, $x, $o) = (black_box(&pts[..]), black_box(&xis[..]), &mut out[..]);
                    $call;
                    black_box(&*$o);
                })
            });
        };
    }
    batch!("perlin3/deterministic-batch", |p, _x, o| Perlin::new(1)
        .sample_batch(p, o)
        .unwrap());
    batch!("perlin3/stochastic-batch", |p, x, o| {
        Perlin::new(1).estimate_batch(p, x, o).unwrap()
    });
    batch!("fbm3/deterministic-batch", |p, _x, o| Fbm::new(f10, 1)
        .sample_batch(p, o)
        .unwrap());
    batch!("fbm3/stochastic-batch", |p, x, o| {
        Fbm::new(f10, 1).estimate_batch(p, x, o).unwrap()
    });
    {
        use noise_functions::{CellDistance, Noise, Perlin};
        let fbm = Perlin.fbm(10, 0.5, 2.0);
        let cell = CellDistance::default();
        bench!(g, "perlin3/noise-functions", pts, xis, |p, _x| Perlin
            .sample3(p));
        bench!(g, "fbm3/noise-functions", pts, xis, |p, _x| fbm.sample3(p));
        bench!(g, "worley3/noise-functions", pts, xis, |p, _x| cell
            .sample3(p));
    }
    {
        use fastnoise_lite::{
            CellularDistanceFunction, CellularReturnType, FastNoiseLite, FractalType, NoiseType,
        };
        let mut perlin = FastNoiseLite::new();
        perlin.set_noise_type(Some(NoiseType::Perlin));
        perlin.set_frequency(Some(1.0));
        let mut fbm = FastNoiseLite::new();
        fbm.set_noise_type(Some(NoiseType::Perlin));
        fbm.set_frequency(Some(1.0));
        fbm.set_fractal_type(Some(FractalType::FBm));
        fbm.set_fractal_octaves(Some(10));
        let mut cell = FastNoiseLite::new();
        cell.set_noise_type(Some(NoiseType::Cellular));
        cell.set_frequency(Some(1.0));
        cell.set_cellular_return_type(Some(CellularReturnType::Distance));
        cell.set_cellular_distance_function(Some(CellularDistanceFunction::Euclidean));
        bench!(g, "perlin3/fastnoise-lite", pts, xis, |p, _x| perlin
            .get_noise_3d(p[0], p[1], p[2]));
        bench!(g, "fbm3/fastnoise-lite", pts, xis, |p, _x| fbm
            .get_noise_3d(p[0], p[1], p[2]));
        bench!(g, "worley3/fastnoise-lite", pts, xis, |p, _x| cell
            .get_noise_3d(p[0], p[1], p[2]));
    }
    g.finish();
}

/// The same functions called through a function pointer, as a renderer does that keeps its
/// noise behind `fn` values or calls it across a crate without inlining: the point travels
/// in memory, and how the callee reads it decides whether the read can be forwarded from the
/// caller's stores (a read spanning two of them stalled every call until `F4::from3` read
/// the point in the pieces callers store it in).
fn called(c: &mut Criterion) {
    let (pts, xis) = points();
    let mut g = c.benchmark_group("noise3d-call");
    g.throughput(Throughput::Elements(N as u64));
    g.sample_size(10)
        .measurement_time(Duration::from_secs(2))
        .warm_up_time(Duration::from_millis(500));
    type Call = fn([f32; 3], f32) -> f32;
    let calls: [(&str, Call); 6] = [
        ("perlin3/deterministic", |p, _| Perlin::new(1).sample(p)),
        ("perlin3/stochastic", |p, x| Perlin::new(1).estimate(p, x)),
        ("simplex3/deterministic", |p, _| Simplex::new(1).sample(p)),
        ("simplex3/stochastic", |p, x| Simplex::new(1).estimate(p, x)),
        ("voronoi3/stochastic", |p, x| {
            SmoothVoronoi::new(1).estimate(p, x)
        }),
        ("worley3/deterministic", |p, _| Worley::new(1).f1(p)),
    ];
    for (name, f) in calls {
        let f = black_box(f);
        bench!(g, name, pts, xis, |p, x| f(p, x));
    }
    g.finish();
}

criterion_group!(benches, noise, called);
criterion_main!(benches);
