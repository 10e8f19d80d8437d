//! Alpha-tested materials in the G-buffer: a green cut-out quad whose mask is clear on its
//! left half stands in front of a red wall. Through the clear half the G-buffer holds the
//! wall, through the opaque half the quad; the opaque draws (their own pipeline, without
//! `discard`) go first and the cut-out is depth-tested against them.

mod common;

use engine::{Channel, Preset, Settings, View};
use glam::{Vec2, Vec3};
use scene::{AlphaMask, Camera, ColorSpace, Material, Mesh, MeshData, Scene, Texture};

const W: u32 = 160;
const H: u32 = 90;

/// 8x8 texels, green; alpha 0 in the four left columns, 1 in the four right ones.
fn mask() -> Texture {
    let bytes: Vec<u8> =
        (0..64).flat_map(|i| [0, 255, 0, if i % 8 < 4 { 0 } else { 255 }]).collect();
    Texture::from_rgba8("mask", 8, 8, &bytes, ColorSpace::Srgb).expect("a valid texture")
}

fn scene() -> Scene {
    let mut s = Scene::new("cut-out");
    let wall = s.add_material(Material::diffuse("wall", Vec3::new(0.8, 0.0, 0.0)));
    let t = s.add_texture(mask());
    let leaf = s.add_material(Material {
        albedo_texture: Some(t),
        alpha_mask: Some(AlphaMask { texture: t, cutoff: 0.5 }),
        ..Material::diffuse("leaf", Vec3::ONE)
    });
    s.meshes.push(common::quad(Vec3::new(-6.0, -3.0, -6.0), Vec3::X * 12.0, Vec3::Y * 8.0, wall));
    // The quad x -2..2, y -1..3 at z -2, u along x.
    let data = MeshData {
        positions: vec![
            Vec3::new(-2.0, -1.0, -2.0),
            Vec3::new(2.0, -1.0, -2.0),
            Vec3::new(2.0, 3.0, -2.0),
            Vec3::new(-2.0, 3.0, -2.0),
        ],
        normals: None,
        uvs: Some(vec![Vec2::Y, Vec2::ONE, Vec2::X, Vec2::ZERO]),
        indices: vec![0, 1, 2, 0, 2, 3],
    };
    s.meshes.push(Mesh::build("leaf", data, leaf).expect("a valid quad").0);
    s.camera =
        Camera::look_at(Vec3::new(0.0, 1.0, 3.0), Vec3::new(0.0, 1.0, -6.0), 60.0, 16.0 / 9.0);
    s.fit_volumes();
    s
}

#[test]
fn cut_outs_show_what_is_behind_their_clear_texels() {
    let settings = Settings::preset(Preset::Low, W, H);
    let Some(mut r) = common::renderer(scene(), settings) else { return };
    r.set_view(View::Channel(Channel::BaseColor));
    let f = r.render_frame().expect("albedo view");
    let at = |x: u32, y: u32| Vec3::from_slice(&f.hdr.pixels[(y * W + x) as usize][..3]);
    // The quad spans x -2..2 at 5 m from the eye: about a third of the view's width.
    for y in [35, 45, 55] {
        let (left, right) = (at(W / 2 - 12, y), at(W / 2 + 12, y));
        assert!(left.x > 0.5 && left.y < 0.1, "row {y}: the wall through the clear half: {left}");
        assert!(right.y > 0.5 && right.x < 0.1, "row {y}: the quad's opaque half: {right}");
    }
}
