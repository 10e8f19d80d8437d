//! Bind groups: the cache makes a group once per set of resources, and every crate of the
//! workspace creates its bind groups through `gpu_harness::create_bind_group`, so that
//! `bind_groups_created` (which the engine's steady-frame test reads) sees them all.

use gpu_harness::{BindGroupCache, CACHED_GROUPS, bind_groups_created, gpu_test_context};
use std::path::Path;

const WGSL: &str = "@group(0) @binding(0) var<storage, read_write> a: array<f32>;
    @group(0) @binding(1) var<storage, read_write> b: array<f32>;
    @compute @workgroup_size(1) fn main() { a[0] = b[0]; }";

#[test]
fn the_cache_makes_a_group_once_per_set_of_resources() {
    let Some(ctx) = gpu_test_context() else { return };
    let device = &ctx.device;
    let pipeline = gpu_harness::compute_pipeline(device, "copy", WGSL, "main", None);
    let layout = pipeline.get_bind_group_layout(0);
    let buffers: Vec<wgpu::Buffer> = (0..CACHED_GROUPS + 2)
        .map(|i| gpu_harness::empty_storage(device, &i.to_string(), 16))
        .collect();
    let cache = BindGroupCache::new();
    let get = |i: usize, j: usize| {
        let before = bind_groups_created();
        let group = cache.get_in_order(
            device,
            "copy",
            &layout,
            &[buffers[i].as_entire_binding(), buffers[j].as_entire_binding()],
        );
        (group, bind_groups_created() - before)
    };
    let (first, made) = get(0, 1);
    assert_eq!(made, 1, "the first call makes the group");
    let (again, made) = get(0, 1);
    assert_eq!((made, again), (0, first.clone()), "the same resources reuse it");
    assert_eq!(get(1, 0).1, 1, "other bindings (the same buffers swapped) make another");
    assert_eq!(get(0, 1).1, 0, "two callers alternating keep both");
    for k in 2..CACHED_GROUPS + 2 {
        assert_eq!(get(0, k).1, 1);
    }
    assert_eq!(get(0, 1).1, 1, "the least recently used of more than CACHED_GROUPS is dropped");
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("a readable source tree").flatten() {
        let path = entry.path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_crate_creates_bind_groups_through_the_counted_call() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for krate in std::fs::read_dir(&crates).expect("crates/").flatten() {
        let src = krate.path().join("src");
        if src.is_dir() {
            rust_files(&src, &mut files);
        }
    }
    assert!(files.len() > 50, "found the workspace's sources ({} files)", files.len());
    let direct: Vec<String> = files
        .iter()
        .filter(|f| !f.ends_with("gpu_harness/src/bind_cache.rs"))
        .filter(|f| std::fs::read_to_string(f).is_ok_and(|s| s.contains(".create_bind_group(")))
        .map(|f| f.display().to_string())
        .collect();
    assert!(direct.is_empty(), "call gpu_harness::create_bind_group instead in {direct:?}");
}
