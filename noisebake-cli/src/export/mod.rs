//! Line plots as PNG ([`plot`]). PNG slices of textures are `build_assets::export::png`.

pub mod plot;
