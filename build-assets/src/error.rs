//! The errors and warnings of a bake, typed so callers can match on them; each displays as one
//! sentence that names the file, texture or key at fault.

use std::fmt;
use std::io;
use std::path::PathBuf;

/// Why a bake (build script, macro or CLI) failed.
#[derive(Debug)]
#[non_exhaustive]
pub enum Error {
    /// The spec file is invalid; `rendered` points at file, line and key.
    Spec {
        /// The spec file.
        file: PathBuf,
        /// The error rendered with file, line, column and the offending line.
        rendered: String,
    },
    /// A file operation failed.
    Io {
        /// What was being done (`"reading the spec"`, `"writing"` …).
        action: &'static str,
        /// The file or directory.
        path: PathBuf,
        /// The operating system's error.
        source: io::Error,
    },
    /// `NOISEBAKE_OFFLINE` is set and a texture is not in the cache.
    Offline {
        /// The texture.
        name: String,
        /// Where it was looked for.
        entry: PathBuf,
        /// Its canonical spec (what the entry would hold).
        spec: String,
    },
    /// No cache directory or fallback could hold a generated texture that has to be a file (the
    /// macro embeds the entry file itself).
    NoWritableCache {
        /// The texture.
        name: String,
        /// Every directory tried, with why it failed.
        tried: Vec<(PathBuf, String)>,
    },
    /// `cache_dir` in a spec file points outside the workspace or is absolute.
    CacheDir {
        /// The spec file.
        file: PathBuf,
        /// The value given.
        value: String,
        /// What is wrong with it.
        why: &'static str,
    },
    /// `bake()` ran outside a build script without [`crate::Bake::out_dir`].
    NoOutDir,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Spec { rendered, .. } => f.write_str(rendered),
            Error::Io {
                action,
                path,
                source,
            } => write!(f, "{action} {}: {source}", path.display()),
            Error::Offline { name, entry, spec } => write!(
                f,
                "NOISEBAKE_OFFLINE is set and texture `{name}` is not in the cache (expected {}); its spec: {spec}. Bake it once without NOISEBAKE_OFFLINE (`cargo build`, or `noisebake bake SPEC.toml --out DIR --cache-dir {}`) and commit the cache directory",
                entry.display(),
                entry
                    .parent()
                    .map_or_else(|| ".".into(), |d| d.display().to_string())
            ),
            Error::NoWritableCache { name, tried } => {
                write!(
                    f,
                    "texture `{name}` was generated but no cache directory could hold it:"
                )?;
                for (dir, why) in tried {
                    write!(f, " {}: {why};", dir.display())?;
                }
                Ok(())
            }
            Error::CacheDir { file, value, why } => write!(
                f,
                "{}: cache_dir = \"{value}\" {why}; use a path relative to the spec file inside the workspace, or NOISEBAKE_CACHE_DIR / Bake::cache_dir for any other place",
                file.display()
            ),
            Error::NoOutDir => f.write_str(
                "OUT_DIR is not set: call bake() from a build script or give Bake::out_dir",
            ),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Something a bake survived and the user should hear about (printed as `cargo:warning` by
/// build scripts and on stderr by the macro and the CLI).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Warning {
    /// An entry failed verification and was regenerated.
    CorruptEntry {
        /// The entry file.
        path: PathBuf,
        /// What failed.
        why: String,
    },
    /// The cache directory could not be written; the entry went to `to` instead.
    Fallback {
        /// The directory that failed.
        from: PathBuf,
        /// The directory used.
        to: PathBuf,
        /// Why `from` failed.
        why: String,
    },
    /// Neither the cache nor its fallback could store the entry; the bake went on without it
    /// (the next build generates it again).
    NotCached {
        /// The texture.
        name: String,
        /// Why.
        why: String,
    },
    /// A `taa` mask whose bake left some 3 × 3 windows without a low or a high value: there
    /// the history clamp acts on its dithers.
    OpenWindows {
        /// The texture.
        name: String,
        /// Open windows.
        open: u64,
        /// All windows (texels).
        windows: u64,
    },
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::CorruptEntry { path, why } => write!(
                f,
                "corrupt cache entry {} ({why}); regenerated it",
                path.display()
            ),
            Warning::Fallback { from, to, why } => write!(
                f,
                "cache directory {} cannot be written ({why}); stored the entry in {}",
                from.display(),
                to.display()
            ),
            Warning::NotCached { name, why } => write!(
                f,
                "texture `{name}` could not be cached ({why}); it is embedded all the same and will be generated again next time"
            ),
            Warning::OpenWindows {
                name,
                open,
                windows,
            } => write!(
                f,
                "texture `{name}`: {open} of {windows} TAA windows stay open (no value below the coverage, or none at or above one less it); the history clamp cuts the dither's history there. A higher `coverage` or larger slices close them"
            ),
        }
    }
}
