//! Named regions of a view: which part of the scene each pixel shows, from the primary ray
//! through the pixel's centre traced in the `reference` world (the reference's first hit).
//!
//! A region is a mesh of the scene seen from one side: the mesh's name and the axis its
//! (viewer-facing) geometric normal is closest to, `up`, `down`, `east` (+X), `west`,
//! `south` (+Z) or `north`. The scene's mesh names are the region names: the generated city
//! names each building's parts (`building_1_0_facade`, `building_0_0_glass`, ...), `street`,
//! `pedestal`, `statue`; a closed room made of one mesh falls apart into its floor (`up`),
//! ceiling (`down`) and walls by the axis. Pixels that see no surface are the region
//! [`BACKGROUND`]. Regions covering less than [`MIN_SHARE`] of the image are merged into no
//! region (too few pixels for a figure).

use engine::EngineError;
use glam::Vec3;
use reference::{SceneLighting, World};

/// The region of the pixels whose primary ray leaves the scene (the sky seen directly).
pub const BACKGROUND: &str = "background";

/// The smallest share of the image a region must cover to be reported.
pub const MIN_SHARE: f64 = 0.005;

/// Per-pixel region ids of one view.
#[derive(Clone, Debug)]
pub struct RegionMap {
    pub width: u32,
    pub height: u32,
    /// Region names, indexed by id.
    pub names: Vec<String>,
    /// Per pixel (row-major, top row first): the region id, or `None` (a region under
    /// [`MIN_SHARE`]).
    pub ids: Vec<Option<u32>>,
}

impl RegionMap {
    /// Pixels of region `id`.
    pub fn pixels(&self, id: u32) -> impl Iterator<Item = usize> + '_ {
        self.ids.iter().enumerate().filter(move |(_, r)| **r == Some(id)).map(|(i, _)| i)
    }

    /// Pixels in no region (regions under [`MIN_SHARE`]).
    pub fn unnamed(&self) -> impl Iterator<Item = usize> + '_ {
        self.ids.iter().enumerate().filter(|(_, r)| r.is_none()).map(|(i, _)| i)
    }

    /// The id of the region called `name`.
    pub fn id(&self, name: &str) -> Option<u32> {
        self.names.iter().position(|n| n == name).map(|i| i as u32)
    }

    /// Per pixel: whether it sees a surface (not the sky seen directly, [`BACKGROUND`]).
    pub fn surface_mask(&self) -> Vec<bool> {
        let sky = self.id(BACKGROUND);
        self.ids.iter().map(|&r| sky.is_none() || r != sky).collect()
    }
}

/// The axis name of a unit normal.
pub fn facing_name(n: Vec3) -> &'static str {
    let a = n.abs();
    if a.y >= a.x && a.y >= a.z {
        if n.y >= 0.0 { "up" } else { "down" }
    } else if a.x >= a.z {
        if n.x >= 0.0 { "east" } else { "west" }
    } else if n.z >= 0.0 {
        "south"
    } else {
        "north"
    }
}

/// A generated scene seen from its own camera at `width x height`, with the region map of that
/// view: what the ledger's examples measure.
pub struct View {
    pub scene: scene::Scene,
    pub camera: scene::Camera,
    pub regions: RegionMap,
}

impl View {
    /// `g` (seed 1) from its camera, its aspect made `width / height`.
    pub fn of(g: scene::Generated, width: u32, height: u32) -> Result<Self, EngineError> {
        let scene = g.build(1);
        let mut camera = scene.camera;
        camera.aspect = width as f32 / height as f32;
        let regions = region_map(&scene, &camera, width, height)?;
        Ok(Self { scene, camera, regions })
    }
}

/// The region map of `scene` seen from `camera` at `width x height`.
pub fn region_map(
    scene: &scene::Scene,
    camera: &scene::Camera,
    width: u32,
    height: u32,
) -> Result<RegionMap, EngineError> {
    regions(scene, camera, width, height, Naming::MeshAndFacing)
}

/// [`region_map`] with one region per mesh, whatever side of it a pixel sees (a sphere is one
/// region, not one per axis).
pub fn mesh_region_map(
    scene: &scene::Scene,
    camera: &scene::Camera,
    width: u32,
    height: u32,
) -> Result<RegionMap, EngineError> {
    regions(scene, camera, width, height, Naming::Mesh)
}

/// How a pixel's region is named.
#[derive(Clone, Copy, PartialEq)]
enum Naming {
    /// `<mesh> <facing>` (the module doc).
    MeshAndFacing,
    /// `<mesh>`.
    Mesh,
}

fn regions(
    scene: &scene::Scene,
    camera: &scene::Camera,
    width: u32,
    height: u32,
    naming: Naming,
) -> Result<RegionMap, EngineError> {
    let tech = |e| EngineError::technique("reference", e);
    let world = reference::world_from_scene(scene, &SceneLighting::DEFAULT).map_err(tech)?;
    let mut cam_scene = scene.clone();
    cam_scene.camera = *camera;
    let cam = reference::camera_from_scene(&cam_scene);
    // First triangle of each mesh (the reference world numbers triangles in mesh order).
    let mut starts = Vec::with_capacity(scene.meshes.len());
    let mut n = 0u32;
    for m in &scene.meshes {
        starts.push(n);
        n += m.indices.len() as u32;
    }
    Ok(build(&world, &cam, scene, &starts, (width, height), naming))
}

fn build(
    world: &World,
    cam: &reference::Camera,
    scene: &scene::Scene,
    starts: &[u32],
    (width, height): (u32, u32),
    naming: Naming,
) -> RegionMap {
    let mut names: Vec<String> = Vec::new();
    let mut raw = Vec::with_capacity((width * height) as usize);
    // The region map's pixels are the render's: the image's aspect, as the reference's.
    let cam = cam.with_aspect(width as f32 / height as f32);
    for y in 0..height {
        for x in 0..width {
            let d = cam.pixel_direction(x as f32 + 0.5, y as f32 + 0.5, width, height);
            let name = world.intersect(cam.position, d, f32::INFINITY).map_or_else(
                || BACKGROUND.to_string(),
                |h| {
                    let mesh = starts.partition_point(|&s| s <= h.triangle).saturating_sub(1);
                    let n = if h.normal.dot(d) > 0.0 { -h.normal } else { h.normal };
                    let mesh_name = scene.meshes.get(mesh).map_or("?", |m| m.name.as_str());
                    match naming {
                        Naming::MeshAndFacing => format!("{mesh_name} {}", facing_name(n)),
                        Naming::Mesh => mesh_name.to_string(),
                    }
                },
            );
            let id = match names.iter().position(|k| *k == name) {
                Some(i) => i as u32,
                None => {
                    names.push(name);
                    names.len() as u32 - 1
                }
            };
            raw.push(Some(id));
        }
    }
    // Drop small regions, renumber by size (largest first).
    let mut count = vec![0usize; names.len()];
    for id in raw.iter().flatten() {
        count[*id as usize] += 1;
    }
    let min = (MIN_SHARE * raw.len() as f64).ceil() as usize;
    let mut order: Vec<usize> = (0..names.len()).filter(|&i| count[i] >= min.max(1)).collect();
    order.sort_by(|&a, &b| count[b].cmp(&count[a]).then(names[a].cmp(&names[b])));
    let mut remap = vec![None; names.len()];
    for (new, &old) in order.iter().enumerate() {
        remap[old] = Some(new as u32);
    }
    RegionMap {
        width,
        height,
        names: order.iter().map(|&i| names[i].clone()).collect(),
        ids: raw.into_iter().map(|r| r.and_then(|i| remap[i as usize])).collect(),
    }
}
