//! Invalidation keys: values whose change makes a pass's output stale, and helpers to quantise
//! continuous inputs (a sun direction) so that tiny changes do not count.

use std::any::Any;

/// One invalidation key of a pass: evaluated every frame the pass is live, compared with the
/// value it had when the pass last (re)started.
pub(crate) trait KeySlot<C>: Send {
    fn label(&self) -> &str;
    /// Evaluates the key; true when it differs from the committed value (or none is committed).
    fn changed(&mut self, ctx: &C) -> bool;
    /// Makes the value last evaluated the committed one.
    fn commit(&mut self);
    /// Hands the committed value over (to the same key of a rebuilt graph).
    fn take_committed(&mut self) -> Option<Box<dyn Any + Send>>;
    /// Takes over a committed value of a previous graph, if it has this key's type.
    fn adopt(&mut self, value: Box<dyn Any + Send>);
}

pub(crate) struct Key<K, F> {
    label: String,
    f: F,
    committed: Option<K>,
    pending: Option<K>,
}

impl<K, F> Key<K, F> {
    pub(crate) fn new(label: String, f: F) -> Self {
        Self { label, f, committed: None, pending: None }
    }
}

impl<C, K, F> KeySlot<C> for Key<K, F>
where
    K: PartialEq + Send + 'static,
    F: Fn(&C) -> K + Send + 'static,
{
    fn label(&self) -> &str {
        &self.label
    }

    fn changed(&mut self, ctx: &C) -> bool {
        let now = (self.f)(ctx);
        let changed = self.committed.as_ref() != Some(&now);
        self.pending = Some(now);
        changed
    }

    fn commit(&mut self) {
        if let Some(v) = self.pending.take() {
            self.committed = Some(v);
        }
    }

    fn take_committed(&mut self) -> Option<Box<dyn Any + Send>> {
        self.committed.take().map(|v| Box::new(v) as Box<dyn Any + Send>)
    }

    fn adopt(&mut self, value: Box<dyn Any + Send>) {
        if let Ok(v) = value.downcast::<K>() {
            self.committed = Some(*v);
        }
    }
}

/// Quantises `value` to multiples of `step`: two values in the same bucket give the same key.
///
/// A non-positive or non-finite `step` compares exact bit patterns instead (every change
/// counts); a NaN value maps to `i64::MIN` so it is a key like any other and never panics.
pub fn quantise(value: f32, step: f32) -> i64 {
    if value.is_nan() {
        return i64::MIN;
    }
    if step <= 0.0 || !step.is_finite() {
        return i64::from(value.to_bits());
    }
    // `as` saturates for huge quotients: still a valid, deterministic key.
    (f64::from(value) / f64::from(step)).round() as i64
}

/// Quantises a direction component-wise (see [`quantise`]); `step` is in the units of the
/// components (for a unit vector, about the angle in radians).
pub fn quantise_dir(dir: [f32; 3], step: f32) -> [i64; 3] {
    dir.map(|c| quantise(c, step))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantise_buckets_and_odd_inputs() {
        assert_eq!(quantise(0.101, 0.01), quantise(0.099, 0.01));
        assert_ne!(quantise(0.10, 0.01), quantise(0.12, 0.01));
        assert_eq!(quantise(f32::NAN, 0.1), i64::MIN);
        assert_ne!(quantise(1.0, 0.0), quantise(1.0000001, 0.0));
        assert_eq!(quantise(f32::INFINITY, 0.1), i64::MAX);
        assert_eq!(quantise_dir([0.0, 1.0, 0.0], 0.5), [0, 2, 0]);
    }

    #[test]
    fn key_changes_only_against_the_committed_value() {
        let mut k = Key::new("x".into(), |c: &i32| *c / 10);
        assert!(KeySlot::<i32>::changed(&mut k, &5));
        k.commit();
        assert!(!KeySlot::<i32>::changed(&mut k, &7));
        assert!(KeySlot::<i32>::changed(&mut k, &15));
        // not committed: still compares with the old value
        assert!(KeySlot::<i32>::changed(&mut k, &15));
        k.commit();
        assert!(!KeySlot::<i32>::changed(&mut k, &19));
    }
}
