//! naga validation of the WGSL (no GPU needed).

#[test]
fn lookup_validates_with_naga() {
    let src = radiance_cache::wgsl::LOOKUP_WGSL;
    let module =
        naga::front::wgsl::parse_str(src).unwrap_or_else(|e| panic!("{}", e.emit_to_string(src)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{}", e.emit_to_string(src)));
}
