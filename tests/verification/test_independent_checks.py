# Independent checks for errors that would be made consistently in every integrator (and so
# escape the consistency tests RK4 vs Newmark, batch vs simulate): damping, wheel-line mapping,
# the static start and the convective deck rate.  Every reference below is derived in this file
# from textbook results, never from vbikit output:
# * free vibration of a viscously damped oscillator, x'' + 2ζωx' + ω²x = 0: the amplitude
#   A(t) = √(x² + ((x' + ζωx)/ω_d)²), ω_d = ω√(1 − ζ²), is exactly A(t₀) e^(−ζω(t − t₀))
#   (any vibrations text, e.g. Clough & Penzien, *Dynamics of Structures*, ch. 2);
# * the damped moving-force response of a simply supported beam, mode by mode (Frýba 1972,
#   ch. 1, with modal damping): harmonic particular solution plus damped homogeneous part;
# * the static state of a linear system: zero velocity and zero acceleration at t = 0;
# * the coupled equations of the docs (docs/theory.md) written again here and integrated with
#   scipy.integrate.solve_ivp, with and without the convective deck rate v·φ'·ξ.
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from vbikit.bridge import EulerBernoulliBeam, paper_beam
from vbikit.contact import DiskTire, MultiPointTire, PointTire, RigidDiskTire
from vbikit.road import RoadProfile, RoadPSD, random_profile
from vbikit.solve import INTEGRATORS, Crossing, simulate
from vbikit.vehicle import GRAVITY, hs20_44, moving_force, sprung_mass

ROUGH = random_profile(RoadPSD.iso("C"), seed=1, length=300.0)  # ISO 8608 class C (average)


# ============================================================== damping: free decay of every mode
@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_free_decay_of_every_mode_after_the_vehicle_leaves(integrator):
    """After the last axle has left, each mode of the bridge vibrates freely: its amplitude
    decays as e^(−ζωt) (within 1 %, the brief), whatever the integrator."""
    beam = EulerBernoulliBeam(span=15.0, EI=8.0e9, mass_per_length=8000.0, damping_ratio=0.03, n_modes=4)
    crossing = Crossing(beam, hs20_44(), road=ROUGH, speed=20.0, approach=5.0, free_vibration=1.0, dt=1e-4,
                        integrator=integrator)
    r = simulate(crossing)
    t0 = crossing.exit_time()
    free = r.time >= t0 + r.dt  # first sample after every contact point has left x = span
    t = r.time[free] - r.time[free][0]
    zeta, omega = beam.damping_ratios, beam.omega
    omega_d = omega * np.sqrt(1 - zeta**2)
    checked = 0
    for m in range(beam.n_modes):
        x, v = r.xi[free, m], r.xi_dot[free, m]
        amp = np.sqrt(x**2 + ((v + zeta[m] * omega[m] * x) / omega_d[m]) ** 2)
        decay = np.exp(-zeta[m] * omega[m] * t)
        keep = decay >= 0.05  # while the mode is still well above round-off
        assert amp[0] > 1e-9 * np.abs(r.xi).max()  # the mode was excited
        ratio = amp[keep] / (amp[0] * decay[keep])
        # measured (dt = 1e-4 s, ω₄dt = 0.07): max |ratio − 1| = 1.8e-6 (RK4), 3.7e-3 (Newmark: the
        # trapezoidal rule errs on the decay rate by O((ω dt)²), mode 5 would reach 9e-3)
        assert np.abs(ratio - 1.0).max() <= 0.01, f"mode {m + 1}"
        checked += decay[keep][-1] < 0.5  # the window shows real decay (halved damping: e^(+…) off)
    assert checked == beam.n_modes


# ============================================================== damping: damped moving-force closed form
def damped_moving_force_midspan(beam: EulerBernoulliBeam, force: float, speed: float, t: np.ndarray) -> np.ndarray:
    """Midspan deflection [m] (z up) of the modal beam under a downward force crossing at ``speed``,
    zero initial state: per mode ξ'' + 2ζωξ' + ω²ξ = −P a sin(Ωt), a = √(2/mL), Ω = jπv/L, then
    free damped vibration once the force has left (t > L/v)."""
    span, a = beam.span, math.sqrt(2.0 / (beam.mass_per_length * beam.span))
    tc = span / speed
    out = np.zeros_like(t)
    for j in range(1, beam.n_modes + 1):
        w, z = beam.omega[j - 1], beam.damping_ratios[j - 1]
        wd = w * math.sqrt(1 - z * z)
        big = j * math.pi * speed / span
        h = -force * a / complex(w * w - big * big, 2 * z * w * big)  # x_p = Im(h e^{iΩt})

        def forced(s):
            xp, vp = np.imag(h * np.exp(1j * big * s)), np.real(h * big * np.exp(1j * big * s))
            amp_a = -float(np.imag(h))  # x_h(0) = −x_p(0)
            amp_b = (z * w * amp_a - float(np.real(h * big))) / wd  # x_h'(0) = −x_p'(0)
            e, c, sn = np.exp(-z * w * s), np.cos(wd * s), np.sin(wd * s)
            x = xp + e * (amp_a * c + amp_b * sn)
            v = vp + e * (-z * w * (amp_a * c + amp_b * sn) + wd * (-amp_a * sn + amp_b * c))
            return x, v

        x_end, v_end = forced(np.array(tc))
        s = np.maximum(t - tc, 0.0)
        e, c, sn = np.exp(-z * w * s), np.cos(wd * s), np.sin(wd * s)
        free = e * (x_end * c + (v_end + z * w * x_end) / wd * sn)
        xi = np.where(t <= tc, forced(np.minimum(t, tc))[0], free)
        out += xi * a * math.sin(j * math.pi / 2)
    return out


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_damped_moving_force_against_closed_form(integrator):
    beam = EulerBernoulliBeam(span=20.0, EI=1.0e10, mass_per_length=1.0e4, damping_ratio=0.05, n_modes=5)
    f1 = beam.frequencies_hz[0]
    speed = 2 * 0.3 * f1 * beam.span  # speed parameter α = 0.3
    r = simulate(Crossing(beam, moving_force(1e5), speed=speed, approach=0.0, free_vibration=2.0 / f1,
                          dt=1.0 / f1 / 4000, integrator=integrator))
    ref = damped_moving_force_midspan(beam, 1e5, speed, r.time)
    err = np.abs(r.displacement() - ref).max() / np.abs(ref).max()
    # measured: 2.7e-11 (RK4), 5.1e-7 (Newmark: its period error (ω dt)²/12 for mode 5); the same
    # history with ζ halved differs by 5.1e-2.  Other integrators: Newmark's bound.
    assert err <= {"rk4": 1e-9, "newmark": 2e-6}.get(integrator, 2e-6)
    undamped = EulerBernoulliBeam(20.0, 1.0e10, 1.0e4, damping_ratio=0.025, n_modes=5)
    assert np.abs(damped_moving_force_midspan(undamped, 1e5, speed, r.time) - ref).max() / np.abs(ref).max() > 1e-3


# ============================================================== static start on a rough road
@pytest.mark.parametrize("tire", [PointTire(), MultiPointTire(6), DiskTire(), RigidDiskTire()], ids=lambda t: t.name)
@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_static_start_on_rough_road_is_at_rest(integrator, tire):
    """At t = 0 the coupled system is in equilibrium on the road under every contact point
    (docs/theory.md): zero velocities and zero accelerations, to round-off."""
    # approach 0: the front patch already on the deck (multipoint, disk), so the deck is deflected
    r = simulate(Crossing(paper_beam(16.76, "II"), hs20_44(), tire=tire, road=ROUGH, speed=20.0, approach=0.0,
                          free_vibration=0.0, integrator=integrator))
    assert np.all(r.q_dot[0] == 0.0) and np.all(r.xi_dot[0] == 0.0)
    # accelerations ~ g = 9.81 m/s² and ω²ξ up to 1 m/s² would be wrong; measured ≤ 3e-13
    assert np.abs(r.q_ddot[0]).max() <= 1e-10
    scale = float(np.abs(r.crossing.bridge.omega**2 * r.xi[0]).max())  # modal spring term ω²ξ
    assert np.abs(r.xi_ddot[0]).max() <= 1e-12 * scale + 1e-15
    if tire.name in ("multipoint", "disk"):
        assert scale > 0.0  # part of the patch on the deck: the deck equilibrium is checked too
    # the start sits on the road: the wheels are not at the flat-ground static state
    flat = hs20_44().static_state()
    assert np.abs(r.q[0] - flat).max() > 1e-3
    # and the tires carry the vehicle: Σ wheel forces = weight (vertical equilibrium; the deck and
    # road carry it, nothing accelerates)
    assert r.wheel_forces[0].sum() == pytest.approx(hs20_44().total_weight, rel=1e-10)


# ============================================================== wheel lines
def test_bump_on_the_right_wheel_line_loads_only_the_right_wheels():
    """y is positive to the driver's left (docs/theory.md, vbikit.vehicle.model): the right wheel
    line is at y < 0.  A bump under the right line only must raise the right wheels' forces
    while the left ones barely notice."""
    veh = hs20_44()
    right = [w for w, wheel in enumerate(veh.wheels) if wheel.name.endswith("_right")]
    left = [w for w, wheel in enumerate(veh.wheels) if wheel.name.endswith("_left")]
    assert len(right) == len(left) == 3
    assert all(veh.wheels[w].lateral < 0 for w in right) and all(veh.wheels[w].lateral > 0 for w in left)
    x = np.arange(-40.0, 80.0, 0.005)
    h, start, length = 0.01, -3.0, 0.5  # a 10 mm cosine bump, 0.5 m long, on the approach road
    u = (x - start) / length
    bump = RoadProfile(x, np.where((u >= 0) & (u <= 1), 0.5 * h * (1 - np.cos(2 * np.pi * u)), 0.0), "bump")
    flat = RoadProfile.flat(-40.0, 80.0)
    r = simulate(Crossing(paper_beam(16.76, "II"), veh, road=flat, road_right=bump, speed=10.0, approach=8.0,
                          free_vibration=0.0))
    # while axle 1 crosses the bump (axle 2 is 4.27 m behind)
    window = (r.front_position[:, 0] >= start) & (r.front_position[:, 0] <= start + length)
    rise = r.wheel_forces[window] - r.wheel_forces[0]
    k_front = veh.wheels[right[0]].stiffness
    up = rise[:, right[0]].max()
    assert up > 0.5 * k_front * h  # the right front wheel is pushed up: measured +6.5 kN (k h = 8.8 kN)
    # the left front wheel is not (measured: it only unloads, by ≤ 0.13 kN, as the tractor rolls);
    # the other left wheels change by ≤ 0.39 kN (axle 2, through the tractor's roll)
    assert rise[:, left[0]].max() <= 0.01 * up
    assert np.abs(rise[:, left]).max() < 0.1 * up


# ============================================================== the convective deck rate v·φ'·ξ
CONV_L, CONV_M, CONV_EI, CONV_MODES, CONV_ZETA = 5.0, 2000.0, 2.03e8, 3, 0.02  # f1 ≈ 20 Hz
CONV_MV, CONV_K, CONV_C, CONV_V = 2000.0, 2.0e6, 1.0e5, 40.0  # heavily damped tire, 144 km/h (α ≈ 0.2)


def coupled_reference(convective: bool, t_eval: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """solve_ivp of the docs' equations for a sprung mass (mass M, tire k, c) on the modal beam:
        ξ̈ₙ + 2ζωₙξ̇ₙ + ωₙ²ξₙ = −φₙ(vt) F,   M z̈ = −M g + F,
        F = k (φ·ξ − z) + c (φ·ξ̇ + [v φ'·ξ] − ż),
    φₙ(x) = √(2/mL) sin(nπx/L); the bracket is the convective term.  Start: z = −Mg/k at rest,
    beam at rest (the wheel at the support, x = 0).  Returns midspan deflection and z̈."""
    n = np.arange(1, CONV_MODES + 1)
    kn = n * np.pi / CONV_L
    omega = kn**2 * np.sqrt(CONV_EI / CONV_M)
    amp = np.sqrt(2.0 / (CONV_M * CONV_L))

    def force(t, y):
        x = CONV_V * t
        phi, dphi = amp * np.sin(kn * x), amp * kn * np.cos(kn * x)
        xi, dxi, z, dz = y[:CONV_MODES], y[CONV_MODES:2 * CONV_MODES], y[-2], y[-1]
        rate = phi @ dxi + (CONV_V * dphi @ xi if convective else 0.0)
        return phi, CONV_K * (phi @ xi - z) + CONV_C * (rate - dz)

    def rhs(t, y):
        phi, f = force(t, y)
        xi, dxi = y[:CONV_MODES], y[CONV_MODES:2 * CONV_MODES]
        return np.concatenate([dxi, -2 * CONV_ZETA * omega * dxi - omega**2 * xi - phi * f, [y[-1], -GRAVITY + f / CONV_MV]])

    y0 = np.zeros(2 * CONV_MODES + 2)
    y0[-2] = -CONV_MV * GRAVITY / CONV_K
    sol = solve_ivp(rhs, (0.0, t_eval[-1]), y0, method="DOP853", rtol=1e-11, atol=1e-14, t_eval=t_eval)
    assert sol.success
    forces = np.array([force(tk, sol.y[:, k])[1] for k, tk in enumerate(sol.t)])
    assert forces.min() > 0.0  # always in contact: no loss-of-contact nonlinearity in the comparison
    return amp * np.sin(n * np.pi / 2) @ sol.y[:CONV_MODES], -GRAVITY + forces / CONV_MV


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_convective_deck_rate_against_independent_solver(integrator):
    beam = EulerBernoulliBeam(CONV_L, CONV_EI, CONV_M, damping_ratio=CONV_ZETA, n_modes=CONV_MODES)
    r = simulate(Crossing(beam, sprung_mass(CONV_MV, CONV_K, CONV_C), speed=CONV_V, approach=0.0,
                          free_vibration=0.0, dt=2e-5, integrator=integrator))
    on = r.time <= CONV_L / CONV_V
    t = r.time[on]
    w_ref, a_ref = coupled_reference(True, t)
    w_wrong, a_wrong = coupled_reference(False, t)
    err_w = np.abs(r.displacement()[on] - w_ref).max() / np.abs(w_ref).max()
    err_a = np.abs(r.q_ddot[on, 0] - a_ref).max() / np.abs(a_ref).max()
    # the term matters here: leaving it out changes the deflection by 2.1 % and z̈ by 37 %
    effect_w = np.abs(w_wrong - w_ref).max() / np.abs(w_ref).max()
    effect_a = np.abs(a_wrong - a_ref).max() / np.abs(a_ref).max()
    assert effect_w > 1e-2 and effect_a > 0.2
    # measured (deflection, z̈): RK4 5.7e-11, 1.8e-8; Newmark 9.8e-7, 2.3e-5 (2nd order at dt = 2e-5 s)
    tol_w, tol_a = {"rk4": (1e-9, 1e-7), "newmark": (5e-6, 1e-4)}.get(integrator, (5e-6, 1e-4))
    assert err_w <= tol_w and err_a <= tol_a


def test_slow_crossing_off_centre_loads_the_girders_on_its_side():
    """Lateral mapping on a 3D deck: a slow HS20-44 with its centreline at y = +1.95 m (left of the
    deck centreline) deflects each girder as the bridge's own static solution under the static
    wheel loads at their (x, y) — computed here from ``mode_shapes`` at the wheels, not through
    the solver's tracks — and the left girders (y > 0) more than the right ones."""
    from vbikit.bridge import BRIDGE_PRESETS

    bridge = BRIDGE_PRESETS["paper-bridge-1"].build(n_modes=10)
    veh = hs20_44()
    offset = 1.95
    r = simulate(Crossing(bridge, veh, speed=2.0, approach=1.0, free_vibration=0.0, lateral_offset=offset))
    xw = r.front_position[:, :1] - np.array([w.offset for w in veh.wheels])[None, :]
    yw = np.broadcast_to(np.array([w.lateral for w in veh.wheels]) + offset, xw.shape)
    loads = np.broadcast_to(-veh.static_wheel_loads(), xw.shape)  # downward [N], z up
    xi_static = bridge.static_modal_coordinates(xw, yw, loads)  # (n_t, n_modes), the bridge's own shapes
    girders = np.asarray(bridge.girder_y)
    shapes = bridge.mode_shapes(np.full(girders.size, bridge.span / 2), girders)  # (n_girders, n_modes)
    static = xi_static @ shapes.T
    dynamic = r.xi @ shapes.T
    peak = np.abs(static).max()
    # the difference is the dynamic increment at α = v/(2 f₁ L) ≈ 4e-3 (a few α of the peak, Frýba)
    # plus the 10-mode truncation common to both; measured 6.9e-3
    assert np.abs(dynamic - static).max() / peak <= 0.02
    g_max = np.abs(static.min(axis=0))  # largest deflection per girder (Girder 1 at y < 0)
    assert girders[0] < 0 < girders[-1]
    # measured: Σ left / Σ right = 29 (Girder 4 at y = +2.13 m carries most); mirrored tracks: 1/29
    assert g_max[girders > 0].sum() > 10 * g_max[girders < 0].sum()


# ============================================================== static reference and impact factor
def _influence(a: np.ndarray, span: float, EI: float) -> np.ndarray:
    """Midspan deflection [m, positive down] per newton at x = a (Roark: P a (3L² − 4a²)/(48 EI), a ≤ L/2)."""
    b = np.where(a <= span / 2, a, span - a)
    return np.where((a >= 0) & (a <= span), b * (3 * span**2 - 4 * b**2) / (48 * EI), 0.0)


@pytest.mark.parametrize("tire", [PointTire(), MultiPointTire(6), DiskTire(), RigidDiskTire()], ids=lambda t: t.name)
def test_static_reference_is_the_static_wheel_loads_on_the_influence_line(tire):
    """The static reference of the impact factor (docs/theory.md) is the vehicle's static wheel
    loads moved along the path: whatever the tire model, the midspan history equals Σ_w P_w δ(x_w)
    with the exact influence line, up to the modal truncation and the spreading of each load over
    its patch."""
    from vbikit.analysis import point_response

    beam = paper_beam(16.76, "II", n_modes=10)
    veh = hs20_44()
    r = simulate(Crossing(beam, veh, tire=tire, road=ROUGH, speed=20.0, approach=2.0, free_vibration=0.0))
    xw = r.front_position[:, :1] - np.array([w.offset for w in veh.wheels])[None, :]
    exact = -(_influence(xw, beam.span, beam.EI) * veh.static_wheel_loads()).sum(axis=1)
    static = point_response(r).static_displacement
    peak = np.abs(exact).max()
    # modal truncation (10 modes): measured 5.5e-5 of the peak for point loads (point, rigid disk);
    # spreading a wheel load by shares β_p over offsets ξ_p moves δ_mid by ≤ (3/L)·E_β|ξ|·P L³/(48EI)
    # (δ_mid is Lipschitz with 3L²/(48EI) per newton, test_tire_models); measured 3.5e-3
    # (multipoint, n = 6) and 2.9e-3 (disk) against bounds of 2.2e-2 and 2.0e-2
    cp = r.crossing.contact
    spread = max(float(np.sum(cp.weight[cp.wheel == w] * np.abs(cp.setback[cp.wheel == w] - veh.wheels[w].offset)))
                 for w in range(len(veh.wheels)))
    bound = 3.0 / beam.span * spread * veh.static_wheel_loads().sum() * beam.span**3 / (48 * beam.EI)
    assert np.abs(static - exact).max() <= 1e-4 * peak + bound


def test_impact_factor_of_a_moving_force_is_frybas_daf_minus_one():
    """IM = (R_dyn,max − R_st,max)/R_st,max (paper §3).  For a constant force on an undamped beam
    R_st,max = PL³/48EI (within the modal truncation) and R_dyn,max/(PL³/48EI) is Frýba's DAF:
    α = 0.5 → 1.705, α = 1.0 → 1.548 (Frýba 1972; docs/verification.md)."""
    from vbikit.analysis import point_response

    beam = EulerBernoulliBeam(span=20.0, EI=1.0e10, mass_per_length=1.0e4, damping_ratio=0.0, n_modes=20)
    f1 = beam.frequencies_hz[0]
    for alpha, daf in ((0.5, 1.705), (1.0, 1.548)):
        r = simulate(Crossing(beam, moving_force(1e5), speed=2 * alpha * f1 * beam.span, approach=0.0,
                              free_vibration=1.0 / f1, dt=1.0 / f1 / 4000))
        im = point_response(r).displacement_impact
        # 20 modes: static peak 2.0e-5 below PL³/48EI (the series (96/π⁴)Σ 1/j⁴); the table has 3
        # decimals (and is 5.5e-4 off the series at α = 0.1, test_fryba_moving_force); measured
        # |IM − (DAF − 1)| = 4.8e-4 (α = 0.5), 1.1e-4 (α = 1.0)
        assert im.static_peak == pytest.approx(-1e5 * 20.0**3 / (48 * 1.0e10), rel=1e-4)
        assert im.impact_factor == pytest.approx(daf - 1.0, abs=1.5e-3)


# ============================================================== the road under the wheel
@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_slow_wheel_follows_the_piecewise_linear_road(integrator):
    """A road given at stations 0.5 m apart is linear in between (vbikit.road.profile).  A stiff,
    damped sprung mass rolling slowly follows it: m z̈ + c(ż − ṙ) + k(z − r) = −mg has, on each
    linear piece, the exact solution z = r − mg/k (ż = ṙ, z̈ = 0); only the slope changes at the
    stations start small transients (velocity jump v·Δr' over ω ≈ 0.01 mm here)."""
    rng = np.random.default_rng(3)
    x = np.arange(-10.0, 20.0, 0.5)
    road = RoadProfile(x, rng.uniform(-0.005, 0.005, x.size), "coarse")
    m, k = 1000.0, 1.0e7
    c = 2 * 0.3 * math.sqrt(k * m)
    beam = EulerBernoulliBeam(span=2.0, EI=1e8, mass_per_length=1000.0, n_modes=1)
    r = simulate(Crossing(beam, sprung_mass(m, k, c), road=road, speed=0.1, approach=6.0, free_vibration=0.0,
                          integrator=integrator))
    on_road = r.front_position[:, 0] < -0.5
    followed = r.q[on_road, 0] + m * GRAVITY / k
    expected = np.interp(r.front_position[on_road, 0], x, road.z)  # linear interpolation, numpy's own
    # measured: 1.4e-5 m (RK4 and Newmark: the station transients); a staircase or a shifted
    # interpolation would be off by up to the 5 mm of the road
    assert np.abs(followed - expected).max() <= 5e-5


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_damped_sprung_mass_on_a_harmonic_road_transmissibility(integrator):
    """Base excitation through a spring and dashpot (any vibrations text, e.g. Clough & Penzien
    ch. 3): on r = A cos(Ωt) the steady amplitude is A |k + icΩ| / |k − mΩ² + icΩ|.  The dashpot
    term needs the road rate ṙ = v·r' under the wheel (without it: A k / |k − mΩ² + icΩ|)."""
    m, k, zeta, v, nu, amp = 1000.0, 1.0e6, 0.5, 5.0, 0.9, 1e-3
    c = 2 * zeta * math.sqrt(k * m)
    x = np.arange(-40.0, 20.0, 0.002)
    road = RoadProfile(x, amp * np.cos(2 * np.pi * nu * x), "harmonic")
    beam = EulerBernoulliBeam(span=2.0, EI=1e8, mass_per_length=1000.0, n_modes=1)
    r = simulate(Crossing(beam, sprung_mass(m, k, c), road=road, speed=v, approach=30.0, free_vibration=0.0,
                          integrator=integrator))
    big = 2 * np.pi * nu * v  # 28.3 rad/s, near the mass's 31.6 rad/s
    sel = (r.time >= 2.5) & (r.front_position[:, 0] < -1.0)  # transient gone: e^(−ζω·2.5) = 1e-7
    t = r.time[sel]
    basis = np.column_stack([np.cos(big * t), np.sin(big * t), np.ones_like(t)])
    coef, *_ = np.linalg.lstsq(basis, r.q[sel, 0], rcond=None)
    measured = math.hypot(coef[0], coef[1])
    expected = amp * abs(complex(k, c * big)) / abs(complex(k - m * big**2, c * big))
    without_rate = amp * k / abs(complex(k - m * big**2, c * big))
    assert abs(expected / without_rate - 1) > 0.3  # the dashpot's road rate matters here (+34 %)
    # The road rate of a sampled (piecewise-linear) road is piecewise constant, so the dashpot's
    # input jumps at every station and the integrators converge at first order in dt there
    # (measured against solve_ivp on the smooth cosine: 4.6e-4 of the amplitude at dt = 1e-4 s,
    # proportional to dt, whatever the sample spacing).  Measured here at the automatic step
    # (4e-4 s): RK4 9.3e-4, Newmark 2.8e-3; the interpolation itself costs (πνΔx)²/2 = 1.6e-5.
    assert measured == pytest.approx(expected, rel={"rk4": 2e-3, "newmark": 5e-3}.get(integrator, 5e-3))
