//! Curl-noise jittering: exact implicit queries (against brute force over large patches), the
//! displacement bounds they rely on, a divergence-free field, the region cache, hard inputs.

use noise_runtime::cnj::*;

use noisebake_test_support::Rng;

#[test]
fn max_displacement_2d_is_within_the_two_ring_guarantee() {
    let c = Cnj2::default();
    let mut max: f32 = 0.0;
    for j in -150..150 {
        for i in -150..150 {
            let d = c.displacement([i, j]);
            max = max.max((d[0] * d[0] + d[1] * d[1]).sqrt());
        }
    }
    eprintln!("max 2D displacement over 90 000 sites: {max:.3} spacings");
    // Two hex rings contain every site within 1.73 spacings of the nearest site; a query is at
    // most 0.58 from its nearest site, so displacements below (2·0.866 − 0.577)/2 ≈ 0.58 are
    // trivially safe and the brute-force test below covers the rest.
    assert!(max < 1.2, "{max}");
}

#[test]
fn closest_and_k_nearest_2d_match_brute_force() {
    for seed in [0u32, 7] {
        let c = Cnj2::default().with_seed(seed).with_spacing(0.5).unwrap();
        let mut pts = Vec::new();
        for j in -40..40 {
            for i in -40..40 {
                pts.push((c.point_f64([i, j]), [i, j]));
            }
        }
        let mut rng = Rng(seed as u64 + 1);
        for _ in 0..8_000 {
            let x = [rng.unit_f64() * 20.0 - 10.0, rng.unit_f64() * 16.0 - 8.0];
            let mut d: Vec<(f64, [i32; 2])> = pts
                .iter()
                .map(|(p, s)| (((p[0] - x[0]).powi(2) + (p[1] - x[1]).powi(2)).sqrt(), *s))
                .collect();
            d.sort_by(|a, b| a.0.total_cmp(&b.0));
            let k = c.k_nearest_f64::<4>(x);
            for n in 0..4 {
                assert_eq!(k[n].site, d[n].1, "seed {seed} query {x:?} rank {n}");
                assert!((k[n].distance as f64 - d[n].0).abs() < 1e-5);
            }
            assert_eq!(c.k_nearest_f64::<1>(x)[0].site, d[0].1);
        }
    }
}

#[test]
fn region_queries_equal_direct_queries() {
    let c = Cnj2::default().with_spacing(3.0).unwrap();
    let (_, dims) = c.region_dims([0.0, 0.0], [64.0, 48.0]);
    let mut buf = vec![[0.0f32; 2]; dims[0] * dims[1]];
    let r = c.region([0.0, 0.0], [64.0, 48.0], &mut buf).unwrap();
    let mut rng = Rng(3);
    for _ in 0..2000 {
        let x = [
            (rng.unit_f64() * 64.0) as f32,
            (rng.unit_f64() * 48.0) as f32,
        ];
        let (a, b) = (r.k_nearest::<4>(x), c.k_nearest::<4>(x));
        for n in 0..4 {
            assert_eq!(a[n].site, b[n].site);
            assert!((a[n].distance - b[n].distance).abs() < 1e-4);
        }
        let cells = r.cells(x);
        assert!(cells.f2_minus_f1() >= 0.0 && cells.foam12(0.06).is_finite());
        assert!(cells.foam11(2.0, 0.06).is_finite());
    }
    // The row fast path equals per-pixel queries, inside the cache and beyond it (fallback).
    for y in [0.5f32, 13.25, 47.5, 80.0] {
        let mut row = vec![0.0f32; 90];
        r.f1_row(y, -10.0, 0.9, &mut row);
        for (k, &v) in row.iter().enumerate() {
            let x = -10.0 + k as f32 * 0.9;
            let want = c.closest([x, y]).distance;
            assert!((v - want).abs() < 1e-3, "({x}, {y}): {v} vs {want}");
        }
    }
    assert!(c.region([0.0, 0.0], [64.0, 48.0], &mut buf[..10]).is_none());
}

#[test]
fn velocity_fields_are_divergence_free() {
    let mut rng = Rng(9);
    let h = 1e-3;
    for _ in 0..200 {
        let p = [rng.unit_f64() * 50.0, rng.unit_f64() * 50.0];
        let v = |q: [f64; 2]| velocity2(q, 2.86207, 0);
        let div = (v([p[0] + h, p[1]])[0] - v([p[0] - h, p[1]])[0] + v([p[0], p[1] + h])[1]
            - v([p[0], p[1] - h])[1]) as f64
            / (2.0 * h);
        assert!(div.abs() < 2e-2, "2D divergence {div}");
        let q = [p[0], p[1], rng.unit_f64() * 50.0];
        let w = |q: [f64; 3]| velocity3(q, 2.5, 0);
        let mut div3 = 0.0;
        for a in 0..3 {
            let (mut hi, mut lo) = (q, q);
            hi[a] += h;
            lo[a] -= h;
            div3 += (w(hi)[a] - w(lo)[a]) as f64 / (2.0 * h);
        }
        assert!(div3.abs() < 2e-2, "3D divergence {div3}");
        let sos = SumOfSines3::new(4);
        let mut div_s = 0.0;
        for a in 0..3 {
            let (mut hi, mut lo) = (q, q);
            hi[a] += h;
            lo[a] -= h;
            div_s += (sos.velocity(hi, 2.5)[a] - sos.velocity(lo, 2.5)[a]) as f64 / (2.0 * h);
        }
        assert!(div_s.abs() < 5e-2, "sum-of-sines divergence {div_s}");
    }
}

#[test]
fn displacement_3d_stays_below_its_bound_and_queries_are_exact() {
    for (lattice, potential) in [
        (Lattice3::Bcc, Potential3::Gradient),
        (Lattice3::Cubic, Potential3::Gradient),
        (Lattice3::Bcc, Potential3::SumOfSines),
    ] {
        let c = Cnj3::default()
            .with_lattice(lattice)
            .with_potential(potential);
        let bound = c.max_displacement() as f32;
        let mut max: f32 = 0.0;
        for k in -12..12 {
            for j in -12..12 {
                for i in -12..12 {
                    for b in 0..2 {
                        let d = c.displacement([i, j, k, b]);
                        max = max.max((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
                    }
                }
            }
        }
        eprintln!("{lattice:?} {potential:?}: max displacement {max:.3} (bound {bound:.3})");
        assert!(max < bound, "{max} vs bound {bound}");
        let subs = if lattice == Lattice3::Bcc { 2 } else { 1 };
        let mut pts = Vec::new();
        for k in -7..7 {
            for j in -7..7 {
                for i in -7..7 {
                    for b in 0..subs {
                        pts.push((c.point_f64([i, j, k, b]), [i, j, k, b]));
                    }
                }
            }
        }
        let mut rng = Rng(5);
        for _ in 0..300 {
            let x = [0, 1, 2].map(|_| rng.unit_f64() * 6.0 - 3.0);
            let mut d: Vec<(f64, [i32; 4])> = pts
                .iter()
                .map(|(p, s)| {
                    (
                        (0..3).map(|a| (p[a] - x[a]).powi(2)).sum::<f64>().sqrt(),
                        *s,
                    )
                })
                .collect();
            d.sort_by(|a, b| a.0.total_cmp(&b.0));
            let k = c.k_nearest_f64::<4>(x);
            for n in 0..4 {
                assert_eq!(k[n].site, d[n].1, "{lattice:?} {x:?} rank {n}");
            }
            assert_eq!(c.k_nearest_f64::<1>(x)[0].site, d[0].1);
        }
    }
}

#[test]
fn huge_and_odd_inputs_never_give_nan() {
    let c = Cnj2::default();
    let c3 = Cnj3::default();
    for v in [0.0f32, 1e7, -1e7, 3.5e9, -1e20, f32::MAX, f32::MIN] {
        let n = c.closest([v, -v]);
        assert!(
            n.distance.is_finite() && n.point.iter().all(|x| x.is_finite()),
            "{v}"
        );
        assert!(c.cells([v, 0.5]).d.iter().all(|x| x.is_finite()));
        let n3 = c3.closest([v, 0.25, -v]);
        assert!(n3.distance.is_finite(), "{v}");
    }
    // Parameters no lattice can have are errors naming the parameter and the value, where a
    // spacing of 0 or -1 once acted silently as 1.
    let d = Cnj2::default();
    for (bad, what) in [
        (d.with_scale(0.0), "cell size"),
        (d.with_scale(f32::NAN), "cell size"),
        (d.with_time(f32::INFINITY), "time"),
        (
            d.with_spacing(-1.0),
            "spacing must be finite and positive, got -1",
        ),
        (
            d.with_spacing(0.0),
            "spacing must be finite and positive, got 0",
        ),
        (
            d.with_integrator(Integrator::Euler).with_steps(1000),
            "steps",
        ),
    ] {
        let e = bad.unwrap_err().to_string();
        assert!(e.contains(what), "{e}");
    }
    let euler = d.with_integrator(Integrator::Euler).with_steps(64).unwrap();
    assert!(euler.closest([3.3, -7.1]).distance.is_finite());
    // Sites far from the origin are exact: the displacement depends only on the site.
    let far = c.displacement([2_000_000_000, -2_000_000_001]);
    assert!(far.iter().all(|x| x.is_finite() && x.abs() < 1.2));
}
