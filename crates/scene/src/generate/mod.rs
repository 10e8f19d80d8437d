//! The generated test scenes, deterministic from a seed:
//!
//! - `city`: the thesis's reference city (chapter 7), about 19 000 triangles, mirrors, glass,
//!   alpha-tested trees, textures, point lights;
//! - `cornell_window`: a Cornell box lit by the sun through a window;
//! - `cornell_area`: the Cornell box lit only by a ceiling emitter;
//! - `two_rooms`: two rooms, one closed (light leaks show);
//! - `plane_box`: a box and a pole on a plane under the sun (shadows, penumbrae);
//! - `furnace`: the white furnace (an analytic radiance everywhere);
//! - `pbr_gallery` ([`pbr_gallery`]): glTF metallic-roughness spheres (5 roughnesses x red
//!   plastic, gold and copper) on a floor, a normal-mapped wall under a grazing sun, a spot
//!   light's pool on the floor and an emissive panel; its glTF twin is in
//!   `tests/data/pbr_gallery/`.

mod builder;
mod city;
mod cornell_area;
mod pbr_gallery;
mod rooms;
mod simple;
mod textures;

pub use city::city;
use cornell_area::cornell_area;
pub use pbr_gallery::{
    PBR_GALLERY_PANEL_EMISSION, PBR_GALLERY_ROUGHNESS, PBR_GALLERY_ROWS, PBR_GALLERY_SPHERE_RADIUS,
    PBR_GALLERY_SPOT_CONE_DEG, PBR_GALLERY_SPOT_POSITION, PBR_GALLERY_SPOT_TARGET,
    PBR_GALLERY_SUN_ELEVATION_DEG, PBR_GALLERY_SUN_GRAZE_DEG, pbr_gallery,
    pbr_gallery_sphere_center,
};
pub use rooms::{cornell_window, two_rooms};
pub use simple::{FURNACE_ALBEDO, FURNACE_EMISSION, furnace, furnace_radiance, plane_box};

use crate::Scene;

/// The generated scenes by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Generated {
    City,
    CornellWindow,
    CornellArea,
    TwoRooms,
    PlaneBox,
    Furnace,
    PbrGallery,
}

impl Generated {
    pub const ALL: [Self; 7] = [
        Self::City,
        Self::CornellWindow,
        Self::CornellArea,
        Self::TwoRooms,
        Self::PlaneBox,
        Self::Furnace,
        Self::PbrGallery,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Self::City => "city",
            Self::CornellWindow => "cornell_window",
            Self::CornellArea => "cornell_area",
            Self::TwoRooms => "two_rooms",
            Self::PlaneBox => "plane_box",
            Self::Furnace => "furnace",
            Self::PbrGallery => "pbr_gallery",
        }
    }

    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|g| g.name() == name)
    }

    /// Builds the scene; the same seed gives the same scene, bit for bit.
    pub fn build(self, seed: u64) -> Scene {
        match self {
            Self::City => city(seed),
            Self::CornellWindow => cornell_window(seed),
            Self::CornellArea => cornell_area(seed),
            Self::TwoRooms => two_rooms(seed),
            Self::PlaneBox => plane_box(seed),
            Self::Furnace => furnace(seed),
            Self::PbrGallery => pbr_gallery(seed),
        }
    }
}
