//! naga validation of the WGSL (no GPU needed).

#[test]
fn lookup_validates_with_naga() {
    gpu_harness::validate_wgsl(radiance_cache::wgsl::LOOKUP_WGSL).unwrap_or_else(|e| panic!("{e}"));
}
