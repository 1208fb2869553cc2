//! Bakes noise.toml and records what the bake did (cache hit or generated, bytes, seconds) for
//! the demo's summary.

use std::fmt::Write;

fn main() {
    let report = build_assets::bake_or_exit("noise.toml");
    let mut summary = String::new();
    for t in &report.textures {
        let _ = writeln!(
            summary,
            "{}\t{}\t{:?}\t{:.3}",
            t.name, t.bytes, t.source, t.seconds
        );
    }
    let out = std::env::var("OUT_DIR").expect("OUT_DIR");
    std::fs::write(format!("{out}/bake_summary.tsv"), summary).expect("write summary");
}
