noisebake::noise_texture!(A = blue2d { dims: [8, 8], sigma: -1.5 });
noisebake::noise_texture!(B = stbn { dims: [8, 8, 4], format: u32 });
noisebake::noise_texture!(C = stbm { dims: [8, 8, 4] });
noisebake::noise_texture!(D = vac { dims: [8, 8, 4], groups: [{ axes: [0, 1] }, { axes: [1, 2] }] });
fn main() {}
