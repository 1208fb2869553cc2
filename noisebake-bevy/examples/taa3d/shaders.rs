//! The example's WGSL: the dithered surfaces (main pass and prepass) and the fog volume. Each
//! reads its noise through the noisebake library (`#import noisebake::…`), by the value of
//! `noise` in its uniform:
//!
//! | `noise` | value per pixel and frame |
//! | --- | --- |
//! | 0 | white: `nb_to_unit(nb_hash3(vec3(pixel, frame), 7u))` |
//! | 1 | interleaved gradient noise, golden-ratio animated: `nb_ign_frame(pixel, frame)` |
//! | 2 | the R2 grid, golden-ratio animated: `nb_r2_frame(pixel, frame)` |
//! | 3 to 6 | the baked masks STBN, FAST (EMA), FAST (TAA), FAST (TAA at Bevy's still blend): `nb_mask_unit(mask, vec3(pixel, frame), 0u)` |
//!
//! and `mode`: 0 dithers (a fragment is kept where the value is below its coverage), 1 is the
//! reference (alpha-blended at its coverage; the fog marched finely), 2 writes the surface's
//! class into the green channel (the measurement's map of which surface each pixel sees).

/// What every shader shares: the noise selection, reading `masks` bound at 1, 2 and 3 of the
/// material's group.
const NOISE: &str = r#"
#import noisebake::{nb_mask_unit, nb_ign_frame, nb_r2_frame, nb_hash3, nb_to_unit}

@group(#{MATERIAL_BIND_GROUP}) @binding(1) var stbn: texture_2d_array<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(2) var fast_ema: texture_2d_array<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(3) var fast_taa: texture_2d_array<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(4) var fast_bevy: texture_2d_array<f32>;

const MODE_DITHER: u32 = 0u;
const MODE_REFERENCE: u32 = 1u;
const MODE_CLASS: u32 = 2u;

// The noise value of pixel p in frame `frame`, in [0, 1).
fn noise_value(p: vec2<i32>, frame: u32, noise: u32) -> f32 {
    let q = vec3<i32>(p, i32(frame));
    switch noise {
        case 0u: { return nb_to_unit(nb_hash3(q, 7u)); }
        case 1u: { return nb_ign_frame(p, frame); }
        case 2u: { return nb_r2_frame(p, frame); }
        case 3u: { return nb_mask_unit(stbn, q, 0u); }
        case 4u: { return nb_mask_unit(fast_ema, q, 0u); }
        case 5u: { return nb_mask_unit(fast_taa, q, 0u); }
        default: { return nb_mask_unit(fast_bevy, q, 0u); }
    }
}
"#;

/// The dithered surfaces' uniform.
const DITHER_UNIFORM: &str = r#"
struct Dither {
    // rgb: the surface's colour; a: its coverage.
    color: vec4<f32>,
    // x: noise, y: mode, z: class.
    flags: vec4<u32>,
}
@group(#{MATERIAL_BIND_GROUP}) @binding(0) var<uniform> dither: Dither;

// Whether the fragment at pixel p is dropped in this frame.
fn dropped(p: vec2<f32>, frame: u32) -> bool {
    return dither.flags.y == MODE_DITHER
        && noise_value(vec2<i32>(floor(p)), frame, dither.flags.x) >= dither.color.a;
}
"#;

/// The main pass of the dithered surfaces: simple diffuse lighting by the scene's sun.
pub fn dither_fragment() -> String {
    format!(
        "#import bevy_pbr::forward_io::VertexOutput
#import bevy_pbr::mesh_view_bindings::globals
{NOISE}{DITHER_UNIFORM}
// The scene's sun (the DirectionalLight's direction, towards the light) and its ambient.
const SUN: vec3<f32> = vec3<f32>(0.424, 0.707, 0.566);

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {{
    if dither.flags.y == MODE_CLASS {{
        return vec4<f32>(0.0, f32(dither.flags.z) / 16.0, 0.0, 1.0);
    }}
    if dropped(in.position.xy, globals.frame_count) {{
        discard;
    }}
    var n = normalize(in.world_normal);
    if !front {{
        n = -n;
    }}
    let lit = dither.color.rgb * (0.3 + 0.9 * max(dot(n, SUN), 0.0));
    // Dithered: opaque where kept. Reference: alpha-blended at the coverage.
    return vec4<f32>(lit, select(1.0, dither.color.a, dither.flags.y == MODE_REFERENCE));
}}
"
    )
}

/// The prepass of the dithered surfaces: the same fragments dropped, so the depth and the
/// motion vectors Bevy's TAA reads are those of the fragments kept.
pub fn dither_prepass() -> String {
    format!(
        "#import bevy_pbr::{{prepass_io::{{VertexOutput, FragmentOutput}}, mesh_view_bindings::view, prepass_bindings::previous_view_uniforms}}
#import bevy_render::globals::Globals
{NOISE}{DITHER_UNIFORM}
// Bevy's prepass binds `globals` at 1 of its view group (the main pass at 11).
@group(0) @binding(1) var<uniform> prepass_globals: Globals;

#ifdef PREPASS_FRAGMENT
@fragment
fn fragment(in: VertexOutput) -> FragmentOutput {{
    if dropped(in.position.xy, prepass_globals.frame_count) {{
        discard;
    }}
    var out: FragmentOutput;
#ifdef NORMAL_PREPASS
    out.normal = vec4<f32>(in.world_normal * 0.5 + vec3<f32>(0.5), 1.0);
#endif
#ifdef MOTION_VECTOR_PREPASS
    // As Bevy's own prepass: the unjittered clip position now and last frame, in UV units.
    let now = view.unjittered_clip_from_world * in.world_position;
    let before = previous_view_uniforms.clip_from_world * in.previous_world_position;
    out.motion_vector = (now.xy / now.w - before.xy / before.w) * vec2<f32>(0.5, -0.5);
#endif
    return out;
}}
#else
@fragment
fn fragment(in: VertexOutput) {{
    if dropped(in.position.xy, prepass_globals.frame_count) {{
        discard;
    }}
}}
#endif
"
    )
}

/// The fog volume: an axis-aligned box of varying density, marched from where the view ray
/// enters it to where it leaves, with `steps` steps; dithering jitters the start by the noise
/// value (an unbiased estimate of the optical depth), the reference takes midpoints of many
/// more. Alpha-blended over the scene (no prepass, as fog in games).
pub fn fog_fragment() -> String {
    format!(
        "#import bevy_pbr::forward_io::VertexOutput
#import bevy_pbr::mesh_view_bindings::{{globals, view}}
{NOISE}
struct Fog {{
    // xyz: the box's centre; w: the density scale.
    center: vec4<f32>,
    // xyz: the box's half extents; w: unused.
    half: vec4<f32>,
    // rgb: the fog's colour; a: unused.
    color: vec4<f32>,
    // x: noise, y: mode, z: class, w: steps.
    flags: vec4<u32>,
}}
@group(#{{MATERIAL_BIND_GROUP}}) @binding(0) var<uniform> fog: Fog;

fn density(p: vec3<f32>) -> f32 {{
    let q = (p - fog.center.xyz) / fog.half.xyz;
    return fog.center.w * (0.55 + 0.45 * sin(3.0 * q.x + 1.0) * sin(2.5 * q.y + 0.3) * cos(2.0 * q.z));
}}

@fragment
fn fragment(in: VertexOutput) -> @location(0) vec4<f32> {{
    if fog.flags.y == MODE_CLASS {{
        return vec4<f32>(0.0, f32(fog.flags.z) / 16.0, 0.0, 1.0);
    }}
    let eye = view.world_position;
    let dir = normalize(in.world_position.xyz - eye);
    // The ray's exit from the box (slab method); it enters at this fragment.
    let lo = (fog.center.xyz - fog.half.xyz - eye) / dir;
    let hi = (fog.center.xyz + fog.half.xyz - eye) / dir;
    let exit = min(min(max(lo.x, hi.x), max(lo.y, hi.y)), max(lo.z, hi.z));
    let enter = length(in.world_position.xyz - eye);
    let span = max(exit - enter, 0.0);
    let steps = select(fog.flags.w, 128u, fog.flags.y == MODE_REFERENCE);
    let dt = span / f32(steps);
    var offset = 0.5;
    if fog.flags.y == MODE_DITHER {{
        offset = noise_value(vec2<i32>(floor(in.position.xy)), globals.frame_count, fog.flags.x);
    }}
    var depth = 0.0;
    for (var i = 0u; i < steps; i++) {{
        depth += density(eye + dir * (enter + (f32(i) + offset) * dt)) * dt;
    }}
    return vec4<f32>(fog.color.rgb, 1.0 - exp(-depth));
}}
"
    )
}
