//! Dithered fog in Bevy: a fullscreen `Material2d` draws each pixel opaque with probability
//! equal to the fog's coverage there (stochastic transparency), comparing the coverage with a
//! per-pixel, per-frame value from a baked STBN mask, interleaved gradient noise or white noise.
//! It renders headless on whatever Vulkan device Bevy finds (lavapipe on a CPU-only machine),
//! reads every frame back, and logs how far the frames' mean and one frame through a 5×5 box
//! (a denoiser's footprint) are from the exact coverage.
//!
//! ```text
//! cargo run --release -p noisebake-bevy --example fog -- --noise stbn --frames 32 --screenshot fog.png
//! ```
//!
//! `--noise stbn|ign|white` (default stbn), `--frames N` (default 32), `--size S` (a multiple
//! of 64, default 256), `--screenshot FILE` (the last frame as PNG).

#[path = "common/headless.rs"]
pub mod headless;
pub use headless::finish_gpu_work;

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use bevy::asset::{RenderAssetUsages, uuid_handle};
use bevy::camera::RenderTarget;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::prelude::*;
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::render_resource::{
    AsBindGroup, Extent3d, TextureDimension, TextureFormat, TextureUsages,
};
use bevy::shader::{Shader, ShaderRef};
use bevy::sprite_render::{Material2d, Material2dPlugin};
use noisebake_bevy::{NoisebakePlugin, mask_image};

noisebake::noise_texture!(pub STBN = stbn { dims: [64, 64, 32], seed: 1 });

/// Which value each pixel compares its coverage against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Noise {
    /// The baked 64×64×32 STBN mask, through `nb_mask_unit`.
    Stbn,
    /// Interleaved gradient noise animated by the golden ratio, `nb_ign_frame`.
    Ign,
    /// A hash of (x, y, frame), `nb_hash3`.
    White,
}

impl Noise {
    fn name(self) -> &'static str {
        match self {
            Noise::Stbn => "stbn",
            Noise::Ign => "ign",
            Noise::White => "white",
        }
    }
}

/// What to render.
#[derive(Clone, Debug)]
pub struct Options {
    pub noise: Noise,
    pub frames: u32,
    pub size: u32,
    pub screenshot: Option<PathBuf>,
}

/// What it measured: RMSE against the exact coverage.
#[derive(Clone, Debug)]
pub struct Report {
    /// The mean of the frames rendered.
    pub mean_rmse: f64,
    /// The last frame through a 5×5 box, against the coverage through the same box.
    pub box5_rmse: f64,
    /// The GPU Bevy rendered on.
    pub adapter: String,
}

const FOG_SHADER: Handle<Shader> = uuid_handle!("0e2f6a57-31d4-4f4f-8f0a-6c1b2f9d7a40");

/// The fog's coverage at a pixel centre `p` of a `size`² target: a ramp left to right,
/// strongest across the middle rows. The same arithmetic as `fog` in the shader.
fn coverage(px: f32, py: f32, size: f32) -> f32 {
    let (u, v) = (px / size, py / size);
    0.05 + 0.9 * u * (4.0 * v * (1.0 - v))
}

const FRAGMENT: &str = r#"
#import bevy_sprite::mesh2d_vertex_output::VertexOutput
#import bevy_sprite::mesh2d_view_bindings::globals
#import noisebake::{nb_mask_unit, nb_ign_frame, nb_hash3, nb_to_unit}

@group(#{MATERIAL_BIND_GROUP}) @binding(0) var<uniform> params: vec4<u32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(1) var mask: texture_2d_array<f32>;

fn fog(p: vec2<f32>, size: f32) -> f32 {
    let u = p.x / size;
    let v = p.y / size;
    return 0.05 + 0.9 * u * (4.0 * v * (1.0 - v));
}

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {
    let px = vec2<i32>(floor(in.position.xy));
    let frame = globals.frame_count;
    var xi: f32;
    switch params.x {
        case 0u: { xi = nb_mask_unit(mask, vec3<i32>(px, i32(frame)), 0u); }
        case 1u: { xi = nb_ign_frame(px, frame); }
        default: { xi = nb_to_unit(nb_hash3(vec3<i32>(px, i32(frame)), 7u)); }
    }
    if xi >= fog(in.position.xy, f32(params.y)) {
        discard;
    }
    return vec4<f32>(1.0);
}
"#;

#[derive(Asset, TypePath, AsBindGroup, Clone)]
struct FogMaterial {
    /// x: the noise (0 STBN, 1 IGN, 2 white); y: the target's size.
    #[uniform(0)]
    params: UVec4,
    #[texture(1, dimension = "2d_array", sample_type = "float", filterable = false)]
    mask: Handle<Image>,
}

impl Material2d for FogMaterial {
    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(FOG_SHADER)
    }
}

/// Renders `opts.frames` frames and measures them.
pub fn run(opts: &Options) -> Result<Report, String> {
    if opts.size == 0 || !opts.size.is_multiple_of(64) || opts.frames == 0 {
        return Err(format!(
            "--size must be a positive multiple of 64 (got {}) and --frames positive (got {})",
            opts.size, opts.frames
        ));
    }
    let mut app = App::new();
    app.add_plugins((
        headless::plugins(),
        NoisebakePlugin,
        Material2dPlugin::<FogMaterial>::default(),
    ));
    headless::start(&mut app);
    app.world_mut()
        .resource_mut::<Assets<Shader>>()
        .insert(&FOG_SHADER, Shader::from_wgsl(FRAGMENT, "fog.wgsl"))
        .map_err(|e| e.to_string())?;
    app.insert_resource(ClearColor(Color::BLACK));

    let n = opts.size;
    let world = app.world_mut();
    let mask = world.resource_mut::<Assets<Image>>().add(mask_image(&STBN));
    let mut target = Image::new_target_texture(n, n, TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let target = world.resource_mut::<Assets<Image>>().add(target);
    let material = world
        .resource_mut::<Assets<FogMaterial>>()
        .add(FogMaterial {
            params: UVec4::new(opts.noise as u32, n, 0, 0),
            mask,
        });
    let quad = world
        .resource_mut::<Assets<Mesh>>()
        .add(Rectangle::new(n as f32, n as f32));
    world.spawn((
        Camera2d,
        RenderTarget::Image(target.clone().into()),
        Tonemapping::None,
    ));
    world.spawn((Mesh2d(quad), MeshMaterial2d(material)));
    let frames: Arc<Mutex<Vec<Vec<u8>>>> = Arc::default();
    let sink = frames.clone();
    world
        .spawn(Readback::texture(target))
        .observe(move |e: On<ReadbackComplete>| sink.lock().unwrap().push(e.data.clone()));

    // Read frames back until `opts.frames` have arrived that show the fog. The frames drawn
    // before the material's pipeline is ready are blank (Bevy compiles it in the background,
    // and a slow driver draws many frames first), and a slow driver delivers readbacks late:
    // so wait for fog frames for up to two minutes, however many updates that takes.
    let texels = (n * n) as usize;
    let mut kept: Vec<Vec<u8>> = Vec::new();
    let started = std::time::Instant::now();
    while started.elapsed() < std::time::Duration::from_secs(120) {
        app.update();
        finish_gpu_work(&app)?;
        for f in frames.lock().unwrap().drain(..) {
            if f.len() != texels * 4 {
                return Err(format!(
                    "readback of {} bytes, expected {}",
                    f.len(),
                    texels * 4
                ));
            }
            if f.chunks_exact(4).any(|t| t[0] != 0) && kept.len() < opts.frames as usize {
                kept.push(f);
            }
        }
        if kept.len() == opts.frames as usize {
            break;
        }
    }
    if kept.len() < opts.frames as usize {
        return Err(format!(
            "only {} frames showed the fog in {:.0} s",
            kept.len(),
            started.elapsed().as_secs_f64()
        ));
    }
    let adapter = app
        .world()
        .get_resource::<bevy::render::renderer::RenderAdapterInfo>()
        .map_or("an unknown adapter".to_string(), |a| a.0.name.clone());

    // Measure: each texel is 0 or 255 (opaque white on black), so coverage = byte / 255.
    let size = n as usize;
    let exact: Vec<f64> = (0..texels)
        .map(|i| coverage((i % size) as f32 + 0.5, (i / size) as f32 + 0.5, n as f32) as f64)
        .collect();
    let frame =
        |f: &Vec<u8>| -> Vec<f64> { f.chunks_exact(4).map(|t| t[0] as f64 / 255.0).collect() };
    let mut mean = vec![0.0; texels];
    for f in &kept {
        for (m, v) in mean.iter_mut().zip(frame(f)) {
            *m += v / kept.len() as f64;
        }
    }
    let rmse = |a: &[f64], b: &[f64]| {
        (a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>() / a.len() as f64).sqrt()
    };
    let last = frame(kept.last().unwrap());
    let report = Report {
        mean_rmse: rmse(&mean, &exact),
        box5_rmse: rmse(&box5(&last, size), &box5(&exact, size)),
        adapter,
    };
    if let Some(path) = &opts.screenshot {
        let image = Image::new(
            Extent3d {
                width: n,
                height: n,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            kept.pop().unwrap(),
            TextureFormat::Rgba8UnormSrgb,
            RenderAssetUsages::MAIN_WORLD,
        );
        image
            .try_into_dynamic()
            .map_err(|e| e.to_string())?
            .save(path)
            .map_err(|e| format!("writing {}: {e}", path.display()))?;
    }
    Ok(report)
}

/// A 5×5 box filter with toroidal wrap.
fn box5(v: &[f64], n: usize) -> Vec<f64> {
    (0..v.len())
        .map(|i| {
            let (x, y) = (i % n, i / n);
            let mut s = 0.0;
            for dy in 0..5 {
                for dx in 0..5 {
                    s += v[(y + n + dy - 2) % n * n + (x + n + dx - 2) % n];
                }
            }
            s / 25.0
        })
        .collect()
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut opts = Options {
        noise: Noise::Stbn,
        frames: 32,
        size: 256,
        screenshot: None,
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or(format!("{a} needs a value"));
        match a.as_str() {
            "--noise" => {
                opts.noise = match value()?.as_str() {
                    "stbn" => Noise::Stbn,
                    "ign" => Noise::Ign,
                    "white" => Noise::White,
                    other => return Err(format!("--noise {other}: expected stbn, ign or white")),
                }
            }
            "--frames" => opts.frames = value()?.parse().map_err(|e| format!("--frames: {e}"))?,
            "--size" => opts.size = value()?.parse().map_err(|e| format!("--size: {e}"))?,
            "--screenshot" => opts.screenshot = Some(PathBuf::from(value()?)),
            other => return Err(format!("unknown argument {other} (see the example's docs)")),
        }
    }
    Ok(opts)
}

#[allow(dead_code)] // the tests include this file for `run`
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = parse(&args).and_then(|opts| {
        println!(
            "noise: {} (choose with --noise stbn|ign|white); {} frames of {}×{}",
            opts.noise.name(),
            opts.frames,
            opts.size,
            opts.size
        );
        run(&opts).map(|r| (opts, r))
    });
    match result {
        Ok((opts, r)) => {
            println!("rendered by Bevy on {}", r.adapter);
            println!(
                "error against the fog's exact coverage (RMSE): mean of the {} frames {:.4}; one frame through a 5×5 box {:.4}",
                opts.frames, r.mean_rmse, r.box5_rmse
            );
            if let Some(p) = &opts.screenshot {
                println!("screenshot: {}", p.display());
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
