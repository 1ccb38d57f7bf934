"""An oblique (skew) OpenSeesPy grid with z up imported by :func:`vbikit.bridge.opensees.modes_from_opensees`.

The ospgrillage test (``test_ospgrillage_import.py``) covers models with y up; this one covers
OpenSees' default axes (x along the span, y to the left, z up: w = u_z, ∂w/∂x = −θ_y, ∂w/∂y = θ_x)
on an oblique mesh with negative skew, built here in a few lines: three girder lines at
y = −1.5, 0, 1.5 m, nine stations ξ = 0 … 8 m along each, node (j, i) at (ξ_i + y_j tan(−30°), y_j)
with exact coordinates, girders and transverse strips (joining the nodes of one station, along the
skew) as elastic beam-columns with made-up properties, lumped masses, bearings (u_z) at both
skewed support lines, in-plane DOFs fixed.  The independent numbers are the skew angle the model
was built with and OpenSees' own eigenvalues and eigenvectors.

Runs when the optional ``opensees`` extra is installed (it is in the ``test`` extra on Linux).
"""
from __future__ import annotations

import numpy as np
import pytest
from test_opensees_crosscheck import ops  # noqa: F401 - the ops fixture (loads the wheel's libblas)

SKEW = -30.0  # [°]
SPAN, N_EL = 8.0, 8
LINES = np.array([-1.5, 0.0, 1.5])
N_MODES = 4


@pytest.fixture(scope="module")
def model(ops, tmp_path_factory):  # noqa: F811
    from vbikit.bridge.opensees import modes_from_opensees

    ops.wipe()
    ops.logFile(str(tmp_path_factory.mktemp("ops") / "ops.log"), "-noEcho")
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    th = np.radians(SKEW)
    xi = np.linspace(0.0, SPAN, N_EL + 1)
    X = xi[None, :] + LINES[:, None] * np.tan(th)
    tags = np.arange(1, X.size + 1).reshape(X.shape)
    for (j, i), t in np.ndenumerate(tags):
        ops.node(int(t), float(X[j, i]), float(LINES[j]), 0.0)
        ops.fix(int(t), 1, 1, 0, 0, 0, 1)  # in-plane DOFs fixed (a grillage)
        if i in (0, N_EL):
            ops.fix(int(t), 0, 0, 1, 0, 0, 0)  # bearings on the skewed support lines
        ops.mass(int(t), 0.0, 0.0, 1500.0 * (0.5 if i in (0, N_EL) else 1.0), 50.0, 50.0, 0.0)
    ops.geomTransf("Linear", 1, 0.0, 1.0, 0.0)  # girders along x
    ops.geomTransf("Linear", 2, float(np.cos(th)), float(-np.sin(th)), 0.0)  # strips along (sin θ, cos θ)
    ele = 1
    for j in range(LINES.size):
        for i in range(N_EL):
            ops.element("elasticBeamColumn", ele, int(tags[j, i]), int(tags[j, i + 1]), 0.5, 30e9, 12.5e9, 0.01, 0.05, 0.08, 1)
            ele += 1
    for j in range(LINES.size - 1):
        for i in range(N_EL + 1):
            ops.element("elasticBeamColumn", ele, int(tags[j, i]), int(tags[j + 1, i]), 0.2, 30e9, 12.5e9, 0.002, 0.01, 0.004, 2)
            ele += 1
    lam = ops.eigen("-fullGenLapack", N_MODES)
    bridge = modes_from_opensees(ops, tags, xi, LINES, lam)
    yield ops, bridge, lam, tags, X
    ops.wipe()


def test_skew_and_frequencies(model):
    ops, bridge, lam, tags, X = model  # noqa: F811
    # exact node coordinates: the fitted tan θ is tan(−30°) to round-off (measured 0 difference)
    assert bridge.skew_tan == pytest.approx(np.tan(np.radians(SKEW)), rel=1e-14)
    assert np.array_equal(bridge.omega, np.sqrt(np.asarray(lam)))
    # θ < 0: the support lines' left (y > 0) ends lie upstream: the deck starts at 1.5 tan 30° = −0.866 m
    # on the left line and ends at 8 + 0.866 m on the right line
    r = 1.5 * np.tan(np.radians(30.0))
    np.testing.assert_allclose(bridge.deck_extent, (-r, SPAN + r), rtol=1e-14)
    assert bridge.default_x_at(1.5) == pytest.approx(SPAN / 2 - r, rel=1e-14)


def test_shapes_and_slopes_are_the_eigenvectors(model):
    ops, bridge, lam, tags, X = model  # noqa: F811
    Y = np.broadcast_to(LINES[:, None], X.shape)
    for k in range(N_MODES):
        u_z, th_x, th_y = (np.array([[ops.nodeEigenvector(int(t), k + 1, d) for t in row] for row in tags]) for d in (3, 4, 5))
        w = bridge.mode_shapes(X.ravel(), Y.ravel())[:, k].reshape(X.shape)
        s = np.sign(w.ravel() @ u_z.ravel())
        np.testing.assert_allclose(w, s * u_z, rtol=0, atol=1e-12 * np.abs(u_z).max())
        np.testing.assert_allclose(bridge.mode_slopes(X.ravel(), Y.ravel())[:, k].reshape(X.shape), -s * th_y,
                                   rtol=0, atol=1e-12 * np.abs(th_y).max())
        np.testing.assert_allclose(bridge.modes.wy[:, :, k], s * th_x, rtol=0, atol=1e-12 * np.abs(th_x).max())
    # the rotations against the shapes alone, on the skewed grid, per mode relative to its largest
    # nodal slope: along the lines the central differences of w are ∂w/∂x = −θ_y (O(h²): measured
    # 2.4 / 1.4 / 0.6 % for modes 1–3); along the oblique strips (constant ξ) the difference of w
    # between two lines per unit y is about the mean of ∂w/∂y + tan θ ∂w/∂x at the strip's ends —
    # in the bending mode 1.9 % (θ_x alone, without the tan θ term, would be off by 56 %)
    m, t = bridge.modes, np.tan(np.radians(SKEW))
    for k in range(3):
        big = max(np.abs(m.wx[:, :, k]).max(), np.abs(m.wy[:, :, k]).max())
        fd_x = (m.w[:, 2:, k] - m.w[:, :-2, k]) / (X[:, 2:] - X[:, :-2])
        assert np.abs(m.wx[:, 1:-1, k] - fd_x).max() < 0.03 * big
    along = m.wy[:, :, 0] + t * m.wx[:, :, 0]
    fd_y = (m.w[1:, :, 0] - m.w[:-1, :, 0]) / np.diff(LINES)[:, None]
    assert np.abs(0.5 * (along[1:] + along[:-1]) - fd_y).max() < 0.03 * max(np.abs(m.wx[:, :, 0]).max(), np.abs(m.wy[:, :, 0]).max())


def test_written_and_read_back_exactly(model, tmp_path):
    """The imported skew bridge saved as a vbikit-modes file (its skew in degrees) reads back with the
    same tan θ to the last bit, and so the same shapes anywhere (the reference: the bridge written)."""
    from vbikit.bridge.modefile import modes_from_file, write_modes

    bridge = model[1]
    again = modes_from_file(write_modes(bridge, tmp_path / "oblique.csv"))
    assert again.skew_tan == bridge.skew_tan and again.deck_extent == bridge.deck_extent
    rng = np.random.default_rng(3)
    x, y = rng.uniform(-1.5, SPAN + 1.5, 300), rng.uniform(-2.0, 2.0, 300)
    for f in ("mode_shapes", "mode_slopes", "strain_shapes"):
        assert np.array_equal(getattr(again, f)(x, y), getattr(bridge, f)(x, y)), f
