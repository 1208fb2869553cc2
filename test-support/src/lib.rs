//! Test helpers shared by the noisebake crates' tests, so no test reaches into another crate's
//! files with `#[path]`.
//!
//! - [`Rng`]: the one test RNG (SplitMix64, Steele, Lea & Flood 2014) for reproducible inputs;
//!   the same stream as the generator's `build_assets::generate::rng::SplitMix64`, without
//!   depending on it, so the runtime's tests compile no generator.
//! - `bake` (feature `bake`): a spec from TOML key-value lines, its texture, its error
//!   message, and the repository's vendored reference data.

/// SplitMix64: a 64-bit state advanced by the golden-ratio increment and finalised by a mixer.
#[derive(Clone, Debug)]
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A uniform `f32` in `[0, 1)` from the top 24 bits.
    pub fn unit_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A uniform `f64` in `[0, 1)` from the top 53 bits.
    pub fn unit_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Any `i32`, from the low 32 bits.
    pub fn i32(&mut self) -> i32 {
        self.next_u64() as i32
    }
}

#[cfg(feature = "bake")]
pub mod bake {
    //! Specs from TOML lines, for the generator's and the CLI's tests.

    use build_assets::spec::{self, TextureSpec};
    use build_assets::{Texture, generate};

    /// A spec from TOML key-value lines (one texture named `T`).
    pub fn spec(body: &str) -> TextureSpec {
        let file = spec::parse_toml(&format!("[[texture]]\nname = \"T\"\n{body}"))
            .unwrap_or_else(|e| panic!("{e}"));
        file.textures.into_iter().next().expect("one texture")
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

    /// Asserts that every slice of `texels` 3-vectors in `after` is a permutation of the same slice
    /// in `before` (bit for bit).
    pub fn assert_slices_permuted(before: &[f64], after: &[f64], texels: usize) {
        let sorted = |s: &[f64]| {
            let mut v: Vec<[u64; 3]> = s
                .chunks(3)
                .map(|c| [c[0].to_bits(), c[1].to_bits(), c[2].to_bits()])
                .collect();
            v.sort_unstable();
            v
        };
        assert_eq!(before.len(), after.len());
        for (a, b) in before.chunks(texels * 3).zip(after.chunks(texels * 3)) {
            assert_eq!(sorted(a), sorted(b));
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
}
