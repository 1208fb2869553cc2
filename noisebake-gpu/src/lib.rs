//! # noisebake-gpu
//!
//! What runs noisebake's WGSL library ([`noisebake::shaders::WGSL`]) and its baked masks on a
//! GPU through wgpu: a headless device ([`Gpu::new`]), naga validation with readable errors
//! ([`validate`]), mask upload from the runtime's raw bytes ([`Gpu::upload_mask`]) and one-shot
//! compute dispatches ([`Gpu::run`]). The GPU tests (`tests/wgsl.rs`) and the GPU example
//! (`cargo run --release --example gpu`) are built on it.
//!
//! On a machine without a GPU, Mesa's lavapipe (Debian `mesa-vulkan-drivers`) provides a
//! software Vulkan device, which is what CI uses.

use noisebake::{GpuFormat, GpuTexture};
use std::time::Duration;
/// The wgpu this crate runs on, for callers that hold its textures.
pub use wgpu;

/// A headless wgpu device and its queue.
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// What the adapter says of itself (name, driver, backend).
    pub info: wgpu::AdapterInfo,
    /// Whether GPU timestamps can be taken ([`Gpu::run_timed`]).
    pub timestamps: bool,
}

/// A Vulkan-only wgpu instance with no display.
fn instance() -> wgpu::Instance {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = wgpu::Backends::VULKAN;
    wgpu::Instance::new(desc)
}

/// Parses and validates WGSL with naga, so that an error in the library or a kernel is reported
/// with its line and message before a pipeline is built.
pub fn validate(source: &str) -> Result<naga::Module, String> {
    let module = naga::front::wgsl::parse_str(source).map_err(|e| e.emit_to_string(source))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)
    .map_err(|e| e.emit_to_string(source))?;
    Ok(module)
}

/// A buffer bound to a compute kernel: `@group(0) @binding(i)` in the order given.
pub enum Binding<'a> {
    /// A read-only storage buffer with these bytes.
    Input(&'a [u8]),
    /// A read-write storage buffer of this many bytes, read back after the dispatch.
    Output(usize),
    /// A uniform buffer with these bytes.
    Uniform(&'a [u8]),
    /// A texture (its default view).
    Texture(&'a wgpu::Texture),
}

impl Gpu {
    /// A device on the first adapter wgpu finds (Vulkan only, software adapters included).
    pub fn new() -> Result<Gpu, String> {
        let instance = instance();
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            ..Default::default()
        }))
        .map_err(|e| format!("no GPU adapter: {e}"))?;
        Gpu::on(adapter)
    }

    /// A device on every Vulkan adapter of the machine, in the order wgpu lists them: a
    /// hardware GPU and the software drivers (lavapipe, SwiftShader) side by side, so a test
    /// can hold each driver to the CPU's values.
    pub fn all() -> Vec<Result<Gpu, String>> {
        let adapters = pollster::block_on(instance().enumerate_adapters(wgpu::Backends::VULKAN));
        adapters.into_iter().map(Gpu::on).collect()
    }

    fn on(adapter: wgpu::Adapter) -> Result<Gpu, String> {
        let info = adapter.get_info();
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let required_features = if timestamps {
            wgpu::Features::TIMESTAMP_QUERY
        } else {
            wgpu::Features::empty()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("noisebake"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| format!("no device on {}: {e}", info.name))?;
        Ok(Gpu {
            device,
            queue,
            info,
            timestamps,
        })
    }

    /// For tests: a device on every Vulkan adapter ([`Gpu::all`]), each test run once per
    /// driver; empty, with a message saying why the tests are skipped, where there is none.
    ///
    /// Under CI (`CI` set in the environment) a missing adapter is a failure instead: there the
    /// GPU tests must run. `NOISEBAKE_GPU_DRIVERS`, a comma-separated list of names
    /// (`llvmpipe,SwiftShader` in `.ci/run`), makes each named driver required: a run where
    /// one of them has no adapter fails rather than passing on the others alone.
    pub fn for_tests() -> Vec<Gpu> {
        let mut gpus = Vec::new();
        let mut errors = Vec::new();
        for g in Gpu::all() {
            match g {
                Ok(g) => gpus.push(g),
                Err(e) => errors.push(e),
            }
        }
        let required = std::env::var("NOISEBAKE_GPU_DRIVERS").unwrap_or_default();
        for name in required.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            let found = gpus.iter().any(|g| g.info.name.contains(name));
            assert!(
                found,
                "NOISEBAKE_GPU_DRIVERS names {name}, but no Vulkan adapter is called so (found: \
                 {:?}; errors: {errors:?}); .ci/run installs lavapipe and SwiftShader",
                gpus.iter().map(|g| &g.info.name).collect::<Vec<_>>()
            );
        }
        if gpus.is_empty() {
            let e = if errors.is_empty() {
                "no GPU adapter".to_string()
            } else {
                errors.join("; ")
            };
            if std::env::var_os("CI").is_some() {
                panic!(
                    "{e}: CI must run the GPU tests (install mesa-vulkan-drivers and libvulkan1)"
                );
            }
            // Straight to the stderr handle: the test harness captures `eprintln!` of passing
            // tests, and a skip must be seen.
            use std::io::Write;
            let _ = writeln!(
                std::io::stderr(),
                "SKIPPED: {e}. The GPU tests need a Vulkan device; on a machine without one, \
                 `apt-get install mesa-vulkan-drivers libvulkan1` gives a software one."
            );
        }
        gpus
    }

    /// Runs `test` on every device of [`Gpu::for_tests`] (made once per test binary), one
    /// driver after another, and fails naming the driver whose run failed.
    pub fn each_for_tests(test: impl Fn(&Gpu)) {
        static GPUS: std::sync::OnceLock<Vec<Gpu>> = std::sync::OnceLock::new();
        let gpus = GPUS.get_or_init(|| {
            let gpus = Gpu::for_tests();
            for g in &gpus {
                eprintln!("GPU tests on {}", g.describe());
            }
            gpus
        });
        for g in gpus {
            let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| test(g)));
            if let Err(e) = run {
                let msg = e
                    .downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| e.downcast_ref::<&str>().copied())
                    .unwrap_or("(no message)");
                panic!("on {}: {msg}", g.describe());
            }
        }
    }

    /// A one-line description of the adapter.
    pub fn describe(&self) -> String {
        format!(
            "{} ({:?}, {} {})",
            self.info.name, self.info.backend, self.info.driver, self.info.driver_info
        )
    }

    /// Uploads a mask as its [`GpuTexture`] describes it, from the bytes
    /// [`Mask3::gpu_bytes`](noisebake::Mask3::gpu_bytes) or
    /// [`write_gpu_bytes`](noisebake::Mask3::write_gpu_bytes) give.
    pub fn upload_mask(&self, tex: GpuTexture, bytes: &[u8]) -> wgpu::Texture {
        assert_eq!(bytes.len(), tex.byte_len(), "mask bytes for {tex:?}");
        let size = wgpu::Extent3d {
            width: tex.width,
            height: tex.height,
            depth_or_array_layers: tex.layers,
        };
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("noisebake mask"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: texture_format(tex.format),
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        self.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(tex.bytes_per_row()),
                rows_per_image: Some(tex.height),
            },
            size,
        );
        texture
    }

    /// Runs `main` of `source` (the WGSL library is prepended) with `workgroups` workgroups and
    /// the bindings given, and returns the bytes of every [`Binding::Output`], in order.
    pub fn run(
        &self,
        source: &str,
        workgroups: [u32; 3],
        bindings: &[Binding<'_>],
    ) -> Result<Vec<Vec<u8>>, String> {
        self.run_timed(source, workgroups, bindings, 1)
            .map(|(out, _)| out)
    }

    /// [`Gpu::run`], dispatching `repeat` times in one pass, with the GPU time of one dispatch
    /// (timestamps around the pass divided by `repeat`; wall-clock time of the submission when
    /// the adapter has no timestamps).
    pub fn run_timed(
        &self,
        source: &str,
        workgroups: [u32; 3],
        bindings: &[Binding<'_>],
        repeat: u32,
    ) -> Result<(Vec<Vec<u8>>, Duration), String> {
        let full = format!("{}\n{source}", noisebake::shaders::WGSL);
        validate(&full)?;
        let device = &self.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("noisebake kernel"),
            source: wgpu::ShaderSource::Wgsl(full.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("noisebake kernel"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        use wgpu::util::DeviceExt;
        let mut buffers = Vec::new();
        let mut outputs = Vec::new();
        let mut views = Vec::new();
        for (i, b) in bindings.iter().enumerate() {
            match b {
                Binding::Input(bytes) | Binding::Uniform(bytes) => {
                    let usage = if matches!(b, Binding::Uniform(_)) {
                        wgpu::BufferUsages::UNIFORM
                    } else {
                        wgpu::BufferUsages::STORAGE
                    };
                    let mut padded = bytes.to_vec();
                    padded.resize(bytes.len().max(16).next_multiple_of(16), 0);
                    buffers.push((
                        i,
                        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                            label: None,
                            contents: &padded,
                            usage,
                        }),
                    ));
                }
                Binding::Output(len) => {
                    let size = (*len as u64).max(16).next_multiple_of(16);
                    let buf = device.create_buffer(&wgpu::BufferDescriptor {
                        label: None,
                        size,
                        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                        mapped_at_creation: false,
                    });
                    let read = device.create_buffer(&wgpu::BufferDescriptor {
                        label: None,
                        size,
                        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    });
                    outputs.push((buf.clone(), read, *len));
                    buffers.push((i, buf));
                }
                Binding::Texture(t) => views.push((i, t.create_view(&Default::default()))),
            }
        }
        let mut entries: Vec<wgpu::BindGroupEntry<'_>> = buffers
            .iter()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: *i as u32,
                resource: b.as_entire_binding(),
            })
            .collect();
        entries.extend(views.iter().map(|(i, v)| wgpu::BindGroupEntry {
            binding: *i as u32,
            resource: wgpu::BindingResource::TextureView(v),
        }));
        entries.sort_by_key(|e| e.binding);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let queries = self.timestamps.then(|| {
            let set = device.create_query_set(&wgpu::QuerySetDescriptor {
                label: None,
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            });
            let resolve = device.create_buffer(&wgpu::BufferDescriptor {
                label: None,
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let read = device.create_buffer(&wgpu::BufferDescriptor {
                label: None,
                size: 16,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            (set, resolve, read)
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: None,
                timestamp_writes: queries.as_ref().map(|(set, _, _)| {
                    wgpu::ComputePassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(0),
                        end_of_pass_write_index: Some(1),
                    }
                }),
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            for _ in 0..repeat.max(1) {
                pass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
            }
        }
        for (buf, read, _) in &outputs {
            encoder.copy_buffer_to_buffer(buf, 0, read, 0, buf.size());
        }
        if let Some((set, resolve, read)) = &queries {
            encoder.resolve_query_set(set, 0..2, resolve, 0);
            encoder.copy_buffer_to_buffer(resolve, 0, read, 0, 16);
        }
        let start = std::time::Instant::now();
        self.queue.submit([encoder.finish()]);
        let mut reads: Vec<&wgpu::Buffer> = outputs.iter().map(|(_, r, _)| r).collect();
        if let Some((_, _, read)) = &queries {
            reads.push(read);
        }
        for r in &reads {
            r.slice(..).map_async(wgpu::MapMode::Read, |res| {
                res.expect("mapping a read-back buffer");
            });
        }
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| format!("waiting for the GPU: {e}"))?;
        let wall = start.elapsed();
        let out = outputs
            .iter()
            .map(|(_, r, len)| {
                r.slice(..)
                    .get_mapped_range()
                    .map(|v| v[..*len].to_vec())
                    .map_err(|e| format!("reading back: {e:?}"))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let elapsed = match &queries {
            Some((_, _, read)) => {
                let t = read
                    .slice(..)
                    .get_mapped_range()
                    .map_err(|e| format!("reading timestamps: {e:?}"))?;
                let a = u64::from_le_bytes(t[0..8].try_into().unwrap());
                let b = u64::from_le_bytes(t[8..16].try_into().unwrap());
                let ns = b.saturating_sub(a) as f64 * self.queue.get_timestamp_period() as f64;
                Duration::from_nanos(ns as u64)
            }
            None => wall,
        };
        Ok((out, elapsed / repeat.max(1)))
    }
}

/// The wgpu format of a runtime [`GpuFormat`].
pub fn texture_format(f: GpuFormat) -> wgpu::TextureFormat {
    use wgpu::TextureFormat as T;
    match f {
        GpuFormat::R8Unorm => T::R8Unorm,
        GpuFormat::Rg8Unorm => T::Rg8Unorm,
        GpuFormat::Rgba8Unorm => T::Rgba8Unorm,
        GpuFormat::R16Uint => T::R16Uint,
        GpuFormat::Rg16Uint => T::Rg16Uint,
        GpuFormat::Rgba16Uint => T::Rgba16Uint,
        GpuFormat::R32Float => T::R32Float,
        GpuFormat::Rg32Float => T::Rg32Float,
        GpuFormat::Rgba32Float => T::Rgba32Float,
    }
}

/// Little-endian bytes of a slice of 32-bit words.
pub fn bytes_of<T: Copy + Into<Word>>(v: &[T]) -> Vec<u8> {
    v.iter().flat_map(|&x| x.into().0.to_le_bytes()).collect()
}

/// A 32-bit word (`u32`, `i32` or `f32`) as the GPU reads it.
#[derive(Clone, Copy)]
pub struct Word(pub u32);
impl From<u32> for Word {
    fn from(v: u32) -> Self {
        Word(v)
    }
}
impl From<i32> for Word {
    fn from(v: i32) -> Self {
        Word(v as u32)
    }
}
impl From<f32> for Word {
    fn from(v: f32) -> Self {
        Word(v.to_bits())
    }
}

/// The 32-bit words of read-back bytes.
pub fn words(bytes: &[u8]) -> Vec<u32> {
    bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// The f32 values of read-back bytes.
pub fn floats(bytes: &[u8]) -> Vec<f32> {
    words(bytes).into_iter().map(f32::from_bits).collect()
}

/// `docs/gpu.md`'s Rust snippets, compiled as this crate's doc tests (they use its wgpu), so a
/// snippet that no longer compiles fails the tests.
#[cfg(doctest)]
#[doc = include_str!("../../docs/gpu.md")]
pub struct GpuDocs;
