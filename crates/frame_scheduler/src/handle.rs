//! Typed handles: resources and passes are named by values the compiler checks, never by
//! strings looked up at run time.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::hash::{Hash, Hasher};
use std::marker::PhantomData;
use std::sync::atomic::{AtomicU32, Ordering};

static NEXT_GRAPH: AtomicU32 = AtomicU32::new(1);

/// A fresh identifier for a new graph, so that a handle used with the wrong graph is caught.
pub(crate) fn next_graph_id() -> u32 {
    NEXT_GRAPH.fetch_add(1, Ordering::Relaxed)
}

/// A resource of type `T` declared in one [`FrameGraph`](crate::FrameGraph).
///
/// It is `Copy`, carries its value type, and is the only way to name the resource: a pass that
/// reads `Res<SkyVolume>` gets a `&SkyVolume`, and a misspelt handle does not compile.
pub struct Res<T> {
    pub(crate) index: u32,
    pub(crate) graph: u32,
    _t: PhantomData<fn() -> T>,
}

impl<T> Res<T> {
    pub(crate) fn new(index: u32, graph: u32) -> Self {
        Self { index, graph, _t: PhantomData }
    }

    /// The untyped identity of this resource.
    pub fn id(self) -> ResourceId {
        ResourceId { index: self.index, graph: self.graph }
    }
}

impl<T> Clone for Res<T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Res<T> {}
impl<T> PartialEq for Res<T> {
    fn eq(&self, other: &Self) -> bool {
        self.index == other.index && self.graph == other.graph
    }
}
impl<T> Eq for Res<T> {}
impl<T> Hash for Res<T> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.id().hash(state);
    }
}
impl<T> fmt::Debug for Res<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Res<{}>#{}", std::any::type_name::<T>(), self.index)
    }
}

/// The untyped identity of a resource (index in its graph).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ResourceId {
    pub(crate) index: u32,
    pub(crate) graph: u32,
}

impl ResourceId {
    /// Declaration index of the resource in its graph.
    pub fn index(self) -> usize {
        self.index as usize
    }
}

/// A pass declared in one [`FrameGraph`](crate::FrameGraph), returned by
/// [`PassBuilder::run`](crate::PassBuilder::run).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct PassId {
    pub(crate) index: u32,
    #[serde(skip)]
    pub(crate) graph: u32,
}

impl PassId {
    /// Declaration index of the pass in its graph.
    pub fn index(self) -> usize {
        self.index as usize
    }
}
