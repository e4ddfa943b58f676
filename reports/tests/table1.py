"""The paper's Table 1 (Yang, Chen & Xiao 2014) as dcfm case-file materials, shared by the
report tests: E, ν, tensile strength f_t0, cohesion c and friction angle φ of the rock and
of the concrete; the rest follows the documented mapping (docs/plastic_damage.md §4)."""

from __future__ import annotations


def materials(regularisation: str | None = None) -> str:
    """`[materials.rock]` and `[materials.concrete]` with Table 1's values, both plastic
    damage; `regularisation` (e.g. "total") is written into both when given."""
    extra = f'regularisation = "{regularisation}"\n' if regularisation else ""
    return f"""
[materials.rock]
model = "plastic_damage"
young = 10.0e9
poisson = 0.25
[materials.rock.plastic_damage]
ft0 = 1.97e6
cohesion = 2.18e6
friction_angle_deg = 41.6
{extra}
[materials.concrete]
model = "plastic_damage"
young = 25.0e9
poisson = 0.17
[materials.concrete.plastic_damage]
ft0 = 1.30e6
cohesion = 2.0e6
friction_angle_deg = 46.0
{extra}"""
