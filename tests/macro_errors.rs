//! `noise_texture!` errors name the key and point at the offending token (expected stderr in
//! tests/ui/*.stderr).

#[test]
fn spec_errors_point_at_their_tokens() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}
