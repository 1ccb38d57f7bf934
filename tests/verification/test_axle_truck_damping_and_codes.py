# Trucks built from axle records: their dampers give the documented damping ratios; design-code
# allowance curves at and between their breakpoints, each against the code formula written out here.
#
# * Damping (docs of ``vbikit.vehicle.axles``): suspension c = 2·0.10·√(k·F/g) per side, tire
#   c = 2·0.03·√(k·m_u/2), springs k = F/δ.  Consequences checked on the truck's own M, C, K on rigid
#   ground (complex eigenvalues by scipy, ζ = −Re λ/|λ|): with near-rigid tires the body rests on
#   suspensions whose c/k = 2ζ_s√(δ_s/g) is the same for every spring (stiffness-proportional
#   damping), so every body mode has ζ = ζ_s·ω/ω_heave with ω_heave = √(g/δ_s): the heave mode has
#   exactly ζ_s = 0.10.  With a soft suspension the axle hop (the unsprung mass on its two tires and
#   suspension dampers, the heavy body standing still): ζ = (c_t + c_s)/√(2(k_t + k_s) m_u), 0.03
#   without suspension damping.
# * Codes: AASHTO Standard 3.8.2.1 I = 50/(L + 125) ≤ 0.30 (L in ft, 1 ft = 0.3048 m);
#   OHBDC 1983 0.20 (f ≤ 1 Hz), linear to 0.40 at 2.5 Hz, 0.40 to 4.5 Hz, linear to 0.20 at 6 Hz,
#   0.20 above; JTG D60-2015 §4.3.2 μ = 0.05 (f < 1.5 Hz), 0.1767 ln f − 0.0157 (1.5 ≤ f ≤ 14 Hz),
#   0.45 (f > 14 Hz); CSA S6 3.8.4.5.3 by axles 0.40 / 0.30 / 0.25.
from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg as sla

from vbikit.analysis import codes
from vbikit.vehicle import axle_truck

G = 9.81


def _ground_modes(v):
    """Natural frequencies [rad/s] and damping ratios of a vehicle on rigid ground (tires to ground)."""
    n = v.n_dof
    K = v.stiffness.copy()
    C = v.damping.copy()
    for w in v.wheels:
        K += w.stiffness * np.outer(w.row, w.row)
        C += w.damping * np.outer(w.row, w.row)
    Minv = np.linalg.inv(v.mass)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    lam = sla.eigvals(A)
    lam = lam[lam.imag > 1e-9]
    w = np.abs(lam)
    order = np.argsort(w)
    return w[order], (-lam.real / np.abs(lam))[order]


def test_gravity_constant():
    from vbikit.vehicle.model import GRAVITY
    assert GRAVITY == pytest.approx(G, abs=0.01)


@pytest.mark.parametrize("loads, spacings, groups", [
    ([60e3, 110e3], [5.0], None),
    ([50e3, 95e3, 95e3], [4.3, 1.3], None),
    ([50e3, 95e3, 95e3], [4.3, 1.3], ["single", "walking-beam"]),  # one suspension per side at the bogie pivot
])
def test_body_modes_of_axle_truck_have_the_documented_damping(loads, spacings, groups):
    from vbikit.vehicle.model import GRAVITY
    zs, ds = 0.10, 0.033
    v = axle_truck(loads, spacings, groups=groups, tire_deflection=1e-6, suspension_deflection=ds)
    w, z = _ground_modes(v)
    w_heave = math.sqrt(GRAVITY / ds)
    body = w < 3 * w_heave  # body heave, pitch, roll; axle hop is ≥ 100× higher with these tires
    assert body.sum() == 3
    # stiffness-proportional suspension damping: ζ = ζ_s ω / ω_heave for every body mode (tires
    # 33,000× stiffer than the suspension: measured agreement 3e-5)
    np.testing.assert_allclose(z[body], zs * w[body] / w_heave, rtol=1e-4)
    # the heave mode, alone at ω_heave (body on the suspension springs k = F/δ_s)
    i = int(np.argmin(np.abs(w - w_heave)))
    assert w[i] == pytest.approx(w_heave, rel=2e-3)
    assert z[i] == pytest.approx(zs, rel=2e-3)


@pytest.mark.parametrize("loads, spacings", [
    ([60e3, 110e3], [5.0]),
    ([50e3, 95e3, 95e3], [4.3, 1.3]),
])
@pytest.mark.parametrize("zeta_s", [0.0, 0.10])
def test_axle_hop_modes_have_the_documented_tire_damping(loads, spacings, zeta_s):
    # soft suspension (δ_s = 3 m, 160× the tire's 0.019 m) under a body 10× heavier than an axle: at the
    # hop frequency the body stands still and each axle bounces and rolls on its tires and the
    # suspension dampers, per side k_t = (P/2)/δ_t, c_t = 2·0.03·√(k_t m_u/2), k_s = (F/2)/δ_s,
    # c_s = 2ζ_s√(k_s (F/2)/g) (F = P − m_u g): ω² = 2(k_t + k_s)/m_u, ζ = (c_t + c_s)/√(2(k_t + k_s) m_u)
    from vbikit.vehicle.model import GRAVITY
    v = axle_truck(loads, spacings, suspension_deflection=3.0, suspension_damping_ratio=zeta_s)
    w, z = _ground_modes(v)
    hop = w > 10.0
    P = np.asarray(loads)
    m_u = np.array([700.0] + [1100.0] * (len(loads) - 1))
    k_t = 0.5 * P / 0.019
    c_t = 2 * 0.03 * np.sqrt(k_t * m_u / 2)
    F = 0.5 * (P - m_u * GRAVITY)
    k_s = F / 3.0
    c_s = 2 * zeta_s * np.sqrt(k_s * F / GRAVITY)
    w_ref = np.sqrt(2 * (k_t + k_s) / m_u)
    z_ref = (c_t + c_s) / np.sqrt(2 * (k_t + k_s) * m_u)
    order = np.argsort(np.repeat(w_ref, 2))
    # bounce and roll of an axle have the same ω and ζ here (roll: k b², c b², m_u b²)
    np.testing.assert_allclose(w[hop], np.repeat(w_ref, 2)[order], rtol=5e-3)  # measured < 0.2 % (body motion)
    np.testing.assert_allclose(z[hop], np.repeat(z_ref, 2)[order], rtol=2e-3)  # measured ≤ 8e-4


def test_damping_ratio_arguments_scale_the_dampers():
    v1 = axle_truck([60e3, 110e3], [5.0], suspension_damping_ratio=0.10, tire_damping_ratio=0.03)
    v2 = axle_truck([60e3, 110e3], [5.0], suspension_damping_ratio=0.20, tire_damping_ratio=0.09)
    np.testing.assert_allclose(v2.damping, 2.0 * v1.damping, rtol=1e-12)
    np.testing.assert_allclose([w.damping for w in v2.wheels], [3.0 * w.damping for w in v1.wheels], rtol=1e-12)
    # per-wheel tire damper from the documented formula: c = 2·0.03·√(k·m_u/2), k = (axle load/2)/0.019
    for w, load, mu in zip(v1.wheels, [60e3, 60e3, 110e3, 110e3], [700, 700, 1100, 1100]):
        k = 0.5 * load / 0.019
        assert w.stiffness == pytest.approx(k, rel=1e-12)
        assert w.damping == pytest.approx(2 * 0.03 * math.sqrt(k * mu / 2), rel=1e-12)


# ---------------------------------------------------------------- design codes
def _aashto_std(L_m):
    return min(50.0 / (L_m / 0.3048 + 125.0), 0.30)


def _ohbdc(f):
    if f <= 1.0 or f >= 6.0:
        return 0.20
    if f < 2.5:
        return 0.20 + (0.40 - 0.20) * (f - 1.0) / (2.5 - 1.0)
    if f <= 4.5:
        return 0.40
    return 0.40 + (0.20 - 0.40) * (f - 4.5) / (6.0 - 4.5)


def _jtg(f):
    return 0.05 if f < 1.5 else 0.45 if f > 14.0 else 0.1767 * math.log(f) - 0.0157


@pytest.mark.parametrize("L", [1.0, 5.0, 11.0, 12.954, 13.0, 16.76, 25.0, 39.62, 60.0, 120.0, 300.0])
def test_aashto_standard_curve(L):
    assert codes.aashto_standard(L) == pytest.approx(_aashto_std(L), rel=1e-12)


def test_aashto_standard_cap_and_continuity():
    # the cap meets the curve at 50/(L+125) = 0.30: L = 41.67 ft = 12.70 m
    L_cap = (50.0 / 0.30 - 125.0) * 0.3048
    assert codes.aashto_standard(L_cap - 1e-6) == pytest.approx(0.30, abs=1e-8)
    assert codes.aashto_standard(L_cap + 1.0) == pytest.approx(50 / ((L_cap + 1) / 0.3048 + 125), rel=1e-12)
    assert codes.aashto_standard(L_cap + 1.0) < 0.30
    L = np.linspace(0.5, 200.0, 4001)
    vals = np.array([codes.aashto_standard(x) for x in L])
    assert np.all(np.diff(vals) <= 1e-15)  # non-increasing
    assert np.max(np.abs(np.diff(vals))) < 1e-3  # continuous: no jump on a 5 cm grid


@pytest.mark.parametrize("f", [0.3, 1.0, 1.2, 1.75, 2.0, 2.49, 2.5, 3.5, 4.5, 4.8, 5.25, 5.9, 6.0, 9.0])
def test_ohbdc_curve_at_and_between_breakpoints(f):
    assert codes.ohbdc_1983(f) == pytest.approx(_ohbdc(f), abs=1e-12)


@pytest.mark.parametrize("f", [0.5, 1.49, 1.5, 2.0, 3.3, 4.5, 7.0, 10.0, 13.99, 14.0, 14.01, 30.0])
def test_jtg_curve_at_and_between_breakpoints(f):
    assert codes.jtg_d60_2015(f) == pytest.approx(_jtg(f), abs=1e-12)


def test_ohbdc_continuous_and_jtg_jumps_where_the_code_does():
    f = np.linspace(0.2, 10.0, 9801)  # 1 mHz grid
    o = np.array([codes.ohbdc_1983(x) for x in f])
    assert np.max(np.abs(np.diff(o))) < 2e-4  # slope 0.2/1.5 per Hz × 1 mHz = 1.3e-4: continuous
    # JTG: continuous inside 1.5 … 14 Hz; the code's own steps at the ends: 0.05 → 0.0559, 0.4506 → 0.45
    assert codes.jtg_d60_2015(1.5) - codes.jtg_d60_2015(1.4999) == pytest.approx(0.1767 * math.log(1.5) - 0.0157 - 0.05, abs=1e-6)
    inner = np.linspace(1.5, 14.0, 12501)
    j = np.array([codes.jtg_d60_2015(x) for x in inner])
    assert np.max(np.abs(np.diff(j))) < 0.1767 / 1.5 * 1e-3 * 1.01


def test_csa_and_code_allowances_put_each_value_under_its_key():
    assert [codes.csa_s6(n) for n in (1, 2, 3, 6)] == [0.40, 0.30, 0.25, 0.25]
    c = codes.code_allowances(20.0, 3.1, 2)
    assert c["aashto_standard"] == pytest.approx(_aashto_std(20.0), rel=1e-12)
    assert c["ohbdc_1983"] == pytest.approx(_ohbdc(3.1)) and c["jtg_d60_2015"] == pytest.approx(_jtg(3.1))
    assert c["csa_s6"] == 0.30 and c["aashto_lrfd"] == 0.33
    c = codes.code_allowances(9.0, 5.0, 1)
    assert c["ohbdc_1983"] == pytest.approx(_ohbdc(5.0)) and c["jtg_d60_2015"] == pytest.approx(_jtg(5.0))
    assert c["aashto_standard"] == 0.30 and c["csa_s6"] == 0.40


# ---------------------------------------------------------------- inputs of the code allowances
def test_axle_count_and_loaded_length_given_to_the_codes():
    from vbikit.analysis.effects import loaded_length, vehicle_axle_count
    from vbikit.bridge.continuous import ContinuousBeam
    from vbikit.vehicle import hs20_44

    # axles: distinct wheel positions along the truck (two wheels each)
    assert vehicle_axle_count(hs20_44()) == 3
    assert vehicle_axle_count(axle_truck([50e3, 120e3, 120e3, 110e3, 110e3], [3.8, 1.3, 8.5, 1.3])) == 5
    # AASHTO Standard 3.8.2.2: the span that holds the section
    beam = ContinuousBeam([12.0, 20.0, 15.0], 1e9, 1000.0, n_modes=2)
    assert loaded_length(beam, 6.0, 0.0) == 12.0
    assert loaded_length(beam, 25.0, 0.0) == 20.0
    assert loaded_length(beam, 40.0, 0.0) == 15.0
    # per load effect: the span, or the mean of the two spans at an interior support (hogging)
    assert beam.load_effect("moment", x=25.0).loaded_length == 20.0
    assert beam.load_effect("moment", x=32.0).loaded_length == pytest.approx(17.5)
    assert beam.load_effect("reaction", support=1).loaded_length == pytest.approx(16.0)
