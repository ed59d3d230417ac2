//! `gltf`: see `firmament_fuzz::gltf`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| firmament_fuzz::gltf(data));
