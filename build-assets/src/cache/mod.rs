//! The content-addressed cache of generated textures, and the one place that decides where it
//! lives for every way in (build script, `noise_texture!`, CLI).
//!
//! **Key**: FNV-1a 128 of the canonical spec (every default filled in,
//! [`TextureSpec::canonical`]) and [`ALGORITHM_VERSION`]; any change of either regenerates,
//! nothing else does.
//!
//! **Entry** `<key>.nbk`: a 64-byte header (magic and format version, data length, data hash,
//! canonical-spec length, canonical-spec hash, zero padding), the texture bytes, then the
//! canonical spec. Reads check every header field, with checked arithmetic, before trusting
//! any: a truncated, bit-flipped, crafted or foreign file is reported as corrupt and
//! regenerated, never a panic.
//!
//! **Writes** take an exclusive lock (`<key>.lock`, `std::fs::File::lock`), re-check for an
//! entry another process finished meanwhile (so the generator runs once), remove temporary
//! files a killed writer left, and write through [`crate::atomic`]. An entry's modification time
//! is set to a fixed instant in the past: the entry is immutable, and a build that embeds it
//! with `include_bytes!` right after generating it would otherwise look stale to Cargo and
//! compile a second time.
//!
//! **Location** ([`Locator::resolve`]), first that applies:
//! 1. `NOISEBAKE_CACHE_DIR`;
//! 2. a directory given in code ([`crate::Bake::cache_dir`], the CLI's `--cache-dir`);
//! 3. `cache_dir = "…"` at the top of the spec file, relative to it — `noise.toml` beside the
//!    crate's `Cargo.toml` for the macro, so both ways in find a committed cache. It must be
//!    relative and stay inside the workspace;
//! 4. `noisebake-cache/` in the workspace target directory (`CARGO_TARGET_DIR`, else found
//!    from `OUT_DIR`, else `target/` beside the outermost `Cargo.lock`).
//!
//! **Tidiness** ([`tidy`]): the first write into a directory leaves a `.gitignore` for its
//! locks, temporaries and `used/` last-use records, so a committed cache commits only its
//! entries; [`tidy::list`], [`tidy::check`] and [`tidy::prune`] are `noisebake cache list |
//! verify | prune`.
//!
//! **Faults** follow one policy: a hit is served from wherever it is readable (a read-only
//! cache with every entry present costs nothing); a miss that cannot be written into the cache
//! directory (read-only, full, a directory where a file should be) is written to the fallback
//! (`OUT_DIR/noisebake-cache`, else the system temporary directory) with a warning; if that
//! fails too the texture is still returned, uncached. With `NOISEBAKE_OFFLINE=1` a miss is an
//! error instead of a generation (commit the cache directory and build offline in CI).

pub mod tidy;

use crate::atomic;
use crate::error::{Error, Warning};
use crate::generate::{ALGORITHM_VERSION, generate};
use crate::spec::TextureSpec;
use crate::texture::Texture;
use std::fs::{self, File, OpenOptions};
use std::io;
use std::path::{Component, Path, PathBuf};
use std::time::{Duration, SystemTime};

/// Magic and entry-format version (the last two bytes).
const MAGIC: &[u8; 8] = b"NBAKE\x00\x02\x00";
/// Bytes before the texture data in an entry file.
pub const HEADER: usize = 64;
/// The modification time of every entry: 2001-09-09, long before any build that reads it.
const ENTRY_MTIME: Duration = Duration::from_secs(1_000_000_000);

/// FNV-1a, 64-bit: content hashes in entry headers (fast, dependency-free, stable forever).
pub fn fnv64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
    })
}

/// FNV-1a, 128-bit (offset basis and prime of the FNV specification): cache keys.
pub fn fnv128(bytes: &[u8]) -> u128 {
    const PRIME: u128 = (1 << 88) + (1 << 8) + 0x3b;
    bytes
        .iter()
        .fold(0x6c62_272e_07bb_0142_62b8_2175_6295_c58d, |h, &b| {
            (h ^ b as u128).wrapping_mul(PRIME)
        })
}

/// The cache key of a spec: 32 hex digits, all 128 bits of one hash.
pub fn key(spec: &TextureSpec) -> String {
    let canon = format!("v{ALGORITHM_VERSION};{}", spec.canonical());
    format!("{:032x}", fnv128(canon.as_bytes()))
}

/// Where an entry came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// Read from the cache.
    Hit,
    /// Generated now.
    Generated,
}

/// A texture and its cache entry.
#[derive(Clone, Debug)]
pub struct Entry {
    /// The texture.
    pub texture: Texture,
    /// The entry file (texture bytes at offset [`HEADER`]); `None` when no directory could
    /// store a generated texture.
    pub path: Option<PathBuf>,
    /// Hit or generated.
    pub source: Source,
    /// Seconds spent generating (0 for a hit).
    pub seconds: f64,
}

/// A cache directory and its policy.
#[derive(Clone, Debug)]
pub struct Cache {
    /// The directory entries live in.
    pub dir: PathBuf,
    /// Where a miss goes when `dir` cannot be written.
    pub fallback: Option<PathBuf>,
    /// Whether a missing entry is an error.
    pub offline: bool,
    /// Warnings met (corrupt entries, fallbacks), for the caller to show.
    pub warnings: Vec<Warning>,
}

/// What the cache location depends on; [`Locator::resolve`] applies the documented order.
#[derive(Clone, Debug, Default)]
pub struct Locator {
    /// A directory chosen in code (`Bake::cache_dir`, `--cache-dir`).
    pub explicit: Option<PathBuf>,
    /// The spec file whose top-level `cache_dir` applies, and that value.
    pub spec_cache_dir: Option<(PathBuf, String)>,
    /// A build script's `OUT_DIR` (finds the target directory; the fallback lives there).
    pub out_dir: Option<PathBuf>,
    /// The crate's manifest directory (finds the workspace root).
    pub manifest_dir: Option<PathBuf>,
}

fn env_on(name: &str) -> bool {
    std::env::var(name).is_ok_and(|v| !v.is_empty() && v != "0" && v != "false")
}

/// The outermost directory at or above `dir` holding a `Cargo.lock`: the workspace root.
pub fn workspace_root(dir: &Path) -> Option<PathBuf> {
    dir.ancestors()
        .filter(|d| d.join("Cargo.lock").is_file())
        .last()
        .map(Path::to_path_buf)
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
    let mut p = out.to_path_buf();
    while let Some(parent) = p.parent() {
        if p.file_name().is_some_and(|n| n == "build") {
            let up = parent.parent()?;
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

/// The directory a spec file lies in. A bare file name (`"noise.toml"`, as build scripts
/// write it) has the empty path as its parent, which names no directory: it means `.`.
fn spec_dir(file: &Path) -> PathBuf {
    match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Joins a spec file's `cache_dir` to the file's directory, refusing absolute paths and `..`
/// after a normal component, and anything outside the workspace that holds the spec file (the
/// outermost directory above it with a `Cargo.lock`), when there is one.
fn spec_relative(file: &Path, value: &str, root: Option<&Path>) -> Result<PathBuf, &'static str> {
    let rel = Path::new(value);
    if value.is_empty() {
        return Err("is empty");
    }
    if rel.has_root() || rel.is_absolute() {
        return Err("is absolute");
    }
    let mut seen_normal = false;
    for c in rel.components() {
        match c {
            Component::ParentDir if seen_normal => return Err("has `..` after a directory name"),
            Component::ParentDir | Component::CurDir => {}
            Component::Normal(_) => seen_normal = true,
            _ => return Err("is absolute"),
        }
    }
    let base = spec_dir(file);
    let base = fs::canonicalize(&base).unwrap_or(base);
    let mut out = base.clone();
    for c in rel.components() {
        match c {
            Component::ParentDir if !out.pop() => return Err("leaves the file system root"),
            Component::Normal(n) => out.push(n),
            _ => {}
        }
    }
    if let Some(root) = root {
        let root = fs::canonicalize(root).unwrap_or_else(|_| root.to_path_buf());
        if !out.starts_with(&root) {
            return Err("leaves the workspace");
        }
    }
    Ok(out)
}

impl Locator {
    /// The locator of a build script: `OUT_DIR` and `CARGO_MANIFEST_DIR` from the environment.
    pub fn from_env() -> Self {
        Self {
            out_dir: std::env::var_os("OUT_DIR").map(PathBuf::from),
            manifest_dir: std::env::var_os("CARGO_MANIFEST_DIR").map(PathBuf::from),
            ..Self::default()
        }
    }

    /// The locator of the `noise_texture!` macro: the crate's manifest directory, and the
    /// `cache_dir` of the `noise.toml` beside its `Cargo.toml` when there is one (read without
    /// validating its textures: the build script reports those).
    pub fn for_macro() -> Self {
        let mut loc = Self::from_env();
        loc.out_dir = None;
        if let Some(file) = loc.manifest_dir.as_ref().map(|d| d.join("noise.toml"))
            && let Ok(text) = fs::read_to_string(&file)
            && let Some(dir) = crate::spec::read_cache_dir(&text)
        {
            loc.spec_cache_dir = Some((file, dir));
        }
        loc
    }

    /// The cache this locator names (see the module docs for the order).
    pub fn resolve(&self) -> Result<Cache, Error> {
        let root = self.manifest_dir.as_deref().and_then(workspace_root);
        let fallback = self
            .out_dir
            .as_ref()
            .map(|o| o.join("noisebake-cache"))
            .unwrap_or_else(|| std::env::temp_dir().join("noisebake-cache"));
        let dir = if let Some(d) = std::env::var_os("NOISEBAKE_CACHE_DIR").filter(|d| !d.is_empty())
        {
            PathBuf::from(d)
        } else if let Some(d) = &self.explicit {
            d.clone()
        } else if let Some((file, value)) = &self.spec_cache_dir {
            let ws = fs::canonicalize(spec_dir(file))
                .ok()
                .and_then(|b| workspace_root(&b));
            spec_relative(file, value, ws.as_deref()).map_err(|why| Error::CacheDir {
                file: file.clone(),
                value: value.clone(),
                why,
            })?
        } else if let Some(t) = target_dir(self.out_dir.as_deref()) {
            t.join("noisebake-cache")
        } else if let Some(r) = &root {
            r.join("target").join("noisebake-cache")
        } else {
            fallback.clone()
        };
        let fallback = (fallback != dir).then_some(fallback);
        Ok(Cache {
            dir,
            fallback,
            offline: env_on("NOISEBAKE_OFFLINE"),
            warnings: Vec::new(),
        })
    }
}

/// Why an entry file failed verification.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Corrupt {
    /// Shorter than a header, or not starting with the magic.
    NotAnEntry,
    /// An entry of another format version.
    Version(u16),
    /// The header's lengths do not add up to the file's.
    Length {
        /// The file's length.
        file: u64,
        /// What the header implies (saturated).
        header: u64,
    },
    /// Padding bytes 40–63 are not zero.
    Padding,
    /// The data or spec hash does not match.
    Hash,
    /// The entry holds another spec.
    OtherSpec,
    /// The data length is not the spec's.
    DataLength {
        /// Held.
        held: u64,
        /// Needed.
        needed: u64,
    },
}

impl std::fmt::Display for Corrupt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Corrupt::NotAnEntry => f.write_str("not a noisebake cache entry"),
            Corrupt::Version(v) => write!(f, "entry format {v}, this build reads {}", MAGIC[6]),
            Corrupt::Length { file, header } => {
                write!(f, "truncated or padded: {file} bytes, header says {header}")
            }
            Corrupt::Padding => f.write_str("header padding is not zero"),
            Corrupt::Hash => f.write_str("content hash mismatch"),
            Corrupt::OtherSpec => f.write_str("entry belongs to a different spec"),
            Corrupt::DataLength { held, needed } => {
                write!(f, "holds {held} bytes, the spec needs {needed}")
            }
        }
    }
}

/// How a read went.
enum Read {
    Absent,
    Hit(Texture),
    Bad(Warning),
}

fn read_entry(path: &Path, spec: &TextureSpec) -> Read {
    let bytes = match fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Read::Absent,
        Err(e) => {
            return Read::Bad(Warning::CorruptEntry {
                path: path.to_path_buf(),
                why: e.to_string(),
            });
        }
    };
    match decode(&bytes, spec) {
        Ok(t) => Read::Hit(t),
        Err(c) => Read::Bad(Warning::CorruptEntry {
            path: path.to_path_buf(),
            why: c.to_string(),
        }),
    }
}

impl Cache {
    /// A cache in `dir` without a fallback (offline when `NOISEBAKE_OFFLINE` is set).
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Self {
            dir: dir.into(),
            fallback: None,
            offline: env_on("NOISEBAKE_OFFLINE"),
            warnings: Vec::new(),
        }
    }

    /// The entry path of a spec in `dir`.
    pub fn path_in(dir: &Path, spec: &TextureSpec) -> PathBuf {
        dir.join(format!("{}.nbk", key(spec)))
    }

    /// The entry path of a spec.
    pub fn path(&self, spec: &TextureSpec) -> PathBuf {
        Self::path_in(&self.dir, spec)
    }

    fn dirs(&self) -> impl Iterator<Item = &PathBuf> {
        std::iter::once(&self.dir).chain(self.fallback.as_ref())
    }

    /// A verified entry from the cache or its fallback, without generating; corrupt entries
    /// are noted in [`Cache::warnings`].
    pub fn lookup(&mut self, spec: &TextureSpec) -> Option<Entry> {
        let mut found = None;
        for dir in self.dirs().cloned().collect::<Vec<_>>() {
            let path = Self::path_in(&dir, spec);
            match read_entry(&path, spec) {
                Read::Hit(texture) => {
                    // A hit in the fallback is copied into the cache directory when it can
                    // be written, so a committed cache gains every entry its builds use.
                    let path = if dir != self.dir {
                        self.promote(&texture, spec).unwrap_or(path)
                    } else {
                        tidy::record_use(&dir, &key(spec));
                        path
                    };
                    found = Some(Entry {
                        texture,
                        path: Some(path),
                        source: Source::Hit,
                        seconds: 0.0,
                    });
                    break;
                }
                Read::Absent => {}
                Read::Bad(w) if !self.warnings.contains(&w) => self.warnings.push(w),
                Read::Bad(_) => {}
            }
        }
        found
    }

    /// Writes a texture found in the fallback into the cache directory (silently nothing when
    /// that cannot be written); the entry's path there on success.
    fn promote(&self, t: &Texture, spec: &TextureSpec) -> Option<PathBuf> {
        let path = self.path(spec);
        fs::create_dir_all(&self.dir).ok()?;
        tidy::ensure_gitignore(&self.dir);
        atomic::write(&path, &encode(t, spec)).ok()?;
        if let Ok(f) = File::options().write(true).open(&path) {
            let _ = f.set_modified(SystemTime::UNIX_EPOCH + ENTRY_MTIME);
        }
        tidy::record_use(&self.dir, &key(spec));
        Some(path)
    }

    /// The texture of `spec`, from the cache or generated (once, under a lock) and stored.
    /// `progress` sees generation progress.
    pub fn get(
        &mut self,
        spec: &TextureSpec,
        progress: &mut dyn FnMut(u64, u64),
    ) -> Result<Entry, Error> {
        if let Some(e) = self.lookup(spec) {
            return Ok(e);
        }
        if self.offline {
            return Err(Error::Offline {
                name: spec.name.clone(),
                entry: self.path(spec),
                spec: spec.canonical(),
            });
        }
        let mut tried = Vec::new();
        let mut texture = None;
        for dir in self.dirs().cloned().collect::<Vec<_>>() {
            match self.store_in(&dir, spec, &mut texture, progress) {
                Ok(entry) => {
                    if let Some((from, why)) = tried.first().cloned() {
                        self.warnings.push(Warning::Fallback {
                            from,
                            to: dir.clone(),
                            why,
                        });
                    }
                    return Ok(entry);
                }
                Err(e) => tried.push((dir.clone(), e.to_string())),
            }
        }
        // No directory took it: still a texture, only uncached.
        let start = std::time::Instant::now();
        let texture = texture.unwrap_or_else(|| generate(spec, progress));
        let seconds = start.elapsed().as_secs_f64();
        self.warnings.push(Warning::NotCached {
            name: spec.name.clone(),
            why: tried
                .iter()
                .map(|(d, w)| format!("{}: {w}", d.display()))
                .collect::<Vec<_>>()
                .join("; "),
        });
        Ok(Entry {
            texture,
            path: None,
            source: Source::Generated,
            seconds,
        })
    }

    /// Generates (unless `texture` already holds it) and stores the entry in `dir` under its
    /// lock. I/O errors leave nothing behind.
    fn store_in(
        &mut self,
        dir: &Path,
        spec: &TextureSpec,
        texture: &mut Option<Texture>,
        progress: &mut dyn FnMut(u64, u64),
    ) -> io::Result<Entry> {
        fs::create_dir_all(dir)?;
        tidy::ensure_gitignore(dir);
        let key = key(spec);
        let lock = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(dir.join(format!("{key}.lock")))?;
        lock.lock()?;
        let path = Self::path_in(dir, spec);
        // Another process may have finished the entry while we waited.
        if let Read::Hit(t) = read_entry(&path, spec) {
            tidy::record_use(dir, &key);
            return Ok(Entry {
                texture: t,
                path: Some(path),
                source: Source::Hit,
                seconds: 0.0,
            });
        }
        atomic::remove_orphans(dir, &format!("{key}.nbk"));
        let start = std::time::Instant::now();
        let t = texture.get_or_insert_with(|| generate(spec, progress));
        let seconds = start.elapsed().as_secs_f64();
        atomic::write(&path, &encode(t, spec))?;
        if let Ok(f) = File::options().write(true).open(&path) {
            let _ = f.set_modified(SystemTime::UNIX_EPOCH + ENTRY_MTIME);
        }
        drop(lock);
        tidy::record_use(dir, &key);
        Ok(Entry {
            texture: t.clone(),
            path: Some(path),
            source: Source::Generated,
            seconds,
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

/// Verifies an entry's bytes against `spec` and returns its texture. Every header field is
/// checked, lengths with checked arithmetic, before any is used to slice.
pub fn decode(bytes: &[u8], spec: &TextureSpec) -> Result<Texture, Corrupt> {
    let (data, canon) = split(bytes)?;
    if canon != spec.canonical().as_bytes() {
        return Err(Corrupt::OtherSpec);
    }
    if data.len() != spec.byte_len() {
        return Err(Corrupt::DataLength {
            held: data.len() as u64,
            needed: spec.byte_len() as u64,
        });
    }
    Ok(Texture {
        name: spec.name.clone(),
        dims: spec.dims.clone(),
        format: spec.format,
        data: data.to_vec(),
    })
}

/// An entry's texel bytes and canonical spec, after checking its magic, format version,
/// padding, lengths (with checked arithmetic) and both hashes; nothing is sliced before the
/// lengths it depends on are checked.
pub(crate) fn split(bytes: &[u8]) -> Result<(&[u8], &[u8]), Corrupt> {
    if bytes.len() < HEADER || bytes[..6] != MAGIC[..6] {
        return Err(Corrupt::NotAnEntry);
    }
    if bytes[6..8] != MAGIC[6..8] {
        return Err(Corrupt::Version(u16::from_le_bytes([bytes[6], bytes[7]])));
    }
    let u = |i: usize| {
        let mut b = [0u8; 8];
        b.copy_from_slice(&bytes[i..i + 8]);
        u64::from_le_bytes(b)
    };
    let (len, hash, clen, chash) = (u(8), u(16), u(24), u(32));
    if bytes[40..HEADER].iter().any(|&b| b != 0) {
        return Err(Corrupt::Padding);
    }
    let total = (HEADER as u64)
        .checked_add(len)
        .and_then(|t| t.checked_add(clen));
    if total != Some(bytes.len() as u64) {
        return Err(Corrupt::Length {
            file: bytes.len() as u64,
            header: total.unwrap_or(u64::MAX),
        });
    }
    // Both fit in the file, so both fit in usize.
    let data_end = HEADER + len as usize;
    let data = &bytes[HEADER..data_end];
    let canon = &bytes[data_end..];
    if fnv64(data) != hash || fnv64(canon) != chash {
        return Err(Corrupt::Hash);
    }
    Ok((data, canon))
}
