//! The demo's stochastic transparency and RGB dithering rendered on a GPU through wgpu, headless,
//! with the demo's baked STBN and FAST masks uploaded from the runtime's bytes and sampled with
//! the WGSL library (`noisebake::shaders::WGSL`), next to the free constructions IGN and R2
//! (`nb_ign_r2`, the demo's `ign` and `r2` rows) computed in the shader.
//!
//! `cargo run --release --example gpu` prints, per application and noise, the GPU time of one
//! frame and the error of the 64-frame EMA after the demo's Gaussian blur against the demo's
//! reference — measured by the demo's own code on the frames read back — beside the CPU
//! render's error of the same noise (equal up to the GPU's `sin`/`cos`; ξ is the same bits).
//! PNGs of the final EMA go to `target/noisebake-demo/`, beside the demo's.
//!
//! Without a GPU it needs a software Vulkan driver (Debian: `apt-get install
//! mesa-vulkan-drivers`); the timings are then the CPU's, through lavapipe.

use noisebake::Mask3;
use noisebake_demo::apps::{App, Dither, Transparency};
use noisebake_demo::noises::{FAST, Noise, STBN};
use noisebake_demo::{Config, GPU_SCENES, blur, evaluate, save_png};
use noisebake_gpu::{Binding, Gpu, bytes_of, floats};
use std::path::PathBuf;
use std::time::Duration;

const NOISES: [(Noise, u32); 4] = [
    (Noise::Stbn, 0),
    (Noise::Fast, 1),
    (Noise::Ign, 2),
    (Noise::R2, 3),
];

/// Uploads a scalar u8 mask from its runtime view, as a game would.
fn upload<const W: u32, const H: u32, const D: u32>(
    gpu: &Gpu,
    m: &Mask3<u8, W, H, D>,
) -> noisebake_gpu::wgpu::Texture {
    let bytes = m.gpu_bytes().expect("scalar masks upload their own bytes");
    gpu.upload_mask(m.gpu_texture(), bytes)
}

fn main() {
    let gpu = match Gpu::new() {
        Ok(g) => g,
        Err(e) => {
            eprintln!(
                "error: {e}\nThe GPU example needs a Vulkan device; without a GPU, `apt-get install \
                 mesa-vulkan-drivers libvulkan1` provides a software one."
            );
            std::process::exit(1);
        }
    };
    let cfg = Config::default();
    let [w, h] = cfg.size;
    let out = PathBuf::from("target/noisebake-demo");
    std::fs::create_dir_all(&out).unwrap_or_else(|e| panic!("{}: {e}", out.display()));
    println!("noisebake on the GPU: {}", gpu.describe());
    println!(
        "{} frames of {w}×{h}; error = RMSE of the {}-frame EMA after the demo's σ 1 px blur, against the demo's reference",
        cfg.frames, cfg.frames
    );
    println!(
        "  {:<13} {:<7} {:>13} {:>11} {:>11} {:>14}",
        "application", "noise", "GPU ms/frame", "GPU error", "CPU error", "max |GPU−CPU|"
    );
    let stbn = upload(&gpu, &STBN);
    let fast = upload(&gpu, &FAST);
    let apps: [(&dyn App, u32); 2] = [
        (&Transparency { size: cfg.size }, 0),
        (&Dither { size: cfg.size }, 1),
    ];
    for (app, app_id) in apps {
        let c = app.channels();
        let reference = app.reference();
        let ref_blur = blur(&reference, cfg.size, c);
        for (noise, noise_id) in NOISES {
            let params = bytes_of(&[w as u32, h as u32, noise_id, app_id]);
            let frame_len = w * h * c;
            // All frames in one dispatch (z = frame), repeated for a steadier timing.
            const REPEAT: u32 = 8;
            let (outputs, per_dispatch): (Vec<Vec<u8>>, Duration) = gpu
                .run_timed(
                    GPU_SCENES,
                    [
                        (w as u32).div_ceil(8),
                        (h as u32).div_ceil(8),
                        cfg.frames as u32,
                    ],
                    &[
                        Binding::Uniform(&params),
                        Binding::Output(frame_len * cfg.frames * 4),
                        Binding::Texture(&stbn),
                        Binding::Texture(&fast),
                    ],
                    REPEAT,
                )
                .unwrap_or_else(|e| panic!("{e}"));
            let frames = floats(&outputs[0]);
            let mut from_gpu = |f: u32, frame: &mut [f32]| {
                let start = f as usize * frame_len;
                frame.copy_from_slice(&frames[start..start + frame_len]);
            };
            let (gpu_m, images) = evaluate(app, &cfg, noise, &reference, &ref_blur, &mut from_gpu);
            let [w_, h_] = cfg.size;
            let mut on_cpu = |f: u32, frame: &mut [f32]| {
                for y in 0..h_ {
                    for x in 0..w_ {
                        let i = (y * w_ + x) * c;
                        app.pixel(noise, x, y, f, &mut frame[i..i + c]);
                    }
                }
            };
            let (cpu_m, cpu_images) =
                evaluate(app, &cfg, noise, &reference, &ref_blur, &mut on_cpu);
            let largest = images[2]
                .iter()
                .zip(&cpu_images[2])
                .map(|(a, b)| (a - b).abs())
                .fold(0.0f32, f32::max);
            let ms = per_dispatch.as_secs_f64() * 1e3 / cfg.frames as f64;
            println!(
                "  {:<13} {:<7} {:>13.4} {:>11.5} {:>11.5} {:>14.1e}",
                app.name(),
                noise.name(),
                ms,
                gpu_m.denoised,
                cpu_m.denoised,
                largest
            );
            let png = out.join(format!("gpu_{}_{}.png", app.name(), noise.name()));
            save_png(&png, &images[2], cfg.size, c).unwrap_or_else(|e| panic!("{e}"));
        }
    }
    println!("PNGs of the final EMA: {}/gpu_*.png", out.display());
}
