noisebake::noise_texture!(A = blue2d { dims: [8, 8], sigma: -1.5 });
noisebake::noise_texture!(B = stbn { dims: [8, 8, 4], format: u32 });
noisebake::noise_texture!(C = stbm { dims: [8, 8, 4] });
noisebake::noise_texture!(D = vac { dims: [8, 8, 4], groups: [{ axes: [0, 1] }, { axes: [1, 2] }] });
fn main() {}
noisebake::noise_texture!(E = fast { dims: [16, 16, 4], sample_space: "sphere", format: u8 });
noisebake::noise_texture!(F = fast { dims: [16, 16, 4], temporal_filter: { kind: "ema", alpha: 1.5 } });
