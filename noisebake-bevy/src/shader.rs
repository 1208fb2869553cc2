//! The WGSL library as a Bevy shader module, importable as `noisebake`.
//!
//! `noise-runtime/wgsl/noisebake.wgsl` is plain WGSL with no preprocessor lines, so that wgpu
//! users can prepend it to their own source. Bevy's preprocessor (naga_oil) finds a module by
//! its `#define_import_path`: the plugin adds that one line and registers the result under a
//! fixed handle, as Bevy's own crates register theirs.

use bevy::asset::{Handle, uuid_handle};
use bevy::shader::Shader;

/// The import path of the library: `#import noisebake::{nb_mask_unit, nb_ign_frame}`.
pub const IMPORT_PATH: &str = "noisebake";

/// The handle the library is stored under in `Assets<Shader>`.
pub const NOISEBAKE_SHADER: Handle<Shader> = uuid_handle!("cb3d87d5-f71d-4c2d-9d9a-449757f6f435");

/// The library's source as Bevy reads it: the import path, then the runtime's WGSL unchanged.
pub fn source() -> String {
    format!(
        "#define_import_path {IMPORT_PATH}\n{}",
        noise_runtime::shaders::WGSL
    )
}

/// The library as a [`Shader`] asset.
pub fn library() -> Shader {
    Shader::from_wgsl(source(), "noisebake/noisebake.wgsl")
}
