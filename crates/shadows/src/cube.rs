//! Cube shadow maps for point lights (thesis 4.2): the six face matrices in the cube-map
//! face order and orientation of Vulkan/D3D/wgpu (`+X, -X, +Y, -Y, +Z, -Z`), so a depth
//! cube rendered with them is sampled correctly by a direction.

use crate::error::{ShadowError, finite3, positive};
use glam::{Mat4, Vec3, Vec4};

/// Per face: the major axis, and the world axes that map to the face's `s` (right) and `t`
/// (down) texture directions (the cube-map selection table of the Vulkan specification).
pub const CUBE_FACES: [(Vec3, Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::NEG_Z, Vec3::NEG_Y),
    (Vec3::NEG_X, Vec3::Z, Vec3::NEG_Y),
    (Vec3::Y, Vec3::X, Vec3::Z),
    (Vec3::NEG_Y, Vec3::X, Vec3::NEG_Z),
    (Vec3::Z, Vec3::X, Vec3::NEG_Y),
    (Vec3::NEG_Z, Vec3::NEG_X, Vec3::NEG_Y),
];

/// The six world-to-clip matrices of a point light's cube shadow map: 90 degree perspective
/// with reversed-nothing depth in `[0, 1]` (0 at `near`), x right along the face's `s`, y up
/// against its `t`. The view part is a reflection for some faces (cube maps are left-handed),
/// so render with culling off or with the front face flipped.
pub fn cube_face_view_proj(light_pos: Vec3, near: f32, far: f32) -> Result<[Mat4; 6], ShadowError> {
    finite3(light_pos, "light position")?;
    positive(near, "near")?;
    if !(far.is_finite() && far > near) {
        return Err(ShadowError::InvalidParameter {
            name: "far",
            reason: format!("must be finite and > near ({near}), got {far}"),
        });
    }
    // 90 degree right-handed perspective, depth 0 at `near` and 1 at `far` (wgpu).
    let (a, b) = (far / (near - far), near * far / (near - far));
    let proj = Mat4::from_cols(
        Vec4::new(1.0, 0.0, 0.0, 0.0),
        Vec4::new(0.0, 1.0, 0.0, 0.0),
        Vec4::new(0.0, 0.0, a, -1.0),
        Vec4::new(0.0, 0.0, b, 0.0),
    );
    Ok(CUBE_FACES.map(|(f, s, t)| {
        // View rows: x = s, y = -t, z = -f (looking down -z).
        let rows = [s, -t, -f];
        let view = Mat4::from_cols(
            Vec4::new(rows[0].x, rows[1].x, rows[2].x, 0.0),
            Vec4::new(rows[0].y, rows[1].y, rows[2].y, 0.0),
            Vec4::new(rows[0].z, rows[1].z, rows[2].z, 0.0),
            Vec4::new(
                -rows[0].dot(light_pos),
                -rows[1].dot(light_pos),
                -rows[2].dot(light_pos),
                1.0,
            ),
        );
        proj * view
    }))
}

/// The face a direction from the light falls on (largest absolute component; ties go to x,
/// then y, as the specification's selection does).
pub fn cube_face_of(dir: Vec3) -> usize {
    let a = dir.abs();
    if a.x >= a.y && a.x >= a.z {
        if dir.x >= 0.0 { 0 } else { 1 }
    } else if a.y >= a.z {
        if dir.y >= 0.0 { 2 } else { 3 }
    } else if dir.z >= 0.0 {
        4
    } else {
        5
    }
}

/// The depth a cube map rendered with [`cube_face_view_proj`] stores for a point at offset
/// `d` from the light (`[0, 1]`, 0 at `near`): the face's perspective depth of the major-axis
/// distance, `far (m - near) / ((far - near) m)`. `cube_shadow_depth` in
/// `shaders/shadows/cube.inc.wgsl` is its twin; a depth cube array sampled with a comparison
/// against it gives the light's visibility.
pub fn cube_shadow_depth(d: Vec3, near: f32, far: f32) -> f32 {
    let m = d.abs().max_element();
    far * (m - near) / ((far - near) * m)
}
