//! `noise_texture!`: declare a baked noise texture inline. A thin front end: tokens are parsed
//! into a `build_assets` spec; validation, cache and generation all live in `build_assets`.
