"""Physics checks of a Yingxiuwan run (issue #10, item 7): the CI variant's few seconds of
shaking in the main job are checked against physics, not against golden numbers.

Reads a run directory of `dcfm run` on a case from `dcfm mesh yingxiuwan` (summary.json,
histories.csv, case.pvd and its VTU frames — the raw appended VTU that dcfm writes) and the
case file, and writes RUN_DIR/checks.json: one entry per check with its measured value, its
limit, where the limit comes from and whether it passed. Exit status 1 if any check fails.

The checks:

- energy balance (VERIFICATION.md W12): on every row of the histories, |residual| ≤ 1 % of
  the largest energy term of the run;
- no penetration: on the first and the last frame of the shaking, every node of a pair or
  point-to-surface contact in contact (bonded, stick, sliding) has |gap| ≤ 1 µm and no
  separated node overlaps its partner by more than 1 µm (the contact method closes gaps to
  round-off: measured 1e-15 m; 1 µm is a thousandth of the smallest element);
- damage is irreversible (Lee–Fenves: d_t and d_c grow with the plastic-damage variables
  κ_t, κ_c, which never decrease; the combined d = 1 − (1 − d_c)(1 − s d_t) may fall when a
  crack closes, through the stiffness recovery s): element by element d_t and d_c of the
  last frame are ≥ those of the first, and 0 ≤ d < 1; the damaged volume of every region
  never decreases from row to row;
- anchors: no bar's axial force exceeds its yield force f_y π d²/4 (elastic–perfectly
  plastic steel, docs/anchors.md);
- contact areas: every interface's area split bonded / stick / slide / separated / surface
  sums to the same total on every row (each node's area is in exactly one state);
- the joint contact solve: steps accepted without settling to the tolerance stay below
  the accepted change (summary.json `contact_unsettled_steps`, contact/joint.rs);
- damage only where the stress reached the strength (Lee–Fenves: damage grows only with
  plastic flow, eqs. 24–25; formulas in lee_fenves.py): on every pair of consecutive whole-mesh
  frames, every element whose d_t or d_c grew has a changed plastic strain and a grown κ_t or
  κ_c (strictly: the element values are volume averages of the points' stored values, so
  an element none of whose points changed has bit-identical values). D and κ of a point are
  both increasing functions of its y = b ε̃ᵖ, but each is rounded on its own — in κ's
  formula and in the volume average over up to 8 points — so a growth of the point's y
  that moves the average of D by a few ulps may leave that of κ on the same double (seen
  on the full mesh: d_c of a lining element 1 − 1e-9 grew by one ulp, 1.1e-16, between two
  frames with κ_c bit-identical and its plastic strain changed by 2.5e-5). A growth of D no
  larger than DAMAGE_ROUNDOFF = 8 × 2⁻⁵² (8 points' sum of values ≤ 1, each rounded to
  2⁻⁵³) is therefore judged on the plastic strain alone, and counted; any larger one needs
  the grown κ as well. On every frame, every
  element still undamaged (κ_t = κ_c = 0) has its stress inside the initial yield surface
  F(σ̄; c̄_t = k_t f_t0, c̄_c = k_c f_c0) ≤ 1e-8 k_c f_c0, and every damaged one-point element
  (the VTU holds its one point's state) has F(σ̄; c̄(d_t, d_c)) ≤ 1e-8 k_c f_c0, with
  σ̄ = σ/(1 − D) by eq. (24). A frame's stress is that of its displacements U^{n+1} with the
  state of the step's update at U^n (one elastic increment beyond the returned stress), so
  F is evaluated at σ̄ − E₀:ε(Δt V^{n+½}), the update's own stress (U^{n+1} = U^n + Δt V^{n+½}).
  1e-8 is 100 × the return mapping's tolerance (|F| ≤ 1e-10 f_c0, returned on the admissible
  side; docs/plastic_damage.md §2): what is left is the round-off of σ/(1 − D) and of the
  increment. Full-integration elements with damage are not checked against the current
  surface: the VTU holds their volume averages, not the states of their eight points;
- anchors in tension where the rock moves inward (docs/anchors.md; perfect bond: the
  axial force N = EA ε with ε = t·(u(q) − u(p))/l from the host displacement since
  installation, the bolts being installed when the seismic stage starts): on every frame of
  anchors.pvd, with the host displacement of the whole-mesh frame of the same time less
  that of the first frame, interpolated with the trilinear shape functions at the segment
  ends (hex8_kinematics.py) and taken at U^n as above: every segment whose elongation
  strain exceeds 1e-9 in magnitude has an axial force of its sign (the floor, a force of
  EA × 1e-9 ≈ 0.1 N for a φ25 bolt, only leaves unjudged the segments whose strain is too
  small for its sign to mean a movement of the rock; the recomputed strain agrees with the
  solver's to round-off of the interpolation, measured 5e-15 on the CI run); and every bar whose head
  (at the excavation face) moved into the cavern relative to its deep end by more than
  1e-9 of its length, δ = t·(u_deep − u_head) > 1e-9 L, has a positive length-weighted mean
  force (its mean is EA δ/L as long as no segment yields: segments that have yielded —
  non-zero `plastic_strain` in anchors.pvd — and the bars holding them are not judged
  from then on, and counted; for a reinforcement mat's bars,
  parallel to the surface, δ is simply the bar's elongation, the same statement);
- the concrete holds together: on every whole-mesh frame, every node of the concrete
  (the regions of material `concrete`) has moved since the first frame by at most 0.1 m
  more than the concrete's median displacement — a tenth of the lining's thickness (1.0 m,
  docs/yingxiuwan.md), the thinnest member. The elements are geometrically linear (small
  displacements): a member displaced by a tenth of its thickness relative to the rest of
  the structure has come off it (a falling crane-beam corbel or lining, docs/yingxiuwan.md
  "Long runs"), and the model no longer describes it.

The whole-mesh frames are those of full.pvd when the case writes compact frames
(`[output.frames]`, docs/outputs.md), else those of case.pvd.

    .venv/bin/python reports/yingxiuwan_checks.py RUN_DIR --case CASE.toml
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import sys
import tempfile
import tomllib
from pathlib import Path
from typing import Any

import numpy as np

import dcfm_vtu
import hex8_kinematics as hk
import lee_fenves as lf

# Limits, with their sources in the module docstring.
ENERGY_RESIDUAL_SHARE = 0.01
GAP_TOLERANCE_M = 1e-6
AREA_TOLERANCE = 1e-9
UNSETTLED_ACCEPTED = 1e-6
YIELD_TOLERANCE = 1e-8
ANCHOR_STRAIN_FLOOR = 1e-9
STRUCTURE_DRIFT_M = 0.1
DAMAGE_ROUNDOFF = 8.0 * 2.0**-52


class CheckError(Exception):
    """A run directory that cannot be read: the file and what is wrong."""


def read_vtu(path: Path, names: list[str]) -> dict[str, np.ndarray]:
    """The named arrays (`Points`, cell arrays, point and cell fields) of a VTU file as dcfm
    writes it (reports/dcfm_vtu.py for the layouts), each of shape (n, components)."""
    try:
        grid = dcfm_vtu.read_vtu(path)
    except dcfm_vtu.VtuError as e:
        raise CheckError(str(e)) from e
    missing = [n for n in names if n != "Points" and n not in grid.cells and n not in grid.point_data
               and n not in grid.cell_data]
    if missing:
        raise CheckError(f"{path}: missing arrays {missing}")
    return {n: grid.array(n) for n in names}


def read_pvd(path: Path) -> list[tuple[float, Path]]:
    """(time, file) of every frame of a PVD collection, in time order."""
    try:
        return dcfm_vtu.read_pvd(path)
    except dcfm_vtu.VtuError as e:
        raise CheckError(str(e)) from e


def read_histories(path: Path) -> dict[str, np.ndarray]:
    try:
        with path.open(encoding="utf-8") as f:
            reader = csv.reader(f)
            header = next(reader)
            rows = [[float(v) for v in row] for row in reader]
    except (OSError, StopIteration, ValueError) as e:
        raise CheckError(f"{path}: {e}") from e
    data = np.array(rows)
    return {h: data[:, k] for k, h in enumerate(header)}


def check(name: str, value: float, limit: float, passed: bool, what: str) -> dict[str, Any]:
    return {"name": name, "value": value, "limit": limit, "passed": bool(passed), "what": what}


def run_checks(run: Path, case_file: Path) -> list[dict[str, Any]]:
    summary = json.loads((run / "summary.json").read_text(encoding="utf-8"))
    cols = read_histories(run / "histories.csv")
    case = tomllib.loads(case_file.read_text(encoding="utf-8"))
    checks: list[dict[str, Any]] = []

    energy_terms = ["kinetic", "internal", "damping", "contact", "external", "input", "boundary"]
    largest = max(float(np.max(np.abs(cols[t]))) for t in energy_terms if t in cols)
    share = float(np.max(np.abs(cols["residual"]))) / largest
    checks.append(check("energy balance", share, ENERGY_RESIDUAL_SHARE, share <= ENERGY_RESIDUAL_SHARE,
                        "largest |residual| of the energy balance over all rows / largest energy term (W12)"))

    pvd = run / "full.pvd" if (run / "full.pvd").exists() else run / "case.pvd"
    frames = read_pvd(pvd)
    if len(frames) < 2:
        raise CheckError(f"{pvd}: {len(frames)} frames, expected the start and the end")
    fields = ["contact_state", "contact_gap", "damage", "damage_tension", "damage_compression"]
    first = read_vtu(frames[0][1], fields)
    last = read_vtu(frames[-1][1], fields)
    worst_contact = 0.0
    worst_overlap = 0.0
    for f in (first, last):
        state = f["contact_state"][:, 0]
        gap = f["contact_gap"][:, 0]
        base = np.where(state >= 10, state - 10, state)
        touching = (state >= 0) & (base <= 2)
        separated = (state >= 0) & (base == 3)
        if np.any(touching):
            worst_contact = max(worst_contact, float(np.max(np.abs(gap[touching]))))
        if np.any(separated):
            worst_overlap = max(worst_overlap, float(np.max(-gap[separated])))
    checks.append(check("no penetration, pairs in contact", worst_contact, GAP_TOLERANCE_M,
                        worst_contact <= GAP_TOLERANCE_M,
                        f"largest |gap| (m) of a bonded, sticking or sliding node, frames at t = {frames[0][0]:g} and {frames[-1][0]:g} s"))
    checks.append(check("no penetration, separated nodes", worst_overlap, GAP_TOLERANCE_M,
                        worst_overlap <= GAP_TOLERANCE_M, "largest overlap (m) of a separated node"))

    d1 = last["damage"][:, 0]
    finite = bool(np.all(np.isfinite(d1)))
    healed = 0.0
    for var in ("damage_tension", "damage_compression"):
        grew = last[var][:, 0] - first[var][:, 0]
        finite = finite and bool(np.all(np.isfinite(grew)))
        healed = max(healed, float(np.max(-grew))) if finite else math.inf
    checks.append(check("damage never heals", healed, 0.0, finite and healed <= 0.0,
                        "largest decrease of an element's tensile or compressive damage d_t, d_c "
                        "from the first to the last frame (the combined d may fall when a crack closes: "
                        "stiffness recovery s)"))
    checks.append(check("damage in [0, 1)", float(np.max(d1)) if finite else math.inf, 1.0,
                        finite and float(np.min(d1)) >= 0.0 and float(np.max(d1)) < 1.0,
                        "largest damage of an element at the last frame (smallest ≥ 0)"))
    worst_drop = 0.0
    for k, v in cols.items():
        if k.startswith("damaged_volume_total_") and len(v) > 1:
            worst_drop = max(worst_drop, float(np.max(v[:-1] - v[1:])))
    checks.append(check("damaged volume never decreases", worst_drop, 1e-9, worst_drop <= 1e-9,
                        "largest drop (m³) of a region's damaged volume between two rows"))

    anchors = case.get("anchors", {})
    worst_ratio = 0.0
    for a in anchors.get("patterns", []) + anchors.get("bars", []) + anchors.get("mats", []):
        col = f"anchor_{a['name']}_max_force"
        if col not in cols:
            raise CheckError(f"{run / 'histories.csv'}: no column '{col}' for anchors '{a['name']}'")
        yield_force = a["yield_stress"] * math.pi * a["diameter"] ** 2 / 4.0
        worst_ratio = max(worst_ratio, float(np.max(np.abs(cols[col]))) / yield_force)
    if anchors:
        checks.append(check("anchors within yield", worst_ratio, 1.0, worst_ratio <= 1.0 + 1e-9,
                            "largest |axial force| of a bar / its yield force f_y π d²/4"))

    worst_area = 0.0
    for iface in case.get("interfaces", []):
        name = iface["name"]
        parts = [f"area_{s}_{name}" for s in ("bonded", "stick", "slide", "separated", "surface")]
        if not all(p in cols for p in parts):
            raise CheckError(f"{run / 'histories.csv'}: missing area columns of interface '{name}'")
        total = sum(cols[p] for p in parts)
        worst_area = max(worst_area, float((np.max(total) - np.min(total)) / np.max(total)))
    checks.append(check("interface areas conserved", worst_area, AREA_TOLERANCE, worst_area <= AREA_TOLERANCE,
                        "largest relative spread over the rows of an interface's summed state areas"))

    count, change = summary.get("contact_unsettled_steps", [0, 0.0])
    checks.append(check("joint contact solve", float(change), UNSETTLED_ACCEPTED, change <= UNSETTLED_ACCEPTED,
                        f"largest force change left in the {count} of {summary.get('steps')} steps accepted without settling to 1e-10"))

    steps = FrameSteps(summary)
    drift = ConcreteDrift(case)
    checks += damage_checks(frames, case, steps, drift)
    checks.append(drift.check())
    if anchors:
        checks += anchor_checks(run, frames, case, steps)
    return checks


class ConcreteDrift:
    """The concrete holds together: the largest displacement of a concrete node since the
    first frame, less the concrete's median displacement since then, over every frame
    (fed the whole-mesh frames that `damage_checks` reads, so they are read once)."""

    def __init__(self, case: dict[str, Any]):
        self.concrete = [k for k, r in enumerate(case.get("regions", [])) if r.get("material") == "concrete"]
        if not self.concrete:
            raise CheckError("the case has no region of material 'concrete' to check for holding together")
        self.worst, self.when, self.where = 0.0, math.nan, [math.nan] * 3
        self.start: np.ndarray | None = None

    def observe(self, t: float, path: Path, f: dict[str, np.ndarray]) -> None:
        conn = f["connectivity"].reshape(-1, 8).astype(np.int64)
        nodes = np.unique(conn[np.isin(f["region"][:, 0].astype(np.int64), self.concrete)])
        u = f["displacement"][nodes]
        if self.start is None:
            self.start, self.when = u, t
        elif self.start.shape != u.shape:
            raise CheckError(f"{path}: {len(nodes)} concrete nodes, the first frame had {len(self.start)}")
        moved = u - self.start
        drift = np.linalg.norm(moved - np.median(moved, axis=0), axis=1)
        k = int(np.argmax(drift))
        if drift[k] > self.worst:
            self.worst, self.when, self.where = float(drift[k]), t, f["Points"][nodes[k]].tolist()

    def check(self) -> dict[str, Any]:
        at = ", ".join(f"{v:.1f}" for v in self.where)
        return check("concrete holds together", self.worst, STRUCTURE_DRIFT_M, self.worst <= STRUCTURE_DRIFT_M,
                     f"largest displacement (m) of a concrete node since the first frame less the concrete's median, "
                     f"at t = {self.when:g} s, node at ({at}); limit a tenth of the lining's thickness")


class FrameSteps:
    """The step that led to a frame (its U^{n+1} = U^n + h V^{n+½}): Δt, or the shortened
    last step at the end (docs/outputs.md, "Times")."""

    def __init__(self, summary: dict[str, Any]):
        self.dt = float(summary["dt"])
        self.last = float(summary.get("last_dt", self.dt))
        self.end = float(summary.get("end_time", math.inf))

    def h(self, t: float) -> float:
        return self.last if abs(t - self.end) <= 1e-9 * self.dt else self.dt


MESH_FIELDS = ["Points", "connectivity", "region", "active"]


class Mesh:
    """Geometry of the whole-mesh frames: connectivity, mean gradients, volumes, crack-band
    lengths; the materials and integration of every region of the case."""

    def __init__(self, frame: dict[str, np.ndarray], case: dict[str, Any], where: str):
        self.coords = frame["Points"]
        self.conn = frame["connectivity"].reshape(-1, 8).astype(np.int64)
        self.grad, self.vol = hk.mean_gradients(self.coords, self.conn)
        self.length = hk.char_lengths(self.coords, self.conn, self.vol)
        self.case = case
        self.regions = case.get("regions", [])
        self.where = where
        self._materials: dict[int, lf.PlasticDamage | None] = {}

    def material(self, r: int) -> lf.PlasticDamage | None:
        """The plastic-damage parameters of region r (None for another model)."""
        if r not in self._materials:
            if r >= len(self.regions):
                raise CheckError(f"{self.where}: region number {r} beyond the case's {len(self.regions)} [[regions]]")
            name = self.regions[r]["material"]
            try:
                self._materials[r] = lf.material(self.case, name, self.where)
            except lf.MaterialError as e:
                if "not a plastic_damage" in str(e):
                    self._materials[r] = None
                else:
                    raise CheckError(str(e)) from e
        return self._materials[r]

    def one_point(self, r: int) -> bool:
        return self.regions[r].get("integration", "one_point") == "one_point"


def _elastic_increment(m: lf.PlasticDamage, de: np.ndarray) -> np.ndarray:
    """E₀ : Δε (isotropic, Voigt with engineering shears)."""
    lam, mu = m.lame()
    out = np.empty_like(de)
    tr = de[:, :3].sum(axis=1)
    out[:, :3] = lam * tr[:, None] + 2.0 * mu * de[:, :3]
    out[:, 3:] = mu * de[:, 3:]
    return out


def damage_checks(frames: list[tuple[float, Path]], case: dict[str, Any], steps: FrameSteps,
                  drift: ConcreteDrift) -> list[dict[str, Any]]:
    """Damage only where the stress reached the strength (module docstring); every frame read
    is also passed to `drift`."""
    fields = MESH_FIELDS + ["displacement", "velocity", "stress", "damage_tension", "damage_compression",
                            "kappa_tension", "kappa_compression", "plastic_strain"]
    mesh: Mesh | None = None
    prev: dict[str, np.ndarray] | None = None
    growths = bad_growth = roundoff_only = 0
    first_bad = ""
    worst = {"undamaged": (-math.inf, ""), "damaged": (-math.inf, "")}
    counted = {"undamaged": 0, "damaged": 0}
    lost = 0
    for t, path in frames:
        f = read_vtu(path, fields)
        drift.observe(t, path, f)
        if mesh is None:
            mesh = Mesh(f, case, str(path))
        region = f["region"][:, 0].astype(int)
        active = (f["active"][:, 0] > 0) & (region >= 0)
        dt_, dc_ = f["damage_tension"][:, 0], f["damage_compression"][:, 0]
        kt_, kc_ = f["kappa_tension"][:, 0], f["kappa_compression"][:, 0]
        if prev is not None:
            gain_t = dt_ - prev["damage_tension"][:, 0]
            gain_c = dc_ - prev["damage_compression"][:, 0]
            grew_t, grew_c = gain_t > 0.0, gain_c > 0.0
            grew = grew_t | grew_c
            flow = np.any(f["plastic_strain"] != prev["plastic_strain"], axis=1)
            # Per variable: no growth, or κ grew with it (strict), or a growth within the
            # averages' round-off (DAMAGE_ROUNDOFF).
            strict_t = ~grew_t | (kt_ > prev["kappa_tension"][:, 0])
            strict_c = ~grew_c | (kc_ > prev["kappa_compression"][:, 0])
            hardened = (strict_t | (gain_t <= DAMAGE_ROUNDOFF)) & (strict_c | (gain_c <= DAMAGE_ROUNDOFF))
            bad = grew & ~(flow & hardened)
            growths += int(np.sum(grew))
            roundoff_only += int(np.sum(grew & flow & hardened & ~(strict_t & strict_c)))
            if np.any(bad) and not first_bad:
                first_bad = f" (first: element {int(np.argmax(bad))} at t = {t:g} s)"
            bad_growth += int(np.sum(bad))
        # The update's own stress: one elastic increment back from the frame's (docstring).
        deps = hk.mean_strain(mesh.grad, mesh.conn, steps.h(t) * f["velocity"])
        for r in np.unique(region[active]):
            m = mesh.material(int(r))
            if m is None:
                continue
            sel = np.nonzero(active & (region == r))[0]
            kt, kc = m.strength_factors(mesh.length[sel])
            undamaged = (kt_[sel] == 0.0) & (kc_[sel] == 0.0)
            ct = kt * m.ft0 * (1.0 + m.at * dt_[sel])
            cc = kc * m.fc0 * (1.0 + m.ac * dc_[sel])
            # An element with no stiffness left (D = 1 in floating point: σ = 0) has no σ̄ to
            # reconstruct: counted, not judged here ("damage in [0, 1)" fails on it).
            left = lf.stiffness_left(f["stress"][sel], dt_[sel], dc_[sel], m.s0)
            spent = left <= 0.0
            lost += int(np.sum(spent))
            eff = np.zeros_like(f["stress"][sel])
            eff[~spent] = lf.effective_stress(f["stress"][sel][~spent], dt_[sel][~spent], dc_[sel][~spent], m.s0)
            eff -= _elastic_increment(m, deps[sel])
            rel = lf.yield_function(eff, ct, cc, m.alpha, m.gamma) / (kc * m.fc0)
            rel[spent] = -np.inf
            # σ̄ of a damaged element is reconstructed from eq. (24), the "lee_fenves" recovery;
            # the "consistent" rule's σ(σ̄, D) is not inverted here, and an undamaged element's
            # σ̄ = σ under either rule.
            damaged = None
            if mesh.one_point(int(r)):
                if m.recovery != "lee_fenves" and np.any(~undamaged):
                    raise CheckError(f"{mesh.where}: region '{mesh.regions[int(r)]['name']}' (one-point) uses "
                                     f"recovery = {m.recovery!r}: the damaged-element check inverts eq. (24) "
                                     "('lee_fenves') only")
                damaged = ~undamaged & ~spent
            for kind, mask in (("undamaged", undamaged), ("damaged", damaged)):
                if mask is None or not np.any(mask):
                    continue
                counted[kind] += int(np.sum(mask))
                k = int(np.argmax(np.where(mask, rel, -np.inf)))
                if rel[k] > worst[kind][0]:
                    worst[kind] = (float(rel[k]), f"element {int(sel[k])} ({mesh.regions[int(r)]['name']}) at t = {t:g} s")
        prev = f
    out = [check("damage only with plastic flow", float(bad_growth), 0.0, bad_growth == 0,
                 f"element-frames whose d_t or d_c grew since the previous frame without a change of plastic strain "
                 f"or growth of κ_t/κ_c (eq. 24: damage comes through plastic flow), of {growths} that grew{first_bad}; "
                 f"{roundoff_only} grew by at most {DAMAGE_ROUNDOFF:.2g} with κ on the same double and were judged on "
                 "their plastic strain alone (the averages' round-off)")]
    for kind, name, what in (
        ("undamaged", "undamaged elements inside the initial yield surface",
         "largest F(σ̄)/(k_c f_c0) (eq. 25) of an active element with κ_t = κ_c = 0, at the update's stress"),
        ("damaged", "damaged elements on or inside the yield surface",
         "largest F(σ̄; c̄(d_t, d_c))/(k_c f_c0) (eq. 25) of a one-point element with κ > 0, σ̄ = σ/(1 − D) of eq. (24)"),
    ):
        value, where = worst[kind]
        n = counted[kind]
        spent = f"; {lost} element-frames with no stiffness left (D = 1) not judged" if kind == "damaged" and lost else ""
        out.append(check(name, value if n else None, YIELD_TOLERANCE, (not n) or value <= YIELD_TOLERANCE,
                         f"{what}; {n} element-frames" + (f", worst {where}" if n else ": none") + spent))
    return out


def anchor_checks(run: Path, frames: list[tuple[float, Path]], case: dict[str, Any], steps: FrameSteps) -> list[dict[str, Any]]:
    """Anchors in tension where the rock moves inward (module docstring)."""
    apvd = run / "anchors.pvd"
    if not apvd.exists():
        raise CheckError(f"{apvd}: missing: the case has anchors but writes no per-bar output "
                         "([output.frames] anchors = true, docs/outputs.md)")
    for kind in ("bars", "patterns", "mats"):
        for i, g in enumerate(case.get("anchors", {}).get(kind, [])):
            for key in ("bond_stiffness", "pretension"):
                if g.get(key, 0.0):
                    raise CheckError(f"anchors.{kind}[{i}].{key} = {g[key]}: the check compares the force of "
                                     "perfect-bond bars without pretension (N = EA ε) with the rock's elongation")
    bars = read_pvd(apvd)
    by_time = {round(t, 9): p for t, p in frames}
    first = read_vtu(frames[0][1], MESH_FIELDS + ["displacement"])
    coords = first["Points"]
    conn = first["connectivity"].reshape(-1, 8).astype(np.int64)
    u0 = first["displacement"]
    active = np.nonzero((first["active"][:, 0] > 0) & (first["region"][:, 0] >= 0))[0]
    geo = read_vtu(bars[0][1], ["Points", "connectivity", "bar"])
    lines = geo["connectivity"].reshape(-1, 2).astype(np.int64)
    p, q = geo["Points"][lines[:, 0]], geo["Points"][lines[:, 1]]
    length = np.linalg.norm(q - p, axis=1)
    axis = (q - p) / length[:, None]
    bar = geo["bar"][:, 0].astype(np.int64)
    # Each segment lies in one host element (docs/anchors.md): the active one holding its
    # midpoint; both ends' natural coordinates in that element.
    host, _ = hk.locate(coords, conn, active, 0.5 * (p + q))
    if np.any(host < 0):
        k = int(np.argmax(host < 0))
        raise CheckError(f"{bars[0][1]}: segment {k} (bar {bar[k]}) at {0.5 * (p[k] + q[k])} lies in no active element")
    shape = []
    xh = coords[conn[host]]  # (segments, 8, 3)
    for ends in (p, q):
        xi = hk.natural_coordinates(xh, ends)
        in_box = np.all((ends >= xh.min(axis=1) - 1e-9) & (ends <= xh.max(axis=1) + 1e-9), axis=1)
        outside = ~(in_box & np.all(np.abs(xi) <= 1.0 + 1e-7, axis=1))
        if np.any(outside):
            k = int(np.argmax(outside))
            raise CheckError(f"{bars[0][1]}: an end of segment {k} lies outside the element {host[k]} holding its midpoint")
        shape.append(hk.shape_values(xi))
    # A bar's segments run from its start (a pattern bolt's head, on the excavation face) to
    # its end (deep in the rock) and tile it, so their elongations add up to the bar's,
    # δ = t·(u_end − u_start), and their length-weighted mean force is its mean force.
    nbars = int(bar.max()) + 1 if len(bar) else 0
    # EA of the bars when every group has the same (the frames do not name a bar's group):
    # then |N − EA ε| is reported too (perfect bond below yield: N = EA ε, docs/anchors.md).
    groups = [g for kind in ("bars", "patterns", "mats") for g in case.get("anchors", {}).get(kind, [])]
    stiffness = {g.get("young", 200e9) * math.pi * g["diameter"] ** 2 / 4.0 for g in groups}
    ea = next(iter(stiffness)) if len(stiffness) == 1 else None
    deviation = 0.0
    sign_bad = inward = inward_bad = not_judged = bars_not_judged = 0
    yielded = np.zeros(len(lines), dtype=bool)
    first_bad = ""
    for t, path in bars:
        full = by_time.get(round(t, 9))
        if full is None:
            continue
        seg = read_vtu(path, ["axial_force", "plastic_strain"])
        force, plastic = seg["axial_force"][:, 0], seg["plastic_strain"][:, 0]
        if len(force) != len(lines):
            raise CheckError(f"{path}: {len(force)} segments, the first frame has {len(lines)}")
        # Once a segment has yielded, N = EA(ε − εᵖ) and neither statement holds: a yielded
        # segment is not judged for its sign, a bar with one is not judged for its mean.
        yielded |= plastic != 0.0
        f = read_vtu(full, ["displacement", "velocity"])
        u = f["displacement"] - steps.h(t) * f["velocity"] - u0
        ue = u[conn[host]]
        du = np.einsum("sa,sai->si", shape[1], ue) - np.einsum("sa,sai->si", shape[0], ue)
        elong = np.einsum("si,si->s", axis, du)
        strain = elong / length
        judged = (np.abs(strain) > ANCHOR_STRAIN_FLOOR) & ~yielded
        not_judged += int(np.sum(yielded))
        wrong = judged & (np.sign(force) != np.sign(strain))
        if np.any(wrong) and not first_bad:
            k = int(np.argmax(wrong))
            first_bad = f"; first: segment {k} of bar {bar[k]} at t = {t:g} s, N = {force[k]:.4g} N, ε = {strain[k]:.3e}"
        sign_bad += int(np.sum(wrong))
        if ea is not None and np.any(force != 0.0):
            deviation = max(deviation, float(np.max(np.abs(force - ea * strain)) / np.max(np.abs(force))))
        delta = np.bincount(bar, elong, nbars)
        total = np.bincount(bar, length, nbars)
        mean = np.bincount(bar, force * length, nbars) / np.where(total > 0, total, 1.0)
        bar_yielded = np.bincount(bar, yielded.astype(float), nbars) > 0
        bars_not_judged += int(np.sum(bar_yielded))
        moved_in = (delta > ANCHOR_STRAIN_FLOOR * total) & ~bar_yielded
        inward += int(np.sum(moved_in))
        inward_bad += int(np.sum(moved_in & (mean <= 0.0)))
    matched = sum(1 for t, _ in bars if round(t, 9) in by_time)
    if matched < 2:
        raise CheckError(f"{apvd}: {matched} frames at the times of the whole-mesh frames, expected the start and later ones")
    return [
        check("anchor forces follow the rock's elongation", float(sign_bad), 0.0, sign_bad == 0,
              f"segment-frames whose axial force has the other sign than the elongation of the host rock "
              f"since installation (|ε| > {ANCHOR_STRAIN_FLOOR:g}), {len(lines)} segments × {matched} frames{first_bad}"
              + (f"; largest |N − EA ε| / largest |N| of a frame: {deviation:.1e}" if ea is not None else "")
              + f"; {not_judged} segment-frames after their segment yielded not judged"),
        check("anchors in tension where the rock moves inward", float(inward_bad), 0.0, inward_bad == 0,
              f"bar-frames whose head moved into the cavern relative to the deep end (δ > {ANCHOR_STRAIN_FLOOR:g} L) "
              f"and whose mean axial force is not tensile, of {inward} such bar-frames ({nbars} bars); "
              f"{bars_not_judged} bar-frames of bars with a yielded segment not judged"),
    ]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", type=Path, help="run directory of `dcfm run`")
    ap.add_argument("--case", type=Path, required=True, help="the case file the run used")
    args = ap.parse_args(argv)
    try:
        checks = run_checks(args.run, args.case)
    except CheckError as e:
        print(f"yingxiuwan_checks: {e}", file=sys.stderr)
        return 2
    fd, tmp = tempfile.mkstemp(dir=args.run, prefix="checks.json", suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        json.dump(checks, f, indent=1)
    os.replace(tmp, args.run / "checks.json")
    for c in checks:
        value = "–" if c["value"] is None else f"{c['value']:.3e}"
        print(f"{'ok  ' if c['passed'] else 'FAIL'} {c['name']}: {value} (limit {c['limit']:.3e})")
    return 0 if all(c["passed"] for c in checks) else 1


if __name__ == "__main__":
    sys.exit(main())
