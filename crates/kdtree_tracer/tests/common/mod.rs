//! Shared checks: an accelerator against brute force.
#![allow(dead_code)]

use kdtree_tracer::{BruteForce, KdTree, Mesh, Ray, RayQuery, Settings};

/// Proptest case count: env PROPTEST_CASES, default 48.
pub fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(48)
}

pub fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-5 * a.abs().max(b.abs()) + 1e-6
}

/// Closest hit agrees with brute force (same t within 1e-5 relative, same triangle unless the
/// two are tied at that t) and any-hit agrees with "a closest hit exists below t_max".
pub fn agree(
    accel: &impl RayQuery,
    brute: &BruteForce,
    ray: &Ray,
    t_max: f32,
) -> Result<(), String> {
    let ours = accel.intersect(ray, t_max);
    let theirs = brute.intersect(ray, t_max);
    match (ours, theirs) {
        (None, None) => {}
        (Some(a), Some(b)) => {
            if !close(a.t, b.t) {
                return Err(format!(
                    "{ray:?} t_max {t_max}: t {} (tri {}) vs brute {} (tri {})",
                    a.t, a.triangle, b.t, b.triangle
                ));
            }
            if a.triangle != b.triangle {
                let again = brute.intersect_triangle(ray, t_max, a.triangle);
                if !again.is_some_and(|h| close(h.t, b.t)) {
                    return Err(format!(
                        "{ray:?}: triangle {} vs brute {} not tied",
                        a.triangle, b.triangle
                    ));
                }
            }
            if a.t < ray.t_min.max(0.0) || a.t > t_max {
                return Err(format!("{ray:?}: t {} outside [{}, {t_max}]", a.t, ray.t_min));
            }
        }
        (a, b) => return Err(format!("{ray:?} t_max {t_max}: ours {a:?} vs brute {b:?}")),
    }
    let occ = accel.occluded(ray, t_max);
    if occ != theirs.is_some() {
        return Err(format!("{ray:?} t_max {t_max}: occluded {occ} vs brute hit {theirs:?}"));
    }
    Ok(())
}

/// `KdTree::any_hit` finds a hit exactly when brute force does, and the hit it reports is
/// real: its triangle is hit at its `t` (within 1e-5 relative), inside `[t_min, t_max]`.
pub fn any_hit_agrees(
    tree: &KdTree,
    brute: &BruteForce,
    ray: &Ray,
    t_max: f32,
) -> Result<(), String> {
    let theirs = brute.intersect(ray, t_max);
    match tree.any_hit(ray, t_max) {
        None if theirs.is_none() => Ok(()),
        None => Err(format!("{ray:?} t_max {t_max}: any_hit none vs brute {theirs:?}")),
        Some(h) => {
            let again = brute.intersect_triangle(ray, t_max, h.triangle);
            if theirs.is_none() || !again.is_some_and(|b| close(b.t, h.t)) {
                return Err(format!("{ray:?} t_max {t_max}: any_hit {h:?}, brute {again:?}"));
            }
            if h.t < ray.t_min.max(0.0) || h.t > t_max {
                return Err(format!("{ray:?}: any_hit t {} outside [{}, {t_max}]", h.t, ray.t_min));
            }
            Ok(())
        }
    }
}

/// Builds, validates, and checks every ray at several `t_max`.
pub fn check_all(mesh: &Mesh, settings: &Settings, rays: &[Ray]) -> Result<KdTree, String> {
    let tree = KdTree::build(mesh, settings).map_err(|e| e.to_string())?;
    tree.validate(mesh).map_err(|e| e.to_string())?;
    let brute = BruteForce::new(mesh).map_err(|e| e.to_string())?;
    for ray in rays {
        for t_max in [f32::INFINITY, 1.0, 0.37, 0.0] {
            agree(&tree, &brute, ray, t_max)?;
            any_hit_agrees(&tree, &brute, ray, t_max)?;
        }
        if let Some(h) = brute.intersect(ray, f32::INFINITY) {
            agree(&tree, &brute, ray, h.t)?;
            any_hit_agrees(&tree, &brute, ray, h.t)?;
        }
    }
    Ok(tree)
}

pub fn settings_variants() -> Vec<Settings> {
    vec![
        Settings::low(),
        Settings::DEFAULT,
        Settings::high(),
        Settings::reference(),
        Settings { leaf_size: 8, empty_bonus: 0.0, ..Settings::DEFAULT },
    ]
}
