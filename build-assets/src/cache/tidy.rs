//! Keeping a cache directory tidy: what is in it, whether every entry checks, and removing
//! the entries no build uses any more (`noisebake cache list | verify | prune`).
//!
//! A committed `cache_dir` collects one entry per spec ever baked. Three things make it
//! manageable without slowing a build:
//!
//! - **Last use.** A hit or a generation touches `used/<key>` (an empty file whose
//!   modification time is the last use) in the directory it served from. The entry itself is
//!   never touched: its fixed past modification time keeps Cargo from rebuilding the crates
//!   that embed it. The record costs one `open` and one `set_modified`; on a read-only cache it
//!   silently does nothing. Cargo runs a build script or a macro only when its crate
//!   recompiles, so "used since T" means "used by a build since T that baked": a cold build
//!   (CI, or after `cargo clean`) uses every entry its specs need.
//! - **Files git should not see.** The first write into a directory leaves a `.gitignore`
//!   naming the locks (`*.lock`), temporaries (`*.tmp`) and the `used/` records, so committing
//!   the directory commits its entries and nothing else.
//! - **Verification without the spec.** An entry carries its canonical spec, so its key can be
//!   recomputed: an entry whose header, lengths or hashes fail is corrupt; one whose key is not
//!   this generator's (another [`ALGORITHM_VERSION`]), or whose spec text does not read back
//!   to itself ([`crate::spec::canonical::to_spec`]: another canonical format), is stale —
//!   intact, but no build of this version reads it.

use super::Corrupt;
use super::key::key_of;
use crate::generate::ALGORITHM_VERSION;
use std::fs::{self, File};
use std::io;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// The directory of last-use records inside a cache directory.
pub const USED_DIR: &str = "used";

/// What the `.gitignore` a cache directory gets says.
pub const GITIGNORE: &str = "\
# Written by noisebake: commit the *.nbk entries; locks, temporaries and last-use records
# are local to each checkout.
*.lock
*.tmp
used/
";

/// Leaves a `.gitignore` in `dir` unless it has one (never overwrites a user's).
pub(super) fn ensure_gitignore(dir: &Path) {
    let path = dir.join(".gitignore");
    if !path.exists()
        && let Ok(mut f) = File::options().write(true).create_new(true).open(&path)
    {
        let _ = io::Write::write_all(&mut f, GITIGNORE.as_bytes());
    }
}

/// Records that the entry `key` in `dir` was used now. Failures (a read-only cache) are
/// ignored: the record only informs `prune`.
pub(super) fn record_use(dir: &Path, key: &str) {
    let used = dir.join(USED_DIR);
    let path = used.join(key);
    let open = || {
        File::options()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
    };
    let file = match open() {
        Ok(f) => f,
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            if fs::create_dir(&used).is_err() && !used.is_dir() {
                return;
            }
            match open() {
                Ok(f) => f,
                Err(_) => return,
            }
        }
        Err(_) => return,
    };
    let _ = file.set_modified(SystemTime::now());
}

/// The state of one entry file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Status {
    /// Every check passes and its key is this generator's: a build reads it.
    Valid,
    /// Intact, but keyed for another generator version: no build of this version reads it.
    Stale,
    /// It fails a check, with the reason.
    Corrupt(String),
}

/// One entry of a cache directory.
#[derive(Clone, Debug)]
pub struct Listed {
    /// The entry file.
    pub path: PathBuf,
    /// Its key (the file stem).
    pub key: String,
    /// Bytes on disk.
    pub bytes: u64,
    /// Its canonical spec, when the entry is intact enough to hold one.
    pub spec: Option<String>,
    /// The last recorded use, if any.
    pub last_use: Option<SystemTime>,
    /// Valid, stale or corrupt.
    pub status: Status,
    /// The open TAA windows its header records (0 for every texture but a `taa` mask whose
    /// bake left some open).
    pub open_windows: u64,
}

/// Checks an entry's bytes without its spec: the header, lengths and both hashes, then the key
/// recomputed from the canonical spec it holds. Returns the spec text and the status.
pub fn check(key: &str, bytes: &[u8]) -> (Option<String>, Status) {
    let canon = match super::split(bytes) {
        Ok((_, canon)) => canon,
        // Another entry format: intact for its own version, unreadable by this one.
        Err(Corrupt::Version(_)) => return (None, Status::Stale),
        Err(c) => return (None, Status::Corrupt(c.to_string())),
    };
    let Ok(canon) = std::str::from_utf8(canon) else {
        return (
            None,
            Status::Corrupt("its spec is not UTF-8 text".to_string()),
        );
    };
    let this = key_of(ALGORITHM_VERSION, canon);
    let current = || crate::spec::canonical::to_spec(canon).is_ok_and(|s| s.canonical() == canon);
    let status = if this == key {
        // Keyed for this version, but written in another canonical format (before 0.1.0):
        // no build of this version asks for that text.
        if current() {
            Status::Valid
        } else {
            Status::Stale
        }
    } else if (0..ALGORITHM_VERSION).any(|v| key_of(v, canon) == key) {
        Status::Stale
    } else {
        Status::Corrupt("its file name is not the key of the spec it holds".to_string())
    };
    (Some(canon.to_string()), status)
}

/// Every entry (`*.nbk`) of `dir`, sorted by key, each checked.
pub fn list(dir: &Path) -> io::Result<Vec<Listed>> {
    let mut out = Vec::new();
    for e in fs::read_dir(dir)? {
        let e = e?;
        let path = e.path();
        let Some(key) = path
            .file_name()
            .and_then(|n| n.to_str())
            .and_then(|n| n.strip_suffix(".nbk"))
        else {
            continue;
        };
        if !e.file_type()?.is_file() {
            continue;
        }
        let key = key.to_string();
        let bytes = fs::read(&path)?;
        let (spec, status) = check(&key, &bytes);
        let last_use = fs::metadata(dir.join(USED_DIR).join(&key))
            .and_then(|m| m.modified())
            .ok();
        out.push(Listed {
            path,
            key,
            bytes: bytes.len() as u64,
            spec,
            last_use,
            status,
            open_windows: super::open_windows(&bytes).unwrap_or(0),
        });
    }
    out.sort_by(|a, b| a.key.cmp(&b.key));
    Ok(out)
}

/// What `prune` removes.
#[derive(Clone, Copy, Debug, Default)]
pub struct Prune {
    /// Entries valid for this version whose last recorded use is before this instant (or
    /// that have no record).
    pub unused_since: Option<SystemTime>,
    /// Entries of other generator versions.
    pub stale: bool,
    /// Entries that fail verification.
    pub corrupt: bool,
    /// Only say what would go.
    pub dry_run: bool,
}

/// Why `prune` deleted nothing.
#[derive(Debug)]
pub enum PruneError {
    /// The directory could not be read.
    Read(io::Error),
    /// The directory is not writable, so nothing was deleted.
    ReadOnly(PathBuf, io::Error),
}

impl std::fmt::Display for PruneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PruneError::Read(e) => write!(f, "cannot read the cache directory: {e}"),
            PruneError::ReadOnly(d, e) => write!(
                f,
                "{} is not writable ({e}); nothing was deleted",
                d.display()
            ),
        }
    }
}

impl std::error::Error for PruneError {}

/// Removes the entries `what` selects from `dir` (and their lock and use record); returns them.
/// A directory that cannot be written is refused before anything is deleted.
pub fn prune(dir: &Path, what: Prune) -> Result<Vec<Listed>, PruneError> {
    let all = list(dir).map_err(PruneError::Read)?;
    let chosen: Vec<Listed> = all
        .into_iter()
        .filter(|e| match &e.status {
            Status::Valid => what
                .unused_since
                .is_some_and(|t| e.last_use.is_none_or(|u| u < t)),
            Status::Stale => what.stale,
            Status::Corrupt(_) => what.corrupt,
        })
        .collect();
    if what.dry_run || chosen.is_empty() {
        return Ok(chosen);
    }
    // Probe before deleting anything: a read-only directory keeps every entry.
    let probe = dir.join(format!(".prune-probe-{}.tmp", std::process::id()));
    File::options()
        .write(true)
        .create_new(true)
        .open(&probe)
        .map_err(|e| PruneError::ReadOnly(dir.to_path_buf(), e))?;
    let _ = fs::remove_file(&probe);
    for e in &chosen {
        fs::remove_file(&e.path).map_err(|err| PruneError::ReadOnly(dir.to_path_buf(), err))?;
        let _ = fs::remove_file(dir.join(format!("{}.lock", e.key)));
        let _ = fs::remove_file(dir.join(USED_DIR).join(&e.key));
    }
    Ok(chosen)
}
