"""The W3 site (docs/verification_references.md §W3) as a dcfm case with seismic
boundaries, its closed-form transfer function, and spectral ratios of histories.

A soil layer (30 m, V_s 300 m/s, ρ 2000, ν 0.3) over rock (30 m meshed, V_s 1500 m/s,
ρ 2500, ν 0.25) on the elastic half-space of that rock: a 6 × 6 m model (2 × 2 elements in
plan; 1 m elements in the soil, 3 m in the rock), viscous-spring base with the seismic
input (`[[boundary.absorbing]] … input = true`), free-field walls on the four sides with
columns at their ends (`[boundary.free_field] sides`), the reference free-field column
read through `RunResult.free_field` (docs/boundaries.md; the set-up of W3).
"""

from __future__ import annotations

import numpy as np

import dcfm

SOIL = {"thickness": 30.0, "vs": 300.0, "density": 2000.0, "poisson": 0.3, "h": 1.0}
ROCK = {"thickness": 30.0, "vs": 1500.0, "density": 2500.0, "poisson": 0.25, "h": 3.0}


def young(layer: dict) -> float:
    return 2.0 * layer["density"] * layer["vs"] ** 2 * (1.0 + layer["poisson"])


def site_case(
    seismic: dict,
    *,
    end: float,
    damping: tuple[float, float] | None = None,
    dt: float | None = None,
    title: str = "W3 site",
) -> dict:
    """The case dict: `seismic` is the `[seismic]` table (definition, quantity, x …);
    `damping` (α, β) is Rayleigh damping of both layers (the free field follows it)."""
    regions = []
    for name in ("rock", "soil"):
        r = {"name": name, "material": name, "integration": "full"}
        if damping is not None:
            r["damping"] = {"alpha": damping[0], "beta": damping[1]}
        regions.append(r)
    return {
        "title": title,
        "time": {"end": end, "dt": dt},
        "mesh": {
            "blocks": [
                {"name": "rock", "origin": [0.0, 0.0, -ROCK["thickness"]], "size": [6.0, 6.0, ROCK["thickness"]], "divisions": [2, 2, int(ROCK["thickness"] / ROCK["h"])]},
                {"name": "soil", "origin": [0.0, 0.0, 0.0], "size": [6.0, 6.0, SOIL["thickness"]], "divisions": [2, 2, int(SOIL["thickness"] / SOIL["h"])]},
            ]
        },
        "materials": {
            "rock": {"model": "elastic", "young": young(ROCK), "poisson": ROCK["poisson"], "density": ROCK["density"]},
            "soil": {"model": "elastic", "young": young(SOIL), "poisson": SOIL["poisson"], "density": SOIL["density"]},
        },
        "regions": regions,
        "node_sets": {
            "centre": {"box": [[2.99, 2.99, 29.99], [3.01, 3.01, 30.01]]},
            "corner": {"box": [[-0.01, -0.01, 29.99], [0.01, 0.01, 30.01]]},
        },
        "boundary": {
            "absorbing": [{"set": "rock.zmin", "kind": "viscous_spring", "input": True}],
            "free_field": {"sides": [["rock.xmin", "soil.xmin"], ["rock.xmax", "soil.xmax"], ["rock.ymin", "soil.ymin"], ["rock.ymax", "soil.ymax"]]},
        },
        "seismic": seismic,
    }


def layer_on_half_space(f, alpha: float = 0.0, beta: float = 0.0) -> np.ndarray:
    """H(f) = U(surface) / U(outcrop of the half-space) = U_s / (2 U_I) of the two layers on
    the rock half-space, Rayleigh damping (α, β) in both layers, elastic half-space
    (Kramer 1996, §7.2, layer matrices): with Z = iωρ_r c_r the base traction is
    τ_0 = Z (U_0 − 2 U_I), [U_s, τ_s] = M [U_0, τ_0] and τ_s = 0."""
    w = 2 * np.pi * np.atleast_1d(np.asarray(f, dtype=float))
    out = np.empty(w.shape, dtype=complex)
    for i, om in enumerate(w):
        m = np.eye(2, dtype=complex)
        for lay in (ROCK, SOIL):
            g = lay["density"] * lay["vs"] ** 2 * (1 + 1j * om * beta)
            k = np.sqrt(lay["density"] * (om**2 - 1j * om * alpha) / g)
            d = lay["thickness"]
            m = np.array([[np.cos(k * d), np.sin(k * d) / (g * k)], [-g * k * np.sin(k * d), np.cos(k * d)]]) @ m
        z = 1j * om * ROCK["density"] * ROCK["vs"]
        u0 = 2 * m[1, 1] * z / (m[1, 0] + m[1, 1] * z)  # for U_I = 1
        us = m[0, 0] * u0 + m[0, 1] * (z * u0 - 2 * z)
        out[i] = us / 2.0
    return out


def dtft(x: np.ndarray, dt: float, f: float) -> complex:
    """Σ x_k e^{−2πi f k Δt} Δt."""
    k = np.arange(len(x))
    return complex(np.exp(-2j * np.pi * f * dt * k) @ x) * dt


def peaks(func, f_grid: np.ndarray, n: int) -> list[tuple[float, float]]:
    """The first `n` local maxima of `func` on the grid, refined by a bounded search."""
    from scipy.optimize import minimize_scalar

    vals = np.array([func(f) for f in f_grid])
    idx = [i for i in range(1, len(vals) - 1) if vals[i] > vals[i - 1] and vals[i] >= vals[i + 1]][:n]
    out = []
    for i in idx:
        res = minimize_scalar(lambda f: -func(f), bounds=(f_grid[i - 1], f_grid[i + 1]), method="bounded", options={"xatol": 1e-5})
        out.append((float(res.x), float(-res.fun)))
    return out
