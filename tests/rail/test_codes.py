"""EN 1991-2 / EN 1990 rules against values worked out by hand here (and Table 6.6 against the same
rule in SincBridgeDynamics.jl, ``ec1damping``)."""
import math

import pytest

from vbikit.bridge.beam import EulerBernoulliBeam
from vbikit.rail import codes


@pytest.mark.parametrize("deck, span, pct", [
    ("prestressed-concrete", 10.0, 1.0 + 0.07 * 10),      # 1.70 %
    ("steel", 5.0, 0.5 + 0.125 * 15),                    # 2.375 %
    ("composite", 25.0, 0.5),
    ("reinforced-concrete", 12.0, 1.5 + 0.07 * 8),       # 2.06 %
    ("filler-beam", 20.0, 1.5),
])
def test_table_6_6(deck, span, pct):
    assert codes.code_damping(deck, span, extra=False) == pytest.approx(pct / 100, rel=1e-12)


@pytest.mark.parametrize("span, pct", [
    # (0.0187 L − 0.00064 L²) / (1 − 0.0441 L − 0.0044 L² + 0.000255 L³), by hand:
    (10.0, (0.187 - 0.064) / (1 - 0.441 - 0.44 + 0.255)),        # 0.123 / 0.374 = 0.32888 %
    (20.0, (0.374 - 0.256) / (1 - 0.882 - 1.76 + 2.04)),         # 0.118 / 0.398 = 0.29648 %
    (5.0, (0.0935 - 0.016) / (1 - 0.2205 - 0.11 + 0.031875)),    # 0.0775 / 0.701375 = 0.11050 %
    (30.0, 0.0),                                                 # only below 30 m
])
def test_additional_damping_eq_6_13(span, pct):
    assert codes.additional_damping(span) == pytest.approx(pct / 100, rel=1e-12, abs=1e-15)


def test_additional_damping_is_added():
    assert codes.code_damping("prestressed-concrete", 10.0) == pytest.approx((1.7 + 0.123 / 0.374) / 100, rel=1e-12)


def test_frequency_limit_and_resonance_speeds():
    assert codes.frequency_limit([3.0, 12.0, 27.0]) == 30.0
    assert codes.frequency_limit([25.0, 100.0, 225.0]) == 225.0       # n3
    assert codes.frequency_limit([25.0, 37.0]) == pytest.approx(37.5)  # 1.5 n0 > n2 > 30 Hz
    v = codes.resonance_speeds(5.0, 18.0, 100.0)
    assert list(v) == pytest.approx([90.0, 45.0, 30.0, 22.5])


def test_dynamic_factors():
    # Φ2 = 1.44/(√20 − 0.2) + 0.82 = 1.44/4.272136 + 0.82 = 1.157068; Φ3 = 2.16/4.272136 + 0.73 = 1.235602
    assert codes.phi2(20.0) == pytest.approx(1.44 / (math.sqrt(20) - 0.2) + 0.82, rel=1e-12)
    assert codes.phi2(20.0) == pytest.approx(1.157068, abs=1e-6)
    assert codes.phi3(20.0) == pytest.approx(1.235602, abs=1e-6)
    assert codes.phi2(2.0) == 1.67 and codes.phi3(1.5) == 2.0   # the upper limits
    assert codes.phi2(400.0) == 1.0   # 1.44/19.8 + 0.82 = 0.893 → the lower limit 1.00


def test_phi_irregularity_annex_c():
    # L = 20 m, n0 = 5 Hz, v > 22 m/s: 56 e^-4 + 50 (100/80 − 1) e^-1 = 1.02567 + 4.59849 → 0.0562416
    expect = (56 * math.exp(-4) + 50 * 0.25 * math.exp(-1)) / 100
    assert codes.phi_irregularity(50.0, 20.0, 5.0) == pytest.approx(expect, rel=1e-12)
    assert codes.phi_irregularity(11.0, 20.0, 5.0) == pytest.approx(expect / 2, rel=1e-12)


def test_lm71_midspan_moment_and_support_shear_of_a_20_m_span():
    beam = EulerBernoulliBeam(20.0, 1e10, 1e4)
    # Moment at midspan, influence line η = x/2 (x ≤ 10 m).  Axles at 8.4, 10, 11.6, 13.2 m (the group
    # 0.8 m off centre: the concentrated sum is 16.8 m for any shift ≤ 0.8 m and the distributed load
    # gains δ²/2 per kN/m): 250 × (4.2 + 5 + 4.2 + 3.4) = 4200 kN m; 80 kN/m outside 7.6 … 14.0 m:
    # 80 × (50 − 10.56 − 16) = 1875.2 kN m → 6075.2 kN m.
    m = codes.lm71_peak(beam.load_effect("moment", 10.0).influence, 20.0)
    assert m == pytest.approx(6075.2e3, rel=1e-7)
    # Shear at the entry support, η = 1 − x/20: axles at 0, 1.6, 3.2, 4.8 m: 250 × (1 + 0.92 + 0.84 + 0.76)
    # = 880 kN; 80 kN/m from 5.6 m: 80 × 14.4²/40 = 414.72 kN → 1294.72 kN.
    v = codes.lm71_peak(beam.load_effect("shear", 0.0).influence, 20.0)
    assert v == pytest.approx(1294.72e3, rel=1e-7)
    assert codes.lm71_peak(beam.load_effect("shear", 0.0).influence, 20.0, alpha=1.33) == pytest.approx(1.33 * v)
