//! Compiles only if the runtime, the facade and generated texture code are `no_std`: every
//! runtime module is used here.
#![no_std]

noisebake::include_textures!();
noisebake::noise_texture!(pub INLINE = blue2d { dims: [8, 8], format: u8 });

/// Touches every module of the runtime.
pub fn use_everything(x: i32, y: i32, frame: u32) -> f32 {
    let m = MASK.get_k_unit(x, y, frame as i32, frame) + INLINE.get_unit(x, y);
    let g = noisebake::ldg::r2(x, y)
        + noisebake::ldg::plus(x, y)
        + noisebake::ldg::ign(x, y)
        + noisebake::ldg::bayer::<4>(x, y);
    let frac = |v: f32| noisebake::math::fract_f64(v as f64) as f32;
    let d = noisebake::warp::cosine_hemisphere(frac(m), frac(g));
    let s = noisebake::sequence::to_unit(noisebake::sequence::golden(frame));
    let [u, v] = noisebake::sampler::ign_r2::<2>(x, y, frame);
    let r = noisebake::sampler::rd_ign_r2::<3>(x, y, frame)[2]
        + noisebake::sampler::sobol_owen::<4>(x, y, frame, 1)[3]
        + noisebake::sampler::rd::<2>(frame, [u, v])[1];
    use noisebake::stochastic::{Fbm, Fractal, Perlin, SmoothVoronoi};
    let st = Fbm::new(Fractal::default(), 1).estimate([g, m, s], frac(m))
        + SmoothVoronoi::new(2).sample([g, m, s]);
    // The batch forms (AVX2 detection without std).
    let mut out = [0.0f32; 9];
    let _ = Perlin::new(1).estimate_batch(&[[g, m, s]; 9], &[frac(m); 9], &mut out);
    m + g + d[2] + s + r + st + out[8] + noisebake::math::sqrt(2.0)
}
