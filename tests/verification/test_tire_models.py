# Verification of the tire-contact family (issue 5): deformable disk, rigid disk, multi-point
# averaging, loss of contact, deck defects.
#
# References (none of the numbers below comes from vbikit itself):
# * Deformable disk (docs/model-data.md §3, [substitute] after Yin et al.): radial springs k_ξ per
#   length under a circle of radius R; on a flat rigid surface pressed by d the force is
#   k_ξ·(area of the circular segment of height d) = k_ξ [R² acos(1 − d/R) − (R − d)√(2Rd − d²)]
#   (elementary geometry), which for d ≪ R is the closed form (4/3) k_ξ √(2R) d^{3/2} of
#   model data §3; calibration d_s = 1.5 F_s/k_t, k_ξ = F_s / ((4/3)√(2R) d_s^{3/2}), static
#   patch 2√(2R d_s) ≈ 0.34 m for an HS20 rear wheel (R = 0.5 m).
# * Rigid disk (model data §3, after Chang et al.): the wheel follows the envelope
#   e(x) = max_ξ [s(x + ξ) − (R − √(R² − ξ²))]; over a step of height h at x0 this is the
#   closed form e = 0 (x < x0 − ℓ_h), h − (R − √(R² − (x0 − x)²)) (x0 − ℓ_h ≤ x ≤ x0),
#   h (x > x0), ℓ_h = √(2Rh − h²) (circle touching the step's corner).
# * Multi-point averaging (paper Eq. 6; model data §3 [computed]): n equal springs at spacing s
#   pass a road harmonic of wavenumber ν scaled by |H(ν)| = |sin(πνsn) / (n sin(πνs))|; we
#   evaluate that formula here, independently of MultiPointTire.transfer.
# * Load spreading (model data §3): spreading a wheel load over a 0.25–0.35 m patch changes a
#   midspan static deflection by < 0.1 %; influence line of a simply supported beam (Euler–
#   Bernoulli, e.g. Timoshenko & Gere): δ_mid(x) = P x (3L² − 4x²) / (48 EI), x ≤ L/2.
# * Moving-force dynamic increment for small speed parameter α = v/(2 f1 L): DAF − 1 ≈ α
#   (Frýba 1972; model data §5 table: α = 0.05 → 1.048, 0.10 → 1.097).
# * Linear base excitation of a damped oscillator (any vibrations text): steady amplitude ∝ the
#   amplitude of the (averaged) input, transient decays as exp(−ζωt).
from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest

from vbikit.analysis import contact_loss, point_response
from vbikit.bridge import EulerBernoulliBeam, paper_beam
from vbikit.contact import DiskTire, MultiPointTire, PointTire, RigidDiskTire
from vbikit.road import (
    DEFECT_DEFAULTS,
    Defect,
    RoadProfile,
    RoadPSD,
    random_profile,
    with_defects,
)
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import GRAVITY, hs20_44, quarter_car, sprung_mass

R = 0.5  # tire radius [m], model data §3 [substitute]


def segment_area(d: float, radius: float = R) -> float:
    """Area [m²] of the circular segment of height d cut from a circle of radius ``radius``."""
    return radius**2 * math.acos(1 - d / radius) - (radius - d) * math.sqrt(2 * radius * d - d * d)


def closed_form_area(d: float, radius: float = R) -> float:
    """(4/3)√(2R) d^{3/2}: the segment area for d ≪ R (parabolic disk), model data §3."""
    return 4.0 / 3.0 * math.sqrt(2 * radius) * d**1.5


def trapezoid_error_bound(d: float, spacing: float, radius: float = R) -> float:
    """Bound [m²] on |Δξ Σ_j f(jΔξ) − ∫ f| for f(ξ) = max(0, d − g(ξ)), g = R − √(R² − ξ²).

    The grid sum of a function vanishing outside its support is the composite trapezoid rule.
    Cells inside the patch: |error| ≤ Δξ³ max|f''| / 12 each, f'' = −R²/(R² − ξ²)^{3/2};
    the (at most two) cells holding a patch end, where f has a kink: ≤ Lip(f) Δξ² / 4 each,
    Lip(f) = ℓ/(R − d) with half-length ℓ = √(2Rd − d²)."""
    half = math.sqrt(2 * radius * d - d * d)
    f2 = radius**2 / (radius - d) ** 3
    lip = half / (radius - d)
    return 2 * half * spacing**2 * f2 / 12 + 2 * lip * spacing**2 / 4


def wheel_z(result, wheel: int = 0) -> np.ndarray:
    """Displacement [m] of the wheel's lowest point, z_w = h_w · q."""
    return result.q @ result.crossing.vehicle.wheels[wheel].row


# ============================================================== deformable disk on flat ground
HS20 = hs20_44()
HS20_REAR_LOAD = float(HS20.static_wheel_loads()[2])  # axle 2 wheel, ≈ 67.1 kN (model data §2)
HS20_REAR_K = HS20.wheels[2].stiffness  # 3,503,307 N/m [paper Table 1]


def flat_force(layout, d: float) -> float:
    """Σ_p k_p max(0, d − g_p): the discretised disk pressed by d into flat rigid ground."""
    return float(np.sum(layout.stiffness * np.clip(d - layout.gaps, 0.0, None)))


@pytest.mark.parametrize("spacing", [0.01, 0.005])
@pytest.mark.parametrize("d", [0.005, 0.015, 0.0287, 0.05, 0.08])
def test_disk_flat_force_matches_segment_and_closed_form(d, spacing):
    tire = DiskTire(radius=R, spacing=spacing)
    lay = tire.contact_layout(HS20_REAR_K, 2000.0, HS20_REAR_LOAD)
    k_xi = lay.stiffness[0] / spacing  # radial stiffness per length [N/m²]
    np.testing.assert_allclose(lay.stiffness, k_xi * spacing, rtol=1e-14)
    np.testing.assert_allclose(np.diff(lay.offsets), spacing, rtol=1e-9)
    np.testing.assert_allclose(lay.gaps, R - np.sqrt(R**2 - lay.offsets**2), atol=1e-15)
    force = flat_force(lay, d)
    # 1. against the exact circular segment: only the quadrature error remains
    assert abs(force - k_xi * segment_area(d)) <= k_xi * trapezoid_error_bound(d, spacing)
    # 2. against the closed form (4/3) k_ξ √(2R) d^{3/2}: add the parabolic approximation.
    #    For |ξ| ≤ ℓ, ξ²/(2R) ≤ g(ξ) = ξ²/(R + √(R² − ξ²)) ≤ ξ²/(2R − d), so the segment lies
    #    between the parabolic areas for radii R − d/2 and R: √(1 − d/2R) ≤ A/A_closed ≤ 1.
    closed = k_xi * closed_form_area(d)
    assert force <= closed + k_xi * trapezoid_error_bound(d, spacing)
    assert force >= closed * math.sqrt(1 - d / (2 * R)) - k_xi * trapezoid_error_bound(d, spacing)


def test_disk_calibration_hs20_rear_wheel():
    tire = DiskTire(radius=R, spacing=0.01)
    k_t, f_s = HS20_REAR_K, HS20_REAR_LOAD
    lay = tire.contact_layout(k_t, 2000.0, f_s)
    d_s = tire.static_compression(k_t, f_s)
    assert d_s == pytest.approx(1.5 * f_s / k_t, rel=1e-14)  # model data §3
    k_xi = lay.stiffness[0] / tire.spacing
    # k_ξ = the closed form's F_s / ((4/3)√(2R) d_s^{3/2}), rescaled so that the discrete circular
    # disk carries exactly F_s at d_s; the factor is the discrete-vs-parabolic force ratio
    scale = k_xi / (f_s / closed_form_area(d_s))
    quad = trapezoid_error_bound(d_s, tire.spacing) / closed_form_area(d_s)
    assert 1.0 - quad <= scale <= 1.0 / (math.sqrt(1 - d_s / (2 * R)) - quad)
    # static patch 2√(2R d_s) ≈ 0.34 m for an HS20 rear wheel (model data §3)
    assert tire.static_patch_length(k_t, f_s) == pytest.approx(2 * math.sqrt(2 * R * d_s), rel=1e-14)
    assert tire.static_patch_length(k_t, f_s) == pytest.approx(0.34, abs=0.005)
    # load at d_s: exactly F_s (the calibration)
    assert flat_force(lay, d_s) == pytest.approx(f_s, rel=1e-12)
    # tangent stiffness at d_s, by central difference: the grid sum is piecewise linear in d with
    # slope k_ξ Δξ N(d), N = number of points with g_p < d, so N Δξ = 2ℓ ± Δξ, ℓ = √(2Rd − d²);
    # the closed form's tangent 2 k_ξ √(2R d_s) equals k_t exactly (calibration).  Hence
    # k_fd/k_t ∈ [√(1 − d/2R) − Δξ/(2√(2R d_s)), 1 + Δξ/(2√(2R d_s))].
    h = 1e-6
    k_fd = (flat_force(lay, d_s + h) - flat_force(lay, d_s - h)) / (2 * h)
    grid = tire.spacing / (2 * math.sqrt(2 * R * d_s))
    # (all × the rescaling factor above)
    assert (math.sqrt(1 - d_s / (2 * R)) - grid) * scale <= k_fd / k_t <= (1 + grid) * scale
    # the tangent damping is calibrated the same way: c_ξ · 2√(2R d_s) = c
    c_xi = lay.damping[0] / tire.spacing
    assert c_xi * 2 * math.sqrt(2 * R * d_s) == pytest.approx(2000.0, rel=1e-12)
    # static shares: the static force distribution over the patch, summing to 1
    assert lay.static_share.sum() == pytest.approx(1.0, rel=1e-14)
    assert lay.gated and not lay.envelope


def _static_run(vehicle, tire):
    """A crossing that starts 6 m before a short bridge; only the approach part is used."""
    beam = EulerBernoulliBeam(span=2.0, EI=1e8, mass_per_length=1000.0, n_modes=1)
    return simulate(Crossing(beam, vehicle, tire=tire, speed=5.0, approach=6.0, free_vibration=0.0))


def test_disk_static_state_sprung_mass():
    # an HS20 rear wheel as a sprung mass (m = F_s/g on k_t), smooth road, far from the bridge
    m = HS20_REAR_LOAD / GRAVITY
    tire = DiskTire(radius=R, spacing=0.01)
    res = _static_run(sprung_mass(m, HS20_REAR_K, 2000.0), tire)
    before = res.front_position[:, 0] < -1.0  # the whole disk (|ξ| ≤ 0.3 m) on the approach
    force = res.wheel_forces[before, 0]
    # equilibrium of the mass: the tire carries its weight (round-off only)
    np.testing.assert_allclose(force, m * GRAVITY, rtol=1e-12)
    np.testing.assert_allclose(res.q[before, 0], res.q[0, 0], rtol=0, atol=1e-12)  # at rest
    # compression d* solves F_disk(d*) = F_s; with the bounds of the calibration test,
    # (1 + quad)^(−2/3) ≤ d*/d_s ≤ (√(1 − d*/2R) − quad)^(−2/3), with d* ≤ 1.02 d_s inside the root
    # (the same bound evaluated once with d* = d_s gives d*/d_s ≤ 1.013)
    d_s = tire.static_compression(HS20_REAR_K, HS20_REAR_LOAD)
    d_star = -res.q[0, 0]
    quad = trapezoid_error_bound(d_s, tire.spacing) / closed_form_area(d_s)
    assert (1 + quad) ** (-2 / 3) <= d_star / d_s <= (math.sqrt(1 - 1.02 * d_s / (2 * R)) - quad) ** (-2 / 3)
    # patch length = Δξ × points in contact = 2ℓ(d*) ± Δξ; 2ℓ(d*) is within a few mm of
    # 2√(2R d_s) (d*/d_s above and the √(1 − d/2R) factor): one spacing + 2 % of the patch
    patch = 2 * math.sqrt(2 * R * d_s)
    lengths = res.contact_lengths[before, 0]
    assert np.ptp(lengths) == 0.0
    assert abs(lengths[0] - patch) <= tire.spacing + 0.02 * patch


def test_disk_static_state_hs20_every_wheel():
    tire = DiskTire(radius=R, spacing=0.01)
    res = _static_run(HS20, tire)
    before = res.front_position[:, 0] < -1.0
    loads = HS20.static_wheel_loads()  # from the vehicle's equilibrium on rigid ground
    np.testing.assert_allclose(res.wheel_forces[before], np.broadcast_to(loads, res.wheel_forces[before].shape),
                               rtol=1e-9)
    for w, (wheel, load) in enumerate(zip(HS20.wheels, loads)):
        patch = tire.static_patch_length(wheel.stiffness, load)
        assert abs(res.contact_lengths[before, w][0] - patch) <= tire.spacing + 0.02 * patch, wheel.name
    rear = tire.static_patch_length(HS20_REAR_K, HS20_REAR_LOAD)
    assert rear == pytest.approx(0.34, abs=0.005)


# ============================================================== rigid disk over a step
def step_envelope(x: np.ndarray, corner: float, h: float, radius: float = R) -> np.ndarray:
    """Closed-form envelope of a rigid circle over an ideal step of height h at ``corner``."""
    reach = math.sqrt(2 * radius * h - h * h)
    u = corner - x
    out = np.where(x >= corner, h, 0.0)
    touching = (u >= 0) & (u <= reach)
    return np.where(touching, h - (radius - np.sqrt(np.clip(radius**2 - u**2, 0.0, None))), out)


def test_rigid_disk_rides_the_step_envelope():
    """A sprung mass with a rigid-disk tire rolls slowly up a 50 mm step on the approach road."""
    h, start, ramp, spacing = 0.05, -1.0, 1e-3, 1e-3
    tire = RigidDiskTire(radius=R, spacing=spacing, max_gap=0.06)  # max_gap ≥ h: the whole obstacle is seen
    road = with_defects(RoadProfile.flat(-10.0, 10.0), [Defect.of_kind("step", start=start, size=h, length=ramp)])
    m, k, v = 1000.0, 1e6, 0.05  # undamped tire: F = k (e − z_w) exactly when in contact
    beam = EulerBernoulliBeam(span=1.0, EI=1.6e5, mass_per_length=1000.0, n_modes=1)
    # dt = 1 ms (ω dt = 0.03): the envelope is only piecewise smooth, so resolve the tire mode finely
    res = simulate(Crossing(beam, sprung_mass(m, k, 0.0), tire=tire, road=road, speed=v, approach=1.5,
                            free_vibration=0.0, dt=1e-3))
    x = res.front_position[:, 0]  # wheel centre (offset 0)
    sel = x < -0.6  # up to 0.6 m before the bridge
    z = wheel_z(res)[sel]
    force = res.wheel_forces[sel, 0]
    assert force.min() > 0.0  # stays in contact
    # The road ramps from 0 at `start` to h at `start + ramp`: its envelope lies between the
    # ideal steps with the corner at start + ramp (lower) and at start (upper).  The discrete
    # maximum over points at spacing Δξ is below the continuous one by at most g'(ξ)Δξ with
    # ξ ≤ ℓ_h + Δξ (the grid point next to the corner): a staircase under the envelope.
    lower = step_envelope(x[sel], start + ramp, h)
    upper = step_envelope(x[sel], start, h)
    reach = math.sqrt(2 * R * h - h * h)
    grid = (reach + spacing) / math.sqrt(R**2 - (reach + spacing) ** 2) * spacing  # ≈ 0.49 mm
    # 1. contact height seen by the wheel: with an undamped tire F = k (e − z_w), so e = z_w + F/k
    seen = z + force / k
    assert np.all(seen <= upper + 1e-12)
    assert np.all(seen >= lower - grid - 1e-12)
    # 2. the wheel's path: z_w − z_w(0) = e − (F − mg)/k.  Deviations: the staircase (≤ grid) and
    #    the oscillation started where the envelope's slope jumps from 0 to ℓ_h/(R − h) (velocity
    #    jump Δv = v ℓ_h/(R − h), amplitude Δv/ω, ω = √(k/m)); the curvature term v²|e''|/ω² is
    #    1e-5 of that.
    omega = math.sqrt(k / m)
    transient = v * reach / (R - h) / omega
    # the discrete envelope is a staircase of kinks every Δξ of travel, each a slope jump of about
    # Δξ/(R − h), i.e. a velocity jump v Δξ/(R − h) exciting an oscillation of v Δξ/((R − h) ω); the
    # ones within the last period (v T/Δξ of them, T = 2π/ω) add at most v² T/((R − h) ω) ≈ 35 µm
    transient += v**2 * (2 * math.pi / omega) / ((R - h) * omega)
    path = z - wheel_z(res)[0]
    assert np.all(path <= upper + transient)
    assert np.all(path >= lower - grid - transient)
    # the wheel really climbs before its centre reaches the step (a point tire would not)
    early = (x[sel] > start - reach + 0.05) & (x[sel] < start - 0.05)
    assert np.all(path[early] > 1e-3)
    assert path[-1] == pytest.approx(h, abs=grid + transient)


def test_rigid_disk_damper_rate_is_bounded_by_the_envelope_slope():
    # e(x) = max_y [s(y) − g(y − x)] ⇒ de/dx = g'(ξ*) (Danskin's theorem), so on a fixed road the
    # envelope moves at |ė| ≤ v max|g'| = v ξ_max/√(R² − ξ_max²) whatever the road's ramps.
    h, v, c = 0.0381, 10.0, 2000.0  # the field test's 1.5 in bump [paper], tire damping c = 2000 N·s/m
    road = with_defects(RoadProfile.flat(-20.0, 20.0), [Defect.of_kind("bump", start=-3.0, size=h)])
    tire = RigidDiskTire(radius=R)
    car = quarter_car(sprung_mass=400.0, unsprung_mass=50.0, suspension_stiffness=40e3, suspension_damping=2e3,
                      tire_stiffness=400e3, tire_damping=c)
    beam = EulerBernoulliBeam(span=2.0, EI=1e8, mass_per_length=1000.0, n_modes=1)
    res = simulate(Crossing(beam, car, tire=tire, road=road, speed=v, approach=6.0, free_vibration=0.0))
    wheel = car.wheels[0]
    on_road = res.front_position[:, 0] < -0.5
    lay = tire.contact_layout(wheel.stiffness, wheel.damping, 1.0)
    xw = res.front_position[on_road, 0] - wheel.offset
    e = np.max(road.elevation(xw[:, None] + lay.offsets[None, :]) - lay.gaps[None, :], axis=1)
    z = (res.q @ wheel.row)[on_road]
    zdot = (res.q_dot @ wheel.row)[on_road]
    force = res.wheel_forces[on_road, 0]
    touch = force > 0
    # F = k (e − z_w) + c (ė − ż_w) in contact ⇒ the rate the dashpot used:
    e_rate = (force - wheel.stiffness * (e - z)) / c + zdot
    xi_max = lay.offsets.max()
    bound = v * xi_max / math.sqrt(R**2 - xi_max**2)  # 7.5 m/s
    assert np.abs(e_rate[touch]).max() <= 1.01 * bound


def test_rigid_disk_rk4_stability_limit_is_the_point_tires():
    # A rigid disk acts through ONE spring k and dashpot c (its highest point), so at any instant its
    # coupled system is the point tire's with the contact moved by ≤ ξ_max: same stability limit
    # (up to the mode shapes at a point 0.24 m away).  Stiff, damped tire so the tire mode sets it.
    from vbikit.solve.timestep import rk4_stability_limit

    beam = EulerBernoulliBeam(span=1.0, EI=1e8, mass_per_length=1000.0, n_modes=1)
    car = sprung_mass(100.0, 1e7, 2 * math.sqrt(1e7 * 100.0))
    limits = {t.name: rk4_stability_limit(Crossing(beam, car, tire=t, speed=1.0, approach=1.0))
              for t in (PointTire(), RigidDiskTire(spacing=0.001, max_gap=0.06))}
    assert limits["rigid-disk"] >= 0.5 * limits["point"]


# ============================================================== convergence to the point tire
V_SLOW = 2.0


@cache
def slow_crossing(tire):
    beam = paper_beam(16.76, "II", n_modes=5)
    res = simulate(Crossing(beam, HS20, tire=tire, speed=V_SLOW, approach=1.0, free_vibration=0.0, dt=1e-3))
    return res, point_response(res)


SPREAD_TIRES = [MultiPointTire(6, layout_rule="ends"), MultiPointTire(6, layout_rule="cells"), DiskTire(), RigidDiskTire()]


@pytest.mark.parametrize("tire", SPREAD_TIRES, ids=lambda t: f"{t.name}-{getattr(t, 'layout_rule', '')}")
def test_spread_tires_converge_to_point_tire_at_low_speed(tire, monkeypatch):
    base, base_pr = slow_crossing(PointTire())
    res, pr = slow_crossing(tire)
    beam = base.crossing.bridge
    n = min(base.time.size, res.time.size)  # same dt; the spread tires leave the span later
    u0, u = base_pr.displacement[:n], pr.displacement[:n]
    peak = np.abs(base_pr.displacement).max()
    # peaks: spreading changes the static midspan deflection by < 0.1 % (model data §3); the
    # dynamic increment (≈ α = v/(2 f1 L) = 0.8 % here, Frýba) is common to all tires to first order
    assert pr.displacement.min() / base_pr.displacement.min() == pytest.approx(1.0, abs=1e-3)
    # histories, whole crossing: static spreading + dynamic parts.  Static: δ_mid is Lipschitz with
    # constant max|δ'| = 3L²P/(48EI) (at the supports, where a patch is partly off the span), so
    # spreading a wheel load by β_p over offsets ξ_p moves δ_mid by ≤ (3/L) δ_mid(P) E_β|ξ|;
    # summed over the wheels ≤ (3/L) E_β|ξ| W L³/(48EI).  Dynamic: each model's ≤ α × peak.
    cp = res.crossing.contact
    mean_abs = max(float(np.sum(cp.weight[cp.wheel == w] * np.abs(cp.setback[cp.wheel == w] - HS20.wheels[w].offset)))
                   for w in range(len(HS20.wheels)))
    w_total = float(HS20.static_wheel_loads().sum())
    spreading = 3.0 / beam.span * mean_abs * w_total * beam.span**3 / (48 * beam.EI)
    alpha = V_SLOW / (2 * beam.frequencies_hz[0] * beam.span)
    assert np.abs(u - u0).max() <= spreading + 2 * alpha * peak
    if isinstance(tire, RigidDiskTire):
        # on a smooth deck the envelope's highest point is the centre as long as the deck slope
        # |θ| < Δξ/(2R) = 0.01 (θ ≈ 4e-4 here): the rigid disk then IS the point tire.  It runs on the full
        # kernel, which holds the wheel loads linear: against the point tire held so (the default holds them
        # quadratic on the lean kernel's steps, ``builtin_integrators.QUADRATIC_WHEEL_LOADS``)
        monkeypatch.setattr("vbikit.solve.builtin_integrators.QUADRATIC_WHEEL_LOADS", False)
        u0 = point_response(simulate(base.crossing)).displacement[:n]
        np.testing.assert_allclose(u, u0, rtol=0, atol=1e-12 * peak)


# ============================================================== loss of contact
BUMP = Defect.of_kind("bump", start=-3.0, size=0.08)  # a large bump on the approach road
BUMP_ROAD = with_defects(RoadProfile.flat(-20.0, 20.0), [BUMP])
LIGHT_CAR = quarter_car(sprung_mass=400.0, unsprung_mass=50.0, suspension_stiffness=40e3, suspension_damping=2e3,
                        tire_stiffness=400e3, tire_damping=500.0)
ALL_TIRES = [PointTire(), MultiPointTire(6), DiskTire(), RigidDiskTire()]


def bump_crossing(tire, loss_of_contact=True):
    beam = EulerBernoulliBeam(span=2.0, EI=1e8, mass_per_length=1000.0, n_modes=1)
    return simulate(Crossing(beam, LIGHT_CAR, tire=tire, road=BUMP_ROAD, speed=10.0, approach=6.0,
                             free_vibration=0.0, loss_of_contact=loss_of_contact))


@pytest.mark.parametrize("tire", ALL_TIRES, ids=lambda t: t.name)
def test_launched_wheel_carries_no_force_and_tires_never_pull(tire):
    res = bump_crossing(tire)
    wheel = LIGHT_CAR.wheels[0]
    force = res.wheel_forces[:, 0]
    assert force.min() >= 0.0  # a tire never pulls
    # airborne: the wheel's lowest point above every surface point the tire can reach, i.e.
    # z_w > max_p [r(x_w + ξ_p) − g_p] (road sampled like the solver: linear between stations)
    lay = tire.contact_layout(wheel.stiffness, wheel.damping, float(LIGHT_CAR.static_wheel_loads()[0]))
    xw = res.front_position[:, 0] - wheel.offset
    surface = np.max(BUMP_ROAD.elevation(xw[:, None] + lay.offsets[None, :]) - lay.gaps[None, :], axis=1)
    airborne = wheel_z(res) > surface + 1e-12
    assert np.all(force[airborne] == 0.0)
    # the 80 mm bump at 10 m/s launches the axle: after the drop-off it must fall 0.08 m under at
    # most (m_u g + suspension force ≲ 10 kN)/m_u ≈ 216 m/s², i.e. ≥ 27 ms airborne for a point
    # tire; 10 ms leaves room for a disk grazing the bump's edge while it falls
    assert airborne.sum() * res.dt >= 0.010
    loss = contact_loss(res)[wheel.name]
    assert loss["lost"] is True
    assert loss["duration"] >= airborne.sum() * res.dt - 1e-12
    # first loss while the bump is within the tire's reach: the surface changes under the tire
    # from x_w = start − max ξ on, and the rearmost point leaves the bump (a 80 mm drop within
    # 0.5 ms that no wheel can follow) by x_w = end + max|ξ|
    reach = float(np.abs(lay.offsets).max())
    assert BUMP.start - reach <= loss["first_x"] <= BUMP.end + reach + 1e-9


@pytest.mark.parametrize("tire", [PointTire(), MultiPointTire(6)], ids=lambda t: t.name)
def test_bilateral_tires_pull_in_the_same_case(tire):
    res = bump_crossing(tire, loss_of_contact=False)
    assert res.wheel_forces[:, 0].min() < -0.1 * LIGHT_CAR.static_wheel_loads()[0]


@pytest.mark.parametrize("tire", [DiskTire(), RigidDiskTire()], ids=lambda t: t.name)
def test_disk_tires_are_unilateral_even_without_loss_of_contact(tire):
    # documented: disk tires are always gated (their patch is where they penetrate)
    a, b = bump_crossing(tire, loss_of_contact=False), bump_crossing(tire)
    assert a.wheel_forces.min() >= 0.0
    np.testing.assert_array_equal(a.wheel_forces, b.wheel_forces)


# ============================================================== filtering of a road harmonic
HARMONIC_DX = 0.002  # road sample spacing [m]
HARMONIC_A = 1e-3  # amplitude [m]: k A = 1 kN ≪ m g ≈ 9.8 kN, no loss of contact


@cache
def harmonic_amplitude(tire, nu: float) -> float:
    """Steady amplitude [m] of a sprung mass's displacement on r(x) = A cos(2πνx) at 1 m/s."""
    x = np.arange(-20.0, 20.0 + HARMONIC_DX / 2, HARMONIC_DX)
    road = RoadProfile(x, HARMONIC_A * np.cos(2 * np.pi * nu * x), f"harmonic {nu} cycle/m")
    m, k = 1000.0, 1e6  # f_v = 5.0 Hz
    c = 2 * 0.2 * math.sqrt(k * m)  # ζ = 0.2
    beam = EulerBernoulliBeam(span=1.0, EI=1e7, mass_per_length=1000.0, n_modes=1)
    speed = 1.0
    # dt: the wheel moves 0.2 mm per step (a tenth of the road spacing), so the integrator
    # resolves the interpolated road's kinks
    res = simulate(Crossing(beam, sprung_mass(m, k, c), tire=tire, road=road, speed=speed, approach=12.0,
                            free_vibration=0.0, dt=2e-4))
    assert res.wheel_forces[:, 0].min() > 0.5 * m * GRAVITY
    f = speed * nu
    t_end = 11.0  # still on the approach; transient after 4 s: exp(−ζω·4) = 1e-11
    periods = math.floor((t_end - 4.0) * f)
    sel = (res.time >= t_end - periods / f) & (res.time <= t_end)
    t = res.time[sel]
    basis = np.column_stack([np.cos(2 * np.pi * f * t), np.sin(2 * np.pi * f * t), np.ones_like(t)])
    coef, *_ = np.linalg.lstsq(basis, res.q[sel, 0], rcond=None)
    return float(np.hypot(coef[0], coef[1]))


@pytest.mark.parametrize("nu", [1.0, 2.0, 3.0])
@pytest.mark.parametrize("layout_rule", ["ends", "cells"])
def test_multipoint_response_ratio_follows_discrete_sinc(layout_rule, nu):
    n, a = 6, 0.254
    s = a / (n - 1) if layout_rule == "ends" else a / n
    expected = abs(math.sin(math.pi * nu * s * n) / (n * math.sin(math.pi * nu * s)))  # model data §3
    tire = MultiPointTire(n, a, layout_rule)
    assert float(tire.transfer(nu)) == pytest.approx(expected, rel=1e-12)
    ratio = harmonic_amplitude(tire, nu) / harmonic_amplitude(PointTire(), nu)
    # The model is linear in the averaged road input Σ β_p r(x + ξ_p) = H·A cos(…), so the ratio
    # is H exactly, up to the linear interpolation of the sampled road: |error| ≤ Δx²/8 |r''|
    # = A (πνΔx)²/2 per point (≤ 1.8e-4 A at 3 cycle/m), i.e. ≤ 3.6e-4 on the ratio; RK4 error
    # ((ω dt)⁴ ~ 1e-9) and the fit are negligible.  Tolerance 1e-3.
    assert ratio == pytest.approx(expected, abs=1e-3)


# ============================================================== deck defects
def test_defect_defaults_are_the_documented_ones():
    dep = Defect.of_kind("depression")
    assert (dep.amplitude, dep.length, dep.ramp, dep.shape) == (-0.020, 0.6, 0.05, "trapezoid")  # 20 mm [paper]
    bump = Defect.of_kind("bump")
    assert (bump.amplitude, bump.length, bump.ramp, bump.shape) == (0.0381, 0.184, 0.005, "trapezoid")  # 1.5 in
    step = Defect.of_kind("step")
    assert (step.amplitude, step.length, step.ramp, step.shape) == (0.01, 0.02, 0.02, "step")
    pot = Defect.of_kind("pothole")
    assert (pot.amplitude, pot.length, pot.shape) == (-0.05, 0.4, "cosine")
    assert set(DEFECT_DEFAULTS) == {"depression", "bump", "step", "pothole"}


def test_trapezoid_shape_depth_length_breakpoints():
    d = Defect.of_kind("depression", start=2.0, size=0.03, length=1.0, ramp=0.1)
    assert d.amplitude == -0.03 and d.end == pytest.approx(3.0)
    np.testing.assert_allclose(d.breakpoints(), [2.0, 2.1, 2.9, 3.0])
    x = np.array([1.0, 2.0, 2.05, 2.1, 2.5, 2.9, 2.95, 3.0, 4.0])
    np.testing.assert_allclose(d.offset(x), [0, 0, -0.015, -0.03, -0.03, -0.03, -0.015, 0, 0], atol=1e-15)
    b = Defect.of_kind("bump", start=-1.0, size=0.1)
    assert b.amplitude == 0.1
    np.testing.assert_allclose(b.offset([-1.0, -0.995, -0.9, -1.0 + 0.184 - 0.005, -1.0 + 0.184]), [0, 0.1, 0.1, 0.1, 0],
                               atol=1e-12)


def test_step_is_signed_and_stays():
    up = Defect.of_kind("step", start=1.0, size=0.02, length=0.04)
    down = Defect.of_kind("step", start=1.0, size=-0.02, length=0.04)
    x = np.array([0.0, 1.0, 1.02, 1.04, 5.0])
    np.testing.assert_allclose(up.offset(x), [0, 0, 0.01, 0.02, 0.02], atol=1e-15)
    np.testing.assert_allclose(down.offset(x), [0, 0, -0.01, -0.02, -0.02], atol=1e-15)
    np.testing.assert_allclose(up.breakpoints(), [1.0, 1.04])


def test_cosine_pothole_shape():
    p = Defect.of_kind("pothole", start=0.0, size=0.04, length=0.8)
    np.testing.assert_allclose(p.offset([-0.1, 0.0, 0.2, 0.4, 0.6, 0.8, 0.9]), [0, 0, -0.02, -0.04, -0.02, 0, 0],
                               atol=1e-15)


@pytest.fixture(scope="module")
def rough():
    return random_profile(RoadPSD.iso("C"), seed=7, spacing=0.01, length=200.0)


def test_with_defects_adds_exactly_to_a_random_profile(rough):
    linear = [Defect.of_kind("depression", start=0.0), Defect.of_kind("bump", start=5.003),
              Defect.of_kind("step", start=-7.3, size=-0.015)]
    road = with_defects(rough, linear)

    def nearest(points):
        i = np.clip(np.searchsorted(road.x, points), 1, road.x.size - 1)
        return np.minimum(np.abs(road.x[i] - points), np.abs(road.x[i - 1] - points))

    # every base station and every breakpoint is a station, up to the documented 1 µm merging of
    # near-coincident stations (which moves a kink by < 1 µm: error < 1e-6 × the slope change)
    assert nearest(rough.x).max() < 1e-6
    for d in linear:
        assert nearest(d.breakpoints()).max() < 1e-6
    on_base = np.isin(road.x, rough.x)
    np.testing.assert_allclose(road.z[on_base], rough.elevation(road.x[on_base])
                               + sum(d.offset(road.x[on_base]) for d in linear), rtol=0, atol=1e-15)
    # linear shapes: their kinks are stations, so the sum is exact everywhere, not only at stations
    x = np.random.default_rng(0).uniform(-9.0, 9.0, 20_000)
    np.testing.assert_allclose(road.elevation(x), rough.elevation(x) + sum(d.offset(x) for d in linear), rtol=0,
                               atol=1e-6 * max(abs(d.amplitude) / d.ramp for d in linear) + 1e-14)
    # cosine pothole sampled at length/80: interpolation error ≤ (h²/8)|f''| = A π²/25600 ≈ 3.9e-4 A
    pot = Defect.of_kind("pothole", start=10.0)
    road2 = with_defects(rough, [pot])
    xs = np.linspace(9.9, 10.5, 5001)
    err = road2.elevation(xs) - rough.elevation(xs) - pot.offset(xs)
    assert np.abs(err).max() <= abs(pot.amplitude) * math.pi**2 / 25600 + 1e-15
    assert road2.label.startswith(rough.label) and "pothole" in road2.label


def test_with_defects_resolution(rough):
    flat = RoadProfile.flat(-50.0, 50.0)
    assert flat.spacing == 0.0
    assert with_defects(flat, [Defect.of_kind("depression")]).spacing == pytest.approx(0.05)  # ramp
    assert with_defects(flat, [Defect.of_kind("pothole")]).spacing == pytest.approx(0.4 / 80)
    assert with_defects(rough, [Defect.of_kind("depression")]).spacing == pytest.approx(0.01)  # road samples
    assert with_defects(rough, [Defect.of_kind("bump")]).spacing == pytest.approx(0.005)  # bump ramp
    assert with_defects(rough, []) is rough


@pytest.mark.parametrize(
    "kwargs,field",
    [
        ({"kind": "crack"}, "kind"),
        ({"kind": "depression", "size": -0.01}, "size"),
        ({"kind": "bump", "size": 0.0}, "size"),
        ({"kind": "bump", "length": 0.0}, "length"),
        ({"kind": "depression", "ramp": 0.4}, "ramp"),
        ({"kind": "bump", "shape": "square"}, "shape"),
    ],
)
def test_invalid_defects_raise_naming_the_field(kwargs, field):
    with pytest.raises(ValueError, match=field):
        Defect.of_kind(**kwargs)
