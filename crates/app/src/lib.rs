//! The applications around the `engine` library: the command-line renderer `serein-render`
//! (`cargo xtask render`), its report beside the thesis's tables, and the measurements of the
//! engine against the `reference` path tracer (whole-frame errors, and the component ledger
//! with its regions and contact sheet). The engine itself stays free of command-line,
//! progress-bar and reference dependencies.
//!
//! - [`cli`]: one render job: load a scene, render frames, write the image and the report.
//! - [`report`]: `report.md`, `report.json` and `timeline.svg`, beside the thesis's Table 7.1
//!   and 7.3 ([`thesis`]).
//! - [`compare`]: a frame against the reference image of the same view.
//! - [`ledger`]: each lighting component against its reference, whole frame and per region
//!   ([`regions`]), with a contact sheet ([`contact_sheet`]) and the light beyond one bounce
//!   ([`beyond`]).
//! - [`truth`]: `serein-reference`, the reference of any scene on the CPU alone, whole or
//!   as partial renders that merge.
//! - [`view`]: `serein-view`, the engine in a window.
//! - [`soak`]: `serein-soak` (`cargo xtask soak`), the renderer for minutes on a schedule,
//!   checked for growth of memory and GPU objects.

pub mod beyond;
pub mod cli;
pub mod compare;
pub mod contact_sheet;
pub mod ledger;
pub mod regions;
pub mod report;
pub mod soak;
pub mod thesis;
pub mod truth;
pub mod view;

use engine::EngineError;
use std::path::Path;

/// An I/O error at `path` as the engine reports it.
pub(crate) fn io_err(path: &Path, e: impl std::fmt::Display) -> EngineError {
    EngineError::Io { path: path.display().to_string(), message: e.to_string() }
}

/// A frame's HDR image as the reference's image type.
pub fn image_of(hdr: &engine::HdrFrame) -> reference::Image {
    let mut im = reference::Image::new(hdr.width, hdr.height);
    im.pixels = hdr.rgb().collect();
    im
}
