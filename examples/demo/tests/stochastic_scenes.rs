//! Every noise variant the equal-time scenes ship as unbiased converges to the deterministic
//! image: in each scene (tiny sizes), the mean over all pixels and samples of the stochastic,
//! tail and octave variants lies within 4 standard errors of the deterministic variant's,
//! each from its own independent samples — and so does a ±1-weighted mean over the pixels,
//! which a bias of either sign in different places would move.

use noisebake_demo::cloud::{Basis, PaperCloud, Rng, Scene, SingleScatter, Variant};
use noisebake_demo::material::{Material, Xi};

/// `(mean, standard error)` of the plain and the ±1-weighted pixel mean.
fn estimate(scene: &dyn Scene, v: Variant, spp: usize, seed: u64) -> [(f64, f64); 2] {
    let n = scene.size();
    let mut acc = [(0.0f64, 0.0f64); 2];
    let mut count = 0.0;
    for i in 0..n * n {
        let sign = if (i * 7 + i / n) % 3 == 0 { -1.0 } else { 1.0 };
        let mut rng = Rng(seed ^ (i as u64).wrapping_mul(0x2545_f491_4f6c_dd1d));
        for s in 0..spp {
            let x = scene.sample(i % n, i / n, s, &mut rng, v) as f64;
            for (k, w) in [1.0, sign].into_iter().enumerate() {
                acc[k].0 += w * x;
                acc[k].1 += x * x;
            }
            count += 1.0;
        }
    }
    acc.map(|(s, s2)| {
        let mean = s / count;
        let var = (s2 / count - mean * mean).max(0.0);
        (mean, (var / count).sqrt())
    })
}

fn check(scene: &dyn Scene, spp: usize) {
    let det = estimate(scene, Variant::Deterministic, spp, 1);
    for v in [Variant::Stochastic, Variant::Tail(2), Variant::TailOctave(1)] {
        let got = estimate(scene, v, spp, 2);
        for k in 0..2 {
            let ((a, sa), (b, sb)) = (got[k], det[k]);
            let bound = 4.0 * (sa * sa + sb * sb).sqrt();
            assert!(
                (a - b).abs() <= bound,
                "{} {}: {} mean {a} vs deterministic {b} (4σ = {bound})",
                scene.name(),
                v.name(),
                ["plain", "weighted"][k]
            );
        }
    }
}

#[test]
fn the_demo_cloud_variants_are_unbiased() {
    check(&SingleScatter { size: 6 }, 3000);
}

#[test]
fn the_paper_cloud_variants_are_unbiased_under_both_majorants() {
    for majorant in [PaperCloud::STRICT, PaperCloud::OPTIMISED] {
        check(
            &PaperCloud {
                size: 5,
                basis: Basis::Perlin,
                majorant,
            },
            2000,
        );
    }
    check(
        &PaperCloud {
            size: 3,
            basis: Basis::Sparse(10),
            majorant: PaperCloud::OPTIMISED,
        },
        300,
    );
}

#[test]
fn the_material_variants_are_unbiased_with_stbn_and_white_numbers() {
    for xi in [Xi::Stbn, Xi::White] {
        check(&Material { size: 8, xi }, 512);
    }
}
