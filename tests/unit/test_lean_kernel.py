"""The lean single-lane kernel (vbikit.solve.kernels.lean) against the full implicit kernel.

``run_implicit`` runs one lane through ``kernels.lean`` (the one-evaluation steps only, flat) and
hands the crossing over to ``kernels.implicit`` when it stops at a step it does not take; with
``integrators.USE_LEAN`` off every run goes to ``implicit``.  Both solve the same end-of-step
contact forces to the same tolerance with the same arithmetic on the common path (the same first
guess, the same quasi-Newton updates and exact increments), so their histories agree to round-off:
measured ≤ 5e-14 of each history's peak on these cases (fastmath reorders the sums), asserted
≤ 1e-10, far below the integrators' own accuracy (the step: ≈ 5e-6 of the peak,
benchmarks/README.md).  The reference is the independent code path: ``implicit``, generic over
lanes, with its own contact law (``contact_forces``), state and update helpers.
"""
from __future__ import annotations

import logging
import re
from pathlib import Path

import numpy as np
import pytest

from vbikit.bridge import EulerBernoulliBeam
from vbikit.road.psd import RoadPSD, random_profile
from vbikit.scenario import demo_scenario_text, load_scenario, parse_scenario, scenario_from_toml
from vbikit.scenario.preflight import preflight
from vbikit.solve import Crossing, integrators, simulate
from vbikit.solve.crossing import VehicleMotion
from vbikit.vehicle import hs20_44, semitrailer_3s2

ROOT = Path(__file__).resolve().parents[2]
HISTORIES = ("xi", "xi_dot", "xi_ddot", "q", "q_dot", "q_ddot", "wheel_forces", "contact_lengths")


def _both(crossing):
    """The crossing by the default dispatch and by ``implicit`` alone, and how the first ran."""
    before = dict(integrators.LEAN_COUNTS)
    default = simulate(crossing)
    ran = {k: integrators.LEAN_COUNTS[k] - before[k] for k in before}
    with integrators.without_lean():
        reference = simulate(crossing)
    assert integrators.USE_LEAN and integrators.LEAN_COUNTS["implicit"] == before["implicit"] + 1
    return default, reference, ran


def _worst(a, b) -> float:
    """max |a − b| / peak |b| over every history."""
    return max(float(np.max(np.abs(getattr(a, h) - getattr(b, h)))) / max(float(np.max(np.abs(getattr(b, h)))), 1e-300)
               for h in HISTORIES)


def _scenario(text_or_dict):
    built = preflight(parse_scenario(text_or_dict) if isinstance(text_or_dict, dict) else text_or_dict).built
    return built.crossing


def test_demo_crossing_runs_lean_and_equals_implicit():
    """`vbikit demo`: HS20-44, multipoint n = 6 (36 points), ISO C, 75 km/h, 1,914 steps."""
    crossing = _scenario(scenario_from_toml(demo_scenario_text(), source="demo.toml"))
    lean, full, ran = _both(crossing)
    assert ran == {"lean": 1, "fallback": 0, "implicit": 0, "lanes": 0, "lanes_fallback": 0}
    assert _worst(lean, full) <= 1e-10


def test_point_tire_runs_lean_and_equals_implicit():
    crossing = _scenario({"bridge": {"model": "paper-bridge-1-beam"}, "vehicle": {"model": "hs20-44"},
                          "tire": {"model": "point"}, "road": {"class": "B", "seed": 3},
                          "crossing": {"speed_kmh": 60.0}})
    lean, full, ran = _both(crossing)
    assert ran["lean"] == 1 and ran["fallback"] == 0
    assert _worst(lean, full) <= 1e-10


@pytest.mark.usefixtures("linear_wheel_loads")
def test_two_vehicles_asymmetric_run_lean_and_equal_implicit():
    """A traffic-like event: a 3S2 driving +x off the centreline and an HS20-44 driving −x,
    entering later, at other speeds, on a class B road (stacked vehicles, two directions)."""
    beam = EulerBernoulliBeam(span=30.0, EI=2.0e10, mass_per_length=1.2e4, damping_ratio=0.02, n_modes=12)
    road = random_profile(RoadPSD.iso("B"), length=120.0, seed=4, x_start=-50.0)
    crossing = Crossing(beam, road=road, approach=3.0, free_vibration=0.1,
                        vehicles=(VehicleMotion(semitrailer_3s2(), 22.0, lateral_offset=1.2),
                                  VehicleMotion(hs20_44(), 17.0, direction="-x", entry_time=0.4)))
    lean, full, ran = _both(crossing)
    assert ran["lean"] == 1 and ran["fallback"] == 0
    assert _worst(lean, full) <= 1e-10


def test_3d_deck_runs_lean_and_equals_implicit():
    """examples/paper/bridge2_hs20_girder4.toml: the 3D paper-bridge-2 deck, 20 modes."""
    crossing = _scenario(load_scenario(ROOT / "examples" / "paper" / "bridge2_hs20_girder4.toml"))
    lean, full, ran = _both(crossing)
    assert ran["lean"] == 1 and ran["fallback"] == 0
    assert _worst(lean, full) <= 1e-10


def _hop(tire: str, road: str, seed: int = 1):
    """HS20-44 at 100 km/h on paper Bridge 1 (beam) over a rough road: heavy wheel hop."""
    return _scenario({"bridge": {"model": "paper-bridge-1-beam"}, "vehicle": {"model": "hs20-44"},
                      "tire": {"model": tire}, "road": {"class": road, "seed": seed}, "crossing": {"speed_kmh": 100.0}})


@pytest.mark.usefixtures("linear_wheel_loads")
def test_lift_off_settled_by_one_evaluation_stays_lean_and_equals_implicit():
    """Point tires on a class F road: the wheels leave the road and land again thousands of times;
    where the one evaluation already gives the step's contact set (as in ``implicit``'s own
    one-evaluation step) the lean kernel takes the step, and the histories agree to round-off."""
    lean, full, ran = _both(_hop("point", "F"))
    assert ran["lean"] == 1 and ran["fallback"] == 0
    assert int(np.sum(full.wheel_forces[1:] == 0.0)) > 1000  # wheels off the road in > 1000 samples
    assert _worst(lean, full) <= 1e-10


@pytest.mark.usefixtures("linear_wheel_loads")
@pytest.mark.parametrize("every", [1, 3])
def test_lift_off_that_needs_iterating_hands_over_to_implicit(caplog, every):
    """Disk tires on a class F road (seed 12; with the deck's loads held quadratic over the step,
    2026-12-05, seeds 1–8, 10, 11 and 13 settle every landing with the one evaluation, as most class D
    roads do, while seeds 9 and 12 hand over): at a landing a contact closes within the step's updates, the
    lean kernel stops there and ``implicit`` goes on from the last state stored (every ``every``-th
    step) for ``LEAN_WINDOW`` steps, then the lean kernel again (``integrators._finish_lane``).  Each
    restart evaluates the law at the stored state and extrapolates from it alone (not from the two
    previous steps' iterates), so the histories differ from an ``implicit`` run from t = 0 by the
    tolerance's order (the iterates agree to IMPLICIT_TOLERANCE = 1e-10 of the largest wheel load;
    accelerations amplify it): measured 5.0e-13 (every step) and 4.6e-13 (every 3rd) of the peak here,
    4.8e-11 and 2.4e-11 with seed 9, asserted ≤ 1e-9.  The hold's loads of the step before a
    hand-over's row are the ones the kernels leave at each stored row, so the thinned run hands over
    exactly too."""
    crossing = _hop("disk", "F", seed=12)
    caplog.set_level(logging.DEBUG, logger="vbikit.solve.integrators")
    before = dict(integrators.LEAN_COUNTS)
    handed = simulate(crossing, output_every=every)
    with integrators.without_lean():
        full = simulate(crossing, output_every=every)
    assert integrators.LEAN_COUNTS["fallback"] == before["fallback"] + 1
    assert integrators.LEAN_COUNTS["lean"] == before["lean"]
    found = [m for r in caplog.records if (m := re.search(r"of (\d+) .* goes on from step (\d+)", r.getMessage()))]
    assert len(found) >= 1
    for m in found:
        n_steps, start = int(m.group(1)), int(m.group(2))
        assert 0 < start < n_steps and start % every == 0
    assert int(np.sum(full.wheel_forces[1:] == 0.0)) > 10  # a wheel does leave the road
    assert _worst(handed, full) <= 1e-9


def test_thinned_histories_are_rows_of_the_full_ones():
    """Stored every 3rd step (``output_every``): the lean kernel's rows are those of every step."""
    crossing = _scenario(scenario_from_toml(demo_scenario_text(), source="demo.toml"))
    every = simulate(crossing)
    before = integrators.LEAN_COUNTS["lean"]
    thin = simulate(crossing, output_every=3)
    assert integrators.LEAN_COUNTS["lean"] == before + 1
    for h in HISTORIES:
        np.testing.assert_array_equal(getattr(thin, h), getattr(every, h)[::3])


def test_a_batch_of_roads_runs_the_many_lane_lean_kernel_and_equals_lean_single_runs():
    """Two roads as lanes of one ``lean_lanes`` call (padded to 8 lanes), each equal to its own
    crossing run by the lean kernel."""
    from dataclasses import replace

    from vbikit.solve.batch import BatchSolver

    crossing = _scenario({"bridge": {"model": "paper-bridge-1-beam"}, "vehicle": {"model": "hs20-44"},
                          "tire": {"model": "point"}, "road": {"class": "B", "seed": 3},
                          "crossing": {"speed_kmh": 60.0}})
    roads = [crossing.road, replace(crossing.road, z=0.5 * crossing.road.z)]
    before = dict(integrators.LEAN_COUNTS)
    lanes = BatchSolver(crossing).run_many(roads)
    assert integrators.LEAN_COUNTS["lanes"] == before["lanes"] + 8
    assert integrators.LEAN_COUNTS["implicit"] == before["implicit"]
    assert integrators.LEAN_COUNTS["lean"] == before["lean"]
    for road, lane in zip(roads, lanes):
        single = simulate(replace(crossing, road=road))
        assert _worst(lane, single) <= 1e-10


def test_the_default_path_compiles_each_flat_kernel_once():
    """The static start calls the compiled contact law ``_law`` from Python (``kernels.lean_law``) with
    the argument types ``lean`` calls it with, so the two share one compilation: after the demo crossing
    and its static reference ``_law`` and ``lean`` have a single specialisation each, and the demo adds at
    most one to the static reference (another one, e.g. from a non-contiguous or read-only argument,
    would compile a kernel again: ≈ 1 s for ``_law``, benchmarks/bench_compile.py; a batch's road
    columns once did so for the compiled assembly, now numpy's, ``system.coupled_system``).  And the flat kernels compile without
    reference counting and rewrite passes (``FLAT_OPTIONS``; should a numba not know those options they
    are dropped, and the cold compile takes ≈ 0.6 s longer)."""
    from vbikit.analysis import static_modal_history
    from vbikit.solve import builtin_integrators, kernels
    from vbikit.solve.kernels.bundles import FLAT_OPTIONS
    from vbikit.solve.kernels.lean import _law, _quasi, _state

    shared = {"static_modal_history": kernels.static_modal_history}
    before = {name: len(k.signatures) for name, k in shared.items()}
    static_modal_history(simulate(_scenario(scenario_from_toml(demo_scenario_text(), source="demo.toml"))))
    # (the helpers of ``lean`` have none when ``lean`` came from numba's cache: its code holds theirs)
    # (the default's variant of ``lean``: the wheel loads held quadratic, ``builtin_integrators.QUADRATIC_WHEEL_LOADS``)
    lean = kernels.lean_quadratic if builtin_integrators.QUADRATIC_WHEEL_LOADS else kernels.lean
    assert (len(_law.signatures), len(lean.signatures)) == (1, 1)
    assert len(_state.signatures) <= 1 and len(_quasi.signatures) <= 1
    assert all(len(k.signatures) - before[name] <= 1 for name, k in shared.items())
    assert FLAT_OPTIONS.get("_nrt") is False and FLAT_OPTIONS.get("no_rewrites") is True


@pytest.mark.usefixtures("linear_wheel_loads")
def test_two_trucks_on_the_3d_deck_run_lean_and_equal_implicit():
    """examples/traffic/two_trucks.toml: a 3-S2 and a three-axle truck in opposite lanes of
    paper-bridge-2, one coupled run (the vehicles stacked block-diagonally,
    ``vehicle.model.combine_vehicles``): the lean kernel with the step map's fused products
    (``FusedVehicleStep``: ``free``, each wheel's nonzero entries) and q̈ when read
    (``result.vehicle_accelerations``) equals ``implicit`` with the unfused products
    (settle·(transition z + load0 G + constant)) and q̈ = M⁻¹(F_G + HᵀG − Ĉq̇ − K̂q) a step."""
    crossing = _scenario(load_scenario(ROOT / "examples" / "traffic" / "two_trucks.toml"))
    assert len(crossing.vehicles) == 2
    lean, full, ran = _both(crossing)
    assert ran["lean"] == 1 and ran["fallback"] == 0
    assert _worst(lean, full) <= 1e-10


def _two_truck_maps():
    """The exact step map of the 3-S2 and the HS20-44 stacked (two different trucks), its fused maps
    and the vehicles' arrays."""
    from vbikit.solve.modal_step import fused_step, vehicle_step
    from vbikit.solve.system import vehicles_data
    from vbikit.vehicle.model import combine_vehicles

    beam = EulerBernoulliBeam(span=30.0, EI=2.0e10, mass_per_length=1.2e4, damping_ratio=0.02, n_modes=4)
    crossing = Crossing(beam, vehicles=(VehicleMotion(semitrailer_3s2(), 22.0), VehicleMotion(hs20_44(), 17.0)))
    vehicles = vehicles_data(combine_vehicles([semitrailer_3s2(), hs20_44()]), crossing.contact)
    step = vehicle_step(vehicles, 0.002)
    return vehicles, step, fused_step(vehicles, step)


def test_fused_vehicle_maps_equal_the_unfused_products():
    """``modal_step.fused_step``'s maps against the products they replace, on random states and wheel loads
    of two different trucks stacked: P Φ z + P L0 G + P g = P (Φ z + L0 G + g) (the free response,
    as ``implicit`` forms it)."""
    vehicles, step, fused = _two_truck_maps()
    from vbikit.solve.modal_step import fused_step

    assert fused_step(vehicles, step) is fused  # made once per step map
    n_d, n_w = vehicles.gravity.size, vehicles.wheel_rows.shape[0]
    rng = np.random.default_rng(11)
    for _ in range(5):
        z = rng.normal(size=2 * n_d) * np.r_[np.full(n_d, 1e-2), np.full(n_d, 1e-1)]
        g = rng.normal(size=n_w) * 1e4
        free = step.settle @ (step.transition @ z + step.load0 @ g + step.constant)
        got = fused.free @ z + fused.free_load @ g + fused.free_constant
        np.testing.assert_allclose(got, free, rtol=0, atol=1e-12 * np.abs(free).max())


def test_vehicle_accelerations_solve_the_equation_of_motion_with_the_nominal_tires():
    """``result.vehicle_accelerations`` (q̈ when read, from the vehicles' own K, C and the tire
    forces F_w) on random histories of two different trucks stacked, two lanes: row by row the solution
    of M q̈ = F_G + Hᵀ G − Ĉ q̇ − K̂ q (numpy's solve with M itself), the implicit step's form with the
    nominal tires (K̂, Ĉ of the step map) and G = F_w + k_w h_w·q + c_w h_w·q̇ the loads it carries."""
    from vbikit.solve.result import vehicle_accelerations

    vehicles, step, _ = _two_truck_maps()
    n_d, n_w = vehicles.gravity.size, vehicles.wheel_rows.shape[0]
    rng = np.random.default_rng(12)
    q = rng.normal(size=(2, 7, n_d)) * 1e-2
    q_dot = rng.normal(size=(2, 7, n_d)) * 1e-1
    forces = rng.normal(size=(2, 7, n_w)) * 1e4
    got = vehicle_accelerations(vehicles, q, q_dot, forces, np.full((2, 7, n_d), np.nan))
    rows = vehicles.wheel_rows
    for lane in range(2):
        for t in range(7):
            z, z_dot = q[lane, t], q_dot[lane, t]
            loads = forces[lane, t] + vehicles.wheel_stiffness * (rows @ z) + vehicles.wheel_damping * (rows @ z_dot)
            rhs = vehicles.gravity + rows.T @ loads - step.c_hat @ z_dot - step.k_hat @ z
            want = np.linalg.solve(vehicles.mass, rhs)
            np.testing.assert_allclose(got[lane, t], want, rtol=0, atol=1e-12 * np.abs(want).max())


def test_wheel_entries_give_the_dense_wheel_rows():
    """``kernels.lean.wheel_entries``: each wheel's nonzero entries (index, value), ascending, padded
    with (0, 0.0), read back into a dense matrix give the rows exactly — on the stacked trucks and on
    a coupled random matrix with scattered zeros, entries in its first and last columns and an empty
    row (a left-out or misplaced entry would change h_w·q); and the sum over the entries in their
    order equals the dense product."""
    from vbikit.solve.kernels.lean import wheel_entries

    vehicles, _, fused = _two_truck_maps()
    dof, h = wheel_entries(vehicles.wheel_rows)
    np.testing.assert_array_equal(dof, fused.wheel_dof)
    np.testing.assert_array_equal(h, fused.wheel_h)
    rng = np.random.default_rng(5)
    coupled = rng.normal(size=(6, 9)) * (rng.random((6, 9)) < 0.6)
    coupled[0, 0], coupled[1, -1], coupled[2] = 1.5, -2.5, 0.0
    for rows in (vehicles.wheel_rows, coupled):
        dof, h = wheel_entries(rows)
        assert dof.dtype == np.int64 and dof.shape == h.shape == (rows.shape[0], int((rows != 0).sum(1).max()))
        back = np.zeros_like(rows)
        for w in range(rows.shape[0]):
            assert np.all(np.diff(dof[w][h[w] != 0]) > 0)
            back[w, dof[w][h[w] != 0]] = h[w][h[w] != 0]
        np.testing.assert_array_equal(back, rows)
        z = rng.normal(size=rows.shape[1])
        np.testing.assert_allclose((h * z[dof]).sum(axis=1), rows @ z, rtol=1e-14, atol=1e-14)
    assert wheel_entries(np.zeros((0, 4)))[0].shape == (0, 0)


def test_lean_results_compute_the_vehicle_accelerations_when_read():
    """A lean run leaves q̈ out of the step loop: its result holds a ``DeferredAccelerations`` until
    ``q_ddot`` is read (``check_finite`` does not read it), then the array, equal to the full kernel's
    q̈ (which computes it every step) to 1e-10 of its peak; a result pickled unread gives the same q̈."""
    import pickle

    from vbikit.solve.result import DeferredAccelerations, check_finite

    crossing = _scenario(scenario_from_toml(demo_scenario_text(), source="demo.toml"))
    lean, full, ran = _both(crossing)
    assert ran["lean"] == 1
    assert isinstance(lean.__dict__["_q_ddot"], DeferredAccelerations)
    assert check_finite(lean) is lean and isinstance(lean.__dict__["_q_ddot"], DeferredAccelerations)
    copy = pickle.loads(pickle.dumps(lean))
    got = lean.q_ddot
    assert isinstance(lean.__dict__["_q_ddot"], np.ndarray) and lean.q_ddot is got
    assert isinstance(full.__dict__["_q_ddot"], np.ndarray)  # implicit alone: filled by the kernel
    peak = np.abs(full.q_ddot).max()
    assert peak > 0 and np.abs(got - full.q_ddot).max() <= 1e-10 * peak
    np.testing.assert_array_equal(copy.q_ddot, got)


def test_moving_force_results_have_empty_vehicle_accelerations():
    """A moving force has no vehicle DOFs: its deferred q̈ is an empty (n_t, 0) history, not an error."""
    from vbikit.vehicle.presets import VEHICLE_PRESETS

    beam = EulerBernoulliBeam(span=20.0, EI=2.0e10, mass_per_length=1.2e4, damping_ratio=0.02, n_modes=3)
    result = simulate(Crossing(beam, vehicle=VEHICLE_PRESETS["moving-force"].build(), speed=20.0))
    assert result.q_ddot.shape == (result.time.size, 0)


def test_a_result_state_with_the_plain_field_name_reads_its_accelerations():
    """A result pickled before q̈ was deferred keeps it under ``q_ddot`` in its state: still read."""
    from vbikit.solve.result import CrossingResult

    beam = EulerBernoulliBeam(span=20.0, EI=2.0e10, mass_per_length=1.2e4, damping_ratio=0.02, n_modes=3)
    result = simulate(Crossing(beam, vehicle=hs20_44(), speed=20.0))
    state = {k: v for k, v in result.__dict__.items() if k != "_q_ddot"}
    state["q_ddot"] = np.arange(6.0)
    old = object.__new__(CrossingResult)
    old.__dict__.update(state)
    np.testing.assert_array_equal(old.q_ddot, np.arange(6.0))


def _long_deferred_result():
    """A beam crossing's lean result (its q̈ deferred), and q̈ computed once from its histories."""
    from vbikit.solve.result import vehicle_accelerations

    beam = EulerBernoulliBeam(span=20.0, EI=2.0e10, mass_per_length=1.2e4, damping_ratio=0.02, n_modes=3)
    result = simulate(Crossing(beam, vehicle=hs20_44(), speed=20.0))
    d = result.__dict__["_q_ddot"]
    right = vehicle_accelerations(d.vehicles, result.q, result.q_dot, result.wheel_forces, np.empty_like(result.q))
    return result, right


def test_threads_reading_a_deferred_acceleration_compute_it_once_and_right():
    """Two threads reading one result's q̈ at once: both get the right values (before the lock they
    wrote into the same array at once, numpy's products releasing the GIL: 8 wrong of 20 trials on a
    43,120-row history, errors of 500× the peak).  Long histories, so that the products overlap."""
    import dataclasses
    import threading

    from vbikit.solve.result import DeferredAccelerations, vehicle_accelerations

    result, _ = _long_deferred_result()
    d = result.__dict__["_q_ddot"]
    q, dq, fw = (np.ascontiguousarray(np.tile(a, (30, 1))) for a in (result.q, result.q_dot, result.wheel_forces))
    right = vehicle_accelerations(d.vehicles, q, dq, fw, np.empty_like(q))
    for _ in range(8):
        r = dataclasses.replace(result, q=q, q_dot=dq, wheel_forces=fw,
                                q_ddot=DeferredAccelerations(d.vehicles, q, dq, fw, np.zeros_like(q)))
        got: list = []
        threads = [threading.Thread(target=lambda: got.append(r.q_ddot)) for _ in range(2)]
        [t.start() for t in threads]
        [t.join() for t in threads]
        assert len(got) == 2 and got[0] is got[1]
        np.testing.assert_array_equal(got[0], right)


def test_histories_changed_in_place_before_q_ddot_is_read_are_refused():
    """q̈ follows from the result's own q, q̇ and wheel forces: changed in place after the run (forces
    in kN) they would give wrong accelerations (11.8 instead of 0.38 m/s² before the check), so the
    read is refused with a message; read first, q̈ is fixed and later edits do not touch it."""
    from vbikit.solve.result import ChangedHistoryError

    result, right = _long_deferred_result()
    result.wheel_forces[:] /= 1e3
    with pytest.raises(ChangedHistoryError, match="changed in place after the run"):
        result.q_ddot
    fresh, right = _long_deferred_result()
    got = fresh.q_ddot
    fresh.q[:] += 1.0
    assert fresh.q_ddot is got
    np.testing.assert_array_equal(got, right)


def test_an_unread_result_pickles_each_vehicle_history_once():
    """The result's q, q̇, wheel forces and its deferred q̈'s inputs are the same array objects: a pickle
    of a result not yet read is no larger than one of the same result read (it was 348 kB larger, the
    three histories twice, on the reviewer's case)."""
    import pickle

    result, _ = _long_deferred_result()
    d = result.__dict__["_q_ddot"]
    assert d.q is result.q and d.q_dot is result.q_dot and d.wheel_force is result.wheel_forces
    unread = len(pickle.dumps(result))
    result.q_ddot
    assert unread <= len(pickle.dumps(result)) + 1000


def test_accelerations_of_a_vehicle_without_wheels():
    """A vehicle with DOFs but no wheels (a body not touching the road): q̈ = M⁻¹(F_G − C q̇ − K q),
    here a free mass under gravity at rest, q̈ = −g (the rows' reshape failed on the empty force array)."""
    from types import SimpleNamespace

    from vbikit.solve.result import vehicle_accelerations

    vehicles = SimpleNamespace(mass_inv=np.array([[0.5]]), stiffness=np.zeros((1, 1)), damping=np.zeros((1, 1)),
                               wheel_rows=np.zeros((0, 1)), gravity=np.array([-2.0 * 9.81]))
    out = vehicle_accelerations(vehicles, np.zeros((4, 1)), np.zeros((4, 1)), np.zeros((4, 0)), np.empty((4, 1)))
    np.testing.assert_allclose(out, -9.81)
