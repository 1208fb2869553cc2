//! Bad specs are errors that name the key, point at it, and never panic or allocate first.

mod common;
use common::error;

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
