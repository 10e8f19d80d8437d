//! Ray / sphere geometry in the planet frame: a point is described by its distance `r` from
//! the planet's centre and a direction by `mu`, the cosine of its angle to the local zenith.

use crate::Atmosphere;

/// Distance along a ray from radius `r` with zenith cosine `mu` to the top of the
/// atmosphere (0 when the ray starts above the top and points away).
#[inline]
pub fn distance_to_top(atm: &Atmosphere, r: f32, mu: f32) -> f32 {
    let disc = r * r * (mu * mu - 1.0) + atm.top_radius_km * atm.top_radius_km;
    (-r * mu + disc.max(0.0).sqrt()).max(0.0)
}

/// Distance to the ground sphere, valid when [`ray_hits_ground`] is true.
#[inline]
pub fn distance_to_ground(atm: &Atmosphere, r: f32, mu: f32) -> f32 {
    let disc = r * r * (mu * mu - 1.0) + atm.bottom_radius_km * atm.bottom_radius_km;
    (-r * mu - disc.max(0.0).sqrt()).max(0.0)
}

/// Whether the ray from (`r`, `mu`) hits the ground.
#[inline]
pub fn ray_hits_ground(atm: &Atmosphere, r: f32, mu: f32) -> bool {
    mu < 0.0 && r * r * (mu * mu - 1.0) + atm.bottom_radius_km * atm.bottom_radius_km >= 0.0
}

/// Cosine of the zenith angle of the geometric horizon seen from radius `r` (<= 0).
#[inline]
pub fn horizon_mu(atm: &Atmosphere, r: f32) -> f32 {
    let s = (atm.bottom_radius_km / r).min(1.0);
    -(1.0 - s * s).max(0.0).sqrt()
}

/// Fraction of the sun's disk above the geometric horizon for a sun at zenith cosine `mu_s`
/// seen from radius `r` (Bruneton 2017's smoothstep across the disk's angular size).
#[inline]
pub fn sun_visible_fraction(atm: &Atmosphere, r: f32, mu_s: f32) -> f32 {
    let sin_h = (atm.bottom_radius_km / r).min(1.0);
    let cos_h = -(1.0 - sin_h * sin_h).max(0.0).sqrt();
    let w = sin_h * atm.sun_angular_radius;
    let x = ((mu_s - cos_h + w) / (2.0 * w)).clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// Splits `[t0, t1]` into `n` segments whose ends grow quadratically, `t0 + (t1 - t0) (k/n)^2`
/// (short segments near the start, where the view ray is in the densest air), yielding each
/// segment's midpoint and length.
#[inline]
pub fn quadratic_segments(t0: f32, t1: f32, n: u32) -> impl Iterator<Item = (f32, f32)> {
    let len = t1 - t0;
    (0..n).map(move |i| {
        let (u0, u1) = (i as f32 / n as f32, (i + 1) as f32 / n as f32);
        let (a, b) = (t0 + len * (u0 * u0), t0 + len * (u1 * u1));
        (0.5 * (a + b), b - a)
    })
}

/// The segment of a ray from (`r`, `mu`) that lies inside the atmosphere: `(t_start, t_end)`
/// along the ray, or `None` when the ray misses the atmosphere. The segment stops at the
/// ground when the ray hits it.
#[inline]
pub fn atmosphere_segment(atm: &Atmosphere, r: f32, mu: f32) -> Option<(f32, f32)> {
    let top = atm.top_radius_km;
    let disc_top = r * r * (mu * mu - 1.0) + top * top;
    if r > top {
        // Outside: the ray must point inwards and meet the top sphere.
        if mu >= 0.0 || disc_top < 0.0 {
            return None;
        }
        let sq = disc_top.sqrt();
        let t0 = -r * mu - sq;
        let t1 =
            if ray_hits_ground(atm, r, mu) { distance_to_ground(atm, r, mu) } else { -r * mu + sq };
        return Some((t0.max(0.0), t1));
    }
    let t1 = if ray_hits_ground(atm, r, mu) {
        distance_to_ground(atm, r, mu)
    } else {
        distance_to_top(atm, r, mu)
    };
    Some((0.0, t1))
}

/// Radius and zenith cosine after travelling `t` along the ray from (`r`, `mu`).
#[inline]
pub fn advance(r: f32, mu: f32, t: f32) -> (f32, f32) {
    let r_t = (t * t + 2.0 * r * mu * t + r * r).max(0.0).sqrt();
    let mu_t = if r_t > 0.0 { ((r * mu + t) / r_t).clamp(-1.0, 1.0) } else { mu };
    (r_t, mu_t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertical_distances() {
        let a = Atmosphere::EARTH;
        let r = a.bottom_radius_km + 1.0;
        assert!((distance_to_top(&a, r, 1.0) - 99.0).abs() < 1e-2);
        assert!(ray_hits_ground(&a, r, -1.0));
        assert!((distance_to_ground(&a, r, -1.0) - 1.0).abs() < 1e-2);
        assert!(!ray_hits_ground(&a, r, 0.0));
        let (r2, mu2) = advance(r, 1.0, 10.0);
        assert!((r2 - r - 10.0).abs() < 1e-2 && (mu2 - 1.0).abs() < 1e-6);
    }

    #[test]
    fn segment_from_outside() {
        let a = Atmosphere::EARTH;
        let r = a.bottom_radius_km + 100.0 + 50.0;
        assert!(atmosphere_segment(&a, r, 1.0).is_none());
        let (t0, t1) = atmosphere_segment(&a, r, -1.0).unwrap();
        assert!((t0 - 50.0).abs() < 1e-2 && (t1 - 150.0).abs() < 2e-2, "{t0} {t1}");
    }
}
