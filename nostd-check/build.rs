fn main() {
    build_assets::bake("noise.toml").unwrap_or_else(|e| panic!("{e}"));
}
