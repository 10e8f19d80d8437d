//! Alpha-tested casters in the resident passes: a quad whose mask is opaque on one half and
//! a hole on the other casts the opaque half only, into a point light's cube and into the
//! RSM; bad masks are typed errors (runs on lavapipe in CI).
#![cfg(feature = "gpu")]

use glam::{DVec3, Vec3};
use gpu_harness::gpu_test_context;
use shadows::gpu::{
    AlphaMask, CubeLight, CubeShadows, DrawRange, Geometry, ReflectiveShadowMap, VertexLayout,
};
use shadows::{LightBasis, ShadowError, ShadowView};
use wgpu::util::DeviceExt;

/// A 16 x 16 m floor at y = 0 (draw 0) and a 2 x 2 m quad at y = 2 (draw 1) whose u runs
/// along x, as position + normal + uv vertices.
fn scene(device: &wgpu::Device) -> (wgpu::Buffer, wgpu::Buffer, Vec<DrawRange>) {
    let quad = |y: f32, h: f32| {
        [[-h, -h], [h, -h], [h, h], [-h, h]].map(|[x, z]| {
            let uv = [f32::from(x > 0.0), f32::from(z > 0.0)];
            [x, y, z, 0.0, 1.0, 0.0, uv[0], uv[1]]
        })
    };
    let vertices: Vec<[f32; 8]> = quad(0.0, 8.0).into_iter().chain(quad(2.0, 1.0)).collect();
    let indices: Vec<u32> = [0u32, 1, 2, 0, 2, 3].iter().flat_map(|&i| [i, i + 4]).collect();
    // Interleaved above; reorder into the floor's six indices, then the quad's.
    let indices: Vec<u32> =
        indices.iter().step_by(2).chain(indices.iter().skip(1).step_by(2)).copied().collect();
    let init = |contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents,
            usage,
        })
    };
    let draws = vec![
        DrawRange { indices: 0..6, base_vertex: 0 },
        DrawRange { indices: 6..12, base_vertex: 0 },
    ];
    (
        init(bytemuck::cast_slice(&vertices), wgpu::BufferUsages::VERTEX),
        init(bytemuck::cast_slice(&indices), wgpu::BufferUsages::INDEX),
        draws,
    )
}

/// A one-row RGBA8 texture of `texels`.
fn row_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texels: &[[u8; 4]],
) -> wgpu::TextureView {
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: None,
            size: wgpu::Extent3d {
                width: texels.len() as u32,
                height: 1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        Default::default(),
        texels.as_flattened(),
    );
    texture.create_view(&Default::default())
}

/// A 2 x 1 mask: opaque where u < 0.5, a hole where u > 0.5 (nearest filtering).
fn half_mask(device: &wgpu::Device, queue: &wgpu::Queue) -> AlphaMask {
    let view = row_texture(device, queue, &[[255; 4], [255, 255, 255, 0]]);
    let sampler = device.create_sampler(&Default::default());
    AlphaMask::new(device, &view, &sampler, 0.5).unwrap()
}

fn geometry<'a>(
    vertices: &'a wgpu::Buffer,
    indices: &'a wgpu::Buffer,
    draws: &'a [DrawRange],
    masks: &'a [Option<AlphaMask>],
) -> Geometry<'a> {
    Geometry { masks, ..Geometry::opaque(vertices, indices, wgpu::IndexFormat::Uint32, draws) }
}

/// The texels of `got` that differ from the floor-only `floor`, and whether each of them
/// holds what `full` (the opaque quad) holds there.
fn quad_texels(floor: &[f32], full: &[f32], got: &[f32]) -> (usize, bool) {
    let mut n = 0;
    let mut inside = true;
    for ((f, q), g) in floor.iter().zip(full).zip(got) {
        if g != f {
            n += 1;
            inside &= g == q;
        }
    }
    (n, inside)
}

#[test]
fn masked_quad_casts_its_opaque_half_into_cubes_and_rsm() {
    let Some(ctx) = gpu_test_context() else { return };
    let (d, q) = (&ctx.device, &ctx.queue);
    let (vertices, indices, draws) = scene(d);
    let mask = half_mask(d, q);
    let layout = VertexLayout::POSITION_NORMAL_UV;
    let masks = [None, Some(mask)];
    let geometry = |draws, masks| geometry(&vertices, &indices, draws, masks);
    let submit = |record: &dyn Fn(&mut wgpu::CommandEncoder)| {
        let mut enc = d.create_command_encoder(&Default::default());
        record(&mut enc);
        q.submit([enc.finish()]);
    };

    // The light 4 m above: the cube's -Y face looks down on the quad and the floor.
    let cubes = CubeShadows::new(d, layout, 64, 1).unwrap();
    let light = [CubeLight { position: Vec3::new(0.0, 4.0, 0.0), near: 0.1, far: 20.0 }];
    let face = |g: &Geometry<'_>| {
        submit(&|enc| cubes.record(q, enc, g, &light).unwrap());
        cubes.read_back(d, q, 0).unwrap()[3].as_slice().to_vec()
    };
    let floor = face(&geometry(&draws[..1], &[]));
    let full = face(&geometry(&draws, &[]));
    let masked = face(&geometry(&draws, &masks));
    let (n_full, _) = quad_texels(&floor, &full, &full);
    let (n_half, inside) = quad_texels(&floor, &full, &masked);
    assert!(n_full > 100, "the quad covers {n_full} texels of the face");
    assert!(inside, "the masked quad casts only where the opaque one does, at its depth");
    let share = n_half as f64 / n_full as f64;
    assert!((share - 0.5).abs() < 0.08, "the opaque half casts {share} of the quad");

    // The RSM of a sun straight down over the same scene.
    let view =
        ShadowView::fit_sphere(LightBasis::new(Vec3::Y).unwrap(), DVec3::ZERO, 4.0, 64, 1.0, false);
    let rsm = ReflectiveShadowMap::new(d, layout, 64, 2).unwrap();
    let lit_quad = |g: &Geometry<'_>| {
        submit(&|enc| rsm.record(q, enc, g, &[Vec3::ONE; 2], &view, Vec3::ONE).unwrap());
        let (map, _) = rsm.read_back(d, q).unwrap();
        map.position.iter().filter(|p| (p.y - 2.0).abs() < 1e-3).count()
    };
    let (full, half) = (lit_quad(&geometry(&draws, &[])), lit_quad(&geometry(&draws, &masks)));
    assert!(full > 100, "the RSM sees the quad on {full} texels");
    let share = half as f64 / full as f64;
    assert!((share - 0.5).abs() < 0.08, "the RSM sees {share} of the masked quad");
}

#[test]
fn bad_masks_are_typed_errors() {
    let Some(ctx) = gpu_test_context() else { return };
    let (d, q) = (&ctx.device, &ctx.queue);
    let (vertices, indices, draws) = scene(d);
    let view = row_texture(d, q, &[[255; 4]]);
    let sampler = d.create_sampler(&Default::default());
    assert!(matches!(
        AlphaMask::new(d, &view, &sampler, f32::NAN),
        Err(ShadowError::NonFinite("alpha cutoff"))
    ));
    let masks = [None, Some(AlphaMask::new(d, &view, &sampler, 0.5).unwrap())];
    let light = [CubeLight { position: Vec3::new(0.0, 4.0, 0.0), near: 0.1, far: 20.0 }];
    let record = |layout: VertexLayout, masks: &[Option<AlphaMask>]| {
        let cubes = CubeShadows::new(d, layout, 16, 1).unwrap();
        let g = geometry(&vertices, &indices, &draws, masks);
        let mut enc = d.create_command_encoder(&Default::default());
        cubes.record(q, &mut enc, &g, &light)
    };
    // Masked draws for a layout without texture coordinates, and masks not one per draw.
    let positions = VertexLayout { stride: 32, ..VertexLayout::POSITION_NORMAL };
    let bad = |r: Result<(), ShadowError>| {
        matches!(r, Err(ShadowError::InvalidParameter { name: "alpha masks", .. }))
    };
    assert!(bad(record(positions, &masks)));
    assert!(bad(record(VertexLayout::POSITION_NORMAL_UV, &masks[1..])));
    assert!(record(VertexLayout::POSITION_NORMAL_UV, &masks).is_ok());
    assert!(record(positions, &[None, None]).is_ok());
    // A texture coordinate that does not fit in the vertex.
    let outside = VertexLayout { uv_offset: Some(28), ..VertexLayout::POSITION_NORMAL_UV };
    assert!(CubeShadows::new(d, outside, 16, 1).is_err());
}
