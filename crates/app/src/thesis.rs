//! The Serenity thesis's measured timings, as data, to print beside ours.
//!
//! Source: the thesis's chapter 7 ("Evaluation"). §7.2 fixes the set-up: the reference city
//! (about 19,000 triangles, 32 occlusion quads) rendered at 1600x900 on an Intel Core 2 Quad at
//! 2.66 GHz with 4 GB of RAM and an NVIDIA GeForce GTX 260. §7.3 gives:
//!
//! * **Table 7.1** ("Timings of the first test"): one typical frame, lighting for the whole
//!   screen, ray-traced reflections on a small part of it: `TABLE_7_1`, total
//!   `TABLE_7_1_TOTAL_MS` (42.6 ms, 23 fps). The sky-volume layer (12.6 ms) is left out of
//!   the total because it stops once the volume is complete; the other rows sum to
//!   `TABLE_7_1_SUM_MS` (65.1 ms): the CPU ray tracing overlaps the GPU lighting, and run in
//!   series the frame took `TABLE_7_1_SERIAL_MS` (68 ms, 14 fps).
//! * **Table 7.2** ("Timings of the second test", reflections filling the screen): the same
//!   rows, kept here as `ThesisPass::worst_ms`, total `TABLE_7_2_TOTAL_MS` (95.6 ms, 10 fps).
//! * **Table 7.3** ("Timings of the third test", a fly-through): `TABLE_7_3`, mean frame
//!   48.4 ms (20 fps), standard deviation 5.9 ms, 5000 frames. The table gives no share of
//!   frames with ray tracing; the text says ray-traced effects were constantly present but
//!   rarely covered much of the screen (`TABLE_7_3_RAY_TRACING`).
//!
//! `thesis_pass_for` maps our pass names to these rows. Rows with no counterpart: Screen
//! Space Ambient Occlusion (6.0 ms; we have no SSAO pass). Our passes with no row: "sky map"
//! (regenerated only when the time of day changes, §3.6, not timed in chapter 7), "shadow maps"
//! (the thesis times shadow-map rendering inside "Direct Lighting (Phong + CSM + PCSS)", which
//! we compare with "lighting"), "point shadows", "g-buffer", "ray casting buffer" (§6.2.6,
//! generated on the GPU, not timed), "traced upload" (the sync point, not timed) and
//! "readback + tonemap".

use serde::Serialize;

const AUXILIARY: &str = "Auxiliary Steps";
const MAIN: &str = "Main Lighting";
const REFLECTIONS: &str = "Ray Traced Reflections";
const LPV_RENDERING: &str = "Light Propagation Volumes Rendering (diffuse + glossy reflections)";

/// One row of Table 7.1 (and the same row of Table 7.2), or a sum of rows that one of our
/// passes covers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub(crate) struct ThesisPass {
    /// A stable key (`"cpu_ray_tracing"`).
    pub(crate) id: &'static str,
    /// The row as the thesis prints it ("O SM" in the extracted text is OSM, the overlapped
    /// shadow maps of §6.3.1).
    pub(crate) name: &'static str,
    /// The table's group: "Auxiliary Steps", "Main Lighting" or "Ray Traced Reflections".
    pub(crate) group: &'static str,
    /// Table 7.1, typical frame, milliseconds.
    pub(crate) ms: f64,
    /// Table 7.2, reflections filling the screen, milliseconds.
    pub(crate) worst_ms: f64,
    /// Counted in the thesis's total frame time (the sky-volume layer is not).
    pub(crate) in_total: bool,
    /// For a sum: the ids of the Table 7.1 rows it adds up; empty for a row.
    pub(crate) parts: &'static [&'static str],
}

const fn row(
    id: &'static str,
    name: &'static str,
    group: &'static str,
    ms: f64,
    worst_ms: f64,
) -> ThesisPass {
    ThesisPass { id, name, group, ms, worst_ms, in_total: true, parts: &[] }
}

impl ThesisPass {
    /// The name, marked when it is a row of the ray-traced group (whose names repeat).
    pub(crate) fn label(&self) -> String {
        if self.group == REFLECTIONS && self.parts.is_empty() {
            format!("{} (reflections)", self.name)
        } else {
            self.name.to_owned()
        }
    }
}

/// Table 7.1 (with Table 7.2's figure for each row), in the thesis's order.
pub(crate) const TABLE_7_1: &[ThesisPass] = &[
    ThesisPass {
        in_total: false,
        ..row("sky_volume_layer", "Sky Lighting Volume Update (one layer)", AUXILIARY, 12.6, 12.6)
    },
    row("lpv_update", "Light Propagation Volumes Update (3 cascades)", AUXILIARY, 5.0, 5.0),
    row("direct", "Direct Lighting (Phong + CSM + PCSS)", MAIN, 6.5, 5.7),
    row("sky_lighting", "Sky Lighting", MAIN, 2.4, 2.4),
    row("lpv_render", LPV_RENDERING, MAIN, 6.8, 6.0),
    row("ssao", "Screen Space Ambient Occlusion", MAIN, 6.0, 6.2),
    row("cpu_ray_tracing", "CPU Ray Tracing", REFLECTIONS, 36.0, 78.0),
    row("rt_direct", "Direct Lighting (Phong + OSM + PCSS)", REFLECTIONS, 0.8, 1.1),
    row("rt_sky_lighting", "Sky Lighting", REFLECTIONS, 0.6, 0.6),
    row("rt_lpv_render", LPV_RENDERING, REFLECTIONS, 1.0, 1.5),
];

/// Direct + sky lighting + LPV rendering of the main view: what our "lighting" pass does.
pub(crate) const MAIN_LIGHTING: ThesisPass = ThesisPass {
    parts: &["direct", "sky_lighting", "lpv_render", "ssao"],
    ..row(
        "main_lighting",
        "Main Lighting: Direct + Sky Lighting + LPV Rendering + SSAO",
        MAIN,
        21.7,
        20.3,
    )
};

/// The same three steps on the traced G-buffer (§6.2). Our ray tracer shades its hits on the
/// CPU, so these are inside our "ray tracing" pass; kept for report.json.
pub(crate) const REFLECTION_LIGHTING: ThesisPass = ThesisPass {
    parts: &["rt_direct", "rt_sky_lighting", "rt_lpv_render"],
    ..row(
        "reflection_lighting",
        "Ray Traced Reflections: Direct + Sky Lighting + LPV Rendering",
        REFLECTIONS,
        2.4,
        3.2,
    )
};

/// Table 7.1's total frame time, without the sky-volume layer (23 fps).
pub(crate) const TABLE_7_1_TOTAL_MS: f64 = 42.6;
/// Sum of Table 7.1's rows counted in the total (§7.3).
pub(crate) const TABLE_7_1_SUM_MS: f64 = 65.1;
/// The first test with the lighting forced to run in series (§7.3, 14 fps).
pub(crate) const TABLE_7_1_SERIAL_MS: f64 = 68.0;
/// Table 7.2's total frame time (10 fps).
pub(crate) const TABLE_7_2_TOTAL_MS: f64 = 95.6;

/// One figure of Table 7.3.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub(crate) struct ThesisStat {
    pub(crate) name: &'static str,
    pub(crate) value: f64,
    pub(crate) unit: &'static str,
}

/// Table 7.3, the fly-through.
pub(crate) const TABLE_7_3: &[ThesisStat] = &[
    ThesisStat { name: "Average Frame Duration (20 FPS)", value: 48.4, unit: "ms" },
    ThesisStat { name: "Standard Deviation", value: 5.9, unit: "ms" },
    ThesisStat { name: "Number of Frames", value: 5000.0, unit: "frames" },
];

/// What §7.3 says about ray tracing in the fly-through (no figure is given).
pub(crate) const TABLE_7_3_RAY_TRACING: &str = "not tabulated; §7.3: ray-traced effects \
     constantly present, rarely covering a large part of the screen";

/// The thesis row (or sum of rows) our pass `engine_pass` compares with; `None` where the
/// thesis times nothing like it (see the module docs).
pub(crate) fn thesis_pass_for(engine_pass: &str) -> Option<&'static ThesisPass> {
    let id = match engine_pass {
        "sky volume" => "sky_volume_layer",
        "lpv" => "lpv_update",
        "ray tracing" => "cpu_ray_tracing",
        "lighting" => return Some(&MAIN_LIGHTING),
        _ => return None,
    };
    TABLE_7_1.iter().find(|p| p.id == id)
}

/// Everything above as JSON, for report.json.
pub(crate) fn json() -> serde_json::Value {
    serde_json::json!({
        "source": "Serenity thesis, chapter 7 (GeForce GTX 260 + Core 2 Quad 2.66 GHz, 1600x900)",
        "table_7_1": TABLE_7_1,
        "sums": [MAIN_LIGHTING, REFLECTION_LIGHTING],
        "table_7_1_total_ms": TABLE_7_1_TOTAL_MS,
        "table_7_1_sum_ms": TABLE_7_1_SUM_MS,
        "table_7_1_serial_ms": TABLE_7_1_SERIAL_MS,
        "table_7_2_total_ms": TABLE_7_2_TOTAL_MS,
        "table_7_3": TABLE_7_3,
        "table_7_3_ray_tracing": TABLE_7_3_RAY_TRACING,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum(parts: &[&str], f: fn(&ThesisPass) -> f64) -> f64 {
        parts.iter().map(|id| f(TABLE_7_1.iter().find(|p| p.id == *id).unwrap())).sum()
    }

    #[test]
    fn sums_match_the_rows() {
        let total: f64 = TABLE_7_1.iter().filter(|p| p.in_total).map(|p| p.ms).sum();
        assert!((total - TABLE_7_1_SUM_MS).abs() < 1e-9, "{total}");
        for s in [MAIN_LIGHTING, REFLECTION_LIGHTING] {
            assert!((sum(s.parts, |p| p.ms) - s.ms).abs() < 1e-9, "{}", s.id);
            assert!((sum(s.parts, |p| p.worst_ms) - s.worst_ms).abs() < 1e-9, "{}", s.id);
        }
    }

    #[test]
    fn engine_passes_map() {
        use engine::pass::*;
        let mapped = [SKY_VOLUME, LPV, RAY_TRACING, LIGHTING];
        let unmapped =
            [SKY_MAP, SHADOW_MAPS, POINT_SHADOWS, GBUFFER, RAY_CASTING, COMBINE, TONE_MAPPING];
        assert!(mapped.iter().all(|p| thesis_pass_for(p).is_some()));
        assert!(unmapped.iter().all(|p| thesis_pass_for(p).is_none()));
        assert_eq!(thesis_pass_for("ray tracing").unwrap().ms, 36.0);
        assert!(!thesis_pass_for("sky volume").unwrap().in_total);
        assert_eq!(json()["table_7_1"].as_array().unwrap().len(), 10);
    }
}
