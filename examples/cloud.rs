//! Render-level check of stochastic noise: a procedural fBm cloud, deterministic vs stochastic
//! density at 16 and 64 spp, time and RMSE against a 1024-spp reference (the code is the demo's
//! `cloud` module, which also renders it as a panel of the demo).
//!
//! `cargo run --release --example cloud` → `target/noisebake-cloud/*.png`

fn main() {
    let dir = std::path::PathBuf::from("target/noisebake-cloud");
    noisebake_demo::cloud::run(&dir);
    println!("images in {}", dir.display());
}
