"""The pseudo-excitation method's two integrators and its wavenumber grid, on the HS20-44 on the
paper's beam (6 modes, point tires, class C, 75 km/h; bilateral tires as in test_pem_monte_carlo).

* One line's pseudo response is the engine's crossing on a cosine road (``vbikit.solve.simulate``,
  its own contact law and Newton iteration) minus the smooth-road crossing: the default path
  (``method="exact"``) is that engine made linear, so the two agree to the road's sampling.
* The default path and the former one (``method="newmark"``: Newmark's average acceleration on the
  assembled equations, two substeps) agree within their time-step errors.
* The default grid (``band_lines``) against a grid 7 × finer, and its own check against that error.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from tests.random_vibration.test_pem_monte_carlo import _plan
from vbikit.random import Probes, PseudoRoad, band_lines, pseudo_excitation
from vbikit.random.lines import Lines
from vbikit.road.profile import RoadProfile
from vbikit.road.psd import RoadPSD
from vbikit.solve import simulate

ROAD = PseudoRoad(RoadPSD.iso("C"))


@pytest.fixture(scope="module")
def case():
    plan = _plan(6, {"model": "point"})
    crossing = plan.built.crossing
    bridge = crossing.bridge
    y = bridge.default_response_y
    xs = [bridge.default_x_at(y), 0.25 * bridge.span_lengths[0]]  # mid-span and quarter span
    probes = Probes(bridge.mode_shapes(xs, [y, y]), bridge.strain_shapes(xs, [y, y]))
    return plan, xs, probes


def test_one_line_is_the_engine_on_a_cosine_road(case):
    """Re ỹ(t) of the line n₀ (amplitude a = √(G_d(n₀) Δn)) is the response to r(x) = a cos 2πn₀x:
    the engine's crossing on that road minus the smooth one, at both deck points.  The engine
    interpolates the road linearly between samples 5 mm apart (relative error (2πn₀Δx)²/8 ≈ 1e-5
    in elevation, ≈ 1 % in slope at the kinks, which its dampers see) and settles the contact
    forces to 1e-6 of the static wheel load: 1 % of the peak is far above both and far below
    any error of the linear step (a wrong sign or a missing term moves the history by O(1))."""
    plan, xs, probes = case
    crossing, dt = plan.built.crossing, plan.run.dt
    n0, width = 0.33, 0.01  # near the first mode (7.3 Hz at 20.8 m/s: 0.35 cycle/m)
    res = pseudo_excitation(crossing, ROAD, probes, dt, lines=Lines(np.array([n0]), np.array([width])),
                            data=plan.run.kernel_data, keep_lines=True)
    amp = float(np.sqrt(ROAD.psd(np.array([n0]))[0] * width))
    x = np.arange(-200.0, 200.0, 0.005)
    road = RoadProfile(x, amp * np.cos(2 * np.pi * n0 * x), "cosine")
    wavy = simulate(dataclasses.replace(crossing, road=road, road_right=None, dt=dt))
    smooth = simulate(dataclasses.replace(crossing, road=None, road_right=None, dt=dt))
    n = min(res.time.size, wavy.time.size)
    for j, xj in enumerate(xs):
        engine = (wavy.displacement(xj) - smooth.displacement(xj))[:n]
        pem = res.lines_displacement[:n, j, 0]
        assert np.abs(engine).max() > 1e-6  # the cosine road moves the deck (≈ 0.1 mm)
        assert np.abs(pem - engine).max() < 0.01 * np.abs(engine).max(), (j, np.abs(pem - engine).max())


@pytest.mark.parametrize("n0", [0.1, 0.33])
def test_one_line_after_a_run_in_is_the_engine_after_the_same_run_in(case, n0):
    """``crossing.run_in`` = 40 m: the line's pseudo response starts from the vehicle's state after 40 m of its
    pseudo-road (``pem._run_in_state``, the harmonic solution in closed form) and equals the engine's crossing
    on the cosine road with the same run-in (``vbikit.solve.run_in``, step by step) minus the smooth one:
    measured 3.3e-05 (n₀ = 0.1) and 2.7e-04 (0.33) of the peak, tolerance 1 %.  At 0.1 cycle/m (2.1 Hz at
    20.8 m/s, the truck's body bounce) the settled start moves the deck's response by 72 % (measured): a run-in
    left out, or its state's sign or phase wrong, fails by far."""
    plan, xs, probes = case
    crossing, dt = plan.built.crossing, plan.run.dt
    width = 0.01
    amp = float(np.sqrt(ROAD.psd(np.array([n0]))[0] * width))
    x = np.arange(-300.0, 300.0, 0.005)
    road = RoadProfile(x, amp * np.cos(2 * np.pi * n0 * x), "cosine")
    peaks = []
    for run_in in (40.0, 0.0):
        c = dataclasses.replace(crossing, run_in=run_in)
        res = pseudo_excitation(c, ROAD, probes, dt, lines=Lines(np.array([n0]), np.array([width])), keep_lines=True)
        wavy = simulate(dataclasses.replace(c, road=road, road_right=None, dt=dt))
        smooth = simulate(dataclasses.replace(c, road=None, road_right=None, dt=dt))
        n = min(res.time.size, wavy.time.size)
        engine = (wavy.displacement(xs[0]) - smooth.displacement(xs[0]))[:n]
        pem = res.lines_displacement[:n, 0, 0]
        assert np.abs(pem - engine).max() < 0.01 * np.abs(engine).max(), (run_in, np.abs(pem - engine).max())
        peaks.append(np.abs(engine).max())
    if n0 == 0.1:
        assert peaks[0] > 1.5 * peaks[1]
    with pytest.raises(ValueError, match="crossing.run_in = 40 m: the pseudo-excitation's 'newmark' path"):
        pseudo_excitation(dataclasses.replace(crossing, run_in=40.0), ROAD, probes, dt, method="newmark",
                          lines=Lines(np.array([n0]), np.array([width])))
    with pytest.raises(ValueError, match="crossing.run_in = 40 m: a contact point is on the deck when the run starts"):
        pseudo_excitation(dataclasses.replace(crossing, run_in=40.0, approach=0.0), ROAD, probes, dt,
                          lines=Lines(np.array([n0]), np.array([width])))  # (the engine refuses it alike)


def test_exact_and_newmark_paths_agree(case):
    """σ(t) of every output by both integrators on the same lines.  Their difference is the two
    time-step errors at dt = 0.96 ms (2 cm of road a step; the engine's automatic step is 3 cm: the
    errors grow as dt²): Newmark's period error (ωh)²/12 at h = dt/2 and the exact step's load linear
    over the step, both largest for the accelerations; measured 0.81 % of the peak for the deck
    acceleration, ≤ 0.2 % for the others, ≤ 0.03 % for displacements."""
    plan, _, probes = case
    crossing = plan.built.crossing
    dt = 0.02 / crossing.max_speed
    lines = band_lines(0.01, 4.0, ratio=0.2, max_width=0.02, tail=0.02)
    exact, newmark = (pseudo_excitation(crossing, ROAD, probes, dt, lines=lines, data=plan.run.kernel_data,
                                        method=m) for m in ("exact", "newmark"))
    limits = {"displacement": 0.001, "vehicle_displacement": 0.001, "wheel_force": 0.003, "strain": 0.003,
              "velocity": 0.003, "vehicle_acceleration": 0.003, "acceleration": 0.01}
    for name, limit in limits.items():
        a, b = exact.std(name), newmark.std(name)
        assert np.abs(a - b).max() <= limit * b.max(), (name, np.abs(a - b).max() / b.max())
    for got, ref in ((exact.cov_dv, newmark.cov_dv), (exact.lambda1, newmark.lambda1)):
        assert np.abs(got - ref).max() <= 0.003 * np.abs(ref).max()


def test_default_grid_matches_a_fine_grid_and_its_check_bounds_the_error(case):
    """The default lines (ratio 0.1, 0.01 cycle/m, tail 0.01) against 7 × as many (ratio 0.0125,
    0.0025 cycle/m, uniform): σ within 0.2 % of each output's peak (over time and channels, as
    ``grid_change``; measured ≤ 0.11 %, the point tires' high wavenumbers: 0.01 % on the demo's
    multi-point tires; a tenth of the 2 % at which ``random_response`` warns); the method's own
    check (every line vs every second line) is at least the true error, so it does not flatter
    the grid."""
    plan, _, probes = case
    crossing, dt = plan.built.crossing, plan.run.dt
    psd = ROAD.psd
    default = pseudo_excitation(crossing, ROAD, probes, dt, data=plan.run.kernel_data)
    fine = pseudo_excitation(crossing, ROAD, probes, dt, data=plan.run.kernel_data,
                             lines=band_lines(psd.n_min, psd.n_max, ratio=0.0125, max_width=0.0025, tail=0.0))
    assert fine.lines.size >= 6 * default.lines.size
    for name in default.var:
        s, ref = default.std(name), fine.std(name)
        err = float(np.abs(s - ref).max() / ref.max())
        assert err <= 2e-3, (name, err)
        assert default.grid_change(name) >= err, (name, default.grid_change(name), err)
