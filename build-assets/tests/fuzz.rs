//! Property tests over untrusted input: spec text, `.npy` files and cache entries. Whatever
//! the bytes, the readers return a value or an error — never a panic, a hang or an allocation
//! the input did not pay for — and what they accept is consistent.

use build_assets::cache::{decode, encode};
use build_assets::export::npy::{from_npy, to_npy};
use build_assets::spec::parse_toml;
use build_assets::{Texture, generate};
use proptest::prelude::*;

const SPEC: &str = "cache_dir = \"c\"\n[[texture]]\nname = \"STBN\"\nkind = \"stbn\"\ndims = [8, 8, 4]\nseed = 7\nformat = \"u16\"\nhistogram = \"slice\"\n\n[[texture]]\nname = \"F\"\nkind = \"fast\"\ndims = [16, 16, 4]\nspatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }\n\n[[texture]]\nname = \"V\"\nkind = \"vac\"\ndims = [4, 4, 2, 2]\ngroups = [{ axes = [0, 1], sigma = 1.9 }, { axes = [2, 3] }]\n";

/// Spec-shaped tokens, so mutations reach the validator and not only the TOML parser.
const TOKENS: &[&str] = &[
    "[[texture]]",
    "name",
    "kind",
    "dims",
    "seed",
    "format",
    "sigma",
    "sigma_xy",
    "sigma_t",
    "groups",
    "axes",
    "histogram",
    "cache_dir",
    "stbn",
    "vac",
    "fast",
    "white",
    "blue2d",
    "golden",
    "independent2d",
    "\"u8\"",
    "\"u16\"",
    "\"f32\"",
    "\"u8x3\"",
    " = ",
    "[",
    "]",
    "{",
    "}",
    ",",
    "\n",
    "\"",
    "0",
    "-1",
    "1e300",
    "nan",
    "inf",
    "65536",
    "4294967296",
    "0.2",
    "1.9",
    "true",
    "spatial_filter",
    "temporal_filter",
    "sample_space",
    "\"cosine_hemisphere\"",
    "{ kind = \"box\", size = 5 }",
    "{ kind = \"ema\", alpha = 0.1, beta = 0.1 }",
    "é",
    "\u{0}",
];

fn mutate(base: &[u8], edits: &[(usize, u8, u8)]) -> Vec<u8> {
    let mut b = base.to_vec();
    for &(at, op, v) in edits {
        if b.is_empty() {
            b.push(v);
            continue;
        }
        let i = at % b.len();
        match op % 4 {
            0 => b[i] = v,
            1 => b[i] ^= 1 << (v % 8),
            2 => {
                b.insert(i, v);
            }
            _ => {
                b.remove(i);
            }
        }
    }
    b
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1500, ..ProptestConfig::default() })]

    #[test]
    fn spec_text_of_tokens_never_panics(picks in prop::collection::vec(0..TOKENS.len(), 0..60)) {
        let text: String = picks.iter().map(|&i| TOKENS[i]).collect();
        let _ = parse_toml(&text).map_err(|e| e.render("noise.toml", &text));
    }

    #[test]
    fn mutated_specs_never_panic_and_what_parses_is_valid(
        edits in prop::collection::vec((any::<usize>(), any::<u8>(), any::<u8>()), 1..8)
    ) {
        let bytes = mutate(SPEC.as_bytes(), &edits);
        let text = String::from_utf8_lossy(&bytes);
        match parse_toml(&text) {
            Ok(file) => {
                for t in &file.textures {
                    // Accepted specs are within the limits every generator relies on.
                    prop_assert!(t.texels() as u64 <= build_assets::spec::MAX_TEXELS);
                    prop_assert!(build_assets::spec::check_identifier(&t.name).is_ok());
                    prop_assert!(!t.canonical().is_empty());
                }
            }
            Err(e) => {
                let _ = e.render("noise.toml", &text);
            }
        }
    }

    #[test]
    fn npy_reader_never_panics_on_mutated_files(
        edits in prop::collection::vec((any::<usize>(), any::<u8>(), any::<u8>()), 1..6),
        channels_last in any::<bool>(),
    ) {
        let t = Texture {
            name: "t".into(),
            dims: vec![4, 3, 2],
            format: build_assets::spec::Format::U16,
            data: (0..48).collect(),
        };
        let bytes = mutate(&to_npy(&t), &edits);
        if let Ok(r) = from_npy(&bytes, "t", channels_last) {
            let n: usize = r.dims.iter().product();
            prop_assert_eq!(r.data.len(), n * r.format.texel_bytes());
        }
    }

    #[test]
    fn npy_reader_never_panics_on_noise(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        let mut b = b"\x93NUMPY\x01\x00".to_vec();
        b.extend_from_slice(&bytes);
        let _ = from_npy(&b, "t", false);
        let _ = from_npy(&bytes, "t", true);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1500, ..ProptestConfig::default() })]

    /// A cache entry that decodes after any mutation is the original entry (all its bytes
    /// are covered by the magic, the lengths, the zero padding and the two hashes).
    #[test]
    fn mutated_cache_entries_are_rejected_or_exact(
        edits in prop::collection::vec((any::<usize>(), any::<u8>(), any::<u8>()), 1..4)
    ) {
        static ENTRY: std::sync::OnceLock<(build_assets::TextureSpec, Vec<u8>)> =
            std::sync::OnceLock::new();
        let (spec, good) = ENTRY.get_or_init(|| {
            let spec = parse_toml(SPEC).unwrap().textures.remove(0);
            let entry = encode(&generate(&spec, &mut |_, _| {}).into(), &spec);
            (spec, entry)
        });
        let bad = mutate(good, &edits);
        if let Ok(t) = decode(&bad, spec) {
            prop_assert_eq!(&bad, good);
            prop_assert_eq!(t.texture.data.len(), spec.byte_len());
        }
    }
}

#[test]
fn the_base_spec_parses() {
    assert_eq!(parse_toml(SPEC).unwrap().textures.len(), 3);
}
