"""A beam whose EI was typed in kN m² instead of N m² (a new user's trial: 4.5 m static deflection on
a 20 m span, only airborne-wheel warnings) is now flagged ``implausible_deflection``: a static
deflection peak above span/100 (vbikit.analysis.checks.IMPLAUSIBLE_DEFLECTION_FRACTION).

Independent number: the Yang–Yau sprung mass (examples/verification/yang_yau_sprung_mass.toml)
weighs P = 5750 kg · 9.81 m/s² = 56 407.5 N; a simply supported beam's midspan deflection under a
point load at midspan is P L³ / (48 EI) (closed form of the simply supported beam; z up, so the summary's peak is −that):
2.207 mm with EI = 8.323e9 N m² (L/11 300: not flagged) and 2.207 m with EI = 8.323e6 (the kN m² mistake:
L/11.3, flagged).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.analysis.checks import IMPLAUSIBLE_DEFLECTION_FRACTION, implausible_deflection_flags
from vbikit.cli import app

ROOT = Path(__file__).resolve().parents[2]
runner = CliRunner()
P, L = 5750.0 * 9.81, 25.0


def _run(text: str, tmp_path: Path) -> dict:
    path, summary = tmp_path / "s.toml", tmp_path / "s.json"
    path.write_text(text)
    res = runner.invoke(app, ["run", str(path), "--summary", str(summary)])
    assert res.exit_code == 0, res.output
    return json.loads(summary.read_text())


def test_ei_in_kilonewtons_flags_the_deflection_and_names_the_units(tmp_path):
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    assert "EI = 8.323e9" in text
    ok = _run(text, tmp_path)
    assert -ok["max_static_displacement"] == pytest.approx(P * L**3 / (48 * 8.323e9), rel=0.01)
    assert not [f for f in ok["flags"] if f["code"] == "implausible_deflection"]
    bad = _run(text.replace("EI = 8.323e9", "EI = 8.323e6"), tmp_path)
    closed = P * L**3 / (48 * 8.323e6)  # 2.207 m
    assert -bad["max_static_displacement"] == pytest.approx(closed, rel=0.01)
    (flag,) = [f for f in bad["flags"] if f["code"] == "implausible_deflection"]
    assert flag["value"] == pytest.approx(closed / L, rel=0.01) and flag["threshold"] == IMPLAUSIBLE_DEFLECTION_FRACTION
    assert flag["point"] == "p1"
    for words in ("not plausible for a bridge under this load", "EI in N m²", "E in Pa", "I in m⁴", "kg/m"):
        assert words in flag["message"]
    assert flag["message"] in bad["warnings"]


def test_threshold_is_span_over_100_and_the_largest_girder_is_named():
    peaks = [("Girder 1", -0.05, 1, None), ("Girder 2", -0.21, 2, None), ("point p1", -0.19, None, "p1")]
    assert implausible_deflection_flags(20.0, peaks[:1]) == []  # L/400: a soft but real bridge
    (flag,) = implausible_deflection_flags(20.0, peaks)  # 0.21 m > 20 m / 100
    assert flag.girder == 2 and flag.value == pytest.approx(0.21 / 20.0)
    assert implausible_deflection_flags(22.0, peaks[1:2]) == []  # 0.21 m on 22 m: L/105, below L/100


def test_the_unit_mistake_leads_the_warnings_and_marks_the_headline_im(tmp_path):
    """The second trial: the flag fired but came after seven contact-loss lines, and the headline IM
    of the report carried no mark. The cause now comes first in ``flags`` and ``warnings`` (and on
    stderr) and the IMPACT FACTOR line is marked with its legend."""
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    path = tmp_path / "soft.toml"
    path.write_text(text.replace("EI = 8.323e9", "EI = 8.323e6"))
    res = runner.invoke(app, ["run", str(path), "--summary", str(tmp_path / "s.json")])
    assert res.exit_code == 0, res.output
    s = json.loads((tmp_path / "s.json").read_text())
    assert len(s["flags"]) > 1  # the symptoms are flagged too
    assert s["flags"][0]["code"] == "implausible_deflection" and s["warnings"][0] == s["flags"][0]["message"]
    headline = next(line for line in res.output.splitlines() if "IMPACT FACTOR" in line)
    assert "!" in headline.split("(strain")[0]
    assert "check the units of the bridge's stiffness and mass" in res.output


def test_a_coarse_step_flag_names_the_impact_factor_it_marks(tmp_path):
    """The report marks the headline IM for ``coarse_step`` / ``unresolved_modes``; their records say
    so (``output`` = impact_factor), as docs/results.md's Flags paragraph states for every mark."""
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    s = _run(text + "\n" if "[crossing]" not in text else text.replace("[crossing]", "[crossing]\ndt = 0.05", 1),
             tmp_path)
    coarse = [f for f in s["flags"] if f["code"] in ("coarse_step", "unresolved_modes")]
    assert coarse and all(f["output"] == "impact_factor" for f in coarse)


def test_the_governing_girder_im_of_a_soft_deck_is_marked(tmp_path):
    """A 3D deck (paper Bridge 2) with E_girder and E_deck typed in kPa instead of Pa (1000 times too
    soft) under a moving force (no wheels to leave the road, so no other flag marks the IMs): a
    linear static solution scales with 1/E, so its static deflections are exactly 1000 times those of
    the real deck — metres on a 16.76 m span — and the report marks the governing girder's IM as it
    marks the headline IM (from the flag's code, ``has_flag``); the real deck's line is not marked."""
    deck = ('[bridge]\nmodel = "paper-bridge-2"\n[bridge.deck]\nE_girder = {E_girder}\nE_deck = {E_deck}\n'
            '[vehicle]\nmodel = "moving-force"\n[road]\nclass = "none"\n[crossing]\nspeed_kmh = 75\n'
            '[response]\ngirder = 4\n')
    runs = []
    for scale in (1.0, 1e-3):
        path, summary = tmp_path / "deck.toml", tmp_path / "s.json"
        path.write_text(deck.format(E_girder=36e9 * scale, E_deck=33e9 * scale))
        res = runner.invoke(app, ["run", str(path), "--summary", str(summary)])
        assert res.exit_code == 0, res.output
        line = next(line for line in res.output.splitlines() if line.strip().startswith("governing girder"))
        runs.append((json.loads(summary.read_text()), line))
    (ok, ok_line), (soft, soft_line) = runs
    g = soft["governing_girder"] - 1
    assert soft["girder_max_static_displacement"][g] == pytest.approx(1000 * ok["girder_max_static_displacement"][g],
                                                                      rel=1e-3)  # (peaks sampled at each run's own step)
    assert abs(ok["girder_max_static_displacement"][g]) < 16.76 * IMPLAUSIBLE_DEFLECTION_FRACTION
    assert abs(soft["girder_max_static_displacement"][g]) > 16.76 * IMPLAUSIBLE_DEFLECTION_FRACTION
    codes = [f["code"] for f in soft["flags"]]
    assert codes[0] == "implausible_deflection"
    assert not {"airborne_wheels", "coarse_step", "unresolved_modes"} & set(codes)  # nothing else marks the line
    assert soft_line.rstrip().endswith("!)") and not ok_line.rstrip().endswith("!)")


def test_validate_flags_the_unit_mistake_before_the_run_and_the_run_states_its_own(tmp_path):
    """``vbikit validate`` (a new user's trial: it said "ok" where the run then flagged L/0.0113) estimates the static
    deflection from the modes, the vehicle's weight as one force at the response point — for the sprung mass at
    midspan P L³ / (48 EI) within the retained modes (the first gives 96/π⁴ = 98.6 % of it, the example's 10 all but
    2e-4) — and warns with
    the same words; the run's summary holds one implausible_deflection flag, its own (from the static peaks)."""
    text = (ROOT / "examples" / "verification" / "yang_yau_sprung_mass.toml").read_text()
    good, bad = tmp_path / "good.toml", tmp_path / "bad.toml"
    good.write_text(text)
    bad.write_text(text.replace("EI = 8.323e9", "EI = 8.323e6"))
    ok = runner.invoke(app, ["validate", str(good)])
    assert ok.exit_code == 0 and "not plausible" not in ok.output
    res = runner.invoke(app, ["validate", str(bad)])
    assert res.exit_code == 0, res.output
    line = next(x for x in res.output.splitlines() if "not plausible" in x)
    assert "before the run" in line and "EI in N m²" in line
    closed = P * L**3 / (48 * 8.323e6)
    assert f"static deflection {closed:.3g} m" in line, line  # (10 modes: within 0.02 % of the closed form)
    summary = _run(bad.read_text(), tmp_path)
    (flag,) = [f for f in summary["flags"] if f["code"] == "implausible_deflection"]
    assert flag["point"] == "p1" and "before the run" not in flag["message"]


def test_the_estimate_before_the_run_takes_one_vehicle_s_axles_that_fit_on_the_span(tmp_path):
    """A train is not put on the span whole (HSLM-A1 weighs 8.5 MN; a new user's review found a plausible 10 m railway
    span, EI 1.6e9 N m², flagged L/90 when it was): ``heaviest_on_span`` is the heaviest window of one span over the
    axles, checked against every window by brute force, and the 10 m span is not flagged (its run finds about
    L/2000)."""
    import numpy as np

    from vbikit.scenario.preflight import heaviest_on_span
    from vbikit.vehicle.trains import get_train, train_vehicle

    train = train_vehicle(get_train("hslm-a1"))
    loads = np.asarray(train.static_wheel_loads())
    offsets = np.array([w.offset for w in train.wheels])
    for span in (5.0, 10.0, 20.0):
        brute = max(loads[(offsets >= a) & (offsets <= a + span)].sum() for a in offsets)
        assert heaviest_on_span(train, span) == pytest.approx(brute, rel=1e-12)
        assert heaviest_on_span(train, span) < 0.25 * loads.sum()
    path = tmp_path / "rail.toml"
    path.write_text('[bridge]\nspan = 10.0\nEI = 1.6e9\nmass_per_length = 10000.0\ndamping_ratio = 0.01\n'
                    '[vehicle]\nmodel = "hslm-a1"\n[crossing]\nspeed_kmh = 200\n[response]\n')
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code == 0 and "not plausible" not in res.output, res.output
