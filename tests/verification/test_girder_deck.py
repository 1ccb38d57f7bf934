"""Verification of the slab-on-girder grillage deck (src/vbikit/bridge/girder_deck.py).

References are independent of the model: the closed-form simply supported Euler–Bernoulli beam
(ωₙ = (nπ/L)² √(EI/m), midspan deflection P L³ / 48 EI; e.g. Frýba 1972 ch. 1) with the
transformed-section properties worked out by hand below; statics (the moment at a cut of a
simply supported span is P a (L − x) / L whatever the transverse distribution, because every
bearing reaction is a vertical force); mirror symmetry; the total mass from the drawings.
"""
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import BRIDGE_PRESETS, SlabOnGirderBridge
from vbikit.bridge.elements import hermite_linear_coupling
from vbikit.bridge.nodal import hermite_basis
from vbikit.bridge.sections import AASHTO_GIRDERS

IN = 0.0254


def hand_composite(b: float, t: float = 0.20, E: float = 33e9):
    """Type II girder (A 369 in², y_b 15.83 in, h 36 in, I 50,979 in⁴; PCI tables) + slab b × t on top, same E."""
    A, yb, h, I = 369 * IN**2, 15.83 * IN, 36 * IN, 50979 * IN**4
    Ad, yd = b * t, h + t / 2
    yna = (A * yb + Ad * yd) / (A + Ad)
    Ic = I + A * (yna - yb) ** 2 + b * t**3 / 12 + Ad * (yd - yna) ** 2
    return E * Ic, 2400.0 * (A + Ad), yna


def single_girder(**kw):
    # one girder, deck exactly its tributary width 2.13 m (no overhang beyond the tributary strip)
    p = dict(span=16.76, n_girders=1, overhang=2.13 / 2, E_girder=33e9, E_deck=33e9, n_modes=12)
    p.update(kw)
    return SlabOnGirderBridge(**p)


def test_single_girder_is_the_composite_beam():
    b = single_girder()
    EI, m, c = hand_composite(2.13)
    L = b.span
    bending = [k for k, d in enumerate(b.mode_descriptions()) if d.startswith("bending")]
    f = b.frequencies_hz[bending][:3]
    f_beam = (np.arange(1, 4) * np.pi / L) ** 2 * np.sqrt(EI / m) / (2 * np.pi)
    assert f == pytest.approx(f_beam, rel=2e-5)  # measured 5e-8 / 8e-7 / 4.1e-6 (grillage vs beam)
    P = 100e3
    exact = -P * L**3 / (48 * EI)
    full = b.static_solution(L / 2, 0.0, -P).evaluate(L / 2, 0.0)[0, 0]
    assert full == pytest.approx(exact, rel=0.01)
    assert full == pytest.approx(exact, rel=1e-9)  # Hermite elements are nodally exact for point loads
    xi = b.static_modal_coordinates([L / 2], [0.0], [-P])
    modal = float(b.mode_shapes(L / 2, 0.0)[0] @ xi)
    assert modal == pytest.approx(exact, rel=0.01)  # 12 modes incl. the 1st, 3rd, 5th… bending: truncation ~0.1 %
    # bottom-fibre strain of the first mode: c ∂²φ/∂x², φ = √(2/mL) sin(πx/L)
    x = np.linspace(0.1, L - 0.1, 9)
    k1 = np.pi / L
    eps = b.strain_shapes(x, 0.0)[:, bending[0]]
    # measured 7.1e-4 (the Hermite curvature of the 34-element mode, O(h²))
    assert eps == pytest.approx(-c * k1**2 * np.sqrt(2 / (m * L)) * np.sin(k1 * x), rel=2e-3, abs=1e-3 * np.abs(eps).max())


def test_mass_normalisation_and_total_mass():
    b = BRIDGE_PRESETS["paper-bridge-2"].build(n_modes=8)
    K, M, free = b.assemble()
    u = np.zeros(K.shape[0])
    u[0::3] = 1.0  # rigid vertical translation
    g = AASHTO_GIRDERS["II"]
    n_d = 3  # end + midspan diaphragms, 0.25 m × 0.75 h between the outer girders
    mass = 2400 * (5 * g.area * 16.76 + 0.20 * 9.75 * 16.76 + n_d * 0.25 * 0.75 * g.depth * 4 * 2.13)
    assert u @ (M @ u) == pytest.approx(mass, rel=1e-12)
    phi = np.zeros((K.shape[0], 8))
    nm = b.nodal_modes
    phi[0::3], phi[1::3], phi[2::3] = (a.reshape(-1, 8) for a in (nm.w, nm.wx, nm.wy))
    assert phi.T @ (M @ phi) == pytest.approx(np.eye(8), abs=1e-9)
    assert phi.T @ (K @ phi) == pytest.approx(np.diag(b.omega**2), rel=1e-8, abs=1e-6 * b.omega[-1] ** 2)


def test_symmetric_load_gives_symmetric_girder_deflections():
    b = BRIDGE_PRESETS["paper-bridge-2"].build()
    L = b.span
    for x in (L / 2, 0.3 * L, 0.37):  # on and off the stations
        s = b.static_solution([x, x], [-1.1, 1.1], [-70e3, -70e3])
        w = s.evaluate(np.full(5, L / 2), b.girder_y)[:, 0]
        assert w == pytest.approx(w[::-1], rel=1e-10)
        assert w.max() < 0


@pytest.mark.parametrize("y_load", [2.13, 1.0, -3.7, 4.6])
def test_sum_of_girder_moments_is_the_beam_moment(y_load):
    b = BRIDGE_PRESETS["paper-bridge-2"].build()
    L, P = b.span, 100e3
    a = b.stations[12]  # load at a station: every element is then loaded at its ends only
    s = b.static_solution(a, y_load, -P)
    EI = b.line_properties["EI"]
    for x in (0.25 * a, 0.9 * a, a + 0.3 * (L - a), L - 0.2):
        k = s.curvatures(np.full(5, x), np.arange(5))[:, 0]
        beam = P * (L - a) * x / L if x < a else P * a * (L - x) / L
        assert EI @ k == pytest.approx(beam, rel=1e-8)


def test_modal_static_converges_to_stiffness_solution():
    b = SlabOnGirderBridge(span=16.76, diaphragms=(0, 8.38, 16.76), n_modes=60, use_cache=False)
    L = b.span
    xs, ys, fs = [L / 2, L / 2 - 4.267], [1.03, 1.03], [-142e3, -142e3]
    exact = b.static_solution(xs, ys, fs).evaluate(np.full(5, L / 2), b.girder_y)[:, 0]
    phi = b.mode_shapes(np.full(5, L / 2), b.girder_y)
    modal = phi @ b.static_modal_coordinates(xs, ys, fs)
    assert modal == pytest.approx(exact, rel=0.01, abs=0.01 * np.abs(exact).max())


@pytest.mark.parametrize("name", ["paper-bridge-1", "paper-bridge-2", "paper-bridge-3", "cypress-bayou"])
def test_default_lateral_offset_loads_the_paper_girder_most(name):
    b = BRIDGE_PRESETS[name].build()
    o, L = b.default_lateral_offset, b.span
    s = b.static_solution([L / 2, L / 2], [o - 1.1, o + 1.1], [-1.0, -1.0])  # HS20-44 track 2.2 m
    w = s.evaluate(np.full(b.n_girders, L / 2), b.girder_y)[:, 0]
    assert int(np.argmin(w)) + 1 == b.default_girder


def test_first_modes_are_bending_then_torsion_and_near_the_beam_estimate():
    # model data §1 [computed]: whole-bridge composite-beam f1 ≈ 24.6 / 7.3 / 2.7 Hz ("a 3D deck model
    # will differ, but not by a factor"); with 36 GPa girders the 3D f1 should be within ±15 % of these.
    for name, f_beam in (("paper-bridge-1", 24.6), ("paper-bridge-2", 7.3), ("paper-bridge-3", 2.7)):
        b = BRIDGE_PRESETS[name].build()
        d = b.mode_descriptions()
        assert d[0].startswith("bending, 1 half-wave") and d[1].startswith("torsion, 1 half-wave")
        assert b.frequencies_hz[0] == pytest.approx(f_beam, rel=0.15)


def test_mesh_convergence_of_first_five_frequencies():
    f = {n: SlabOnGirderBridge(span=16.76, diaphragms=(0, 8.38, 16.76), n_modes=5, n_elements=n, use_cache=False).frequencies_hz
         for n in (10, 20, 40, 160)}
    err = {n: np.abs(f[n] / f[160] - 1).max() for n in (10, 20, 40)}
    assert err[10] > err[20] > err[40]
    assert err[40] < 1e-3  # measured O(h²): slab strips lumped at the stations, linear twist elements
    default = BRIDGE_PRESETS["paper-bridge-2"].build(n_modes=5).frequencies_hz
    assert np.abs(default / f[160] - 1).max() < 1e-3


def test_mode_shapes_are_c1_along_x_between_girders():
    b = BRIDGE_PRESETS["paper-bridge-2"].build()
    xn = b.stations[5:30:6]
    for y in (1.0, -2.9, 4.7):
        lo = b.mode_slopes(xn - 1e-9, y)
        hi = b.mode_slopes(xn + 1e-9, y)
        assert hi == pytest.approx(lo, abs=1e-6 * np.abs(lo).max())
        # the tabulated slopes are the derivative of the values
        h = 1e-5
        fd = (b.mode_shapes(xn + 0.3 + h, y) - b.mode_shapes(xn + 0.3 - h, y)) / (2 * h)
        assert b.mode_slopes(xn + 0.3, y) == pytest.approx(fd, abs=1e-6 * np.abs(fd).max())


def test_shapes_vanish_off_the_span_and_match_nodes_on_lines():
    b = BRIDGE_PRESETS["paper-bridge-1"].build()
    assert not b.mode_shapes([-0.5, b.span + 0.1], [0.0, 2.0]).any()
    nm = b.nodal_modes
    X, Y = np.meshgrid(b.stations, b.girder_y)
    assert b.mode_shapes(X.ravel(), Y.ravel()) == pytest.approx(nm.w.reshape(-1, nm.n_modes), abs=1e-15)


def test_hermite_linear_coupling_matches_quadrature():
    h = 0.73
    xg, wg = np.polynomial.legendre.leggauss(6)
    t = 0.5 * (xg + 1)
    nh = np.array(hermite_basis(t, h, 0))
    nl = np.array([1 - t, t])
    quad = (nh * wg) @ nl.T * h / 2
    assert hermite_linear_coupling(h) == pytest.approx(quad, rel=1e-13)


def test_cache_round_trip(tmp_path):
    kw = dict(span=9.16, n_modes=6, cache_dir=str(tmp_path))
    a = SlabOnGirderBridge(**kw)
    first = a.omega.copy()
    assert len(list((tmp_path / "modes").glob("*.npz"))) == 1
    b = SlabOnGirderBridge(**kw)
    assert np.array_equal(b.omega, first) and np.array_equal(b.nodal_modes.w, a.nodal_modes.w)
    assert SlabOnGirderBridge(**kw, damping_ratio=0.05).cache_key() == a.cache_key()  # damping does not change modes
    assert SlabOnGirderBridge(**{**kw, "deck_thickness": 0.21}).cache_key() != a.cache_key()
    (tmp_path / "modes" / f"slab-on-girder-{a.cache_key()}.npz").write_text("garbage")
    assert np.array_equal(SlabOnGirderBridge(**kw).omega, first)  # a broken cache is re-solved


def test_max_frequency_cutoff():
    b = SlabOnGirderBridge(span=16.76, max_frequency=40.0, use_cache=False)
    ref = SlabOnGirderBridge(span=16.76, n_modes=30, use_cache=False).frequencies_hz
    assert b.frequencies_hz == pytest.approx(ref[ref <= 40.0], rel=1e-9)
