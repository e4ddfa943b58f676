"""The Python module itself: cases from files and dicts give the same model and the same
errors, wrong Python types and shapes name the argument, runs record what they promise
and stop when the callback says so, results do not depend on the thread count, and the
contact-pair and material-point drivers reproduce closed forms (docs/
verification_references.md §W9; Hooke's law)."""

from __future__ import annotations

import ast
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import dcfm
from dcfm_reference.paths import CASES

W01 = CASES / "w01_p_pulse.toml"
ROCK = {"model": "elastic", "young": 20e9, "poisson": 0.25, "density": 2700.0}


def w01_dict() -> dict:
    return tomllib.loads(W01.read_text(encoding="utf-8"))


def test_dict_and_file_build_the_same_case():
    a = dcfm.Case.from_file(W01)
    b = dcfm.Case.from_dict(w01_dict(), label=str(W01))
    assert (a.n_nodes, a.n_elements, a.dt, a.end) == (b.n_nodes, b.n_elements, b.dt, b.end)
    np.testing.assert_array_equal(a.coords, b.coords)
    np.testing.assert_array_equal(a.elements, b.elements)
    ra = a.run(steps=50)
    rb = b.run(steps=50)
    np.testing.assert_array_equal(ra.fields["displacement"], rb.fields["displacement"])


def test_errors_are_identical_for_file_and_dict(tmp_path):
    bad = w01_dict()
    bad["materials"]["rock"]["poisson"] = 0.7
    path = tmp_path / "bad.toml"
    path.write_text(W01.read_text(encoding="utf-8").replace("poisson = 0.25", "poisson = 0.7"))
    with pytest.raises(dcfm.DcfmError) as from_file:
        dcfm.Case.from_file(path)
    with pytest.raises(dcfm.DcfmError) as from_dict:
        dcfm.Case.from_dict(bad, label=str(path))
    assert str(from_file.value) == str(from_dict.value)
    assert str(from_file.value) == f"{path}: materials.rock.poisson = 0.7: must be in (-1, 0.5)"
    e = from_dict.value
    assert (e.kind, e.file, e.field, e.value) == ("invalid_input", str(path), "materials.rock.poisson", "0.7")


def test_unknown_field_and_missing_file():
    d = w01_dict()
    d["time"]["ending"] = 1.0
    with pytest.raises(dcfm.DcfmError, match=r"(?s)<dict>: .*unknown field `ending`"):
        dcfm.Case.from_dict(d)
    with pytest.raises(dcfm.DcfmError, match=r"nowhere\.toml: "):
        dcfm.Case.from_file("nowhere.toml")


def test_too_large_time_step_names_time_dt():
    case = dcfm.Case.from_file(W01)
    with pytest.raises(dcfm.DcfmError) as e:
        case.start(dt=10 * case.dt)
    assert e.value.field == "time.dt" and "exceeds the stable step" in str(e.value)


def test_wrong_python_types_name_the_argument():
    with pytest.raises(TypeError, match="^case: expected a dict"):
        dcfm.Case.from_dict([1, 2])
    d = w01_dict()
    d["materials"]["rock"]["young"] = {1, 2}
    with pytest.raises(TypeError, match=r"materials\.rock\.young: a set cannot be written"):
        dcfm.Case.from_dict(d)
    with pytest.raises(ValueError, match=r"^strain: expected shape \(n, 6\), got \[3, 5\]"):
        dcfm.material_point(ROCK, np.zeros((3, 5)))
    with pytest.raises(TypeError, match="^strain: expected an array of numbers"):
        dcfm.material_point(ROCK, [["a"] * 6])
    with pytest.raises(ValueError, match=r"^normal: expected shape \(3\)"):
        dcfm.contact_pair_step(state="stick", normal=[0, 1], w_sum=1, dt=1, rel_pred=[0, 0, 0], rel_old=[0, 0, 0], mu_s=0.5, mu_d=0.4)
    with pytest.raises(ValueError, match="^state: "):
        dcfm.contact_pair_step(state="glued", normal=[0, 0, 1], w_sum=1, dt=1, rel_pred=[0, 0, 0], rel_old=[0, 0, 0], mu_s=0.5, mu_d=0.4)
    sim = dcfm.Case.from_file(W01).start()
    with pytest.raises(ValueError, match=r"^velocity: expected shape \(804, 3\)"):
        sim.set_velocity(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="^nodes: id 99999 out of range"):
        sim.run(steps=1, nodes=[99999])
    with pytest.raises(TypeError, match="^callback: expected a callable"):
        sim.run(steps=1, callback=3)


def test_dict_values_may_be_numpy():
    d = w01_dict()
    d["materials"]["rock"]["young"] = np.float64(20e9)
    d["mesh"]["blocks"][0]["divisions"] = np.array([1, 1, 200])
    d["title"] = None  # left out: the default applies
    case = dcfm.Case.from_dict(d)
    assert case.n_elements == 200 and case.title == ""


def test_run_records_and_callback_stops():
    case = dcfm.Case.from_file(W01)
    calls = []

    def progress(step, time, energies):
        calls.append((step, time, energies["kinetic"]))
        return step < 300

    r = case.run(record_every=10, callback=progress, callback_every=100)
    assert r.stopped and r.steps == 300
    assert [c[0] for c in calls] == [100, 200, 300]
    assert math.isclose(calls[-1][1], 300 * case.dt, rel_tol=1e-12)
    assert r.time.shape == (31,) and r.displacement.shape == (31, 2, 3) and r.stress.shape == (31, 2, 6)
    assert r.nodes == [400, 800] and r.elements == [100, 199]  # the case's [output] lists
    assert set(r.energies) == {"kinetic", "internal", "damping", "contact", "external", "input", "residual"}
    f = r.fields
    assert f["displacement"].shape == (804, 3) and f["stress"].shape == (200, 6) and f["damage"].shape == (200,)
    # The recorded node history ends at the final field.
    np.testing.assert_array_equal(r.displacement[-1, 0], f["displacement"][400])


def test_threads_do_not_change_results():
    case = dcfm.Case.from_file(W01)
    a, b = case.start(), case.start()
    a.step(200, threads=1)
    b.step(200, threads=2)
    np.testing.assert_array_equal(a.displacement, b.displacement)
    np.testing.assert_array_equal(a.velocity, b.velocity)


def test_contact_fields_are_returned():
    case = dcfm.Case.from_file(CASES / "w05_bar_impact.toml")
    r = case.run(steps=20)
    state = r.fields["contact_state"]
    assert state.shape == (case.n_nodes,)
    assert set(np.unique(state)) <= {-1.0, 0.0, 1.0, 2.0, 3.0}
    assert (state >= 0).sum() > 0


def test_box_mesh_merges_and_splits():
    blocks = [
        {"name": "a", "origin": [0, 0, 0], "size": [1, 1, 1], "divisions": [1, 1, 1]},
        {"name": "b", "origin": [0, 0, 1], "size": [1, 1, 1], "divisions": [1, 1, 1]},
    ]
    assert dcfm.box_mesh(blocks).n_nodes == 12
    m = dcfm.box_mesh(blocks, split=[["a", "b"]])
    assert m.n_nodes == 16 and m.n_elements == 2
    assert m.face_sets["a-b"].tolist() == [[0, 1]]  # element 0, local face 1 (ζ+)
    with pytest.raises(dcfm.DcfmError, match=r"divisions\[0\] = 0"):
        dcfm.box_mesh([dict(blocks[0], divisions=[0, 1, 1])])


W9 = [  # docs/verification_references.md §W9: load on mass 1 (normal, tangential), state → result
    ((20, 0), "bonded", "bonded", 15.0, 0.0),
    ((-10, 0), "bonded", "separated", 0.0, 0.0),
    ((-4, 0), "bonded", "bonded", -3.0, 0.0),
    ((-4, 0), "stick", "separated", 0.0, 0.0),
    ((20, 8), "bonded", "bonded", 15.0, 6.0),
    ((20, 16), "stick", "sliding", 15.0, 6.0),
    ((20, 16), "bonded", "bonded", 15.0, 12.0),
    ((20, 18), "bonded", "sliding", 15.0, 6.0),
]


@pytest.mark.parametrize("load, state, expected, normal, tangential", W9)
def test_contact_pair_w09_table(load, state, expected, normal, tangential):
    """One step from rest of masses 1 (loaded, surface a) and 3: Ū_a = Δt² f, Ū_b = 0."""
    dt = 1e-3
    f = np.array([load[1], 0.0, load[0]])  # +z: towards b (compression)
    out = dcfm.contact_pair_step(
        state=state, normal=[0, 0, 1], w_sum=1 + 1 / 3, dt=dt, rel_pred=-dt**2 * f,
        rel_old=[0, 0, 0], mu_s=0.5, mu_d=0.4, shear_capacity=5.0, tensile_capacity=5.0,
    )
    assert out["state"] == expected
    assert out["normal"] == pytest.approx(normal, rel=1e-10, abs=1e-10)
    assert np.linalg.norm(out["tangential"]) == pytest.approx(tangential, rel=1e-10, abs=1e-10)
    if expected == "sliding":
        # Tangential accelerations: mass 1 (16 − 6)/1 = 10, mass 3: 6/3 = 2 m/s².
        r = out["force"]
        assert (f[0] + r[0]) / 1.0 == pytest.approx(load[1] - 6.0)
        assert -r[0] / 3.0 == pytest.approx(2.0)


def test_material_point_elastic_is_hooke():
    rng = np.random.default_rng(1)
    eps = rng.normal(scale=1e-4, size=(5, 6))
    out = dcfm.material_point(ROCK, eps)
    e, nu = ROCK["young"], ROCK["poisson"]
    lam, mu = e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))
    tr = eps[:, :3].sum(axis=1)
    expected = np.hstack([lam * tr[:, None] + 2 * mu * eps[:, :3], mu * eps[:, 3:]])
    np.testing.assert_allclose(out["stress"], expected, rtol=1e-13)
    assert not out["damage"].any()


def test_material_point_damage_grows_and_errors_name_the_field():
    concrete = {
        "model": "plastic_damage", "young": 31027e6, "poisson": 0.18, "density": 2400.0,
        "plastic_damage": {"ft0": 2.9e6, "fc": 24.1e6, "fc0": 13e6, "gt": 200.0, "gc": 1e4},
    }
    eps = np.zeros((400, 6))
    eps[:, 0] = np.linspace(0, 1e-3, 400)  # uniaxial strain in tension, past cracking
    out = dcfm.material_point(concrete, eps, char_length=0.1)
    d = out["damage_tension"]
    assert d[0] == 0 and 0.5 < d[-1] <= 1 and np.all(np.diff(d) >= 0)
    assert out["stress"][:, 0].max() < 1.3 * 2.9e6 / (1 - 0.18**2) * (1 - 0.18)  # bounded near f_t0
    bad = dict(concrete, plastic_damage=dict(concrete["plastic_damage"], ft0=-1.0))
    with pytest.raises(dcfm.DcfmError, match=r"^<material_point>: materials\.material\.plastic_damage"):
        dcfm.material_point(bad, eps[:2])


def test_stubs_match_the_module():
    pyi = Path(dcfm.__file__).with_name("__init__.pyi")
    tree = ast.parse(pyi.read_text(encoding="utf-8"))
    declared = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    declared |= {t.id for n in tree.body if isinstance(n, ast.AnnAssign) for t in [n.target] if isinstance(t, ast.Name)}
    declared -= {"FloatArray", "IntArray", "PairStateName"}
    assert declared == set(dcfm.__all__)
    assert Path(dcfm.__file__).with_name("py.typed").exists()
    for cls in ("Case", "Simulation", "Mesh", "RunResult"):
        node = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls)
        members = {m.name for m in node.body if isinstance(m, ast.FunctionDef)}
        members |= {m.target.id for m in node.body if isinstance(m, ast.AnnAssign)}
        for name in members:
            assert hasattr(getattr(dcfm, cls), name), f"{cls}.{name} declared in the stubs but missing"
