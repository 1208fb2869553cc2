//! Every WGSL snippet the documentation shows is checked against the library as it is: the
//! README, the facade's front page, `docs/gpu.md` and the Bevy plugin's docs and README. A
//! snippet is WGSL at module scope (bindings and functions); it is prepended with the library
//! and validated by naga, so a function called with the wrong arguments or a mask bound as the
//! wrong texture type fails here, not in a user's shader.
//!
//! Bevy snippets (`#import …`) are validated the same way after their imports are replaced by
//! the library and stand-ins for what Bevy's imports declare (`VertexOutput`'s position, the
//! `globals` uniform with `frame_count`) and `#{MATERIAL_BIND_GROUP}` by a group number.

use std::path::Path;

/// The ```` ```wgsl ```` blocks of `text` (lines of a `//!` doc comment included), with the
/// line each starts on.
fn wgsl_blocks(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (n, line) in text.lines().enumerate() {
        let line = line
            .trim_start()
            .strip_prefix("//!")
            .map_or(line, |l| l.strip_prefix(' ').unwrap_or(l));
        let fence = line.trim_start();
        match &mut current {
            None if fence.starts_with("```wgsl") => current = Some((n + 1, String::new())),
            Some(_) if fence.starts_with("```") => out.push(current.take().unwrap()),
            Some((_, body)) => {
                body.push_str(line);
                body.push('\n');
            }
            None => {}
        }
    }
    out
}

/// What Bevy's `#import`s bring that the snippets use.
const BEVY_STANDINS: &str = "
struct VertexOutput { @builtin(position) position: vec4<f32> }
struct Globals { time: f32, delta_time: f32, frame_count: u32 }
@group(0) @binding(11) var<uniform> globals: Globals;
";

/// A snippet as a module naga can validate.
fn module(snippet: &str) -> String {
    let bevy = snippet
        .lines()
        .any(|l| l.trim_start().starts_with("#import"));
    let body: String = snippet
        .lines()
        .filter(|l| !l.trim_start().starts_with("#import"))
        .map(|l| l.replace("#{MATERIAL_BIND_GROUP}", "2") + "\n")
        .collect();
    format!(
        "{}\n{}\n{body}",
        noisebake::shaders::WGSL,
        if bevy { BEVY_STANDINS } else { "" }
    )
}

#[test]
fn every_wgsl_snippet_in_the_docs_validates_against_the_library() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let files = [
        "README.md",
        "src/lib.rs",
        "docs/gpu.md",
        "noisebake-bevy/src/lib.rs",
        "noisebake-bevy/README.md",
    ];
    let mut checked = 0;
    for file in files {
        let text = std::fs::read_to_string(root.join(file)).unwrap();
        for (line, snippet) in wgsl_blocks(&text) {
            if let Err(e) = noisebake_gpu::validate(&module(&snippet)) {
                panic!(
                    "{file}:{line}: the WGSL snippet does not validate against the library:\n{snippet}\n{e}"
                );
            }
            checked += 1;
        }
    }
    assert!(
        checked >= 3,
        "only {checked} WGSL snippets found: the docs lost theirs?"
    );
}

/// The check can fail: a call with one argument too few, as the docs once showed
/// `nb_sampler_tile`, is refused.
#[test]
fn a_wrong_call_is_caught() {
    let wrong = "@group(0) @binding(0) var keys: texture_2d_array<u32>;
fn ao(pixel: vec2<i32>, frame: u32) -> f32 {
    return nb_sampler_tile(keys, pixel, frame, 0u, 0u, 4u);
}";
    assert!(noisebake_gpu::validate(&module(wrong)).is_err());
    let u16_as_float = "@group(0) @binding(0) var stbn: texture_2d_array<u32>;
fn xi(p: vec2<i32>) -> f32 { return nb_mask_unit(stbn, vec3<i32>(p, 0), 0u); }";
    assert!(noisebake_gpu::validate(&module(u16_as_float)).is_err());
    let blocks =
        wgsl_blocks("//! ```wgsl\n//! fn a() {}\n//! ```\ntext\n```wgsl\nfn b() {}\n```\n");
    assert_eq!(blocks.len(), 2);
    assert_eq!(blocks[0].1, "fn a() {}\n");
}
