//! `glb`: see `firmament_fuzz::glb`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| firmament_fuzz::glb(data));
