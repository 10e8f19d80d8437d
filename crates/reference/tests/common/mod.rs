//! Small analytic worlds shared by the tests.
#![allow(dead_code)]

use glam::Vec3;
use reference::{Estimate, Material, World, WorldBuilder};
use std::f32::consts::PI;

/// A closed UV sphere of radius `r` around the origin (shared vertices: watertight), its
/// faces wound outwards.
pub fn sphere(b: &mut WorldBuilder, r: f32, slices: u32, stacks: u32, material: u32) {
    let (p, idx) = sphere_mesh(r, slices, stacks);
    b.triangles(&p, &idx, material);
}

/// The positions and triangles of [`sphere`].
pub fn sphere_mesh(r: f32, slices: u32, stacks: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut p = vec![Vec3::new(0.0, r, 0.0)];
    for i in 1..stacks {
        let th = PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let ph = 2.0 * PI * j as f32 / slices as f32;
            p.push(r * Vec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()));
        }
    }
    p.push(Vec3::new(0.0, -r, 0.0));
    let bottom = p.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + i * slices + j % slices;
    let mut idx = Vec::new();
    for j in 0..slices {
        idx.push([0, ring(0, j + 1), ring(0, j)]);
        idx.push([bottom, ring(stacks - 2, j), ring(stacks - 2, j + 1)]);
    }
    for i in 0..stacks - 2 {
        for j in 0..slices {
            idx.push([ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)]);
            idx.push([ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)]);
        }
    }
    (p, idx)
}

/// The furnace: a closed sphere of a matte material of base colour `a` ([`furnace_brdf`])
/// and emission `e`, emitting from both sides (its faces point outwards; the scene crate's
/// furnace is wound inwards and one-sided). Its radiance is `reference::analytic::
/// SphereFurnace`'s (`e / (1 - a)` for a Lambertian albedo `a`; glTF's matte material
/// reflects a little more at grazing angles, a little less along the normal).
pub fn furnace(a: f32, e: f32) -> World {
    let mut b = World::builder();
    let m = b.material(Material::emissive(Vec3::splat(a), Vec3::splat(e)).two_sided());
    sphere(&mut b, 1.0, 24, 12, m);
    b.build().unwrap()
}

/// The BRDF of [`furnace`]'s wall.
pub fn furnace_brdf(a: f32) -> scene::Brdf {
    Material::diffuse(Vec3::splat(a)).brdf
}

/// A 40 x 40 m ground plane (y = 0, facing up) with the given material.
pub fn ground(b: &mut WorldBuilder, material: u32) {
    b.quad(
        Vec3::new(-20.0, 0.0, 20.0),
        Vec3::new(40.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -40.0),
        material,
    );
}

/// Unit vector at `elevation_deg` above the horizon towards azimuth `azimuth_deg` (from +X
/// towards -Z).
pub fn dir(elevation_deg: f32, azimuth_deg: f32) -> Vec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    Vec3::new(e.cos() * a.cos(), e.sin(), -e.cos() * a.sin())
}

/// Pooled mean of the red channel over a set of estimates, and its standard error.
pub fn pooled(est: &[Estimate]) -> (f64, f64) {
    let n = est.len() as f64;
    let mean = est.iter().map(|e| e.mean.x as f64).sum::<f64>() / n;
    let se = est.iter().map(|e| (e.std_error.x as f64).powi(2)).sum::<f64>().sqrt() / n;
    (mean, se)
}
