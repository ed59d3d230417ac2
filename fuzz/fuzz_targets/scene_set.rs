//! `scene_set`: see `firmament_fuzz::scene_set`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| firmament_fuzz::scene_set(data));
