"""Trilinear hex8 kinematics for the checks of a run's VTU output, written from the
textbook element (Hughes, *The Finite Element Method*, 1987, §3.5; node order of VTK and
Gmsh, the solver's own: corners (−1,−1,−1), (1,−1,−1), (1,1,−1), (−1,1,−1), then the same
at ζ = +1), not from the solver's code:

- `mean_gradients`: the volume-averaged shape-function gradients (1/V)∫∂N_a/∂x dV by 2×2×2
  Gauss quadrature (exact for the trilinear hex: ∂N_a/∂x det J is a polynomial of degree
  ≤ 2 in each natural coordinate). Their strain is the mean strain of the element — the
  strain of a one-point (uniform-strain, Flanagan–Belytschko 1981) element, and the
  volume average of the Gauss-point strains of a fully integrated one;
- `shape_values` and `locate`: u(ξ) = Σ N_a(ξ) u_a at a point, and the natural coordinates
  of a physical point (Newton on x(ξ) = x).
"""

from __future__ import annotations

import numpy as np

CORNERS = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
# The six faces (corner indices, in cyclic order).
FACES = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])


def shape_values(xi: np.ndarray) -> np.ndarray:
    """N_a(ξ), shape (n, 8), for natural coordinates ξ of shape (n, 3)."""
    return np.prod(1.0 + xi[:, None, :] * CORNERS[None, :, :], axis=2) / 8.0


def shape_derivatives(xi: np.ndarray) -> np.ndarray:
    """∂N_a/∂ξ_j, shape (n, 8, 3)."""
    f = 1.0 + xi[:, None, :] * CORNERS[None, :, :]  # (n, 8, 3)
    out = np.empty(f.shape)
    for j in range(3):
        others = [k for k in range(3) if k != j]
        out[:, :, j] = CORNERS[None, :, j] * f[:, :, others[0]] * f[:, :, others[1]] / 8.0
    return out


def mean_gradients(coords: np.ndarray, conn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(1/V)∫∂N_a/∂x dV of every element, shape (ne, 8, 3), and the volumes V (ne,)."""
    x = coords[conn]  # (ne, 8, 3)
    g = 1.0 / np.sqrt(3.0)
    grad = np.zeros(x.shape)
    vol = np.zeros(len(conn))
    for gp in CORNERS * g:
        dn = shape_derivatives(gp[None, :])[0]  # (8, 3)
        jac = np.einsum("eai,aj->eij", x, dn)  # ∂x_i/∂ξ_j
        det = np.linalg.det(jac)
        dndx = np.einsum("aj,eji->eai", dn, np.linalg.inv(jac))
        grad += det[:, None, None] * dndx
        vol += det
    return grad / vol[:, None, None], vol


def mean_strain(grad: np.ndarray, conn: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Mean small strain of every element for nodal displacements u (nn, 3): Voigt xx, yy,
    zz, xy, yz, zx with engineering shears (the solver's order, docs/outputs.md)."""
    h = np.einsum("eaj,eai->eij", grad, u[conn])  # ∂u_i/∂x_j
    return np.stack([h[:, 0, 0], h[:, 1, 1], h[:, 2, 2], h[:, 0, 1] + h[:, 1, 0],
                     h[:, 1, 2] + h[:, 2, 1], h[:, 2, 0] + h[:, 0, 2]], axis=1)


def char_lengths(coords: np.ndarray, conn: np.ndarray, vol: np.ndarray) -> np.ndarray:
    """V / A_max of every element (the crack band's length, docs/plastic_damage.md §8), a
    face's area taken as half the cross product of its diagonals."""
    x = coords[conn]
    areas = []
    for f in FACES:
        d1 = x[:, f[2]] - x[:, f[0]]
        d2 = x[:, f[3]] - x[:, f[1]]
        areas.append(0.5 * np.linalg.norm(np.cross(d1, d2), axis=1))
    return vol / np.max(np.stack(areas, axis=1), axis=1)


def natural_coordinates(x: np.ndarray, points: np.ndarray) -> np.ndarray:
    """ξ of each point (n, 3) in its element, nodal coordinates x (n, 8, 3): Newton on
    x(ξ) = x from ξ = 0, each point until its step is below 1e-12 (at most 50 steps)."""
    xi = np.zeros((len(points), 3))
    todo = np.arange(len(points))
    for _ in range(50):
        if len(todo) == 0:
            break
        xe, z = x[todo], xi[todo]
        r = np.einsum("ka,kai->ki", shape_values(z), xe) - points[todo]
        jac = np.einsum("kai,kaj->kij", xe, shape_derivatives(z))
        step = np.linalg.solve(jac, r[:, :, None])[:, :, 0]
        xi[todo] = z - step
        todo = todo[np.max(np.abs(step), axis=1) >= 1e-12]
    return xi


def _bbox_pairs(lo: np.ndarray, hi: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every (point, box) with the point inside the box [lo, hi], sorted by point then box:
    boxes binned on a uniform grid of their median extent, so each point meets the few
    boxes of its cell rather than all of them."""
    h = float(np.median(np.max(hi - lo, axis=1)))
    if not np.isfinite(h) or h <= 0.0:
        h = 1.0
    origin = np.minimum(lo.min(axis=0), points.min(axis=0))
    b0 = np.floor((lo - origin) / h).astype(np.int64)
    b1 = np.floor((hi - origin) / h).astype(np.int64)
    dims = np.maximum(b1.max(axis=0), np.floor((points.max(axis=0) - origin) / h).astype(np.int64)) + 1
    span = b1 - b0 + 1
    count = np.prod(span, axis=1)
    box = np.repeat(np.arange(len(lo)), count)
    # The k-th cell of a box's range, k = 0 .. count−1, as (i, j, l) offsets.
    k = np.arange(len(box)) - np.repeat(np.cumsum(count) - count, count)
    sy, sz = span[box, 1], span[box, 2]
    cell = b0[box] + np.stack([k // (sy * sz), (k // sz) % sy, k % sz], axis=1)
    key = (cell[:, 0] * dims[1] + cell[:, 1]) * dims[2] + cell[:, 2]
    order = np.argsort(key, kind="stable")
    key, box = key[order], box[order]
    pc = np.floor((points - origin) / h).astype(np.int64)
    inside_grid = np.all((pc >= 0) & (pc < dims), axis=1)
    pkey = (pc[:, 0] * dims[1] + pc[:, 1]) * dims[2] + pc[:, 2]
    start = np.searchsorted(key, pkey, side="left")
    stop = np.searchsorted(key, pkey, side="right")
    stop = np.where(inside_grid, stop, start)
    n = stop - start
    pt = np.repeat(np.arange(len(points)), n)
    at = np.repeat(start, n) + np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    bx = box[at]
    keep = np.all((points[pt] >= lo[bx]) & (points[pt] <= hi[bx]), axis=1)
    pt, bx = pt[keep], bx[keep]
    order = np.lexsort((bx, pt))
    return pt[order], bx[order]


def locate(coords: np.ndarray, conn: np.ndarray, candidates: np.ndarray, points: np.ndarray,
           slack: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    """For every point (n, 3) the first element among `candidates` (element ids) that holds
    it (|ξ_i| ≤ 1 + slack after Newton on x(ξ) = x, to 1e-12) and its ξ; −1 where none.
    The candidates whose bounding box holds a point are tried in their order, all points'
    first ones together, then the second ones of the points still without a host, …"""
    candidates = np.asarray(candidates)
    x = coords[conn[candidates]]  # (m, 8, 3)
    lo, hi = x.min(axis=1) - 1e-9, x.max(axis=1) + 1e-9
    host = np.full(len(points), -1)
    xi_out = np.zeros((len(points), 3))
    if len(points) == 0 or len(candidates) == 0:
        return host, xi_out
    pt, bx = _bbox_pairs(lo, hi, points)
    rank = np.arange(len(pt)) - np.searchsorted(pt, pt, side="left")
    for r in range(int(rank.max()) + 1 if len(rank) else 0):
        sel = np.nonzero((rank == r) & (host[pt] < 0))[0]
        if len(sel) == 0:
            continue
        p, c = pt[sel], bx[sel]
        xi = natural_coordinates(x[c], points[p])
        ok = np.all(np.abs(xi) <= 1.0 + slack, axis=1)
        host[p[ok]] = candidates[c[ok]]
        xi_out[p[ok]] = xi[ok]
    return host, xi_out
