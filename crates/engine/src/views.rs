//! What a frame shows: the lit frame, one lighting term ([`Component`]), or one G-buffer
//! channel ([`Channel`]), the debug views a viewer offers beside the lighting components.
//!
//! A channel view replaces the lighting pass's output with the channel's value mapped to
//! `[0, 1]` and is displayed as it is (no exposure, no tone curve; eye adaptation holds its
//! state until the frame is shown again).

use crate::components::{self, Component};

/// A G-buffer channel (thesis Table 3.1) or a quantity the lighting pass computes per pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Channel {
    /// Base colour (with its texture), linear RGB.
    BaseColor,
    /// Metallic (the base colour target's alpha), grey.
    Metallic,
    /// Shading normal, `0.5 + 0.5 n` in world space.
    ShadingNormal,
    /// Geometric normal, `0.5 + 0.5 n` in world space.
    GeometryNormal,
    /// Linear view depth, `1 - exp(-depth / 20 m)` (near is dark).
    Depth,
    /// Screen-space ambient occlusion (1: open), with the frame's SSAO settings.
    AmbientOcclusion,
    /// Roughness as the lighting reads it (widened for specular anti-aliasing), grey.
    Roughness,
}

impl Channel {
    pub const ALL: [Channel; 7] = [
        Channel::BaseColor,
        Channel::Metallic,
        Channel::ShadingNormal,
        Channel::GeometryNormal,
        Channel::Depth,
        Channel::AmbientOcclusion,
        Channel::Roughness,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Self::BaseColor => "base colour",
            Self::Metallic => "metallic",
            Self::ShadingNormal => "shading normal",
            Self::GeometryNormal => "geometry normal",
            Self::Depth => "depth",
            Self::AmbientOcclusion => "ambient occlusion",
            Self::Roughness => "roughness",
        }
    }
}

/// What the frame shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum View {
    /// The lit, combined frame.
    #[default]
    Frame,
    /// One lighting term in the reference's units.
    Component(Component),
    /// One G-buffer channel, displayed as it is.
    Channel(Channel),
}

/// The shaders' code of the first channel (`CHANNEL_BASE` in `common.inc.wgsl`); channel `i`
/// of [`Channel::ALL`] is `CHANNEL_BASE + i`.
pub const CHANNEL_BASE: u32 = 16;

impl View {
    /// The frame uniform's view code: a `COMPONENT_*` code, or `CHANNEL_BASE + i`.
    pub fn code(self) -> u32 {
        match self {
            View::Frame => 0,
            View::Component(c) => components::code(Some(c)),
            View::Channel(ch) => {
                CHANNEL_BASE + Channel::ALL.iter().position(|&c| c == ch).unwrap_or(0) as u32
            }
        }
    }

    /// The view a code stands for (`None`: no view has that code).
    pub fn of_code(code: u32) -> Option<View> {
        if code == 0 {
            return Some(View::Frame);
        }
        if let Some(i) = code.checked_sub(CHANNEL_BASE) {
            return Channel::ALL.get(i as usize).map(|&c| View::Channel(c));
        }
        Component::ALL.into_iter().find(|&c| components::code(Some(c)) == code).map(|c| match c {
            Component::Full => View::Frame,
            c => View::Component(c),
        })
    }

    /// Shown without exposure and tone curve.
    pub fn is_raw(self) -> bool {
        matches!(self, View::Channel(_))
    }

    pub fn name(self) -> &'static str {
        match self {
            View::Frame => "frame",
            View::Component(c) => c.name(),
            View::Channel(c) => c.name(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_distinct_and_round_trip() {
        let mut views = vec![View::Frame];
        views.extend(
            Component::ALL.iter().filter(|&&c| c != Component::Full).map(|&c| View::Component(c)),
        );
        views.extend(Channel::ALL.map(View::Channel));
        let mut codes: Vec<u32> = views.iter().map(|v| v.code()).collect();
        for v in &views {
            assert_eq!(View::of_code(v.code()), Some(*v), "{v:?}");
        }
        codes.sort();
        codes.dedup();
        assert_eq!(codes.len(), views.len());
        assert!(View::of_code(CHANNEL_BASE + Channel::ALL.len() as u32).is_none());
        assert!(View::Channel(Channel::Depth).is_raw() && !View::Frame.is_raw());
    }
}
