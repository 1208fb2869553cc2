//! The WGSL library and baked masks in Bevy's own renderer, on the machine's Vulkan device
//! (lavapipe under CI): a compute pass imports `noisebake::…`, reads three masks uploaded
//! through [`mask_image`] (u8, u16, f32) and Bevy's `globals.frame_count`, and writes what it
//! read into a storage texture; the test reads the texture back and compares with the CPU
//! runtime at the frame the GPU saw. Without a Vulkan device the test is skipped, except under
//! `CI`, where it fails.

use std::sync::{Arc, Mutex};

use bevy::asset::RenderAssetUsages;
use bevy::diagnostic::FrameCount;
use bevy::prelude::*;
use bevy::render::extract_resource::{ExtractResource, ExtractResourcePlugin};
use bevy::render::globals::{GlobalsBuffer, GlobalsUniform};
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::binding_types::{
    texture_2d_array, texture_storage_2d, uniform_buffer,
};
use bevy::render::render_resource::*;
use bevy::render::renderer::{RenderContext, RenderDevice, RenderGraph};
use bevy::render::texture::GpuImage;
use bevy::render::{Render, RenderApp, RenderStartup, RenderSystems};
use bevy::shader::Shader;
use noise_runtime::{Mask3, ldg};
use noisebake_bevy::{NoisebakePlugin, mask_image};
use noisebake_test_support::bake::gen_tex;

const W: u32 = 16;
const H: u32 = 16;
const D: u32 = 8;
/// Written by the shader into every texel it wrote, so frames rendered before the pipeline was
/// ready (an uninitialised texture) are told apart.
const MARKER: u32 = 0xC0FF_EE00;

/// The compute pass: for each pixel, two `rgba32uint` texels side by side.
/// `(2x, y)`: frame, u8 mask k = 0, u16 mask k = 0, f32 mask k = 0;
/// `(2x + 1, y)`: IGN, R2, u8 mask k = 1 (an R2-offset address), the marker.
const SHADER: &str = r#"
#import noisebake::{nb_mask_unit, nb_mask_load, nb_mask_load_u, nb_u16_unit, nb_ign_frame, nb_r2_frame}
#import bevy_render::globals::Globals

@group(0) @binding(0) var mask_u8: texture_2d_array<f32>;
@group(0) @binding(1) var mask_u16: texture_2d_array<u32>;
@group(0) @binding(2) var mask_f32: texture_2d_array<f32>;
@group(0) @binding(3) var<uniform> globals: Globals;
@group(0) @binding(4) var out: texture_storage_2d<rgba32uint, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let frame = globals.frame_count;
    let px = vec2<i32>(id.xy);
    let p = vec3<i32>(px, i32(frame));
    let a = vec4<u32>(
        frame,
        bitcast<u32>(nb_mask_unit(mask_u8, p, 0u)),
        bitcast<u32>(nb_u16_unit(nb_mask_load_u(mask_u16, p, 0u).x)),
        bitcast<u32>(nb_mask_load(mask_f32, p, 0u).x),
    );
    let b = vec4<u32>(
        bitcast<u32>(nb_ign_frame(px, frame)),
        bitcast<u32>(nb_r2_frame(px, frame)),
        bitcast<u32>(nb_mask_unit(mask_u8, p, 1u)),
        0xC0FFEE00u,
    );
    textureStore(out, vec2<i32>(2 * px.x, px.y), a);
    textureStore(out, vec2<i32>(2 * px.x + 1, px.y), b);
}
"#;

const SHADER_HANDLE: Handle<Shader> =
    bevy::asset::uuid_handle!("5d8e3c1a-0f4e-4b55-9a51-2f0d8c3b7e11");

#[derive(Resource, ExtractResource, Clone)]
struct Targets {
    masks: [Handle<Image>; 3],
    out: Handle<Image>,
}

#[derive(Resource)]
struct Pipeline {
    layout: BindGroupLayoutDescriptor,
    id: CachedComputePipelineId,
}

#[derive(Resource)]
struct Bound(BindGroup);

fn init_pipeline(mut commands: Commands, cache: Res<PipelineCache>) {
    let layout = BindGroupLayoutDescriptor::new(
        "noisebake test",
        &BindGroupLayoutEntries::sequential(
            ShaderStages::COMPUTE,
            (
                texture_2d_array(TextureSampleType::Float { filterable: false }),
                texture_2d_array(TextureSampleType::Uint),
                texture_2d_array(TextureSampleType::Float { filterable: false }),
                uniform_buffer::<GlobalsUniform>(false),
                texture_storage_2d(TextureFormat::Rgba32Uint, StorageTextureAccess::WriteOnly),
            ),
        ),
    );
    let id = cache.queue_compute_pipeline(ComputePipelineDescriptor {
        label: Some("noisebake test".into()),
        layout: vec![layout.clone()],
        shader: SHADER_HANDLE,
        ..default()
    });
    commands.insert_resource(Pipeline { layout, id });
}

fn bind(
    mut commands: Commands,
    pipeline: Res<Pipeline>,
    device: Res<RenderDevice>,
    cache: Res<PipelineCache>,
    targets: Res<Targets>,
    images: Res<RenderAssets<GpuImage>>,
    globals: Res<GlobalsBuffer>,
) {
    let (Some(a), Some(b), Some(c), Some(out), Some(g)) = (
        images.get(&targets.masks[0]),
        images.get(&targets.masks[1]),
        images.get(&targets.masks[2]),
        images.get(&targets.out),
        globals.buffer.binding(),
    ) else {
        return;
    };
    let group = device.create_bind_group(
        None,
        &cache.get_bind_group_layout(&pipeline.layout),
        &BindGroupEntries::sequential((
            &a.texture_view,
            &b.texture_view,
            &c.texture_view,
            g,
            &out.texture_view,
        )),
    );
    commands.insert_resource(Bound(group));
}

fn dispatch(
    mut ctx: RenderContext,
    cache: Res<PipelineCache>,
    pipeline: Res<Pipeline>,
    bound: Option<Res<Bound>>,
) {
    let (Some(compute), Some(bound)) = (cache.get_compute_pipeline(pipeline.id), bound) else {
        return;
    };
    let mut pass = ctx
        .command_encoder()
        .begin_compute_pass(&ComputePassDescriptor::default());
    pass.set_bind_group(0, &bound.0, &[]);
    pass.set_pipeline(compute);
    pass.dispatch_workgroups(W / 8, H / 8, 1);
}

struct ComputePlugin;
impl Plugin for ComputePlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(ExtractResourcePlugin::<Targets>::default());
        let Some(render) = app.get_sub_app_mut(RenderApp) else {
            return;
        };
        render
            .add_systems(RenderStartup, init_pipeline)
            .add_systems(Render, bind.in_set(RenderSystems::PrepareBindGroups))
            .add_systems(RenderGraph, dispatch);
    }
}

fn leak(bytes: Vec<u8>) -> &'static [u8] {
    Box::leak(bytes.into_boxed_slice())
}

/// An app with the renderer started, or `None` (skipped) without a Vulkan device outside CI.
fn render_app() -> Option<App> {
    let started = std::panic::catch_unwind(|| {
        let mut app = App::new();
        app.add_plugins((fog::headless::plugins(), NoisebakePlugin, ComputePlugin));
        fog::headless::start(&mut app);
        app
    });
    if let (Ok(app), Ok(want)) = (&started, std::env::var("WGPU_ADAPTER_NAME")) {
        // Bevy falls back to its default adapter when none has the name: say so, since the
        // run is then not on the driver it was asked for.
        let got = app
            .world()
            .get_resource::<bevy::render::renderer::RenderAdapterInfo>()
            .map(|a| a.0.name.clone())
            .unwrap_or_default();
        assert!(
            got.to_lowercase().contains(&want.to_lowercase()),
            "asked Bevy for the adapter {want:?}, got {got:?}"
        );
    }
    match started {
        Ok(app) => {
            // The driver and its version, in the test output (`.ci/run` unpacks SwiftShader
            // from whatever chromium-common the distribution serves).
            if let Some(a) = app
                .world()
                .get_resource::<bevy::render::renderer::RenderAdapterInfo>()
            {
                eprintln!(
                    "Bevy renders on {} (driver {} {})",
                    a.0.name, a.0.driver, a.0.driver_info
                );
            }
            Some(app)
        }
        Err(_) if std::env::var_os("CI").is_some() => {
            panic!("Bevy found no GPU: CI must run the Bevy tests (install mesa-vulkan-drivers)")
        }
        Err(_) => {
            use std::io::Write;
            let _ = writeln!(
                std::io::stderr(),
                "SKIPPED: Bevy found no GPU; `apt-get install mesa-vulkan-drivers` gives a software one."
            );
            None
        }
    }
}

/// Runs `test` (the test of this file called `name`) once per driver named in
/// `NOISEBAKE_GPU_DRIVERS` (`.ci/run` names lavapipe and SwiftShader), each in a child process
/// of this test binary with `WGPU_ADAPTER_NAME` set, since Bevy chooses its adapter once per
/// process from the environment. Without the variable, or inside such a child, it runs `test`
/// here on the adapter Bevy finds.
fn on_each_driver(name: &str, test: impl FnOnce()) {
    let drivers = std::env::var("NOISEBAKE_GPU_DRIVERS").unwrap_or_default();
    if std::env::var_os("WGPU_ADAPTER_NAME").is_some() || drivers.trim().is_empty() {
        return test();
    }
    for driver in drivers.split(',').map(str::trim).filter(|d| !d.is_empty()) {
        let exe = std::env::current_exe().expect("the test binary's path");
        let out = std::process::Command::new(exe)
            .args([name, "--exact", "--nocapture", "--test-threads=1"])
            .env("WGPU_ADAPTER_NAME", driver)
            .output()
            .expect("the test binary runs again");
        let log = String::from_utf8_lossy(&out.stdout) + String::from_utf8_lossy(&out.stderr);
        assert!(
            out.status.success() && log.contains("1 passed"),
            "{name} on {driver}: {}\n{log}",
            out.status
        );
        eprintln!("{name}: passed on {driver}");
    }
}

#[test]
fn bevy_renders_the_wgsl_library_as_the_cpu_computes_it() {
    on_each_driver(
        "bevy_renders_the_wgsl_library_as_the_cpu_computes_it",
        library_test,
    );
}

fn library_test() {
    let u8_mask: Mask3<u8, W, H, D> = Mask3::new(leak(
        gen_tex("kind = \"stbn\"\ndims = [16, 16, 8]\nseed = 3").data,
    ));
    let u16_mask: Mask3<u16, W, H, D> = Mask3::new(leak(
        gen_tex("kind = \"white\"\ndims = [16, 16, 8]\nseed = 4\nformat = \"u16\"").data,
    ));
    let f32_mask: Mask3<f32, W, H, D> = Mask3::new(leak(
        gen_tex("kind = \"stbn\"\ndims = [16, 16, 8]\nseed = 5\nformat = \"f32\"").data,
    ));

    let Some(mut app) = render_app() else {
        return;
    };
    app.world_mut()
        .resource_mut::<Assets<Shader>>()
        .insert(
            &SHADER_HANDLE,
            Shader::from_wgsl(SHADER, "noisebake_test.wgsl"),
        )
        .unwrap();
    let mut images = app.world_mut().resource_mut::<Assets<Image>>();
    let masks = [
        images.add(mask_image(&u8_mask)),
        images.add(mask_image(&u16_mask)),
        images.add(mask_image(&f32_mask)),
    ];
    let mut out = Image::new_uninit(
        Extent3d {
            width: 2 * W,
            height: H,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba32Uint,
        RenderAssetUsages::RENDER_WORLD,
    );
    out.texture_descriptor.usage |= TextureUsages::COPY_SRC | TextureUsages::STORAGE_BINDING;
    let out = images.add(out);
    let frames: Arc<Mutex<Vec<Vec<u8>>>> = Arc::default();
    let sink = frames.clone();
    app.world_mut()
        .spawn(Readback::texture(out.clone()))
        .observe(move |e: On<ReadbackComplete>| sink.lock().unwrap().push(e.data.clone()));
    app.insert_resource(Targets { masks, out });

    // Frames before, at and well past the masks' depth of 8, set through Bevy's own counter.
    // Bounded by time, not by a count of updates: a slow driver (SwiftShader on a busy
    // machine) delivers readbacks several updates late and drops some.
    let mut seen = Vec::new();
    let started = std::time::Instant::now();
    for update in 0u32.. {
        if started.elapsed() > std::time::Duration::from_secs(120) {
            break;
        }
        let start = [0, 5, 8, 13, 40, 1001][(update / 8) as usize % 6];
        if update % 8 == 0 {
            app.world_mut().insert_resource(FrameCount(start));
        }
        app.update();
        // One frame in flight: a slow driver's queue never grows, and the app drops idle.
        fog::finish_gpu_work(&app).unwrap();
        for data in frames.lock().unwrap().drain(..) {
            let words: Vec<u32> = data
                .chunks_exact(4)
                .map(|b| u32::from_le_bytes(b.try_into().unwrap()))
                .collect();
            assert_eq!(words.len(), (2 * W * H * 4) as usize, "readback size");
            if words[7] != MARKER {
                continue; // rendered before the pipeline was ready
            }
            let frame = words[0];
            for y in 0..H {
                for x in 0..W {
                    let i = ((y * 2 * W + 2 * x) * 4) as usize;
                    let t = &words[i..i + 8];
                    let (xi, yi) = (x as i32, y as i32);
                    let at = format!("pixel ({x}, {y}), frame {frame}");
                    assert_eq!(t[0], frame, "one frame per dispatch");
                    assert_eq!(t[7], MARKER, "{at}: marker");
                    let u8k0 = u8_mask.get_k_unit(x, y, frame, 0);
                    assert_eq!(f32::from_bits(t[1]), u8k0, "{at}: u8 mask");
                    let u16k0 = u16_mask.get_k_unit(x, y, frame, 0);
                    assert_eq!(f32::from_bits(t[2]), u16k0, "{at}: u16 mask");
                    let f32k0 = f32_mask.get_k_unit(x, y, frame, 0);
                    assert_eq!(f32::from_bits(t[3]), f32k0, "{at}: f32 mask");
                    let ign = ldg::ign_frame(xi, yi, frame);
                    let d = (f32::from_bits(t[4]) - ign).abs();
                    assert!(
                        d.min(1.0 - d) <= 2f32.powi(-23),
                        "{at}: IGN {} vs {ign}",
                        f32::from_bits(t[4])
                    );
                    let r2 = ldg::r2_frame(xi, yi, frame);
                    assert_eq!(f32::from_bits(t[5]), r2, "{at}: R2");
                    let u8k1 = u8_mask.get_k_unit(x, y, frame, 1);
                    assert_eq!(f32::from_bits(t[6]), u8k1, "{at}: u8 mask, k = 1");
                }
            }
            seen.push(frame);
        }
        if seen.iter().any(|&f| f >= 1001) && seen.iter().any(|&f| f < D) && seen.len() >= 6 {
            break;
        }
    }
    assert!(
        seen.iter().any(|&f| f < D) && seen.iter().any(|&f| (D..2 * D).contains(&f)),
        "frames compared: {seen:?} (want some within the depth and some past it)"
    );
    assert!(seen.iter().any(|&f| f > 1000), "frames compared: {seen:?}");
}

#[path = "../examples/fog.rs"]
#[allow(dead_code)]
mod fog;

/// The example runs headless on the device Bevy finds, writes its screenshot, and the baked
/// mask leaves less error than white noise on both of its measures (the mean over frames, and
/// one frame through a denoiser's 5×5 box), as blue noise in space and time must.
#[test]
fn the_fog_example_renders_headless_and_the_mask_beats_white_noise() {
    on_each_driver(
        "the_fog_example_renders_headless_and_the_mask_beats_white_noise",
        fog_test,
    );
}

fn fog_test() {
    if render_app().is_none() {
        return;
    }
    let shot = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("noisebake-bevy-fog.png");
    let _ = std::fs::remove_file(&shot);
    let run = |noise, screenshot| {
        fog::run(&fog::Options {
            noise,
            frames: 16,
            size: 128,
            screenshot,
        })
        .unwrap()
    };
    let stbn = run(fog::Noise::Stbn, Some(shot.clone()));
    let white = run(fog::Noise::White, None);
    let png = std::fs::read(&shot).expect("the screenshot was written");
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    // The IHDR chunk: width and height, big-endian, at bytes 16..24.
    assert_eq!(png[16..24], [0, 0, 0, 128, 0, 0, 0, 128]);
    assert!(
        stbn.mean_rmse < white.mean_rmse && stbn.box5_rmse < white.box5_rmse,
        "stbn {stbn:?} vs white {white:?}"
    );
}

// Each example is its own crate and declares the headless helpers itself, so this test crate,
// which holds both examples, loads that file twice.
#[path = "../examples/taa3d.rs"]
#[allow(dead_code, clippy::duplicate_mod)]
mod taa3d;

/// The 3D example measures in Bevy's own TAA, headless, on a short run: every figure it
/// reports is finite where its surface is in view, every noise leaves the TAA output off the
/// reference (the dithered frames are not the blended ones), the structured noises leave less
/// error than white noise with the camera still, and the reference does not depend on the
/// runs before it.
#[test]
fn the_taa3d_example_measures_every_noise_in_bevys_taa() {
    on_each_driver(
        "the_taa3d_example_measures_every_noise_in_bevys_taa",
        taa3d_test,
    );
}

fn taa3d_test() {
    use taa3d::{CameraPath, Noise, Setting};
    if render_app().is_none() {
        return;
    }
    let opts = taa3d::Options {
        size: 64,
        frames: 8,
        still_warmup: 16,
        moving_warmup: 4,
        settings: vec![
            Setting {
                path: CameraPath::Still,
                hdr: false,
            },
            Setting {
                path: CameraPath::Orbit,
                hdr: true,
            },
        ],
        noises: vec![Noise::White, Noise::R2, Noise::FastTaa],
        markdown: None,
        frames_out: None,
    };
    let m = taa3d::measure_all(&opts, true).unwrap();
    assert_eq!(m.paths.len(), 2);
    for p in &m.paths {
        assert_eq!(p.noises.len(), 3);
        for (noise, f) in &p.noises {
            for (k, (class, _)) in taa3d_classes().iter().enumerate() {
                if p.class_pixels[k] > 0.0 {
                    assert!(
                        f.rmse[k][0].is_finite() && f.rmse[k][1].is_finite() && f.rmse[k][0] > 0.0,
                        "{:?} {noise:?} {class}: {:?}",
                        p.setting,
                        f.rmse[k]
                    );
                }
            }
            // Over the whole image (the same pixels every frame) the error's mean over the
            // frames cannot exceed the error: the static part is a part of it.
            let image = taa3d_classes().len() - 1;
            let (part, whole) = (f.static_part[image], f.rmse[image][1]);
            assert!(
                part.is_finite() && part > 0.0 && part <= whole * (1.0 + 1e-9),
                "{:?} {noise:?}: static part {part} of {whole}",
                p.setting
            );
            if p.setting.path == CameraPath::Still {
                // The pane fills its pixels in every frame, jitter or not.
                assert!(
                    f.static_part[0].is_finite(),
                    "{noise:?}: {:?}",
                    f.static_part
                );
            }
        }
        assert!(
            p.class_pixels.iter().all(|&c| c > 0.0),
            "{:?}: a surface out of view: {:?}",
            p.setting,
            p.class_pixels
        );
    }
    let image = taa3d_classes().len() - 1;
    let still = &m.paths[0].noises;
    assert!(
        still[1].1.rmse[image][1] < still[0].1.rmse[image][1],
        "R2 {:?} against white {:?}",
        still[1].1.rmse[image],
        still[0].1.rmse[image]
    );
    let markdown = taa3d::markdown(&m, "# stamp\n");
    assert!(markdown.contains("## Camera `orbit`, `Hdr`"), "{markdown}");
    assert!(markdown.contains("| pane 30 % |"), "{markdown}");
    assert!(markdown.contains("| static part (image) |"), "{markdown}");

    let (a, b) = taa3d::reference_twice(
        Setting {
            path: CameraPath::Pan,
            hdr: false,
        },
        64,
        6,
    )
    .unwrap();
    assert_eq!(a, b, "the reference changed after the dithered runs");
}

fn taa3d_classes() -> Vec<(&'static str, u32)> {
    taa3d::CLASSES.to_vec()
}
