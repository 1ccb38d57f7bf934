"""A single run states how good its automatic step is (``step_check``, vbikit.scenario.step_check.half_step_check):
the same crossing at half the step, and the largest change of a deflection or strain impact factor.  The
independent numbers: the crossing simulated directly at the run's step and at half of it, the IMs read with
``point_response``."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

import vbikit
from vbikit.analysis import point_response
from vbikit.scenario import build, load_scenario
from vbikit.solve import simulate

ROOT = Path(__file__).resolve().parents[2]
DEMO = ROOT / "src" / "vbikit" / "scenario" / "demo.toml"


def test_the_demo_states_the_change_at_half_its_step():
    report = vbikit.run(DEMO)
    check = report.summary["step_check"]
    dt = report.summary["dt"]
    assert check["dt"] == pytest.approx(dt / 2, rel=1e-12)
    built = build(load_scenario(DEMO))
    changes = {}
    for step in (dt, dt / 2):
        resp = point_response(simulate(dataclasses.replace(built.crossing, dt=step)), built.response_x,
                              built.response_y)
        changes.setdefault("impact_factor", []).append(resp.displacement_impact.impact_factor)
        changes.setdefault("strain_impact_factor", []).append(resp.strain_impact.impact_factor)
    by_hand = {k: abs(v[1] - v[0]) for k, v in changes.items()}
    assert report.summary["impact_factor"] == pytest.approx(changes["impact_factor"][0], abs=1e-12)
    assert check["largest_change"] == pytest.approx(max(by_hand.values()), rel=1e-6, abs=1e-12)
    assert check["output"] == max(by_hand, key=by_hand.get)
    assert 0 < check["largest_change"] < 5e-4  # (the automatic step's bound of docs/verification.md)
    assert f"{check['largest_change']:.1e}" == "5.2e-05"  # (quoted in docs/verification.md)
    assert not [f for f in report.summary["flags"] if f["code"] == "step_not_converged"]


def test_a_change_above_the_tolerance_is_flagged_and_a_given_step_is_not_checked(monkeypatch, tmp_path):
    """Above ``STEP_TOLERANCE`` the summary gets ``step_not_converged`` naming the output; a run at a given
    crossing.dt states no step check (the user chose the step)."""
    from vbikit.scenario import step_check

    monkeypatch.setattr(step_check, "STEP_TOLERANCE", 1e-9)
    report = vbikit.run(DEMO)
    (flag,) = [f for f in report.summary["flags"] if f["code"] == "step_not_converged"]
    assert flag["value"] == report.summary["step_check"]["largest_change"] and flag["output"]
    given = tmp_path / "given.toml"
    given.write_text(DEMO.read_text().replace("approach = 10", "approach = 10\ndt = 0.001"))
    assert "step_check" not in vbikit.run(given).summary


def test_step_check_false_leaves_it_out_and_a_crossing_gets_it_too():
    """``vbikit.run(..., step_check=False)`` runs the crossing once (no ``step_check``); a built Crossing run through
    ``vbikit.run`` states the same check as its scenario."""
    assert "step_check" not in vbikit.run(DEMO, step_check=False).summary
    built = build(load_scenario(DEMO))
    from_crossing = vbikit.run(built.crossing).summary["step_check"]
    assert from_crossing["largest_change"] > 0 and from_crossing["dt"] == pytest.approx(vbikit.run(DEMO).summary["dt"] / 2)
