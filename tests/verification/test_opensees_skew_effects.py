"""Girder bending moments and shears of the skewed slab-on-girder deck, and a continuous skewed
deck, against the independent OpenSeesPy oblique grillage of ``test_opensees_skew.py`` (its
builder, with a third skewed line of bearings for the continuous deck).

* Simply supported, 20° and 40°: HS20-44 axle loads at the nodes (``truck_nodes``); every girder's
  moment at its own midspan station ξ = L/2, at the station ξ_8 near the quarter span and at the
  quarter point ξ = L/4 inside element 8, and its shear just right of its entry bearing.  vbikit:
  ``bridge.load_effect(kind, x, girder=g).influence`` at the deck's x = ``bridge.girder_x(g, ξ)``
  (full stiffness).  The same nodal loads on the same stiffness: equal to solver round-off.
* Continuous, two 16.76 m spans, 20° (``paper_deck(2, spans=(16.76, 16.76), skew=20)``: the pier
  line through (16.76, 0) skewed like the ends, diaphragms at the three support lines and at both
  midspans): frequencies 1–5 (lumped vs consistent girder mass, ≈ 1e-5, as the simple deck), MAC,
  and under the same truck on span 1 each girder's pier reaction and moment over the pier.

OpenSees sign convention.  ``ops.eleForce(tag)`` gives the 12 end forces the nodes exert on the
element, in global axes: (F_x, F_y, F_z, M_x, M_y, M_z) at node i, then at node j.  A girder
element runs along +x from node i (station ξ_a) to node j, z up.  F_z at node i is the upward
force on the element's left end, the shear V(ξ_a⁺) (vbikit: the sum of the upward forces left of
the section, just right of it).  M_y at node i is the couple about +y on that end; a sagging
section (bottom fibre in tension, σ > 0 at z < 0) has on its −x face the moment ∫ −z σ dA about
+y > 0, so M_y,i = the sagging moment M(ξ_a⁺).  Loads are at the nodes only, so each OpenSees
element's moment is linear: M(s) = M_y,i + F_z,i (s − ξ_a) inside it.  On the grillage the girder
moment jumps at every node by the couple of the transverse members (their torsion, and at a skew
their bending, act on ∂w/∂x); vbikit's moment at a station is the one just right of it, like its
shear, which is OpenSees' element that starts there.

Runs when the optional ``opensees`` extra is installed (it is in the ``test`` extra on Linux).
"""
from __future__ import annotations

import numpy as np
import pytest
from test_opensees_crosscheck import ops  # noqa: F401 - the ops fixture
from test_opensees_skew import AXLES, L, build_skew_grillage, frequencies, static_nodal, truck_nodes

from vbikit.bridge import paper_deck

SKEWS = (20.0, 40.0)
QUARTER_STATION = 8  # ξ_8 = 3.944 m; the quarter point L/4 = 4.19 m lies in element 8 (34 elements)


def girder_end_forces(ops, n_el, j, i):  # noqa: F811
    """OpenSees end forces of the girder element of line j that starts at station i (the builder
    numbers the girder elements line by line from 1)."""
    return np.array(ops.eleForce(j * n_el + i + 1))


def nodal_truck(bridge, xg, ys):
    """The HS20-44 at the nodes: OpenSees' loads [(j, i, P)] and vbikit's points and forces (z up)."""
    pts = truck_nodes(xg, AXLES)
    px = np.array([xg[j, i] for j, i, _ in pts])
    py = np.array([ys[j] for j, _, _ in pts])
    return pts, px, py, -np.array([P for _, _, P in pts])


# ---------------------------------------------------------------- simply supported skewed decks
@pytest.fixture(scope="module", params=SKEWS, ids=lambda v: f"skew{v:g}")
def simple(request, ops, tmp_path_factory):  # noqa: F811
    skew = request.param
    bridge = paper_deck(2, n_modes=8, overhang=0.0, skew=skew, use_cache=False)
    n_el = bridge.element_count
    tag, xi, ys, xg = build_skew_grillage(ops, L, n_el, skew, tmp_path_factory.mktemp("ops") / "ops.log")
    assert np.allclose(bridge.stations, xi, rtol=0, atol=1e-12)
    pts, px, py, pf = nodal_truck(bridge, xg, ys)
    static_nodal(ops, tag, pts)
    mid, q = n_el // 2, QUARTER_STATION
    ops_effects = {}
    for j in range(5):
        f_mid, f_q, f_0 = (girder_end_forces(ops, n_el, j, i) for i in (mid, q, 0))
        ops_effects[j] = {("moment", xi[mid]): f_mid[4], ("moment", xi[q]): f_q[4],
                          ("moment", L / 4): f_q[4] + f_q[2] * (L / 4 - xi[q]), ("shear", 0.0): f_0[2]}
    r_entry = np.array([ops.nodeReaction(tag[j, 0], 3) for j in range(5)])
    return dict(skew=skew, bridge=bridge, px=px, py=py, pf=pf, ops=ops_effects, r_entry=r_entry)


def test_girder_moments_and_shears_of_a_skewed_deck_agree(simple):
    bridge, px, py, pf = simple["bridge"], simple["px"], simple["py"], simple["pf"]
    worst = 0.0
    for g in range(1, 6):
        for (kind, xi), ref in simple["ops"][g - 1].items():
            ours = bridge.load_effect(kind, x=float(bridge.girder_x(g, xi)), girder=g).influence(px, py) @ pf
            worst = max(worst, abs(ours / ref - 1))
            assert ours == pytest.approx(ref, rel=1e-6), (g, kind, xi)
    print(f"skew {simple['skew']}: largest relative difference {worst:.1e}")  # measured 1.9e-10 (20°), 2.3e-11 (40°)


def test_entry_shears_add_up_to_the_entry_reactions(simple):
    """Statics of the sign convention: the free body of the entry support line (its bearing nodes and
    the transverse members between them) is held by the bearings and by the girder elements that
    start there, so Σ_g V_g(0⁺) = Σ_g R_g,entry — in OpenSees (its end forces F_z,i against its own
    reactions) and in vbikit — while each girder's shear differs from its own bearing's reaction
    by what the transverse members bring to that bearing."""
    bridge, px, py, pf = simple["bridge"], simple["px"], simple["py"], simple["pf"]
    v_ops = np.array([simple["ops"][j]["shear", 0.0] for j in range(5)])
    assert v_ops.sum() == pytest.approx(simple["r_entry"].sum(), rel=1e-9)
    v = np.array([bridge.load_effect("shear", x=float(bridge.girder_x(g, 0.0)), girder=g).influence(px, py) @ pf
                  for g in range(1, 6)])
    assert v.sum() == pytest.approx(simple["r_entry"].sum(), rel=1e-9)
    assert np.abs(v_ops - simple["r_entry"]).max() > 1e-3 * np.abs(v_ops).max()  # not the reactions themselves


# ---------------------------------------------------------------- continuous skewed deck
@pytest.fixture(scope="module")
def continuous(ops, tmp_path_factory):  # noqa: F811
    skew = 20.0
    bridge = paper_deck(2, n_modes=8, overhang=0.0, spans=(L, L), skew=skew, use_cache=False)
    n_el = bridge.element_count
    tag, xi, ys, xg = build_skew_grillage(ops, 2 * L, n_el, skew, tmp_path_factory.mktemp("ops") / "ops.log",
                                          strip_twist_inertia=False, spans=(L, L))
    pier = int(np.argmin(np.abs(xi - L)))
    assert bridge.support_stations == (0, pier, n_el) and np.allclose(bridge.stations, xi, rtol=0, atol=1e-12)
    f_ops = frequencies(ops, 5, "-genBandArpack")
    w_ops = np.array([[[ops.nodeEigenvector(tag[j, i], k + 1, 3) for k in range(5)] for i in range(xi.size)] for j in range(5)])
    pts, px, py, pf = nodal_truck(bridge, xg, ys)
    static_nodal(ops, tag, pts)
    r_ops = np.array([[ops.nodeReaction(tag[j, i], 3) for i in (0, pier, n_el)] for j in range(5)])
    m_pier = np.array([girder_end_forces(ops, n_el, j, pier)[4] for j in range(5)])
    return dict(bridge=bridge, f=f_ops, w=w_ops, px=px, py=py, pf=pf, r=r_ops, m_pier=m_pier)


def test_continuous_skewed_deck_frequencies_and_modes_agree(continuous):
    bridge = continuous["bridge"]
    f_vbi = bridge.frequencies_hz[:5]
    print("continuous 20°: OpenSees", continuous["f"], "vbikit", f_vbi, "rel", f_vbi / continuous["f"] - 1)
    # measured +1.9e-7 … +1.3e-5 (lumped vs consistent girder mass)
    assert f_vbi == pytest.approx(continuous["f"], rel=1e-4)
    for k in range(5):
        a, b = continuous["w"][:, :, k].ravel(), bridge.nodal_modes.w[:, :, k].ravel()
        assert 1 - (a @ b) ** 2 / ((a @ a) * (b @ b)) < 1e-7  # measured 5e-13 … 1.7e-11


def test_continuous_skewed_deck_pier_reactions_and_hogging_moments_agree(continuous):
    bridge, px, py, pf = continuous["bridge"], continuous["px"], continuous["py"], continuous["pf"]
    total = -pf.sum()
    r = np.array([[bridge.load_effect("reaction", support=k, girder=g).influence(px, py) @ pf for k in range(3)]
                  for g in range(1, 6)])
    assert r.sum() == pytest.approx(total, rel=1e-9)
    np.testing.assert_allclose(r, continuous["r"], rtol=0, atol=1e-9 * total)
    m = np.array([bridge.load_effect("moment", x=float(bridge.girder_x(g, L)), girder=g).influence(px, py) @ pf
                  for g in range(1, 6)])
    print("moments over the pier [N m]: OpenSees", continuous["m_pier"], "vbikit", m)
    np.testing.assert_allclose(m, continuous["m_pier"], rtol=0, atol=1e-6 * np.abs(continuous["m_pier"]).max())
    assert np.all(m[1:] < 0)  # hogging over the pier on Girders 2–5 (Girder 1, lifting at the pier, is not)
