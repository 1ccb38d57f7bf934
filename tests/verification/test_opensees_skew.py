"""Independent cross-check of the skewed slab-on-girder deck against a skewed grillage built in
OpenSeesPy, and the point symmetry of a skewed deck's modes.

The OpenSees model is the "oblique mesh" grillage (Hambly, *Bridge Deck Behaviour*, 2nd ed. 1991,
§5; ospgrillage's oblique mesh) built directly in openseespy, like the straight deck's cross-check
(``test_opensees_crosscheck.py``): girder lines along x at y_j, nodes at the stations ξ_i along each
girder placed at global (ξ_i + y_j tan θ, y_j), so that every station lies on a line parallel to the
skewed support lines (x − y tan θ = const).  Girder members join consecutive nodes of a line
(same composite section, lumped girder mass and rotary inertia as the straight check); slab strips
(and diaphragms) join neighbouring lines along the skew direction, length s / cos θ, with the slab
width measured perpendicular to the member, l_i cos θ (l_i the station's tributary length along
the girders), so EI = E t³ l_i cos θ / (12 (1 − ν²)), GJ = G t³ l_i cos θ / 6 and the consistent
slab mass μ l_i cos θ per member length; a diaphragm keeps its section on the longer member.
OpenSees' ``geomTransf`` does the rotation of each member's stiffness into the global DOFs: the
transverse members' local z axis is the in-plane normal (cos θ, −sin θ, 0), so their strong-axis
I_z gives vertical bending.  Section properties are worked out again here from the documented
formulas (docs/bridges.md), not taken from vbikit.  Bearings restrain u_z at every girder node on
the support lines (the two ends, and the interior lines of a continuous deck).  In-plane DOFs are
fixed (a grillage); overhang zero, as in the straight check.

Expected agreement.  The two models differ only in the girders' mass, lumped at the nodes here and
consistent in vbikit (frequencies within ≈ 3e-5), once OpenSees' consistent member mass is kept
from adding a twist inertia m J / A to the slab strips (``strip_twist_inertia``), which the
documented model does not have and which is most of the straight cross-check's difference (0.12 %
on its 5th mode).  Static deflections and reactions under the same nodal loads agree to solver
round-off.  Skew 0 is compared too: the straight deck on the same terms.

Runs when the optional ``opensees`` extra is installed (it is in the ``test`` extra on Linux).
"""
from __future__ import annotations

import numpy as np
import pytest
from test_opensees_crosscheck import build_grillage, composite_line, ops, static_nodal  # noqa: F401 - the ops fixture, static_nodal for the effects test

from vbikit.bridge import paper_deck

IN = 0.0254
L = 16.76  # Bridge 2 span [m]


def build_skew_grillage(ops, span, n_el, skew_deg, log_path, strip_twist_inertia=True, spans=None):  # noqa: F811
    """Bridge-2 grillage (five Type II girders at 2.13 m, no overhang) with support lines skewed by
    ``skew_deg`` [°]; returns node tags [line, station], the stations ξ [m], the lines' y [m] and
    the node coordinates x[line, station] [m].

    ``spans`` [m] (adding up to ``span``; default one span): the girders run continuous over
    interior lines of bearings at ξ = x_k (the cumulative span lengths), skewed like the end lines
    through (x_k, 0); the ``n_el`` elements are shared among the spans in proportion to their
    lengths, equal within a span.  Diaphragms at every support line and at the middle of every
    span (Bridge 2's, ``paper_deck(2)``).

    OpenSees' consistent beam mass (``-cMass``) gives a member the torsional inertia m J / A per
    length besides its translational mass m; the documented deck model has none on its slab strips.
    ``strip_twist_inertia=False`` removes it: the strips' area only enters that term and the axial
    stiffness, which acts on the fixed in-plane DOFs alone, so an area 1e6 times larger makes it
    vanish without changing anything else."""
    ops.wipe()
    ops.logFile(str(log_path), "-noEcho")
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    s, t = 2.13, 0.20
    Eg, Ed, nu, rho = 36e9, 33e9, 0.2, 2400.0
    Gg, Gd = Eg / (2 * (1 + nu)), Ed / (2 * (1 + nu))
    A, h, I = 369 * IN**2, 36 * IN, 50979 * IN**4  # AASHTO Type II (PCI); girder lines: composite_line
    th = np.radians(skew_deg)
    c, sn, tn = np.cos(th), np.sin(th), np.tan(th)
    spans = (span,) if spans is None else tuple(spans)
    edges = np.concatenate([[0.0], np.cumsum(spans)])
    n_span = [int(round(n_el * length / span)) for length in spans]
    assert sum(n_span) == n_el and abs(edges[-1] - span) < 1e-9 * span
    xi = np.concatenate([np.linspace(a, b, n + 1)[:-1] for a, b, n in zip(edges[:-1], edges[1:], n_span)] + [[span]])
    bearings = np.concatenate([[0], np.cumsum(n_span)])  # station indices of the support lines
    first = bearings[:-1]
    h_el = np.repeat(xi[first + 1] - xi[first], n_span)  # element lengths (equal within a span)
    trib_x = np.concatenate([h_el / 2, [0.0]]) + np.concatenate([[0.0], h_el / 2])  # station tributary length
    ys = (np.arange(5) - 2) * s
    xg = xi[None, :] + ys[:, None] * tn
    trib_y = np.array([s / 2, s, s, s, s / 2])
    tag = {}
    for j, y in enumerate(ys):
        for i in range(xi.size):
            tag[j, i] = 1000 * j + i + 1
            ops.node(tag[j, i], float(xg[j, i]), float(y), 0.0)
            ops.fix(tag[j, i], 1, 1, 0, 0, 0, 1)  # grillage: in-plane DOFs fixed
    for j in range(5):
        for i in bearings:
            ops.fix(tag[j, int(i)], 0, 0, 1, 0, 0, 0)  # bearings on the skewed support lines
    ops.geomTransf("Linear", 1, 0.0, 1.0, 0.0)  # girders along x: local z = global y
    ops.geomTransf("Linear", 2, float(c), float(-sn), 0.0)  # strips along (sin θ, cos θ): local z = in-plane normal
    ele = 1
    for j in range(5):
        area, Ic, GJ = composite_line(trib_y[j])
        for i in range(n_el):
            ops.element("elasticBeamColumn", ele, tag[j, i], tag[j, i + 1], area, Eg, Gg, GJ / Gg, 1.0, Ic, 1)
            ele += 1
        for i in range(n_el + 1):
            ops.mass(tag[j, i], 0.0, 0.0, rho * A * trib_x[i], rho * I * trib_x[i], 0.0, 0.0)
    Dd, bd = 0.75 * h, 0.25
    GJd = Gd * (1 - 0.63 * bd / Dd) / 3 * Dd * bd**3
    dxi = tuple(edges) + tuple(0.5 * (edges[1:] + edges[:-1]))  # support and midspan diaphragms (paper_deck(2))
    area_factor = 1.0 if strip_twist_inertia else 1e6
    for i, x in enumerate(xi):
        w = trib_x[i] * c  # strip width perpendicular to the member
        n_d = sum(abs(x - d) < 1e-9 for d in dxi)
        Iz = t**3 * w / (12 * (1 - nu**2)) + n_d * bd * Dd**3 / 12
        J = t**3 / 6 * w + n_d * GJd / Gd
        m = rho * t * w + n_d * rho * bd * Dd
        for j in range(4):
            ops.element("elasticBeamColumn", ele, tag[j, i], tag[j + 1, i], t * w * area_factor, Ed, Gd, J, 1.0, Iz, 2, "-mass", m, "-cMass")
            ele += 1
    return tag, xi, ys, xg


def truck_nodes(xg, axles, lines=(2, 3)):
    """HS20-44 axles [(x [m], axle load [N])] perpendicular to the girders, each split over the
    wheel lines above ``lines``, at the node of each line nearest to the axle: [(j, i, P)]."""
    return [(j, int(np.argmin(np.abs(xg[j] - x))), P / 2) for x, P in axles for j in lines]


AXLES = [(12.5, 35.6e3), (12.5 - 4.27, 142.3e3), (12.5 - 8.54, 142.3e3)]  # HS20-44 [m, N] (AASHTO)


def frequencies(ops, k, solver="-fullGenLapack"):  # noqa: F811
    """The k lowest frequencies [Hz]; ``"-genBandArpack"`` (shift-invert Lanczos) is 50× faster than the
    dense solver on the two-span model and agrees with it to 2e-11 (frequencies) and 1e-15 (1 − MAC)."""
    return np.sqrt(np.array(ops.eigen(solver, k))) / (2 * np.pi)


# ---------------------------------------------------------------- the OpenSees model on its own
def test_skew_zero_is_the_straight_opensees_grillage(ops, tmp_path):  # noqa: F811
    bridge = paper_deck(2, n_modes=8, overhang=0.0)
    build_grillage(ops, bridge, tmp_path / "a.log")
    f_straight = frequencies(ops, 6)
    build_skew_grillage(ops, L, bridge.element_count, 0.0, tmp_path / "b.log")
    f_skew0 = frequencies(ops, 6)
    assert np.array_equal(f_skew0, f_straight)


@pytest.mark.parametrize("skew", [20.0, 40.0])
def test_opensees_skew_reactions_balance_the_load(ops, tmp_path, skew):  # noqa: F811
    n_el = 34
    tag, xi, ys, xg = build_skew_grillage(ops, L, n_el, skew, tmp_path / "ops.log")
    pts = truck_nodes(xg, AXLES)
    static_nodal(ops, tag, pts)
    R = sum(ops.nodeReaction(tag[j, i], 3) for j in range(5) for i in (0, n_el))
    total = sum(P for _, _, P in pts)
    assert R == pytest.approx(total, rel=1e-10)


# ---------------------------------------------------------------- vbikit against OpenSees
SKEWS = (20.0, 40.0)


@pytest.fixture(scope="module", params=(0.0,) + SKEWS, ids=lambda v: f"skew{v:g}")
def skewed(request, ops, tmp_path_factory):  # noqa: F811
    skew = request.param
    bridge = paper_deck(2, n_modes=8, overhang=0.0, skew=skew, use_cache=False)
    tag, xi, ys, xg = build_skew_grillage(ops, L, bridge.element_count, skew, tmp_path_factory.mktemp("ops") / "ops.log",
                                          strip_twist_inertia=False)
    assert np.allclose(bridge.stations, xi, rtol=0, atol=1e-12) and np.allclose(bridge.girder_y, ys, rtol=0, atol=1e-12)
    f_ops = frequencies(ops, 5)
    w_ops = np.array([[[ops.nodeEigenvector(tag[j, i], k + 1, 3) for k in range(5)] for i in range(xi.size)] for j in range(5)])
    pts = truck_nodes(xg, AXLES)
    static_nodal(ops, tag, pts)
    u_ops = np.array([[ops.nodeDisp(tag[j, i], 3) for i in range(xi.size)] for j in range(5)])
    r_ops = np.array([[ops.nodeReaction(tag[j, i], 3) for i in (0, xi.size - 1)] for j in range(5)])
    return dict(skew=skew, bridge=bridge, xg=xg, ys=ys, f=f_ops, w=w_ops, pts=pts, u=u_ops, r=r_ops)


def test_skewed_deck_frequencies_and_mode_shapes_agree(skewed):
    bridge = skewed["bridge"]
    f_vbi = bridge.frequencies_hz[:5]
    print(f"skew {skewed['skew']}: OpenSees", skewed["f"], "vbikit", f_vbi, "rel", f_vbi / skewed["f"] - 1)
    # measured +8e-8 … +3.0e-5 (lumped vs consistent girder mass, the only difference left)
    assert f_vbi == pytest.approx(skewed["f"], rel=1e-4)
    for k in range(5):
        a, b = skewed["w"][:, :, k].ravel(), bridge.nodal_modes.w[:, :, k].ravel()
        mac = (a @ b) ** 2 / ((a @ a) * (b @ b))
        assert 1 - mac < 1e-7  # measured 4e-13 … 3.5e-9


def test_skewed_deck_static_deflections_under_a_truck_agree(skewed):
    bridge, xg, ys, pts = skewed["bridge"], skewed["xg"], skewed["ys"], skewed["pts"]
    s = bridge.static_solution([xg[j, i] for j, i, _ in pts], [ys[j] for j, _, _ in pts], [-P for _, _, P in pts])
    u = s.w[:, :, 0]
    err = np.abs(u - skewed["u"]).max() / np.abs(skewed["u"]).max()
    assert err < 1e-9  # measured 5e-11 (20°), 6e-12 (40°): same nodal loads, same stiffness


def test_skewed_deck_bearing_reactions_agree_and_balance_the_load(skewed):
    bridge, xg, ys, pts = skewed["bridge"], skewed["xg"], skewed["ys"], skewed["pts"]
    px = np.array([xg[j, i] for j, i, _ in pts])
    py = np.array([ys[j] for j, _, _ in pts])
    pf = -np.array([P for _, _, P in pts])
    r = np.array([[bridge.load_effect("reaction", support=k, girder=g).influence(px, py) @ pf for k in (0, 1)]
                  for g in range(1, 6)])
    total = -pf.sum()
    assert r.sum() == pytest.approx(total, rel=1e-9)  # measured 3e-11
    assert skewed["r"].sum() == pytest.approx(total, rel=1e-9)
    np.testing.assert_allclose(r, skewed["r"], rtol=0, atol=1e-9 * total)  # measured 9e-12 of the load


# ---------------------------------------------------------------- physics of the skewed deck alone
@pytest.mark.parametrize("skew", SKEWS)
def test_skewed_deck_modes_are_point_symmetric(skew):
    """A skewed simply supported deck is symmetric under the 180° rotation (x, y) → (span − x, −y)
    about its centre: node (j, i) maps to node (n − 1 − j, N − i), so each mode is symmetric or
    antisymmetric under the rotation, and its slopes the opposite."""
    bridge = paper_deck(2, n_modes=8, skew=skew, use_cache=False)  # with its overhangs
    m = bridge.nodal_modes
    for k in range(m.n_modes):
        w, wx, wy = m.w[:, :, k], m.wx[:, :, k], m.wy[:, :, k]
        rot = w[::-1, ::-1]
        sign = 1.0 if np.abs(w - rot).max() < np.abs(w + rot).max() else -1.0
        scale = np.abs(w).max()
        assert np.abs(w - sign * rot).max() < 1e-8 * scale  # measured ≤ 2e-11
        slope = max(np.abs(wx).max(), np.abs(wy).max())
        assert np.abs(wx + sign * wx[::-1, ::-1]).max() < 1e-8 * slope
        assert np.abs(wy + sign * wy[::-1, ::-1]).max() < 1e-8 * slope


def test_opposite_skews_are_mirror_images():
    """Skew −θ is the mirror image y → −y of skew θ: node (j, i) of one is node (n − 1 − j, i) of the
    other, the frequencies are equal and each mode is the mirrored one (up to its sign), with
    ∂w/∂x kept and ∂w/∂y reversed."""
    a = paper_deck(2, n_modes=8, skew=20.0, use_cache=False)
    b = paper_deck(2, n_modes=8, skew=-20.0, use_cache=False)
    assert b.frequencies_hz == pytest.approx(a.frequencies_hz, rel=1e-10)  # measured 2e-12
    ma, mb = a.nodal_modes, b.nodal_modes
    for k in range(ma.n_modes):
        w, wm = ma.w[:, :, k], mb.w[::-1, :, k]
        sign = 1.0 if np.abs(w - wm).max() < np.abs(w + wm).max() else -1.0
        assert np.abs(w - sign * wm).max() < 1e-8 * np.abs(w).max()  # measured ≤ 2e-11
        slope = max(np.abs(ma.wx[:, :, k]).max(), np.abs(ma.wy[:, :, k]).max())
        assert np.abs(ma.wx[:, :, k] - sign * mb.wx[::-1, :, k]).max() < 1e-8 * slope
        assert np.abs(ma.wy[:, :, k] + sign * mb.wy[::-1, :, k]).max() < 1e-8 * slope
