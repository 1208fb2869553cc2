//! The GPU example's scenes (`noisebake_demo::GPU_SCENES`) against the CPU demo, pixel by pixel,
//! on every Vulkan driver of the machine: the demo's baked STBN and FAST masks uploaded from the
//! runtime's bytes and read through the WGSL library, and the free IGN/R2 pairs computed in the
//! shader, give every pixel of every frame the CPU's ξ bit for bit (integer paths). What may
//! differ is the scene's own colour, which the shader computes in `f32` with the GPU's
//! arithmetic. The model of allowed differences, from Vulkan's precision rules (SPIR-V lets a
//! driver fuse `a * b + c`, naga emits no `NoContraction`; division is within 2.5 ulp, `sqrt`
//! within 3 ulp; `sin` and `cos` within 2^-11 absolute):
//!
//! - a colour computed from `+`, `*`, `/` and `sqrt` (the dither's red and blue, the
//!   transparency's layers away from `sin`) may differ by at most [`ARITH`] = 2^-20;
//! - one scaled by a `sin` or `cos` of amplitude `a` by at most `a · 2^-11 + ARITH`;
//! - a threshold `c > ξ` may therefore come out the other way only where the CPU's colour lies
//!   within that distance of ξ. The scene is built so that such ties happen: its red channel
//!   `0.1 + 0.8u` equals the 8-bit mask value 192/256 at x = 52, where a fused multiply-add
//!   decides the comparison. A pixel that flips farther from its threshold, or a layer
//!   decision `ξ < α` that flips at all (ξ exact, α a constant), fails the test.

use noisebake_demo::apps::{App, Dither, Transparency};
use noisebake_demo::noises::{FAST, Noise, STBN};
use noisebake_gpu::{Binding, Gpu, bytes_of, floats};

/// How far a colour of `+`, `*`, `/` and `sqrt` on values in [0, 1] may move on a GPU: a few
/// roundings of fused or unfused products and a 2.5-ulp division, bounded by 16 ulp of 1.
const ARITH: f32 = 1.0 / (1 << 20) as f32;
/// Vulkan's absolute error bound for `sin` and `cos`.
const TRIG: f32 = 1.0 / (1 << 11) as f32;

#[test]
fn gpu_scenes_match_the_cpu_demo() {
    Gpu::each_for_tests(|gpu| {
        let (w, h, frames) = (64usize, 48usize, 8u32);
        let stbn = gpu.upload_mask(STBN.gpu_texture(), STBN.gpu_bytes().unwrap());
        let fast = gpu.upload_mask(FAST.gpu_texture(), FAST.gpu_bytes().unwrap());
        let dither = Dither { size: [w, h] };
        let apps: [(&dyn App, u32); 2] = [(&Transparency { size: [w, h] }, 0), (&dither, 1)];
        let noises = [
            (Noise::Stbn, 0u32),
            (Noise::Fast, 1),
            (Noise::Ign, 2),
            (Noise::R2, 3),
        ];
        let mut ties = 0;
        let mut flips = 0;
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
                for f in 0..frames {
                    for y in 0..h {
                        for x in 0..w {
                            app.pixel(noise, x, y, f, &mut px);
                            let i = ((f as usize * h + y) * w + x) * c;
                            for k in 0..c {
                                let (gpu_v, cpu_v) = (got[i + k], px[k]);
                                let what = || {
                                    format!(
                                        "{} {}: pixel ({x}, {y}) frame {f} channel {k}: GPU {gpu_v}, CPU {cpu_v}",
                                        app.name(),
                                        noise.name()
                                    )
                                };
                                if app_id == 0 {
                                    // Transparency: the layer is decided by ξ < α, exact on
                                    // both sides; the background may move by its `sin`'s
                                    // error (amplitude 0.25 at most).
                                    let layer = |v: f32| v == 0.95;
                                    assert_eq!(layer(gpu_v), layer(cpu_v), "{}", what());
                                    let tol = 0.25 * TRIG + ARITH;
                                    assert!(
                                        (gpu_v - cpu_v).abs() <= tol,
                                        "{} (tolerance {tol:e})",
                                        what()
                                    );
                                } else {
                                    // Dithering: c > ξ, c within its tolerance of the CPU's.
                                    let xi = noise.xi(x as i32, y as i32, f, k as u32);
                                    let colour = dither.colour(x, y)[k];
                                    let tol = if k == 1 { 0.45 * TRIG + ARITH } else { ARITH };
                                    let near = (colour - xi).abs() <= tol;
                                    ties += near as usize;
                                    if gpu_v != cpu_v {
                                        assert!(
                                            near,
                                            "{}: the colour {colour} is {:e} from ξ {xi}, beyond the tolerance {tol:e}",
                                            what(),
                                            (colour - xi).abs()
                                        );
                                        flips += 1;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        eprintln!(
            "{}: {flips} dithered channels flipped at {ties} within tolerance of their threshold",
            gpu.describe()
        );
    });
}
