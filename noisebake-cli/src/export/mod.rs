//! PNG output: one image per 2D slice of a texture ([`png`]) and line plots ([`plot`]).

pub mod plot;
pub mod png;
