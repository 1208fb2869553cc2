//! Every noise variant the equal-time scenes ship as unbiased converges to the deterministic
//! image, pixel by pixel. In each scene (tiny sizes), each pixel's mean over its samples under
//! the stochastic, tail and octave variants is compared with the deterministic variant's, each
//! from its own independent samples: with `z` the difference over its standard error, the sum
//! of `z²` over the pixels must stay below its χ² bound (`N + 6·√(2N)` for `N` pixels) and no
//! `|z|` may exceed 5.5 — probabilities far below 10⁻⁶ for an unbiased variant.

use noisebake_demo::cloud::{Basis, PaperCloud, Rng, Scene, SingleScatter, Variant};
use noisebake_demo::material::{Material, Xi};

/// Per pixel: `(mean, squared standard error)` over `spp` samples.
fn pixels(scene: &dyn Scene, v: Variant, spp: usize, seed: u64) -> Vec<(f64, f64)> {
    let n = scene.size();
    (0..n * n)
        .map(|i| {
            let mut rng = Rng::new(seed ^ (i as u64).wrapping_mul(0x2545_f491_4f6c_dd1d));
            let (mut s, mut s2) = (0.0f64, 0.0f64);
            for k in 0..spp {
                let x = scene.sample(i % n, i / n, k, &mut rng, v) as f64;
                s += x;
                s2 += x * x;
            }
            let mean = s / spp as f64;
            let var = (s2 / spp as f64 - mean * mean).max(0.0);
            (mean, var / spp as f64)
        })
        .collect()
}

fn check(scene: &dyn Scene, spp: usize) {
    let det = pixels(scene, Variant::Deterministic, spp, 1);
    for v in [
        Variant::Stochastic,
        Variant::Tail(2),
        Variant::TailOctave(1),
    ] {
        let got = pixels(scene, v, spp, 2);
        let (mut chi2, mut worst, mut n) = (0.0f64, 0.0f64, 0.0f64);
        for ((a, sa), (b, sb)) in got.iter().zip(&det) {
            let se2 = sa + sb;
            if se2 == 0.0 {
                assert_eq!(
                    a,
                    b,
                    "{} {}: a noiseless pixel differs",
                    scene.name(),
                    v.name()
                );
                continue;
            }
            let z = (a - b) / se2.sqrt();
            chi2 += z * z;
            worst = worst.max(z.abs());
            n += 1.0;
        }
        let bound = n + 6.0 * (2.0 * n).sqrt();
        assert!(
            chi2 <= bound && worst <= 5.5,
            "{} {}: Σz² = {chi2:.1} over {n} pixels (bound {bound:.1}), largest |z| {worst:.2}",
            scene.name(),
            v.name()
        );
    }
}

#[test]
fn the_demo_cloud_variants_are_unbiased() {
    check(&SingleScatter { size: 6 }, 3000);
}

#[test]
fn the_paper_cloud_variants_are_unbiased_under_a_bounding_and_a_non_bounding_majorant() {
    for majorant in [PaperCloud::STRICT, PaperCloud::HALF] {
        check(&PaperCloud::new(5, Basis::Perlin, majorant), 2000);
    }
    check(
        &PaperCloud::new(3, Basis::Sparse(10), PaperCloud::HALF),
        300,
    );
}

#[test]
fn the_material_variants_are_unbiased_with_stbn_and_white_numbers() {
    for xi in [Xi::Stbn, Xi::White] {
        check(&Material { size: 8, xi }, 512);
    }
}
