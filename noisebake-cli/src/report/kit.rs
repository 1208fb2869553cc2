//! The measuring kit every report shares: how a report bakes a row (through the workspace's
//! cache, announcing long bakes), the spec of a row, the free constructions games use (IGN
//! and the R2 grid, animated), EA's published texture, and FAST's scalar parameters. The
//! reports sit above it and do not import each other's kit.

use build_assets::cache::Locator;
use build_assets::generate::fast::{
    self, Combine, FastParams, Filter, SampleSpace, TemporalFilter,
};
use build_assets::spec::TextureSpec;
use std::path::Path;
use std::time::Instant;

/// The file name of EA's published FAST texture (BSD-3-Clause, vendored in the repository's
/// `testdata/ea-fast-bsd3/` with its licence; not shipped with the crate).
pub const EA_FILE: &str = "real_uniform_gauss_1.3435_exponential_0.1_0.1_product.png";

/// Where EA's FAST texture is: `NOISEBAKE_EA_TEXTURE` (the PNG), else the repository's
/// `testdata/` when this binary was built from a checkout. `None` for an installed binary
/// without the variable: the report then leaves EA's row out and says why.
pub fn ea_path() -> Option<std::path::PathBuf> {
    if let Some(p) = std::env::var_os("NOISEBAKE_EA_TEXTURE").filter(|p| !p.is_empty()) {
        return Some(p.into());
    }
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/ea-fast-bsd3")
        .join(EA_FILE);
    p.is_file().then_some(p)
}

/// Why EA's row is missing, for the report to print.
pub const EA_MISSING: &str = "EA's published FAST texture is not here (it is reference data of the repository, not shipped with the crate): set NOISEBAKE_EA_TEXTURE to its PNG (testdata/ea-fast-bsd3/ in a checkout) to add its row";

/// EA's texture at `path` as values `(v + 0.5) / 256`, x fastest, 128 × 128 × 64.
pub fn ea_values(path: &Path) -> Result<Vec<f64>, String> {
    let img = image::open(path)
        .map_err(|e| format!("{}: {e}", path.display()))?
        .to_rgba8();
    if img.dimensions() != (128, 128 * 64) {
        return Err(format!(
            "EA texture is {:?}, expected 128×8192",
            img.dimensions()
        ));
    }
    Ok(img
        .pixels()
        .map(|p| (p.0[0] as f64 + 0.5) / 256.0)
        .collect())
}

/// Interleaved gradient noise (Jimenez 2014), animated by shifting x and y by 5.588238 pixels
/// per frame, as games use it.
pub fn ign(dims: [usize; 3]) -> Vec<f64> {
    (0..dims[2])
        .flat_map(|f| fast::ign_slice(dims[0], dims[1], f))
        .collect()
}

/// The R2 low-discrepancy grid animated by the golden ratio (the runtime's `ldg::r2_frame`).
pub fn r2(dims: [usize; 3]) -> Vec<f64> {
    let [w, h, t] = dims;
    (0..t)
        .flat_map(|f| {
            (0..h).flat_map(move |y| {
                (0..w)
                    .map(move |x| noise_runtime::ldg::r2_frame(x as i32, y as i32, f as u32) as f64)
            })
        })
        .collect()
}

/// The spec of a baked row: `kind` at `dims` (any count) with extra TOML keys, seed 1, u8
/// (the comparisons' masks; the vector report's scalar rows too).
pub(crate) fn spec(name: &str, kind: &str, dims: &[usize], extra: &str) -> TextureSpec {
    let dims: Vec<String> = dims.iter().map(usize::to_string).collect();
    let text = format!(
        "[[texture]]\nname = \"{name}\"\nkind = \"{kind}\"\ndims = [{}]\nseed = 1\nformat = \"u8\"\n{extra}",
        dims.join(", ")
    );
    build_assets::spec::parse_toml(&text)
        .map_err(|e| e.render("compare", &text))
        .expect("the comparison's specs are valid")
        .textures
        .remove(0)
}

/// Bakes `s` through the workspace cache; `(values, seconds, cached)`.
pub(crate) fn bake(
    s: &TextureSpec,
    log: &mut dyn FnMut(&str),
) -> Result<(Vec<f64>, f64, bool), String> {
    let (t, secs, cached) = bake_texture(s, log)?;
    Ok((t.values(), secs, cached))
}

/// Bakes `s` through the workspace cache; `(texture, seconds, cached)`.
pub(crate) fn bake_texture(
    s: &TextureSpec,
    log: &mut dyn FnMut(&str),
) -> Result<(build_assets::Texture, f64, bool), String> {
    let mut cache = Locator {
        manifest_dir: Some(Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()),
        ..Locator::default()
    }
    .resolve()
    .map_err(|e| e.to_string())?;
    let start = Instant::now();
    let e = build_assets::bake::obtain(
        &mut cache,
        s,
        2.0,
        &mut |line| log(&format!("  {line}")),
        &mut |_, _| {},
    )
    .map_err(|e| e.to_string())?;
    let cached = e.source == build_assets::cache::Source::Hit;
    let secs = if cached {
        e.seconds
    } else {
        start.elapsed().as_secs_f64()
    };
    Ok((e.texture, secs, cached))
}

/// EA's published scalar texture's filter: Gaussian σ 1.3435 × EMA (α 0.1) with history
/// rejection β 0.1 (eq. 17), product; the report times the optimiser on it.
pub fn scalar_params(combine: Combine) -> FastParams {
    FastParams {
        sample_space: SampleSpace::Scalar,
        distribution: fast::Distribution::Uniform,
        spatial: Filter::Gauss { sigma: 1.3435 },
        temporal: TemporalFilter::Ema {
            alpha: 0.1,
            beta: 0.1,
        },
        combine,
        iterations: None,
        start: fast::Start::Random,
    }
}
