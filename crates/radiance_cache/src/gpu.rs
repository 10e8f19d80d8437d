//! The lookup as a resident WGSL compute pass (`shaders/radiance_cache/lookup.wgsl`).
//!
//! [`GpuLookup`] is built once from a device (it owns the pipeline); [`GpuCacheData`] owns
//! the cache's GPU copy (tables, light, moments), rewritten in place from the CPU cache after
//! each update; [`GpuLookup::bind`] binds it once to the caller's query and output buffers,
//! and [`GpuLookup::record_bound`] records one dispatch into the caller's encoder, creating
//! nothing. [`ResidentCache`] is the three kept together, as a renderer uses them: made once,
//! written after each update (re-bound when the copy grew), recorded every frame.
//! [`read_back`] is separate, for parity tests.

use crate::cache::RadianceCache;
use crate::error::CacheError;
use crate::pool::NONE;
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

pub use crate::wgsl::{COMMON_WGSL, LOOKUP_WGSL};

/// Threads per workgroup of the lookup.
pub const WORKGROUP: u32 = 64;

/// `RcLattice` of the WGSL.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLattice {
    pub origin_key: [i32; 3],
    pub res: u32,
    pub spacing: f32,
    pub table_offset: u32,
    pub _pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<GpuLattice>() == 32);

/// `LookupParams` of the WGSL.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LookupParams {
    pub lattices: [GpuLattice; 4],
    pub cascades: u32,
    pub coefficients: u32,
    pub moment_res: u32,
    pub count: u32,
    pub blend: f32,
    pub normal_bias: f32,
    pub _pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<LookupParams>() == 160);

/// One query: position (w unused) and normal (w unused), as the kernel reads them.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuQuery {
    pub position: [f32; 4],
    pub normal: [f32; 4],
}

impl GpuQuery {
    pub fn new(p: glam::Vec3, n: glam::Vec3) -> Self {
        Self { position: p.extend(0.0).to_array(), normal: n.extend(0.0).to_array() }
    }
}

/// The GPU copy of a [`RadianceCache`]: its lattices (in the params), slot tables (unlit
/// caches as `NONE`), light and moments. Resident: [`GpuCacheData::write`] rewrites it in
/// place after each update and recreates a buffer only when the allocated caches outgrow it
/// (then [`GpuCacheData::generation`] changes and bindings made before are stale).
pub struct GpuCacheData {
    params: LookupParams,
    tables: wgpu::Buffer,
    irradiance: wgpu::Buffer,
    moments: wgpu::Buffer,
    generation: u64,
}

/// The lookup parameters and the slot tables of `cache` as the kernel reads them.
fn contents(cache: &RadianceCache) -> (LookupParams, Vec<u32>) {
    let s = cache.settings();
    let mut params = LookupParams {
        cascades: cache.lattices.len() as u32,
        coefficients: s.coefficients() as u32,
        moment_res: s.moment_resolution,
        blend: s.blend_cells,
        normal_bias: s.normal_bias,
        ..LookupParams::default()
    };
    let mut tables = Vec::new();
    for (i, (l, t)) in cache.lattices.iter().zip(&cache.tables).enumerate() {
        params.lattices[i] = GpuLattice {
            origin_key: l.origin_key.to_array(),
            res: l.res,
            spacing: l.spacing(),
            table_offset: tables.len() as u32,
            _pad: [0; 2],
        };
        tables.extend(t.iter().map(|&slot| {
            if slot != NONE && cache.pool.last_lit[slot as usize] > 0 { slot } else { NONE }
        }));
    }
    (params, tables)
}

impl GpuCacheData {
    /// Buffers for `cache` as it is now (fill them with [`GpuCacheData::write`]).
    pub fn with_capacity_of(device: &wgpu::Device, cache: &RadianceCache) -> Self {
        let (params, tables) = contents(cache);
        let slots = cache.pool.len() as u64;
        Self {
            params,
            tables: gpu_harness::empty_storage(
                device,
                "radiance_cache tables",
                tables.len() as u64 * 4,
            ),
            irradiance: gpu_harness::empty_storage(
                device,
                "radiance_cache irradiance",
                slots * IRRADIANCE_BYTES,
            ),
            moments: gpu_harness::empty_storage(
                device,
                "radiance_cache moments",
                cache.pool.moments.len() as u64 * 8,
            ),
            generation: 0,
        }
    }

    /// Uploads `cache` (tests, tools: a fresh copy).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, cache: &RadianceCache) -> Self {
        let mut data = Self::with_capacity_of(device, cache);
        data.write(device, queue, cache);
        data
    }

    /// Rewrites the copy from `cache` (call after each allocation or update). A buffer the
    /// allocated caches outgrew is recreated with room for twice as many (bindings must then
    /// be remade: [`Written::grown`]).
    pub fn write(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        cache: &RadianceCache,
    ) -> Written {
        let (params, tables) = contents(cache);
        self.params = params;
        let (mut grown, mut written) = (false, 0);
        for (buffer, bytes, label) in [
            (&mut self.tables, bytemuck::cast_slice::<u32, u8>(&tables), "radiance_cache tables"),
            (
                &mut self.irradiance,
                bytemuck::cast_slice(&cache.pool.irradiance),
                "radiance_cache irradiance",
            ),
            (
                &mut self.moments,
                bytemuck::cast_slice(&cache.pool.moments),
                "radiance_cache moments",
            ),
        ] {
            if bytes.len() as u64 > buffer.size() {
                *buffer = gpu_harness::empty_storage(device, label, 2 * bytes.len() as u64);
                grown = true;
            }
            if !bytes.is_empty() {
                queue.write_buffer(buffer, 0, bytes);
                written += bytes.len() as u64;
            }
        }
        self.generation += u64::from(grown);
        Written { grown, bytes: written }
    }

    /// Changes whenever [`GpuCacheData::write`] recreated a buffer.
    pub fn generation(&self) -> u64 {
        self.generation
    }
}

/// What [`GpuCacheData::write`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Written {
    /// A buffer was recreated: bindings to the old one must be remade.
    pub grown: bool,
    /// Bytes uploaded (the tables and every allocated cache's light).
    pub bytes: u64,
}

/// Bytes of one slot's light.
const IRRADIANCE_BYTES: u64 = (crate::light::IRRADIANCE_FLOATS * 4) as u64;

/// The lookup bound to a [`GpuCacheData`], a query buffer and an output buffer: made once,
/// recorded every frame with [`GpuLookup::record_bound`] (no buffer, no bind group per call).
pub struct LookupBinding {
    uniform: wgpu::Buffer,
    group: wgpu::BindGroup,
    count: u32,
    generation: u64,
}

impl LookupBinding {
    /// False once `data` recreated a buffer since this binding was made.
    pub fn is_current(&self, data: &GpuCacheData) -> bool {
        self.generation == data.generation
    }
}

/// The compiled lookup pipeline.
pub struct GpuLookup {
    pipeline: wgpu::ComputePipeline,
}

impl GpuLookup {
    /// Compiles [`LOOKUP_WGSL`] on `device`; a shader or pipeline error is [`CacheError::Gpu`].
    pub fn new(device: &wgpu::Device) -> Result<Self, CacheError> {
        let label = "radiance_cache lookup";
        let pipeline = gpu_harness::validated(device, || {
            gpu_harness::compute_pipeline(device, label, LOOKUP_WGSL, "main", None)
        })
        .map_err(CacheError::Gpu)?;
        Ok(Self { pipeline })
    }

    /// Binds the lookup of `count` [`GpuQuery`]s in `queries` into `output` (one
    /// `vec4<f32>` per query, RGB irradiance) over `data`'s buffers.
    pub fn bind(
        &self,
        device: &wgpu::Device,
        data: &GpuCacheData,
        queries: &wgpu::Buffer,
        output: &wgpu::Buffer,
        count: u32,
    ) -> LookupBinding {
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("radiance_cache lookup params"),
            size: std::mem::size_of::<LookupParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let entries = [&uniform, &data.tables, &data.irradiance, &data.moments, queries, output];
        let resources = entries.map(|b| b.as_entire_binding());
        let layout = self.pipeline.get_bind_group_layout(0);
        let group = gpu_harness::bind_group(device, "radiance_cache lookup", &layout, &resources);
        LookupBinding { uniform, group, count, generation: data.generation }
    }

    /// Records the bound lookup with `data`'s current lattices (written to the binding's
    /// uniform through `queue`). A binding made before `data` grew is
    /// [`CacheError::StaleBinding`].
    pub fn record_bound(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        data: &GpuCacheData,
        binding: &LookupBinding,
    ) -> Result<(), CacheError> {
        if !binding.is_current(data) {
            return Err(CacheError::StaleBinding);
        }
        let params = LookupParams { count: binding.count, ..data.params };
        queue.write_buffer(&binding.uniform, 0, bytemuck::bytes_of(&params));
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &binding.group, &[]);
        pass.dispatch_workgroups(binding.count.div_ceil(WORKGROUP).max(1), 1, 1);
        Ok(())
    }

    /// Uploads `points`, records, submits and reads the result back (tests, tools).
    pub fn lookup_blocking(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        data: &GpuCacheData,
        points: &[GpuQuery],
    ) -> Result<Vec<glam::Vec3>, CacheError> {
        let one = [GpuQuery::default()];
        let points_or_one = if points.is_empty() { &one[..] } else { points };
        let queries = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("radiance_cache queries"),
            contents: bytemuck::cast_slice(points_or_one),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("radiance_cache lookup output"),
            size: (points.len().max(1) * 16) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        gpu_harness::validated(device, || {
            let mut encoder = device.create_command_encoder(&Default::default());
            let binding = self.bind(device, data, &queries, &output, points.len() as u32);
            self.record_bound(queue, &mut encoder, data, &binding)?;
            queue.submit([encoder.finish()]);
            Ok::<(), CacheError>(())
        })
        .map_err(CacheError::Gpu)??;
        let v: Vec<[f32; 4]> = read_back(device, queue, &output)?;
        Ok(v.iter().take(points.len()).map(|c| glam::Vec3::new(c[0], c[1], c[2])).collect())
    }
}

/// The caller's buffers a [`ResidentCache`] is bound to (kept to re-bind after a growth).
struct Target {
    queries: wgpu::Buffer,
    output: wgpu::Buffer,
    count: u32,
}

/// The lookup as one resident pass: the cache's GPU copy ([`GpuCacheData`]), the compiled
/// kernel ([`GpuLookup`]) and its binding to the caller's query and output buffers
/// ([`LookupBinding`]), kept consistent.
///
/// Made once from a device ([`ResidentCache::new`]); after each CPU update
/// [`ResidentCache::write`] rewrites the copy in place (and re-binds when a buffer had to
/// grow); [`ResidentCache::bind`] names the caller's buffers (a new binding only when they
/// changed); [`ResidentCache::record`] records the bound lookup into the caller's encoder
/// every frame, creating nothing. While the allocated caches stay within the buffers'
/// capacity, a steady frame (write, bind, record) creates no buffer and no bind group.
pub struct ResidentCache {
    data: GpuCacheData,
    lookup: GpuLookup,
    binding: Option<LookupBinding>,
    target: Option<Target>,
}

impl ResidentCache {
    /// Buffers with room for `cache` as it is now (empty until the first
    /// [`ResidentCache::write`]) and the compiled lookup; a shader or pipeline error is
    /// [`CacheError::Gpu`].
    pub fn new(device: &wgpu::Device, cache: &RadianceCache) -> Result<Self, CacheError> {
        let data = GpuCacheData::with_capacity_of(device, cache);
        let lookup = GpuLookup::new(device)?;
        Ok(Self { data, lookup, binding: None, target: None })
    }

    /// Rewrites the GPU copy from `cache` (after each [`RadianceCache::allocate`] or
    /// [`RadianceCache::update`]); what was uploaded ([`Written::bytes`]: a renderer counts
    /// them). When a buffer had to grow, the lookup is bound again to the same caller's
    /// buffers, so [`ResidentCache::record`] keeps working.
    pub fn write(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        cache: &RadianceCache,
    ) -> Written {
        let written = self.data.write(device, queue, cache);
        if written.grown {
            self.rebind(device);
        }
        written
    }

    /// Binds the lookup of the first `count` [`GpuQuery`]s of `queries` into `output` (one
    /// `vec4<f32>` per query, RGB irradiance). Idempotent: the same buffers and count as the
    /// current binding make nothing; other ones replace it. True when a binding was made.
    pub fn bind(
        &mut self,
        device: &wgpu::Device,
        queries: &wgpu::Buffer,
        output: &wgpu::Buffer,
        count: u32,
    ) -> bool {
        let same = self
            .target
            .as_ref()
            .is_some_and(|t| t.queries == *queries && t.output == *output && t.count == count);
        let current = self.binding.as_ref().is_some_and(|b| b.is_current(&self.data));
        if same && current {
            return false;
        }
        self.target = Some(Target { queries: queries.clone(), output: output.clone(), count });
        self.rebind(device);
        true
    }

    fn rebind(&mut self, device: &wgpu::Device) {
        if let Some(t) = &self.target {
            self.binding =
                Some(self.lookup.bind(device, &self.data, &t.queries, &t.output, t.count));
        }
    }

    /// Whether the lookup is bound ([`ResidentCache::bind`] was called), so that
    /// [`ResidentCache::record`] records it.
    pub fn ready(&self) -> bool {
        self.binding.is_some()
    }

    /// Records the bound lookup with the lattices of the last [`ResidentCache::write`]
    /// (written to the binding's uniform through `queue`); `Ok(false)` and nothing recorded
    /// when nothing is bound yet.
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<bool, CacheError> {
        let Some(binding) = &self.binding else { return Ok(false) };
        self.lookup.record_bound(queue, encoder, &self.data, binding)?;
        Ok(true)
    }

    /// The GPU copy (its buffers' generation, for tests and tools).
    pub fn data(&self) -> &GpuCacheData {
        &self.data
    }

    /// The compiled lookup (for one-off lookups: [`GpuLookup::lookup_blocking`]).
    pub fn lookup(&self) -> &GpuLookup {
        &self.lookup
    }
}

/// Copies a storage buffer (with `COPY_SRC`) to the CPU (blocking).
pub fn read_back<T: Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
) -> Result<Vec<T>, CacheError> {
    let bytes =
        gpu_harness::read_buffer(device, queue, buffer, buffer.size()).map_err(CacheError::Gpu)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}
