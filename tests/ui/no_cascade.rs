// A bad spec is one error: the macro still defines a typed placeholder, so code using the
// texture compiles on and reports nothing more.
noisebake::noise_texture!(pub M = stbn { dims: [8, 8, 4], sigma_xyz: 2 });

fn main() {
    let _ = M.get(1, 2, 3);
    let _ = M.get_k_unit(1, 2, 3, 4);
}
