"""Validation (a): a quarter car on the rigid road of the approach, driven by a band-limited ISO 8608
road.  Long after the start the response is stationary and its variance is the closed-form
integral σ² = ∫ |H(2π n v)|² G_d(n) dn (H of the 2-DOF quarter car from its equations of motion,
written here independently of vbikit; scipy.integrate.quad).  PEM must match it."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from vbikit.random import PseudoRoad, Probes, band_lines, pseudo_excitation
from vbikit.random.pem import NonlinearTireError
from vbikit.road.psd import RoadPSD
from vbikit.scenario.pipeline import scenario_of
from vbikit.scenario.preflight import preflight

MS, MU, KS, CS, KT, CT = 10_000.0, 1_000.0, 400e3, 40e3, 1_750e3, 3e3
SPEED = 25.0
PSD = RoadPSD.iso("C", n_min=0.05, n_max=2.0)


def _crossing(tire: str = "point"):
    spec = {"bridge": {"model": "paper-bridge-2-beam", "n_modes": 2},
            "vehicle": {"model": "quarter-car", "sprung_mass": MS, "unsprung_mass": MU, "suspension_stiffness": KS,
                        "suspension_damping": CS, "tire_stiffness": KT, "tire_damping": CT},
            "tire": {"model": tire}, "road": {"class": "C"},
            "crossing": {"speed": SPEED, "approach": 100.0, "dt": 0.002}}
    return preflight(scenario_of(spec)).built.crossing


def _transfer(n: float) -> tuple[complex, complex]:
    """Body and axle displacement per unit road elevation at wavenumber n [cycle/m]."""
    w = 2 * np.pi * n * SPEED
    s = 1j * w * CS + KS
    a = np.array([[-w * w * MS + s, -s], [-s, -w * w * MU + s + KT + 1j * w * CT]])
    z = np.linalg.solve(a, np.array([0.0, KT + 1j * w * CT]))
    return complex(z[0]), complex(z[1])


def _closed_form(f) -> float:
    val, _ = quad(lambda n: abs(f(n)) ** 2 * float(PSD(np.array(n))), PSD.n_min, PSD.n_max, limit=400,
                  points=[0.9 / SPEED, 7.0 / SPEED, 8.0 / SPEED])
    return float(np.sqrt(val))


def test_stationary_quarter_car_matches_closed_form():
    crossing = _crossing()
    res = pseudo_excitation(crossing, PseudoRoad(PSD), Probes(np.zeros((1, 2))), 0.002,
                            lines=band_lines(PSD.n_min, PSD.n_max, ratio=0.02, max_width=0.005))
    late = (res.time > 3.4) & (res.time < 3.9)  # 4 s on the approach: 7 body time constants after the start
    body, axle = crossing.vehicle.dof_names.index("body_heave"), crossing.vehicle.dof_names.index("axle_heave")
    w = lambda n: 2 * np.pi * n * SPEED  # noqa: E731
    expected = {
        "body displacement": (_closed_form(lambda n: _transfer(n)[0]), res.std("vehicle_displacement")[late, body]),
        "axle displacement": (_closed_form(lambda n: _transfer(n)[1]), res.std("vehicle_displacement")[late, axle]),
        "body acceleration": (_closed_form(lambda n: w(n) ** 2 * _transfer(n)[0]),
                              res.std("vehicle_acceleration")[late, body]),
        "tire force": (_closed_form(lambda n: (KT + 1j * w(n) * CT) * (1 - _transfer(n)[1])),
                       res.std("wheel_force")[late, 0]),
    }
    for name, (exact, pem) in expected.items():
        # 1 %: the midpoint rule on the lines and Newmark's period error at the top lines (ω dt ≤ 0.63)
        assert np.allclose(pem, exact, rtol=0.01), (name, exact, pem.min(), pem.max())


def test_disk_tires_are_refused():
    with pytest.raises(NonlinearTireError, match="Monte Carlo"):
        pseudo_excitation(_crossing("disk"), PseudoRoad(PSD), Probes(np.zeros((1, 2))), 0.002)
