// Shared by the integration tests (each test file includes it with `mod common;`).

/// Proptest cases: env PROPTEST_CASES, default 64.
#[allow(dead_code)]
pub fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(64)
}
