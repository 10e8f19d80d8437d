//! Tone mapping and eye adaptation on the GPU (`shaders/post/tonemap.wgsl`), the twin of
//! [`crate::ToneMapper`].

use crate::{Exposure, PostError};
use bytemuck::{Pod, Zeroable};

/// Workgroups of the luminance reduction (`REDUCE_GROUPS` in the shader).
pub const REDUCE_GROUPS: u32 = 64;

const LABEL: &str = "post tone mapping";

/// The shader's `Params` uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub(crate) struct Params {
    width: u32,
    height: u32,
    dt: f32,
    rate: f32,
    key: f32,
    reset: u32,
    raw: u32,
    _pad: u32,
}

const _: () = assert!(std::mem::size_of::<Params>() == 32);

/// Tone mapping with eye adaptation, resident: made once over the caller's HDR images
/// (`texture_2d<f32>`, read with `textureLoad`), it records three compute dispatches per
/// frame (reduce, adapt, map) and writes the display image into its own RGBA8 texture
/// ([`Self::texture`]; sRGB-encoded values in a linear format, usable as a storage, sampled
/// or copy source). The adapted luminance stays in a GPU buffer between frames.
pub struct ToneMapPass {
    reduce: wgpu::ComputePipeline,
    adapt: wgpu::ComputePipeline,
    map: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    state: wgpu::Buffer,
    /// Per source: the reduction's and the display image's bind groups.
    reduce_groups: Vec<wgpu::BindGroup>,
    map_groups: Vec<wgpu::BindGroup>,
    adapt_group: wgpu::BindGroup,
    output: wgpu::Texture,
    size: (u32, u32),
}

impl ToneMapPass {
    /// Bytes each [`Self::record`] writes through the queue (the frame's uniforms), for a
    /// renderer that counts its uploads.
    pub const UPLOAD_BYTES: u64 = std::mem::size_of::<Params>() as u64;

    /// The pass over `sources`, each `width` x `height`: the pipelines, the buffers, the
    /// output texture and every source's bind groups, made once. No source, an empty size or
    /// a source of another size is an error, as is a pipeline the device refuses.
    pub fn new(
        device: &wgpu::Device,
        width: u32,
        height: u32,
        sources: &[&wgpu::TextureView],
    ) -> Result<Self, PostError> {
        super::check_sources(sources, width, height)?;
        let pipe = |entry| {
            gpu_harness::validated(device, || {
                gpu_harness::compute_pipeline(device, LABEL, super::TONEMAP_WGSL, entry, None)
            })
        };
        let (reduce, adapt, map) = (pipe("reduce")?, pipe("adapt")?, pipe("map")?);
        let params =
            gpu_harness::uniform_buffer(device, LABEL, bytemuck::bytes_of(&Params::default()));
        let partial =
            gpu_harness::empty_storage(device, "luminance sums", REDUCE_GROUPS as u64 * 8);
        let state = gpu_harness::empty_storage(device, "adapted luminance", 16);
        let output = gpu_harness::texture_2d(
            device,
            "display",
            (width, height),
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let ldr = output.create_view(&Default::default());
        use wgpu::BindingResource as R;
        let bind = |pipeline: &wgpu::ComputePipeline, entries: &[(u32, R<'_>)]| {
            gpu_harness::bind_entries(device, LABEL, &pipeline.get_bind_group_layout(0), entries)
        };
        let (p, sums, st) =
            (params.as_entire_binding(), partial.as_entire_binding(), state.as_entire_binding());
        let reduce_groups = sources
            .iter()
            .map(|hdr| {
                bind(&reduce, &[(0, p.clone()), (1, R::TextureView(hdr)), (2, sums.clone())])
            })
            .collect();
        let adapt_group = bind(&adapt, &[(0, p.clone()), (2, sums.clone()), (3, st.clone())]);
        let map_groups = sources
            .iter()
            .map(|hdr| {
                let hdr = R::TextureView(hdr);
                bind(&map, &[(0, p.clone()), (1, hdr), (3, st.clone()), (4, R::TextureView(&ldr))])
            })
            .collect();
        Ok(Self {
            reduce,
            adapt,
            map,
            params,
            state,
            reduce_groups,
            map_groups,
            adapt_group,
            output,
            size: (width, height),
        })
    }

    /// Records the luminance reduction, the adaptation and the display image of source
    /// `source` with exposure `e` (its uniforms written through `queue`, [`Self::UPLOAD_BYTES`]).
    /// A source the pass was not made with is [`PostError::NoSuchSource`].
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        source: usize,
        e: Exposure,
    ) -> Result<(), PostError> {
        super::check_index(source, self.map_groups.len())?;
        let (width, height) = self.size;
        let p = Params {
            width,
            height,
            dt: e.dt,
            rate: e.rate,
            key: e.key,
            reset: u32::from(e.reset),
            raw: u32::from(e.raw),
            _pad: 0,
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&p));
        let steps = [
            (&self.reduce, &self.reduce_groups[source], [REDUCE_GROUPS, 1, 1]),
            (&self.adapt, &self.adapt_group, [1, 1, 1]),
            (&self.map, &self.map_groups[source], [width.div_ceil(8), height.div_ceil(8), 1]),
        ];
        for (pipeline, group, groups) in steps {
            gpu_harness::dispatch(encoder, pipeline, group, groups);
        }
        Ok(())
    }

    /// The display image (RGBA8, `width` x `height`).
    pub fn texture(&self) -> &wgpu::Texture {
        &self.output
    }

    /// The sources the pass was made with.
    pub fn sources(&self) -> usize {
        self.map_groups.len()
    }

    /// Reads the display image back once the work submitted has written it: RGBA8 rows, top
    /// row first (blocking; for tests and tools).
    pub fn read_back(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Vec<u8>, PostError> {
        let all = wgpu::TextureAspect::All;
        Ok(gpu_harness::read_texture(device, queue, &self.output, 0, all, 4)?)
    }

    /// Reads back the adapted luminance and the last frame's log average (blocking; for
    /// tests and tools). Both are 0 before the first frame.
    pub fn read_adaptation(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<(f32, f32), PostError> {
        let bytes = gpu_harness::read_buffer(device, queue, &self.state, 8)?;
        let v: Vec<f32> = gpu_harness::cast_vec(&bytes);
        Ok((v[0], v[1]))
    }
}

#[cfg(test)]
mod tests {
    //! The Rust side's copies of the shader's layout and constants are the shader's.

    /// The literal `const name` of `module` is initialised with.
    fn constant(module: &naga::Module, name: &str) -> naga::Literal {
        let (_, c) = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("const {name} not in the shader"));
        match module.global_expressions[c.init] {
            naga::Expression::Literal(l) => l,
            ref e => panic!("const {name} = {e:?}"),
        }
    }

    #[test]
    fn params_and_constants_match_the_shader() {
        let module = naga::front::wgsl::parse_str(super::super::TONEMAP_WGSL).expect("parses");
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).expect("lays out");
        let (params, _) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some("Params"))
            .expect("struct Params");
        assert_eq!(layouter[params].size as usize, std::mem::size_of::<super::Params>());
        assert_eq!(constant(&module, "REDUCE_GROUPS"), naga::Literal::U32(super::REDUCE_GROUPS));
        assert_eq!(constant(&module, "LOG_DELTA"), naga::Literal::F32(crate::LOG_DELTA));
    }
}
