noisebake::noise_texture!(pub WHITE = white { dims: [16, 16], sed: 3 });
fn main() {}
