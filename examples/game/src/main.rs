//! A game-like crate using both ways in: `noise.toml` through build.rs, and `noise_texture!`.

noisebake::include_textures!();

// The same STBN spec inline: one spec, one cache, the same bytes.
noisebake::noise_texture!(pub STBN_INLINE = stbn { dims: [32, 32, 16], seed: 7, format: u16, histogram: slice });
noisebake::noise_texture!(pub WHITE = white { dims: [16, 16], seed: 3 });

fn main() {
    println!("DITHER(3, 5)          = {:.4}", DITHER.get_unit(3, 5));
    println!("STBN(3, 5, frame 2)   = {}", STBN.get(3, 5, 2));
    println!("STBN_INLINE(3, 5, 2)  = {}", STBN_INLINE.get(3, 5, 2));
    println!(
        "STBN k=1..3 at (3,5)  = {:?}",
        [1, 2, 3].map(|k| STBN.get_k(3, 5, 2, k))
    );
    println!("WHITE(-1, -1)         = {}", WHITE.get(-1, -1));
    println!("ldg::r2(10, 20)       = {:.4}", noisebake::ldg::r2(10, 20));
    let covered = (0..32)
        .flat_map(|y| (0..32).map(move |x| (x, y)))
        .filter(|&(x, y)| STBN.threshold(x, y, 0, 0.3))
        .count();
    println!("30% threshold of frame 0 covers {covered} of 1024 texels");
    assert_eq!(
        STBN.bytes(),
        STBN_INLINE.bytes(),
        "both ways in give the same bytes"
    );
}
