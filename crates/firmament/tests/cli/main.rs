//! End-to-end tests of the `firmament` binary, in one test binary (one link instead of one per
//! file): one module per command or subject. Run one with `cargo test -p firmament --test cli
//! <module>::`, e.g. `timelapse::`.

mod bad_inputs;
mod commands;
mod determinism;
mod envmap;
mod png_bits;
mod sun;
mod support;
mod timelapse;
mod untrusted;
mod view;
