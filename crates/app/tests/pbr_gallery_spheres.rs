//! Issue 53's per-sphere target on the material gallery: every sphere of `pbr_gallery` (three
//! materials from smooth to rough) reflects the sun as the reference does, its region's
//! luminance ratio within 0.9-1.1 in the direct-sun and point/spot components at the default
//! preset. Measured: the ten spheres the reference resolves to 3% at 16 spp read 1.001-1.026
//! in direct sun; the smooth and middling metals' sun term (no diffuse lobe, small) is within
//! the reference's noise there. The
//! view is the gallery's camera narrowed onto the spheres, so that each covers enough pixels
//! at a test's size (at the ledger's 320x180 from the full view each is under 0.5% of the
//! frame). The spot light's cone falls on the floor beside them; of the spheres only the
//! nearest catches a little of it, and the point-light component is checked the same way.

mod common;

use engine::Component;
use glam::{Vec3, Vec4, Vec4Swizzles};
use scene::{Generated, PBR_GALLERY_ROUGHNESS, PBR_GALLERY_ROWS, PBR_GALLERY_SPHERE_RADIUS};

const SIZE: (u32, u32) = (128, 72);
/// Reference samples per pixel: each sphere's mean to well under 1% here.
const SPP: u32 = 16;

fn luminance(p: Vec3) -> f64 {
    (0.2126 * p.x + 0.7152 * p.y + 0.0722 * p.z) as f64
}

/// The gallery's camera turned to the spheres' centre and narrowed until they fill the view.
fn spheres_camera(scene: &scene::Scene) -> scene::Camera {
    let (rows, cols) = (PBR_GALLERY_ROWS.len(), PBR_GALLERY_ROUGHNESS.len());
    let centres: Vec<Vec3> = (0..rows)
        .flat_map(|r| (0..cols).map(move |c| scene::pbr_gallery_sphere_center(r, c)))
        .collect();
    let middle = centres.iter().sum::<Vec3>() / centres.len() as f32;
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    let eye = scene.camera.position;
    let forward = (middle - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    // The tangent of the half field of view that holds every sphere, with a tenth to spare.
    let half = centres
        .iter()
        .map(|&c| {
            let d = c - eye;
            let (x, y, z) = (d.dot(right), d.dot(up), d.dot(forward));
            let r = PBR_GALLERY_SPHERE_RADIUS / z;
            ((x.abs() / z + r) / aspect).max(y.abs() / z + r)
        })
        .fold(0.0f32, f32::max);
    let fov = 2.0 * (1.1 * half).atan().to_degrees();
    scene::Camera::look_at(scene.camera.position, middle, fov, aspect)
}

#[test]
fn every_sphere_reflects_the_sun_as_the_reference_does() {
    let scene = Generated::PbrGallery.build(1);
    let camera = spheres_camera(&scene);
    let regions =
        app::regions::mesh_region_map(&scene, &camera, SIZE.0, SIZE.1).expect("region map");
    let settings = engine::Settings::preset(engine::Preset::Default, SIZE.0, SIZE.1);
    let Some(mut r) = common::renderer(scene.clone(), settings) else { return };
    r.set_camera(camera).expect("camera");
    let mut engine_image = |c: Component| {
        r.set_component(Some(c));
        r.settle().expect("settle");
        r.read_frame().expect("read back").0.pixels
    };
    let sun = engine_image(Component::SunDirect);
    let points = engine_image(Component::PointLights);
    let truth = |c| {
        app::compare::reference_component(&scene, &camera, SIZE, SPP, c, false).expect("reference")
    };
    let (sun_ref, points_ref) = (truth(Component::SunDirect), truth(Component::PointLights));
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for (name, ..) in PBR_GALLERY_ROWS {
        for roughness in PBR_GALLERY_ROUGHNESS {
            let label = format!("{name}_roughness_{roughness:.2}");
            let id = regions.id(&label).unwrap_or_else(|| panic!("{label} in view"));
            let px: Vec<usize> = regions.pixels(id).collect();
            assert!(px.len() >= 40, "{label}: {} pixels", px.len());
            let n = px.len() as f64;
            for (component, engine, truth) in
                [("sun", &sun, &sun_ref), ("point/spot", &points, &points_ref)]
            {
                let e =
                    px.iter().map(|&i| luminance(Vec4::from_array(engine[i]).xyz())).sum::<f64>()
                        / n;
                let r = px.iter().map(|&i| luminance(truth.mean.pixels[i])).sum::<f64>() / n;
                let se = px
                    .iter()
                    .map(|&i| luminance(truth.std_error.pixels[i]).powi(2))
                    .sum::<f64>()
                    .sqrt()
                    / n;
                report.push(format!(
                    "{label} {component}: engine {e:.3e} reference {r:.3e} +- {se:.1e}"
                ));
                // The band (0.9-1.1 of the truth), widened by the reference's own noise
                // (4 standard errors): on the smooth metals, whose sun term has no diffuse
                // lobe and is small, the noise decides; a sphere lit 15% off fails elsewhere.
                if (e - r).abs() > 0.1 * r + 4.0 * se {
                    failures.push(format!("{label} {component}: {:.3}", e / r));
                }
            }
        }
    }
    eprintln!("per sphere, mean luminance:\n  {}", report.join("\n  "));
    assert!(failures.is_empty(), "outside 0.9-1.1: {failures:?}\nall: {report:?}");
}
