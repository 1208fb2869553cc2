// noisebake.wgsl: noisebake's runtime functions for the GPU.
//
// Plain WGSL: no preprocessor, no bindings, no entry points. Prepend it to a shader module
// (wgpu), or load it as a Bevy shader library. Every function is prefixed `nb_` and computes
// what the runtime function of the same name computes on the CPU (noise_runtime, Rust); the
// `noisebake-gpu` tests run each one on a Vulkan device and compare.
//
// Agreement with the CPU:
// - Integer work (mask addresses, R2 and golden-ratio offsets, the grids, the hashes) is the
//   same bit for bit. The runtime takes its products in 64-bit fixed point; WGSL has no 64-bit
//   integers, so they are taken here in pairs of u32 (`vec2<u32>(low, high)`).
// - Floating-point functions (Perlin, fBm, their estimators, CNJ) agree within tolerances:
//   WGSL lets an implementation fuse `a * b + c` into one rounding and has no f64. See
//   noise_runtime::shaders for the tolerances and the tests for how they are measured.
// - Coordinates of the gradient noises must satisfy |p| < 2^22 (the runtime's fast range).
//
// Licence: MIT OR Apache-2.0, as the rest of noisebake.

// ---------------------------------------------------------------------------------------------
// 64-bit arithmetic in u32 pairs

// The high 32 bits of the 64-bit product a·b.
fn nb_mulhi(a: u32, b: u32) -> u32 {
    let a0 = a & 0xffffu;
    let a1 = a >> 16u;
    let b0 = b & 0xffffu;
    let b1 = b >> 16u;
    let p00 = a0 * b0;
    let p01 = a0 * b1;
    let p10 = a1 * b0;
    let mid = (p00 >> 16u) + (p01 & 0xffffu) + (p10 & 0xffffu);
    return a1 * b1 + (p01 >> 16u) + (p10 >> 16u) + (mid >> 16u);
}

// The wrapping 64-bit product of two (low, high) pairs.
fn nb_mul64(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    return vec2<u32>(a.x * b.x, nb_mulhi(a.x, b.x) + a.x * b.y + a.y * b.x);
}

// The wrapping 64-bit sum of two (low, high) pairs.
fn nb_add64(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let lo = a.x + b.x;
    return vec2<u32>(lo, a.y + b.y + select(0u, 1u, lo < a.x));
}

// An i32 sign-extended to 64 bits.
fn nb_wide(v: i32) -> vec2<u32> {
    return vec2<u32>(bitcast<u32>(v), select(0u, 0xffffffffu, v < 0));
}

// ---------------------------------------------------------------------------------------------
// Sequences (noise_runtime::sequence): R2 (Roberts 2018) and the golden ratio in fixed point

// 2^64/ρ and 2^64/ρ², ρ the plastic number; 2^64·(φ − 1), φ the golden ratio.
const NB_R2_A1 = vec2<u32>(0x02a6328fu, 0xc13fa9a9u);
const NB_R2_A2 = vec2<u32>(0xc79e7b1cu, 0x91e10da5u);
const NB_GOLDEN = vec2<u32>(0x7f4a7c15u, 0x9e3779b9u);

// frac(k·α) as a 32-bit fraction: the high word of the 64-bit product k·α.
fn nb_frac_mul(k: u32, alpha: vec2<u32>) -> u32 {
    return nb_mulhi(k, alpha.x) + k * alpha.y;
}

// The k-th R2 point without its ½ seed, as 32-bit fractions (sequence::r2_point).
fn nb_r2_point(k: u32) -> vec2<u32> {
    return vec2<u32>(nb_frac_mul(k, NB_R2_A1), nb_frac_mul(k, NB_R2_A2));
}

// frac(k·(φ − 1)) as a 32-bit fraction (sequence::golden).
fn nb_golden(k: u32) -> u32 {
    return nb_frac_mul(k, NB_GOLDEN);
}

// A 32-bit fraction scaled to 0..n: floor(f·n / 2^32) (sequence::scale).
fn nb_scale(f: u32, n: u32) -> u32 {
    return nb_mulhi(f, n);
}

// A 32-bit fraction as an f32 in [0, 1): its top 24 bits, exactly (sequence::to_unit).
fn nb_to_unit(f: u32) -> f32 {
    return f32(f >> 8u) * (1.0 / 16777216.0);
}

// ---------------------------------------------------------------------------------------------
// Masks (noise_runtime::mask): toroidal wrap and the k-th value through R2 offsets

// c mod n in 0..n for any i32 c (Coord::wrap): a mask for powers of two.
fn nb_wrap(c: i32, n: u32) -> u32 {
    if ((n & (n - 1u)) == 0u) {
        return bitcast<u32>(c) & (n - 1u);
    }
    if (c >= 0) {
        return u32(c) % n;
    }
    let m = (0u - bitcast<u32>(c)) % n;
    return select(n - m, 0u, m == 0u);
}

fn nb_wrap_u(c: u32, n: u32) -> u32 {
    if ((n & (n - 1u)) == 0u) {
        return c & (n - 1u);
    }
    return c % n;
}

// The texel (x, y, layer) holding the k-th independent value of pixel p.xy in frame p.z of a
// mask of dims (width, height, layers): the pixel offset by the k-th R2 point scaled to the
// mask (STBN §5.2; FAST §6). k = 0 is the pixel itself. Mask3::get_k's address, bit for bit.
fn nb_mask_coord_k(p: vec3<i32>, dims: vec3<u32>, k: u32) -> vec3<u32> {
    let o = nb_r2_point(k);
    return vec3<u32>(
        nb_wrap_u(nb_wrap(p.x, dims.x) + nb_scale(o.x, dims.x), dims.x),
        nb_wrap_u(nb_wrap(p.y, dims.y) + nb_scale(o.y, dims.y), dims.y),
        nb_wrap(p.z, dims.z),
    );
}

// The same for a 4D mask (x, y, z, w) uploaded layer-major: layer z + D·w (Mask4::get_k).
fn nb_mask4_coord_k(p: vec4<i32>, dims: vec4<u32>, k: u32) -> vec3<u32> {
    let c = nb_mask_coord_k(p.xyz, dims.xyz, k);
    return vec3<u32>(c.xy, c.z + dims.z * nb_wrap(p.w, dims.w));
}

// The k-th value of a unorm or float mask (r8unorm, rgba8unorm, r32float, …) at pixel p.xy,
// frame p.z. Unorm channels arrive as v/255; see nb_unorm8_unit for the runtime's v/256.
fn nb_mask_load(t: texture_2d_array<f32>, p: vec3<i32>, k: u32) -> vec4<f32> {
    let c = nb_mask_coord_k(p, vec3<u32>(textureDimensions(t), textureNumLayers(t)), k);
    return textureLoad(t, c.xy, c.z, 0);
}

// The k-th value of a 16-bit mask (r16uint) at pixel p.xy, frame p.z.
fn nb_mask_load_u(t: texture_2d_array<u32>, p: vec3<i32>, k: u32) -> vec4<u32> {
    let c = nb_mask_coord_k(p, vec3<u32>(textureDimensions(t), textureNumLayers(t)), k);
    return textureLoad(t, c.xy, c.z, 0);
}

// An 8-bit unorm channel as loaded (v/255) to the runtime's unit value v/256 (Texel::unit):
// the value a threshold compares against, bit for bit.
fn nb_unorm8_unit(v: f32) -> f32 {
    return round(v * 255.0) * (1.0 / 256.0);
}

// A 16-bit channel (r16uint) to the runtime's unit value v/65536 (Texel::unit).
fn nb_u16_unit(v: u32) -> f32 {
    return f32(v) * (1.0 / 65536.0);
}

// One function per kind of texture a mask becomes, each giving the k-th texel of pixel p.xy in
// frame p.z with every channel as the runtime's unit value (Texel::unit, Mask3::get_k): take
// .x of a scalar mask, .xy of a 2-channel one, .xyz of a 3-channel one (uploaded with a fourth
// channel of padding, which reads 255/256, 65535/65536 or 1).
//
// | the mask's format (Rust)     | GPU format        | WGSL binding             | function        |
// | u8, [u8; 2], [u8; 3], [u8; 4] | r8/rg8/rgba8unorm | texture_2d_array<f32>    | nb_mask_unit_u8  |
// | u16, [u16; 2 to 4]           | r16/rg16/rgba16uint | texture_2d_array<u32>  | nb_mask_unit_u16 |
// | f32, [f32; 2 to 4]           | r32/rg32/rgba32float | texture_2d_array<f32> | nb_mask_unit_f32 |

// An 8-bit mask: each channel v/256, bit for bit.
fn nb_mask_unit_u8(t: texture_2d_array<f32>, p: vec3<i32>, k: u32) -> vec4<f32> {
    return round(nb_mask_load(t, p, k) * 255.0) * (1.0 / 256.0);
}

// A 16-bit mask: each channel v/65536, bit for bit.
fn nb_mask_unit_u16(t: texture_2d_array<u32>, p: vec3<i32>, k: u32) -> vec4<f32> {
    return vec4<f32>(nb_mask_load_u(t, p, k)) * (1.0 / 65536.0);
}

// A float mask: the values as stored.
fn nb_mask_unit_f32(t: texture_2d_array<f32>, p: vec3<i32>, k: u32) -> vec4<f32> {
    return nb_mask_load(t, p, k);
}

// The k-th value of pixel p.xy in frame p.z of a scalar 8-bit mask, in [0, 1) as
// Mask3::get_k_unit gives it: nb_mask_unit_u8(t, p, k).x. For a 16-bit or float mask, use
// nb_mask_unit_u16 or nb_mask_unit_f32 (a 16-bit mask does not bind as texture_2d_array<f32>).
fn nb_mask_unit(t: texture_2d_array<f32>, p: vec3<i32>, k: u32) -> f32 {
    return nb_unorm8_unit(nb_mask_load(t, p, k).x);
}

// ---------------------------------------------------------------------------------------------
// Low-discrepancy grids (noise_runtime::ldg), exact for every i32 coordinate

fn nb_r2_bits(p: vec2<i32>) -> u32 {
    return nb_add64(nb_mul64(nb_wide(p.x), NB_R2_A1), nb_mul64(nb_wide(p.y), NB_R2_A2)).y;
}

// The R2 grid frac(x/ρ + y/ρ²) (ldg::r2).
fn nb_r2(p: vec2<i32>) -> f32 {
    return nb_to_unit(nb_r2_bits(p));
}

// R2 animated by the golden ratio per frame (ldg::r2_frame).
fn nb_r2_frame(p: vec2<i32>, frame: u32) -> f32 {
    return nb_to_unit(nb_r2_bits(p) + nb_golden(frame));
}

// A value in [0, 1) advanced by frame·(φ − 1) mod 1 (ldg's animation).
fn nb_animate(v: f32, frame: u32) -> f32 {
    return nb_to_unit(u32(v * 4294967296.0) + nb_golden(frame));
}

// The plus-shaped grid ((x + 3y + ½)/5) mod 1 (ldg::plus).
fn nb_plus(p: vec2<i32>) -> f32 {
    let k = (nb_wrap(p.x, 5u) + 3u * nb_wrap(p.y, 5u)) % 5u;
    return (f32(k) + 0.5) * 0.2;
}

fn nb_plus_frame(p: vec2<i32>, frame: u32) -> f32 {
    return nb_animate(nb_plus(p), frame);
}

// Interleaved gradient noise (Jimenez 2014), frac(52.9829189·frac(0.06711056x + 0.00583715y)),
// as a 32-bit fraction: the inner fraction exact in 64-bit fixed point, the outer product as
// 52·f (exact) plus 0.9829189·f (to 2^-32). The runtime rounds an f64 instead: the two agree
// to within 2^-23, modulo 1.
fn nb_ign_bits(p: vec2<i32>) -> u32 {
    let inner = nb_add64(
        nb_mul64(nb_wide(p.x), vec2<u32>(0x6a8f1506u, 0x112e285cu)),
        nb_mul64(nb_wide(p.y), vec2<u32>(0x5a129b0du, 0x017e8b20u)),
    );
    let whole = 52u * inner.y + nb_mulhi(52u, inner.x);
    return whole + nb_mulhi(0xfba092b2u, inner.y);
}

fn nb_ign(p: vec2<i32>) -> f32 {
    return nb_to_unit(nb_ign_bits(p));
}

// IGN animated by the golden ratio per frame (ldg::ign_frame).
fn nb_ign_frame(p: vec2<i32>, frame: u32) -> f32 {
    return nb_to_unit(nb_ign_bits(p) + nb_golden(frame));
}

// The Bayer matrix of size 2^log2n (log2n in 1..=11, clamped), tiled: (index + ½)/N²
// (ldg::bayer::<N>; exact up to N = 2048).
fn nb_bayer(p: vec2<i32>, log2n: u32) -> f32 {
    let levels = clamp(log2n, 1u, 11u);
    let x = bitcast<u32>(p.x);
    let y = bitcast<u32>(p.y);
    var index = 0u;
    for (var k = 0u; k < levels; k++) {
        let xb = (x >> k) & 1u;
        let yb = (y >> k) & 1u;
        index |= (((xb ^ yb) << 1u) | yb) << (2u * (levels - 1u - k));
    }
    return ldexp(f32(index) + 0.5, -2 * i32(levels));
}

fn nb_bayer_frame(p: vec2<i32>, log2n: u32, frame: u32) -> f32 {
    return nb_animate(nb_bayer(p, log2n), frame);
}

// ---------------------------------------------------------------------------------------------
// Hashes (noise_runtime::hash)

// The runtime's 32-bit avalanche mix.
fn nb_mix(x: u32) -> u32 {
    var h = x;
    h ^= h >> 16u;
    h *= 0x7feb352du;
    h ^= h >> 15u;
    h *= 0x846ca68bu;
    h ^= h >> 16u;
    return h;
}

const NB_PRIME = vec4<u32>(0x8da6b343u, 0xd8163841u, 0xcb1ab31fu, 0x165667b1u);
const NB_CORNER_MUL = 0x27d4eb2du;

// Hash of a 2D cell (hash::hash2).
fn nb_hash2(p: vec2<i32>, seed: u32) -> u32 {
    let c = bitcast<vec2<u32>>(p) * NB_PRIME.xy;
    return nb_mix(seed ^ c.x ^ c.y);
}

// Hash of a 3D cell (hash::hash3).
fn nb_hash3(p: vec3<i32>, seed: u32) -> u32 {
    let c = bitcast<vec3<u32>>(p) * NB_PRIME.xyz;
    return nb_mix(seed ^ c.x ^ c.y ^ c.z);
}

// The PCG hash of one word (PCG-RXS-M-XS; Jarzynski & Olano 2020) (hash::pcg).
fn nb_pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// ---------------------------------------------------------------------------------------------
// Several values per pixel per frame, no texture (noise_runtime::sampler)

// IGN of an inner fraction (nb_ign_bits after its inner product).
fn nb_ign_of_inner(inner: vec2<u32>) -> u32 {
    let whole = 52u * inner.y + nb_mulhi(52u, inner.x);
    return whole + nb_mulhi(0xfba092b2u, inner.y);
}

// IGN's inner fraction at p plus frame·shift (sampler::ign_inner).
fn nb_ign_inner(p: vec2<i32>, frame: u32, shift: vec2<u32>) -> vec2<u32> {
    let inner = nb_add64(
        nb_mul64(nb_wide(p.x), vec2<u32>(0x6a8f1506u, 0x112e285cu)),
        nb_mul64(nb_wide(p.y), vec2<u32>(0x5a129b0du, 0x017e8b20u)),
    );
    return nb_add64(inner, nb_mul64(vec2<u32>(frame, 0u), shift));
}

// 5.588238 px per frame in x and y, and in x only, as shifts of IGN's inner fraction.
const NB_IGN_SHIFT_XY = vec2<u32>(0x11235c12u, 0x685bb218u);
const NB_IGN_SHIFT_X = vec2<u32>(0xf81ae4ebu, 0x6001f3a6u);

// −1/ρ² as a 64-bit fraction (2^64 − NB_R2_A2): the mirrored R2 grid's second weight.
const NB_R2_A2_NEG = vec2<u32>(0x386184e4u, 0x6e1ef25au);

// The four free per-pixel values in a frame as 32-bit fractions: IGN moved 5.588238 px per
// frame, R2 + frame·(φ − 1), mirrored R2 frac(x/ρ − y/ρ²) + frame/ρ, IGNᵀ moved along one axis
// (sampler::grids).
fn nb_sampler_grids(p: vec2<i32>, frame: u32) -> vec4<u32> {
    return vec4<u32>(
        nb_ign_of_inner(nb_ign_inner(p, frame, NB_IGN_SHIFT_XY)),
        nb_r2_bits(p) + nb_golden(frame),
        nb_add64(nb_mul64(nb_wide(p.x), NB_R2_A1), nb_mul64(nb_wide(p.y), NB_R2_A2_NEG)).y
            + nb_frac_mul(frame, NB_R2_A1),
        nb_ign_of_inner(nb_ign_inner(p.yx, frame, NB_IGN_SHIFT_X)),
    );
}

fn nb_to_unit4(f: vec4<u32>) -> vec4<f32> {
    return vec4<f32>(nb_to_unit(f.x), nb_to_unit(f.y), nb_to_unit(f.z), nb_to_unit(f.w));
}

// IGN, R2, mirrored R2 and IGNᵀ of a pixel in a frame (sampler::ign_r2::<4>; .xy for a pair).
fn nb_ign_r2(p: vec2<i32>, frame: u32) -> vec4<f32> {
    return nb_to_unit4(nb_sampler_grids(p, frame));
}

// 2^64·φ_d^-(k+1) of the R3 and R4 sequences (R1 is NB_GOLDEN, R2 NB_R2_A1 and NB_R2_A2).
const NB_R3_A1 = vec2<u32>(0xd192ed04u, 0xd1b54a32u);
const NB_R3_A2 = vec2<u32>(0xfb8fac03u, 0xabc98388u);
const NB_R3_A3 = vec2<u32>(0x2f3d8dd7u, 0x8cb92ba7u);
const NB_R4_A1 = vec2<u32>(0x75ae2165u, 0xdb4f0b91u);
const NB_R4_A2 = vec2<u32>(0x03a4615fu, 0xbbe05633u);
const NB_R4_A3 = vec2<u32>(0xa1fe1576u, 0xa0f2ec75u);
const NB_R4_A4 = vec2<u32>(0x7d9ed689u, 0x89e18285u);

fn nb_rd2_bits(frame: u32) -> vec2<u32> {
    return nb_r2_point(frame);
}

fn nb_rd3_bits(frame: u32) -> vec3<u32> {
    return vec3<u32>(nb_frac_mul(frame, NB_R3_A1), nb_frac_mul(frame, NB_R3_A2), nb_frac_mul(frame, NB_R3_A3));
}

fn nb_rd4_bits(frame: u32) -> vec4<u32> {
    return vec4<u32>(
        nb_frac_mul(frame, NB_R4_A1), nb_frac_mul(frame, NB_R4_A2),
        nb_frac_mul(frame, NB_R4_A3), nb_frac_mul(frame, NB_R4_A4),
    );
}

// A value in [0, 1) as a 32-bit fraction.
fn nb_fraction(v: f32) -> u32 {
    return u32(clamp(v, 0.0, 1.0) * 4294967296.0);
}

// The frame-th point of R2 / R3, Cranley–Patterson rotated by values in [0, 1) (sampler::rd).
fn nb_rd2(frame: u32, rotation: vec2<f32>) -> vec2<f32> {
    let b = nb_rd2_bits(frame) + vec2<u32>(nb_fraction(rotation.x), nb_fraction(rotation.y));
    return vec2<f32>(nb_to_unit(b.x), nb_to_unit(b.y));
}

fn nb_rd3(frame: u32, rotation: vec3<f32>) -> vec3<f32> {
    let r = vec3<u32>(nb_fraction(rotation.x), nb_fraction(rotation.y), nb_fraction(rotation.z));
    return nb_to_unit4(vec4<u32>(nb_rd3_bits(frame) + r, 0u)).xyz;
}

// R2 / R3 / R4 rotated by the free grids of nb_ign_r2 in frame 0 (sampler::rd_ign_r2).
fn nb_rd2_ign_r2(p: vec2<i32>, frame: u32) -> vec2<f32> {
    return nb_to_unit4(vec4<u32>(nb_rd2_bits(frame) + nb_sampler_grids(p, 0u).xy, 0u, 0u)).xy;
}

fn nb_rd3_ign_r2(p: vec2<i32>, frame: u32) -> vec3<f32> {
    return nb_to_unit4(vec4<u32>(nb_rd3_bits(frame) + nb_sampler_grids(p, 0u).xyz, 0u)).xyz;
}

fn nb_rd4_ign_r2(p: vec2<i32>, frame: u32) -> vec4<f32> {
    return nb_to_unit4(nb_rd4_bits(frame) + nb_sampler_grids(p, 0u));
}

// The free baseline: a rank-1 R2 lattice per pair of dimensions, each pair walking R2 from
// its own per-pixel shifts, the grids of frame 0 (sampler::r2_pairs; .xy for one pair).
fn nb_r2_pairs(p: vec2<i32>, index: u32) -> vec4<f32> {
    return nb_to_unit4(nb_r2_point(index).xyxy + nb_sampler_grids(p, 0u));
}

// The first four dimensions of the index-th Sobol point as 32-bit fractions, the direction
// numbers made by their recurrences as the index's bits are read (dimension 0 is the radical
// inverse; 1–3 from x + 1, x² + x + 1 and x³ + x + 1).
fn nb_sobol4(index: u32) -> vec4<u32> {
    var out = vec4<u32>(reverseBits(index), 0u, 0u, 0u);
    var n = index;
    var v1 = 0x80000000u;
    var v2 = vec2<u32>(0x80000000u, 0xc0000000u);
    var v3 = vec3<u32>(0x80000000u, 0xc0000000u, 0x20000000u);
    loop {
        if (n == 0u) { break; }
        if ((n & 1u) != 0u) {
            out.y ^= v1;
            out.z ^= v2.x;
            out.w ^= v3.x;
        }
        v1 ^= v1 >> 1u;
        v2 = vec2<u32>(v2.y, v2.x ^ (v2.x >> 2u) ^ v2.y);
        v3 = vec3<u32>(v3.y, v3.z, v3.x ^ (v3.x >> 3u) ^ v3.y);
        n >>= 1u;
    }
    return out;
}

// Burley's hash-based Owen scramble of a 32-bit fraction (Laine–Karras on reversed bits).
fn nb_owen(x: u32, seed: u32) -> u32 {
    var v = reverseBits(x);
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16u) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return reverseBits(v);
}

fn nb_seed_combine(seed: u32, v: u32) -> u32 {
    return nb_mix(seed ^ (v + 0x9e3779b9u + (seed << 6u) + (seed >> 2u)));
}

// Four values of a pixel from the shuffled, Owen-scrambled Sobol sequence (Burley 2020)
// (sampler::sobol_owen::<4>; the first D are those of smaller D).
fn nb_sobol_owen(p: vec2<i32>, frame: u32, seed: u32) -> vec4<f32> {
    let pixel = nb_hash2(p, seed);
    let s = nb_sobol4(nb_owen(frame, pixel));
    return nb_to_unit4(vec4<u32>(
        nb_owen(s.x, nb_seed_combine(pixel, 0u)), nb_owen(s.y, nb_seed_combine(pixel, 1u)),
        nb_owen(s.z, nb_seed_combine(pixel, 2u)), nb_owen(s.w, nb_seed_combine(pixel, 3u)),
    ));
}

// A free sampler built for a moving camera (sampler::motion_pairs): per pair and frame a
// rank-1 lattice {i·(1, z)/N} moved by a shift linear in the pixel and the frame,
// c = frac(x·a + y·b + frame·g) in 32-bit fixed point; the second pair's sample i is its
// lattice point i + h, h a hash of the pixel and frame. The constants are the runtime's
// MOTION_PAIRS, two vec4 per spp and pair: (z, a.x, a.y, b.x), (b.y, g.x, g.y, 0).
// motion_pairs table (noisebake search-sampler --all --wgsl): begin
var<private> NB_MOTION: array<vec4<u32>, 64> = array<vec4<u32>, 64>(
    vec4<u32>(0u, 0x8c65a2ddu, 0xe2062926u, 0x51e5544eu), vec4<u32>(0x9b5489eau, 0x0dfda986u, 0x3954f93fu, 0u), // spp 1, pair 0
    vec4<u32>(0u, 0xedd5e720u, 0x968138c8u, 0xa30d8a18u), vec4<u32>(0x458dc40du, 0x2d3f3f55u, 0x3484a983u, 0u), // spp 1, pair 1
    vec4<u32>(1u, 0x9369ae36u, 0x0e6925adu, 0xbfedd09cu), vec4<u32>(0x65034d56u, 0x25744af8u, 0x301bf6ddu, 0u), // spp 2, pair 0
    vec4<u32>(1u, 0x65df569eu, 0xa029aa08u, 0xd9278108u), vec4<u32>(0x8a6cb80au, 0xc360b13eu, 0xa902fcf2u, 0u), // spp 2, pair 1
    vec4<u32>(1u, 0x2438d7e1u, 0x5f8f3aebu, 0x5ed227ceu), vec4<u32>(0x031ada04u, 0x4bd477b8u, 0x6c2e6462u, 0u), // spp 3, pair 0
    vec4<u32>(1u, 0x52d1fa2bu, 0x1aab9d1du, 0x65c79221u), vec4<u32>(0x599fb012u, 0xde8a094au, 0x2486c583u, 0u), // spp 3, pair 1
    vec4<u32>(1u, 0x93a594d6u, 0x0888cefau, 0x44888421u), vec4<u32>(0x5f42bb10u, 0xeee20c7eu, 0x9fc8b024u, 0u), // spp 4, pair 0
    vec4<u32>(1u, 0x4b8e9a65u, 0xa7b1b101u, 0x29a471f0u), vec4<u32>(0x8b5edcf0u, 0xf5086b5cu, 0x3e8003f8u, 0u), // spp 4, pair 1
    vec4<u32>(1u, 0xcd13c5aeu, 0x62921828u, 0x4d74eb6fu), vec4<u32>(0x14f7e051u, 0xa0f970fdu, 0x890ca9c1u, 0u), // spp 5, pair 0
    vec4<u32>(1u, 0xb7851f83u, 0x96470b8cu, 0x1a3d6a75u), vec4<u32>(0x9ecc7cd8u, 0xece86fdbu, 0xf17a26d2u, 0u), // spp 5, pair 1
    vec4<u32>(1u, 0x4a99fb4eu, 0xdc682919u, 0x384083ffu), vec4<u32>(0x85d50a6au, 0x7b59dbd9u, 0x90bf748cu, 0u), // spp 6, pair 0
    vec4<u32>(1u, 0xdec7b8f2u, 0x7dc9fe58u, 0x87c7fe63u), vec4<u32>(0xcba984c9u, 0xcb4e8c2fu, 0xec1a31f8u, 0u), // spp 6, pair 1
    vec4<u32>(1u, 0xd3b30836u, 0x8cb1cdbfu, 0xb8eeeb61u), vec4<u32>(0xc4296aa8u, 0xa5310778u, 0x8557d989u, 0u), // spp 7, pair 0
    vec4<u32>(3u, 0xc1a044f7u, 0x92d9fe47u, 0xaf4488aeu), vec4<u32>(0xf66440d9u, 0x4ff984cbu, 0x2e2dca56u, 0u), // spp 7, pair 1
    vec4<u32>(3u, 0xa9f18421u, 0x44b3cf87u, 0x620f1b2du), vec4<u32>(0x28f056adu, 0x89470492u, 0xed043e68u, 0u), // spp 8, pair 0
    vec4<u32>(3u, 0xb452fa2eu, 0x40fde7bcu, 0x41531651u), vec4<u32>(0x34530da3u, 0x08278d85u, 0x5745bbf3u, 0u), // spp 8, pair 1
    vec4<u32>(2u, 0x64024f64u, 0x70330486u, 0xe0303e99u), vec4<u32>(0x5ee18d5fu, 0xb9a0433eu, 0x757f7417u, 0u), // spp 9, pair 0
    vec4<u32>(2u, 0xf065e6fcu, 0xa37991d9u, 0x66b83356u), vec4<u32>(0x6eeabe60u, 0x308d5ad2u, 0x6cb375d8u, 0u), // spp 9, pair 1
    vec4<u32>(3u, 0xb9767f60u, 0xe4d4eaa8u, 0x360965beu), vec4<u32>(0x77f77d56u, 0x22a10253u, 0x710bf80bu, 0u), // spp 10, pair 0
    vec4<u32>(3u, 0x56cbeb37u, 0xa7571536u, 0x997390aau), vec4<u32>(0xf1aa13a6u, 0x1b604a5bu, 0xdca097ddu, 0u), // spp 10, pair 1
    vec4<u32>(3u, 0xe159aeaeu, 0xb048f565u, 0x6a5d0fb4u), vec4<u32>(0x692d0eccu, 0x55fa8853u, 0xcd3ae946u, 0u), // spp 11, pair 0
    vec4<u32>(3u, 0x438a0440u, 0x5791be3du, 0x70b91816u), vec4<u32>(0xf4c89d9cu, 0x6ba71537u, 0x5958bfe9u, 0u), // spp 11, pair 1
    vec4<u32>(5u, 0xd7a2eeeeu, 0x95c612d2u, 0x90ca18ceu), vec4<u32>(0x89edcf65u, 0xae896724u, 0x41196248u, 0u), // spp 12, pair 0
    vec4<u32>(1u, 0xc41a23d6u, 0x8fb821e3u, 0x5077d136u), vec4<u32>(0xd6cf5b5fu, 0xae95832fu, 0x62d78e17u, 0u), // spp 12, pair 1
    vec4<u32>(4u, 0x55dbeb44u, 0x4e7b7f22u, 0x95e29c22u), vec4<u32>(0x5eb0f8e3u, 0x7d8af120u, 0xa2f85674u, 0u), // spp 13, pair 0
    vec4<u32>(6u, 0x4aa6c86au, 0x714d4aadu, 0x1fa90fa7u), vec4<u32>(0x319ee702u, 0x8a6583e7u, 0x06a0a2b8u, 0u), // spp 13, pair 1
    vec4<u32>(1u, 0x8972120cu, 0xc8d53563u, 0x461e7094u), vec4<u32>(0x7376d394u, 0xe9bba021u, 0xd6a41d4eu, 0u), // spp 14, pair 0
    vec4<u32>(3u, 0x657dbba3u, 0xa3d418b9u, 0xbc9b96a8u), vec4<u32>(0xb95ee2a4u, 0x893ff394u, 0x0521a1cbu, 0u), // spp 14, pair 1
    vec4<u32>(1u, 0x6bbc7419u, 0x413f176bu, 0x521e2301u), vec4<u32>(0x96d255cau, 0x979e1855u, 0x2b8990dfu, 0u), // spp 15, pair 0
    vec4<u32>(7u, 0xb33f8926u, 0x7d820fbbu, 0x2814a8bcu), vec4<u32>(0x2cc142b3u, 0xebc47ae6u, 0xbf4b48b3u, 0u), // spp 15, pair 1
    vec4<u32>(5u, 0x4ab882afu, 0x066026c0u, 0xc76c755fu), vec4<u32>(0x99af903au, 0xe0de020cu, 0x4feb895fu, 0u), // spp 16, pair 0
    vec4<u32>(5u, 0x437e1de1u, 0xa5e735adu, 0x6ab883ddu), vec4<u32>(0x11f7cdcdu, 0xc5d3b8d9u, 0xd3ccf6a3u, 0u), // spp 16, pair 1
);
// motion_pairs table: end

const NB_MOTION_PAIRING_SEED = 0x6d6f7469u;

// Point i of the n-point lattice of spp n's pair `pair`, moved by its shift at pixel p in
// frame f, as 32-bit fractions.
fn nb_motion_pair(p: vec2<i32>, f: u32, i: u32, n: u32, pair: u32) -> vec2<u32> {
    let k = ((n - 1u) * 2u + pair) * 2u;
    let t0 = NB_MOTION[k];
    let t1 = NB_MOTION[k + 1u];
    let u = bitcast<vec2<u32>>(p);
    let c = vec2<u32>(u.x * t0.y + u.y * t0.w + f * t1.y, u.x * t0.z + u.y * t1.x + f * t1.z);
    var ux = c.x;
    if (n > 1u) {
        // floor(2^32 / n): (2^32 − 1) / n, plus one where n divides 2^32.
        let r = 0xffffffffu / n + select(0u, 1u, 0xffffffffu % n == n - 1u);
        ux = i * r + nb_mulhi(c.x, r);
    }
    return vec2<u32>(ux, t0.x * ux + c.y);
}

// Sample i of frame `frame` at pixel p for a renderer taking spp samples per pixel per frame,
// four dimensions as 32-bit fractions (sampler::motion_pairs::<4>; .xy for one pair).
fn nb_motion_pairs_bits(p: vec2<i32>, frame: u32, i: u32, spp: u32) -> vec4<u32> {
    var n = max(spp, 1u);
    var f = frame + i / n;
    var s = i % n;
    if (n > 16u) {
        let blocks = (n + 15u) / 16u;
        f = f * blocks + s / 16u;
        s = s % 16u;
        n = 16u;
    }
    let h = nb_hash3(vec3<i32>(p, bitcast<i32>(f)), NB_MOTION_PAIRING_SEED);
    return vec4<u32>(nb_motion_pair(p, f, s, n, 0u), nb_motion_pair(p, f, (s + h % n) % n, n, 1u));
}

fn nb_motion_pairs(p: vec2<i32>, frame: u32, i: u32, spp: u32) -> vec4<f32> {
    return nb_to_unit4(nb_motion_pairs_bits(p, frame, i, spp));
}

// The tiles' rank-1 lattice generator, one odd multiplier per dimension (TILE_GENERATOR).
fn nb_tile_generator(d: u32) -> u32 {
    var g = array<u32, 8>(
        1u, 47597u, 65513u, 3118222261u, 65447u, 3115080859u, 65169u, 3101848893u,
    );
    return g[d & 7u];
}

// Dimension `axis` (0 or 1) of point n of the Sobol sequence as a 32-bit fraction
// (sampler::sobol2): van der Corput (n bit-reversed), then the Pascal matrix's image of n
// (direction numbers v_0 = 2^31, v_k = v_(k-1) ^ (v_(k-1) >> 1)), bit by bit.
fn nb_sobol2(n: u32, axis: u32) -> u32 {
    if ((axis & 1u) == 0u) {
        return reverseBits(n);
    }
    var x = 0u;
    var v = 0x80000000u;
    var m = n;
    while (m != 0u) {
        if ((m & 1u) != 0u) {
            x = x ^ v;
        }
        m = m >> 1u;
        v = v ^ (v >> 1u);
    }
    return x;
}

// Dimension d of sample n of a pixel whose key in that dimension is `key`, in a dims-dimensional
// tile whose pairs flagged in `sobol_pairs` (bit p for dimensions 2p, 2p + 1) run Sobol
// (sampler::tile_point): reverseBits(n) * generator + key * 2^16 wrapping for a lattice
// dimension (the rank-1 lattice in radical-inverse order),
// owen(sobol2(n, d % 2), mix(key * 2^16 + d)) for a Sobol one.
fn nb_tile_point(n: u32, d: u32, dims: u32, key: u32, sobol_pairs: u32) -> u32 {
    let dd = d % clamp(dims, 1u, 8u);
    if (((sobol_pairs >> (dd / 2u)) & 1u) != 0u) {
        return nb_owen(nb_sobol2(n, dd), nb_mix((key << 16u) | dd));
    }
    return reverseBits(n) * nb_tile_generator(dd) + (key << 16u);
}

// Dimension d of sample i of pixel p in frame `frame` of a baked sampler tile, as a 32-bit
// fraction (SamplerTile::sample_bits): `keys` is the tile's r16uint key mask (one layer per
// dimension), `spp` the samples per frame it was baked for, `sobol_pairs` its
// SamplerTile::sobol_pairs. The sample is point n = frame * spp + i of the pair's sequence,
// shifted by the pixel's key (nb_tile_point).
fn nb_sampler_tile_bits(keys: texture_2d_array<u32>, p: vec2<i32>, frame: u32, i: u32, d: u32, spp: u32, sobol_pairs: u32) -> u32 {
    let dims = textureNumLayers(keys);
    let size = textureDimensions(keys);
    let dd = d % dims;
    let c = vec2<u32>(nb_wrap(p.x, size.x), nb_wrap(p.y, size.y));
    let key = textureLoad(keys, c, dd, 0).x;
    let n = frame * max(spp, 1u) + i % max(spp, 1u);
    return nb_tile_point(n, dd, dims, key, sobol_pairs);
}

// The same in [0, 1) (SamplerTile::sample).
fn nb_sampler_tile(keys: texture_2d_array<u32>, p: vec2<i32>, frame: u32, i: u32, d: u32, spp: u32, sobol_pairs: u32) -> f32 {
    return nb_to_unit(nb_sampler_tile_bits(keys, p, frame, i, d, spp, sobol_pairs));
}

// Pair `pair` (dimensions 2 pair, 2 pair + 1) of sample i as a cosine-weighted direction about
// +z by the polar map r = sqrt(u), phi = 2 pi v, z = sqrt(1 - u)
// (SamplerTile::cosine_hemisphere, warp::cosine_hemisphere_polar). A float path: within the
// documented tolerance of the CPU's (noise_runtime::shaders).
fn nb_sampler_tile_cosine_hemisphere(keys: texture_2d_array<u32>, p: vec2<i32>, frame: u32, i: u32, pair: u32, spp: u32, sobol_pairs: u32) -> vec3<f32> {
    let u = nb_sampler_tile(keys, p, frame, i, 2u * pair, spp, sobol_pairs);
    let v = nb_sampler_tile(keys, p, frame, i, 2u * pair + 1u, spp, sobol_pairs);
    return nb_cosine_hemisphere_polar(u, v);
}

// The polar map of the unit square to the unit disk: r = sqrt(u), phi = 2 pi v
// (warp::disk_polar).
fn nb_disk_polar(u: f32, v: f32) -> vec2<f32> {
    let r = sqrt(clamp(u, 0.0, 1.0));
    let phi = 6.283185307179586 * clamp(v, 0.0, 1.0);
    return vec2<f32>(r * cos(phi), r * sin(phi));
}

// Cosine-weighted direction about +z: the polar disk point lifted, z = sqrt(1 - u)
// (warp::cosine_hemisphere_polar).
fn nb_cosine_hemisphere_polar(u: f32, v: f32) -> vec3<f32> {
    let d = nb_disk_polar(u, v);
    return vec3<f32>(d, sqrt(1.0 - clamp(u, 0.0, 1.0)));
}

// ---------------------------------------------------------------------------------------------
// 3D Perlin noise and fBm (noise_runtime::stochastic), deterministic and one-sample estimators
// (Fajardo & Pharr, Algorithms 1 and 2)

// The 12 cube-edge gradients of improved noise padded to 16 (Perlin 2002), the runtime's order.
var<private> NB_GRAD3: array<vec3<f32>, 16> = array<vec3<f32>, 16>(
    vec3<f32>(1.0, 1.0, 0.0), vec3<f32>(-1.0, 1.0, 0.0), vec3<f32>(1.0, -1.0, 0.0), vec3<f32>(-1.0, -1.0, 0.0),
    vec3<f32>(1.0, 0.0, 1.0), vec3<f32>(-1.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, -1.0), vec3<f32>(-1.0, 0.0, -1.0),
    vec3<f32>(0.0, 1.0, 1.0), vec3<f32>(0.0, -1.0, 1.0), vec3<f32>(0.0, 1.0, -1.0), vec3<f32>(0.0, -1.0, -1.0),
    vec3<f32>(1.0, 1.0, 0.0), vec3<f32>(1.0, -1.0, 0.0), vec3<f32>(-1.0, 1.0, 0.0), vec3<f32>(0.0, -1.0, -1.0),
);

// The gradient of a corner hash: its top four bits choose.
fn nb_grad3(h: u32) -> vec3<f32> {
    return NB_GRAD3[h >> 28u];
}

// Perlin's quintic fade 6t⁵ − 15t⁴ + 10t³ (math::fade).
fn nb_fade(t: f32) -> f32 {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

fn nb_lerp(t: f32, a: f32, b: f32) -> f32 {
    return a + t * (b - a);
}

// The dot product of corner (xp, yp, zp)'s gradient with the offset d.
fn nb_corner(seed: u32, xp: u32, yp: u32, zp: u32, d: vec3<f32>) -> f32 {
    let g = nb_grad3((seed ^ xp ^ yp ^ zp) * NB_CORNER_MUL);
    return g.x * d.x + g.y * d.y + g.z * d.z;
}

// 3D Perlin noise (improved noise), about [-1, 1] (stochastic::perlin3).
fn nb_perlin3(p: vec3<f32>, seed: u32) -> f32 {
    let fl = floor(p);
    let f = p - fl;
    let lo = bitcast<vec3<u32>>(vec3<i32>(fl)) * NB_PRIME.xyz;
    let hi = lo + NB_PRIME.xyz;
    let u = nb_fade(f.x);
    let v = nb_fade(f.y);
    let w = nb_fade(f.z);
    let g = f - vec3<f32>(1.0);
    return nb_lerp(
        w,
        nb_lerp(
            v,
            nb_lerp(u, nb_corner(seed, lo.x, lo.y, lo.z, f), nb_corner(seed, hi.x, lo.y, lo.z, vec3<f32>(g.x, f.y, f.z))),
            nb_lerp(u, nb_corner(seed, lo.x, hi.y, lo.z, vec3<f32>(f.x, g.y, f.z)), nb_corner(seed, hi.x, hi.y, lo.z, vec3<f32>(g.x, g.y, f.z))),
        ),
        nb_lerp(
            v,
            nb_lerp(u, nb_corner(seed, lo.x, lo.y, hi.z, vec3<f32>(f.x, f.y, g.z)), nb_corner(seed, hi.x, lo.y, hi.z, vec3<f32>(g.x, f.y, g.z))),
            nb_lerp(u, nb_corner(seed, lo.x, hi.y, hi.z, vec3<f32>(f.x, g.y, g.z)), nb_corner(seed, hi.x, hi.y, hi.z, g)),
        ),
    );
}

// The largest f32 below 1.
const NB_ONE_BELOW: f32 = 0.99999994;

// ξ clamped into [0, 1): negatives and NaN to 0, 1 and above to the largest f32 below 1
// (estimators::sanitize_xi).
fn nb_sanitize_xi(xi: f32) -> f32 {
    let b = bitcast<u32>(xi);
    return min(bitcast<f32>(select(0u, b, b <= 0x7f800000u)), NB_ONE_BELOW);
}

// A weight in [0, 1] as a fixed-point number with 23 fractional bits (estimators::fixed).
fn nb_fixed(t: f32) -> u32 {
    return bitcast<u32>(t + 1.0) - 0x3f800000u;
}

// The interval one ξ narrows as Algorithm 1 decides axis after axis (estimators::Narrowing):
// ξ's residue r in it and its length l, in 23-bit fixed point.
struct NbNarrowing {
    r: u32,
    l: u32,
}

fn nb_narrowing(xi: f32) -> NbNarrowing {
    return NbNarrowing(min(nb_fixed(nb_sanitize_xi(xi)), 0x7fffffu), 0x800000u);
}

// One decision with weight t: all ones when the upper side was taken (Narrowing::upper).
fn nb_upper(n: ptr<function, NbNarrowing>, t: f32) -> u32 {
    let w = nb_fixed(t);
    // (l·w) >> 23 in 64 bits: both factors are at most 2^23 (and an ulp).
    let cut = (nb_mulhi((*n).l, w) << 9u) | (((*n).l * w) >> 23u);
    let up = select(0u, 0xffffffffu, (*n).r < cut);
    if (up == 0u) {
        (*n).r -= cut;
        (*n).l -= cut;
    } else {
        (*n).l = cut;
    }
    return up;
}

// One-sample estimator of nb_perlin3 (Algorithm 1): one corner, chosen with probability equal
// to its interpolation weight by one ξ, and only its gradient evaluated
// (stochastic::perlin3_stochastic).
fn nb_perlin3_estimate(p: vec3<f32>, seed: u32, xi: f32) -> f32 {
    let fl = floor(p);
    let f = p - fl;
    let cell = bitcast<vec3<u32>>(vec3<i32>(fl));
    let t = vec3<f32>(nb_fade(f.x), nb_fade(f.y), nb_fade(f.z));
    var n = nb_narrowing(xi);
    var h = seed;
    var o = vec3<f32>(0.0);
    for (var a = 0u; a < 3u; a++) {
        let up = nb_upper(&n, t[a]);
        h ^= cell[a] * NB_PRIME[a] + (up & NB_PRIME[a]);
        o[a] = f32(up & 1u);
    }
    let d = nb_grad3(h * NB_CORNER_MUL) * (f - o);
    return d.x + d.y + d.z;
}

// Octaves, lacunarity and gain of a fractal sum (stochastic::Fractal).
struct NbFractal {
    octaves: u32,
    lacunarity: f32,
    gain: f32,
}

// The paper's settings: 10 octaves, lacunarity 2, gain ½ (Fractal::default).
fn nb_fractal_default() -> NbFractal {
    return NbFractal(10u, 2.0, 0.5);
}

// The parameters made safe as the runtime makes them: octaves in 1..=32, lacunarity in
// [-1024, 1024], gain in [-16, 16].
fn nb_fractal_sane(f: NbFractal) -> NbFractal {
    return NbFractal(clamp(f.octaves, 1u, 32u), clamp(f.lacunarity, -1024.0, 1024.0), clamp(f.gain, -16.0, 16.0));
}

// The seed of octave o (each octave an independent noise).
fn nb_octave_seed(seed: u32, o: u32) -> u32 {
    return seed + o * 0x9e3779b9u;
}

// fBm of 3D Perlin noise: Σ gain^o · perlin3(p · lacunarity^o) (eq. 9; stochastic::fbm3).
fn nb_fbm3(p: vec3<f32>, fractal: NbFractal, seed: u32) -> f32 {
    let f = nb_fractal_sane(fractal);
    var amp = 1.0;
    var freq = 1.0;
    var sum = 0.0;
    for (var o = 0u; o < f.octaves; o++) {
        sum += amp * nb_perlin3(p * freq, nb_octave_seed(seed, o));
        amp *= f.gain;
        freq *= f.lacunarity;
    }
    return sum;
}

// One-sample estimator of nb_fbm3 (Algorithm 2): octave o chosen with probability
// |gain^o| / Σ|gain^i| by ξ, ξ remapped within the octave's interval, and one Perlin gradient
// in it — one hash and one dot product whatever the octave count (stochastic::fbm3_stochastic).
fn nb_fbm3_estimate(p: vec3<f32>, fractal: NbFractal, seed: u32, xi: f32) -> f32 {
    let f = nb_fractal_sane(fractal);
    let g = abs(f.gain);
    var total = 0.0;
    var a = 1.0;
    for (var o = 0u; o < f.octaves; o++) {
        total += a;
        a *= g;
    }
    let goal = min(nb_sanitize_xi(xi) * total, bitcast<f32>(bitcast<u32>(total) - 1u));
    // The chosen octave is the last whose interval starts at or below the goal.
    var start = 0.0;
    var amp = 1.0;
    var freq = 1.0;
    var pick = vec4<f32>(0.0, 1.0, 1.0, 0.0); // start, amplitude, frequency, octave
    for (var o = 0u; o < f.octaves; o++) {
        if (o == 0u || goal >= start) {
            pick = vec4<f32>(start, amp, freq, f32(o));
        }
        start += amp;
        amp *= g;
        freq *= f.lacunarity;
    }
    let octave = u32(pick.w);
    var x = 0.0;
    if (pick.y > 0.0) {
        x = clamp((goal - pick.x) / pick.y, 0.0, NB_ONE_BELOW);
    }
    let v = total * nb_perlin3_estimate(p * pick.z, nb_octave_seed(seed, octave), x);
    return select(v, -v, f.gain < 0.0 && (octave & 1u) == 1u);
}

// ---------------------------------------------------------------------------------------------
// Curl-noise jittering in 2D (noise_runtime::cnj; Bærentzen, Frisvad & Martínez 2023)

// Parameters of the jittered triangular lattice (cnj::Cnj2; RK4 integration only).
struct NbCnj2 {
    // Streamline time (the paper's t).
    t: f32,
    // Noise cell size in lattice spacings (the paper's s); at least 1e-3.
    s: f32,
    seed: u32,
    // Distance between neighbouring lattice points, world units.
    spacing: f32,
    // RK4 steps over [0, t], 1..=64.
    steps: u32,
}

// The paper's Perlin-noise parameters (Table 1; Cnj2::PAPER).
fn nb_cnj2_paper() -> NbCnj2 {
    return NbCnj2(1.05862, 2.86207, 0u, 1.0, 1u);
}

// One jittered point found by a query (cnj::Neighbor2).
struct NbNeighbor2 {
    point: vec2<f32>,
    distance: f32,
    site: vec2<i32>,
}

// Row spacing of the triangular lattice: √3/2.
const NB_ROW: f32 = 0.8660254;
// Amplitude of the 2D field relative to nb_noise2's (cnj::field::NOISE_GAIN).
const NB_NOISE_GAIN: f32 = 1.4375;

// A lattice gradient in [-1, 1]² (cnj::field's grad2).
fn nb_cnj_grad2(c: vec2<i32>, seed: u32) -> vec2<f32> {
    let m = bitcast<vec2<u32>>(c) * NB_PRIME.xy;
    var h = (seed ^ m.x ^ m.y) * NB_CORNER_MUL;
    h = (h ^ (h >> 15u)) * 0x2c1b3c6du;
    return vec2<f32>(f32(h >> 16u), f32(h & 0xffffu)) * (1.0 / 32768.0) - 1.0;
}

// The gradient (∂n/∂x, ∂n/∂y) of 2D gradient noise with quintic fade (cnj::noise2).
fn nb_noise2_grad(p: vec2<f32>, seed: u32) -> vec2<f32> {
    let fl = floor(p);
    let c = vec2<i32>(fl);
    let x = p.x - fl.x;
    let y = p.y - fl.y;
    let ga = nb_cnj_grad2(c, seed);
    let gb = nb_cnj_grad2(c + vec2<i32>(1, 0), seed);
    let gc = nb_cnj_grad2(c + vec2<i32>(0, 1), seed);
    let gd = nb_cnj_grad2(c + vec2<i32>(1, 1), seed);
    let va = ga.x * x + ga.y * y;
    let vb = gb.x * (x - 1.0) + gb.y * y;
    let vc = gc.x * x + gc.y * (y - 1.0);
    let vd = gd.x * (x - 1.0) + gd.y * (y - 1.0);
    let ux = nb_fade(x);
    let uy = nb_fade(y);
    let sx = x * (x - 1.0);
    let sy = y * (y - 1.0);
    let dx = 30.0 * sx * sx;
    let dy = 30.0 * sy * sy;
    let k = va - vb - vc + vd;
    let nx = ga.x + ux * (gb.x - ga.x) + uy * (gc.x - ga.x) + ux * uy * (ga.x - gb.x - gc.x + gd.x)
        + dx * (uy * k + (vb - va));
    let ny = ga.y + ux * (gb.y - ga.y) + uy * (gc.y - ga.y) + ux * uy * (ga.y - gb.y - gc.y + gd.y)
        + dy * (ux * k + (vc - va));
    return vec2<f32>(nx, ny);
}

// The curl-noise velocity V = (∂N(p/s)/∂y, −∂N(p/s)/∂x) (eq. 5; cnj::velocity2).
fn nb_cnj_velocity2(p: vec2<f32>, s: f32, seed: u32) -> vec2<f32> {
    let n = nb_noise2_grad(p * (1.0 / s), seed);
    let inv = NB_NOISE_GAIN / s;
    return vec2<f32>(n.y * inv, -n.x * inv);
}

// A site's position on the lattice (spacing 1): odd rows shifted by half a spacing.
fn nb_cnj2_site_position(site: vec2<i32>) -> vec2<f32> {
    return vec2<f32>(f32(site.x) + 0.5 * f32(site.y & 1), f32(site.y) * NB_ROW);
}

// The jittered point of a site, world units: the site moved along the flow for time t by RK4
// (direct CNJ, eq. 4; Cnj2::point).
fn nb_cnj2_point(c: NbCnj2, site: vec2<i32>) -> vec2<f32> {
    let s = max(c.s, 1e-3);
    let steps = clamp(c.steps, 1u, 64u);
    let p0 = nb_cnj2_site_position(site);
    let h = c.t / f32(steps);
    var d = vec2<f32>(0.0);
    for (var i = 0u; i < steps; i++) {
        let k1 = nb_cnj_velocity2(p0 + d, s, c.seed);
        let k2 = nb_cnj_velocity2(p0 + d + 0.5 * h * k1, s, c.seed);
        let k3 = nb_cnj_velocity2(p0 + d + 0.5 * h * k2, s, c.seed);
        let k4 = nb_cnj_velocity2(p0 + d + h * k3, s, c.seed);
        d += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    return (p0 + d) * c.spacing;
}

// The lattice site nearest to a position in lattice units (Cnj2::nearest_site).
fn nb_cnj2_nearest_site(q: vec2<f32>) -> vec2<i32> {
    let j0 = i32(round(q.y / NB_ROW));
    var best = vec2<i32>(0);
    var best_d = 3.4e38;
    for (var j = j0 - 1; j <= j0 + 1; j++) {
        let par = 0.5 * f32(j & 1);
        let i = i32(round(q.x - par));
        let e = vec2<f32>(f32(i) + par, f32(j) * NB_ROW) - q;
        let d = dot(e, e);
        if (d < best_d) {
            best = vec2<i32>(i, j);
            best_d = d;
        }
    }
    return best;
}

// The nearest jittered point to x (world units): point, distance and site (Cnj2::closest).
// Searches the 19 sites within two hex rings of the nearest lattice site, which hold the
// nearest point whenever displacements stay below about 1.2 spacings (the paper's parameters
// give 1.15). Positions are f32 here, so queries should stay within a few thousand spacings of
// the origin (see noise_runtime::shaders).
fn nb_cnj2_closest(c: NbCnj2, x: vec2<f32>) -> NbNeighbor2 {
    let sp = select(1.0, c.spacing, c.spacing > 0.0);
    var cfg = c;
    cfg.spacing = sp;
    let center = nb_cnj2_nearest_site(x / sp);
    var best = NbNeighbor2(vec2<f32>(0.0), 3.4e38, vec2<i32>(0));
    var best_d = 3.4e38;
    let x0 = 2 * center.x + (center.y & 1);
    for (var dj = -2; dj <= 2; dj++) {
        let jr = center.y + dj;
        let half = 4 - abs(dj);
        let par = jr & 1;
        let lo = (x0 - half - par + 1) >> 1u;
        let hi = (x0 + half - par) >> 1u;
        for (var ii = lo; ii <= hi; ii++) {
            let site = vec2<i32>(ii, jr);
            let p = nb_cnj2_point(cfg, site);
            let e = p - x;
            let d = dot(e, e);
            if (d < best_d) {
                best_d = d;
                best = NbNeighbor2(p, sqrt(d), site);
            }
        }
    }
    return best;
}
