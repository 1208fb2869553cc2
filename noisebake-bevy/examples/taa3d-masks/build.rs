fn main() {
    // As a game bakes its masks: noise.toml through the shared cache, with Cargo's own `error:`
    // lines for a bad spec.
    build_assets::bake_or_exit("noise.toml");
}
