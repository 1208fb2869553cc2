//! # noise-runtime
//!
//! The part of noisebake a game links: `#![no_std]`, no dependencies by default.
//! Baked masks are read through typed views; everything else is computed on the fly.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]
