//! `bake()`: the build-script way in. Reads a spec file, fetches or generates every texture
//! through the cache, and writes one Rust file into `OUT_DIR` for `noisebake::include_textures!()`.

use crate::cache::{Cache, Entry, Locator, Source};
use crate::codegen;
use crate::error::{Error, Warning};
use crate::spec::TextureSpec;
use crate::spec::parse_toml;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Name of the generated file in `OUT_DIR`.
pub const GENERATED: &str = "noisebake_textures.rs";
/// Generations longer than this are announced (a `cargo:warning` from build scripts, a line on
/// stderr from the macro), saying what took the time.
pub const SLOW_SECONDS: f64 = 1.0;

/// A failed bake (kept as a name for [`Error`]).
pub type BakeError = Error;

/// One baked texture.
#[derive(Debug, Clone)]
pub struct Baked {
    /// The item name.
    pub name: String,
    /// Bytes embedded.
    pub bytes: usize,
    /// From the cache or generated now.
    pub source: Source,
    /// Seconds spent generating (0 for a cache hit).
    pub seconds: f64,
}

/// What a bake did.
#[derive(Debug, Clone)]
pub struct Report {
    /// Every texture, in spec order.
    pub textures: Vec<Baked>,
    /// The generated Rust file.
    pub generated: PathBuf,
    /// The cache directory used.
    pub cache_dir: PathBuf,
    /// Warnings (also printed as `cargo:warning` lines when `cargo_output` is on).
    pub warnings: Vec<Warning>,
}

/// Bakes `spec` with default options (see [`Bake`]).
pub fn bake(spec: impl AsRef<Path>) -> Result<Report, Error> {
    Bake::new(spec).run()
}

/// Bakes `spec` from a build script and, on failure, reports the error the way Cargo shows a
/// build script's errors best, then ends the script: the whole of `build.rs`'s `main` is
///
/// ```no_run
/// build_assets::bake_or_exit("noise.toml");
/// ```
///
/// See [`Bake::run_or_exit`].
pub fn bake_or_exit(spec: impl AsRef<Path>) -> Report {
    Bake::new(spec).run_or_exit()
}

/// Writes `error` as Cargo build-script directives, one `cargo::error=` line per line of the
/// message (a directive ends at its line break). Cargo prints each as `error: <crate>: …` at the
/// top of its output, before anything else it says of the failure.
pub fn write_cargo_error(error: &Error, out: &mut impl std::io::Write) -> std::io::Result<()> {
    for line in error.to_string().lines() {
        writeln!(out, "cargo::error={line}")?;
    }
    out.flush()
}

/// Look up, announce, generate — what every way in (build script, macro, CLI, reports) does
/// for one texture: `spec` from `cache` when it is there; else the
/// [`announcement`](crate::generate::estimate::announcement) of its estimate goes to `announce`
/// when it exceeds `threshold` seconds, and it is generated (reporting to `progress`) and
/// stored.
pub fn obtain(
    cache: &mut Cache,
    spec: &TextureSpec,
    threshold: f64,
    announce: &mut dyn FnMut(&str),
    progress: crate::generate::Progress,
) -> Result<Entry, Error> {
    let entry = match cache.lookup(spec) {
        Some(e) => e,
        None => {
            if let Some(line) = crate::generate::estimate::announcement(spec, threshold) {
                announce(&line);
            }
            cache.get_or_insert_with(spec, || crate::generate::bake_texture(spec, progress))?
        }
    };
    if let open @ 1.. = entry.open_windows {
        cache.warnings.push(Warning::OpenWindows {
            name: spec.name.clone(),
            open,
            windows: spec.texels() as u64,
        });
    }
    Ok(entry)
}

/// The line that reports a slow generation once it is done.
pub fn announce(name: &str, what: &str, seconds: f64, dir: &Path) -> String {
    format!(
        "noisebake: generated `{name}` ({what}) in {seconds:.1} s; later builds read it from {}",
        dir.display()
    )
}

/// Options of a bake.
#[derive(Debug, Clone)]
pub struct Bake {
    spec: PathBuf,
    out_dir: Option<PathBuf>,
    cache_dir: Option<PathBuf>,
    krate: String,
    cargo_output: bool,
    ktx2_dir: Option<PathBuf>,
}

impl Bake {
    /// A bake of the spec file at `spec` (relative paths are relative to the package root when
    /// run from a build script).
    pub fn new(spec: impl AsRef<Path>) -> Self {
        Self {
            spec: spec.as_ref().to_path_buf(),
            out_dir: None,
            cache_dir: None,
            krate: "::noisebake".into(),
            cargo_output: true,
            ktx2_dir: None,
        }
    }

    /// Where to write the generated file (default: `$OUT_DIR`).
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.out_dir = Some(dir.into());
        self
    }

    /// The cache directory (overrides the spec file's `cache_dir` and the target dir, but not
    /// `NOISEBAKE_CACHE_DIR`). Any path is accepted here: it is the program's choice.
    pub fn cache_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.cache_dir = Some(dir.into());
        self
    }

    /// The path of the noisebake crate in generated code (default `::noisebake`).
    pub fn crate_path(mut self, path: impl Into<String>) -> Self {
        self.krate = path.into();
        self
    }

    /// Whether to print `cargo:` lines (on by default; off for use outside build scripts).
    pub fn cargo_output(mut self, on: bool) -> Self {
        self.cargo_output = on;
        self
    }

    /// Also writes every texture as `dir/<name>.ktx2` (a KTX 2.0 array texture, see
    /// [`export::ktx2`](crate::export::ktx2)), for a game's asset folder: relative paths are
    /// relative to the package root in a build script. Files are rewritten only when their
    /// bytes change.
    pub fn ktx2_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.ktx2_dir = Some(dir.into());
        self
    }

    /// Runs the bake from a build script, ending the script on failure with the error shown as
    /// Cargo shows a build script's own errors: the message, line by line, as `cargo::error=`
    /// directives ([`write_cargo_error`]; every Cargo this crate's `rust-version` allows reads
    /// them), and no panic, so no backtrace however `RUST_BACKTRACE` is set.
    ///
    /// The script then exits with status 0 on purpose: the logged errors fail the build
    /// ("build script logged errors"), whereas a non-zero exit makes Cargo append its
    /// "failed to run custom build command" block with the script's whole output repeated
    /// below the message.
    pub fn run_or_exit(self) -> Report {
        match self.run() {
            Ok(report) => report,
            Err(e) => {
                let _ = write_cargo_error(&e, &mut std::io::stdout().lock());
                std::process::exit(0)
            }
        }
    }

    /// Runs the bake.
    pub fn run(self) -> Result<Report, Error> {
        let cargo = |line: String| {
            if self.cargo_output {
                println!("cargo:{line}");
            }
        };
        cargo(format!("rerun-if-changed={}", self.spec.display()));
        for var in [
            "NOISEBAKE_CACHE_DIR",
            "NOISEBAKE_OFFLINE",
            "CARGO_TARGET_DIR",
            "RUST_ANALYZER_INTERNALS_DO_NOT_USE",
        ] {
            cargo(format!("rerun-if-env-changed={var}"));
        }
        let out_dir = self
            .out_dir
            .clone()
            .or_else(|| std::env::var_os("OUT_DIR").map(PathBuf::from))
            .ok_or(Error::NoOutDir)?;
        let text = std::fs::read_to_string(&self.spec).map_err(|source| Error::Io {
            action: "reading the spec",
            path: self.spec.clone(),
            source,
        })?;
        let file = parse_toml(&text).map_err(|e| Error::Spec {
            file: self.spec.clone(),
            rendered: e.render(&self.spec.display().to_string(), &text),
        })?;
        let mut locator = Locator::from_env();
        locator.out_dir = Some(out_dir.clone());
        locator.explicit = self.cache_dir.clone();
        locator.spec_cache_dir = file.cache_dir.clone().map(|d| (self.spec.clone(), d));
        let mut cache = locator.resolve()?;
        let data_dir = out_dir.join("noisebake");
        std::fs::create_dir_all(&data_dir).map_err(|source| Error::Io {
            action: "creating",
            path: data_dir.clone(),
            source,
        })?;
        let mut code = String::from("// Generated by build_assets::bake(); do not edit.\n\n");
        let mut textures = Vec::new();
        let mut announced = false;
        let analyzer = std::env::var_os("RUST_ANALYZER_INTERNALS_DO_NOT_USE").is_some();
        for spec in &file.textures {
            let entry = if analyzer {
                match cache.lookup(spec) {
                    Some(e) => e,
                    None => {
                        code += &codegen::placeholder(spec, "pub ", &self.krate);
                        continue;
                    }
                }
            } else {
                let start = Instant::now();
                let e = obtain(
                    &mut cache,
                    spec,
                    crate::generate::estimate::ANNOUNCE_SECONDS,
                    &mut |line| {
                        // Shown when the script ends (Cargo holds build-script output), and
                        // on stderr at once for `cargo build -vv`.
                        eprintln!("noisebake: {line}");
                        cargo(format!("warning=noisebake: {line}"));
                        announced = true;
                    },
                    &mut |_, _| {},
                )?;
                if e.source == Source::Generated && start.elapsed().as_secs_f64() > SLOW_SECONDS {
                    let what = format!("{} {:?}", spec.kind.name(), spec.dims);
                    let dir = e
                        .path
                        .as_deref()
                        .and_then(Path::parent)
                        .unwrap_or(&cache.dir);
                    cargo(format!(
                        "warning={}",
                        announce(&spec.name, &what, e.seconds, dir)
                    ));
                    announced = true;
                }
                e
            };
            if let Some(dir) = &self.ktx2_dir {
                std::fs::create_dir_all(dir).map_err(|source| Error::Io {
                    action: "creating",
                    path: dir.clone(),
                    source,
                })?;
                let file = dir.join(format!("{}.ktx2", spec.name));
                write_if_changed(
                    &file,
                    &crate::export::ktx2::to_ktx2(&entry.texture, Some(spec)),
                )?;
            }
            let bin = data_dir.join(format!("{}.bin", spec.name));
            write_if_changed(&bin, &entry.texture.data)?;
            code += &codegen::item(spec, "pub ", &bin.display().to_string(), 0, &self.krate);
            textures.push(Baked {
                name: spec.name.clone(),
                bytes: entry.texture.data.len(),
                source: entry.source,
                seconds: entry.seconds,
            });
        }
        let generated = out_dir.join(GENERATED);
        write_if_changed(&generated, code.as_bytes())?;
        // Cargo replays a build script's warnings on every build until the script runs again.
        // When this run has something to say, a stamp written now (after Cargo's start time)
        // makes the next build run the script once more, quietly: every texture is then a
        // cache hit and the generated file is unchanged, so nothing else is rebuilt.
        let stamp = data_dir.join("announced");
        if self.cargo_output && (announced || !cache.warnings.is_empty()) {
            let _ = std::fs::write(&stamp, b"");
        }
        if stamp.exists() {
            cargo(format!("rerun-if-changed={}", stamp.display()));
        }
        for w in &cache.warnings {
            cargo(format!("warning=noisebake: {w}"));
        }
        Ok(Report {
            textures,
            generated,
            cache_dir: cache.dir,
            warnings: cache.warnings,
        })
    }
}

/// Writes only when the contents differ, so unchanged files keep their timestamps and a no-op
/// rebuild recompiles nothing.
fn write_if_changed(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    if std::fs::read(path).is_ok_and(|old| old == bytes) {
        return Ok(());
    }
    crate::atomic::write(path, bytes).map_err(|source| Error::Io {
        action: "writing",
        path: path.to_path_buf(),
        source,
    })
}
