//! Quality presets: one switch that sets every technique's knobs at once.

use crate::EngineError;
use std::fmt;
use std::str::FromStr;

/// A quality preset.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Preset {
    Low,
    #[default]
    Default,
    High,
}

impl Preset {
    pub const ALL: [Preset; 3] = [Preset::Low, Preset::Default, Preset::High];

    pub fn name(self) -> &'static str {
        match self {
            Preset::Low => "low",
            Preset::Default => "default",
            Preset::High => "high",
        }
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The member of `all` whose `name` is `s`, or a settings error that lists the names.
fn parse_named<T: Copy>(
    all: &[T],
    name: fn(T) -> &'static str,
    s: &str,
    what: &str,
) -> Result<T, EngineError> {
    all.iter().copied().find(|&v| name(v) == s).ok_or_else(|| {
        let names: Vec<&str> = all.iter().map(|&v| name(v)).collect();
        EngineError::Settings(format!("unknown {what} {s:?} ({})", names.join(", ")))
    })
}

impl FromStr for Preset {
    type Err = EngineError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse_named(&Preset::ALL, Preset::name, s, "preset")
    }
}

/// The one-bounce indirect sunlight technique.
///
/// The presets gather the bounce from the RSM instead of propagating it through the LPV,
/// because the component ledger says so: against the reference, the gather's one-bounce
/// error is a half to a third of the LPV's at the same or less time, and the radiance cache,
/// the most accurate of the three, costs more on a software adapter while it converges. The
/// figures: `docs/differences.md` ("The one-bounce technique").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Indirect {
    /// Light propagation volumes (the thesis): RSM texels injected into cascaded volumes,
    /// propagated, looked up per pixel; also lights the traced hits.
    Lpv,
    /// Gathered from the sun's RSM per pixel (`rsm_gi`, interleaved): no propagation blur, no
    /// occlusion; the traced hits get no bounce. The presets' choice.
    #[default]
    Rsm,
    /// Dynamic radiance volumes (`radiance_cache`): SH light caches allocated where the view
    /// needs them, lit on the CPU from the sun RSM's VPLs with ray-traced indirect shadows,
    /// looked up per pixel with DDGI's visibility weights (no leaks through walls); amortised
    /// over frames; also lights the traced hits.
    Cache,
    /// No indirect sunlight.
    None,
}

impl Indirect {
    pub const ALL: [Indirect; 4] = [Indirect::Lpv, Indirect::Rsm, Indirect::Cache, Indirect::None];

    pub fn name(self) -> &'static str {
        match self {
            Indirect::Lpv => "lpv",
            Indirect::Rsm => "rsm",
            Indirect::Cache => "cache",
            Indirect::None => "none",
        }
    }
}

impl fmt::Display for Indirect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Indirect {
    type Err = EngineError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse_named(&Indirect::ALL, Indirect::name, s, "indirect technique")
    }
}

/// Where the surfaces the traced rays find are lit (thesis 6.3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TracedShading {
    /// On the CPU where they are found, with shadow rays through the kd-tree (the presets'):
    /// glass lets the sun through, and the sky volume, the LPV and the radiance cache light
    /// them.
    #[default]
    Cpu,
    /// The thesis's design: the first surfaces go to the GPU as a traced G-buffer and are lit
    /// there with the deferred pass's BRDF, the sun through overlapped shadow maps
    /// ([`Settings::osm`]), the point lights through their cubes, the sky volume and the LPV
    /// by their lookup kernels (the radiance cache does not light them; glass casts the
    /// shadow maps' opaque shadows). The CPU traces no shadow rays for them.
    Gpu,
}

impl TracedShading {
    pub const ALL: [TracedShading; 2] = [TracedShading::Cpu, TracedShading::Gpu];

    pub fn name(self) -> &'static str {
        match self {
            TracedShading::Cpu => "cpu",
            TracedShading::Gpu => "gpu",
        }
    }
}

impl fmt::Display for TracedShading {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for TracedShading {
    type Err = EngineError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        parse_named(&TracedShading::ALL, TracedShading::name, s, "traced shading")
    }
}

/// Every knob of the engine. Build with [`Settings::preset`] and adjust fields.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Settings {
    pub width: u32,
    pub height: u32,
    pub preset: Preset,
    /// Sun cascades and their resolution (thesis 4.3.1, which gives neither; its Fig. 4.1
    /// draws three).
    pub csm_cascades: u32,
    pub csm_resolution: u32,
    /// PCSS blocker-search and PCF taps (0 PCF taps: hard shadows).
    pub pcss_blocker_taps: u32,
    pub pcss_pcf_taps: u32,
    /// Point-light shadows (cube maps) are rendered when a light is in range.
    pub point_shadow_resolution: u32,
    /// At most this many point lights stand for the scene's emissive surfaces
    /// ([`scene::emitter_lights`]), each shadowed by its cube like a point light; 0: emissive
    /// surfaces light nothing (only the reference sees their light).
    pub emitter_lights: u32,
    /// Sky volume: hemisphere samples per point and layers filled per frame (thesis 5.3.5:
    /// one layer per frame).
    pub sky_samples: usize,
    pub sky_layers_per_frame: u32,
    /// Sky map resolution (thesis 3.6.2: 256²).
    pub sky_map_size: u32,
    /// The one-bounce technique at the start (the renderer can switch it per frame).
    pub indirect: Indirect,
    /// RSM gather (`Indirect::Rsm`): VPLs per pixel, interleaving pattern, radius.
    #[serde(skip)]
    pub rsm_gi: rsm_gi::Settings,
    /// RSM gather: the map covers the whole scene when its bounding sphere's radius is at
    /// most this (metres), else this radius around the camera (the `rsm_gi` sweep's city
    /// view: 30 m).
    pub rsm_gather_radius: f32,
    /// LPV: cells per axis, cascades, propagation iterations, geometry volume, RSM size.
    #[serde(skip)]
    pub lpv: lpv::LpvSettings,
    pub rsm_resolution: u32,
    /// Inject and propagate the LPV on the GPU, resident (`lpv::gpu::ResidentLpv`: straight
    /// from the RSM's textures, nothing read back but the volumes when traced rays need them).
    /// `None`: on a hardware GPU yes; on a software adapter the crate's multi-threaded CPU
    /// path, which is faster than Mesa's emulation of the kernels (`docs/differences.md`).
    pub lpv_on_gpu: Option<bool>,
    /// LPV: sky-bounce VPLs across the view (thesis 5.3.7; rows follow the aspect ratio):
    /// the G-buffer sampled on that grid of cells is an RSM of sky light, injected beside the
    /// sun's (`passes::sky_bounce`); the LPV then carries sky light bounced once, in the
    /// `sun_indirect_diffuse` component. 0: off (the presets): against the reference it buys
    /// nothing measurable, and it makes the LPV view-dependent (it reruns whenever the camera
    /// moves); `docs/differences.md` has the figures, the bench's `engine/sky_bounce_*`
    /// entries track it.
    pub sky_bounce: u32,
    /// LPV: the glossy lookup (thesis 5.2.7, "diffuse + glossy reflections"): glossy
    /// surfaces reflect the LPV's radiance arriving from their mirror direction, marched
    /// over this many cells (`lpv::Lpv::glossy`); full frame only (the reference's
    /// one-bounce component is diffuse). 0: off (the presets): it barely moves the error
    /// against the reference and costs lighting time on glossy pixels (non-glossy pixels skip
    /// it); `docs/differences.md` has the figures, the bench's `engine/lpv_glossy_*` entries
    /// track it.
    pub lpv_glossy: u32,
    /// Radiance cache (`Indirect::Cache`): cascades, SH bands, shadow rays per lighting,
    /// caches lit per frame, and the bounces its caches carry (`bounces`): `Bounces::One`
    /// (the presets') lights them from the sun RSM's VPLs alone, today's one bounce bit for
    /// bit; `Bounces::Many` also traces `bounce_rays` rays from each lit cache and gathers
    /// the light their hits reflect (`passes::cache_bounce`: the sky and the point lights
    /// there, and the caches' own previous light, so each update adds a bounce and the
    /// caches converge to the many-bounce solution), and reruns the cache pass when the sky
    /// volume changed. The presets keep one bounce: on the ledger many bounces move the
    /// city's clamped rel RMS 0.154 -> 0.152 for twice the cache pass's time, and
    /// `cornell_window`'s 0.151 -> 0.154 (its one-bounce cache is already too bright;
    /// `docs/differences.md` has the figures).
    #[serde(skip)]
    pub radiance_cache: radiance_cache::Settings,
    /// Radiance cache: frames it keeps relighting (its `budget` caches each, oldest first)
    /// after the camera or the sun moved, so a still view converges and then costs nothing.
    pub cache_frames: u32,
    /// Radiance cache: at most this many surface points (columns x rows of the view, traced
    /// on the CPU) decide which caches are allocated.
    pub cache_points: (u32, u32),
    /// SSAO samples (0: off), radius in metres (thesis 5.3.8).
    pub ssao_samples: u32,
    pub ssao_radius: f32,
    /// Ray tracing: on when the scene needs it; depth 1 is the thesis (no recursion).
    pub trace_depth: u32,
    /// Where the traced rays' surfaces are lit (the presets: on the CPU).
    pub traced_shading: TracedShading,
    /// The overlapped shadow maps that light the traced G-buffer
    /// ([`TracedShading::Gpu`]; thesis 6.3.1).
    #[serde(skip)]
    pub osm: shadows::OsmSettings,
    /// The sun's glint in mirror and glass parts (off in the presets): the lighting pass adds
    /// `w_delta E_sun V_sun` times the density of the pixel's reflected directions at the
    /// sun (a Gaussian of the sun disk's, the pixel's and the normal's angular variance), so
    /// a glint far smaller than a pixel (the chrome statue's) is spread over the pixels that
    /// see it instead of missed. Energy: a flat mirror returns `0.97 R E_sun` over the image
    /// (`tests/glint.rs`). Off: on the ledger the spread glints sit a pixel or two from the
    /// reference's, and on the curved statue they carry too much energy, so the frame's error
    /// grows (`docs/differences.md` has the figures). Off until both match.
    pub sun_glints: bool,
    /// The sun mirrored by the scene's large planar reflectors (glass walls, mirrors) onto
    /// the surfaces in front of them ([`crate::mirrored_sun`]), in the full frame.
    pub mirrored_sun: bool,
    /// Anti-aliasing of a still view (`post`'s accumulation): while the camera, the sun, the
    /// view shown and the switches stay the same and no amortised pass is still filling,
    /// each frame's G-buffer is offset by a sub-pixel jitter and the lit frame is averaged
    /// with the ones before it, up to this many frames; then the frame is reused as it is
    /// until something changes. 1: off (every frame shades its pixels' centres). A moving
    /// camera restarts it every frame: its frames are first frames, shown as they were lit,
    /// so the average costs it nothing and buys it nothing.
    pub still_samples: u32,
    /// Reinhard key (middle grey) and eye adaptation rate per second (thesis 3.4.2-3.4.3).
    pub key: f32,
    pub adaptation_per_s: f32,
}

/// The LPV lookup offset, in cells along the normal, of the default and high presets (their
/// cells are half a metre; the low preset's metre cells keep the crate's half cell): a
/// surface sees less of the bounce it injected itself, and the ledger's LPV error falls by
/// about a quarter (`docs/differences.md`; `crates/app/tests/indirect_choice.rs` checks it).
pub const ENGINE_LPV_LOOKUP_OFFSET: f32 = 1.5;

impl Settings {
    /// The settings of a preset at `width x height`.
    pub fn preset(preset: Preset, width: u32, height: u32) -> Self {
        let base = Self::default_preset(width, height);
        match preset {
            Preset::Low => base.low(),
            Preset::Default => base,
            Preset::High => base.high(),
        }
    }

    /// The default preset's settings.
    fn default_preset(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            preset: Preset::Default,
            csm_cascades: 4,
            csm_resolution: 1024,
            pcss_blocker_taps: 16,
            pcss_pcf_taps: 16,
            point_shadow_resolution: 256,
            emitter_lights: 8,
            sky_samples: 100,
            sky_layers_per_frame: 4,
            sky_map_size: 256,
            // The lookup 1.5 cells along the normal instead of the crate's half cell: less of a
            // surface's own injected bounce (the ledger: cornell_window LPV rel RMS 4.08 ->
            // 3.08, full frame 0.374 -> 0.311; city street LPV ratio 77x -> 52x).
            lpv: lpv::LpvSettings {
                lookup_offset_cells: ENGINE_LPV_LOOKUP_OFFSET,
                ..lpv::LpvSettings::default_preset()
            },
            rsm_resolution: 256,
            // The RSM gather beat the LPV on the component ledger ([`Indirect`]).
            indirect: Indirect::Rsm,
            // Gathered at half resolution and upsampled (the seed's smaller indirect buffer):
            // the same error on the ledger, a third less lighting time at 1600x900.
            rsm_gi: rsm_gi::Settings { low_res: 2, ..rsm_gi::Settings::DEFAULT },
            rsm_gather_radius: 30.0,
            lpv_on_gpu: None,
            sky_bounce: 0,
            lpv_glossy: 0,
            radiance_cache: radiance_cache::Settings::DEFAULT,
            cache_frames: 8,
            cache_points: (320, 180),
            ssao_samples: 8,
            ssao_radius: 0.5,
            trace_depth: 1,
            traced_shading: TracedShading::Cpu,
            osm: shadows::OsmSettings::DEFAULT,
            sun_glints: false,
            // The city's ledger (320x180, 16 spp): the east facade across from the glass
            // tower 0.14 -> 1.01 of the reference, the whole frame 0.449 -> 0.429.
            mirrored_sun: true,
            still_samples: 16,
            key: 0.18,
            adaptation_per_s: 1.5,
        }
    }

    /// The low preset: `self` (the default's) with cheaper knobs.
    fn low(self) -> Self {
        Self {
            preset: Preset::Low,
            csm_cascades: 3,
            csm_resolution: 512,
            pcss_blocker_taps: 8,
            pcss_pcf_taps: 8,
            point_shadow_resolution: 128,
            emitter_lights: 4,
            sky_samples: 64,
            sky_layers_per_frame: 16,
            sky_map_size: 128,
            lpv: lpv::LpvSettings::low(),
            osm: shadows::OsmSettings::low(),
            rsm_resolution: 128,
            rsm_gi: rsm_gi::Settings::LOW,
            // Not the crate's low preset: its 1 m caches and 32 moment rays let the sunlit
            // room's bounce through `two_rooms`' 5 cm wall (the closed room's mean bounce
            // 1.4e-3 against 7e-6 with the default's 0.5 m and 64 rays). The default's
            // lattice with the low preset's lighting costs.
            radiance_cache: radiance_cache::Settings {
                cascades: 2,
                bands: 2,
                vpl_samples: 16,
                budget: 256,
                ..radiance_cache::Settings::DEFAULT
            },
            cache_frames: 4,
            ssao_samples: 0,
            still_samples: 4,
            ..self
        }
    }

    /// The high preset: `self` (the default's) with dearer knobs.
    fn high(self) -> Self {
        Self {
            preset: Preset::High,
            csm_resolution: 2048,
            pcss_blocker_taps: 32,
            pcss_pcf_taps: 32,
            point_shadow_resolution: 512,
            emitter_lights: 16,
            sky_samples: 256,
            lpv: lpv::LpvSettings {
                lookup_offset_cells: ENGINE_LPV_LOOKUP_OFFSET,
                ..lpv::LpvSettings::high()
            },
            rsm_resolution: 512,
            // Full resolution. Not the crate's HIGH (1024 VPLs, 2x2): on cornell_window
            // the bounce comes out 12.9x too bright (rel RMS 6.3 against 1.39 here). Not a
            // bug but what the gather converges to there: its one pattern at every pixel
            // undersamples the near field with 512 uniform (Poisson) samples and finds
            // it with 1024; the paper's polar pattern, which samples the near field
            // densely, converges at any count (a floor lighting a wall: 0.45-0.50 of the
            // floor's radiosity from 32 to 4096 samples, Poisson 0.25-0.74) and gives
            // 10.7 / 12.8 / 16.6x at low / default / high on cornell_window, where the
            // sunlit ground outside lights the room through its walls (no occlusion: the
            // radiance cache's 1.8x). The city, with its open streets, prefers polar
            // (0.57 against 0.69) but the presets keep Poisson's luckier total.
            rsm_gi: rsm_gi::Settings::DEFAULT,
            radiance_cache: radiance_cache::Settings::HIGH,
            cache_frames: 16,
            ssao_samples: 16,
            // The city's direct sun against a 64-spp reference (320x180): 0.099 with the
            // default's 16 samples, 0.035 with 64 (the statue's highlights, a few pixels,
            // converge slowly; 4x4 supersampling: 0.069).
            still_samples: 64,
            trace_depth: 2,
            osm: shadows::OsmSettings::high(),
            ..self
        }
    }

    /// Rejects sizes and knobs the passes cannot work with.
    pub fn validate(&self) -> Result<(), EngineError> {
        let bad = |m: String| Err(EngineError::Settings(m));
        if self.width < 8 || self.height < 8 || self.width > 8192 || self.height > 8192 {
            return bad(format!("image size {}x{} (8..8192 per side)", self.width, self.height));
        }
        if !(1..=4).contains(&self.csm_cascades) {
            return bad(format!("{} cascades (1..4)", self.csm_cascades));
        }
        if !(64..=4096).contains(&self.csm_resolution)
            || !(16..=2048).contains(&self.rsm_resolution)
        {
            return bad("shadow map or RSM resolution out of range".into());
        }
        if self.pcss_blocker_taps > 64 || self.pcss_pcf_taps > 64 || self.ssao_samples > 64 {
            return bad("at most 64 PCSS or SSAO taps".into());
        }
        if self.sky_samples == 0 || self.sky_layers_per_frame == 0 {
            return bad("sky volume needs samples and at least one layer per frame".into());
        }
        if !(1..=256).contains(&self.still_samples) {
            return bad(format!("{} still-view samples (1..256)", self.still_samples));
        }
        if self.lpv_glossy > 16 {
            return bad(format!("{} glossy LPV steps (0..16)", self.lpv_glossy));
        }
        if self.emitter_lights > 64 {
            return bad(format!("{} emitter lights (0..64)", self.emitter_lights));
        }
        if self.sky_bounce > 1024 {
            return bad(format!("{} sky-bounce VPL columns (0..1024)", self.sky_bounce));
        }
        self.osm.validate().map_err(|e| EngineError::Settings(e.to_string()))?;
        if !(1..=3).contains(&self.trace_depth) {
            return bad(format!("trace depth {} (1..3)", self.trace_depth));
        }
        if !(self.rsm_gather_radius > 0.0 && self.rsm_gather_radius.is_finite()) {
            return bad(format!("RSM gather radius {}", self.rsm_gather_radius));
        }
        if !(self.key > 0.0 && self.adaptation_per_s >= 0.0) {
            return bad("tone-mapping key must be positive".into());
        }
        let (cols, rows) = self.cache_points;
        if self.cache_frames == 0 || !(1..=4096).contains(&cols) || !(1..=4096).contains(&rows) {
            return bad("radiance cache: at least one frame and 1..4096 points per side".into());
        }
        self.radiance_cache.validate().map_err(|e| EngineError::Settings(e.to_string()))?;
        self.rsm_gi.validate().map_err(|e| EngineError::Settings(e.to_string()))?;
        self.lpv.validate().map_err(|e| EngineError::Settings(e.to_string()))
    }
}
