//! `bake()`: the build-script way in. Reads a spec file, fetches or generates every texture
//! through the cache, and writes one Rust file into `OUT_DIR` for `noisebake::include_textures!()`.

use crate::cache::{Cache, Source, writable};
use crate::codegen;
use crate::spec::parse_toml;
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Name of the generated file in `OUT_DIR`.
pub const GENERATED: &str = "noisebake_textures.rs";
/// Generations longer than this print a `cargo:warning` saying what took the time.
pub const SLOW_SECONDS: f64 = 1.0;

/// A failed bake: the message says what and where (file:line for spec errors).
#[derive(Debug, Clone, PartialEq)]
pub struct BakeError(pub String);

impl fmt::Display for BakeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BakeError {}

/// One baked texture.
#[derive(Debug, Clone)]
pub struct Baked {
    /// The item name.
    pub name: String,
    /// Bytes embedded.
    pub bytes: usize,
    /// From the cache or generated now.
    pub source: Source,
    /// Seconds spent (generation or read).
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
    pub warnings: Vec<String>,
}

/// Bakes `spec` with default options (see [`Bake`]).
pub fn bake(spec: impl AsRef<Path>) -> Result<Report, BakeError> {
    Bake::new(spec).run()
}

/// Options of a bake.
#[derive(Debug, Clone)]
pub struct Bake {
    spec: PathBuf,
    out_dir: Option<PathBuf>,
    cache_dir: Option<PathBuf>,
    krate: String,
    cargo_output: bool,
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
        }
    }

    /// Where to write the generated file (default: `$OUT_DIR`).
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.out_dir = Some(dir.into());
        self
    }

    /// The cache directory (overrides the spec file's `cache_dir` and the target dir, but not
    /// `NOISEBAKE_CACHE_DIR`).
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

    /// Runs the bake.
    pub fn run(self) -> Result<Report, BakeError> {
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
            .ok_or_else(|| {
                BakeError(
                    "OUT_DIR is not set: call bake() from a build script or give Bake::out_dir"
                        .into(),
                )
            })?;
        let text = std::fs::read_to_string(&self.spec)
            .map_err(|e| BakeError(format!("{}: {e}", self.spec.display())))?;
        let file = parse_toml(&text)
            .map_err(|e| BakeError(e.render(&self.spec.display().to_string(), &text)))?;
        let spec_dir = self.spec.parent().unwrap_or(Path::new("."));
        let from_spec = file.cache_dir.as_ref().map(|d| spec_dir.join(d));
        let mut cache = Cache::locate(
            self.cache_dir.clone().or(from_spec),
            Some(&out_dir),
            &out_dir,
        );
        if !cache.offline && !writable(&cache.dir) {
            let fallback = out_dir.join("noisebake-cache");
            cache.warnings.push(format!(
                "cache directory {} is not writable; using {}",
                cache.dir.display(),
                fallback.display()
            ));
            cache.dir = fallback;
        }
        let data_dir = out_dir.join("noisebake");
        std::fs::create_dir_all(&data_dir)
            .map_err(|e| BakeError(format!("{}: {e}", data_dir.display())))?;
        let mut code = String::from("// Generated by build_assets::bake(); do not edit.\n\n");
        let mut textures = Vec::new();
        let analyzer = std::env::var_os("RUST_ANALYZER_INTERNALS_DO_NOT_USE").is_some();
        for spec in &file.textures {
            let start = Instant::now();
            if analyzer && cache.read(spec).ok().flatten().is_none() {
                code += &codegen::placeholder(spec, "pub ", &self.krate);
                continue;
            }
            let entry = cache.get(spec, &mut |_, _| {}).map_err(BakeError)?;
            let seconds = start.elapsed().as_secs_f64();
            if entry.source == Source::Generated && seconds > SLOW_SECONDS {
                cargo(format!(
                    "warning=noisebake: baked `{}` ({} {:?}) in {seconds:.1} s; later builds read it from {}",
                    spec.name,
                    spec.kind.name(),
                    spec.dims,
                    cache.dir.display()
                ));
            }
            let bin = data_dir.join(format!("{}.bin", spec.name));
            write_if_changed(&bin, &entry.texture.data)?;
            code += &codegen::item(spec, "pub ", &bin.display().to_string(), 0, &self.krate);
            textures.push(Baked {
                name: spec.name.clone(),
                bytes: entry.texture.data.len(),
                source: entry.source,
                seconds,
            });
        }
        let generated = out_dir.join(GENERATED);
        write_if_changed(&generated, code.as_bytes())?;
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
fn write_if_changed(path: &Path, bytes: &[u8]) -> Result<(), BakeError> {
    if std::fs::read(path).is_ok_and(|old| old == bytes) {
        return Ok(());
    }
    crate::export::write_atomic(path, bytes)
        .map_err(|e| BakeError(format!("{}: {e}", path.display())))
}
