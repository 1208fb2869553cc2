//! NumPy `.npy` version 1.0: little-endian, C order, shape = dims reversed (`[W, H, T]` is stored
//! as `(T, H, W)`, x fastest) plus a trailing channel axis for vector formats.

use crate::spec::{Format, Scalar};
use crate::texture::Texture;

/// The complete `.npy` file for a texture.
pub fn to_npy(t: &Texture) -> Vec<u8> {
    let mut shape: Vec<usize> = t.dims.iter().rev().copied().collect();
    if t.format.channels > 1 {
        shape.push(t.format.channels as usize);
    }
    with_header(t.format.scalar.npy_descr(), &shape, &t.data)
}

/// The complete `.npy` file of an `f32` array of `shape` (C order, the last axis fastest),
/// for tools that export samples or frames rather than textures.
pub fn f32_array(shape: &[usize], data: &[f32]) -> Vec<u8> {
    debug_assert_eq!(shape.iter().product::<usize>(), data.len());
    let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
    with_header("<f4", shape, &bytes)
}

/// `data` behind a version 1.0 header of type `descr` and `shape`.
fn with_header(descr: &str, shape: &[usize], data: &[u8]) -> Vec<u8> {
    let shape_str = match shape.len() {
        1 => format!("({},)", shape[0]),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let mut header =
        format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape_str}, }}");
    // Magic (6) + version (2) + header length (2) + header, padded with spaces and a newline to
    // a multiple of 64 bytes.
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat(total.next_multiple_of(64) - total));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + data.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

/// The most texels [`from_npy`] accepts (2^28: a 1 GiB f32 texture).
pub const MAX_TEXELS: usize = 1 << 28;

/// The value of `'key':` in a `.npy` header dictionary, from the first character after the
/// colon.
fn field<'a>(header: &'a str, key: &str) -> Result<&'a str, String> {
    let quoted = format!("'{key}'");
    let at = header
        .find(&quoted)
        .ok_or(format!("the .npy header has no '{key}'"))?;
    let rest = header[at + quoted.len()..].trim_start();
    rest.strip_prefix(':')
        .map(str::trim_start)
        .ok_or(format!("the .npy header's '{key}' has no value"))
}

/// Reads a `.npy` written by [`to_npy`] (or NumPy: `|u1`, `<u2`, `<f4`, C order). A trailing
/// axis of 2–4 is read as channels only when `channels_last` is set.
///
/// Untrusted input: every length is checked before it is used, the header must be ASCII, the
/// shape must have 1–4 axes (plus channels) of at least one texel each, at most
/// [`MAX_TEXELS`] in all, and the data must be exactly as long as the shape says. Any other
/// file is an error naming what is wrong, never a panic or a huge allocation.
pub fn from_npy(bytes: &[u8], name: &str, channels_last: bool) -> Result<Texture, String> {
    let (scalar, mut shape, end) = header(bytes)?;
    let mut channels = 1u8;
    if channels_last && shape.len() > 1 && (2..=4).contains(shape.last().unwrap_or(&0)) {
        channels = shape.pop().unwrap_or(1) as u8;
    }
    if !(1..=4).contains(&shape.len()) {
        return Err(format!(
            "the .npy shape has {} axes; masks have 1 to 4 (plus a channel axis with --channels-last)",
            shape.len()
        ));
    }
    if shape.contains(&0) {
        return Err("the .npy shape has an empty axis".into());
    }
    let texels = shape
        .iter()
        .try_fold(1usize, |acc, &d| acc.checked_mul(d))
        .filter(|&n| n <= MAX_TEXELS)
        .ok_or(format!(
            "the .npy shape {shape:?} holds more than {MAX_TEXELS} texels"
        ))?;
    let dims: Vec<usize> = shape.iter().rev().copied().collect();
    let format = Format { scalar, channels };
    let want = texels * format.texel_bytes();
    let data = &bytes[end..];
    if data.len() != want {
        return Err(format!(
            "the .npy data holds {} bytes, its shape needs {want}",
            data.len()
        ));
    }
    Ok(Texture {
        name: name.to_string(),
        dims,
        format,
        data: data.to_vec(),
    })
}

/// The shape of a `.npy` file as NumPy states it (slowest axis first), read from its header.
pub fn shape(bytes: &[u8]) -> Result<Vec<usize>, String> {
    header(bytes).map(|(_, shape, _)| shape)
}

/// Parses [`from_npy`]'s header: the scalar type, the shape and where the data starts.
fn header(bytes: &[u8]) -> Result<(Scalar, Vec<usize>, usize), String> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err("not a .npy file (bad magic)".into());
    }
    let (hlen, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10usize),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        v => return Err(format!("unsupported .npy version {v}")),
    };
    let end = start
        .checked_add(hlen)
        .filter(|&e| e <= bytes.len())
        .ok_or("truncated .npy header")?;
    let header = &bytes[start..end];
    if !header.is_ascii() {
        return Err("the .npy header is not ASCII text".into());
    }
    let header = std::str::from_utf8(header).map_err(|_| "the .npy header is not text")?;
    let descr = field(header, "descr")?;
    let scalar = if descr.starts_with("'|u1'") || descr.starts_with("'<u1'") {
        Scalar::U8
    } else if descr.starts_with("'<u2'") {
        Scalar::U16
    } else if descr.starts_with("'<f4'") {
        Scalar::F32
    } else {
        return Err(format!(
            "unsupported dtype {}",
            descr.split(',').next().unwrap_or(descr)
        ));
    };
    if field(header, "fortran_order")?.starts_with("True") {
        return Err("Fortran-order .npy files are not supported".into());
    }
    let shape_s = field(header, "shape")?;
    let inner = shape_s
        .strip_prefix('(')
        .and_then(|r| r.find(')').map(|c| &r[..c]))
        .ok_or("the .npy shape is not a tuple `(…)`")?;
    let shape: Vec<usize> = inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().map_err(|_| format!("bad shape entry `{s}`")))
        .collect::<Result<_, String>>()?;
    Ok((scalar, shape, end))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_aligns_the_header() {
        let t = Texture {
            name: "t".into(),
            dims: vec![3, 2, 2],
            format: Format::U16,
            data: (0..24).collect(),
        };
        let bytes = to_npy(&t);
        let hlen = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        assert_eq!((10 + hlen) % 64, 0);
        let header = std::str::from_utf8(&bytes[10..10 + hlen]).unwrap();
        assert!(header.contains("'shape': (2, 2, 3)"), "{header}");
        assert!(header.contains("'descr': '<u2'"), "{header}");
        assert_eq!(from_npy(&bytes, "t", false).unwrap(), t);
    }

    fn with_header(h: &str, data: &[u8]) -> Vec<u8> {
        let mut b = b"\x93NUMPY\x01\x00".to_vec();
        b.extend_from_slice(&(h.len() as u16).to_le_bytes());
        b.extend_from_slice(h.as_bytes());
        b.extend_from_slice(data);
        b
    }

    /// The malformed files that once panicked, aborted or allocated without bound.
    #[test]
    fn malformed_headers_are_errors() {
        let h =
            |shape: &str| format!("{{'descr': '|u1', 'fortran_order': False, 'shape': {shape}, }}");
        for (what, bytes) in [
            ("empty axis", with_header(&h("(0,)"), &[])),
            ("no axes", with_header(&h("()"), &[1])),
            ("no tuple", with_header(&h(")"), &[1])),
            (
                "wrapping product",
                with_header(&h("(4294967296, 4294967296, 1)"), &[0; 64]),
            ),
            ("huge", with_header(&h("(65536, 65536, 65536)"), &[0; 8])),
            ("five axes", with_header(&h("(1, 1, 1, 1, 1)"), &[0])),
            (
                "non-ASCII",
                with_header("{'descr': '|u1', 'shape': (é,), }", &[0]),
            ),
            ("header past the end", {
                let mut b = with_header(&h("(1,)"), &[0]);
                b[8] = 0xff;
                b[9] = 0xff;
                b
            }),
            ("short data", with_header(&h("(4,)"), &[0; 3])),
            ("no colon", with_header("{'descr' '|u1'}", &[0])),
        ] {
            assert!(from_npy(&bytes, "t", false).is_err(), "{what}");
            assert!(
                from_npy(&bytes, "t", true).is_err(),
                "{what} (channels last)"
            );
        }
    }
}
