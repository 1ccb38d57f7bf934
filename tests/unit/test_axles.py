"""Trucks from axle loads and spacings (model = "axles") and the 3-S2 preset."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.vehicle import GRAVITY, axle_truck, semitrailer_3s2
from vbikit.vehicle.axles import default_groups

g = GRAVITY


def axle_loads(v) -> np.ndarray:
    """Static axle loads [N]: left + right wheel of each axle (wheels are named axle<i>_<side>)."""
    loads = v.static_wheel_loads()
    names = [w.name.split("_")[0] for w in v.wheels]
    return np.array([sum(f for f, n in zip(loads, names) if n == a) for a in dict.fromkeys(names)])


CASES = {
    # loads [N], spacings [m], groups, tractor_groups
    "two-axle rigid": ([40e3, 90e3], [4.5], None, None),
    "rigid with tandem": ([55e3, 95e3, 80e3], [5.0, 1.3], None, None),
    "rigid with tridem": ([60e3, 70e3, 90e3, 80e3], [4.0, 1.3, 1.3], ["single", "tridem"], None),
    "3-S2, unequal tandems": ([53.4e3, 80e3, 70e3, 72e3, 66e3], [5.5, 1.3, 9.5, 1.3], None, None),
    "3-S2, walking beams": ([50e3, 81e3, 69e3, 75e3, 61e3], [5.5, 1.3, 9.5, 1.3],
                            ["single", "walking-beam", "walking-beam"], None),
    "2-S1-2 articulated after 2 groups": ([45e3, 80e3, 70e3, 60e3, 60e3], [4.0, 7.0, 6.0, 1.2], None, 2),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_static_axle_loads_are_the_given_ones(case):
    loads, spacings, groups, tractor = CASES[case]
    v = axle_truck(loads, spacings, groups=groups, tractor_groups=tractor)
    got = axle_loads(v)
    # the given loads are the reference: equilibrium must return them (round-off ~1e-10 N measured)
    np.testing.assert_allclose(got, loads, rtol=1e-9)
    assert v.total_weight == pytest.approx(sum(loads), rel=1e-12)
    left = v.static_wheel_loads()[0::2]
    right = v.static_wheel_loads()[1::2]
    np.testing.assert_allclose(left, right, rtol=1e-9)  # symmetric truck: no static roll
    # axle positions as given
    s = sorted({w.offset for w in v.wheels})
    np.testing.assert_allclose(np.diff(s), spacings, rtol=1e-12)


def test_walking_beam_equalises_whatever_the_tire_stiffness():
    """Bogie moment balance about its pivot: loads split by the inverse arm ratio, independent of springs."""
    v = axle_truck([50e3, 80e3, 60e3], [5.0, 1.4], groups=["single", "walking-beam"])
    got = axle_loads(v)
    np.testing.assert_allclose(got, [50e3, 80e3, 60e3], rtol=1e-9)


def test_truck_frequencies_in_the_documented_range():
    """Body modes (heave, pitch, roll; + semitrailer pitch, roll) 1.2–4 Hz, axle and bogie modes
    8–16 Hz (vbikit.vehicle.axles docstring; measured 1.38–3.52 and 8.98–13.23 Hz here)."""
    for loads, spacings, groups, tractor in CASES.values():
        v = axle_truck(loads, spacings, groups=groups, tractor_groups=tractor)
        f = v.natural_frequencies()
        n_body = sum(name.split("_")[0] in ("body", "tractor", "trailer") for name in v.dof_names)
        body, axle = f[:n_body], f[n_body:]
        assert 1.2 < body.min() and body.max() < 4.0, (loads, f)
        assert 8.0 < axle.min() and axle.max() < 16.0, (loads, f)


def test_default_groups_from_spacings():
    assert default_groups([5.5, 1.3, 9.5, 1.3]) == ["single", "tandem", "tandem"]
    assert default_groups([4.0]) == ["single", "single"]
    assert default_groups([4.0, 1.2, 1.2]) == ["single", "tridem"]


@pytest.mark.parametrize("kwargs, match", [
    ({"axle_loads": [50e3, 80e3], "axle_spacings": [4.0, 1.0]}, "axle_spacings needs 1"),
    ({"axle_loads": [50e3, -80e3], "axle_spacings": [4.0]}, r"axle_loads must be in \(0, 1e\+07\] N"),
    ({"axle_loads": [50e3, 80e3], "axle_spacings": [4.0], "groups": ["tandem", "single"]}, "hold 3 axles"),
    ({"axle_loads": [50e3, 80e3], "axle_spacings": [4.0], "groups": ["bogie"]}, "unknown axle group"),
    ({"axle_loads": [5e3, 80e3], "axle_spacings": [4.0]}, "too small for its unsprung mass"),
])
def test_bad_axle_data_is_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        axle_truck(**kwargs)


def test_3s2_static_loads_from_hand_statics():
    """VBI-2D's five-axle numbers in the 3-S2 layout: statically determinate, so the axle loads
    follow from two moment balances (written out here independently of the builder)."""
    w_tractor, w_trailer = 3100 * g, 20000 * g
    s_cg_tr, s5, s_cg_t, s_drive, s_trail = 1.0, 4.0, 9.0, 4.5, 12.2
    p_trail = w_trailer * (s_cg_t - s5) / (s_trail - s5)  # trailer: moments about the fifth wheel
    r = w_trailer - p_trail
    p_drive = (w_tractor * s_cg_tr + r * s5) / s_drive  # tractor: moments about the steer axle
    p_steer = w_tractor + r - p_drive
    expected = [p_steer + 750 * g, *(2 * [(p_drive + 1500 * g) / 2]), *(2 * [(p_trail + 2200 * g) / 2])]
    v = semitrailer_3s2()
    np.testing.assert_allclose(axle_loads(v), expected, rtol=1e-9)
    assert v.total_weight == pytest.approx(27550 * g, rel=1e-12)
    s = sorted({w.offset for w in v.wheels})
    np.testing.assert_allclose(s, [0.0, 3.9, 5.1, 11.6, 12.8], atol=1e-12)


def test_3s2_frequencies_in_the_documented_range():
    f = semitrailer_3s2().natural_frequencies()
    assert f.size == 13
    assert 2.0 < f[0] and f[4] < 5.0  # bodies (docstring: 2.2 … 4.6 Hz)
    assert 7.0 < f[5] and f[-1] < 20.0  # axles and bogies (7.7 … 19.6 Hz)


def test_absurd_axle_load_is_refused():
    """1e300 N on one axle (a generated input that once overflowed the step rule): refused with the range."""
    with pytest.raises(ValueError, match=r"axle_loads must be in \(0, 1e\+07\] N, got \[20000.0, 1e\+300\]"):
        axle_truck([20e3, 1e300], [1.0])
