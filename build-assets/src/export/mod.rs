//! Writing textures out: NumPy `.npy` and raw little-endian `.bin`. Every writer goes through a
//! temporary file and a rename, so an interrupted run never leaves a half-written file under the
//! final name. (PNG slices and plots are the CLI's: `noisebake-cli`.)

pub mod npy;

use std::io;
use std::path::Path;

/// Writes `bytes` to `path` atomically (see [`crate::atomic`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    crate::atomic::write(path, bytes)
}
