//! Rust code for baked textures: one `static` per texture, a typed runtime view over bytes
//! included with `include_bytes!` inside an alignment wrapper — never an array literal (16 MiB
//! as a literal costs rustc a minute and gigabytes; `include_bytes!` a fraction of a second).

use crate::spec::{Format, Kind, Scalar, TextureSpec};

/// The runtime view type of a spec, e.g. `::noisebake::Mask3<u16, 64, 64, 16>`, or
/// `::noisebake::SamplerTile<128, 128, 4, 4>` for a sampler tile.
pub fn view_type(spec: &TextureSpec, krate: &str) -> String {
    if let Kind::Sampler(p) = &spec.kind {
        return format!(
            "{krate}::SamplerTile<{}, {}, {}, {}>",
            spec.dims[0], spec.dims[1], p.spp, p.sample_dims
        );
    }
    mask_type(spec, krate)
}

/// The mask view over a spec's stored texels (a sampler tile's key mask for a sampler).
fn mask_type(spec: &TextureSpec, krate: &str) -> String {
    let texel = texel_type(spec.format);
    let d = &spec.storage_dims();
    match d.len() {
        1 => format!("{krate}::Mask2<{texel}, {}, 1>", d[0]),
        2 => format!("{krate}::Mask2<{texel}, {}, {}>", d[0], d[1]),
        3 => format!("{krate}::Mask3<{texel}, {}, {}, {}>", d[0], d[1], d[2]),
        _ => format!(
            "{krate}::Mask4<{texel}, {}, {}, {}, {}>",
            d[0], d[1], d[2], d[3]
        ),
    }
}

/// The Rust texel type of a format.
pub fn texel_type(f: Format) -> String {
    let s = match f.scalar {
        Scalar::U8 => "u8",
        Scalar::U16 => "u16",
        Scalar::F32 => "f32",
    };
    if f.channels == 1 {
        s.to_string()
    } else {
        format!("[{s}; {}]", f.channels)
    }
}

/// The item for one texture whose bytes are at `offset..offset + len` of the file `path`.
pub fn item(spec: &TextureSpec, vis: &str, path: &str, offset: usize, krate: &str) -> String {
    let bytes = format!(
        "{krate}::mask::payload({krate}::include_aligned!({path:?}), {offset}, {})",
        spec.byte_len()
    );
    format!(
        "/// Baked noise texture `{name}`: {kind} {dims:?}, {format}.\n///\n/// Spec: `{canon}`\n{vis}static {name}: {ty} = {init};\n",
        name = spec.name,
        kind = spec.kind.name(),
        dims = spec.dims,
        format = spec.format,
        canon = spec.canonical(),
        ty = view_type(spec, krate),
        init = construct(spec, &bytes, krate),
    )
}

/// The expression that builds a spec's view over the byte-slice expression `bytes`.
fn construct(spec: &TextureSpec, bytes: &str, krate: &str) -> String {
    let mask = mask_type(spec, krate);
    let mask_ctor = mask.split('<').next().unwrap_or(&mask);
    let mask = format!("{mask_ctor}::new({bytes})");
    match &spec.kind {
        Kind::Sampler(p) => format!(
            "{krate}::SamplerTile::new({mask}, {:#010b})",
            p.sobol_pairs()
        ),
        _ => mask,
    }
}

/// A typed placeholder (zeros) for a texture that is not generated now (an error elsewhere, or
/// a cache miss under rust-analyzer): code using it still type-checks.
pub fn placeholder(spec: &TextureSpec, vis: &str, krate: &str) -> String {
    let bytes = format!("&[0u8; {}]", spec.byte_len());
    format!(
        "{vis}static {}: {} = {};\n",
        spec.name,
        view_type(spec, krate),
        construct(spec, &bytes, krate)
    )
}
