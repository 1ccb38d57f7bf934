"""A single run states how good its automatic step is (``step_check``, vbikit.scenario.step_check.half_step_check):
the same crossing at half the step, the largest change of a deflection or strain impact factor and the largest
relative change of a peak deck acceleration.  The independent numbers: the crossing simulated directly at the
run's step and at half of it (and a quarter), the IMs and accelerations read with ``point_response``."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import vbikit
from vbikit.analysis import point_response
from vbikit.scenario import build, load_scenario
from vbikit.solve import simulate

ROOT = Path(__file__).resolve().parents[2]
DEMO = ROOT / "src" / "vbikit" / "scenario" / "demo.toml"
FRYBA = ROOT / "examples" / "verification" / "fryba_moving_force.toml"


def _peak_accelerations(path: Path, steps: tuple[float, ...]) -> list[float]:
    """The peak |deck acceleration| at the scenario's response point, simulated directly at each step."""
    built = build(load_scenario(path))
    return [float(np.max(np.abs(point_response(simulate(dataclasses.replace(built.crossing, dt=step)),
                                               built.response_x, built.response_y).acceleration))) for step in steps]


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
    a_coarse, a_fine = _peak_accelerations(DEMO, (dt, dt / 2))
    assert report.summary["max_abs_acceleration"] == pytest.approx(a_coarse, rel=1e-12)
    assert check["acceleration_change"] == pytest.approx(abs(a_fine - a_coarse) / a_coarse, rel=1e-6)
    assert 0 < check["acceleration_change"] < 5e-3 and "acceleration" in check["acceleration_output"]
    assert f"{check['acceleration_change']:.2%}" == "0.09%"  # (quoted in docs/verification.md)
    assert not [f for f in report.summary["flags"] if f["code"] == "step_not_converged"]


def test_an_unconverged_peak_acceleration_is_flagged_where_the_impact_factors_are_converged():
    """Frýba's moving force (50 modes, undamped, 430 km/h): its IMs change by 4.5e-4 at half the automatic step, its
    peak deck acceleration by 0.77 % — the force rings the highest modes, which the step does not resolve.  The
    flag names the acceleration and its relative change; a quarter of the step shows it was right: the automatic
    step's peak is several times the tolerance away from the finer runs'."""
    report = vbikit.run(FRYBA)
    check, dt = report.summary["step_check"], report.summary["dt"]
    assert check["largest_change"] < 5e-3  # the deflection and strain IMs are converged
    a = _peak_accelerations(FRYBA, (dt, dt / 2, dt / 4))
    assert check["acceleration_change"] == pytest.approx(abs(a[1] - a[0]) / a[0], rel=1e-6)
    assert check["acceleration_output"] == "max_abs_acceleration"
    (flag,) = [f for f in report.summary["flags"] if f["code"] == "step_not_converged"]
    assert flag["output"] == "max_abs_acceleration" and flag["value"] == check["acceleration_change"]
    assert flag["threshold"] == 5e-3 and "% of its value" in flag["message"]
    assert abs(a[2] - a[0]) / a[0] > 2 * 5e-3  # the coarse peak is off by more than the flag says it may be
    assert f"{check['largest_change']:.1e}" == "4.5e-04"  # (these three quoted in docs/verification.md)
    assert f"{check['acceleration_change']:.2%}" == "0.77%" and f"{abs(a[2] - a[0]) / a[0]:.1%}" == "3.7%"


def test_a_peak_acceleration_changes_relative_to_itself_above_a_floor_and_girders_count():
    """The comparison itself: a point whose peak is near zero (at a support) changes relative to 1 % of the largest
    peak, not to its own round-off; every girder's peak is compared, by its index."""
    from vbikit.scenario.step_check import _largest_change

    coarse = {"max_abs_acceleration": 2.0, "points": [{"name": "mid", "max_abs_acceleration": 2.0},
                                                      {"name": "support", "max_abs_acceleration": 1e-9}],
              "girder_max_abs_acceleration": [1.0, 2.0], "impact_factor": 0.3}
    fine = {"max_abs_acceleration": 2.004, "points": [{"name": "mid", "max_abs_acceleration": 2.004},
                                                      {"name": "support", "max_abs_acceleration": 3e-9}],
            "girder_max_abs_acceleration": [1.0, 2.03], "impact_factor": 0.9}
    accelerations = ("max_abs_acceleration", "girder_max_abs_acceleration")
    change, worst = _largest_change(coarse, fine, accelerations, only_relative=True)
    assert worst == "girder_max_abs_acceleration[1]" and change == pytest.approx(0.015)
    fine["girder_max_abs_acceleration"][1] = 2.0
    change, worst = _largest_change(coarse, fine, accelerations, only_relative=True)
    assert worst == "max_abs_acceleration" and change == pytest.approx(0.002)  # not the support's 200 %
    assert _largest_change(coarse, fine)[1] == "impact_factor"  # the impact factors alone by default
    # every girder's deflection IM is an impact factor too (a list in the summary)
    girders = {"impact_factor": 0.3, "girder_impact_factors": [0.30, 0.20]}
    assert _largest_change(girders, {"impact_factor": 0.301, "girder_impact_factors": [0.30, 0.23]}) \
        == (pytest.approx(0.03), "girder_impact_factors[1]")
    # the flag: the peak accelerations' change alone (the IM's 0.6 is larger), the half step in its message
    from vbikit.scenario.step_check import acceleration_flags, is_acceleration

    fine["girder_max_abs_acceleration"][1] = 2.03
    (change, worst), (flag,), above = acceleration_flags(coarse, fine, 5e-4)
    assert above == ["girder_max_abs_acceleration[1]"]  # the others within the tolerance
    assert (worst, flag.output, flag.value) == ("girder_max_abs_acceleration[1]", worst, change)
    assert "changed by 1.50% of its value when the step was halved to 0.0005 s" in flag.message
    assert is_acceleration(worst) and is_acceleration("points[mid].max_abs_acceleration")
    assert not is_acceleration("points[mid].impact_factor") and not is_acceleration(None)


def test_a_change_above_the_tolerance_is_flagged_and_a_given_step_is_not_checked(monkeypatch, tmp_path):
    """Above ``STEP_TOLERANCE`` the summary gets ``step_not_converged`` naming the output; a run at a given
    crossing.dt states no step check (the user chose the step)."""
    from vbikit.scenario import step_check

    monkeypatch.setattr(step_check, "STEP_TOLERANCE", 1e-9)
    report = vbikit.run(DEMO)
    check = report.summary["step_check"]
    ims, accelerations = [f for f in report.summary["flags"] if f["code"] == "step_not_converged"]
    assert ims["value"] == check["largest_change"] and ims["output"] == check["output"]
    assert accelerations["value"] == check["acceleration_change"]
    assert accelerations["output"] == check["acceleration_output"]
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


def test_a_load_effect_halving_states_the_last_halving_s_acceleration_change():
    """A run that halves its step for its load effects (``converge_step``, not a train) stops when the impact factors
    settle and flags a peak deck acceleration that still changed by more than the tolerance over that last halving,
    with the change between the last two runs; a train's halving goes on for it instead (no such flag)."""
    from types import SimpleNamespace

    from vbikit.scenario.step_check import STEP_TOLERANCE, converge_step

    built = build(load_scenario(DEMO))
    peaks = {0: 1.0, 1: 1.02, 2: 1.03, 3: 1.031}  # by halving: 2 %, then 1 %, then 0.1 %
    ims = {0: 0.30, 1: 0.31, 2: 0.311, 3: 0.311}  # 0.01, then 0.001: settled at the second halving

    def report(k: int):
        summary = {"impact_factor": ims[k], "max_abs_acceleration": peaks[k], "flags": []}
        return SimpleNamespace(summary=summary, result=SimpleNamespace(integration_dt=1e-3 / 2 ** k, dt=1e-3 / 2 ** k),
                               k=k)

    def rerun(plan):
        return report(round(np.log2(1e-3 / plan.dt)))

    road_run = converge_step(report(0), built.crossing, rerun)
    assert road_run.k == 2  # the impact factors settled at the second halving
    (flag,) = [f for f in road_run.summary["flags"] if f["code"] == "step_not_converged"]
    assert flag["output"] == "max_abs_acceleration" and flag["value"] == pytest.approx(0.01 / 1.02)
    assert flag["value"] > STEP_TOLERANCE
    train_run = converge_step(report(0), built.crossing, rerun, train=True)
    assert train_run.k == 3 and not train_run.summary["flags"]  # halved on until the peak settled too
