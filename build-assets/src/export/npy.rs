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
    let mut header = format!(
        "{{'descr': '{}', 'fortran_order': False, 'shape': {shape_str}, }}",
        t.format.scalar.npy_descr()
    );
    // Magic (6) + version (2) + header length (2) + header, padded with spaces and a newline to
    // a multiple of 64 bytes.
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat(total.next_multiple_of(64) - total));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + t.data.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(&t.data);
    out
}

/// Reads a `.npy` written by [`to_npy`] (or NumPy: `|u1`, `<u2`, `<f4`, C order). A trailing
/// axis of 2–4 is read as channels only when `channels_last` is set.
pub fn from_npy(bytes: &[u8], name: &str, channels_last: bool) -> Result<Texture, String> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err("not a .npy file (bad magic)".into());
    }
    let (hlen, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (
            u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
            12,
        ),
        v => return Err(format!("unsupported .npy version {v}")),
    };
    let header = std::str::from_utf8(
        bytes
            .get(start..start + hlen)
            .ok_or("truncated .npy header")?,
    )
    .map_err(|_| "the .npy header is not text")?;
    let field = |key: &str| -> Result<&str, String> {
        let at = header
            .find(&format!("'{key}'"))
            .ok_or(format!("the .npy header has no '{key}'"))?;
        Ok(header[at + key.len() + 2..]
            .trim_start()
            .trim_start_matches(':')
            .trim_start())
    };
    let descr = field("descr")?;
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
    if field("fortran_order")?.starts_with("True") {
        return Err("Fortran-order .npy files are not supported".into());
    }
    let shape_s = field("shape")?;
    let close = shape_s.find(')').ok_or("bad shape")?;
    let mut shape: Vec<usize> = shape_s[1..close]
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().map_err(|_| format!("bad shape entry `{s}`")))
        .collect::<Result<_, String>>()?;
    let mut channels = 1u8;
    if channels_last && shape.len() > 1 && (2..=4).contains(shape.last().unwrap()) {
        channels = shape.pop().unwrap() as u8;
    }
    let dims: Vec<usize> = shape.iter().rev().copied().collect();
    let format = Format { scalar, channels };
    let want = dims.iter().product::<usize>() * format.texel_bytes();
    let data = &bytes[start + hlen..];
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
}
