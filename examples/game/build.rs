fn main() {
    if let Err(e) = build_assets::bake("noise.toml") {
        // A spec error reads like a compiler error: file, line, key.
        panic!("{e}");
    }
}
