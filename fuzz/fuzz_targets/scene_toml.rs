//! `scene_toml`: see `firmament_fuzz::scene_toml`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| firmament_fuzz::scene_toml(data));
