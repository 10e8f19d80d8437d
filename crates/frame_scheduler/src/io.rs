//! What a pass body sees: its frame context, its inputs, its outputs, its unit of work.

use crate::error::ResourceError;
use crate::handle::Res;
use std::any::Any;
use std::sync::{Arc, Mutex, MutexGuard};

pub(crate) type Value = Arc<dyn Any + Send + Sync>;

/// The values of every resource, persisting across frames (that is how outputs are reused).
pub(crate) struct Store {
    slots: Mutex<Vec<Option<Value>>>,
}

impl Store {
    pub(crate) fn new(n: usize) -> Self {
        Self { slots: Mutex::new(vec![None; n]) }
    }

    pub(crate) fn lock(&self) -> MutexGuard<'_, Vec<Option<Value>>> {
        self.slots.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// Unit `index` of an amortised pass whose cycle has `total` units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unit {
    pub index: u32,
    pub total: u32,
}

/// Why a resource a pass reads is not available this frame (filled by the planner).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Availability {
    Active,
    /// Its producer (pass index) is skipped this frame.
    ProducerSkipped(u32),
    /// An external input that was never set.
    InputUnset,
}

/// The names a pass needs to word its errors, shared by every pass of a graph.
pub(crate) struct Names<'a> {
    pub passes: &'a [String],
    pub resources: &'a [String],
}

/// The interface of a pass body to the graph: read declared inputs, store declared outputs.
///
/// Values persist across frames: a reused pass leaves its outputs in place, and a pass may
/// [`take_previous`](Self::take_previous) to update last frame's value in place.
pub struct PassIo<'a, C> {
    pub(crate) ctx: &'a C,
    pub(crate) pass: usize,
    pub(crate) graph: u32,
    pub(crate) reads: &'a [u32],
    pub(crate) writes: &'a [u32],
    pub(crate) values: &'a [Option<Value>],
    pub(crate) availability: &'a [Availability],
    pub(crate) store: &'a Store,
    pub(crate) names: &'a Names<'a>,
    pub(crate) unit: Option<Unit>,
}

impl<'a, C> PassIo<'a, C> {
    /// The frame context the schedule was run with.
    pub fn ctx(&self) -> &'a C {
        self.ctx
    }

    /// The name of the running pass.
    pub fn pass_name(&self) -> &str {
        &self.names.passes[self.pass]
    }

    /// For an amortised pass, the unit this call must do; `None` for ordinary passes.
    pub fn unit(&self) -> Option<Unit> {
        self.unit
    }

    fn check<T>(&self, res: Res<T>) -> Result<(), ResourceError> {
        if res.graph != self.graph {
            return Err(ResourceError::ForeignHandle { pass: self.pass_name().to_owned() });
        }
        Ok(())
    }

    fn resource_name(&self, index: u32) -> String {
        self.names.resources[index as usize].clone()
    }

    /// The value of an input declared with [`reads`](crate::PassBuilder::reads).
    ///
    /// Errors when the pass did not declare the read, when the producer is skipped this frame
    /// (its condition is false), or when no value was ever stored.
    pub fn read<T: Any + Send + Sync>(&self, res: Res<T>) -> Result<&T, ResourceError> {
        self.check(res)?;
        let Some(slot) = self.reads.iter().position(|&r| r == res.index) else {
            return Err(ResourceError::Undeclared {
                pass: self.pass_name().to_owned(),
                resource: self.resource_name(res.index),
                access: "reads",
            });
        };
        match self.availability[res.index as usize] {
            Availability::Active => {}
            Availability::ProducerSkipped(p) => {
                return Err(ResourceError::Inactive {
                    resource: self.resource_name(res.index),
                    why: format!("its producer '{}' is skipped", self.names.passes[p as usize]),
                });
            }
            Availability::InputUnset => {
                return Err(ResourceError::Inactive {
                    resource: self.resource_name(res.index),
                    why: "the external input was never set".to_owned(),
                });
            }
        }
        self.values[slot]
            .as_deref()
            .and_then(|v| v.downcast_ref::<T>())
            .ok_or_else(|| ResourceError::Empty { resource: self.resource_name(res.index) })
    }

    /// Like [`read`](Self::read), but `None` for any reason it would fail (an optional input).
    pub fn try_read<T: Any + Send + Sync>(&self, res: Res<T>) -> Option<&T> {
        self.read(res).ok()
    }

    fn check_write<T>(&self, res: Res<T>) -> Result<(), ResourceError> {
        self.check(res)?;
        if self.writes.contains(&res.index) {
            Ok(())
        } else {
            Err(ResourceError::Undeclared {
                pass: self.pass_name().to_owned(),
                resource: self.resource_name(res.index),
                access: "writes",
            })
        }
    }

    /// Stores the new value of an output declared with [`writes`](crate::PassBuilder::writes).
    pub fn put<T: Any + Send + Sync>(
        &mut self,
        res: Res<T>,
        value: T,
    ) -> Result<(), ResourceError> {
        self.check_write(res)?;
        self.store.lock()[res.index as usize] = Some(Arc::new(value));
        Ok(())
    }

    /// Takes the output's current value (last frame's, or an earlier unit's) to update it in
    /// place; `None` when there is none or somebody outside the graph still holds it (see
    /// [`Scheduler::get`](crate::Scheduler::get)). Store it back with [`put`](Self::put).
    pub fn take_previous<T: Any + Send + Sync>(
        &mut self,
        res: Res<T>,
    ) -> Result<Option<T>, ResourceError> {
        self.check_write(res)?;
        let mut store = self.store.lock();
        let slot = &mut store[res.index as usize];
        let Some(value) = slot.take() else { return Ok(None) };
        match value.downcast::<T>() {
            Ok(typed) => match Arc::try_unwrap(typed) {
                Ok(v) => Ok(Some(v)),
                Err(shared) => {
                    *slot = Some(shared);
                    Ok(None)
                }
            },
            Err(other) => {
                *slot = Some(other);
                Ok(None)
            }
        }
    }

    /// Updates an output in place: takes its previous value (or `T::default()`), applies `f`
    /// and stores it back.
    pub fn update<T: Any + Send + Sync + Default>(
        &mut self,
        res: Res<T>,
        f: impl FnOnce(&mut T),
    ) -> Result<(), ResourceError> {
        let mut v = self.take_previous(res)?.unwrap_or_default();
        f(&mut v);
        self.put(res, v)
    }
}
