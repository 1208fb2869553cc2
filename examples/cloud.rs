//! Stochastic noise at equal time: the scenes of `noisebake_demo::cloud` (the demo's cloud, the
//! paper's Table 3 cloud with Perlin and sparse-convolution fBm under strict and optimised
//! majorants, and a procedural material under temporal accumulation), each variant of the noise
//! rendered over a range of sample counts, timed interleaved on one thread, RMSE against a
//! reference of the deterministic noise.
//!
//! ```text
//! cargo run --release --example cloud [-- --json rows.json] [--scene NAME] [--quick]
//! ```
//!
//! Prints, per scene, the RMSE each variant reaches in the time the deterministic render takes
//! at 16 and at 64 spp and the time it needs to reach the deterministic 64-spp RMSE; `--json`
//! writes every render as `{scene, density, spp, seconds, rmse}`. Images go to
//! `target/noisebake-cloud/`.

use noisebake_demo::cloud::{self, Basis, PaperCloud, Scene, SingleScatter, Variant};
use noisebake_demo::equal_time::{self, Row};
use noisebake_demo::material::Material;
use std::path::PathBuf;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut json = None;
    let mut only = None;
    let mut quick = false;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--json" => json = it.next().map(PathBuf::from),
            "--scene" => only = it.next().cloned(),
            "--quick" => quick = true,
            other => {
                eprintln!("unknown argument `{other}`; use --json FILE, --scene NAME, --quick");
                std::process::exit(2);
            }
        }
    }
    let dir = PathBuf::from("target/noisebake-cloud");
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let (spps, ref_spp, repeats): (&[usize], usize, usize) = if quick {
        (&[4, 16, 64], 256, 1)
    } else {
        (&[4, 8, 16, 32, 64, 128], 1024, 2)
    };
    let paper = |basis, majorant, size| PaperCloud {
        size,
        basis,
        majorant,
    };
    let scenes: Vec<(Box<dyn Scene>, Vec<Variant>, usize)> = vec![
        (
            Box::new(SingleScatter { size: 64 }),
            cloud::variants(true),
            ref_spp,
        ),
        (
            Box::new(paper(Basis::Perlin, PaperCloud::STRICT, 32)),
            cloud::variants(true),
            ref_spp,
        ),
        (
            Box::new(paper(Basis::Perlin, PaperCloud::OPTIMISED, 32)),
            cloud::variants(true),
            ref_spp,
        ),
        (
            Box::new(paper(Basis::Sparse(4), PaperCloud::STRICT, 16)),
            cloud::variants(false),
            ref_spp / 4,
        ),
        (
            Box::new(paper(Basis::Sparse(4), PaperCloud::OPTIMISED, 16)),
            cloud::variants(false),
            ref_spp / 4,
        ),
        (Box::new(Material::new(64)), Material::variants(), ref_spp),
    ];
    let mut all: Vec<Row> = Vec::new();
    for (scene, variants, r) in &scenes {
        let name = scene.name();
        if only.as_ref().is_some_and(|o| !name.starts_with(o.as_str())) {
            continue;
        }
        let (rows, table, reference) =
            cloud::equal_time(scene.as_ref(), variants, spps, *r, repeats);
        println!("{table}");
        cloud::save(&dir, &format!("{name}_reference"), &reference, scene.size());
        all.extend(rows);
    }
    if let Some(path) = json {
        std::fs::write(&path, equal_time::json(&all))
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        println!("rows: {}", path.display());
    }
    println!("images in {}", dir.display());
}
