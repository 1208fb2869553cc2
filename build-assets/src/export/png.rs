//! PNG slices: each 2D (x, y) slice of a texture as its own image, 8-bit for u8 masks and
//! 16-bit for u16 and f32 masks (f32 scaled by 65536), RGB/RGBA 8-bit for vector formats.

use crate::spec::Scalar;
use crate::texture::Texture;
use image::{ImageBuffer, Luma};
use std::path::{Path, PathBuf};

/// File names of the slices: `stem.png` for 2D, `stem_t003.png` for 3D, `stem_z03_w05.png` for 4D.
pub fn slice_names(stem: &str, dims: &[usize]) -> Vec<String> {
    let slices: usize = dims.iter().skip(2).product();
    (0..slices)
        .map(|s| match dims.len() {
            0..=2 => format!("{stem}.png"),
            3 => format!("{stem}_t{s:03}.png"),
            _ => {
                let (z, w) = (s % dims[2], s / dims[2]);
                format!("{stem}_z{z:02}_w{w:02}.png")
            }
        })
        .collect()
}

/// Whether [`write_slices`] can write a format: scalars of any type, u8 RGB and RGBA.
pub fn supported(f: crate::spec::Format) -> bool {
    f.channels == 1 || (f.scalar == Scalar::U8 && matches!(f.channels, 3 | 4))
}

/// Writes every slice of `t` into `dir`; returns the paths written.
pub fn write_slices(t: &Texture, dir: &Path, stem: &str) -> Result<Vec<PathBuf>, String> {
    let w = t.dims[0] as u32;
    let h = t.dims.get(1).copied().unwrap_or(1) as u32;
    let per = (w * h) as usize * t.format.texel_bytes();
    let mut paths = Vec::new();
    for (bytes, name) in t.data.chunks(per).zip(slice_names(stem, &t.dims)) {
        let path = dir.join(name);
        let mut png = Vec::new();
        let enc = image::codecs::png::PngEncoder::new(&mut png);
        let ch = t.format.channels;
        let res = match (t.format.scalar, ch) {
            (Scalar::U8, 1) => {
                image::ImageEncoder::write_image(enc, bytes, w, h, image::ExtendedColorType::L8)
            }
            (Scalar::U8, 3) => {
                image::ImageEncoder::write_image(enc, bytes, w, h, image::ExtendedColorType::Rgb8)
            }
            (Scalar::U8, 4) => {
                image::ImageEncoder::write_image(enc, bytes, w, h, image::ExtendedColorType::Rgba8)
            }
            (_, 1) => {
                let vals: Vec<u16> = crate::encoding::decode_unit(bytes, t.format.scalar)
                    .iter()
                    .map(|v| (v * 65536.0).floor().clamp(0.0, 65535.0) as u16)
                    .collect();
                let img: ImageBuffer<Luma<u16>, Vec<u16>> =
                    ImageBuffer::from_raw(w, h, vals).ok_or("slice size mismatch")?;
                img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
                    .map_err(|e| e.to_string())?;
                Ok(())
            }
            _ => {
                return Err(format!(
                    "PNG export of {} textures is not supported; use .npy",
                    t.format
                ));
            }
        };
        res.map_err(|e| e.to_string())?;
        super::write_atomic(&path, &png).map_err(|e| format!("{}: {e}", path.display()))?;
        paths.push(path);
    }
    Ok(paths)
}

/// Reads a grayscale PNG (8 or 16 bit) as values in `[0, 1)` (bin centres) with its size.
pub fn read_gray(path: &Path) -> Result<(usize, usize, Vec<f64>), String> {
    let img = image::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let (w, h) = (img.width() as usize, img.height() as usize);
    let vals = match img {
        image::DynamicImage::ImageLuma8(b) => b
            .into_raw()
            .iter()
            .map(|&v| (v as f64 + 0.5) / 256.0)
            .collect(),
        other => other
            .into_luma16()
            .into_raw()
            .iter()
            .map(|&v| (v as f64 + 0.5) / 65536.0)
            .collect(),
    };
    Ok((w, h, vals))
}
