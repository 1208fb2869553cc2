//! The constants of `motion_pairs`, written by `noisebake search-sampler --all --out noise-runtime/src/sampler/motion_table.rs`: do not edit, search again.

use super::motion::PairDrift;

/// Per samples-per-frame `N` (index `N − 1`), the two pairs' constants.
#[rustfmt::skip]
pub(super) const TABLE: [[PairDrift; 2]; 16] = [
    // 1 sample(s) a frame
    [
        PairDrift { z: 0, x: [0x8c65a2dd, 0xe2062926], y: [0x51e5544e, 0x9b5489ea], frame: [0x0dfda986, 0x3954f93f] },
        PairDrift { z: 0, x: [0xedd5e720, 0x968138c8], y: [0xa30d8a18, 0x458dc40d], frame: [0x2d3f3f55, 0x3484a983] },
    ],
    // 2 sample(s) a frame
    [
        PairDrift { z: 1, x: [0x9369ae36, 0x0e6925ad], y: [0xbfedd09c, 0x65034d56], frame: [0x25744af8, 0x301bf6dd] },
        PairDrift { z: 1, x: [0x65df569e, 0xa029aa08], y: [0xd9278108, 0x8a6cb80a], frame: [0xc360b13e, 0xa902fcf2] },
    ],
    // 3 sample(s) a frame
    [
        PairDrift { z: 1, x: [0x2438d7e1, 0x5f8f3aeb], y: [0x5ed227ce, 0x031ada04], frame: [0x4bd477b8, 0x6c2e6462] },
        PairDrift { z: 1, x: [0x52d1fa2b, 0x1aab9d1d], y: [0x65c79221, 0x599fb012], frame: [0xde8a094a, 0x2486c583] },
    ],
    // 4 sample(s) a frame
    [
        PairDrift { z: 1, x: [0x93a594d6, 0x0888cefa], y: [0x44888421, 0x5f42bb10], frame: [0xeee20c7e, 0x9fc8b024] },
        PairDrift { z: 1, x: [0x4b8e9a65, 0xa7b1b101], y: [0x29a471f0, 0x8b5edcf0], frame: [0xf5086b5c, 0x3e8003f8] },
    ],
    // 5 sample(s) a frame
    [
        PairDrift { z: 1, x: [0xcd13c5ae, 0x62921828], y: [0x4d74eb6f, 0x14f7e051], frame: [0xa0f970fd, 0x890ca9c1] },
        PairDrift { z: 1, x: [0xb7851f83, 0x96470b8c], y: [0x1a3d6a75, 0x9ecc7cd8], frame: [0xece86fdb, 0xf17a26d2] },
    ],
    // 6 sample(s) a frame
    [
        PairDrift { z: 1, x: [0x4a99fb4e, 0xdc682919], y: [0x384083ff, 0x85d50a6a], frame: [0x7b59dbd9, 0x90bf748c] },
        PairDrift { z: 1, x: [0xdec7b8f2, 0x7dc9fe58], y: [0x87c7fe63, 0xcba984c9], frame: [0xcb4e8c2f, 0xec1a31f8] },
    ],
    // 7 sample(s) a frame
    [
        PairDrift { z: 1, x: [0xd3b30836, 0x8cb1cdbf], y: [0xb8eeeb61, 0xc4296aa8], frame: [0xa5310778, 0x8557d989] },
        PairDrift { z: 3, x: [0xc1a044f7, 0x92d9fe47], y: [0xaf4488ae, 0xf66440d9], frame: [0x4ff984cb, 0x2e2dca56] },
    ],
    // 8 sample(s) a frame
    [
        PairDrift { z: 3, x: [0xa9f18421, 0x44b3cf87], y: [0x620f1b2d, 0x28f056ad], frame: [0x89470492, 0xed043e68] },
        PairDrift { z: 3, x: [0xb452fa2e, 0x40fde7bc], y: [0x41531651, 0x34530da3], frame: [0x08278d85, 0x5745bbf3] },
    ],
    // 9 sample(s) a frame
    [
        PairDrift { z: 2, x: [0x64024f64, 0x70330486], y: [0xe0303e99, 0x5ee18d5f], frame: [0xb9a0433e, 0x757f7417] },
        PairDrift { z: 2, x: [0xf065e6fc, 0xa37991d9], y: [0x66b83356, 0x6eeabe60], frame: [0x308d5ad2, 0x6cb375d8] },
    ],
    // 10 sample(s) a frame
    [
        PairDrift { z: 3, x: [0xb9767f60, 0xe4d4eaa8], y: [0x360965be, 0x77f77d56], frame: [0x22a10253, 0x710bf80b] },
        PairDrift { z: 3, x: [0x56cbeb37, 0xa7571536], y: [0x997390aa, 0xf1aa13a6], frame: [0x1b604a5b, 0xdca097dd] },
    ],
    // 11 sample(s) a frame
    [
        PairDrift { z: 3, x: [0xe159aeae, 0xb048f565], y: [0x6a5d0fb4, 0x692d0ecc], frame: [0x55fa8853, 0xcd3ae946] },
        PairDrift { z: 3, x: [0x438a0440, 0x5791be3d], y: [0x70b91816, 0xf4c89d9c], frame: [0x6ba71537, 0x5958bfe9] },
    ],
    // 12 sample(s) a frame
    [
        PairDrift { z: 5, x: [0xd7a2eeee, 0x95c612d2], y: [0x90ca18ce, 0x89edcf65], frame: [0xae896724, 0x41196248] },
        PairDrift { z: 1, x: [0xc41a23d6, 0x8fb821e3], y: [0x5077d136, 0xd6cf5b5f], frame: [0xae95832f, 0x62d78e17] },
    ],
    // 13 sample(s) a frame
    [
        PairDrift { z: 4, x: [0x55dbeb44, 0x4e7b7f22], y: [0x95e29c22, 0x5eb0f8e3], frame: [0x7d8af120, 0xa2f85674] },
        PairDrift { z: 6, x: [0x4aa6c86a, 0x714d4aad], y: [0x1fa90fa7, 0x319ee702], frame: [0x8a6583e7, 0x06a0a2b8] },
    ],
    // 14 sample(s) a frame
    [
        PairDrift { z: 1, x: [0x8972120c, 0xc8d53563], y: [0x461e7094, 0x7376d394], frame: [0xe9bba021, 0xd6a41d4e] },
        PairDrift { z: 3, x: [0x657dbba3, 0xa3d418b9], y: [0xbc9b96a8, 0xb95ee2a4], frame: [0x893ff394, 0x0521a1cb] },
    ],
    // 15 sample(s) a frame
    [
        PairDrift { z: 1, x: [0x6bbc7419, 0x413f176b], y: [0x521e2301, 0x96d255ca], frame: [0x979e1855, 0x2b8990df] },
        PairDrift { z: 7, x: [0xb33f8926, 0x7d820fbb], y: [0x2814a8bc, 0x2cc142b3], frame: [0xebc47ae6, 0xbf4b48b3] },
    ],
    // 16 sample(s) a frame
    [
        PairDrift { z: 5, x: [0x4ab882af, 0x066026c0], y: [0xc76c755f, 0x99af903a], frame: [0xe0de020c, 0x4feb895f] },
        PairDrift { z: 5, x: [0x437e1de1, 0xa5e735ad], y: [0x6ab883dd, 0x11f7cdcd], frame: [0xc5d3b8d9, 0xd3ccf6a3] },
    ],
];
