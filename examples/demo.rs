//! The main job: a scene that declares its noise, bakes it at build time, renders the papers'
//! applications with every noise type and shows speed against error. The scene lives in
//! `examples/demo/` (its own `noise.toml`, `build.rs` and `noise_texture!` declarations).
//!
//! `cargo run --release --example demo` → `target/noisebake-demo/index.html`

fn main() {
    noisebake_demo::main();
}
