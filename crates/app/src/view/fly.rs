//! The fly camera: WASD to move along the view, Q/E down and up, mouse to look, Shift to go
//! fast; plain functions of the held keys and the mouse, so the window only feeds them.

use glam::Vec3;

/// Keys held and mouse movement since the last frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlyInput {
    pub forward: bool,
    pub back: bool,
    pub left: bool,
    pub right: bool,
    pub up: bool,
    pub down: bool,
    pub fast: bool,
    /// Mouse movement in pixels (x right, y down) while looking.
    pub look: (f32, f32),
}

/// Position and orientation as yaw (about +Y, 0 looking along -Z) and pitch (radians).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    pub position: Vec3,
    pub yaw: f32,
    pub pitch: f32,
    /// Metres per second (Shift: four times).
    pub speed: f32,
}

/// Radians per pixel of mouse movement.
const LOOK_PER_PIXEL: f32 = 0.003;
/// Pitch stays this far from straight up or down (the up vector stays defined).
const PITCH_LIMIT: f32 = 1.55;

impl FlyCamera {
    /// The fly camera at `camera`'s position, looking where it looks.
    pub fn from_camera(camera: &scene::Camera, speed: f32) -> Self {
        let f = camera.forward.normalize_or(Vec3::NEG_Z);
        Self {
            position: camera.position,
            yaw: (-f.x).atan2(-f.z),
            pitch: f.y.clamp(-1.0, 1.0).asin().clamp(-PITCH_LIMIT, PITCH_LIMIT),
            speed,
        }
    }

    pub fn forward(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(-sy * cp, sp, -cy * cp)
    }

    /// Moves by `dt` seconds of `input`; non-finite or negative `dt` moves nothing.
    pub fn update(&mut self, input: &FlyInput, dt: f32) {
        let dt = if dt.is_finite() { dt.clamp(0.0, 0.5) } else { 0.0 };
        self.yaw -= input.look.0 * LOOK_PER_PIXEL;
        self.pitch = (self.pitch - input.look.1 * LOOK_PER_PIXEL).clamp(-PITCH_LIMIT, PITCH_LIMIT);
        let f = self.forward();
        let right = f.cross(Vec3::Y).normalize_or(Vec3::X);
        let axis = |pos: bool, neg: bool| f32::from(u8::from(pos)) - f32::from(u8::from(neg));
        let dir = f * axis(input.forward, input.back)
            + right * axis(input.right, input.left)
            + Vec3::Y * axis(input.up, input.down);
        let speed = self.speed * if input.fast { 4.0 } else { 1.0 };
        self.position += dir.normalize_or_zero() * speed * dt;
    }

    /// `base` (field of view, planes, aspect) moved to this position and orientation.
    pub fn camera(&self, base: &scene::Camera) -> scene::Camera {
        scene::Camera { position: self.position, forward: self.forward(), up: Vec3::Y, ..*base }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> scene::Camera {
        scene::Camera::look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, 1.0, -2.0), 60.0, 1.5)
    }

    #[test]
    fn round_trips_a_camera() {
        let b = base();
        let c = FlyCamera::from_camera(&b, 5.0).camera(&b);
        assert!(c.forward.distance(b.forward.normalize()) < 1e-5, "{} vs {}", c.forward, b.forward);
        assert_eq!(c.position, b.position);
    }

    #[test]
    fn w_moves_along_the_view_and_shift_is_faster() {
        let mut f = FlyCamera::from_camera(&base(), 2.0);
        let start = f.position;
        f.update(&FlyInput { forward: true, ..Default::default() }, 0.5);
        assert!((f.position - start - f.forward()).length() < 1e-5);
        let mid = f.position;
        f.update(&FlyInput { forward: true, fast: true, ..Default::default() }, 0.5);
        assert!((f.position - mid).length() > 3.9);
    }

    #[test]
    fn looking_turns_and_pitch_is_limited() {
        let mut f = FlyCamera::from_camera(&base(), 1.0);
        let yaw = f.yaw;
        f.update(&FlyInput { look: (100.0, -1e6), ..Default::default() }, 0.0);
        assert!(f.yaw < yaw && f.pitch <= PITCH_LIMIT && f.forward().is_finite());
        f.update(&FlyInput { forward: true, ..Default::default() }, f32::NAN);
        assert!(f.position.is_finite());
    }
}
