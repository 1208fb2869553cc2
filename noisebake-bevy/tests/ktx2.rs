//! KTX2 files as `Bake::ktx2_dir` writes them (`build_assets::export::ktx2::to_ktx2`), loaded
//! by Bevy's asset server and its `ktx2` loader through [`NoiseMasks`]: every format the
//! writer has (8-bit unorm, 16-bit uint, 32-bit float; 1 to 4 channels) and every layout
//! (2D: one layer; 3D: a layer per frame; 4D: layer-major) arrives with the format, size,
//! layer count and view a shader binds, and with the bytes of the baked static as
//! [`mask_image`] uploads them. No GPU needed: the loader runs on the CPU.

use std::path::Path;
use std::time::{Duration, Instant};

use bevy::asset::{AssetPlugin, LoadState};
use bevy::ecs::system::RunSystemOnce;
use bevy::image::{CompressedImageFormats, ImageLoader, ImagePlugin};
use bevy::prelude::*;
use bevy::render::render_resource::{TextureFormat, TextureViewDimension};
use noise_runtime::{Mask2, Mask3, Mask4, SamplerTile};
use noisebake_bevy::{BakedMask, NoiseMasks, NoisebakePlugin, mask_image};
use noisebake_test_support::bake::{gen_tex, spec};

fn leak(bytes: Vec<u8>) -> &'static [u8] {
    Box::leak(bytes.into_boxed_slice())
}

/// Bakes `body`, writes its KTX2 file into `dir` as `name.ktx2`, and returns the texels.
fn write(dir: &Path, name: &str, body: &str) -> &'static [u8] {
    let tex = gen_tex(body);
    let file = build_assets::export::ktx2::to_ktx2(&tex, Some(&spec(body)));
    std::fs::write(dir.join(format!("{name}.ktx2")), file).unwrap();
    leak(tex.data)
}

struct Case {
    name: String,
    expected: Image,
    format: TextureFormat,
    layers: u32,
}

fn case(
    dir: &Path,
    name: &str,
    body: &str,
    mask: impl FnOnce(&'static [u8]) -> Box<dyn BakedMask>,
    format: TextureFormat,
    layers: u32,
) -> Case {
    let mask = mask(write(dir, name, body));
    Case {
        name: name.to_string(),
        expected: mask_image(&*mask),
        format,
        layers,
    }
}

#[test]
fn bevys_ktx2_loader_reads_every_format_the_bake_writes() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("noisebake-bevy-ktx2");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let d = dir.as_path();
    // White noise for the scalar formats; FAST (the kind that makes vectors) for the others.
    let white = |dims: &str, format: &str| {
        let channels = format.split('x').nth(1).unwrap_or("1");
        match channels {
            "1" => format!("kind = \"white\"\ndims = {dims}\nseed = 9\nformat = \"{format}\""),
            n => format!(
                "kind = \"fast\"\ndims = {dims}\nseed = 9\nformat = \"{format}\"\nsample_space = \"vec{n}\"\niterations = 1"
            ),
        }
    };
    let d3 = "[16, 16, 4]";
    use TextureFormat as F;
    let cases = vec![
        case(
            d,
            "u8",
            &white(d3, "u8"),
            |b| Box::new(Mask3::<u8, 16, 16, 4>::new(b)),
            F::R8Unorm,
            4,
        ),
        case(
            d,
            "u8x2",
            &white(d3, "u8x2"),
            |b| Box::new(Mask3::<[u8; 2], 16, 16, 4>::new(b)),
            F::Rg8Unorm,
            4,
        ),
        case(
            d,
            "u8x3",
            &white(d3, "u8x3"),
            |b| Box::new(Mask3::<[u8; 3], 16, 16, 4>::new(b)),
            F::Rgba8Unorm,
            4,
        ),
        case(
            d,
            "u8x4",
            &white(d3, "u8x4"),
            |b| Box::new(Mask3::<[u8; 4], 16, 16, 4>::new(b)),
            F::Rgba8Unorm,
            4,
        ),
        // A sampler tile: its 16-bit keys, one layer per sample dimension.
        case(
            d,
            "sampler",
            "kind = \"sampler\"\ndims = [16, 16]\nseed = 9\nspp = 4\nsample_dims = 4",
            |b| {
                Box::new(SamplerTile::<16, 16, 4, 4>::new(
                    Mask3::<u16, 16, 16, 4>::new(b),
                    0b11,
                ))
            },
            F::R16Uint,
            4,
        ),
        case(
            d,
            "u16",
            &white(d3, "u16"),
            |b| Box::new(Mask3::<u16, 16, 16, 4>::new(b)),
            F::R16Uint,
            4,
        ),
        case(
            d,
            "u16x2",
            &white(d3, "u16x2"),
            |b| Box::new(Mask3::<[u16; 2], 16, 16, 4>::new(b)),
            F::Rg16Uint,
            4,
        ),
        case(
            d,
            "u16x3",
            &white(d3, "u16x3"),
            |b| Box::new(Mask3::<[u16; 3], 16, 16, 4>::new(b)),
            F::Rgba16Uint,
            4,
        ),
        case(
            d,
            "u16x4",
            &white(d3, "u16x4"),
            |b| Box::new(Mask3::<[u16; 4], 16, 16, 4>::new(b)),
            F::Rgba16Uint,
            4,
        ),
        case(
            d,
            "f32",
            &white(d3, "f32"),
            |b| Box::new(Mask3::<f32, 16, 16, 4>::new(b)),
            F::R32Float,
            4,
        ),
        case(
            d,
            "f32x2",
            &white(d3, "f32x2"),
            |b| Box::new(Mask3::<[f32; 2], 16, 16, 4>::new(b)),
            F::Rg32Float,
            4,
        ),
        case(
            d,
            "f32x3",
            &white(d3, "f32x3"),
            |b| Box::new(Mask3::<[f32; 3], 16, 16, 4>::new(b)),
            F::Rgba32Float,
            4,
        ),
        case(
            d,
            "f32x4",
            &white(d3, "f32x4"),
            |b| Box::new(Mask3::<[f32; 4], 16, 16, 4>::new(b)),
            F::Rgba32Float,
            4,
        ),
        // One layer: Bevy's loader alone would give this a `D2` view.
        case(
            d,
            "blue2d",
            "kind = \"blue2d\"\ndims = [16, 16]\nseed = 1",
            |b| Box::new(Mask2::<u8, 16, 16>::new(b)),
            F::R8Unorm,
            1,
        ),
        // Layer-major 4D: layer z + D·w.
        case(
            d,
            "vac4d",
            "kind = \"vac\"\ndims = [8, 8, 2, 3]\nseed = 3\nformat = \"u16\"\ngroups = [{ axes = [0, 1] }, { axes = [2] }, { axes = [3] }]",
            |b| Box::new(Mask4::<u16, 8, 8, 2, 3>::new(b)),
            F::R16Uint,
            6,
        ),
    ];

    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin {
            file_path: d.display().to_string(),
            ..default()
        },
        ImagePlugin::default(),
        NoisebakePlugin,
    ));
    // Bevy's image loader (which reads KTX2) is registered by the renderer once it knows the
    // device's compressed formats; without a renderer, register the same loader for none.
    app.register_asset_loader(ImageLoader::new(CompressedImageFormats::NONE));
    app.finish();
    app.cleanup();
    let handles: Vec<Handle<Image>> = cases
        .iter()
        .map(|c| {
            let path = format!("{}.ktx2", c.name);
            app.world_mut()
                .run_system_once(move |mut masks: NoiseMasks| masks.load(path.clone()))
                .unwrap()
        })
        .collect();

    let start = Instant::now();
    loop {
        app.update();
        let server = app.world().resource::<AssetServer>();
        let states: Vec<LoadState> = handles.iter().map(|h| server.load_state(h)).collect();
        if let Some((c, LoadState::Failed(e))) =
            cases.iter().zip(&states).find(|(_, s)| s.is_failed())
        {
            panic!("{}: Bevy's loader failed: {e}", c.name);
        }
        if states.iter().all(|s| s.is_loaded()) {
            // One more frame for PostUpdate to give the views.
            app.update();
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "loads still pending: {states:?}"
        );
        std::thread::sleep(Duration::from_millis(5));
    }

    let images = app.world().resource::<Assets<Image>>();
    for (c, h) in cases.iter().zip(&handles) {
        let got = images.get(h).unwrap();
        let desc = &got.texture_descriptor;
        assert_eq!(desc.format, c.format, "{}: format", c.name);
        assert_eq!(
            desc.format, c.expected.texture_descriptor.format,
            "{}: format",
            c.name
        );
        assert_eq!(
            desc.size, c.expected.texture_descriptor.size,
            "{}: size",
            c.name
        );
        assert_eq!(
            desc.size.depth_or_array_layers, c.layers,
            "{}: layers",
            c.name
        );
        assert_eq!(desc.mip_level_count, 1, "{}: mips", c.name);
        assert_eq!(
            got.texture_view_descriptor
                .as_ref()
                .and_then(|v| v.dimension),
            Some(TextureViewDimension::D2Array),
            "{}: view",
            c.name
        );
        assert!(
            got.data == c.expected.data,
            "{}: bytes differ from the static's",
            c.name
        );
    }
}
