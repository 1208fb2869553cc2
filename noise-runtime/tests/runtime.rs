//! Runtime behaviour: exact lookups, R2 offsets against a 128-bit reference, thresholds, warps,
//! and no panic / NaN / out-of-bounds read for any input.

use noise_runtime::sequence::{golden, r2_point, scale};
use noise_runtime::{Mask2, Mask3, Mask4, ldg, warp};
use proptest::prelude::*;

fn leak(v: Vec<u8>) -> &'static [u8] {
    Box::leak(v.into_boxed_slice())
}

/// A W×H×D u16 mask whose value at (x, y, t) is its index (so reads are checkable).
fn indexed<const W: u32, const H: u32, const D: u32>() -> Mask3<u16, W, H, D> {
    let n = (W * H * D) as usize;
    Mask3::new(leak(
        (0..n).flat_map(|i| (i as u16).to_le_bytes()).collect(),
    ))
}

/// `frac(k · α)` to 32 bits from α to 128 bits (constants from 80-digit decimal arithmetic).
fn reference(k: u32, alpha128: u128) -> u32 {
    ((k as u128).wrapping_mul(alpha128) >> 96) as u32
}
const A1_128: u128 = 0xc13fa9a902a6328f434ff71b2d97724b;
const A2_128: u128 = 0x91e10da5c79e7b1cd438a0a8e6c9c0fc;
const G_128: u128 = 0x9e3779b97f4a7c15f39cc0605cedc834;

#[test]
fn r2_and_golden_are_exact_at_large_indices() {
    for k in [
        0u32,
        1,
        2,
        1000,
        1 << 20,
        123_456_789,
        (1 << 31) - 1,
        1 << 31,
        u32::MAX,
    ] {
        let (x, y) = r2_point(k);
        for (got, want) in [
            (x, reference(k, A1_128)),
            (y, reference(k, A2_128)),
            (golden(k), reference(k, G_128)),
        ] {
            assert!(got.abs_diff(want) <= 1, "k = {k}: {got:#x} vs {want:#x}");
        }
    }
    // What f32 would have given at k = 2^31 − 1: nothing of the fraction survives.
    let k = (1u32 << 31) - 1;
    let f32_frac = (k as f32 * 0.754_877_7_f32).fract();
    assert_eq!(f32_frac, 0.0);
    assert!(reference(k, A1_128) != 0);
}

#[test]
fn get_wraps_toroidally_for_any_coordinates() {
    let m = indexed::<8, 4, 2>();
    let npot = indexed::<5, 3, 3>();
    for (x, y, t) in [
        (0i64, 0i64, 0i64),
        (-1, -1, -1),
        (9, 5, 7),
        (-1_000_000_007, 123_456_789, -3),
        (i32::MIN as i64, i32::MAX as i64, 1),
    ] {
        let want = (x.rem_euclid(8) + 8 * y.rem_euclid(4) + 32 * t.rem_euclid(2)) as u16;
        assert_eq!(m.get(x as i32, y as i32, t as i32), want, "{x} {y} {t}");
        assert_eq!(m.get(x, y, t), want);
        let want = (x.rem_euclid(5) + 5 * y.rem_euclid(3) + 15 * t.rem_euclid(3)) as u16;
        assert_eq!(
            npot.get(x as i32, y as i32, t as i32),
            want,
            "npot {x} {y} {t}"
        );
    }
    assert_eq!(m.get(u32::MAX, u32::MAX, u32::MAX), m.get(-1, -1, -1));
    assert_eq!(
        npot.get(u32::MAX, 0u32, 0u32),
        npot.get((u32::MAX % 5) as i32, 0, 0)
    );
}

#[test]
fn get_k_offsets_by_the_scaled_r2_point() {
    let m = indexed::<16, 8, 4>();
    for k in [0u32, 1, 7, 1 << 30, u32::MAX] {
        let (ox, oy) = r2_point(k);
        let (ox, oy) = (scale(ox, 16) as i32, scale(oy, 8) as i32);
        assert_eq!(m.get_k(3, -2, 5, k), m.get(3 + ox, -2 + oy, 5), "k = {k}");
    }
    assert_eq!(m.get_k(3, 4, 1, 0), m.get(3, 4, 1));
    let m2: Mask2<u8, 4, 4> = Mask2::new(leak((0..16).collect()));
    assert_eq!(m2.get_k(1, 1, 0), m2.get(1, 1));
    let m4: Mask4<u8, 2, 2, 2, 2> = Mask4::new(leak((0..16).collect()));
    assert_eq!(m4.get(-1, -1, -1, -1), 15);
    assert_eq!(m4.get_k(0, 0, 1, 1, 0), m4.get(0, 0, 1, 1));
}

#[test]
fn try_new_rejects_wrong_sizes() {
    assert!(Mask2::<u16, 4, 4>::try_new(leak(vec![0; 31])).is_err());
    assert!(Mask2::<u16, 4, 4>::try_new(leak(vec![0; 32])).is_ok());
    assert!(Mask2::<[u8; 3], 2, 2>::try_new(leak(vec![0; 12])).is_ok());
}

#[test]
fn thresholding_a_flat_histogram_mask_covers_p_to_within_one_texel() {
    // Every slice holds each of the 256 u16 levels r·256 once (a flat histogram).
    let mut bytes = Vec::new();
    for t in 0..3u32 {
        for i in 0..256u32 {
            let r = (i * 97 + t * 31) % 256;
            bytes.extend(((r * 256) as u16).to_le_bytes());
        }
    }
    let m: Mask3<u16, 16, 16, 3> = Mask3::new(leak(bytes));
    for t in 0..3 {
        for p in [0.0f32, 0.1, 0.2, 0.3, 0.4, 0.5, 0.77, 1.0] {
            let on = (0..16)
                .flat_map(|y| (0..16).map(move |x| (x, y)))
                .filter(|&(x, y)| m.threshold(x, y, t, p))
                .count();
            assert!((on as f32 - p * 256.0).abs() <= 1.0, "t {t} p {p}: {on}");
        }
    }
}

#[test]
fn vector_texels_decode_to_signed_unit_range() {
    let m: Mask2<[u8; 3], 1, 2> = Mask2::new(leak(vec![0, 128, 255, 255, 255, 0]));
    assert_eq!(m.get_signed(0, 0, 0), -1.0);
    assert!(m.get_signed(0, 0, 1).abs() < 0.01);
    assert_eq!(m.get_signed(0, 0, 2), 1.0);
    assert_eq!(m.get(0, 1), [255, 255, 0]);
}

#[test]
fn plus_neighbourhoods_hold_every_fifth_once() {
    for y in -20..20 {
        for x in -20..20 {
            let mut seen = [false; 5];
            for (dx, dy) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)] {
                let v = ldg::plus(x + dx, y + dy);
                seen[(v * 5.0) as usize] = true;
            }
            assert!(seen.iter().all(|&s| s), "({x}, {y})");
        }
    }
}

#[test]
fn grids_are_exact_at_huge_coordinates() {
    // Shifting by the grid's period gives the same value, however far out.
    assert_eq!(ldg::plus(10_000_000, 3), ldg::plus(10_000_000 - 5, 3));
    assert_eq!(
        ldg::bayer::<8>(10_000_000, -7),
        ldg::bayer::<8>(10_000_000 - 8, -7 + 8)
    );
    // R2 at x = 10^7 differs from its neighbour by exactly 1/ρ mod 1, as at the origin.
    let d = |x: i32| (ldg::r2(x + 1, 5) - ldg::r2(x, 5)).rem_euclid(1.0);
    assert!(
        (d(10_000_000) - d(0)).abs() < 1e-6,
        "{} {}",
        d(10_000_000),
        d(0)
    );
    let d = |x: i32| (ldg::ign(x + 1, 0) - ldg::ign(x, 0)).rem_euclid(1.0);
    assert!(d(10_000_000).is_finite());
    // Bayer 2×2 is [[0, 2], [3, 1]] / 4 (+ ½ level).
    let b: Vec<f32> = [(0, 0), (1, 0), (0, 1), (1, 1)]
        .iter()
        .map(|&(x, y)| ldg::bayer::<2>(x, y) * 4.0 - 0.5)
        .collect();
    assert_eq!(b, [0.0, 2.0, 3.0, 1.0]);
}

fn moments(f: impl Fn(f32, f32) -> [f32; 3], n: u32) -> ([f64; 3], [f64; 3]) {
    let (mut m1, mut m2) = ([0.0; 3], [0.0; 3]);
    for i in 0..n {
        let (u, v) = r2_point(i);
        let p = f(
            noise_runtime::sequence::to_unit(u),
            noise_runtime::sequence::to_unit(v),
        );
        for c in 0..3 {
            m1[c] += p[c] as f64 / n as f64;
            m2[c] += (p[c] * p[c]) as f64 / n as f64;
        }
    }
    (m1, m2)
}

#[test]
fn warps_have_the_right_measure() {
    let n = 1 << 16;
    let (m1, m2) = moments(warp::sphere_uniform, n);
    for c in 0..3 {
        assert!(
            m1[c].abs() < 2e-3 && (m2[c] - 1.0 / 3.0).abs() < 2e-3,
            "sphere {m1:?} {m2:?}"
        );
    }
    let (m1, m2) = moments(warp::hemisphere_uniform, n);
    assert!(
        (m1[2] - 0.5).abs() < 2e-3 && (m2[2] - 1.0 / 3.0).abs() < 2e-3,
        "hemisphere {m1:?} {m2:?}"
    );
    let (m1, m2) = moments(warp::cosine_hemisphere, n);
    // Cosine-weighted: E[z] = 2/3, E[z²] = 1/2.
    assert!(
        (m1[2] - 2.0 / 3.0).abs() < 2e-3 && (m2[2] - 0.5).abs() < 2e-3,
        "cosine {m1:?} {m2:?}"
    );
    let (m1, m2) = moments(
        |u, v| {
            let [x, y] = warp::disk_concentric(u, v);
            [x, y, x * x + y * y]
        },
        n,
    );
    // Uniform disk: E[r²] = 1/2, E[r⁴] = 1/3.
    assert!(
        m1[0].abs() < 2e-3 && (m1[2] - 0.5).abs() < 2e-3 && (m2[2] - 1.0 / 3.0).abs() < 2e-3,
        "disk {m1:?} {m2:?}"
    );
}

const EDGES: [f32; 5] = [0.0, 1.0, 0.999_999_94, 1e-30, 0.5];

#[test]
fn warps_are_safe_at_zero_and_one() {
    for &u in &EDGES {
        for &v in &EDGES {
            for d in [
                warp::sphere_uniform(u, v),
                warp::hemisphere_uniform(u, v),
                warp::cosine_hemisphere(u, v),
            ] {
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                assert!(
                    d.iter().all(|c| c.is_finite()) && (len - 1.0).abs() < 1e-5,
                    "{u} {v}: {d:?}"
                );
            }
            let [x, y] = warp::disk_concentric(u, v);
            assert!(x.is_finite() && y.is_finite() && x * x + y * y <= 1.0 + 1e-6);
        }
    }
}

proptest! {
    #[test]
    fn nothing_panics_or_returns_nan(x: i32, y: i32, t: i32, k: u32, frame: u32, u in proptest::num::f32::ANY, v in proptest::num::f32::ANY) {
        let m = indexed::<8, 4, 2>();
        let npot = indexed::<5, 3, 3>();
        let _ = (m.get(x, y, t), m.get_k(x, y, t, k), npot.get(x, y, t), npot.get_k(x, y, t, k));
        prop_assert!(m.get_k_unit(x, y, t, k) < 1.0);
        for g in [ldg::r2(x, y), ldg::plus(x, y), ldg::ign(x, y), ldg::bayer::<16>(x, y), ldg::r2_frame(x, y, frame), ldg::ign_frame(x, y, frame), ldg::plus_frame(x, y, frame), ldg::bayer_frame::<4>(x, y, frame)] {
            prop_assert!((0.0..1.0).contains(&g), "{g}");
        }
        for d in [warp::sphere_uniform(u, v), warp::hemisphere_uniform(u, v), warp::cosine_hemisphere(u, v)] {
            prop_assert!(d.iter().all(|c| c.is_finite()));
        }
        let [a, b] = warp::disk_concentric(u, v);
        prop_assert!(a.is_finite() && b.is_finite());
    }
}
