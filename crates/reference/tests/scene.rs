//! The adapter from `scene::Scene`: generated scenes render, the furnace matches its
//! radiance equation.

use glam::Vec3;
use reference::{
    Component, QuerySettings, RenderSettings, SceneLighting, camera_from_scene, radiance, render,
    world_from_scene,
};

#[test]
fn scene_furnace_converges_to_its_analytic_radiance() {
    let s = scene::Generated::Furnace.build(3);
    let world = world_from_scene(&s, &SceneLighting::low()).unwrap();
    world.validate().unwrap();
    let rays: Vec<(Vec3, Vec3)> = (0..32)
        .map(|i| {
            (Vec3::new(0.1, -0.2, 0.05), Vec3::new((i as f32).cos(), (i as f32 * 0.37).sin(), 0.5))
        })
        .collect();
    let est = radiance(
        &world,
        Component::Full,
        &rays,
        &QuerySettings { samples: 128, ..QuerySettings::DEFAULT },
    )
    .unwrap();
    let n = est.len() as f64;
    let mean = est.iter().map(|e| e.mean.x as f64).sum::<f64>() / n;
    let se = est.iter().map(|e| (e.std_error.x as f64).powi(2)).sum::<f64>().sqrt() / n;
    // Near the centre every ray meets the wall along its normal: the sphere's radiance
    // equation for the wall's BRDF (`E / (1 - a)` were it Lambertian).
    let brdf = world.material(0).brdf;
    let furnace = reference::analytic::SphereFurnace::new(&brdf);
    let e = Vec3::splat(scene::FURNACE_EMISSION);
    let want = furnace.centre(e, QuerySettings::DEFAULT.path.max_bounces).x as f64;
    eprintln!("scene furnace: {mean} +- {se} vs {want} ({brdf:?})");
    assert!((mean - want).abs() < 3.0 * se, "{mean} +- {se} vs {want}");
}

#[test]
fn generated_scenes_render_finite_non_negative_images() {
    for g in scene::Generated::ALL {
        let s = g.build(1);
        let world = world_from_scene(&s, &SceneLighting::low()).unwrap();
        let settings = RenderSettings { width: 16, height: 9, spp: 1, ..RenderSettings::low() };
        let r = render(&world, camera_from_scene(&s), settings).unwrap();
        let img = r.mean();
        assert!(img.pixels.iter().all(|p| p.is_finite() && p.min_element() >= 0.0), "{}", g.name());
        match g {
            // The camera stands in the closed east room: any light there is a leak.
            scene::Generated::TwoRooms => {
                assert_eq!(img.mean(), Vec3::ZERO, "light leaked into the closed room")
            }
            scene::Generated::Furnace => {}
            _ => assert!(img.mean().max_element() > 0.0, "{} is black", g.name()),
        }
    }
}

#[test]
fn cornell_area_light_sampling_is_unbiased_and_far_less_noisy() {
    let s = scene::Generated::CornellArea.build(1);
    let world = world_from_scene(&s, &SceneLighting::low()).unwrap();
    assert_eq!(world.emitter_count(), 2);
    let cam = camera_from_scene(&s);
    let settings = RenderSettings {
        width: 16,
        height: 16,
        spp: 32,
        path: reference::PathSettings::new(6, 2),
        seed: 3,
        ..RenderSettings::DEFAULT
    };
    let new = render(&world, cam, settings).unwrap();
    let old_settings =
        RenderSettings { path: settings.path.with_emitter_sampling(false), ..settings };
    let old = render(&world, cam, old_settings).unwrap();
    let pooled = |r: &reference::Renderer| {
        let e = r.estimates();
        let n = e.len() as f64;
        let m = e.iter().map(|e| e.mean.y as f64).sum::<f64>() / n;
        let se = e.iter().map(|e| (e.std_error.y as f64).powi(2)).sum::<f64>().sqrt() / n;
        (m, se)
    };
    let ((a, sa), (b, sb)) = (pooled(&new), pooled(&old));
    assert!((a - b).abs() < 4.0 * (sa * sa + sb * sb).sqrt(), "{a} +- {sa} vs {b} +- {sb}");
    // Variance per sample (equal sample counts): light sampling at least 10x lower.
    let ratio = (old.mean_rel_std_error() / new.mean_rel_std_error()).powi(2);
    assert!(ratio > 10.0, "variance ratio {ratio}");
}

/// Vertex normals shade: a triangle whose corners lean its normals is hit with the
/// interpolated normal (on the geometric side), a triangle without them with its geometric
/// normal, and the generated city's statue (a smooth torus knot wound inwards: its vertex
/// normals are turned to the wound side) carries its own.
#[test]
fn hits_carry_interpolated_shading_normals() {
    let mut b = reference::World::builder();
    let m = b.material(reference::Material::diffuse(Vec3::splat(0.5)));
    let p = [Vec3::ZERO, Vec3::X, Vec3::Z];
    let lean = [Vec3::new(1.0, 1.0, 0.0), Vec3::new(-1.0, 1.0, 0.0), Vec3::Y];
    b.smooth_triangles(&p, &lean, &[[0, 2, 1]], m);
    b.triangles(&p.map(|v| v + Vec3::X * 3.0), &[[0, 2, 1]], m);
    let w = b.build().unwrap();
    let down = Vec3::NEG_Y;
    let h = w.intersect(Vec3::new(0.25, 1.0, 0.25), down, 10.0).unwrap();
    assert!((h.normal - Vec3::Y).length() < 1e-6, "geometric {}", h.normal);
    // Barycentrics (0.25, 0.25) along the corners as indexed (0, 2, 1).
    let want =
        (lean[0].normalize() * 0.5 + lean[2] * 0.25 + lean[1].normalize() * 0.25).normalize();
    assert!((h.shading_normal - want).length() < 1e-4, "{} vs {want}", h.shading_normal);
    let flat = w.intersect(Vec3::new(3.25, 1.0, 0.25), down, 10.0).unwrap();
    assert_eq!(flat.shading_normal, flat.normal);

    let scene = scene::Generated::City.build(1);
    let world = reference::world_from_scene(&scene, &reference::SceneLighting::DEFAULT).unwrap();
    let statue = scene.meshes.iter().find(|m| m.name == "statue").expect("the city has a statue");
    let c = statue.transform.transform_point3(statue.positions[0]);
    let n = statue.normal_matrix() * statue.normals[0];
    let h = world.intersect(c + n * 0.05, -n, 1.0).expect("the statue is hit along its normal");
    assert!(h.shading_normal.dot(h.normal) > 0.0);
    assert!(h.shading_normal != h.normal, "the statue is shaded smooth: {h:?}");
}

/// The reference applies a scene's normal map in the mesh's tangent frame: a floor whose
/// constant map leans 45 degrees along +U (+x) under a sun 45 degrees up towards +x reflects
/// the sun as a floor facing it (the BRDF at the mapped normal, `n.l = 1`, within the sun
/// disk's sampling noise, four standard errors); unmapped it would reflect `n.l = 0.71` of
/// that.
#[test]
fn normal_maps_turn_the_surface_the_reference_shades() {
    use glam::Vec2;
    use scene::{Material, MeshData, Texture};
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let mut sc = scene::Scene::new("mapped floor");
    let stored = ((Vec3::new(s, 0.0, s) + Vec3::ONE) * 0.5).extend(1.0);
    let map = sc.add_texture(Texture::from_linear("lean", 1, 1, vec![stored]).unwrap());
    let m = sc.add_material(Material {
        normal_texture: Some(map),
        ..Material::diffuse("floor", Vec3::splat(0.5))
    });
    let positions = [(-5.0, -5.0), (5.0, -5.0), (5.0, 5.0), (-5.0, 5.0)]
        .map(|(x, z)| Vec3::new(x, 0.0, z))
        .to_vec();
    let uvs = positions.iter().map(|p| Vec2::new(p.x + 5.0, p.z + 5.0) / 10.0).collect();
    let data =
        MeshData { positions, normals: None, uvs: Some(uvs), indices: vec![0, 2, 1, 0, 3, 2] };
    sc.meshes.push(scene::Mesh::build("floor", data, m).unwrap().0);
    let sun = Vec3::new(1.0, 1.0, 0.0).normalize();
    sc.sun = Some(scene::Sun::from_direction(sun));
    let world = world_from_scene(&sc, &SceneLighting::low()).unwrap();
    let d = Vec3::new(0.1, -1.0, 0.2).normalize();
    let q = QuerySettings { samples: 256, ..QuerySettings::low() };
    let est = radiance(&world, Component::SunDirect, &[(-d * 3.0, d)], &q).unwrap()[0];
    let mapped = Vec3::new(s, s, 0.0);
    let want = scene::Brdf::new(Vec3::splat(0.5), 0.0, 1.0).eval(mapped, -d, sun) * mapped.dot(sun);
    let (got, se) = (est.mean.x, est.std_error.x.max(1e-4 * want.x));
    assert!((got - want.x).abs() < 4.0 * se, "{got} +- {se} vs {}", want.x);
    assert!(got > 1.3 * s * want.x, "the map turns the floor to the sun: {got}");
}
