//! Helpers shared by the integration tests.
#![allow(dead_code)]

use build_assets::spec::{self, TextureSpec};
use build_assets::{Texture, generate};

/// A spec from TOML key-value lines (one texture named `T`).
pub fn spec(body: &str) -> TextureSpec {
    let file = spec::parse_toml(&format!("[[texture]]\nname = \"T\"\n{body}"))
        .unwrap_or_else(|e| panic!("{e}"));
    file.textures.into_iter().next().unwrap()
}

/// Generates a texture from TOML key-value lines.
pub fn gen_tex(body: &str) -> Texture {
    generate(&spec(body), &mut |_, _| {})
}

/// The error message of an invalid texture body.
pub fn error(body: &str) -> String {
    let text = format!("[[texture]]\nname = \"T\"\n{body}");
    match spec::parse_toml(&text) {
        Ok(_) => panic!("expected an error for {body}"),
        Err(e) => e.render("noise.toml", &text),
    }
}

/// A file of the repository's vendored reference data (`testdata/`, each with its licence).
pub fn testdata(path: &str) -> std::path::PathBuf {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata")
        .join(path);
    assert!(p.exists(), "{} is missing from the repository", p.display());
    p
}
