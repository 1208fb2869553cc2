//! Stochastic noise: every estimator is unbiased (a statistical test with a fixed seed), and
//! every function is total on the hard cases (ξ of 0 and 1, fade weights of exactly 0 and 1,
//! degenerate fractal parameters, huge coordinates).

use noise_runtime::stochastic::*;
use proptest::prelude::*;

use noisebake_test_support::Rng;

type Pair = (&'static str, fn([f32; 3]) -> f32, fn([f32; 3], f32) -> f32);

/// The octaves of the fractal sparse convolution under test.
const FBM_SPARSE: Fractal = Fractal::new(4, 2.0, 0.5);

/// The sparse convolution sums whose estimators are tested, each against two estimators.
fn sparse(p: [f32; 3]) -> f32 {
    SparseConvolution::new(10, 3).sample(p)
}

fn fbm_sparse(p: [f32; 3]) -> f32 {
    SparseConvolutionFbm::new(FBM_SPARSE, 6, 3).sample(p)
}

fn pairs() -> Vec<Pair> {
    vec![
        (
            "perlin2",
            |p| Perlin::new(3).sample([p[0], p[1]]),
            |p, x| Perlin::new(3).estimate([p[0], p[1]], x),
        ),
        (
            "perlin3",
            |p| Perlin::new(3).sample(p),
            |p, x| Perlin::new(3).estimate(p, x),
        ),
        (
            "perlin4",
            |p| Perlin::new(3).sample([p[0], p[1], p[2], p[0] - p[1]]),
            |p, x| Perlin::new(3).estimate([p[0], p[1], p[2], p[0] - p[1]], x),
        ),
        (
            "simplex2",
            |p| Simplex::new(3).sample([p[0], p[1]]),
            |p, x| Simplex::new(3).estimate([p[0], p[1]], x),
        ),
        (
            "simplex3",
            |p| Simplex::new(3).sample(p),
            |p, x| Simplex::new(3).estimate(p, x),
        ),
        (
            "simplex4",
            |p| Simplex::new(3).sample([p[0], p[1], p[2], p[0] - p[1]]),
            |p, x| Simplex::new(3).estimate([p[0], p[1], p[2], p[0] - p[1]], x),
        ),
        (
            "fbm3",
            |p| Fbm::new(Fractal::new(6, 2.0, 0.5), 3).sample(p),
            |p, x| Fbm::new(Fractal::new(6, 2.0, 0.5), 3).estimate(p, x),
        ),
        // The octave choice by a table of the CDF (any lacunarity and gain), and the
        // exponent-bit form with a negative gain (alternating signs).
        (
            "fbm3 (lacunarity 1.93, gain 0.6)",
            |p| Fbm::new(Fractal::new(5, 1.93, 0.6), 3).sample(p),
            |p, x| Fbm::new(Fractal::new(5, 1.93, 0.6), 3).estimate(p, x),
        ),
        (
            "fbm3 (gain -0.5)",
            |p| Fbm::new(Fractal::new(5, 2.0, -0.5), 3).sample(p),
            |p, x| Fbm::new(Fractal::new(5, 2.0, -0.5), 3).estimate(p, x),
        ),
        // Exact top octaves and one sampled octave of the rest (the renderer's variant), with
        // one, two and all-but-one exact octaves, and a general lacunarity and negative gain.
        (
            "fbm3 tail (1 exact)",
            |p| Fbm::new(Fractal::new(6, 2.0, 0.5), 3).sample(p),
            |p, x| Fbm::new(Fractal::new(6, 2.0, 0.5), 3).estimate_tail(p, 1, x),
        ),
        (
            "fbm3 tail (2 exact, gain -0.5)",
            |p| Fbm::new(Fractal::new(6, 2.0, -0.5), 3).sample(p),
            |p, x| Fbm::new(Fractal::new(6, 2.0, -0.5), 3).estimate_tail(p, 2, x),
        ),
        (
            "fbm3 tail (4 exact, lacunarity 1.93, gain 0.6)",
            |p| Fbm::new(Fractal::new(5, 1.93, 0.6), 3).sample(p),
            |p, x| Fbm::new(Fractal::new(5, 1.93, 0.6), 3).estimate_tail(p, 4, x),
        ),
        (
            "fbm3 octave (1 exact)",
            |p| Fbm::new(Fractal::new(6, 2.0, 0.5), 3).sample(p),
            |p, x| Fbm::new(Fractal::new(6, 2.0, 0.5), 3).estimate_octave(p, 1, x),
        ),
        (
            "fbm3 octave (0 exact, gain -0.5)",
            |p| Fbm::new(Fractal::new(6, 2.0, -0.5), 3).sample(p),
            |p, x| Fbm::new(Fractal::new(6, 2.0, -0.5), 3).estimate_octave(p, 0, x),
        ),
        ("fbm_sparse_conv3 octave (1 exact)", fbm_sparse, |p, x| {
            SparseConvolutionFbm::new(FBM_SPARSE, 6, 3).estimate_octave(p, 1, x)
        }),
        ("fbm_sparse_conv3 tail (2 exact)", fbm_sparse, |p, x| {
            SparseConvolutionFbm::new(FBM_SPARSE, 6, 3).estimate_tail(p, 2, x)
        }),
        ("sparse_conv3", sparse, |p, x| {
            SparseConvolution::new(10, 3).estimate(p, x)
        }),
        ("fbm_sparse_conv3", fbm_sparse, |p, x| {
            SparseConvolutionFbm::new(FBM_SPARSE, 6, 3).estimate(p, x)
        }),
        // The one-term estimators of the same two sums.
        ("sparse_conv3 one-term", sparse, |p, x| {
            SparseConvolution::new(10, 3).estimate_one_term(p, x)
        }),
        ("fbm_sparse_conv3 one-term", fbm_sparse, |p, x| {
            SparseConvolutionFbm::new(FBM_SPARSE, 6, 3).estimate_one_term(p, x)
        }),
        (
            "gabor3",
            |p| gabor(3).sample(p),
            |p, x| gabor(3).estimate(p, x),
        ),
        (
            "voronoi3",
            |p| SmoothVoronoi::new(3).sample(p),
            |p, x| SmoothVoronoi::new(3).estimate_with(p, SMOOTH_VORONOI_Q, x),
        ),
    ]
}

/// Test points: random, near lattice points, on cell borders and cell centres.
fn points(rng: &mut Rng) -> Vec<[f32; 3]> {
    let mut pts = Vec::new();
    for _ in 0..30 {
        pts.push([
            rng.unit_f32() * 40.0 - 20.0,
            rng.unit_f32() * 40.0 - 20.0,
            rng.unit_f32() * 40.0 - 20.0,
        ]);
    }
    for k in 0..10 {
        let base = (k as f32 - 5.0) * 3.0;
        let e = 1e-3 * rng.unit_f32();
        pts.push([base + e, base - 2.0 + e, 7.0 - e]); // near a lattice point
        pts.push([base + 0.5, base + 0.5, 0.5]); // cell centre (smooth Voronoi's 2×2×2 border)
        pts.push([base + 0.999, 2.0 + 0.9999, 0.25]); // fade rounds to 1 in f32
    }
    pts
}

/// Mean over 2048 i.i.d. ξ (2^15 for the one-term estimators) at each point against the
/// deterministic value. Under the null
/// hypothesis (unbiased), a point lands beyond 3 standard errors with probability ≈ 0.27 %, so
/// of the 60 points of each function more than 3 such misses (≥ 5 %) has probability below
/// 0.1 % per function; and no point may be beyond 6 standard errors (probability 2e-9).
#[test]
fn every_estimator_is_unbiased() {
    for (name, det, sto) in pairs() {
        let mut rng = Rng(0x5eed ^ name.len() as u64);
        let pts = points(&mut rng);
        let mut misses = 0;
        for p in &pts {
            let exact = det(*p) as f64;
            // The one-term estimators sample the 27-cell sum too: about 20× the variance, so
            // 16× the draws keep their standard error, and so the smallest bias the test can
            // see, close to that of the eq. 8 estimator.
            let n = if name.ends_with("one-term") {
                1 << 15
            } else {
                2048
            };
            let (mut s, mut s2) = (0.0f64, 0.0f64);
            for _ in 0..n {
                let v = sto(*p, rng.unit_f32()) as f64;
                s += v;
                s2 += v * v;
            }
            let mean = s / n as f64;
            let var = (s2 / n as f64 - mean * mean).max(0.0);
            let se = (var / n as f64).sqrt();
            let err = (mean - exact).abs();
            // Rounding (f32 sums in a different order) and corners or octaves so unlikely that
            // 2048 draws miss them (probability < 1/2048, so their share of the mean is below
            // ~5e-4 of the value's scale): a small allowance beside the statistical bound.
            let tol = 5e-4 * (1.0 + exact.abs());
            assert!(
                err <= 6.0 * se + tol,
                "{name} at {p:?}: mean {mean} vs {exact} (se {se})"
            );
            if err > 3.0 * se + tol {
                misses += 1;
            }
        }
        assert!(
            misses <= 3,
            "{name}: {misses} of {} points beyond 3 se",
            pts.len()
        );
    }
}

#[test]
fn lerp_and_roulette_building_blocks_are_unbiased() {
    // Exact expectation over a fine stratified ξ grid.
    let n = 1 << 16;
    let grid = |f: &dyn Fn(f32) -> f32| {
        (0..n)
            .map(|i| f((i as f32 + 0.5) / n as f32) as f64)
            .sum::<f64>()
            / n as f64
    };
    for t in [0.0, 0.1, 0.5, 0.9, 1.0] {
        let m = grid(&|x| lerp_estimate(t, x, || 2.0f32, || 5.0f32));
        assert!((m - (2.0 + 3.0 * t as f64)).abs() < 1e-4, "lerp t {t}: {m}");
        let m = grid(&|x| bilerp_estimate(t, 0.3, x, |i, j| (i * 2 + j) as f32));
        let want = 2.0 * t as f64 + 0.3;
        assert!((m - want).abs() < 1e-3, "bilerp t {t}: {m} vs {want}");
    }
    for q in [0.0, 0.5, 0.875] {
        let m = grid(&|x| russian_roulette(q, x, 0.5, || 0.8));
        assert!((m - 0.8).abs() < 1e-4, "roulette q {q}: {m}");
    }
}

#[test]
fn perlin_gradient_matches_finite_differences() {
    let mut rng = Rng(9);
    for _ in 0..200 {
        let p = [
            rng.unit_f32() * 10.0,
            rng.unit_f32() * 10.0,
            rng.unit_f32() * 10.0,
        ];
        let (v, g) = Perlin::new(1).gradient(p);
        assert!((v - Perlin::new(1).sample(p)).abs() < 1e-5);
        let h = 1e-2f32;
        for a in 0..3 {
            let (mut lo, mut hi) = (p, p);
            lo[a] -= h;
            hi[a] += h;
            let fd = (Perlin::new(1).sample(hi) - Perlin::new(1).sample(lo)) / (2.0 * h);
            assert!((fd - g[a]).abs() < 0.02, "axis {a}: fd {fd} vs {}", g[a]);
        }
        let (v2, g2) = Perlin::new(1).gradient([p[0], p[1]]);
        assert!((v2 - Perlin::new(1).sample([p[0], p[1]])).abs() < 1e-5);
        for a in 0..2 {
            let (mut lo, mut hi) = ([p[0], p[1]], [p[0], p[1]]);
            lo[a] -= h;
            hi[a] += h;
            let fd = (Perlin::new(1).sample(hi) - Perlin::new(1).sample(lo)) / (2.0 * h);
            assert!(
                (fd - g2[a]).abs() < 0.02,
                "2D axis {a}: fd {fd} vs {}",
                g2[a]
            );
        }
        let p4 = [p[0], p[1], p[2], rng.unit_f32() * 10.0 - 5.0];
        let (v4, g4) = Perlin::new(1).gradient(p4);
        assert!(
            (v4 - Perlin::new(1).sample(p4)).abs() < 1e-5,
            "{v4} vs {}",
            Perlin::new(1).sample(p4)
        );
        for a in 0..4 {
            let (mut lo, mut hi) = (p4, p4);
            lo[a] -= h;
            hi[a] += h;
            let fd = (Perlin::new(1).sample(hi) - Perlin::new(1).sample(lo)) / (2.0 * h);
            assert!(
                (fd - g4[a]).abs() < 0.02,
                "4D axis {a}: fd {fd} vs {}",
                g4[a]
            );
        }
    }
}

/// The simplex gradients against central differences of the noise, and their values against
/// the noise's (the module's own test checks them to second order across the faces).
#[test]
fn simplex_gradient_matches_finite_differences() {
    fn check<const N: usize>(
        name: &str,
        p: [f32; N],
        value: impl Fn([f32; N]) -> f32,
        grad: impl Fn([f32; N]) -> (f32, [f32; N]),
    ) {
        let (v, g) = grad(p);
        assert!(
            (v - value(p)).abs() < 1e-6,
            "{name} at {p:?}: {v} vs {}",
            value(p)
        );
        let h = 1e-2f32;
        for a in 0..N {
            let (mut lo, mut hi) = (p, p);
            lo[a] -= h;
            hi[a] += h;
            let fd = (value(hi) - value(lo)) / (2.0 * h);
            assert!(
                (fd - g[a]).abs() < 0.02 * (1.0 + g[a].abs()),
                "{name} axis {a} at {p:?}: fd {fd} vs {}",
                g[a]
            );
        }
    }
    let mut rng = Rng(10);
    for _ in 0..300 {
        let p: [f32; 4] = std::array::from_fn(|_| rng.unit_f32() * 20.0 - 10.0);
        check(
            "simplex2",
            [p[0], p[1]],
            |q| Simplex::new(1).sample(q),
            |q| Simplex::new(1).gradient(q),
        );
        check(
            "simplex3",
            [p[0], p[1], p[2]],
            |q| Simplex::new(1).sample(q),
            |q| Simplex::new(1).gradient(q),
        );
        check(
            "simplex4",
            p,
            |q| Simplex::new(1).sample(q),
            |q| Simplex::new(1).gradient(q),
        );
    }
}

#[test]
fn worley_f1_is_the_true_nearest_point() {
    // Brute force over a 5×5×5 block of cells: the pruned 27-cell search must agree.
    let mut rng = Rng(4);
    for _ in 0..2000 {
        let p = [
            rng.unit_f32() * 50.0 - 25.0,
            rng.unit_f32() * 50.0 - 25.0,
            rng.unit_f32() * 50.0 - 25.0,
        ];
        let c = p.map(|x| x.floor() as i32);
        let mut best = f32::MAX;
        for dz in -2..=2 {
            for dy in -2..=2 {
                for dx in -2..=2 {
                    let cell = [c[0] + dx, c[1] + dy, c[2] + dz];
                    let q = Worley::new(7).feature_point(cell);
                    let d: f32 = (0..3)
                        .map(|a| {
                            let t = p[a] - (cell[a] as f32 + q[a]);
                            t * t
                        })
                        .sum();
                    best = best.min(d.sqrt());
                }
            }
        }
        assert!((Worley::new(7).f1(p) - best).abs() < 2e-5, "{p:?}");
    }
}

#[test]
fn smooth_voronoi_is_eq_12_within_3e7() {
    // Eq. 12 in f64 from the same f32 point and feature points: the error of our f32
    // distances, exponentials, sum and logarithm together. Near the origin, where the f32
    // point is finest, and out to ±50.
    let mut rng = Rng(12);
    let mut worst = 0.0f64;
    for k in 0..40_000 {
        let half = if k % 2 == 0 { 2.0 } else { 50.0 };
        let p = [0; 3].map(|_| (rng.unit_f32() * 2.0 - 1.0) * half);
        let c = p.map(|x| x.floor() as i32);
        let mut sum = 0.0f64;
        for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let cell = [c[0] + dx, c[1] + dy, c[2] + dz];
                    let q = Worley::new(5).feature_point(cell);
                    let d2: f64 = (0..3)
                        .map(|a| (p[a] as f64 - (cell[a] as f64 + q[a] as f64)).powi(2))
                        .sum();
                    sum += (-32.0 * d2.sqrt()).exp();
                }
            }
        }
        let err = (SmoothVoronoi::new(5).sample(p) as f64 + sum.ln() / 32.0).abs();
        assert!(err < 3e-7, "{p:?}: error {err:e}");
        worst = worst.max(err);
    }
    assert!(
        worst > 3e-8,
        "a bound {worst:e} this far from tight tests nothing"
    );
}

fn hard_xis() -> [f32; 7] {
    [
        0.0,
        1.0,
        0.999_999_94,
        f32::MIN_POSITIVE,
        -1.0,
        2.0,
        f32::NAN,
    ]
}

fn hard_coords() -> [f32; 9] {
    [
        0.0,
        0.9999,
        -0.9999,
        1e7,
        -1e7,
        3.5e9,
        -1e20,
        f32::MAX,
        f32::MIN,
    ]
}

#[test]
fn hard_cases_are_finite() {
    let fracs = [
        Fractal::new(1, 2.0, 0.5),
        Fractal::new(32, 2.0, 0.5),
        Fractal::new(0, 2.0, 0.5),
        Fractal::new(500, 2.0, 0.5),
        Fractal::new(10, 2.0, 1.0),
        Fractal::new(10, 2.0, 0.0),
        Fractal::new(32, 1e30, 1e30),
        Fractal::new(32, f32::NAN, f32::NAN),
        Fractal::new(32, -3.0, -0.9),
    ];
    for &c in &hard_coords() {
        let p = [c, -c * 0.5, 0.25];
        for &x in &hard_xis() {
            let mut vals = vec![
                Perlin::new(1).sample([c, 0.3]),
                Perlin::new(1).estimate([c, 0.3], x),
                Perlin::new(1).sample(p),
                Perlin::new(1).gradient(p).0,
                Perlin::new(1).estimate(p, x),
                Perlin::new(1).sample([c, 1.5, c, 0.2]),
                Perlin::new(1).estimate([c, 1.5, c, 0.2], x),
                Perlin::new(1).gradient([c, 1.5, c, 0.2]).0,
                Simplex::new(1).sample([c, 0.3]),
                Simplex::new(1).estimate([c, 0.3], x),
                Simplex::new(1).gradient([c, 0.3]).0,
                Simplex::new(1).sample(p),
                Simplex::new(1).estimate(p, x),
                Simplex::new(1).gradient(p).0,
                Simplex::new(1).sample([c, 1.5, c, 0.2]),
                Simplex::new(1).estimate([c, 1.5, c, 0.2], x),
                Simplex::new(1).gradient([c, 1.5, c, 0.2]).0,
                SparseConvolution::new(10, 1).sample(p),
                SparseConvolution::new(10, 1).estimate(p, x),
                SparseConvolution::new(10, 1).estimate_one_term(p, x),
                gabor(1).sample(p),
                gabor(1).estimate(p, x),
                SmoothVoronoi::new(1).sample(p),
                SmoothVoronoi::new(1).estimate_with(p, SMOOTH_VORONOI_Q, x),
                SmoothVoronoi::new(1).estimate_with(p, 1.0, x),
                Worley::new(1).f1(p),
            ];
            vals.extend(Perlin::new(1).gradient(p).1);
            vals.extend(Perlin::new(1).gradient([c, 1.5, c, 0.2]).1);
            vals.extend(Simplex::new(1).gradient([c, 0.3]).1);
            vals.extend(Simplex::new(1).gradient(p).1);
            vals.extend(Simplex::new(1).gradient([c, 1.5, c, 0.2]).1);
            for f in fracs {
                vals.push(Fbm::new(f, 1).sample(p));
                vals.push(Fbm::new(f, 1).estimate(p, x));
                vals.push(SparseConvolutionFbm::new(f, 4, 1).sample(p));
                vals.push(SparseConvolutionFbm::new(f, 4, 1).estimate(p, x));
            }
            for (i, v) in vals.iter().enumerate() {
                assert!(v.is_finite(), "value {i} at coord {c}, ξ {x}: {v}");
            }
        }
    }
}

#[test]
fn fbm_with_gain_one_samples_octaves_uniformly() {
    // gain = 1: every octave has probability 1/n; the estimator's mean over a ξ grid is the sum.
    let f = Fractal::new(8, 2.0, 1.0);
    let p = [0.3, 1.7, -2.2];
    let n = 1 << 15;
    let m: f64 = (0..n)
        .map(|i| Fbm::new(f, 5).estimate(p, (i as f32 + 0.5) / n as f32) as f64)
        .sum::<f64>()
        / n as f64;
    assert!(
        (m - Fbm::new(f, 5).sample(p) as f64).abs() < 2e-3,
        "{m} vs {}",
        Fbm::new(f, 5).sample(p)
    );
}

proptest! {
    #[test]
    fn any_finite_input_gives_a_finite_value(
        x in -1e12f32..1e12, y in -1e12f32..1e12, z in -1e3f32..1e3,
        xi in 0.0f32..=1.0, oct in 0u32..40, lac in -2000f32..2000.0, gain in -40f32..40.0,
    ) {
        let p = [x, y, z];
        let f = Fractal::new(oct, lac, gain);
        for v in [
            Perlin::new(2).estimate(p, xi),
            Simplex::new(2).estimate([x, y], xi),
            Simplex::new(2).estimate(p, xi),
            Simplex::new(2).estimate([x, y, z, x - z], xi),
            Fbm::new(f, 2).sample(p),
            Fbm::new(f, 2).estimate(p, xi),
            SparseConvolutionFbm::new(f, 3, 2).estimate(p, xi),
            SparseConvolutionFbm::new(f, 3, 2).estimate_one_term(p, xi),
            SmoothVoronoi::new(2).estimate_with(p, SMOOTH_VORONOI_Q, xi),
            gabor(2).estimate(p, xi),
        ] {
            prop_assert!(v.is_finite());
        }
    }
}

proptest! {
    /// The batch forms (eight points per instruction where the CPU has AVX2) return what the
    /// single-point functions return, bit for bit, for any points, ξ, seed and fractal.
    #[test]
    fn batch_forms_are_the_single_point_functions(
        pts in proptest::collection::vec(proptest::array::uniform3(-1e4f32..1e4), 0..40),
        xi in proptest::collection::vec(0.0f32..=1.0, 40),
        seed: u32, oct in 1u32..16, halving: bool, gain in -2f32..2.0,
    ) {
        let f = if halving {
            Fractal::new(oct, 2.0, if gain < 0.0 { -0.5 } else { 0.5 })
        } else {
            Fractal::new(oct, 1.5 + gain.abs(), gain)
        };
        let n = pts.len();
        let mut out = vec![0.0f32; n];
        let check = |got: &[f32], want: &dyn Fn(usize) -> f32| {
            got.iter().enumerate().all(|(i, g)| g.to_bits() == want(i).to_bits())
        };
        let xi = &xi[..n];
        prop_assert!(Perlin::new(seed).sample_batch(&pts, &mut out).is_ok());
        prop_assert!(check(&out, &|i| Perlin::new(seed).sample(pts[i])));
        prop_assert!(Perlin::new(seed).estimate_batch(&pts, xi, &mut out).is_ok());
        prop_assert!(check(&out, &|i| Perlin::new(seed).estimate(pts[i], xi[i])));
        prop_assert!(Fbm::new(f, seed).sample_batch(&pts, &mut out).is_ok());
        prop_assert!(check(&out, &|i| Fbm::new(f, seed).sample(pts[i])));
        prop_assert!(Fbm::new(f, seed).estimate_batch(&pts, xi, &mut out).is_ok());
        prop_assert!(check(&out, &|i| Fbm::new(f, seed).estimate(pts[i], xi[i])));
    }
}

/// Gabor noise with the default parameters, prepared once per seed (building the tables takes
/// microseconds; the tests call it millions of times).
fn gabor(seed: u32) -> &'static GaborNoise {
    use std::sync::OnceLock;
    static G: [OnceLock<GaborNoise>; 4] = [const { OnceLock::new() }; 4];
    assert!((seed as usize) < G.len(), "seed {seed}: extend the table");
    G[seed as usize].get_or_init(|| GaborNoise::new(Gabor::default(), seed))
}

/// A batch call whose slices differ in length is an error naming the lengths, and writes
/// nothing (it once ran the shortest slice silently).
#[test]
fn batch_forms_refuse_mismatched_lengths() {
    let pts = [[0.5f32, 1.5, 2.5]; 9];
    let xi = [0.25f32; 9];
    let (perlin, fbm) = (Perlin::new(3), Fbm::new(Fractal::default(), 3));
    for (n_xi, n_out) in [(9, 8), (8, 9), (9, 10), (0, 9)] {
        let mut out = vec![-7.0f32; n_out];
        let e = perlin
            .estimate_batch(&pts, &xi[..n_xi], &mut out)
            .unwrap_err();
        assert_eq!((e.points, e.xi, e.out), (9, Some(n_xi), n_out));
        assert!(e.to_string().contains("9 points"), "{e}");
        assert!(fbm.estimate_batch(&pts, &xi[..n_xi], &mut out).is_err());
        if n_out != 9 {
            assert!(perlin.sample_batch(&pts, &mut out).is_err());
            assert!(fbm.sample_batch(&pts, &mut out).is_err());
        }
        assert!(out.iter().all(|&v| v == -7.0), "written: {out:?}");
    }
    let mut out = [0.0f32; 9];
    assert!(perlin.sample_batch(&pts, &mut out).is_ok());
    assert_eq!(out[4].to_bits(), perlin.sample(pts[4]).to_bits());
}

/// Perlin through the generic forms of [`Octaves`] (a wrapper that overrides nothing): the
/// fractal sum and its estimators as eq. 9 and Algorithm 2 state them.
#[derive(Clone, Copy)]
struct Generic(Perlin);

impl Noise<[f32; 3]> for Generic {
    fn sample(&self, p: [f32; 3]) -> f32 {
        self.0.sample(p)
    }
    fn estimate(&self, p: [f32; 3], xi: f32) -> f32 {
        self.0.estimate(p, xi)
    }
}

impl Octaves for Generic {
    fn octave(&self, o: u32) -> Generic {
        Generic(Perlin::new(octave_seed(self.0.seed, o)))
    }
}

/// `Fbm` is generic over its noise, and Perlin's own fBm kernels (lanes, the halving
/// estimator, the batch kernels) give exactly the generic forms' bits; another noise's fBm is
/// its octaves summed.
#[test]
fn fbm_is_generic_over_its_noise_and_perlins_kernels_are_the_generic_forms() {
    let mut rng = Rng(77);
    for f in [
        Fractal::default(),
        Fractal::new(7, 2.0, -0.5),
        Fractal::new(5, 1.9, 0.6),
    ] {
        let (fast, generic) = (Fbm::new(f, 9), Fbm::of(f, Generic(Perlin::new(9))));
        let simplex = Fbm::of(f, Simplex::new(4));
        let pts: Vec<[f32; 3]> = (0..3000)
            .map(|_| [0; 3].map(|_| (rng.unit_f32() - 0.5) * 300.0))
            .collect();
        let xis: Vec<f32> = (0..pts.len()).map(|_| rng.unit_f32()).collect();
        for (&p, &xi) in pts.iter().zip(&xis) {
            assert_eq!(
                fast.sample(p).to_bits(),
                generic.sample(p).to_bits(),
                "{p:?}"
            );
            assert_eq!(
                fast.estimate(p, xi).to_bits(),
                generic.estimate(p, xi).to_bits(),
                "{p:?} {xi}"
            );
            for exact in [0, 1, 3] {
                assert_eq!(
                    fast.estimate_tail(p, exact, xi).to_bits(),
                    generic.estimate_tail(p, exact, xi).to_bits()
                );
                assert_eq!(
                    fast.estimate_octave(p, exact, xi).to_bits(),
                    generic.estimate_octave(p, exact, xi).to_bits()
                );
            }
            let sum = fractal(p, f, |q, o| Simplex::new(octave_seed(4, o)).sample(q));
            assert_eq!(simplex.sample(p).to_bits(), sum.to_bits());
        }
        let (mut a, mut b) = (vec![0.0; pts.len()], vec![0.0; pts.len()]);
        fast.estimate_batch(&pts, &xis, &mut a).unwrap();
        generic.estimate_batch(&pts, &xis, &mut b).unwrap();
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
        fast.sample_batch(&pts, &mut a).unwrap();
        generic.sample_batch(&pts, &mut b).unwrap();
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
    }
}

/// Every noise type stands behind one trait object, its verbs the inherent ones; the batch
/// verbs of the trait give the single-point values for 2D and 4D points too.
#[test]
fn every_noise_is_a_noise() {
    let f = Fractal::new(4, 2.0, 0.5);
    type Named = (&'static str, Box<dyn Noise<[f32; 3]>>);
    let noises: Vec<Named> = vec![
        ("perlin", Box::new(Perlin::new(1))),
        ("simplex", Box::new(Simplex::new(1))),
        ("fbm", Box::new(Fbm::new(f, 1))),
        ("fbm simplex", Box::new(Fbm::of(f, Simplex::new(1)))),
        ("sparse", Box::new(SparseConvolution::new(10, 1))),
        ("sparse fbm", Box::new(SparseConvolutionFbm::new(f, 10, 1))),
        ("gabor", Box::new(GaborNoise::new(Gabor::default(), 1))),
        ("voronoi", Box::new(SmoothVoronoi::new(1))),
        ("worley", Box::new(Worley::new(1))),
    ];
    let mut rng = Rng(5);
    let pts: Vec<[f32; 3]> = (0..200)
        .map(|_| [0; 3].map(|_| rng.unit_f32() * 20.0 - 10.0))
        .collect();
    let xis: Vec<f32> = (0..pts.len()).map(|_| rng.unit_f32()).collect();
    for (name, n) in &noises {
        let mut out = vec![0.0; pts.len()];
        n.estimate_batch(&pts, &xis, &mut out).unwrap();
        for i in 0..pts.len() {
            assert_eq!(
                out[i].to_bits(),
                n.estimate(pts[i], xis[i]).to_bits(),
                "{name}"
            );
        }
        assert!(n.sample_batch(&pts, &mut out[1..]).is_err(), "{name}");
    }
    assert_eq!(
        noises[0].1.sample(pts[3]).to_bits(),
        Perlin::new(1).sample(pts[3]).to_bits()
    );
    let p2: Vec<[f32; 2]> = pts.iter().map(|p| [p[0], p[1]]).collect();
    let mut out = vec![0.0; p2.len()];
    Noise::<[f32; 2]>::sample_batch(&Perlin::new(2), &p2, &mut out).unwrap();
    assert!(
        out.iter()
            .zip(&p2)
            .all(|(o, &p)| o.to_bits() == Perlin::new(2).sample(p).to_bits())
    );
    let (v, g) = Gradient::gradient(&Simplex::new(3), [0.3f32, 0.7, 1.1]);
    assert_eq!((v, g), Simplex::new(3).gradient([0.3f32, 0.7, 1.1]));
}
