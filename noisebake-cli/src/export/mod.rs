//! Line plots as PNG ([`plot`]); the runtime's free samplers as `export-sampler` reads them
//! ([`samplers`]). PNG slices of textures are `build_assets::export::png`.

pub mod plot;
pub mod samplers;
