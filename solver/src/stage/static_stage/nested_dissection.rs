//! Geometric nested dissection of the node graph (George 1973; the coordinate-bisection
//! variant of Heath & Raghavan 1995): split the nodes at the median of their longest
//! extent, take the nodes of one side that touch the other as the separator, order the two
//! halves recursively and the separator last. On 3D meshes it gives far less fill than
//! minimum degree (the factor of a 41³-node cube: see `docs/static_stage.md`); the
//! factorisation takes whichever of the two orderings fills less.

/// Parts of at most this many nodes are not split further (natural order).
const LEAF: usize = 64;

/// Nested-dissection order of the nodes of a graph given by its upper-triangle adjacency
/// (`col_ptr`, `row_idx`, with the diagonal) and node coordinates: `order[k]` is the node
/// eliminated k-th.
pub fn order(col_ptr: &[usize], row_idx: &[usize], coords: &[[f64; 3]]) -> Vec<usize> {
    let n = coords.len();
    // Full (symmetric) adjacency without the diagonal.
    let mut deg = vec![0usize; n + 1];
    for c in 0..n {
        for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
            if r != c {
                deg[r + 1] += 1;
                deg[c + 1] += 1;
            }
        }
    }
    for i in 0..n {
        deg[i + 1] += deg[i];
    }
    let mut fill = deg.clone();
    let mut adj = vec![0usize; deg[n]];
    for c in 0..n {
        for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
            if r != c {
                adj[fill[r]] = c;
                fill[r] += 1;
                adj[fill[c]] = r;
                fill[c] += 1;
            }
        }
    }
    let mut side = vec![0u8; n];
    let mut out = Vec::with_capacity(n);
    let mut stack: Vec<(Vec<usize>, bool)> = vec![((0..n).collect(), false)];
    // Iterative post-order: a part is split into (left, right, separator); they are pushed
    // so that left, then right, then the separator come out in that order.
    while let Some((nodes, done)) = stack.pop() {
        if done || nodes.len() <= LEAF {
            out.extend_from_slice(&nodes);
            continue;
        }
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for &v in &nodes {
            for d in 0..3 {
                lo[d] = lo[d].min(coords[v][d]);
                hi[d] = hi[d].max(coords[v][d]);
            }
        }
        let axis = (0..3)
            .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
            .expect("three axes");
        let mut keys: Vec<f64> = nodes.iter().map(|&v| coords[v][axis]).collect();
        let mid = keys.len() / 2;
        let (_, median, _) = keys.select_nth_unstable_by(mid, |a, b| a.total_cmp(b));
        let median = *median;
        let (mut left, mut right): (Vec<usize>, Vec<usize>) =
            nodes.iter().partition(|&&v| coords[v][axis] < median);
        if left.is_empty() || right.is_empty() {
            // All on one coordinate: no geometric split; keep the natural order.
            out.extend_from_slice(&nodes);
            continue;
        }
        for &v in &left {
            side[v] = 1;
        }
        for &v in &right {
            side[v] = 2;
        }
        // Separator: the nodes of the smaller side that have a neighbour on the other.
        let (small, other) = if left.len() <= right.len() {
            (1u8, 2u8)
        } else {
            (2u8, 1u8)
        };
        let part = if small == 1 { &mut left } else { &mut right };
        let mut separator = Vec::new();
        part.retain(|&v| {
            let touches = adj[deg[v]..deg[v + 1]].iter().any(|&w| side[w] == other);
            if touches {
                separator.push(v);
            }
            !touches
        });
        for &v in &nodes {
            side[v] = 0;
        }
        stack.push((separator, true));
        stack.push((right, false));
        stack.push((left, false));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orders_every_node_once_with_the_middle_plane_last() {
        // 9 × 9 × 9 grid graph (7-point).
        let k = 9;
        let id = |i: usize, j: usize, l: usize| i + k * (j + k * l);
        let mut coords = Vec::new();
        for l in 0..k {
            for j in 0..k {
                for i in 0..k {
                    coords.push([i as f64, j as f64, l as f64]);
                }
            }
        }
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for l in 0..k {
            for j in 0..k {
                for i in 0..k {
                    let mut rows = vec![id(i, j, l)];
                    if i > 0 {
                        rows.push(id(i - 1, j, l));
                    }
                    if j > 0 {
                        rows.push(id(i, j - 1, l));
                    }
                    if l > 0 {
                        rows.push(id(i, j, l - 1));
                    }
                    rows.sort_unstable();
                    row_idx.extend(rows);
                    col_ptr.push(row_idx.len());
                }
            }
        }
        let ord = order(&col_ptr, &row_idx, &coords);
        let mut seen = vec![false; k * k * k];
        for &v in &ord {
            assert!(!seen[v]);
            seen[v] = true;
        }
        assert!(seen.iter().all(|&s| s));
        // The last nodes form one plane (the top-level separator).
        let last: Vec<usize> = ord[ord.len() - k * k..].to_vec();
        let plane = (0..3).any(|d| {
            let x = coords[last[0]][d];
            last.iter().all(|&v| coords[v][d] == x)
        });
        assert!(plane, "{last:?}");
    }
}
