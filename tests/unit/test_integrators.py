"""The integrator registry (vbikit.solve.integrators) and the run plan (vbikit.solve.plan)."""
from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.scenario import parse_scenario
from vbikit.scenario.cite import scenario_references
from vbikit.solve import (
    INTEGRATORS,
    Crossing,
    UnstableTimeStepError,
    choose_time_step,
    get_integrator,
    integrator_names,
    plan_run,
    register_integrator,
    simulate,
)
from vbikit.vehicle import hs20_44, sprung_mass


@pytest.fixture(scope="module")
def beam():
    return EulerBernoulliBeam(20.0, 1e10, 6000.0, n_modes=4)


def test_builtin_integrators_are_registered():
    assert integrator_names()[:3] == ("exact", "rk4", "newmark")
    assert [get_integrator(n).explicit for n in ("exact", "rk4", "newmark")] == [False, True, False]
    assert get_integrator("rk4").stability_limit is not None
    assert get_integrator("exact").references == ("NigamJennings1969", "Chopra2017")


def test_unknown_integrator_lists_the_allowed_names(beam):
    with pytest.raises(ValueError, match="must be one of .*'exact'.*'rk4'.*'newmark'.*got 'euler'"):
        get_integrator("euler")
    with pytest.raises(ValueError, match="crossing.integrator must be one of"):
        Crossing(beam, sprung_mass(), integrator="euler")
    with pytest.raises(ValueError, match="unknown integrator 'euler'; allowed: 'exact', 'rk4', 'newmark'"):
        parse_scenario({"bridge": {"model": "beam", "span": 20.0, "EI": 1e10, "mass_per_length": 6000.0}, "vehicle": {"model": "hs20-44"}, "crossing": {"speed": 20.0, "integrator": "euler"}})


def test_an_explicit_integrator_needs_a_stability_limit():
    newmark = get_integrator("newmark")
    with pytest.raises(ValueError, match="stability_limit"):
        dataclasses.replace(newmark, name="broken", explicit=True)


def test_a_registered_integrator_runs_like_the_one_it_wraps(beam):
    newmark = get_integrator("newmark")
    copy = register_integrator(dataclasses.replace(newmark, name="newmark-copy", references=("Biggs1964",)))
    try:
        assert "newmark-copy" in integrator_names()
        with pytest.raises(ValueError, match="registered already"):
            register_integrator(dataclasses.replace(copy, run=get_integrator("rk4").run))
        a = simulate(Crossing(beam, sprung_mass(), speed=15.0, integrator="newmark"))
        b = simulate(Crossing(beam, sprung_mass(), speed=15.0, integrator="newmark-copy"))
        assert a.dt == b.dt
        np.testing.assert_array_equal(a.xi, b.xi)
        np.testing.assert_array_equal(a.q, b.q)
        # the scenario schema and the citations read the registry
        spec = parse_scenario({"bridge": {"model": "beam", "span": 20.0, "EI": 1e10, "mass_per_length": 6000.0}, "vehicle": {"model": "hs20-44"}, "crossing": {"speed": 20.0, "integrator": "newmark-copy"}})
        assert "Biggs1964" in [r.key for r in scenario_references(spec)]
    finally:
        INTEGRATORS.pop("newmark-copy", None)


def test_a_user_run_through_run_implicit_gets_the_vehicle_accelerations(beam):
    """A registered ``run`` that calls ``run_implicit`` and returns nothing (docs/extending.md's
    pattern): the lean kernels leave q̈ out, ``run_implicit`` says so in ``call.deferred``, and the
    result's q̈ is computed when read — the built-in "exact" integrator's to the last bit (the same
    maps), and not the zeros of the unfilled output (the HS20-44's largest acceleration on this
    smooth crossing is ≈ 0.4 m/s²)."""
    from vbikit.solve.integrators import run_implicit
    from vbikit.solve.modal_step import LINEAR, QUADRATIC, exact_step, vehicle_step

    def run(call):  # the built-in's maps: the wheel loads quadratic on the lean steps, linear on the full kernel's
        run_implicit(call, exact_step(call.data.modes.omega, call.data.modes.zeta, call.dt, QUADRATIC),
                     vehicle_step(call.data.vehicles, call.dt, QUADRATIC), vehicle_step(call.data.vehicles, call.dt, LINEAR))

    register_integrator(dataclasses.replace(get_integrator("exact"), name="exact-by-hand", run=run))
    try:
        mine = simulate(Crossing(beam, hs20_44(), speed=15.0, integrator="exact-by-hand"))
    finally:
        INTEGRATORS.pop("exact-by-hand", None)
    built_in = simulate(Crossing(beam, hs20_44(), speed=15.0, integrator="exact"))
    np.testing.assert_array_equal(mine.q, built_in.q)
    np.testing.assert_array_equal(mine.q_ddot, built_in.q_ddot)
    assert np.abs(mine.q_ddot).max() > 0.1


def test_a_stability_limit_of_an_implicit_integrator_is_enforced(beam):
    newmark = get_integrator("newmark")
    limited = register_integrator(dataclasses.replace(newmark, name="limited", stability_limit=lambda c: 1e-3))
    try:
        assert choose_time_step(Crossing(beam, sprung_mass(), integrator="limited")) == 0.9 * 1e-3
        with pytest.raises(UnstableTimeStepError, match="stability limit .* integrator = \"exact\""):
            choose_time_step(Crossing(beam, sprung_mass(), integrator="limited", dt=2e-3))
    finally:
        INTEGRATORS.pop(limited.name, None)


@pytest.mark.parametrize("integrator", ["exact", "rk4"])
def test_simulate_reuses_a_plan(beam, integrator):
    crossing = Crossing(beam, hs20_44(), speed=20.0, integrator=integrator)
    plan = plan_run(crossing)
    assert plan.dt == choose_time_step(crossing)
    assert plan.estimate.n_steps == plan.grid.n_steps
    data = plan.kernel_data
    planned = simulate(crossing, plan=plan)
    assert plan.kernel_data is data and planned.dt == plan.dt
    fresh = simulate(crossing)
    np.testing.assert_array_equal(planned.xi, fresh.xi)
    np.testing.assert_array_equal(planned.wheel_forces, fresh.wheel_forces)
    with pytest.raises(ValueError, match="another crossing"):
        simulate(dataclasses.replace(crossing, speed=21.0), plan=plan)


def test_planning_does_not_load_the_kernels():
    code = ("import sys\n"
            "from vbikit.bridge import EulerBernoulliBeam\n"
            "from vbikit.solve import Crossing, plan_run\n"
            "from vbikit.scenario.schema import Scenario\n"
            "from vbikit.vehicle import hs20_44\n"
            "plan = plan_run(Crossing(EulerBernoulliBeam(20.0, 1e10, 6000.0), hs20_44()))\n"
            "assert plan.dt > 0 and plan.n_steps > 0\n"
            "assert 'numba' not in sys.modules and 'vbikit.solve.kernels' not in sys.modules, "
            "sorted(m for m in sys.modules if 'numba' in m or 'kernels' in m)\n")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_rows_an_integrator_leaves_unwritten_fail_the_finiteness_check(beam):
    """The histories' rows after the static start come as NaN until the integrator writes them
    (``simulate._histories``): an integrator whose ``run`` stops half way (here: the built-in exact
    one, then its rows after the middle put back to how they came) is refused by ``check_finite``
    with the first unwritten step, instead of returning zeros or whatever memory held."""
    from vbikit.solve.result import DivergenceError

    exact = get_integrator("exact")
    seen = {}

    def run(call):
        before = [np.array(a[:, 1:], copy=True) for a in call.outputs]
        exact.run(call)
        half = call.outputs[0].shape[1] // 2
        seen["half"] = half
        seen["came_as_nan"] = all(np.isnan(b).all() for b in before)
        for a, b in zip(call.outputs, before):
            a[:, half:] = b[:, half - 1:]  # as they came: an integrator that stopped at the middle row

    register_integrator(dataclasses.replace(exact, name="half-written", run=run))
    try:
        with pytest.raises(DivergenceError, match=r"at step (\d+)") as err:
            simulate(Crossing(beam, sprung_mass(), speed=15.0, integrator="half-written"))
    finally:
        INTEGRATORS.pop("half-written", None)
    assert seen["came_as_nan"]
    assert f"at step {seen['half']} " in str(err.value)
