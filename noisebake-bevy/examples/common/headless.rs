//! What the examples (and the plugin's render tests) need to run Bevy's renderer headless: the
//! plugins without a window, starting the app without an event loop, and waiting for the GPU.

use bevy::app::{PluginGroupBuilder, PluginsState};
use bevy::prelude::*;
use bevy::render::RenderPlugin;

/// Bevy's default plugins for a headless run: pipelines compiled before the first frame that
/// uses them, no window, and no winit event loop (which needs a display).
pub fn plugins() -> PluginGroupBuilder {
    DefaultPlugins
        .set(RenderPlugin {
            synchronous_pipeline_compilation: true,
            ..default()
        })
        .set(bevy::window::WindowPlugin {
            primary_window: None,
            exit_condition: bevy::window::ExitCondition::DontExit,
            ..default()
        })
        .disable::<bevy::winit::WinitPlugin>()
}

/// Finishes building an app that no runner drives: waits for the plugins (the renderer's
/// adapter is requested asynchronously), then runs their `finish` and `cleanup`.
pub fn start(app: &mut App) {
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();
}

/// Blocks until the GPU has finished every submission so far, without a time limit.
///
/// A headless app has no swapchain to hold it back: each `app.update()` submits a frame and
/// returns, so on a slow driver (SwiftShader on a busy CPU) submissions pile up faster than they
/// run. When the app is dropped, wgpu's queue waits for the last of them for at most 6.3 s and
/// then panics ("We timed out while waiting on the last successful submission to complete!"),
/// which aborted the process on SwiftShader. Waiting after every update keeps one frame in
/// flight, delivers each readback in the update after its frame, and leaves the queue idle
/// whenever the app is dropped.
pub fn finish_gpu_work(app: &App) -> Result<(), String> {
    use bevy::render::render_resource::PollType;
    use bevy::render::renderer::RenderDevice;
    match app.world().get_resource::<RenderDevice>() {
        Some(device) => device
            .poll(PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| format!("waiting for the GPU: {e}")),
        None => Ok(()),
    }
}
