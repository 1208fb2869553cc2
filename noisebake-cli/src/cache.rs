//! `noisebake cache list | verify | prune`: a committed cache directory, kept tidy (see
//! [`build_assets::cache::tidy`] for what is recorded and why it costs a build nothing).

use build_assets::cache::Locator;
use build_assets::cache::tidy::{self, Listed, Prune, Status};
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// The cache directory a command works on: `explicit`, else the one `noisebake bake
/// noise.toml` would use from `cwd` (`NOISEBAKE_CACHE_DIR`, the `cache_dir` of `cwd/noise.toml`,
/// else the workspace's `target/noisebake-cache`).
pub fn locate(explicit: Option<PathBuf>, cwd: &Path) -> Result<PathBuf, String> {
    let mut loc = Locator {
        explicit,
        manifest_dir: Some(cwd.to_path_buf()),
        ..Locator::default()
    };
    let file = cwd.join("noise.toml");
    if let Ok(text) = std::fs::read_to_string(&file)
        && let Some(d) = build_assets::spec::read_cache_dir(&text)
    {
        loc.spec_cache_dir = Some((file, d));
    }
    loc.resolve().map(|c| c.dir).map_err(|e| e.to_string())
}

/// Parses `--unused-since`: seconds since the Unix epoch (`date +%s`), or an age such as `30d`,
/// `12h`, `45m`, `90s` before `now`.
pub fn parse_since(s: &str, now: SystemTime) -> Result<SystemTime, String> {
    let bad = || {
        format!(
            "--unused-since takes seconds since 1970 (as `date +%s` prints) or an age like 30d, 12h, 45m, 90s; got `{s}`"
        )
    };
    let unit = s.chars().last().ok_or_else(bad)?;
    let scale = match unit {
        'd' => Some(86_400),
        'h' => Some(3_600),
        'm' => Some(60),
        's' => Some(1),
        _ => None,
    };
    match scale {
        Some(k) => {
            let n: u64 = s[..s.len() - 1].parse().map_err(|_| bad())?;
            let age = n.checked_mul(k).ok_or_else(bad)?;
            now.checked_sub(Duration::from_secs(age)).ok_or_else(bad)
        }
        None => {
            let secs: u64 = s.parse().map_err(|_| bad())?;
            SystemTime::UNIX_EPOCH
                .checked_add(Duration::from_secs(secs))
                .ok_or_else(bad)
        }
    }
}

fn ago(t: Option<SystemTime>, now: SystemTime) -> String {
    let Some(t) = t else {
        return "never recorded".into();
    };
    let s = now.duration_since(t).map_or(0, |d| d.as_secs());
    match s {
        0..120 => format!("{s} s ago"),
        120..7_200 => format!("{} min ago", s / 60),
        7_200..172_800 => format!("{} h ago", s / 3_600),
        _ => format!("{} days ago", s / 86_400),
    }
}

fn status(e: &Listed) -> String {
    match &e.status {
        Status::Valid if e.open_windows > 0 => {
            format!("valid, {} TAA windows open", e.open_windows)
        }
        Status::Valid => "valid".into(),
        Status::Stale => "stale (another generator version)".into(),
        Status::Corrupt(why) => format!("CORRUPT: {why}"),
    }
}

fn size(bytes: u64) -> String {
    match bytes {
        0..10_240 => format!("{bytes} B"),
        10_240..10_485_760 => format!("{:.1} KiB", bytes as f64 / 1024.0),
        _ => format!("{:.1} MiB", bytes as f64 / 1_048_576.0),
    }
}

/// `cache list`: one block per entry (key, status, size, last use, spec) and a total.
pub fn list(dir: &Path, now: SystemTime) -> Result<String, String> {
    let all = tidy::list(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut out = format!("{}: {} entries\n", dir.display(), all.len());
    for e in &all {
        out += &format!(
            "  {}  {}  {}  last used {}\n    {}\n",
            e.key,
            size(e.bytes),
            status(e),
            ago(e.last_use, now),
            e.spec.as_deref().unwrap_or("(no readable spec)")
        );
    }
    let total: u64 = all.iter().map(|e| e.bytes).sum();
    out += &format!("  total {}\n", size(total));
    Ok(out)
}

/// `cache verify`: the report, and whether every entry is intact (stale entries are intact,
/// and named with the command that removes them; a corrupt one is never deleted here).
pub fn verify(dir: &Path) -> Result<(String, bool), String> {
    let all = tidy::list(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let corrupt: Vec<&Listed> = all
        .iter()
        .filter(|e| matches!(e.status, Status::Corrupt(_)))
        .collect();
    let stale = all.iter().filter(|e| e.status == Status::Stale).count();
    let mut out = format!(
        "{}: {} entries, {} valid, {stale} stale, {} corrupt\n",
        dir.display(),
        all.len(),
        all.len() - stale - corrupt.len(),
        corrupt.len()
    );
    for e in &corrupt {
        out += &format!("  {}: {}\n", e.path.display(), status(e));
    }
    if !corrupt.is_empty() {
        out += "  a build regenerates a corrupt entry (with a warning); `noisebake cache prune --corrupt` removes them\n";
    }
    if stale > 0 {
        out += "  stale entries are read by no build of this version; `noisebake cache prune --stale` removes them\n";
    }
    Ok((out, corrupt.is_empty()))
}

/// `cache prune`: what went (or would go, with `dry_run`).
pub fn prune(dir: &Path, what: Prune) -> Result<String, String> {
    if what.unused_since.is_none() && !what.stale && !what.corrupt {
        return Err(
            "say what to prune: --unused-since TIME, --stale and/or --corrupt (see --help)".into(),
        );
    }
    let gone = tidy::prune(dir, what).map_err(|e| e.to_string())?;
    let verb = if what.dry_run {
        "would remove"
    } else {
        "removed"
    };
    let bytes: u64 = gone.iter().map(|e| e.bytes).sum();
    let mut out = format!(
        "{}: {verb} {} entries ({})\n",
        dir.display(),
        gone.len(),
        size(bytes)
    );
    for e in &gone {
        out += &format!("  {}  {}\n", e.key, status(e));
    }
    Ok(out)
}
