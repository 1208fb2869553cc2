//! The content-addressed cache of generated textures, and the one place that decides where it
//! lives for every way in (build script, `noise_texture!`, CLI).
//!
//! **Key**: FNV-1a 128 of the canonical spec (every default filled in,
//! [`TextureSpec::canonical`]) and [`ALGORITHM_VERSION`](crate::ALGORITHM_VERSION); any change of either regenerates,
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

mod entry;
mod key;
mod location;
pub mod tidy;

pub use entry::{Corrupt, HEADER, decode, encode, open_windows};
pub(crate) use entry::{ENTRY_MTIME, split};
pub use key::{fnv64, fnv128, key};
use location::env_on;
pub use location::{Locator, target_dir, workspace_root};

use crate::atomic;
use crate::error::{Error, Warning};
use crate::spec::TextureSpec;
use crate::texture::{Baked, Texture};
use std::cell::LazyCell;
use std::fs::{self, File, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

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
    /// The open TAA windows the bake counted ([`Baked::open_windows`]), from the entry's header
    /// on a hit.
    pub open_windows: u64,
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

/// How a read went.
enum Read {
    Absent,
    Hit(Baked),
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
                Read::Hit(baked) => {
                    // A hit in the fallback is copied into the cache directory when it can
                    // be written, so a committed cache gains every entry its builds use.
                    let path = if dir != self.dir {
                        self.promote(&baked, spec).unwrap_or(path)
                    } else {
                        tidy::record_use(&dir, &key(spec));
                        path
                    };
                    found = Some(Entry {
                        texture: baked.texture,
                        path: Some(path),
                        source: Source::Hit,
                        seconds: 0.0,
                        open_windows: baked.open_windows,
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
    fn promote(&self, t: &Baked, spec: &TextureSpec) -> Option<PathBuf> {
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

    /// The texture of `spec`, from the cache, or made by `make` and stored. `make` runs at
    /// most once, under the entry's lock and after a last look for an entry another process
    /// finished meanwhile, so concurrent builds generate once. The cache never generates by
    /// itself: the caller passes the generation (usually `|| bake_texture(spec, progress)`,
    /// which counts what the entry records; a bare [`Texture`] records nothing more).
    pub fn get_or_insert_with<B: Into<Baked>, F: FnOnce() -> B>(
        &mut self,
        spec: &TextureSpec,
        make: F,
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
        let texture = LazyCell::new(move || make().into());
        for dir in self.dirs().cloned().collect::<Vec<_>>() {
            match self.store_in(&dir, spec, &texture) {
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
        let baked = LazyCell::force(&texture).clone();
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
            texture: baked.texture,
            path: None,
            source: Source::Generated,
            seconds,
            open_windows: baked.open_windows,
        })
    }

    /// Makes the texture (unless `texture` already has) and stores the entry in `dir` under its
    /// lock. I/O errors leave nothing behind.
    fn store_in<F: FnOnce() -> Baked>(
        &mut self,
        dir: &Path,
        spec: &TextureSpec,
        texture: &LazyCell<Baked, F>,
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
        if let Read::Hit(b) = read_entry(&path, spec) {
            tidy::record_use(dir, &key);
            return Ok(Entry {
                texture: b.texture,
                path: Some(path),
                source: Source::Hit,
                seconds: 0.0,
                open_windows: b.open_windows,
            });
        }
        atomic::remove_orphans(dir, &format!("{key}.nbk"));
        let start = std::time::Instant::now();
        let t = LazyCell::force(texture);
        let seconds = start.elapsed().as_secs_f64();
        atomic::write(&path, &encode(t, spec))?;
        if let Ok(f) = File::options().write(true).open(&path) {
            let _ = f.set_modified(SystemTime::UNIX_EPOCH + ENTRY_MTIME);
        }
        drop(lock);
        tidy::record_use(dir, &key);
        Ok(Entry {
            texture: t.texture.clone(),
            path: Some(path),
            source: Source::Generated,
            seconds,
            open_windows: t.open_windows,
        })
    }
}
