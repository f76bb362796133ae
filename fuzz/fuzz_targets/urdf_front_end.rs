//! Arbitrary UTF-8 through the URDF reader and the chain builder (default base, tip and
//! snap): no panic; every refusal names a line; whatever builds a chain of up to eight
//! joints generates without an internal error and computes the pose a numeric reference
//! computes from the parsed joints.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|src: &str| {
    let _ = kinegen_fuzz::urdf_check::urdf(src, &[0.3, -1.1, 0.7, 2.0, -0.4, 1.3, 0.2, -2.5], true);
});
