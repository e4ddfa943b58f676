"""`hex8_kinematics.locate` (the bars' host elements in the Yingxiuwan checks) against the
plain search it replaces: every point tried against every candidate in order, the first
whose Newton ξ lies in [−1 − slack, 1 + slack]³ holding it."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import hex8_kinematics as hk  # noqa: E402


def distorted_block(n: tuple[int, int, int], rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """A block of n hex8 with jittered interior nodes and graded spacing (VTK node order)."""
    axes = [np.cumsum(np.r_[0.0, rng.uniform(0.3, 3.0, k)]) for k in n]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    inner = (slice(1, -1),) * 3
    grid[inner] += rng.uniform(-0.08, 0.08, grid[inner].shape)
    nx, ny, nz = (k + 1 for k in n)
    coords = grid.reshape(-1, 3)
    node = lambda i, j, k: (i * ny + j) * nz + k  # noqa: E731
    conn = []
    for i in range(n[0]):
        for j in range(n[1]):
            for k in range(n[2]):
                conn.append([node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                             node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)])
    return coords, np.array(conn)


def plain_locate(coords, conn, candidates, points, slack):
    x = coords[conn[candidates]]
    lo, hi = x.min(axis=1) - 1e-9, x.max(axis=1) + 1e-9
    host = np.full(len(points), -1)
    xi_out = np.zeros((len(points), 3))
    for k, p in enumerate(points):
        for c in np.nonzero(np.all((p >= lo) & (p <= hi), axis=1))[0]:
            xi = hk.natural_coordinates(x[c][None], p[None])[0]
            if np.all(np.abs(xi) <= 1.0 + slack):
                host[k], xi_out[k] = candidates[c], xi
                break
    return host, xi_out


def test_locate_matches_the_plain_search():
    rng = np.random.default_rng(20261127)
    coords, conn = distorted_block((6, 5, 4), rng)
    candidates = rng.permutation(len(conn))[: len(conn) - 15]  # some elements not candidates
    lo, hi = coords.min(axis=0), coords.max(axis=0)
    inside = lo + (hi - lo) * rng.uniform(-0.05, 1.05, (400, 3))  # some outside the block
    nodes = coords[rng.choice(len(coords), 60)]  # on shared corners, edges and faces
    faces = 0.5 * (coords[conn[:40, 0]] + coords[conn[:40, 6]])  # centres
    points = np.vstack([inside, nodes, faces])
    host, xi = hk.locate(coords, conn, candidates, points)
    ref_host, ref_xi = plain_locate(coords, conn, candidates, points, 1e-9)
    assert np.array_equal(host, ref_host)
    assert np.max(np.abs(xi - ref_xi)) < 1e-12
    found = host >= 0
    assert 0 < found.sum() < len(points)  # both found and missed points exercised
    # The ξ found map back to the points.
    x = coords[conn[host[found]]]
    back = np.einsum("ka,kai->ki", hk.shape_values(xi[found]), x)
    assert np.max(np.abs(back - points[found])) < 1e-9
