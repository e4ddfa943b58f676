//! What the damaged-volume scan of a history row
//! ([`crate::element::groups::ElementGroup::damaged_volume`], every row, every step by
//! default) keeps between rows: its chunk sums, so that a row allocates nothing, and for
//! every element whether each of its integration points (or the element's mean) had D_t
//! and D_c at or above the threshold when its state was last read, with a mark the force
//! kernel sets when an element's hardening variables move. An element whose y_t, y_c have
//! not moved since its state was read has the same D_t, D_c (eq. 24: functions of y
//! alone), so the scan adds its volumes from the kept answers without reading its state
//! again: the same points in the same order and the same additions, so bit for bit the
//! sums of reading every state.
//!
//! The kept answers are used only while the group's passes update the states in place
//! (the explicit core: every pass commits). A buffered pass (the static stage's trials)
//! writes a pending state that may be discarded or committed after a scan, so there every
//! state is read; and every other change of the states (restored from a checkpoint,
//! replaced by the static stage, a switch between the modes) makes the group call
//! [`DamageScan::forget`].

use rayon::prelude::*;
use std::sync::Mutex;

use crate::element::damage_marks::DamageMarks;

/// Points per element whose answers are kept (2 bits each in a `u16`); the points of a
/// larger rule are read at every row.
pub const KNOWN_POINTS: usize = 8;

/// What the kept answers were computed for: the threshold's bits and whether the scan
/// counts points or element means.
type ScanKey = (u64, bool);

#[derive(Clone, Debug, Default)]
struct Memory {
    key: Option<ScanKey>,
    /// One sum per chunk of the last scan.
    partial: Vec<[f64; 3]>,
    /// Per element: bit 2g (2g + 1) set when point g had D_t (D_c) at or above the
    /// threshold when last read; for element means, bits 0 and 1.
    known: Vec<u16>,
}

/// The scan's memory between history rows (module docs).
#[derive(Debug, Default)]
pub struct DamageScan {
    memory: Mutex<Memory>,
    /// Elements whose hardening variables may have moved since their state was last
    /// read by a scan (all of them at first and after [`DamageScan::forget`]).
    changed: DamageMarks,
}

impl Clone for DamageScan {
    fn clone(&self) -> Self {
        Self {
            memory: Mutex::new(self.lock().clone()),
            changed: self.changed.clone(),
        }
    }
}

impl DamageScan {
    /// The memory of a group of `elements` elements: nothing known yet.
    pub fn new(elements: usize) -> Self {
        Self {
            memory: Mutex::default(),
            changed: DamageMarks::from_fn(elements, |_| true),
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Memory> {
        // Every scan rewrites the sums it returns; a scan that panicked midway may have
        // cleared marks of elements whose answers it did not store, so the memory is
        // dropped.
        match self.memory.lock() {
            Ok(m) => m,
            Err(poisoned) => {
                let mut m = poisoned.into_inner();
                m.key = None;
                m
            }
        }
    }

    /// The marks the force kernel sets on an element whose y_t or y_c moved.
    pub fn changes(&self) -> &DamageMarks {
        &self.changed
    }

    /// Forget every kept answer: after the states were changed other than by an
    /// in-place force pass.
    pub fn forget(&mut self) {
        let n = self.changed.len();
        self.changed = DamageMarks::from_fn(n, |_| true);
        let memory = self.memory.get_mut().unwrap_or_else(|p| p.into_inner());
        memory.key = None;
    }

    /// Element `le`'s kept answers are still true (its hardening has not moved since they
    /// were stored); clears its mark, so the caller must store fresh answers when false.
    #[inline]
    pub fn unchanged(&self, le: usize) -> bool {
        !self.changed.take(le)
    }

    /// Σ over the chunks of `chunk` elements (of the scan's elements) of
    /// `chunk_sum(c, known)`, the chunks computed in parallel and added in the order
    /// c = 0, 1, … ([`add_in_order`]: the same sums on any number of threads); `known` is
    /// chunk c's slice of the kept answers for `threshold` and `per_element` (module
    /// docs). When these differ from the last scan's, every element is marked changed
    /// first. Allocates only at a group's first scan.
    pub fn sum_in_order(
        &self,
        chunk: usize,
        threshold: f64,
        per_element: bool,
        chunk_sum: impl Fn(usize, &mut [u16]) -> [f64; 3] + Sync,
    ) -> [f64; 3] {
        let mut memory = self.lock();
        let Memory {
            key,
            partial,
            known,
        } = &mut *memory;
        let elements = self.changed.len();
        let this = (threshold.to_bits(), per_element);
        if *key != Some(this) || known.len() != elements {
            known.clear();
            known.resize(elements, 0);
            for le in 0..self.changed.len() {
                self.changed.mark(le);
            }
            *key = Some(this);
        }
        let chunks = elements.div_ceil(chunk.max(1));
        if partial.len() < chunks {
            partial.resize(chunks, [0.0; 3]);
        }
        partial[..chunks]
            .par_iter_mut()
            .zip(known.par_chunks_mut(chunk.max(1)))
            .enumerate()
            .for_each(|(c, (sum, known))| *sum = chunk_sum(c, known));
        add_in_order(&partial[..chunks])
    }
}

/// Σ of the chunk sums `partial`, added in their order c = 0, 1, … (how every damaged
/// volume is summed, with or without kept answers).
pub fn add_in_order(partial: &[[f64; 3]]) -> [f64; 3] {
    partial
        .iter()
        .fold([0.0; 3], |a, p| std::array::from_fn(|k| a[k] + p[k]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_in_chunk_order_and_keeps_answers_per_threshold() {
        let scan = DamageScan::new(37);
        let chunk_sum = |c: usize, known: &mut [u16]| {
            for k in known.iter_mut() {
                *k += 1;
            }
            [c as f64, 0.1 * c as f64, known.len() as f64]
        };
        let expected = (0..5).fold([0.0; 3], |a: [f64; 3], c| {
            let l = if c < 4 { 8.0 } else { 5.0 };
            [a[0] + c as f64, a[1] + 0.1 * c as f64, a[2] + l]
        });
        // At first every element is changed; the marks clear as they are taken.
        assert!(!scan.unchanged(3) && scan.unchanged(3));
        // The first scan marks every element changed (nothing is known).
        assert_eq!(scan.sum_in_order(8, 0.1, false, chunk_sum), expected);
        assert!((0..37).all(|le| !scan.unchanged(le)));
        // The answers carry over to the next scan of the same threshold …
        scan.changes().mark(5);
        scan.sum_in_order(8, 0.1, false, |_, known| {
            assert!(known.iter().all(|&k| k == 1));
            [0.0; 3]
        });
        assert!(!scan.unchanged(5) && scan.unchanged(6));
        // … not to another threshold, nor to element means (every element marked
        // changed), nor after `forget`.
        scan.sum_in_order(8, 0.2, false, |_, known| {
            assert!(known.iter().all(|&k| k == 0));
            known.fill(5);
            [0.0; 3]
        });
        assert!(!scan.unchanged(6) && scan.unchanged(6));
        scan.sum_in_order(8, 0.2, true, |_, known| {
            assert!(known.iter().all(|&k| k == 0));
            [0.0; 3]
        });
        let mut forgetful = scan.clone();
        forgetful.forget();
        assert!(!forgetful.unchanged(7) && scan.changes().is_marked(7));
        forgetful.sum_in_order(8, 0.2, true, |_, known| {
            assert!(known.iter().all(|&k| k == 0));
            [0.0; 3]
        });
    }
}
