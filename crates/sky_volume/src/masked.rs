//! Masked sums by per-byte lookup tables: `sum_{i : bit i of mask set} term_i` for a fixed
//! set of per-sample vectors `term_i` of width `W`. For every group of 8 samples a table of
//! the 256 subset sums is built once (255 vector additions per group); a masked sum is then
//! one table read and one vector addition per 8 samples instead of one per visible sample.
//! This is the re-light of [`crate::FillMethod::CachedVisibility`] (W = 27: RGB x 9 SH) and
//! the transfer build of [`crate::FillMethod::Transfer`] (W = 9 k^2).

#![allow(clippy::needless_range_loop)] // index loops over fixed-size coefficient arrays

/// Above this many table floats the sums are done sample by sample (same result up to
/// rounding): 8 Mi floats = 32 MiB.
const MAX_TABLE_FLOATS: usize = 8 << 20;

#[derive(Clone, Debug)]
pub(crate) struct MaskedSum<const W: usize> {
    /// `table[g * 256 + m]`, or empty when too large (then `terms` is used directly).
    table: Vec<[f32; W]>,
    terms: Vec<[f32; W]>,
}

impl<const W: usize> MaskedSum<W> {
    pub fn new(terms: Vec<[f32; W]>) -> Self {
        let groups = terms.len().div_ceil(8);
        let mut table = Vec::new();
        if groups * 256 * W <= MAX_TABLE_FLOATS {
            table = vec![[0.0; W]; groups * 256];
            for g in 0..groups {
                let t = &mut table[g * 256..(g + 1) * 256];
                for m in 1..256usize {
                    let low = m.trailing_zeros() as usize;
                    let i = g * 8 + low;
                    let prev = t[m & (m - 1)];
                    let term = terms.get(i).copied().unwrap_or([0.0; W]);
                    let mut out = [0.0; W];
                    for k in 0..W {
                        out[k] = prev[k] + term[k];
                    }
                    t[m] = out;
                }
            }
        }
        Self { table, terms }
    }

    /// Per-sample term `i`.
    pub fn term(&self, i: usize) -> &[f32; W] {
        &self.terms[i]
    }

    /// Adds the masked sum to `out`.
    #[inline]
    pub fn add_masked(&self, mask: &[u8], out: &mut [f32; W]) {
        if self.table.is_empty() {
            for (g, &m) in mask.iter().enumerate() {
                let mut bits = m;
                while bits != 0 {
                    let i = g * 8 + bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let t = &self.terms[i];
                    for k in 0..W {
                        out[k] += t[k];
                    }
                }
            }
            return;
        }
        for (g, &m) in mask.iter().enumerate() {
            if m == 0 {
                continue;
            }
            let t = &self.table[g * 256 + m as usize];
            for k in 0..W {
                out[k] += t[k];
            }
        }
    }
}
