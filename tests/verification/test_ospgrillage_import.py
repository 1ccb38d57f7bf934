"""Modes of an ospgrillage model imported with :func:`vbikit.bridge.opensees.modes_from_opensees`.

This checks the import, not ospgrillage's physics: ospgrillage (ssp-research/ospgrillage on
GitHub/PyPI) builds a live OpenSeesPy model, OpenSees solves its eigenproblem, and the bridge
vbikit imports must reproduce what OpenSees itself reports — the eigenvalues exactly, the vertical
mode shapes at every imported node to round-off, the longitudinal and transverse slopes from the
nodal rotations in ospgrillage's axes (x along the span, y up, z across: w = u_y, ∂w/∂x = θ_z,
∂w/∂y = θ_x with y = −z), and the mass normalisation φᵀMφ = 1 that the import relies on, against
the mass matrix OpenSees assembles (``GimmeMCK`` integrator).  The independent numbers are
OpenSees' own: ``nodeEigenvector``, ``nodeCoord`` and the assembled M.

The model: 12 m × 8 m straight deck, ``Ortho`` mesh of 5 longitudinal by 13 transverse grid
lines (1 m stations), elastic members with made-up section properties; the density is given as
2400/1000 kg/m³ because ospgrillage 0.6 multiplies A·ρ by 1e3 (``members.py``: ``mm = 1e3``).
In-plane DOFs (u_x, u_z, θ_y) are fixed after ospgrillage has built the model, as in the
cross-check grillage, so that eigen returns the plate-bending modes only.  ospgrillage writes
``mat_lib.json`` into the working directory: the tests run in a temporary one.  A skewed mesh has
no common stations along its lines, so the import refuses it with a clear error.

Runs when ospgrillage (optional extra ``ospgrillage``) and openseespy are installed.
"""
from __future__ import annotations

import numpy as np
import pytest
from test_opensees_crosscheck import ops  # noqa: F401 - the ops fixture (loads the wheel's libblas)

N_MODES = 6
L, WIDTH = 12.0, 8.0


def _build(og, skew: float = 0.0):
    concrete = og.create_material(E=30e9, G=12.5e9, rho=2400.0 / 1000)  # ospgrillage 0.6 multiplies A·ρ by 1e3
    beam = og.create_section(A=0.6, J=0.02, Iz=0.15, Iy=0.08, Az=0.3, Ay=0.3)
    slab = og.create_section(A=0.2, J=0.003, Iz=0.0015, Iy=0.02, Az=0.1, Ay=0.1)
    edge = og.create_section(A=0.3, J=0.005, Iz=0.01, Iy=0.01, Az=0.1, Ay=0.1)
    members = {name: og.create_member(section=sec, material=concrete) for name, sec in
               (("beam", beam), ("slab", slab), ("edge", edge))}
    deck = og.create_grillage(bridge_name="import_check", long_dim=L, width=WIDTH, skew=skew, num_long_grid=5,
                              num_trans_grid=13, edge_beam_dist=1.0, mesh_type="Ortho" if skew == 0 else "Oblique")
    for group, m in (("interior_main_beam", "beam"), ("exterior_main_beam_1", "beam"), ("exterior_main_beam_2", "beam"),
                     ("edge_beam", "edge"), ("start_edge", "slab"), ("end_edge", "slab"), ("transverse_slab", "slab")):
        deck.set_member(members[m], member=group)
    deck.create_osp_model(pyfile=False)
    return deck


def _fix_in_plane(ops):  # noqa: F811
    fixed = {n: set(ops.getFixedDOFs(n)) for n in ops.getFixedNodes()}
    for n in ops.getNodeTags():
        mask = [int(d in (1, 3, 5) and d not in fixed.get(n, ())) for d in range(1, 7)]
        if any(mask):
            ops.fix(n, *mask)


def _grid(ops):  # noqa: F811
    """Node tags [line][station]: lines by ascending vbikit y = −z, stations by ascending x."""
    coord = {n: ops.nodeCoord(n) for n in ops.getNodeTags()}
    x = np.array(sorted({round(c[0], 6) for c in coord.values()}))
    z = np.array(sorted({round(c[2], 6) for c in coord.values()}, reverse=True))
    at = {(round(c[0], 6), round(c[2], 6)): n for n, c in coord.items()}
    tags = np.array([[at.get((xi, zj), -1) for xi in x] for zj in z])
    return tags, x, -z


@pytest.fixture
def og(ops, tmp_path, monkeypatch):  # noqa: F811
    monkeypatch.chdir(tmp_path)  # ospgrillage writes mat_lib.json into the working directory
    ospgrillage = pytest.importorskip("ospgrillage", reason="ospgrillage is not installed (optional extra 'ospgrillage')")
    yield ospgrillage
    ops.wipe()


@pytest.fixture
def straight(og, ops, tmp_path):  # noqa: F811
    from vbikit.bridge.opensees import modes_from_opensees

    _build(og)
    _fix_in_plane(ops)
    ops.logFile(str(tmp_path / "ops.log"), "-noEcho")
    lam = ops.eigen("-fullGenLapack", N_MODES)
    tags, x, y = _grid(ops)
    bridge = modes_from_opensees(ops, tags, x, y, lam, vertical_axis="y", girder_y=y[1:-1], default_girder=2)
    return bridge, lam, tags, x, y


def test_frequencies_are_the_eigenvalues(straight):
    bridge, lam, tags, x, y = straight
    assert tags.shape == (5, 13) and (tags > 0).all()  # a full rectangular grid of 65 nodes
    assert np.array_equal(bridge.omega, np.sqrt(np.asarray(lam)))
    # sanity of the mass compensation (not a physics check): the first bending mode (all lines in
    # phase at midspan; mode 2, 12.65 Hz, after a torsional mode at 12.40 Hz) against
    # (π/2L²)·√(EI/m) for the whole section, EI = 30e9·(3·0.15 + 2·0.01) = 1.41e10 N m² and
    # m = 2400·(3·0.6 + 2·0.3 + 0.2·8 m / 1 m) = 9600 kg/m: 13.22 Hz (measured −4.3 %; without the
    # 1/1000 the frequencies would be √1000 ≈ 32× lower)
    mid = bridge.modes.w[:, x.size // 2, :]
    k = next(m for m in range(N_MODES) if np.all(mid[:, m] > 0) or np.all(mid[:, m] < 0))
    assert k == 1
    assert bridge.frequencies_hz[k] == pytest.approx(np.pi / (2 * L**2) * np.sqrt(1.41e10 / 9600), rel=0.06)


def test_shapes_and_slopes_at_the_nodes_are_opensees_eigenvectors(straight, ops):  # noqa: F811
    bridge, lam, tags, x, y = straight
    X, Y = np.broadcast_arrays(x[None, :], y[:, None])
    for k in range(N_MODES):
        u_y = np.array([[ops.nodeEigenvector(int(t), k + 1, 2) for t in row] for row in tags])
        th_x = np.array([[ops.nodeEigenvector(int(t), k + 1, 4) for t in row] for row in tags])
        th_z = np.array([[ops.nodeEigenvector(int(t), k + 1, 6) for t in row] for row in tags])
        w = bridge.mode_shapes(X.ravel(), Y.ravel())[:, k].reshape(X.shape)
        s = np.sign(w.ravel() @ u_y.ravel())  # the import makes the largest |w| positive
        scale = np.abs(u_y).max()
        np.testing.assert_allclose(w, s * u_y, rtol=0, atol=1e-12 * scale)
        assert (w.ravel() @ u_y.ravel()) ** 2 / ((w.ravel() @ w.ravel()) * (u_y.ravel() @ u_y.ravel())) > 1 - 1e-12
        np.testing.assert_allclose(bridge.mode_slopes(X.ravel(), Y.ravel())[:, k].reshape(X.shape), s * th_z,
                                   rtol=0, atol=1e-12 * np.abs(th_z).max())
        np.testing.assert_allclose(bridge.modes.wy[:, :, k], s * th_x, rtol=0, atol=1e-12 * np.abs(th_x).max())
    # the signs of the rotations against the shapes (not against the import's own formulas):
    # ∂w/∂x from θ_z and central differences of w along the lines (1 m stations) agree: measured
    # 1.2e-2 of the largest slope for modes 1–3 (the O(h²) error of the differences)
    w = bridge.modes.w[:, :, :3]
    fd = (w[:, 2:] - w[:, :-2]) / (x[2] - x[0])
    np.testing.assert_allclose(bridge.modes.wx[:, 1:-1, :3], fd, atol=0.02 * np.abs(fd).max())
    # ∂w/∂y from θ_x: in the torsional mode (mode 1) θ_x has the sign of the transverse central
    # difference of w on every interior line at every interior station
    w = bridge.modes.w[:, :, 0]
    dy = (w[2:, 1:-1] - w[:-2, 1:-1]) / (y[2:] - y[:-2])[:, None]
    assert np.all(np.abs(dy) > 0) and np.array_equal(np.sign(bridge.modes.wy[1:-1, 1:-1, 0]), np.sign(dy))


def test_eigenvectors_are_normalised_to_the_opensees_mass_matrix(straight, ops):  # noqa: F811
    bridge, lam, tags, x, y = straight
    ops.wipeAnalysis()
    ops.system("FullGeneral")
    ops.numberer("Plain")
    ops.constraints("Plain")
    ops.algorithm("Linear")
    ops.analysis("Transient")
    ops.integrator("GimmeMCK", 1.0, 0.0, 0.0)
    ops.analyze(1, 0.0)
    n_eq = ops.systemSize()
    M = np.array(ops.printA("-ret")).reshape(n_eq, n_eq)
    phi = np.zeros((n_eq, N_MODES))
    for node in ops.getNodeTags():
        for d, eq in enumerate(ops.nodeDOFs(node)):
            if eq >= 0:
                phi[eq] = [ops.nodeEigenvector(node, k + 1, d + 1) for k in range(N_MODES)]
    # φᵀMφ = I: what modes_from_opensees assumes (measured largest deviation 9e-11).  M is singular
    # (no rotary mass), so analyze() reports a failed solve, but GimmeMCK has assembled M by then
    np.testing.assert_allclose(phi.T @ M @ phi, np.eye(N_MODES), atol=1e-9)


def test_a_skewed_mesh_is_refused_with_a_clear_error(og, ops):  # noqa: F811
    from vbikit.bridge.opensees import modes_from_opensees

    _build(og, skew=20.0)
    _fix_in_plane(ops)
    lam = ops.eigen("-fullGenLapack", 2)
    coord = {n: ops.nodeCoord(n) for n in ops.getNodeTags()}
    lines = sorted({round(c[2], 6) for c in coord.values()}, reverse=True)
    tags = [sorted((n for n, c in coord.items() if round(c[2], 6) == z), key=lambda n: coord[n][0]) for z in lines]
    n_st = min(len(t) for t in tags)
    tags = [t[:n_st] for t in tags]
    x = np.array([coord[t][0] for t in tags[0]]) - coord[tags[0][0]][0]
    with pytest.raises(ValueError, match="rectangular grid"):
        modes_from_opensees(ops, tags, x, -np.array(lines), lam, vertical_axis="y")
