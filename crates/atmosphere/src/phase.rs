//! Phase functions. Molecules: Rayleigh, `3/(16 pi) (1 + c^2)`. Aerosols: Cornette-Shanks
//! (1992), a Henyey-Greenstein variant with a Rayleigh-like `(1 + c^2)` factor that is exactly
//! normalised: `3/(8 pi) (1 - g^2)(1 + c^2) / ((2 + g^2)(1 + g^2 - 2 g c)^{3/2})`, as used by
//! Bruneton 2017 and Hillaire 2020. Both integrate to 1 over the sphere; `c` is the cosine
//! of the angle between the view direction and the direction towards the sun.

use std::f32::consts::PI;

/// Rayleigh phase function of the cosine `c`.
#[inline]
pub fn rayleigh_phase(c: f32) -> f32 {
    3.0 / (16.0 * PI) * (1.0 + c * c)
}

/// Cornette-Shanks phase function of the cosine `c` with asymmetry `g`.
#[inline]
pub fn cornette_shanks_phase(c: f32, g: f32) -> f32 {
    let g2 = g * g;
    let denom = (1.0 + g2 - 2.0 * g * c).max(1e-12);
    3.0 / (8.0 * PI) * (1.0 - g2) * (1.0 + c * c) / ((2.0 + g2) * denom * denom.sqrt())
}

/// Henyey-Greenstein phase function (for comparison; not used by the sky model).
#[inline]
pub fn henyey_greenstein_phase(c: f32, g: f32) -> f32 {
    let g2 = g * g;
    let denom = (1.0 + g2 - 2.0 * g * c).max(1e-12);
    (1.0 - g2) / (4.0 * PI * denom * denom.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn integrate(f: impl Fn(f32) -> f32) -> f64 {
        // Integral over the sphere = 2 pi * integral over c in [-1, 1].
        let n = 200_000;
        (0..n)
            .map(|i| {
                let c = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
                f(c as f32) as f64
            })
            .sum::<f64>()
            * 2.0
            / n as f64
            * 2.0
            * std::f64::consts::PI
    }

    #[test]
    fn phase_functions_are_normalised() {
        assert!((integrate(rayleigh_phase) - 1.0).abs() < 1e-4);
        for g in [0.0, 0.5, 0.8, -0.3] {
            assert!((integrate(|c| cornette_shanks_phase(c, g)) - 1.0).abs() < 1e-3, "CS {g}");
            assert!((integrate(|c| henyey_greenstein_phase(c, g)) - 1.0).abs() < 1e-3, "HG {g}");
        }
    }
}
