//! Tests of the CPU reflection/refraction tracer (`traced_effects::trace`): analytic shading of a
//! sunlit plane, shadows, sky, mirrors, glass, alpha testing, invalid rays, empty scenes and
//! seeded random rays in a generated scene.

use glam::{Vec2, Vec3};
use scene::{AlphaMask, Generated, Material, MaterialId, MeshData, Scene, Texture};
use std::f32::consts::PI;
use traced_effects::trace::{Sun, TraceLighting, TraceRay, TraceScene, TraceSettings, trace_rays};

const E: Vec3 = Vec3::new(1.0, 0.9, 0.8);

fn mesh(positions: Vec<Vec3>, faces: &[[u32; 4]], material: MaterialId) -> scene::Mesh {
    let uvs = (0..positions.len()).map(|i| Vec2::new((i & 1) as f32, ((i >> 1) & 1) as f32));
    let indices = faces.iter().flat_map(|&[a, b, c, d]| [a, b, c, a, c, d]).collect();
    let data = MeshData { positions, normals: None, uvs: Some(uvs.collect()), indices };
    scene::Mesh::build("m", data, material).unwrap().0
}

/// A quad `corner + [0, 1] u + [0, 1] v` facing `u x v`.
fn quad(corner: Vec3, u: Vec3, v: Vec3, material: MaterialId) -> scene::Mesh {
    mesh(vec![corner, corner + u, corner + u + v, corner + v], &[[0, 1, 2, 3]], material)
}

fn cube(lo: Vec3, hi: Vec3, material: MaterialId) -> scene::Mesh {
    let p = (0..8u32)
        .map(|i| Vec3::select(glam::BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), hi, lo));
    let faces =
        [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]];
    mesh(p.collect(), &faces, material)
}

/// A 10 x 10 m floor at y = 0 (albedo 0.5) lit by a sun from `sun`.
fn floor_scene() -> Scene {
    let mut s = Scene::new("floor");
    let m = s.add_material(Material::diffuse("floor", Vec3::splat(0.5)));
    s.meshes.push(quad(Vec3::new(-5.0, 0.0, -5.0), Vec3::Z * 10.0, Vec3::X * 10.0, m));
    s
}

/// Radiance of a sunlit material of base colour `c` (dielectric, roughness 1, as
/// `Material::diffuse`) on the floor seen along the ray direction `d`, lit by `e` from `l`:
/// the BRDF (`scene::Brdf`) times the irradiance.
fn lit(c: f32, d: Vec3, l: Vec3, e: Vec3) -> Vec3 {
    scene::Brdf::new(Vec3::splat(c), 0.0, 1.0).eval(Vec3::Y, -d.normalize(), l) * e * l.y
}

fn sky(d: Vec3) -> Vec3 {
    Vec3::new(0.1, 0.2, 0.3) + d.abs() * 0.1
}

fn trace(s: &Scene, sun: Vec3, ambient: Vec3, rays: &[TraceRay], st: TraceSettings) -> Vec<Vec3> {
    let ts = TraceScene::new(s).unwrap();
    let amb = move |_: Vec3, _: Vec3| ambient;
    let lighting = TraceLighting {
        sun: Some(Sun::new(sun.normalize(), E)),
        point_lights: &[],
        sky: &sky,
        ambient: &amb,
        reflectors: &[],
    };
    trace_rays(&ts, &lighting, rays, &st)
}

fn ray(origin: Vec3, target: Vec3) -> TraceRay {
    TraceRay { origin, dir: target - origin }
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-3
}

const D1: TraceSettings = TraceSettings { max_depth: 1, alpha_test: true };
const D2: TraceSettings = TraceSettings { max_depth: 2, alpha_test: true };

#[test]
fn sunlit_plane_shadow_and_sky() {
    let sun = Vec3::new(1.0, 1.0, 0.3).normalize();
    let p = Vec3::new(0.3, 0.0, -0.2);
    let rays = [
        ray(p + Vec3::new(-1.0, 2.0, 0.5), p),
        TraceRay { origin: p + Vec3::Y, dir: Vec3::new(0.2, 1.0, 0.1) },
    ];
    let lit = lit(0.5, rays[0].dir, sun, E);
    let out = trace(&floor_scene(), sun, Vec3::ZERO, &rays, D1);
    assert!(close(out[0], lit), "{} vs {lit}", out[0]);
    assert!((out[1] - sky(rays[1].dir.normalize())).abs().max_element() < 1e-6);
    // A box between the point and the sun: only the ambient term remains.
    let mut s = floor_scene();
    s.meshes.push(cube(p + sun * 2.0 - 0.5, p + sun * 2.0 + 0.5, MaterialId(0)));
    let ambient = Vec3::new(0.2, 0.3, 0.4);
    let out = trace(&s, sun, ambient, &rays[..1], D1);
    assert!(close(out[0], 0.5 / PI * ambient), "{}", out[0]);
}

#[test]
fn mirror_reflects_the_lit_floor_only_with_recursion() {
    let mut s = floor_scene();
    let mirror = s.add_material(Material::mirror("mirror", 0.8));
    // At x = 2 facing -x; the ray hits it at y = 0.5 and reflects onto the floor at x = 0.
    s.meshes.push(quad(Vec3::new(2.0, 0.0, -3.0), Vec3::Z * 6.0, Vec3::Y * 3.0, mirror));
    let sun = Vec3::new(-1.0, 2.0, 0.5).normalize();
    let r = [ray(Vec3::Y, Vec3::new(2.0, 0.5, 0.0))];
    let reflected = Vec3::new(-2.0, -0.5, 0.0);
    let floor = lit(0.5, reflected, sun, E);
    // The smooth metal's Schlick weight at the ray's incidence.
    let w = scene::brdf::fresnel_schlick(Vec3::splat(0.8), r[0].dir.normalize().x).x;
    let d2 = trace(&s, sun, Vec3::ZERO, &r, D2)[0];
    assert!(close(d2, w * floor), "{d2} vs {}", w * floor);
    let d1 = trace(&s, sun, Vec3::ZERO, &r, D1)[0];
    assert!(d1.max_element() < 1e-6, "{d1}");
}

#[test]
fn glass_splits_with_schlick_and_passes_sunlight() {
    let mut s = floor_scene();
    // All transmitting (the share 1 - t would add a smooth dielectric's mirror).
    let glass = s.add_material(Material::glass("glass", 1.0, 1.5));
    s.meshes.push(quad(Vec3::new(2.0, 0.0, -3.0), Vec3::Z * 6.0, Vec3::Y * 3.0, glass));
    // The sun behind the pane (no highlight on it, no shadow of it on the floor beyond).
    let sun = Vec3::new(1.0, 2.0, 0.5).normalize();
    let dir = Vec3::new(1.0, -0.25, 0.0).normalize();
    let origin = Vec3::new(0.0, 0.6, 0.0);
    let got = trace(&s, sun, Vec3::ONE, &[TraceRay { origin, dir }], D2)[0];
    // The refracted ray reaches the sunlit floor behind the pane; the reflected one the floor
    // in front of it, where the sun arrives through the pane: `0.9 (1 - F)` of it, Fresnel
    // at the sun's incidence on the pane (its normal is x).
    let schlick = |cos: f32| 0.04 + 0.96 * (1.0 - cos).powi(5);
    let f = schlick(dir.x);
    let through = 1.0 - schlick(sun.x);
    let (reflected, refracted) = (dir.reflect(Vec3::X), dir.refract(-Vec3::X, 1.0 / 1.5));
    // The unit ambient irradiance reflected by the floor's directional albedo, diffuse and
    // (roughness 1) specular, seen along `d`.
    let ambient = |d: Vec3| {
        let b = scene::Brdf::new(Vec3::splat(0.5), 0.0, 1.0);
        let nv = -d.normalize().y;
        (b.diffuse_albedo(nv) + b.specular_albedo(nv)) / PI
    };
    let want = f * (lit(0.5, reflected, sun, E * through) + ambient(reflected))
        + (1.0 - f) * (lit(0.5, refracted, sun, E) + ambient(refracted));
    assert!(close(got, want), "{got} vs {want}");
    // Two panes in a row pass the product; an opaque wall behind them blocks all of it.
    s.meshes.push(quad(Vec3::new(1.8, 0.0, -3.0), Vec3::Z * 6.0, Vec3::Y * 3.0, glass));
    let two =
        trace(&s, sun, Vec3::ZERO, &[ray(Vec3::new(1.5, 1.0, 0.0), Vec3::new(1.6, 0.0, 0.0))], D1)
            [0];
    let down = Vec3::new(0.1, -1.0, 0.0);
    let want = lit(0.5, down, sun, E * through * through);
    assert!(close(two, want), "{two} vs {want}");
    s.meshes.push(quad(Vec3::new(1.9, 0.0, -3.0), Vec3::Z * 6.0, Vec3::Y * 3.0, MaterialId(0)));
    let none =
        trace(&s, sun, Vec3::ZERO, &[ray(Vec3::new(1.5, 1.0, 0.0), Vec3::new(1.6, 0.0, 0.0))], D1)
            [0];
    assert!(none.max_element() < 1e-6, "{none}");
}

#[test]
fn alpha_tested_holes_are_skipped() {
    let mut s = floor_scene();
    let tex = s.add_texture(Texture::solid("hole", glam::Vec4::new(1.0, 1.0, 1.0, 0.0)).unwrap());
    let leaf = s.add_material(Material {
        alpha_mask: Some(AlphaMask { texture: tex, cutoff: 0.5 }),
        albedo_texture: Some(tex),
        ..Material::diffuse("leaf", Vec3::splat(0.8))
    });
    s.meshes.push(quad(Vec3::new(-2.0, 1.0, -2.0), Vec3::Z * 4.0, Vec3::X * 4.0, leaf));
    let sun = Vec3::new(0.3, 1.0, 0.2).normalize();
    let r = [ray(Vec3::new(0.0, 3.0, 0.5), Vec3::ZERO)];
    let through = trace(&s, sun, Vec3::ZERO, &r, D1)[0];
    assert!(close(through, lit(0.5, r[0].dir, sun, E)), "{through}");
    let st = TraceSettings { alpha_test: false, ..D1 };
    let card = trace(&s, sun, Vec3::ZERO, &r, st)[0];
    assert!(close(card, lit(0.8, r[0].dir, sun, E)), "{card}");
}

#[test]
fn invalid_rays_are_black_and_empty_scenes_show_the_sky() {
    let bad = [Vec3::ZERO, Vec3::NAN, Vec3::new(f32::INFINITY, 0.0, 1.0)];
    let mut rays: Vec<TraceRay> =
        bad.iter().map(|&dir| TraceRay { origin: Vec3::Y, dir }).collect();
    rays.push(TraceRay { origin: Vec3::NAN, dir: -Vec3::Y });
    for out in trace(&floor_scene(), Vec3::Y, Vec3::ONE, &rays, D2) {
        assert_eq!(out, Vec3::ZERO);
    }
    let empty = Scene::new("empty");
    assert_eq!(TraceScene::new(&empty).unwrap().triangle_count(), 0);
    let d = Vec3::new(0.3, -0.8, 0.1);
    let out = trace(&empty, Vec3::Y, Vec3::ONE, &[TraceRay { origin: Vec3::ZERO, dir: d }], D2);
    assert!((out[0] - sky(d.normalize())).abs().max_element() < 1e-6);
    // Huge and tiny directions still normalise.
    let out =
        trace(&empty, Vec3::Y, Vec3::ONE, &[TraceRay { origin: Vec3::ZERO, dir: d * 1e30 }], D1);
    assert!((out[0] - sky(d.normalize())).abs().max_element() < 1e-6);
}

/// Seeded random rays in the Cornell window scene, with a mirror wall and glass boxes added:
/// always finite, non-negative and the same on every run.
#[test]
fn random_rays_in_a_generated_scene_are_finite() {
    let mut s = Generated::CornellWindow.build(1);
    let mirror = s.add_material(Material::mirror("mirror", 0.9));
    let glass = s.add_material(Material::glass("glass", 0.9, 1.5));
    for (i, m) in s.meshes.iter_mut().enumerate() {
        m.material = [m.material, mirror, glass][i % 3];
    }
    s.point_lights.push(scene::PointLight::new(
        "lamp",
        Vec3::new(2.0, 4.0, -2.0),
        Vec3::splat(5.0),
        6.0,
    ));
    let ts = TraceScene::new(&s).unwrap();
    assert_eq!(ts.triangle_count(), s.triangle_count());
    let sun = s.sun.map(|sun| sun.light().unwrap());
    let amb = |_: Vec3, n: Vec3| n.abs() * 0.1;
    let lighting = TraceLighting {
        sun,
        point_lights: &s.point_lights,
        sky: &sky,
        ambient: &amb,
        reflectors: &[],
    };
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let rays: Vec<TraceRay> = (0..3000)
        .map(|_| TraceRay {
            origin: Vec3::new(next() * 7.0 - 0.75, next() * 7.0 - 0.75, -next() * 7.0 + 0.75),
            dir: Vec3::new(next(), next(), next()) * 2.0 - 1.0,
        })
        .collect();
    for depth in [1, 2, 4] {
        let st = TraceSettings { max_depth: depth, alpha_test: true };
        let a = trace_rays(&ts, &lighting, &rays, &st);
        assert!(a.iter().all(|v| v.is_finite() && v.min_element() >= 0.0));
        assert!(a.iter().any(|v| v.max_element() > 0.0));
        assert_eq!(a, trace_rays(&ts, &lighting, &rays, &st));
    }
}

/// The sun mirrored by a mirror wall (`TraceLighting::reflectors`) lights a traced hit on the
/// floor in front of it as a second sun from the mirrored direction, times the mirror's
/// reflectance; with the mirror shaded by a roof (shadow ray from the mirror to the sun), or
/// the hit beyond the mirrored rays' footprint, it adds nothing.
#[test]
fn a_mirror_wall_mirrors_the_sun_onto_traced_hits() {
    let sun = Vec3::new(0.6, 0.8, 0.0);
    let scene = |roof: bool| {
        let mut s = floor_scene();
        // A smooth white metal: reflectance 1.
        let m = s.add_material(Material::mirror("mirror", 1.0));
        s.meshes.push(quad(Vec3::new(0.0, 0.0, 4.0), -Vec3::Z * 8.0, Vec3::Y * 4.0, m));
        if roof {
            let w = s.add_material(Material::diffuse("roof", Vec3::ONE));
            s.meshes.push(quad(Vec3::new(-1.0, 6.0, -5.0), Vec3::X * 6.0, Vec3::Z * 10.0, w));
        }
        s
    };
    let radiance = |s: &Scene, x: f32, mirrored: bool| {
        let ts = TraceScene::new(s).unwrap();
        let reflectors = traced_effects::mirrored_sun::planar_reflectors(s);
        assert_eq!(reflectors.len(), 1);
        let no_ambient = |_: Vec3, _: Vec3| Vec3::ZERO;
        let lighting = TraceLighting {
            sun: Some(Sun::new(sun, E)),
            point_lights: &[],
            sky: &sky,
            ambient: &no_ambient,
            reflectors: if mirrored { &reflectors } else { &[] },
        };
        let r = [ray(Vec3::new(x, 5.0, 0.5), Vec3::new(x, 0.0, 0.5))];
        trace_rays(&ts, &lighting, &r, &TraceSettings::default())[0]
    };
    let open = scene(false);
    for x in [1.0, 2.0, 2.7] {
        let added = radiance(&open, x, true) - radiance(&open, x, false);
        // The floor's BRDF, lit from the mirrored direction (cosine 0.8), reflectance 1.
        let mirrored = Vec3::new(-0.6, 0.8, 0.0);
        let want = lit(0.5, -Vec3::Y, mirrored, E);
        assert!(close(added, want), "x = {x}: {added} vs {want}");
    }
    assert_eq!(radiance(&open, 3.6, true), radiance(&open, 3.6, false), "beyond the footprint");
    let roofed = scene(true);
    let sunlit = radiance(&roofed, 2.0, false);
    let want = lit(0.5, -Vec3::Y, sun, E);
    assert!(close(sunlit, want), "the floor stays sunlit: {sunlit} vs {want}");
    assert_eq!(radiance(&roofed, 2.0, true), sunlit, "the mirror is in the roof's shadow");
}

/// A traced hit is shaded with the normal map in the mesh's tangent frame: a floor whose
/// constant map leans 45 degrees along +U (+x) faces a sun 45 degrees up towards +x, so it
/// is lit as if facing the sun (the BRDF at the mapped normal, `n.l = 1`); unmapped it would
/// be lit at `n.l = 0.71`.
#[test]
fn traced_hits_apply_the_normal_map() {
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let mut scene = Scene::new("mapped floor");
    let stored = ((Vec3::new(s, 0.0, s) + Vec3::ONE) * 0.5).extend(1.0);
    let map = scene.add_texture(Texture::from_linear("lean", 1, 1, vec![stored]).unwrap());
    let m = scene.add_material(Material {
        normal_texture: Some(map),
        ..Material::diffuse("floor", Vec3::splat(0.5))
    });
    // u along +x, v along +z (down the image: the map's +Y is -z).
    let positions = [(-5.0, -5.0), (5.0, -5.0), (5.0, 5.0), (-5.0, 5.0)]
        .map(|(x, z)| Vec3::new(x, 0.0, z))
        .to_vec();
    let uvs = positions.iter().map(|p| Vec2::new(p.x + 5.0, p.z + 5.0) / 10.0).collect();
    let data =
        MeshData { positions, normals: None, uvs: Some(uvs), indices: vec![0, 2, 1, 0, 3, 2] };
    scene.meshes.push(scene::Mesh::build("floor", data, m).unwrap().0);
    let sun = Vec3::new(1.0, 1.0, 0.0).normalize();
    let d = Vec3::new(0.1, -1.0, 0.2);
    let got = trace(&scene, sun, Vec3::ZERO, &[TraceRay { origin: -d * 3.0, dir: d }], D1)[0];
    let mapped = Vec3::new(s, s, 0.0);
    let brdf = scene::Brdf::new(Vec3::splat(0.5), 0.0, 1.0);
    let want = brdf.eval(mapped, -d.normalize(), sun) * E * mapped.dot(sun);
    assert!((got - want).abs().max_element() < 1e-3 * want.max_element(), "{got} vs {want}");
    let flat = lit(0.5, d, sun, E);
    assert!(got.x > 1.3 * flat.x, "the map turns the floor to the sun: {got} vs flat {flat}");
}
