//! The generated test scenes, deterministic from a seed.

mod builder;
mod city;
mod cornell_area;
mod rooms;
mod simple;
mod textures;

pub use city::city;
use cornell_area::cornell_area;
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
}

impl Generated {
    pub const ALL: [Self; 6] = [
        Self::City,
        Self::CornellWindow,
        Self::CornellArea,
        Self::TwoRooms,
        Self::PlaneBox,
        Self::Furnace,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Self::City => "city",
            Self::CornellWindow => "cornell_window",
            Self::CornellArea => "cornell_area",
            Self::TwoRooms => "two_rooms",
            Self::PlaneBox => "plane_box",
            Self::Furnace => "furnace",
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
        }
    }
}
