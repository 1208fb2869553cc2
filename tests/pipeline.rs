//! Both ways in give the same bytes: `noise_texture!` against the generator called directly
//! (the build.rs path is checked the same way by examples/game, which asserts equality).

use build_assets::spec::parse_toml;

noisebake::noise_texture!(
    STBN = stbn {
        dims: [16, 16, 4],
        seed: 7,
        format: u16,
        histogram: slice
    }
);
noisebake::noise_texture!(pub(crate) GROUPS = vac { dims: [8, 8, 4, 4], seed: 2, format: f32, groups: [{ axes: [0, 1], sigma: 1.9 }, { axes: [2] }, { axes: [3] }] });

noisebake::noise_texture!(
    TILE = sampler {
        dims: [16, 8],
        spp: 4,
        sample_dims: 3,
        seed: 1
    }
);

/// A crate that reaches noisebake through a path of its own (a re-export, as a plugin wrapping
/// noisebake gives its users) names that path with `crate = …`.
mod my_plugin {
    pub use ::noisebake as nb;
}

noisebake::noise_texture!(
    crate = crate::my_plugin::nb;
    BOXED = fast { dims: [8, 8, 2], seed: 3, spatial_filter: { kind: box, size: 3 }, iterations: 2 }
);

fn generated(body: &str) -> Vec<u8> {
    let s = parse_toml(&format!("[[texture]]\nname = \"T\"\n{body}"))
        .unwrap()
        .textures
        .remove(0);
    build_assets::generate(&s, &mut |_, _| {}).data
}

#[test]
fn macro_tables_equal_the_generator_bytes() {
    assert_eq!(
        STBN.bytes(),
        generated(
            "kind = \"stbn\"\ndims = [16, 16, 4]\nseed = 7\nformat = \"u16\"\nhistogram = \"slice\""
        )
    );
    assert_eq!(
        GROUPS.bytes(),
        generated(
            "kind = \"vac\"\ndims = [8, 8, 4, 4]\nseed = 2\nformat = \"f32\"\ngroups = [{ axes = [0, 1], sigma = 1.9 }, { axes = [2] }, { axes = [3] }]"
        )
    );
    // A sampler tile is its key mask, viewed as a tile of 4 samples × 3 dimensions.
    assert_eq!(
        TILE.keys().bytes(),
        generated("kind = \"sampler\"\ndims = [16, 8]\nspp = 4\nsample_dims = 3\nseed = 1")
    );
    let _: &noisebake::SamplerTile<16, 8, 4, 3> = &TILE;
    let v = TILE.sample(-1, 9, 2, 3, 2);
    assert!((0.0..1.0).contains(&v));
    // Through a re-exported path, with a keyword (`box`) as a bare value.
    let _: &my_plugin::nb::Mask3<u8, 8, 8, 2> = &BOXED;
    assert_eq!(
        BOXED.bytes(),
        generated(
            "kind = \"fast\"\ndims = [8, 8, 2]\nseed = 3\nspatial_filter = { kind = \"box\", size = 3 }\niterations = 2"
        )
    );
    // Typed views: dims and texel type are part of the item's type.
    let _: &noisebake::Mask3<u16, 16, 16, 4> = &STBN;
    assert!(GROUPS.get(-1, -1, -1, -1) > 0.0 && GROUPS.get(0, 0, 0, 0) < 1.0);
}

/// The spec examples on the facade's front page and in ARCHITECTURE.md's sense of "documented
/// in the repo" stay valid: every ```toml block of `src/lib.rs` that declares textures parses.
#[test]
fn the_front_page_spec_examples_parse() {
    let src = include_str!("../src/lib.rs");
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in src.lines() {
        let Some(doc) = line.strip_prefix("//!") else {
            continue;
        };
        let doc = doc.strip_prefix(' ').unwrap_or(doc);
        match (&mut current, doc.trim()) {
            (None, "```toml") => current = Some(String::new()),
            (Some(_), "```") => blocks.push(current.take().unwrap()),
            (Some(b), _) => {
                b.push_str(doc);
                b.push('\n');
            }
            _ => {}
        }
    }
    let specs: Vec<_> = blocks
        .iter()
        .filter(|b| b.contains("[[texture]]"))
        .collect();
    assert!(specs.len() >= 2, "found {} spec blocks", specs.len());
    let mut kinds = std::collections::BTreeSet::new();
    for b in specs {
        let file = parse_toml(b).unwrap_or_else(|e| panic!("{}", e.render("src/lib.rs", b)));
        kinds.extend(file.textures.iter().map(|t| t.kind.name().to_string()));
    }
    for kind in [
        "blue2d",
        "stbn",
        "vac",
        "white",
        "independent2d",
        "golden",
        "fast",
    ] {
        assert!(kinds.contains(kind), "no example of `{kind}`");
    }
}
