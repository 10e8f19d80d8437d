//! Coefficient vectors: [`Sh<C>`] (one channel) and [`ShRgb<C>`] (three planar channels).
//!
//! `C` is the **coefficient count**, always `bands * bands`; the aliases name the **band
//! count**: [`Sh2`] has 2 bands (l = 0, 1) and 4 coefficients, [`Sh3`] 3 bands and 9
//! coefficients. "Order" is not used anywhere in this crate because it is ambiguous.

use bytemuck::{Pod, Zeroable};
use std::ops::{Add, AddAssign, Index, IndexMut, Mul, MulAssign, Neg, Sub, SubAssign};

/// Real SH coefficients of one channel, `C = bands²`, index `i = l(l+1) + m`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Sh<const C: usize> {
    pub c: [f32; C],
}

/// 1 band (l = 0): 1 coefficient.
pub type Sh1 = Sh<1>;
/// 2 bands (l = 0..=1): 4 coefficients (LPV).
pub type Sh2 = Sh<4>;
/// 3 bands (l = 0..=2): 9 coefficients (irradiance, the sky volume).
pub type Sh3 = Sh<9>;
/// 4 bands (l = 0..=3): 16 coefficients.
pub type Sh4 = Sh<16>;
/// 5 bands (l = 0..=4): 25 coefficients (references and tests).
pub type Sh5 = Sh<25>;

// SAFETY: `Sh<C>` is `repr(C)` around `[f32; C]`, which is Pod and Zeroable for every C.
unsafe impl<const C: usize> Zeroable for Sh<C> {}
unsafe impl<const C: usize> Pod for Sh<C> {}

/// Band count for a coefficient count, or a compile-time error if `C` is not a square.
pub const fn bands_for(coefficients: usize) -> usize {
    let mut b = 0;
    while b * b < coefficients {
        b += 1;
    }
    assert!(b * b == coefficients, "SH coefficient count must be a perfect square");
    b
}

/// Coefficient index of band `l`, index `m` in `-l..=l`.
pub const fn sh_index(l: usize, m: i32) -> usize {
    ((l * (l + 1)) as i64 + m as i64) as usize
}

impl<const C: usize> Sh<C> {
    /// Number of bands (`sqrt(C)`).
    pub const BANDS: usize = bands_for(C);
    pub const ZERO: Self = Self { c: [0.0; C] };

    pub const fn new(c: [f32; C]) -> Self {
        Self { c }
    }

    pub fn dot(&self, other: &Self) -> f32 {
        self.c.iter().zip(&other.c).map(|(a, b)| a * b).sum()
    }

    /// `self + (other - self) * t`.
    pub fn lerp(&self, other: &Self, t: f32) -> Self {
        let mut out = *self;
        for (o, b) in out.c.iter_mut().zip(&other.c) {
            *o += (b - *o) * t;
        }
        out
    }

    /// Energy of band `l`: the sum of its squared coefficients (rotation-invariant).
    pub fn band_energy(&self, l: usize) -> f32 {
        self.c[l * l..(l + 1) * (l + 1)].iter().map(|x| x * x).sum()
    }

    /// The first `D` coefficients (fewer bands), or zero-padded (more bands).
    pub fn resize<const D: usize>(&self) -> Sh<D> {
        let mut out = Sh::<D>::ZERO;
        let n = C.min(D);
        out.c[..n].copy_from_slice(&self.c[..n]);
        out
    }

    pub fn is_finite(&self) -> bool {
        self.c.iter().all(|x| x.is_finite())
    }
}

impl<const C: usize> Default for Sh<C> {
    fn default() -> Self {
        Self::ZERO
    }
}

impl<const C: usize> Index<usize> for Sh<C> {
    type Output = f32;
    fn index(&self, i: usize) -> &f32 {
        &self.c[i]
    }
}

impl<const C: usize> IndexMut<usize> for Sh<C> {
    fn index_mut(&mut self, i: usize) -> &mut f32 {
        &mut self.c[i]
    }
}

impl<const C: usize> Add for Sh<C> {
    type Output = Self;
    fn add(mut self, rhs: Self) -> Self {
        self += rhs;
        self
    }
}

impl<const C: usize> AddAssign for Sh<C> {
    fn add_assign(&mut self, rhs: Self) {
        for (a, b) in self.c.iter_mut().zip(rhs.c) {
            *a += b;
        }
    }
}

impl<const C: usize> Sub for Sh<C> {
    type Output = Self;
    fn sub(mut self, rhs: Self) -> Self {
        self -= rhs;
        self
    }
}

impl<const C: usize> SubAssign for Sh<C> {
    fn sub_assign(&mut self, rhs: Self) {
        for (a, b) in self.c.iter_mut().zip(rhs.c) {
            *a -= b;
        }
    }
}

impl<const C: usize> Neg for Sh<C> {
    type Output = Self;
    fn neg(self) -> Self {
        self * -1.0
    }
}

impl<const C: usize> Mul<f32> for Sh<C> {
    type Output = Self;
    fn mul(mut self, s: f32) -> Self {
        self *= s;
        self
    }
}

impl<const C: usize> MulAssign<f32> for Sh<C> {
    fn mul_assign(&mut self, s: f32) {
        for a in &mut self.c {
            *a *= s;
        }
    }
}

/// RGB SH: three planar channels, so a GPU storage buffer of `ShRgb<9>` is 27 consecutive f32.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[repr(C)]
pub struct ShRgb<const C: usize> {
    pub r: Sh<C>,
    pub g: Sh<C>,
    pub b: Sh<C>,
}

/// 2-band RGB (12 floats).
pub type Sh2Rgb = ShRgb<4>;
/// 3-band RGB (27 floats).
pub type Sh3Rgb = ShRgb<9>;
/// 4-band RGB (48 floats).
pub type Sh4Rgb = ShRgb<16>;
/// 5-band RGB (75 floats).
pub type Sh5Rgb = ShRgb<25>;

// SAFETY: three `Sh<C>` (each Pod, no padding, alignment 4) in a `repr(C)` struct.
unsafe impl<const C: usize> Zeroable for ShRgb<C> {}
unsafe impl<const C: usize> Pod for ShRgb<C> {}

impl<const C: usize> ShRgb<C> {
    pub const BANDS: usize = bands_for(C);
    pub const ZERO: Self = Self { r: Sh::ZERO, g: Sh::ZERO, b: Sh::ZERO };

    /// The same scalar SH scaled by a colour.
    pub fn from_scalar(sh: &Sh<C>, colour: glam::Vec3) -> Self {
        Self { r: *sh * colour.x, g: *sh * colour.y, b: *sh * colour.z }
    }

    /// Adds `sh` scaled by `colour` (the projection of one coloured sample).
    pub fn add_scaled(&mut self, sh: &Sh<C>, colour: glam::Vec3) {
        for i in 0..C {
            self.r.c[i] += sh.c[i] * colour.x;
            self.g.c[i] += sh.c[i] * colour.y;
            self.b.c[i] += sh.c[i] * colour.z;
        }
    }

    /// Per-channel dot product with a basis (or any scalar SH).
    pub fn dot(&self, basis: &Sh<C>) -> glam::Vec3 {
        let (mut r, mut g, mut b) = (0.0, 0.0, 0.0);
        for i in 0..C {
            r += self.r.c[i] * basis.c[i];
            g += self.g.c[i] * basis.c[i];
            b += self.b.c[i] * basis.c[i];
        }
        glam::Vec3::new(r, g, b)
    }

    pub fn lerp(&self, other: &Self, t: f32) -> Self {
        Self {
            r: self.r.lerp(&other.r, t),
            g: self.g.lerp(&other.g, t),
            b: self.b.lerp(&other.b, t),
        }
    }

    /// Applies `f` to each channel.
    pub fn map(&self, mut f: impl FnMut(&Sh<C>) -> Sh<C>) -> Self {
        Self { r: f(&self.r), g: f(&self.g), b: f(&self.b) }
    }

    pub fn is_finite(&self) -> bool {
        self.r.is_finite() && self.g.is_finite() && self.b.is_finite()
    }
}

impl<const C: usize> Add for ShRgb<C> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self { r: self.r + o.r, g: self.g + o.g, b: self.b + o.b }
    }
}

impl<const C: usize> AddAssign for ShRgb<C> {
    fn add_assign(&mut self, o: Self) {
        self.r += o.r;
        self.g += o.g;
        self.b += o.b;
    }
}

impl<const C: usize> Sub for ShRgb<C> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self { r: self.r - o.r, g: self.g - o.g, b: self.b - o.b }
    }
}

impl<const C: usize> Mul<f32> for ShRgb<C> {
    type Output = Self;
    fn mul(self, s: f32) -> Self {
        Self { r: self.r * s, g: self.g * s, b: self.b * s }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_match_the_gpu_layout() {
        assert_eq!(std::mem::size_of::<Sh3>(), 9 * 4);
        assert_eq!(std::mem::size_of::<Sh3Rgb>(), 27 * 4);
        assert_eq!(std::mem::size_of::<Sh2Rgb>(), 12 * 4);
        assert_eq!(Sh5::BANDS, 5);
        assert_eq!(Sh2::BANDS, 2);
        assert_eq!(sh_index(2, -2), 4);
        assert_eq!(sh_index(4, 4), 24);
    }

    #[test]
    fn arithmetic_and_lerp() {
        let a = Sh2::new([1.0, 2.0, 3.0, 4.0]);
        let b = Sh2::new([3.0, 2.0, 1.0, 0.0]);
        assert_eq!((a + b).c, [4.0; 4]);
        assert_eq!((a - a).c, [0.0; 4]);
        assert_eq!((a * 2.0).c, [2.0, 4.0, 6.0, 8.0]);
        assert_eq!(a.lerp(&b, 0.5).c, [2.0; 4]);
        assert_eq!(a.dot(&b), 3.0 + 4.0 + 3.0);
        assert_eq!(a.band_energy(1), 4.0 + 9.0 + 16.0);
        assert_eq!(a.resize::<1>().c, [1.0]);
        assert_eq!(a.resize::<9>().c[4..], [0.0; 5]);
    }
}
