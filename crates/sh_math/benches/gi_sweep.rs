//! sh_math's accuracy-vs-time sweep for `cargo xtask bench`.
//!
//! - `sh_math/eval_sh3_rgb`: one 3-band RGB evaluation at a normal (target < 5 ns).
//! - `sh_math/irradiance_sun_bands_{2,3,4,5}`: irradiance from a sun-like lobe with `b` bands,
//!   rel RMS over 256 normals against exact numeric integration; time of one evaluation.
//! - `sh_math/irradiance_sky_bands_{2,3,4,5}`: the same for a smooth sky with a dark ground.
//! - `sh_math/projection_<set>_<n>`: projection error (3 bands, rel RMS of the coefficients)
//!   vs samples for each point set, against a converged projection; time of one projection.
//!   `sh_math/projection_saff_kuijlaars_100` is the thesis's sky-volume set (100 hemisphere
//!   points).
//! - rotation and per-sample projection throughput.

use gi_report::{Entry, Sweep, black_box, rel_rms, time_ms, time_ns_per_call};
use glam::Vec3;
use sh_math::*;
use std::f64::consts::PI;

/// Sharpness of the sun-like lobe `exp(k (cos - 1))`: about 7 degrees wide at half maximum.
const SUN_K: f64 = 300.0;

fn sun_dir() -> Vec3 {
    Vec3::new(0.3, 0.8, 0.52).normalize()
}

fn sun_lobe(cos: f64) -> f64 {
    (SUN_K * (cos - 1.0)).exp()
}

/// A smooth sky over a dark ground (+Y up): brighter towards the zenith and one side.
fn sky(d: Vec3) -> f64 {
    if d.y > 0.0 { 0.6 + 0.8 * d.y as f64 + 0.3 * d.x as f64 } else { 0.05 }
}

/// Exact zonal coefficients of a lobe `f(cos)` about +Z, by fine 1D quadrature:
/// `z_l = 2 pi sqrt((2l+1) / 4 pi) integral_{-1}^{1} P_l(t) f(t) dt`.
fn zonal_coefficients(f: impl Fn(f64) -> f64, bands: usize) -> Vec<f64> {
    let n = 200_000;
    (0..bands)
        .map(|l| {
            let mut acc = 0.0;
            for i in 0..n {
                let t = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
                acc += legendre(l, t) * f(t);
            }
            2.0 * PI * ((2 * l + 1) as f64 / (4.0 * PI)).sqrt() * acc * 2.0 / n as f64
        })
        .collect()
}

fn legendre(l: usize, x: f64) -> f64 {
    let (mut p0, mut p1) = (1.0, x);
    if l == 0 {
        return 1.0;
    }
    for k in 2..=l {
        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
        p0 = p1;
        p1 = p2;
    }
    p1
}

/// The rotated zonal lobe as SH: `f(l, m) = sqrt(4 pi / (2l+1)) z_l Y(l, m)(axis)`.
fn zonal_to_sh<const C: usize>(z: &[f64], axis: Vec3) -> Sh<C> {
    let y: Sh<C> = eval_basis(axis);
    let mut out = Sh::<C>::ZERO;
    for (l, zl) in z.iter().enumerate().take(Sh::<C>::BANDS) {
        let s = (4.0 * PI / (2 * l + 1) as f64).sqrt() * zl;
        for i in l * l..(l + 1) * (l + 1) {
            out.c[i] = (s * y.c[i] as f64) as f32;
        }
    }
    out
}

/// Exact irradiance `integral L(w) max(0, n.w) dw` by midpoint quadrature on a fine grid in
/// the frame of `axis`, with theta limited to `theta_max` (where L is negligible beyond).
fn exact_irradiance(
    l: impl Fn(Vec3) -> f64,
    n: Vec3,
    axis: Vec3,
    theta_max: f64,
    res: usize,
) -> f64 {
    let q = glam::Quat::from_rotation_arc(Vec3::Z, axis);
    let (nt, np) = (res, 2 * res);
    let (dt, dp) = (theta_max / nt as f64, 2.0 * PI / np as f64);
    let mut acc = 0.0;
    for i in 0..nt {
        let theta = (i as f64 + 0.5) * dt;
        let (st, ct) = theta.sin_cos();
        for j in 0..np {
            let phi = (j as f64 + 0.5) * dp;
            let local = Vec3::new((st * phi.cos()) as f32, (st * phi.sin()) as f32, ct as f32);
            let w = q * local;
            acc += l(w) * (n.dot(w) as f64).max(0.0) * st;
        }
    }
    acc * dt * dp
}

/// Timed loops index `normals` with `i & 63` (needs at least 64 normals): a division per
/// call would cost more than the operation being timed.
fn irradiance_sweep<const C: usize>(
    sweep: &mut Sweep,
    kind: &str,
    sh: &Sh<C>,
    exact: &[f64],
    normals: &[Vec3],
) {
    let approx: Vec<f64> = normals.iter().map(|n| irradiance(sh, *n) as f64).collect();
    let err = rel_rms(&approx, exact);
    let ns = time_ns_per_call(sweep.reps(50), 4096, |i| irradiance(black_box(sh), normals[i & 63]));
    let bands = Sh::<C>::BANDS;
    sweep.entry(
        Entry::new(
            format!("sh_math/irradiance_{kind}_bands_{bands}"),
            format!("irradiance_{kind}"),
            ns * 1e-6,
        )
        .setting("bands", bands)
        .setting("normals", normals.len())
        .error("rel_rms", err, "exact_numeric_integration"),
    );
}

fn main() {
    let mut sweep = Sweep::from_env("sh_math");
    let quick = sweep.quick();
    let normals = fibonacci_sphere(if quick { 96 } else { 256 }).dirs;

    sweep.stage("3-band RGB evaluation");
    let sky_sh: Sh3Rgb = project_fn_rgb(&fibonacci_sphere(4096), |d| Vec3::splat(sky(d) as f32));
    let irr = CLAMPED_COSINE.apply_rgb(&sky_sh);
    let ns = time_ns_per_call(sweep.reps(50), 1 << 16, |i| {
        evaluate_rgb(black_box(&irr), normals[i & 63])
    });
    sweep.entry(
        Entry::new("sh_math/eval_sh3_rgb", "evaluation", ns * 1e-6)
            .setting("bands", 3)
            .note("one pre-convolved 3-band RGB evaluation at a normal; target < 5 ns on one core"),
    );

    sweep.stage("irradiance of a sun-like lobe vs bands");
    let z = zonal_coefficients(sun_lobe, 5);
    let theta_max = (1.0 - 40.0 / SUN_K).acos();
    let res = if quick { 96 } else { 256 };
    let exact: Vec<f64> = normals
        .iter()
        .map(|n| {
            exact_irradiance(|w| sun_lobe(w.dot(sun_dir()) as f64), *n, sun_dir(), theta_max, res)
        })
        .collect();
    irradiance_sweep::<4>(&mut sweep, "sun", &zonal_to_sh(&z, sun_dir()), &exact, &normals);
    irradiance_sweep::<9>(&mut sweep, "sun", &zonal_to_sh(&z, sun_dir()), &exact, &normals);
    irradiance_sweep::<16>(&mut sweep, "sun", &zonal_to_sh(&z, sun_dir()), &exact, &normals);
    irradiance_sweep::<25>(&mut sweep, "sun", &zonal_to_sh(&z, sun_dir()), &exact, &normals);

    sweep.stage("irradiance of a smooth sky vs bands");
    let dense = fibonacci_sphere(if quick { 100_000 } else { 400_000 });
    let sky5: Sh5 = project_fn(&dense, |d| sky(d) as f32);
    let exact: Vec<f64> =
        normals.iter().map(|n| exact_irradiance(sky, *n, Vec3::Y, PI, res)).collect();
    irradiance_sweep::<4>(&mut sweep, "sky", &sky5.resize(), &exact, &normals);
    irradiance_sweep::<9>(&mut sweep, "sky", &sky5.resize(), &exact, &normals);
    irradiance_sweep::<16>(&mut sweep, "sky", &sky5.resize(), &exact, &normals);
    irradiance_sweep::<25>(&mut sweep, "sky", &sky5, &exact, &normals);

    sweep.stage("projection error vs samples");
    let lobe_axis = Vec3::new(0.2, 0.5, 0.84).normalize();
    let lobe = |d: Vec3| (8.0 * (d.dot(lobe_axis) - 1.0)).exp();
    let exact_sphere: Sh3 =
        zonal_to_sh(&zonal_coefficients(|t| (8.0 * (t - 1.0)).exp(), 3), lobe_axis);
    let exact_hemi: Sh3 = project_fn(&dense, |d| if d.y > 0.0 { sky(d) as f32 } else { 0.0 });
    let coeff_err = |a: &Sh3, r: &Sh3| rel_rms(&a.c.map(|v| v as f64), &r.c.map(|v| v as f64));
    let counts: &[usize] = if quick { &[16, 100, 1024] } else { &[16, 64, 100, 256, 1024, 4096] };
    for &n in counts {
        let sphere_sets = [
            ("saff_kuijlaars_sphere", saff_kuijlaars_sphere(n)),
            ("fibonacci_sphere", fibonacci_sphere(n)),
            ("hammersley_sphere", hammersley_sphere(n)),
        ];
        for (name, set) in &sphere_sets {
            let (ms, p) = time_ms(sweep.reps(50), || project_fn::<9>(set, lobe));
            sweep.entry(
                Entry::new(format!("sh_math/projection_{name}_{n}"), "projection_sphere", ms)
                    .setting("set", *name)
                    .setting("samples", n)
                    .error("rel_rms", coeff_err(&p, &exact_sphere), "analytic_zonal_projection"),
            );
        }
        let seeds = if quick { 4 } else { 16 };
        let random_err = (0..seeds)
            .map(|s| coeff_err(&project_fn::<9>(&random_sphere(n, s), lobe), &exact_sphere))
            .sum::<f64>()
            / seeds as f64;
        let set = random_sphere(n, 0);
        let (ms, _) = time_ms(sweep.reps(50), || project_fn::<9>(&set, lobe));
        sweep.entry(
            Entry::new(format!("sh_math/projection_random_sphere_{n}"), "projection_sphere", ms)
                .setting("set", "random_sphere")
                .setting("samples", n)
                .setting("seeds_averaged", seeds)
                .error("rel_rms", random_err, "analytic_zonal_projection"),
        );
        let hemi_sets = [
            ("saff_kuijlaars", saff_kuijlaars_hemisphere(n, Vec3::Y)),
            ("fibonacci_hemisphere", fibonacci_hemisphere(n, Vec3::Y)),
            ("hammersley_hemisphere", hammersley_hemisphere(n, Vec3::Y)),
            ("random_hemisphere", random_hemisphere(n, Vec3::Y, 0)),
        ];
        for (name, set) in &hemi_sets {
            let (ms, p) = time_ms(sweep.reps(50), || project_fn::<9>(set, |d| sky(d) as f32));
            let mut e =
                Entry::new(format!("sh_math/projection_{name}_{n}"), "projection_hemisphere", ms)
                    .setting("set", *name)
                    .setting("samples", n)
                    .error(
                        "rel_rms",
                        coeff_err(&p, &exact_hemi),
                        "converged_projection_fibonacci_dense",
                    );
            if *name == "saff_kuijlaars" && n == 100 {
                e = e
                    .note("the thesis's sky-volume sampling: 100 Saff-Kuijlaars hemisphere points");
            }
            sweep.entry(e);
        }
    }

    sweep.stage("throughput");
    let dirs = random_sphere(1024, 3).dirs;
    let ns = time_ns_per_call(sweep.reps(50), 1 << 16, |i| {
        let mut acc = Sh3Rgb::ZERO;
        acc.add_scaled(&eval_basis::<9>(dirs[i & 1023]), Vec3::ONE);
        acc
    });
    sweep.entry(
        Entry::new("sh_math/project_per_sample_sh3_rgb", "throughput", ns * 1e-6)
            .setting("bands", 3),
    );
    let q = glam::Quat::from_euler(glam::EulerRot::YXZ, 0.3, 1.2, -0.4);
    let ns = time_ns_per_call(sweep.reps(50), 1 << 12, |_| ShRotation::new(black_box(q)));
    sweep.entry(
        Entry::new("sh_math/rotation_setup", "throughput", ns * 1e-6)
            .note("bands 3 and 4 matrices built"),
    );
    let rot = ShRotation::new(q);
    let sh5 = Sh5::new(std::array::from_fn(|i| i as f32 * 0.1));
    let ns =
        time_ns_per_call(sweep.reps(50), 1 << 16, |_| rot.rotate(black_box(&sh5.resize::<9>())));
    sweep.entry(Entry::new("sh_math/rotate_sh3", "throughput", ns * 1e-6).setting("bands", 3));
    let ns = time_ns_per_call(sweep.reps(50), 1 << 16, |_| rot.rotate(black_box(&sh5)));
    sweep.entry(Entry::new("sh_math/rotate_sh5", "throughput", ns * 1e-6).setting("bands", 5));

    sweep.finish().expect("writing the sweep");
}
