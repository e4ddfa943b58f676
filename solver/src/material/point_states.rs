//! Per-integration-point state buffers (old / new), swapped once per step.

/// State of every integration point of a set of elements: `stride` values per point,
/// points of one element contiguous, elements in mesh order. Reading `old` and writing
/// `new` lets every element update in parallel without ordering effects.
#[derive(Clone, Debug, Default)]
pub struct PointStates {
    stride: usize,
    old: Vec<f64>,
    new: Vec<f64>,
}

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
        Self { stride, old, new }
    }

    /// Values per point.
    #[inline]
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// The state at the start of the step (read-only) and the buffer for its end.
    #[inline]
    pub fn split(&mut self) -> (&[f64], &mut [f64]) {
        (&self.old, &mut self.new)
    }

    /// The latest committed state (after [`PointStates::commit`]).
    #[inline]
    pub fn current(&self) -> &[f64] {
        &self.old
    }

    /// The state written during the step in progress.
    #[inline]
    pub fn pending(&self) -> &[f64] {
        &self.new
    }

    /// End of step: the new state becomes the old one.
    #[inline]
    pub fn commit(&mut self) {
        std::mem::swap(&mut self.old, &mut self.new);
    }

    /// End of a step that updated only some elements (subcycling): the new state of
    /// every element `le` (`per` values each) with `updated(le)` becomes its old one; the
    /// other elements keep their old state (their new buffer is stale).
    pub fn commit_elements(&mut self, per: usize, updated: impl Fn(usize) -> bool + Sync) {
        use rayon::prelude::*;
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
        self.new.copy_from_slice(values);
    }

    /// Bytes held (both buffers).
    pub fn bytes(&self) -> usize {
        (self.old.len() + self.new.len()) * std::mem::size_of::<f64>()
    }
}
