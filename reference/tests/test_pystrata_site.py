"""Cross-check: site response of a layered site under a real record, pystrata's linear
elastic (frequency-domain) calculation against dcfm's free-field column and its 3D model
with free-field sides, and the outcrop → within conversion of the seismic input.

Site: the W3 layering (``dcfm_reference/site.py``) — soil 30 m (V_s 300 m/s, ρ 2000) over
rock 30 m (V_s 1500 m/s, ρ 2500) on the elastic half-space of that rock. Damping: none in
the layers (pystrata: ξ = 0, frequency-independent; dcfm: no Rayleigh damping), so both
codes solve the same undamped linear problem and the only damping is radiation into the
half-space (|H| = 6.25 at the resonances). Tuning Rayleigh damping to pystrata's
frequency-independent ξ matches it at one or two frequencies only; the undamped site
compares like with like at every frequency.

Input: NIS090.AT2 (Kobe 1995, PEER AT2, shipped in pystrata's sdist; fixture with
PROVENANCE.md), mean removed, zero-phase Butterworth 0.1–15 Hz, resampled to 1 ms and end
corrected (dcfm's processing), given to both codes as the **outcrop** motion of the rock
half-space. pystrata: ``LinearElasticCalculator`` with the input at
``location("outcrop", index=-1)``; the record is padded with 20 s of zeros (pystrata's FFT
is periodic). dcfm: ``[seismic] definition = "outcrop"`` (u_in = ½ outcrop,
docs/boundaries.md §3) through the viscous-spring base, the motion given as a
``dcfm.Motion`` (``Case.from_dict(…, motions=…)``), 45 s.

Compared (tolerances of W3, whose mesh this is: ≥ 10 elements per wavelength up to 17 Hz
in the soil; the discrete column's resonances lie within 2 % of the continuum's, and near a
resonance of an undamped layer a 1 % frequency shift changes the response by a few %):

- transfer function |H(f)| = surface / outcrop input: resonances 1–3 (frequency ±2 %,
  peak ±5 %), dcfm's from the spectral ratio of its surface acceleration and the input it
  was driven with;
- surface motion: PGA and the 5 % response spectrum (dcfm's Nigam–Jennings for both
  series) at 0.1–4 s, ±5 %;
- outcrop → within: pystrata's within motion at the top of the half-space (the total,
  up + down, motion at the model's base) drives dcfm's rigid-base column
  (``definition = "within"``); its surface response spectrum against pystrata's surface
  (±5 %) and against dcfm's outcrop run (±5 %); and pystrata's incoming wave at the base is
  exactly ½ its outcrop motion (dcfm's convention, 1e-12).
"""

from __future__ import annotations

import importlib.metadata

import numpy as np
import pytest

import dcfm
from dcfm_reference import record, site
from dcfm_reference.paths import ROOT

pystrata = pytest.importorskip("pystrata")

CASE = "Site response of the W3 site under NIS090 (outcrop input, undamped layers on the rock half-space)"
PEER = f"pystrata {importlib.metadata.version('pystrata')} (linear elastic, frequency domain)"
SRC = "pystrata LinearElasticCalculator, same profile and input"
G = 9.80665
END = 45.0
PERIODS = np.logspace(-1, np.log10(4.0), 30)


@pytest.fixture(scope="module")
def inputs():
    m = dcfm.read_motion(ROOT / "verification/fixtures/motions/NIS090.AT2", name="kobe")
    return m.process(baseline="mean", highpass=0.1, lowpass=15.0, resample_dt=0.001, zero_end=True)


def pystrata_run(motion: dcfm.Motion):
    """pystrata's calculator on the W3 profile with `motion` as the half-space outcrop."""
    dt = motion.dt
    acc = np.concatenate([motion.acceleration, np.zeros(int(20.0 / dt))]) / G
    ts = pystrata.motion.TimeSeriesMotion("NIS090", "W3 input", dt, acc)
    layers = []
    for lay, thickness in ((site.SOIL, site.SOIL["thickness"]), (site.ROCK, site.ROCK["thickness"]), (site.ROCK, 0.0)):
        soil = pystrata.site.SoilType("layer", lay["density"] * G, None, 0.0)
        layers.append(pystrata.site.Layer(soil, thickness, lay["vs"]))
    profile = pystrata.site.Profile(layers)
    calc = pystrata.propagation.LinearElasticCalculator()
    loc_in = profile.location("outcrop", index=-1)
    calc(ts, profile, loc_in)
    n = motion.npts

    def series(loc):
        return ts.calc_time_series(calc.calc_accel_tf(loc_in, loc))[:n] * G

    out = {
        "calc": calc,
        "freqs": ts.freqs,
        "surface": series(profile.location("within", index=0)),
        "within_base": series(profile.location("within", index=-1)),
        "tf_surface": calc.calc_accel_tf(loc_in, profile.location("within", index=0)),
        "incoming_ratio": calc.calc_accel_tf(loc_in, profile.location("incoming_only", index=-1)),
    }
    return out


def dcfm_run(motion: dcfm.Motion, definition: str):
    case = dcfm.Case.from_dict(
        site.site_case({"definition": definition, "quantity": "acceleration", "x": {"type": "motion", "motion": "kobe", "component": "x"}}, end=END, title=f"W3 site, NIS090 {definition}"),
        label=f"w3_nis090_{definition}",
        motions={"kobe": motion},
    )
    centre = int(case.nodes_of("centre")[0])
    run = case.run(nodes=[centre], elements=[], free_field=True, record_every=2, threads=1)
    ff = run.free_field
    return {
        "dt_column": float(ff["time"][1] - ff["time"][0]),
        "t_column": ff["time"],
        "column": ff["acceleration"][:, -1, 0],
        "dt_3d": float(run.time[1] - run.time[0]),
        "centre": run.acceleration[:, 0, 0],
        "case_dt": case.dt,
    }


def psa(a: np.ndarray, dt: float) -> np.ndarray:
    m = dcfm.Motion.from_arrays(a, dt, "m/s2")
    return dcfm.response_spectrum(m, PERIODS, 0.05)["psa"]


def test_site_response(inputs):
    record.describe(CASE, "The W3 layering (soil 30 m, V_s 300, over rock 30 m, V_s 1500, on the rock half-space), "
                    "undamped layers (radiation damping only), NIS090 (0.1–15 Hz, 1 ms) as the rock-outcrop motion. pystrata's "
                    "linear-elastic frequency-domain solution against dcfm's reference free-field column and the 3D model "
                    "with free-field sides and the viscous-spring base (outcrop: u_in = ½ outcrop). Resonances ±2 %, peaks, "
                    "PGA and surface PSA (0.1–4 s) ±5 % (W3's mesh: ≥ 10 elements per wavelength to 17 Hz). Outcrop → "
                    "within: pystrata's within motion at the base drives dcfm's rigid-base column (definition = within).")
    ps = pystrata_run(inputs)
    out = dcfm_run(inputs, "outcrop")
    rows = []
    # pystrata's convention: incoming = ½ outcrop at the half-space (dcfm's u_in = ½ u_outcrop).
    ratio = ps["incoming_ratio"][1:]
    rows.append(record.check(CASE, "outcrop → incident: pystrata incoming / outcrop at the half-space (dcfm: ½)", 0.5, float(np.max(np.abs(ratio - 0.5))) + 0.5, 1e-12, SRC, PEER))

    # Transfer function: pystrata's |H| against dcfm's spectral ratio (same input seen by both).
    f_ps, tf_ps = ps["freqs"], np.abs(ps["tf_surface"])
    grid = np.arange(0.5, 15.0, 0.05)

    def h_ps(f):
        return float(np.interp(f, f_ps, tf_ps))

    ref = site.peaks(h_ps, grid, 3)
    t_in = np.arange(inputs.npts) * inputs.dt

    def ratio_fn(t, a, dt):
        inp = np.interp(t, t_in, inputs.acceleration, right=0.0)
        return lambda f: abs(site.dtft(a, dt, f) / site.dtft(inp, dt, f))

    col = ratio_fn(out["t_column"], out["column"], out["dt_column"])
    t3 = np.arange(len(out["centre"])) * out["dt_3d"]
    cen = ratio_fn(t3, out["centre"], out["dt_3d"])
    # pystrata's own |H| against the closed form (the peer's set-up).
    closed = site.peaks(lambda f: abs(site.layer_on_half_space(f)[0]), grid, 3)
    for j in range(3):
        rows.append(record.check(CASE, f"pystrata resonance {j + 1} (Hz) vs closed form", closed[j][0], ref[j][0], 0.01, "Kramer 1996 §7.2 (site.layer_on_half_space)", PEER))
    for name, fn in (("column", col), ("3D centre", cen)):
        pk = site.peaks(fn, grid, 3)
        print(name, pk, "pystrata", ref)
        for j in range(3):
            rows.append(record.check(CASE, f"dcfm {name}: resonance {j + 1} frequency (Hz)", ref[j][0], pk[j][0], 0.02, SRC, PEER))
            rows.append(record.check(CASE, f"dcfm {name}: resonance {j + 1} peak |H|", ref[j][1], pk[j][1], 0.05, SRC, PEER))

    # Surface motion: PGA and response spectra.
    sa_ps = psa(ps["surface"], inputs.dt)
    sa_col = psa(out["column"], out["dt_column"])
    sa_cen = psa(out["centre"], out["dt_3d"])
    pga_ps = float(np.max(np.abs(ps["surface"])))
    for name, a, sa in (("column", out["column"], sa_col), ("3D centre", out["centre"], sa_cen)):
        rows.append(record.check(CASE, f"dcfm {name}: surface PGA (m/s²)", pga_ps, float(np.max(np.abs(a))), 0.05, SRC, PEER))
        rows.append(record.check(CASE, f"dcfm {name}: surface PSA 0.1–4 s, max relative difference", 0.0, float(np.max(np.abs(sa / sa_ps - 1))), 0.05, SRC, PEER, absolute=True))

    # Outcrop → within: pystrata's within motion at the base drives dcfm's rigid-base column.
    within = dcfm.Motion.from_arrays(ps["within_base"], inputs.dt, "m/s2", name="kobe_within")
    win = dcfm_run(within, "within")
    sa_win = psa(win["column"], win["dt_column"])
    rows.append(record.check(CASE, "within (pystrata's base motion, rigid-base column): surface PSA vs pystrata", 0.0, float(np.max(np.abs(sa_win / sa_ps - 1))), 0.05, SRC, PEER, absolute=True))
    rows.append(record.check(CASE, "within vs outcrop input (both dcfm columns): surface PSA", 0.0, float(np.max(np.abs(sa_win / sa_col - 1))), 0.05, "dcfm outcrop run (this test)", PEER, absolute=True))

    f_plot = np.linspace(0.2, 15.0, 150)
    record.series(CASE, "|H(f)| surface / outcrop input", "frequency (Hz)", "|H|", f_plot, {
        "pystrata": [h_ps(f) for f in f_plot],
        "dcfm column": [col(f) for f in f_plot],
        "dcfm 3D centre": [cen(f) for f in f_plot],
    })
    record.series(CASE, "Surface PSA, 5 %", "T (s)", "PSA (m/s²)", PERIODS, {
        "pystrata": sa_ps, "dcfm column (outcrop)": sa_col, "dcfm 3D centre (outcrop)": sa_cen, "dcfm column (within)": sa_win,
    })
    assert not record.failures(rows), record.failures(rows)
