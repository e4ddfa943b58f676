//! The contributions that add to each boundary node, listed per node (compressed rows) in
//! the order of the list they come from: a node's sum can then be formed on its own, in
//! parallel with the others, in the same order as a serial pass over the list.

/// Indices into a list of contributions, grouped by the boundary slot each one adds to.
#[derive(Clone, Debug, Default)]
pub struct PerSlot {
    /// Row starts: the contributions of slot b are `items[offsets[b]..offsets[b + 1]]`.
    offsets: Vec<u32>,
    items: Vec<u32>,
}

impl PerSlot {
    /// Group the contributions whose slots `slots` yields (in list order) over `n_slots`
    /// slots; within a slot the list order is kept (a stable counting sort).
    pub fn new(n_slots: usize, slots: impl Iterator<Item = u32> + Clone) -> Self {
        let mut offsets = vec![0u32; n_slots + 1];
        for s in slots.clone() {
            offsets[s as usize + 1] += 1;
        }
        for b in 0..n_slots {
            offsets[b + 1] += offsets[b];
        }
        let mut next = offsets.clone();
        let mut items = vec![0u32; offsets[n_slots] as usize];
        for (k, s) in slots.enumerate() {
            let at = &mut next[s as usize];
            items[*at as usize] = k as u32;
            *at += 1;
        }
        Self { offsets, items }
    }

    /// The contributions of slot `b`, in list order.
    #[inline]
    pub fn of(&self, b: usize) -> &[u32] {
        &self.items[self.offsets[b] as usize..self.offsets[b + 1] as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_by_slot_keeping_list_order() {
        let slots = [2u32, 0, 2, 1, 0, 2];
        let p = PerSlot::new(4, slots.iter().copied());
        assert_eq!(p.of(0), &[1, 4]);
        assert_eq!(p.of(1), &[3]);
        assert_eq!(p.of(2), &[0, 2, 5]);
        assert!(p.of(3).is_empty());
    }
}
