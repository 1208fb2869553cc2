//! # noisebake-cli
//!
//! The library behind the `noisebake` command-line tool: quality analysis of masks and point
//! sets, the reports that set speed against error, PNG slices and plots, and 2D point-set
//! generators (CNJ, jittered grid, Poisson disk) for comparisons. A game's build never compiles
//! this crate; the generators it measures live in `build-assets`.

pub mod analysis;
pub mod cache;
pub mod export;
pub mod motion_search;
pub mod points;
#[cfg(feature = "render")]
pub mod render;
pub mod report;
pub mod zsobol;
