"""The Lee–Fenves plastic-damage yield function and strengths, written in Python from the
paper and docs/plastic_damage.md (not from the solver's code), for checking a run's output:
damage only where the stress reached the strength.

- Yield function, paper eq. (25) (Lubliner et al. 1989; Lee & Fenves 1998), on the
  effective stress σ̄ with principal values σ̂₁ ≥ σ̂₂ ≥ σ̂₃:
  F = [α Ī₁ + √(3J̄₂) + β⟨σ̂₁⟩ − γ⟨−σ̂₁⟩]/(1 − α) − c̄_c,
  α = (f_b0/f_c0 − 1)/(2 f_b0/f_c0 − 1), β = (1 − α) c̄_c/c̄_t − (1 + α),
  γ = 3(1 − K_c)/(2K_c − 1).
- Effective cohesions (LF98, docs/plastic_damage.md §1, r = d/b = 1, the default):
  c̄_N = f_N0 [(1 + a_N) − a_N e^(−y_N)] and D_N = 1 − e^(−y_N) (eq. 24), so
  c̄_N = f_N0 (1 + a_N D_N): the cohesions follow from the damage variables alone.
- Damage with stiffness recovery, eq. (24): σ = (1 − D) σ̄, D = 1 − (1 − D_c)(1 − s D_t),
  s = s₀ + (1 − s₀) r(σ̄), r = Σ⟨σ̂ᵢ⟩/Σ|σ̂ᵢ| (0 at σ̄ = 0). r depends on σ̄'s direction only,
  which σ shares, so σ̄ = σ/(1 − D) with r taken from σ.
- Table 1 mapping (§4): f_c = 2c cos φ/(1 − sin φ) from Mohr–Coulomb, f_c0 = 0.5 f_c unless
  given, a_c = 2 f_c/f_c0 − 1 + 2√((f_c/f_c0)² − f_c/f_c0); G_t = 73 f_c^0.18 N/m and
  G_c = 8.8 √f_c N/mm (f_c in MPa) unless given.
- Crack band `"total"` (§1): strengths scaled by k, k² = min(1, (1 − θ) G/(l w_e)), θ = 0.05,
  w_e = (f₀²/2E₀)[(1 + a) + a²/3] (r = 1; no snap-back minimum then); `"plastic"` (the
  default, LF98): k = 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

MIN_SOFTENING_SHARE = 0.05  # θ of the "total" regularisation (docs/plastic_damage.md §1)

# Keys whose non-default values change what the check reconstructs; refused by name.
_UNSUPPORTED = {"dt_half": None, "dc_peak": None, "viscosity": 0.0}


class MaterialError(Exception):
    """A material the check cannot evaluate (named with the key and value)."""


@dataclass(frozen=True)
class PlasticDamage:
    young: float
    poisson: float
    ft0: float
    fc0: float
    fc: float
    at: float
    ac: float
    gt: float
    gc: float
    alpha: float
    gamma: float
    s0: float
    regularisation: str
    recovery: str = "lee_fenves"

    def strength_factors(self, length: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """k_t, k_c for elements of characteristic length l (m)."""
        one = np.ones_like(length, dtype=float)
        if self.regularisation == "plastic":
            return one, one
        out = []
        for f0, a, g in ((self.ft0, self.at, self.gt), (self.fc0, self.ac, self.gc)):
            we = f0 * f0 / (2.0 * self.young) * ((1.0 + a) + a * a / 3.0)
            out.append(np.sqrt(np.minimum(1.0, (1.0 - MIN_SOFTENING_SHARE) * g / (length * we))))
        return out[0], out[1]

    def lame(self) -> tuple[float, float]:
        e, nu = self.young, self.poisson
        return e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))


def material(case: dict[str, Any], name: str, where: str) -> PlasticDamage:
    """The plastic-damage parameters of material `name` of a parsed case file."""
    m = case.get("materials", {}).get(name)
    if m is None or m.get("model") != "plastic_damage":
        raise MaterialError(f"{where}: material '{name}' is not a plastic_damage material")
    p = m.get("plastic_damage", {})
    for key, default in _UNSUPPORTED.items():
        if p.get(key, default) != default:
            raise MaterialError(f"{where}: materials.{name}.plastic_damage.{key} = {p[key]}: "
                                f"the check reconstructs the default (r = d/b = 1, rate independent) only")
    recovery = p.get("recovery", "lee_fenves")
    if recovery not in ("lee_fenves", "consistent"):
        raise MaterialError(f"{where}: materials.{name}.plastic_damage.recovery = {recovery!r}")
    reg = p.get("regularisation", "plastic")
    if reg not in ("plastic", "total"):
        raise MaterialError(f"{where}: materials.{name}.plastic_damage.regularisation = {reg!r}")
    ft0 = float(p["ft0"])
    if "fc" in p:
        fc = float(p["fc"])
    else:
        phi = math.radians(float(p["friction_angle_deg"]))
        fc = 2.0 * float(p["cohesion"]) * math.cos(phi) / (1.0 - math.sin(phi))
    fc0 = float(p.get("fc0", 0.5 * fc))
    q = fc / fc0
    ac = 2.0 * q - 1.0 + 2.0 * math.sqrt(max(q * q - q, 0.0))
    fb = float(p.get("fb0_fc0", 1.16))
    kc = float(p.get("kc", 2.0 / 3.0))
    fc_mpa = fc / 1e6
    return PlasticDamage(
        young=float(m["young"]), poisson=float(m["poisson"]), ft0=ft0, fc0=fc0, fc=fc,
        at=float(p.get("at", 0.0)), ac=ac,
        gt=float(p.get("gt", 73.0 * fc_mpa**0.18)), gc=float(p.get("gc", 8.8e3 * math.sqrt(fc_mpa))),
        alpha=(fb - 1.0) / (2.0 * fb - 1.0), gamma=3.0 * (1.0 - kc) / (2.0 * kc - 1.0),
        s0=float(p.get("s0", 0.0)), regularisation=reg, recovery=recovery)


def principal(sig: np.ndarray) -> np.ndarray:
    """Principal values, descending, of Voigt stresses (n, 6) (xx, yy, zz, xy, yz, zx)."""
    t = np.empty((len(sig), 3, 3))
    t[:, 0, 0], t[:, 1, 1], t[:, 2, 2] = sig[:, 0], sig[:, 1], sig[:, 2]
    t[:, 0, 1] = t[:, 1, 0] = sig[:, 3]
    t[:, 1, 2] = t[:, 2, 1] = sig[:, 4]
    t[:, 2, 0] = t[:, 0, 2] = sig[:, 5]
    return np.linalg.eigvalsh(t)[:, ::-1]


def yield_function(sig_eff: np.ndarray, ct: np.ndarray, cc: np.ndarray, alpha: float, gamma: float) -> np.ndarray:
    """F of eq. (25) (Pa) at effective stresses (n, 6) with cohesions c̄_t, c̄_c (n,)."""
    s = principal(sig_eff)
    i1 = s.sum(axis=1)
    m = i1 / 3.0
    q = np.sqrt(1.5 * ((s - m[:, None]) ** 2).sum(axis=1))
    beta = (1.0 - alpha) * cc / ct - (1.0 + alpha)
    smax = s[:, 0]
    return (alpha * i1 + q + beta * np.maximum(smax, 0.0) - gamma * np.maximum(-smax, 0.0)) / (1.0 - alpha) - cc


def tension_weight(sig: np.ndarray) -> np.ndarray:
    """r(σ) = Σ⟨σ̂ᵢ⟩/Σ|σ̂ᵢ| (0 at σ = 0)."""
    s = principal(sig)
    den = np.abs(s).sum(axis=1)
    return np.where(den > 0.0, np.maximum(s, 0.0).sum(axis=1) / np.where(den > 0.0, den, 1.0), 0.0)


def stiffness_left(sig: np.ndarray, dt: np.ndarray, dc: np.ndarray, s0: float) -> np.ndarray:
    """1 − D = (1 − d_c)(1 − s d_t) of eq. (24), s = s₀ + (1 − s₀) r(σ) from σ's direction."""
    s = s0 + (1.0 - s0) * tension_weight(sig)
    return (1.0 - dc) * (1.0 - s * dt)


def effective_stress(sig: np.ndarray, dt: np.ndarray, dc: np.ndarray, s0: float) -> np.ndarray:
    """σ̄ = σ/(1 − D) with D of eq. (24) (stiffness recovery s from σ's direction); only for
    1 − D > 0 (`stiffness_left`): at D = 1 σ = 0 and σ̄ is not determined by it."""
    return sig / stiffness_left(sig, dt, dc, s0)[:, None]
