//! Atomic file writes: the bytes go to a fresh temporary file in the target's directory, are
//! synced, and the temporary is renamed over the target. A reader sees the old file or the new
//! one, never half of one; every failure path (and a panic) removes the temporary.
//!
//! The temporary's name carries 64 random bits (from the standard library's per-process hash
//! keys) and is opened with `create_new`, so it never follows a symlink planted under a
//! predictable name and two writers never share one.

use std::collections::hash_map::RandomState;
use std::fs::{self, File, OpenOptions};
use std::hash::{BuildHasher, Hasher};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Temporary files of `name` in its directory start with this.
pub fn temp_prefix(name: &str) -> String {
    format!(".{name}.")
}

/// Temporary files end with this.
pub const TEMP_SUFFIX: &str = ".tmp";

fn random() -> u64 {
    let mut h = RandomState::new().build_hasher();
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos()),
    );
    h.write_u32(std::process::id());
    h.finish()
}

/// Removes the temporary file unless disarmed.
struct Temp(Option<PathBuf>);

impl Drop for Temp {
    fn drop(&mut self) {
        if let Some(p) = self.0.take() {
            let _ = fs::remove_file(p);
        }
    }
}

/// Writes `bytes` to `path` atomically, creating the parent directory if needed.
pub fn write(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .filter(|n| *n != "." && *n != "..")
        .ok_or_else(|| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{} does not name a file", path.display()),
            )
        })?;
    fs::create_dir_all(dir)?;
    let (mut file, temp) = {
        let mut tries = 0;
        loop {
            let tmp = dir.join(format!(
                "{}{:016x}{TEMP_SUFFIX}",
                temp_prefix(name),
                random()
            ));
            match OpenOptions::new().write(true).create_new(true).open(&tmp) {
                Ok(f) => break (f, Temp(Some(tmp))),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists && tries < 8 => tries += 1,
                Err(e) => return Err(e),
            }
        }
    };
    file.write_all(bytes)?;
    file.sync_all()?;
    drop::<File>(file);
    let mut temp = temp;
    let tmp = temp.0.clone().expect("armed");
    fs::rename(&tmp, path)?;
    temp.0 = None;
    Ok(())
}

/// Removes temporary files of `name` left in `dir` by a writer that was killed. Only call this
/// while holding the lock that serialises writers of `name`.
pub fn remove_orphans(dir: &Path, name: &str) {
    let prefix = temp_prefix(name);
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let n = e.file_name();
        let Some(n) = n.to_str() else { continue };
        if n.starts_with(&prefix) && n.ends_with(TEMP_SUFFIX) {
            let _ = fs::remove_file(e.path());
        }
    }
}
