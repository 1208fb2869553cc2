fn main() {
    // A failure (a spec error reads like a compiler error: file, line, key) is shown as Cargo's
    // own `error:` lines and fails the build, with no panic or backtrace.
    build_assets::bake_or_exit("noise.toml");
}
