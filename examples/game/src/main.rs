//! A game's noise, as the README's first page shows it: free functions for the common jobs,
//! and one table baked by build.rs from noise.toml where a table pays.

use noisebake::{ldg, sampler, warp};

// LIGHT_SAMPLES, baked by build.rs from noise.toml (a `SamplerTile`).
noisebake::include_textures!();

/// Stochastic transparency (or any dither) at `coverage`: keep the pixel where the R2 grid,
/// animated by the golden ratio, is below it. Free; under Bevy's TAA it leaves the least error.
fn kept(x: i32, y: i32, frame: u32, coverage: f32) -> bool {
    ldg::r2_frame(x, y, frame) < coverage
}

/// Ray `i` of `spp` this frame for ambient occlusion or a bounce: a cosine-weighted direction
/// around +z from the sampler built for a moving camera. Free.
fn ao_direction(x: i32, y: i32, frame: u32, i: u32, spp: u32) -> [f32; 3] {
    let [u, v] = sampler::motion_pairs::<2>(x, y, frame, i, spp);
    warp::cosine_hemisphere_polar(u, v)
}

/// Ray `i` of 4 this frame towards an area light: a point of the unit square, from the baked
/// table (a still camera's shadows).
fn light_point(x: i32, y: i32, frame: u32, i: u32) -> [f32; 2] {
    LIGHT_SAMPLES.sample2(x, y, frame, i, 0)
}

fn main() {
    let (x, y, frame) = (3, 5, 2);
    println!("pixel ({x}, {y}) in frame {frame}:");
    println!("  kept at 30 % coverage: {}", kept(x, y, frame, 0.3));
    for i in 0..4 {
        println!(
            "  ray {i}: AO direction {:?}, light point {:?}",
            ao_direction(x, y, frame, i, 4),
            light_point(x, y, frame, i)
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dither keeps the coverage asked for, to within a pixel in a 64 × 64 block, every
    /// frame.
    #[test]
    fn the_dither_keeps_its_coverage() {
        for frame in [0, 1, 17] {
            let kept = (0..64 * 64)
                .filter(|p| kept(p % 64, p / 64, frame, 0.3))
                .count() as f32;
            assert!(
                (kept / 4096.0 - 0.3).abs() < 1.0 / 64.0,
                "frame {frame}: {kept}"
            );
        }
    }

    /// A frame's rays are unit directions in the upper hemisphere, and its light points lie in
    /// the square, each of its four quadrants holding one (a net per pixel).
    #[test]
    fn rays_and_light_points_are_well_formed() {
        for (x, y, frame) in [(0, 0, 0), (3, 5, 2), (-40, 900, 77)] {
            let mut quadrants = [0; 4];
            for i in 0..4 {
                let d = ao_direction(x, y, frame, i, 4);
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                assert!((len - 1.0).abs() < 1e-5 && d[2] >= 0.0, "{d:?}");
                let p = light_point(x, y, frame, i);
                assert!(p.iter().all(|v| (0.0..1.0).contains(v)), "{p:?}");
                quadrants[usize::from(p[0] >= 0.5) + 2 * usize::from(p[1] >= 0.5)] += 1;
            }
            assert_eq!(quadrants, [1, 1, 1, 1], "({x}, {y}, {frame})");
        }
    }
}
