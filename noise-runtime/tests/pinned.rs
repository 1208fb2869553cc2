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
