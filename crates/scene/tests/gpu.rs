//! The scene on the GPU (`scene::gpu`, feature `gpu`; runs on lavapipe in CI): what is
//! uploaded is the scene, and the material struct has one size in Rust and WGSL.
#![cfg(feature = "gpu")]

use gpu_harness::gpu_test_context;
use scene::gpu::{GpuMaterial, GpuScene, MATERIAL_INC_WGSL};

#[test]
fn material_struct_has_the_size_of_its_wgsl_twin() {
    let size = gpu_harness::wgsl_struct_size(MATERIAL_INC_WGSL, "Material");
    assert_eq!(size, Ok(std::mem::size_of::<GpuMaterial>()));
}

/// The material table as the GPU holds it.
fn materials(ctx: &gpu_harness::GpuContext, gpu: &GpuScene) -> Vec<GpuMaterial> {
    let bytes = gpu.materials.size();
    gpu_harness::cast_vec(
        &gpu_harness::read_buffer(&ctx.device, &ctx.queue, &gpu.materials, bytes).unwrap(),
    )
}

#[test]
fn uploaded_buffers_hold_the_scene_and_each_material_gets_one_group() {
    let Some(ctx) = gpu_test_context() else { return };
    let city = scene::Generated::City.build(1);
    let groups_before = gpu_harness::bind_groups_created();
    let gpu = GpuScene::new(&ctx.device, &ctx.queue, &city);
    assert_eq!(gpu.material_groups.len(), city.materials.len());
    assert!(gpu_harness::bind_groups_created() - groups_before >= city.materials.len() as u64);
    let table = materials(&ctx, &gpu);
    assert_eq!(table, city.materials.iter().map(GpuMaterial::new).collect::<Vec<_>>());
    assert_eq!(gpu.triangle_count, city.stats().triangles);
    let drawn: u32 = gpu.draws.iter().map(|d| d.index_count).sum();
    assert_eq!(drawn as usize, 3 * city.stats().triangles);
    assert_eq!(gpu.indices.size() as usize, 4 * drawn as usize);
}

#[test]
fn an_empty_scene_binds_one_zeroed_material() {
    let Some(ctx) = gpu_test_context() else { return };
    let gpu = GpuScene::new(&ctx.device, &ctx.queue, &scene::Scene::new("empty"));
    assert_eq!(materials(&ctx, &gpu), vec![GpuMaterial::default()]);
    assert!(gpu.draws.is_empty() && gpu.triangle_count == 0);
}
