//! The sun mirrored by a planar reflector (`Settings::mirrored_sun`): a mirror wall facing the
//! sun lights the floor in front of it, where the mirrored sun's rays come down, by its
//! reflectance times the sun's irradiance from the mirrored direction, and nowhere else; a
//! mirror in shadow sends nothing.

mod common;

use engine::components::Component;
use engine::{Preset, Settings};
use glam::{Vec3, Vec4};
use scene::{Camera, Material, MeshData, Scene, Sun};

const W: u32 = 160;
const H: u32 = 90;

/// A rectangle with corners `o`, `o + u`, `o + u + v`, `o + v`, wound to face `u x v`.
fn rectangle(o: Vec3, u: Vec3, v: Vec3, material: scene::MaterialId) -> scene::Mesh {
    let positions = vec![o, o + u, o + u + v, o + v];
    let data = MeshData { positions, normals: None, uvs: None, indices: vec![0, 1, 2, 0, 2, 3] };
    scene::Mesh::build("rectangle", data, material).unwrap().0
}

/// A white floor, and a mirror wall 4 m high at x = 0 facing +x, the sun in the +x half at
/// 53 degrees: the mirrored rays come down along `(0.6, -0.8, 0)` onto the floor between
/// x = 0 and x = 3. With `slab`, a roof 6 m up over x in -1..5 shades the mirror but not
/// that floor (whose sun rays pass it beyond x = 5.5).
fn scene(slab: bool) -> Scene {
    let mut s = Scene::new("mirrored sun");
    let white = s.add_material(Material::diffuse("white", Vec3::ONE));
    // A smooth white metal: reflectance 1.
    let mirror = s.add_material(Material::mirror("mirror", 1.0));
    s.meshes.push(rectangle(Vec3::new(-1.0, 0.0, 4.0), Vec3::X * 12.0, -Vec3::Z * 8.0, white));
    s.meshes.push(rectangle(Vec3::new(0.0, 0.0, 4.0), -Vec3::Z * 8.0, Vec3::Y * 4.0, mirror));
    if slab {
        let o = Vec3::new(-1.0, 6.0, -5.0);
        s.meshes.push(rectangle(o, Vec3::X * 6.0, Vec3::Z * 10.0, white));
    }
    s.sun = Some(Sun::from_direction(Vec3::new(0.6, 0.8, 0.0)));
    s.camera =
        Camera::look_at(Vec3::new(3.0, 4.0, 9.0), Vec3::new(2.5, 0.0, 0.0), 60.0, 16.0 / 9.0);
    s
}

/// The pixel that sees world point `p`.
fn pixel(camera: &Camera, p: Vec3) -> usize {
    let c = camera.view_projection() * Vec4::new(p.x, p.y, p.z, 1.0);
    let (x, y) = (c.x / c.w, c.y / c.w);
    let (px, py) = ((x + 1.0) * 0.5 * W as f32, (1.0 - y) * 0.5 * H as f32);
    py as usize * W as usize + px as usize
}

/// The linear image of `component` (`None`: the full frame) with the setting on or off.
fn frame(slab: bool, mirrored_sun: bool, component: Option<Component>) -> Option<Vec<Vec3>> {
    let settings = Settings { mirrored_sun, ..Settings::preset(Preset::Default, W, H) };
    let mut r = common::renderer(scene(slab), settings)?;
    r.set_component(component);
    let mut f = r.render_frame().expect("frame");
    for _ in 0..r.sky_volume_frames() {
        f = r.render_frame().expect("frame");
    }
    Some(f.hdr.rgb().collect())
}

#[test]
fn a_mirror_wall_lights_the_floor_where_its_reflected_sun_comes_down() {
    let (Some(on), Some(off)) = (frame(false, true, None), frame(false, false, None)) else {
        return;
    };
    let Some(direct) = frame(false, true, Some(Component::SunDirect)) else { return };
    let camera = scene(false).camera;
    let at = |image: &[Vec3], x: f32| image[pixel(&camera, Vec3::new(x, 0.0, 0.5))].y;
    for x in [1.0, 2.0, 2.7] {
        // The floor's own sun: E f cos with cos 0.8; the mirrored sun's: E R f cos with R = 1
        // and the same cosine: as much again (the floor's BRDF, rough, nearly the same for
        // the two mirror-image directions).
        let (with, without, sun) = (at(&on, x), at(&off, x), at(&direct, x));
        let ratio = (with - without) / sun;
        eprintln!("x = {x}: mirrored / direct sun {ratio}");
        assert!(
            (0.95..1.05).contains(&ratio),
            "x = {x}: mirrored / direct sun {ratio} ({with} - {without} vs {sun})"
        );
    }
    for x in [3.6, 6.0] {
        let (with, without) = (at(&on, x), at(&off, x));
        assert!((with - without).abs() <= 1e-3 * without, "x = {x}: {with} vs {without}");
    }
}

#[test]
fn a_mirror_in_shadow_sends_no_sun() {
    let (Some(on), Some(off)) = (frame(true, true, None), frame(true, false, None)) else {
        return;
    };
    let Some(direct) = frame(true, true, Some(Component::SunDirect)) else { return };
    let camera = scene(true).camera;
    let at = |image: &[Vec3], x: f32| image[pixel(&camera, Vec3::new(x, 0.0, 0.5))].y;
    for x in [1.0, 2.0, 2.7] {
        let (with, without, sun) = (at(&on, x), at(&off, x), at(&direct, x));
        assert!(sun > 0.1 * without, "x = {x}: the floor is not sunlit ({sun} of {without})");
        assert!((with - without).abs() <= 1e-3 * without, "x = {x}: {with} vs {without}");
    }
}
