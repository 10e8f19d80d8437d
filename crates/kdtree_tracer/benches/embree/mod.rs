//! Embree as a peer in the crate's races (`gi_sweep`, `kdrace`, `kdbench`): a minimal binding
//! of the system's Embree 3 library, opened at run time.
//!
//! Dev-only: the crate itself never depends on Embree. The library is opened with `dlopen`
//! (through `libloading`) rather than linked, so a machine without it builds and tests as
//! before and the races leave Embree out with a message. Debian 12 ships Embree 3.13
//! (`apt-get install libembree3-3`; the header comes with `libembree-dev`); `EMBREE_LIB` names
//! another library file. Why not a crate: the Rust bindings of Embree 3 (`embree` 0.3, 2021;
//! `embree3-sys` 0.1, bindgen at build time) link the library unconditionally, so a machine
//! without it fails to build, and the maintained ones (`embree4-sys`, `embree4-rs`) need
//! Embree 4, which Debian does not ship.
//!
//! The ~15 functions used here are declared from Embree 3's `rtcore_*.h` (the public C API):
//! one triangle geometry per scene holding the whole [`Mesh`] (so `primID` is the mesh's
//! triangle index), `rtcIntersect1` / `rtcOccluded1` one ray at a time with an incoherent
//! intersection context, as a renderer calling Embree from Rust would.
#![allow(dead_code)]

use std::ffi::{CString, c_char, c_int, c_uint, c_void};
use std::sync::OnceLock;

use glam::Vec2;
use kdtree_tracer::{Hit, Mesh, Ray, RayQuery};
use libloading::Library;

type Device = *mut c_void;
type Scene = *mut c_void;
type Geometry = *mut c_void;

/// `RTC_SCENE_FLAG_ROBUST`: "avoid optimizations that reduce arithmetic accuracy".
const SCENE_FLAG_ROBUST: c_int = 1 << 2;
const GEOMETRY_TYPE_TRIANGLE: c_int = 0;
const BUFFER_TYPE_INDEX: c_int = 0;
const BUFFER_TYPE_VERTEX: c_int = 1;
const FORMAT_UINT3: c_int = 0x5003;
const FORMAT_FLOAT3: c_int = 0x9003;
const DEVICE_PROPERTY_VERSION_MAJOR: c_int = 1;
const DEVICE_PROPERTY_VERSION: c_int = 0;
const INVALID_GEOMETRY_ID: c_uint = u32::MAX;

/// `struct RTCRayHit` (Embree 3, `RTC_MAX_INSTANCE_LEVEL_COUNT` 1): the ray, then the hit.
#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct RayHit {
    org: [f32; 3],
    tnear: f32,
    dir: [f32; 3],
    time: f32,
    tfar: f32,
    mask: c_uint,
    id: c_uint,
    flags: c_uint,
    ng: [f32; 3],
    u: f32,
    v: f32,
    prim_id: c_uint,
    geom_id: c_uint,
    inst_id: [c_uint; 1],
}

const _: () = assert!(std::mem::size_of::<RayHit>() == 80);

/// `struct RTCIntersectContext` (Embree 3, one instance level, no minimum width).
#[repr(C)]
struct Context {
    flags: c_int,
    filter: *const c_void,
    inst_id: [c_uint; 1],
}

impl Context {
    /// `rtcInitIntersectContext`: incoherent rays, no filter, no instance.
    fn incoherent() -> Self {
        Self { flags: 0, filter: std::ptr::null(), inst_id: [INVALID_GEOMETRY_ID] }
    }
}

/// The entry points, resolved once.
struct Api {
    new_device: unsafe extern "C" fn(*const c_char) -> Device,
    release_device: unsafe extern "C" fn(Device),
    device_error: unsafe extern "C" fn(Device) -> c_int,
    device_property: unsafe extern "C" fn(Device, c_int) -> isize,
    new_scene: unsafe extern "C" fn(Device) -> Scene,
    set_scene_flags: unsafe extern "C" fn(Scene, c_int),
    commit_scene: unsafe extern "C" fn(Scene),
    release_scene: unsafe extern "C" fn(Scene),
    new_geometry: unsafe extern "C" fn(Device, c_int) -> Geometry,
    new_buffer: unsafe extern "C" fn(Geometry, c_int, c_uint, c_int, usize, usize) -> *mut c_void,
    commit_geometry: unsafe extern "C" fn(Geometry),
    attach_geometry: unsafe extern "C" fn(Scene, Geometry) -> c_uint,
    release_geometry: unsafe extern "C" fn(Geometry),
    intersect1: unsafe extern "C" fn(Scene, *mut Context, *mut RayHit),
    occluded1: unsafe extern "C" fn(Scene, *mut Context, *mut RayHit),
}

/// An Embree device: the opened library and one `RTCDevice` whose builds use `threads`
/// threads (queries run on the caller's threads).
pub struct Embree {
    api: Api,
    device: Device,
    threads: usize,
    version: String,
}

/// The library, opened once and never closed: Embree's TBB worker threads outlive its devices,
/// and unmapping their code under them crashes the process.
fn library() -> Result<&'static Library, String> {
    static LIB: OnceLock<Result<Library, String>> = OnceLock::new();
    LIB.get_or_init(|| {
        let names: Vec<String> = match std::env::var("EMBREE_LIB") {
            Ok(p) => vec![p],
            Err(_) => vec!["libembree3.so.3".into(), "libembree3.so".into()],
        };
        let mut why = Vec::new();
        names
            .iter()
            .find_map(|n| {
                // SAFETY: loading Embree runs its (and TBB's) initialisers, which have no
                // preconditions.
                unsafe { Library::new(n) }.map_err(|e| why.push(format!("{n}: {e}"))).ok()
            })
            .ok_or_else(|| why.join("; "))
    })
    .as_ref()
    .map_err(Clone::clone)
}

// SAFETY: an Embree device may be used from any thread (Embree's API is thread-safe for
// creating scenes and tracing committed ones).
unsafe impl Send for Embree {}
unsafe impl Sync for Embree {}

/// How a scene is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// `RTC_SCENE_FLAG_ROBUST`: watertight traversal, no accuracy-reducing optimisations.
    Robust,
    /// Embree's defaults (no scene flags, medium build quality): its fastest tracing.
    Default,
}

impl Mode {
    pub const ALL: [Mode; 2] = [Mode::Robust, Mode::Default];

    pub fn name(self) -> &'static str {
        match self {
            Mode::Robust => "robust",
            Mode::Default => "default",
        }
    }
}

impl Embree {
    /// Opens the library (`EMBREE_LIB`, else `libembree3.so.3`, else `libembree3.so`) and
    /// makes a device building with `threads` threads. The error says what was tried.
    pub fn new(threads: usize) -> Result<Self, String> {
        let lib = library()?;
        // SAFETY: each symbol is given the signature Embree 3's rtcore headers declare.
        let api = unsafe {
            macro_rules! sym {
                ($name:literal) => {
                    *lib.get(concat!($name, "\0").as_bytes())
                        .map_err(|e| format!("{}: {e}", $name))?
                };
            }
            Api {
                new_device: sym!("rtcNewDevice"),
                release_device: sym!("rtcReleaseDevice"),
                device_error: sym!("rtcGetDeviceError"),
                device_property: sym!("rtcGetDeviceProperty"),
                new_scene: sym!("rtcNewScene"),
                set_scene_flags: sym!("rtcSetSceneFlags"),
                commit_scene: sym!("rtcCommitScene"),
                release_scene: sym!("rtcReleaseScene"),
                new_geometry: sym!("rtcNewGeometry"),
                new_buffer: sym!("rtcSetNewGeometryBuffer"),
                commit_geometry: sym!("rtcCommitGeometry"),
                attach_geometry: sym!("rtcAttachGeometry"),
                release_geometry: sym!("rtcReleaseGeometry"),
                intersect1: sym!("rtcIntersect1"),
                occluded1: sym!("rtcOccluded1"),
            }
        };
        let config = CString::new(format!("threads={},verbose=0", threads.max(1)))
            .map_err(|e| e.to_string())?;
        // SAFETY: a valid C string; a null device is handled below.
        let device = unsafe { (api.new_device)(config.as_ptr()) };
        if device.is_null() {
            return Err("rtcNewDevice failed (unsupported CPU?)".into());
        }
        // SAFETY: a live device.
        let (major, packed) = unsafe {
            (
                (api.device_property)(device, DEVICE_PROPERTY_VERSION_MAJOR),
                (api.device_property)(device, DEVICE_PROPERTY_VERSION),
            )
        };
        let embree = Self {
            version: format!("{}.{}.{}", packed / 10000, packed / 100 % 100, packed % 100),
            api,
            device,
            threads: threads.max(1),
        };
        if major != 3 {
            return Err(format!("Embree {} found; this binding speaks Embree 3", embree.version));
        }
        Ok(embree)
    }

    /// `Embree::new`, or `None` after printing why the races leave Embree out.
    pub fn or_explain(threads: usize) -> Option<Self> {
        match Self::new(threads) {
            Ok(e) => Some(e),
            Err(why) => {
                eprintln!(
                    "embree: left out of the race, the library did not open ({why}); install \
                     it with `apt-get install libembree3-3` (Debian) or set EMBREE_LIB"
                );
                None
            }
        }
    }

    /// "3.13.5".
    pub fn version(&self) -> &str {
        &self.version
    }

    /// Threads its builds use.
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// A committed scene of `mesh` (one triangle geometry), built in `mode`.
    pub fn scene(&self, mesh: &Mesh, mode: Mode) -> Result<EmbreeScene<'_>, String> {
        let (p, idx) = (mesh.positions(), mesh.indices());
        let a = &self.api;
        // SAFETY: Embree 3's documented sequence; the buffers it returns hold `itemCount`
        // items of the stated stride (plus its own padding) and are filled before the commit.
        unsafe {
            let scene = (a.new_scene)(self.device);
            if scene.is_null() {
                return Err(self.error("rtcNewScene"));
            }
            let out = EmbreeScene { embree: self, scene };
            if mode == Mode::Robust {
                (a.set_scene_flags)(scene, SCENE_FLAG_ROBUST);
            }
            let geom = (a.new_geometry)(self.device, GEOMETRY_TYPE_TRIANGLE);
            if geom.is_null() {
                return Err(self.error("rtcNewGeometry"));
            }
            let v = (a.new_buffer)(geom, BUFFER_TYPE_VERTEX, 0, FORMAT_FLOAT3, 12, p.len());
            let i = (a.new_buffer)(geom, BUFFER_TYPE_INDEX, 0, FORMAT_UINT3, 12, idx.len());
            if v.is_null() || i.is_null() {
                (a.release_geometry)(geom);
                return Err(self.error("rtcSetNewGeometryBuffer"));
            }
            let v = std::slice::from_raw_parts_mut(v.cast::<[f32; 3]>(), p.len());
            for (d, s) in v.iter_mut().zip(p) {
                *d = s.to_array();
            }
            std::slice::from_raw_parts_mut(i.cast::<[u32; 3]>(), idx.len()).copy_from_slice(idx);
            (a.commit_geometry)(geom);
            (a.attach_geometry)(scene, geom);
            (a.release_geometry)(geom);
            (a.commit_scene)(scene);
            match (a.device_error)(self.device) {
                0 => Ok(out),
                e => Err(format!("rtcCommitScene: RTCError {e}")),
            }
        }
    }

    fn error(&self, what: &str) -> String {
        // SAFETY: a live device.
        format!("{what} failed: RTCError {}", unsafe { (self.api.device_error)(self.device) })
    }
}

impl Drop for Embree {
    fn drop(&mut self) {
        // SAFETY: the device is live and every scene borrowing it has been dropped.
        unsafe { (self.api.release_device)(self.device) }
    }
}

/// A committed Embree scene answering the crate's [`RayQuery`].
pub struct EmbreeScene<'a> {
    embree: &'a Embree,
    scene: Scene,
}

// SAFETY: a committed Embree scene may be traced from several threads at once.
unsafe impl Send for EmbreeScene<'_> {}
unsafe impl Sync for EmbreeScene<'_> {}

impl Drop for EmbreeScene<'_> {
    fn drop(&mut self) {
        // SAFETY: the scene is live and no query is running (we hold it uniquely).
        unsafe { (self.embree.api.release_scene)(self.scene) }
    }
}

impl EmbreeScene<'_> {
    fn ray_hit(ray: &Ray, t_max: f32) -> RayHit {
        RayHit {
            org: ray.origin.to_array(),
            tnear: ray.t_min.max(0.0),
            dir: ray.dir.to_array(),
            time: 0.0,
            tfar: t_max,
            mask: u32::MAX,
            id: 0,
            flags: 0,
            ng: [0.0; 3],
            u: 0.0,
            v: 0.0,
            prim_id: INVALID_GEOMETRY_ID,
            geom_id: INVALID_GEOMETRY_ID,
            inst_id: [INVALID_GEOMETRY_ID],
        }
    }
}

impl RayQuery for EmbreeScene<'_> {
    /// `Hit::mesh` is 0: the triangle index is the mesh's, its mesh id is `Mesh::mesh_of`.
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let in_order = ray.t_min.max(0.0) <= t_max;
        if !ray.is_valid() || !in_order {
            return None;
        }
        let mut rh = Self::ray_hit(ray, t_max);
        let mut ctx = Context::incoherent();
        // SAFETY: a committed scene, an initialised context and an aligned ray-hit.
        unsafe { (self.embree.api.intersect1)(self.scene, &mut ctx, &mut rh) };
        (rh.geom_id != INVALID_GEOMETRY_ID).then(|| Hit {
            t: rh.tfar,
            triangle: rh.prim_id,
            mesh: 0,
            barycentrics: Vec2::new(rh.u, rh.v),
        })
    }

    #[inline]
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let in_order = ray.t_min.max(0.0) <= t_max;
        if !ray.is_valid() || !in_order {
            return false;
        }
        let mut rh = Self::ray_hit(ray, t_max);
        let mut ctx = Context::incoherent();
        // SAFETY: as above; `rtcOccluded1` reads the ray part and sets `tfar` to -inf on a hit.
        unsafe { (self.embree.api.occluded1)(self.scene, &mut ctx, &mut rh) };
        rh.tfar == f32::NEG_INFINITY
    }
}

/// Tolerance on `t` when two tracers' hits are compared: `T_TOLERANCE` of the distance plus
/// `T_TOLERANCE / 10` of the ray origin's magnitude (over the direction's length), for hits
/// close to the origin. Both tracers are exact to a few ulps of the hit point's coordinates;
/// a wrong surface is off by far more.
pub const T_TOLERANCE: f32 = 1e-4;

fn t_close(ray: &Ray, a: f32, b: f32) -> bool {
    let near = 0.1 * T_TOLERANCE * (1.0 + ray.origin.abs().max_element()) / ray.dir.length();
    (a - b).abs() <= T_TOLERANCE * a.abs().max(b.abs()) + near
}

/// How two tracers' closest hits differ over `rays` (all queried to infinity).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Agreement {
    pub rays: usize,
    /// Rays one tracer hits and the other misses.
    pub hit_miss: usize,
    /// Rays both hit at distances further apart than [`T_TOLERANCE`] allows.
    pub t_beyond: usize,
    /// Largest relative `t` difference among the rays both hit.
    pub max_rel_t: f32,
}

impl Agreement {
    pub fn of(
        ours: &(impl RayQuery + ?Sized),
        theirs: &(impl RayQuery + ?Sized),
        rays: &[Ray],
    ) -> Self {
        use rayon::prelude::*;
        rays.par_chunks(4096)
            .map(|c| {
                let mut a = Agreement { rays: c.len(), ..Self::default() };
                for r in c {
                    match (ours.intersect(r, f32::INFINITY), theirs.intersect(r, f32::INFINITY)) {
                        (None, None) => {}
                        (Some(x), Some(y)) => {
                            let rel = (x.t - y.t).abs() / x.t.abs().max(y.t.abs()).max(1e-30);
                            a.max_rel_t = a.max_rel_t.max(rel);
                            a.t_beyond += usize::from(!t_close(r, x.t, y.t));
                        }
                        _ => a.hit_miss += 1,
                    }
                }
                a
            })
            .reduce(Self::default, |a, b| Agreement {
                rays: a.rays + b.rays,
                hit_miss: a.hit_miss + b.hit_miss,
                t_beyond: a.t_beyond + b.t_beyond,
                max_rel_t: a.max_rel_t.max(b.max_rel_t),
            })
    }

    /// Exact hit/miss agreement and every `t` within tolerance.
    pub fn exact(&self) -> bool {
        self.hit_miss == 0 && self.t_beyond == 0
    }

    /// "hits checked against the kd-tree's on all 40000 rays: 0 hit/miss disagreements, 0 t
    /// beyond tolerance (1e-4 relative; largest relative difference 3.1e-7)".
    pub fn describe(&self) -> String {
        format!(
            "hits checked against the kd-tree's on all {} rays: {} hit/miss disagreements, {} t \
             beyond tolerance ({T_TOLERANCE:e} relative; largest relative difference {:.1e})",
            self.rays, self.hit_miss, self.t_beyond, self.max_rel_t
        )
    }
}

/// "Embree 3.13.5 (system library, ...)", for notes.
pub fn describe(e: &Embree) -> String {
    format!(
        "Embree {} (the system library opened at run time, rtcIntersect1 one ray at a time, \
         medium build quality, build threads {})",
        e.version(),
        e.threads()
    )
}
