# Girder load effects of the slab-on-girder deck (grillage) where the load stands inside the
# section's own element, and the modal values of those effects.
#
# * Statics (any beam text): a girder's moment influence line is continuous everywhere (a kink at
#   the section); its shear influence line is continuous except at the section, where it jumps by
#   the part of the unit load the girder line carries there.  On the girder's own line that part
#   is 1; midway between two girder lines it is the value weight of the transverse cubic Hermite
#   element at t = 1/2, 1 − 3t² + 2t³ = 1/2 (the deck's documented transverse interpolation).
# * Modal values: with every mode kept, Σ_i r_i φ_i(x, y)/ω_i² equals the full-stiffness influence
#   I(x, y) for a load on a girder line outside the section's element (K⁻¹ = Σ φ φᵀ/ω², φᵀMφ = 1); the
#   influence lines are checked against OpenSees in test_opensees_deck_effects.py.  (A shear's modal
#   inertia term ω² m φ (s − element middle) is an O(h) correction this identity does not resolve.)
from __future__ import annotations

import numpy as np
import pytest

from vbikit.bridge import paper_deck

EPS = 1e-7


@pytest.fixture(scope="module")
def deck():
    return paper_deck(1, n_modes=4, use_cache=False, n_elements=12)


@pytest.mark.parametrize("girder", [2, 4])
@pytest.mark.parametrize("between", [False, True])
def test_influence_inside_the_section_element(deck, girder, between):
    xs = deck.stations
    s = 3.1
    e = int(np.searchsorted(xs, s) - 1)
    a, b = xs[e], xs[e + 1]
    assert a < s < b
    gy = deck.girder_y
    y = 0.5 * (gy[girder - 1] + gy[girder]) if between else gy[girder - 1]
    share = 0.5 if between else 1.0
    M = deck.load_effect("moment", x=s, girder=girder).influence
    V = deck.load_effect("shear", x=s, girder=girder).influence

    def at(f, x):
        return f(np.array([x]), np.array([y]))[0]

    scale_m = abs(at(M, s))
    for x0 in (a, b, s):
        assert at(M, x0 - EPS) == pytest.approx(at(M, x0 + EPS), abs=1e-6 * scale_m)
    for x0 in (a, b):
        assert at(V, x0 - EPS) == pytest.approx(at(V, x0 + EPS), abs=1e-6)
    # V counts a load at x ≤ s as left of the section: an upward unit load there adds its share
    assert at(V, s - EPS) - at(V, s + EPS) == pytest.approx(share, abs=1e-6)


@pytest.fixture(scope="module")
def full_deck():
    d = paper_deck(1, n_modes=1000, use_cache=False, n_elements=16)
    return d


@pytest.mark.parametrize("kind, kw", [
    ("moment", {"x": 4.58, "girder": 4}), ("moment", {"x": 2.0, "girder": 2}),
    ("reaction", {"support": 0, "girder": 4}), ("reaction", {"support": 1, "girder": 2}),
])
def test_all_modes_superpose_to_the_influence(full_deck, kind, kw):
    d = full_deck
    e = d.load_effect(kind, **kw)
    gy = d.girder_y
    xp = np.array([0.9, 2.9, 5.3, 7.9, 8.6, 3.7])
    # on the girder lines, where φ is the FE model's own Hermite interpolation (between lines the
    # transverse slope is a spline through the nodal values, not the FE shape functions)
    yp = np.array([gy[0], gy[2], gy[3], gy[1], gy[4], gy[4]])
    if kind == "reaction":  # away from the bearing (the consistent mass couples its node to its neighbours)
        keep = np.abs(xp - d.support_x[kw["support"]]) > 2.0
        xp, yp = xp[keep], yp[keep]
    else:
        xs = d.stations
        j = int(np.searchsorted(xs, kw["x"], side="right") - 1)
        keep = (xp < xs[j] - 1e-9) | (xp > xs[min(j + 1, xs.size - 1)] + 1e-9)
        xp, yp = xp[keep], yp[keep]
    modal = (d.mode_shapes(xp, yp) / d.omega**2) @ e.modal
    ref = e.influence(xp, yp)
    # measured: moment 1e-11 (exact: an unloaded element's cubic is the exact girder line); a bearing's
    # reaction ≤ 4e-4 more than 2 m from it (the consistent mass couples the bearing node to its neighbours)
    np.testing.assert_allclose(modal, ref, atol=(1e-8 if kind == "moment" else 2e-3) * np.abs(ref).max())


# ---------------------------------------------------------------- modal values from equilibrium
def test_bearing_modal_reactions_balance_the_modes_inertia(deck):
    # free vibration in mode i (ξ̈ = −ω² ξ): the bearings of all girders carry the deck's whole inertia
    # force, Σ_bearings R = −ω² ∫ m φ dA = −ω² e_wᵀ M φ (e_w: unit vertical translation of every node;
    # M the deck's assembled mass, bearing rows included)
    _, M, _ = deck.assemble()
    dofs = deck.dof_map
    full = dofs.vector(deck.nodal_modes)
    e_w = np.zeros(M.shape[0])
    for line in range(deck.girder_y.size):
        for st in range(deck.stations.size):
            e_w[dofs.dof(line, st, 0)] = 1.0
    inertia = -deck.omega**2 * (e_w @ (M @ full))
    total = sum(deck.load_effect("reaction", support=k, girder=g).modal for g in range(1, 6) for k in (0, 1))
    np.testing.assert_allclose(total, inertia, rtol=1e-9, atol=1e-9 * np.abs(inertia).max())


def test_modal_shear_against_the_elements_equilibrium(deck):
    # mode i in free vibration: the girder element [a, b] holding s is loaded by its nodes with
    # f = (K_e − ω² M_e) u_e (Przemieniecki 1968 §5.3, §11.3; u_e the mode's nodal w, ∂w/∂x) and by
    # the distributed inertia ω² m φ(x), so V(s) = f_w(a) + ω² m ∫_a^s φ dx (trapezoid, 2001 points)
    g, s = 4, 3.1
    j = deck.girder_index(g)
    xs = deck.stations
    e = int(np.searchsorted(xs, s, side="right") - 1)
    a, b = xs[e], xs[e + 1]
    h = b - a
    EI = deck.girder_element_EI(j, e)
    m = float(deck.line_properties["m"][j])
    nm = deck.nodal_modes
    ue = np.stack([nm.w[j][e], nm.wx[j][e], nm.w[j][e + 1], nm.wx[j][e + 1]])
    Ke = EI / h**3 * np.array([[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                               [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    Me = m * h / 420 * np.array([[156, 22 * h, 54, -13 * h], [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                                 [54, 13 * h, 156, -22 * h], [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
    om = deck.omega
    xq = np.linspace(a, s, 2001)
    V = (Ke @ ue - om**2 * (Me @ ue))[0] + om**2 * m * np.trapezoid(nm.line_values(xq, 0)[j], xq, axis=0)
    r = deck.load_effect("shear", x=s, girder=g).modal
    # the model's shear is the cubic's EI w''' plus a linear inertia correction: measured 0.5 % (mode 1),
    # 1.1 % (2), 4.6 % (3) from the element's equilibrium (12 elements; the cubic is coarse for higher modes)
    np.testing.assert_allclose(r[:2], V[:2], rtol=2e-2)
    np.testing.assert_allclose(r[:4], V[:4], rtol=6e-2)
