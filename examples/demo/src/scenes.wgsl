// The demo's stochastic transparency and RGB dithering in WGSL, for the GPU example and the GPU
// tests: the same scenes as `apps.rs`, number for number, with ξ from the same sources
// (`noises.rs`). Needs noisebake's WGSL library (`noisebake::shaders::WGSL`) before it.
//
// Bindings: params (size, noise: 0 STBN / 1 FAST / 2 IGN / 3 R2 (the free pairs of
// sampler::ign_r2), app: 0 transparency /
// 1 dither), the frames (x fastest, then y, then frame; channels interleaved), and the two
// masks. One invocation per pixel and frame (z = frame).
struct Params { size: vec2<u32>, noise: u32, app: u32 }
@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read_write> frames: array<f32>;
@group(0) @binding(2) var stbn: texture_2d_array<f32>;
@group(0) @binding(3) var fast: texture_2d_array<f32>;

// The k-th uniform number of pixel p in frame f, as noisebake_demo::noises::Noise::xi.
fn xi(p: vec2<i32>, f: u32, k: u32) -> f32 {
    let g = nb_ign_r2(p, f);
    let k3 = min(k, 2u);
    switch params.noise {
        case 0u: { return nb_mask_unit(stbn, vec3<i32>(p, i32(f)), k); }
        case 1u: { return nb_mask_unit(fast, vec3<i32>(p, i32(f)), k); }
        case 2u: { return g[k3]; }
        default: { return vec3<f32>(g.y, g.z, g.x)[k3]; }
    }
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = params.size;
    if (id.x >= size.x || id.y >= size.y) { return; }
    let p = vec2<i32>(id.xy);
    let u = f32(id.x) / f32(size.x);
    let v = f32(id.y) / f32(size.y);
    let f = id.z;
    if (params.app == 0u) {
        // Stochastic transparency (STBN §5.1): α 0.9 left, 0.3 right, over a background.
        let alpha = select(0.3, 0.9, id.x < size.x / 2u);
        let background = 0.15 + 0.5 * (0.5 + 0.5 * sin(9.0 * u + 4.0 * v)) * v;
        let i = (f * size.y + id.y) * size.x + id.x;
        frames[i] = select(background, 0.95, xi(p, f, 0u) < alpha);
    } else {
        // RGB dithering to one bit per channel with three values per pixel (STBN §5.2).
        let r = sqrt((u - 0.35) * (u - 0.35) + (v - 0.4) * (v - 0.4));
        let c = clamp(vec3<f32>(0.1 + 0.8 * u, 0.5 + 0.45 * cos(6.0 * r), 0.2 + 0.7 * v * (1.0 - u * 0.5)), vec3<f32>(0.0), vec3<f32>(1.0));
        let i = 3u * ((f * size.y + id.y) * size.x + id.x);
        for (var k = 0u; k < 3u; k++) {
            frames[i + k] = select(0.0, 1.0, c[k] > xi(p, f, k));
        }
    }
}
