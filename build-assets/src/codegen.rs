//! Rust code for baked textures: one `static` per texture, a typed runtime view over bytes
//! included with `include_bytes!` inside an alignment wrapper — never an array literal (16 MiB
//! as a literal costs rustc a minute and gigabytes; `include_bytes!` a fraction of a second).

use crate::spec::{Format, Scalar, TextureSpec};

/// The runtime view type of a spec, e.g. `::noisebake::Mask3<u16, 64, 64, 16>`.
pub fn view_type(spec: &TextureSpec, krate: &str) -> String {
    let texel = texel_type(spec.format);
    let d = &spec.dims;
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
    let ty = view_type(spec, krate);
    let ctor = ty.split('<').next().unwrap_or(&ty);
    format!(
        "/// Baked noise texture `{name}`: {kind} {dims:?}, {format}.\n///\n/// Spec: `{canon}`\n{vis}static {name}: {ty} = {ctor}::new({krate}::mask::payload({krate}::include_aligned!({path:?}), {offset}, {len}));\n",
        name = spec.name,
        kind = spec.kind.name(),
        dims = spec.dims,
        format = spec.format,
        canon = spec.canonical(),
        len = spec.byte_len(),
    )
}

/// A typed placeholder (zeros) for a texture that is not generated now (an error elsewhere, or
/// a cache miss under rust-analyzer): code using it still type-checks.
pub fn placeholder(spec: &TextureSpec, vis: &str, krate: &str) -> String {
    let ty = view_type(spec, krate);
    let ctor = ty.split('<').next().unwrap_or(&ty);
    format!(
        "{vis}static {}: {ty} = {ctor}::new(&[0u8; {}]);\n",
        spec.name,
        spec.byte_len()
    )
}
