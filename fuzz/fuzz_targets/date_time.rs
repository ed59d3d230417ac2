//! `date_time`: see `firmament_fuzz::date_time`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| firmament_fuzz::date_time(data));
