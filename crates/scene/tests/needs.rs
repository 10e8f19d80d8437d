//! SceneNeeds on the hard cases (no meshes, no lights, a sun below the horizon, things out of
//! view) and the change summary between two scene states.

use glam::Vec3;
use scene::{Camera, Generated, Material, PointLight, Scene, SceneChange, SceneNeeds, Sun};

#[test]
fn empty_scene_needs_nothing_and_says_why() {
    let s = Scene::new("empty");
    s.validate().unwrap();
    let n = s.needs();
    for (name, need) in n.iter() {
        assert!(!need.needed, "{name}: {}", need.reason);
        assert!(!need.reason.is_empty());
    }
    assert_eq!(n.sun_lighting.reason, "no sun in the scene");
    assert_eq!(n.reflections.reason, "no mirror materials");
    assert_eq!(n.point_light_shadows.reason, "no points lights".replace("points", "point"));
    assert!(s.triangles().indices.is_empty());
}

#[test]
fn sun_without_meshes_and_sun_below_the_horizon() {
    let mut s = Scene::new("s");
    s.sun = Some(Sun::from_direction(Vec3::new(0.0, 1.0, 1.0)));
    s.sky = true;
    let n = s.needs();
    assert!(!n.sun_lighting.needed && n.sun_lighting.reason.contains("no geometry"));
    assert!(n.sky_lighting.needed, "the sky is still visible: {}", n.sky_lighting.reason);

    let mut p = scene::plane_box(0);
    p.sun = Some(Sun::from_direction(Vec3::new(0.0, -0.05, 1.0)));
    let n = p.needs();
    assert!(
        !n.sun_lighting.needed && n.sun_lighting.reason.contains("below the horizon"),
        "{}",
        n.sun_lighting.reason
    );
    assert!(!n.sun_shadows.needed && !n.indirect.needed);
    assert!(n.sky_lighting.needed, "twilight: {}", n.sky_lighting.reason);
    p.sun = Some(Sun::from_direction(Vec3::new(0.0, -0.5, 1.0)));
    let n = p.needs();
    assert!(
        !n.sky_lighting.needed && n.sky_lighting.reason.contains("night"),
        "{}",
        n.sky_lighting.reason
    );
    // A night in Lisbon from a date: the same.
    p.sun = Some(Sun::at_time(scene::CivilDate::new(2024, 12, 21), 2.0, 38.72, -9.14));
    assert!(!p.needs().sun_lighting.needed);
    // An impossible date is a reason, not a panic.
    p.sun = Some(Sun::at_time(scene::CivilDate::new(2024, 2, 30), 2.0, 38.72, -9.14));
    let n = p.needs();
    assert!(!n.sun_lighting.needed && n.sun_lighting.reason.contains("unusable"));
    assert!(matches!(
        p.validate(),
        Err(scene::SceneError::Solar(atmosphere::AtmosphereError::InvalidDate { day: 30, .. }))
    ));
}

#[test]
fn ray_tracing_needs_count_mirrors_and_their_visibility() {
    let mut c = scene::city(1);
    let n = c.needs();
    assert!(n.reflections.needed && n.refractions.needed);
    assert!(
        n.reflections.reason.starts_with("ray tracing reflections: 3 mirror materials"),
        "{}",
        n.reflections.reason
    );
    // Look at the sky: nothing visible, nothing to trace.
    c.camera = Camera::look_at(Vec3::new(0.0, 100.0, 0.0), Vec3::new(0.0, 200.0, 0.0), 40.0, 1.0);
    let n = c.needs();
    assert!(
        !n.reflections.needed && n.reflections.reason.contains("0 visible"),
        "{}",
        n.reflections.reason
    );
    assert!(!n.refractions.needed && !n.sun_shadows.needed);
    assert!(n.sun_lighting.needed, "the sun still lights the scene (and the LPV)");
    assert!(!n.ray_tracing());
    // The camera in SceneNeeds::of overrides the scene's camera.
    let n2 = SceneNeeds::of(&c, &scene::city(1).camera);
    assert!(n2.reflections.needed);
}

#[test]
fn plain_scenes_need_no_ray_tracing_and_point_light_shadows_need_a_caster_in_range() {
    let mut p = scene::plane_box(0);
    let n = p.needs();
    assert!(
        n.sun_lighting.needed && n.sun_shadows.needed && n.indirect.needed && n.sky_lighting.needed
    );
    assert!(!n.reflections.needed && !n.refractions.needed && !n.point_light_shadows.needed);
    p.point_lights.push(PointLight::new("far", Vec3::new(500.0, 1.0, 0.0), Vec3::ONE, 3.0));
    assert!(!p.needs().point_light_shadows.needed);
    p.point_lights.push(PointLight::new("near", Vec3::new(0.0, 2.0, 0.0), Vec3::ONE, 3.0));
    let n = p.needs();
    assert!(n.point_light_shadows.needed, "{}", n.point_light_shadows.reason);
    assert!(n.point_light_shadows.reason.contains("2 shadow-casting point lights, 1 reach"));
    // A glass box in view turns refraction on.
    let m = p.add_material(Material::glass("g", 0.9, 1.5));
    p.meshes[1].material = m;
    assert!(p.needs().refractions.needed);
}

#[test]
fn furnace_and_indoor_scenes() {
    let f = Generated::Furnace.build(0);
    let n = f.needs();
    assert!(!n.sun_lighting.needed && !n.sky_lighting.needed && !n.indirect.needed);
    let c = Generated::CornellWindow.build(0).needs();
    assert!(c.sun_lighting.needed && c.indirect.needed && !c.reflections.needed);
}

#[test]
fn change_summary_reports_sun_geometry_lights_and_nothing() {
    let mut s = scene::plane_box(0);
    let a = s.state();
    assert!(SceneChange::between(&a, &s.state()).is_empty());
    assert_eq!(SceneChange::between(&a, &s.state()).to_string(), "no change");

    // Rotate the sun by exactly 10 degrees about the vertical.
    let d = s.sun.unwrap().direction().unwrap();
    let elev = d.y.asin();
    let horiz = Vec3::new(d.x, 0.0, d.z).normalize();
    let rotated = glam::Quat::from_rotation_y(10f32.to_radians()) * horiz;
    s.sun = Some(Sun::from_direction(rotated * elev.cos() + Vec3::Y * elev.sin()));
    let ch = SceneChange::between(&a, &s.state());
    // The angle between the directions: 2 asin(cos(e) sin(5 deg)).
    let expect = 2.0 * (elev.cos() * 5f32.to_radians().sin()).asin().to_degrees();
    assert!((ch.sun_moved_deg - expect).abs() < 1e-3, "{} vs {expect}", ch.sun_moved_deg);
    assert!(ch.sun_invalidates(1.0) && !ch.sun_invalidates(20.0));
    assert!(!ch.geometry_changed() && !ch.lights_changed);
    assert!(ch.to_string().starts_with("sun moved by"));

    let b = s.state();
    s.meshes[1].transform.translation.x += 1.0;
    s.meshes[2].positions[0].y += 0.1;
    s.point_lights.push(PointLight::new("l", Vec3::Y, Vec3::ONE, 2.0));
    let ch = SceneChange::between(&b, &s.state());
    assert_eq!(ch.meshes_moved, vec![1]);
    assert_eq!(ch.meshes_edited, vec![2]);
    assert!(ch.geometry_changed() && ch.lights_changed && ch.sun_moved_deg == 0.0);
    assert!(!ch.sky_volume_invalidated(1.0));
    let lines = ch.lines();
    assert!(lines.contains(&"geometry moved: 1 meshes".to_owned()), "{lines:?}");
    assert!(lines.contains(&"point lights changed".to_owned()));

    let c = s.state();
    s.sun = None;
    s.occlusion_quads.clear();
    s.materials[0].base_color = Vec3::splat(0.1);
    let ch = SceneChange::between(&c, &s.state());
    assert!(ch.sun_toggled && ch.materials_changed && ch.sky_volume_invalidated(90.0));
}

#[test]
fn flattened_triangles_are_world_space_with_mesh_ids() {
    let mut s = scene::plane_box(0);
    s.meshes[1].transform = glam::Affine3A::from_translation(Vec3::new(0.0, 10.0, 0.0));
    let t = s.triangles();
    assert_eq!(t.indices.len(), s.triangle_count());
    assert_eq!(t.mesh_ids.len(), t.indices.len());
    assert!(t.indices.iter().flatten().all(|&i| (i as usize) < t.positions.len()));
    let moved: Vec<_> = (0..t.indices.len()).filter(|&k| t.mesh_ids[k] == 1).collect();
    assert!(!moved.is_empty());
    assert!(moved.iter().all(|&k| t.triangle(k).iter().all(|p| p.y >= 9.99)));
    assert_eq!(t.positions_array().len(), t.positions.len());
}

#[test]
fn flattened_normals_uvs_and_materials_follow_each_mesh() {
    // A unit quad in y = 0 (normal +y, uvs at its corners), scaled unevenly and turned 90
    // degrees about z: its world normal is -x, unit length whatever the scale.
    let data = scene::MeshData {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z],
        normals: Some(vec![Vec3::Y; 4]),
        uvs: Some(vec![glam::Vec2::ZERO, glam::Vec2::X, glam::Vec2::ONE, glam::Vec2::Y]),
        indices: vec![0, 2, 1, 0, 3, 2],
    };
    let mut s = scene::Scene::new("t");
    s.add_material(scene::Material::default());
    s.add_material(scene::Material::default());
    let (mut quad, _) = scene::Mesh::build("quad", data, scene::MaterialId(1)).unwrap();
    quad.transform = glam::Affine3A::from_scale_rotation_translation(
        Vec3::new(3.0, 0.5, 2.0),
        glam::Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
        Vec3::new(0.0, 5.0, 0.0),
    );
    let bare = scene::MeshData {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Z],
        indices: vec![0, 1, 2],
        ..Default::default()
    };
    let (bare, _) = scene::Mesh::build("bare", bare, scene::MaterialId(0)).unwrap();
    s.meshes = vec![quad, bare];
    let t = s.triangles();
    assert_eq!(t.materials, vec![1, 1, 0]);
    assert_eq!((t.normals.len(), t.uvs.len()), (t.positions.len(), t.positions.len()));
    for k in 0..2 {
        let [a, b, c] = t.triangle(k);
        let face = (b - a).cross(c - a).normalize();
        for n in t.corner_normals(k) {
            assert!((n.length() - 1.0).abs() < 1e-6 && n.dot(face).abs() > 0.9999, "{n} {face}");
            assert!((n - Vec3::NEG_X).length() < 1e-6, "{n}");
        }
    }
    assert_eq!(t.corner_uvs(0), [glam::Vec2::ZERO, glam::Vec2::ONE, glam::Vec2::X]);
    assert_eq!(t.corner_uvs(1)[1], glam::Vec2::Y);
    // A mesh loaded without normals has its face normals, and zero uvs.
    assert_eq!(t.corner_normals(2), [Vec3::NEG_Y; 3]);
    assert_eq!(t.corner_uvs(2), [glam::Vec2::ZERO; 3]);
}
