//! The cache: hits, misses, key changes, corruption, offline mode, concurrency, fallbacks, and
//! `bake()` end to end.

mod common;
use build_assets::cache::{Cache, Source};
use build_assets::{Bake, generate};
use common::spec;
use std::path::PathBuf;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("noisebake-cache-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const STBN: &str = "kind = \"stbn\"\ndims = [16, 16, 4]\nseed = 5\nformat = \"u16\"";

#[test]
fn miss_then_hit_with_identical_bytes_and_keys_follow_the_spec() {
    let dir = tmp("hit");
    let s = spec(STBN);
    let mut c = Cache::new(&dir);
    let first = c.get(&s, &mut |_, _| {}).unwrap();
    assert_eq!(first.source, Source::Generated);
    let second = Cache::new(&dir).get(&s, &mut |_, _| {}).unwrap();
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
    let good = Cache::new(&dir).get(&s, &mut |_, _| {}).unwrap();
    let path = good.path.clone();
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
        let e = c.get(&s, &mut |_, _| {}).unwrap();
        assert_eq!(e.source, Source::Generated, "{what}");
        assert_eq!(e.texture.data, good.texture.data, "{what}");
        assert!(
            c.warnings.iter().any(|w| w.contains("corrupt cache entry")),
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
    let e = c.get(&s, &mut |_, _| {}).unwrap_err();
    assert!(
        e.contains("NOISEBAKE_OFFLINE") && e.contains("not in the cache"),
        "{e}"
    );
    assert!(!c.path(&s).exists(), "nothing generated offline");
    Cache::new(&dir).get(&s, &mut |_, _| {}).unwrap();
    assert_eq!(c.get(&s, &mut |_, _| {}).unwrap().source, Source::Hit);
}

#[test]
fn eight_concurrent_bakes_generate_once_and_all_read_a_complete_entry() {
    let dir = tmp("concurrent");
    let s = spec("kind = \"stbn\"\ndims = [32, 32, 8]\nseed = 11\nformat = \"u16\"");
    let want = generate(&s, &mut |_, _| {}).data;
    let results: Vec<_> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..8)
            .map(|_| scope.spawn(|| Cache::new(&dir).get(&s, &mut |_, _| {}).unwrap()))
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
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "no temporary files left behind");
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
    assert_eq!(r.cache_dir, dir.join("out/noisebake-cache"));
    assert!(
        r.warnings.iter().any(|w| w.contains("not writable")),
        "{:?}",
        r.warnings
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
