//! Writing textures out: NumPy `.npy`, raw little-endian `.bin`, KTX 2.0 array textures for
//! GPUs (`.ktx2`), and PNG slices (feature `png`). Every writer goes through a temporary file and a rename, so an interrupted run never
//! leaves a half-written file under the final name.

pub mod ktx2;
pub mod npy;
#[cfg(feature = "png")]
#[cfg_attr(docsrs, doc(cfg(feature = "png")))]
pub mod png;

use std::io;
use std::path::Path;

/// Writes `bytes` to `path` atomically (see [`crate::atomic`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    crate::atomic::write(path, bytes)
}
