"""Left and right wheel lines on their own road profiles (issue 4, item 4).

By construction r_R = c r_L + √(1 − c²) r_I with r_I an independent realisation of the same PSD,
so E[r_L r_R] / E[r_L²] = c and var(r_R) = var(r_L) in expectation (checked over 40 seeds, where
the sampling error of the mean correlation is ≈ 0.15/√40 ≈ 0.03); c = 1 reproduces the paper's
identical profiles bit for bit."""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import BRIDGE_PRESETS
from vbikit.road import RoadProfile, RoadPSD, correlated_profile, random_profile
from vbikit.solve import simulate
from vbikit.solve.crossing import Crossing
from vbikit.vehicle.presets import VEHICLE_PRESETS


def test_coherence_one_is_identical_and_statistics_hold():
    psd = RoadPSD.iso("C")
    left = random_profile(psd, 5, spacing=0.05, length=500.0)
    assert np.array_equal(correlated_profile(left, psd, 5, 1.0, spacing=0.05, length=500.0).z, left.z)
    for c in (0.0, 0.6):
        rho, ratio = [], []
        for seed in range(40):
            l = random_profile(psd, seed, spacing=0.05, length=500.0)
            r = correlated_profile(l, psd, seed, c, spacing=0.05, length=500.0)
            rho.append(np.mean(l.z * r.z) / np.mean(l.z**2))
            ratio.append(np.mean(r.z**2) / np.mean(l.z**2))
        assert np.mean(rho) == pytest.approx(c, abs=0.06)
        assert np.mean(ratio) == pytest.approx(1.0, abs=0.1)
    with pytest.raises(ValueError, match="coherence"):
        correlated_profile(left, psd, 5, 1.5, spacing=0.05, length=500.0)


def crossing(**kw):
    return Crossing(bridge=BRIDGE_PRESETS["paper-bridge-1"].build(n_modes=6), vehicle=VEHICLE_PRESETS["hs20-44"].build(),
                    speed=15.0, approach=5.0, lateral_offset=1.0, **kw)


def test_same_profile_on_both_lines_is_the_default():
    road = random_profile(RoadPSD.iso("C"), 2, length=200.0)
    a, b = simulate(crossing(road=road)), simulate(crossing(road=road, road_right=road))
    assert np.array_equal(a.xi, b.xi) and np.array_equal(a.wheel_forces, b.wheel_forces)


def test_bump_under_the_right_line_only_rolls_the_truck():
    flat = RoadProfile.flat(-200.0, 200.0)
    x = np.arange(-200.0, 200.0, 0.01)
    bump = RoadProfile(x, np.where((x > 2.0) & (x < 2.3), 0.02, 0.0), "20 mm bump")
    res = simulate(crossing(road=flat, road_right=bump))
    names = [w.name for w in res.crossing.vehicle.wheels]
    left, right = names.index("axle1_left"), names.index("axle1_right")
    assert np.abs(res.wheel_forces[:, right] - res.wheel_forces[:, left]).max() > 5e3  # N
    roll = [j for j, n in enumerate(res.crossing.vehicle.dof_names) if "roll" in n]
    assert np.abs(res.q[:, roll]).max() > 1e-4  # rad
    with pytest.raises(ValueError, match="road_right"):
        crossing(road=None, road_right=bump)
