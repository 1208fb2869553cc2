//! Value stability, in the manner of `rand`'s: exact outputs of the runtime's functions at fixed
//! inputs. A game that seeds its world with these functions sees every pinned value again on
//! every target, so **changing any value here is a breaking change for every game that uses
//! it**: bump the major version and say so in the changelog, never "fix" the table quietly.

use noise_runtime::cnj::{Cnj2, Cnj3};
use noise_runtime::sequence::r2_point;
use noise_runtime::stochastic::*;
use noise_runtime::{Mask3, ldg};

/// The inputs every pinned function is evaluated at.
const P: [[f32; 3]; 4] = [
    [0.3, 1.7, -2.2],
    [123.456, -78.9, 0.001],
    [-1e4, 5e3, 33.25],
    [0.0, 0.0, 0.0],
];
const XI: [f32; 4] = [0.0, 0.25, 0.618, 0.999];

fn bits(v: impl IntoIterator<Item = f32>) -> Vec<u32> {
    v.into_iter().map(f32::to_bits).collect()
}

/// Compares, and on a mismatch prints the whole new table so a deliberate (major-version)
/// change can be reviewed value by value. `NOISEBAKE_PRINT_PINS=1` prints every table as Rust
/// instead (for that review), without failing.
fn check(name: &str, got: Vec<u32>, want: &[u32]) {
    if std::env::var_os("NOISEBAKE_PRINT_PINS").is_some() {
        let items: Vec<String> = got.iter().map(|v| format!("{v:#010x}")).collect();
        println!("PIN {name}: [{}]", items.join(", "));
        return;
    }
    if got != want {
        panic!("{name} changed: now {got:#010x?}, pinned {want:#010x?}");
    }
}

#[test]
fn lattice_noise_is_pinned() {
    check(
        "perlin3",
        bits(P.map(|p| Perlin::new(7).sample(p))),
        &PERLIN3,
    );
    check(
        "fbm3",
        bits(P.map(|p| Fbm::new(Fractal::default(), 7).sample(p))),
        &FBM3,
    );
    check(
        "perlin3_stochastic",
        bits(
            P.iter()
                .zip(XI)
                .map(|(&p, x)| Perlin::new(7).estimate(p, x)),
        ),
        &PERLIN3_STOCHASTIC,
    );
    check(
        "fbm3_stochastic",
        bits(
            P.iter()
                .zip(XI)
                .map(|(&p, x)| Fbm::new(Fractal::default(), 7).estimate(p, x)),
        ),
        &FBM3_STOCHASTIC,
    );
    check(
        "simplex3",
        bits(P.map(|p| Simplex::new(7).sample(p))),
        &SIMPLEX3,
    );
    check(
        "worley3_f1",
        bits(P.map(|p| Worley::new(7).f1(p))),
        &WORLEY3,
    );
    check(
        "sparse_conv3_stochastic",
        bits(
            P.iter()
                .zip(XI)
                .map(|(&p, x)| SparseConvolution::new(10, 7).estimate(p, x)),
        ),
        &SPARSE3_STOCHASTIC,
    );
}

#[test]
fn grids_and_offsets_are_pinned() {
    let at = [(0, 0), (17, -3), (-1000, 2047), (i32::MAX, i32::MIN)];
    check("r2", bits(at.map(|(x, y)| ldg::r2(x, y))), &R2);
    check("ign", bits(at.map(|(x, y)| ldg::ign(x, y))), &IGN);
    check("plus", bits(at.map(|(x, y)| ldg::plus(x, y))), &PLUS);
    check(
        "bayer8",
        bits(at.map(|(x, y)| ldg::bayer::<8>(x, y))),
        &BAYER8,
    );
    check(
        "r2_frame",
        bits(at.map(|(x, y)| ldg::r2_frame(x, y, 12345))),
        &R2_FRAME,
    );
    let pts: Vec<u32> = [0u32, 1, 1000, u32::MAX, 7, 1 << 20, 123_456_789, 1 << 31]
        .iter()
        .flat_map(|&k| {
            let (a, b) = r2_point(k);
            [a, b]
        })
        .collect();
    check("r2_point", pts, &R2_POINT);
    // The k-th value of a mask texel goes through the R2 offset: pin where it reads.
    static BYTES: [u8; 64] = {
        let mut b = [0u8; 64];
        let mut i = 0;
        while i < 64 {
            b[i] = i as u8;
            i += 1;
        }
        b
    };
    let m: Mask3<u8, 4, 4, 4> = Mask3::new(&BYTES);
    let ks: Vec<u32> = (0..8).map(|k| m.get_k(1, 2, 3, k) as u32).collect();
    check("get_k", ks, &GET_K);
}

#[test]
fn cnj_is_pinned() {
    let q = [[0.3f32, 1.7], [123.456, -78.9], [-1e4, 5e3], [0.0, 0.0]];
    let c2 = Cnj2::default();
    check(
        "cnj2 closest",
        bits(q.iter().flat_map(|&x| c2.closest(x).point)),
        &CNJ2,
    );
    let c3 = Cnj3::default();
    check(
        "cnj3 closest",
        bits(P.iter().flat_map(|&x| c3.closest(x).point)),
        &CNJ3,
    );
}

const PERLIN3: [u32; 4] = [0x3d4c35b8, 0xbdc14afd, 0xbd9f0000, 0x00000000];
const FBM3: [u32; 4] = [0xbe08fd3f, 0xbe52ce1b, 0xbe4f8000, 0x00000000];
const PERLIN3_STOCHASTIC: [u32; 4] = [0xbf7fffff, 0xbdced84a, 0x00000000, 0x00000000];
const FBM3_STOCHASTIC: [u32; 4] = [0xbfffbfff, 0xbe4ea494, 0x80000000, 0x00000000];
const SIMPLEX3: [u32; 4] = [0x3e8383ce, 0xbed5ac9b, 0xbd89c160, 0x00000000];
const WORLEY3: [u32; 4] = [0x3f21afd6, 0x3ef3cb3a, 0x3f2a932d, 0x3f123a30];
const SPARSE3_STOCHASTIC: [u32; 4] = [0x3c8977ae, 0x3ec20a8a, 0xbd92ab64, 0x3ddcd5bf];
const R2: [u32; 4] = [0x00000000, 0x3dfcb8d8, 0x3f15dd64, 0x3f5c4432];
const IGN: [u32; 4] = [0x00000000, 0x3f09518a, 0x3ecef93b, 0x3e086fb1];
const PLUS: [u32; 4] = [0x3dcccccd, 0x3f333333, 0x3e99999a, 0x3f333333];
const BAYER8: [u32; 4] = [0x3c000000, 0x3e9c0000, 0x3f7e0000, 0x3f2a0000];
const R2_FRAME: [u32; 4] = [0x3f212ce2, 0x3f40c3fd, 0x3e5c2918, 0x3efae228];
const R2_POINT: [u32; 16] = [
    0x00000000, 0x00000000, 0xc13fa9a9, 0x91e10da5, 0xe0aebc32, 0xd71d4f93, 0x416688e5, 0x35bd6d76,
    0x48bda39f, 0xfd275f88, 0x9a902a63, 0xda5c79e7, 0xc33bbe72, 0x91c72a26, 0x81531947, 0xe3cf3d8e,
];
const GET_K: [u32; 8] = [
    0x00000039, 0x00000030, 0x0000003b, 0x00000032, 0x0000003d, 0x00000034, 0x0000003f, 0x00000036,
];
const CNJ2: [u32; 8] = [
    0x3f078eb4, 0x4002f7bc, 0x42f6162f, 0xc29da5ce, 0xc61c3ecf, 0x459c3e59, 0x3eb4ab42, 0xbedb9757,
];
const CNJ3: [u32; 12] = [
    0x3e9f56ac, 0x3fc8f7e6, 0xc0252836, 0x42f5e88f, 0xc29dd035, 0x3d662528, 0xc61c4045, 0x459c3f8e,
    0x4203851a, 0x3e042303, 0x3e04c45e, 0xbe76f53f,
];

/// Inputs for the fingerprints: every triple of values that are hard for the lattice split
/// (±0, the smallest subnormal, integers and their neighbouring floats, the edge of the fast
/// split's range 2^22, coordinates far beyond it, ±∞, NaN), then random points at three
/// scales; with ξ cycling through odd values (0, −0, just below 1, 1, 2, −1, NaN) and random
/// ones.
fn fingerprint_inputs() -> Vec<([f32; 4], f32)> {
    let hard = [
        0.0f32,
        -0.0,
        1e-45,
        1.0,
        f32::from_bits(1.0f32.to_bits() + 1),
        -1.0,
        -2.5,
        4_194_303.5,
        -4_194_304.0,
        1e7,
        -3e38,
        f32::INFINITY,
        f32::NAN,
    ];
    let odd_xi = [0.0f32, -0.0, 0.99999994, 1.0, 2.0, -1.0, f32::NAN];
    let mut s = 0x0123_4567_89ab_cdefu64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / 16_777_216.0
    };
    let n = hard.len();
    let mut v = Vec::new();
    for i in 0..n * n * n {
        let p = [
            hard[i % n],
            hard[i / n % n],
            hard[i / n / n],
            hard[(i * 7) % n],
        ];
        let xi = if i % 2 == 0 {
            odd_xi[i / 2 % odd_xi.len()]
        } else {
            next()
        };
        v.push((p, xi));
    }
    for scale in [3.0f32, 500.0, 3e6] {
        for _ in 0..3000 {
            let p = [0; 4].map(|_| (next() - 0.5) * scale);
            v.push((p, next()));
        }
    }
    v
}

/// FNV-1a over the bits of every output.
fn fingerprint(mut f: impl FnMut([f32; 4], f32) -> f32) -> u64 {
    fingerprint_inputs()
        .into_iter()
        .fold(0xcbf2_9ce4_8422_2325, |h, (p, xi)| {
            (h ^ f(p, xi).to_bits() as u64).wrapping_mul(0x100_0000_01b3)
        })
}

/// Every noise, deterministic and estimator, 2D to 4D, at ten thousand inputs including the
/// hard ones above, folded into one number each: the explicit pins above show values, these
/// catch a change anywhere, also far outside the fast paths' ranges and on the portable path.
#[test]
fn every_noise_is_pinned_by_fingerprint() {
    let p2 = |p: [f32; 4]| [p[0], p[1]];
    let p3 = |p: [f32; 4]| [p[0], p[1], p[2]];
    let gabor = GaborNoise::new(Gabor::default(), 7);
    let got: Vec<(&str, u64)> = vec![
        ("perlin2", fingerprint(|p, _| Perlin::new(7).sample(p2(p)))),
        ("perlin3", fingerprint(|p, _| Perlin::new(7).sample(p3(p)))),
        ("perlin4", fingerprint(|p, _| Perlin::new(7).sample(p))),
        (
            "perlin2 estimate",
            fingerprint(|p, x| Perlin::new(7).estimate(p2(p), x)),
        ),
        (
            "perlin3 estimate",
            fingerprint(|p, x| Perlin::new(7).estimate(p3(p), x)),
        ),
        (
            "perlin4 estimate",
            fingerprint(|p, x| Perlin::new(7).estimate(p, x)),
        ),
        (
            "perlin3 gradient",
            fingerprint(|p, _| Perlin::new(7).gradient(p3(p)).1[1]),
        ),
        (
            "simplex2",
            fingerprint(|p, _| Simplex::new(7).sample(p2(p))),
        ),
        (
            "simplex3",
            fingerprint(|p, _| Simplex::new(7).sample(p3(p))),
        ),
        ("simplex4", fingerprint(|p, _| Simplex::new(7).sample(p))),
        (
            "simplex3 estimate",
            fingerprint(|p, x| Simplex::new(7).estimate(p3(p), x)),
        ),
        (
            "simplex4 estimate",
            fingerprint(|p, x| Simplex::new(7).estimate(p, x)),
        ),
        (
            "fbm3",
            fingerprint(|p, _| Fbm::new(Fractal::default(), 7).sample(p3(p))),
        ),
        (
            "fbm3 estimate",
            fingerprint(|p, x| Fbm::new(Fractal::default(), 7).estimate(p3(p), x)),
        ),
        (
            "fbm3 odd estimate",
            fingerprint(|p, x| Fbm::new(Fractal::new(5, 2.5, 0.6), 7).estimate(p3(p), x)),
        ),
        (
            "sparse3",
            fingerprint(|p, _| SparseConvolution::new(6, 7).sample(p3(p))),
        ),
        (
            "sparse3 estimate",
            fingerprint(|p, x| SparseConvolution::new(6, 7).estimate(p3(p), x)),
        ),
        ("gabor3", fingerprint(|p, _| gabor.sample(p3(p)))),
        (
            "gabor3 estimate",
            fingerprint(|p, x| gabor.estimate(p3(p), x)),
        ),
        (
            "smooth voronoi",
            fingerprint(|p, _| SmoothVoronoi::new(7).sample(p3(p))),
        ),
        (
            "smooth voronoi estimate",
            fingerprint(|p, x| SmoothVoronoi::new(7).estimate(p3(p), x)),
        ),
        ("worley f1", fingerprint(|p, _| Worley::new(7).f1(p3(p)))),
    ];
    let got_table: Vec<String> = got
        .iter()
        .map(|(n, h)| format!("(\"{n}\", {h:#018x}),"))
        .collect();
    if std::env::var_os("NOISEBAKE_PRINT_PINS").is_some() {
        println!("PIN fingerprints:\n{}", got_table.join("\n"));
        return;
    }
    assert_eq!(got.len(), FINGERPRINTS.len());
    for (&(name, h), &(want_name, want)) in got.iter().zip(FINGERPRINTS.iter()) {
        assert_eq!(name, want_name);
        assert_eq!(
            h, want,
            "{name} changed (fingerprint {h:#018x}, pinned {want:#018x})"
        );
    }
}

const FINGERPRINTS: [(&str, u64); 22] = [
    ("perlin2", 0x50d27b71aff50a97),
    ("perlin3", 0x362bb67204687e79),
    ("perlin4", 0x86a2b3545cb5c661),
    ("perlin2 estimate", 0xbdda984f15a01cf0),
    ("perlin3 estimate", 0x9c9934386532d00d),
    ("perlin4 estimate", 0x2a77a7cb762c4107),
    ("perlin3 gradient", 0x676f4352336ac3f4),
    ("simplex2", 0x5f6fea845fa18cb7),
    ("simplex3", 0x02e6993569ef0855),
    ("simplex4", 0xa9b49d7e3e0a1059),
    ("simplex3 estimate", 0x530c0f59241a611c),
    ("simplex4 estimate", 0x2542b6820f7a5fc8),
    ("fbm3", 0xf57c6bc754c640cf),
    ("fbm3 estimate", 0x59caa1f683a6fed3),
    ("fbm3 odd estimate", 0xd24acc9e6a4eec83),
    ("sparse3", 0x7f1d2cb6e8b94cc0),
    ("sparse3 estimate", 0xb69ed9570add7859),
    ("gabor3", 0xce0fac8fd73c121c),
    ("gabor3 estimate", 0x8f75f0e214a09833),
    ("smooth voronoi", 0x2df408ea7ae096fc),
    ("smooth voronoi estimate", 0xdb1fa98b5702159f),
    ("worley f1", 0x85a29ab3030db7ee),
];

#[test]
fn samplers_are_pinned() {
    use noise_runtime::sampler;
    let at = [
        (0, 0, 0u32),
        (5, -3, 7),
        (-1000, 250, 99),
        (i32::MAX, i32::MIN, u32::MAX),
    ];
    check(
        "ign_r2",
        bits(
            at.iter()
                .flat_map(|&(x, y, f)| sampler::ign_r2::<4>(x, y, f)),
        ),
        &[
            0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x3dba9318, 0x3ec83ef6, 0x3f449f1c,
            0x3b95f100, 0x3ecfb39e, 0x3f448caa, 0x3eca5118, 0x3f2045cc, 0x3da77c08, 0x3f3d5734,
            0x3f654936, 0x3eed4c06,
        ],
    );
    check(
        "rd_ign_r2",
        bits(at.iter().flat_map(|&(x, y, f)| {
            let a = sampler::rd_ign_r2::<2>(x, y, f);
            let b = sampler::rd_ign_r2::<3>(x, y, f);
            a.into_iter().chain(b)
        })),
        &[
            0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x3e0a23f0, 0x3d5c2860,
            0x3f15c05f, 0x3f431dc0, 0x3ea9e354, 0x3e56847c, 0x3f7f20de, 0x3f131e35, 0x3c80cea0,
            0x3da92e88, 0x3ec704ea, 0x3d900cf8, 0x3e07e63c, 0x3e302968, 0x3e8cce1e,
        ],
    );
    check(
        "sobol_owen",
        bits(
            at.iter()
                .flat_map(|&(x, y, f)| sampler::sobol_owen::<4>(x, y, f, 3)),
        ),
        &[
            0x3e899302, 0x3eca7c46, 0x3f7a7954, 0x3f449ffe, 0x3f200c5e, 0x3f27b6d0, 0x3ec317c4,
            0x3eddb1a6, 0x3f25cc85, 0x3e0aac60, 0x3e087734, 0x3d8e2e20, 0x3f12da61, 0x3eb4e930,
            0x3f4f2f97, 0x3c8d0da0,
        ],
    );
    check(
        "r2_pairs",
        bits(
            at.iter()
                .flat_map(|&(x, y, f)| sampler::r2_pairs::<4>(x, y, f)),
        ),
        &[
            0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x3e0a23f0, 0x3d5c2860, 0x3f449f1c,
            0x3f59db99, 0x3e56847c, 0x3f7f20de, 0x3eca5118, 0x3e79f3d4, 0x3ec704ea, 0x3d900cf8,
            0x3f654936, 0x3e35cc98,
        ],
    );
    // The sampler built for motion, at 1, 4, 5 and 20 samples a frame (5: a lattice whose N
    // does not divide 2^32; 20: two blocks of the 16-sample design), checked against a
    // computation outside the crate from the constants of MOTION_PAIRS.
    check(
        "motion_pairs",
        bits(
            at.iter()
                .zip([1u32, 4, 5, 20])
                .flat_map(|(&(x, y, f), spp)| sampler::motion_pairs::<4>(x, y, f, spp - 1, spp)),
        ),
        &[
            0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x3f67342c, 0x3ea529ae, 0x3f6c05a7,
            0x3e8bc342, 0x3f764815, 0x3ecb20dc, 0x3d9629c8, 0x3f032f0c, 0x3e751a5c, 0x3f5c1546,
            0x3e7dab88, 0x3f436240,
        ],
    );
    // A baked tile's points: the rank-1 lattice's point n in dimension d (n bit-reversed times
    // the generator) shifted by a key (lattice pairs), or Sobol's Owen-scrambled by it (pairs
    // flagged in the last field); both checked against a computation outside the crate.
    let points = [
        (0u32, 0u32, 4u32, 0u16, 0u8),
        (7, 3, 4, 0x1234, 0),
        (u32::MAX, 1, 2, 0xffff, 0),
        (40_000, 7, 8, 9, 0),
        (5, 0, 4, 0x8001, 0b01),
        (0x0123_4567, 3, 4, 0x00ff, 0b10),
        (u32::MAX, 1, 2, 0xffff, 0b01),
        (40_000, 6, 8, 9, 0b1000),
    ];
    check(
        "sampler tile",
        points
            .iter()
            .map(|&(n, d, dims, key, sobol)| sampler::tile_point(n, d, dims, key, sobol))
            .collect(),
        &[
            0x00000000, 0x72340000, 0xfffe4613, 0x949e0000, 0x95449f9b, 0x3cb1c621, 0x6fd4bb4e,
            0x39998cc2,
        ],
    );
}
