"""Steps whose contact forces did not converge are counted and flagged, never only logged: the
result's ``unconverged_steps``, the catalogue output of that name (JSON, study and traffic
datasets), the run flag and the dataset flags ``contact_not_converged``.

The unconverged runs are made by allowing the full implicit kernel one contact-law evaluation a step
(``IMPLICIT_MAX_ITERATIONS`` = 1) on rigid-disk tyres, which go to that kernel directly: a step then
settles only if the first guess F = 2F_n − F_(n−1) already satisfies the contact law to 1e-10 of the
wheel load, which on a rough road (the warm-up crossing's 1 mm sine) no step does, and on a smooth road
only the steps where the tyre's envelope force is linear in time do."""
from __future__ import annotations

import copy
import math
from dataclasses import replace
from importlib import import_module

import numpy as np
import pytest

from vbikit.analysis.checks import FLAG_CODES, convergence_flags, run_flags, unconverged_dataset_flags
from vbikit.contact import RigidDiskTire
from vbikit.outputs import QUALITY_OUTPUTS, OUTPUTS
from vbikit.road import RoadProfile
from vbikit.solve import integrators, simulate
from vbikit.solve.batch import BatchSolver
from vbikit.solve.warmup import _tiny_crossing

simulate_module = import_module("vbikit.solve.simulate")  # (the package exports the function of that name)


@pytest.fixture
def one_iteration(monkeypatch):
    monkeypatch.setattr(integrators, "IMPLICIT_MAX_ITERATIONS", 1)
    monkeypatch.setattr(simulate_module, "UNCONVERGED_HALVINGS", 0)  # counted at the step given, not run again


def _disk_crossing(road=None):
    c = _tiny_crossing("exact")
    return replace(c, tire=RigidDiskTire(), **({"road": road} if road is not None else {}))


def test_a_sound_run_counts_none_and_is_not_flagged():
    result = simulate(_disk_crossing())
    assert result.unconverged_steps == 0
    assert convergence_flags(result) == []
    assert "contact_not_converged" not in [f.code for f in run_flags(result)]


def test_every_step_of_a_rough_road_at_one_iteration_is_counted_and_flagged(one_iteration):
    result = simulate(_disk_crossing())
    steps = result.n_steps  # every step stored (no thinning)
    assert result.unconverged_steps == steps
    [flag] = [f for f in run_flags(result) if f.code == "contact_not_converged"]
    assert flag.value == steps and flag.threshold == 0.0 and flag.output == "unconverged_steps"
    assert f"in {steps} of the run's {steps} time steps" in flag.message
    assert "shorter crossing.dt" in flag.message and "rk4" in flag.message
    from vbikit.outputs import Reduction

    assert OUTPUTS["unconverged_steps"].reduce(Reduction(result=result, point=None, effects={})) == float(steps)


def test_a_batch_of_rigid_disk_lanes_counts_a_step_for_every_lane(one_iteration):
    """The full kernel's lanes settle together: a step any lane needs more evaluations for counts for
    all (documented on ``CrossingResult.unconverged_steps``); each lane alone on the smooth road
    settles in fewer steps' worth (the steps where the rough lane needs more are not its own)."""
    x = np.linspace(-20.0, 30.0, 5001)
    smooth, rough = RoadProfile(x, 0.0 * x, "smooth"), RoadProfile(x, 1e-3 * np.sin(x), "rough")
    crossing = _disk_crossing(smooth)
    batch = BatchSolver(crossing).run_many([smooth, rough])
    alone = [simulate(replace(crossing, road=r)).unconverged_steps for r in (smooth, rough)]
    assert batch[0].unconverged_steps == batch[1].unconverged_steps > 0
    assert alone[0] < alone[1]
    assert batch[0].unconverged_steps >= max(alone)


def test_dataset_flag_counts_crossings_and_names_the_worst():
    counts = np.array([[0.0, 4.0], [math.nan, 1.0]])
    [flag] = unconverged_dataset_flags(counts, describe=lambda i: f"cell {i}")
    assert flag.code == "contact_not_converged" and flag.value == 4.0
    assert "in some time steps of 2 of 4 crossings" in flag.message
    assert "the most: 4 steps in cell (0, 1)" in flag.message
    assert unconverged_dataset_flags(np.zeros(3)) == []
    [event] = unconverged_dataset_flags(np.array([0.0, 0.0, 7.0]), "event")
    assert "1 of 3 events" in event.message and "7 steps in event 2" in event.message


def test_the_flag_code_and_the_quality_outputs_are_in_their_one_place():
    assert "contact_not_converged" in FLAG_CODES
    assert all(name in OUTPUTS and OUTPUTS[name].scope == "crossing" for name in QUALITY_OUTPUTS)


def test_a_study_that_asks_for_other_outputs_still_stores_and_flags_it(tmp_path, one_iteration):
    """A study of rigid-disk crossings at one iteration a step: ``unconverged_steps`` is stored although
    only ``impact_factor`` was asked for, every crossing counts steps, and the dataset says so."""
    from vbikit.study import parse_study, run_study

    base = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "vehicle": {"model": "two-axle"},
            "tire": {"model": "rigid-disk"}, "road": {"class": "C", "length": 200}, "crossing": {"speed_kmh": 90}}
    spec = {"name": "unconverged", "seed": 3, "batch_size": 2, "base": copy.deepcopy(base),
            "axes": {"crossing.speed_kmh": [60, 90]}, "outputs": ["impact_factor"]}
    ds = run_study(parse_study(spec), tmp_path / "s.nc", workers=1)
    counts = ds["unconverged_steps"].values
    assert counts.shape == (2,) and np.all(counts > 0)
    assert "contact_not_converged" in ds.attrs["flag_codes"]
    assert "2 of 2 crossings" in ds.attrs["warnings"]


def test_a_traffic_stream_stores_and_flags_it(tmp_path, one_iteration):
    """Three trucks on rigid-disk tyres at one iteration a step, the stream asking for the impact
    factor only: every event counts steps, the dataset's warnings say how many events."""
    from vbikit.study import run_study
    from vbikit.traffic import LaneTraffic, synthetic_stream
    from vbikit.traffic.study import traffic_study

    stream = synthetic_stream([LaneTraffic(1, "+x", 900, 80, 5)], 3, seed=2)
    base = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 4}, "tire": {"model": "rigid-disk"},
            "road": {"class": "B", "length": 200.0}, "crossing": {"approach": 5.0, "free_vibration": 0.1}}
    ds = run_study(traffic_study(stream, base, seed=5, batch_size=2, outputs=["impact_factor"]), tmp_path / "t.nc",
                   workers=1)
    counts = ds["unconverged_steps"].values
    assert counts.shape == (ds.sizes["event"],) and np.all(counts > 0)
    assert "contact_not_converged" in ds.attrs["flag_codes"]
    assert f"{counts.size} of {counts.size} events" in ds.attrs["warnings"]
