fn main() {
    build_assets::bake_or_exit("noise.toml");
}
