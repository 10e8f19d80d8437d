//! Bind groups made once and reused while what they bind stays the same: a resident pass
//! records every frame, and its inputs (the caller's buffers and views) rarely change, so a
//! frame should not create its bind groups again.

use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Bind groups created through this crate ([`create_bind_group`] and everything built on it:
/// [`crate::bind_group`], [`crate::bind_entries`], [`BindGroupCache::get`] when it has to
/// make one), in this process.
static CREATED: AtomicU64 = AtomicU64::new(0);

/// How many bind groups this crate's helpers have created in this process so far: the
/// difference across a steady frame says whether a renderer creates bind groups per frame.
pub fn bind_groups_created() -> u64 {
    CREATED.load(Ordering::Relaxed)
}

/// `device.create_bind_group(descriptor)`, counted in [`bind_groups_created`]: the one way
/// the workspace's crates create bind groups (a test keeps it so).
pub fn create_bind_group(
    device: &wgpu::Device,
    descriptor: &wgpu::BindGroupDescriptor<'_>,
) -> wgpu::BindGroup {
    CREATED.fetch_add(1, Ordering::Relaxed);
    device.create_bind_group(descriptor)
}

/// What a binding is, by identity: wgpu's handles compare by the object they name.
#[derive(Clone, PartialEq)]
enum Bound {
    Buffer(wgpu::Buffer, u64, Option<wgpu::BufferSize>),
    View(wgpu::TextureView),
    Sampler(wgpu::Sampler),
}

fn bound(resource: &wgpu::BindingResource<'_>) -> Option<Bound> {
    Some(match resource {
        wgpu::BindingResource::Buffer(b) => Bound::Buffer(b.buffer.clone(), b.offset, b.size),
        wgpu::BindingResource::TextureView(v) => Bound::View((*v).clone()),
        wgpu::BindingResource::Sampler(s) => Bound::Sampler((*s).clone()),
        _ => return None,
    })
}

/// How many bind groups a [`BindGroupCache`] keeps: enough for a pass that one frame
/// records for a few callers (the view and the traced hits, say) with their own buffers.
pub const CACHED_GROUPS: usize = 4;

type Key = Vec<(u32, Bound)>;

/// The bind groups of one layout, each made again only when no group made before binds the
/// same resources (the same buffers with the same offsets and sizes, views and samplers).
/// It keeps the [`CACHED_GROUPS`] most recently used.
///
/// A cached group keeps its resources alive until it is evicted or the cache dropped.
/// Arrays of bindings are not compared: a group with one is made on every call.
#[derive(Default)]
pub struct BindGroupCache {
    /// Most recently used first.
    groups: Mutex<Vec<(Key, wgpu::BindGroup)>>,
}

impl BindGroupCache {
    pub fn new() -> Self {
        Self::default()
    }

    /// The bind group of `layout` with `entries` (`(binding, resource)` pairs): a cached one
    /// when one binds the same resources, a new one otherwise. Use one cache per layout.
    pub fn get(
        &self,
        device: &wgpu::Device,
        label: &str,
        layout: &wgpu::BindGroupLayout,
        entries: &[(u32, wgpu::BindingResource<'_>)],
    ) -> wgpu::BindGroup {
        let key: Option<Key> = entries.iter().map(|(b, r)| bound(r).map(|k| (*b, k))).collect();
        let mut groups = self.groups.lock().unwrap_or_else(|e| e.into_inner());
        let Some(key) = key else { return crate::bind_entries(device, label, layout, entries) };
        if let Some(i) = groups.iter().position(|(k, _)| *k == key) {
            let hit = groups.remove(i);
            let group = hit.1.clone();
            groups.insert(0, hit);
            return group;
        }
        let group = crate::bind_entries(device, label, layout, entries);
        groups.insert(0, (key, group.clone()));
        groups.truncate(CACHED_GROUPS);
        group
    }

    /// As [`BindGroupCache::get`] with the bindings `0..` in order.
    pub fn get_in_order(
        &self,
        device: &wgpu::Device,
        label: &str,
        layout: &wgpu::BindGroupLayout,
        resources: &[wgpu::BindingResource<'_>],
    ) -> wgpu::BindGroup {
        self.get(device, label, layout, &crate::plumbing::numbered(resources))
    }
}
