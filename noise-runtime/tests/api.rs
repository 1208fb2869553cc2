//! The API shape: every noise type's verbs compute exactly what the free functions of earlier
//! releases compute (now deprecated aliases, kept one release), bit for bit, and every mask
//! dimension has the same methods.
#![allow(deprecated)]

use noise_runtime::stochastic::*;
use noise_runtime::{Mask2, Mask3, Mask4};

fn points() -> Vec<([f32; 4], f32)> {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut u = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / 16_777_216.0
    };
    (0..2000)
        .map(|_| {
            let p = [0.0; 4].map(|_| u() * 40.0 - 20.0);
            (p, u())
        })
        .collect()
}

macro_rules! same {
    ($a:expr, $b:expr, $what:expr) => {{
        let (a, b) = ($a, $b);
        assert_eq!(format!("{a:?}"), format!("{b:?}"), "{}", $what);
    }};
}

#[test]
fn noise_types_are_the_functions_they_replace() {
    let f = Fractal::new(7, 2.0, 0.5);
    let g = Fractal::new(5, 1.9, -0.6);
    let gabor = GaborNoise::new(Gabor::default(), 3);
    for (p, xi) in points() {
        let (p2, p3) = ([p[0], p[1]], [p[0], p[1], p[2]]);
        let (pe, si) = (Perlin::new(3), Simplex::new(3));
        same!(pe.sample(p2), perlin2(p2, 3), "perlin2");
        same!(pe.sample(p3), perlin3(p3, 3), "perlin3");
        same!(pe.sample(p), perlin4(p, 3), "perlin4");
        same!(
            pe.estimate(p2, xi),
            perlin2_stochastic(p2, 3, xi),
            "perlin2 estimate"
        );
        same!(
            pe.estimate(p3, xi),
            perlin3_stochastic(p3, 3, xi),
            "perlin3 estimate"
        );
        same!(
            pe.estimate(p, xi),
            perlin4_stochastic(p, 3, xi),
            "perlin4 estimate"
        );
        same!(pe.gradient(p2), perlin2_grad(p2, 3), "perlin2 gradient");
        same!(pe.gradient(p3), perlin3_grad(p3, 3), "perlin3 gradient");
        same!(pe.gradient(p), perlin4_grad(p, 3), "perlin4 gradient");
        same!(si.sample(p2), simplex2(p2, 3), "simplex2");
        same!(si.sample(p3), simplex3(p3, 3), "simplex3");
        same!(si.sample(p), simplex4(p, 3), "simplex4");
        same!(
            si.estimate(p2, xi),
            simplex2_stochastic(p2, 3, xi),
            "simplex2 estimate"
        );
        same!(
            si.estimate(p3, xi),
            simplex3_stochastic(p3, 3, xi),
            "simplex3 estimate"
        );
        same!(
            si.estimate(p, xi),
            simplex4_stochastic(p, 3, xi),
            "simplex4 estimate"
        );
        same!(si.gradient(p3), simplex3_grad(p3, 3), "simplex3 gradient");
        for fr in [f, g] {
            let fbm = Fbm::new(fr, 3);
            same!(fbm.sample(p3), fbm3(p3, fr, 3), "fbm3");
            same!(
                fbm.estimate(p3, xi),
                fbm3_stochastic(p3, fr, 3, xi),
                "fbm3 estimate"
            );
            // No exact octave is the full estimator's octave choice; all of them the sum.
            same!(
                fbm.estimate_tail(p3, 99, xi),
                fbm3(p3, fr, 3),
                "tail, all exact"
            );
            let sc = SparseConvolutionFbm::new(fr, 4, 3);
            same!(sc.sample(p3), fbm_sparse_conv3(p3, fr, 4, 3), "fbm sparse");
            same!(
                sc.estimate(p3, xi),
                fbm_sparse_conv3_stochastic(p3, fr, 4, 3, xi),
                "fbm sparse estimate"
            );
            same!(
                sc.estimate_one_term(p3, xi),
                fbm_sparse_conv3_stochastic1(p3, fr, 4, 3, xi),
                "fbm sparse one-term"
            );
        }
        let sc = SparseConvolution::new(10, 3);
        same!(sc.sample(p3), sparse_conv3(p3, 10, 3), "sparse");
        same!(
            sc.estimate(p3, xi),
            sparse_conv3_stochastic(p3, 10, 3, xi),
            "sparse estimate"
        );
        same!(
            sc.estimate_one_term(p3, xi),
            sparse_conv3_stochastic1(p3, 10, 3, xi),
            "sparse one-term"
        );
        same!(gabor.sample(p3), gabor3(p3, Gabor::default(), 3), "gabor");
        same!(
            gabor.estimate(p3, xi),
            gabor3_stochastic(p3, Gabor::default(), 3, xi),
            "gabor estimate"
        );
        let sv = SmoothVoronoi::new(3);
        same!(sv.sample(p3), smooth_voronoi3(p3, 3), "voronoi");
        same!(
            sv.estimate(p3, xi),
            smooth_voronoi3_stochastic(p3, 3, SMOOTH_VORONOI_Q, xi),
            "voronoi estimate"
        );
        same!(Worley::new(3).f1(p3), worley3_f1(p3, 3), "worley");
    }
}

#[test]
fn batch_verbs_are_the_batch_functions() {
    let pts: Vec<[f32; 3]> = points().iter().map(|(p, _)| [p[0], p[1], p[2]]).collect();
    let xis: Vec<f32> = points().iter().map(|(_, x)| *x).collect();
    let f = Fractal::default();
    let (mut a, mut b) = (vec![0.0; pts.len()], vec![0.0; pts.len()]);
    Perlin::new(5).sample_batch(&pts, &mut a);
    perlin3_batch(&pts, 5, &mut b);
    assert_eq!(a, b);
    Perlin::new(5).estimate_batch(&pts, &xis, &mut a);
    perlin3_stochastic_batch(&pts, 5, &xis, &mut b);
    assert_eq!(a, b);
    Fbm::new(f, 5).sample_batch(&pts, &mut a);
    fbm3_batch(&pts, f, 5, &mut b);
    assert_eq!(a, b);
    Fbm::new(f, 5).estimate_batch(&pts, &xis, &mut a);
    fbm3_stochastic_batch(&pts, f, 5, &xis, &mut b);
    assert_eq!(a, b);
}

static BYTES: [u8; 4 * 4 * 2 * 3] = {
    let mut b = [0u8; 96];
    let mut i = 0;
    while i < 96 {
        b[i] = (i * 37 % 96) as u8;
        i += 1;
    }
    b
};

/// Every mask dimension has `get`, `get_unit`, `get_k`, `get_k_unit`, `get_pair_unit` and
/// `threshold`, and a higher-dimensional mask with unit extra axes reads as the lower one.
#[test]
fn every_mask_dimension_has_the_same_methods() {
    let m2: Mask2<u8, 4, 24> = Mask2::new(&BYTES);
    let m3: Mask3<u8, 4, 24, 1> = Mask3::new(&BYTES);
    let m4: Mask4<u8, 4, 24, 1, 1> = Mask4::new(&BYTES);
    for y in -30..30 {
        for x in -5..9 {
            for k in [0u32, 1, 7, 1000, u32::MAX] {
                assert_eq!(m2.get_k(x, y, k), m3.get_k(x, y, 0, k));
                assert_eq!(m2.get_k(x, y, k), m4.get_k(x, y, 0, 0, k));
                assert_eq!(m2.get_k_unit(x, y, k), m3.get_k_unit(x, y, 0, k));
                assert_eq!(m2.get_k_unit(x, y, k), m4.get_k_unit(x, y, 0, 0, k));
                assert_eq!(m2.get_pair_unit(x, y, k), m3.get_pair_unit(x, y, 0, k));
                assert_eq!(m2.get_pair_unit(x, y, k), m4.get_pair_unit(x, y, 0, 0, k));
            }
            assert_eq!(m2.get_k(x, y, 0), m2.get(x, y));
            assert_eq!(m2.get_unit(x, y), m4.get_unit(x, y, 0, 0));
            assert_eq!(m2.threshold(x, y, 0.5), m3.threshold(x, y, 0, 0.5));
        }
    }
}

/// Each coordinate takes its own integer type: a game's pixel as `i32` and its frame counter
/// as `u32` (as `ldg::ign_frame` takes them) need no cast, and read what one type would read.
#[test]
fn mask_coordinates_mix_integer_types() {
    let m3: Mask3<u8, 4, 12, 2> = Mask3::new(&BYTES);
    let m4: Mask4<u8, 4, 3, 2, 4> = Mask4::new(&BYTES);
    for frame in 0..7u32 {
        for y in 0..30usize {
            for x in -5..9i32 {
                let (yi, fi) = (y as i32, frame as i32);
                assert_eq!(m3.get(x, y, frame), m3.get(x, yi, fi));
                assert_eq!(m3.get_unit(x, y as u16, frame), m3.get_unit(x, yi, fi));
                assert_eq!(m3.threshold(x, yi, frame, 0.4), m3.threshold(x, yi, fi, 0.4));
                assert_eq!(m3.get_k_unit(x, yi, frame, 3), m3.get_k_unit(x, yi, fi, 3));
                assert_eq!(m3.get_pair_unit(x, y, frame, 1), m3.get_pair_unit(x, yi, fi, 1));
                assert_eq!(
                    m4.get_k(x, y as u64, frame, -1i64, 2),
                    m4.get_k(x, yi, fi, -1, 2)
                );
            }
        }
    }
}
