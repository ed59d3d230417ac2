//! Examples of firmament's library crates, written as an application that embeds them would
//! write them (`examples/`); the headless ones run in this crate's tests.
//!
//! - `headless_still`: a scene to a PNG on a device of your own, in about ten lines —
//!   `cargo run -p firmament-examples --example headless_still -- [OUT.png] [WIDTH HEIGHT] [PRESET]`.
