//! The content-addressed cache of generated textures.
//!
//! Key: a hash of the canonical spec (every default filled in, [`TextureSpec::canonical`]) and
//! [`ALGORITHM_VERSION`]; any change of either regenerates, nothing else does.
//!
//! Entry file `<key>.nbk`: a 64-byte header (magic, format version, data length, data hash,
//! canonical-spec length), the texture bytes, then the canonical spec. Reads verify all of it: a
//! truncated, bit-flipped or foreign file is reported and regenerated. Writes take an exclusive
//! lock (`<key>.lock`, `std::fs::File::lock`), re-check for an entry another process finished
//! meanwhile (so the generator runs once), write a temporary file in the same directory and
//! rename it into place, so no reader ever sees half an entry.
//!
//! Location, first that applies: `NOISEBAKE_CACHE_DIR`; the spec file's `cache_dir`; the workspace
//! target directory's `noisebake-cache/` (`CARGO_TARGET_DIR`, else found by walking up from
//! `OUT_DIR`). With `NOISEBAKE_OFFLINE=1` a missing entry is an error instead of a generation
//! (commit the cache directory, like sqlx's `.sqlx/`, and build offline in CI).

use crate::generate::{ALGORITHM_VERSION, generate};
use crate::spec::TextureSpec;
use crate::texture::Texture;
use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

const MAGIC: &[u8; 8] = b"NBAKE\x00\x01\x00";
/// Bytes before the texture data in an entry file.
pub const HEADER: usize = 64;

/// FNV-1a, 64-bit: keys and content hashes (fast, dependency-free, stable forever).
pub fn fnv64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
    })
}

/// The cache key of a spec.
pub fn key(spec: &TextureSpec) -> String {
    let canon = format!("v{ALGORITHM_VERSION};{}", spec.canonical());
    format!(
        "{:016x}{:016x}",
        fnv64(canon.as_bytes()),
        fnv64(&[canon.as_bytes(), b"#2"].concat())
    )
}

/// Where an entry came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// Read from the cache.
    Hit,
    /// Generated now (and stored).
    Generated,
}

/// A texture and its cache entry.
#[derive(Clone, Debug)]
pub struct Entry {
    /// The texture.
    pub texture: Texture,
    /// The entry file (texture bytes at offset [`HEADER`]).
    pub path: PathBuf,
    /// Hit or generated.
    pub source: Source,
}

/// A cache directory and its policy.
#[derive(Clone, Debug)]
pub struct Cache {
    /// The directory entries live in.
    pub dir: PathBuf,
    /// Whether a missing entry is an error.
    pub offline: bool,
    /// Warnings met (corrupt entries, fallbacks), for the caller to show.
    pub warnings: Vec<String>,
}

/// Finds the workspace target directory: `CARGO_TARGET_DIR`, else the ancestor of `OUT_DIR`
/// (`…/target/<profile>/build/<pkg>/out`) that holds the profile dirs; then, if that directory
/// lies inside another directory Cargo tagged with `CACHEDIR.TAG`, the outermost such one. So
/// builds nested in the workspace target (trybuild sets `CARGO_TARGET_DIR` to
/// `target/tests/trybuild`) share the workspace's cache instead of baking everything again.
pub fn target_dir(out_dir: Option<&Path>) -> Option<PathBuf> {
    let base = match std::env::var_os("CARGO_TARGET_DIR") {
        Some(t) => PathBuf::from(t),
        None => profile_parent(out_dir?)?,
    };
    let outer = base
        .ancestors()
        .filter(|a| a.join("CACHEDIR.TAG").is_file())
        .last()
        .map(Path::to_path_buf);
    Some(outer.unwrap_or(base))
}

/// The directory that holds the profile dirs above `out` (`…/<profile>/build/<pkg>/out`).
fn profile_parent(out: &Path) -> Option<PathBuf> {
    // out -> <pkg-hash> -> build -> <profile> (-> <triple>) -> target
    let mut p = out.to_path_buf();
    while let Some(parent) = p.parent() {
        if p.file_name().is_some_and(|n| n == "build") {
            let profile = parent;
            let up = profile.parent()?;
            // A target triple directory sits between the target dir and the profile.
            if up.join("CACHEDIR.TAG").exists() || up.file_name().is_some_and(|n| n == "target") {
                return Some(up.to_path_buf());
            }
            return up
                .parent()
                .map(Path::to_path_buf)
                .or(Some(up.to_path_buf()));
        }
        p = parent.to_path_buf();
    }
    None
}

fn env_on(name: &str) -> bool {
    std::env::var(name).is_ok_and(|v| !v.is_empty() && v != "0" && v != "false")
}

impl Cache {
    /// A cache in `dir` (offline when `NOISEBAKE_OFFLINE` is set).
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Self {
            dir: dir.into(),
            offline: env_on("NOISEBAKE_OFFLINE"),
            warnings: Vec::new(),
        }
    }

    /// The cache a build uses: `NOISEBAKE_CACHE_DIR`, else `spec_dir`, else the target dir's
    /// `noisebake-cache`, else `fallback`.
    pub fn locate(spec_dir: Option<PathBuf>, out_dir: Option<&Path>, fallback: &Path) -> Self {
        let dir = std::env::var_os("NOISEBAKE_CACHE_DIR")
            .map(PathBuf::from)
            .or(spec_dir)
            .or_else(|| target_dir(out_dir).map(|t| t.join("noisebake-cache")))
            .unwrap_or_else(|| fallback.join("noisebake-cache"));
        Self::new(dir)
    }

    /// Uses `dir` unless `NOISEBAKE_CACHE_DIR` chose the directory.
    pub fn with_default_dir(mut self, dir: PathBuf) -> Self {
        if std::env::var_os("NOISEBAKE_CACHE_DIR").is_none() {
            self.dir = dir;
        }
        self
    }

    /// The entry path of a spec.
    pub fn path(&self, spec: &TextureSpec) -> PathBuf {
        self.dir.join(format!("{}.nbk", key(spec)))
    }

    /// Reads and verifies an entry; `Ok(None)` when absent, `Err` describing a bad one.
    pub fn read(&self, spec: &TextureSpec) -> Result<Option<Texture>, String> {
        let path = self.path(spec);
        let bytes = match fs::read(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(format!("{}: {e}", path.display())),
        };
        decode(&bytes, spec)
            .map(Some)
            .map_err(|why| format!("{}: {why}", path.display()))
    }

    /// The texture of `spec`, from the cache or generated (once, under a lock) and stored.
    /// `progress` sees generation progress.
    pub fn get(
        &mut self,
        spec: &TextureSpec,
        progress: &mut dyn FnMut(u64, u64),
    ) -> Result<Entry, String> {
        let path = self.path(spec);
        match self.read(spec) {
            Ok(Some(texture)) => {
                return Ok(Entry {
                    texture,
                    path,
                    source: Source::Hit,
                });
            }
            Ok(None) => {}
            Err(why) => self
                .warnings
                .push(format!("corrupt cache entry, regenerating: {why}")),
        }
        if self.offline {
            return Err(format!(
                "NOISEBAKE_OFFLINE is set and texture `{}` is not in the cache {} (expected {}); bake it once online and commit the cache directory",
                spec.name,
                self.dir.display(),
                path.display()
            ));
        }
        fs::create_dir_all(&self.dir)
            .map_err(|e| format!("cannot create cache dir {}: {e}", self.dir.display()))?;
        let lock_path = self.dir.join(format!("{}.lock", key(spec)));
        let lock = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .map_err(|e| format!("cannot open {}: {e}", lock_path.display()))?;
        lock.lock()
            .map_err(|e| format!("cannot lock {}: {e}", lock_path.display()))?;
        // Another process may have finished the entry while we waited.
        if let Ok(Some(texture)) = self.read(spec) {
            return Ok(Entry {
                texture,
                path,
                source: Source::Hit,
            });
        }
        let texture = generate(spec, progress);
        write_entry(&path, &encode(&texture, spec))
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        drop(lock);
        Ok(Entry {
            texture,
            path,
            source: Source::Generated,
        })
    }
}

/// The bytes of an entry file.
pub fn encode(t: &Texture, spec: &TextureSpec) -> Vec<u8> {
    let canon = spec.canonical();
    let mut out = Vec::with_capacity(HEADER + t.data.len() + canon.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&(t.data.len() as u64).to_le_bytes());
    out.extend_from_slice(&fnv64(&t.data).to_le_bytes());
    out.extend_from_slice(&(canon.len() as u64).to_le_bytes());
    out.extend_from_slice(&fnv64(canon.as_bytes()).to_le_bytes());
    out.resize(HEADER, 0);
    out.extend_from_slice(&t.data);
    out.extend_from_slice(canon.as_bytes());
    out
}

fn decode(bytes: &[u8], spec: &TextureSpec) -> Result<Texture, String> {
    if bytes.len() < HEADER || &bytes[..8] != MAGIC {
        return Err("not a noisebake cache entry (bad magic or truncated header)".into());
    }
    let u = |i: usize| u64::from_le_bytes(bytes[i..i + 8].try_into().expect("8 bytes")) as usize;
    let (len, hash, clen) = (u(8), u(16) as u64, u(24));
    if bytes.len() != HEADER + len + clen {
        return Err(format!(
            "truncated: {} bytes, header says {}",
            bytes.len(),
            HEADER + len + clen
        ));
    }
    let data = &bytes[HEADER..HEADER + len];
    if fnv64(data) != hash {
        return Err("content hash mismatch (corrupted)".into());
    }
    if &bytes[HEADER + len..] != spec.canonical().as_bytes() {
        return Err("entry belongs to a different spec".into());
    }
    if len != spec.byte_len() {
        return Err(format!(
            "holds {len} bytes, the spec needs {}",
            spec.byte_len()
        ));
    }
    Ok(Texture {
        name: spec.name.clone(),
        dims: spec.dims.clone(),
        format: spec.format,
        data: data.to_vec(),
    })
}

fn write_entry(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let tmp = dir.join(format!(
        ".{}.{}.{:?}.tmp",
        path.file_name().and_then(|n| n.to_str()).unwrap_or("entry"),
        std::process::id(),
        std::thread::current().id()
    ));
    let mut f = File::create(&tmp)?;
    f.write_all(bytes)?;
    f.sync_all()?;
    drop(f);
    fs::rename(&tmp, path).inspect_err(|_| {
        let _ = fs::remove_file(&tmp);
    })
}

/// Whether `dir` can be written (created if needed).
pub fn writable(dir: &Path) -> bool {
    if fs::create_dir_all(dir).is_err() {
        return false;
    }
    let probe = dir.join(format!(".probe.{}", std::process::id()));
    let ok = File::create(&probe).is_ok();
    let _ = fs::remove_file(&probe);
    ok
}
