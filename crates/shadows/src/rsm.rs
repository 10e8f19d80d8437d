//! Reflective shadow maps (Dachsbacher & Stamminger 2005): per texel of the light's view,
//! the flux the surface there reflects, its world normal and world position, and virtual
//! point lights (VPLs) extracted from it for light propagation volumes.

use crate::depth_map::DepthMap;
use crate::error::{ShadowError, finite3};
use crate::light_space::ShadowView;
use crate::raster::{NO_TRIANGLE, rasterize};
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// A virtual point light: a small diffuse emitter with the flux (W) a patch of the RSM
/// reflects, at its position, facing along its normal.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "gpu", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct Vpl {
    pub position: Vec3,
    pub normal: Vec3,
    pub flux: Vec3,
}

const _: () = assert!(std::mem::size_of::<Vpl>() == 36);

/// A reflective shadow map: three row-major planes of `width * height` texels (row 0 at the
/// top, like [`DepthMap`]). Texels no surface covers have zero flux and a zero normal.
#[derive(Clone, Debug, PartialEq)]
pub struct Rsm {
    pub width: u32,
    pub height: u32,
    /// Reflected flux per texel: `light colour * albedo * texel area`, where the light colour
    /// is the irradiance on a plane facing the light and the texel area is the map texel's
    /// cross-section perpendicular to the light (metres squared); the surface's own tilt is
    /// already accounted for by that cross-section.
    pub flux: Vec<Vec3>,
    /// World-space unit normal, facing the light.
    pub normal: Vec<Vec3>,
    /// World-space position of the texel centre's surface point.
    pub position: Vec<Vec3>,
}

impl Rsm {
    /// Renders an RSM for a directional light over an orthographic shadow view on the CPU:
    /// `albedo[i]` is triangle `i`'s diffuse albedo, `light_colour` the irradiance facing the
    /// light. Also returns the depth map of the same pass.
    pub fn render(
        view: &ShadowView,
        triangles: &[[Vec3; 3]],
        albedo: &[Vec3],
        light_colour: Vec3,
    ) -> Result<(Self, DepthMap), ShadowError> {
        finite3(light_colour, "light colour")?;
        if albedo.len() != triangles.len() {
            return Err(ShadowError::InvalidParameter {
                name: "albedo",
                reason: format!("{} albedos for {} triangles", albedo.len(), triangles.len()),
            });
        }
        if triangles.iter().flatten().any(|v| !v.is_finite()) {
            return Err(ShadowError::NonFinite("triangle vertex"));
        }
        let (w, h) = (view.resolution, view.resolution);
        let mut depth = DepthMap::new(w, h)?;
        let mut ids = vec![NO_TRIANGLE; w as usize * h as usize];
        let vp = view.view_proj_f64();
        rasterize(&mut depth, Some(&mut ids), &vp, triangles)?;
        let area = (view.texel_size * view.texel_size) as f32;
        let to_light = view.basis.to_light.as_vec3();
        let normals: Vec<Vec3> = triangles
            .iter()
            .map(|t| {
                let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
                if n.dot(to_light) < 0.0 { -n } else { n }
            })
            .collect();
        let texels: Vec<(Vec3, Vec3, Vec3)> = (0..w as usize * h as usize)
            .into_par_iter()
            .map(|i| {
                let id = ids[i];
                if id == NO_TRIANGLE {
                    return (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
                }
                let (x, y) = ((i % w as usize) as f64 + 0.5, (i / w as usize) as f64 + 0.5);
                let z = depth.as_slice()[i] as f64;
                let p = view.map_to_world(DVec3::new(x, y, z)).as_vec3();
                let flux = light_colour * albedo[id as usize] * area;
                (flux, normals[id as usize], p)
            })
            .collect();
        let mut rsm = Self {
            width: w,
            height: h,
            flux: Vec::with_capacity(texels.len()),
            normal: Vec::with_capacity(texels.len()),
            position: Vec::with_capacity(texels.len()),
        };
        for (f, n, p) in texels {
            rsm.flux.push(f);
            rsm.normal.push(n);
            rsm.position.push(p);
        }
        Ok((rsm, depth))
    }

    /// Total reflected flux (summed in double precision).
    pub fn total_flux(&self) -> glam::DVec3 {
        self.flux.iter().map(|f| f.as_dvec3()).sum()
    }

    /// One VPL per `block x block` tile of covered texels: the tile's summed flux, its
    /// flux-weighted mean position and normal (luminance weights; plain means where the flux
    /// is zero). Total flux is conserved. Tiles with no covered texel give no VPL.
    pub fn extract_vpls(&self, block: u32) -> Result<Vec<Vpl>, ShadowError> {
        if block == 0 {
            return Err(ShadowError::InvalidParameter {
                name: "block",
                reason: "must be >= 1".into(),
            });
        }
        let (w, h, b) = (self.width as usize, self.height as usize, block as usize);
        let tiles_x = w.div_ceil(b);
        let tiles_y = h.div_ceil(b);
        let out: Vec<Option<Vpl>> = (0..tiles_x * tiles_y)
            .into_par_iter()
            .map(|t| {
                let (tx, ty) = (t % tiles_x, t / tiles_x);
                let mut flux = Vec3::ZERO;
                let (mut pw, mut nw, mut wsum) = (Vec3::ZERO, Vec3::ZERO, 0.0f32);
                let (mut pp, mut np, mut count) = (Vec3::ZERO, Vec3::ZERO, 0u32);
                for y in ty * b..((ty + 1) * b).min(h) {
                    for x in tx * b..((tx + 1) * b).min(w) {
                        let i = y * w + x;
                        if self.normal[i] == Vec3::ZERO {
                            continue;
                        }
                        let f = self.flux[i];
                        let lum = f.dot(Vec3::new(0.2126, 0.7152, 0.0722)).max(0.0);
                        flux += f;
                        pw += self.position[i] * lum;
                        nw += self.normal[i] * lum;
                        wsum += lum;
                        pp += self.position[i];
                        np += self.normal[i];
                        count += 1;
                    }
                }
                if count == 0 {
                    return None;
                }
                let (position, normal) =
                    if wsum > 0.0 { (pw / wsum, nw) } else { (pp / count as f32, np) };
                let normal = normal.try_normalize().unwrap_or(np.normalize_or_zero());
                Some(Vpl { position, normal, flux })
            })
            .collect();
        Ok(out.into_iter().flatten().collect())
    }

    /// Plane lengths match, normals are unit or zero, flux is finite and non-negative.
    pub fn validate(&self) -> Result<(), ShadowError> {
        let n = self.width as usize * self.height as usize;
        if self.flux.len() != n || self.normal.len() != n || self.position.len() != n {
            return Err(ShadowError::Invariant(
                "RSM plane lengths differ from width * height".into(),
            ));
        }
        for i in 0..n {
            let l = self.normal[i].length();
            if !(l == 0.0 || (l - 1.0).abs() < 1e-4) {
                return Err(ShadowError::Invariant(format!("texel {i}: normal not unit")));
            }
            if !self.flux[i].is_finite() || self.flux[i].min_element() < 0.0 {
                return Err(ShadowError::Invariant(format!("texel {i}: bad flux")));
            }
        }
        Ok(())
    }
}
