//! Which elements of a group may hold damage: the damaged-volume scan of a history row
//! ([`crate::element::groups::ElementGroup::damaged_volume`]) visits these elements only.
//!
//! A point with y_t = y_c = 0 has D_t = D_c = 0 exactly (eq. 24, `Hardening::damage`), so
//! an element none of whose points has yielded adds nothing to a damaged volume whose
//! threshold is above zero. The force kernel marks an element when it writes a state with
//! a yielded point; every other change of the states (built, restored from a checkpoint,
//! replaced by the static stage) recomputes the marks from the states. Marks are never
//! cleared by a pass: a mark set by a trial pass that is later discarded only costs the
//! scan a visit, the marked set is always a superset of the damaged elements, and the
//! scan's sums (the same additions in the same order) are bit for bit those of a scan of
//! every element.

use std::sync::atomic::{AtomicBool, Ordering};

/// One flag per element of a group (in the group's order).
#[derive(Debug, Default)]
pub struct DamageMarks(Vec<AtomicBool>);

impl Clone for DamageMarks {
    fn clone(&self) -> Self {
        Self(
            self.0
                .iter()
                .map(|m| AtomicBool::new(m.load(Ordering::Relaxed)))
                .collect(),
        )
    }
}

impl DamageMarks {
    /// Marks of `n` elements, element `le` marked when `marked(le)`.
    pub fn from_fn(n: usize, marked: impl Fn(usize) -> bool) -> Self {
        Self((0..n).map(|le| AtomicBool::new(marked(le))).collect())
    }

    /// Mark element `le` (from any thread; a load first, so that an element marked long
    /// ago costs its cache line no write).
    #[inline]
    pub fn mark(&self, le: usize) {
        let m = &self.0[le];
        if !m.load(Ordering::Relaxed) {
            m.store(true, Ordering::Relaxed);
        }
    }

    /// Element `le` is marked.
    #[inline]
    pub fn is_marked(&self, le: usize) -> bool {
        self.0[le].load(Ordering::Relaxed)
    }

    /// Element `le` was marked; the mark is cleared (a load first: no write when it was
    /// not marked).
    #[inline]
    pub fn take(&self, le: usize) -> bool {
        let m = &self.0[le];
        m.load(Ordering::Relaxed) && m.swap(false, Ordering::Relaxed)
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// No elements.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Number of marked elements.
    pub fn count(&self) -> usize {
        self.0.iter().filter(|m| m.load(Ordering::Relaxed)).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marks_are_set_once_and_survive_a_clone() {
        let m = DamageMarks::from_fn(5, |le| le == 3);
        assert!(m.is_marked(3) && !m.is_marked(0));
        m.mark(1);
        m.mark(1);
        assert_eq!(m.count(), 2);
        let c = m.clone();
        assert!(c.is_marked(1) && c.is_marked(3) && !c.is_marked(4));
        assert!(m.take(1) && !m.take(1) && !m.take(0));
        assert!(!m.is_marked(1) && c.is_marked(1));
    }
}
