//! KTX 2.0 export (Khronos KTX File Format Specification 2.0): a baked texture as one
//! uncompressed 2D array texture, ready for `wgpu`, Bevy's `Image::from_buffer` or any KTX2
//! loader.
//!
//! - **Layers.** One mip level; `width × height` per layer. A 2D mask is one layer (the file
//!   is still an array, so one shader binding type, `texture_2d_array`, reads every mask); a 3D
//!   mask one layer per time slice; a 4D mask `(x, y, z, w)` is flattened layer-major, layer
//!   `z + D·w` — the bytes' own order, so the level data is the `.npy` payload unchanged. A 1D
//!   mask is one row.
//! - **Formats** (`VkFormat`, as [`noise_runtime::GpuFormat`] uploads them): `u8` →
//!   `R8_UNORM`, `u16` → `R16_UINT`, `f32` → `R32_SFLOAT`, 2- and 4-channel vectors the
//!   matching `R8G8`/`R8G8B8A8_UNORM`, `R16G16`/`R16G16B16A16_UINT`, `R32G32`/`R32G32B32A32_SFLOAT`.
//!   3-channel vectors are padded to 4 (padding channel at its largest value: 255, 65535, 1.0),
//!   since WebGPU has no 3-channel formats. 16-bit masks are `R16_UINT` rather than `R16_UNORM`:
//!   `R16_UNORM` needs a native-only wgpu feature and does not exist on the web, while the
//!   integer load is exact everywhere (`nb_u16_unit` in the WGSL library scales it).
//! - **Data format descriptor** (Khronos Data Format Specification 1.3, basic block, §5):
//!   colour model RGBSDA; primaries unspecified (noise is data, not colour); transfer function
//!   linear for UNORM and SFLOAT, unspecified for UINT (as KTX 2.0 §3.10.2 asks of integer
//!   formats); one sample per channel with its bit offset and length, float samples qualified
//!   `FLOAT | SIGNED` with bounds −1.0…1.0, UNORM bounds 0…2^bits − 1, UINT bounds 0…1.
//! - **Metadata.** `KTXwriter`, and our own keys prefixed `noisebake.`: `kind`, `dims`,
//!   `format`, `layout`, `seed`, `spec` (the canonical spec) and `spec_hash` (the cache key,
//!   which names the exact bytes), each a NUL-terminated UTF-8 string.

use crate::spec::{Scalar, TextureSpec};
use crate::texture::Texture;
use noise_runtime::GpuFormat;

/// The file identifier `«KTX 20»\r\n\x1A\n`.
const IDENTIFIER: [u8; 12] = [
    0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A,
];

/// Header (48) + index (32) + one level index entry (24).
const LEVEL0: usize = 48 + 32 + 24;

/// The GPU format a texture is written as.
pub fn gpu_format(t: &Texture) -> GpuFormat {
    GpuFormat::for_texel(t.format.scalar.bytes(), t.format.channels as usize)
}

/// `(width, height, layers)` of a texture's KTX2 image.
pub fn extent(dims: &[usize]) -> (usize, usize, usize) {
    let w = dims.first().copied().unwrap_or(1);
    let h = dims.get(1).copied().unwrap_or(1);
    let layers = dims.iter().skip(2).product::<usize>().max(1);
    (w, h, layers)
}

/// The texture as a KTX 2.0 file. `spec` adds the kind, seed, canonical spec and its hash to
/// the metadata (textures read from `.npy` files have none).
pub fn to_ktx2(t: &Texture, spec: Option<&TextureSpec>) -> Vec<u8> {
    let format = gpu_format(t);
    let (w, h, layers) = extent(&t.dims);
    let channels = t.format.channels as usize;
    let cb = format.channel_bytes();

    // The level data: the texels, 3-channel ones padded to 4.
    let level: Vec<u8> = if channels == format.channels() {
        t.data.clone()
    } else {
        let mut out = Vec::with_capacity(t.texels() * format.texel_bytes());
        for texel in t.data.chunks_exact(channels * cb) {
            out.extend_from_slice(texel);
            out.extend_from_slice(format.pad());
        }
        out
    };

    let dfd = descriptor(format, t.format.scalar);
    let kvd = key_values(t, spec, format);
    let dfd_offset = LEVEL0;
    let kvd_offset = dfd_offset + dfd.len();
    // Level data starts at a multiple of lcm(texel size, 4) (§3.9.7 alignment).
    let align = lcm(format.texel_bytes(), 4);
    let level_offset = (kvd_offset + kvd.len()).next_multiple_of(align);

    let mut f = Vec::with_capacity(level_offset + level.len());
    f.extend_from_slice(&IDENTIFIER);
    for v in [
        format.vk_format(),
        cb as u32, // typeSize
        w as u32,
        h as u32,
        0, // pixelDepth: a 2D texture
        layers as u32,
        1, // faceCount
        1, // levelCount
        0, // supercompressionScheme: none
    ] {
        f.extend_from_slice(&v.to_le_bytes());
    }
    for v in [dfd_offset, dfd.len(), kvd_offset, kvd.len()] {
        f.extend_from_slice(&(v as u32).to_le_bytes());
    }
    f.extend_from_slice(&0u64.to_le_bytes()); // sgdByteOffset
    f.extend_from_slice(&0u64.to_le_bytes()); // sgdByteLength
    for v in [level_offset, level.len(), level.len()] {
        f.extend_from_slice(&(v as u64).to_le_bytes());
    }
    debug_assert_eq!(f.len(), LEVEL0);
    f.extend_from_slice(&dfd);
    f.extend_from_slice(&kvd);
    f.resize(level_offset, 0);
    f.extend_from_slice(&level);
    f
}

/// The data format descriptor: `dfdTotalSize` and one basic descriptor block.
fn descriptor(format: GpuFormat, scalar: Scalar) -> Vec<u8> {
    const MODEL_RGBSDA: u8 = 1;
    const PRIMARIES_UNSPECIFIED: u8 = 0;
    const TRANSFER_UNSPECIFIED: u8 = 0;
    const TRANSFER_LINEAR: u8 = 1;
    const QUALIFIER_SIGNED: u8 = 0x40;
    const QUALIFIER_FLOAT: u8 = 0x80;
    const CHANNEL_ID: [u8; 4] = [0, 1, 2, 15]; // R, G, B, A
    let samples = format.channels();
    let block = 24 + 16 * samples;
    let mut d = Vec::with_capacity(4 + block);
    d.extend_from_slice(&((4 + block) as u32).to_le_bytes());
    d.extend_from_slice(&0u32.to_le_bytes()); // vendorId 0 (Khronos), descriptorType 0 (basic)
    d.extend_from_slice(&2u16.to_le_bytes()); // versionNumber: 1.3
    d.extend_from_slice(&(block as u16).to_le_bytes());
    let transfer = match scalar {
        Scalar::U16 => TRANSFER_UNSPECIFIED,
        _ => TRANSFER_LINEAR,
    };
    d.extend_from_slice(&[MODEL_RGBSDA, PRIMARIES_UNSPECIFIED, transfer, 0]);
    d.extend_from_slice(&[0, 0, 0, 0]); // texelBlockDimension: 1×1×1×1
    let mut planes = [0u8; 8];
    planes[0] = format.texel_bytes() as u8;
    d.extend_from_slice(&planes);
    let bits = 8 * format.channel_bytes();
    for (c, id) in CHANNEL_ID.iter().enumerate().take(samples) {
        d.extend_from_slice(&((c * bits) as u16).to_le_bytes()); // bitOffset
        d.push((bits - 1) as u8); // bitLength − 1
        let (qualifiers, lower, upper) = match scalar {
            Scalar::U8 => (0, 0u32, 255u32),
            Scalar::U16 => (0, 0, 1),
            Scalar::F32 => (
                QUALIFIER_FLOAT | QUALIFIER_SIGNED,
                (-1.0f32).to_bits(),
                1.0f32.to_bits(),
            ),
        };
        d.push(id | qualifiers);
        d.extend_from_slice(&[0, 0, 0, 0]); // samplePosition
        d.extend_from_slice(&lower.to_le_bytes());
        d.extend_from_slice(&upper.to_le_bytes());
    }
    d
}

/// The key/value data: entries sorted by key, each padded to 4 bytes.
fn key_values(t: &Texture, spec: Option<&TextureSpec>, format: GpuFormat) -> Vec<u8> {
    let dims: Vec<String> = t.dims.iter().map(|d| d.to_string()).collect();
    let padded = if format.channels() != t.format.channels as usize {
        format!(" (padded to {})", format.name())
    } else {
        String::new()
    };
    let layout = match t.dims.len() {
        0..=2 => "one layer".to_string(),
        3 => "layer = t".to_string(),
        _ => "layer = z + D*w (layer-major)".to_string(),
    };
    let mut pairs = vec![
        (
            "KTXwriter".to_string(),
            format!("noisebake build-assets {}", env!("CARGO_PKG_VERSION")),
        ),
        ("noisebake.dims".into(), dims.join("x")),
        ("noisebake.format".into(), format!("{}{padded}", t.format)),
        ("noisebake.layout".into(), layout),
    ];
    if let Some(s) = spec {
        pairs.push(("noisebake.kind".into(), s.kind.name().to_string()));
        pairs.push(("noisebake.seed".into(), s.seed.to_string()));
        pairs.push(("noisebake.spec".into(), s.canonical()));
        pairs.push(("noisebake.spec_hash".into(), crate::cache::key(s)));
    }
    pairs.sort_by(|a, b| a.0.as_bytes().cmp(b.0.as_bytes()));
    let mut out = Vec::new();
    for (k, v) in pairs {
        let len = k.len() + 1 + v.len() + 1;
        out.extend_from_slice(&(len as u32).to_le_bytes());
        out.extend_from_slice(k.as_bytes());
        out.push(0);
        out.extend_from_slice(v.as_bytes());
        out.push(0);
        out.resize(out.len().next_multiple_of(4), 0);
    }
    out
}

fn lcm(a: usize, b: usize) -> usize {
    let gcd = |mut a: usize, mut b: usize| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    a / gcd(a, b) * b
}
