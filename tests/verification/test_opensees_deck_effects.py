"""Girder moments, bearing reactions and imported modes of the slab-on-girder deck against the
independent OpenSeesPy grillage of ``test_opensees_crosscheck.py`` (same node grid, members and
masses, built from the documented formulas in that file).

* Statics: HS20-44 axle loads at grid nodes; OpenSees' element end forces give each girder's
  moment at the midspan node and its bearing reactions; vbikit's influence functions (full
  stiffness) must give the same numbers to solver round-off.
* Import: the OpenSees modes read by :func:`vbikit.bridge.opensees.modes_from_opensees` reproduce
  OpenSees' frequencies exactly and vbikit's own deck (static modal deflection, frequencies) to
  the cross-check's tolerance.

Runs when the optional ``opensees`` extra is installed.
"""
from __future__ import annotations

import numpy as np
import pytest
from test_opensees_crosscheck import build_grillage, ops, static_truck  # noqa: F401 - the ops fixture

from vbikit.bridge import paper_deck

AXLES = [(12.5, 35.6e3), (12.5 - 4.27, 142.3e3), (12.5 - 8.54, 142.3e3)]  # HS20-44 [m, N]


@pytest.fixture(scope="module")
def static_model(ops, tmp_path_factory):  # noqa: F811
    bridge = paper_deck(2, n_modes=8, overhang=0.0)
    tag, xs, ys = build_grillage(ops, bridge, tmp_path_factory.mktemp("ops") / "ops.log")
    pts = static_truck(ops, tag, xs, AXLES)
    ops.reactions()
    return ops, bridge, tag, xs, ys, pts


def test_girder_midspan_moments_and_reactions_agree(static_model):
    ops, bridge, tag, xs, ys, pts = static_model
    n_el = xs.size - 1
    mid = n_el // 2
    px = np.array([xs[i] for i, _, _ in pts])
    py = np.array([ys[j] for _, j, _ in pts])
    pf = -np.array([P for _, _, P in pts])
    for g in range(1, 6):
        j = g - 1
        # girder elements are numbered line by line from 1 (build_grillage); element `mid` starts at midspan
        my = ops.eleForce(j * n_el + mid + 1)[4]  # M_y at its first node = sagging moment there
        ours = bridge.load_effect("moment", x=float(xs[mid]), girder=g).influence(px, py) @ pf
        assert ours == pytest.approx(my, rel=1e-6)
        for support, i in ((0, 0), (1, n_el)):
            r_ops = ops.nodeReaction(tag[j, i], 3)
            r = bridge.load_effect("reaction", support=support, girder=g).influence(px, py) @ pf
            assert r == pytest.approx(r_ops, rel=1e-6, abs=1e-6 * abs(pf).sum())


def test_modes_imported_from_a_live_opensees_model(ops, tmp_path):  # noqa: F811
    from vbikit.bridge.opensees import modes_from_opensees

    bridge = paper_deck(2, n_modes=8, overhang=0.0)
    tag, xs, ys = build_grillage(ops, bridge, tmp_path / "ops.log")
    lam = ops.eigen("-fullGenLapack", 8)
    tags = np.array([[tag[j, i] for i in range(xs.size)] for j in range(ys.size)])
    imported = modes_from_opensees(ops, tags, xs, ys, lam, default_girder=4)
    assert np.array_equal(imported.omega, np.sqrt(np.asarray(lam)))
    assert imported.frequencies_hz[:5] == pytest.approx(bridge.frequencies_hz[:5], rel=0.005)
    # same shapes as vbikit's deck (MAC) and, for the first bending mode, the same mass
    # normalisation (measured ratio 0.9975; torsional modes differ by 3–12 % because the OpenSees
    # model lumps the girder mass without the slab's twist inertia, as its docstring says)
    for k in range(5):
        a, b = bridge.nodal_modes.w[:, :, k].ravel(), imported.modes.w[:, :, k].ravel()
        assert (a @ b) ** 2 / ((a @ a) * (b @ b)) > 0.9999
    a, b = bridge.nodal_modes.w[:, :, 0].ravel(), imported.modes.w[:, :, 0].ravel()
    assert (a @ b) / (b @ b) == pytest.approx(1.0, abs=0.005)
    # slopes from the rotations (∂w/∂x = −θ_y, ∂w/∂y = θ_x): against central differences of w
    w, h = imported.modes.w[:, :, :3], xs[1] - xs[0]
    np.testing.assert_allclose(imported.modes.wx[:, 5:-5, :3], (w[:, 6:-4] - w[:, 4:-6]) / (2 * h),
                               atol=2e-3 * np.abs(imported.modes.wx[:, :, :3]).max())
    dy = (w[2:] - w[:-2]) / (ys[2] - ys[0])
    twist = imported.modes.wy[1:-1, :, 1]  # mode 2 (torsion): the sign and size of ∂w/∂y
    assert np.sign(twist[:, 17]).tolist() == np.sign(dy[:, 17, 1]).tolist()
