//! Every input class at the runtime's public functions: i32/u32 extremes, NaN, ±∞, ±0,
//! subnormals, huge and tiny magnitudes, ξ outside [0, 1), tiny and huge parameters. The
//! documented behaviour is checked (no panic in debug or release — overflow checks included —
//! no hang, finite output for finite input where the docs promise it, ranges kept).
//!
//! Run it in debug too: `cargo test -p noise-runtime --test extremes` (CI runs the release
//! build; both must pass).

use noise_runtime::cnj::{Cnj2, Cnj3, velocity2, velocity3};
use noise_runtime::stochastic::*;
use noise_runtime::{Mask2, Mask3, Mask4, ldg, warp};

const F: [f32; 19] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    1e-45,
    -1e-45,
    f32::MIN_POSITIVE,
    1e7,
    -1e7,
    6.5e7,
    -6.5e7,
    1e20,
    -1e30,
    f32::MAX,
    -f32::MAX,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
];
const XI: [f32; 9] = [
    0.0,
    -0.0,
    0.999_999_94,
    1.0,
    2.0,
    -1.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
];
const I: [i32; 7] = [0, 1, -1, i32::MAX, i32::MIN, i32::MAX - 1, i32::MIN + 1];

fn points3() -> impl Iterator<Item = [f32; 3]> {
    F.iter()
        .flat_map(|&x| F.iter().map(move |&y| [x, y, 0.25]))
        .chain(F.iter().map(|&z| [0.5, -0.25, z]))
}

fn finite3(p: [f32; 3]) -> bool {
    p.iter().all(|v| v.is_finite())
}

#[test]
fn lattice_noise_is_total_and_finite_on_finite_input() {
    for p in points3() {
        for &xi in &XI {
            let vals = [
                Perlin::new(7).sample(p),
                Perlin::new(7).estimate(p, xi),
                Perlin::new(7).gradient(p).0,
                Simplex::new(7).sample(p),
                Simplex::new(7).estimate(p, xi),
                Perlin::new(7).sample([p[0], p[1]]),
                Perlin::new(7).estimate([p[0], p[1]], xi),
                Simplex::new(7).sample([p[0], p[1]]),
                Simplex::new(7).estimate([p[0], p[1]], xi),
                Perlin::new(7).sample([p[0], p[1], p[2], 0.5]),
                Perlin::new(7).estimate([p[0], p[1], p[2], 0.5], xi),
                Simplex::new(7).sample([p[0], p[1], p[2], 0.5]),
                Simplex::new(7).estimate([p[0], p[1], p[2], 0.5], xi),
            ];
            if finite3(p) {
                for (i, v) in vals.iter().enumerate() {
                    assert!(v.is_finite(), "function {i} at {p:?}, ξ {xi}: {v}");
                }
            }
        }
    }
}

#[test]
fn fractal_and_cellular_noise_are_total() {
    let fractals = [
        Fractal::default(),
        Fractal::new(1, 2.0, 0.5),
        Fractal::new(32, 2.0, 0.5),
        Fractal::new(10, 1e30, 0.5),
        Fractal::new(10, 2.0, 2.0),
        Fractal::new(0, 2.0, 0.5),
        Fractal::new(10, f32::NAN, f32::NAN),
        Fractal::new(u32::MAX, 2.0, 0.5),
    ];
    for p in points3().step_by(3) {
        for &xi in &XI[..7] {
            for f in fractals {
                let a = Fbm::new(f, 3).sample(p);
                let b = Fbm::new(f, 3).estimate(p, xi);
                if finite3(p) && f.lacunarity.is_finite() && f.gain.is_finite() {
                    assert!(!a.is_nan() && !b.is_nan(), "{p:?} {f:?} ξ {xi}: {a} {b}");
                }
            }
            let _ = SparseConvolution::new(10, 1).sample(p);
            let _ = SparseConvolution::new(10, 1).estimate(p, xi);
            let _ = SparseConvolution::new(10, 1).estimate_one_term(p, xi);
            let _ = SparseConvolution::new(u32::MAX, 1).sample(p);
            let _ = SparseConvolution::new(0, 1).estimate(p, xi);
            let _ = SparseConvolutionFbm::new(Fractal::default(), 10, 1).estimate(p, xi);
            let _ = gabor(1).sample(p);
            let _ = gabor(1).estimate(p, xi);
            let w = Worley::new(1).f1(p);
            let s = SmoothVoronoi::new(1).sample(p);
            let sv = SmoothVoronoi::new(1).estimate_with(p, 0.875, xi);
            let _ = SmoothVoronoi::new(1).estimate_with(p, f32::NAN, xi);
            let _ = SmoothVoronoi::new(1).estimate_with(p, 2.0, xi);
            if finite3(p) {
                assert!(w.is_finite() && s.is_finite() && sv.is_finite(), "{p:?}");
            }
        }
    }
}

#[test]
fn batch_forms_match_single_points_on_extremes() {
    let pts: Vec<[f32; 3]> = points3().collect();
    let xis: Vec<f32> = (0..pts.len()).map(|i| XI[i % XI.len()]).collect();
    let mut out = vec![0.0; pts.len()];
    Perlin::new(5).sample_batch(&pts, &mut out).unwrap();
    for (p, o) in pts.iter().zip(&out) {
        assert_eq!(o.to_bits(), Perlin::new(5).sample(*p).to_bits(), "{p:?}");
    }
    Perlin::new(5).estimate_batch(&pts, &xis, &mut out).unwrap();
    for ((p, x), o) in pts.iter().zip(&xis).zip(&out) {
        let want = Perlin::new(5).estimate(*p, *x);
        assert!(
            o.to_bits() == want.to_bits() || (o.is_nan() && want.is_nan()),
            "{p:?} ξ {x}: {o} vs {want}"
        );
    }
}

#[test]
fn cnj_queries_are_total_and_bounded() {
    // The extremes a lattice can have; values none can have are refused by the setters.
    let c2 = Cnj2::default();
    let lattices = [
        c2,
        c2.with_time(0.0).unwrap(),
        c2.with_time(f32::MAX).unwrap(),
        c2.with_time(-f32::MAX).unwrap(),
        c2.with_scale(noise_runtime::cnj::MIN_SCALE as f32 * 1.01)
            .unwrap(),
        c2.with_scale(f32::MAX).unwrap(),
        c2.with_spacing(1e-30).unwrap(),
        c2.with_spacing(f32::MAX).unwrap(),
        c2.with_steps(64).unwrap(),
    ];
    for bad in [
        c2.with_spacing(0.0),
        c2.with_spacing(-1.0),
        c2.with_spacing(f32::NAN),
        c2.with_spacing(f32::INFINITY),
        c2.with_time(f32::NAN),
        c2.with_scale(1e-30),
        c2.with_scale(f32::INFINITY),
        c2.with_steps(0),
        c2.with_steps(u32::MAX),
    ] {
        let e = bad.unwrap_err();
        assert!(e.to_string().starts_with("CNJ "), "{e}");
    }
    for c in lattices {
        for &x in &F {
            for &y in &F[..8] {
                let n = c.closest([x, y]);
                if x.is_finite() && y.is_finite() {
                    assert!(n.distance.is_finite(), "{c:?} at {x}, {y}");
                }
                let _ = c.cells([y, x]);
            }
        }
        for &i in &I {
            let _ = c.point([i, i.wrapping_neg()]);
            let _ = c.point([i, i]);
        }
        let (_, [w, h]) = c.region_dims([-10.0, -10.0], [10.0, 10.0]);
        let mut buf = vec![[0.0f32; 2]; w * h];
        if let Some(r) = c.region([-10.0, -10.0], [10.0, 10.0], &mut buf) {
            for &x in &F {
                let _ = r.closest([x, 6.5e7]);
                let _ = r.closest([6.5e7, x]);
                let _ = r.cells([x, -x]);
                let mut row = [0.0f32; 4];
                r.f1_row(x, -x, 0.5, &mut row);
            }
        }
        for (a, b) in [
            ([f32::MAX, 0.0], [-f32::MAX, 0.0]),
            ([f32::NAN, f32::INFINITY], [0.0, f32::NEG_INFINITY]),
            ([-1e30, -1e30], [1e30, 1e30]),
        ] {
            let (_, [w, h]) = c.region_dims(a, b);
            assert!(w >= 1 && h >= 1 && w * h <= noise_runtime::cnj::MAX_REGION_SITES);
        }
    }
    let c3 = Cnj3::default();
    let lattices3 = [
        c3,
        c3.with_time(30.0).unwrap(),
        c3.with_time(f32::MAX).unwrap(),
        c3.with_scale(noise_runtime::cnj::MIN_SCALE as f32 * 1.01)
            .unwrap(),
        c3.with_spacing(1e-30).unwrap(),
        c3.with_steps(64).unwrap(),
    ];
    assert!(c3.with_spacing(0.0).is_err() && c3.with_time(f32::NAN).is_err());
    for c in lattices3 {
        for p in points3().step_by(7) {
            let n = c.closest(p);
            if finite3(p) {
                assert!(n.distance.is_finite(), "{c:?} at {p:?}");
            }
        }
        assert!(c.max_displacement().is_finite());
    }
}

#[test]
fn curl_fields_are_finite_for_finite_input() {
    let v = [0.0, -0.0, 0.5, 0.3, -2.0, 1e-300, 1e10, -1e15, 1e300];
    for &x in &v {
        for &y in &v {
            for &z in &v {
                for s in [1.0, 2.86207, 0.0, -1.0, 1e-30, 1e30, 1e-310] {
                    let a = velocity3([x, y, z], s, 1);
                    assert!(
                        a.iter().all(|c| c.is_finite()),
                        "velocity3 {x} {y} {z} s {s}: {a:?}"
                    );
                    let b = velocity2([x, y], s, 1);
                    assert!(
                        b.iter().all(|c| c.is_finite()),
                        "velocity2 {x} {y} s {s}: {b:?}"
                    );
                }
            }
        }
    }
    let _ = velocity3([f64::NAN, f64::INFINITY, 0.0], 1.0, 1);
    let _ = velocity2([f64::NAN, f64::INFINITY], 0.0, 1);
}

#[test]
fn grids_and_warps_keep_their_ranges() {
    for &x in &I {
        for &y in &I {
            for f in [0u32, 1, u32::MAX] {
                for v in [
                    ldg::r2(x, y),
                    ldg::r2_frame(x, y, f),
                    ldg::plus(x, y),
                    ldg::plus_frame(x, y, f),
                    ldg::ign(x, y),
                    ldg::ign_frame(x, y, f),
                    ldg::bayer::<2>(x, y),
                    ldg::bayer::<4096>(x, y),
                    ldg::bayer::<8192>(x, y),
                    ldg::bayer::<65536>(x, y),
                    ldg::bayer_frame::<65536>(x, y, f),
                ] {
                    assert!((0.0..1.0).contains(&v), "({x}, {y}, frame {f}): {v}");
                }
            }
        }
    }
    for &u in &XI {
        for &v in &XI {
            for d in [
                warp::cosine_hemisphere(u, v),
                warp::hemisphere_uniform(u, v),
                warp::sphere_uniform(u, v),
            ] {
                assert!(d.iter().all(|c| c.is_finite()), "({u}, {v}): {d:?}");
            }
            let d = warp::disk_concentric(u, v);
            assert!(d.iter().all(|c| c.is_finite()));
        }
    }
}

#[test]
fn mask_reads_wrap_at_every_extreme() {
    static B: [u8; 64] = [7; 64];
    let m2: Mask2<u8, 8, 8> = Mask2::new(&B);
    let m3: Mask3<u8, 4, 4, 4> = Mask3::new(&B);
    let m4: Mask4<u8, 2, 4, 4, 2> = Mask4::new(&B);
    for &x in &I {
        for &y in &I {
            assert_eq!(m2.get(x, y), 7);
            assert_eq!(m3.get(x, y, x), 7);
            assert_eq!(m4.get(x, y, y, x), 7);
            for k in [0u32, 1, u32::MAX] {
                assert_eq!(m3.get_k(x, y, i32::MAX, k), 7);
                let u = m3.get_k_unit(x, y, i32::MIN, k);
                assert!((0.0..1.0).contains(&u));
            }
            for p in [f32::NAN, -1.0, 0.0, 1.0, 2.0, f32::INFINITY] {
                let _ = m2.threshold(x, y, p);
                let _ = m3.threshold(x, y, i32::MAX, p);
            }
        }
    }
}

mod arbitrary_bits {
    use super::*;
    use proptest::prelude::*;

    fn any_f32() -> impl Strategy<Value = f32> {
        any::<u32>().prop_map(f32::from_bits)
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

        /// Any bit pattern for every coordinate and ξ: no panic, and finite output for finite
        /// input; the batch form agrees with the single-point one bit for bit.
        #[test]
        fn noise_functions_take_any_bits(
            x in any_f32(), y in any_f32(), z in any_f32(), xi in any_f32(), seed in any::<u32>()
        ) {
            let p = [x, y, z];
            let vals = [
                Perlin::new(seed).sample(p),
                Perlin::new(seed).estimate(p, xi),
                Simplex::new(seed).sample(p),
                Fbm::new(Fractal::default(), seed).sample(p),
                Fbm::new(Fractal::default(), seed).estimate(p, xi),
                Worley::new(seed).f1(p),
                SmoothVoronoi::new(seed).estimate_with(p, 0.875, xi),
                SparseConvolution::new(10, seed).estimate(p, xi),
                GaborNoise::new(Gabor::default(), seed).estimate(p, xi),
            ];
            if finite3(p) {
                for v in vals {
                    prop_assert!(v.is_finite());
                }
            }
            let mut out = [0.0f32; 1];
            Fbm::new(Fractal::default(), seed).estimate_batch(&[p], &[xi], &mut out).unwrap();
            let single = Fbm::new(Fractal::default(), seed).estimate(p, xi);
            prop_assert!(out[0].to_bits() == single.to_bits() || (out[0].is_nan() && single.is_nan()));
        }

        #[test]
        fn cnj_and_grids_take_any_bits(
            x in any_f32(), y in any_f32(), i in any::<i32>(), j in any::<i32>(), f in any::<u32>()
        ) {
            let n = Cnj2::default().closest([x, y]);
            if x.is_finite() && y.is_finite() {
                prop_assert!(n.distance.is_finite());
            }
            let _ = Cnj3::default().closest([x, y, 0.5]);
            for v in [ldg::r2_frame(i, j, f), ldg::ign_frame(i, j, f), ldg::plus_frame(i, j, f), ldg::bayer_frame::<4096>(i, j, f)] {
                prop_assert!((0.0..1.0).contains(&v));
            }
            let d = warp::cosine_hemisphere(x, y);
            prop_assert!(d.iter().all(|c| c.is_finite()));
        }
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
