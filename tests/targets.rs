//! Every target the runtime promises the same bits on is built and tested, not assumed:
//! - the whole `noise-runtime` test suite once more on its portable scalar path (feature
//!   `portable`), on this x86_64 machine: every non-x86 code path runs, and the pinned values
//!   and bit-for-bit comparisons must hold there too;
//! - `cargo check` of the runtime for aarch64 Linux and for a `no_std` embedded target
//!   (thumbv7em-none-eabihf, no allocator, no OS);
//! - `cargo build` for `wasm32-unknown-unknown`, where Bevy and wgpu games ship to the web, of
//!   the crates such a game compiles: the runtime and the facade (with and without its macro).
//!   The Bevy plugin builds there too (`cargo build --release --lib --target
//!   wasm32-unknown-unknown -p noisebake-bevy`), but compiling Bevy for a second target would
//!   take `.ci/run` past its time on 2 cores, so the test leaves it out.
//!
//! `.ci/run` installs the three targets (`rustup target add`); where they are missing locally the
//! cross checks say so and are skipped (in CI, with `CI` set, a missing target fails).

use std::path::PathBuf;
use std::process::Command;

fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A separate target directory, so the nested cargo never waits on the outer one's lock.
fn target_dir() -> PathBuf {
    workspace().join("target").join("targets-test")
}

fn cargo() -> Command {
    let mut c = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    c.current_dir(workspace())
        .env("CARGO_TARGET_DIR", target_dir());
    c
}

fn installed(target: &str) -> bool {
    Command::new("rustup")
        .args(["target", "list", "--installed"])
        .output()
        .is_ok_and(|o| {
            String::from_utf8_lossy(&o.stdout)
                .lines()
                .any(|l| l.trim() == target)
        })
}

#[test]
fn the_runtime_checks_for_aarch64_and_a_no_std_embedded_target() {
    for target in ["aarch64-unknown-linux-gnu", "thumbv7em-none-eabihf"] {
        if !installed(target) {
            eprintln!("SKIPPED: target {target} is not installed (rustup target add {target})");
            assert!(std::env::var_os("CI").is_none(), "CI must install {target}");
            continue;
        }
        let out = cargo()
            .args(["check", "-p", "noise-runtime", "--lib", "--target", target])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "cargo check for {target} failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn a_web_game_builds_for_wasm32() {
    let target = "wasm32-unknown-unknown";
    if !installed(target) {
        eprintln!("SKIPPED: target {target} is not installed (rustup target add {target})");
        assert!(std::env::var_os("CI").is_none(), "CI must install {target}");
        return;
    }
    for args in [
        &["-p", "noise-runtime", "-p", "noisebake"][..],
        &["-p", "noisebake", "--no-default-features"],
    ] {
        let out = cargo()
            .args(["build", "--release", "--lib", "--target", target])
            .args(args)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "cargo build {args:?} for {target} failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn the_runtime_suite_passes_on_the_portable_path() {
    let out = cargo()
        .args([
            "test",
            "--release",
            "-p",
            "noise-runtime",
            "--features",
            "portable",
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "the portable runtime suite failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let passed: usize = stdout
        .lines()
        .filter_map(|l| l.strip_prefix("test result: ok. "))
        .filter_map(|l| l.split(' ').next()?.parse::<usize>().ok())
        .sum();
    eprintln!("portable path: {passed} runtime tests passed");
    assert!(passed >= 50, "only {passed} tests ran on the portable path");
}
