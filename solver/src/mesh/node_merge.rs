//! Merge coincident nodes (within a distance tolerance) with a hashed grid.

use std::collections::HashMap;

use crate::mesh::Mesh;

/// Merge nodes closer than `tol` (m). Node numbering keeps the first occurrence; all
/// connectivity and node sets are renumbered; unused nodes cannot arise.
pub fn merge_coincident_nodes(mut mesh: Mesh, tol: f64) -> Mesh {
    let cell = tol.max(f64::MIN_POSITIVE) * 4.0;
    let key = |x: &[f64; 3]| -> [i64; 3] { x.map(|c| (c / cell).floor() as i64) };
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut map = vec![0u32; mesh.n_nodes()];
    let mut coords: Vec<[f64; 3]> = Vec::with_capacity(mesh.n_nodes());
    for (i, x) in mesh.coords.iter().enumerate() {
        let k = key(x);
        let mut found = None;
        'search: for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    if let Some(cands) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        for &c in cands {
                            let y = coords[c as usize];
                            let d2 = (0..3).map(|d| (x[d] - y[d]).powi(2)).sum::<f64>();
                            if d2 <= tol * tol {
                                found = Some(c);
                                break 'search;
                            }
                        }
                    }
                }
            }
        }
        map[i] = match found {
            Some(c) => c,
            None => {
                let c = coords.len() as u32;
                coords.push(*x);
                grid.entry(k).or_default().push(c);
                c
            }
        };
    }
    for conn in mesh.elements.iter_mut() {
        for a in conn.iter_mut() {
            *a = map[*a as usize];
        }
    }
    for nodes in mesh.node_sets.values_mut() {
        for a in nodes.iter_mut() {
            *a = map[*a as usize];
        }
        nodes.sort_unstable();
        nodes.dedup();
    }
    mesh.coords = coords;
    mesh
}
