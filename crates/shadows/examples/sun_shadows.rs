//! Use `shadows` in your renderer: every frame, fit the sun's cascades to the camera, render
//! each cascade's depth map (here with the crate's CPU rasteriser; on a GPU with the `gpu`
//! feature's resident pass), and for each visible point pick its cascade and filter the map
//! with PCSS. Prints the shadow of a table on the ground, seen from above, as text: the
//! penumbra widens away from the table's legs.
//!
//! `cargo run -p serein-shadows --example sun_shadows`

use glam::{DVec3, Vec3};
use shadows::{Camera, CascadedShadowMap, CsmSettings, DepthMap, Pcss, PcssSettings, rasterize};

fn main() -> Result<(), shadows::ShadowError> {
    // The casters: a 2 x 2 m table top 1.5 m up, and a 4 m pole, as world-space triangles.
    let quad = |a: Vec3, b: Vec3, c: Vec3, d: Vec3| [[a, b, c], [a, c, d]];
    let mut casters = Vec::new();
    casters.extend(quad(
        Vec3::new(-1.0, 1.5, -1.0),
        Vec3::new(1.0, 1.5, -1.0),
        Vec3::new(1.0, 1.5, 1.0),
        Vec3::new(-1.0, 1.5, 1.0),
    ));
    // The pole: two crossed 0.4 m wide panels.
    casters.extend(quad(
        Vec3::new(2.3, 0.0, -1.0),
        Vec3::new(2.7, 0.0, -1.0),
        Vec3::new(2.7, 4.0, -1.0),
        Vec3::new(2.3, 4.0, -1.0),
    ));
    casters.extend(quad(
        Vec3::new(2.5, 0.0, -1.2),
        Vec3::new(2.5, 0.0, -0.8),
        Vec3::new(2.5, 4.0, -0.8),
        Vec3::new(2.5, 4.0, -1.2),
    ));

    // The frame: the camera, and the sun's light travelling down and towards +x.
    let camera = Camera::look_to(
        DVec3::new(0.0, 6.0, 10.0),
        Vec3::new(0.0, -0.5, -1.0),
        Vec3::Y,
        1.0,
        1.6,
        0.1,
        200.0,
    )?;
    let to_sun = Vec3::new(-0.5, 1.0, -0.2);
    let settings = CsmSettings { resolution: 512, ..CsmSettings::DEFAULT };
    let csm = CascadedShadowMap::fit(&camera, to_sun, &settings)?;
    csm.validate(&camera)?;
    let pcss_settings = PcssSettings::DEFAULT;
    let mut maps = Vec::new();
    for cascade in &csm.cascades {
        let mut map = DepthMap::new(settings.resolution, settings.resolution)?;
        rasterize(&mut map, None, &cascade.view.view_proj_f64(), &casters)?;
        let pcss = Pcss::directional(&cascade.view, 0.004675, &pcss_settings)?;
        maps.push((map, pcss));
    }

    // The lighting pass, per visible point: its cascade, then PCSS (1 lit, 0 in shadow).
    let shades = b"@%#*+=-:. ";
    for row in 0..20 {
        let z = -3.0 + 0.4 * row as f64;
        let line: String = (0..64)
            .map(|col| {
                let p = DVec3::new(-4.0 + 0.14 * col as f64, 0.0, z);
                let Some(i) = csm.select_by_position(p, 2.0) else { return '?' };
                let (map, pcss) = &maps[i];
                let lit = pcss.pcss(map, &csm.cascades[i].view.receiver(p, Vec3::Y));
                shades[((lit * 9.99) as usize).min(9)] as char
            })
            .collect();
        println!("{line}");
    }
    Ok(())
}
