//! Greedy element colouring: no two elements of one colour share a node, so each colour's
//! internal forces can be added to the nodes in parallel without races, and the sum at
//! every node happens in the same order whatever the number of threads.

/// Colour of every element (greedy, first colour not used by a neighbour through a node).
/// At most 64 colours (a hex8 mesh needs 8 when structured, rarely more than ~27).
pub fn colour_elements(elements: &[[u32; 8]], n_nodes: usize) -> Vec<u8> {
    let mut used = vec![0u64; n_nodes];
    let mut colour = Vec::with_capacity(elements.len());
    for conn in elements {
        let mask = conn.iter().fold(0u64, |m, &a| m | used[a as usize]);
        let c = (!mask).trailing_zeros().min(63) as u8;
        for &a in conn {
            used[a as usize] |= 1u64 << c;
        }
        colour.push(c);
    }
    colour
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::BoxMeshSpec;

    #[test]
    fn structured_box_needs_eight_colours_and_no_conflicts() {
        let m = BoxMeshSpec::single("b", [0.0; 3], [1.0; 3], [4, 3, 5])
            .build("t")
            .unwrap();
        let c = colour_elements(&m.elements, m.n_nodes());
        assert_eq!(*c.iter().max().unwrap(), 7);
        for col in 0..8u8 {
            let mut seen = vec![false; m.n_nodes()];
            for (e, conn) in m.elements.iter().enumerate() {
                if c[e] == col {
                    for &a in conn {
                        assert!(!seen[a as usize]);
                        seen[a as usize] = true;
                    }
                }
            }
        }
    }
}
