//! Integer coordinates that wrap toroidally onto a mask axis.

/// An integer coordinate type (`i32`, `u32`, `i64`, `u64`, `isize`, `usize`) that can be wrapped
/// onto an axis of `n` texels: negative coordinates wrap from the far side.
pub trait Coord: Copy {
    /// `self mod n` in `0..n` (`n > 0`). A power-of-two `n` known at compile time becomes a mask.
    fn wrap(self, n: u32) -> u32;
}

macro_rules! signed {
    ($($t:ty),*) => {$(
        impl Coord for $t {
            #[inline(always)]
            fn wrap(self, n: u32) -> u32 {
                if n.is_power_of_two() {
                    // Two's complement: the low bits of a negative number are its value mod 2^k.
                    (self as u32) & (n - 1)
                } else {
                    (self as i64).rem_euclid(n as i64) as u32
                }
            }
        }
    )*};
}
macro_rules! unsigned {
    ($($t:ty),*) => {$(
        impl Coord for $t {
            #[inline(always)]
            fn wrap(self, n: u32) -> u32 {
                if n.is_power_of_two() { (self as u32) & (n - 1) } else { (self as u64 % n as u64) as u32 }
            }
        }
    )*};
}
signed!(i8, i16, i32, isize);
unsigned!(u8, u16, u32, usize);

impl Coord for i64 {
    #[inline(always)]
    fn wrap(self, n: u32) -> u32 {
        if n.is_power_of_two() {
            (self as u32) & (n - 1)
        } else {
            self.rem_euclid(n as i64) as u32
        }
    }
}

impl Coord for u64 {
    #[inline(always)]
    fn wrap(self, n: u32) -> u32 {
        if n.is_power_of_two() {
            (self as u32) & (n - 1)
        } else {
            (self % n as u64) as u32
        }
    }
}
