//! libFuzzer target: [`streamline_studio::fuzz::stl`] (see docs/reliability.md).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    streamline_studio::fuzz::stl(data);
});
