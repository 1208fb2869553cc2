//! FAST masks as the generator makes them (Donnelly et al. 2024): the loss falls monotonically
//! and is eq. 7 exactly, every slice keeps its stratified values, the bytes do not depend on
//! the thread count, vector masks store unit vectors, and bad specs name the key. The claims
//! about error after filtering, which need the CLI's analysis, are `noisebake-cli/tests/fast.rs`.

use build_assets::generate::fast::{
    self, Combine, Distribution, FastParams, Filter, SampleSpace, Start, TemporalFilter,
};
use noisebake_test_support::bake::{assert_slices_permuted, error, gen_tex};

/// EA's published texture's filter: Gaussian σ 1.3435 × EMA (α 0.1, β 0.1), scalars.
fn scalar_params(combine: Combine) -> FastParams {
    FastParams {
        sample_space: SampleSpace::Scalar,
        distribution: Distribution::Uniform,
        spatial: Filter::Gauss { sigma: 1.3435 },
        temporal: TemporalFilter::Ema {
            alpha: 0.1,
            beta: 0.1,
        },
        combine,
        iterations: None,
        start: Start::Random,
    }
}

fn run(params: &FastParams, dims: &[usize], seed: u64) -> fast::Outcome {
    fast::generate(params, dims, seed, &mut |_, _| {})
}

#[test]
fn loss_falls_monotonically_and_matches_eq7() {
    let p = scalar_params(Combine::Product);
    let dims = [24, 24, 6];
    let out = run(&p, &dims, 3);
    assert!(out.curve.len() > 3);
    let mut prev = 0.0;
    for pt in &out.curve {
        assert!(
            pt.decrease >= prev,
            "loss rose: decrease {prev} -> {}",
            pt.decrease
        );
        prev = pt.decrease;
    }
    let exact = fast::loss(&p, &dims, &out.samples);
    let start = fast::loss(&p, &dims, &fast::initial_samples(&p, &dims, 3));
    assert!((start - exact - out.decrease()).abs() < 1e-9 * exact.abs());
    assert!(exact < start);
}

#[test]
fn every_slice_keeps_its_stratified_values() {
    // Uniform scalars: each 32×32 slice holds every u16 rank bin exactly once.
    let t =
        gen_tex("kind = \"fast\"\ndims = [32, 32, 4]\nformat = \"u16\"\niterations = 3\nseed = 2");
    for slice in t.data.chunks(32 * 32 * 2) {
        let mut v: Vec<u16> = slice
            .chunks(2)
            .map(|c| u16::from_le_bytes([c[0], c[1]]))
            .collect();
        v.sort_unstable();
        let want: Vec<u16> = (0..1024).map(|r| (r * 64) as u16).collect();
        assert_eq!(v, want);
    }
    // Vectors: optimisation only permutes each slice's initial samples.
    let mut p = scalar_params(Combine::Product);
    p.sample_space = fast::SampleSpace::CosineHemisphere;
    p.iterations = Some(3);
    let dims = [20, 20, 3];
    let init = fast::initial_samples(&p, &dims, 9);
    let out = run(&p, &dims, 9);
    assert_slices_permuted(&init, &out.samples, 400);
}

#[test]
fn same_bytes_on_one_and_two_threads() {
    let p = scalar_params(Combine::Separate(0.3));
    let dims = [64, 32, 4];
    let pool = |n| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
    };
    let a = pool(1).install(|| run(&p, &dims, 11).samples);
    let b = pool(2).install(|| run(&p, &dims, 11).samples);
    assert_eq!(a, b);
}

#[test]
fn bad_fast_specs_name_the_key() {
    let has = |msg: String, parts: &[&str]| {
        for p in parts {
            assert!(msg.contains(p), "expected {p:?} in:\n{msg}");
        }
    };
    has(
        error("kind = \"fast\"\ndims = [8, 8, 4]\nspatial_filter = { kind = \"box\", size = 9 }"),
        &["`spatial_filter` is 9 texels wide, wider than the texture (8×8)"],
    );
    has(
        error("kind = \"fast\"\ndims = [8, 8, 4]"),
        &["the default `spatial_filter` (Gaussian σ 1.3435) is 11 texels wide"],
    );
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16, 4]\ntemporal_filter = { kind = \"ema\", alpha = 1.5 }",
        ),
        &["`temporal_filter.alpha` must be in [0.001, 1], got 1.5"],
    );
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16, 4]\ntemporal_filter = { kind = \"ema\", beta = -0.5 }",
        ),
        &["`temporal_filter.beta` must be in [0, 1], got -0.5"],
    );
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16, 4]\ntemporal_filter = { kind = \"taa\", coverage = 0.1 }",
        ),
        &[
            "`temporal_filter.coverage` must be in [0.15, 0.5]",
            "got 0.1",
        ],
    );
    for (filter, want) in [
        (
            "{ kind = \"taa\", motion = [3] }",
            "`temporal_filter.motion` takes two integers (pixels per frame in x and y), got 1",
        ),
        (
            "{ kind = \"taa\", motion = [3, 1.5] }",
            "`temporal_filter.motion` must be integers (whole pixels per frame)",
        ),
        (
            "{ kind = \"taa\", motion = [9, 1] }",
            "`temporal_filter.motion` must be within ±8 pixels per frame, got 9",
        ),
        (
            "{ kind = \"taa\", moving = 0.3 }",
            "`temporal_filter.moving` weighs a moving camera: give its `motion` too",
        ),
        (
            "{ kind = \"taa\", motion = [1, 0], moving = 1 }",
            "`temporal_filter.moving` must be in [0, 1), got 1",
        ),
        (
            "{ kind = \"taa\", motion = \"3,1\" }",
            "`temporal_filter.motion` must be two integers like [3, 1]",
        ),
    ] {
        has(
            error(&format!(
                "kind = \"fast\"\ndims = [16, 16, 4]\ntemporal_filter = {filter}"
            )),
            &[want, "noise.toml:5:"],
        );
    }
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16, 4]\nsample_space = \"sphere\"\nformat = \"u8x3\"\ntemporal_filter = { kind = \"taa\" }",
        ),
        &["`sample_space` \"sphere\" is not scalar (use `ema`)"],
    );
    has(
        error("kind = \"fast\"\ndims = [16, 16]\ntemporal_filter = { kind = \"taa\" }"),
        &["`temporal_filter` needs a time axis"],
    );
    has(
        error("kind = \"fast\"\ndims = [16, 16, 4]\nsample_space = \"hemisphre\""),
        &["unknown `sample_space` \"hemisphre\" (did you mean `hemisphere`?)"],
    );
    has(
        error("kind = \"fast\"\ndims = [16, 16]\nsample_space = \"sphere\"\nformat = \"u8\""),
        &["sample space `sphere` has 3 channel(s); `format` must be u8x3 or f32x3, got u8"],
    );
    has(
        error("kind = \"fast\"\ndims = [16, 16]\ndistribution = \"gauss\""),
        &["Gaussian samples are unbounded and need `format = \"f32\"`"],
    );
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16, 4]\ntemporal_filter = { kind = \"box\", size = 6 }",
        ),
        &["`temporal_filter` spans 6 frames, more than the texture's 4"],
    );
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16]\ntemporal_filter = { kind = \"gauss\", sigma = 0.5 }",
        ),
        &["`temporal_filter` needs a time axis"],
    );
    has(
        error("kind = \"fast\"\ndims = [16, 16, 4]\ncombine = { separate = 2 }"),
        &["`combine.separate` is a weight in [0, 1], got 2"],
    );
    has(
        error("kind = \"fast\"\ndims = [16, 16, 4]\nspatial_filter = { kind = \"gaus\" }"),
        &["unknown spatial filter \"gaus\""],
    );
}

#[test]
fn vector_masks_store_unit_vectors_like_the_public_textures() {
    let t = gen_tex(
        "kind = \"fast\"\ndims = [16, 16, 2]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 3 }\niterations = 2",
    );
    assert_eq!(t.data.len(), 16 * 16 * 2 * 3);
    for px in t.data.chunks(3) {
        let v: Vec<f64> = px.iter().map(|&b| b as f64 / 255.0 * 2.0 - 1.0).collect();
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        assert!((len - 1.0).abs() < 0.02 && v[2] >= -0.005, "{v:?}");
    }
}

/// Edges found by fuzzing the TAA filter and the sampler kind: each message names what is
/// wrong and where to go, lists every key a filter takes, and never echoes a huge value whole.
#[test]
fn fuzzed_taa_and_filter_specs_get_clear_messages() {
    let has = |msg: String, parts: &[&str]| {
        for p in parts {
            assert!(msg.contains(p), "expected {p:?} in:\n{msg}");
        }
    };
    // Every key of the filter's kind, not only the first one read.
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16, 4]\ntemporal_filter = { kind = \"taa\", clamp = 1 }",
        ),
        &[
            "unknown key `clamp`",
            "`alpha`, `coverage`, `motion`, `moving`",
        ],
    );
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16, 4]\ntemporal_filter = { kind = \"ema\", gamma = 1 }",
        ),
        &["unknown key `gamma`", "`alpha`, `beta`"],
    );
    // `taa` is a filter of `fast`, not a kind that resembles `vac`.
    let msg = error("kind = \"taa\"\ndims = [16, 16, 4]");
    has(
        msg.clone(),
        &["kind = \"fast\"", "temporal_filter = { kind = \"taa\""],
    );
    assert!(!msg.contains("vac"), "{msg}");
    // A 309-digit number and a 10 000-character word are shortened.
    let msg = error(
        "kind = \"fast\"\ndims = [16, 16, 4]\ntemporal_filter = { kind = \"taa\", motion = [1, 0], moving = 1e308 }",
    );
    has(msg.clone(), &["got 1e308"]);
    assert!(msg.len() < 200, "{msg}");
    let long = "x".repeat(10_000);
    let msg = error(&format!(
        "kind = \"fast\"\ndims = [16, 16, 4]\nformat = \"{long}\""
    ));
    has(msg.clone(), &["(10000 characters)"]);
    assert!(msg.len() < 400, "{} characters", msg.len());
    // An EMA's α has a floor (a history of a thousand frames).
    has(
        error(
            "kind = \"fast\"\ndims = [16, 16, 64]\ntemporal_filter = { kind = \"taa\", alpha = 5e-324 }",
        ),
        &["`temporal_filter.alpha` must be in [0.001, 1], got 5e-324"],
    );
    // Coverage too low for any arrangement of a slice this small, as u8 stores its ranks.
    has(
        error(
            "kind = \"fast\"\ndims = [4, 3, 2]\nspatial_filter = { kind = \"none\" }\ntemporal_filter = { kind = \"taa\", coverage = 0.15 }",
        ),
        &["1 at or above one less it", "needs 2 of each"],
    );
    has(
        error(
            "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\", coverage = 0.12 }",
        ),
        &["must be in [0.15, 0.5]"],
    );
}

/// The TAA masks the fuzzer found with open windows: a bake closes them (the repair swaps
/// within a slice, so every slice keeps its values).
#[test]
fn taa_bakes_close_the_windows_the_optimiser_left_open() {
    for body in [
        "kind = \"fast\"\ndims = [5, 3, 2]\nspatial_filter = { kind = \"none\" }\ntemporal_filter = { kind = \"taa\" }",
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\", coverage = 0.15 }",
        "kind = \"fast\"\ndims = [16, 16, 64]\ntemporal_filter = { kind = \"taa\", alpha = 0.001 }",
    ] {
        let s = noisebake_test_support::bake::spec(body);
        let t = gen_tex(body);
        assert_eq!(
            build_assets::generate::open_windows_of(&s, &t),
            Some(0),
            "{body}"
        );
    }
}
