"""The Lee–Fenves formulas of the damage check against the closed forms and the tables of
docs/plastic_damage.md (§1 yield surface and stiffness recovery, §4 Table 1 mapping and
the strength factors of the "total" crack band)."""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import lee_fenves as lf  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import table1  # noqa: E402

TABLE1 = table1.materials("total")


def test_table1_mapping_matches_the_documented_values():
    case = tomllib.loads(TABLE1)
    rock, concrete = lf.material(case, "rock", "t"), lf.material(case, "concrete", "t")
    # docs/plastic_damage.md §4 table (rounded there).
    assert rock.fc == pytest.approx(9.701e6, abs=1e3) and rock.fc0 == pytest.approx(4.851e6, abs=1e3)
    assert concrete.fc == pytest.approx(9.900e6, abs=1e3)
    assert rock.ac == pytest.approx(3 + 2 * np.sqrt(2), rel=1e-12)
    assert rock.gt == pytest.approx(109.9, abs=0.05) and rock.gc == pytest.approx(27.4e3, abs=50)
    assert concrete.gt == pytest.approx(110.3, abs=0.05) and concrete.gc == pytest.approx(27.7e3, abs=50)


@pytest.mark.parametrize(
    "name, length, ft, fc",
    [("rock", 1.0, 1.445e6, 9.701e6), ("rock", 2.0, 1.022e6, 7.575e6), ("rock", 7.0, 0.546e6, 4.049e6),
     ("concrete", 3.0, 1.300e6, 9.829e6), ("concrete", 7.0, 0.865e6, 6.435e6)],
)
def test_total_regularisation_strengths_match_the_documented_table(name, length, ft, fc):
    m = lf.material(tomllib.loads(TABLE1), name, "t")
    kt, kc = m.strength_factors(np.array([length]))
    assert kt[0] * m.ft0 == pytest.approx(ft, abs=1e3)
    assert kc[0] * m.fc == pytest.approx(fc, abs=1e3)


def test_yield_surface_meets_the_uniaxial_and_biaxial_strengths():
    ct, cc = np.array([2.9e6]), np.array([13e6])
    alpha, gamma = (1.16 - 1) / (2 * 1.16 - 1), 3.0
    for sig in ([2.9e6, 0, 0, 0, 0, 0], [0, 0, -13e6, 0, 0, 0], [0, -1.16 * 13e6, -1.16 * 13e6, 0, 0, 0]):
        assert abs(lf.yield_function(np.array([sig]), ct, cc, alpha, gamma)[0]) < 1e-6
    # Inside and outside.
    assert lf.yield_function(np.array([[2.8e6, 0, 0, 0, 0, 0]]), ct, cc, alpha, gamma)[0] < 0
    assert lf.yield_function(np.array([[3.0e6, 0, 0, 0, 0, 0]]), ct, cc, alpha, gamma)[0] > 0
    # A shear stress is rotated correctly: pure shear τ has principal values ±τ.
    tau = 2.0e6
    f_shear = lf.yield_function(np.array([[0, 0, 0, tau, 0, 0]]), ct, cc, alpha, gamma)[0]
    f_princ = lf.yield_function(np.array([[tau, 0, -tau, 0, 0, 0]]), ct, cc, alpha, gamma)[0]
    assert f_shear == pytest.approx(f_princ, rel=1e-12)


def test_stiffness_recovery_of_eq24():
    """W10: D_t 0.6, D_c 0.1, s0 0 → σ/σ̄ = 0.36 in tension, 0.90 in compression."""
    dt, dc = np.array([0.6, 0.6]), np.array([0.1, 0.1])
    nominal = np.array([[0.36, 0, 0, 0, 0, 0], [-0.9, 0, 0, 0, 0, 0]])
    eff = lf.effective_stress(nominal, dt, dc, 0.0)
    assert eff[:, 0] == pytest.approx([1.0, -1.0], rel=1e-12)


def test_unsupported_options_are_refused_by_name():
    case = tomllib.loads(TABLE1.replace('regularisation = "total"\n\n', 'regularisation = "total"\ndt_half = 0.3\n\n', 1))
    with pytest.raises(lf.MaterialError, match="dt_half"):
        lf.material(case, "rock", "t")
