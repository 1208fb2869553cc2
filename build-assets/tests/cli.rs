//! The `noisebake` binary end to end: gen, bake, analyze, and its errors.

use std::process::Command;

fn noisebake(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_noisebake"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("noisebake-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn gen_writes_npy_bin_and_png_and_analyze_reads_it() {
    let d = tmp("gen");
    let npy = d.join("stbn.npy");
    let (ok, _, err) = noisebake(&[
        "gen",
        "--kind",
        "stbn",
        "--dims",
        "16x16x4",
        "--seed",
        "3",
        "--format",
        "u16",
        "--histogram",
        "slice",
        "--out",
        npy.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let bytes = std::fs::read(&npy).unwrap();
    let hlen = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!(bytes.len(), 10 + hlen + 16 * 16 * 4 * 2);
    assert!(String::from_utf8_lossy(&bytes[10..10 + hlen]).contains("'shape': (4, 16, 16)"));
    let bin = d.join("stbn.bin");
    assert!(
        noisebake(&[
            "gen",
            "--kind",
            "stbn",
            "--dims",
            "[16, 16, 4]",
            "--seed",
            "3",
            "--format",
            "u16",
            "--histogram",
            "slice",
            "--out",
            bin.to_str().unwrap()
        ])
        .0
    );
    assert_eq!(
        std::fs::read(&bin).unwrap(),
        bytes[10 + hlen..],
        "same spec, same bytes"
    );
    let png = d.join("mask.png");
    assert!(
        noisebake(&[
            "gen",
            "--kind",
            "stbn",
            "--dims",
            "8x8x3",
            "--out",
            png.to_str().unwrap()
        ])
        .0
    );
    for t in 0..3 {
        assert!(d.join(format!("mask_t{t:03}.png")).exists());
    }
    let (ok, json, err) = noisebake(&["analyze", npy.to_str().unwrap()]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["histogram_max_deviation"], 0.0);
    assert_eq!(v["spatial_lf"].as_array().unwrap().len(), 4);
    assert_eq!(v["convergence"].as_array().unwrap().len(), 3);
}

#[test]
fn bake_writes_every_texture_and_reports_errors_with_lines() {
    let d = tmp("bake");
    let spec = d.join("noise.toml");
    std::fs::write(&spec, "[[texture]]\nname = \"A\"\nkind = \"blue2d\"\ndims = [16, 16]\n\n[[texture]]\nname = \"B\"\nkind = \"white\"\ndims = [4, 4, 2]\n").unwrap();
    let (ok, out, err) = noisebake(&[
        "bake",
        spec.to_str().unwrap(),
        "--out",
        d.join("out").to_str().unwrap(),
        "--png",
    ]);
    assert!(ok, "{err}");
    assert!(out.contains('A') && out.contains('B'), "{out}");
    assert!(
        d.join("out/A.npy").exists()
            && d.join("out/A.png").exists()
            && d.join("out/B_t001.png").exists()
    );
    std::fs::write(
        &spec,
        "[[texture]]\nname = \"A\"\nkind = \"blue2d\"\ndims = [16, 16]\nsigma = 0\n",
    )
    .unwrap();
    let (ok, _, err) = noisebake(&[
        "bake",
        spec.to_str().unwrap(),
        "--out",
        d.join("out").to_str().unwrap(),
    ]);
    assert!(!ok);
    assert!(
        err.contains("noise.toml:5:9") && err.contains("`sigma`"),
        "{err}"
    );
}

#[test]
fn gen_rejects_bad_flags_clearly() {
    let (ok, _, err) = noisebake(&[
        "gen",
        "--kind",
        "stbn",
        "--dims",
        "16x0x4",
        "--out",
        "/tmp/x.npy",
    ]);
    assert!(!ok && err.contains("`dims[1]` must be at least 1"), "{err}");
    let (ok, _, err) = noisebake(&[
        "gen",
        "--kind",
        "stbn",
        "--dims",
        "8x8x4",
        "--out",
        "/tmp/x.exr",
    ]);
    assert!(!ok && err.contains("unknown output extension"), "{err}");
    let (ok, _, err) = noisebake(&["gen", "--kind", "stbn", "--dims", "8x8x4"]);
    assert!(!ok && err.contains("--out"), "{err}");
    let (ok, _, err) = noisebake(&["analyze", "/nonexistent.npy"]);
    assert!(!ok && err.contains("/nonexistent.npy"), "{err}");
}
