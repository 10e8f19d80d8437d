//! The city from morning to night with one renderer: the sun moves, so the sky map is rebuilt
//! and the sky volume refills over the next frames; the report of each hour's last frame says
//! which passes ran. Writes `target/time_of_day/HHhMM.png`.
//!
//! `cargo run --release -p serein-engine --example time_of_day [-- WIDTHxHEIGHT]`

use engine::{Preset, Renderer, Settings, pass};
use scene::{CivilDate, Sun};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let size = std::env::args().nth(1).unwrap_or_else(|| "480x270".into());
    let (w, h) = size.split_once('x').ok_or("size: expected WIDTHxHEIGHT")?;
    let (w, h): (u32, u32) = (w.parse()?, h.parse()?);
    let out = std::path::Path::new("target/time_of_day");
    std::fs::create_dir_all(out)?;
    let mut r =
        Renderer::new(scene::Generated::City.build(1), Settings::preset(Preset::Default, w, h))?;
    r.set_fixed_frame_time(Some(1.0 / 30.0));
    println!("adapter: {}", r.adapter());
    for local in [8.0, 12.0, 17.5, 20.5, 22.0] {
        // Lisbon, summer time (UTC+1).
        r.set_sun(Some(Sun::at_time(CivilDate::new(2024, 6, 21), local - 1.0, 38.72, -9.14)))?;
        let mut frame = r.render_frame()?;
        let sky_map = frame.report.pass(pass::SKY_MAP).map(|p| p.outcome);
        for _ in 0..r.sky_volume_frames() {
            frame = r.render_frame()?;
        }
        let (hh, mm) = (local as u32, ((local % 1.0) * 60.0).round() as u32);
        let path = out.join(format!("{hh:02}h{mm:02}.png"));
        frame.write_png(&path)?;
        println!(
            "{local:5.2} h: sky map {:?} in the first frame; ray tracing {:?} in the last, {:.0} ms -> {}",
            sky_map,
            frame.report.pass(pass::RAY_TRACING).map(|p| p.outcome),
            frame.wall_ms,
            path.display()
        );
    }
    Ok(())
}
