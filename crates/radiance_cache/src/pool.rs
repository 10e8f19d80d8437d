//! The allocated caches (structure of arrays, one slot per cache, in cascade-then-linear
//! order) and the per-cascade tables from lattice position to slot.

use crate::lattice::Lattice;
use crate::light::IRRADIANCE_FLOATS;
use glam::IVec3;

/// Table value of a lattice position with no cache.
pub const NONE: u32 = u32::MAX;

/// The allocated caches.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Pool {
    /// `(cascade, world key)` of each slot, sorted.
    pub keys: Vec<(u32, IVec3)>,
    /// Clamped-cosine-convolved irradiance SH, `[r 16][g 16][b 16]`.
    pub irradiance: Vec<[f32; IRRADIANCE_FLOATS]>,
    /// `moment_texels` `[mean, mean²]` per slot, slot-major.
    pub moments: Vec<[f32; 2]>,
    /// Frame of the last lighting (0: never lit; such caches are not read by lookups).
    pub last_lit: Vec<u64>,
    pub moment_texels: usize,
}

impl Pool {
    pub fn new(moment_texels: usize) -> Self {
        Self { moment_texels, ..Self::default() }
    }

    pub fn len(&self) -> usize {
        self.keys.len()
    }

    pub fn moments_of(&self, slot: usize) -> &[[f32; 2]] {
        &self.moments[slot * self.moment_texels..(slot + 1) * self.moment_texels]
    }

    /// Appends a cache, copying its state from `old`'s slot when given.
    pub fn push(&mut self, key: (u32, IVec3), old: Option<(&Pool, usize)>) {
        self.keys.push(key);
        match old {
            Some((p, s)) => {
                self.irradiance.push(p.irradiance[s]);
                self.moments.extend_from_slice(p.moments_of(s));
                self.last_lit.push(p.last_lit[s]);
            }
            None => {
                self.irradiance.push([0.0; IRRADIANCE_FLOATS]);
                self.moments.extend(std::iter::repeat_n([0.0; 2], self.moment_texels));
                self.last_lit.push(0);
            }
        }
    }

    /// Bytes of cache data (keys, light, moments, ages).
    pub fn bytes(&self) -> usize {
        self.len()
            * (std::mem::size_of::<(u32, IVec3)>()
                + std::mem::size_of::<[f32; IRRADIANCE_FLOATS]>()
                + self.moment_texels * 8
                + 8)
    }
}

/// The slot of a world key in a cascade, through its table.
pub fn slot_of(lattice: &Lattice, table: &[u32], key: IVec3) -> Option<usize> {
    let l = lattice.local_of_key(key)?;
    let s = table[lattice.linear(l)];
    (s != NONE).then_some(s as usize)
}
