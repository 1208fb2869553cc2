//! Every lane kernel of the runtime, timed as the fastest of 21 passes over the same 65 536
//! random points (single thread), inline in the timing loop and through a function pointer.
//! The fastest pass, not the mean: on a shared machine the load of the neighbours only ever
//! adds time, so the minimum is the figure that repeats from run to run, and two builds
//! (before and after a change to the lane layer) can be compared to a few percent where
//! criterion's means, taken minutes apart, drift by tens of percent.
//!
//! `cargo bench -p noise-runtime --bench kernels` prints one line per function: ns per call
//! inline, and through a pointer.

use noise_runtime::stochastic::*;
use std::hint::black_box;
use std::time::Instant;

const N: usize = 1 << 16;
const PASSES: usize = 21;

/// Nanoseconds per call of `f`, the fastest of [`PASSES`] passes over the points.
#[inline(never)]
fn fastest<P: Copy, F: Fn(P, f32) -> f32>(pts: &[P], xis: &[f32], f: F) -> f64 {
    let mut best = f64::MAX;
    for _ in 0..PASSES {
        let t = Instant::now();
        let mut acc = 0.0f32;
        for (p, x) in black_box(pts).iter().zip(black_box(xis)) {
            acc += f(*p, *x);
        }
        black_box(acc);
        best = best.min(t.elapsed().as_secs_f64() * 1e9 / pts.len() as f64);
    }
    best
}

/// Nanoseconds per point of a batch form, the fastest of [`PASSES`] calls over all points.
#[inline(never)]
fn fastest_batch(
    pts: &[[f32; 3]],
    xis: &[f32],
    f: impl Fn(&[[f32; 3]], &[f32], &mut [f32]),
) -> f64 {
    let mut out = vec![0.0f32; pts.len()];
    let mut best = f64::MAX;
    for _ in 0..PASSES {
        let t = Instant::now();
        f(black_box(pts), black_box(xis), &mut out);
        black_box(&out);
        best = best.min(t.elapsed().as_secs_f64() * 1e9 / pts.len() as f64);
    }
    best
}

fn main() {
    let mut s = 0x1234_5678_9abc_def0u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / 16_777_216.0
    };
    let pts: Vec<[f32; 3]> = (0..N)
        .map(|_| [0; 3].map(|_| next() * 100.0 - 50.0))
        .collect();
    let xis: Vec<f32> = (0..N).map(|_| next()).collect();
    // 4D points stored as such: a point built inside the timed closure would time the
    // closure's own reads of its argument as much as the noise.
    let pts4: Vec<[f32; 4]> = pts
        .iter()
        .map(|p| [p[0], p[1], p[2], p[0] - p[1]])
        .collect();
    macro_rules! row {
        ($name:expr, |$p:ident, $x:ident| $body:expr) => {
            row!($name, pts, [f32; 3], |$p, $x| $body)
        };
        ($name:expr, $pts:ident, $t:ty, |$p:ident, $x:ident| $body:expr) => {{
            let inline = fastest(&$pts, &xis, |$p: $t, $x| $body);
            let call: fn($t, f32) -> f32 = black_box(|$p, $x| $body);
            let pointer = fastest(&$pts, &xis, call);
            println!(
                "{:<28} {inline:>7.2} ns inline {pointer:>7.2} ns through a pointer",
                $name
            );
        }};
    }
    row!("perlin3", |p, _x| Perlin::new(1).sample(p));
    row!("perlin3 estimate", |p, x| Perlin::new(1).estimate(p, x));
    row!("perlin4", pts4, [f32; 4], |p, _x| Perlin::new(1).sample(p));
    row!("perlin4 estimate", pts4, [f32; 4], |p, x| Perlin::new(1)
        .estimate(p, x));
    row!("simplex3", |p, _x| Simplex::new(1).sample(p));
    row!("simplex3 estimate", |p, x| Simplex::new(1).estimate(p, x));
    row!("simplex4", pts4, [f32; 4], |p, _x| Simplex::new(1)
        .sample(p));
    row!("simplex4 estimate", pts4, [f32; 4], |p, x| Simplex::new(1)
        .estimate(p, x));
    row!("fbm3", |p, _x| Fbm::new(Fractal::new(10, 2.0, 0.5), 1)
        .sample(p));
    row!("fbm3 estimate", |p, x| Fbm::new(
        Fractal::new(10, 2.0, 0.5),
        1
    )
    .estimate(p, x));
    row!("worley3 f1", |p, _x| Worley::new(1).f1(p));
    row!("smooth voronoi3", |p, _x| SmoothVoronoi::new(1).sample(p));
    row!("smooth voronoi3 estimate", |p, x| SmoothVoronoi::new(1)
        .estimate(p, x));
    for (name, ns) in [
        (
            "perlin3 batch",
            fastest_batch(&pts, &xis, |p, _, o| {
                Perlin::new(1).sample_batch(p, o).unwrap();
            }),
        ),
        (
            "perlin3 estimate batch",
            fastest_batch(&pts, &xis, |p, x, o| {
                Perlin::new(1).estimate_batch(p, x, o).unwrap();
            }),
        ),
        (
            "fbm3 batch",
            fastest_batch(&pts, &xis, |p, _, o| {
                Fbm::new(Fractal::new(10, 2.0, 0.5), 1)
                    .sample_batch(p, o)
                    .unwrap();
            }),
        ),
        (
            "fbm3 estimate batch",
            fastest_batch(&pts, &xis, |p, x, o| {
                Fbm::new(Fractal::new(10, 2.0, 0.5), 1)
                    .estimate_batch(p, x, o)
                    .unwrap();
            }),
        ),
    ] {
        println!("{name:<28} {ns:>7.2} ns per point");
    }
}
