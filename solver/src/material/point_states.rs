//! Per-integration-point state buffers: the committed state and, for passes that must
//! leave it untouched, a pending one.

/// Most `f64` of state one element may hold for an in-place pass
/// ([`PointStates::set_in_place`]): eight integration points of the plastic-damage model.
pub const MAX_ELEMENT_STATE: usize = 8 * crate::material::plastic_damage::STATE_LEN;

/// State of every integration point of a set of elements: `stride` values per point,
/// points of one element contiguous, elements in mesh order.
///
/// Two ways of running a force pass over it:
/// - **buffered** (the default): a pass reads the committed state and writes a pending
///   one, which [`PointStates::commit`] makes the committed one (a buffer swap). A pass
///   may be repeated from the same committed state (the static stage's trial passes).
/// - **in place** ([`PointStates::set_in_place`]): a pass commits as it goes; each element
///   copies its own state to the stack, updates from the copy and writes the committed
///   buffer. The explicit core, which commits every pass, runs this way: it reads the
///   state once and writes it back into lines already in cache, where the buffered pass
///   reads one buffer and writes the other (read for ownership, then write-back) — about
///   a third less memory traffic for the state, the largest stream of a plastic-damage
///   element, and half the memory. The same arithmetic on the same values: the results
///   are bit for bit those of the buffered pass.
#[derive(Clone, Debug, Default)]
pub struct PointStates {
    stride: usize,
    old: Vec<f64>,
    /// Pending state of a buffered pass (empty in place).
    new: Vec<f64>,
    in_place: bool,
}

/// Where a force pass reads and writes the states ([`PointStates::access`]).
#[derive(Clone, Copy, Debug)]
pub struct StateAccess {
    /// The committed states.
    pub old: *const f64,
    /// Where a pass writes (the committed states themselves in place).
    pub new: *mut f64,
    /// Values in each buffer.
    pub len: usize,
    /// The pass updates in place (each element from a copy of its own state).
    pub in_place: bool,
}

// SAFETY: a pass hands each element's slice to one thread at a time (its own slice only).
unsafe impl Send for StateAccess {}
unsafe impl Sync for StateAccess {}

impl PointStates {
    /// `n_points` points of `stride` values each, filled by `init` (one point at a time).
    pub fn new(stride: usize, n_points: usize, mut init: impl FnMut(usize, &mut [f64])) -> Self {
        let mut old = vec![0.0; stride * n_points];
        if stride > 0 {
            for (p, chunk) in old.chunks_exact_mut(stride).enumerate() {
                init(p, chunk);
            }
        }
        let new = old.clone();
        Self {
            stride,
            old,
            new,
            in_place: false,
        }
    }

    /// Values per point.
    #[inline]
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// Switch between buffered and in-place passes (see the type's documentation). Going
    /// in place frees the pending buffer, going back allocates it as a copy of the
    /// committed state; `per_element` values per element must fit
    /// [`MAX_ELEMENT_STATE`] to go in place (else the states stay buffered).
    pub fn set_in_place(&mut self, in_place: bool, per_element: usize) {
        let in_place = in_place && per_element <= MAX_ELEMENT_STATE;
        if in_place == self.in_place {
            return;
        }
        self.in_place = in_place;
        self.new = if in_place {
            Vec::new()
        } else {
            self.old.clone()
        };
    }

    /// Passes update in place.
    #[inline]
    pub fn is_in_place(&self) -> bool {
        self.in_place
    }

    /// The buffers of one force pass. Each element may read its own slice of `old` and
    /// write its own slice of `new`, and nothing else.
    #[inline]
    pub fn access(&mut self) -> StateAccess {
        let len = self.old.len();
        let old = self.old.as_mut_ptr();
        StateAccess {
            old,
            new: if self.in_place {
                old
            } else {
                self.new.as_mut_ptr()
            },
            len,
            in_place: self.in_place,
        }
    }

    /// The latest committed state (after [`PointStates::commit`], or after an in-place
    /// pass).
    #[inline]
    pub fn current(&self) -> &[f64] {
        &self.old
    }

    /// End of step: the state of the last pass becomes the committed one (nothing to do
    /// in place).
    #[inline]
    pub fn commit(&mut self) {
        if !self.in_place {
            std::mem::swap(&mut self.old, &mut self.new);
        }
    }

    /// End of a step that updated only some elements (subcycling): the new state of
    /// every element `le` (`per` values each) with `updated(le)` becomes its old one; the
    /// other elements keep their old state (their new buffer is stale). Nothing to do in
    /// place (an element not updated was not written).
    pub fn commit_elements(&mut self, per: usize, updated: impl Fn(usize) -> bool + Sync) {
        use rayon::prelude::*;
        if self.in_place {
            return;
        }
        self.old
            .par_chunks_mut(per)
            .zip(self.new.par_chunks(per))
            .enumerate()
            .with_min_len(256)
            .for_each(|(le, (o, n))| {
                if updated(le) {
                    o.copy_from_slice(n);
                }
            });
    }

    /// Replace the committed state (e.g. from a checkpoint); `values` has the same length.
    pub fn restore(&mut self, values: &[f64]) {
        self.old.copy_from_slice(values);
        if !self.in_place {
            self.new.copy_from_slice(values);
        }
    }

    /// Bytes held (both buffers when buffered).
    pub fn bytes(&self) -> usize {
        (self.old.len() + self.new.len()) * std::mem::size_of::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn in_place_frees_the_pending_buffer_and_back_restores_it() {
        let mut s = PointStates::new(2, 3, |p, c| c.fill(p as f64));
        assert_eq!(s.bytes(), 2 * 6 * 8);
        s.set_in_place(true, 2);
        assert!(s.is_in_place());
        assert_eq!(s.bytes(), 6 * 8);
        let a = s.access();
        assert_eq!(a.old as *mut f64, a.new);
        // A committed value survives a commit in place and the way back.
        unsafe { *a.new.add(5) = 7.0 };
        s.commit();
        assert_eq!(s.current()[5], 7.0);
        s.set_in_place(false, 2);
        assert_eq!(s.bytes(), 2 * 6 * 8);
        let a = s.access();
        assert_ne!(a.old as *mut f64, a.new);
        unsafe { *a.new.add(5) = 9.0 };
        assert_eq!(
            s.current()[5],
            7.0,
            "a buffered pass leaves the committed state"
        );
        s.commit();
        assert_eq!(s.current()[5], 9.0);
    }

    #[test]
    fn elements_with_more_state_than_the_stack_copy_stay_buffered() {
        let mut s = PointStates::new(1, MAX_ELEMENT_STATE + 1, |_, _| {});
        s.set_in_place(true, MAX_ELEMENT_STATE + 1);
        assert!(!s.is_in_place());
    }
}
