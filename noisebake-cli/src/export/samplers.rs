//! The runtime's free samplers as `noisebake export-sampler` reads them: each as its
//! documented use reads sample `i` of frame `f` at `spp` samples a frame.

use noise_runtime::sampler;

/// A free sampler of the runtime.
pub struct Free {
    /// Its name (the runtime function's).
    pub name: &'static str,
    /// How it is read, in the runtime's terms.
    pub read_as: &'static str,
    /// Sample `i` of frame `f` at pixel `(x, y)`, `spp` samples a frame: four dimensions.
    pub read: fn(i32, i32, u32, u32, u32) -> [f32; 4],
}

/// Every free sampler of the runtime, in `export-sampler --list` order.
pub const FREE: [Free; 5] = [
    Free {
        name: "motion_pairs",
        read_as: "sampler::motion_pairs::<4>(x, y, frame, i, spp)",
        read: |x, y, f, i, spp| sampler::motion_pairs::<4>(x, y, f, i, spp),
    },
    Free {
        name: "r2_pairs",
        read_as: "sampler::r2_pairs::<4>(x, y, frame * spp + i)",
        read: |x, y, f, i, spp| sampler::r2_pairs::<4>(x, y, f.wrapping_mul(spp).wrapping_add(i)),
    },
    Free {
        name: "rd_ign_r2",
        read_as: "sampler::rd_ign_r2::<4>(x, y, frame * spp + i)",
        read: |x, y, f, i, spp| sampler::rd_ign_r2::<4>(x, y, f.wrapping_mul(spp).wrapping_add(i)),
    },
    Free {
        name: "ign_r2",
        read_as: "sampler::ign_r2::<4>(x, y, frame * spp + i)",
        read: |x, y, f, i, spp| sampler::ign_r2::<4>(x, y, f.wrapping_mul(spp).wrapping_add(i)),
    },
    Free {
        name: "sobol_owen",
        read_as: "sampler::sobol_owen::<4>(x, y, frame * spp + i, 0)",
        read: |x, y, f, i, spp| {
            sampler::sobol_owen::<4>(x, y, f.wrapping_mul(spp).wrapping_add(i), 0)
        },
    },
];
