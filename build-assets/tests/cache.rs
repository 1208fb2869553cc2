//! The cache: hits, misses, key changes, corruption, offline mode, concurrency, fallbacks, and
//! `bake()` end to end.

use build_assets::cache::{Cache, Corrupt, Locator, Source, decode, encode};
use build_assets::{Bake, generate};
use build_assets::{Error, Warning};
use noisebake_test_support::bake::spec;
use std::path::PathBuf;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("noisebake-cache-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Names of the files in `dir` ending with any of `suffixes`.
fn files_ending(dir: &std::path::Path, suffixes: &[&str]) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| suffixes.iter().any(|s| n.ends_with(s)))
        .collect()
}

const STBN: &str = "kind = \"stbn\"\ndims = [16, 16, 4]\nseed = 5\nformat = \"u16\"";

#[test]
fn miss_then_hit_with_identical_bytes_and_keys_follow_the_spec() {
    let dir = tmp("hit");
    let s = spec(STBN);
    let mut c = Cache::new(&dir);
    let first = c
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    assert_eq!(first.source, Source::Generated);
    let second = Cache::new(&dir)
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    assert_eq!(second.source, Source::Hit);
    assert_eq!(first.texture.data, second.texture.data);
    assert_eq!(first.texture.data, generate(&s, &mut |_, _| {}).data);
    // Any change of the spec is a different entry; the name is not part of the key.
    let other_seed = spec(&STBN.replace("seed = 5", "seed = 6"));
    assert_ne!(c.path(&s), c.path(&other_seed));
    let mut renamed = s.clone();
    renamed.name = "OTHER".into();
    assert_eq!(c.path(&s), c.path(&renamed));
    // Defaults filled in: spelling out a default is the same spec.
    assert_eq!(
        c.path(&s),
        c.path(&spec(&format!(
            "{STBN}\nsigma_xy = 1.9\nhistogram = \"volume\""
        )))
    );
}

#[test]
fn truncated_flipped_and_foreign_entries_are_detected_and_regenerated() {
    let dir = tmp("corrupt");
    let s = spec(STBN);
    let good = Cache::new(&dir)
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    let path = good.path.clone().unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let mut flipped = bytes.clone();
    flipped[100] ^= 0x10;
    for (what, bad) in [
        ("truncated", bytes[..bytes.len() / 2].to_vec()),
        ("bit-flipped", flipped),
        ("foreign", b"hello, not a cache entry".to_vec()),
    ] {
        std::fs::write(&path, &bad).unwrap();
        let mut c = Cache::new(&dir);
        let e = c
            .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
            .unwrap();
        assert_eq!(e.source, Source::Generated, "{what}");
        assert_eq!(e.texture.data, good.texture.data, "{what}");
        assert!(
            c.warnings
                .iter()
                .any(|w| matches!(w, Warning::CorruptEntry { .. })),
            "{what}: {:?}",
            c.warnings
        );
        assert_eq!(
            std::fs::read(&path).unwrap(),
            bytes,
            "{what}: the entry is rewritten whole"
        );
    }
}

#[test]
fn offline_mode_errors_on_a_miss_and_serves_hits() {
    let dir = tmp("offline");
    let s = spec(STBN);
    let mut c = Cache::new(&dir);
    c.offline = true;
    let e = c
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap_err();
    assert!(matches!(e, Error::Offline { .. }), "{e}");
    let e = e.to_string();
    assert!(
        e.contains("NOISEBAKE_OFFLINE") && e.contains("not in the cache"),
        "{e}"
    );
    assert!(!c.path(&s).exists(), "nothing generated offline");
    Cache::new(&dir)
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    assert_eq!(
        c.get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
            .unwrap()
            .source,
        Source::Hit
    );
}

#[test]
fn eight_concurrent_bakes_generate_once_and_all_read_a_complete_entry() {
    let dir = tmp("concurrent");
    let s = spec("kind = \"stbn\"\ndims = [32, 32, 8]\nseed = 11\nformat = \"u16\"");
    let want = generate(&s, &mut |_, _| {}).data;
    let results: Vec<_> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..8)
            .map(|_| {
                scope.spawn(|| {
                    Cache::new(&dir)
                        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
                        .unwrap()
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(
        results
            .iter()
            .filter(|e| e.source == Source::Generated)
            .count(),
        1,
        "the generator runs once"
    );
    assert!(results.iter().all(|e| e.texture.data == want));
    assert!(
        files_ending(&dir, &[".tmp"]).is_empty(),
        "no temporary files left behind"
    );
}

#[test]
fn bake_writes_typed_items_and_a_second_bake_changes_nothing() {
    let dir = tmp("bake");
    let spec_path = dir.join("noise.toml");
    std::fs::write(&spec_path, format!("cache_dir = \"cache\"\n[[texture]]\nname = \"STBN\"\n{STBN}\n[[texture]]\nname = \"V\"\nkind = \"vac\"\ndims = [4, 4, 2, 2]\nformat = \"f32\"\n")).unwrap();
    let out = dir.join("out");
    let run = || {
        Bake::new(&spec_path)
            .out_dir(&out)
            .cargo_output(false)
            .run()
            .unwrap()
    };
    let first = run();
    assert!(first.textures.iter().all(|t| t.source == Source::Generated));
    assert_eq!(first.cache_dir, dir.join("cache"));
    let code = std::fs::read_to_string(&first.generated).unwrap();
    assert!(
        code.contains(
            "pub static STBN: ::noisebake::Mask3<u16, 16, 16, 4> = ::noisebake::Mask3::new("
        ),
        "{code}"
    );
    assert!(
        code.contains("pub static V: ::noisebake::Mask4<f32, 4, 4, 2, 2>"),
        "{code}"
    );
    assert!(
        code.contains("include_aligned!") && !code.contains("[0u8"),
        "bytes are included, never spelled out"
    );
    let stamp = std::fs::metadata(&first.generated)
        .unwrap()
        .modified()
        .unwrap();
    let second = run();
    assert!(second.textures.iter().all(|t| t.source == Source::Hit));
    assert_eq!(
        std::fs::metadata(&second.generated)
            .unwrap()
            .modified()
            .unwrap(),
        stamp,
        "a no-op bake touches nothing"
    );
}

#[test]
fn an_unwritable_cache_falls_back_to_out_dir_with_a_warning() {
    let dir = tmp("readonly");
    // A cache "directory" under a regular file can never be created (even as root).
    std::fs::write(dir.join("file"), b"x").unwrap();
    let spec_path = dir.join("noise.toml");
    std::fs::write(&spec_path, format!("[[texture]]\nname = \"S\"\n{STBN}\n")).unwrap();
    let r = Bake::new(&spec_path)
        .out_dir(dir.join("out"))
        .cache_dir(dir.join("file/cache"))
        .cargo_output(false)
        .run()
        .unwrap();
    let fallback = dir.join("out/noisebake-cache");
    assert!(
        r.warnings
            .iter()
            .any(|w| matches!(w, Warning::Fallback { to, .. } if *to == fallback)),
        "{:?}",
        r.warnings
    );
    let mut names: Vec<String> = std::fs::read_dir(&fallback)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names.len(), 4, "entry, lock, .gitignore, used/: {names:?}");
    assert!(names[0] == ".gitignore" && names[3] == "used", "{names:?}");
}

/// A read-only cache whose entries are all present serves them: nothing is generated or
/// written. (Root ignores permission bits, so the read-only state is a cache path that cannot
/// be created under, with the entries reached through the fallback's read.)
#[test]
fn hits_are_served_before_any_write_is_tried() {
    let dir = tmp("readonly_hits");
    let s = spec(STBN);
    let filled = dir.join("filled");
    Cache::new(&filled)
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    let stamp = std::fs::metadata(Cache::path_in(&filled, &s))
        .unwrap()
        .modified()
        .unwrap();
    let mut c = Cache::new(&filled);
    // Remove the lock file and make its place a directory: a write would fail here.
    let lock = filled.join(format!("{}.lock", build_assets::cache::key(&s)));
    std::fs::remove_file(&lock).unwrap();
    std::fs::create_dir(&lock).unwrap();
    let e = c
        .get_or_insert_with(&s, || -> build_assets::Texture {
            panic!("generated on a hit")
        })
        .unwrap();
    assert_eq!(e.source, Source::Hit);
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
    let after = std::fs::metadata(Cache::path_in(&filled, &s))
        .unwrap()
        .modified()
        .unwrap();
    assert_eq!(stamp, after);
}

/// A directory where the entry or its lock should be, in the cache and in the fallback: the
/// texture is still returned (uncached) with a warning, and no temporary file is left.
#[test]
fn blocked_entry_paths_cost_the_cache_not_the_build() {
    let dir = tmp("blocked");
    let s = spec(STBN);
    let (main, fb) = (dir.join("main"), dir.join("fallback"));
    for d in [&main, &fb] {
        std::fs::create_dir_all(Cache::path_in(d, &s)).unwrap();
    }
    let mut c = Cache::new(&main);
    c.fallback = Some(fb.clone());
    let e = c
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    assert_eq!(e.source, Source::Generated);
    assert!(e.path.is_none());
    assert_eq!(e.texture.data, generate(&s, &mut |_, _| {}).data);
    assert!(
        c.warnings
            .iter()
            .any(|w| matches!(w, Warning::NotCached { .. })),
        "{:?}",
        c.warnings
    );
    for d in [&main, &fb] {
        let tmps = files_ending(d, &[".tmp"]);
        assert!(tmps.is_empty(), "{}: {tmps:?}", d.display());
    }
    // With only the main entry blocked, the fallback takes it and says so.
    std::fs::remove_dir(Cache::path_in(&fb, &s)).unwrap();
    let mut c = Cache::new(&main);
    c.fallback = Some(fb.clone());
    let e = c
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    assert_eq!(e.path, Some(Cache::path_in(&fb, &s)));
    assert!(
        c.warnings
            .iter()
            .any(|w| matches!(w, Warning::Fallback { .. }))
    );
}

/// Crafted headers: every field is checked before it is trusted, with no panic.
#[test]
fn crafted_headers_are_corrupt_not_panics() {
    let s = spec(STBN);
    let t = generate(&s, &mut |_, _| {});
    let good = encode(&t.into(), &s);
    assert!(decode(&good, &s).is_ok());
    let set = |at: usize, v: u64| {
        let mut b = good.clone();
        b[at..at + 8].copy_from_slice(&v.to_le_bytes());
        b
    };
    type Case = (&'static str, Vec<u8>, fn(&Corrupt) -> bool);
    let cases: Vec<Case> = vec![
        ("data length near 2^64", set(8, u64::MAX - 10), |c| {
            matches!(c, Corrupt::Length { .. })
        }),
        ("spec length near 2^64", set(24, u64::MAX), |c| {
            matches!(c, Corrupt::Length { .. })
        }),
        (
            "lengths that wrap to the file size",
            {
                let b = set(8, u64::MAX);
                let extra = good.len() as u64 - 64 + 1;
                let mut b2 = b.clone();
                b2[24..32].copy_from_slice(&extra.to_le_bytes());
                b2
            },
            |c| matches!(c, Corrupt::Length { .. }),
        ),
        ("spec hash", set(32, 1), |c| matches!(c, Corrupt::Hash)),
        (
            "padding",
            {
                let mut b = good.clone();
                b[50] = 1;
                b
            },
            |c| matches!(c, Corrupt::Padding),
        ),
        (
            "version",
            {
                let mut b = good.clone();
                b[6] = 9;
                b
            },
            |c| matches!(c, Corrupt::Version(_)),
        ),
        ("empty", Vec::new(), |c| matches!(c, Corrupt::NotAnEntry)),
    ];
    for (what, bytes, ok) in cases {
        let e = decode(&bytes, &s).unwrap_err();
        assert!(ok(&e), "{what}: {e:?}");
    }
}

/// A writer killed mid-write leaves a temporary file; the next writer of that entry removes it.
#[test]
fn orphaned_temporaries_are_removed_by_the_next_writer() {
    let dir = tmp("orphans");
    let s = spec(STBN);
    let name = format!("{}.nbk", build_assets::cache::key(&s));
    let orphan = dir.join(format!(".{name}.deadbeef.tmp"));
    std::fs::write(&orphan, b"half").unwrap();
    Cache::new(&dir)
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    assert!(!orphan.exists());
}

/// Generated entries carry a fixed old modification time, so a crate that embeds one right
/// after generating it is not stale to Cargo (no second compile).
#[test]
fn generated_entries_are_dated_in_the_past() {
    let dir = tmp("mtime");
    let s = spec(STBN);
    let e = Cache::new(&dir)
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    let m = std::fs::metadata(e.path.unwrap())
        .unwrap()
        .modified()
        .unwrap();
    assert!(m < std::time::SystemTime::now() - std::time::Duration::from_secs(86_400 * 365));
}

/// `cache_dir` in a spec file: relative and inside the workspace; the macro reads the crate's
/// `noise.toml` to find it.
#[test]
fn spec_cache_dirs_stay_in_the_workspace_and_the_macro_finds_them() {
    let ws = tmp("ws");
    std::fs::write(ws.join("Cargo.lock"), "").unwrap();
    let krate = ws.join("game");
    std::fs::create_dir_all(&krate).unwrap();
    let file = krate.join("noise.toml");
    let loc = |v: &str| Locator {
        spec_cache_dir: Some((file.clone(), v.to_string())),
        manifest_dir: Some(krate.clone()),
        ..Locator::default()
    };
    if std::env::var_os("NOISEBAKE_CACHE_DIR").is_some() {
        eprintln!("NOISEBAKE_CACHE_DIR is set: it overrides every spec file; not checkable here");
        return;
    }
    let canon = |p: PathBuf| std::fs::canonicalize(&ws).unwrap().join(p);
    assert_eq!(
        loc("cache").resolve().unwrap().dir,
        canon("game/cache".into())
    );
    assert_eq!(
        loc("../baked").resolve().unwrap().dir,
        canon("baked".into())
    );
    for (bad, why) in [
        ("/etc/noise", "absolute"),
        ("../../outside", "leaves the workspace"),
        ("a/../../b", "`..` after"),
        ("", "empty"),
    ] {
        let e = loc(bad).resolve().unwrap_err();
        assert!(
            matches!(e, Error::CacheDir { .. }) && e.to_string().contains(why),
            "{bad}: {e}"
        );
    }
    // The macro's locator reads `cache_dir` from noise.toml beside the manifest, even when its
    // textures are invalid (the build script reports those).
    std::fs::write(&file, "cache_dir = \"committed\"\n[[texture]]\nname = 1\n").unwrap();
    let got = build_assets::spec::read_cache_dir(&std::fs::read_to_string(&file).unwrap());
    assert_eq!(got.as_deref(), Some("committed"));
}

/// The child side of the bare-file-name test: bakes `noise.toml` named as build scripts name
/// it, relative to the working directory the parent set.
#[test]
fn bare_spec_name_child() {
    let Some(out) = std::env::var_os("NOISEBAKE_BARE_TEST_OUT") else {
        return;
    };
    let report = Bake::new("noise.toml")
        .out_dir(PathBuf::from(out))
        .cargo_output(false)
        .run()
        .unwrap_or_else(|e| panic!("BAKE FAILED: {e}"));
    println!("CACHE_DIR={}", report.cache_dir.display());
}

/// `bake("noise.toml")` with a top-level `cache_dir`, exactly as the README's build script
/// writes it: the bare name's parent is the empty path, which must mean the working directory
/// (it once made every committed cache "leave the workspace").
#[test]
fn a_bare_spec_file_name_finds_its_committed_cache() {
    let ws = tmp("bare");
    std::fs::write(ws.join("Cargo.lock"), "").unwrap();
    let krate = ws.join("game");
    std::fs::create_dir_all(&krate).unwrap();
    std::fs::write(
        krate.join("noise.toml"),
        format!("cache_dir = \"noise-cache\"\n[[texture]]\nname = \"STBN\"\n{STBN}\n"),
    )
    .unwrap();
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "bare_spec_name_child", "--nocapture"])
        .current_dir(&krate)
        .env("NOISEBAKE_BARE_TEST_OUT", ws.join("out"))
        .env_remove("NOISEBAKE_CACHE_DIR")
        .env_remove("NOISEBAKE_OFFLINE")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let want = std::fs::canonicalize(&krate).unwrap().join("noise-cache");
    assert!(
        stdout.contains(&format!("CACHE_DIR={}", want.display())),
        "{stdout}"
    );
    assert_eq!(files_ending(&want, &[".nbk"]).len(), 1);
}

/// The child side of the build-script error test: `bake_or_exit` on the spec the parent names.
#[test]
fn bake_or_exit_child() {
    let Some(spec) = std::env::var_os("NOISEBAKE_EXIT_TEST_SPEC") else {
        return;
    };
    build_assets::Bake::new(PathBuf::from(spec))
        .out_dir(std::env::temp_dir())
        .cargo_output(false)
        .run_or_exit();
    println!("NOT REACHED");
}

/// A build script's failure is shown as Cargo's own errors: every line of the message as a
/// `cargo::error=` directive, no panic (so no backtrace, even with `RUST_BACKTRACE=1`), and the
/// script ends there.
#[test]
fn bake_or_exit_reports_errors_as_cargo_directives() {
    let dir = tmp("exit");
    let file = dir.join("noise.toml");
    std::fs::write(
        &file,
        "[[texture]]\nname = \"T\"\nkind = \"stbn\"\ndims = [64, 0, 16]\n",
    )
    .unwrap();
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "bake_or_exit_child", "--nocapture"])
        .env("NOISEBAKE_EXIT_TEST_SPEC", &file)
        .env("RUST_BACKTRACE", "1")
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    let directives: Vec<&str> = stdout
        .lines()
        .filter_map(|l| l.strip_prefix("cargo::error="))
        .collect();
    assert!(directives.len() >= 2, "{stdout}");
    assert!(
        directives[0].contains("noise.toml:4") && stdout.contains("`dims[1]` must be at least 1"),
        "{stdout}"
    );
    assert!(!stdout.contains("NOT REACHED"), "{stdout}");
    assert!(
        !stderr.contains("panicked") && !stderr.contains("backtrace"),
        "{stderr}"
    );
}

#[test]
fn bake_errors_name_file_line_and_key() {
    let dir = tmp("errors");
    let spec_path = dir.join("noise.toml");
    std::fs::write(
        &spec_path,
        "[[texture]]\nname = \"S\"\nkind = \"stbn\"\ndims = [16, 16, 4]\nsigma_xy = -1\n",
    )
    .unwrap();
    let e = Bake::new(&spec_path)
        .out_dir(dir.join("out"))
        .cargo_output(false)
        .run()
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("noise.toml:5:12") && e.contains("`sigma_xy`"),
        "{e}"
    );
    let e = Bake::new(dir.join("missing.toml"))
        .out_dir(dir.join("out"))
        .cargo_output(false)
        .run()
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing.toml"), "{e}");
}

#[test]
fn nested_target_dirs_share_the_outermost_tagged_cache() {
    let root = tmp("nested_target");
    let target = root.join("target");
    let nested = target.join("tests/trybuild/x86_64-unknown-linux-gnu");
    let out = nested.join("debug/build/demo-0123/out");
    std::fs::create_dir_all(&out).unwrap();
    if std::env::var_os("CARGO_TARGET_DIR").is_some() {
        // The variable decides the base; the tagged-ancestor rule is checked below through it
        // only when it is unset (as under plain `cargo test`).
        eprintln!("CARGO_TARGET_DIR is set: checking the OUT_DIR rule is not possible here");
        return;
    }
    let expect = |dir: &std::path::Path| Some(dir.to_path_buf());
    // Untagged: the directory named `target` above the profile dirs.
    let plain = target.join("debug/build/demo-0123/out");
    std::fs::create_dir_all(&plain).unwrap();
    assert_eq!(
        build_assets::cache::target_dir(Some(&plain)),
        expect(&target)
    );
    // Tagged at two levels (Cargo tags every target dir it creates): the outermost wins, so a
    // nested trybuild build reads the workspace's cache.
    let tag = "Signature: 8a477f597d28d172789f06886806bc55";
    std::fs::write(nested.join("CACHEDIR.TAG"), tag).unwrap();
    std::fs::write(target.join("CACHEDIR.TAG"), tag).unwrap();
    assert_eq!(build_assets::cache::target_dir(Some(&out)), expect(&target));
}

/// A full disk (a 256 KiB tmpfs, mounted when the tests run as root, as CI does): the entry
/// goes to the fallback with a warning, no temporary file is left on the full disk, and a
/// disk too full even for the fallback still yields the texture, uncached.
#[test]
fn a_full_disk_costs_the_cache_not_the_build() {
    let dir = tmp("full");
    let small = dir.join("small");
    std::fs::create_dir_all(&small).unwrap();
    let mounted = std::process::Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=256k", "tmpfs"])
        .arg(&small)
        .status()
        .is_ok_and(|s| s.success());
    if !mounted {
        eprintln!("SKIPPED: mounting a tmpfs needs root; the disk-full test did not run");
        assert!(
            std::env::var_os("CI").is_none(),
            "CI runs as root and must run this test"
        );
        return;
    }
    struct Unmount(PathBuf);
    impl Drop for Unmount {
        fn drop(&mut self) {
            let _ = std::process::Command::new("umount").arg(&self.0).status();
        }
    }
    let _guard = Unmount(small.clone());
    // 128×128×16 u16 = 512 KiB: more than the disk holds.
    let s = spec("kind = \"white\"\ndims = [128, 128, 16]\nseed = 1\nformat = \"u16\"");
    let fallback = dir.join("fallback");
    let mut c = Cache::new(small.join("cache"));
    c.fallback = Some(fallback.clone());
    let e = c
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    assert_eq!(e.path, Some(Cache::path_in(&fallback, &s)));
    assert_eq!(e.texture.data, generate(&s, &mut |_, _| {}).data);
    assert!(
        c.warnings
            .iter()
            .any(|w| matches!(w, Warning::Fallback { .. })),
        "{:?}",
        c.warnings
    );
    let left = files_ending(&small.join("cache"), &[".tmp", ".nbk"]);
    assert!(left.is_empty(), "left on the full disk: {left:?}");
    // Both full: still the texture, uncached, with a warning.
    let mut c = Cache::new(small.join("cache"));
    c.fallback = Some(small.join("fallback"));
    let e = c
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    assert!(e.path.is_none());
    assert_eq!(e.texture.data.len(), s.byte_len());
    assert!(
        c.warnings
            .iter()
            .any(|w| matches!(w, Warning::NotCached { .. }))
    );
}

/// The child side of the kill test: bakes into the directory the parent names, then idles.
#[test]
fn kill_test_child() {
    let Some(dir) = std::env::var_os("NOISEBAKE_KILL_TEST_DIR") else {
        return;
    };
    let s = spec(KILL_SPEC);
    Cache::new(PathBuf::from(dir))
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
}

const KILL_SPEC: &str = "kind = \"stbn\"\ndims = [64, 64, 64]\nseed = 3\nformat = \"f32\"";

/// kill -9 at spread-out moments of a bake (generation, write, rename): afterwards the cache
/// never serves a corrupt entry, the next bake leaves no temporary file, and no lock is stale.
#[test]
fn kill_9_mid_bake_leaves_nothing_wrong() {
    let dir = tmp("kill");
    let s = spec(KILL_SPEC);
    let want = generate(&s, &mut |_, _| {}).data;
    let start = std::time::Instant::now();
    Cache::new(dir.join("timing"))
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    let full = start.elapsed();
    for round in 0..6u32 {
        let d = dir.join(format!("r{round}"));
        let mut child = std::process::Command::new(std::env::current_exe().unwrap())
            .args([
                "--exact",
                "kill_test_child",
                "--nocapture",
                "--test-threads",
                "1",
            ])
            .env("NOISEBAKE_KILL_TEST_DIR", &d)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        // From early in the generation to past its end.
        std::thread::sleep(full.mul_f64(0.3 + 0.25 * round as f64));
        let _ = child.kill();
        let _ = child.wait();
        let mut c = Cache::new(&d);
        let e = c
            .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
            .unwrap();
        assert_eq!(e.texture.data, want, "round {round}");
        let tmps = files_ending(&d, &[".tmp"]);
        assert!(tmps.is_empty(), "round {round}: {tmps:?}");
    }
}

/// A written cache directory ignores its locks, temporaries and use records for git; hits and
/// generations record their last use in `used/<key>`, never touching the entry itself.
#[test]
fn writes_leave_a_gitignore_and_hits_record_their_use() {
    use build_assets::cache::tidy;
    let dir = tmp("tidy");
    let s = spec(STBN);
    let key = build_assets::cache::key(&s);
    Cache::new(&dir)
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    let ignore = std::fs::read_to_string(dir.join(".gitignore")).unwrap();
    for pat in ["*.lock", "*.tmp", "used/"] {
        assert!(ignore.lines().any(|l| l == pat), "{ignore}");
    }
    // A user's own .gitignore is never overwritten.
    std::fs::write(dir.join(".gitignore"), "mine\n").unwrap();
    let used = dir.join(tidy::USED_DIR).join(&key);
    let old = std::time::SystemTime::UNIX_EPOCH + std::time::Duration::from_secs(1_500_000_000);
    std::fs::File::options()
        .write(true)
        .open(&used)
        .unwrap()
        .set_modified(old)
        .unwrap();
    let entry_time = std::fs::metadata(Cache::path_in(&dir, &s))
        .unwrap()
        .modified()
        .unwrap();
    let e = Cache::new(&dir)
        .get_or_insert_with(&s, || -> build_assets::Texture { panic!("a hit") })
        .unwrap();
    assert_eq!(e.source, Source::Hit);
    let t = std::fs::metadata(&used).unwrap().modified().unwrap();
    assert!(t > old, "the hit was not recorded");
    assert_eq!(
        std::fs::metadata(Cache::path_in(&dir, &s))
            .unwrap()
            .modified()
            .unwrap(),
        entry_time
    );
    assert_eq!(
        std::fs::read_to_string(dir.join(".gitignore")).unwrap(),
        "mine\n"
    );
}

/// `tidy::list` checks entries without their specs: valid, stale (keyed for an older
/// generator) and corrupt, each named; `prune` removes what it is told to and refuses a
/// directory it cannot write before deleting anything.
#[test]
fn tidy_lists_verifies_and_prunes() {
    use build_assets::cache::tidy::{self, Prune, Status};
    let dir = tmp("prune");
    let (a, b) = (
        spec(STBN),
        spec("kind = \"white\"\ndims = [8, 8]\nseed = 2"),
    );
    let mut c = Cache::new(&dir);
    c.get_or_insert_with(&a, || generate(&a, &mut |_, _| {}))
        .unwrap();
    c.get_or_insert_with(&b, || generate(&b, &mut |_, _| {}))
        .unwrap();
    // A stale entry: a's bytes under the key an older generator version gave its spec.
    let old_key = format!(
        "{:032x}",
        build_assets::cache::fnv128(
            format!("v{};{}", build_assets::ALGORITHM_VERSION - 1, a.canonical()).as_bytes()
        )
    );
    std::fs::copy(Cache::path_in(&dir, &a), dir.join(format!("{old_key}.nbk"))).unwrap();
    // A corrupt one: b's entry with a flipped data byte.
    let bad = Cache::path_in(&dir, &b);
    let mut bytes = std::fs::read(&bad).unwrap();
    bytes[build_assets::cache::HEADER] ^= 0x40;
    std::fs::write(&bad, &bytes).unwrap();
    let listed = tidy::list(&dir).unwrap();
    assert_eq!(listed.len(), 3);
    let state = |k: &str| {
        listed
            .iter()
            .find(|e| e.key == k)
            .map(|e| e.status.clone())
            .unwrap()
    };
    assert_eq!(state(&build_assets::cache::key(&a)), Status::Valid);
    assert_eq!(state(&old_key), Status::Stale);
    assert!(
        matches!(state(&build_assets::cache::key(&b)), Status::Corrupt(w) if w.contains("hash")),
        "{listed:?}"
    );
    let valid = listed.iter().find(|e| e.status == Status::Valid).unwrap();
    assert_eq!(valid.spec.as_deref(), Some(a.canonical().as_str()));

    // Nothing is deleted where nothing can be written: the probe's place is taken.
    let probe = dir.join(format!(".prune-probe-{}.tmp", std::process::id()));
    std::fs::create_dir(&probe).unwrap();
    let all = Prune {
        unused_since: Some(std::time::SystemTime::now() + std::time::Duration::from_secs(60)),
        stale: true,
        corrupt: true,
        dry_run: false,
    };
    let e = tidy::prune(&dir, all).unwrap_err();
    assert!(e.to_string().contains("nothing was deleted"), "{e}");
    assert_eq!(tidy::list(&dir).unwrap().len(), 3);
    std::fs::remove_dir(&probe).unwrap();

    // A dry run names, a run removes: stale and corrupt first, the valid entry is kept
    // because it was used after the cut-off.
    let cut = std::time::SystemTime::now() - std::time::Duration::from_secs(3600);
    let some = Prune {
        unused_since: Some(cut),
        stale: true,
        corrupt: true,
        dry_run: true,
    };
    assert_eq!(tidy::prune(&dir, some).unwrap().len(), 2);
    assert_eq!(tidy::list(&dir).unwrap().len(), 3);
    let gone = tidy::prune(
        &dir,
        Prune {
            dry_run: false,
            ..some
        },
    )
    .unwrap();
    assert_eq!(gone.len(), 2);
    let left = tidy::list(&dir).unwrap();
    assert_eq!(left.len(), 1);
    assert_eq!(left[0].status, Status::Valid);
    // Unused since a time after its last use: it goes too.
    assert_eq!(tidy::prune(&dir, all).unwrap().len(), 1);
    assert!(tidy::list(&dir).unwrap().is_empty());
}

/// An entry found only in the fallback is copied into the cache directory when that can be
/// written: pointing a build at a new (committed) cache directory fills it with every entry
/// the build uses, even those an earlier build left in the fallback.
#[test]
fn fallback_hits_are_promoted_into_the_cache_directory() {
    let dir = tmp("promote");
    let s = spec(STBN);
    Cache::new(dir.join("fallback"))
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    let mut c = Cache::new(dir.join("committed"));
    c.fallback = Some(dir.join("fallback"));
    let e = c
        .get_or_insert_with(&s, || -> build_assets::Texture { panic!("a hit") })
        .unwrap();
    assert_eq!(e.source, Source::Hit);
    let promoted = Cache::path_in(&dir.join("committed"), &s);
    assert_eq!(e.path.as_deref(), Some(promoted.as_path()));
    assert_eq!(
        std::fs::read(&promoted).unwrap(),
        std::fs::read(Cache::path_in(&dir.join("fallback"), &s)).unwrap()
    );
}

/// An intact entry whose spec text is in another canonical format (the pre-0.1 `Debug` form),
/// under the key this version would give that text, is stale: no build asks for that text.
#[test]
fn entries_of_another_canonical_format_are_stale() {
    use build_assets::cache::{fnv64, fnv128, tidy};
    let dir = tmp("oldformat");
    let text = "kind=fast;dims=[16,16,4];seed=0;format=u8;sample_space=scalar;distribution=Uniform;spatial=Gauss { sigma: 1.3435 };temporal=Ema { alpha: 0.1, beta: 0.1 };combine=Product;iterations=None;start=ign";
    let data = vec![7u8; 16 * 16 * 4];
    let mut bytes = b"NBAKE\x00\x04\x00".to_vec();
    // The data's hash covers the open windows after it (0 here).
    let hashed: Vec<u8> = data.iter().copied().chain([0; 8]).collect();
    for v in [
        data.len() as u64,
        fnv64(&hashed),
        text.len() as u64,
        fnv64(text.as_bytes()),
    ] {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    bytes.resize(build_assets::cache::HEADER, 0);
    bytes.extend_from_slice(&data);
    bytes.extend_from_slice(text.as_bytes());
    let key = format!(
        "{:032x}",
        fnv128(format!("v{};{text}", build_assets::ALGORITHM_VERSION).as_bytes())
    );
    std::fs::write(dir.join(format!("{key}.nbk")), &bytes).unwrap();
    let (held, status) = tidy::check(&key, &bytes);
    assert_eq!(status, tidy::Status::Stale);
    assert_eq!(held.as_deref(), Some(text));
    // A current entry of the same texture is valid.
    let s = spec("kind = \"fast\"\ndims = [16, 16, 4]\niterations = 1");
    let e = Cache::new(&dir)
        .get_or_insert_with(&s, || generate(&s, &mut |_, _| {}))
        .unwrap();
    let fresh = std::fs::read(e.path.unwrap()).unwrap();
    assert_eq!(
        tidy::check(&build_assets::cache::key(&s), &fresh).1,
        tidy::Status::Valid
    );
}

/// An entry records the open TAA windows the bake counted in its header (bytes 40–47), under
/// the data's hash (entry format 4): `cache list` shows them, a hit returns them without
/// re-counting, and a header that lies about them fails the checksum.
#[test]
fn entries_record_open_taa_windows() {
    use build_assets::cache::open_windows;
    use build_assets::{Baked, bake_texture};
    let s = spec(
        "kind = \"fast\"\ndims = [16, 16, 2]\ntemporal_filter = { kind = \"taa\", coverage = 0.2 }",
    );
    // Every texel mid-grey: no window holds a low or a high value.
    let t = build_assets::Texture {
        name: s.name.clone(),
        dims: s.dims.clone(),
        format: s.format,
        data: vec![128; 16 * 16 * 2],
    };
    let counted = build_assets::generate::open_windows_of(&s, &t);
    assert_eq!(counted, Some(512));
    let baked = Baked {
        texture: t.clone(),
        open_windows: 512,
    };
    let bytes = encode(&baked, &s);
    assert_eq!(&bytes[..8], b"NBAKE\x00\x04\x00");
    assert_eq!(open_windows(&bytes), Some(512));
    assert_eq!(decode(&bytes, &s).unwrap(), baked);
    let mut lied = bytes.clone();
    lied[40] = 0;
    lied[41] = 0;
    assert_eq!(open_windows(&lied), Some(0));
    assert_eq!(decode(&lied, &s), Err(Corrupt::Hash));
    // Through the cache: the bake's count is recorded on a miss and read back on a hit.
    let dir = std::env::temp_dir().join(format!("nb-open-windows-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let made = bake_texture(&s, &mut |_, _| {});
    let want = build_assets::generate::open_windows_of(&s, &made.texture).unwrap();
    assert_eq!(made.open_windows, want);
    let miss = Cache::new(&dir)
        .get_or_insert_with(&s, || made.clone())
        .unwrap();
    assert_eq!((miss.source, miss.open_windows), (Source::Generated, want));
    let hit = Cache::new(&dir)
        .get_or_insert_with(&s, || -> Baked { panic!("generated on a hit") })
        .unwrap();
    assert_eq!((hit.source, hit.open_windows), (Source::Hit, want));
    assert_eq!(hit.texture, made.texture);
    std::fs::remove_dir_all(&dir).ok();
    // Any other kind records 0.
    let w = spec("kind = \"white\"\ndims = [8, 8]");
    let wt = generate(&w, &mut |_, _| {});
    assert_eq!(open_windows(&encode(&wt.into(), &w)), Some(0));
}

/// The cache knows entries, not generators: no file under `src/cache/` calls into
/// `generate` (the key names `ALGORITHM_VERSION`, the one thing it may take from there).
#[test]
fn the_cache_never_calls_a_generator() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/cache");
    let mut files = 0;
    for f in std::fs::read_dir(&dir).unwrap() {
        let path = f.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        files += 1;
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            for (at, _) in code.match_indices("generate::") {
                let rest = &code[at + "generate::".len()..];
                assert!(
                    rest.starts_with("ALGORITHM_VERSION"),
                    "{}:{}: the cache calls into the generators: {line}",
                    path.display(),
                    n + 1
                );
            }
            assert!(
                !code.contains("generate(") && !code.contains("open_windows_of"),
                "{}:{}: {line}",
                path.display(),
                n + 1
            );
        }
    }
    assert!(files >= 4, "read {files} files of {}", dir.display());
}
