//! Bad specs are errors that name the key, point at it, and never panic or allocate first.

use noisebake_test_support::bake::{error, spec};

fn has(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "expected {p:?} in:\n{msg}");
    }
}

#[test]
fn zero_and_huge_dims() {
    has(
        &error("kind = \"stbn\"\ndims = [64, 0, 16]"),
        &["noise.toml:4:", "`dims[1]` must be at least 1, got 0"],
    );
    let huge = error("kind = \"stbn\"\ndims = [65536, 65536, 64]");
    has(&huge, &["texels", "GiB of working memory", "limit"]);
    has(&error("kind = \"white\"\ndims = []"), &["`dims` is empty"]);
    has(
        &error("kind = \"stbn\"\ndims = [64, 64]"),
        &["kind `stbn` takes 3 dims, got 2"],
    );
    has(
        &error("kind = \"stbn\"\ndims = \"64x64\""),
        &["`dims` must be an array"],
    );
    has(
        &error("kind = \"sampler\"\ndims = [512, 256]"),
        &[
            "noise.toml:4:",
            "a sampler tile of [512, 256] has 131072 pixels; the limit is 65536",
        ],
    );
    spec("kind = \"sampler\"\ndims = [256, 256]");
}

#[test]
fn bad_sigmas_and_densities() {
    has(
        &error("kind = \"blue2d\"\ndims = [8, 8]\nsigma = 0"),
        &["`sigma` must be a number in (0, 100], got 0", ":5:"],
    );
    has(
        &error("kind = \"blue2d\"\ndims = [8, 8]\nsigma = -1.5"),
        &["`sigma`", "got -1.5"],
    );
    has(
        &error("kind = \"blue2d\"\ndims = [8, 8]\nsigma = nan"),
        &["`sigma` must be finite"],
    );
    has(
        &error("kind = \"stbn\"\ndims = [8, 8, 4]\nsigma_t = inf"),
        &["`sigma_t` must be finite"],
    );
    has(
        &error("kind = \"stbn\"\ndims = [8, 8, 4]\ninitial_density = 0.9"),
        &["`initial_density` must be in (0, 0.5]"],
    );
    has(
        &error("kind = \"blue2d\"\ndims = [8, 8]\nsigma = \"wide\""),
        &["`sigma` must be a number, got a string"],
    );
    has(
        &error(
            "kind = \"vac\"\ndims = [1024, 1024, 64]\ngroups = [{ axes = [0, 1, 2], sigma = 90 }]",
        ),
        &["energy updates per texel"],
    );
}

#[test]
fn bad_groups() {
    has(
        &error("kind = \"vac\"\ndims = [8, 8, 4]\ngroups = [{ axes = [0, 1] }, { axes = [1, 2] }]"),
        &["`groups[1].axes`: axis 1 is listed twice"],
    );
    has(
        &error("kind = \"vac\"\ndims = [8, 8, 4]\ngroups = [{ axes = [0, 1] }]"),
        &["axis 2 is missing from every group"],
    );
    has(
        &error("kind = \"vac\"\ndims = [8, 8, 4]\ngroups = [{ axes = [0, 1, 2, 3] }]"),
        &["axis 3 does not exist"],
    );
    has(
        &error("kind = \"vac\"\ndims = [8, 8]\ngroups = [{ axes = [0, 1], sigma = -1 }]"),
        &["groups[0]", "`sigma`"],
    );
    has(
        &error("kind = \"vac\"\ndims = [8, 8]\ngroups = [{ axes = [0, 1], sgma = 1 }]"),
        &["unknown key `sgma`", "did you mean `sigma`"],
    );
    has(
        &error("kind = \"vac\"\ndims = [8, 8]\ntoroidal = [true]"),
        &["`toroidal` has 1 entries for 2 dims"],
    );
}

#[test]
fn unknown_kinds_keys_and_formats() {
    has(
        &error("kind = \"stbm\"\ndims = [8, 8, 4]"),
        &["unknown kind `stbm`", "did you mean `stbn`"],
    );
    has(
        &error("kind = \"bayer\"\ndims = [8, 8, 4]"),
        &["kind `bayer` is not available"],
    );
    has(
        &error("kind = \"stbn\"\ndims = [8, 8, 4]\nsigma_xyz = 2"),
        &[
            "unknown key `sigma_xyz`",
            "did you mean `sigma_xy`",
            "valid keys here",
        ],
    );
    has(
        &error("kind = \"stbn\"\ndims = [8, 8, 4]\nformat = \"u32\""),
        &["`format` must be u8, u16, f32"],
    );
    has(
        &error("kind = \"stbn\"\ndims = [8, 8, 4]\nformat = \"u8x3\""),
        &["makes scalar masks", "u8x3"],
    );
    has(
        &error("kind = \"stbn\"\ndims = [8, 8, 4]\nhistogram = \"frame\""),
        &["`histogram` must be \"volume\" or \"slice\""],
    );
    has(
        &error("kind = \"stbn\"\ndims = [8, 8, 4]\nseed = -1"),
        &["`seed` must be a non-negative integer"],
    );
    has(&error("dims = [8, 8, 4]"), &["needs a `kind` key"]);
}

#[test]
fn names_must_be_unique_identifiers() {
    let text = "[[texture]]\nname = \"A\"\nkind = \"white\"\ndims = [4]\n[[texture]]\nname = \"A\"\nkind = \"white\"\ndims = [4]\n";
    let e = build_assets::spec::parse_toml(text)
        .unwrap_err()
        .render("noise.toml", text);
    has(&e, &["duplicate texture name `A`", "noise.toml:6:"]);
    for bad in ["\"2D\"", "\"my-mask\"", "\"fn\"", "\"\""] {
        let text = format!("[[texture]]\nname = {bad}\nkind = \"white\"\ndims = [4]\n");
        let e = build_assets::spec::parse_toml(&text)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("identifier") || e.contains("keyword"),
            "{bad}: {e}"
        );
    }
    let e = build_assets::spec::parse_toml(
        "[[texture]]\nname = \"A\"\nkind = \"white\"\ndims = [4]\n[[textures]]\n",
    )
    .unwrap_err()
    .to_string();
    has(
        &e,
        &["unknown top-level key `textures`", "did you mean `texture`"],
    );
    let e = build_assets::spec::parse_toml("[[texture]\nname = 1")
        .unwrap_err()
        .to_string();
    has(&e, &["invalid TOML"]);
}

/// σ so narrow that void and cluster bakes white noise is refused, with why; the bound itself
/// is checked against the masks on both sides of it.
#[test]
fn sigmas_too_narrow_for_blue_noise_are_refused() {
    for (kind, key, dims) in [
        ("blue2d", "sigma", "[16, 16]"),
        ("stbn", "sigma_xy", "[16, 16, 4]"),
        ("stbn", "sigma_t", "[16, 16, 4]"),
        ("independent2d", "sigma", "[16, 16, 2]"),
        ("golden", "sigma", "[16, 16, 2]"),
    ] {
        has(
            &error(&format!("kind = \"{kind}\"\ndims = {dims}\n{key} = 0.2")),
            &[&format!("`{key}` = 0.2 is below 0.5"), "white noise", ":5:"],
        );
    }
    has(
        &error("kind = \"vac\"\ndims = [16, 16]\ngroups = [{ axes = [0, 1], sigma = 1e-300 }]"),
        &["= 1e-300 is below 0.5", "groups[0]"],
    );
    // The bound: the narrowest accepted σ still bakes clearly blue noise, while just below it
    // the low-frequency power is many times higher (white noise has about 1).
    let lf = |sigma: f64| {
        let mut v = 0.0;
        for seed in 0..3 {
            let r = build_assets::generate::blue2d_ranks(64, 64, sigma, 0.1, seed);
            let vals: Vec<f64> = r.iter().map(|&r| (r as f64 + 0.5) / 4096.0).collect();
            v += spatial_lf(&vals, 64);
        }
        v / 3.0
    };
    let (at, below) = (lf(build_assets::spec::MIN_SIGMA), lf(0.3));
    assert!(at < 0.05 && below > 2.0 * at, "σ 0.5: {at}, σ 0.3: {below}");
}

/// Low-frequency power (|f| ≤ 1/8 cycle per texel, DC excluded) over all power, of a square
/// mask: a direct DFT, enough for 64×64.
fn spatial_lf(v: &[f64], n: usize) -> f64 {
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let (mut low, mut all) = (0.0, 0.0);
    for ky in 0..n {
        for kx in 0..n {
            if kx == 0 && ky == 0 {
                continue;
            }
            let (mut re, mut im) = (0.0, 0.0);
            for y in 0..n {
                for x in 0..n {
                    let a = -std::f64::consts::TAU * ((kx * x + ky * y) % n) as f64 / n as f64;
                    re += (v[y * n + x] - mean) * a.cos();
                    im += (v[y * n + x] - mean) * a.sin();
                }
            }
            let p = re * re + im * im;
            let f = |k: usize| if 2 * k > n { n - k } else { k } as f64 / n as f64;
            all += p;
            if (f(kx).powi(2) + f(ky).powi(2)).sqrt() <= 0.125 {
                low += p;
            }
        }
    }
    low / all
}

/// A key given twice, or a known top-level key of the wrong type, says so instead of
/// suggesting itself.
#[test]
fn known_keys_never_suggest_themselves() {
    let e = error("kind = \"white\"\ndims = [4, 4]\nseed = 1\nseed = 2");
    assert!(!e.contains("did you mean"), "{e}");
    let text = "cache_dir = 1\n[[texture]]\nname = \"T\"\nkind = \"white\"\ndims = [4]\n";
    let e = build_assets::spec::parse_toml(text)
        .unwrap_err()
        .render("noise.toml", text);
    has(&e, &["`cache_dir` must be a string", "got an integer"]);
    assert!(!e.contains("did you mean"), "{e}");
}

#[test]
fn names_longer_than_a_file_name_allows_are_refused() {
    let long = "N".repeat(300);
    let text = format!("[[texture]]\nname = \"{long}\"\nkind = \"white\"\ndims = [4]\n");
    let e = build_assets::spec::parse_toml(&text)
        .unwrap_err()
        .render("noise.toml", &text);
    has(&e, &["300 characters", "file name"]);
}

/// Left out, FAST's temporal filter is the plain EMA (α 0.1, no history rejection) that a
/// game's accumulation runs, and so is an `ema` that leaves out `beta`: the same spec, the same
/// cache key as writing it out. EA's β 0.1 must be asked for.
#[test]
fn fast_defaults_to_the_plain_ema_games_run() {
    use build_assets::generate::fast::TemporalFilter;
    let temporal = |body: &str| match spec(body).kind {
        build_assets::spec::Kind::Fast(p) => p.temporal,
        k => panic!("not fast: {k:?}"),
    };
    let plain = TemporalFilter::Ema {
        alpha: 0.1,
        beta: 0.0,
    };
    let base = "kind = \"fast\"\ndims = [16, 16, 8]";
    assert_eq!(temporal(base), plain);
    let no_beta = format!("{base}\ntemporal_filter = {{ kind = \"ema\", alpha = 0.1 }}");
    assert_eq!(temporal(&no_beta), plain);
    let explicit = format!("{base}\ntemporal_filter = {{ kind = \"ema\", alpha = 0.1, beta = 0 }}");
    let key = build_assets::cache::key;
    assert_eq!(key(&spec(base)), key(&spec(&explicit)));
    let ea = format!("{base}\ntemporal_filter = {{ kind = \"ema\", alpha = 0.1, beta = 0.1 }}");
    assert_ne!(key(&spec(base)), key(&spec(&ea)));
    assert_eq!(
        temporal("kind = \"fast\"\ndims = [16, 16]"),
        TemporalFilter::None
    );
}

#[test]
fn free_pair_starts_need_a_space_made_from_two_values() {
    has(
        &error("kind = \"fast\"\ndims = [16, 16, 4]\nstart = \"ign_r2\""),
        &[
            "`start = \"ign_r2\"` warps a pair of values",
            "\"scalar\"",
            "noise.toml:5:9:",
        ],
    );
    has(
        &error(
            "kind = \"fast\"\ndims = [16, 16, 4]\nsample_space = \"vec3\"\nformat = \"u8x3\"\nstart = \"rd_ign_r2\"",
        ),
        &[
            "`start = \"rd_ign_r2\"`",
            "\"vec3\"",
            "vec2, sphere, hemisphere or cosine_hemisphere",
        ],
    );
    has(
        &error("kind = \"fast\"\ndims = [16, 16, 4]\nstart = \"sobol\""),
        &["\"random\", \"ign\", \"ign_r2\" or \"rd_ign_r2\", got \"sobol\""],
    );
}
