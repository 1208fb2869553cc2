//! The GPU example's scenes (`noisebake_demo::GPU_SCENES`) against the CPU demo, pixel by pixel:
//! the demo's baked STBN and FAST masks uploaded from the runtime's bytes and read through the
//! WGSL library give every pixel of every frame the CPU's value — exactly for dithering, and
//! for transparency up to the GPU's `sin` in the background (1e-6), with a pixel allowed to
//! choose the other layer only where IGN's ξ, which the GPU computes in fixed point, lies within
//! 2^-22 of the opacity.

use noisebake_demo::apps::{App, Dither, Transparency};
use noisebake_demo::noises::{FAST, Noise, STBN};
use noisebake_gpu::{Binding, Gpu, bytes_of, floats};

#[test]
fn gpu_scenes_match_the_cpu_demo() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let (w, h, frames) = (64usize, 48usize, 8u32);
    let stbn = gpu.upload_mask(STBN.gpu_texture(), STBN.gpu_bytes().unwrap());
    let fast = gpu.upload_mask(FAST.gpu_texture(), FAST.gpu_bytes().unwrap());
    let apps: [(&dyn App, u32); 2] = [
        (&Transparency { size: [w, h] }, 0),
        (&Dither { size: [w, h] }, 1),
    ];
    let noises = [
        (Noise::Stbn, 0u32),
        (Noise::Fast, 1),
        (Noise::Ign, 2),
        (Noise::R2, 3),
    ];
    for (app, app_id) in apps {
        let c = app.channels();
        for (noise, noise_id) in noises {
            let params = bytes_of(&[w as u32, h as u32, noise_id, app_id]);
            let out = gpu
                .run(
                    noisebake_demo::GPU_SCENES,
                    [(w as u32).div_ceil(8), (h as u32).div_ceil(8), frames],
                    &[
                        Binding::Uniform(&params),
                        Binding::Output(w * h * c * frames as usize * 4),
                        Binding::Texture(&stbn),
                        Binding::Texture(&fast),
                    ],
                )
                .unwrap_or_else(|e| panic!("{e}"));
            let got = floats(&out[0]);
            let mut px = vec![0.0f32; c];
            let mut flips = 0;
            for f in 0..frames {
                for y in 0..h {
                    for x in 0..w {
                        app.pixel(noise, x, y, f, &mut px);
                        let i = ((f as usize * h + y) * w + x) * c;
                        for k in 0..c {
                            let d = (got[i + k] - px[k]).abs();
                            let tol = if app_id == 0 { 1e-6 } else { 0.0 };
                            if d > tol {
                                let alpha = if x < w / 2 { 0.9 } else { 0.3 };
                                let xi = noise.xi(x as i32, y as i32, f, 0);
                                assert!(
                                    noise == Noise::Ign && (xi - alpha).abs() <= 2.0 * f32::EPSILON,
                                    "{} {}: pixel ({x}, {y}) frame {f} channel {k}: GPU {}, CPU {}",
                                    app.name(),
                                    noise.name(),
                                    got[i + k],
                                    px[k]
                                );
                                flips += 1;
                            }
                        }
                    }
                }
            }
            assert!(
                flips <= 2,
                "{} {}: {flips} pixels chose the other layer",
                app.name(),
                noise.name()
            );
        }
    }
}
