//! `texture`: see `firmament_fuzz::texture`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| firmament_fuzz::texture(data));
