//! Stochastic noise at equal time: the scenes of `noisebake_demo::cloud` (the demo's cloud, the
//! paper's Table 3 cloud with Perlin and sparse-convolution fBm under strict and optimised
//! majorants, and a procedural material under temporal accumulation), each variant of the noise
//! rendered over a range of sample counts, timed interleaved on one thread, RMSE against a
//! reference of the deterministic noise.
//!
//! ```text
//! cargo run --release --example cloud [-- --json rows.json] [--scene NAME] [--quick] [--markdown FILE]
//! ```
//!
//! Prints, per scene, the RMSE each variant reaches in the time the deterministic render takes
//! at 16 and at 64 spp and the time it needs to reach the deterministic 64-spp RMSE, then the
//! paper's Table 3 rows beside ours; `--json` writes every render as `{scene, density, spp,
//! seconds, rmse}`; `--markdown FILE` writes the tables as a stamped Markdown document (what
//! `docs/measured/cloud.md` is). Images go to `target/noisebake-cloud/`.

use noisebake_demo::cloud::{self, Basis, PaperCloud, Scene, SingleScatter, Variant};
use noisebake_demo::equal_time::{self, Row};
use noisebake_demo::material::{Material, Xi};
use std::path::PathBuf;

/// A scene, its variants, its reference sample count, and whether its majorants are optimised
/// per variant.
type Entry = (Box<dyn Scene>, Vec<Variant>, usize, bool);

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut json = None;
    let mut only = None;
    let mut quick = false;
    let mut markdown: Option<PathBuf> = None;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--json" => json = it.next().map(PathBuf::from),
            "--scene" => only = it.next().cloned(),
            "--quick" => quick = true,
            "--markdown" => markdown = it.next().map(PathBuf::from),
            other => {
                eprintln!(
                    "unknown argument `{other}`; use --json FILE, --scene NAME, --quick, --markdown FILE"
                );
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
    // The scenes in order; a paper cloud marked `optimise` takes its per-variant majorants
    // from a sweep against the reference of the strict scene before it (the same image: every
    // majorant is unbiased).
    let scenes: Vec<Entry> = vec![
        (
            Box::new(SingleScatter { size: 64 }),
            cloud::variants(true),
            ref_spp,
            false,
        ),
        (
            Box::new(PaperCloud::new(32, Basis::Perlin, PaperCloud::STRICT)),
            cloud::variants(true),
            ref_spp,
            false,
        ),
        (
            Box::new(PaperCloud::new(32, Basis::Perlin, PaperCloud::STRICT)),
            cloud::variants(true),
            ref_spp,
            true,
        ),
        (
            Box::new(PaperCloud::new(16, Basis::Sparse(10), PaperCloud::STRICT)),
            cloud::variants(false),
            ref_spp / 4,
            false,
        ),
        (
            Box::new(PaperCloud::new(16, Basis::Sparse(10), PaperCloud::STRICT)),
            cloud::variants(false),
            ref_spp / 4,
            true,
        ),
        (
            Box::new(Material::new(64)),
            Material::variants(),
            ref_spp,
            false,
        ),
        (
            Box::new(Material {
                size: 64,
                xi: Xi::White,
            }),
            Material::variants(),
            ref_spp,
            false,
        ),
    ];
    let sweep_spp = if quick { 16 } else { 32 };
    let mut all: Vec<Row> = Vec::new();
    let mut tables = String::new();
    let mut last_reference: Vec<f32> = Vec::new();
    for (scene, variants, r, optimise) in scenes {
        let mut scene = scene;
        let mut note = String::new();
        if optimise {
            // Only paper clouds are marked; rebuild with the sweep's majorants.
            let size = scene.size();
            let basis = if scene.name().contains("sparse") {
                Basis::Sparse(10)
            } else {
                Basis::Perlin
            };
            if only.as_ref().is_some_and(|o| {
                !format!(
                    "paper-cloud-{}-optimised",
                    if matches!(basis, Basis::Perlin) {
                        "perlin"
                    } else {
                        "sparse"
                    }
                )
                .starts_with(o.as_str())
            }) {
                continue;
            }
            if last_reference.len() != size * size {
                last_reference = cloud::reference(scene.as_ref(), r);
            }
            let per_variant =
                cloud::optimise_majorants(size, basis, &variants, sweep_spp, &last_reference);
            note = "  majorants (× strict), smallest leaving the RMSE within 5 %: ".to_string()
                + &per_variant
                    .iter()
                    .map(|(v, m)| format!("{} {:.2}", v.name(), m / PaperCloud::STRICT))
                    .collect::<Vec<_>>()
                    .join(", ")
                + "\n";
            scene = Box::new(PaperCloud {
                per_variant,
                ..PaperCloud::new(size, basis, PaperCloud::STRICT)
            });
        }
        let name = scene.name();
        if only.as_ref().is_some_and(|o| !name.starts_with(o.as_str())) {
            continue;
        }
        let (rows, table, reference) =
            cloud::equal_time(scene.as_ref(), &variants, spps, r, repeats);
        let table = table + &note;
        println!("{table}");
        tables += &table;
        tables += "\n";
        cloud::save(&dir, &format!("{name}_reference"), &reference, scene.size());
        last_reference = reference;
        all.extend(rows);
    }
    let table3 = table3(&all, if quick { 16 } else { 32 });
    print!("{table3}");
    if let Some(path) = markdown {
        let stamp =
            noisebake_cli::report::stamp::Stamp::now_as("cargo run --release --example cloud --");
        let doc = format!(
            "{}\nStochastic noise at equal time (`cargo run --release --example cloud`): per scene and variant, the RMSE reached in the time the deterministic render takes at 16 and 64 spp, and the time to reach its 64-spp RMSE (ratios below 1 are better); then the paper's Table 3 beside ours.\n\n```text\n{}\n\n{}```\n",
            stamp.header("Stochastic noise at equal time"),
            tables.trim_end(),
            table3
        );
        noisebake_cli::report::stamp::write(&path, &doc).unwrap_or_else(|e| panic!("{e}"));
        println!("wrote {}", path.display());
    }
    if let Some(path) = json {
        std::fs::write(&path, equal_time::json(&all))
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        println!("rows: {}", path.display());
    }
    println!("images in {}", dir.display());
}

/// The paper's Table 3 (Fajardo & Pharr, CPU column: AMD 3970X, 1080p, 32 spp): the speedup of
/// the stochastic noise over the deterministic one at about equal MRSE.
const PAPER_TABLE3: [(&str, &str, f64); 4] = [
    ("sparse", "strict", 3.85),
    ("perlin", "strict", 2.69),
    ("sparse", "optimised", 6.14),
    ("perlin", "optimised", 2.88),
];

/// Our rows of the paper's Table 3 beside its CPU speedups: per paper-cloud scene, the best
/// stochastic variant's speedup at equal sample count (`spp`) and at equal error (the time the
/// deterministic render takes to 64 spp over the time the variant needs for that RMSE).
fn table3(rows: &[Row], spp: usize) -> String {
    let mut out = format!(
        "Table 3 (paper cloud: delta tracking with null scattering, multiple scattering, 10 octaves)\n  {:<10} {:<10} {:<30} {:>9} {:>10} {:>12} {:>13} {:>7}\n",
        "noise",
        "majorant",
        "best stochastic variant",
        "RMSE",
        "speedup",
        "RMSE (det)",
        "equal-error",
        "paper"
    );
    for (noise, majorant, paper) in PAPER_TABLE3 {
        let scene = format!("paper-cloud-{noise}-{majorant}");
        let at = |name: &str| {
            rows.iter()
                .find(|r| r.scene == scene && r.density == name && r.spp == spp)
        };
        let Some(det) = at("deterministic") else {
            continue;
        };
        let Some(t64) = rows
            .iter()
            .find(|r| r.scene == scene && r.density == "deterministic" && r.spp == 64)
        else {
            continue;
        };
        // The stochastic variant (no band-limiting: those are biased) that reaches the
        // deterministic 64-spp error fastest.
        let best = rows
            .iter()
            .filter(|r| r.scene == scene && r.spp == spp)
            .filter(|r| r.density.starts_with("stochastic"))
            .filter_map(|r| equal_time::time_to(rows, &scene, &r.density, t64.rmse).map(|t| (r, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((r, t)) = best {
            out += &format!(
                "  {noise:<10} {majorant:<10} {:<30} {:>9.5} {:>9.2}x {:>12.5} {:>12.2}x {:>6.2}x\n",
                r.density,
                r.rmse,
                det.seconds / r.seconds,
                det.rmse,
                t64.seconds / t,
                paper
            );
        }
    }
    out += &format!(
        "  speedup: deterministic time / variant time at {spp} spp; equal-error: deterministic time at 64 spp / the variant's time to its RMSE; paper: its CPU speedup at 32 spp, about equal MRSE\n"
    );
    out
}
