//! Arbitrary UTF-8 through the TOML front end: no panic; whatever loads generates
//! without an internal error and computes what the numeric reference computes.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|src: &str| {
    let _ = kinegen_fuzz::check::toml(src, &[0.3, -1.1, 0.7, 2.0, -0.4, 1.3, 0.2, -2.5]);
});
