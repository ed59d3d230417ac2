//! Examples of firmament's library crates, written as an application that embeds them would
//! write them (`examples/`); the headless ones run in this crate's tests.
//!
//! - `headless_still`: a scene to a PNG on a device of your own, in about ten lines —
//!   `cargo run -p firmament-examples --example headless_still -- [OUT.png] [WIDTH HEIGHT] [PRESET]`.
//! - `custom_material`: your own WGSL material, in your own pipeline and HDR target, lit by
//!   firmament's sun and sky and fogged by its aerial perspective —
//!   `cargo run -p firmament-examples --example custom_material -- [OUT.png] [WIDTH HEIGHT]`.
//! - `embed_minimal`: a winit app of your own drawing a cube with its own pipeline, lit by
//!   firmament's sun and sky, with firmament's sky, aerial perspective and flares added and the
//!   finished image written to the window (built in CI; it needs a display) —
//!   `cargo run -p firmament-examples --example embed_minimal -- [PRESET] [FRAMES]`.
