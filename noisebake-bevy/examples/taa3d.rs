//! Stochastic transparency, alpha-cut foliage and a jittered fog march in a lit 3D scene under
//! Bevy's own temporal anti-aliasing, with a still or moving camera — and, headless, the
//! measurement of every noise through Bevy's renderer.
//!
//! ```text
//! cargo run --release -p noisebake-bevy --example taa3d                  # in a window
//! cargo run --release -p noisebake-bevy --example taa3d -- --measure --markdown bevy-taa.md
//! ```
//!
//! **The scene.** A floor, a wall and a few lit boxes; a glass pane at 30 % coverage drawn by
//! stochastic transparency (a fragment is kept where the noise value is below the coverage);
//! five foliage cards at 10, 25, 50, 75 and 90 %; a fog box marched in six steps from a start
//! jittered by the noise. Every surface picks its noise at run time: white, interleaved
//! gradient noise (`nb_ign_frame`), the R2 grid (`nb_r2_frame`), or one of three 64×64×64
//! masks that `noise.toml` declares and `build.rs` bakes (the `taa3d-masks` crate beside this
//! file, as a game would): STBN, a FAST mask for an EMA, and the FAST mask for TAA. The camera
//! (`Camera3d`, `Msaa::Off`, `TemporalAntiAliasing` with its depth and motion-vector
//! prepasses, the projection jittered each frame) is still or follows a path: `pan` (a yaw out
//! and back), `orbit` (around the scene: parallax and disocclusion) or `dolly` (in and out).
//! It renders in Bevy's default low dynamic range, or with `Hdr` (`H` in the window; the paths
//! `still-hdr`, `pan-hdr`, … when measuring): there Bevy's TAA blends in a reversible
//! tonemapped space, `c / (1 + max(c))`, and a dither converges to the tonemapped mean of its
//! two colours rather than to their mean, whatever the noise.
//!
//! **In a window** (the default): `N` cycles the noise, `C` the camera path, `R` toggles the
//! reference (the surfaces alpha-blended, the fog marched finely), `H` toggles `Hdr`.
//!
//! **Measured** (`--measure`): headless at `--size` (256) pixels on whatever Vulkan device
//! Bevy finds (lavapipe on a machine without a GPU). For each path and noise, the TAA output
//! of `--frames` (64) frames is read back after `--warmup` frames on the same path (224 for
//! the still camera, whose history Bevy blends at as little as 1.5 % a frame with `Hdr`, and
//! 24 for the moving ones),
//! and compared with the reference: the same scene, TAA and path, with every surface
//! alpha-blended at its coverage and the fog marched in 128 steps. Errors are RMSE over frames
//! 32–63 (of 64), raw and after a Gaussian of σ 1 px, per surface (a class run maps which
//! surface each pixel sees) and over the image; the flicker: the RMS of the frame-to-frame
//! change of the Gaussian-filtered error; and the static part: the RMS over pixels of that
//! error's mean over the measured frames, a bias per pixel. In low dynamic range Bevy keeps
//! the history in the 8-bit sRGB view-target format, which rounds every blended value and
//! saturates the confidence it keeps in alpha (a still pixel then blends at 1/11, not 0.015);
//! the static part shows what that rounding leaves. `--markdown FILE` writes them as a
//! stamped document; `--frames-out DIR` writes `DIR/<path>/<noise>.npy` and
//! `DIR/<path>/reference.npy`, float32 `(frames, H, W, 3)`, the linear TAA output of every
//! frame. `--paths` (`still`, `pan`, `orbit`, `dolly`, each also with `-hdr`; by default the
//! four in low dynamic range and `still-hdr`) and `--noises` (comma-separated)
//! measure a subset; `--size`, `--frames` and `--warmup` change the run.
//!
//! **The reference's own error.** Bevy's prepasses skip alpha-blended meshes: in the
//! reference the blended surfaces write no depth or motion vectors, so TAA reprojects their
//! pixels with the motion of what lies behind them (the wall, the floor), and clips their
//! history to a neighbourhood of smooth blended colour rather than of a dither. With the
//! camera still that changes nothing; with it moving, a blended pane's history is fetched
//! from where the surface behind it was, a small ghost the dithered runs do not have (they
//! write their own motion vectors). The document gives the reference's distance from itself
//! rendered without TAA, which bounds what TAA adds to it.

#[path = "common/headless.rs"]
mod headless;
#[path = "taa3d/measure.rs"]
mod measure;
#[path = "taa3d/shaders.rs"]
mod shaders;

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use bevy::anti_alias::taa::TemporalAntiAliasing;
use bevy::asset::uuid_handle;
use bevy::camera::{Hdr, RenderTarget};
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::diagnostic::FrameCount;
use bevy::mesh::MeshVertexBufferLayoutRef;
use bevy::pbr::{MaterialPipeline, MaterialPipelineKey};
use bevy::prelude::*;
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::render_resource::{
    AsBindGroup, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError, TextureFormat,
    TextureUsages,
};
use bevy::shader::{Shader, ShaderRef};
pub use measure::{CLASSES, Frame};
use noisebake_bevy::{NoisebakePlugin, mask_image};

/// The noises every surface can read, in the order of `noise` in the shaders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Noise {
    White,
    Ign,
    R2,
    Stbn,
    FastEma,
    FastTaa,
    FastBevy,
}

impl Noise {
    pub const ALL: [Noise; 7] = [
        Noise::White,
        Noise::Ign,
        Noise::R2,
        Noise::Stbn,
        Noise::FastEma,
        Noise::FastTaa,
        Noise::FastBevy,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Noise::White => "white",
            Noise::Ign => "ign",
            Noise::R2 => "r2",
            Noise::Stbn => "stbn",
            Noise::FastEma => "fast_ema",
            Noise::FastTaa => "fast_taa",
            Noise::FastBevy => "fast_bevy",
        }
    }

    /// What it is, for the document.
    pub fn describe(self) -> &'static str {
        match self {
            Noise::White => "white noise (`nb_hash3`)",
            Noise::Ign => "IGN, golden-ratio animated (`nb_ign_frame`)",
            Noise::R2 => "the R2 grid, golden-ratio animated (`nb_r2_frame`)",
            Noise::Stbn => "STBN 64×64×64 (`kind = \"stbn\"`)",
            Noise::FastEma => "FAST for Gaussian σ 1 × EMA α 0.1",
            Noise::FastTaa => "FAST for TAA (`kind = \"taa\"`, α 0.1, coverage 0.2)",
            Noise::FastBevy => {
                "FAST for TAA at Bevy's still blend with `Hdr` (`kind = \"taa\"`, α 0.015, coverage 0.2)"
            }
        }
    }
}

/// A camera path over frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraPath {
    Still,
    Pan,
    Orbit,
    Dolly,
}

/// `…, 0, 1, …, n, n − 1, …, 0, …` for any integer `t`: a sweep out and back.
fn triangle(t: i64, n: i64) -> f32 {
    let p = t.rem_euclid(2 * n);
    (if p > n { 2 * n - p } else { p }) as f32
}

/// Where the camera stands and looks with the camera still.
const EYE: Vec3 = Vec3::new(0.0, 1.7, 6.5);
const TARGET: Vec3 = Vec3::new(0.0, 1.0, 0.0);

impl CameraPath {
    pub const ALL: [CameraPath; 4] = [
        CameraPath::Still,
        CameraPath::Pan,
        CameraPath::Orbit,
        CameraPath::Dolly,
    ];

    pub fn name(self) -> &'static str {
        match self {
            CameraPath::Still => "still",
            CameraPath::Pan => "pan",
            CameraPath::Orbit => "orbit",
            CameraPath::Dolly => "dolly",
        }
    }

    /// The camera in frame `t` (any integer: the warm-up runs at negative frames).
    pub fn transform(self, t: i64) -> Transform {
        match self {
            CameraPath::Still => Transform::from_translation(EYE).looking_at(TARGET, Vec3::Y),
            CameraPath::Pan => {
                // A yaw of 0.006 rad a frame out and back (about 2 px a frame at 256²).
                let yaw = 0.006 * (triangle(t, 24) - 12.0);
                let look = Quat::from_rotation_y(yaw) * (TARGET - EYE);
                Transform::from_translation(EYE).looking_at(EYE + look, Vec3::Y)
            }
            CameraPath::Orbit => {
                let angle = 0.008 * (triangle(t, 32) - 16.0);
                let eye = TARGET + Quat::from_rotation_y(angle) * (EYE - TARGET);
                Transform::from_translation(eye).looking_at(TARGET, Vec3::Y)
            }
            CameraPath::Dolly => {
                let ahead = (TARGET - EYE).normalize() * (0.04 * triangle(t, 32));
                Transform::from_translation(EYE + ahead).looking_at(TARGET + ahead, Vec3::Y)
            }
        }
    }
}

/// A camera path rendered in Bevy's default low dynamic range (an 8-bit sRGB view target, so
/// TAA blends linear colour at 8 bits) or with `Hdr` (a 16-bit float target; TAA blends in a
/// reversible tonemapped space, `c / (1 + max(c))`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Setting {
    pub path: CameraPath,
    pub hdr: bool,
}

impl Setting {
    /// What `--measure` renders by default: every path in low dynamic range, then the still
    /// camera with `Hdr` (the tonemapped bias it shows is the same on every path, and one more
    /// path would take the run past five minutes on two cores; `--paths pan-hdr` adds it).
    pub const ALL: [Setting; 5] = [
        Setting {
            path: CameraPath::Still,
            hdr: false,
        },
        Setting {
            path: CameraPath::Pan,
            hdr: false,
        },
        Setting {
            path: CameraPath::Orbit,
            hdr: false,
        },
        Setting {
            path: CameraPath::Dolly,
            hdr: false,
        },
        Setting {
            path: CameraPath::Still,
            hdr: true,
        },
    ];

    /// `still`, `pan`, … and `still-hdr`, `pan-hdr`, …: the name of its `--frames-out` folder.
    pub fn name(self) -> String {
        if self.hdr {
            format!("{}-hdr", self.path.name())
        } else {
            self.path.name().to_string()
        }
    }

    fn parse(name: &str) -> Option<Setting> {
        let (path, hdr) = match name.strip_suffix("-hdr") {
            Some(p) => (p, true),
            None => (name, false),
        };
        CameraPath::ALL
            .into_iter()
            .find(|c| c.name() == path)
            .map(|path| Setting { path, hdr })
    }
}

/// What the surfaces draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Dither(Noise),
    Reference,
    Classes,
}

impl Mode {
    fn flags(self) -> (u32, u32) {
        match self {
            Mode::Dither(n) => (n as u32, 0),
            Mode::Reference => (0, 1),
            Mode::Classes => (0, 2),
        }
    }
}

const DITHER_SHADER: Handle<Shader> = uuid_handle!("6c1f9e0a-3b0b-4e7c-8a63-1f6b8f0c2d11");
const DITHER_PREPASS: Handle<Shader> = uuid_handle!("9a4d1c7e-52e8-4a2b-9f0e-3c8a7b5e6d22");
const FOG_SHADER: Handle<Shader> = uuid_handle!("2f7b8c1d-0e4a-4c9b-b6d3-8e1f2a3b4c33");

#[derive(Clone, Copy, Debug, ShaderType)]
struct DitherUniform {
    color: Vec4,
    flags: UVec4,
}

/// A surface drawn by stochastic transparency: kept where the noise is below its coverage.
#[derive(Asset, TypePath, AsBindGroup, Clone)]
struct Dithered {
    #[uniform(0)]
    params: DitherUniform,
    #[texture(1, dimension = "2d_array", sample_type = "float", filterable = false)]
    stbn: Handle<Image>,
    #[texture(2, dimension = "2d_array", sample_type = "float", filterable = false)]
    fast_ema: Handle<Image>,
    #[texture(3, dimension = "2d_array", sample_type = "float", filterable = false)]
    fast_taa: Handle<Image>,
    #[texture(4, dimension = "2d_array", sample_type = "float", filterable = false)]
    fast_bevy: Handle<Image>,
    /// Alpha-blended (the reference) rather than dithered.
    blend: bool,
}

impl Material for Dithered {
    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(DITHER_SHADER)
    }

    fn prepass_fragment_shader() -> ShaderRef {
        ShaderRef::Handle(DITHER_PREPASS)
    }

    fn alpha_mode(&self) -> AlphaMode {
        if self.blend {
            AlphaMode::Blend
        } else {
            // A fragment may be discarded, so the prepass runs the material's fragment shader.
            AlphaMode::Mask(0.5)
        }
    }

    fn enable_shadows() -> bool {
        false
    }

    fn specialize(
        _: &MaterialPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        _: &MeshVertexBufferLayoutRef,
        _: MaterialPipelineKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        // Panes and cards are seen from both sides.
        descriptor.primitive.cull_mode = None;
        Ok(())
    }
}

#[derive(Clone, Copy, Debug, ShaderType)]
struct FogUniform {
    center: Vec4,
    half: Vec4,
    color: Vec4,
    flags: UVec4,
}

/// A box of fog, ray-marched from a jittered start.
#[derive(Asset, TypePath, AsBindGroup, Clone)]
struct Fog {
    #[uniform(0)]
    params: FogUniform,
    #[texture(1, dimension = "2d_array", sample_type = "float", filterable = false)]
    stbn: Handle<Image>,
    #[texture(2, dimension = "2d_array", sample_type = "float", filterable = false)]
    fast_ema: Handle<Image>,
    #[texture(3, dimension = "2d_array", sample_type = "float", filterable = false)]
    fast_taa: Handle<Image>,
    #[texture(4, dimension = "2d_array", sample_type = "float", filterable = false)]
    fast_bevy: Handle<Image>,
}

impl Material for Fog {
    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(FOG_SHADER)
    }

    fn alpha_mode(&self) -> AlphaMode {
        AlphaMode::Blend
    }

    fn enable_prepass() -> bool {
        false
    }

    fn enable_shadows() -> bool {
        false
    }
}

/// The fog box and its steps when dithered.
const FOG_CENTER: Vec3 = Vec3::new(-2.2, 0.9, -0.6);
const FOG_HALF: Vec3 = Vec3::new(0.9, 0.9, 0.9);
const FOG_STEPS: u32 = 6;

/// The handles the runner switches, and the opaque materials' colours (the class run paints
/// them black).
#[derive(Resource, Clone)]
struct SceneHandles {
    dithered: Vec<Handle<Dithered>>,
    fog: Handle<Fog>,
    opaque: Vec<(Handle<StandardMaterial>, Color)>,
    camera: Entity,
}

/// Builds the scene into `world`; the camera renders to `target`, or to the window.
fn build_scene(world: &mut World, target: Option<Handle<Image>>) {
    let masks = {
        let mut images = world.resource_mut::<Assets<Image>>();
        [
            images.add(mask_image(&noisebake_bevy_taa3d_masks::STBN)),
            images.add(mask_image(&noisebake_bevy_taa3d_masks::FAST_EMA)),
            images.add(mask_image(&noisebake_bevy_taa3d_masks::FAST_TAA)),
            images.add(mask_image(&noisebake_bevy_taa3d_masks::FAST_BEVY)),
        ]
    };
    let mesh = |world: &mut World, m: Mesh| world.resource_mut::<Assets<Mesh>>().add(m);
    let mut opaque = Vec::new();
    let mut solid = |world: &mut World, m: Mesh, color: Color, at: Transform| {
        let mesh = mesh(world, m);
        let material = world
            .resource_mut::<Assets<StandardMaterial>>()
            .add(StandardMaterial {
                base_color: color,
                perceptual_roughness: 0.8,
                ..default()
            });
        opaque.push((material.clone(), color));
        world.spawn((Mesh3d(mesh), MeshMaterial3d(material), at));
    };
    solid(
        world,
        Plane3d::default().mesh().size(20.0, 20.0).into(),
        Color::srgb(0.55, 0.52, 0.48),
        Transform::IDENTITY,
    );
    solid(
        world,
        Cuboid::new(12.0, 4.0, 0.2).into(),
        Color::srgb(0.7, 0.35, 0.25),
        Transform::from_xyz(0.0, 2.0, -3.0),
    );
    for (i, (x, z, h, color)) in [
        (1.6, -1.6, 1.2, Color::srgb(0.2, 0.4, 0.75)),
        (2.8, -0.4, 0.6, Color::srgb(0.85, 0.8, 0.3)),
        (-0.6, -2.2, 2.0, Color::srgb(0.3, 0.65, 0.35)),
    ]
    .into_iter()
    .enumerate()
    {
        solid(
            world,
            Cuboid::new(0.8, h, 0.8).into(),
            color,
            Transform::from_xyz(x, h / 2.0, z).with_rotation(Quat::from_rotation_y(0.4 * i as f32)),
        );
    }
    let [stbn, fast_ema, fast_taa, fast_bevy] = masks;
    let mut dithered = Vec::new();
    // The glass pane, then the foliage cards: (class, coverage, colour, size, place).
    let surfaces = [
        (
            1u32,
            0.30,
            Color::srgb(0.55, 0.75, 0.95),
            Vec2::new(2.2, 1.2),
            Vec3::new(0.3, 1.05, 1.2),
            0.25,
        ),
        (
            2,
            0.10,
            Color::srgb(0.25, 0.6, 0.2),
            Vec2::new(0.55, 0.7),
            Vec3::new(-1.3, 2.45, 2.5),
            -0.4,
        ),
        (
            3,
            0.25,
            Color::srgb(0.35, 0.7, 0.25),
            Vec2::new(0.55, 0.7),
            Vec3::new(-0.65, 2.45, 2.5),
            -0.2,
        ),
        (
            4,
            0.50,
            Color::srgb(0.3, 0.55, 0.15),
            Vec2::new(0.55, 0.7),
            Vec3::new(0.0, 2.45, 2.5),
            0.0,
        ),
        (
            5,
            0.75,
            Color::srgb(0.4, 0.65, 0.2),
            Vec2::new(0.55, 0.7),
            Vec3::new(0.65, 2.45, 2.5),
            0.2,
        ),
        (
            6,
            0.90,
            Color::srgb(0.2, 0.5, 0.25),
            Vec2::new(0.55, 0.7),
            Vec3::new(1.3, 2.45, 2.5),
            0.4,
        ),
    ];
    for (class, coverage, color, size, at, yaw) in surfaces {
        let handle = world.resource_mut::<Assets<Dithered>>().add(Dithered {
            params: DitherUniform {
                color: color.to_linear().to_vec3().extend(coverage),
                flags: UVec4::new(Noise::Ign as u32, 0, class, 0),
            },
            stbn: stbn.clone(),
            fast_ema: fast_ema.clone(),
            fast_taa: fast_taa.clone(),
            fast_bevy: fast_bevy.clone(),
            blend: false,
        });
        let quad = mesh(world, Rectangle::new(size.x, size.y).into());
        world.spawn((
            Mesh3d(quad),
            MeshMaterial3d(handle.clone()),
            Transform::from_translation(at).with_rotation(Quat::from_rotation_y(yaw)),
        ));
        dithered.push(handle);
    }
    let fog = world.resource_mut::<Assets<Fog>>().add(Fog {
        params: FogUniform {
            center: FOG_CENTER.extend(0.9),
            half: FOG_HALF.extend(0.0),
            color: Color::srgb(0.8, 0.82, 0.85).to_linear().to_vec4(),
            flags: UVec4::new(Noise::Ign as u32, 0, 7, FOG_STEPS),
        },
        stbn,
        fast_ema,
        fast_taa,
        fast_bevy,
    });
    let cube = mesh(world, Cuboid::from_size(2.0 * FOG_HALF).into());
    world.spawn((
        Mesh3d(cube),
        MeshMaterial3d(fog.clone()),
        Transform::from_translation(FOG_CENTER),
    ));
    world.spawn((
        DirectionalLight {
            illuminance: 6000.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::IDENTITY.looking_to(-Vec3::new(0.424, 0.707, 0.566), Vec3::Y),
    ));
    world.insert_resource(GlobalAmbientLight {
        brightness: 400.0,
        ..default()
    });
    world.insert_resource(ClearColor(Color::srgb(0.25, 0.32, 0.45)));
    let mut camera = world.spawn((
        Camera3d::default(),
        Msaa::Off,
        TemporalAntiAliasing::default(),
        Tonemapping::None,
        Projection::Perspective(PerspectiveProjection {
            fov: 45f32.to_radians(),
            ..default()
        }),
        CameraPath::Still.transform(0),
    ));
    if let Some(t) = target {
        camera.insert(RenderTarget::Image(t.into()));
    }
    let camera = camera.id();
    world.insert_resource(SceneHandles {
        dithered,
        fog,
        opaque,
        camera,
    });
}

/// Sets every surface to `mode`.
fn set_mode(world: &mut World, mode: Mode) {
    let handles = world.resource::<SceneHandles>().clone();
    let (noise, m) = mode.flags();
    let mut mats = world.resource_mut::<Assets<Dithered>>();
    for h in &handles.dithered {
        let mut mat = mats.get_mut(h).expect("the scene's material");
        mat.params.flags.x = noise;
        mat.params.flags.y = m;
        mat.blend = mode == Mode::Reference;
    }
    {
        let mut fog = world.resource_mut::<Assets<Fog>>();
        let mut f = fog.get_mut(&handles.fog).expect("the fog");
        f.params.flags.x = noise;
        f.params.flags.y = m;
    }
    {
        let mut std = world.resource_mut::<Assets<StandardMaterial>>();
        for (h, color) in &handles.opaque {
            std.get_mut(h).expect("the scene's material").base_color = if mode == Mode::Classes {
                Color::BLACK
            } else {
                *color
            };
        }
    }
    world.insert_resource(ClearColor(if mode == Mode::Classes {
        Color::BLACK
    } else {
        Color::srgb(0.25, 0.32, 0.45)
    }));
}

/// The plugins, the example's shaders and materials; headless (no window, the renderer's
/// pipelines compiled as they are asked for) or in a window.
fn app(headless: bool) -> App {
    let mut app = App::new();
    if headless {
        app.add_plugins(headless::plugins());
    } else {
        app.add_plugins(DefaultPlugins);
    }
    app.add_plugins((
        NoisebakePlugin,
        MaterialPlugin::<Dithered>::default(),
        MaterialPlugin::<Fog>::default(),
    ));
    if headless {
        headless::start(&mut app);
    }
    let mut shaders = app.world_mut().resource_mut::<Assets<Shader>>();
    for (handle, source, path) in [
        (
            DITHER_SHADER,
            shaders::dither_fragment(),
            "taa3d/dither.wgsl",
        ),
        (
            DITHER_PREPASS,
            shaders::dither_prepass(),
            "taa3d/dither_prepass.wgsl",
        ),
        (FOG_SHADER, shaders::fog_fragment(), "taa3d/fog.wgsl"),
    ] {
        shaders
            .insert(&handle, Shader::from_wgsl(source, path))
            .expect("a uuid handle is always valid");
    }
    app
}

/// What to measure.
#[derive(Clone, Debug)]
pub struct Options {
    pub size: u32,
    pub frames: u32,
    pub still_warmup: u32,
    pub moving_warmup: u32,
    pub settings: Vec<Setting>,
    pub noises: Vec<Noise>,
    pub markdown: Option<PathBuf>,
    pub frames_out: Option<PathBuf>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            size: 256,
            frames: 64,
            still_warmup: 224,
            moving_warmup: 24,
            settings: Setting::ALL.to_vec(),
            noises: Noise::ALL.to_vec(),
            markdown: None,
            frames_out: None,
        }
    }
}

/// One setting's figures.
pub struct PathResult {
    pub setting: Setting,
    /// Per noise, its figures ([`measure::Figures`]).
    pub noises: Vec<(Noise, measure::Figures)>,
    /// The reference against itself without TAA (RMSE raw and after the Gaussian, over the
    /// image and the measured frames).
    pub reference_vs_no_taa: [f64; 2],
    /// Pixels of each class in the measured frames (mean per frame).
    pub class_pixels: Vec<f64>,
}

/// A run's frames and its name (a noise's, or `reference`).
pub type Named = (String, Vec<Frame>);

/// The measurement.
pub struct Measurement {
    pub adapter: String,
    pub driver: String,
    pub options: Options,
    pub paths: Vec<PathResult>,
    pub seconds: f64,
    /// The reference frames and each noise's, per path, when kept (tests).
    pub frames: Vec<(Setting, Vec<Named>)>,
}

/// Drives a headless app: renders frames and reads each back.
struct Runner {
    app: App,
    sink: Arc<Mutex<Vec<Vec<u8>>>>,
    size: u32,
}

impl Runner {
    fn new(size: u32) -> Result<Runner, String> {
        let mut app = app(true);
        let mut target = Image::new_target_texture(size, size, TextureFormat::Rgba32Float, None);
        target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
        let target = app.world_mut().resource_mut::<Assets<Image>>().add(target);
        build_scene(app.world_mut(), Some(target.clone()));
        let sink: Arc<Mutex<Vec<Vec<u8>>>> = Arc::default();
        let s = sink.clone();
        app.world_mut()
            .spawn(Readback::texture(target))
            .observe(move |e: On<ReadbackComplete>| s.lock().unwrap().push(e.data.clone()));
        let mut runner = Runner { app, sink, size };
        // Bevy prepares meshes, images and materials over its first frames, and a slow driver
        // draws blank frames meanwhile: render until the scene shows, in both the dithered
        // and the blended modes (their pipelines differ), before any frame counts.
        let started = std::time::Instant::now();
        let setting = Setting::ALL[0];
        loop {
            let frames = runner.run(setting, Mode::Dither(Noise::Ign), 0, 4, true)?;
            let shown = |f: &Frame| f.iter().any(|p| p.iter().any(|&c| c > 0.0));
            if frames.iter().all(shown) {
                break;
            }
            if started.elapsed() > std::time::Duration::from_secs(120) {
                return Err("the scene did not show in 120 s".into());
            }
        }
        runner.run(setting, Mode::Reference, 0, 4, true)?;
        Ok(runner)
    }

    /// Renders `warmup + frames` frames of `path` in `mode` (frame 0 after the warm-up is the
    /// first kept), the TAA history reset at the start (at every frame with `taa` off), and
    /// returns the kept frames.
    fn run(
        &mut self,
        setting: Setting,
        mode: Mode,
        warmup: u32,
        frames: u32,
        taa: bool,
    ) -> Result<Vec<Frame>, String> {
        set_mode(self.app.world_mut(), mode);
        let camera = self.app.world().resource::<SceneHandles>().camera;
        let path = setting.path;
        if setting.hdr {
            self.app.world_mut().entity_mut(camera).insert(Hdr);
        } else {
            self.app.world_mut().entity_mut(camera).remove::<Hdr>();
        }
        // One frame for the materials' change to reach the render world, not kept.
        self.app.update();
        headless::finish_gpu_work(&self.app)?;
        self.sink.lock().unwrap().clear();
        *self.app.world_mut().resource_mut::<FrameCount>() = FrameCount(0);
        let texels = (self.size * self.size) as usize;
        let mut kept = Vec::with_capacity(frames as usize);
        let total = warmup + frames;
        for k in 0..=total {
            let t = k as i64 - warmup as i64;
            let w = self.app.world_mut();
            *w.get_mut::<Transform>(camera).expect("the camera") = path.transform(t);
            w.get_mut::<TemporalAntiAliasing>(camera)
                .expect("the camera's TAA")
                .reset = k == 0 || !taa;
            self.app.update();
            headless::finish_gpu_work(&self.app)?;
            let got: Vec<Vec<u8>> = self.sink.lock().unwrap().drain(..).collect();
            // Update k delivers the readback of frame k − 1 (of this run; at k = 0, the
            // settling frame's, dropped).
            if k == 0 {
                continue;
            }
            if got.len() != 1 {
                return Err(format!(
                    "update {k} delivered {} readbacks, not one: the readback is out of step",
                    got.len()
                ));
            }
            let bytes = &got[0];
            if bytes.len() != texels * 16 {
                return Err(format!(
                    "a readback of {} bytes, expected {}",
                    bytes.len(),
                    texels * 16
                ));
            }
            if k > warmup {
                kept.push(
                    bytes
                        .chunks_exact(16)
                        .map(|t| {
                            core::array::from_fn(|c| {
                                f32::from_le_bytes(t[4 * c..4 * c + 4].try_into().unwrap())
                            })
                        })
                        .collect(),
                );
            }
        }
        Ok(kept)
    }

    fn adapter(&self) -> (String, String) {
        self.app
            .world()
            .get_resource::<bevy::render::renderer::RenderAdapterInfo>()
            .map_or(("an unknown adapter".into(), String::new()), |a| {
                (
                    a.0.name.clone(),
                    format!("{} {}", a.0.driver, a.0.driver_info),
                )
            })
    }
}

/// The frames whose errors count: the second half.
fn measured(frames: u32) -> std::ops::Range<usize> {
    (frames / 2) as usize..frames as usize
}

/// Measures every path and noise of `opts`; `keep`: return every frame too.
pub fn measure_all(opts: &Options, keep: bool) -> Result<Measurement, String> {
    if opts.size == 0 || opts.size > 1024 || opts.frames < 4 {
        return Err(format!(
            "--size must be 1 to 1024 (got {}) and --frames at least 4 (got {})",
            opts.size, opts.frames
        ));
    }
    let start = std::time::Instant::now();
    let mut runner = Runner::new(opts.size)?;
    let (adapter, driver) = runner.adapter();
    let n = opts.size as usize;
    let mut paths = Vec::new();
    let mut all_frames = Vec::new();
    // The class maps depend on the path only, not on the dynamic range.
    let mut class_maps_of: Vec<(CameraPath, Vec<Vec<u32>>)> = Vec::new();
    for &setting in &opts.settings {
        let path = setting.path;
        let warmup = if path == CameraPath::Still {
            opts.still_warmup
        } else {
            opts.moving_warmup
        };
        let class_maps = match class_maps_of.iter().find(|c| c.0 == path) {
            Some((_, maps)) => maps.clone(),
            None => {
                let frames = runner.run(setting, Mode::Classes, 0, opts.frames, false)?;
                let maps: Vec<Vec<u32>> = frames.iter().map(measure::classes).collect();
                class_maps_of.push((path, maps.clone()));
                maps
            }
        };
        let reference = runner.run(setting, Mode::Reference, warmup, opts.frames, true)?;
        let no_taa = runner.run(setting, Mode::Reference, 0, opts.frames, false)?;
        let vs = measure::figures(
            &reference,
            &no_taa,
            &class_maps,
            measured(opts.frames),
            n,
            n,
        );
        let image = CLASSES.len() - 1;
        let mut result = PathResult {
            setting,
            noises: Vec::new(),
            reference_vs_no_taa: vs.rmse[image],
            class_pixels: CLASSES
                .iter()
                .map(|&(_, code)| {
                    let m = measured(opts.frames);
                    let count = m.len() as f64;
                    class_maps[m]
                        .iter()
                        .map(|c| c.iter().filter(|&&v| code == 0 || v == code).count() as f64)
                        .sum::<f64>()
                        / count
                })
                .collect(),
        };
        let mut kept = Vec::new();
        for &noise in &opts.noises {
            let frames = runner.run(setting, Mode::Dither(noise), warmup, opts.frames, true)?;
            let f = measure::figures(
                &frames,
                &reference,
                &class_maps,
                measured(opts.frames),
                n,
                n,
            );
            eprintln!(
                "  {:<9} {:<9} RMSE {:.5} raw, {:.5} after the Gaussian; flicker {:.5} ({:.0} s)",
                setting.name(),
                noise.name(),
                f.rmse[image][0],
                f.rmse[image][1],
                f.flicker[image],
                start.elapsed().as_secs_f64()
            );
            result.noises.push((noise, f));
            if keep || opts.frames_out.is_some() {
                kept.push((noise.name().to_string(), frames));
            }
        }
        if let Some(dir) = &opts.frames_out {
            let dir = dir.join(setting.name());
            std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            for (name, frames) in kept.iter().chain(std::iter::once(&(
                "reference".to_string(),
                reference.clone(),
            ))) {
                let file = dir.join(format!("{name}.npy"));
                std::fs::write(&file, measure::npy(frames, n, n))
                    .map_err(|e| format!("{}: {e}", file.display()))?;
            }
        }
        if keep {
            kept.push(("reference".into(), reference));
            all_frames.push((setting, kept));
        }
        paths.push(result);
    }
    Ok(Measurement {
        adapter,
        driver,
        options: opts.clone(),
        paths,
        seconds: start.elapsed().as_secs_f64(),
        frames: all_frames,
    })
}

/// The reference of `setting` rendered twice at `size`, with a dithered run of every noise
/// between: a reference that carried state from the runs before it (a material left
/// dithering, a history not reset) would differ.
pub fn reference_twice(
    setting: Setting,
    size: u32,
    frames: u32,
) -> Result<(Vec<Frame>, Vec<Frame>), String> {
    let mut runner = Runner::new(size)?;
    let first = runner.run(setting, Mode::Reference, 0, frames, true)?;
    for noise in Noise::ALL {
        runner.run(setting, Mode::Dither(noise), 0, frames, true)?;
    }
    let second = runner.run(setting, Mode::Reference, 0, frames, true)?;
    Ok((first, second))
}

/// The measurement as a Markdown document below `header` (the stamp).
pub fn markdown(m: &Measurement, header: &str) -> String {
    use std::fmt::Write;
    let o = &m.options;
    let mut s = header.to_string();
    let _ = writeln!(
        s,
        "Rendered by Bevy 0.19 on {} (driver {}), {}×{} pixels, in {:.0} s.\n",
        m.adapter, m.driver, o.size, o.size, m.seconds
    );
    let _ = writeln!(
        s,
        "Bevy's TAA (`TemporalAntiAliasing` on a `Camera3d` with `Msaa::Off`: jittered projection, depth and motion-vector prepasses, Catmull-Rom history, variance clipping in YCoCg, a blend of 0.1 that falls towards 0.015 as a still pixel's confidence grows), in Bevy's default low dynamic range and, for the cameras marked so, with `Hdr`. In low dynamic range the history is an 8-bit sRGB texture, the view target's format: every blended value is rounded to 8 bits, and the confidence, kept in its alpha channel, saturates at 1, so a still pixel blends at 1/11 every frame rather than 0.015. With `Hdr` the history is 16-bit float, a still pixel's blend does fall to 0.015, and TAA blends in a reversible tonemapped space. over {} frames after a warm-up of {} frames (still camera) or {} (moving). RMSE of the linear TAA output against the reference (the same scene, TAA and path, every surface alpha-blended at its coverage, the fog marched in 128 steps) over frames {}–{}, raw / after a Gaussian of σ 1 px, over the pixels that show each surface; flicker: the RMS of the frame-to-frame change of the Gaussian-filtered error; static part: the RMS over pixels of the Gaussian-filtered error's mean over the measured frames, the part that stays put (a bias per pixel, which further accumulation does not remove, against what a noise's arrangement can lower). Lower is better.\n",
        o.frames,
        o.still_warmup,
        o.moving_warmup,
        o.frames / 2,
        o.frames - 1
    );
    s.push_str("Noises: ");
    let names: Vec<String> = o
        .noises
        .iter()
        .map(|n| format!("`{}` {}", n.name(), n.describe()))
        .collect();
    s.push_str(&names.join("; "));
    s.push_str(".\n");
    for p in &m.paths {
        let _ = writeln!(
            s,
            "\n## Camera `{}`, {}\n\nThe reference against itself rendered without TAA: {:.5} raw, {:.5} after the Gaussian (what Bevy's TAA does to a smooth image: its jitter and resampling, and for the blended surfaces the history reprojected by the motion of what lies behind them).\n",
            p.setting.path.name(),
            if p.setting.hdr {
                "`Hdr` (`--frames-out` folder `…-hdr`)"
            } else {
                "low dynamic range (Bevy's default)"
            },
            p.reference_vs_no_taa[0],
            p.reference_vs_no_taa[1]
        );
        s.push_str("| surface | pixels |");
        for (n, _) in &p.noises {
            let _ = write!(s, " {} |", n.name());
        }
        s.push_str(" best |\n| --- | --- |");
        for _ in &p.noises {
            s.push_str(" --- |");
        }
        s.push_str(" --- |\n");
        for (k, (class, _)) in CLASSES.iter().enumerate() {
            let _ = write!(s, "| {class} | {:.0} |", p.class_pixels[k]);
            for (_, f) in &p.noises {
                let _ = write!(s, " {:.5} / {:.5} |", f.rmse[k][0], f.rmse[k][1]);
            }
            let best = p
                .noises
                .iter()
                .filter(|(_, f)| f.rmse[k][1].is_finite())
                .min_by(|a, b| a.1.rmse[k][1].total_cmp(&b.1.rmse[k][1]))
                .map_or("–", |(n, _)| n.name());
            let _ = writeln!(s, " {best} |");
        }
        s.push_str("| flicker (image) | |");
        for (_, f) in &p.noises {
            let _ = write!(s, " {:.5} |", f.flicker[CLASSES.len() - 1]);
        }
        s.push_str(" |\n");
        for (k, (class, _)) in CLASSES.iter().enumerate() {
            if k != 0 && k != CLASSES.len() - 1 {
                continue;
            }
            let _ = write!(s, "| static part ({class}) | |");
            for (_, f) in &p.noises {
                let _ = write!(s, " {:.5} |", f.static_part[k]);
            }
            s.push_str(" |\n");
        }
    }
    s
}

fn parse(args: &[String]) -> Result<(bool, Options), String> {
    let mut opts = Options::default();
    let mut measure = false;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or(format!("{a} needs a value"));
        match a.as_str() {
            "--measure" => measure = true,
            "--size" => opts.size = value()?.parse().map_err(|e| format!("--size: {e}"))?,
            "--frames" => opts.frames = value()?.parse().map_err(|e| format!("--frames: {e}"))?,
            "--warmup" => {
                let w: u32 = value()?.parse().map_err(|e| format!("--warmup: {e}"))?;
                (opts.still_warmup, opts.moving_warmup) = (w, w.min(opts.moving_warmup));
            }
            "--markdown" => opts.markdown = Some(PathBuf::from(value()?)),
            "--frames-out" => opts.frames_out = Some(PathBuf::from(value()?)),
            "--paths" => {
                opts.settings = value()?
                    .split(',')
                    .map(|p| {
                        Setting::parse(p).ok_or(format!(
                            "--paths: no path `{p}` (still, pan, orbit, dolly; `-hdr` after one renders it with Hdr)"
                        ))
                    })
                    .collect::<Result<_, _>>()?
            }
            "--noises" => {
                opts.noises = value()?
                    .split(',')
                    .map(|p| {
                        Noise::ALL.into_iter().find(|n| n.name() == p).ok_or(format!(
                            "--noises: no noise `{p}` (white, ign, r2, stbn, fast_ema, fast_taa, fast_bevy)"
                        ))
                    })
                    .collect::<Result<_, _>>()?
            }
            other => return Err(format!("unknown argument {other} (see the example's docs)")),
        }
    }
    if !measure && (opts.markdown.is_some() || opts.frames_out.is_some()) {
        return Err("--markdown and --frames-out go with --measure".into());
    }
    Ok((measure, opts))
}

/// The window: `N` cycles the noise, `C` the camera path, `R` the reference.
#[derive(Resource, Default)]
struct Interactive {
    noise: usize,
    path: usize,
    reference: bool,
    hdr: bool,
    frame: i64,
}

fn interact(
    keys: Res<ButtonInput<KeyCode>>,
    mut state: ResMut<Interactive>,
    mut taa: Query<(Entity, &mut Transform, &mut TemporalAntiAliasing)>,
    mut commands: Commands,
) {
    let mut changed = false;
    if keys.just_pressed(KeyCode::KeyN) {
        state.noise = (state.noise + 1) % Noise::ALL.len();
        changed = true;
    }
    if keys.just_pressed(KeyCode::KeyC) {
        state.path = (state.path + 1) % CameraPath::ALL.len();
        changed = true;
    }
    if keys.just_pressed(KeyCode::KeyR) {
        state.reference = !state.reference;
        changed = true;
    }
    if keys.just_pressed(KeyCode::KeyH) {
        state.hdr = !state.hdr;
        changed = true;
    }
    state.frame += 1;
    let path = CameraPath::ALL[state.path];
    for (camera, mut t, mut a) in &mut taa {
        *t = path.transform(state.frame);
        a.reset |= changed;
        if state.hdr {
            commands.entity(camera).insert(Hdr);
        } else {
            commands.entity(camera).remove::<Hdr>();
        }
    }
    if changed {
        let mode = if state.reference {
            Mode::Reference
        } else {
            Mode::Dither(Noise::ALL[state.noise])
        };
        println!(
            "noise {} ({}), camera {}",
            Noise::ALL[state.noise].name(),
            if state.reference {
                "reference"
            } else {
                "dithered"
            },
            path.name()
        );
        commands.queue(move |w: &mut World| set_mode(w, mode));
    }
}

#[allow(dead_code)] // the tests include this file for `measure_all`
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (measure, opts) = match parse(&args) {
        Ok(v) => v,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    if !measure {
        println!("N: next noise, C: next camera path, R: the reference (alpha-blended), H: Hdr");
        let mut app = app(false);
        build_scene(app.world_mut(), None);
        app.init_resource::<Interactive>()
            .add_systems(Update, interact)
            .run();
        return;
    }
    eprintln!(
        "measuring {} noise(s) on {} camera path(s) at {}² in Bevy's renderer",
        opts.noises.len(),
        opts.settings.len(),
        opts.size
    );
    match measure_all(&opts, false) {
        Ok(m) => {
            println!(
                "rendered by Bevy on {} (driver {}) in {:.0} s",
                m.adapter, m.driver, m.seconds
            );
            let stamp = noisebake_cli::report::stamp::Stamp::now_as(
                "cargo run --release -p noisebake-bevy --example taa3d --",
            );
            let text = markdown(
                &m,
                &stamp.header("Noise under Bevy's TAA (the `taa3d` example)"),
            );
            print!("{text}");
            if let Some(path) = &opts.markdown {
                if let Err(e) = noisebake_cli::report::stamp::write(path, &text) {
                    eprintln!("error: {e}");
                    std::process::exit(1);
                }
                println!("wrote {}", path.display());
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
