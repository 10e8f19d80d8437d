//! The metallic-roughness gallery: a ramp of spheres from smooth to rough in three materials,
//! a normal-mapped wall under a grazing sun, a spot light's pool on the floor and an emissive
//! panel, all in one view.

use super::builder::Parts;
use super::textures::studs;
use crate::{Camera, Material, PointLight, Scene, Sun};
use glam::{Affine3A, Quat, Vec3};

/// The gallery's roughness ramp, left to right (glTF's perceptual roughness).
pub const PBR_GALLERY_ROUGHNESS: [f32; 5] = [0.05, 0.25, 0.5, 0.75, 1.0];

/// The gallery's rows of spheres, front to back: name, base colour (linear RGB) and metallic.
/// Red plastic (a dielectric), gold and copper (metals; the base colours are the measured
/// specular reflectances at normal incidence, as glTF's model wants for a metal).
pub const PBR_GALLERY_ROWS: [(&str, Vec3, f32); 3] = [
    ("plastic", Vec3::new(0.80, 0.10, 0.08), 0.0),
    ("gold", Vec3::new(1.000, 0.766, 0.336), 1.0),
    ("copper", Vec3::new(0.955, 0.638, 0.538), 1.0),
];

/// The spheres' radius, metres.
pub const PBR_GALLERY_SPHERE_RADIUS: f32 = 0.35;

/// The emissive panel's radiance (linear RGB, in the sun's units: a white Lambertian surface
/// facing the sun at the top of the atmosphere has radiance `1 / pi`), a warm white about five
/// times as bright as that.
pub const PBR_GALLERY_PANEL_EMISSION: Vec3 = Vec3::new(1.6, 1.2, 0.7);

/// The sun's elevation (degrees), and its azimuth measured from the wall's plane (east, +X)
/// round towards the wall's front (+Z), degrees: light that meets the wall 78 degrees from
/// its normal, grazing it, so that its studs cast their relief.
pub const PBR_GALLERY_SUN_ELEVATION_DEG: f32 = 10.0;
pub const PBR_GALLERY_SUN_GRAZE_DEG: f32 = 12.0;

/// The spot light: where it hangs, the floor point its axis meets, and its cone (inner and
/// outer angles, degrees).
pub const PBR_GALLERY_SPOT_POSITION: Vec3 = Vec3::new(-4.4, 3.2, 1.5);
pub const PBR_GALLERY_SPOT_TARGET: Vec3 = Vec3::new(-3.8, 0.0, 0.5);
pub const PBR_GALLERY_SPOT_CONE_DEG: (f32, f32) = (16.0, 24.0);

/// The centre of the sphere in `row` (front to back) and `column` (smooth to rough).
pub fn pbr_gallery_sphere_center(row: usize, column: usize) -> Vec3 {
    Vec3::new(-1.8 + 0.9 * column as f32, PBR_GALLERY_SPHERE_RADIUS, 0.6 - 1.2 * row as f32)
}

/// The glTF metallic-roughness gallery, a test of a renderer's BRDF and of its lights:
///
/// - fifteen spheres of radius [`PBR_GALLERY_SPHERE_RADIUS`] resting on a floor, in three rows
///   ([`PBR_GALLERY_ROWS`]: red plastic in front, gold, copper at the back) of five columns
///   from smooth to rough ([`PBR_GALLERY_ROUGHNESS`]), every material made by
///   [`Material::metallic_roughness`] (the smoothest gold and copper, below
///   [`crate::TRACED_ROUGHNESS`], are traced mirrors). Each
///   sphere is one mesh, a unit sphere (40 x 20 segments) placed by its transform;
/// - a 16 x 10 m floor (grey dielectric, roughness 0.6) whose top is the plane y = 0;
/// - behind the spheres a 10 x 3.5 m wall facing +Z (the camera) with a generated
///   tangent-space normal map of round studs, 8 per metre, under the sun
///   [`PBR_GALLERY_SUN_ELEVATION_DEG`] above the eastern horizon, its azimuth only
///   [`PBR_GALLERY_SUN_GRAZE_DEG`] round from the wall's plane: light 78 degrees from the
///   wall's normal, grazing it, where normal maps show most; with the sky;
/// - a spot light hanging left of the spheres, its whole cone falling on the floor where the
///   spheres' long shadows reach (so that its pool of light is not lost in the sun's);
/// - an emissive panel (1.2 x 1.6 m, [`PBR_GALLERY_PANEL_EMISSION`]) standing right of the
///   spheres, turned towards them and the camera;
/// - a camera in front, above, looking down at the spheres, framing all of it.
///
/// The seed draws the studs' heights; nothing else changes. The same scene as a glTF file,
/// with its normal map as a PNG, is in `tests/data/pbr_gallery/`.
pub fn pbr_gallery(seed: u64) -> Scene {
    let mut scene = Scene::new("pbr_gallery");
    let seed32 = (seed ^ (seed >> 32)) as u32;
    let floor =
        scene.add_material(Material::metallic_roughness("floor", Vec3::splat(0.35), 0.0, 0.6));
    // The generated texture always builds: fixed size, finite texels.
    let normal = studs(seed32).ok().map(|t| scene.add_texture(t));
    let wall = scene.add_material(Material {
        normal_texture: normal,
        ..Material::metallic_roughness("wall", Vec3::new(0.70, 0.66, 0.60), 0.0, 0.8)
    });
    let panel = scene.add_material(Material {
        emission: PBR_GALLERY_PANEL_EMISSION,
        ..Material::metallic_roughness("panel", Vec3::splat(0.8), 0.0, 0.9)
    });
    let mut parts = Parts::default();
    let f = parts.get("floor", floor);
    for i in 0..8 {
        for j in 0..5 {
            // 2 m tiles over x in [-8, 8], z in [-2.8, 7.2], facing up.
            let corner = Vec3::new(-8.0 + 2.0 * i as f32, 0.0, -0.8 + 2.0 * j as f32);
            f.quad(corner, Vec3::X * 2.0, -Vec3::Z * 2.0, 1.0);
        }
    }
    parts.get("wall", wall).quad(Vec3::new(-5.0, 0.0, -2.8), Vec3::X * 10.0, Vec3::Y * 3.5, 1.0);
    // The panel faces n (towards the spheres and the camera); card's normal is u x v.
    let n = Vec3::new(-1.0, 0.0, 0.5).normalize();
    parts.get("panel", panel).card(
        Vec3::new(3.2, 1.0, -0.9),
        Vec3::Y.cross(n) * 0.6,
        Vec3::Y * 0.8,
    );
    for (row, &(name, color, metallic)) in PBR_GALLERY_ROWS.iter().enumerate() {
        for (column, &roughness) in PBR_GALLERY_ROUGHNESS.iter().enumerate() {
            let label = format!("{name}_roughness_{roughness:.2}");
            let m = scene.add_material(Material::metallic_roughness(
                label.clone(),
                color,
                metallic,
                roughness,
            ));
            let place = Affine3A::from_scale_rotation_translation(
                Vec3::splat(PBR_GALLERY_SPHERE_RADIUS),
                Quat::IDENTITY,
                pbr_gallery_sphere_center(row, column),
            );
            parts.placed(&label, m, place).sphere(Vec3::ZERO, 1.0, 40, 20, false);
        }
    }
    let (meshes, cleanup) = parts.finish();
    scene.meshes = meshes;
    scene.cleanup = cleanup;

    let (e, g) =
        (PBR_GALLERY_SUN_ELEVATION_DEG.to_radians(), PBR_GALLERY_SUN_GRAZE_DEG.to_radians());
    scene.sun = Some(Sun::from_direction(Vec3::new(e.cos() * g.cos(), e.sin(), e.cos() * g.sin())));
    scene.sky = true;
    let (inner, outer) = PBR_GALLERY_SPOT_CONE_DEG;
    scene.point_lights.push(PointLight::spot(
        "spot",
        PBR_GALLERY_SPOT_POSITION,
        PBR_GALLERY_SPOT_TARGET - PBR_GALLERY_SPOT_POSITION,
        // About 270 000 cd of warm white, a follow spot (the sun's units: 1 is 133 800 cd):
        // its pool, about 0.18 of the sun's irradiance, outshines the low sun on the floor.
        Vec3::new(1.0, 0.86, 0.65) * 2.0,
        8.0,
        inner.to_radians(),
        outer.to_radians(),
    ));
    scene.camera =
        Camera::look_at(Vec3::new(0.0, 3.2, 6.8), Vec3::new(0.0, 0.7, -0.9), 50.0, 16.0 / 9.0);
    scene.fit_volumes();
    scene
}
