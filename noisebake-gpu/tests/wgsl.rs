//! Every function of `noise-runtime/wgsl/noisebake.wgsl` run on a GPU (a Vulkan device through wgpu;
//! lavapipe in CI) and compared with the Rust runtime on a few hundred thousand inputs: integer
//! paths bit for bit, unorm loads within one ulp, floating-point paths within the tolerances
//! `noise_runtime::shaders` documents.
//!
//! Without a Vulkan device the GPU tests print why and pass, except under CI (`CI` set), where
//! they fail: see `Gpu::for_tests`.

use noisebake::cnj::Cnj2;
use noisebake::stochastic::{self, Fractal};
use noisebake::{Mask3, hash, ldg, sequence};
use noisebake_gpu::{Binding, Gpu, bytes_of, floats, validate, words};

/// Inputs per function.
const N: usize = 1 << 18;

use noisebake_test_support::Rng;

/// An i32 from a mix of scales: extremes, small, medium, any.
fn coord(rng: &mut Rng) -> i32 {
    const EDGE: [i32; 7] = [i32::MIN, i32::MIN + 1, -1, 0, 1, i32::MAX - 1, i32::MAX];
    match rng.next_u64() % 4 {
        0 => EDGE[(rng.next_u64() % 7) as usize],
        1 => (rng.next_u64() % 512) as i32 - 256,
        2 => (rng.next_u64() % 2_000_000) as i32 - 1_000_000,
        _ => rng.i32(),
    }
}

/// Runs `kernel` (its `main`, 64 invocations a workgroup) over `n` inputs with one input and
/// one output buffer, and returns the output bytes.
fn run(g: &Gpu, kernel: &str, input: &[u8], n: usize, out_bytes: usize) -> Vec<u8> {
    let groups = n.div_ceil(64) as u32;
    let (x, y) = (groups.min(4096), groups.div_ceil(4096));
    g.run(
        kernel,
        [x, y, 1],
        &[Binding::Input(input), Binding::Output(out_bytes)],
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .remove(0)
}

/// A compute kernel over an input array of `input` at binding 0, the `bindings` declared after
/// it, and `body` run for every input index `i` (invocations over a 2D grid of workgroups, 4096
/// wide; those past the input's end return).
fn kernel(input: &str, bindings: &str, body: &str) -> String {
    format!(
        "@group(0) @binding(0) var<storage, read> inp: array<{input}>;
         {bindings}
         @compute @workgroup_size(64)
         fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
             let i = id.x + id.y * 4096u * 64u;
             if (i >= arrayLength(&inp)) {{ return; }}
             {body}
         }}"
    )
}

#[test]
fn library_passes_naga_validation() {
    let module = validate(noisebake::shaders::WGSL).unwrap_or_else(|e| panic!("{e}"));
    for name in [
        "nb_mask_coord_k",
        "nb_mask_load",
        "nb_mask_unit_u8",
        "nb_mask_unit_u16",
        "nb_mask_unit_f32",
        "nb_r2_frame",
        "nb_plus_frame",
        "nb_ign_frame",
        "nb_bayer_frame",
        "nb_ign_r2",
        "nb_rd2",
        "nb_rd3",
        "nb_rd2_ign_r2",
        "nb_r2_pairs",
        "nb_motion_pairs",
        "nb_rd3_ign_r2",
        "nb_rd4_ign_r2",
        "nb_sobol_owen",
        "nb_pcg",
        "nb_hash3",
        "nb_cnj2_closest",
        "nb_perlin3",
        "nb_fbm3",
        "nb_perlin3_estimate",
        "nb_fbm3_estimate",
    ] {
        assert!(
            module
                .functions
                .iter()
                .any(|(_, f)| f.name.as_deref() == Some(name)),
            "{name} missing"
        );
    }
    // A broken library is reported with its line, not as a pipeline failure.
    let broken = noisebake::shaders::WGSL.replace(
        "fn nb_pcg(v: u32) -> u32 {",
        "fn nb_pcg(v: u32) -> u32 { let q = v +;",
    );
    let e = validate(&broken).unwrap_err();
    assert!(e.contains("nb_pcg") || e.contains("expected"), "{e}");
}

/// A mask whose texel at address i holds i: reading it gives back the address `get_k` used.
fn address_mask<const W: u32, const H: u32, const D: u32>() -> Mask3<f32, W, H, D> {
    let n = (W * H * D) as usize;
    let bytes: Vec<u8> = (0..n).flat_map(|i| (i as f32).to_le_bytes()).collect();
    Mask3::new(Box::leak(bytes.into_boxed_slice()))
}

#[test]
fn integer_functions_match_bit_for_bit() {
    Gpu::each_for_tests(|g| {
        let mut rng = Rng(1);
        let inputs: Vec<[i32; 4]> = (0..N)
            .map(|_| {
                [
                    coord(&mut rng),
                    coord(&mut rng),
                    coord(&mut rng),
                    coord(&mut rng),
                ]
            })
            .collect();
        let flat: Vec<i32> = inputs.iter().flatten().copied().collect();
        const OUT: usize = 16;
        let kernel = kernel(
            "vec4<i32>",
            "@group(0) @binding(1) var<storage, read_write> outp: array<u32>;",
            &format!(
                "let p = inp[i];
             let f = bitcast<u32>(p.z);
             let k = bitcast<u32>(p.w);
             let o = i * {OUT}u;
             outp[o + 0u] = bitcast<u32>(nb_r2(p.xy));
             outp[o + 1u] = bitcast<u32>(nb_r2_frame(p.xy, f));
             outp[o + 2u] = bitcast<u32>(nb_plus(p.xy));
             outp[o + 3u] = bitcast<u32>(nb_plus_frame(p.xy, f));
             outp[o + 4u] = bitcast<u32>(nb_bayer(p.xy, 3u));
             outp[o + 5u] = bitcast<u32>(nb_bayer(p.xy, 11u));
             outp[o + 6u] = bitcast<u32>(nb_bayer_frame(p.xy, 4u, f));
             outp[o + 7u] = nb_hash2(p.xy, k);
             outp[o + 8u] = nb_hash3(p.xyz, k);
             outp[o + 9u] = nb_pcg(bitcast<u32>(p.x));
             outp[o + 10u] = nb_r2_point(k).x;
             outp[o + 11u] = nb_r2_point(k).y;
             outp[o + 12u] = nb_golden(f);
             let a = nb_mask_coord_k(p.xyz, vec3<u32>(37u, 64u, 13u), k);
             outp[o + 13u] = a.x + 37u * (a.y + 64u * a.z);
             let b = nb_mask_coord_k(p.xyz, vec3<u32>(64u, 32u, 16u), k);
             outp[o + 14u] = b.x + 64u * (b.y + 32u * b.z);
             let c = nb_mask4_coord_k(vec4<i32>(p.xyz, p.x ^ p.y), vec4<u32>(8u, 8u, 3u, 5u), k);
             outp[o + 15u] = c.x + 8u * (c.y + 8u * c.z);"
            ),
        );
        let out = words(&run(g, &kernel, &bytes_of(&flat), N, N * OUT * 4));
        let odd = address_mask::<37, 64, 13>();
        let pow2 = address_mask::<64, 32, 16>();
        let m4 = {
            let bytes: Vec<u8> = (0..8 * 8 * 3 * 5)
                .flat_map(|i| (i as f32).to_le_bytes())
                .collect();
            noisebake::Mask4::<f32, 8, 8, 3, 5>::new(Box::leak(bytes.into_boxed_slice()))
        };
        let names = [
            "r2",
            "r2_frame",
            "plus",
            "plus_frame",
            "bayer<8>",
            "bayer<2048>",
            "bayer_frame<16>",
            "hash2",
            "hash3",
            "pcg",
            "r2_point.0",
            "r2_point.1",
            "golden",
            "get_k 37x64x13",
            "get_k 64x32x16",
            "Mask4 get_k",
        ];
        for (i, &[x, y, z, w]) in inputs.iter().enumerate() {
            let (f, k) = (z as u32, w as u32);
            let cpu = [
                ldg::r2(x, y).to_bits(),
                ldg::r2_frame(x, y, f).to_bits(),
                ldg::plus(x, y).to_bits(),
                ldg::plus_frame(x, y, f).to_bits(),
                ldg::bayer::<8>(x, y).to_bits(),
                ldg::bayer::<2048>(x, y).to_bits(),
                ldg::bayer_frame::<16>(x, y, f).to_bits(),
                hash::hash2(x, y, k),
                hash::hash3(x, y, z, k),
                hash::pcg(x as u32),
                sequence::r2_point(k).0,
                sequence::r2_point(k).1,
                sequence::golden(f),
                odd.get_k(x, y, z, k) as u32,
                pow2.get_k(x, y, z, k) as u32,
                m4.get_k(x, y, z, x ^ y, k) as u32,
            ];
            for (j, c) in cpu.iter().enumerate() {
                assert_eq!(
                    out[i * OUT + j],
                    *c,
                    "{} at {:?}: GPU {:#x}, CPU {c:#x}",
                    names[j],
                    inputs[i],
                    out[i * OUT + j]
                );
            }
        }
    });
}

/// The samplers of several values per pixel (`noise_runtime::sampler`) are integer arithmetic
/// on 32-bit fractions: bit for bit, every value of every construction.
#[test]
fn samplers_match_bit_for_bit() {
    use noisebake::sampler;
    Gpu::each_for_tests(|g| {
        let mut rng = Rng(4);
        let inputs: Vec<[i32; 4]> = (0..N)
            .map(|_| {
                let f = match rng.next_u64() % 3 {
                    0 => (rng.next_u64() % 256) as i32,
                    _ => rng.i32(),
                };
                [coord(&mut rng), coord(&mut rng), f, rng.i32()]
            })
            .collect();
        let flat: Vec<i32> = inputs.iter().flatten().copied().collect();
        const OUT: usize = 30;
        let kernel = kernel(
            "vec4<i32>",
            "@group(0) @binding(1) var<storage, read_write> outp: array<u32>;",
            &format!(
                "let p = inp[i];
             let f = bitcast<u32>(p.z);
             let s = bitcast<u32>(p.w);
             let o = i * {OUT}u;
             let a = bitcast<vec4<u32>>(nb_ign_r2(p.xy, f));
             let b = bitcast<vec2<u32>>(nb_rd2_ign_r2(p.xy, f));
             let c = bitcast<vec3<u32>>(nb_rd3_ign_r2(p.xy, f));
             let d = bitcast<vec4<u32>>(nb_rd4_ign_r2(p.xy, f));
             let e = bitcast<vec4<u32>>(nb_sobol_owen(p.xy, f, s));
             let rot = vec3<f32>(nb_r2(p.xy), nb_to_unit(s), nb_to_unit(bitcast<u32>(p.x)));
             let r2 = bitcast<vec2<u32>>(nb_rd2(f, rot.xy));
             let r3 = bitcast<vec3<u32>>(nb_rd3(f, rot));
             outp[o + 0u] = a.x; outp[o + 1u] = a.y; outp[o + 2u] = a.z; outp[o + 3u] = a.w;
             outp[o + 4u] = b.x; outp[o + 5u] = b.y;
             outp[o + 6u] = c.x; outp[o + 7u] = c.y; outp[o + 8u] = c.z;
             outp[o + 9u] = d.x; outp[o + 10u] = d.y; outp[o + 11u] = d.z; outp[o + 12u] = d.w;
             outp[o + 13u] = e.x; outp[o + 14u] = e.y; outp[o + 15u] = e.z; outp[o + 16u] = e.w;
             outp[o + 17u] = r2.x; outp[o + 18u] = r2.y;
             outp[o + 19u] = r3.x; outp[o + 20u] = r3.y; outp[o + 21u] = r3.z;
             let q = bitcast<vec4<u32>>(nb_r2_pairs(p.xy, f));
             outp[o + 22u] = q.x; outp[o + 23u] = q.y; outp[o + 24u] = q.z; outp[o + 25u] = q.w;
             let m = bitcast<vec4<u32>>(nb_motion_pairs(p.xy, f, s % 23u, (s >> 8u) % 21u));
             outp[o + 26u] = m.x; outp[o + 27u] = m.y; outp[o + 28u] = m.z; outp[o + 29u] = m.w;"
            ),
        );
        let out = words(&run(g, &kernel, &bytes_of(&flat), N, N * OUT * 4));
        let unit = |v: u32| sequence::to_unit(v);
        for (i, &[x, y, f, s]) in inputs.iter().enumerate() {
            let (f, s) = (f as u32, s as u32);
            let rot = [ldg::r2(x, y), unit(s), unit(x as u32)];
            let cpu: Vec<f32> = [
                sampler::ign_r2::<4>(x, y, f).to_vec(),
                sampler::rd_ign_r2::<2>(x, y, f).to_vec(),
                sampler::rd_ign_r2::<3>(x, y, f).to_vec(),
                sampler::rd_ign_r2::<4>(x, y, f).to_vec(),
                sampler::sobol_owen::<4>(x, y, f, s).to_vec(),
                sampler::rd::<2>(f, [rot[0], rot[1]]).to_vec(),
                sampler::rd::<3>(f, rot).to_vec(),
                sampler::r2_pairs::<4>(x, y, f).to_vec(),
                sampler::motion_pairs::<4>(x, y, f, s % 23, (s >> 8) % 21).to_vec(),
            ]
            .concat();
            for (j, c) in cpu.iter().enumerate() {
                assert_eq!(
                    out[i * OUT + j],
                    c.to_bits(),
                    "value {j} at {:?}: GPU {}, CPU {c}",
                    inputs[i],
                    f32::from_bits(out[i * OUT + j])
                );
            }
        }
    });
}

/// A baked sampler tile read through `nb_sampler_tile_bits` (its keys uploaded as the r16uint
/// mask they are) gives the runtime's `SamplerTile::sample_bits` for every pixel, frame, sample
/// and dimension, coordinates far outside the tile included; the first pair runs Sobol (the
/// byte tables against WGSL's bit loop) and the lone third dimension the lattice.
#[test]
fn sampler_tiles_match_bit_for_bit() {
    use noisebake::SamplerTile;
    // 8×4 pixels, 5 samples per frame, 3 dimensions (a pair and a lone one).
    let keys: Mask3<u16, 8, 4, 3> = Mask3::new(Vec::leak(
        noisebake_test_support::bake::gen_tex(
            "kind = \"sampler\"\ndims = [8, 4]\nspp = 5\nsample_dims = 3\nseed = 2",
        )
        .data,
    ));
    let tile: SamplerTile<8, 4, 5, 3> = SamplerTile::new(keys, 0b01);
    Gpu::each_for_tests(|g| {
        let texture = g.upload_mask(keys.gpu_texture(), keys.gpu_bytes().unwrap());
        let mut rng = Rng(6);
        let inputs: Vec<[i32; 4]> = (0..N / 8)
            .map(|_| {
                let f = match rng.next_u64() % 2 {
                    0 => (rng.next_u64() % 64) as i32,
                    _ => rng.i32(),
                };
                let sd = (rng.next_u64() % 64) as i32; // sample (low 3 bits of 8) and dimension
                [coord(&mut rng), coord(&mut rng), f, sd]
            })
            .collect();
        let flat: Vec<i32> = inputs.iter().flatten().copied().collect();
        let kernel = kernel(
            "vec4<i32>",
            "@group(0) @binding(1) var<storage, read_write> outp: array<u32>;
             @group(0) @binding(2) var keys: texture_2d_array<u32>;",
            "let p = inp[i];
             let sd = bitcast<u32>(p.w);
             outp[i] = nb_sampler_tile_bits(keys, p.xy, bitcast<u32>(p.z), sd & 7u, sd >> 3u, 5u, 1u);",
        );
        let groups = inputs.len().div_ceil(64) as u32;
        let out = g
            .run(
                &kernel,
                [groups.min(4096), groups.div_ceil(4096), 1],
                &[
                    Binding::Input(&bytes_of(&flat)),
                    Binding::Output(inputs.len() * 4),
                    Binding::Texture(&texture),
                ],
            )
            .unwrap_or_else(|e| panic!("{e}"))
            .remove(0);
        let out = words(&out);
        for (j, &[x, y, f, sd]) in inputs.iter().enumerate() {
            let (i, d) = (sd as u32 & 7, sd as u32 >> 3);
            let cpu = tile.sample_bits(x, y, f as u32, i, d);
            assert_eq!(
                out[j], cpu,
                "pixel ({x}, {y}) frame {f} sample {i} dimension {d}"
            );
        }
    });
}

/// IGN: the runtime rounds an f64 product, the GPU keeps it in 32-bit fixed point; they agree
/// within 2^-23 modulo 1 (a value near 1 on one side may be near 0 on the other).
#[test]
fn ign_matches_within_two_to_the_minus_23() {
    Gpu::each_for_tests(|g| {
        let mut rng = Rng(2);
        let inputs: Vec<[i32; 4]> = (0..N)
            .map(|_| [coord(&mut rng), coord(&mut rng), rng.i32(), 0])
            .collect();
        let flat: Vec<i32> = inputs.iter().flatten().copied().collect();
        let kernel = kernel(
            "vec4<i32>",
            "@group(0) @binding(1) var<storage, read_write> outp: array<f32>;",
            "let p = inp[i];
             outp[2u * i] = nb_ign(p.xy);
             outp[2u * i + 1u] = nb_ign_frame(p.xy, bitcast<u32>(p.z));",
        );
        let out = floats(&run(g, &kernel, &bytes_of(&flat), N, N * 8));
        let mut worst = 0.0f32;
        for (i, &[x, y, f, _]) in inputs.iter().enumerate() {
            for (j, cpu) in [ldg::ign(x, y), ldg::ign_frame(x, y, f as u32)]
                .into_iter()
                .enumerate()
            {
                let d = (out[2 * i + j] - cpu).abs();
                let d = d.min(1.0 - d);
                worst = worst.max(d);
                assert!(
                    d <= f32::EPSILON,
                    "ign{} at ({x}, {y}, {f}): GPU {}, CPU {cpu}",
                    ["", "_frame"][j],
                    out[2 * i + j]
                );
            }
        }
        eprintln!(
            "ign: largest difference {worst:e} (bound 2^-23 = {:e})",
            f32::EPSILON
        );
    });
}

/// Points for the gradient noises: a quarter near the origin, a quarter at lattice planes and
/// their neighbours (offsets 0 and 1 − ulp), the rest spread over |p| < 2^12; ξ uniform with
/// a few out-of-range and edge values (0, 1, −0.5, 1.5, NaN).
fn noise_inputs(seed: u64) -> Vec<[f32; 4]> {
    let mut rng = Rng(seed);
    (0..N)
        .map(|i| {
            let mut c = || match rng.next_u64() % 4 {
                0 => rng.unit_f32() * 8.0 - 4.0,
                1 => {
                    let k = (rng.next_u64() % 200) as f32 - 100.0;
                    [k, (k + 1.0).next_down(), k + 0.5][(rng.next_u64() % 3) as usize]
                }
                _ => (rng.unit_f32() * 2.0 - 1.0) * 4096.0,
            };
            let p = [c(), c(), c()];
            let xi = match i % 64 {
                0 => [0.0, 1.0, -0.5, 1.5, f32::NAN][(i / 64) % 5],
                _ => rng.unit_f32(),
            };
            [p[0], p[1], p[2], xi]
        })
        .collect()
}

/// The fractal settings the float tests run: the paper's, a general one, one with a negative
/// gain.
const FRACTALS: [(u32, f32, f32); 3] = [(10, 2.0, 0.5), (6, 1.9, 0.55), (5, 2.0, -0.5)];

/// Values per input of the noise kernel: perlin3, perlin3_estimate, and per fractal fbm3 and
/// fbm3_estimate.
const NOISE_OUT: usize = 2 + 2 * FRACTALS.len();

fn noise_kernel() -> String {
    let mut body = String::new();
    for (j, (o, l, g)) in FRACTALS.iter().enumerate() {
        body += &format!(
            "let f{j} = NbFractal({o}u, {l:?}, {g:?});
             outp[o + {a}u] = nb_fbm3(p.xyz, f{j}, 7u);
             outp[o + {b}u] = nb_fbm3_estimate(p.xyz, f{j}, 7u, p.w);\n",
            a = 2 + 2 * j,
            b = 3 + 2 * j
        );
    }
    kernel(
        "vec4<f32>",
        "@group(0) @binding(1) var<storage, read_write> outp: array<f32>;",
        &format!(
            "let p = inp[i];
             let o = i * {NOISE_OUT}u;
             outp[o] = nb_perlin3(p.xyz, 7u);
             outp[o + 1u] = nb_perlin3_estimate(p.xyz, 7u, p.w);
             {body}"
        ),
    )
}

/// The deterministic forms: within 2^-16 for Perlin (values of magnitude ≤ 2, a chain of seven
/// lerps and the fades, each of which may round once more or once less where the GPU fuses a
/// multiply-add: a few ulps of 2, far below 2^-16) and within Σ|gain^o| · 2^-16 for fBm.
/// The estimators: bit for bit, except where a decision flips because a fade weight or a
/// remapped ξ landed one rounding away from its cut — then the GPU evaluated another corner
/// or octave, equally valid; such inputs must stay below 1 in 10^4.
#[test]
fn gradient_noise_matches_within_tolerance() {
    Gpu::each_for_tests(|g| {
        let inputs = noise_inputs(3);
        let flat: Vec<f32> = inputs.iter().flatten().copied().collect();
        let out = floats(&run(
            g,
            &noise_kernel(),
            &bytes_of(&flat),
            N,
            N * NOISE_OUT * 4,
        ));
        let mut worst = [0.0f64; NOISE_OUT];
        let mut flips = [0usize; NOISE_OUT];
        for (i, &[x, y, z, xi]) in inputs.iter().enumerate() {
            let p = [x, y, z];
            let mut cpu = vec![
                stochastic::Perlin::new(7).sample(p),
                stochastic::Perlin::new(7).estimate(p, xi),
            ];
            let mut tol = vec![2f64.powi(-16), 0.0];
            for &(o, l, gain) in &FRACTALS {
                let f = Fractal::new(o, l, gain);
                cpu.push(stochastic::Fbm::new(f, 7).sample(p));
                cpu.push(stochastic::Fbm::new(f, 7).estimate(p, xi));
                let weight: f64 = (0..o).map(|k| (gain.abs() as f64).powi(k as i32)).sum();
                tol.push(weight * 2f64.powi(-16));
                tol.push(0.0);
            }
            for j in 0..NOISE_OUT {
                let gpu_v = out[i * NOISE_OUT + j];
                let d = (gpu_v as f64 - cpu[j] as f64).abs();
                if tol[j] == 0.0 {
                    // An estimator: equal bits, or a flipped decision.
                    if gpu_v.to_bits() != cpu[j].to_bits() {
                        flips[j] += 1;
                        assert!(gpu_v.is_finite(), "estimator {j} at {p:?}, ξ {xi}: {gpu_v}");
                    }
                } else {
                    worst[j] = worst[j].max(d);
                    assert!(
                        d <= tol[j],
                        "value {j} at {p:?}: GPU {gpu_v}, CPU {}, |Δ| {d:e} > {:e}",
                        cpu[j],
                        tol[j]
                    );
                }
            }
        }
        eprintln!(
            "largest |GPU − CPU| per value (estimators: 0): {:?}",
            worst.map(|w| format!("{w:.2e}"))
        );
        eprintln!("estimator decisions that flipped, of {N}: {flips:?}");
        for (j, &f) in flips.iter().enumerate() {
            assert!(f * 10_000 <= N, "value {j}: {f} flipped decisions of {N}");
        }
    });
}

/// CNJ's closest point: WGSL has no f64, so the GPU places points in f32. Over queries within
/// 256 spacings of the origin a point's position has a rounding error of a few ulps of 256
/// carried through the flow (whose displacement varies by at most a few spacings per spacing):
/// within 2^-12 spacings. The closest site is the same unless the two nearest points are
/// within twice that of a tie.
#[test]
fn cnj_closest_point_matches() {
    Gpu::each_for_tests(|g| {
        let mut rng = Rng(4);
        let cnj = Cnj2::PAPER;
        let queries: Vec<[f32; 2]> = (0..N / 4)
            .map(|_| {
                [
                    (rng.unit_f32() * 2.0 - 1.0) * 256.0,
                    (rng.unit_f32() * 2.0 - 1.0) * 256.0,
                ]
            })
            .collect();
        let flat: Vec<f32> = queries.iter().flatten().copied().collect();
        let kernel = kernel(
            "vec2<f32>",
            "@group(0) @binding(1) var<storage, read_write> outp: array<vec4<f32>>;",
            "let n = nb_cnj2_closest(nb_cnj2_paper(), inp[i]);
             outp[i] = vec4<f32>(n.point, bitcast<f32>(n.site.x), bitcast<f32>(n.site.y));",
        );
        let n = queries.len();
        let out = floats(&run(g, &kernel, &bytes_of(&flat), n, n * 16));
        const TOL: f32 = 1.0 / 4096.0;
        let (mut worst, mut ties) = (0.0f32, 0);
        for (i, q) in queries.iter().enumerate() {
            let near = cnj.k_nearest::<2>(*q);
            let site = [
                out[4 * i + 2].to_bits() as i32,
                out[4 * i + 3].to_bits() as i32,
            ];
            let point = [out[4 * i], out[4 * i + 1]];
            if site != near[0].site {
                ties += 1;
                assert!(
                    near[1].distance - near[0].distance <= 2.0 * TOL && site == near[1].site,
                    "query {q:?}: GPU site {site:?}, CPU {:?} (F2 − F1 = {:e})",
                    near[0].site,
                    near[1].distance - near[0].distance
                );
                continue;
            }
            let d = (point[0] - near[0].point[0])
                .abs()
                .max((point[1] - near[0].point[1]).abs());
            worst = worst.max(d);
            assert!(
                d <= TOL,
                "query {q:?}: GPU point {point:?}, CPU {:?}",
                near[0].point
            );
        }
        eprintln!(
            "cnj: largest point difference {worst:e} spacings; near-ties resolved the other way: {ties} of {n}"
        );
    });
}

/// Mask dims for the load tests: a width that is not a power of two, so the wrap takes the
/// general path, and a power-of-two height.
const MW: u32 = 24;
const MH: u32 = 16;
const MD: u32 = 5;

/// Uploads a mask of texel type `T` with random bytes through `gpu_texture` and
/// `write_gpu_bytes` (as a game would), reads the k-th value of random pixels with
/// `nb_mask_load` / `nb_mask_load_u`, and compares every channel with the mask's own bytes:
/// integers exactly, unorm within one ulp of `v/255`, floats bit for bit, padding as
/// documented; and the unit value of channel 0 (`nb_unorm8_unit`, `nb_u16_unit`) bit for bit
/// with `get_k_unit`.
fn check_mask_format<T: noisebake::Texel>(g: &Gpu, seed: u64) {
    let mut rng = Rng(seed);
    let n = (MW * MH * MD) as usize * T::BYTES;
    let cb = T::BYTES / T::CHANNELS;
    let bytes: Vec<u8> = (0..n / cb)
        .flat_map(|_| match cb {
            4 => rng.unit_f32().to_le_bytes().to_vec(),
            2 => (rng.next_u64() as u16).to_le_bytes().to_vec(),
            _ => vec![rng.next_u64() as u8],
        })
        .collect();
    let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
    let mask = Mask3::<T, MW, MH, MD>::new(bytes);
    let addr = address_mask::<MW, MH, MD>();
    let tex = mask.gpu_texture();
    let mut upload = vec![0u8; tex.byte_len()];
    mask.write_gpu_bytes(&mut upload).unwrap();
    assert_eq!(mask.gpu_bytes().is_some(), T::CHANNELS != 3);
    let texture = g.upload_mask(tex, &upload);
    let inputs: Vec<[i32; 4]> = (0..N / 16)
        .map(|_| {
            [
                coord(&mut rng),
                coord(&mut rng),
                coord(&mut rng),
                (rng.next_u64() % 4096) as i32,
            ]
        })
        .collect();
    let flat: Vec<i32> = inputs.iter().flatten().copied().collect();
    let integer = cb == 2;
    // The raw load, and the unit values through the function the docs name for this kind of
    // texture.
    let (ty, load, unit) = if integer {
        ("u32", "nb_mask_load_u", "nb_mask_unit_u16")
    } else if cb == 1 {
        ("f32", "nb_mask_load", "nb_mask_unit_u8")
    } else {
        ("f32", "nb_mask_load", "nb_mask_unit_f32")
    };
    let kernel = kernel(
        "vec4<i32>",
        &format!(
            "@group(0) @binding(1) var<storage, read_write> outp: array<vec4<u32>>;
             @group(0) @binding(2) var<storage, read_write> units: array<vec4<f32>>;
             @group(0) @binding(3) var mask: texture_2d_array<{ty}>;"
        ),
        &format!(
            "let p = inp[i];
             let v = {load}(mask, p.xyz, bitcast<u32>(p.w));
             outp[i] = bitcast<vec4<u32>>(v);
             units[i] = {unit}(mask, p.xyz, bitcast<u32>(p.w));"
        ),
    );
    let m = inputs.len();
    let groups = m.div_ceil(64) as u32;
    let out = g
        .run(
            &kernel,
            [groups, 1, 1],
            &[
                Binding::Input(&bytes_of(&flat)),
                Binding::Output(m * 16),
                Binding::Output(m * 16),
                Binding::Texture(&texture),
            ],
        )
        .unwrap_or_else(|e| panic!("{e}"));
    let (vals, units) = (words(&out[0]), floats(&out[1]));
    let name = core::any::type_name::<T>();
    for (i, &[x, y, t, k]) in inputs.iter().enumerate() {
        let a = addr.get_k(x, y, t, k as u32) as usize;
        assert_eq!(
            units[4 * i].to_bits(),
            mask.get_k_unit(x, y, t, k as u32).to_bits(),
            "{name}: unit value at {:?}",
            inputs[i]
        );
        let texel = mask.get_k(x, y, t, k as u32);
        for c in 0..T::CHANNELS {
            assert_eq!(
                units[4 * i + c].to_bits(),
                texel.unit(c).to_bits(),
                "{name}: channel {c}'s unit value at {:?}",
                inputs[i]
            );
        }
        for c in 0..tex.format.channels() {
            let got = vals[4 * i + c];
            let raw = &bytes[(a * T::CHANNELS + c) * cb..];
            let pad = c >= T::CHANNELS;
            match cb {
                1 => {
                    let want = if pad { 1.0 } else { raw[0] as f32 / 255.0 };
                    let got = f32::from_bits(got);
                    assert!(
                        (got - want).abs() <= f32::EPSILON * want.max(f32::MIN_POSITIVE),
                        "{name}: channel {c} at {:?}: GPU {got}, bytes say {want}",
                        inputs[i]
                    );
                }
                2 => {
                    let want = if pad {
                        65535
                    } else {
                        u16::from_le_bytes([raw[0], raw[1]]) as u32
                    };
                    assert_eq!(got, want, "{name}: channel {c} at {:?}", inputs[i]);
                }
                _ => {
                    let want = if pad {
                        1.0f32.to_bits()
                    } else {
                        u32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]])
                    };
                    assert_eq!(got, want, "{name}: channel {c} at {:?}", inputs[i]);
                }
            }
        }
    }
}

#[test]
fn masks_of_every_format_upload_and_load_as_the_runtime_reads_them() {
    Gpu::each_for_tests(|g| {
        check_mask_format::<u8>(g, 10);
        check_mask_format::<[u8; 2]>(g, 11);
        check_mask_format::<[u8; 3]>(g, 12);
        check_mask_format::<[u8; 4]>(g, 13);
        check_mask_format::<u16>(g, 14);
        check_mask_format::<[u16; 2]>(g, 15);
        check_mask_format::<[u16; 3]>(g, 16);
        check_mask_format::<[u16; 4]>(g, 17);
        check_mask_format::<f32>(g, 18);
        check_mask_format::<[f32; 2]>(g, 19);
        check_mask_format::<[f32; 3]>(g, 20);
        check_mask_format::<[f32; 4]>(g, 21);
    });
}

/// The polar warps a sampler tile's pairs are trained for: the same `(u, v)` in, the CPU's
/// direction and disk point out, within `2^-10` per component (Vulkan's `sin`/`cos`), edges
/// of the square included.
#[test]
fn polar_warps_match_within_tolerance() {
    use noisebake::warp;
    Gpu::each_for_tests(|g| {
        let mut rng = Rng(11);
        let mut inputs: Vec<[f32; 4]> = (0..N)
            .map(|_| {
                let u = (rng.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
                let v = (rng.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
                [u, v, 0.0, 0.0]
            })
            .collect();
        inputs[0] = [0.0, 0.0, 0.0, 0.0];
        inputs[1] = [1.0, 1.0, 0.0, 0.0];
        inputs[2] = [0.999_999_94, 0.5, 0.0, 0.0];
        let flat: Vec<f32> = inputs.iter().flatten().copied().collect();
        let kernel = kernel(
            "vec4<f32>",
            "@group(0) @binding(1) var<storage, read_write> outp: array<vec4<f32>>;",
            "let p = inp[i];
             outp[2u * i] = vec4<f32>(nb_cosine_hemisphere_polar(p.x, p.y), 0.0);
             outp[2u * i + 1u] = vec4<f32>(nb_disk_polar(p.x, p.y), 0.0, 0.0);",
        );
        let out = floats(&run(g, &kernel, &bytes_of(&flat), N, N * 32));
        let mut worst = 0.0f32;
        for (i, &[u, v, _, _]) in inputs.iter().enumerate() {
            let d = warp::cosine_hemisphere_polar(u, v);
            let k = warp::disk_polar(u, v);
            for c in 0..3 {
                worst = worst.max((out[8 * i + c] - d[c]).abs());
            }
            for c in 0..2 {
                worst = worst.max((out[8 * i + 4 + c] - k[c]).abs());
            }
        }
        assert!(worst <= 2f32.powi(-10), "{}: worst {worst}", g.describe());
    });
}
