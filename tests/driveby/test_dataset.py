"""Drive-by datasets: the decoupled mode and the per-pass variability, against independent numbers.

* the decoupled mode against Yang & Lin's closed form of a light sprung mass (its assumptions are
  exactly the decoupled mode's: the beam under the moving weight, the vehicle on the beam's
  motion), and its error against the coupled run growing with the mass ratio;
* reproducible draws: the same pass index gives the same draw in any order;
* scour classes: the first frequency of a simply supported beam on vertical support springs from
  a finite-element model written here (Hermite beam elements, scipy's generalised eigensolver).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from test_sensors_contact import EI, MASS, SPAN, closed_form_acceleration

from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.driveby import on_bridge, sensor_cart
from vbikit.driveby.decoupled import relative_rms_error, simulate_decoupled
from vbikit.driveby.variability import VariabilityError, draw, parse_coupling, parse_variability, pass_rng
from vbikit.solve import Crossing, simulate


def _pass(ratio):
    bridge = EulerBernoulliBeam(span=SPAN, EI=EI, mass_per_length=MASS, damping_ratio=0.0, n_modes=1)
    cart = sensor_cart(mass=ratio * MASS * SPAN)
    crossing = Crossing(bridge, cart, speed=8.0, approach=0.0, dt=5e-4)
    return cart, simulate(crossing), simulate_decoupled(crossing)


def test_decoupled_equals_the_light_vehicle_closed_form_and_its_error_grows_with_the_mass_ratio():
    errors = []
    for ratio in (1e-4, 1e-3, 1e-2):
        cart, coupled, decoupled = _pass(ratio)
        on = on_bridge(decoupled)
        expected, _ = closed_form_acceleration(decoupled.time[on], 8.0, cart.mass[0, 0], cart.wheels[0].stiffness)
        err = np.max(np.abs(decoupled.q_ddot[on, 0] - expected)) / np.max(np.abs(expected))
        # the closed form's assumptions are the decoupled mode's: agreement to the time step's error,
        # independent of the mass (achieved 8.4e-6 at every ratio; the coupled run: 1.7e-3 … 0.17)
        assert err < 1e-4, (ratio, err)
        errors.append(relative_rms_error(decoupled.q_ddot[:, 0], coupled.q_ddot[:, 0]))
    # against the coupled run: first order in the mass ratio (1.5e-3, 1.5e-2, 0.15)
    assert errors[0] < 3e-3
    assert 8 < errors[1] / errors[0] < 12 and 8 < errors[2] / errors[1] < 12, errors


def test_same_pass_index_same_draw_in_any_order():
    var = parse_variability({"speed": [19.0, 21.0], "vehicle_spread": 0.1, "temperature": [0.0, 30.0]})
    forward = [draw(var, 7, i, 3, 2) for i in range(6)]
    backward = [draw(var, 7, i, 3, 2) for i in reversed(range(6))][::-1]
    assert forward == backward
    assert forward[0] != forward[1]                       # passes differ
    assert draw(var, 8, 0, 3, 2) != forward[0]            # seeds differ
    # the i-th child of SeedSequence(seed).spawn: what a worker spawning children would draw
    child = np.random.SeedSequence(7).spawn(4)[3]
    assert np.random.default_rng(child).random() == pass_rng(7, 3).random()
    for d in forward:
        assert 19.0 <= d["speed"] <= 21.0 and 0.0 <= d["temperature"] <= 30.0
        assert all(0.9 <= f <= 1.1 for group in d["vehicle_factors"] for f in group)


@pytest.mark.parametrize("table, key", [({"passes": 0}, "variability.passes"), ({"speed": [21.0, 19.0]}, "variability.speed"),
                                        ({"vehicle_spread": 0.7}, "variability.vehicle_spread"),
                                        ({"scour_classes": [1.0, 0.9]}, "variability.scour_classes"),
                                        ({"temperature_coefficient": 0.5}, "variability.temperature_coefficient"),
                                        ({"colour": 1}, "variability.colour")])
def test_bad_variability_names_the_key(table, key):
    with pytest.raises(VariabilityError, match=key.replace(".", r"\.")):
        parse_variability(table)


def test_bad_coupling_names_the_key():
    with pytest.raises(VariabilityError, match="coupling"):
        parse_coupling({"coupling": "loose"})
    with pytest.raises(VariabilityError, match="coupling_check_every"):
        parse_coupling({"coupling_check_every": -1})


def test_decoupled_residual_refused_before_running():
    from vbikit.driveby.spec import DriveByError, parse_driveby
    from vbikit.driveby.study import check_cases

    spec = parse_driveby({"coupling": "decoupled", "bridge": {"model": "beam", "span": 25.0, "EI": EI, "mass_per_length": MASS},
                          "sensors": [{"name": "acc", "body": "body"}], "identification": {"method": "residual"}})
    with pytest.raises(DriveByError, match="coupling"):
        check_cases(spec)


def beam_on_springs_frequency(span, ei, mbar, k_support, n_el=40):
    """First natural frequency [Hz] of a beam pinned on two vertical springs k [N/m]: Hermite
    (cubic) beam elements with consistent mass, the springs added to the end deflection DOFs,
    ``scipy.linalg.eigh`` (independent of vbikit's model)."""
    from scipy.linalg import eigh

    h = span / n_el
    ke = ei / h**3 * np.array([[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                               [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    me = mbar * h / 420 * np.array([[156, 22 * h, 54, -13 * h], [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                                    [54, 13 * h, 156, -22 * h], [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
    n = 2 * (n_el + 1)
    K, M = np.zeros((n, n)), np.zeros((n, n))
    for e in range(n_el):
        i = slice(2 * e, 2 * e + 4)
        K[i, i] += ke
        M[i, i] += me
    K[0, 0] += k_support
    K[n - 2, n - 2] += k_support
    return math.sqrt(eigh(K, M, eigvals_only=True, subset_by_index=[0, 0])[0]) / (2 * math.pi)


def test_scour_classes_change_the_first_frequency_as_a_beam_on_springs():
    from vbikit.driveby.spec import parse_driveby
    from vbikit.driveby.study import case_crossing

    span, ei, mbar, k0 = 25.0, 3.5e10 * 1.3901, 18358.0, 2.0e8
    spec = parse_driveby({
        "bridge": {"model": "continuous-beam", "spans": [span], "EI": ei, "mass_per_length": mbar, "n_modes": 2},
        "sensors": [{"name": "acc", "body": "body"}], "identification": {"method": "sensor"},
        "variability": {"support_stiffness": k0, "scour_classes": [1.0, 0.95, 0.9]}})
    assert len(spec.cases) == 3 and [c["scour_class"] for c in spec.cases] == [0, 1, 2]
    got = [float(case_crossing(spec, c).bridge.frequencies_hz[0]) for c in spec.cases]
    expected = [beam_on_springs_frequency(span, ei, mbar, k0 * f) for f in (1.0, 0.95, 0.9)]
    rigid = beam_on_springs_frequency(span, ei, mbar, 1e16)
    assert expected[0] < 0.9 * rigid  # the springs matter at this stiffness (otherwise the test proves nothing)
    for g, e in zip(got, expected):
        assert abs(g / e - 1) < 2e-3, (got, expected)
    assert got[0] > got[1] > got[2]


def test_dataset_labels_recomputed_independently(tmp_path):
    """A small decoupled dataset (test cart, 2 scour classes × 2 passes, drawn speed, temperature and
    cart): every label recomputed here from (seed, index) and a beam-on-springs FE model."""
    import xarray as xr

    from vbikit.driveby.spec import parse_driveby
    from vbikit.driveby.study import run_driveby

    span, ei, mbar, k0, seed, rate = 25.0, 2.4e10, 4800.0, 5e8, 3, 200.0
    spec = parse_driveby({
        "seed": seed, "coupling": "decoupled", "coupling_check_every": 2,
        "bridge": {"model": "continuous-beam", "spans": [span], "EI": ei, "mass_per_length": mbar, "n_modes": 3},
        "crossing": {"approach": 5.0}, "sampling": {"rate": rate},
        "sensors": [{"name": "acc", "body": "body"}], "identification": {"band": [1.0, 20.0]},
        "variability": {"passes": 2, "speed": [7.0, 9.0], "vehicle_spread": 0.1, "support_stiffness": k0,
                        "scour_classes": [1.0, 0.9], "temperature": [0.0, 30.0]}})
    run_driveby(spec, tmp_path, workers=1, figures=False)
    ds = xr.open_dataset(tmp_path / "driveby.nc", chunks={"case": 4})
    assert ds["sensor_history"].encoding["chunksizes"][0] == 4  # chunked on disk
    assert ds.sizes["case"] == 4
    for i in range(4):
        rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(i,)))
        speed, temperature = rng.uniform(7.0, 9.0), rng.uniform(0.0, 30.0)
        mass_factor = rng.uniform(0.9, 1.1)
        assert float(ds.speed[i]) == pytest.approx(speed, rel=1e-12)
        assert float(ds.temperature_c[i]) == pytest.approx(temperature, rel=1e-12)
        assert float(ds.vehicle_mass_kg[i]) == pytest.approx(120.0 * mass_factor, rel=1e-9)
        factor = (1.0, 0.9)[i // 2]
        assert int(ds.scour_class[i]) == i // 2 and int(ds.pass_index[i]) == i % 2
        assert float(ds.support_stiffness[i]) == pytest.approx(k0 * factor)
        stiffness = 1 - 0.003 * (temperature - 20.0)  # E(T) of the module docstring, α_E = 0.003 /°C
        expected = beam_on_springs_frequency(span, ei * stiffness, mbar, k0 * factor)
        assert float(ds.bridge_frequency_hz[i]) == pytest.approx(expected, rel=2e-3)
        # segmentation: the record starts with the front wheel 5 m before the deck (t = 0), which it
        # enters at t = 5 / v and leaves at (5 + L) / v
        t0 = float(ds.time_start[i])
        assert t0 == 0.0
        assert int(ds.on_bridge_start_sample[i]) == math.ceil(5.0 / speed * rate)
        assert int(ds.on_bridge_end_sample[i]) == math.floor((5.0 + span) / speed * rate)
        assert int(ds.off_bridge_sample[i]) == math.floor((5.0 + span) / speed * rate) + 1  # one-axle cart
        checked = i % 2 == 0
        assert np.isfinite(float(ds.coupling_error_rms[i])) == checked
        if checked:  # a 120 kg cart on a 120 t span (mass ratio 1e-3): about 1.5 % (test above)
            assert 1e-3 < float(ds.coupling_error_rms[i]) < 5e-2
        u = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(i, 1))).random()
        assert int(ds.split[i]) == (0 if u < 0.7 else 1 if u < 0.85 else 2)


def test_scour_example_is_the_published_set():
    from pathlib import Path

    from vbikit.driveby.spec import load_driveby

    spec = load_driveby(Path(__file__).resolve().parents[2] / "examples" / "driveby" / "scour_1800.toml")
    assert len(spec.cases) == 1800 and spec.variability.scour_classes == (1.0, 0.95, 0.9)
    assert spec.scenario["bridge"]["EI"] == pytest.approx(3.5e10 * 1.3901, rel=1e-5)
    assert sum(spec.vehicle["axle_loads"]) == pytest.approx(35e3 * 9.81)
    assert spec.sampling.rate == 1000.0 and spec.variability.speed == (19.0, 21.0)
