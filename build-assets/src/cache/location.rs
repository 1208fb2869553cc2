//! Where the cache lives: one resolver ([`Locator::resolve`]) for the build script, the macro
//! and the CLI, in the order the module docs of [`crate::cache`] give.

use super::Cache;
use crate::error::Error;
use std::fs;
use std::path::{Component, Path, PathBuf};

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

pub(crate) fn env_on(name: &str) -> bool {
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
///
/// The result is absolute. A relative `CARGO_TARGET_DIR` is relative to the directory Cargo was
/// run in, which a build script (run in its package's directory) or a proc macro cannot know:
/// then the target directory `OUT_DIR` lies in (always absolute) is used, and without one the
/// variable is taken relative to the current directory. A relative path would otherwise reach
/// `include_bytes!`, which resolves it against the source file instead.
pub fn target_dir(out_dir: Option<&Path>) -> Option<PathBuf> {
    let var = std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from);
    let base = base_target_dir(var, out_dir, &std::env::current_dir().ok()?)?;
    let outer = base
        .ancestors()
        .filter(|a| a.join("CACHEDIR.TAG").is_file())
        .last()
        .map(Path::to_path_buf);
    Some(outer.unwrap_or(base))
}

/// The target directory before the `CACHEDIR.TAG` walk: `var` (`CARGO_TARGET_DIR`) if
/// absolute; if relative, the one `out_dir` lies in, else `var` under `cwd`; without `var`, the
/// one `out_dir` lies in.
fn base_target_dir(var: Option<PathBuf>, out_dir: Option<&Path>, cwd: &Path) -> Option<PathBuf> {
    match var {
        Some(t) if t.is_absolute() => Some(t),
        Some(t) => match out_dir.and_then(profile_parent) {
            Some(p) if p.is_absolute() => Some(p),
            _ => Some(cwd.join(t)),
        },
        None => profile_parent(out_dir?),
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A relative `CARGO_TARGET_DIR` never reaches `include_bytes!` relative: it is resolved
    /// through `OUT_DIR` (absolute, inside the real target directory) or the current directory.
    #[test]
    fn relative_target_dirs_become_absolute() {
        // A target directory as Cargo leaves it: tagged, with a build script's OUT_DIR inside.
        let root = std::env::temp_dir().join(format!("nb-target-{}", std::process::id()));
        let target = root.join("target/package-verify");
        let out = target.join("debug/build/demo-1a2b/out");
        std::fs::create_dir_all(&out).unwrap();
        std::fs::write(
            target.join("CACHEDIR.TAG"),
            "Signature: 8a477f597d28d172789f06886806bc55",
        )
        .unwrap();
        let cwd = root.join("examples/demo");
        let rel = Some(PathBuf::from("target/package-verify"));
        assert_eq!(
            base_target_dir(rel.clone(), Some(&out), &cwd),
            Some(target.clone())
        );
        assert_eq!(
            base_target_dir(rel, None, &cwd),
            Some(cwd.join("target/package-verify"))
        );
        let abs = Some(PathBuf::from("/elsewhere/t"));
        assert_eq!(
            base_target_dir(abs, Some(&out), &cwd),
            Some(PathBuf::from("/elsewhere/t"))
        );
        assert_eq!(base_target_dir(None, Some(&out), &cwd), Some(target));
        assert_eq!(base_target_dir(None, None, &cwd), None);
        std::fs::remove_dir_all(&root).unwrap();
    }
}
