//! A frame graph for real-time renderers: run only what the frame needs, amortise the rest,
//! overlap CPU and GPU work, and report every pass's fate and cost.
//!
//! The two scheduling ideas come from the Serenity engine, a hybrid GPU rasterization + CPU
//! ray-tracing engine described in a master's thesis (sections 5.3.5 and 6.3.6): spread an expensive volume over frames, one
//! layer at a time (the sky irradiance volume, 369 ms in one go, 16 frames of one layer), and
//! trace reflections on the CPU while the GPU lights the scene, placing the two CPU/GPU
//! transfers (sync points) so that neither side stalls for long (Fig. 6.14: 42.6 ms per frame
//! instead of 68 ms in series). The third idea is to simulate only what the scene calls for:
//! passes carry `run_if` conditions and invalidation keys, and a pass whose outputs nobody
//! needs is culled. The crate knows nothing of lighting; it is the machinery. The design
//! follows frame-graph practice (O'Donnell, "FrameGraph: Extensible Rendering Architecture in
//! Frostbite", GDC 2017): declare passes with the resources they read and write, let the
//! scheduler order, cull and run them.
//!
//! * [`FrameGraph`] declares typed resources ([`Res<T>`]: a misspelt resource is a compile
//!   error, and a read returns a `&T`) and passes on three [`Lane`]s: CPU job (rayon worker),
//!   GPU submission, sync point. [`FrameGraph::build`] validates (cycles, missing producers,
//!   double writers, CPU/GPU exchanges without a sync point: [`GraphError`] names the passes)
//!   and orders the passes, launching CPU jobs early and joining them late.
//! * [`Scheduler::run_frame`] evaluates the conditions and keys against the frame context,
//!   culls, reuses the outputs of passes whose keys and inputs did not change, advances
//!   amortised passes within their [`Budget`], runs CPU jobs on worker threads while the
//!   calling thread submits GPU work, and returns a [`FrameReport`]: a markdown table, JSON
//!   (serde) and an SVG timeline with a CPU lane and a GPU lane.
//! * Build the graph once and keep the [`Scheduler`], or declare it anew each frame (when the
//!   set of passes changes) and hand it to [`Scheduler::rebuild`], which carries values, keys,
//!   input versions and amortisation progress over by name.
//! * GPU time comes from a [`GpuTimer`]: with the feature `wgpu`, `WgpuTimer` measures each
//!   GPU pass with wgpu timestamp queries; [`SimGpu`] is a simulated GPU queue and timer for
//!   tests and demos.
//!
//! ```
//! use frame_scheduler::{Budget, FrameGraph, Outcome, quantise_dir};
//!
//! struct Frame { sun_dir: [f32; 3], needs_sky_light: bool }
//! struct SkyVolume { layers_done: Vec<u32> }
//!
//! let mut graph = FrameGraph::<Frame>::new();
//! let volume = graph.resource::<SkyVolume>("sky volume");
//! let image = graph.resource::<f32>("image");
//! graph.output(image);
//!
//! // Sky volume: amortised over 16 layers, reruns when the quantised sun direction changes,
//! // runs only if the scene needs sky light.
//! let sky = graph
//!     .gpu_pass("sky volume")
//!     .writes(volume)
//!     .run_if("scene needs sky light", |f: &Frame| f.needs_sky_light)
//!     .key("sun direction", |f: &Frame| quantise_dir(f.sun_dir, 0.02))
//!     .amortised(16, Budget::Units(4))
//!     .run(move |io| {
//!         let layer = io.unit().map_or(0, |u| u.index);
//!         let mut v = io.take_previous(volume)?.unwrap_or(SkyVolume { layers_done: vec![] });
//!         if layer == 0 { v.layers_done.clear(); }
//!         v.layers_done.push(layer);
//!         io.put(volume, v)?;
//!         Ok(())
//!     });
//! graph.gpu_pass("lighting").reads(volume).writes(image).run(move |io| {
//!     let sky = io.try_read(volume).map_or(0, |v| v.layers_done.len());
//!     io.put(image, sky as f32)?;
//!     Ok(())
//! });
//!
//! let mut scheduler = graph.build()?;
//! let noon = Frame { sun_dir: [0.0, 1.0, 0.0], needs_sky_light: true };
//! for frame in 0..5 {
//!     let report = scheduler.run_frame(&noon)?;
//!     let outcome = report.pass("sky volume").unwrap().outcome;
//!     if frame < 4 {
//!         assert_eq!(outcome, Outcome::Amortised { from: 4 * frame, to: 4 * frame + 4, total: 16 });
//!     } else {
//!         assert_eq!(outcome, Outcome::Reused); // complete, and the sun did not move
//!     }
//! }
//! assert!(scheduler.progress(sky).unwrap().complete());
//! assert_eq!(*scheduler.get(image).unwrap(), 16.0);
//!
//! // No sky light needed: the volume is skipped, and the report says why.
//! let night = Frame { sun_dir: [0.0, -1.0, 0.0], needs_sky_light: false };
//! let report = scheduler.run_frame(&night)?;
//! assert_eq!(report.pass("sky volume").unwrap().outcome, Outcome::Skipped);
//! println!("{}", report.to_markdown());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
mod exec;
mod graph;
mod handle;
mod io;
mod key;
mod pass;
mod plan;
mod report;
mod scheduler;
mod sim;
mod svg;
mod timer;
#[cfg(feature = "wgpu")]
mod wgpu_timer;

pub use error::{FrameError, GraphError, PassResult, ResourceError};
pub use graph::FrameGraph;
pub use handle::{PassId, Res, ResourceId};
pub use io::{PassIo, Unit};
pub use key::{quantise, quantise_dir};
pub use pass::{Amortise, Budget, Lane, PassBuilder, Progress};
pub use report::{ExecMode, FrameReport, Outcome, PassRecord, Reason, Span};
pub use scheduler::Scheduler;
pub use sim::SimGpu;
pub use timer::{GpuSample, GpuTimer, GpuTimingSupport, NoGpuTimer};
#[cfg(feature = "wgpu")]
pub use wgpu_timer::WgpuTimer;
