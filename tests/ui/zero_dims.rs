noisebake::noise_texture!(pub STBN = stbn { dims: [64, 0, 16], seed: 7, format: u16 });
fn main() {}
