//! The API shape: every mask dimension has the same methods, and mask coordinates take any
//! integer type, each its own.

use noise_runtime::{Mask2, Mask3, Mask4};

static BYTES: [u8; 4 * 4 * 2 * 3] = {
    let mut b = [0u8; 96];
    let mut i = 0;
    while i < 96 {
        b[i] = (i * 37 % 96) as u8;
        i += 1;
    }
    b
};

/// Every mask dimension has `get`, `get_unit`, `get_k`, `get_k_unit`, `get_pair_unit` and
/// `threshold`, and a higher-dimensional mask with unit extra axes reads as the lower one.
#[test]
fn every_mask_dimension_has_the_same_methods() {
    let m2: Mask2<u8, 4, 24> = Mask2::new(&BYTES);
    let m3: Mask3<u8, 4, 24, 1> = Mask3::new(&BYTES);
    let m4: Mask4<u8, 4, 24, 1, 1> = Mask4::new(&BYTES);
    for y in -30..30 {
        for x in -5..9 {
            for k in [0u32, 1, 7, 1000, u32::MAX] {
                assert_eq!(m2.get_k(x, y, k), m3.get_k(x, y, 0, k));
                assert_eq!(m2.get_k(x, y, k), m4.get_k(x, y, 0, 0, k));
                assert_eq!(m2.get_k_unit(x, y, k), m3.get_k_unit(x, y, 0, k));
                assert_eq!(m2.get_k_unit(x, y, k), m4.get_k_unit(x, y, 0, 0, k));
                assert_eq!(m2.get_pair_unit(x, y, k), m3.get_pair_unit(x, y, 0, k));
                assert_eq!(m2.get_pair_unit(x, y, k), m4.get_pair_unit(x, y, 0, 0, k));
            }
            assert_eq!(m2.get_k(x, y, 0), m2.get(x, y));
            assert_eq!(m2.get_unit(x, y), m4.get_unit(x, y, 0, 0));
            assert_eq!(m2.threshold(x, y, 0.5), m3.threshold(x, y, 0, 0.5));
        }
    }
}

/// Each coordinate takes its own integer type: a game's pixel as `i32` and its frame counter
/// as `u32` (as `ldg::ign_frame` takes them) need no cast, and read what one type would read.
#[test]
fn mask_coordinates_mix_integer_types() {
    let m3: Mask3<u8, 4, 12, 2> = Mask3::new(&BYTES);
    let m4: Mask4<u8, 4, 3, 2, 4> = Mask4::new(&BYTES);
    for frame in 0..7u32 {
        for y in 0..30usize {
            for x in -5..9i32 {
                let (yi, fi) = (y as i32, frame as i32);
                assert_eq!(m3.get(x, y, frame), m3.get(x, yi, fi));
                assert_eq!(m3.get_unit(x, y as u16, frame), m3.get_unit(x, yi, fi));
                assert_eq!(
                    m3.threshold(x, yi, frame, 0.4),
                    m3.threshold(x, yi, fi, 0.4)
                );
                assert_eq!(m3.get_k_unit(x, yi, frame, 3), m3.get_k_unit(x, yi, fi, 3));
                assert_eq!(
                    m3.get_pair_unit(x, y, frame, 1),
                    m3.get_pair_unit(x, yi, fi, 1)
                );
                assert_eq!(
                    m4.get_k(x, y as u64, frame, -1i64, 2),
                    m4.get_k(x, yi, fi, -1, 2)
                );
            }
        }
    }
}
