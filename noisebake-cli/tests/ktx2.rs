//! KTX 2.0 export end to end: files written by `noisebake gen --out x.ktx2`, `noisebake bake
//! --ktx2` and `Bake::ktx2_dir` parse with the `ktx2` crate, describe their format as the KTX
//! and Khronos Data Format specifications ask, carry our metadata, and hold exactly the texels
//! of the `.npy` export (3-channel ones padded to 4) — which are also exactly the bytes a game
//! uploads from a runtime mask (`write_gpu_bytes`).

use build_assets::export::ktx2::to_ktx2;
use build_assets::export::npy;
use build_assets::spec::{self, TextureSpec};
use build_assets::{Texture, cache, generate};
use ktx2::dfd::{self, ChannelTypeQualifiers};
use ktx2::{ColorModel, Format, Reader, TransferFunction};
use std::process::Command;

fn spec_of(body: &str) -> TextureSpec {
    let file = spec::parse_toml(&format!("[[texture]]\nname = \"T\"\n{body}"))
        .unwrap_or_else(|e| panic!("{e}"));
    file.textures.into_iter().next().unwrap()
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("noisebake-ktx2-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Every storage format and dimensionality a mask can have.
const CASES: [(&str, Format); 12] = [
    (
        "kind = \"stbn\"\ndims = [16, 8, 4]\nformat = \"u8\"",
        Format::R8_UNORM,
    ),
    (
        "kind = \"stbn\"\ndims = [16, 8, 4]\nformat = \"u16\"",
        Format::R16_UINT,
    ),
    (
        "kind = \"stbn\"\ndims = [16, 8, 4]\nformat = \"f32\"",
        Format::R32_SFLOAT,
    ),
    (
        "kind = \"blue2d\"\ndims = [12, 10]\nformat = \"u8\"",
        Format::R8_UNORM,
    ),
    (
        "kind = \"white\"\ndims = [32]\nformat = \"u16\"",
        Format::R16_UINT,
    ),
    (
        "kind = \"vac\"\ndims = [8, 8, 2, 3]\ngroups = [{ axes = [0, 1] }, { axes = [2] }, { axes = [3] }]\nformat = \"u8\"",
        Format::R8_UNORM,
    ),
    (
        "kind = \"fast\"\ndims = [16, 16, 2]\nsample_space = \"vec2\"\nformat = \"u8x2\"",
        Format::R8G8_UNORM,
    ),
    (
        "kind = \"fast\"\ndims = [16, 16, 2]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"",
        Format::R8G8B8A8_UNORM,
    ),
    (
        "kind = \"fast\"\ndims = [16, 16, 2]\nsample_space = \"vec4\"\nformat = \"u8x4\"",
        Format::R8G8B8A8_UNORM,
    ),
    (
        "kind = \"fast\"\ndims = [16, 16, 2]\nsample_space = \"sphere\"\nformat = \"u16x3\"",
        Format::R16G16B16A16_UINT,
    ),
    (
        "kind = \"fast\"\ndims = [16, 16, 2]\nsample_space = \"vec2\"\nformat = \"f32x2\"",
        Format::R32G32_SFLOAT,
    ),
    (
        "kind = \"fast\"\ndims = [16, 16, 2]\nsample_space = \"sphere\"\nformat = \"f32x3\"",
        Format::R32G32B32A32_SFLOAT,
    ),
];

/// The level data expected for a texture: its bytes, 3-channel texels padded with the
/// channel's largest value.
fn expected_level(t: &Texture) -> Vec<u8> {
    let ch = t.format.channels as usize;
    let cb = t.format.scalar.bytes();
    if ch != 3 {
        return t.data.clone();
    }
    let pad: &[u8] = match cb {
        1 => &[0xff],
        2 => &[0xff, 0xff],
        _ => &[0, 0, 0x80, 0x3f],
    };
    t.data
        .chunks_exact(3 * cb)
        .flat_map(|texel| [texel, pad].concat())
        .collect()
}

/// Checks a KTX2 file against the texture and spec it was written from.
fn check(bytes: &[u8], t: &Texture, s: Option<&TextureSpec>, format: Format) {
    let r = Reader::new(bytes).unwrap_or_else(|e| panic!("{:?}: {e:?}", t.dims));
    let h = r.header();
    let dims = &t.dims;
    let layers: usize = dims.iter().skip(2).product::<usize>().max(1);
    assert_eq!(h.format, Some(format), "{dims:?}");
    assert_eq!(h.type_size as usize, t.format.scalar.bytes());
    assert_eq!(h.pixel_width as usize, dims[0]);
    assert_eq!(h.pixel_height as usize, dims.get(1).copied().unwrap_or(1));
    assert_eq!(h.pixel_depth, 0);
    assert_eq!(h.layer_count as usize, layers);
    assert_eq!((h.face_count, h.level_count), (1, 1));
    assert!(h.supercompression_scheme.is_none());
    let levels: Vec<_> = r.levels().collect();
    assert_eq!(levels.len(), 1);
    assert_eq!(
        levels[0].data,
        expected_level(t).as_slice(),
        "{dims:?} level data"
    );
    assert_eq!(
        levels[0].uncompressed_byte_length as usize,
        levels[0].data.len()
    );
    // Level data is aligned to lcm(texel size, 4) from the file's start.
    let offset = levels[0].data.as_ptr() as usize - bytes.as_ptr() as usize;
    let texel = t.format.scalar.bytes()
        * if t.format.channels == 3 {
            4
        } else {
            t.format.channels as usize
        };
    assert_eq!(offset % texel.max(4), 0, "level offset {offset}");

    // The descriptor: as the ktx2 crate's own generator describes the format, except that
    // primaries are unspecified (noise is data) and integer formats have an unspecified
    // transfer function (KTX 2.0 §3.10.2), which the generator gets wrong.
    let basic = r.basic_dfd().expect("a basic descriptor block");
    let (reference, _) = dfd::Basic::from_format(format).unwrap();
    assert_eq!(basic.color_model, Some(ColorModel::RGBSDA));
    assert_eq!(basic.color_primaries, None, "primaries unspecified");
    let integer = t.format.scalar.bytes() == 2;
    if integer {
        assert_eq!(basic.transfer_function, None, "UINT: transfer unspecified");
    } else {
        assert_eq!(basic.transfer_function, Some(TransferFunction::Linear));
    }
    assert_eq!(
        basic.texel_block_dimensions,
        reference.texel_block_dimensions
    );
    assert_eq!(basic.bytes_planes, reference.bytes_planes);
    assert_eq!(
        basic.sample_information.len(),
        reference.sample_information.len()
    );
    for (a, b) in basic
        .sample_information
        .iter()
        .zip(&reference.sample_information)
    {
        assert_eq!(
            (
                a.bit_offset,
                a.bit_length,
                a.channel_type,
                a.channel_type_qualifiers
            ),
            (
                b.bit_offset,
                b.bit_length,
                b.channel_type,
                b.channel_type_qualifiers
            ),
            "{format:?}"
        );
        assert_eq!((a.lower, a.upper), (b.lower, b.upper), "{format:?}");
    }
    if t.format.scalar.bytes() == 4 {
        let q = basic.sample_information[0].channel_type_qualifiers;
        assert!(
            q.contains(ChannelTypeQualifiers::FLOAT) && q.contains(ChannelTypeQualifiers::SIGNED)
        );
    }

    // Metadata: sorted keys, our own prefixed.
    let kv: Vec<(String, String)> = r
        .key_value_data()
        .map(|(k, v)| {
            (
                k.to_string(),
                String::from_utf8(v.strip_suffix(&[0]).expect("NUL-terminated").to_vec()).unwrap(),
            )
        })
        .collect();
    let keys: Vec<&str> = kv.iter().map(|(k, _)| k.as_str()).collect();
    let mut sorted = keys.clone();
    sorted.sort();
    assert_eq!(keys, sorted, "keys in byte order");
    let get = |k: &str| kv.iter().find(|(key, _)| key == k).map(|(_, v)| v.clone());
    assert!(r.writer().unwrap().starts_with("noisebake"));
    let dims_s: Vec<String> = dims.iter().map(|d| d.to_string()).collect();
    assert_eq!(get("noisebake.dims"), Some(dims_s.join("x")));
    if let Some(s) = s {
        assert_eq!(get("noisebake.kind").as_deref(), Some(s.kind.name()));
        assert_eq!(get("noisebake.seed"), Some(s.seed.to_string()));
        assert_eq!(get("noisebake.spec_hash"), Some(cache::key(s)));
        assert_eq!(get("noisebake.spec"), Some(s.canonical()));
    }
}

#[test]
fn every_format_parses_with_the_ktx2_crate_and_holds_the_texels() {
    for (body, format) in CASES {
        let s = spec_of(body);
        let t = generate(&s, &mut |_, _| {});
        check(&to_ktx2(&t, Some(&s)), &t, Some(&s), format);
        // From a texture without a spec (read from .npy): no kind, seed or hash.
        let back = npy::from_npy(&npy::to_npy(&t), "T", t.format.channels > 1).unwrap();
        check(&to_ktx2(&back, None), &back, None, format);
    }
}

/// The level data is what a game uploads from the runtime's view of the same bytes.
#[test]
fn level_data_equals_the_runtime_upload_bytes() {
    let s = spec_of(CASES[7].0);
    let t = generate(&s, &mut |_, _| {});
    let bytes: &'static [u8] = Box::leak(t.data.clone().into_boxed_slice());
    let mask = noise_runtime::Mask3::<[u8; 3], 16, 16, 2>::new(bytes);
    let tex = mask.gpu_texture();
    let mut upload = vec![0u8; tex.byte_len()];
    mask.write_gpu_bytes(&mut upload).unwrap();
    let file = to_ktx2(&t, Some(&s));
    let r = Reader::new(&file[..]).unwrap();
    assert_eq!(r.levels().next().unwrap().data, upload.as_slice());
    assert_eq!(
        r.header().format.map(|f| f.value()),
        Some(tex.format.vk_format())
    );
    assert_eq!(
        (
            r.header().pixel_width,
            r.header().pixel_height,
            r.header().layer_count
        ),
        (tex.width, tex.height, tex.layers)
    );
}

#[test]
fn cli_gen_and_bake_write_ktx2() {
    let d = tmp("cli");
    let out = d.join("fast_cos.ktx2");
    let status = Command::new(env!("CARGO_BIN_EXE_noisebake"))
        .args([
            "gen",
            "--kind",
            "fast",
            "--dims",
            "16x16x2",
            "--sample-space",
            "cosine_hemisphere",
        ])
        .args([
            "--format",
            "u8x3",
            "--seed",
            "4",
            "--out",
            out.to_str().unwrap(),
        ])
        .status()
        .unwrap();
    assert!(status.success());
    let s = spec_of(
        "kind = \"fast\"\ndims = [16, 16, 2]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nseed = 4",
    );
    let t = generate(&s, &mut |_, _| {});
    let mut s_named = s.clone();
    s_named.name = "fast_cos".into();
    check(
        &std::fs::read(&out).unwrap(),
        &t,
        Some(&s_named),
        Format::R8G8B8A8_UNORM,
    );

    let spec = d.join("noise.toml");
    std::fs::write(
        &spec,
        "[[texture]]\nname = \"STBN\"\nkind = \"stbn\"\ndims = [16, 16, 4]\nseed = 2\n\n[[texture]]\nname = \"W\"\nkind = \"white\"\ndims = [8, 8]\nformat = \"u16\"\n",
    )
    .unwrap();
    let dir = d.join("baked");
    let status = Command::new(env!("CARGO_BIN_EXE_noisebake"))
        .args([
            "bake",
            spec.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
            "--ktx2",
        ])
        .args(["--cache-dir", d.join("cache").to_str().unwrap()])
        .status()
        .unwrap();
    assert!(status.success());
    let file = spec::parse_toml(&std::fs::read_to_string(&spec).unwrap()).unwrap();
    for (s, format) in file
        .textures
        .iter()
        .zip([Format::R8_UNORM, Format::R16_UINT])
    {
        // The .npy beside it holds the same texels.
        let t = npy::from_npy(
            &std::fs::read(dir.join(format!("{}.npy", s.name))).unwrap(),
            &s.name,
            false,
        )
        .unwrap();
        check(
            &std::fs::read(dir.join(format!("{}.ktx2", s.name))).unwrap(),
            &t,
            Some(s),
            format,
        );
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn build_scripts_write_ktx2_for_the_asset_folder() {
    let d = tmp("build");
    let spec = d.join("noise.toml");
    std::fs::write(
        &spec,
        "[[texture]]\nname = \"BLUE\"\nkind = \"stbn\"\ndims = [16, 16, 4]\nseed = 9\n",
    )
    .unwrap();
    let assets = d.join("assets/noise");
    let run = || {
        build_assets::Bake::new(&spec)
            .out_dir(d.join("out"))
            .cache_dir(d.join("cache"))
            .cargo_output(false)
            .ktx2_dir(&assets)
            .run()
            .unwrap()
    };
    run();
    let path = assets.join("BLUE.ktx2");
    let s = &spec::parse_toml(&std::fs::read_to_string(&spec).unwrap())
        .unwrap()
        .textures[0];
    let t = generate(s, &mut |_, _| {});
    check(
        &std::fs::read(&path).unwrap(),
        &t,
        Some(s),
        Format::R8_UNORM,
    );
    // A second bake leaves an unchanged file alone (its timestamp too).
    let before = std::fs::metadata(&path).unwrap().modified().unwrap();
    std::thread::sleep(std::time::Duration::from_millis(20));
    run();
    assert_eq!(
        std::fs::metadata(&path).unwrap().modified().unwrap(),
        before
    );
    std::fs::remove_dir_all(&d).ok();
}
