//! Same spec, same bytes: across runs, thread counts, and (through the golden digests below)
//! debug and release builds and machines.

use build_assets::cache::fnv64 as fnv;
use build_assets::generate;
use noisebake_test_support::bake::spec;

const SPECS: &[&str] = &[
    "kind = \"blue2d\"\ndims = [32, 32]\nseed = 1\nformat = \"u16\"",
    "kind = \"stbn\"\ndims = [16, 16, 8]\nseed = 7\nformat = \"u8\"",
    "kind = \"vac\"\ndims = [8, 8, 4, 4]\nseed = 3\nformat = \"f32\"\ngroups = [{ axes = [0, 1] }, { axes = [2] }, { axes = [3] }]",
    "kind = \"independent2d\"\ndims = [16, 16, 4]\nseed = 2",
    "kind = \"golden\"\ndims = [16, 16, 4]\nseed = 2\nformat = \"u16\"",
    "kind = \"white\"\ndims = [16, 16, 4]\nseed = 2",
    // EA's history rejection (β 0.1), the default before 0.1.0.
    "kind = \"fast\"\ndims = [16, 16, 4]\nseed = 5\nformat = \"u16\"\niterations = 4\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }",
    "kind = \"fast\"\ndims = [16, 16, 2]\nseed = 5\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 3 }\niterations = 3\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }\nstart = \"random\"",
    // The default temporal filter, the plain EMA (β 0).
    "kind = \"fast\"\ndims = [16, 16, 4]\nseed = 5\nformat = \"u16\"\niterations = 4",
    "kind = \"fast\"\ndims = [16, 16, 2]\nseed = 5\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 3 }\niterations = 3\nstart = \"random\"",
    // The default starts of two-value spaces: the free pair (ign_r2 under a box, rd_ign_r2
    // otherwise), which go through the runtime's f32 warps.
    "kind = \"fast\"\ndims = [16, 16, 2]\nseed = 5\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 3 }\niterations = 3",
    "kind = \"fast\"\ndims = [16, 16, 4]\nseed = 5\nsample_space = \"sphere\"\nformat = \"u16x3\"\nspatial_filter = { kind = \"gauss\", sigma = 1.0 }\niterations = 3",
    // A sampler tile: two pairs run on their own threads, a lone third dimension.
    "kind = \"sampler\"\ndims = [16, 16]\nseed = 5\nspp = 4\nsample_dims = 3\nspatial_filter = { kind = \"box\", size = 3 }",
];

#[test]
fn output_does_not_depend_on_the_thread_count() {
    for body in SPECS {
        let s = spec(body);
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| generate(&s, &mut |_, _| {}));
        let three = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap()
            .install(|| generate(&s, &mut |_, _| {}));
        assert_eq!(one.data, three.data, "{body}");
    }
}

/// Byte-exact goldens. If a change alters these on purpose, bump
/// `build_assets::ALGORITHM_VERSION` (cached textures must regenerate) and update the digests.
#[test]
fn output_matches_the_golden_digests() {
    let digests: Vec<u64> = SPECS
        .iter()
        .map(|b| fnv(&generate(&spec(b), &mut |_, _| {}).data))
        .collect();
    eprintln!("{digests:#018x?}");
    assert_eq!(
        digests,
        GOLDEN,
        "generator output changed: bump ALGORITHM_VERSION (now {}) and update GOLDEN",
        build_assets::ALGORITHM_VERSION
    );
}

const GOLDEN: [u64; 13] = [
    0x02bcc607887f687d,
    0xcb5fdf9617060b15,
    0x893f58b1ed87e261,
    0x21a8de4dc539ee8f,
    0xfd30af622a49b1ad,
    0x678bc41f284dccd3,
    0xf207ee1257430205,
    0x66b74f98b2fb8569,
    0x3e25ae57aee1bfd5,
    0xec72c00d766b7a25,
    0x1a6fc64ea2ffa362,
    0xd569656c31a8846c,
    0xaa939a8993754d8b,
];
