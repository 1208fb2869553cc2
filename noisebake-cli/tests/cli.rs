//! The `noisebake` binary end to end: gen, bake, analyze, and its errors.

mod common;
use common::noisebake;

/// A `.npy` file's header text and where its data starts.
fn npy_header(bytes: &[u8]) -> (String, usize) {
    let hlen = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    (
        String::from_utf8_lossy(&bytes[10..10 + hlen]).to_string(),
        10 + hlen,
    )
}

fn tmp(name: &str) -> std::path::PathBuf {
    common::tmp_dir("cli", name)
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
    let (header, start) = npy_header(&bytes);
    assert_eq!(bytes.len(), start + 16 * 16 * 4 * 2);
    assert!(header.contains("'shape': (4, 16, 16)"));
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
        bytes[start..],
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
    let (ok, json, err) = noisebake(&["analyze", npy.to_str().unwrap(), "--json"]);
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
    // A flag followed by a flag has no value (not "expected a --key, got `s.npy`").
    let (ok, _, err) = noisebake(&[
        "gen", "--kind", "sampler", "--dims", "8x8", "--spp", "--out", "s.npy",
    ]);
    assert!(!ok && err.contains("--spp has no value"), "{err}");
    // A value that starts as TOML and is not TOML says why, instead of "got a string".
    let (ok, _, err) = noisebake(&[
        "gen",
        "--kind",
        "fast",
        "--dims",
        "16x16x4",
        "--temporal-filter",
        "{ kind = \"taa\", coverage = 0.2, coverage = 0.3 }",
        "--out",
        "/tmp/x.npy",
    ]);
    assert!(!ok && err.contains("duplicate key"), "{err}");
    let (ok, _, err) = noisebake(&[
        "gen",
        "--kind",
        "sampler",
        "--dims",
        "8x8",
        "--spp",
        "99999999999999999999",
        "--out",
        "/tmp/x.npy",
    ]);
    assert!(
        !ok && err.contains("out of range") && !err.contains("string"),
        "{err}"
    );
    // Words stay words.
    let (ok, _, err) = noisebake(&[
        "gen",
        "--kind",
        "white",
        "--dims",
        "8x8",
        "--format",
        "u16",
        "--out",
        "/tmp/w.npy",
    ]);
    assert!(ok, "{err}");
}

#[test]
fn points_writes_csv_in_the_unit_torus_and_rejects_unknown_methods() {
    let d = tmp("points");
    let csv = d.join("p.csv");
    let (ok, out, err) = noisebake(&[
        "points",
        "--method",
        "cnj",
        "--n",
        "1000",
        "--seed",
        "3",
        "--out",
        csv.to_str().unwrap(),
        "--analyze",
    ]);
    assert!(ok, "{err}");
    assert!(out.contains("ν_eff") && out.contains("q "), "{out}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let pts: Vec<(f64, f64)> = text
        .lines()
        .map(|l| {
            let (x, y) = l.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect();
    assert!((900..=1100).contains(&pts.len()));
    assert!(
        pts.iter()
            .all(|&(x, y)| (0.0..1.0).contains(&x) && (0.0..1.0).contains(&y))
    );
    let (ok, _, err) = noisebake(&[
        "points",
        "--method",
        "sobol",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("unknown point method `sobol`") && err.contains("cnj-iterative"),
        "{err}"
    );
}

#[test]
fn report_json_is_the_documented_list_of_rows() {
    let d = tmp("report");
    let json = d.join("rows.json");
    let (ok, _, err) = noisebake(&[
        "report",
        "stochastic",
        "--quick",
        "--out",
        d.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let rows: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = rows.as_array().expect("a list of rows");
    for name in [
        "perlin2",
        "perlin3",
        "perlin4",
        "fbm3",
        "sparse_conv3",
        "fbm_sparse_conv3",
        "gabor3",
        "voronoi3",
        "worley3",
    ] {
        let det = rows
            .iter()
            .find(|r| r["noise"] == name && r["variant"] == "deterministic")
            .unwrap_or_else(|| panic!("no deterministic {name}"));
        assert!(det["ns_per_eval"].as_f64().unwrap() > 0.0);
        if name != "worley3" {
            let s = rows
                .iter()
                .find(|r| r["noise"] == name && r["variant"] == "stochastic")
                .unwrap_or_else(|| panic!("no stochastic {name}"));
            // Timed in alternating passes with the deterministic function: a finite ratio.
            let speedup = s["speedup"].as_f64().expect("a speedup");
            assert!(speedup.is_finite() && speedup > 0.0, "{name}: {speedup}");
            let rmse = &s["rmse"];
            // Averaging more ξ converges: RMSE falls roughly as 1/√k.
            let (r1, r64) = (rmse["1"].as_f64().unwrap(), rmse["64"].as_f64().unwrap());
            assert!(r64 < 0.3 * r1, "{name}: {r1} -> {r64}");
            assert!(
                s["bias"].as_f64().unwrap().abs() < 0.05 * r1.max(1e-3) + 1e-2,
                "{name}"
            );
        }
    }
    let (ok, _, err) = noisebake(&[
        "report",
        "cnj",
        "--json",
        json.to_str().unwrap(),
        "--out",
        d.to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("--json writes the stochastic-noise rows"),
        "{err}"
    );
}

/// `analyze` reads a mask beside white noise of its size and says which way is better; a
/// vector mask's channel axis is never silently read as a texture axis.
#[test]
fn analyze_explains_its_numbers_and_refuses_to_misread_vectors() {
    let d = tmp("analyze");
    let stbn = d.join("stbn.npy");
    let vec3 = d.join("vec.npy");
    for (args, out) in [
        (
            &[
                "--kind",
                "stbn",
                "--dims",
                "16x16x8",
                "--histogram",
                "slice",
            ][..],
            &stbn,
        ),
        (
            &[
                "--kind",
                "fast",
                "--dims",
                "16x16x4",
                "--sample_space",
                "hemisphere",
                "--format",
                "u8x3",
            ][..],
            &vec3,
        ),
    ] {
        let mut a = vec!["gen"];
        a.extend_from_slice(args);
        a.extend_from_slice(&["--out", out.to_str().unwrap()]);
        let (ok, _, err) = noisebake(&a);
        assert!(ok, "{err}");
    }
    let (ok, text, err) = noisebake(&["analyze", stbn.to_str().unwrap()]);
    assert!(ok, "{err}");
    for part in ["white noise", "better", "lower", "reading:", "0.00 %"] {
        assert!(text.contains(part), "{part:?} in:\n{text}");
    }
    // Blue noise's spatial low-frequency power is far below white noise's, in the same row.
    let row = text
        .lines()
        .find(|l| l.contains("spatial low-frequency"))
        .unwrap();
    let nums: Vec<f64> = row
        .split_whitespace()
        .filter_map(|w| w.parse().ok())
        .collect();
    assert!(nums.len() == 2 && nums[0] < 0.2 * nums[1], "{row}");

    let (ok, _, err) = noisebake(&["analyze", vec3.to_str().unwrap()]);
    assert!(!ok);
    assert!(
        err.contains("3 entries") && err.contains("--channels-last") && err.contains("--scalar"),
        "{err}"
    );
    let (ok, text, err) = noisebake(&["analyze", vec3.to_str().unwrap(), "--channels-last"]);
    assert!(ok, "{err}");
    assert!(text.contains("16×16×4 texels, u8x3 (channel 0"), "{text}");
    let (ok, text, err) = noisebake(&["analyze", vec3.to_str().unwrap(), "--scalar"]);
    assert!(ok, "{err}");
    assert!(text.contains("3×16×16×4 texels"), "{text}");
}

/// `cache list | verify | prune` on a committed-style cache: the spec of each entry, a
/// corrupt entry reported with its reason and a failing exit code (never deleted by
/// `verify`), then removed by `prune --corrupt`; `prune` with nothing to select says so.
#[test]
fn cache_commands_list_verify_and_prune() {
    let d = tmp("cachecmd");
    let spec = d.join("noise.toml");
    let cache = d.join("committed");
    std::fs::write(&spec, "[[texture]]\nname = \"A\"\nkind = \"blue2d\"\ndims = [16, 16]\n\n[[texture]]\nname = \"B\"\nkind = \"white\"\ndims = [4, 4, 2]\n").unwrap();
    let c = cache.to_str().unwrap();
    let (ok, _, err) = noisebake(&[
        "bake",
        spec.to_str().unwrap(),
        "--out",
        d.join("out").to_str().unwrap(),
        "--cache-dir",
        c,
    ]);
    assert!(ok, "{err}");
    let (ok, out, err) = noisebake(&["cache", "list", "--cache-dir", c]);
    assert!(ok, "{err}");
    assert!(
        out.contains("2 entries") && out.contains("kind=blue2d"),
        "{out}"
    );
    assert!(out.contains("valid") && out.contains("s ago"), "{out}");
    let (ok, out, _) = noisebake(&["cache", "verify", "--cache-dir", c]);
    assert!(ok && out.contains("2 valid, 0 stale, 0 corrupt"), "{out}");

    let entry = std::fs::read_dir(&cache)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|x| x == "nbk"))
        .unwrap();
    let mut bytes = std::fs::read(&entry).unwrap();
    bytes.truncate(bytes.len() - 1);
    std::fs::write(&entry, &bytes).unwrap();
    let (ok, out, err) = noisebake(&["cache", "verify", "--cache-dir", c]);
    assert!(!ok, "{out}");
    assert!(
        out.contains("CORRUPT: truncated") && err.contains("corrupt"),
        "{out}{err}"
    );
    assert!(entry.exists(), "verify deleted an entry");

    let (ok, _, err) = noisebake(&["cache", "prune", "--cache-dir", c]);
    assert!(!ok && err.contains("say what to prune"), "{err}");
    let (ok, _, err) = noisebake(&["cache", "prune", "--cache-dir", c, "--unused-since", "soon"]);
    assert!(!ok && err.contains("date +%s"), "{err}");
    let (ok, out, err) = noisebake(&["cache", "prune", "--cache-dir", c, "--corrupt"]);
    assert!(ok, "{err}");
    assert!(
        out.contains("removed 1 entries") && !entry.exists(),
        "{out}"
    );
    // Everything was used moments ago: an hour's cut-off keeps the rest.
    let (ok, out, _) = noisebake(&["cache", "prune", "--cache-dir", c, "--unused-since", "1h"]);
    assert!(ok && out.contains("removed 0 entries"), "{out}");
    let (ok, out, _) = noisebake(&["cache", "verify", "--cache-dir", c]);
    assert!(ok && out.contains("1 entries, 1 valid"), "{out}");
}

/// The sampler contract for outside checks: `gen --kind sampler … --out S.npy` writes the
/// samples as the runtime returns them, float32 of shape (H, W, spp, D), or (N, H, W, spp, D)
/// for frames 0 … N − 1 with `--npy-frames N` (an export option: the bake is the same), and
/// `.bin` the baked keys the runtime reads them from; the warped pair runs the lattice and
/// the `square` one Sobol, as the generated code's `sobol_pairs` says.
#[test]
fn gen_writes_a_sampler_tiles_samples_and_its_keys() {
    let d = tmp("sampler");
    let args = |out: &std::path::Path, npy_frames: Option<&str>| {
        let mut a: Vec<String> = [
            "gen",
            "--kind",
            "sampler",
            "--dims",
            "16x8",
            "--spp",
            "4",
            "--sample-dims",
            "3",
            "--sample-space",
            "[\"cosine_hemisphere\",\"square\"]",
            "--spatial-filter",
            "{kind=\"box\",size=3}",
            "--seed",
            "2",
        ]
        .map(String::from)
        .to_vec();
        if let Some(n) = npy_frames {
            a.extend(["--npy-frames".to_string(), n.to_string()]);
        }
        a.extend(["--out".to_string(), out.to_str().unwrap().to_string()]);
        a
    };
    let run = |a: Vec<String>| {
        let refs: Vec<&str> = a.iter().map(String::as_str).collect();
        let (ok, _, err) = noisebake(&refs);
        assert!(ok, "{err}");
    };
    let (npy, bin, npy3) = (d.join("s.npy"), d.join("s.bin"), d.join("s3.npy"));
    run(args(&npy, None));
    run(args(&bin, None));
    run(args(&npy3, Some("3")));
    let header = npy_header;
    let floats = |b: &[u8]| -> Vec<f32> {
        b.chunks_exact(4)
            .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect()
    };
    let bytes = std::fs::read(&npy).unwrap();
    let (h, start) = header(&bytes);
    assert!(
        h.contains("'descr': '<f4'") && h.contains("'shape': (8, 16, 4, 3)"),
        "{h}"
    );
    let samples = floats(&bytes[start..]);
    assert_eq!(samples.len(), 8 * 16 * 4 * 3);
    let keys = std::fs::read(&bin).unwrap();
    assert_eq!(keys.len(), 16 * 8 * 3 * 2, "three layers of 16-bit keys");
    let bytes3 = std::fs::read(&npy3).unwrap();
    let (h3, start3) = header(&bytes3);
    assert!(h3.contains("'shape': (3, 8, 16, 4, 3)"), "{h3}");
    let all = floats(&bytes3[start3..]);
    assert_eq!(all.len(), 3 * samples.len());
    assert_eq!(&all[..samples.len()], &samples[..], "frame 0 is the bake's");
    // Pair 0 is warped (the lattice), the lone dimension 2 is `square` (Sobol): bit 1.
    let tile: noise_runtime::SamplerTile<16, 8, 4, 3> =
        noise_runtime::SamplerTile::new(noise_runtime::Mask3::new(Vec::leak(keys)), 0b10);
    for f in 0..3u32 {
        for y in 0..8 {
            for x in 0..16 {
                for i in 0..4 {
                    for dim in 0..3 {
                        let at = (((f as usize * 8 + y) * 16 + x) * 4 + i) * 3 + dim;
                        assert_eq!(
                            all[at],
                            tile.sample(x as i32, y as i32, f, i as u32, dim as u32),
                            "frame {f} ({x}, {y}) sample {i} dimension {dim}"
                        );
                    }
                }
            }
        }
    }
}

/// The TAA mask through the command line, as the contract writes it (smaller): the
/// stored u8 values keep every 3×3 window of every slice spread over the coverage range.
#[test]
fn gen_bakes_a_fast_mask_for_taa() {
    let d = tmp("taa");
    let npy = d.join("m.npy");
    let (ok, _, err) = noisebake(&[
        "gen",
        "--kind",
        "fast",
        "--dims",
        "24x24x8",
        "--format",
        "u8",
        "--spatial-filter",
        "{kind=\"gauss\",sigma=1.3435}",
        "--temporal-filter",
        "{kind=\"taa\",alpha=0.1}",
        "--out",
        npy.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(
        err.contains("temporal_filter={kind=taa,alpha=0.1,coverage=0.2,motion=[0,0],moving=0}"),
        "{err}"
    );
    let bytes = std::fs::read(&npy).unwrap();
    let (_, start) = npy_header(&bytes);
    let v: Vec<f64> = bytes[start..].iter().map(|&q| q as f64 / 256.0).collect();
    assert_eq!(v.len(), 24 * 24 * 8);
    let open = build_assets::generate::fast::open_windows(&v, [24, 24, 8], 0.2);
    assert!(open <= 2, "{open} windows open");
    let (ok, _, err) = noisebake(&[
        "gen",
        "--kind",
        "fast",
        "--dims",
        "24x24x8",
        "--sample-space",
        "\"vec2\"",
        "--format",
        "u8x2",
        "--temporal-filter",
        "{kind=\"taa\"}",
        "--out",
        npy.to_str().unwrap(),
    ]);
    assert!(!ok);
    assert!(err.contains("is not scalar"), "{err}");
}

/// An output the file system refuses is reported before the work that would fill it: a name
/// over 255 bytes, or a directory that does not exist, for `gen` (a bake of minutes) and
/// `points` (up to minutes), and nothing is left behind.
#[test]
fn outputs_are_checked_before_the_work() {
    let d = tmp("checked");
    let long = d.join(format!("{}.npy", "n".repeat(300)));
    let missing = d.join("no/such/dir/m.npy");
    for out in [&long, &missing] {
        let started = std::time::Instant::now();
        // A FAST bake of 64×64×64 takes seconds; refused before it starts, the run ends at once.
        let (ok, _, err) = noisebake(&[
            "gen",
            "--kind",
            "fast",
            "--dims",
            "64x64x64",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(!ok, "gen wrote {}", out.display());
        assert!(
            err.contains("cannot be written") || err.contains("does not exist"),
            "{err}"
        );
        assert!(
            !err.contains("generating"),
            "gen generated before checking its output: {err}"
        );
        assert!(started.elapsed() < std::time::Duration::from_secs(2));
        let csv = out.with_extension("csv");
        let (ok, _, err) = noisebake(&["points", "--n", "100", "--out", csv.to_str().unwrap()]);
        assert!(
            !ok && (err.contains("cannot be written") || err.contains("does not exist")),
            "{err}"
        );
    }
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        0,
        "something was left behind"
    );
}

/// A long `points` run says so before it starts (a bar shows only on a terminal).
#[test]
fn long_point_runs_announce_themselves() {
    let d = tmp("announce");
    let out = d.join("p.csv");
    let (ok, _, err) = noisebake(&[
        "points",
        "--method",
        "poisson-disk",
        "--n",
        "400000",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(
        err.contains("generating 400000 `poisson-disk` points: about"),
        "{err}"
    );
    let (ok, _, err) = noisebake(&["points", "--n", "1000", "--out", out.to_str().unwrap()]);
    assert!(ok && !err.contains("generating"), "{err}");
}

/// The help says what the code does: every section `report` accepts is named in its help, and
/// every flag of `report` is described there.
#[test]
fn report_help_names_every_section_and_flag() {
    let (ok, help, err) = noisebake(&["report", "--help"]);
    assert!(ok, "{err}");
    for section in [
        "all",
        "fast",
        "stochastic",
        "cnj",
        "bench",
        "vector",
        "sampler",
        "taa",
        "render",
    ] {
        assert!(
            help.contains(&format!("`{section}`")),
            "report --help lacks `{section}`:\n{help}"
        );
        if section == "all" {
            continue;
        }
        // And the code accepts it (an unknown one is refused with the list).
        let (_, _, err) = noisebake(&["report", "nonesuch"]);
        assert!(err.contains(section), "{err}");
    }
    for flag in [
        "--json",
        "--out",
        "--full",
        "--paper",
        "--quick",
        "--scene",
        "--samplers",
        "--markdown",
    ] {
        assert!(help.contains(flag), "report --help lacks {flag}");
    }
    // The moving cameras and what `--full` adds are in the help.
    for phrase in [
        "moving",
        "--full",
        "a fast pan, a yaw and a dolly",
        "OpenQMC",
    ] {
        assert!(
            help.contains(phrase),
            "report --help lacks {phrase:?}:\n{help}"
        );
    }
}
