//! `noisebake`: bake spec files, generate single textures, analyse masks.
//!
//! ```text
//! noisebake bake SPEC.toml --out DIR [--png] [--ktx2]
//! noisebake gen --kind stbn --dims 64x64x16 [--seed 7 --format u16 --KEY VALUE ...] --out FILE.{npy,ktx2,png,bin}
//! noisebake analyze FILE.npy
//! noisebake cache list | verify | prune [--cache-dir DIR]
//! ```

use build_assets::cache::{Locator, Source};
use build_assets::export::png;
use build_assets::export::{ktx2, npy, write_atomic};
use build_assets::spec::{self, Shown, Span, Spanned, Table, TextureSpec, Value};
use build_assets::{Texture, generate};
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

#[derive(Parser)]
#[command(
    name = "noisebake",
    version,
    about = "Bake blue-noise masks and other noise textures"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Bake every texture of a spec file through the cache (the same one build scripts and the
    /// macro use) into `DIR/<name>.npy` (and PNG slices, and KTX2 array textures).
    Bake {
        /// The spec file (`[[texture]]` tables).
        spec: PathBuf,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        /// Also write each 2D slice as a PNG.
        #[arg(long)]
        png: bool,
        /// Also write `DIR/<name>.ktx2`: a KTX 2.0 array texture (one layer per time slice) to
        /// load on a GPU.
        #[arg(long)]
        ktx2: bool,
        /// The cache directory (default: NOISEBAKE_CACHE_DIR, the spec's cache_dir, else the
        /// workspace's target/noisebake-cache).
        #[arg(long)]
        cache_dir: Option<PathBuf>,
    },
    /// Generate one texture from flags: the spec keys as `--key value` (values in TOML syntax;
    /// dims also as WxHxT), written as .npy, .ktx2 (GPU array texture), .png (slices) or .bin
    /// (raw little-endian).
    #[command(allow_hyphen_values = true)]
    Gen {
        /// `--kind K --dims WxH[xT…] [--seed N] [--format F] [--KEY VALUE…] --out FILE`
        #[arg(trailing_var_arg = true, allow_hyphen_values = true, num_args = 0..)]
        args: Vec<String>,
    },
    /// Print quality metrics of a .npy mask beside white noise of the same size, with what
    /// each means and which way is better (`--json`: the raw metrics).
    Analyze {
        /// The .npy file.
        file: PathBuf,
        /// Read a trailing axis of 2–4 as channels (vector formats such as `u8x3`).
        #[arg(long, conflicts_with = "scalar")]
        channels_last: bool,
        /// Read every axis as a texture axis, even a trailing one of 2–4 entries.
        #[arg(long)]
        scalar: bool,
        /// Print the metrics as JSON instead of the table.
        #[arg(long)]
        json: bool,
    },
    /// Write a 2D point set in the unit torus as CSV (`x,y` per line).
    Points {
        /// cnj, cnj-iterative, lattice, jitter, poisson-disk or white.
        #[arg(long, default_value = "cnj")]
        method: String,
        /// About this many points.
        #[arg(long, default_value_t = 1000)]
        n: usize,
        /// Seed.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Output CSV file.
        #[arg(long)]
        out: PathBuf,
        /// Also print the quality metrics (ν_eff, ā, q).
        #[arg(long)]
        analyze: bool,
    },
    /// Write what a free sampler of the runtime returns, for checks outside this project:
    /// float32 (frames, H, W, spp, 4) in a .npy, sample `i` of frame `f` at pixel (x, y) read
    /// as its documented use reads it (`--list`: the samplers' names and their reads).
    ExportSampler {
        /// The sampler (see `--list`).
        #[arg(required_unless_present = "list")]
        name: Option<String>,
        /// Print the samplers this command knows, one a line, with how each is read.
        #[arg(long)]
        list: bool,
        /// Width x height.
        #[arg(long, default_value = "128x128")]
        dims: String,
        /// Samples per pixel per frame.
        #[arg(long, default_value_t = 4)]
        spp: u32,
        /// Frames.
        #[arg(long, default_value_t = 64)]
        frames: u32,
        /// The .npy file to write.
        #[arg(long, required_unless_present = "list")]
        out: Option<PathBuf>,
    },
    /// Search the constants of the free sampler `motion_pairs` (a rank-1 lattice per pair and
    /// frame, moved by a shift linear in the pixel and the frame) by its modelled error under a
    /// still camera, one frame and pans in every direction, against `r2_pairs`; prints each
    /// choice and its error ratios, and with `--out` and `--wgsl` writes the runtime's tables.
    /// About 5–20 s per spp on 2 cores; `--all` runs every spp from 1 to 16 (about 2 minutes).
    SearchSampler {
        /// Samples per frame to search (1 to 16).
        #[arg(long, conflicts_with = "all")]
        spp: Option<u32>,
        /// Every spp from 1 to 16.
        #[arg(long)]
        all: bool,
        /// Random shifts tried per lattice generator.
        #[arg(long, default_value_t = 65536)]
        samples: usize,
        /// Seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// With `--all`: write the table as Rust source (what
        /// `noise-runtime/src/sampler/motion_table.rs` is).
        #[arg(long, requires = "all")]
        out: Option<PathBuf>,
        /// With `--all`: replace the table in this WGSL file (between its markers; what
        /// `noise-runtime/wgsl/noisebake.wgsl` holds).
        #[arg(long, requires = "all")]
        wgsl: Option<PathBuf>,
    },
    /// A cache directory: `list` its entries (spec, size, last use), `verify` every entry
    /// (exit code 1 if any is corrupt; for CI), `prune` the ones no build uses any more.
    Cache {
        #[command(subcommand)]
        action: CacheAction,
    },
    /// The speed-against-error report. Sections: `all` (the default: `cnj`, `fast` and
    /// `stochastic`); `fast` (FAST masks against every other mask after the filters they are
    /// made for); `stochastic` (noise functions: speed against error); `cnj` (point sets, CNJ's
    /// Table 2); `bench` (bake time against size for every generator, on one and two threads,
    /// beside its estimate, and each FAST case and a sampler tile run on to the cap: about 5
    /// minutes on 2 cores); `vector` (directions: vector FAST masks against EA's and the free
    /// constructions after box 5×5 and Gaussian σ 1 × EMA); `sampler` (sampler tiles against
    /// Heitz et al. 2019's tables with `--features peers`, and the free samplers, at 1–16 spp
    /// after four filters, on the half-plane proxy); `taa` (masks under a game's TAA: the
    /// history clamped to the 3×3 neighbourhood or variance-clipped, blended at 0.1 or at
    /// Bevy's still 1/11 (0.015 with `Hdr`), dithers at several coverages and continuous integrands, a still and
    /// a moving camera: about 30 s once its bakes are cached, about 7 minutes cold); `render`
    /// (every sampler in a ray-traced room, or `--scene FILE.obj`: AO, an area light's soft
    /// shadow and a bounce at 1, 4 and 16 spp, after a Gaussian, a box and an SVGF-style
    /// à-trous, on one frame, under a 64-frame EMA with the camera still, and with it moving —
    /// a pan, a truck and dolly with parallax, and a fast pan, a yaw and a dolly that the
    /// search behind `motion_pairs` never saw — against an 8192-spp reference; about 9 minutes
    /// on 2 cores with its tiles baked cold; Heitz's tables with `--features peers`; `--full`
    /// adds 2 and 8 spp, OpenQMC's sampler and `ign_r2`, every sampler under the moving
    /// cameras and the per-pixel anchor experiment).
    Report {
        /// Which section: all, fast, stochastic, cnj, bench, vector, sampler, taa or render.
        #[arg(default_value = "all")]
        section: String,
        /// Write the stochastic-noise rows as a JSON list (`{"noise", "variant", "ns_per_eval",
        /// "rmse": {"1", "4", "16", "64"}, "bias", …}`).
        #[arg(long)]
        json: Option<PathBuf>,
        /// Directory for plots and the FAST / CNJ JSON details.
        #[arg(long, default_value = "target/noisebake-report")]
        out: PathBuf,
        /// Include the slow cases: for `fast`, FAST 128×128×32 cosine hemisphere; for
        /// `bench`, void and cluster at 2048²; for `render`, 2 and 8 spp, OpenQMC and `ign_r2`,
        /// every sampler under the moving cameras and the anchor experiment.
        #[arg(long)]
        full: bool,
        /// Run the FAST paper's own schedule against our optimiser on 64×64×16 cosine
        /// hemisphere (about 15 minutes on 2 cores).
        #[arg(long)]
        paper: bool,
        /// Time the stochastic noise on 1 024 points instead of 65 536 (seconds, not a minute;
        /// noisier timings, same error columns).
        #[arg(long)]
        quick: bool,
        /// For `render`: a Wavefront `.obj` to trace instead of the built-in room (the camera
        /// and light are placed around its bounds).
        #[arg(long)]
        scene: Option<PathBuf>,
        /// For `render`: only the samplers whose names contain one of these words
        /// (comma-separated, e.g. `--samplers motion_pairs,r2_pairs`): a quick look at a few.
        /// The goal tables compare the tiles with every peer, so they need a full run.
        #[arg(long, value_delimiter = ',')]
        samplers: Vec<String>,
        /// For `render`, `taa`, `fast`, `vector` and `cnj`: also write the results as a
        /// Markdown document stamped with the machine, date, commit and command (what
        /// `docs/measured/*.md` are).
        #[arg(long)]
        markdown: Option<PathBuf>,
    },
}

#[derive(Subcommand)]
enum CacheAction {
    /// Every entry: key, size, valid/stale/corrupt, last use, and the spec it holds.
    List {
        /// The cache directory (default: the one `noisebake bake noise.toml` uses from here).
        #[arg(long)]
        cache_dir: Option<PathBuf>,
    },
    /// Checks every entry (header, lengths, hashes, key); exits 1 if any is corrupt.
    Verify {
        /// The cache directory (default: the one `noisebake bake noise.toml` uses from here).
        #[arg(long)]
        cache_dir: Option<PathBuf>,
    },
    /// Removes entries: unused since a time, stale (another generator version), corrupt.
    /// After a full build: `T=$(date +%s); cargo clean && cargo build; noisebake cache prune
    /// --unused-since $T`.
    Prune {
        /// The cache directory (default: the one `noisebake bake noise.toml` uses from here).
        #[arg(long)]
        cache_dir: Option<PathBuf>,
        /// Remove valid entries no build has used since then: seconds since 1970 (`date
        /// +%s`), or an age such as 30d, 12h, 45m.
        #[arg(long)]
        unused_since: Option<String>,
        /// Remove entries of other generator versions.
        #[arg(long)]
        stale: bool,
        /// Remove entries that fail verification.
        #[arg(long)]
        corrupt: bool,
        /// Say what would be removed, remove nothing.
        #[arg(long)]
        dry_run: bool,
    },
}

fn cache_cmd(action: CacheAction) -> Result<(), String> {
    use noisebake_cli::cache;
    let cwd = std::env::current_dir().map_err(|e| format!("the working directory: {e}"))?;
    let now = std::time::SystemTime::now();
    match action {
        CacheAction::List { cache_dir } => {
            print!("{}", cache::list(&cache::locate(cache_dir, &cwd)?, now)?);
        }
        CacheAction::Verify { cache_dir } => {
            let (text, ok) = cache::verify(&cache::locate(cache_dir, &cwd)?)?;
            print!("{text}");
            if !ok {
                return Err("corrupt cache entries (listed above)".into());
            }
        }
        CacheAction::Prune {
            cache_dir,
            unused_since,
            stale,
            corrupt,
            dry_run,
        } => {
            let what = build_assets::cache::tidy::Prune {
                unused_since: unused_since
                    .map(|s| cache::parse_since(&s, now))
                    .transpose()?,
                stale,
                corrupt,
                dry_run,
            };
            print!("{}", cache::prune(&cache::locate(cache_dir, &cwd)?, what)?);
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Bake {
            spec,
            out,
            png,
            ktx2,
            cache_dir,
        } => bake(&spec, &out, png, ktx2, cache_dir),
        Command::Gen { args } => gen_cmd(&args),
        Command::Analyze {
            file,
            channels_last,
            scalar,
            json,
        } => analyze(&file, channels_last, scalar, json),
        Command::Points {
            method,
            n,
            seed,
            out,
            analyze,
        } => points_cmd(&method, n, seed, &out, analyze),
        Command::Cache { action } => cache_cmd(action),
        Command::ExportSampler {
            name,
            list,
            dims,
            spp,
            frames,
            out,
        } => export_sampler(name.as_deref(), list, &dims, spp, frames, out.as_deref()),
        Command::SearchSampler {
            spp,
            all,
            samples,
            seed,
            out,
            wgsl,
        } => search_sampler(spp, all, samples, seed, out.as_deref(), wgsl.as_deref()),
        Command::Report {
            section,
            json,
            out,
            full,
            paper,
            quick,
            scene,
            samplers,
            markdown,
        } => {
            if section == "render" {
                render_report(&out, scene.as_deref(), full, &samplers, markdown.as_deref())
            } else if scene.is_some() {
                Err("--scene is for `report render`".to_string())
            } else if !samplers.is_empty() {
                Err("--samplers is for `report render`".to_string())
            } else if section == "taa" {
                taa_report(&out, markdown.as_deref())
            } else if markdown.is_some() && !matches!(section.as_str(), "fast" | "vector" | "cnj") {
                Err(
                    "--markdown is for `report render`, `taa`, `fast`, `vector` and `cnj`"
                        .to_string(),
                )
            } else {
                report(
                    &section,
                    json.as_deref(),
                    &out,
                    [full, paper],
                    quick,
                    markdown.as_deref(),
                )
            }
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Fails, before any work, if `path` cannot be written: its directory is missing, the name is
/// one the file system refuses (too long, say), or it is a directory or read-only. A file that
/// did not exist is not left behind.
fn check_output_path(path: &Path) -> Result<(), String> {
    let shown = path.display();
    if path.is_dir() {
        return Err(format!("{shown}: is a directory, not a file to write"));
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        return Err(format!(
            "{shown}: the directory {} does not exist",
            dir.display()
        ));
    }
    if path.exists() {
        std::fs::OpenOptions::new()
            .append(true)
            .open(path)
            .map(drop)
            .map_err(|e| format!("{shown}: cannot be written: {e}"))
    } else {
        std::fs::File::create_new(path).map_err(|e| format!("{shown}: cannot be written: {e}"))?;
        std::fs::remove_file(path).map_err(|e| format!("{shown}: {e}"))
    }
}

/// `export-sampler`: a free sampler's values as float32 (frames, H, W, spp, 4).
fn export_sampler(
    name: Option<&str>,
    list: bool,
    dims: &str,
    spp: u32,
    frames: u32,
    out: Option<&Path>,
) -> Result<(), String> {
    use noisebake_cli::export::samplers::FREE;
    if list {
        for s in FREE {
            println!("{}", s.name);
        }
        return Ok(());
    }
    let (Some(name), Some(out)) = (name, out) else {
        return Err("say a sampler's name and --out FILE.npy (or --list)".into());
    };
    let sampler = FREE.iter().find(|s| s.name == name).ok_or_else(|| {
        let names: Vec<&str> = FREE.iter().map(|s| s.name).collect();
        format!("no free sampler `{name}`; there are {}", names.join(", "))
    })?;
    let [w, h] = match dims
        .split('x')
        .map(str::parse::<usize>)
        .collect::<Result<Vec<_>, _>>()
        .as_deref()
    {
        Ok(&[w, h]) if w > 0 && h > 0 => [w, h],
        _ => return Err(format!("--dims {dims}: expected WxH, e.g. 128x128")),
    };
    if spp == 0 || frames == 0 {
        return Err("--spp and --frames must be positive".into());
    }
    let values = (frames as u64)
        .checked_mul((w * h) as u64)
        .and_then(|v| v.checked_mul(spp as u64 * 4))
        .filter(|&v| v <= 1 << 28)
        .ok_or(format!(
            "{frames} frames of {w}x{h} at {spp} spp is over 2^28 values (1 GiB): export less"
        ))?;
    check_output_path(out)?;
    let mut data = Vec::with_capacity(values as usize);
    for f in 0..frames {
        for y in 0..h as i32 {
            for x in 0..w as i32 {
                for i in 0..spp {
                    data.extend((sampler.read)(x, y, f, i, spp));
                }
            }
        }
    }
    let shape = [frames as usize, h, w, spp as usize, 4];
    write_atomic(out, &npy::f32_array(&shape, &data))
        .map_err(|e| format!("{}: {e}", out.display()))?;
    println!(
        "{}: `{name}` ({}), float32 {shape:?}",
        out.display(),
        sampler.read_as
    );
    Ok(())
}

/// `search-sampler`: the constants of `motion_pairs`.
fn search_sampler(
    spp: Option<u32>,
    all: bool,
    samples: usize,
    seed: u64,
    out: Option<&Path>,
    wgsl: Option<&Path>,
) -> Result<(), String> {
    use noisebake_cli::motion_search as ms;
    let spps: Vec<u32> = match (spp, all) {
        (_, true) => (1..=16).collect(),
        (Some(n), false) if (1..=16).contains(&n) => vec![n],
        (Some(n), false) => return Err(format!("--spp {n}: 1 to 16")),
        (None, false) => return Err("say --spp N (1 to 16) or --all".into()),
    };
    if let Some(path) = out {
        check_output_path(path)?;
    }
    let wgsl_text = match wgsl {
        Some(path) => {
            let text =
                std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
            let (Some(a), Some(b)) = (text.find(ms::WGSL_BEGIN), text.find(ms::WGSL_END)) else {
                return Err(format!(
                    "{}: no `{}` … `{}` markers to put the table between",
                    path.display(),
                    ms::WGSL_BEGIN,
                    ms::WGSL_END
                ));
            };
            Some((path, text, a, b + ms::WGSL_END.len()))
        }
        None => None,
    };
    let budget = ms::Budget {
        samples,
        ..ms::Budget::default()
    };
    eprintln!(
        "searching {} spp value(s) on {} threads: about {} s each on 2 cores",
        spps.len(),
        rayon::current_num_threads(),
        (ms::estimate_seconds(budget) * 2.0 / rayon::current_num_threads() as f64).round()
    );
    let start = Instant::now();
    let setup = ms::Setup::new();
    let mut rows = Vec::new();
    for n in spps {
        let t = Instant::now();
        let pairs = ms::search(n, &setup, budget, seed);
        println!("spp {n} ({:.0} s):", t.elapsed().as_secs_f64());
        for (k, p) in pairs.iter().enumerate() {
            println!("  pair {k}: {}", ms::literal(p));
            for line in ms::describe(n, p, &setup) {
                println!("    {line}");
            }
        }
        rows.push(pairs);
    }
    if let Some(path) = out {
        write_atomic(path, ms::table_source(&rows).as_bytes())
            .map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    if let Some((path, text, a, b)) = wgsl_text {
        let text = format!("{}{}{}", &text[..a], ms::table_wgsl(&rows), &text[b..]);
        write_atomic(path, text.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote the table into {}", path.display());
    }
    eprintln!("{:.0} s in all", start.elapsed().as_secs_f64());
    Ok(())
}

/// Generates with a progress bar on stderr that appears once a generation has run for 2 s,
/// announced first when it is expected to take longer than that.
fn generate_with_progress(spec: &TextureSpec) -> Texture {
    if let Some(line) = build_assets::generate::estimate::announcement(spec, ANNOUNCE_SECONDS) {
        eprintln!("{line}");
    }
    with_progress(spec, |cb| generate(spec, cb))
}

/// A generation expected to take longer than this is announced with its estimate.
const ANNOUNCE_SECONDS: f64 = 2.0;

/// Runs `run` with a progress callback that shows a bar on stderr once it has run for 2 s.
fn with_progress<T>(spec: &TextureSpec, run: impl FnOnce(&mut dyn FnMut(u64, u64)) -> T) -> T {
    let start = Instant::now();
    let mut bar: Option<ProgressBar> = None;
    let mut cb = |done: u64, total: u64| {
        if bar.is_none() && start.elapsed() > Duration::from_secs(2) {
            let b = ProgressBar::new(total);
            b.set_style(
                ProgressStyle::with_template("{msg} [{bar:40}] {percent}% ({elapsed}, eta {eta})")
                    .expect("static template")
                    .progress_chars("=> "),
            );
            b.set_message(spec.name.clone());
            bar = Some(b);
        }
        if let Some(b) = &bar {
            b.set_position(done);
        }
    };
    let t = run(&mut cb);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    t
}

fn write_outputs(
    t: &Texture,
    spec: Option<&TextureSpec>,
    out: &Path,
    with_png: bool,
    npy_frames: Option<u32>,
) -> Result<(), String> {
    let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("");
    match ext {
        // A sampler tile's .npy holds its samples as the runtime returns them, for outside
        // checks; .bin and .ktx2 hold the baked keys.
        "npy" => match spec.map(|s| &s.kind) {
            Some(spec::Kind::Sampler(p)) => {
                // `--npy-frames N`: frames 0 … N − 1 as a leading axis; without it, frame 0
                // alone and no frame axis.
                let mut samples =
                    build_assets::generate::sampler::samples(t, p, npy_frames.unwrap_or(1));
                if npy_frames.is_none() {
                    samples.dims.pop();
                }
                write_atomic(out, &npy::to_npy(&samples))
                    .map_err(|e| format!("{}: {e}", out.display()))?
            }
            _ => {
                write_atomic(out, &npy::to_npy(t)).map_err(|e| format!("{}: {e}", out.display()))?
            }
        },
        "bin" => write_atomic(out, &t.data).map_err(|e| format!("{}: {e}", out.display()))?,
        "png" => {
            let dir = out.parent().unwrap_or(Path::new("."));
            let stem = out.file_stem().and_then(|s| s.to_str()).unwrap_or(&t.name);
            png::write_slices(t, dir, stem)?;
        }
        "ktx2" => write_atomic(out, &ktx2::to_ktx2(t, spec))
            .map_err(|e| format!("{}: {e}", out.display()))?,
        other => {
            return Err(format!(
                "unknown output extension `.{other}`; use .npy, .ktx2, .png or .bin"
            ));
        }
    }
    if with_png && ext != "png" {
        let dir = out.parent().unwrap_or(Path::new("."));
        png::write_slices(t, dir, &t.name)?;
    }
    Ok(())
}

fn bake(
    spec_path: &Path,
    out: &Path,
    with_png: bool,
    with_ktx2: bool,
    cache_dir: Option<PathBuf>,
) -> Result<(), String> {
    let text =
        std::fs::read_to_string(spec_path).map_err(|e| format!("{}: {e}", spec_path.display()))?;
    let file =
        spec::parse_toml(&text).map_err(|e| e.render(&spec_path.display().to_string(), &text))?;
    let spec_dir = spec_path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let locator = Locator {
        explicit: cache_dir,
        spec_cache_dir: file.cache_dir.clone().map(|d| (spec_path.to_path_buf(), d)),
        out_dir: None,
        manifest_dir: std::fs::canonicalize(spec_dir).ok(),
    };
    let mut cache = locator.resolve().map_err(|e| e.to_string())?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    for s in &file.textures {
        let entry = with_progress(s, |cb| {
            build_assets::bake::obtain(
                &mut cache,
                s,
                ANNOUNCE_SECONDS,
                &mut |line| eprintln!("{line}"),
                cb,
            )
        })
        .map_err(|e| e.to_string())?;
        for w in cache.warnings.drain(..) {
            eprintln!("warning: {w}");
        }
        let t = entry.texture;
        write_outputs(
            &t,
            Some(s),
            &out.join(format!("{}.npy", s.name)),
            with_png,
            None,
        )?;
        if with_ktx2 {
            write_outputs(
                &t,
                Some(s),
                &out.join(format!("{}.ktx2", s.name)),
                false,
                None,
            )?;
        }
        let how = match entry.source {
            Source::Hit => "cached".to_string(),
            Source::Generated => format!("{:.3} s", entry.seconds),
        };
        println!(
            "{:<24} {:<14} {:>10} bytes  {how:>9}",
            s.name,
            format!("{}{:?}", s.kind.name(), s.dims),
            t.data.len(),
        );
    }
    println!("cache: {}", cache.dir.display());
    Ok(())
}

/// Parses `--key value` pairs into a spec table (dashes in keys become underscores).
/// What `gen` writes beside the spec: the output file and, for a sampler tile's `.npy`, how
/// many frames of samples (`--npy-frames`, an export option: it never changes the bake).
struct Export {
    out: Option<PathBuf>,
    npy_frames: Option<u32>,
}

/// Most frames `--npy-frames` writes.
const MAX_NPY_FRAMES: u32 = 4096;

fn flags_to_table(args: &[String]) -> Result<(Table, Export), String> {
    let mut table: Table = Vec::new();
    let mut out = None;
    let mut npy_frames = None;
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let key = flag
            .strip_prefix("--")
            .ok_or_else(|| format!("expected a --key, got `{}`", Shown(flag)))?
            .replace('-', "_");
        let raw = it.next().ok_or_else(|| format!("--{key} needs a value"))?;
        // `--spp --out s.npy`: the next token is a flag, not this one's value (a negative
        // number starts with one dash, never two).
        if raw.starts_with("--") {
            return Err(format!(
                "{} has no value (the next argument, `{}`, is a flag)",
                Shown(flag),
                Shown(raw)
            ));
        }
        if key == "out" {
            out = Some(PathBuf::from(raw));
            continue;
        }
        if key == "npy_frames" {
            npy_frames = Some(
                raw.parse::<u32>()
                    .ok()
                    .filter(|n| (1..=MAX_NPY_FRAMES).contains(n))
                    .ok_or_else(|| {
                        format!(
                            "--npy-frames `{}` must be a count of frames from 1 to {MAX_NPY_FRAMES}",
                            Shown(raw)
                        )
                    })?,
            );
            continue;
        }
        let value = if key == "dims" && raw.contains('x') {
            let dims = raw
                .split('x')
                .map(|d| d.parse::<i64>().map(|d| Spanned::bare(Value::Int(d))))
                .collect::<Result<Vec<_>, _>>()
                .map_err(|_| format!("--dims `{raw}` is not WxH[xT…]"))?;
            Value::Array(dims)
        } else {
            parse_value(flag, raw)?
        };
        table.push((
            Spanned::bare(key),
            Spanned {
                value,
                span: None::<Span>,
            },
        ));
    }
    Ok((table, Export { out, npy_frames }))
}

/// A flag value in TOML syntax (`1.9`, `[0, 1]`, `{ axes = [2], sigma = 1.9 }`, `true`); a word
/// that is not TOML is a bare string (`u16`, `stbn`, `slice`). A value that starts as TOML
/// does (a number, a table, an array, a quoted string) and does not parse is an error naming
/// TOML's complaint (`duplicate key`, `integer number overflowed`), not a string.
fn parse_value(flag: &str, raw: &str) -> Result<Value, String> {
    match spec::parse_value(raw) {
        Ok(v) => Ok(v),
        Err(e) if looks_like_toml(raw) => Err(format!(
            "{} `{}` is not a TOML value: {e}",
            Shown(flag),
            Shown(raw)
        )),
        Err(_) => Ok(Value::Str(raw.to_string())),
    }
}

/// Whether a flag value starts as a TOML number, table, array or quoted string does.
fn looks_like_toml(raw: &str) -> bool {
    let t = raw.trim_start();
    let mut chars = t.chars();
    match chars.next() {
        Some('{' | '[' | '"' | '\'') => true,
        Some(c) if c.is_ascii_digit() => true,
        Some('+' | '-' | '.') => chars.next().is_some_and(|c| c.is_ascii_digit()),
        _ => false,
    }
}

fn gen_cmd(args: &[String]) -> Result<(), String> {
    let (table, Export { out, npy_frames }) = flags_to_table(args)?;
    let out = out.ok_or("gen needs --out FILE.{npy,ktx2,png,bin}")?;
    let stem = out
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("TEXTURE")
        .to_string();
    let name: String = stem
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let name = if name.starts_with(|c: char| c.is_ascii_digit()) {
        format!("_{name}")
    } else {
        name
    };
    let s = spec::from_table(&table, Some(&name)).map_err(|e| e.to_string())?;
    // Everything about the output is checked before minutes of generation: its kind, and that
    // the file (for PNG slices, the first slice) can be written there.
    match output_kind(&out, &s)? {
        "png" => {
            let dir = out.parent().unwrap_or(Path::new("."));
            if let Some(first) = png::slice_names(&stem, &s.storage_dims()).first() {
                check_output_path(&dir.join(first))?;
            }
        }
        _ => check_output_path(&out)?,
    }
    if npy_frames.is_some()
        && !(matches!(s.kind, spec::Kind::Sampler(_))
            && out.extension().is_some_and(|e| e == "npy"))
    {
        return Err(
            "--npy-frames writes a sampler tile's samples over frames: it needs --kind sampler and an --out ending in .npy".to_string(),
        );
    }
    let start = Instant::now();
    let t = generate_with_progress(&s);
    eprintln!(
        "{}: {} in {:.3} s",
        out.display(),
        s.canonical(),
        start.elapsed().as_secs_f64()
    );
    if let Some(open @ 1..) = generate::open_windows_of(&s, &t) {
        let w = build_assets::Warning::OpenWindows {
            name: s.name.clone(),
            open,
            windows: s.texels() as u64,
        };
        eprintln!("warning: {w}");
    }
    write_outputs(&t, Some(&s), &out, false, npy_frames)
}

/// The output format a path asks for, or why it cannot be written.
fn output_kind(out: &Path, s: &TextureSpec) -> Result<&'static str, String> {
    let raw = out.as_os_str().to_string_lossy();
    if raw.ends_with('/') || raw.ends_with("/.") || raw.ends_with("/..") || out.is_dir() {
        return Err(format!(
            "--out {} names a directory, not a file",
            out.display()
        ));
    }
    match out.extension().and_then(|e| e.to_str()).unwrap_or("") {
        "npy" => Ok("npy"),
        "bin" => Ok("bin"),
        "png" if !png::supported(s.format) => Err(format!(
            "PNG export of {} textures is not supported; use .npy",
            s.format
        )),
        "png" => Ok("png"),
        "ktx2" => Ok("ktx2"),
        other => Err(format!(
            "unknown output extension `.{other}`; use .npy, .ktx2, .png or .bin"
        )),
    }
}

fn analyze(file: &Path, channels_last: bool, scalar: bool, json: bool) -> Result<(), String> {
    let bytes = std::fs::read(file).map_err(|e| format!("{}: {e}", file.display()))?;
    if !channels_last && !scalar {
        // A vector mask's .npy ends in its channel axis; read as a texture axis it would be
        // analysed as a meaningless scalar mask of one more dimension.
        if let Some(c) = npy::shape(&bytes)
            .ok()
            .and_then(|s| (s.len() > 1).then(|| s[s.len() - 1]))
            .filter(|c| (2..=4).contains(c))
        {
            return Err(format!(
                "{}: the last axis has {c} entries, as a {c}-channel (vector) mask's channel axis \
                 does; pass --channels-last to analyse it as channels, or --scalar to read it as a \
                 texture axis {c} texels wide",
                file.display()
            ));
        }
    }
    let t = npy::from_npy(&bytes, "mask", channels_last)
        .map_err(|e| format!("{}: {e}", file.display()))?;
    let report = noisebake_cli::analysis::analyze(&t);
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?
        );
    } else {
        let white = noisebake_cli::analysis::white_like(&t);
        let base = noisebake_cli::analysis::analyze(&white);
        print!(
            "{}",
            noisebake_cli::analysis::explain(&file.display().to_string(), &t, &report, &base)
        );
    }
    Ok(())
}

/// `report render`: the samplers in a ray-traced scene (feature `render`, on by default).
fn render_report(
    out: &Path,
    scene: Option<&Path>,
    full: bool,
    samplers: &[String],
    markdown: Option<&Path>,
) -> Result<(), String> {
    #[cfg(feature = "render")]
    {
        use noisebake_cli::render::scene::Scene;
        use noisebake_cli::report::render;
        let scene = match scene {
            Some(p) => Scene::from_obj(p)?,
            None => Scene::room(),
        };
        for l in render::READING.lines() {
            println!("  {l}");
        }
        #[cfg(not(feature = "peers"))]
        println!(
            "  (Heitz et al. 2019's tables are measured with `--features peers`, OpenQMC's with `--features peers` and `--full`: cargo run --release -p noisebake-cli --features peers -- report render)"
        );
        let options = render::Options {
            full,
            only: samplers.to_vec(),
        };
        let r = render::run(&scene, out, options, &mut |s| println!("{s}"))?;
        if let Some(path) = markdown {
            let md = render::markdown(&r, &noisebake_cli::report::stamp::Stamp::now());
            noisebake_cli::report::stamp::write(path, &md)?;
            println!("  wrote {}", path.display());
        }
        println!(
            "  {:.0} s in all; wrote {}, {} and the render-*.png images",
            r.seconds,
            out.join("render.json").display(),
            out.join("render.png").display()
        );
        Ok(())
    }
    #[cfg(not(feature = "render"))]
    {
        let _ = (out, scene, full, samplers, markdown);
        Err("this noisebake was built without the `render` feature (the ray tracer)".to_string())
    }
}

/// `report taa`, and with `markdown` its stamped Markdown document.
fn taa_report(out: &Path, markdown: Option<&Path>) -> Result<(), String> {
    use noisebake_cli::report::stamp::{Stamp, write};
    use noisebake_cli::report::taa;
    let mut text = String::new();
    for l in taa::READING.lines() {
        println!("  {l}");
        text += &format!("  {l}\n");
    }
    let r = taa::run(out, &mut |s| println!("{s}"))?;
    for line in taa::describe(&r) {
        println!("{line}");
        text += &format!("{line}\n");
    }
    println!("  wrote {}", out.join("taa.json").display());
    if let Some(path) = markdown {
        let doc = format!(
            "{}\nMasks under a game's TAA (`noisebake report taa`); `taa.json` beside the run holds every row.\n\n```text\n{text}```\n",
            Stamp::now().header("Masks under TAA (`noisebake report taa`)")
        );
        write(path, &doc)?;
        println!("  wrote {}", path.display());
    }
    Ok(())
}

fn report(
    section: &str,
    json: Option<&Path>,
    out: &Path,
    [full, paper]: [bool; 2],
    quick: bool,
    markdown: Option<&Path>,
) -> Result<(), String> {
    let mut log = |s: &str| println!("{s}");
    let mut doc = serde_json::Map::new();
    // The tables as printed, for `--markdown`.
    let mut table: Vec<String> = Vec::new();
    let mut show = |line: String| {
        println!("{line}");
        table.push(line);
    };
    if !matches!(
        section,
        "all" | "fast" | "stochastic" | "cnj" | "bench" | "vector" | "sampler" | "taa"
    ) {
        return Err(format!(
            "unknown report section `{section}`: use fast, stochastic, cnj, all, bench, vector, sampler, taa or render"
        ));
    }
    if section == "sampler" {
        use noisebake_cli::report::sampler;
        for l in sampler::READING.lines() {
            println!("  {l}");
        }
        #[cfg(not(feature = "peers"))]
        println!(
            "  (Heitz et al. 2019's tables are measured with `--features peers`: cargo run --release -p noisebake-cli --features peers -- report sampler)"
        );
        sampler::run(out, &mut log)?;
        println!(
            "  wrote {} and {}",
            out.join("sampler.json").display(),
            out.join("sampler.png").display()
        );
        return Ok(());
    }
    if section == "vector" {
        let r = noisebake_cli::report::vector::run(out, &mut log)?;
        for line in noisebake_cli::report::vector::describe(&r) {
            show(line);
        }
        println!(
            "  wrote {} and {}",
            out.join("vector.json").display(),
            out.join("vector.png").display()
        );
        return write_report_markdown(section, &table, markdown);
    }
    if section == "bench" {
        println!(
            "bake time against size (wall seconds; estimate: what `gen` and build scripts announce, and its ratio to the time):"
        );
        let b = noisebake_cli::report::bench::run(out, full, &mut log)?;
        for line in noisebake_cli::report::bench::describe_fits(&b) {
            println!("{line}");
        }
        println!(
            "  wrote {} and {}",
            out.join("bench.json").display(),
            out.join("bench.png").display()
        );
        return Ok(());
    }
    if json.is_some() && !matches!(section, "all" | "stochastic") {
        return Err(format!(
            "--json writes the stochastic-noise rows; section `{section}` has none (use `report stochastic` or `report`)"
        ));
    }
    if matches!(section, "all" | "cnj") {
        use noisebake_cli::report::cnj;
        let rows = cnj::run();
        for line in cnj::describe(&rows) {
            show(line);
        }
        doc.insert(
            "cnj".into(),
            serde_json::to_value(&rows).map_err(|e| e.to_string())?,
        );
    }
    if matches!(section, "all" | "fast") {
        use noisebake_cli::report::fast;
        println!("FAST (filter-adapted masks):");
        let r = fast::run(out, full, paper, &mut log)?;
        for line in fast::describe(&r) {
            show(line);
        }
        doc.insert(
            "fast".into(),
            serde_json::to_value(&r).map_err(|e| e.to_string())?,
        );
    }
    let mut rows_json = None;
    if matches!(section, "all" | "stochastic") {
        use noisebake_cli::report::stochastic;
        let rows = if quick {
            stochastic::run_with(1024)
        } else {
            stochastic::run()
        };
        for line in stochastic::describe(&rows) {
            println!("{line}");
        }
        rows_json = Some(serde_json::to_value(&rows).map_err(|e| e.to_string())?);
    }
    // FAST and CNJ details go beside the plots; `--json` is the documented list of
    // speed-against-error rows of the stochastic-noise report.
    for (key, value) in &doc {
        let path = out.join(format!("{key}.json"));
        let text = serde_json::to_string_pretty(value).map_err(|e| e.to_string())?;
        write_atomic(&path, text.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    if let Some(path) = json {
        let rows = rows_json.ok_or("internal: the stochastic section did not run")?;
        let text = serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?;
        write_atomic(path, text.as_bytes()).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    write_report_markdown(section, &table, markdown)
}

/// `report fast|vector|cnj --markdown FILE`: the section's table as printed, in a stamped
/// document (what `docs/measured/fast.md`, `vector.md` and `cnj.md` are).
fn write_report_markdown(
    section: &str,
    table: &[String],
    path: Option<&Path>,
) -> Result<(), String> {
    use noisebake_cli::report::stamp::{Stamp, write};
    let Some(path) = path else {
        return Ok(());
    };
    let title = match section {
        "fast" => "FAST masks against every other mask (`noisebake report fast`)",
        "vector" => "Directions from a pair per pixel (`noisebake report vector`)",
        _ => "Point sets: curl-noise jittering against the others (`noisebake report cnj`)",
    };
    let doc = format!(
        "{}
The report's table as it prints it; the JSON beside the run holds every row.

```text
{}
```
",
        Stamp::now().header(title),
        table.join("\n")
    );
    write(path, &doc)?;
    println!("  wrote {}", path.display());
    Ok(())
}

fn points_cmd(method: &str, n: usize, seed: u64, out: &Path, analyze: bool) -> Result<(), String> {
    use noisebake_cli::points::{METHODS, Method, generate_with_progress};
    let m = Method::parse(method).ok_or_else(|| {
        format!(
            "unknown point method `{method}`; valid: {}",
            METHODS.join(", ")
        )
    })?;
    if n == 0 || n > 10_000_000 {
        return Err(format!("`--n` must be in 1..=10000000, got {n}"));
    }
    let max = noisebake_cli::analysis::points::MAX_POINTS;
    if analyze && n > max {
        return Err(format!(
            "--analyze takes at most {max} points (the periodogram costs about 100·n² operations and 32·n·√n bytes); got {n}"
        ));
    }
    let raw = out.as_os_str().to_string_lossy();
    if raw.ends_with('/') || raw.ends_with("/.") || raw.ends_with("/..") || out.is_dir() {
        return Err(format!(
            "--out {} names a directory, not a file",
            out.display()
        ));
    }
    // The file is checked before the work it would hold.
    check_output_path(out)?;
    let estimate = noisebake_cli::points::estimate_seconds(m, n);
    if estimate >= ANNOUNCE_SECONDS {
        eprintln!(
            "generating {n} `{method}` points: about {estimate:.0} s on 2 cores (a progress bar follows on a terminal)"
        );
    }
    let start = Instant::now();
    // A bar once the run has taken 2 s (`cnj-iterative` integrates 64 RK4 steps a point:
    // 10 million points take about 20 s).
    let mut bar: Option<ProgressBar> = None;
    let pts = generate_with_progress(m, n, seed, &mut |done, total| {
        if bar.is_none() && done < total && start.elapsed() > Duration::from_secs(2) {
            let b = ProgressBar::new(total);
            b.set_style(
                ProgressStyle::with_template("{msg} [{bar:40}] {percent}% ({elapsed}, eta {eta})")
                    .expect("static template")
                    .progress_chars("=> "),
            );
            b.set_message(format!("{method} points"));
            bar = Some(b);
        }
        if let Some(b) = &bar {
            b.set_position(done);
        }
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let secs = start.elapsed().as_secs_f64();
    let mut text = String::with_capacity(pts.len() * 24);
    for p in &pts {
        text += &format!("{},{}\n", p[0], p[1]);
    }
    write_atomic(out, text.as_bytes()).map_err(|e| format!("{}: {e}", out.display()))?;
    println!(
        "{}: {} points ({method}, seed {seed}) in {:.3} ms",
        out.display(),
        pts.len(),
        secs * 1e3
    );
    if analyze {
        let s = noisebake_cli::analysis::points::analyze(&pts);
        println!(
            "ν_eff {:.3} (higher is better)  anisotropy ā {:.2} (lower is better)  q {:.5} (higher is better)",
            s.nu_eff, s.anisotropy, s.q
        );
        println!(
            "one set: ν_eff varies by about ±0.3 between seeds; `noisebake report cnj` gives the mean of 20 sets and says what each number measures"
        );
    }
    Ok(())
}
