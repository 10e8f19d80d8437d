//! Settings: how many sample directions, which fill method, which non-negativity policy.

use crate::SkyVolumeError;

/// How the volume is filled. One API ([`crate::SkyVolume::update`]); the methods differ in
/// what they keep between fills and so in what a change of the sky costs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FillMethod {
    /// The thesis (5.3.4): every fill traces every sample direction of every point against
    /// the quads (any-hit, SoA quads, hemisphere culling) and projects the unblocked sky.
    /// Nothing is cached: a sky change costs a whole fill.
    BruteForce,
    /// Per-point visibility of each sample direction (a bitmask; with translucent quads also
    /// the sparse per-sample transmittance) is computed when the quads change and cached. A
    /// sky change re-lights by a masked projection with per-byte lookup tables: no rays.
    /// Same result as brute force at the same sample count (up to summation order).
    CachedVisibility,
    /// Precomputed radiance transfer (Sloan, Kautz & Snyder 2002): per point a 9 x k^2
    /// matrix maps the sky's k-band SH projection to the point's 3-band radiance SH. A sky
    /// change is one projection of the sky plus a small matrix-vector product per point.
    /// `sky_bands` is k, 3..=5; the error is the sky's band-limiting.
    Transfer { sky_bands: u32 },
}

/// Non-negativity policy of the lookup (3-band SH of an occluded sky rings).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Window {
    /// No windowing: sharpest, may ring negative near strong occlusion boundaries.
    None,
    /// Hann window over 3 bands (sh_math::hann_window).
    Hann,
    /// Sloan's window `1 / (1 + lambda l^2 (l+1)^2)`.
    Sloan(f32),
}

/// Everything that decides accuracy and cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Saff-Kuijlaars hemisphere directions per point (thesis: 100). 1..=8192.
    pub samples: usize,
    pub method: FillMethod,
    /// Window applied (with the clamped cosine) at lookup. Whatever the window, the lookup's
    /// irradiance is clamped at zero per channel: see [`crate::SkyVolume::irradiance`].
    pub window: Window,
    /// Directions used to project the sky onto `sky_bands` bands for [`FillMethod::Transfer`].
    pub sky_projection_samples: usize,
    /// Lookup: leave out of the interpolation the probes behind the surface's plane (on the
    /// side its normal does not face) and renormalise the others' weights; with none in
    /// front, plain trilinear. A probe inside a building sees no sky, so with plain trilinear
    /// (the thesis, `false`) a facade between probes inside and outside gets about half its
    /// sky light (the engine's city: vertical faces 0.4-0.5x of the reference).
    pub oriented_lookup: bool,
}

impl Settings {
    /// 36 samples, cached visibility.
    pub const fn low() -> Self {
        Self {
            samples: 36,
            method: FillMethod::CachedVisibility,
            window: Window::None,
            sky_projection_samples: 512,
            oriented_lookup: true,
        }
    }

    /// The thesis's 100 samples, cached visibility (re-light without rays).
    pub const DEFAULT: Self = Self {
        samples: 100,
        method: FillMethod::CachedVisibility,
        window: Window::None,
        sky_projection_samples: 1024,
        oriented_lookup: true,
    };

    /// 256 samples, cached visibility.
    pub const fn high() -> Self {
        Self { samples: 256, ..Self::DEFAULT }
    }

    /// The report's reference: 4096 samples, brute force.
    pub const fn reference() -> Self {
        Self { samples: 4096, method: FillMethod::BruteForce, ..Self::DEFAULT }
    }

    /// The same settings with another method.
    pub const fn with_method(mut self, method: FillMethod) -> Self {
        self.method = method;
        self
    }

    /// The same settings with another sample count.
    pub const fn with_samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }

    /// Checks the ranges.
    pub fn validate(&self) -> Result<(), SkyVolumeError> {
        let bad = |s: String| Err(SkyVolumeError::InvalidSettings(s));
        if !(1..=8192).contains(&self.samples) {
            return bad(format!("samples {} outside 1..=8192", self.samples));
        }
        if let FillMethod::Transfer { sky_bands } = self.method
            && !(3..=5).contains(&sky_bands)
        {
            return bad(format!("sky_bands {sky_bands} outside 3..=5"));
        }
        if !(16..=65536).contains(&self.sky_projection_samples) {
            return bad(format!(
                "sky_projection_samples {} outside 16..=65536",
                self.sky_projection_samples
            ));
        }
        if let Window::Sloan(l) = self.window
            && !(l.is_finite() && l >= 0.0)
        {
            return bad(format!("Sloan lambda {l} must be finite and >= 0"));
        }
        Ok(())
    }
}

impl Default for Settings {
    fn default() -> Self {
        Self::DEFAULT
    }
}
