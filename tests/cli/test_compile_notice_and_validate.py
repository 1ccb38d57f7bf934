"""Two findings of a new user, each test failing on the code before the fix (main at 7bca391):

1. after ``vbikit demo`` (the one-lane kernels cached), ``vbikit study paper-fig6`` compiled the
   many-lane kernel ``lean_lanes`` for about a minute without a notice: the study's notice checked
   only the one-lane kernel ``lean``;
2. ``vbikit validate`` refused a traffic base scenario (``vehicle: missing required key``), and on
   ``examples/verification/fryba_moving_force.toml`` left out the three load-effect step warnings
   ``vbikit run`` reports (``vbikit.analysis.effect_step``), which need no run.
"""
from __future__ import annotations

import json
import logging
from pathlib import Path

import pytest
from typer.testing import CliRunner

from vbikit.cli import app

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
FRYBA = EXAMPLES / "verification" / "fryba_moving_force.toml"
BASE = EXAMPLES / "traffic" / "base" / "bridge2.toml"


@pytest.fixture
def after_demo(monkeypatch):
    """The state after ``vbikit demo``: the one-lane kernel ``lean_quadratic`` (the default "exact" holds the
    wheel loads quadratic) in numba's cache, nothing else;
    nothing announced yet in this process."""
    from vbikit.solve import compile_notice, kernels

    monkeypatch.setattr(compile_notice, "_ANNOUNCED", set())
    monkeypatch.setattr(compile_notice, "kernels_cached", lambda k: k is kernels.lean_quadratic)


def test_study_announces_the_many_lane_kernel_its_batches_run(after_demo, caplog):
    from vbikit.solve import kernels
    from vbikit.solve.compile_notice import COMPILE_SECONDS
    from vbikit.study.paper import paper_study
    from vbikit.study.run import _announce_compile, batch_kernels

    study = paper_study("fig6", 20, False, method="monte-carlo")
    batches = study.batches()
    assert len(batches[0]) > 1  # the batches run their crossings as lanes of one call
    assert batch_kernels(study, batches) == [kernels.lean_lanes_quadratic]
    with caplog.at_level(logging.INFO, logger="vbikit.solve.compile"):
        _announce_compile(study, batches, None, 2)
        _announce_compile(study, batches, None, 2)  # once a process and kernel
    assert caplog.text.count("compiling the kernel lean_lanes_quadratic") == 1
    assert f"about {COMPILE_SECONDS['lean_lanes_quadratic']} s of CPU" in caplog.text
    assert "each of the 2 worker processes" in caplog.text
    # its class D roads make wheels hop: the full kernel too, once (``may_hand_over``)
    assert caplog.text.count("compiling the kernel implicit") == 1 and "wheel leaves or lands" in caplog.text


def test_a_batch_of_one_crossing_runs_the_one_lane_kernel(after_demo, caplog):
    from vbikit.solve import kernels
    from vbikit.study.paper import paper_study
    from vbikit.study.run import _announce_compile, batch_kernels

    study = paper_study("fig6", 20, False, method="monte-carlo")
    one = [(study.batches()[0][0],)]
    assert batch_kernels(study, one) == [kernels.lean_quadratic]
    assert batch_kernels(study, [*one, study.batches()[0]]) == [kernels.lean_quadratic, kernels.lean_lanes_quadratic]
    with caplog.at_level(logging.INFO, logger="vbikit.solve.compile"):
        _announce_compile(study, one, None, 1)
    assert "kernel lean" not in caplog.text  # lean is cached (the demo compiled it)


def test_a_stream_that_settles_its_trucks_announces_the_run_in_loops():
    """A traffic stream's events drive their trucks the population's run-in first: its batches run the
    run-in's two compiled loops beside the one-lane kernel; with ``run_in = 0`` in the base scenario, not."""
    from vbikit.solve import kernels
    from vbikit.study.run import batch_kernels
    from vbikit.traffic import LaneTraffic, synthetic_stream
    from vbikit.traffic.study import traffic_study

    records = synthetic_stream([LaneTraffic(1, "+x", 600, 80, 5)], 3, seed=1)
    base = {"bridge": {"model": "paper-bridge-1-beam", "n_modes": 3}, "tire": {"model": "point"}, "road": {"class": "B"}}
    settled = traffic_study(records, base)
    assert settled.settles_vehicles
    assert batch_kernels(settled, settled.batches()) == [kernels.lean_quadratic, kernels.run_in_loads, kernels.linear_recursion]
    at_rest = traffic_study(records, base | {"crossing": {"run_in": 0}})
    assert not at_rest.settles_vehicles and batch_kernels(at_rest, at_rest.batches()) == [kernels.lean_quadratic]


def test_a_study_announces_the_full_kernel_only_where_wheels_may_leave_the_road():
    """``may_hand_over``: rigid-disk tires or roads of ISO 8608 class D and rougher, in the base or an axis."""
    from types import SimpleNamespace

    from vbikit.study.paper import paper_study
    from vbikit.study.run import may_hand_over

    assert may_hand_over(paper_study("fig6", 2, False, method="monte-carlo"))  # classes B–D
    smooth = {"tire": {"model": "point"}, "road": {"class": "B"}}
    assert not may_hand_over(SimpleNamespace(base=smooth, axes=()))
    assert may_hand_over(SimpleNamespace(base={**smooth, "road": {"class": "poor"}}, axes=()))
    assert may_hand_over(SimpleNamespace(base=smooth, axes=(SimpleNamespace(key="tire.model", values=("disk", "rigid-disk")),)))
    assert not may_hand_over(SimpleNamespace(base=smooth, axes=(SimpleNamespace(key="road.class", values=("A", "C")),)))
    assert may_hand_over(SimpleNamespace(base=smooth, axes=(SimpleNamespace(key="road.class", values=("C", "E")),)))


def test_validate_checks_a_traffic_base_scenario():
    res = runner.invoke(app, ["validate", str(BASE)])
    assert res.exit_code == 0, res.output
    assert "traffic base scenario" in res.output and "10 modes" in res.output
    # told by the missing [vehicle], it says so: a scenario whose vehicle was forgotten is not silently "ok"
    assert "`vbikit run` needs one" in res.output
    told = runner.invoke(app, ["validate", "--kind", "traffic-base", str(BASE)])
    assert told.exit_code == 0 and "`vbikit run` needs one" not in told.output


def test_validate_refuses_a_base_scenario_as_vbikit_traffic_does(tmp_path):
    path = tmp_path / "base.toml"
    path.write_text(BASE.read_text() + "\n[speeds]\nmin = 10\n")  # a section a base scenario does not take
    res = runner.invoke(app, ["validate", "--kind", "traffic-base", str(path)])
    assert res.exit_code != 0
    assert "a traffic base scenario takes" in res.output and "remove speeds" in res.output


def _warnings(output: str) -> list[str]:
    return [ln.removeprefix("warning: ") for ln in output.splitlines() if ln.startswith("warning: ")]


def test_validate_reports_the_step_warnings_run_reports():
    res = runner.invoke(app, ["validate", str(FRYBA)])
    assert res.exit_code == 0, res.output
    shown = _warnings(res.output)
    steps = [w for w in shown if "does not resolve" in w]
    assert len(steps) == 3 and all("crossing dt <= 0.00029 s" in w for w in steps)
    # the same warnings as the run's summary (the run computes them from its result)
    ran = runner.invoke(app, ["run", str(FRYBA), "--json"])
    assert ran.exit_code == 0, ran.output
    summary = json.loads(ran.stdout[ran.stdout.index("{"):])
    # beside them the run's half-step check finds its peak acceleration unconverged (a finding of the run alone)
    checked = [f for f in summary["flags"] if f["code"] == "step_not_converged"]
    assert [f["output"] for f in checked] == ["max_abs_acceleration"]
    assert sorted(shown) == sorted(w for w in summary["warnings"] if w not in [f["message"] for f in checked])


def test_a_scenario_with_a_misspelt_vehicle_table_is_still_read_as_a_scenario(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(BASE.read_text() + '\n[vehicel]\nmodel = "hs20-44"\n')  # not a base scenario's section
    res = runner.invoke(app, ["validate", str(path)])
    assert res.exit_code != 0 and "invalid scenario" in res.output and "vehicel: unknown key" in res.output


def test_lane_chunks_split_by_step_then_by_threads():
    """BatchSolver.run_many's split, by hand: the crossings of one step together, each group cut into
    ``threads`` calls of at most ``lanes``."""
    from vbikit.solve.batch import lane_chunks

    assert lane_chunks([1e-3, 1e-3, 2e-3]) == [(1e-3, [0, 1]), (2e-3, [2])]
    assert lane_chunks([1e-3] * 4, threads=2) == [(1e-3, [0, 1]), (1e-3, [2, 3])]
    assert lane_chunks([1e-3] * 3, threads=3) == [(1e-3, [0]), (1e-3, [1]), (1e-3, [2])]
    assert lane_chunks([1e-3] * 5, lanes=2) == [(1e-3, [0, 1]), (1e-3, [2, 3]), (1e-3, [4])]


def test_the_notice_names_the_one_lane_kernel_when_the_batch_is_split(after_demo, caplog):
    """A batch runs the many-lane kernel only if BatchSolver gives some call several crossings: with as
    many threads as crossings (``vbikit study run --threads``) every call has one, and a batch of a
    smooth and a random road (different steps: the random road's samples set its step) splits by step —
    in both cases only ``lean`` runs, which the demo compiled, so nothing is announced (the notice
    announced ``lean_lanes`` for every batch of two or more).  The steps are BatchSolver's own."""
    from vbikit.solve import kernels
    from vbikit.solve.batch import BatchSolver
    from vbikit.study.compute import _road
    from vbikit.study.paper import paper_study, paper_study_dict
    from vbikit.study.run import _announce_compile, batch_kernels, batch_steps
    from vbikit.study.spec import parse_study
    from vbikit.scenario import build, parse_scenario

    study = paper_study("fig6", 20, False, method="monte-carlo")
    batches = study.batches()
    assert batch_kernels(study, batches) == [kernels.lean_lanes_quadratic]
    assert batch_kernels(study, batches, threads=len(batches[0])) == [kernels.lean_quadratic]
    with caplog.at_level(logging.INFO, logger="vbikit.solve.compile"):
        _announce_compile(study, batches, None, 2, threads=len(batches[0]))
    assert "kernel lean" not in caplog.text  # (its class D roads announce the full kernel: ``may_hand_over``)

    d = paper_study_dict("fig6", 2, True) | {"axes": {"road.class": ["none", "C"]}}
    d["base"]["crossing"]["speed_kmh"] = 105  # class C's step is then set by its road (3 cm), the smooth road's by the truck
    mixed = parse_study(d)
    (batch,) = mixed.batches()
    assert len(batch) == 2
    steps = batch_steps(mixed, batch)
    dicts = [mixed.scenario_dict(idx) for idx in batch]
    scenarios = [parse_scenario(sd, mixed.base_dir) for sd in dicts]
    solver = BatchSolver(build(scenarios[0]).crossing)  # as run_batch: the first crossing, the others' roads
    assert steps == [solver.time_step(solver.crossing(*_road(sc, sd))) for sc, sd in zip(scenarios, dicts)]
    assert steps[0] != steps[1]
    assert batch_kernels(mixed, [batch]) == [kernels.lean_quadratic]


def test_the_full_kernel_announces_its_compilation(after_demo, caplog):
    """A new user's finding (2026-12-06): after ``vbikit demo``, ``vbikit compare-tires`` on the paper's
    Fig. 9 case spent ≈ 55 s in its rigid-disk row compiling the full contact kernel ``implicit``
    (``integrators._full``: rigid disks, and the steps where a wheel leaves or lands on the road)
    without a notice.  It is announced now, with its own expected time, once a process."""
    from vbikit.scenario import demo_scenario_text, scenario_from_toml
    from vbikit.scenario.preflight import preflight
    from vbikit.solve import simulate
    from vbikit.solve.compile_notice import COMPILE_SECONDS
    from vbikit.solve.integrators import without_lean

    crossing = preflight(scenario_from_toml(demo_scenario_text(), source="demo.toml")).built.crossing
    with caplog.at_level(logging.INFO, logger="vbikit.solve.compile"), without_lean():
        simulate(crossing)
        simulate(crossing)
    assert caplog.text.count("compiling the kernel implicit") == 1
    assert f"about {COMPILE_SECONDS['implicit']} s of CPU" in caplog.text and "wheel leaves or lands" in caplog.text
    assert COMPILE_SECONDS["implicit"] > 2 * COMPILE_SECONDS["lean"]  # (its own figure, not lean's default)
