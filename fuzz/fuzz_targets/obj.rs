//! `obj`: see `firmament_fuzz::obj`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| firmament_fuzz::obj(data));
