//! The traced views the benches share (the tests' `common` module, included by path).
#![allow(dead_code)]
#[path = "../../tests/common/mod.rs"]
mod common;
pub use common::*;
