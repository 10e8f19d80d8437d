//! Small box scenes and an exact one-bounce VPL gather, so the crate can measure its own
//! error without the `scene` and `reference` crates (tests, the sweep and the example).
//!
//! A [`BoxScene`] is a set of solid axis-aligned boxes (walls, floors, ceilings) around air
//! regions (rooms), and sunlight that enters through openings. Its VPLs are made the way an
//! RSM makes them: a grid of sun rays over the opening, each traced to the first surface it
//! hits, where a VPL with the reflected flux `albedo * E_sun * A_opening * |cos| / N` sits.
//! [`vpl_gather`] is the reference: the exact sum over the same VPLs of
//! `flux / pi * max(0, n_v.w) * max(0, -n.w) / max(r², r_min²)` with visibility by ray-box
//! tests: one bounce of indirect diffuse light from the VPL set, no discretisation. The
//! difference between the LPV and this isolates what the volume does (injection, propagation,
//! leaking); the error of the VPL set itself against a converged renderer is not in it.

use crate::vpl::{Surfel, Vpl};
use glam::Vec3;
use rayon::prelude::*;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// Ray `o + t d` against the box: entry distance and the entry face's outward normal,
    /// for `t` in `(t_min, t_max)`.
    pub fn intersect(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> Option<(f32, Vec3)> {
        let inv = d.recip();
        let t0 = (self.min - o) * inv;
        let t1 = (self.max - o) * inv;
        let near = t0.min(t1);
        let far = t0.max(t1);
        // NaN-safe max/min (0 * inf): treat NaN components as not limiting.
        let tn = near.x.max(near.y).max(near.z);
        let tf = far.x.min(far.y).min(far.z);
        if tn <= tf && tn > t_min && tn < t_max {
            let axis = if tn == near.x {
                0
            } else if tn == near.y {
                1
            } else {
                2
            };
            let mut n = Vec3::ZERO;
            n[axis] = -d[axis].signum();
            Some((tn, n))
        } else {
            None
        }
    }

    /// True when the open segment `(t_min, t_max)` of the ray overlaps the box.
    pub fn overlaps_segment(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> bool {
        let inv = d.recip();
        let t0 = (self.min - o) * inv;
        let t1 = (self.max - o) * inv;
        let tn = t0.min(t1).max_element().max(t_min);
        let tf = t0.max(t1).min_element().min(t_max);
        tn < tf
    }
}

/// Solid boxes, their albedos, the rooms (air) and the sun's VPLs.
#[derive(Clone, Debug, PartialEq)]
pub struct BoxScene {
    pub name: &'static str,
    pub solids: Vec<Aabb>,
    pub albedo: Vec<Vec3>,
    /// Air regions; receivers are taken on the surfaces that face into them.
    pub rooms: Vec<Aabb>,
    /// Index into `rooms` of the room the sun lights (the others are "dark").
    pub lit_room: usize,
    pub vpls: Vec<Vpl>,
}

/// A receiver point: position on a surface, normal into the room, and its room.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Receiver {
    pub position: Vec3,
    pub normal: Vec3,
    pub room: usize,
}

const T: f32 = 0.1; // wall thickness (thinner than the default 0.5 cell: the leaking case)

fn shell(min: Vec3, max: Vec3) -> [Aabb; 6] {
    let (a, b) = (min - T, max + T);
    [
        Aabb::new(Vec3::new(a.x, a.y, a.z), Vec3::new(b.x, min.y, b.z)), // floor
        Aabb::new(Vec3::new(a.x, max.y, a.z), Vec3::new(b.x, b.y, b.z)), // ceiling
        Aabb::new(Vec3::new(a.x, min.y, a.z), Vec3::new(min.x, max.y, b.z)), // -x wall
        Aabb::new(Vec3::new(max.x, min.y, a.z), Vec3::new(b.x, max.y, b.z)), // +x wall
        Aabb::new(Vec3::new(min.x, min.y, a.z), Vec3::new(max.x, max.y, min.z)), // -z wall
        Aabb::new(Vec3::new(min.x, min.y, max.z), Vec3::new(max.x, max.y, b.z)), // +z wall
    ]
}

/// Cuts a rectangular hole (`hole`, a box through the wall) out of wall box `w`: up to 4
/// boxes around it.
fn cut(w: Aabb, hole: Aabb) -> Vec<Aabb> {
    let mut out = Vec::new();
    // Split along the two axes in which the wall is large; keep the thickness axis whole.
    let size = w.max - w.min;
    let thin = if size.x <= size.y && size.x <= size.z {
        0
    } else if size.y <= size.z {
        1
    } else {
        2
    };
    let (u, v) = match thin {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let mut rest = w;
    for (axis, lo) in [(u, true), (u, false), (v, true), (v, false)] {
        let mut piece = rest;
        if lo {
            piece.max[axis] = hole.min[axis];
            rest.min[axis] = hole.min[axis];
        } else {
            piece.min[axis] = hole.max[axis];
            rest.max[axis] = hole.max[axis];
        }
        if piece.max[axis] > piece.min[axis] {
            out.push(piece);
        }
    }
    out
}

impl BoxScene {
    /// A 5 x 3 x 5 m room (red -x wall, green +x wall, white elsewhere) with a 2 x 1.2 m
    /// window in its +z wall; the sun shines in and lights a patch of floor and red wall.
    /// `vpl_side²` sun rays through the window make the VPLs.
    pub fn cornell_window(vpl_side: u32) -> Self {
        let (min, max) = (Vec3::ZERO, Vec3::new(5.0, 3.0, 5.0));
        let walls = shell(min, max);
        let window = Aabb::new(Vec3::new(1.0, 1.2, 4.9), Vec3::new(3.0, 2.4, 5.2));
        let mut solids = Vec::new();
        let mut albedo = Vec::new();
        let white = Vec3::splat(0.75);
        for (i, w) in walls.into_iter().enumerate() {
            let a = match i {
                2 => Vec3::new(0.75, 0.15, 0.1),
                3 => Vec3::new(0.15, 0.7, 0.15),
                _ => white,
            };
            let pieces = if i == 5 { cut(w, window) } else { vec![w] };
            for p in pieces {
                solids.push(p);
                albedo.push(a);
            }
        }
        let sun = Vec3::new(-0.45, -0.55, -1.0).normalize();
        let mut s = Self {
            name: "cornell_window",
            solids,
            albedo,
            rooms: vec![Aabb::new(min, max)],
            lit_room: 0,
            vpls: vec![],
        };
        s.vpls = s.sun_vpls(window, 2, sun, 1.0, vpl_side);
        s
    }

    /// Two 4 x 3 x 4 m rooms side by side along x, separated by a 0.1 m wall (a fifth of
    /// the default finest cell) with a 0.8 x 2.1 m door at its far end; the sun enters the
    /// first room through a 2 x 2 m skylight. The second room is lit only through the door.
    pub fn two_rooms(vpl_side: u32) -> Self {
        let a = Aabb::new(Vec3::ZERO, Vec3::new(4.0, 3.0, 4.0));
        let b = Aabb::new(Vec3::new(4.0 + T, 0.0, 0.0), Vec3::new(8.0 + T, 3.0, 4.0));
        let outer = shell(a.min, b.max);
        let skylight = Aabb::new(Vec3::new(1.0, 2.9, 0.8), Vec3::new(3.0, 3.2, 2.8));
        let mut solids = Vec::new();
        for (i, w) in outer.into_iter().enumerate() {
            if i == 1 { solids.extend(cut(w, skylight)) } else { solids.push(w) }
        }
        let wall = Aabb::new(Vec3::new(4.0, 0.0, 0.0), Vec3::new(4.0 + T, 3.0, 4.0));
        let door = Aabb::new(Vec3::new(3.9, 0.0, 3.0), Vec3::new(4.2, 2.1, 3.8));
        solids.extend(cut(wall, door));
        let albedo = vec![Vec3::splat(0.75); solids.len()];
        let sun = Vec3::new(0.25, -1.0, 0.3).normalize();
        let mut s = Self {
            name: "two_rooms",
            solids,
            albedo,
            rooms: vec![a, b],
            lit_room: 0,
            vpls: vec![],
        };
        s.vpls = s.sun_vpls(skylight, 1, sun, 1.0, vpl_side);
        s
    }

    /// VPLs from a grid of `side²` sun rays (direction `sun`, irradiance `e_sun` normal to
    /// it) through the face of `opening` perpendicular to `axis`.
    fn sun_vpls(&self, opening: Aabb, axis: usize, sun: Vec3, e_sun: f32, side: u32) -> Vec<Vpl> {
        let (u, v) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let size = opening.max - opening.min;
        let area = size[u] * size[v];
        let mut n_open = Vec3::ZERO;
        n_open[axis] = 1.0;
        let flux_per_ray = e_sun * area * sun.dot(n_open).abs() / (side * side) as f32;
        let mut out = Vec::new();
        for j in 0..side {
            for i in 0..side {
                let mut o = Vec3::ZERO;
                o[u] = opening.min[u] + (i as f32 + 0.5) / side as f32 * size[u];
                o[v] = opening.min[v] + (j as f32 + 0.5) / side as f32 * size[v];
                o[axis] = if sun[axis] < 0.0 { opening.max[axis] } else { opening.min[axis] };
                if let Some((t, n, k)) = self.trace(o, sun, 1e-4, 1e3) {
                    out.push(Vpl::new(o + t * sun, n, self.albedo[k] * flux_per_ray));
                }
            }
        }
        out
    }

    /// Closest hit: distance, outward normal of the hit face, box index.
    pub fn trace(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> Option<(f32, Vec3, usize)> {
        let mut best: Option<(f32, Vec3, usize)> = None;
        for (k, b) in self.solids.iter().enumerate() {
            let lim = best.map_or(t_max, |h| h.0);
            if let Some((t, n)) = b.intersect(o, d, t_min, lim) {
                best = Some((t, n, k));
            }
        }
        best
    }

    /// True when nothing solid lies strictly between `a` and `b`.
    pub fn visible(&self, a: Vec3, b: Vec3) -> bool {
        let d = b - a;
        !self.solids.iter().any(|s| s.overlaps_segment(a, d, 1e-4, 1.0 - 1e-4))
    }

    fn room_of(&self, p: Vec3) -> Option<usize> {
        self.rooms.iter().position(|r| r.contains(p))
    }

    fn in_solid(&self, p: Vec3) -> bool {
        self.solids.iter().any(|s| s.contains(p))
    }

    /// Points on every solid face that faces into a room, on a grid of `spacing`.
    pub fn receivers(&self, spacing: f32) -> Vec<Receiver> {
        let mut out = Vec::new();
        self.for_each_face_point(spacing, |p, n, _| {
            if let Some(room) = self.room_of(p + n * 1e-3) {
                out.push(Receiver { position: p, normal: n, room });
            }
        });
        out
    }

    /// Surfels for the geometry volume: every face of every solid (both sides of thin
    /// walls), sampled on a grid of `spacing`, each with its share of the face's area.
    pub fn surfels(&self, spacing: f32) -> Vec<Surfel> {
        let mut out = Vec::new();
        self.for_each_face_point(spacing, |p, n, area| out.push(Surfel::new(p, n, area)));
        out
    }

    fn for_each_face_point(&self, spacing: f32, mut f: impl FnMut(Vec3, Vec3, f32)) {
        for b in &self.solids {
            let size = b.max - b.min;
            for axis in 0..3 {
                let (u, v) = match axis {
                    0 => (1, 2),
                    1 => (0, 2),
                    _ => (0, 1),
                };
                let nu = ((size[u] / spacing).round() as usize).max(1);
                let nv = ((size[v] / spacing).round() as usize).max(1);
                let area = size[u] * size[v] / (nu * nv) as f32;
                for side in [-1.0f32, 1.0] {
                    let mut n = Vec3::ZERO;
                    n[axis] = side;
                    for j in 0..nv {
                        for i in 0..nu {
                            let mut p = Vec3::ZERO;
                            p[axis] = if side < 0.0 { b.min[axis] } else { b.max[axis] };
                            p[u] = b.min[u] + (i as f32 + 0.5) / nu as f32 * size[u];
                            p[v] = b.min[v] + (j as f32 + 0.5) / nv as f32 * size[v];
                            if !self.in_solid(p + n * 1e-3) {
                                f(p, n, area);
                            }
                        }
                    }
                }
            }
        }
    }
}

/// Closest distance at which the reference gather evaluates a VPL (metres): closer, the
/// `1 / r²` of a point light is clamped (the usual VPL singularity clamp).
pub const GATHER_MIN_DISTANCE: f32 = 0.1;

/// The reference: one-bounce irradiance at `p` (normal `n`) from `vpls`, exact sum with
/// visibility against `scene` (see the module doc).
pub fn vpl_gather(scene: &BoxScene, vpls: &[Vpl], p: Vec3, n: Vec3) -> Vec3 {
    let mut e = Vec3::ZERO;
    let from = p + n * 1e-3;
    for v in vpls {
        let Some((nv, flux)) = v.sanitized() else { continue };
        let to = v.position + nv * 1e-3;
        let d = from - to;
        let r2 = d.length_squared();
        if r2 == 0.0 {
            continue;
        }
        let w = d / r2.sqrt();
        let g = nv.dot(w).max(0.0) * (-n.dot(w)).max(0.0);
        if g > 0.0 && scene.visible(to, from) {
            e += flux * (g / (std::f32::consts::PI * r2.max(GATHER_MIN_DISTANCE.powi(2))));
        }
    }
    e
}

/// [`vpl_gather`] at every receiver, in parallel.
pub fn vpl_gather_all(scene: &BoxScene, receivers: &[Receiver]) -> Vec<Vec3> {
    receivers.par_iter().map(|r| vpl_gather(scene, &scene.vpls, r.position, r.normal)).collect()
}
