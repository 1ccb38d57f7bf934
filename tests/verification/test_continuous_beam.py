# Continuous beams: frequencies, static load effects and a moving force, each against an
# independent number.
#
# * Frequencies: Blevins, *Formulas for Natural Frequency and Mode Shape* (1979), continuous
#   beams on rigid supports, f_i = (λ_i²/2π)√(EI/m)/L²: two equal spans λL = π, 3.9266, 2π, 7.0686;
#   three equal spans π, 3.5564, 4.2975; spans 1 : 1.5 : 1 (L the short span) 2.4894, 3.4167,
#   3.6980, 4.7872 (the last set from an independent 60-element script, agreeing with the closed
#   forms to 1e-4).  The 4-decimal rounding of λL is ≤ 1.2e-5 relative.
# * Statics: pycba (an independent continuous-beam code) influence lines; the closed form of two
#   equal spans, M_B = −P a (L² − a²)/(4L²) (largest 0.0962 P L at a = L/√3).
# * Moving force on two equal spans: the closed-form modes (antisymmetric sin(nπx/L); symmetric
#   pinned–clamped modes sin λx − (sin λL/sinh λL) sinh λx with tan λL = tanh λL, mirrored about
#   the pier) integrated by scipy's solve_ivp — no vbikit code on that side.
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from vbikit.analysis.effects import load_effect_response
from vbikit.bridge.continuous import ContinuousBeam
from vbikit.bridge.damage import Damage
from vbikit.solve import Crossing, simulate
from vbikit.vehicle import moving_force

L, EI, M = 10.0, 1.0e9, 1000.0
# fixed step for the moving-force test: T_10 / 23 (ω_10 = 2719 rad/s).  The automatic step
# (4.6e-4 s here) is set for deflections; with it the pier-moment peak differs by 0.17 %.
DT = 1.0e-4


def _lambda_l(beam: ContinuousBeam, length: float) -> np.ndarray:
    return np.sqrt(beam.omega / math.sqrt(EI / M)) * length


@pytest.mark.parametrize("spans, expected, short", [
    ([L, L], [math.pi, 3.9266, 2 * math.pi, 7.0686], L),
    ([L, L, L], [math.pi, 3.5564, 4.2975], L),
    ([L, 1.5 * L, L], [2.4894, 3.4167, 3.6980, 4.7872], L),
])
def test_frequencies_of_equal_and_unequal_spans(spans, expected, short):
    beam = ContinuousBeam(spans, EI, M, n_modes=len(expected))
    lam = _lambda_l(beam, short)
    # measured: largest |λL/λL_ref − 1| = 2.4e-6 (two spans), 7e-6 (three), < 2e-5 (1:1.5:1, 4-decimal refs)
    np.testing.assert_allclose(lam, expected, rtol=3e-5)
    # f ∝ λ² : within 0.1 % as the issue asks, with room to spare
    np.testing.assert_allclose(beam.omega / beam.omega[0], (np.array(expected) / expected[0]) ** 2, rtol=1e-4)


def test_one_span_is_the_simply_supported_beam():
    beam = ContinuousBeam([L], EI, M, n_modes=4)
    exact = (np.arange(1, 5) * math.pi / L) ** 2 * math.sqrt(EI / M)
    # measured (40 elements): 3e-8, 4e-7, 2.1e-6, 6.7e-6 for modes 1–4 (the O((kh)⁴) FE error)
    np.testing.assert_allclose(beam.omega, exact, rtol=1e-5)


@pytest.fixture(scope="module")
def pycba_lines():
    pycba = pytest.importorskip("pycba")
    spans = [20.0, 25.0, 20.0]
    il = pycba.InfluenceLines(spans, 1.0e9, [-1, 0] * 4)
    il.create_ils(step=0.25)
    return spans, il


@pytest.mark.parametrize("kind, poi, kw, code", [
    ("moment", 10.0, {"x": 10.0}, "M"),       # sagging, span 1
    ("moment", 32.5, {"x": 32.5}, "M"),       # sagging, span 2
    ("moment", 20.0, {"x": 20.0}, "M"),       # hogging over pier 1
    ("shear", 5.0, {"x": 5.0}, "V"),
    ("reaction", 0.0, {"support": 0}, "R"),
    ("reaction", 20.0, {"support": 1}, "R"),
])
def test_static_influence_lines_against_pycba(pycba_lines, kind, poi, kw, code):
    spans, il = pycba_lines
    beam = ContinuousBeam(spans, 1.0e9, 1000.0)
    x, eta = il.get_il(poi, code)
    x, eta = np.asarray(x), np.asarray(eta)
    ours = -beam.load_effect(kind, **kw).influence(x)  # pycba: unit load downward
    if code == "V":  # at the jump itself pycba counts a load at x = s right of the section, vbikit left
        keep = np.abs(x - poi) > 1e-9
        x, eta, ours = x[keep], eta[keep], ours[keep]
    # the brief asks for 0.5 %; measured: max |difference| / max |ordinate| below 1e-12
    np.testing.assert_allclose(ours, eta, atol=1e-9 * np.abs(eta).max())


def test_pier_moment_of_two_spans_closed_form():
    beam = ContinuousBeam([L, L], EI, M)
    a = np.linspace(0.0, L, 401)
    exact = -a * (L**2 - a**2) / (4 * L**2)  # per unit downward load
    mb = beam.load_effect("moment", x=L)
    np.testing.assert_allclose(-mb.influence(a), exact, atol=1e-12 * L)
    fine = np.linspace(0.0, 2 * L, 200_001)
    line = -mb.influence(fine)
    i = int(np.argmin(line))
    assert line[i] / L == pytest.approx(-0.0962, abs=5e-5)  # −1/(6√3) = −0.096225
    assert fine[i] / L == pytest.approx(0.577, abs=5e-4)
    rb = beam.load_effect("reaction", support=1)
    np.testing.assert_allclose(-rb.influence(a), a * (3 * L**2 - a**2) / (2 * L**3), atol=1e-12)


def test_static_reactions_balance_the_load():
    beam = ContinuousBeam([20.0, 25.0, 20.0], [1e9, 2e9, 1e9], [900.0, 1100.0, 900.0], support_stiffness=[math.inf, 4e7, 4e7, math.inf])
    x = np.linspace(0.0, beam.span, 301)
    total = sum(beam.load_effect("reaction", support=j).influence(x) for j in range(4))
    np.testing.assert_allclose(total, -1.0, atol=1e-9)  # Σ R = −(unit upward force)
    # moment at the far end vanishes (pinned), by equilibrium of the whole beam
    np.testing.assert_allclose(beam.load_effect("moment", x=beam.span).influence(x), 0.0, atol=1e-8)


def test_all_modes_superpose_to_the_static_moment():
    # with every FE mode, Σ r_i φ_i(x)/ω_i² is the full-stiffness value for a load outside the
    # element next to the section (a consistency check of the modal values r_i)
    beam = ContinuousBeam([L, L], EI, M, n_modes=159)
    xp = np.array([2.3, 13.7])
    for kind, kw in (("moment", {"x": L}), ("moment", {"x": 4.0}), ("reaction", {"support": 1})):
        e = beam.load_effect(kind, **kw)
        # measured 1.4e-6: the point load's moment arm (s − x)·[x < s] has a kink at s that the C¹
        # Hermite space cannot hold, so its projection differs slightly away from the section
        np.testing.assert_allclose((beam.mode_shapes(xp) / beam.omega**2) @ e.modal, e.influence(xp), rtol=1e-5)


# ---------------------------------------------------------------- moving force, two spans
class _TwoSpanModes:
    """Closed-form modes of two equal spans L (rigid supports), ascending, mass-normalised numerically:
    antisymmetric φ = ±sin(λu), symmetric φ = sin λu − (sin λL / sinh λL) sinh λu, u = min(x, 2L − x)."""

    def __init__(self, n_each: int):
        lam, c, anti = [], [], []
        for n in range(1, n_each + 1):
            lam.append(n * math.pi / L), c.append(0.0), anti.append(True)
            root = brentq(lambda z: math.tan(z) - math.tanh(z), (n + 0.01) * math.pi, (n + 0.49) * math.pi) / L
            lam.append(root), c.append(math.sin(root * L) / math.sinh(root * L)), anti.append(False)
        order = np.argsort(lam)
        self.lam, self.c, self.anti = np.array(lam)[order], np.array(c)[order], np.array(anti)[order]
        self.amp = np.ones_like(self.lam)
        xq = np.linspace(0.0, 2 * L, 40_001)
        self.amp = 1.0 / np.sqrt(np.trapezoid(M * self.shape(xq) ** 2, xq, axis=0))
        self.omega = self.lam**2 * math.sqrt(EI / M)

    def _parts(self, x):
        x = np.atleast_1d(np.asarray(x, float))[:, None]
        u = np.where(x <= L, x, 2 * L - x)
        sign = np.where(self.anti & (x[:, :1] > L), -1.0, 1.0)
        return u, sign

    def shape(self, x):
        """φ_i(x), shape (n_x, n_modes)."""
        u, sign = self._parts(x)
        return self.amp * (sign * np.sin(self.lam * u) - self.c * np.sinh(self.lam * u))

    def curvature(self, x):
        """φ_i''(x), shape (n_x, n_modes)."""
        u, sign = self._parts(x)
        return self.amp * self.lam**2 * (-sign * np.sin(self.lam * u) - self.c * np.sinh(self.lam * u))


def test_moving_force_on_two_spans_against_solve_ivp():
    P, v, n_modes = 1.0e5, 25.0, 10
    beam = ContinuousBeam([L, L], EI, M, damping_ratio=0.0, n_modes=n_modes, elements_per_span=40)
    crossing = Crossing(beam, moving_force(P), speed=v, approach=0.0, free_vibration=0.2, dt=DT)
    res = simulate(crossing)
    t = res.time
    mid = res.displacement(L / 2)
    pier = load_effect_response(res, beam.load_effect("moment", x=L)).dynamic

    modes = _TwoSpanModes(n_modes // 2)
    om = modes.omega
    t_exit = 2 * L / v

    def force(tt):
        tt = np.atleast_1d(tt)
        return np.where((tt <= t_exit)[:, None], -P * modes.shape(np.clip(v * tt, 0.0, 2 * L)), 0.0)  # (n_t, n_modes)

    def force_at(tt):
        """``force(tt)[0]`` for one time without the array machinery (the integrator calls it ~120,000
        times): the same closed-form modes as ``_TwoSpanModes.shape``."""
        if tt > t_exit:
            return np.zeros(n_modes)
        x = min(max(v * tt, 0.0), 2 * L)
        u = x if x <= L else 2 * L - x
        sign = np.where(modes.anti & (x > L), -1.0, 1.0)
        return -P * (modes.amp * (sign * np.sin(modes.lam * u) - modes.c * np.sinh(modes.lam * u)))

    def rhs(tt, z):
        return np.concatenate([z[n_modes:], force_at(tt) - om**2 * z[:n_modes]])

    sol = solve_ivp(rhs, (0.0, t[-1]), np.zeros(2 * n_modes), t_eval=t, method="DOP853", rtol=1e-10, atol=1e-14)
    q = sol.y[:n_modes].T
    ddq = force(t) - om**2 * q
    # the integrator's scalar force is the array one (round-off apart)
    np.testing.assert_allclose([force_at(tt) for tt in t], force(t), rtol=0.0, atol=1e-12 * P)
    mid_ref = q @ modes.shape(L / 2)[0]
    # pier moment, mode acceleration: exact static line −P a (L² − a²)/(4L²) (either span) minus Σ r_i q̈_i/ω_i²
    a = np.where(v * t <= L, v * t, 2 * L - v * t)
    static = np.where(t <= t_exit, -P * a * (L**2 - a**2) / (4 * L**2), 0.0)
    r = EI * modes.curvature(L)[0]
    pier_ref = static - ddq @ (r / om**2)
    # the brief asks for 0.5 %; measured: peaks differ by 5e-8 (midspan) and 1.9e-5 (pier moment),
    # histories by 2e-6 and 6e-5 of the peak
    assert mid.min() == pytest.approx(mid_ref.min(), rel=1e-5)
    np.testing.assert_allclose(mid, mid_ref, atol=2e-5 * np.abs(mid_ref).max())
    assert pier.min() == pytest.approx(pier_ref.min(), rel=1e-4)
    np.testing.assert_allclose(pier, pier_ref, atol=2e-4 * np.abs(pier_ref).max())


# ---------------------------------------------------------------- damage
def test_damage_severity_zero_is_bit_identical():
    intact = ContinuousBeam([20.0, 25.0], EI, M, n_modes=8)
    zero = ContinuousBeam([20.0, 25.0], EI, M, n_modes=8, damage=(Damage(7.3, 2.1, 0.0),))
    assert np.array_equal(intact.omega, zero.omega)
    x = np.linspace(0, 45, 777)
    assert np.array_equal(intact.mode_shapes(x), zero.mode_shapes(x))


@pytest.mark.parametrize("start, length", [(4.0, 2.0), (0.0, 1.0), (11.0, 3.0)])
def test_damage_lowers_f1_as_rayleigh_predicts(start, length):
    # first order: Δ(ω₁²) = −s ∫_region EI (φ₁'')² dx with the closed-form intact mode
    # φ₁ = √(2/(mL)) sin(πx/L) of a simply supported span (Rayleigh's quotient; Doebling et al. 1998)
    span, s = 20.0, 0.02
    intact = ContinuousBeam([span], EI, M, n_modes=1)
    damaged = ContinuousBeam([span], EI, M, n_modes=1, damage=(Damage(start, length, s),))
    k = math.pi / span
    b = start + length
    integral = 2.0 / (M * span) * k**4 * (0.5 * (b - start) - (math.sin(2 * k * b) - math.sin(2 * k * start)) / (4 * k))
    predicted = -s * EI * integral / (2.0 * intact.omega[0] ** 2)  # Δf/f = Δ(ω²)/(2ω²)
    measured = damaged.omega[0] / intact.omega[0] - 1.0
    # second-order terms are O(s²) relative to the first-order drop: measured agreement 1 … 2 %
    assert measured == pytest.approx(predicted, rel=0.03)
