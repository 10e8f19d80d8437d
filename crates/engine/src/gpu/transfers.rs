//! What crosses between the CPU and the GPU in a frame: bytes uploaded (buffer writes and
//! buffers created with contents), bytes read back, and the times the CPU waited for the GPU.
//! Every engine call that moves data counts itself here; the renderer takes the counts at the
//! end of each frame for the report. Not counted: the timestamp queries' own read-back (16
//! bytes per timed pass, instrumentation) and transfers inside a crate's GPU path that the
//! engine cannot see (the resident LPV's own uniforms when it runs on the GPU).

use std::sync::atomic::{AtomicU64, Ordering};

/// Counts for one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct TransferCounts {
    pub uploaded_bytes: u64,
    pub read_back_bytes: u64,
    /// Blocking waits of the CPU on the GPU (each read-back is one).
    pub cpu_waits: u64,
}

#[derive(Debug, Default)]
pub struct Transfers {
    uploaded: AtomicU64,
    read_back: AtomicU64,
    waits: AtomicU64,
}

impl Transfers {
    pub fn uploaded(&self, bytes: u64) {
        self.uploaded.fetch_add(bytes, Ordering::Relaxed);
    }

    /// A read-back of `bytes`, which the CPU waited for.
    pub fn read_back(&self, bytes: u64) {
        self.read_back.fetch_add(bytes, Ordering::Relaxed);
        self.waited();
    }

    pub fn waited(&self) {
        self.waits.fetch_add(1, Ordering::Relaxed);
    }

    /// What a `traced_effects` pass moved.
    pub fn traced(&self, t: traced_effects::gpu::Transferred) {
        self.uploaded(t.uploaded);
        self.read_back.fetch_add(t.read_back, Ordering::Relaxed);
        self.waits.fetch_add(t.reads as u64, Ordering::Relaxed);
    }

    /// What the LPV (`lpv::gpu::LpvPass`) moved.
    pub fn lpv(&self, t: lpv::gpu::Transferred) {
        self.uploaded(t.uploaded);
        self.read_back.fetch_add(t.read_back, Ordering::Relaxed);
        self.waits.fetch_add(t.reads as u64, Ordering::Relaxed);
    }

    /// The counts since the last call, which start again from zero.
    pub fn take(&self) -> TransferCounts {
        TransferCounts {
            uploaded_bytes: self.uploaded.swap(0, Ordering::Relaxed),
            read_back_bytes: self.read_back.swap(0, Ordering::Relaxed),
            cpu_waits: self.waits.swap(0, Ordering::Relaxed),
        }
    }
}
