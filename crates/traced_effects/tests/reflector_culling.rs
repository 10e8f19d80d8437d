//! The view's reflectors (`ReflectorSet::in_view`, `Reflector::may_light`) leave out only
//! reflectors that light no point of the view: for random suns and cameras over the city,
//! points that a reflector lights (sampled in the prism its rectangle sweeps along the
//! mirrored light) and that the camera sees inside the scene's bounds always belong to a
//! reflector the view keeps.

use glam::{Vec3, Vec4Swizzles};
use proptest::prelude::*;
use traced_effects::mirrored_sun::{Reflector, ReflectorSet, planar_reflectors};

fn city() -> (scene::Scene, Vec<Reflector>) {
    let s = scene::Generated::City.build(1);
    let r = planar_reflectors(&s);
    (s, r)
}

/// Inside the camera's clip volume (projected, not through the frustum's planes).
fn seen(cam: &scene::Camera, p: Vec3) -> bool {
    let c = cam.view_projection() * p.extend(1.0);
    let ndc = c.xyz() / c.w;
    c.w > 0.0 && ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0 && (0.0..=1.0).contains(&ndc.z)
}

fn unit(v: Vec3) -> Vec3 {
    v.try_normalize().unwrap_or(Vec3::Y)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn reflectors_left_out_light_nothing_in_view(
        sun in (-1.0f32..1.0, -0.1f32..1.0, -1.0f32..1.0),
        eye in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0),
        look in (-1.0f32..1.0, -0.5f32..0.5, -1.0f32..1.0),
        fov in 20.0f32..100.0,
        samples in prop::collection::vec((-1.0f32..1.0, -1.0f32..1.0, 0.0f32..1.0), 400),
    ) {
        let (scene, reflectors) = city();
        let b = scene.bounds();
        let l = unit(Vec3::new(sun.0, sun.1, sun.2));
        let eye = b.min + (b.max - b.min) * Vec3::new(eye.0, eye.1, eye.2);
        let cam = scene::Camera::look_at(eye, eye + unit(Vec3::new(look.0, look.1, look.2)), fov, 16.0 / 9.0);
        let kept = ReflectorSet::in_view(&reflectors, l, &b, &cam.frustum());
        let kept = &kept.items[..kept.count[0] as usize];
        let reach = (b.max - b.min).length();
        for r in &reflectors {
            let (c, u) = (Vec3::from_slice(&r.center[..3]), Vec3::from_slice(&r.axis_u[..3]));
            let mut n = Vec3::from_slice(&r.normal[..3]);
            let v = n.cross(u);
            if l.dot(n) < 0.0 && r.axis_u[3] > 0.5 {
                n = -n;
            }
            // A point lit through `at` sees the mirrored sun along `lm`, towards `at`.
            let lm = l - 2.0 * l.dot(n) * n;
            for &(a, w, s) in &samples {
                let at = c + u * (a * r.center[3]) + v * (w * r.normal[3]);
                let p = at - lm * (s * reach);
                if !(b.contains(p) && seen(&cam, p)) || r.mirror(p, l).is_none() {
                    continue;
                }
                prop_assert!(kept.contains(r), "a reflector lighting {p} in view was left out");
            }
        }
    }
}

/// The city's own view keeps the reflectors that light it and leaves some out.
#[test]
fn the_city_view_leaves_out_reflectors_behind_it() {
    let (scene, reflectors) = city();
    let l = scene.sun.as_ref().expect("a sun").direction().expect("a direction");
    let set = ReflectorSet::in_view(&reflectors, l, &scene.bounds(), &scene.camera.frustum());
    let kept = set.count[0] as usize;
    assert!(kept > 0 && kept < reflectors.len(), "{kept} of {}", reflectors.len());
}
