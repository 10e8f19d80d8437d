//! Partial renders merge into exactly the statistics of all their samples: renders of
//! different seeds into the sample-count-weighted mean with the standard error of all their
//! batches, renders of different pixels into the whole render, bit for bit; what does not
//! belong together, and files that are not partial renders, are typed errors.

mod common;

use glam::Vec3;
use reference::{
    Camera, Error, Material, Part, Partial, PathSettings, RenderSettings, Renderer, Sun, World,
    render,
};

/// A grey ground and a red box under the sun and a blue sky: noise, edges and shadows.
fn world() -> World {
    let mut b = World::builder();
    let grey = b.material(Material::diffuse(Vec3::splat(0.5)));
    let red = b.material(Material::diffuse(Vec3::new(0.7, 0.2, 0.1)));
    common::ground(&mut b, grey);
    b.quad(Vec3::new(-0.5, 0.0, 0.5), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), red);
    b.quad(Vec3::new(0.5, 0.0, 0.5), Vec3::new(0.0, 0.0, -1.0), Vec3::new(0.0, 1.0, 0.0), red);
    b.quad(Vec3::new(-0.5, 1.0, 0.5), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -1.0), red);
    b.sun(Sun::new(common::dir(35.0, 60.0), Vec3::splat(3.0)));
    b.sky(|d| Vec3::new(0.2, 0.3, 0.5) * d.y.max(0.0));
    b.build().unwrap()
}

fn camera() -> Camera {
    Camera::look_at(Vec3::new(2.0, 1.5, 3.0), Vec3::new(0.0, 0.4, 0.0), 50.0, 1.0)
}

fn settings(spp: u32, seed: u64) -> RenderSettings {
    RenderSettings {
        width: 20,
        height: 12,
        spp,
        path: PathSettings::new(4, 2),
        seed,
        ..RenderSettings::DEFAULT
    }
}

/// The mean and standard error of a pixel from its batches' sample counts and means, the
/// textbook way (two passes): `m = sum n_b m_b / N`,
/// `se^2 = sum n_b (m_b - m)^2 / ((K - 1) N)`.
fn from_batches(batches: &[(u32, Vec3)]) -> (Vec3, Vec3) {
    let n: f64 = batches.iter().map(|b| b.0 as f64).sum();
    let k = batches.len() as f64;
    let mut mean = Vec3::ZERO;
    let mut se = Vec3::ZERO;
    for c in 0..3 {
        let m = batches.iter().map(|b| b.0 as f64 * b.1[c] as f64).sum::<f64>() / n;
        let s = batches.iter().map(|b| b.0 as f64 * (b.1[c] as f64 - m).powi(2)).sum::<f64>();
        mean[c] = m as f32;
        se[c] = (s / ((k - 1.0) * n)).sqrt() as f32;
    }
    (mean, se)
}

#[test]
fn renders_of_two_seeds_merge_into_the_statistics_of_all_their_batches() {
    let world = world();
    // Different sample counts: the merged mean is weighted by them.
    let a = render(&world, camera(), settings(16, 1)).unwrap();
    let b = render(&world, camera(), settings(48, 2)).unwrap();
    let mut merged = a.partial("box");
    merged.merge(&b.partial("box")).unwrap();
    merged.validate().unwrap();
    assert_eq!(merged.parts.len(), 2);
    let mut other_way = b.partial("box");
    other_way.merge(&a.partial("box")).unwrap();
    assert_eq!(merged.estimates(), other_way.estimates(), "merging is symmetric");

    let (ea, eb, em) = (a.estimates(), b.estimates(), merged.estimates());
    let mut checked = 0;
    for y in 0..12 {
        for x in 0..20 {
            let p = (y * 20 + x) as usize;
            assert_eq!(em[p].samples, 64);
            let weighted = (ea[p].mean * 16.0 + eb[p].mean * 48.0) / 64.0;
            let tol = 1e-6 * weighted.abs().max_element() + 1e-9;
            assert!((em[p].mean - weighted).abs().max_element() <= tol, "pixel {p}");
            let mut batches = a.batch_means(x, y);
            batches.extend(b.batch_means(x, y));
            assert_eq!(batches.len(), 16);
            let (mean, se) = from_batches(&batches);
            let tol = 1e-5 * se.max_element() + 1e-6 * mean.abs().max_element() + 1e-9;
            assert!(
                (em[p].std_error - se).abs().max_element() <= tol,
                "pixel {p}: {} vs {se}",
                em[p].std_error
            );
            checked += usize::from(se.max_element() > 0.0);
        }
    }
    assert!(checked > 200, "only {checked} pixels with noise");
}

#[test]
fn renders_of_pixel_shares_merge_into_the_whole_render_bit_for_bit() {
    let world = world();
    let whole = render(&world, camera(), settings(8, 3)).unwrap();
    let mut merged: Option<Partial> = None;
    for range in [0..37, 37..38, 38..200, 200..240] {
        let mut r = Renderer::new(&world, camera(), settings(8, 3))
            .unwrap()
            .with_pixels(range.clone())
            .unwrap();
        r.add_samples(8);
        assert_eq!(r.pixels(), range);
        let part = r.partial("box");
        match &mut merged {
            Some(m) => m.merge(&part).unwrap(),
            None => merged = Some(part),
        }
    }
    let merged = merged.unwrap();
    assert_eq!(merged.pixels, 0..240);
    assert_eq!(merged.stats, whole.partial("box").stats);
    assert_eq!(merged.mean(), whole.mean());
    assert_eq!(merged.std_error(), whole.std_error());
}

#[test]
fn what_does_not_belong_together_does_not_merge() {
    let world = world();
    let a = render(&world, camera(), settings(4, 1)).unwrap().partial("box");
    let same_seed = render(&world, camera(), settings(8, 1)).unwrap().partial("box");
    assert!(matches!(a.clone().merge(&same_seed), Err(Error::Merge(_))));
    let b = render(&world, camera(), settings(4, 2)).unwrap();
    assert!(matches!(a.clone().merge(&b.partial("another view")), Err(Error::Merge(_))));
    let small = RenderSettings { width: 10, ..settings(4, 2) };
    let small = render(&world, camera(), small).unwrap().partial("box");
    assert!(matches!(a.clone().merge(&small), Err(Error::Merge(_))));
    // The same seed on other pixels is fine.
    let mut left =
        Renderer::new(&world, camera(), settings(4, 1)).unwrap().with_pixels(0..100).unwrap();
    left.add_samples(4);
    let mut right =
        Renderer::new(&world, camera(), settings(4, 1)).unwrap().with_pixels(100..240).unwrap();
    right.add_samples(4);
    let mut both = left.partial("box");
    both.merge(&right.partial("box")).unwrap();
    // ... but not once a part of that seed covers them.
    assert!(matches!(both.merge(&a), Err(Error::Merge(_))));
    // Pixel ranges out of the image.
    let r = Renderer::new(&world, camera(), settings(4, 1)).unwrap();
    assert!(matches!(r.with_pixels(200..241), Err(Error::InvalidSettings(_))));
    let r = Renderer::new(&world, camera(), settings(4, 1)).unwrap();
    assert!(matches!(r.with_pixels(5..5), Err(Error::InvalidSettings(_))));
}

#[test]
fn partials_read_back_as_written_and_other_files_are_typed_errors() {
    let world = world();
    let mut r =
        Renderer::new(&world, camera(), settings(4, 7)).unwrap().with_pixels(13..190).unwrap();
    r.add_samples(4);
    let p = r.partial("box | sun | camera");
    assert_eq!(p.parts, vec![Part { seed: 7, pixels: 13..190, spp: 4 }]);
    let bytes = p.to_bytes();
    assert_eq!(Partial::from_bytes(&bytes).unwrap(), p);
    let path = std::env::temp_dir().join(format!("serein-partial-{}.partial", std::process::id()));
    p.write(&path).unwrap();
    assert_eq!(Partial::read(&path).unwrap(), p);
    std::fs::remove_file(&path).unwrap();
    assert!(matches!(Partial::read(&path), Err(Error::Read { .. })));

    let broken = |f: &dyn Fn(&mut Vec<u8>)| {
        let mut b = bytes.clone();
        f(&mut b);
        Partial::from_bytes(&b)
    };
    for (what, result) in [
        ("truncated", broken(&|b| b.truncate(b.len() - 3))),
        ("empty", broken(&|b| b.clear())),
        ("magic", broken(&|b| b[0] ^= 1)),
        ("version", broken(&|b| b[24] = 9)),
        ("trailing bytes", broken(&|b| b.push(0))),
        // The last pixel's last sum: NaN.
        (
            "non-finite",
            broken(&|b| {
                let n = b.len();
                b[n - 8..].copy_from_slice(&f64::NAN.to_le_bytes());
            }),
        ),
    ] {
        assert!(matches!(result, Err(Error::Partial(_))), "{what}: {result:?}");
    }
}
