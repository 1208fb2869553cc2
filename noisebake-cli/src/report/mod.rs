//! The speed-against-error reports of the `noisebake report` command: every time is printed
//! next to the error it was bought with.

pub mod bench;
pub mod cnj;
pub mod compare;
pub mod fast;
pub mod kit;
#[cfg(feature = "render")]
pub mod render;
pub mod sampler;
pub mod stamp;
pub mod stochastic;
pub mod taa;
pub mod vector;
