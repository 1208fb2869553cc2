//! The demo's two panels on a small image, held to properties their verdicts rest on.

use noisebake_demo::{Config, spp_panel, taa_panel};

fn small(frames: usize) -> Config {
    Config {
        size: [64, 64],
        frames,
        mc_frames: 1,
        out: None,
    }
}

/// Four rays per pixel: every sampler beats white noise on one frame after the blur, and the
/// tile baked for that blur is among the best (no sampler's error below the tile's by more
/// than twice the standard error of the difference).
#[test]
fn the_tile_is_among_the_best_four_ray_samplers_and_white_is_the_worst() {
    let rows = spp_panel::run(&small(2));
    let get = |n: &str| rows.iter().find(|r| r.name == n).expect(n);
    let (white, tile) = (get("white"), get("sampler tile"));
    for r in &rows {
        if r.name != "white" {
            assert!(r.first.0 < white.first.0, "{} vs white", r.name);
        }
        assert!(
            tile.first.0 - r.first.0 <= 2.0 * tile.first.1.hypot(r.first.1),
            "{} ({:?}) beats the tile ({:?})",
            r.name,
            r.first,
            tile.first
        );
    }
    assert!(spp_panel::verdict(&rows).starts_with("least error on one frame"));
}

/// Under TAA at opacity 0.3 the mask made for TAA keeps its windows, so the clamp leaves its
/// error as the EMA's (up to the image border's cut windows, which the measure leaves out),
/// while white noise, whose windows often lie on one side, loses to the clamp.
#[test]
fn the_clamp_spares_the_taa_mask_and_not_white_noise() {
    let rows = taa_panel::run(&small(32));
    let get = |n: &str| rows.iter().find(|r| r.noise.name() == n).expect(n);
    let (taa, white) = (get("fast-taa"), get("white"));
    assert!(
        (taa.taa.0 - taa.ema.0).abs() <= 0.02 * taa.ema.0,
        "{:?} vs {:?}",
        taa.taa,
        taa.ema
    );
    assert!(
        white.taa.0 > 1.5 * white.ema.0,
        "{:?} vs {:?}",
        white.taa,
        white.ema
    );
}
