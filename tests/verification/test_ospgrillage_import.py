"""Modes of an ospgrillage model imported with :func:`vbikit.bridge.opensees.modes_from_opensees`.

This checks the import, not ospgrillage's physics: ospgrillage (ssp-research/ospgrillage on
GitHub/PyPI) builds a live OpenSeesPy model, OpenSees solves its eigenproblem, and the bridge
vbikit imports must reproduce what OpenSees itself reports — the eigenvalues exactly, the vertical
mode shapes at every imported node to round-off, the longitudinal and transverse slopes from the
nodal rotations in ospgrillage's axes (x along the span, y up, z across: w = u_y, ∂w/∂x = θ_z,
∂w/∂y = θ_x with y = −z), and the mass normalisation φᵀMφ = 1 that the import relies on, against
the mass matrix OpenSees assembles (``GimmeMCK`` integrator).  The independent numbers are
OpenSees' own: ``nodeEigenvector``, ``nodeCoord`` and the assembled M, and for the skewed deck the
skew angle given to ospgrillage.

The models: 12 m × 8 m deck, 5 longitudinal by 13 transverse grid lines (1 m stations along the
lines), elastic members with made-up section properties: the straight deck (``Ortho`` mesh) and a
deck with 20° skew supports (``Oblique`` mesh: every line has its 13 nodes at the same stations ξ
along it, shifted by z tan 20° from line to line).  The density is given as 2400/1000 kg/m³
because ospgrillage 0.6 multiplies A·ρ by 1e3 (``members.py``: ``mm = 1e3``).  In-plane DOFs
(u_x, u_z, θ_y) are fixed after ospgrillage has built the model, as in the cross-check grillage,
so that eigen returns the plate-bending modes only.  ospgrillage writes ``mat_lib.json`` into the
working directory: the tests run in a temporary one.

Runs when ospgrillage (optional extra ``ospgrillage``) and openseespy are installed.
"""
from __future__ import annotations

import re

import numpy as np
import pytest
from test_opensees_crosscheck import ops  # noqa: F401 - the ops fixture (loads the wheel's libblas)

N_MODES = 6
L, WIDTH = 12.0, 8.0
SKEW = 20.0  # [°] the oblique deck's skew, as given to ospgrillage


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
    """Node tags [line][station] (lines by ascending vbikit y, nodes along each line by ascending x),
    the stations along the lines ξ_i = x − x of the line's first node, the lines' y = WIDTH/2 − z (from
    the deck centreline; ospgrillage's z runs from 0 to WIDTH) and the nodes' plan x [line][station]."""
    coord = {n: ops.nodeCoord(n) for n in ops.getNodeTags()}
    z = np.array(sorted({round(c[2], 6) for c in coord.values()}, reverse=True))
    tags = np.array([sorted((n for n, c in coord.items() if round(c[2], 6) == zj), key=lambda n: coord[n][0]) for zj in z])
    plan_x = np.array([[coord[t][0] for t in row] for row in tags])
    return tags, plan_x[0] - plan_x[0, 0], WIDTH / 2 - z, plan_x


@pytest.fixture
def og(ops, tmp_path, monkeypatch):  # noqa: F811
    monkeypatch.chdir(tmp_path)  # ospgrillage writes mat_lib.json into the working directory
    ospgrillage = pytest.importorskip("ospgrillage", reason="ospgrillage is not installed (optional extra 'ospgrillage')")
    yield ospgrillage
    ops.wipe()


def _import(og, ops, tmp_path, skew):  # noqa: F811
    from vbikit.bridge.opensees import modes_from_opensees

    _build(og, skew=skew)
    _fix_in_plane(ops)
    ops.logFile(str(tmp_path / "ops.log"), "-noEcho")
    lam = ops.eigen("-fullGenLapack", N_MODES)
    tags, x, y, plan_x = _grid(ops)
    bridge = modes_from_opensees(ops, tags, x, y, lam, vertical_axis="y", girder_y=y[1:-1], default_girder=2,
                                 deck_width=WIDTH)
    # the nodes' x in vbikit's frame, where the entry support line crosses y = 0 at x = 0: the first
    # line's first node is at x = y_0 tan θ; from ospgrillage's node coordinates and its skew angle
    X = plan_x - plan_x[0, 0] + y[0] * np.tan(np.radians(skew))
    return bridge, lam, tags, X, np.broadcast_to(y[:, None], X.shape)


def _grid_x(bridge, Y):
    """x of the imported grid's nodes, ξ_i + y_j tan θ with the import's fitted tan θ."""
    return bridge.modes.x[None, :] + Y * bridge.skew_tan


@pytest.fixture(params=[0.0, SKEW], ids=["straight", "skew20"])
def imported(og, ops, tmp_path, request):  # noqa: F811
    return _import(og, ops, tmp_path, request.param) + (request.param,)


@pytest.fixture
def straight(og, ops, tmp_path):  # noqa: F811
    return _import(og, ops, tmp_path, 0.0)


@pytest.fixture
def oblique(og, ops, tmp_path):  # noqa: F811
    return _import(og, ops, tmp_path, SKEW)


def test_frequencies_are_the_eigenvalues(imported):
    bridge, lam, tags, X, Y, skew = imported
    assert tags.shape == (5, 13) and (tags > 0).all()  # a full grid of 65 nodes
    assert np.array_equal(bridge.omega, np.sqrt(np.asarray(lam)))
    if skew:
        return
    # sanity of the mass compensation (not a physics check): the first bending mode (all lines in
    # phase at midspan; mode 2, 12.65 Hz, after a torsional mode at 12.40 Hz) against
    # (π/2L²)·√(EI/m) for the whole section, EI = 30e9·(3·0.15 + 2·0.01) = 1.41e10 N m² and
    # m = 2400·(3·0.6 + 2·0.3 + 0.2·8 m / 1 m) = 9600 kg/m: 13.22 Hz (measured −4.3 %; without the
    # 1/1000 the frequencies would be √1000 ≈ 32× lower)
    mid = bridge.modes.w[:, X.shape[1] // 2, :]
    k = next(m for m in range(N_MODES) if np.all(mid[:, m] > 0) or np.all(mid[:, m] < 0))
    assert k == 1
    assert bridge.frequencies_hz[k] == pytest.approx(np.pi / (2 * L**2) * np.sqrt(1.41e10 / 9600), rel=0.06)


def test_the_skew_is_the_one_given_to_ospgrillage(oblique):
    bridge, lam, tags, X, Y = oblique
    # ospgrillage 0.6 rounds node coordinates to 4 decimals (osp_grillage.py, ``round(…, 4)``), so the
    # skew fitted from the nodes is tan 20° to about 5e-5 m over the 8 m between the outer lines
    # (measured 3.6e-6); every node within that rounding of its grid point (measured 4.1e-5 m)
    assert bridge.skew_tan == pytest.approx(np.tan(np.radians(SKEW)), rel=0, abs=1e-5)
    assert np.abs(_grid_x(bridge, Y) - X).max() < 1e-4
    # the deck's x extent: where the oblique support lines meet the deck edges y = ±4 m (measured 1.5e-5 m)
    reach = 0.5 * WIDTH * np.tan(np.radians(SKEW))
    np.testing.assert_allclose(bridge.deck_extent, (-reach, L + reach), rtol=0, atol=5e-5)
    # the default response point: the middle of the default girder's line (Girder 2, on y = 0), and
    # of the line y = 3 m: L/2 + 3 tan 20° (measured 1.1e-5 m)
    assert bridge.default_response_x == L / 2
    assert bridge.default_x_at(3.0) == pytest.approx(L / 2 + 3.0 * np.tan(np.radians(SKEW)), abs=3e-5)
    assert bridge.span_coordinate(X[4, 3], Y[4, 3]) == pytest.approx(3.0, abs=1e-4)  # the node's ξ


def test_shapes_and_slopes_at_the_nodes_are_opensees_eigenvectors(imported, ops):  # noqa: F811
    bridge, lam, tags, X, Y, skew = imported
    X = _grid_x(bridge, Y)  # the nodes as the import placed them (within 1e-4 m of ospgrillage's, tested above)
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
    fd = (w[:, 2:] - w[:, :-2]) / (X[:, 2:] - X[:, :-2])[:, :, None]
    np.testing.assert_allclose(bridge.modes.wx[:, 1:-1, :3], fd, atol=0.02 * np.abs(fd).max())
    # ∂w/∂y from θ_x: in the torsional mode (mode 1) θ_x has the sign of the transverse central
    # difference of w on every interior line at every interior station
    if skew:
        return
    w = bridge.modes.w[:, :, 0]
    y = Y[:, 0]
    dy = (w[2:, 1:-1] - w[:-2, 1:-1]) / (y[2:] - y[:-2])[:, None]
    assert np.all(np.abs(dy) > 0) and np.array_equal(np.sign(bridge.modes.wy[1:-1, 1:-1, 0]), np.sign(dy))


def test_eigenvectors_are_normalised_to_the_opensees_mass_matrix(imported, ops):  # noqa: F811
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
    # φᵀMφ = I: what modes_from_opensees assumes (measured largest deviation 9e-11 straight, 8e-12
    # skewed).  M is singular (no rotary mass), so analyze() reports a failed solve, but GimmeMCK has
    # assembled M by then
    np.testing.assert_allclose(phi.T @ M @ phi, np.eye(N_MODES), atol=1e-9)


def test_no_response_before_the_oblique_entry_support(oblique):
    """A moving force at y = 2 m reaches the entry support line at x = 2 tan 20° = 0.728 m (the
    ospgrillage deck's geometry), not at x = 0: until then the bridge does not move."""
    from vbikit.solve import Crossing, simulate
    from vbikit.vehicle import moving_force

    bridge = oblique[0]
    e = 2.0
    result = simulate(Crossing(bridge, vehicle=moving_force(100e3), speed=20.0, approach=2.0, lateral_offset=e,
                               free_vibration=0.0, dt=1e-3))
    support = e * np.tan(np.radians(SKEW))
    wheel = result.wheel_positions()[:, 0]
    # the solver's mode-shape tables start each track at its own entry support line (vbikit.solve.tabulate),
    # so nothing moves until the force is on it
    before, after = wheel < support, wheel > support + 0.05
    assert np.count_nonzero(before & (wheel > 0.0)) > 30 and after.any()  # x = 0 … 0.73 m: on the deck if unskewed
    assert np.all(result.xi[before] == 0.0)
    d = result.displacement(bridge.default_x_at(e), e)
    assert np.all(d[before] == 0.0)
    # once on the deck it deflects it (down, at the line's midspan by the time the force gets there)
    assert np.all(np.abs(result.xi[after]).max(axis=1) > 0)
    assert d[np.argmin(np.abs(wheel - bridge.default_x_at(e)))] < 0


def test_a_distorted_grid_is_refused_naming_the_node(og, ops, tmp_path):  # noqa: F811
    """One node of the oblique mesh moved 5 cm along x: the import names it and the offset (the node
    is on the first line, which does not enter the skew fit, so the offset is the 5 cm exactly)."""
    from vbikit.bridge.opensees import modes_from_opensees

    _build(og, skew=SKEW)
    _fix_in_plane(ops)
    lam = ops.eigen("-fullGenLapack", 2)
    tags, x, y, plan_x = _grid(ops)
    node = int(tags[0, 6])
    ops.setNodeCoord(node, 1, float(plan_x[0, 6]) + 0.05)
    with pytest.raises(ValueError, match=rf"node_tags\[0\]\[6\] \(node {node}\) .* m off its grid point") as err:
        modes_from_opensees(ops, tags, x, y, lam, vertical_axis="y")
    message = str(err.value)
    off = float(re.search(r"([0-9.e-]+) m off its grid point", message).group(1))
    assert off == pytest.approx(0.05, abs=1e-4)  # 1e-4: ospgrillage's rounding of the coordinates
    assert "1 node(s) off" in message and "tan θ = 0.36397" in message  # tan 20° = 0.363970
