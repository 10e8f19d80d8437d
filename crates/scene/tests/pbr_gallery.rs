//! The `pbr_gallery` generated scene and its glTF twin in `tests/data/pbr_gallery/` (written
//! by `common/write_gltf.rs`): the file loads through `scene::load` as the generator's
//! scene (materials, triangles per material, lights after the photometric conversion, the
//! camera, the normal map on the wall), the gallery is what its documentation says (the
//! roughness x material ramp, a grazing sun, a spot whose cone falls on the floor, an
//! emissive panel, all in view), and its spheres are closed, finite, unit-normalled for any
//! seed. Case counts are sized for CI; `PROPTEST_CASES` raises them.

mod common;

use common::cast;
use common::write_gltf::{GALLERY_DIR, GALLERY_FILE, GALLERY_SEED};
use glam::{Vec3, Vec4Swizzles};
use proptest::prelude::*;
use scene::{Generated, Material, Scene, from_photometric};
use std::collections::HashMap;

fn gallery() -> Scene {
    Generated::PbrGallery.build(GALLERY_SEED)
}

fn loaded() -> Scene {
    let path = std::path::Path::new(GALLERY_DIR).join(GALLERY_FILE);
    scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol * b.abs().max_element().max(1.0)
}

/// Per material: triangles, world-space area and bounds.
fn per_material(s: &Scene) -> Vec<(usize, f32, scene::Aabb)> {
    let mut out = vec![(0, 0.0, scene::Aabb::EMPTY); s.materials.len()];
    for m in &s.meshes {
        let e = &mut out[m.material.index()];
        e.0 += m.triangle_count();
        e.1 += m.world_area();
        e.2 = e.2.union(m.world_bounds());
    }
    out
}

#[test]
fn the_gallery_file_loads_as_the_generated_gallery() {
    let (g, f) = (gallery(), loaded());
    f.validate().unwrap();
    assert!(f.warnings.is_empty(), "{:?}", f.warnings);
    assert_eq!(f.cleanup, g.cleanup);

    // Materials: same order, the same glTF fields.
    assert_eq!(f.materials.len(), g.materials.len());
    for (a, b) in f.materials.iter().zip(&g.materials) {
        let n = &b.name;
        assert_eq!(a.name, *n);
        assert!(close(a.base_color, b.base_color, 1e-6), "{n}: {} {}", a.base_color, b.base_color);
        assert!((a.metallic - b.metallic).abs() < 1e-6, "{n}");
        assert!((a.roughness - b.roughness).abs() < 1e-6, "{n}");
        assert!(close(a.emission, b.emission, 1e-6), "{n}: {} {}", a.emission, b.emission);
        assert_eq!((a.transparency, a.ior, a.alpha_mask), (b.transparency, b.ior, b.alpha_mask));
        assert_eq!(a.double_sided, b.double_sided, "{n}");
        assert_eq!(a.albedo_texture.is_some(), b.albedo_texture.is_some(), "{n}");
        assert_eq!(a.normal_texture.is_some(), b.normal_texture.is_some(), "{n}");
    }

    // The normal map: present, bound to the wall, the same texels (8-bit values both ways).
    let wall = |s: &Scene| s.material(s.material_by_name("wall").expect("a wall")).cloned();
    let (gw, fw) = (wall(&g).unwrap(), wall(&f).unwrap());
    let (gt, ft) = (gw.normal_texture.expect("normal map"), fw.normal_texture.expect("loaded"));
    let (gt, ft) = (&g.textures[gt.index()], &f.textures[ft.index()]);
    assert_eq!(ft.name, gt.name);
    assert_eq!(ft.source_space, scene::ColorSpace::Linear);
    assert_eq!((ft.width(), ft.height()), (gt.width(), gt.height()));
    for (a, b) in ft.levels[0].texels.iter().zip(&gt.levels[0].texels) {
        assert!((*a - *b).abs().max_element() < 1e-6, "{a} vs {b}");
    }
    assert_eq!(f.textures.len(), g.textures.len());
    assert!(f.materials.iter().filter(|m| m.normal_texture.is_some()).count() == 1);

    // Geometry: per material the same triangles, area and bounds.
    for (k, (a, b)) in per_material(&f).iter().zip(per_material(&g)).enumerate() {
        let n = &g.materials[k].name;
        assert_eq!(a.0, b.0, "{n}: triangles");
        assert!((a.1 - b.1).abs() <= 1e-4 * b.1, "{n}: area {} vs {}", a.1, b.1);
        assert!(close(a.2.min, b.2.min, 1e-5) && close(a.2.max, b.2.max, 1e-5), "{n}");
    }
    assert_eq!(f.triangle_count(), g.triangle_count());
    assert_eq!(f.meshes.len(), g.meshes.len());

    // Lights: the spot as the file states it, converted by `from_photometric`, is the
    // generator's.
    let json: serde_json::Value = serde_json::from_slice(
        &std::fs::read(std::path::Path::new(GALLERY_DIR).join(GALLERY_FILE)).unwrap(),
    )
    .unwrap();
    let defs = json["extensions"]["KHR_lights_punctual"]["lights"].as_array().unwrap();
    let number = |v: &serde_json::Value| v.as_f64().unwrap() as f32;
    let rgb = |v: &serde_json::Value| Vec3::new(number(&v[0]), number(&v[1]), number(&v[2]));
    assert_eq!(f.point_lights.len(), g.point_lights.len());
    for (a, b) in f.point_lights.iter().zip(&g.point_lights) {
        let def = defs.iter().find(|d| d["name"] == b.name.as_str()).expect("in the file");
        let stated = from_photometric(rgb(&def["color"]), number(&def["intensity"]));
        assert!(close(a.color, stated, 1e-6), "{}: {} vs {stated}", b.name, a.color);
        assert!(close(a.color, b.color, 1e-5), "{}: {} vs {}", b.name, a.color, b.color);
        assert!(close(a.position, b.position, 1e-6), "{}", b.name);
        assert!((a.radius - b.radius).abs() < 1e-5 && a.casts_shadows == b.casts_shadows);
        let (ca, cb) = (a.spot.expect("a spot"), b.spot.expect("a spot"));
        assert!(close(ca.direction, cb.direction, 1e-5), "{ca:?} vs {cb:?}");
        assert_eq!((ca.inner_angle, ca.outer_angle), (cb.inner_angle, cb.outer_angle));
    }
    let (fs, gs) = (f.sun.expect("the sun"), g.sun.unwrap());
    assert!(close(fs.direction().unwrap(), gs.direction().unwrap(), 1e-5));
    assert!(close(fs.color, gs.color, 1e-5), "{} vs {}", fs.color, gs.color);
    assert_eq!(fs.angular_radius, gs.angular_radius);
    let sun_def = defs.iter().find(|d| d["type"] == "directional").unwrap();
    assert!(close(
        fs.color,
        from_photometric(rgb(&sun_def["color"]), number(&sun_def["intensity"])),
        1e-6
    ));
    // glTF has no sky: the file's scene is lit by its sun alone.
    assert!(g.sky && !f.sky);

    // The camera: the same view and projection.
    let (fc, gc) = (f.camera, g.camera);
    assert!(close(fc.position, gc.position, 1e-6));
    assert!(close(fc.forward, gc.forward, 1e-5), "{} vs {}", fc.forward, gc.forward);
    assert!((fc.fov_y_deg - gc.fov_y_deg).abs() < 1e-4 && (fc.aspect - gc.aspect).abs() < 1e-6);
    assert_eq!((fc.near, fc.far), (gc.near, gc.far));
    let (a, b) = (fc.view_projection(), gc.view_projection());
    assert!(a.abs_diff_eq(b, 1e-4), "{a} vs {b}");

    // The loaded file calls for what the generator's scene does, but the sky.
    let (nf, ng) = (f.needs(), g.needs());
    for ((name, a), (_, b)) in nf.iter().into_iter().zip(ng.iter()) {
        if name != "sky_lighting" {
            assert_eq!(a.needed, b.needed, "{name}: {} / {}", a.reason, b.reason);
        }
    }
}

#[test]
fn the_gallery_is_a_roughness_by_material_ramp_of_metallic_roughness_materials() {
    let g = gallery();
    g.validate().unwrap();
    let tris: HashMap<u32, usize> = g.meshes.iter().fold(HashMap::new(), |mut h, m| {
        *h.entry(m.material.0).or_default() += m.triangle_count();
        h
    });
    for (row, &(name, color, metallic)) in scene::PBR_GALLERY_ROWS.iter().enumerate() {
        for (column, &roughness) in scene::PBR_GALLERY_ROUGHNESS.iter().enumerate() {
            let label = format!("{name}_roughness_{roughness:.2}");
            let id = g.material_by_name(&label).unwrap_or_else(|| panic!("{label}"));
            let m = g.material(id).unwrap();
            // Made by the metallic-roughness constructor: both sets of fields agree.
            assert_eq!(*m, Material::metallic_roughness(&label, color, metallic, roughness));
            // Smooth spheres, metal or plastic, are traced mirrors; rough ones are not.
            let mirror = roughness < scene::TRACED_ROUGHNESS;
            assert_eq!(m.is_mirror(), mirror, "{label}");
            // One sphere each, placed at its centre by its transform.
            let mesh = g.meshes.iter().find(|x| x.material == id).unwrap();
            assert_eq!(tris[&id.0], mesh.triangle_count());
            let c = mesh.world_bounds().center();
            assert!(close(c, scene::pbr_gallery_sphere_center(row, column), 1e-5), "{label}: {c}");
        }
    }
    // Gold and copper are coloured metals: their specular colour is their base colour, red
    // over blue, and they have no diffuse lobe.
    for name in ["gold", "copper"] {
        let m = g.material(g.material_by_name(&format!("{name}_roughness_0.50")).unwrap()).unwrap();
        let f0 = m.brdf().f0();
        assert!(f0.max_element() - f0.min_element() > 0.2 && f0.x > 1.5 * f0.z, "{name}: {f0}");
        assert_eq!(m.diffuse_albedo(), glam::Vec3::ZERO, "{name}");
    }
    assert_eq!(g.materials.len(), 3 + 15);
}

#[test]
fn the_gallery_needs_its_sun_sky_spot_mirrors_and_emission() {
    let g = gallery();
    let n = g.needs();
    for (name, need) in [
        ("sun lighting", &n.sun_lighting),
        ("sun shadows", &n.sun_shadows),
        ("sky lighting", &n.sky_lighting),
        ("indirect", &n.indirect),
        ("reflections", &n.reflections),
        ("point light shadows", &n.point_light_shadows),
    ] {
        assert!(need.needed, "{name}: {}", need.reason);
    }
    assert!(!n.refractions.needed, "{}", n.refractions.reason);
    // The smooth plastic, gold and copper spheres (roughness 0.05).
    assert!(n.reflections.reason.contains("3 mirror materials"), "{}", n.reflections.reason);
    assert!(n.point_light_shadows.reason.contains("1 reach"), "{}", n.point_light_shadows.reason);
    // `SceneNeeds` has no decision for emitters or spot cones: the scene's own counts.
    let stats = g.stats();
    assert_eq!(stats.emissive_materials, 1);
    assert_eq!(stats.point_lights, 1);
    assert!(g.point_lights[0].spot.is_some());
    assert_eq!(g.textures.len(), 1);
}

#[test]
fn the_sun_grazes_the_wall_and_the_spot_cone_falls_on_the_floor() {
    let g = gallery();
    let tris = g.triangles();
    let sun = g.sun.unwrap().direction().unwrap();
    let e = sun.y.asin().to_degrees();
    assert!((e - scene::PBR_GALLERY_SUN_ELEVATION_DEG).abs() < 1e-3, "{e}");
    // The wall faces +Z: the sun's azimuth is 12 degrees round from the wall's plane (east)
    // towards its front, so the light meets the wall 78 degrees from its normal.
    let azimuth = sun.z.atan2(sun.x).to_degrees();
    assert!((azimuth - scene::PBR_GALLERY_SUN_GRAZE_DEG).abs() < 1e-3, "{azimuth}");
    let incidence = sun.z.acos().to_degrees();
    assert!((75.0..80.0).contains(&incidence), "{incidence}");
    let wall = g.meshes.iter().find(|m| m.name == "wall").unwrap();
    assert!(wall.normals.iter().all(|n| close(*n, Vec3::Z, 1e-6)));

    // The spot's axis and its whole outer cone meet the floor (y = 0) in front of the wall,
    // unobstructed, within the spot's radius.
    let spot = &g.point_lights[0];
    let cone = spot.spot.unwrap();
    let hit = cast(&tris, spot.position, cone.direction).expect("the axis hits");
    let p = spot.position + cone.direction * hit;
    assert!(close(p, scene::PBR_GALLERY_SPOT_TARGET, 1e-4), "{p}");
    let side = cone.direction.any_orthonormal_vector();
    for k in 0..16 {
        let phi = k as f32 / 16.0 * std::f32::consts::TAU;
        let around = glam::Quat::from_axis_angle(cone.direction, phi) * side;
        let d = glam::Quat::from_axis_angle(around, cone.outer_angle) * cone.direction;
        assert!((d.angle_between(cone.direction) - cone.outer_angle).abs() < 1e-4);
        let t = cast(&tris, spot.position, d).expect("the cone's edge hits");
        let q = spot.position + d * t;
        assert!(q.y.abs() < 1e-4 && q.z > -2.8 && t < spot.radius, "{k}: {q}");
    }
    // The panel faces the spheres.
    let panel = g.meshes.iter().find(|m| m.name == "panel").unwrap();
    let to_spheres = (Vec3::new(0.0, 0.35, -0.6) - panel.world_bounds().center()).normalize();
    assert!(panel.normals[0].dot(to_spheres) > 0.8, "{}", panel.normals[0]);
    assert!(g.materials[panel.material.index()].emission == scene::PBR_GALLERY_PANEL_EMISSION);
}

#[test]
fn the_camera_frames_spheres_wall_panel_and_the_spot_pool() {
    let g = gallery();
    let vp = g.camera.view_projection();
    let ndc = |p: Vec3| {
        let h = vp * p.extend(1.0);
        h.xyz() / h.w
    };
    let mut points = vec![scene::PBR_GALLERY_SPOT_TARGET];
    for m in &g.meshes {
        let b = m.world_bounds();
        if m.name == "floor" {
            continue; // it runs out of the frame on purpose
        }
        points.extend((0..8).map(|k| {
            Vec3::new(
                if k & 1 == 0 { b.min.x } else { b.max.x },
                if k & 2 == 0 { b.min.y } else { b.max.y },
                if k & 4 == 0 { b.min.z } else { b.max.z },
            )
        }));
    }
    for p in points {
        let q = ndc(p);
        assert!(q.x.abs() <= 1.0 && q.y.abs() <= 1.0 && q.z > 0.0 && q.z < 1.0, "{p} -> {q}");
    }
}

/// Positions welded to a grid of `1e-4`, for finding shared edges across a sphere's seam
/// and poles, where the vertices are repeated.
fn key(p: Vec3) -> [i64; 3] {
    (p * 1e4).round().as_i64vec3().to_array()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: common::cases(4), ..ProptestConfig::default() })]

    /// For any seed: every sphere is closed (each edge, welded across the seam, has exactly
    /// two triangles, in opposite directions), finite, its normals unit and outward, its
    /// vertices on the sphere, its volume a sphere's; the wall's normal map decodes to unit
    /// normals leaning no further than 50 degrees.
    #[test]
    fn every_sphere_is_closed_finite_and_unit_normalled(seed in any::<u64>()) {
        let g = Generated::PbrGallery.build(seed);
        g.validate().unwrap();
        let r = scene::PBR_GALLERY_SPHERE_RADIUS;
        let mut spheres = 0;
        for m in g.meshes.iter().filter(|m| m.name.contains("_roughness_")) {
            spheres += 1;
            let world: Vec<Vec3> =
                m.positions.iter().map(|&p| m.transform.transform_point3(p)).collect();
            let centre = m.world_bounds().center();
            let nm = m.normal_matrix();
            for (p, n) in world.iter().zip(&m.normals) {
                prop_assert!(p.is_finite() && n.is_finite());
                prop_assert!((n.length() - 1.0).abs() < 1e-5);
                prop_assert!(((*p - centre).length() - r).abs() < 1e-5);
                prop_assert!((nm * *n).normalize().dot((*p - centre) / r) > 0.999);
            }
            let mut edges: HashMap<([i64; 3], [i64; 3]), i32> = HashMap::new();
            let mut volume = 0.0f64;
            for t in &m.indices {
                let [a, b, c] = t.map(|i| world[i as usize]);
                volume += f64::from((a - centre).dot((b - centre).cross(c - centre))) / 6.0;
                for (u, v) in [(a, b), (b, c), (c, a)] {
                    *edges.entry((key(u), key(v))).or_default() += 1;
                }
            }
            for (&(u, v), &count) in &edges {
                prop_assert_eq!(count, 1, "edge used twice in one direction");
                prop_assert_eq!(edges.get(&(v, u)).copied(), Some(1), "open edge");
            }
            let exact = 4.0 / 3.0 * std::f64::consts::PI * f64::from(r).powi(3);
            prop_assert!(volume > 0.97 * exact && volume < exact, "{} vs {}", volume, exact);
        }
        prop_assert_eq!(spheres, 15);
        let wall = g.material(g.material_by_name("wall").unwrap()).unwrap();
        let t = &g.textures[wall.normal_texture.unwrap().index()];
        for v in &t.levels[0].texels {
            let n = v.xyz() * 2.0 - Vec3::ONE;
            prop_assert!((n.length() - 1.0).abs() < 0.02, "{}", n);
            prop_assert!(n.z > 50f32.to_radians().cos(), "{}", n);
        }
    }
}
