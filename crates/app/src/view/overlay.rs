//! The overlay (egui): the adapter and its warning, frame time and its rolling graph, the
//! controls (time of day and date, effect switches, indirect technique with the radiance
//! cache's state, preset, view shown, fly-through), and the last frame's pass table. It only reads and edits [`Controls`]; the window applies them.

use super::controls::{Controls, views};
use engine::{Effect, FrameStats, Indirect, Preset, View};
use std::collections::VecDeque;

/// What the overlay shows besides the controls.
pub struct OverlayInfo<'a> {
    pub adapter: &'a str,
    pub software: bool,
    pub size: (u32, u32),
    pub frame_ms: &'a VecDeque<f32>,
    /// Milliseconds from the overlay's input to the present: the UI, the blit of the engine's image
    /// and the overlay's draw, and the present (which waits for the surface).
    pub overlay_ms: f32,
    pub last: Option<&'a FrameStats>,
    /// The still-view samples the renderer averages (`engine::Settings::still_samples`).
    pub still_samples: u32,
    pub message: Option<&'a str>,
    /// The radiance cache's last update, while it is the indirect technique.
    pub cache: Option<engine::CacheSummary>,
}

/// Buttons pressed this frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OverlayActions {
    pub screenshot: bool,
    pub reset_camera: bool,
}

/// The label of a view in the list.
fn view_label(v: View) -> String {
    match v {
        View::Frame => "frame".into(),
        View::Component(c) => format!("component: {}", c.name()),
        View::Channel(c) => format!("g-buffer: {}", c.name()),
    }
}

/// The overlay's egui context: no window shadow (a software rasteriser pays for every
/// blended pixel of its soft edge: on lavapipe at 1280x720 the overlay's span fell from 26 to
/// 17 ms without it).
pub fn context() -> egui::Context {
    let ctx = egui::Context::default();
    ctx.all_styles_mut(|s| {
        s.visuals.window_shadow = egui::epaint::Shadow::NONE;
        s.visuals.popup_shadow = egui::epaint::Shadow::NONE;
    });
    ctx
}

pub fn draw(
    ctx: &egui::Context,
    controls: &mut Controls,
    info: &OverlayInfo<'_>,
) -> OverlayActions {
    let mut actions = OverlayActions::default();
    egui::Window::new("serein").default_pos([8.0, 8.0]).default_width(360.0).show(ctx, |ui| {
        ui.label(format!("{}  {}x{}", info.adapter, info.size.0, info.size.1));
        if info.software {
            ui.colored_label(
                egui::Color32::YELLOW,
                "software adapter (Mesa): timings are CPU timings, not GPU timings",
            );
        }
        let last = info.frame_ms.back().copied().unwrap_or(0.0);
        ui.label(format!(
            "frame {last:.1} ms ({:.1} fps), overlay + present {:.2} ms",
            1e3 / last.max(1e-3),
            info.overlay_ms
        ));
        frame_graph(ui, info.frame_ms);
        if let Some(s) = info.last.filter(|_| info.still_samples > 1) {
            let k = s.still_sample;
            let n = info.still_samples;
            ui.label(match k {
                0 => format!("first frame of the view (it moved or changed; {n} when still)"),
                _ => format!("still view: {k} of {n} jittered samples averaged"),
            });
        }
        if let Some(m) = info.message {
            ui.label(m);
        }
        ui.separator();
        let h = controls.local_hours;
        let mut hours = h as f32;
        ui.add(egui::Slider::new(&mut hours, 0.0..=23.99).text(format!(
            "time {:02}:{:02}, {}-{:02}-{:02}",
            h as u32,
            ((h.fract()) * 60.0) as u32,
            controls.date.year,
            controls.date.month,
            controls.date.day
        )));
        if (hours as f64 - h).abs() > 1e-4 {
            controls.local_hours = hours as f64;
        }
        let mut day = controls.date.day_of_year();
        if ui.add(egui::Slider::new(&mut day, 1..=366).text("day of the year")).changed() {
            controls.set_day_of_year(day);
        }
        for (i, e) in Effect::ALL.into_iter().enumerate() {
            let mut on = controls.effects.is_on(e);
            if ui.checkbox(&mut on, format!("[{}] {}", i + 1, e.name())).changed() {
                controls.effects.set(e, on);
            }
        }
        egui::ComboBox::from_label("[I] indirect technique")
            .selected_text(controls.indirect.name())
            .show_ui(ui, |ui| {
                for i in Indirect::ALL {
                    ui.selectable_value(&mut controls.indirect, i, i.name());
                }
            });
        if let Some(c) = &info.cache {
            ui.label(format!("radiance cache: {c}"));
        }
        egui::ComboBox::from_label("[C] shown").selected_text(view_label(controls.view)).show_ui(
            ui,
            |ui| {
                for v in views() {
                    ui.selectable_value(&mut controls.view, v, view_label(v));
                }
            },
        );
        egui::ComboBox::from_label("[F5] preset").selected_text(controls.preset.name()).show_ui(
            ui,
            |ui| {
                for p in Preset::ALL {
                    ui.selectable_value(&mut controls.preset, p, p.name());
                }
            },
        );
        ui.horizontal(|ui| {
            ui.toggle_value(&mut controls.playing, "[P] fly-through");
            actions.reset_camera = ui.button("[R] reset camera").clicked();
            actions.screenshot = ui.button("[F12] screenshot").clicked();
        });
        if let Some(stats) = info.last {
            ui.separator();
            pass_table(ui, stats);
        }
        ui.small(
            "WASD + Q/E fly, right mouse look, Shift fast, T / Shift+T time ±15 min, Tab overlay",
        );
    });
    actions
}

fn frame_graph(ui: &mut egui::Ui, ms: &VecDeque<f32>) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(340.0, 48.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, egui::Color32::from_black_alpha(120));
    let max = ms.iter().copied().fold(1.0f32, f32::max);
    let n = ms.len().max(2) as f32;
    let points: Vec<egui::Pos2> = ms
        .iter()
        .enumerate()
        .map(|(i, v)| {
            egui::pos2(
                rect.left() + rect.width() * i as f32 / (n - 1.0),
                rect.bottom() - rect.height() * v / max,
            )
        })
        .collect();
    painter.add(egui::Shape::line(points, egui::Stroke::new(1.5, egui::Color32::LIGHT_GREEN)));
    painter.text(
        rect.left_top(),
        egui::Align2::LEFT_TOP,
        format!("{max:.0} ms"),
        egui::FontId::monospace(10.0),
        egui::Color32::WHITE,
    );
}

fn pass_table(ui: &mut egui::Ui, stats: &FrameStats) {
    let ms = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:.2}"));
    egui::Grid::new("passes").striped(true).show(ui, |ui| {
        for h in ["pass", "outcome", "CPU ms", "GPU ms"] {
            ui.strong(h);
        }
        ui.end_row();
        for p in &stats.report.passes {
            ui.label(&p.name).on_hover_text(p.reason.to_string());
            ui.label(p.outcome.to_string()).on_hover_text(p.reason.to_string());
            ui.label(ms(p.cpu_ms));
            ui.label(ms(p.gpu_ms));
            ui.end_row();
        }
    });
}
