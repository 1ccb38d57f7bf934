"""``Vehicle.slowest_decay_rate``: σ_min, the smallest −Re λ of the vehicle on rigid ground over the modes the road
excites, against closed forms (one DOF: c / 2m, and the overdamped root ζω − ω√(ζ² − 1)), the roots of a quarter
car's characteristic polynomial det(M s² + Ĉ s + K̂) expanded by hand, proportional damping's (α + β ω²) / 2 with
ω from the undamped problem; and the road's reach: a roll mode is excited only when the two wheel lines read
different profiles."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import eigh

from vbikit.vehicle.model import Vehicle, Wheel
from vbikit.vehicle.presets import VEHICLE_PRESETS


def _vehicle(mass, damping, stiffness, wheels) -> Vehicle:
    n = len(mass)
    return Vehicle("test", tuple(f"q{i}" for i in range(n)), np.array(mass, float), np.array(damping, float),
                   np.array(stiffness, float), -9.81 * np.diag(mass), tuple(wheels))


def _one_dof(m: float, k: float, c: float) -> Vehicle:
    return _vehicle([[m]], [[0.0]], [[0.0]], [Wheel("w", 0.0, 0.0, k, c, np.array([1.0]))])


def test_one_dof_underdamped_decays_at_c_over_2m():
    m, k, c = 1200.0, 4.0e5, 3.0e3  # ζ = c / (2 √(k m)) = 0.068
    assert _one_dof(m, k, c).slowest_decay_rate() == pytest.approx(c / (2 * m), rel=1e-10)


def test_one_dof_overdamped_decays_at_its_slower_root():
    m, k, c = 100.0, 1.0e4, 6.0e3  # ω = 10 rad/s, ζ = 3
    omega, zeta = math.sqrt(k / m), c / (2 * math.sqrt(k * m))
    assert _one_dof(m, k, c).slowest_decay_rate() == pytest.approx(zeta * omega - omega * math.sqrt(zeta**2 - 1),
                                                                    rel=1e-9)


def test_quarter_car_against_the_roots_of_its_characteristic_polynomial():
    """Sprung mass ms on ks, cs over the axle mu on the tire kt, ct: det(M s² + Ĉ s + K̂) =
    (ms s² + cs s + ks)(mu s² + (cs + ct) s + ks + kt) − (cs s + ks)², its roots by numpy."""
    ms, mu, ks, cs, kt, ct = 4000.0, 600.0, 2.0e5, 4.0e3, 1.6e6, 1.5e3
    car = _vehicle([[ms, 0.0], [0.0, mu]], [[cs, -cs], [-cs, cs]], [[ks, -ks], [-ks, ks]],
                   [Wheel("w", 0.0, 0.0, kt, ct, np.array([0.0, 1.0]))])
    poly = np.polysub(np.polymul([ms, cs, ks], [mu, cs + ct, ks + kt]), np.polymul([cs, ks], [cs, ks]))
    assert car.slowest_decay_rate() == pytest.approx(float(np.min(-np.roots(poly).real)), rel=1e-9)


def test_proportional_damping_decays_at_alpha_plus_beta_omega_squared_over_two():
    """Ĉ = α M + β K̂ (undamped tires): each mode decays at ζω = (α + β ω²) / 2, ω from eigh(K̂, M)."""
    mass = np.diag([3000.0, 8000.0, 500.0])
    k = np.array([[3.0e5, -1.0e5, 0.0], [-1.0e5, 2.5e5, -1.5e5], [0.0, -1.5e5, 1.5e5]])
    wheels = [Wheel("w", 0.0, 0.0, 9.0e5, 0.0, np.array([0.0, 0.0, 1.0]))]
    k_hat = k + 9.0e5 * np.outer([0, 0, 1.0], [0, 0, 1.0])
    alpha, beta = 0.4, 2.0e-4
    truck = _vehicle(mass, alpha * mass + beta * k_hat, k, wheels)
    omega2 = eigh(k_hat, mass, eigvals_only=True)
    assert truck.slowest_decay_rate() == pytest.approx(float(np.min((alpha + beta * omega2) / 2)), rel=1e-9)


def _rolling_body() -> Vehicle:
    """A body in heave and roll on two wheels at y = ±0.9 m, damped in heave only (its dampers on the centreline):
    its roll is undamped."""
    m, inertia, k, c, b = 2000.0, 900.0, 3.0e5, 6.0e3, 0.9
    rows = (np.array([1.0, b]), np.array([1.0, -b]))
    wheels = [Wheel("left", 0.0, b, k, 0.0, rows[0]), Wheel("right", 0.0, -b, k, 0.0, rows[1])]
    return _vehicle([[m, 0.0], [0.0, inertia]], [[c, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 0.0]], wheels)


def test_a_mode_the_road_does_not_reach_does_not_count():
    """Both wheels in one group (one axle on one profile): the roll mode is at rest on a rough road as on a flat
    one, σ_min is the heave's c / 2m; each wheel on its own profile: the undamped roll counts, σ_min = 0."""
    body = _rolling_body()
    assert body.slowest_decay_rate(np.array([0, 0])) == pytest.approx(6.0e3 / (2 * 2000.0), rel=1e-9)
    assert body.slowest_decay_rate(np.array([0, 1])) == 0.0
    assert body.slowest_decay_rate() == 0.0  # (None: each wheel on its own)


def test_groups_must_name_every_wheel_and_a_moving_force_has_nothing_to_settle():
    with pytest.raises(ValueError, match="one group number per wheel"):
        _rolling_body().slowest_decay_rate(np.array([0]))
    assert VEHICLE_PRESETS["moving-force"].build().slowest_decay_rate() == math.inf  # (nothing to settle)
    loose = _vehicle([[100.0]], [[0.0]], [[1.0e4]], [Wheel("w", 0.0, 0.0, 0.0, 0.0, np.array([1.0]))])
    assert loose.slowest_decay_rate() == math.inf  # (a tire without spring or dashpot: the road reaches no mode)


def test_presets_with_an_undamped_mode_the_road_excites_never_settle():
    """The paper's sprung mass (no dashpot) and the 3S2's tandem bogie pitch (no damper acts on it, tires undamped)
    keep their start transient, per axle as per wheel; HS20-44's slowest mode, a lightly damped trailer roll, is not
    excited when both wheel lines read one profile (per axle its slowest road-excited mode decays ten times faster)."""
    for name in ("sprung-mass", "3s2"):
        vehicle = VEHICLE_PRESETS[name].build()
        axles = np.unique([w.offset for w in vehicle.wheels], return_inverse=True)[1]
        assert vehicle.slowest_decay_rate() == 0.0 and vehicle.slowest_decay_rate(axles) == 0.0
    hs20 = VEHICLE_PRESETS["hs20-44"].build()
    axles = np.unique([w.offset for w in hs20.wheels], return_inverse=True)[1]
    assert hs20.slowest_decay_rate(axles) > 10 * hs20.slowest_decay_rate() > 0.0
